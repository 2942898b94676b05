"""Charts of the transient runs: data in, PNG path out (matplotlib Agg, lazy).

- ``runup_chart``: rotor speed and tip amplitude against time, the
  resonances marked, and optional extra speed histories (weaker and stronger
  motors); beside it, zoomed on the passage through the resonances, the
  speed with each crossing's Omega-dot / omega**2 (how far from
  quasi-static) and the tip's X against the averaging's +-a_max;
- ``earthquake_chart``: ground acceleration, tip and rotor displacement and
  the rotor speed, the interval when the ground moves shaded (drawn by
  `rotorpillar simulate` and by the report);
- ``sweep_chart``: the quasi-static sweep against the averaging theory: the
  stationary curve M0(Omega) (numeric up and down, the paper's equations
  19-23 and the exact linear balance) with the jumps, and the amplitude
  against z = Omega/omega_i (numeric, the paper's Eq. 19, exact), with
  the relative error;
- ``integrators_chart``: error against cost per integrator, stability as
  modes are added, energy drift.

Figures, colours and the atomic PNG write come from :mod:`.style`.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..records import Figure
from .style import COLOURS, CYCLE, figure, save

if TYPE_CHECKING:
    from ..scene import Scene
    from ..transients.integrator_study import AccuracyRow, DriftRow, StabilityRow
    from ..transients.sweep import SweepAnalysis

#: Standard gravity, to show the ground acceleration in g (m/s**2).
STANDARD_GRAVITY = 9.80665


def envelope(x, t, window: float):
    """Running maximum of |x| over ``window`` seconds (an amplitude envelope)."""
    from scipy.ndimage import maximum_filter1d

    t = np.asarray(t)
    dt = (t[-1] - t[0]) / max(len(t) - 1, 1)
    return maximum_filter1d(np.abs(np.asarray(x)), size=max(1, int(round(window / dt))))


def crossings(t, Omega, resonances) -> list[tuple[str, float, float, float]]:
    """Where a run crosses each resonance: [(label, omega, t, dOmega/dt)] for
    each (label, omega) the speed reaches, in time order (the first
    crossing; dOmega/dt from the samples around it, rad/s**2).

    >>> t = np.linspace(0, 2, 201); [(l, w, round(tc, 3), round(a, 3)) for l, w, tc, a in crossings(t, 10 * t, [("a", 5.0)])]
    [('a', 5.0, 0.5, 10.0)]
    """
    t, W = np.asarray(t, dtype=float), np.asarray(Omega, dtype=float)
    out = []
    for label, w in resonances:
        k = np.flatnonzero((W[:-1] - w) * (W[1:] - w) <= 0)
        if not len(k):
            continue
        i = int(k[0])
        tc = t[i] + (w - W[i]) / (W[i + 1] - W[i]) * (t[i + 1] - t[i]) if W[i + 1] != W[i] else t[i]
        j0, j1 = max(i - 2, 0), min(i + 3, len(t) - 1)
        out.append((label, float(w), float(tc), float((W[j1] - W[j0]) / (t[j1] - t[j0]))))
    return sorted(out, key=lambda c: c[2])


def passage_window(t, passes) -> tuple[float, float] | None:
    """The time window around a run's passages through its resonances
    (``crossings``): from the first to the last, widened by their span (at
    least a tenth of a second) on each side; None without a passage."""
    if not passes:
        return None
    t0, t1 = min(c[2] for c in passes), max(c[2] for c in passes)
    pad = max(t1 - t0, 0.1)
    # the response rings on after the last crossing: twice the room after it
    return max(float(t[0]), t0 - pad), min(float(t[-1]), t1 + 2 * pad)


def runup_chart(
    path,
    t,
    Omega,
    tip_peak,
    resonances,
    title: str = "",
    extra_runs=None,
    label: str = "this run",
    tip=None,
    a_max=None,
) -> Path:
    """Omega(t) and the tip envelope over the whole run (left) and, where
    the run crosses resonances, zoomed on the passage (right): the speed with
    each crossing's Omega-dot / omega**2, the tip's X itself with the
    averaging's stationary amplitude +-a_max of each resonance beside it.
    ``resonances`` = [(label, omega)]; ``extra_runs`` = [(label, t, Omega,
    tip_peak or None)]; ``tip``: the tip's X (m); ``a_max``: {label: m}."""
    from .style import freeze_layout, place_labels

    t, Omega = np.asarray(t, dtype=float), np.asarray(Omega, dtype=float)
    passes = crossings(t, Omega, resonances)
    window = passage_window(t, passes)
    fig, axes = figure(
        1060,
        715,
        nrows=2,
        ncols=2 if window else 1,
        squeeze=False,
        sharex="col",
        width_ratios=(1, 1) if window else None,
    )
    (a1, a2) = axes[:, 0]
    a1.plot(t, Omega, lw=1.6, label=label, color=COLOURS["drive"])
    span = t[-1] - t[0]
    env_window = 0.01 * span
    for (lab, tt, W, pk), c in zip(extra_runs or [], CYCLE[1:]):
        a1.plot(tt, W, lw=1.0, ls="--", label=lab, color=c)
        if pk is not None:
            a2.plot(tt, 1e3 * envelope(pk, tt, env_window), lw=0.9, ls="--", color=c)
    labels = []
    for name, w in resonances:
        a1.axhline(w, color=COLOURS["reference"], lw=0.7, ls=":")
        labels.append(
            {"xy": (t[-1], w), "offset": (-4, 2), "ha": "right", "fontsize": 8, "color": "0.35", "text": name}
        )
    a1.set_ylabel("rotor speed Omega [rad/s]")
    a1.legend(loc="lower right", fontsize=8)
    a1.set_title("the whole run" + ("\n" if window else ""), fontsize=9)
    a2.plot(t, 1e3 * envelope(tip_peak, t, env_window), lw=1.2, color=COLOURS["drive"])
    a2.set_ylabel(f"|tip, horizontal X| envelope\nover {env_window:.2g} s [mm]")
    a2.set_xlabel("t [s]")
    zoom_labels = []
    if window:
        z1, z2 = axes[:, 1]
        sel = (t >= window[0]) & (t <= window[1])
        z1.plot(t[sel], Omega[sel], lw=1.6, color=COLOURS["drive"])
        for name, w, tc, acc in passes:
            z1.axhline(w, color=COLOURS["reference"], lw=0.7, ls=":")
            z1.plot([tc], [w], "o", color=COLOURS["unstable"], ms=4)
            zoom_labels.append(
                {"xy": (tc, w), "offset": (6, -10), "fontsize": 8, "text": f"{name.split(' ')[0]}: {acc / w**2:.2g}"}
            )
        z1.set_title(
            f"the passage, {window[0]:.3g} .. {window[1]:.3g} s\nat each crossing: Omega-dot / omega^2", fontsize=9
        )
        y = np.asarray(tip if tip is not None else tip_peak, dtype=float)[sel]
        z2.plot(t[sel], 1e3 * y, lw=0.8, color=COLOURS["drive"], label="tip X" if tip is not None else "|tip X|")
        for (name, _w), c in zip(resonances, CYCLE[1:]):
            a = (a_max or {}).get(name)
            if a is None or not any(p[0] == name for p in passes):
                continue
            for sgn in (1, -1) if tip is not None else (1,):
                z2.axhline(
                    sgn * 1e3 * a, color=c, lw=0.9, ls="--", label=f"+-a_max, {name} (averaging)" if sgn == 1 else None
                )
        z2.set_ylabel("tip, horizontal X [mm]")
        z2.set_xlabel("t [s]")
        z2.legend(loc="upper right", fontsize=8)
    fig.suptitle(title, fontsize=10)
    freeze_layout(fig)
    place_labels(a1, labels, lines=[ln for ln in a1.lines if len(ln.get_xdata()) > 2], drawn=True)
    if window:
        place_labels(axes[0, 1], zoom_labels, lines=[axes[0, 1].lines[0]], drawn=True)
    return save(fig, path)


