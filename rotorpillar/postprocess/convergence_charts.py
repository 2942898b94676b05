"""Charts of the convergence study: error against DOFs and against wall time.

One figure per cost (DOFs, wall time), three panels and the legend in a
2 x 2 grid at the report's width: the first bending frequency, the first
ovalling frequency, and the band (the largest error over the frequencies
the scene needs, what the choice of a model uses).
One line per model family; the Pareto front drawn as a staircase with its
points ringed; the tolerance and the reference's own uncertainty drawn
across; the chosen model starred.  Failures stay on the chart: a run
without the mode (a beam has no ovalling mode; a coarse mesh may miss it)
is marked on a "no mode" strip at the top, and the locking of P1 elements
shows as its own line far above the rest.  Figure, colours and the atomic
PNG write come from :mod:`.style`.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from .style import COLOURS, figure, save

if TYPE_CHECKING:
    from ..converge.result import ConvergenceRun, ConvergenceStudy, RunBrief

#: Colours of the model families (one hue per kind of model, a lighter one
#: for its variant); markers and line styles tell the variants apart.
FAMILY_COLOURS = {
    "closed_form": "#000000",
    "beam_euler": "#0072B2",
    "beam_timoshenko": "#56B4E9",
    "shell": "#009E73",
    "shell_light": "#7FCEB9",
    "solid_p1": "#D55E00",
    "solid_p1_light": "#EAAE80",
    "solid_p2": "#CC79A7",
    "solid_p2_light": "#E5BCD3",
}
STYLE: dict[str, dict[str, Any]] = {
    "closed_form": dict(color=FAMILY_COLOURS["closed_form"], marker="*", ms=11),
    "beam_euler": dict(color=FAMILY_COLOURS["beam_euler"], marker="o"),
    "beam_timoshenko": dict(color=FAMILY_COLOURS["beam_timoshenko"], marker="s"),
    "shell_quad": dict(color=FAMILY_COLOURS["shell"], marker="D"),
    "shell_tri": dict(color=FAMILY_COLOURS["shell_light"], marker="^"),
    "shell_quad_around": dict(color=FAMILY_COLOURS["shell"], marker="D", ls="--", mfc="none"),
    "solid_hex_p1": dict(color=FAMILY_COLOURS["solid_p1"], marker="s"),
    "solid_tet_p1": dict(color=FAMILY_COLOURS["solid_p1_light"], marker="^"),
    "solid_hex_p2": dict(color=FAMILY_COLOURS["solid_p2"], marker="s"),
    "solid_tet_p2": dict(color=FAMILY_COLOURS["solid_p2_light"], marker="^"),
    "solid_hex_p2_around": dict(color=FAMILY_COLOURS["solid_p2"], marker="s", ls="--", mfc="none"),
    "solid_hex_p2_along": dict(color=FAMILY_COLOURS["solid_p2"], marker="v", ls="-.", mfc="none"),
}
COST_LABEL = {"dofs": "degrees of freedom", "wall_time": "wall time per run (s)"}
PANELS = (
    ("bending", "first bending frequency: |error|"),
    ("ovalling", "first ovalling frequency: |error|"),
    ("band", "the band's frequencies: error bound (model + mesh + reference)"),
)
FLOOR = 1e-9


def _error(run: ConvergenceRun | RunBrief, q: str, needed, ref_unc=None) -> float | None:
    """|measured error| of quantity q, or for the band what the choice uses: the
    largest error bound plus the reference's uncertainty over the needed ones."""
    if q != "band":
        e = getattr(run, f"{q}_error")
        return None if e is None else abs(e)
    errs = [getattr(run, f"{k}_error_bound") for k in needed]
    if any(e is None for e in errs):
        return None
    ref_unc = ref_unc or {}
    return max((e + ref_unc.get(k, 0.0) for k, e in zip(needed, errs)), default=0.0)


