"""Charts drawn from `rotorpillar analyze`.

- :func:`drive_chart`: the motor torque Md and the total resistance L over
  the speed, with the stable and unstable branches of the stationary regimes
  and the jumps A -> B (run-up) and D -> C (run-down): the paper's Figs. 3-4.
  L is evaluated by the closed forms of :mod:`rotorpillar.reduced.averaging`
  on the resonance parameters analyze.json carries (omega_i, f_i, g_i, nu_i),
  over the whole speed range, not only the +-50 % of the stored curves (a
  jump may land far beyond them); the tests check it against those curves.
  A regime on L is stable where the paper's equation 23 says so
  (:func:`rotorpillar.reduced.averaging.branch_is_stable`).
- :func:`amplitude_chart`: a_i(z) by averaging (the paper's equation 19,
  omega_i**2 restored) against the exact linear steady state, per resonance.

The analysis is read with attribute access (``analysis.drive.slope``), as
:func:`rotorpillar.postprocess.inputs.read_analysis` gives it.  The
earthquake, transient and convergence charts are drawn by
``transient_charts`` and ``convergence_charts``.
"""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ..reduced import averaging as av
from .style import COLOURS, blank, figure, save

def resonances_of(analysis) -> list:
    """The resonances of analyze.json as objects the averaging closed forms take."""
    return [SimpleNamespace(index=r.index, direction=r.direction, omega=r.omega,
                            forcing=r.forcing, coupling=r.coupling, nu=r.nu)
            for r in analysis.resonances]


def drive_curve_data(analysis, points: int = 6000) -> dict:
    """Everything the Md/L chart draws, as arrays (no plotting).

    Keys: omega (grid, rad/s), L (total resistance), Mc, Md (the scene's
    motor), stable (bool mask: the paper's equation 23 on L), jumps (list
    of dicts with the from/to points), stationary (list of records with
    omega and stable), top (grid end).
    """
    d = analysis.drive
    res = resonances_of(analysis)
    k, s, M0 = d.load_coefficient, d.slope, d.torque_at_zero
    ends = [1.6 * r.omega for r in res]
    free = d.free_speed
    if free is not None and math.isfinite(free):
        ends.append(1.08 * free)
    ends += [1.1 * j.omega_to for j in d.jumps] + [1.1 * j.omega_from for j in d.jumps]
    top = max(ends)
    grid = np.unique(np.concatenate([np.linspace(0.0, top, points)]
                                    + [r.omega * (1 + r.nu * np.linspace(-8, 8, 801)) for r in res]))
    grid = grid[(grid >= 0) & (grid <= top)]
    L = av.total_resistance(grid, k, res)
    jumps = []
    for n, j in enumerate(d.jumps, start=1):
        up = j.direction == "up"
        level = j.torque_at_zero
        jumps.append({"direction": j.direction, "resonance": j.resonance,
                      "label_from": ("A" if up else "D"), "label_to": ("B" if up else "C"),
                      "number": n, "level": level,
                      "from": (j.omega_from, level - s * j.omega_from),
                      "to": (j.omega_to, level - s * j.omega_to)})
    return {"omega": grid, "L": L, "Mc": k * grid**2, "Md": M0 - s * grid,
            "stable": np.asarray(av.branch_is_stable(grid, s, k, res), dtype=bool),
            "jumps": jumps, "stationary": d.stationary,
            "slope": s, "torque_at_zero": M0, "top": top}


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
        ax.plot(x[sl], y[sl], color=COLOURS["stable" if st else "unstable"],
                ls="-" if st else "--", lw=1.8 if st else 1.6,
                label=name if (label and name not in seen) else None)
        seen.add(name)


def _jump_arrows(ax, jumps, s, xlim, z_scale=1.0):
    for j in jumps:
        (x0, y0), (x1, y1) = j["from"], j["to"]
        xs = np.linspace(*xlim, 50)
        ax.plot(xs / z_scale, j["level"] - s * xs, color=COLOURS["drive"], lw=0.7, ls=":")
        ax.annotate("", xy=(x1 / z_scale, y1), xytext=(x0 / z_scale, y0),
                    arrowprops=dict(arrowstyle="->", color="black", lw=1.2))
        n = j["number"]
        for (x, y), name in (((x0, y0), j["label_from"]), ((x1, y1), j["label_to"])):
            ax.plot([x / z_scale], [y], "o", color="black", ms=3.5)
            ax.annotate(f"{name}{n}", (x / z_scale, y), textcoords="offset points", xytext=(4, 4),
                        fontsize=8)