def _plain_axis(ax, y) -> None:
    """No offset notation, and a visible band around a (nearly) constant signal
    instead of its round-off noise blown up to the full height."""
    ax.ticklabel_format(axis="y", useOffset=False, style="plain")
    y = np.asarray(y, dtype=float)
    y = y[np.isfinite(y)]
    if y.size and np.ptp(y) <= 1e-6 * max(np.abs(y).max(), 1e-300):
        c = float(np.mean(y))
        pad = 0.1 * abs(c) if c != 0 else 1.0
        ax.set_ylim(c - pad, c + pad)


def earthquake_chart(
    path, t, ground_acceleration, tip_x, rotor_x, Omega, title: str = "", frame: str = "", size=(900, 800)
) -> Path:
    """Ground acceleration (in g), the tip's and the rotor's X (in ``frame``,
    e.g. "absolute") and the rotor speed against time; the interval when the
    ground moves is shaded.  A series that is None (not stored) leaves its
    panel empty."""
    t = np.asarray(t, dtype=float)
    as_array = lambda x: None if x is None else np.asarray(x, dtype=float)
    ground, tip, rotor, Om = map(as_array, (ground_acceleration, tip_x, rotor_x, Omega))
    fig, ax = figure(*size, nrows=4, sharex=True)
    if ground is not None:
        ax[0].plot(t, ground / STANDARD_GRAVITY, lw=0.8, color=COLOURS["ground"])
    ax[0].set_ylabel("ground acceleration,\nhorizontal X [g]")
    if tip is not None:
        ax[1].plot(t, tip, lw=0.8, color=COLOURS["drive"])
    ax[1].set_ylabel(f"tip, horizontal X [m]\n{frame}" if frame else "tip, horizontal X [m]")
    if rotor is not None:
        ax[2].plot(t, rotor, lw=0.8, color=COLOURS["unstable"])
    ax[2].set_ylabel("rotor, horizontal X [m]")
    if Om is not None:
        ax[3].plot(t, Om, lw=0.8, color=COLOURS["drive"])
        _plain_axis(ax[3], Om)
    ax[3].set_ylabel("Omega [rad/s]")
    ax[3].set_xlabel("t [s]")
    if ground is not None:
        moving = np.flatnonzero(np.abs(ground) > 1e-12 * max(1.0, np.abs(ground).max()))
        if moving.size:
            for a in ax:
                a.axvspan(t[moving[0]], t[moving[-1]], color=COLOURS["ground"], alpha=0.08, lw=0)
    ax[0].set_title(title or "Earthquake response")
    return save(fig, path)