def _missing_row(study: ConvergenceStudy) -> float:
    """Height of the "no such mode" strip, above every error of every panel."""
    import numpy as np

    needed = study.selection.needed
    unc = study.selection.reference_uncertainty
    ys = [_error(r, q, needed, unc) for r in study.runs if r.status == "ok" for q in ("bending", "ovalling", "band")]
    top = max([y for y in ys if y is not None] + [study.selection.tolerance * 10])
    return 3 * 10 ** np.ceil(np.log10(top))


def _bottom_row(study: ConvergenceStudy) -> float:
    """Bottom of the error axis: a decade under the smallest error or uncertainty."""
    import numpy as np

    needed = study.selection.needed
    unc = study.selection.reference_uncertainty
    found = [_error(r, q, needed, unc) for r in study.runs if r.status == "ok" for q in ("bending", "ovalling", "band")]
    ys = [y for y in found if y is not None and y > 0] + list(unc.values())
    lo = min([y for y in ys if y > 0] or [1e-6])
    return max(FLOOR, 10 ** (np.floor(np.log10(lo)) - 1))


def _panel(ax: Any, study: ConvergenceStudy, cost: str, q: str, title: str, families: dict[str, str]) -> None:
    runs = [r for r in study.runs if r.status == "ok"]
    sel = study.selection
    needed = sel.needed
    unc = sel.reference_uncertainty

    def err_of(run, q, needed):
        return _error(run, q, needed, unc)

    tol = sel.tolerance
    missing_y = _missing_row(study)
    no_mode = []
    for fam, style in STYLE.items():
        rows = sorted((r for r in runs if r.family == fam), key=lambda r: getattr(r, cost))
        if not rows:
            continue
        pts = [(getattr(r, cost), err_of(r, q, needed)) for r in rows]
        have = [(c, max(e, FLOOR)) for c, e in pts if e is not None]
        miss = [c for c, e in pts if e is None]
        kw: dict[str, Any] = dict(style)
        ls = kw.pop("ls", "-")
        if have:
            ax.plot(*zip(*have), ls=ls, lw=1.3, label=families[fam], **kw)
        if miss:
            if len(miss) == len(pts):
                no_mode.append(families[fam])
            ax.plot(
                miss,
                [missing_y] * len(miss),
                ls="none",
                marker="x",
                color=kw["color"],
                label=None if have else families[fam],
            )
    # Pareto front
    front = set(getattr(getattr(study.pareto, cost), q))
    fr = sorted(
        ((getattr(r, cost), max(err_of(r, q, needed), FLOOR)) for r in runs if r.label in front), key=lambda t: t[0]
    )
    if fr:
        xs, es = zip(*fr)
        ax.step(xs, es, where="post", color="0.3", lw=2.5, alpha=0.35, zorder=0, label="Pareto front")
        ax.plot(xs, es, ls="none", marker="o", ms=13, mfc="none", mec="0.3", zorder=0)
    ax.axhline(tol, color=COLOURS["tolerance"], ls=":", lw=1.2, label=f"tolerance {tol:g}")
    ref = study.reference
    shade = (
        [ref[k].error_estimate / abs(ref[k].value) for k in needed if k in ref]
        if q == "band"
        else [ref[q].error_estimate / abs(ref[q].value)]
        if q in ref
        else []
    )
    if shade:
        ax.axhspan(_bottom_row(study), max(max(shade), FLOOR), color="0.85", zorder=-1, label="reference uncertainty")
    chosen = sel.chosen
    if chosen is not None:
        e = err_of(chosen, q, needed)
        if e is not None:
            ax.plot(
                [getattr(chosen, cost)],
                [max(e, FLOOR)],
                marker="*",
                ms=20,
                color=COLOURS["numeric"],
                mec="k",
                ls="none",
                zorder=5,
                label="chosen",
            )
    ax.axhline(missing_y, color="0.6", lw=0.6)
    # at the right: the runs without the mode are marked on this line at the left; the
    # placed labels keep off this text and the box below (place_labels' obstacles)
    fixed = []
    fixed.append(
        ax.text(
            0.99,
            missing_y,
            "no such mode ",
            transform=ax.get_yaxis_transform(),
            va="bottom",
            ha="right",
            fontsize=8,
            color="0.4",
        )
    )
    if no_mode:
        fixed.append(
            ax.text(
                0.02,
                0.02,
                "no " + (q if q != "band" else "needed") + " mode:\n  " + "\n  ".join(no_mode),
                transform=ax.transAxes,
                fontsize=8,
                va="bottom",
                bbox=dict(fc="white", ec="0.7"),
            )
        )
    ax._fixed_texts = fixed
    labels = []
    for fam in ("solid_hex_p1", "solid_tet_p1"):
        rows = [r for r in runs if r.family == fam and err_of(r, q, needed) is not None]
        if rows:
            r = max(rows, key=lambda r: getattr(r, cost))
            labels.append(
                {
                    "xy": (getattr(r, cost), err_of(r, q, needed)),
                    "text": "P1 locking",
                    "fontsize": 8,
                    "offset": (5, 5),
                    "color": STYLE[fam]["color"],
                }
            )
    for fam in ("shell_quad_around", "solid_hex_p2_around"):
        rows = [r for r in runs if r.family == fam]
        if rows:
            r = min(rows, key=lambda r: r.level)
            e = err_of(r, q, needed)
            labels.append(
                {
                    "xy": (getattr(r, cost), missing_y if e is None else max(e, FLOOR)),
                    "text": f"{r.params['elements_around']} around",
                    "fontsize": 8,
                    "offset": (4, -12),
                    "color": STYLE[fam]["color"],
                }
            )
    ax._pending_labels = labels
    ax.set_xscale("log")
    ax.set_yscale("log")
    # over these many decades a log axis labels no minor tick; saying so up front spares
    # every draw the measuring of their empty labels (most of a draw's time here)
    from matplotlib.ticker import NullFormatter, NullLocator

    ax.xaxis.set_minor_formatter(NullFormatter())
    # the error axis spans nine decades or more (1e-6 up to the "no such mode" row), a labelled
    # major tick and a grid line each: its minor ticks, eight a decade a few pixels apart, are
    # clutter, and each is an artist every draw lays out (both charts 3.4 -> 2.0 s of CPU)
    ax.yaxis.set_minor_locator(NullLocator())
    ax.set_ylim(_bottom_row(study), missing_y * 4)
    ax.set_xlabel(COST_LABEL[cost])
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", alpha=0.3)


