"""The spatial model's steady unbalance response: Bode curves and orbits in every direction,
and each peak's amplification factor (API 684).

At a constant speed Omega (theta = Omega t) the static unbalance pulls the
shaft by c2 e (cos theta, sin theta) in (x, z) and the couple unbalance turns
a moment U_c Omega**2 with it; every coordinate is Z = Re(Z^ e^{i theta}) with

    (K_f - Omega**2 M + i Omega (C + Omega G)) Z^ = c2 e (d_x - i d_v) + U_c Omega**2 (b_c - i b_s).

Per output (rotorpillar.reduced.spatial_model.OUTPUTS) and speed: the
amplitude |o.Z^| and the phase lag behind the unbalance's component in the
same direction (x: cos theta; z: sin theta, so 90 degrees are taken off; the
others behind cos theta), in degrees; the shaft's deflection includes -e (cos,
sin).  Orbits: the ellipse a point draws in a plane, from the complex
amplitudes (X, Y) of its two components: semi-axes (the singular values of
[[Re X, -Im X], [Re Y, -Im Y]]), and the way it turns (forward from the first
axis towards the second when the determinant is positive).

**Amplification factor** (API 684, 2nd ed., 2005, the half-power method):
AF = N_c / (N_2 - N_1), N_c the speed of a peak of the response, N_1 and
N_2 the speeds either side where the amplitude is the peak's / sqrt(2).  A
peak whose amplitude does not fall to that level on either side within
HALF_POWER_SPAN of it is not a resonance peak (a bump on another mode's
flank): it gets no AF, and API 684 asks no margin of a mode that shows none.
Where only one side falls, N_2 - N_1 is twice that side's distance (noted).
A peak below SIGNIFICANT_SHARE of the machine's largest unbalance response
(a mode out of the rotor's plane that a 3D mode's round-off couples to it at
1e-11) is no response a probe would read: ``peak_near`` passes it by.

>>> from rotorpillar.reduced.spatial_model import tilt_example
>>> m = tilt_example()
>>> r = unbalance_response(tilt_example(), np.linspace(5.0, 30.0, 6))
>>> [c.name for c in r.curves][:3]
['tip_x', 'tip_y', 'tip_z']
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq, minimize_scalar

from ..provenance import Record, replace
from .spatial_model import OUTPUTS, SpatialStructure
from .spatial_modes import Array

#: how far from a peak its half-power points are looked for (a fraction of its speed, -)
HALF_POWER_SPAN = 0.3
#: the curves whose peaks are read (API 684 reads the rotor's and the bearings' response)
PEAK_CURVES = ("shaft_x", "shaft_z", "rotor_x", "rotor_z", "rotor_y", "tip_x", "tip_y", "tip_z", "top_pitch", "top_yaw")
#: the rotations among them, compared with the translations times the pillar's height
ROTATIONS = ("top_pitch", "top_yaw", "top_roll", "rotor_pitch", "rotor_yaw")
#: a mode moves a curve's output when that output's share of its largest is at least this (-)
CURVE_SHARE = 0.1
#: a peak below this share of the machine's largest unbalance response is no response: an
#: instrument beside the largest would not read it, and API 684 reads the response (-)
SIGNIFICANT_SHARE = 1e-3
#: the orbits drawn: name, the two outputs, what the plane is
ORBITS = (
    ("shaft", "shaft_x", "shaft_z", "the shaft's deflection in the plane normal to the spin axis (x, vertical)"),
    ("rotor", "rotor_x", "rotor_z", "the rotor centre in the plane normal to the spin axis (x, vertical)"),
    ("tip", "tip_x", "tip_y", "the pillar's top in the horizontal plane (in the rotor's plane, along the spin axis)"),
)


class ResponsePeak(Record):
    """A peak of one response curve and its half-power bandwidth."""

    curve: str
    """the output whose curve it is (spatial_model.OUTPUTS)"""
    speed: float
    """N_c: the peak's speed (rad/s)"""
    amplitude: float
    """the peak's amplitude (m or rad)"""
    lower: float | None
    """N_1: the half-power speed below it (rad/s); None when the curve does not fall that far"""
    upper: float | None
    """N_2: the half-power speed above it (rad/s); None likewise"""
    amplification_factor: float | None
    """AF = N_c / (N_2 - N_1) (-); None: no half-power point on either side (not a resonance peak)"""
    note: str = ""
    share: float | None = None
    """its amplitude over the largest unbalance response of the machine's peak curves, a rotation
    counted times the pillar's height (-); None where not compared"""