def sweep_chart(path, sweep: SweepAnalysis, resonances, title: str = "") -> Path:
    """Two panels: M0 against Omega (stationary curves and jumps) and the
    amplitude against z for the resonance(s) the sweep crosses.

    ``sweep``: the sweep's bins up and down, its curves (omega, F_averaging,
    F_exact, exact {tip_x, rotor_y}, eq19 {label: a}) and jumps;
    resonances: [(label, omega, direction)].
    """
    up, down, curves = sweep.up, sweep.down, sweep.curves
    fig, (a1, a2) = figure(1060, 605, ncols=2)
    W = np.asarray(curves["omega"])
    lo = min(np.nanmin(up.omega), np.nanmin(down.omega)) * 0.95
    hi = max(np.nanmax(up.omega), np.nanmax(down.omega)) * 1.02
    sel = (W >= lo) & (W <= hi)
    a1.plot(
        W[sel],
        np.asarray(curves["F_averaging"])[sel],
        color=COLOURS["analytic"],
        lw=1.2,
        label="Eq. 19-23: M0 = L + s Omega",
    )
    a1.plot(
        W[sel],
        np.asarray(curves["F_exact"])[sel],
        color=COLOURS["stable"],
        lw=1.0,
        ls="--",
        label="exact linear balance",
    )
    a1.plot(
        up.omega,
        up.M0_inertia_corrected,
        ".",
        ms=3,
        color=COLOURS["rising"],
        label="numeric, M0 rising (M0 - J dOmega/dt)",
    )
    a1.plot(
        down.omega,
        down.M0_inertia_corrected,
        ".",
        ms=3,
        color=COLOURS["falling"],
        label="numeric, M0 falling (M0 - J dOmega/dt)",
    )
    for jp in sweep.predicted_jumps:
        a1.annotate(
            "",
            xy=(jp.omega_to, jp.torque_at_zero),
            xytext=(jp.omega_from, jp.torque_at_zero),
            arrowprops=dict(arrowstyle="->", color=COLOURS["analytic"], lw=1.0),
        )
    for j in sweep.numeric_jumps:
        c = COLOURS["rising"] if j.direction == "up" else COLOURS["falling"]
        a1.annotate(
            "",
            xy=(j.omega_to, j.torque_at_zero),
            xytext=(j.omega_from, j.torque_at_zero),
            arrowprops=dict(arrowstyle="->", color=c, lw=1.0, ls="--"),
        )
    a1.set_xlabel("Omega [rad/s]")
    a1.set_ylabel("M0 [N*m]")
    a1.legend(fontsize=8, loc="upper left")
    # amplitude panel: the X resonances on the tip, Y on the rotor
    for label, w, direction in resonances:
        if not (lo <= w <= hi):
            continue
        key = "tip_x" if direction == "X" else "rotor_y"
        a2.plot(W[sel] / w, 1e3 * np.asarray(curves["eq19"][label])[sel], lw=1.2, label=f"Eq. 19, {label} ({key})")
        a2.plot(W[sel] / w, 1e3 * np.asarray(curves["exact"][key])[sel], lw=0.9, ls="--", label=f"exact linear ({key})")
        a2.plot(
            np.asarray(up.omega) / w,
            1e3 * np.asarray(up.column(key)),
            ".",
            ms=3,
            color=COLOURS["rising"],
            label=f"numeric, rising ({key})",
        )
        a2.plot(
            np.asarray(down.omega) / w,
            1e3 * np.asarray(down.column(key)),
            ".",
            ms=3,
            color=COLOURS["falling"],
            label=f"numeric, falling ({key})",
        )
        a2.set_xlim(0.7, 1.3)
        break
    a2.set_xlabel("z = Omega / omega_i")
    a2.set_ylabel("amplitude [mm]")
    if a2.get_legend_handles_labels()[0]:  # no resonance in the sweep's range: nothing drawn
        a2.legend(fontsize=7, loc="upper right")
    fig.suptitle(title)
    return save(fig, path)


