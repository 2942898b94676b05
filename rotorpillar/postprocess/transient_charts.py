"""Charts of the transient runs: data in, PNG path out (matplotlib Agg, lazy).

- ``runup_chart``: rotor speed and tip amplitude against time, the
  resonances marked, and optional extra speed histories (weaker and stronger
  motors);
- ``earthquake_chart``: ground acceleration, tip and rotor displacement;
- ``sweep_chart``: the quasi-static sweep against the averaging theory: the
  stationary curve M0(Omega) (numeric up and down, Eq. 19-23 and the exact
  linear balance) with the jumps, and the amplitude against z = Omega/omega_i
  (numeric, Eq. 19, exact), with the relative error;
- ``integrators_chart``: error against cost per integrator, stability as
  modes are added, energy drift.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..provenance import atomic_path

FIGSIZE = (10.0, 6.5)
DPI = 110


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _save(fig, path) -> Path:
    path = Path(path)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=DPI, format="png")
    _plt().close(fig)
    return path


def envelope(x, t, window: float):
    """Running maximum of |x| over ``window`` seconds (an amplitude envelope)."""
    from scipy.ndimage import maximum_filter1d
    t = np.asarray(t)
    dt = (t[-1] - t[0]) / max(len(t) - 1, 1)
    return maximum_filter1d(np.abs(np.asarray(x)), size=max(1, int(round(window / dt))))


def runup_chart(path, t, Omega, tip_peak, resonances, title: str = "", extra_runs=None,
                label: str = "this run") -> Path:
    """Omega(t) and the tip envelope; ``resonances`` = [(label, omega)];
    ``extra_runs`` = [(label, t, Omega, tip_peak or None)]."""
    plt = _plt()
    fig, (a1, a2) = plt.subplots(2, 1, figsize=FIGSIZE, sharex=True)
    a1.plot(t, Omega, lw=1.6, label=label, color="tab:blue")
    window = 0.01 * (t[-1] - t[0])
    for (lab, tt, W, pk), c in zip(extra_runs or [], ("tab:orange", "tab:green", "tab:red", "tab:purple")):
        a1.plot(tt, W, lw=1.0, ls="--", label=lab, color=c)
        if pk is not None:
            a2.plot(tt, 1e3 * envelope(pk, tt, window), lw=0.9, ls="--", color=c)
    for label, w in resonances:
        a1.axhline(w, color="0.6", lw=0.7, ls=":")
        a1.text(t[-1], w, f" {label}", va="center", fontsize=8, color="0.35")
    a1.set_ylabel("rotor speed Omega [rad/s]")
    a1.legend(loc="lower right", fontsize=8)
    a1.set_title(title)
    a2.plot(t, 1e3 * envelope(tip_peak, t, window), lw=1.2, color="tab:blue")
    a2.set_ylabel("|tip X| envelope [mm]")
    a2.set_xlabel("t [s]")
    for a in (a1, a2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    return _save(fig, path)


def earthquake_chart(path, t, ground_acceleration, tip_x, rotor_x, Omega, title: str = "",
                     frame: str = "") -> Path:
    plt = _plt()
    fig, ax = plt.subplots(4, 1, figsize=(10.0, 8.0), sharex=True)
    ax[0].plot(t, np.asarray(ground_acceleration) / 9.80665, lw=0.8)
    ax[0].set_ylabel("ground a_g [g]")
    ax[1].plot(t, tip_x, lw=0.8)
    ax[1].set_ylabel(f"tip X [m]\n{frame}")
    ax[2].plot(t, rotor_x, lw=0.8)
    ax[2].set_ylabel("rotor X [m]")
    ax[3].plot(t, Omega, lw=0.8)
    ax[3].set_ylabel("Omega [rad/s]")
    ax[3].set_xlabel("t [s]")
    ax[0].set_title(title)
    for a in ax:
        a.grid(alpha=0.3)
    fig.tight_layout()
    return _save(fig, path)


def sweep_chart(path, up: dict, down: dict, curves: dict, resonances, jumps_numeric,
                jumps_predicted, title: str = "") -> Path:
    """Two panels: M0 against Omega (stationary curves and jumps) and the
    amplitude against z for the resonance(s) the sweep crosses.

    up/down: bins with M0, omega, tip_x, rotor_y; curves: omega,
    F_averaging, F_exact, exact {tip_x, rotor_y}, eq19 {label: a};
    resonances: [(label, omega, direction)].
    """
    plt = _plt()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12.0, 5.5))
    W = np.asarray(curves["omega"])
    lo = min(np.nanmin(up["omega"]), np.nanmin(down["omega"])) * 0.95
    hi = max(np.nanmax(up["omega"]), np.nanmax(down["omega"])) * 1.02
    sel = (W >= lo) & (W <= hi)
    a1.plot(W[sel], np.asarray(curves["F_averaging"])[sel], color="k", lw=1.2,
            label="Eq. 19-23: M0 = L + s Omega")
    a1.plot(W[sel], np.asarray(curves["F_exact"])[sel], color="tab:green", lw=1.0, ls="--",
            label="exact linear balance")
    key = "M0_inertia_corrected" if "M0_inertia_corrected" in up else "M0"
    a1.plot(up["omega"], up[key], ".", ms=3, color="tab:red", label="numeric, M0 rising (M0 - J dOmega/dt)")
    a1.plot(down["omega"], down[key], ".", ms=3, color="tab:blue", label="numeric, M0 falling (M0 - J dOmega/dt)")
    for j in jumps_predicted:
        a1.annotate("", xy=(j["omega_to"], j["torque_at_zero"]), xytext=(j["omega_from"], j["torque_at_zero"]),
                    arrowprops=dict(arrowstyle="->", color="k", lw=1.0))
    for j in jumps_numeric:
        c = "tab:red" if j["direction"] == "up" else "tab:blue"
        a1.annotate("", xy=(j["omega_to"], j["torque_at_zero"]), xytext=(j["omega_from"], j["torque_at_zero"]),
                    arrowprops=dict(arrowstyle="->", color=c, lw=1.0, ls="--"))
    a1.set_xlabel("Omega [rad/s]")
    a1.set_ylabel("M0 [N*m]")
    a1.legend(fontsize=8, loc="upper left")
    a1.grid(alpha=0.3)
    # amplitude panel: the X resonances on the tip, Y on the rotor
    for label, w, direction in resonances:
        if not (lo <= w <= hi):
            continue
        key = "tip_x" if direction == "X" else "rotor_y"
        a2.plot(W[sel] / w, 1e3 * np.asarray(curves["eq19"][label])[sel], lw=1.2,
                label=f"Eq. 19, {label} ({key})")
        a2.plot(W[sel] / w, 1e3 * np.asarray(curves["exact"][key])[sel], lw=0.9, ls="--",
                label=f"exact linear ({key})")
        a2.plot(np.asarray(up["omega"]) / w, 1e3 * np.asarray(up[key]), ".", ms=3, color="tab:red",
                label=f"numeric, rising ({key})")
        a2.plot(np.asarray(down["omega"]) / w, 1e3 * np.asarray(down[key]), ".", ms=3,
                color="tab:blue", label=f"numeric, falling ({key})")
        a2.set_xlim(0.7, 1.3)
        break
    a2.set_xlabel("z = Omega / omega_i")
    a2.set_ylabel("amplitude [mm]")
    a2.legend(fontsize=7, loc="upper right")
    a2.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    return _save(fig, path)


def integrators_chart(path, accuracy_rows, stability_rows, drift_rows, title: str = "") -> Path:
    """accuracy_rows: [{method, wall_seconds, nfev, error}]; stability_rows:
    [{method, modes, omega_max, ok, nfev}]; drift_rows: [{method, drift}]."""
    plt = _plt()
    fig, ax = plt.subplots(1, 3, figsize=(15.0, 5.0))
    methods = sorted({r["method"] for r in accuracy_rows})
    for m in methods:
        # along the ladder (loose to tight), cost as force evaluations: the
        # wall time of a shared machine is too noisy for a curve
        rows = sorted((r for r in accuracy_rows if r["method"] == m and r["error"] is not None
                       and np.isfinite(r["error"])), key=lambda r: -r["setting"])
        if rows:
            ls = "--" if rows[0].get("family") == "fixed" else "-"
            ax[0].loglog([r["nfev"] for r in rows], [max(r["error"], 1e-16) for r in rows],
                         "o", ls=ls, ms=3, lw=1, label=m)
    ax[0].axhline(0.1, color="0.5", lw=0.7, ls=":")
    ax[0].set_xlabel("force evaluations (dashed: fixed step)")
    ax[0].set_ylabel("max tip error / max tip")
    ax[0].set_title("accuracy against cost (run-up)")
    ax[0].legend(fontsize=7)
    ax[0].grid(alpha=0.3, which="both")
    for m in sorted({r["method"] for r in stability_rows}):
        rows = sorted((r for r in stability_rows if r["method"] == m), key=lambda r: r["modes"])
        xs = [r["omega_max"] for r in rows]
        ys = [r["nfev"] if r["ok"] else np.nan for r in rows]
        ax[1].loglog(xs, ys, "o-", ms=3, lw=1, label=m)
        bad = [r["omega_max"] for r in rows if not r["ok"]]
        if bad:
            ax[1].plot(bad, [max(y for y in ys if np.isfinite(y)) if np.isfinite(ys).any() else 1] * len(bad),
                       "x", color="k", ms=7)
    ax[1].set_xlabel("highest structural frequency [rad/s] (modes added)")
    ax[1].set_ylabel("force evaluations (x = failed)")
    ax[1].set_title("stiffness: cost and stability")
    ax[1].legend(fontsize=7)
    ax[1].grid(alpha=0.3, which="both")
    names = [r["method"] for r in drift_rows]
    vals = [max(abs(r["drift"]), 1e-17) if r["drift"] is not None else np.nan for r in drift_rows]
    ax[2].barh(names, vals, log=True)
    ax[2].set_xlabel("|relative energy drift|, undamped and unforced")
    ax[2].set_title("energy drift")
    ax[2].grid(alpha=0.3, axis="x")
    fig.suptitle(title)
    fig.tight_layout()
    return _save(fig, path)
