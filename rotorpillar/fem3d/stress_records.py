"""Records of the 3D von Mises recovery and base reactions (rotorpillar.fem3d.stress); no dolfinx."""

from __future__ import annotations

from dataclasses import dataclass

from ..provenance import JsonRecord
from ..records import Record


@dataclass(frozen=True)
class StressPeak(JsonRecord):
    """A peak of the von Mises field: its value, where and when."""

    value: float
    """von Mises stress (Pa)"""
    position: tuple[float, float, float]
    """(x, y, z) of the node (m)"""
    time: float
    """(s)"""
    nominal: float
    """the section's nominal stress at that height and instant, |M| c / I + N / A (Pa)"""
    ratio: float
    """value / nominal (-)"""


@dataclass(frozen=True)
class VonMisesSummary(JsonRecord):
    """What the von Mises recovery found over the frames and the peak instants."""

    peak: StressPeak
    """the largest anywhere"""
    clamp: StressPeak
    """the largest within the clamp's boundary layer (z <= clamp_zone); ratio: the stress concentration"""
    away_from_clamp: StressPeak
    """the largest above the clamp's boundary layer; ratio: against the beam's nominal stress"""
    clamp_zone: float
    """height of the clamp's boundary layer l_b (m)"""
    instants: int
    """states evaluated: the frames and the peak instants of base moment and shear (-)"""
    gravity: str
    """how self-weight enters"""
    space: str
    """the continuous space the stress was projected on"""


class BaseComponent(Record, frozen=True):
    """One component of the base reaction: its peak over the run."""

    name: str
    """shear_x, shear_y, axial, moment_x, moment_y or torque (rotorpillar.fem3d.sections)"""
    peak: float
    """largest |value| (N or N*m)"""
    time: float
    """when (s)"""
    minimum: float
    """smallest value (N or N*m; axial: compression positive)"""
    maximum: float
    """largest value (N or N*m)"""


class BaseReactionsSix(Record, frozen=True):
    """What the clamp carries in all six components over a 3D run (the foundation's loads):
    the section resultants at the base cut (the part above on the foundation, as
    rotorpillar.fem3d.sections signs them), shear in x and y (N), axial force (N,
    compression positive, self-weight included), moments about x and y (N*m), torque (N*m)."""

    components: tuple[BaseComponent, ...]
    """in SPATIAL_COMPONENTS' order: shear_x, moment_y, axial, shear_y, moment_x, torque"""
    horizontal_shear: float
    """largest sqrt(V_x**2 + V_y**2) (N)"""
    overturning_moment: float
    """largest sqrt(M_x**2 + M_y**2) (N*m)"""


def base_reactions_six(t, resultants) -> BaseReactionsSix:
    """The six base components' peaks from a run's (t, resultants (n_t, n_z, 6)) (base first).

    >>> import numpy as np
    >>> res = np.zeros((3, 2, 6)); res[:, 0, 0] = [0, 3, -1]; res[:, 0, 3] = [0, 4, 0]
    >>> r = base_reactions_six(np.array([0.0, 1.0, 2.0]), res)
    >>> r.components[0].peak, r.components[0].time, r.horizontal_shear
    (3.0, 1.0, 5.0)
    """
    import numpy as np

    t = np.asarray(t, dtype=float)
    base = np.asarray(resultants, dtype=float)[:, 0, :]
    if base.shape[1] != 6:
        raise ValueError("the six base components need the spatial section functionals (6 per cut)")
    out = []
    for i, name in enumerate(("shear_x", "moment_y", "axial", "shear_y", "moment_x", "torque")):
        k = int(np.argmax(np.abs(base[:, i])))
        out.append(
            BaseComponent(name, float(abs(base[k, i])), float(t[k]), float(base[:, i].min()), float(base[:, i].max()))
        )
    return BaseReactionsSix(
        tuple(out),
        float(np.max(np.hypot(base[:, 0], base[:, 3]))),
        float(np.max(np.hypot(base[:, 1], base[:, 4]))),
    )
