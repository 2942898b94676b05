"""How far one model's run is from a reference run: errors that measure the model.

With a whirling unbalance the tip history of two good models drifts apart in
phase: a rotor angle that lags by a fraction of a radian after a minute
shifts the whirl by as much, and the pointwise history error then reads tens
of per cent while the amplitudes agree to a fraction of one.  So beside the
history error three measures are taken separately:

- the envelope error: the running peak |x| over a window of one period of the
  slowest resonance, compared pointwise (phase-blind within the window);
- the peak difference;
- the rotor angle's drift, theta - theta_ref (rad), which is the phase error.

``lead`` says which measure fits the case: the history while the rotors stay
in phase (drift < ``PHASE_LOCKED`` rad: both models see the same forcing at
the same time, so the history error is the model's), else the envelope.

>>> import math
>>> t = np.linspace(0.0, 10.0, 2001)
>>> ref = np.sin(2 * np.pi * t)
>>> late = np.sin(2 * np.pi * t - 0.5)          # the same whirl, half a radian behind
>>> m = compare_series(t, late, t, ref, window=1.0, theta=0.5 + t, theta_ref=t)
>>> round(m.history_error, 3), round(2 * math.sin(0.25), 3)   # the closed form: 2 sin(0.5 / 2)
(0.495, 0.495)
>>> round(m.envelope_error, 3), m.lead
(0.0, 'envelope')
"""

from __future__ import annotations

import math

import numpy as np

from ..records import Record

#: Rotor angles within this of each other (rad) keep the whirls in phase.
PHASE_LOCKED = 0.1


def running_peak(t: np.ndarray, x: np.ndarray, window: float) -> np.ndarray:
    """max |x| over [t - window/2, t + window/2] at each t (m): the peak envelope."""
    t, a = np.asarray(t, dtype=float), np.abs(np.asarray(x, dtype=float))
    lo = np.searchsorted(t, t - window / 2, side="left")
    hi = np.searchsorted(t, t + window / 2, side="right")
    out = np.empty_like(a)
    for i, (j, k) in enumerate(zip(lo, hi)):
        out[i] = a[j : max(k, j + 1)].max()
    return out


class SeriesErrors(Record):
    """One model's tip history against the reference's, on the reference's times."""

    history_error: float
    """max |x - x_ref| / max |x_ref| (-)"""
    envelope_error: float
    """max |env - env_ref| / max env_ref, env the running peak over ``window`` (-)"""
    window: float
    """the envelope's window: one period of the slowest resonance (s)"""
    peak_difference: float | None
    """max |x| / max |x_ref| - 1 (-)"""
    angle_drift: float | None
    """largest |theta - theta_ref| over the run (rad); None without rotor angles"""
    angle_drift_final: float | None
    """theta - theta_ref at the end (rad)"""
    lead: str
    """"history" or "envelope": the measure that fits the case"""
    why: str
    """why that measure leads, in words"""


def compare_series(t, x, t_ref, x_ref, *, window: float, theta=None, theta_ref=None) -> SeriesErrors:
    """The errors of ``x(t)`` against ``x_ref(t_ref)`` (see the module text)."""
    t_ref, x_ref = np.asarray(t_ref, dtype=float), np.asarray(x_ref, dtype=float)
    xi = np.interp(t_ref, np.asarray(t, dtype=float), np.asarray(x, dtype=float))
    scale = max(float(np.max(np.abs(x_ref))), 1e-300)
    hist = float(np.max(np.abs(xi - x_ref)) / scale)
    env, env_ref = running_peak(t_ref, xi, window), running_peak(t_ref, x_ref, window)
    envelope = float(np.max(np.abs(env - env_ref)) / max(float(np.max(env_ref)), 1e-300))
    peak_ref = float(np.max(np.abs(x_ref)))
    peak = float(np.max(np.abs(np.asarray(x, dtype=float))))
    drift = final = None
    if theta is not None and theta_ref is not None:
        th = np.interp(t_ref, np.asarray(t, dtype=float), np.asarray(theta, dtype=float))
        d = th - np.asarray(theta_ref, dtype=float)
        drift, final = float(np.max(np.abs(d))), float(d[-1])
    if drift is not None and drift >= PHASE_LOCKED:
        lead = "envelope"
        why = (
            f"the rotor angles drift apart by up to {drift:.3g} rad: the whirl's history error "
            "measures that phase drift, not the model; the envelope (the running peak over "
            f"{window:.3g} s) and the peak measure the model"
        )
    else:
        lead = "history"
        why = (
            "the rotors stay in phase (angle drift "
            + ("not measured" if drift is None else f"{drift:.2g} rad")
            + "): both models see the same forcing at the same time, so the history error "
            "measures the model"
        )
    return SeriesErrors(
        hist, envelope, float(window), peak / peak_ref - 1 if peak_ref > 0 else None, drift, final, lead, why
    )


def envelope_window(omegas) -> float:
    """One period of the slowest resonance (s), the envelope's window."""
    w = [float(o) for o in omegas if o and math.isfinite(o) and o > 0]
    return 2 * math.pi / min(w) if w else 1.0