def convergence_chart(study: ConvergenceStudy, cost: str, path: str | Path) -> Path:
    """Write one chart (PNG) of |relative error| against ``cost`` ("dofs" or
    "wall_time"): the three panels and the legend in a 2 x 2 grid, at the
    width the report shows it (its text legible there)."""
    from .style import place_labels

    families = {k: v.label for k, v in study.families.items()}
    fig, grid = figure(1060, 960, nrows=2, ncols=2)
    axes = [grid[0, 0], grid[0, 1], grid[1, 0]]
    for ax, (q, title) in zip(axes, PANELS):
        _panel(ax, study, cost, q, title, families)
        ax.set_ylabel("|relative error| against the reference")
    handles: dict[str, Any] = {}
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    spare = grid[1, 1]
    spare.set_axis_off()
    spare.legend(list(handles.values()), list(handles.keys()), loc="center", fontsize=8, frameon=False, ncol=1)
    band = study.selection.band
    fig.suptitle(
        f"{study.scene_name}: error against {COST_LABEL[cost]} (band to {band.omega_max:.0f} rad/s)", fontsize=11
    )
    fig.canvas.draw()
    fig.set_layout_engine("none")
    for ax in axes:
        place_labels(
            ax,
            getattr(ax, "_pending_labels", []),
            obstacles=getattr(ax, "_fixed_texts", []),
            lines=list(ax.lines),
            drawn=True,
        )
    return save(fig, path)


def convergence_charts(study: ConvergenceStudy, out_dir: str | Path) -> dict[str, Path]:
    """Both charts: ``convergence_dofs.png`` and ``convergence_time.png``."""
    out_dir = Path(out_dir)
    return {
        "dofs": convergence_chart(study, "dofs", out_dir / "convergence_dofs.png"),
        "wall_time": convergence_chart(study, "wall_time", out_dir / "convergence_time.png"),
    }