class ResponseCurve(Record, eq=False):
    """One output's steady unbalance response against speed."""

    name: str
    """the output (spatial_model.OUTPUTS)"""
    description: str
    amplitude: Array
    """(n,) |o.Z^| (m or rad)"""
    phase: Array
    """(n,) lag behind the unbalance's component in the same direction (deg, 0 ... 360)"""
    peaks: tuple[ResponsePeak, ...]


class Orbit(Record, eq=False):
    """The ellipse a point draws at each speed."""

    name: str
    """"shaft", "rotor" or "tip" """
    plane: str
    """the plane, in words"""
    semi_major: Array
    """(n,) (m)"""
    semi_minor: Array
    """(n,) (m)"""
    whirl: tuple[str, ...]
    """(n,) "forward" (turning from the plane's first axis towards its second), "backward" or "none" (a line)"""


class SpatialResponse(Record, eq=False):
    """The spatial model's unbalance response (the Bode curves and the orbits)."""

    speeds: Array
    """(n,) Omega (rad/s)"""
    eccentricity: float
    """e (m)"""
    couple_unbalance: float
    """U_c (kg*m**2)"""
    curves: tuple[ResponseCurve, ...]
    orbits: tuple[Orbit, ...]

    def curve(self, name: str) -> ResponseCurve:
        for c in self.curves:
            if c.name == name:
                return c
        raise KeyError(name)


def steady_state(m: SpatialStructure, speed: float) -> NDArray[np.complex128]:
    """Z^ at a constant ``speed`` (rad/s), the static and the couple unbalance together."""
    out: NDArray[np.complex128] = steady_states(m, np.array([float(speed)]))[0]
    return out


def steady_states(m: SpatialStructure, speeds: ArrayLike) -> NDArray[np.complex128]:
    """(n, nz) Z^ at every speed of ``speeds`` (rad/s, (n,)) in one stacked solve: each row is
    :func:`steady_state`'s at that speed, by the same arithmetic (the operator built entry by
    entry as one speed builds it, one LAPACK solve per speed), speed by speed it cost a Python
    round trip and a new K_f per speed (an earthquake run's stationary speeds: ~10**4 of them)."""
    return steady_solver(m)(speeds)


def steady_solver(m: SpatialStructure) -> Callable[[ArrayLike], NDArray[np.complex128]]:
    """:func:`steady_states` of ``m`` with its speed-free parts (K + c2 (d_x d_x^T + d_v d_v^T),
    the unbalance's forcing) built once: a peak's refinement asks one speed at a time, ~35
    times a peak (the tornado's 18 harmonic analyses: 61k calls, 3 s of its 8 when each
    built them again)."""
    K_f, M, C, G = m.stiffness_full(), m.mass, m.damping, m.gyroscopic
    dx, dv = m.shaft
    static = m.shaft_stiffness * m.eccentricity * (dx - 1j * dv)
    couple = m.couple[0] - 1j * m.couple[1]

    def solve(speeds: ArrayLike) -> NDArray[np.complex128]:
        W = np.atleast_1d(np.asarray(speeds, dtype=float))[:, None, None]
        # K_f - W**2 M + i W (C + W G), its real and imaginary parts written apart: the same
        # entries (i W times a real entry is exactly 0 + i W x), without complex temporaries
        D = np.empty((W.shape[0], *M.shape), dtype=complex)
        D.real = K_f - W**2 * M
        D.imag = W * (C + W * G)
        f = static + m.couple_unbalance * W[:, :, 0] ** 2 * couple
        out: NDArray[np.complex128] = np.linalg.solve(D, f.astype(complex)[..., None])[..., 0]
        return out

    return solve


