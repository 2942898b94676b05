"""Charts of a design study (``rotorpillar study``), from its ``StudyResult``.

- ``capture_map``: run-ups over two axes, one cell per run: captured, passed
  what it reached (its free speed below the next resonance), or passed every
  resonance; with the boundary the study carries drawn over it: the torque
  needed to pass by the averaging theory (the A fold of the paper's
  Eq. 19-23) and by the exact linear torque balance, along the other
  axis, in pieces, each labelled with the resonance its fold belongs to;
- ``final_speed_chart``: one axis, the final speed of each run against it,
  captured runs marked, the predicted threshold drawn;
- ``ida_chart``: earthquakes, the incremental dynamic analysis curves: peak
  tip displacement relative to the ground and peak shaft deflection against
  the peak ground acceleration, one line per record (or per value of the
  other axes).

Nothing is recomputed here: the curves are the ones study.json holds.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..records import Figure
from ..studies.boundary import ThresholdBoundary, TorqueBoundary
from .style import COLOURS, CYCLE, figure, save

STANDARD_GRAVITY = 9.80665
TORQUE = "drive.torque_at_zero"
CAPTURE_MAP, FINAL, IDA = "study_capture_map.png", "study_final.png", "study_ida.png"
INTENSITY_KEYS = ("excitation.record_scale", "excitation.amplitude")


def _numeric(values) -> bool:
    return all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)


def _edges(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    if len(v) == 1:
        d = 0.05 * abs(v[0]) or 0.5
        return np.array([v[0] - d, v[0] + d])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.r_[v[0] - (mid[0] - v[0]), mid, v[-1] + (v[-1] - mid[-1])]


def _label(key: str) -> str:
    units = {
        "drive.torque_at_zero": "M0 [N*m]",
        "rotor.eccentricity": "eccentricity e [m]",
        "shaft.stiffness": "c2 [N/m]",
        "drive.slope": "slope s [N*m*s]",
        "load.coefficient": "k [N*m*s^2]",
        "rotor.mass": "m_C [kg]",
    }
    return units.get(key, key)


#: A run-up's outcome on the capture map: (code, colour, legend).
OUTCOMES = (
    (0, COLOURS["unstable"], "captured at a resonance"),
    (1, COLOURS["accent"], "passed what it reached: free speed below the next resonance"),
    (2, COLOURS["stable"], "passed every resonance"),
)


def outcome(run, resonances) -> int:
    """0 captured, 1 passed but settled below a resonance it never reached
    (the drive's free speed lies below it), 2 above every resonance.

    >>> from types import SimpleNamespace as S
    >>> [outcome(S(passed=p, final_speed=w), [S(omega=20.0), S(omega=60.0)])
    ...  for p, w in ((False, 19.0), (True, 30.0), (True, 70.0))]
    [0, 1, 2]
    """
    if not run.passed:
        return 0
    top = max((float(r.omega) for r in resonances or ()), default=0.0)
    return 2 if run.final_speed > top else 1


def _segments(xs, ys, which) -> list[tuple[int | None, np.ndarray, np.ndarray]]:
    """The boundary split where the resonance it belongs to changes: no line
    joins the fold of one resonance to the next's."""
    out, start = [], 0
    for k in range(1, len(xs) + 1):
        if k == len(xs) or which[k] != which[start]:
            out.append((which[start], np.asarray(xs[start:k], float), np.asarray(ys[start:k], float)))
            start = k
    return out


def capture_map(path, result) -> Path:
    """Each run's outcome per cell over two axes (captured; passed what it
    reached, its free speed below the next resonance; passed every
    resonance), the predicted passing torque over it in pieces, each
    labelled with the resonance it belongs to."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from .style import place_labels

    axes = list(result.axes)
    keys = [a.key for a in axes]
    # the torque on the vertical axis, the other axis horizontal
    if TORQUE in keys:
        ykey = TORQUE
        xkey = next(k for k in keys if k != TORQUE)
    else:
        xkey, ykey = keys
    xs = list(next(a for a in axes if a.key == xkey).values)
    ys = list(next(a for a in axes if a.key == ykey).values)
    b = result.boundary.predicted if result.boundary is not None else None
    res = b.resonances if isinstance(b, TorqueBoundary) else ()
    grid = np.full((len(ys), len(xs)), np.nan)
    for r in result.runs:
        i, j = ys.index(r.params[ykey]), xs.index(r.params[xkey])
        grid[i, j] = outcome(r, res) if res else (2.0 if r.passed else 0.0)
    fig, ax = figure(1060, 720)
    cmap = ListedColormap([c for _, c, _ in OUTCOMES])
    ax.pcolormesh(
        _edges(xs),
        _edges(ys),
        np.ma.masked_invalid(grid),
        cmap=cmap,
        vmin=-0.5,
        vmax=2.5,
        alpha=0.55,
        edgecolors="white",
        linewidth=0.6,
    )
    seen = {int(v) for v in grid[np.isfinite(grid)]}
    handles = [Patch(color=c, alpha=0.55, label=lab) for k, c, lab in OUTCOMES if k in seen]
    bad = [r for r in result.runs if not r.ok]
    if bad:
        (h,) = ax.plot([r.params[xkey] for r in bad], [r.params[ykey] for r in bad], "kx", label="integrator failed")
        handles.append(h)
    y_lo, y_hi = _edges(ys)[0], _edges(ys)[-1]
    labels = []
    if isinstance(b, TorqueBoundary) and b.other_key == xkey:
        bx = list(np.asarray(b.other_values, dtype=float))
        which = list(b.resonance or [None] * len(bx))
        omega = {r.index: r.omega for r in res}
        for name, style, lab in (
            ("averaging", "-", "needed to pass: averaging (Eq. 19-23), A fold"),
            ("exact_linear", "--", "needed to pass: exact linear balance"),
        ):
            by = [np.nan if v is None else v for v in getattr(b, name)]
            first = True
            for idx, sx, sy in _segments(bx, by, which):
                (h,) = ax.plot(sx, sy, style, color=COLOURS["analytic"], lw=1.8, label=lab if first else None)
                if first:
                    handles.append(h)
                first = False
                if name != "averaging" or idx is None:
                    continue
                inside = np.flatnonzero((sy >= y_lo) & (sy <= y_hi))
                what = f"resonance {idx}" + (f" ({omega[idx]:.1f} rad/s)" if idx in omega else "")
                if inside.size:
                    k = inside[len(inside) // 2]
                    labels.append(
                        {
                            "xy": (float(sx[k]), float(sy[k])),
                            "offset": (6, 6),
                            "fontsize": 8,
                            "text": what,
                            "bbox": dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.85),
                        }
                    )
                elif np.isfinite(sy).any():
                    # the whole piece lies off the map: say where, at the edge it lies beyond
                    up = np.nanmin(sy) > y_hi
                    xm = float(np.clip(np.nanmean(sx), _edges(xs)[0], _edges(xs)[-1]))
                    labels.append(
                        {
                            "xy": (xm, y_hi if up else y_lo),
                            "offset": (4, -14 if up else 6),
                            "fontsize": 8,
                            "text": f"{xkey.split('.')[-1]} {sx.min():.3g} .. "
                            f"{sx.max():.3g}: {what} needs M0 = {np.nanmin(sy):,.0f} N*m, "
                            f"{'above' if up else 'below'} the map",
                            "bbox": dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.85),
                        }
                    )
    ax.set_xlim(_edges(xs)[0], _edges(xs)[-1])
    ax.set_ylim(y_lo, y_hi)
    ax.set_xlabel(_label(xkey))
    ax.set_ylabel(_label(ykey))
    ax.grid(False)
    legend = fig.legend(handles=handles, loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    ax.set_title(
        f"{result.scene_name}: run-ups from rest, {len(result.runs)} runs "
        f"({result.model} model); the lines: torque needed to pass",
        fontsize=10,
    )
    fig.canvas.draw()
    fig.set_layout_engine("none")
    place_labels(ax, labels, obstacles=[legend], lines=[ln for ln in ax.lines if len(ln.get_xdata()) > 2], drawn=True)
    return save(fig, path)


def final_speed_chart(path, result) -> Path:
    """Final speed against the one axis, captured runs marked, the threshold drawn."""
    key = result.axes[0].key
    x = np.array([r.params[key] for r in result.runs], dtype=float)
    W = np.array([r.final_speed for r in result.runs])
    cap = np.array([r.captured_at is not None for r in result.runs])
    fig, ax = figure(1000, 600)
    ax.plot(x, W, "-", color=COLOURS["reference"], lw=0.8)
    ax.plot(x[~cap], W[~cap], "o", color=COLOURS["stable"], label="passed")
    ax.plot(x[cap], W[cap], "s", color=COLOURS["unstable"], label="captured at a resonance")
    b = result.boundary.predicted if result.boundary is not None else None
    marks: list[tuple[float | None, str, str]] = []
    if isinstance(b, TorqueBoundary) and key == TORQUE:
        marks = [(b.averaging[0], "-", "averaging theory (Eq. 19-23)"), (b.exact_linear[0], "--", "exact linear")]
    elif isinstance(b, ThresholdBoundary):
        marks = [
            (b.threshold_averaging, "-", "averaging theory (Eq. 19-23)"),
            (b.threshold_exact_linear, "--", "exact linear"),
        ]
    for v, style, lab in marks:
        if v is not None:
            ax.axvline(v, ls=style, color=COLOURS["analytic"], lw=1.4, label=f"predicted threshold, {lab}: {v:.4g}")
    ax.set_xlabel(_label(key))
    ax.set_ylabel("final speed [rad/s]")
    ax.legend(fontsize=8)
    ax.set_title(f"{result.scene_name}: {result.case}, final speed ({result.model} model)")
    return save(fig, path)


def ida_chart(path, result) -> Path:
    """Peak tip and peak shaft deflection against PGA, one line per record."""
    keys = [a.key for a in result.axes]
    inten = next((k for k in INTENSITY_KEYS if k in keys), None)
    others = [k for k in keys if k != inten]
    lines: dict = {}
    for r in result.runs:
        label = (
            ", ".join(f"{Path(str(r.params[k])).name if k == 'excitation.record' else r.params[k]}" for k in others)
            or "record"
        )
        lines.setdefault(label, []).append(r)
    fig, (a1, a2) = figure(1060, 560, ncols=2, sharey=True)
    for (label, runs), c in zip(lines.items(), CYCLE * 10):
        runs.sort(key=lambda r: r.pga or 0.0)
        g = np.array([(r.pga or 0.0) / STANDARD_GRAVITY for r in runs])
        a1.plot([1e3 * r.peak_tip for r in runs], g, "o-", color=c, label=label)
        a2.plot([1e3 * r.peak_shaft_deflection for r in runs], g, "o-", color=c, label=label)
    a1.set_xlabel("peak tip displacement relative to the ground [mm]")
    a2.set_xlabel("peak shaft deflection [mm]")
    a1.set_ylabel("peak ground acceleration [g]")
    a1.legend(fontsize=8)
    a1.set_title(f"{result.scene_name}: incremental dynamic analysis ({result.model} model)")
    a2.set_title("shaft: rotor centre against the pillar tip")
    return save(fig, path)


def study_charts(result, out_dir) -> list[Figure]:
    """Every chart the study allows, into ``out_dir``."""
    out = Path(out_dir)
    figs = []
    keys = [a.key for a in result.axes]
    if result.case == "earthquake":
        ida_chart(out / IDA, result)
        figs.append(
            Figure(
                file=IDA,
                caption="Incremental dynamic analysis: peak tip displacement "
                "relative to the ground and peak shaft deflection against the peak ground "
                "acceleration, one line per record.",
            )
        )
    elif len(keys) == 2 and all(_numeric(a.values) for a in result.axes):
        capture_map(out / CAPTURE_MAP, result)
        figs.append(
            Figure(
                file=CAPTURE_MAP,
                caption="Capture map of run-ups from rest, per run: "
                "captured at a resonance (red), passed the resonances it reached but settled "
                "at a free speed below the next one (blue), or passed every resonance "
                "(green); the lines are the torque needed to pass by the averaging theory "
                "(Eq. 19-23, solid) and by the exact linear torque balance (dashed), in "
                "pieces, each labelled with the resonance it belongs to."
                if result.case == "runup"
                else "Run-downs: settled at no resonance (green) or caught at one (red).",
            )
        )
    elif len(keys) == 1 and _numeric(result.axes[0].values):
        final_speed_chart(out / FINAL, result)
        figs.append(
            Figure(
                file=FINAL,
                caption="Final speed of each run against the study's axis; "
                "squares: captured at a resonance; vertical lines: the threshold the "
                "averaging theory and the exact linear balance predict.",
            )
        )
    return figs
