"""Charts drawn from `rotorpillar analyze`.

- :func:`drive_chart`: the motor torque Md and the total resistance L over
  the speed, with the stable and unstable branches of the stationary regimes
  and the jumps A -> B (run-up) and D -> C (run-down): the paper's Figs. 3-4.
  L is evaluated by the closed forms of :mod:`rotorpillar.reduced.averaging`
  on the resonance parameters analyze.json carries (omega_i, f_i, g_i, nu_i),
  over the whole speed range, not only the +-50 % of the stored curves (a
  jump may land far beyond them); the tests check it against those curves.
  A regime on L is stable where the paper's Eq. 23 says so
  (:func:`rotorpillar.reduced.averaging.branch_is_stable`).  The main panel
  shows what the motor reaches: its torque axis spans the drive's range
  (Md over the speeds drawn), the resonance peaks of L above it are marked at
  the top edge with their value, and the jumps beyond it are left to the
  panels below: near each resonance, L with its jumps and the resonance's
  own extra torque dL_i on its own axis, and the scene's motor's margin
  Md - L (what is left to accelerate), so that drive and resonance read
  together; the legend sits outside the panels; no two labels overlap
  and none covers a curve (:func:`rotorpillar.postprocess.style.place_labels`).
- :func:`amplitude_chart`: a_i(z) by averaging (the paper's Eq. 19,
  omega_i**2 restored) against the exact linear steady state, per resonance.

The analysis is read with attribute access (``analysis.drive.slope``), as
:func:`rotorpillar.postprocess.readers.read_analysis` gives it.  The
earthquake, transient and convergence charts are drawn by
``transient_charts`` and ``convergence_charts``.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..reduced import averaging as av
from .directions import short
from .style import COLOURS, blank, figure, freeze_layout, place_labels, save

if TYPE_CHECKING:
    from ..analysis.results import AnalysisResult, ResonanceAnalysis

#: Headroom of the main panel's torque axis over the motor's largest torque.
HEADROOM = 1.15


def resonances_of(analysis: AnalysisResult) -> list[ResonanceAnalysis]:
    """The resonances of analyze.json (the averaging closed forms take their index,
    direction, omega, forcing, coupling and nu)."""
    return list(analysis.resonances)


def drive_curve_data(analysis: AnalysisResult, points: int = 6000) -> dict[str, Any]:
    """Everything the Md/L chart draws, as arrays (no plotting).

    Keys: omega (grid, rad/s), L (total resistance), Mc, Md (the scene's
    motor), stable (bool mask: the paper's Eq. 23 on L), jumps (list
    of dicts with the from/to points and ``shown``: within the main panel),
    stationary (list of records with omega and stable), top (grid end);
    the main panel's range: x_max (past the free speed and every resonance),
    y_max (the drive's range: HEADROOM times the largest Md over [0, x_max]),
    and beyond (per resonance whose own peak of L, Mc + its dL alone, exceeds
    y_max: resonance, omega, peak, in the units above).
    """
    d = analysis.drive
    res = resonances_of(analysis)
    k, s, M0 = d.load_coefficient, d.slope, d.torque_at_zero
    ends: list[float] = [1.6 * r.omega for r in res]
    free = d.free_speed
    finite_free = free is not None and math.isfinite(free)
    if finite_free:
        ends.append(1.08 * free)
    ends += [1.1 * j.omega_to for j in d.jumps] + [1.1 * j.omega_from for j in d.jumps]
    top = max(ends)
    grid = np.unique(
        np.concatenate([np.linspace(0.0, top, points)] + [r.omega * (1 + r.nu * np.linspace(-8, 8, 801)) for r in res])
    )
    grid = grid[(grid >= 0) & (grid <= top)]
    L = np.asarray(av.total_resistance(grid, k, res), dtype=float)
    # The main panel: the speeds the motor runs at and the resonances; the
    # torques it can give there.
    x_max = max([1.1 * r.omega for r in res] + ([1.15 * free] if finite_free else []))
    y_max = HEADROOM * max(M0, M0 - s * x_max)
    if not y_max > 0:
        y_max = HEADROOM * float(np.max(L[grid <= x_max]))
    jumps = []
    for n, j in enumerate(d.jumps, start=1):
        up = j.direction == "up"
        level = j.torque_at_zero
        pair = ((j.omega_from, level - s * j.omega_from), (j.omega_to, level - s * j.omega_to))
        shown = all(0 <= y <= y_max for _, y in pair)
        if shown:
            x_max = max(x_max, 1.05 * max(j.omega_from, j.omega_to))
        jumps.append(
            {
                "direction": j.direction,
                "resonance": j.resonance,
                "label_from": ("A" if up else "D"),
                "label_to": ("B" if up else "C"),
                "number": n,
                "level": level,
                "from": pair[0],
                "to": pair[1],
                "shown": shown,
            }
        )
    x_max = min(x_max, top)
    beyond = []
    for r in res:
        # the resonance's own peak: Mc with its dL alone (neighbours' peaks may fall in its window)
        near = grid[(grid >= r.omega * (1 - 8 * r.nu)) & (grid <= r.omega * (1 + 8 * r.nu))]
        peak = float(np.max(av.total_resistance(np.append(near, r.omega), k, [r])))
        if peak > y_max and r.omega <= x_max:
            beyond.append({"resonance": r.index, "omega": r.omega, "peak": peak})
    return {
        "omega": grid,
        "L": L,
        "Mc": k * grid**2,
        "Md": M0 - s * grid,
        "stable": np.asarray(av.branch_is_stable(grid, s, k, res), dtype=bool),
        "jumps": jumps,
        "stationary": d.stationary,
        "slope": s,
        "torque_at_zero": M0,
        "top": top,
        "x_max": x_max,
        "y_max": y_max,
        "beyond": beyond,
    }


def _branches(ax, x, y, stable, label=True):
    """Draw y(x) solid where stable, dashed where not."""
    edges = np.flatnonzero(np.diff(stable.astype(int))) + 1
    starts = np.concatenate([[0], edges])
    stops = np.concatenate([edges, [len(x)]])
    seen = set()
    for a, b in zip(starts, stops):
        st = bool(stable[a])
        sl = slice(max(a - 1, 0), b)
        name = "L: stable regimes" if st else "L: unstable regimes"
        ax.plot(
            x[sl],
            y[sl],
            color=COLOURS["stable" if st else "unstable"],
            ls="-" if st else "--",
            lw=1.8 if st else 1.6,
            label=name if (label and name not in seen) else None,
        )
        seen.add(name)


def _jump_arrows(
    ax: Any, jumps: list[dict[str, Any]], s: float, xlim: tuple[float, float], z_scale: float = 1.0
) -> list[dict[str, Any]]:
    """Draw each jump's drive line, arrow and end points; return their labels
    (for :func:`place_labels`)."""
    labels = []
    for j in jumps:
        (x0, y0), (x1, y1) = j["from"], j["to"]
        xs = np.linspace(*xlim, 50)
        ax.plot(xs / z_scale, j["level"] - s * xs, color=COLOURS["drive"], lw=0.7, ls=":")
        ax.annotate(
            "",
            xy=(x1 / z_scale, y1),
            xytext=(x0 / z_scale, y0),
            arrowprops=dict(arrowstyle="->", color="black", lw=1.2),
        )
        n = j["number"]
        for (x, y), name in (((x0, y0), j["label_from"]), ((x1, y1), j["label_to"])):
            ax.plot([x / z_scale], [y], "o", color="black", ms=3.5)
            labels.append({"xy": (x / z_scale, y), "text": f"{name}{n}", "fontsize": 8})
    return labels


def _grid_of(n: int, most: int = 3) -> tuple[int, int]:
    """(rows, columns) of ``n`` panels, at most ``most`` to a row, the rows as even as they
    can be (four panels: two rows of two, wider than three and one).

    >>> [_grid_of(n) for n in (1, 3, 4, 5, 7)]
    [(1, 1), (1, 3), (2, 2), (2, 3), (3, 3)]
    """
    if not n:
        return 0, 1
    rows = math.ceil(n / most)
    return rows, math.ceil(n / rows)


def _overview(
    top: Any, data: dict[str, Any], res: list[ResonanceAnalysis], W: Any
) -> tuple[list[dict[str, Any]], list[Any]]:
    """The top panel: Md, L and Mc over the drive's range, the stationary
    speeds, the jumps shown there, each resonance marked; returns its labels
    and the curves they must stay off."""
    s, x_max, y_max = data["slope"], data["x_max"], data["y_max"]
    top.plot(W, data["Mc"], color=COLOURS["load"], ls=":", label="Mc = k Omega^2 (the load alone)")
    _branches(top, W, data["L"], data["stable"])
    (md,) = top.plot(
        W,
        data["Md"],
        color=COLOURS["drive"],
        label=f"Md = {data['torque_at_zero']:g} - {s:g} Omega (the scene's motor)",
    )
    labels = []
    for st in data["stationary"]:
        y = data["torque_at_zero"] - s * st.omega
        top.plot([st.omega], [y], "o", ms=7, mec="black", mfc=COLOURS["stable"] if st.stable else "white", zorder=5)
        labels.append(
            {
                "xy": (st.omega, y),
                "offset": (6, 6),
                "fontsize": 8,
                "text": f"{st.omega:.2f} rad/s ({'stable' if st.stable else 'unstable'})",
            }
        )
    labels += _jump_arrows(top, [j for j in data["jumps"] if j["shown"]], s, (0, x_max))
    peaks = {b["resonance"]: b for b in data["beyond"]}
    for r in res:
        top.axvline(r.omega, color=COLOURS["reference"], lw=0.6, ls="--")
        b = peaks.get(r.index)
        if b is None:
            labels.append(
                {
                    "xy": (r.omega, 0.04 * y_max),
                    "offset": (3, 2),
                    "fontsize": 8,
                    "color": "#555555",
                    "text": f"omega_{r.index}",
                }
            )
            continue
        # beyond the panel: an arrow at the top edge with the peak's value
        top.annotate(
            "",
            xy=(r.omega, y_max),
            xytext=(r.omega, 0.9 * y_max),
            arrowprops=dict(arrowstyle="->", color=COLOURS["unstable"], lw=1.4),
            annotation_clip=False,
        )
        labels.append(
            {
                "xy": (r.omega, 0.9 * y_max),
                "offset": (4, -4),
                "fontsize": 8,
                "va": "top",
                "color": COLOURS["unstable"],
                "text": f"omega_{r.index}: L peaks at {b['peak']:,.0f} N*m",
            }
        )
    top.set_xlim(0, x_max)
    top.set_ylim(0, y_max)
    top.set_xlabel("rotor speed Omega (rad/s)")
    top.set_ylabel("torque (N*m)")
    return labels, [ln for ln in top.lines if len(ln.get_xdata()) > 2] + [md]


def _resonance_block(ax, mx, data, r, others, W, first: bool) -> list:
    """Near resonance ``r``, against z = Omega / omega_r: L with its jumps and,
    on the right axis, this resonance's own extra torque dL_r (the
    neighbours' dashed); below (``mx``), the scene's motor's margin Md - L,
    the torque left to accelerate, at the resonance beside dL_r.  Returns the
    jumps' labels (to place on ``ax``)."""
    s, w = data["slope"], r.omega
    lo, hi = 0.5 * w, 1.5 * w
    mine = [j for j in data["jumps"] if j["resonance"] == r.index]
    for j in mine:
        lo = min(lo, 0.95 * j["from"][0], 0.95 * j["to"][0])
        hi = max(hi, 1.05 * j["from"][0], 1.05 * j["to"][0])
    m = (W >= lo) & (W <= hi)
    z = W[m] / w
    ax.plot(z, data["Mc"][m], color=COLOURS["load"], ls=":")
    _branches(ax, z, data["L"][m], data["stable"][m], label=False)
    c = r.curves
    ax.plot(
        np.asarray(c.z)[::8],
        np.asarray(c.L_all)[::8],
        ".",
        color="black",
        ms=2.5,
        label="analyze.json" if first else None,
    )
    jump_labels = _jump_arrows(ax, mine, s, (lo, hi), z_scale=w)
    ys = [data["L"][m]] + [np.array([j["from"][1], j["to"][1]]) for j in mine]
    y0, y1 = float(min(map(np.min, ys))), float(max(map(np.max, ys)))
    pad = 0.08 * (y1 - y0 or 1.0)
    ax.set_ylim(y0 - pad, y1 + 2 * pad)
    ax.set_xlim(lo / w, hi / w)
    ax.set_ylabel("L (N*m)")
    ax.tick_params(labelbottom=False)
    note = (f"{len(mine)} jump(s)" if mine else "no jump") + (
        "; above the motor's free speed" if data["free_speed"] is not None and w > data["free_speed"] else ""
    )
    ax.set_title(f"resonance {r.index}: {w:.2f} rad/s, {short(r.direction)}\n{note}", fontsize=9)
    own = av.total_resistance(W[m], 0.0, [r])
    extra = ax.twinx()
    extra.plot(z, own, color=COLOURS["accent"], lw=1.2, label="its own dL (right)")
    rest = [o for o in others if o.index != r.index]
    if rest:
        theirs = av.total_resistance(W[m], 0.0, rest)
        if np.max(np.abs(theirs)) > 0.02 * max(np.max(np.abs(own)), 1e-300):
            extra.plot(z, theirs, color=COLOURS["reference"], lw=0.9, ls="--", label="other resonances' dL (right)")
    extra.set_ylabel("dL (N*m)", color=COLOURS["accent"])
    extra.grid(False)
    extra.spines["right"].set_visible(True)
    # the margin of the scene's motor: what is left to accelerate the rotor
    margin = data["Md"][m] - data["L"][m]
    mx.plot(z, margin, color=COLOURS["drive"], lw=1.3)
    lo_m, hi_m = float(margin.min()), float(margin.max())
    if lo_m < 0.25 * max(hi_m, 1e-300):  # near or below zero: show where it crosses
        mx.axhline(0.0, color=COLOURS["unstable"], lw=0.8)
    at = float(np.interp(1.0, z, margin))
    hump = float(np.asarray(av.total_resistance(np.array([w]), 0.0, [r]))[0])
    mx.plot([1.0], [at], "o", color=COLOURS["drive"], ms=4)
    mx.set_xlim(lo / w, hi / w)
    mx.set_xlabel(f"z = Omega / omega_{r.index}")
    mx.set_ylabel("Md - L (N*m)")
    share = f" ({100 * hump / at:.2g} %)" if at > 0 else ""
    # a legend without a handle: matplotlib puts it where it covers the least of the curve
    from matplotlib.lines import Line2D

    mx.legend(
        [Line2D([], [], ls="none")],
        [f"at z = 1:\nMd - L = {at:,.0f} N*m\ndL_{r.index} = {hump:.3g} N*m{share}"],
        loc="best",
        fontsize=8,
        handlelength=0,
        handletextpad=0,
        framealpha=0.85,
    )
    return jump_labels


def drive_figure(analysis: AnalysisResult, width: int = 1060) -> Any:
    """The Md/L figure (matplotlib): the overview over the drive's range
    (top), then near each resonance, as the paper's Figs. 3-4 draw them,
    L with its jumps and the resonance's own extra torque dL_i (its own axis:
    a hump of a few N*m is invisible beside Md), and below it the scene's
    motor's margin Md - L.  :func:`drive_chart` saves it."""
    data = drive_curve_data(analysis)
    data["free_speed"] = getattr(analysis.drive, "free_speed", None)
    res = list(analysis.resonances)
    rows, cols = _grid_of(len(res))
    fig = blank(width, 420 + 400 * rows)
    gs = fig.add_gridspec(1 + 2 * rows, cols, height_ratios=[1.5] + [1.0, 0.75] * rows)
    top = fig.add_subplot(gs[0, :])
    W = data["omega"]
    labels, curves = _overview(top, data, res, W)
    far = [j for j in data["jumps"] if not j["shown"]]
    verdict = (
        f"{len(data['jumps'])} jump(s): "
        + ", ".join(f"{j['label_from']}{j['number']}->{j['label_to']}{j['number']}" for j in data["jumps"])
        if data["jumps"]
        else "no jumps: with this drive every stationary regime is stable"
    )
    fig.suptitle(
        f"Motor torque and resistance (paper Figs. 3-4): {verdict}"
        + (f"\ntorque axis: the motor's range; {len(far)} jump(s) above it, in the panels below" if far else ""),
        fontsize=10,
    )
    blocks = []
    for n, r in enumerate(res):
        row, col = divmod(n, cols)
        ax = fig.add_subplot(gs[1 + 2 * row, col])
        mx = fig.add_subplot(gs[2 + 2 * row, col], sharex=ax)
        blocks.append((ax, _resonance_block(ax, mx, data, r, resonances_of(analysis), W, first=n == 0)))
    handles: dict[str, Any] = {}
    for a in fig.axes:
        for h, lab in zip(*a.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    # the legend outside every panel: it covers no curve
    fig.legend(
        list(handles.values()),
        list(handles.keys()),
        loc="outside lower center",
        ncol=min(4, len(handles)),
        fontsize=8,
        frameon=False,
    )
    # Labels last, on the final layout, frozen so that saving does not move the axes.
    freeze_layout(fig)
    place_labels(top, labels, lines=curves, drawn=True)
    for ax, jump_labels in blocks:
        place_labels(ax, jump_labels, lines=[ln for ln in ax.lines if len(ln.get_xdata()) > 2], drawn=True)
    return fig


def drive_chart(analysis: AnalysisResult, path: str | Path, width: int = 1060) -> Path:
    """Md and L over the speed (top) and near each resonance (below): the PNG."""
    return save(drive_figure(analysis, width), path)


def amplitude_chart(analysis: AnalysisResult, path: str | Path, width: int = 1060) -> Path:
    """a_i(z): averaging (the paper's Eq. 19) against the exact linear
    steady state, one panel per resonance, at most three to a row."""
    res = list(analysis.resonances)
    rows, cols = _grid_of(len(res))
    fig, axes = figure(width, 70 + 330 * rows, nrows=rows, ncols=cols, squeeze=False)
    for ax, r in zip(axes.flat, res):
        c = r.curves
        z = np.asarray(c.z)
        ax.plot(z, 1e3 * np.asarray(c.a), color=COLOURS["analytic"], label="averaging, Eq. 19")
        ax.plot(z, 1e3 * np.asarray(c.a_linear), color=COLOURS["numeric"], ls="--", label="linear steady state")
        ax.set_xlabel(f"z = Omega / omega_{r.index}")
        ax.set_ylabel(f"a_{r.index} (mm)")
        ax.set_title(
            f"resonance {r.index}: {r.omega:.2f} rad/s, {short(r.direction)}\n"
            f"nu = {r.nu:.3f}, a_max = {1e3 * r.a_max:.3g} mm",
            fontsize=9,
        )
    for ax in list(axes.flat)[len(res) :]:
        ax.set_visible(False)
    # outside the panels: it covers no curve
    fig.legend(*axes.flat[0].get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=8, frameon=False)
    return save(fig, path)