def output_amplitude(m: SpatialStructure, name: str, Z: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """The complex amplitude of an output, the shaft's -e (cos, sin) included."""
    out = np.asarray(Z @ m.outputs[name], dtype=complex)
    if name == "shaft_x":
        out = out - m.eccentricity
    elif name == "shaft_z":
        out = out + 1j * m.eccentricity
    return out


def _lag(name: str, a: NDArray[np.complex128]) -> NDArray[np.float64]:
    ref = -90.0 if name in ("rotor_z", "shaft_z", "tip_z") else 0.0
    out: NDArray[np.float64] = np.mod(-np.degrees(np.angle(a)) + ref, 360.0)
    return out


def orbit_axes(X: NDArray[np.complex128], Y: NDArray[np.complex128]) -> tuple[NDArray[np.float64], ...]:
    """(semi-major, semi-minor, signed turn) of the ellipses Re((X, Y) e^{i w t}) (m, m, -).

    >>> [np.round(a, 6).tolist() for a in orbit_axes(np.array([1.0 + 0j]), np.array([-1j]))]
    [[1.0], [1.0], [1.0]]
    """
    A = np.stack([np.stack([X.real, -X.imag], -1), np.stack([Y.real, -Y.imag], -1)], -2)
    sv = np.linalg.svd(A, compute_uv=False)
    det = np.linalg.det(A)
    turn = np.where(sv[..., 0] > 0, det / np.maximum(sv[..., 0] ** 2, 1e-300), 0.0)
    return sv[..., 0], sv[..., 1], turn


def unbalance_response(m: SpatialStructure, speeds: NDArray[np.float64]) -> SpatialResponse:
    """The steady response at every speed (rad/s) of every output, its peaks and the orbits."""
    speeds = np.asarray(speeds, dtype=float)
    Z = steady_states(m, speeds)
    amp = {name: output_amplitude(m, name, Z) for name in OUTPUTS}
    H = float(m.modes.section_heights[-1]) if m.modes.section_heights is not None else 1.0
    largest = max(float(np.max(np.abs(amp[n]))) * (H if n in ROTATIONS else 1.0) for n in PEAK_CURVES)
    curves = []
    for name, desc in OUTPUTS.items():
        size = np.abs(amp[name])
        peaks = find_peaks(m, name, speeds, size) if name in PEAK_CURVES else ()
        scale = (H if name in ROTATIONS else 1.0) / largest if largest > 0 else 0.0
        peaks = tuple(replace(p, share=p.amplitude * scale) for p in peaks)
        curves.append(ResponseCurve(name, desc, size, _lag(name, amp[name]), peaks))
    orbits = []
    for name, first, second, plane in ORBITS:
        major, minor, turn = orbit_axes(amp[first], amp[second])
        whirl = tuple("none" if abs(t) < 1e-3 else ("forward" if t > 0 else "backward") for t in turn)
        orbits.append(Orbit(name, plane, major, minor, whirl))
    return SpatialResponse(speeds, m.eccentricity, m.couple_unbalance, tuple(curves), tuple(orbits))


def find_peaks(
    m: SpatialStructure, name: str, speeds: NDArray[np.float64], amplitude: NDArray[np.float64]
) -> tuple[ResponsePeak, ...]:
    """Each interior local maximum of an output's curve, refined on the model, with its half-power points."""

    amp = _amplitude_at_one_speed(m, name)
    out = []
    top = float(np.max(amplitude)) if len(amplitude) else 0.0
    for i in range(1, len(speeds) - 1):
        if not (amplitude[i] >= amplitude[i - 1] and amplitude[i] > amplitude[i + 1]) or amplitude[i] <= 1e-12 * top:
            continue
        res = minimize_scalar(
            lambda w: -amp(w),
            bounds=(speeds[i - 1], speeds[i + 1]),
            method="bounded",
            options={"xatol": 1e-9 * speeds[i]},
        )
        out.append(half_power_peak(amp, float(res.x), -float(res.fun), name))
    return tuple(out)


def _amplitude_at_one_speed(m: SpatialStructure, name: str) -> Callable[[float], float]:
    """speed (rad/s) -> |the output ``name``|, :func:`steady_states` at that one speed
    (:func:`steady_solver`: the speed-free parts built once)."""
    solve = steady_solver(m)
    return lambda w: float(abs(output_amplitude(m, name, solve([w]))[0]))


def half_power_peak(amp: object, speed: float, peak: float, curve: str = "") -> ResponsePeak:
    """A ResponsePeak from an amplitude function ``amp(speed)`` and its peak (API 684's
    half-power method; see the module text)."""
    f = amp  # callable: speed (rad/s) -> amplitude
    assert callable(f)
    level = peak / math.sqrt(2)

    def side(sign: float) -> float | None:
        step = 0.01 * speed
        a = speed
        while abs(a - speed) < HALF_POWER_SPAN * speed:
            b = a + sign * step
            if b <= 0:
                return None
            fb = f(b)
            if not math.isfinite(fb):
                return None
            if fb <= level:
                lo, hi = (b, a) if sign < 0 else (a, b)
                return float(brentq(lambda w: f(w) - level, lo, hi, xtol=1e-10 * speed))
            a = b
            step *= 1.5
        return None

    lower, upper = side(-1.0), side(+1.0)
    note = ""
    if lower is not None and upper is not None:
        af: float | None = speed / (upper - lower)
    elif lower is not None or upper is not None:
        near = lower if lower is not None else upper
        assert near is not None
        af = speed / (2 * abs(speed - near))
        note = "one half-power point only: the bandwidth taken as twice its distance from the peak"
    else:
        af = None
        note = (
            f"the amplitude stays above the peak's / sqrt(2) within {100 * HALF_POWER_SPAN:.0f} % of it: "
            "a bump on another mode's flank, not a resonance peak"
        )
    return ResponsePeak(curve, float(speed), float(peak), lower, upper, af, note)


def curves_moved(
    m: SpatialStructure, v: NDArray[np.complex128], names: tuple[str, ...] = PEAK_CURVES
) -> tuple[str, ...]:
    """The outputs among ``names`` a mode shape v moves: at least CURVE_SHARE of the largest of
    them, a rotation counted times the pillar's height (the shaft's deflection without e)."""
    H = float(m.modes.section_heights[-1]) if m.modes.section_heights is not None else 1.0
    size = {n: abs(complex(v @ m.outputs[n])) * (H if n in ROTATIONS else 1.0) for n in names}
    top = max(size.values(), default=0.0)
    return tuple(n for n in names if top > 0 and size[n] >= CURVE_SHARE * top)


def peak_near(
    response: SpatialResponse, omega: float, width: float = 0.15, curves: tuple[str, ...] | None = None
) -> ResponsePeak | None:
    """Of the peaks within +-``width`` of ``omega`` (rad/s) that have an AF, on ``curves`` (None:
    every curve), the one with the largest AF (the most demanding); None when the response shows
    no peak there."""
    near = [
        p
        for c in response.curves
        if curves is None or c.name in curves
        for p in c.peaks
        if p.amplification_factor is not None
        and abs(p.speed - omega) <= width * omega
        and (p.share is None or p.share >= SIGNIFICANT_SHARE)
    ]
    return max(near, key=lambda p: p.amplification_factor or 0.0) if near else None


def peaks_from_samples(
    curve: str, speeds: NDArray[np.float64], amplitude: NDArray[np.float64]
) -> tuple[ResponsePeak, ...]:
    """The peaks of a sampled response curve (another model's: the 3D harmonic response), each with
    its half-power points on the curve interpolated linearly between the samples."""
    from .bode import local_peaks

    W, a = np.asarray(speeds, dtype=float), np.asarray(amplitude, dtype=float)

    def amp(w: float) -> float:
        return float(np.interp(w, W, a, left=np.inf, right=np.inf))

    return tuple(half_power_peak(amp, s, p, curve) for s, p in local_peaks(W, a))
