"""Typed records of a run's internal forces, stresses and shaft demand (in simulate_<case>_<model>.json).

``InternalForcesSummary`` is the ``internal_forces`` block of each
transient's JSON: the section forces' envelopes along the height, the base
reactions for the foundation, the shaft's demand, and for the modal ROM its
mode count and truncation check, for the 3D model its von Mises field's
peaks.  Imports only provenance and the numpy-only records it nests (the
report reads it).
"""

from __future__ import annotations

from ..fem3d.stress_records import VonMisesSummary
from ..records import Record
from ..reduced.internal_forces import ForceTruncation


class BaseReactions(Record):
    """What the clamp carries, peaks over the run (the foundation designer's loads)."""

    moment: float
    """largest |M(0, t)| (N*m)"""
    moment_time: float
    """when (s)"""
    shear: float
    """largest |V(0, t)| (N)"""
    shear_time: float
    """when (s)"""
    axial_min: float
    """smallest N(0, t), compression positive (N)"""
    axial_max: float
    """largest N(0, t) (N)"""
    stress: float
    """largest extreme-fibre meridional stress |M| c / I + N / A at the base, compression (Pa)"""
    stress_time: float
    """when (s)"""
    axial_share: float
    """N / A over that stress at that instant: the share of the axial force (EN 1993-1-6's C_x) (-)"""


class ShaftDemand(Record):
    """The shaft's deflection and force, peaks over the run."""

    deflection: float
    """largest radial shaft deflection sqrt(d_x**2 + d_y**2) (m)"""
    deflection_time: float
    """when (s)"""
    spring_force: float
    """largest c2 |d| (N): what the shaft spring carries"""
    bearing_force: float
    """largest |c2 d + b2 v_r| (N): the spring and the damper b2 together, v_r the
    rotor centre's velocity the model's damper acts on (relative to the ground);
    the demand of the force check (the larger: b2 Omega matters beside c2 here)"""
    bearing_force_time: float
    """when (s)"""
    sampled: bool
    """True: peaks over the output samples (velocities by central differences where
    the model gives none); False: from the model's own rates"""


class InternalForcesSummary(Record, omit_defaults=True):
    """The ``internal_forces`` block of a transient's JSON (SI units)."""

    model: str
    """"modal", "beam", "fem3d\""""
    method: str
    """how the section forces were obtained, in words"""
    heights: tuple[float, ...]
    """section heights, base first (m)"""
    moment_envelope: tuple[float, ...]
    """max_t |M(z, t)| at each height (N*m)"""
    shear_envelope: tuple[float, ...]
    """max_t |V(z, t)| at each height (N)"""
    axial_static: tuple[float, ...]
    """N(z) of self-weight, gondola and rotor, compression positive (N)"""
    base: BaseReactions
    shaft: ShaftDemand
    modes: int | None = None
    """the modal ROM: modes the forces superpose"""
    modes_in_run: int | None = None
    """the modal ROM: modes of the case's run (its band)"""
    truncation: ForceTruncation | None = None
    """the modal ROM: the modes the section forces need (rotorpillar.reduced.internal_forces)"""
    von_mises: VonMisesSummary | None = None
    """the 3D model: its von Mises field's peaks"""
    stress_field: str | None = None
    """the 3D model: the XDMF time series (file name, beside the JSON), or None"""
    note: str = ""
