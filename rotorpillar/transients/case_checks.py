"""The checks a case's summary carries beside its numbers (``simulate_<case>.json``):

- ``truncation``: the modal model's answers against the same case with one more
  pillar mode (:class:`TruncationEstimate`), or why there is none
  (:class:`NoTruncationEstimate`);
- ``response_spectrum_check``: an earthquake on a record, the tip's largest
  displacement relative to the ground beside the response-spectrum estimate
  (:class:`SpectrumCheck`), or why there is none (:class:`NoSpectrumCheck`).

Built by rotorpillar.transients.cases; each pair is a union tagged by ``kind``.
"""

from __future__ import annotations

from ..records import Record


class SpectralMode(Record):
    """One pillar mode's part in the response-spectrum estimate of the tip."""

    mode: int
    """its number, from 1 (-)"""
    period: float
    """(s)"""
    damping_ratio: float
    """its own damping ratio (-)"""
    participation_factor: float
    """Gamma_j for a base acceleration (-)"""
    s_d: float
    """the record's spectral displacement at its period and damping (m)"""
    contribution: float
    """|Gamma_j| S_d(T_j) (m)"""


class TruncationEstimate(Record, tag_field="kind", tag="estimate"):
    """How much the (k+1)-th pillar mode changes a modal run's answers: the
    truncation error estimate (relative differences: the run with k + 1 modes
    over the run with k, minus 1)."""

    modes: int
    """k: the pillar modes of the run (-)"""
    modes_check: int
    """k + 1: the pillar modes of the check (-)"""
    omega_added: float
    """circular frequency of the mode the check adds (rad/s)"""
    effective_mass_fraction: float
    """share of the base-excited mass the k modes carry (-)"""
    effective_mass_fraction_check: float
    """the same for the k + 1 modes (-)"""
    omega_final_rel_diff: float | None
    """of the final speed (-); None when the run ends at rest"""
    tip_series_max_rel_diff: float
    """max_t |tip_k - tip_k+1| over max_t |tip_k+1| (-)"""
    tip_x_max_rel_diff: float | None
    """of the largest |tip X| (-); None when the run's is zero"""
    rotor_x_max_rel_diff: float | None
    """of the largest |rotor X| (-); None when the run's is zero"""
    rotor_y_max_rel_diff: float | None
    """of the largest |rotor Y| (-); None when the run's is zero"""


class NoTruncationEstimate(Record, tag_field="kind", tag="unavailable"):
    """A modal run without its truncation estimate: the mode source offers no more modes."""

    modes: int
    """the pillar modes of the run (-)"""
    modes_check: None
    """no check run (always None)"""
    statement: str
    """why, in words"""


#: The truncation estimate, or why there is none.
Truncation = TruncationEstimate | NoTruncationEstimate


class SpectralEstimate(Record):
    """The response-spectrum estimate of the tip's largest displacement relative to the
    ground: per pillar mode j, Gamma_j S_d(T_j, zeta_j), combined by SRSS."""

    modes: tuple[SpectralMode, ...]
    """each pillar mode's part, in the modal model's order"""
    srss_tip_estimate: float
    """the square root of the sum of the contributions' squares (m)"""


class SpectrumCheck(Record, tag_field="kind", tag="check"):
    """The tip's largest displacement relative to the ground beside the response-spectrum
    estimate of the first pillar mode alone (Gamma_1 S_d(T_1, zeta_1)), and of all the
    modes kept (SRSS)."""

    period: float
    """T_1: the first pillar mode's period (s)"""
    damping_ratio: float
    """zeta_1: its own damping ratio (-)"""
    participation_factor: float
    """Gamma_1 for a base acceleration (-)"""
    s_d: float
    """the record's spectral displacement at T_1, zeta_1 (m)"""
    tip_estimate: float
    """|Gamma_1| S_d(T_1, zeta_1) (m)"""
    tip_numeric: float
    """the run's largest |tip X| relative to the ground after the motion starts (m)"""
    ratio: float | None
    """tip_numeric / tip_estimate (-); None when the estimate is zero"""
    srss_tip_estimate: float
    """every mode kept, SRSS (m)"""
    modes: tuple[SpectralMode, ...]
    """each pillar mode's part"""
    note: str
    """what the estimate is, in words"""


class NoSpectrumCheck(Record, tag_field="kind", tag="unavailable"):
    """No response-spectrum check: the model has no pillar modes."""

    note: str
    """why, in words"""


#: The response-spectrum check, or why there is none.
SpectrumCheckResult = SpectrumCheck | NoSpectrumCheck