#: Markers of the integrators' lines: with the colours of CYCLE, every method its own pair.
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "<", ">", "*")


def method_styles(methods) -> dict:
    """A distinct (colour, marker) per method, in sorted order; dp5 and RK45
    (the same Dormand-Prince pair, compiled and scipy's) are drawn so that
    both show where they coincide: dp5 a large open circle around RK45's marker.

    >>> st = method_styles(["dp5", "RK45", "BDF"]); len({(v["color"], v["marker"]) for v in st.values()})
    3
    """
    palette = CYCLE + ["#8c564b", "#7f7f7f", "#bcbd22"]
    out = {}
    for k, m in enumerate(sorted(methods)):
        out[m] = dict(color=palette[k % len(palette)], marker=MARKERS[k % len(MARKERS)], ms=4)
    if "dp5" in out:
        out["dp5"].update(marker="o", ms=9, mfc="none", mew=1.4)
    return out


def integrators_chart(
    path,
    accuracy_rows: Sequence[AccuracyRow],
    stability_rows: Sequence[StabilityRow],
    drift_rows: Sequence[DriftRow],
    title: str = "",
) -> Path:
    """The rows of the integrator study's three experiments
    (``rotorpillar.transients.integrator_study``).
    Three panels stacked: error against force evaluations, cost and
    failure as modes are added, energy drift; one colour and marker per
    method throughout, one legend for all."""
    methods = sorted(
        {r.method for r in accuracy_rows} | {r.method for r in stability_rows} | {r.method for r in drift_rows}
    )
    style = method_styles(methods)
    fig, ax = figure(1060, 1100, nrows=3, height_ratios=(1.2, 1.0, 0.9))
    for m in methods:
        # along the ladder (loose to tight), cost as force evaluations: the
        # wall time of a shared machine is too noisy for a curve
        rows = sorted(
            (r for r in accuracy_rows if r.method == m and r.error is not None and np.isfinite(r.error)),
            key=lambda r: -r.setting,
        )
        if rows:
            ls = "--" if rows[0].family == "fixed" else "-"
            errors = [max(r.error or 0.0, 1e-16) for r in rows]  # the rows kept have one
            ax[0].loglog([r.nfev for r in rows], errors, ls=ls, lw=1, label=m, **style[m])
    ax[0].axhline(0.1, color=COLOURS["reference"], lw=0.7, ls=":")
    ax[0].set_xlabel("force evaluations (dashed lines: fixed step)")
    ax[0].set_ylabel("max tip error / max tip")
    ax[0].set_title("accuracy against cost on a run-up (dotted: 10 % error)", fontsize=10)
    ax[0].grid(alpha=0.3, which="both")
    for m in sorted({r.method for r in stability_rows}):
        srows = sorted((r for r in stability_rows if r.method == m), key=lambda r: r.modes)
        xs = [r.omega_max for r in srows]
        ys = [r.nfev if r.ok else np.nan for r in srows]
        ax[1].loglog(xs, ys, "-", lw=1, **style[m])
        bad = [r.omega_max for r in srows if not r.ok]
        if bad:
            top = max(y for y in ys if np.isfinite(y)) if np.isfinite(ys).any() else 1
            ax[1].plot(bad, [top] * len(bad), "x", color=style[m]["color"], ms=8, mew=2)
    ax[1].set_xlabel("highest structural frequency [rad/s] (pillar modes added)")
    ax[1].set_ylabel("force evaluations (x = failed)")
    ax[1].set_title("stiffness: cost and stability as modes are added", fontsize=10)
    ax[1].grid(alpha=0.3, which="both")
    names = [r.method for r in drift_rows]
    vals = [max(abs(r.drift), 1e-17) if r.drift is not None else np.nan for r in drift_rows]
    ax[2].barh(names, vals, log=True, color=[style[n]["color"] for n in names])
    ax[2].set_xlabel("|relative energy drift|, undamped and unforced")
    ax[2].set_title("energy drift", fontsize=10)
    ax[2].grid(alpha=0.3, axis="x")
    handles, labels = ax[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside right upper", fontsize=8, title="integrator", title_fontsize=8)
    fig.suptitle(title, fontsize=10)
    return save(fig, path)


def model_run_charts(out: Path, scene: Scene, run: Any, stem: str) -> list[Figure]:
    """A transient run's charts (a ``rotorpillar.transients.model_run.ModelRun``): the
    earthquake's histories, the run-up's or run-down's speed and tip envelope,
    the sweep's curves; returns [{file, caption}]."""
    data, case, name = run.data, run.case, run.model
    frame = run.record.tip_x_frame.replace("_", " ")
    title = f"{scene.name}: {case}, {name} model"
    path = out / f"{stem}.png"
    if case == "earthquake":
        earthquake_chart(
            path,
            data["t"],
            data["ground_acceleration"],
            data["tip_x"],
            data["rotor_x"],
            data["Omega"],
            title,
            frame=frame,
        )
        return [
            Figure(
                file=path.name,
                caption=f"Earthquake on the {name} model: ground acceleration, tip and rotor X ({frame}), rotor speed.",
            )
        ]
    resonances = [
        (f"omega_{r.index} ({r.direction})", r.omega)
        for r in run.resonances
        if r.omega <= 1.2 * max(np.max(data["Omega"]), 1.0)
    ]
    from ..reduced.stationary import PassingTorqueStudy
    from ..transients.model_run import ReducedRun

    extra = []
    pt = run.record.passing_torque if isinstance(run.record, ReducedRun) else None
    if isinstance(pt, PassingTorqueStudy):
        bs = pt.bracket_series
        for row, W, pk, f in zip(pt.bracket_runs, bs.Omega, bs.tip_peak, (0.95, 1.05)):
            extra.append(
                (
                    f"M0 = {row.torque_at_zero:.0f} N*m ({f:g} x the predicted {pt.predicted:.0f})",
                    np.asarray(bs.t),
                    np.asarray(W),
                    np.asarray(pk),
                )
            )
    tip_peak = data["peak"][:, -1] if data["peak"].ndim == 2 else np.abs(data["tip_x"])
    from ..reduced import averaging as av

    a_max = {
        f"omega_{r.index} ({r.direction})": float(av.amplitude(r.omega, r))
        for r in run.resonances
        if str(r.direction) == "X"
    }
    tip = data.get("tip_x_relative", data["tip_x"])
    runup_chart(
        path,
        data["t"],
        data["Omega"],
        tip_peak,
        resonances,
        title,
        extra,
        label=f"M0 = {scene.drive.torque_at_zero:g} N*m (the scene's motor)" if case == "runup" else "this run",
        tip=tip,
        a_max=a_max,
    )
    zoom = (
        " Right: zoomed on the passage through the resonances, each crossing's "
        "Omega-dot / omega^2, the tip's X against the averaging's stationary +-a_max."
    )
    caption = {
        "runup": "Run-up from rest: rotor speed and tip envelope"
        + (" (dashed: motors 5 % below and above the torque the analysis says is needed to pass)." if extra else ".")
        + zoom,
        "rundown": "Run-down from the operating speed: rotor speed and tip envelope." + zoom,
        "sweep": "Quasi-static sweep of M0 up and down: rotor speed and tip envelope.",
    }[case]
    figs = [Figure(file=path.name, caption=caption)]
    if case == "sweep" and run.case_result is not None:
        sweep = run.case_result.sweep
        labels = [(f"{r.direction}{r.index}", r.omega, r.direction) for r in run.resonances]
        labels.sort(
            key=lambda L: (
                -max((a.numeric_peak for a in sweep.amplitudes if f"{a.direction}{a.index}" == L[0]), default=0.0)
            )
        )
        p2 = out / f"{stem}_az.png".replace(f"_{name}_az", f"_az_{name}")
        sweep_chart(p2, sweep, labels, f"{scene.name}: quasi-static sweep against Eq. 19-23")
        figs.append(
            Figure(
                file=p2.name,
                caption="Quasi-static sweep against the averaging theory: "
                "stationary curve M0(Omega) with the jumps (left), "
                "amplitude against z = Omega/omega_i (right).",
            )
        )
    return figs