def drive_chart(analysis, path: str | Path, size=(1000, 760)) -> Path:
    """Md and L over the speed (top) and near each resonance (bottom)."""
    data = drive_curve_data(analysis)
    res = analysis.resonances
    fig = blank(*size)
    gs = fig.add_gridspec(2, len(res), height_ratios=[1.15, 1])
    top = fig.add_subplot(gs[0, :])
    zooms = [fig.add_subplot(gs[1, i]) for i in range(len(res))]
    W, s = data["omega"], data["slope"]
    top.plot(W, data["Mc"], color=COLOURS["load"], ls=":", label="Mc = k Omega^2 (load alone)")
    _branches(top, W, data["L"], data["stable"])
    top.plot(W, data["Md"], color=COLOURS["drive"],
             label=f"Md = {data['torque_at_zero']:g} - {s:g} Omega (scene's motor)")
    for st in data["stationary"]:
        y = data["torque_at_zero"] - s * st.omega
        top.plot([st.omega], [y], "o", ms=7, mec="black",
                 mfc=COLOURS["stable"] if st.stable else "white")
        top.annotate(f"{st.omega:.2f} rad/s ({'stable' if st.stable else 'unstable'})",
                     (st.omega, y), textcoords="offset points", xytext=(-10, 10), ha="right",
                     fontsize=8)
    _jump_arrows(top, data["jumps"], s, (0, data["top"]))
    for r in res:
        top.axvline(r.omega, color=COLOURS["reference"], lw=0.6, ls="--")
        top.annotate(f"omega_{r.index}", (r.omega, 0), textcoords="offset points",
                     xytext=(2, 2), fontsize=7, color="#666666", rotation=90)
    y_hi = max(float(np.max(data["L"])), data["torque_at_zero"]) * 1.05
    top.set_xlim(0, data["top"])
    top.set_ylim(0, y_hi)
    top.set_xlabel("Omega (rad/s)")
    top.set_ylabel("torque (N*m)")
    verdict = (f"{len(data['jumps'])} jump(s): " + ", ".join(
        f"{j['label_from']}{j['number']}->{j['label_to']}{j['number']}" for j in data["jumps"])
        if data["jumps"] else "no jumps: with this drive every stationary regime is stable")
    top.set_title(f"Motor torque and resistance (paper Figs. 3-4) - {verdict}")
    top.legend(loc="upper left")
    # zooms: near each resonance, in z = Omega / omega_i as the paper draws them
    for ax, r in zip(zooms, res):
        w = r.omega
        lo, hi = 0.5 * w, 1.5 * w
        mine = [j for j in data["jumps"] if j["resonance"] == r.index]
        for j in mine:
            lo = min(lo, 0.95 * j["from"][0], 0.95 * j["to"][0])
            hi = max(hi, 1.05 * j["from"][0], 1.05 * j["to"][0])
        m = (W >= lo) & (W <= hi)
        ax.plot(W[m] / w, data["Mc"][m], color=COLOURS["load"], ls=":")
        _branches(ax, W[m] / w, data["L"][m], data["stable"][m], label=False)
        c = r.curves
        ax.plot(c.z[::8], c.L_all[::8], ".", color="black", ms=2.5,
                label="analyze.json curve" if r is res[0] else None)
        _jump_arrows(ax, mine, s, (lo, hi), z_scale=w)
        ys = [data["L"][m]] + [np.array([j["from"][1], j["to"][1]]) for j in mine]
        y0, y1 = float(min(map(np.min, ys))), float(max(map(np.max, ys)))
        pad = 0.08 * (y1 - y0 or 1.0)
        ax.set_ylim(y0 - pad, y1 + pad)
        ax.set_xlim(lo / w, hi / w)
        ax.set_xlabel(f"z = Omega / omega_{r.index}")
        ax.set_ylabel("torque (N*m)")
        note = f"{len(mine)} jump(s)" if mine else "no jump"
        ax.set_title(f"res. {r.index} ({r.direction}, {w:.2f} rad/s): {note}", fontsize=9)
        # the resonance's own torque, visible even where it is ~1 % of Mc
        extra = ax.twinx()
        extra.plot(W[m] / w, data["L"][m] - data["Mc"][m], color=COLOURS["accent"], lw=1.0,
                   label="L - Mc (right axis)")
        extra.set_ylabel("L - Mc (N*m)", color=COLOURS["accent"])
        extra.grid(False)
        extra.spines["right"].set_visible(True)
        if r is res[0]:
            extra.legend(loc="lower right", fontsize=7)
        if r is res[0]:
            ax.legend(loc="upper left", fontsize=7)
    return save(fig, path)


def amplitude_chart(analysis, path: str | Path, size=(1000, 360)) -> Path:
    """a_i(z): averaging (the paper's equation 19) against the exact linear steady state."""
    res = analysis.resonances
    fig, axes = figure(*size, ncols=len(res), squeeze=False)
    for ax, r in zip(axes[0], res):
        c = r.curves
        z = np.asarray(c.z)
        ax.plot(z, 1e3 * np.asarray(c.a), color=COLOURS["analytic"], label="averaging, Eq. 19")
        ax.plot(z, 1e3 * np.asarray(c.a_linear), color=COLOURS["numeric"], ls="--",
                label="linear steady state")
        ax.set_xlabel(f"z = Omega / omega_{r.index}")
        ax.set_ylabel(f"a_{r.index} (mm)")
        ax.set_title(f"resonance {r.index} ({r.direction}), omega = {r.omega:.2f} rad/s, "
                     f"nu = {r.nu:.3f}", fontsize=9)
        if r is res[0]:
            ax.legend(fontsize=7)
    return save(fig, path)
