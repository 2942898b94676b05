"""Charts of a design study (``rotorpillar study``), from its ``StudyResult``.

- ``capture_map``: run-ups over two axes, one cell per run, passed or
  captured, with the boundary the study carries drawn over it: the torque
  needed to pass by the averaging theory (the A fold of the paper's
  equations 19-23) and by the exact linear torque balance, along the other axis;
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
    units = {"drive.torque_at_zero": "M0 [N*m]", "rotor.eccentricity": "eccentricity e [m]",
             "shaft.stiffness": "c2 [N/m]", "drive.slope": "slope s [N*m*s]",
             "load.coefficient": "k [N*m*s^2]", "rotor.mass": "m_C [kg]"}
    return units.get(key, key)


def capture_map(path, result) -> Path:
    """Passed / captured per cell over two axes, the predicted boundaries over it."""
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
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
    grid = np.full((len(ys), len(xs)), np.nan)
    for r in result.runs:
        i, j = ys.index(r.params[ykey]), xs.index(r.params[xkey])
        grid[i, j] = 1.0 if r.passed else 0.0
    fig, ax = figure(1000, 700)
    cmap = ListedColormap([COLOURS["unstable"], COLOURS["stable"]])
    ax.pcolormesh(_edges(xs), _edges(ys), np.ma.masked_invalid(grid), cmap=cmap, vmin=0, vmax=1,
                  alpha=0.55, edgecolors="white", linewidth=0.6)
    bad = [r for r in result.runs if not r.ok]
    if bad:
        ax.plot([r.params[xkey] for r in bad], [r.params[ykey] for r in bad], "kx",
                label="integrator failed")
    handles = [Patch(color=COLOURS["stable"], alpha=0.55, label="passed (runs up to its speed)"),
               Patch(color=COLOURS["unstable"], alpha=0.55, label="captured at a resonance")]
    b = result.boundary or {}
    if b.get("kind") == "torque" and b.get("other_key") == xkey:
        bx = np.asarray(b["other_values"], dtype=float)
        for name, style, lab in (("averaging", "-", "averaging theory (Eq. 19-23): A fold"),
                                 ("exact_linear", "--", "exact linear torque balance: A fold")):
            by = np.array([np.nan if v is None else v for v in b[name]], dtype=float)
            h, = ax.plot(bx, by, style, color=COLOURS["analytic"], lw=1.8, label=lab)
            handles.append(h)
    ax.set_xlim(_edges(xs)[0], _edges(xs)[-1])
    ax.set_ylim(_edges(ys)[0], _edges(ys)[-1])
    ax.set_xlabel(_label(xkey))
    ax.set_ylabel(_label(ykey))
    ax.grid(False)
    ax.legend(handles=handles, loc="upper left", fontsize=8, framealpha=0.9)
    ax.set_title(f"{result.scene_name}: run-ups from rest, {len(result.runs)} runs "
                 f"({result.model} model); the line: torque needed to pass")
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
    b = result.boundary or {}
    marks = []
    if b.get("kind") == "torque" and key == TORQUE:
        marks = [(b["averaging"][0], "-", "averaging theory (Eq. 19-23)"),
                 (b["exact_linear"][0], "--", "exact linear")]
    elif b.get("kind") == "threshold":
        marks = [(b.get("threshold_averaging"), "-", "averaging theory (Eq. 19-23)"),
                 (b.get("threshold_exact_linear"), "--", "exact linear")]
    for v, style, lab in marks:
        if v is not None:
            ax.axvline(v, ls=style, color=COLOURS["analytic"], lw=1.4,
                       label=f"predicted threshold, {lab}: {v:.4g}")
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
        label = ", ".join(f"{Path(str(r.params[k])).name if k == 'excitation.record' else r.params[k]}"
                          for k in others) or "record"
        lines.setdefault(label, []).append(r)
    fig, (a1, a2) = figure(1200, 560, ncols=2, sharey=True)
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


def study_charts(result, out_dir) -> list[dict]:
    """Every chart the study allows, into ``out_dir``: [{file, caption}]."""
    out = Path(out_dir)
    figs = []
    keys = [a.key for a in result.axes]
    if result.case == "earthquake":
        ida_chart(out / IDA, result)
        figs.append({"file": IDA, "caption": "Incremental dynamic analysis: peak tip displacement "
                     "relative to the ground and peak shaft deflection against the peak ground "
                     "acceleration, one line per record."})
    elif len(keys) == 2 and all(_numeric(a.values) for a in result.axes):
        capture_map(out / CAPTURE_MAP, result)
        figs.append({"file": CAPTURE_MAP, "caption": "Capture map of run-ups from rest: passed "
                     "(green) or captured at a resonance (red) per run; the lines are the torque "
                     "needed to pass by the averaging theory (Eq. 19-23, solid) and by the exact "
                     "linear torque balance (dashed)." if result.case == "runup" else
                     "Run-downs: settled at no resonance (green) or caught at one (red)."})
    elif len(keys) == 1 and _numeric(result.axes[0].values):
        final_speed_chart(out / FINAL, result)
        figs.append({"file": FINAL, "caption": "Final speed of each run against the study's axis; "
                     "squares: captured at a resonance; vertical lines: the threshold the "
                     "averaging theory and the exact linear balance predict."})
    return figs
