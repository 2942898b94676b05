"""The records of the quasi-static sweep (rotorpillar.transients.sweep): the bins of a
ramp, the jumps found and predicted, the amplitudes against Eq. 19, the rate checks and
the rate study; ``SweepFindings`` is what a sweep adds to ``simulate_sweep.json`` (each
record's ``to_json()`` a row or section as that file writes it)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..records import Record
from ..reduced.averaging import Jump


class SweepBins(Record, eq=False, omit_defaults=True):
    """Stationary speed and amplitudes per M0 bin over one ramp of a sweep, the bins in
    the ramp's order (M0 rising for "up", falling for "down"); empty bins left out."""

    M0: np.ndarray
    """the bin's middle torque at zero speed (N*m)"""
    omega: np.ndarray
    """mean rotor speed in the bin (rad/s)"""
    tip_x: np.ndarray
    """largest |tip X| in the bin (m)"""
    rotor_y: np.ndarray
    """largest |rotor Y| in the bin (m)"""
    rotor_x: np.ndarray
    """largest |rotor X| in the bin (m)"""
    M0_inertia_corrected: np.ndarray
    """M0 - J dOmega/dt: the torque the stationary balance sees (N*m)"""
    direction: str
    """up or down"""
    in_jump: np.ndarray | None = None
    """per bin: inside a jump, not stationary (``detect_jumps``); None before the scan"""

    def column(self, name: str) -> np.ndarray:
        """The column called ``name`` ("tip_x", "rotor_y", ...)."""
        value: np.ndarray = getattr(self, name)
        return value


class JumpScan(Record, eq=False):
    """One ramp's jumps (``detect_jumps``)."""

    jumps: list[NumericJump]
    """the numeric jumps, in the ramp's order"""
    largest_step_ratio: float
    """the largest speed step over what the motor and load alone allow (-; 1 on a smooth curve)"""
    in_jump: np.ndarray
    """per bin: inside a jump (not stationary)"""


class NumericJump(Record):
    """A jump the sweep made: consecutive bins whose speed moved more than JUMP_FACTOR
    times what the motor and load alone allow."""

    direction: str
    """up or down: the ramp it was found on"""
    omega_from: float
    """the speed it left (rad/s)"""
    omega_to: float
    """the speed it reached (rad/s)"""
    torque_at_zero: float
    """M0 at the jump: the middle of its first two bins (N*m)"""
    bins: int
    """consecutive flagged bin steps it spans (-)"""


class JumpMatch(Record, omit_defaults=True):
    """A predicted jump beside the numeric one it is matched to, or beside none."""

    predicted: Jump
    """the averaging theory's jump"""
    numeric: NumericJump | None
    """the numeric jump of the same direction nearest to it (and it nearest to that), or None"""
    rel_error_omega_from: float | None = None
    """numeric / predicted - 1 of the speed left (-); absent without a match"""
    rel_error_omega_to: float | None = None
    """numeric / predicted - 1 of the speed reached (-); absent without a match"""
    rel_error_torque: float | None = None
    """numeric / predicted - 1 of M0 at the jump (-); absent without a match"""


class AmplitudeCheck(Record):
    """The sweep's stationary amplitudes near one resonance against the paper's Eq. 19 and
    the exact linear steady state (relative errors: model / numeric - 1)."""

    index: int
    """the resonance's index (-)"""
    direction: str
    """X or Y: the resonance's direction"""
    omega: float
    """its circular frequency omega_i (rad/s)"""
    coordinate: str
    """the amplitude compared: tip_x (X) or rotor_y (Y)"""
    sweep: str
    """up or down: the ramp"""
    bins: int
    """stationary bins near the resonance (-)"""
    numeric_peak: float
    """the largest numeric amplitude among them (m)"""
    omega_at_numeric_peak: float
    """the speed of that bin (rad/s)"""
    eq19_at_that_speed: float
    """Eq. 19's amplitude there (m)"""
    exact_at_that_speed: float
    """the exact linear amplitude there (m)"""
    eq19_a_max: float
    """Eq. 19's amplitude at omega_i (m)"""
    rel_error_eq19: float
    """largest |error| of Eq. 19 over the bins (-)"""
    rel_error_exact: float
    """largest |error| of the exact linear amplitude over the bins (-)"""
    rel_error_eq19_median: float
    """median |error| of Eq. 19 (-)"""
    rel_error_exact_median: float
    """median |error| of the exact linear amplitude (-)"""
    rel_error_eq19_at_peak: float
    """Eq. 19's error at the numeric peak (-)"""
    rel_error_exact_at_peak: float
    """the exact linear amplitude's error at the numeric peak (-)"""


class RateCheck(Record):
    """Whether the sweep is slow enough at one resonance it crosses: the speed's rate over
    n_i**2 (quasi-static when < 0.1)."""

    index: int
    """the resonance's index (-)"""
    omega: float
    """its circular frequency omega_i (rad/s)"""
    n: float
    """its half-power width n_i (rad/s)"""
    speed_rate: float
    """dOmega/dt the sweep's rate of M0 drives there (rad/s**2)"""
    ratio: float
    """speed_rate / n_i**2 (-)"""
    quasi_static: bool
    """ratio < 0.1"""


