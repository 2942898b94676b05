"""What the integrators need of a model and of a ground motion (rotorpillar.reduced.integration)."""

from __future__ import annotations

from typing import Any, Protocol, TypeVar

import numpy as np
from numpy.typing import NDArray

from .drive import DriveSchedule
from .excitation import GroundMotion
from .ground3d import SpatialGroundMotion
from .rhs import Packed

#: A ground motion the integrators take: one component in the rotor's plane, or several.
Motion = GroundMotion | SpatialGroundMotion


class TransientModel(Protocol):
    """What the integrators need of a model: the planar RotorStructure or the spatial
    SpatialStructure (rotorpillar.reduced.spatial_model)."""

    @property
    def name(self) -> str: ...
    @property
    def frame(self) -> str: ...
    @property
    def eccentricity(self) -> float: ...
    @property
    def rotor_inertia(self) -> float: ...
    @property
    def n(self) -> int: ...
    @property
    def nx(self) -> int: ...
    @property
    def tip(self) -> NDArray[np.float64]: ...
    def pack(self, drive: DriveSchedule, motion: Any, prescribed_speed: bool = False, **overrides: float) -> Packed: ...
    def energy(
        self, q: NDArray[np.float64], v: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
    def undamped_modes_x(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
    def stiffest_frequency(self) -> float: ...
    def fastest_rate(self) -> float: ...


#: the model a Transient was run on
M = TypeVar("M", bound=TransientModel)

#: the ground motion a Transient was run under
G = TypeVar("G", bound=Motion)