class RateRow(Record, omit_defaults=True):
    """One numeric jump at the sweep rates r, r/2, r/4, and its limit at zero rate: per
    quantity the limit and the fitted exponent p of the delay ~ rate**p (None where the
    three do not converge monotonically, or a rate found no such jump)."""

    direction: str
    """up or down"""
    rates: tuple[float, ...]
    """the sweep rates of M0 (N*m/s)"""
    torque_at_zero: tuple[float | None, ...]
    """the jump's M0 at each rate (N*m); None where that rate found no jump of the direction"""
    omega_from: tuple[float | None, ...]
    """the speed it left at each rate (rad/s)"""
    omega_to: tuple[float | None, ...]
    """the speed it reached at each rate (rad/s)"""
    torque_at_zero_limit: float | None
    """M0 extrapolated to zero rate (N*m)"""
    torque_at_zero_exponent: float | None
    """p of M0's delay (-)"""
    omega_from_limit: float | None
    """the speed left, extrapolated to zero rate (rad/s)"""
    omega_from_exponent: float | None
    """p of its delay (-)"""
    omega_to_limit: float | None
    """the speed reached, extrapolated to zero rate (rad/s)"""
    omega_to_exponent: float | None
    """p of its delay (-)"""
    predicted_torque_at_zero: float | None = None
    """the averaging theory's M0 of the nearest predicted jump (N*m); absent without one or without a limit"""
    rel_error_limit_vs_predicted: float | None = None
    """torque_at_zero_limit / predicted_torque_at_zero - 1 (-); absent with it"""


class RateConvergence(Record):
    """The sweep's jumps at decreasing rates, extrapolated to a quasi-static sweep
    (``rate_convergence`` in ``simulate_sweep.json``)."""

    rows: tuple[RateRow, ...]
    """one per numeric jump at the scene's rate"""
    note: str
    """what the rows are, in words"""


class SweepAnalysis(Record, eq=False):
    """A quasi-static sweep against the averaging theory (``sweep_analysis``); its parts
    that ``simulate_sweep.json`` writes are rows as the JSON has them."""

    up: SweepBins
    """the bins of the ramp with M0 rising"""
    down: SweepBins
    """the bins of the ramp with M0 falling"""
    numeric_jumps: tuple[NumericJump, ...]
    """the jumps the sweep made, up then down (``JumpScan.jumps``)"""
    predicted_jumps: tuple[Jump, ...]
    """the averaging theory's jumps inside the swept torque range"""
    jump_comparison: tuple[JumpMatch, ...]
    """each predicted jump beside the nearest numeric one (``match_jumps``)"""
    largest_speed_step_ratio: dict[str, float]
    """per direction ("up", "down"): the largest speed step over what motor and load alone
    allow (-); a mapping by direction, as the JSON has it"""
    amplitudes: tuple[AmplitudeCheck, ...]
    """numeric stationary amplitudes against the paper's Eq. 19 and the exact linear ones
    (``compare_amplitudes``)"""
    rate_check: tuple[RateCheck, ...]
    """per resonance in range: is the sweep quasi-static there"""
    no_jump_reason: str | None
    """why no jump was found, or None"""
    captured_at: float | None
    """the up-sweep held below a resonance until its fold: the speed it left (rad/s), or None"""
    captured_resonance: float | None
    """that resonance's omega_i (rad/s), or None"""
    captured_index: int | None
    """that resonance's index (-), or None"""
    curves: dict[str, Any]
    """the stationary curves on a speed grid, by name: omega (rad/s), F_averaging and F_exact
    (N*m), exact (m, by coordinate) and eq19 (m, by resonance label)"""


class SweepFindings(Record):
    """What a quasi-static sweep adds to its summary (rotorpillar.transients.sweep):
    ``to_json()`` the keys ``simulate_sweep.json`` writes after ``jumps``, in this order."""

    predicted_jumps: tuple[Jump, ...]
    """the averaging theory's jumps inside the swept torque range"""
    jump_comparison: tuple[JumpMatch, ...]
    """each predicted jump beside the nearest numeric one"""
    largest_speed_step_ratio: dict[str, float]
    """{"up", "down"}: the largest speed step over what motor and load alone allow (-)"""
    amplitudes: tuple[AmplitudeCheck, ...]
    """numeric stationary amplitudes against the paper's Eq. 19 and the exact linear ones"""
    rate_check: tuple[RateCheck, ...]
    """per resonance in range: is the sweep quasi-static there"""
    no_jump_reason: str | None
    """why no jump was found, or None"""
    rate_convergence: RateConvergence | None
    """the jumps at rates r, r/2, r/4 and their limit, or None without jumps"""
