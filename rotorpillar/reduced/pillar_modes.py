"""Pillar modes as arrays: the interface between a modal solver and the modal model.

``PillarModes`` holds the bending modes (X) of the pillar clamped at its
base with the gondola riding on its top, each scaled to a unit tip
deflection, so a modal coordinate is that mode's share of the tip
displacement (m).  With phi_j the mode and M the pillar's mass matrix
(gondola included), r the rigid X translation of the whole pillar:

- modal mass          m_j = phi_j^T M phi_j            (kg)
- modal stiffness     k_j = omega_j**2 m_j             (N/m)
- participation       L_j = phi_j^T M r                (kg): a base acceleration
                      a_g forces mode j with -L_j a_g
- effective mass      L_j**2 / m_j, summing to r^T M r over all modes.

Any solver can fill it: the 1D beam here (``beam_pillar_modes``: Euler-Bernoulli
or Timoshenko with the gondola as a tip mass and rotary inertia), or the 3D
model (rotorpillar.fem3d.pillar_modes).  Nothing here imports dolfinx.

>>> from rotorpillar.scene import load_scene
>>> paper = load_scene("paper")
>>> pm = beam_pillar_modes(paper.pillar, paper.gondola.mass, 3, theory="euler", elements=40)
>>> [round(w, 2) for w in pm.omega]
[25.92, 170.57, 491.23]
>>> round(float(pm.effective_mass_fraction(3)), 3)
0.886
"""

from __future__ import annotations

import math
from typing import Any

import msgspec
import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eigh

from ..errors import InputError
from ..provenance import Record
from ..scene import Pillar
from .beam_fe import (
    THEORIES,
    BaseSprings,
    BeamLine,
    BeamProperties,
    assemble,
    first_free_dof,
    section_forces,
    uniform_line,
)
from .pillar import cowper_shear_coefficient
from .tower import section_at, tower_line


class PillarModes(Record, eq=False):  # arrays: no elementwise ==
    """Bending modes of the pillar with the gondola on top, unit tip deflection."""

    omega: NDArray[np.float64]
    """(k,) natural angular frequencies, ascending (rad/s)"""
    modal_mass: NDArray[np.float64]
    """(k,) m_j with phi_j(tip) = 1 (kg)"""
    participation: NDArray[np.float64]
    """(k,) L_j = phi_j^T M r (kg)"""
    total_mass: float
    """r^T M r: everything the base carries in X, pillar and gondola (kg)"""
    source: str
    """where the modes come from, e.g. "beam:timoshenko:40" or "fem3d\""""
    damping_ratio: NDArray[np.float64] | None = None
    """(k,) modal damping ratios, if the source gives them (-)"""
    heights: NDArray[np.float64] | None = None
    """(n_nodes,) node heights of the shapes (m)"""
    shapes: NDArray[np.float64] | None = None
    """(n_nodes, k) lateral deflection along the height, 1 at the tip (m/m)"""
    notes: dict[str, Any] = msgspec.field(default_factory=dict)
    """what the source adds (the gondola's mass and inertia, a frequency scale)"""
    section_heights: NDArray[np.float64] | None = None
    """(n_z,) heights of the sections whose resultants each mode carries, base
    (0) first (m)"""
    moment_shapes: NDArray[np.float64] | None = None
    """(n_z, k) bending moment M_j(z) at ``section_heights`` per unit modal
    coordinate: the y-moment the part above exerts on the part below, about
    the section's centre, positive for a tip pushed along +X (N*m per m)"""
    shear_shapes: NDArray[np.float64] | None = None
    """(n_z, k) shear force V_j(z) in X that the part above exerts on the part
    below, per unit modal coordinate (N per m)"""
    base_rotation: NDArray[np.float64] | None = None
    """(k,) the base's rotation per unit modal coordinate on a flexible foundation
    (its translation is ``shapes[0]``); None: clamped (rad per m)"""

    def __post_init__(self) -> None:
        k = len(self.omega)
        for name in ("modal_mass", "participation"):
            if len(getattr(self, name)) != k:
                raise ValueError(f"{name} must have {k} entries")
        for name in ("moment_shapes", "shear_shapes"):
            a = getattr(self, name)
            if a is not None and (self.section_heights is None or np.shape(a) != (len(self.section_heights), k)):
                raise ValueError(f"{name} must be (len(section_heights), {k})")
        if k == 0 or np.any(~np.isfinite(self.omega)) or np.any(np.asarray(self.omega) <= 0):
            raise ValueError("omega must be finite and > 0")
        if np.any(np.diff(self.omega) < 0):
            raise ValueError("modes must be sorted by frequency")

    @property
    def count(self) -> int:
        return len(self.omega)

    @property
    def modal_stiffness(self) -> NDArray[np.float64]:
        """k_j = omega_j**2 m_j (N/m)"""
        return np.asarray(self.omega) ** 2 * np.asarray(self.modal_mass)

    def effective_mass_fraction(self, k: int | None = None) -> float:
        """Share of the base-excited mass the first k modes carry (-)."""
        k = self.count if k is None else k
        L, m = np.asarray(self.participation[:k]), np.asarray(self.modal_mass[:k])
        return float(np.sum(L**2 / m) / self.total_mass)

    def truncate(self, k: int) -> PillarModes:
        """The first k modes."""
        if not 1 <= k <= self.count:
            raise ValueError(f"k must be in 1..{self.count}")

        def cut(a: NDArray[np.float64] | None) -> NDArray[np.float64] | None:
            return None if a is None else np.asarray(a)[..., :k]

        return PillarModes(
            np.asarray(self.omega)[:k],
            np.asarray(self.modal_mass)[:k],
            np.asarray(self.participation)[:k],
            self.total_mass,
            self.source,
            cut(self.damping_ratio),
            self.heights,
            cut(self.shapes),
            dict(self.notes),
            self.section_heights,
            cut(self.moment_shapes),
            cut(self.shear_shapes),
            cut(self.base_rotation),
        )

    @property
    def has_resultants(self) -> bool:
        """Whether the modes carry their section resultants (moment and shear)."""
        return self.moment_shapes is not None and self.shear_shapes is not None

    def scaled(self, factor: float) -> PillarModes:
        """The same modes with every frequency times ``factor`` (the shapes and
        modal masses kept, so the modal stiffnesses scale by factor**2): how a
        frequency error of the mode source propagates into what the ROM gives."""
        return msgspec.structs.replace(
            self, omega=np.asarray(self.omega) * factor, notes={**self.notes, "frequency_scale": float(factor)}
        )

    def describe(self) -> ModesDescription:
        """The modes' numbers as a run's JSON states them."""
        return ModesDescription(
            source=self.source,
            count=self.count,
            omega=tuple(map(float, self.omega)),
            frequency_hz=tuple(float(w) / (2 * math.pi) for w in self.omega),
            modal_mass=tuple(map(float, self.modal_mass)),
            modal_stiffness=tuple(map(float, self.modal_stiffness)),
            participation=tuple(map(float, self.participation)),
            total_mass=self.total_mass,
            effective_mass_fraction=self.effective_mass_fraction(),
            damping_ratio=None if self.damping_ratio is None else tuple(map(float, self.damping_ratio)),
            notes=dict(self.notes),
        )


class ModesDescription(Record):
    """Pillar modes as a run's JSON states them (``PillarModes.describe``)."""

    source: str
    """where the modes come from"""
    count: int
    """modes (-)"""
    omega: tuple[float, ...]
    """natural angular frequencies (rad/s)"""
    frequency_hz: tuple[float, ...]
    """(Hz)"""
    modal_mass: tuple[float, ...]
    """m_j, unit tip deflection (kg)"""
    modal_stiffness: tuple[float, ...]
    """k_j (N/m)"""
    participation: tuple[float, ...]
    """L_j (kg)"""
    total_mass: float
    """(kg)"""
    effective_mass_fraction: float
    """the share of the base-excited mass the modes carry (-)"""
    damping_ratio: tuple[float, ...] | None
    """modal damping ratios (-), if the source gives them"""
    notes: dict[str, Any]
    """what the source adds (the gondola's mass and inertia, a frequency scale)"""


def beam_properties(pillar: Pillar) -> BeamProperties:
    """The uniform ``[pillar]`` tube as a 1D beam, with Cowper's shear coefficient: the same
    properties for either theory (the Euler-Bernoulli element takes no shear term, so the
    theory is the element's choice: ``beam_fe.assemble(..., theory)``).  A tower of cans has
    no single section: ``beam_line`` takes it element by element."""
    p = pillar
    if not p.is_uniform:
        raise ValueError("a tower of cans has no single beam section: use rotorpillar.reduced.pillar_modes.beam_line")
    sec = section_at(p, 0.0)
    kappa = cowper_shear_coefficient(sec.outer_diameter, sec.inner_diameter, p.poisson_ratio)
    return BeamProperties(p.youngs_modulus, p.poisson_ratio, kappa, p.density, sec.area, sec.second_moment, p.height)


def beam_line(pillar: Pillar, elements: int) -> BeamLine:
    """The ``[pillar]`` tube as a beam of ``elements``: each element's own section (rotorpillar.reduced.tower)."""
    if pillar.is_uniform:
        return uniform_line(beam_properties(pillar), elements)
    return tower_line(pillar, elements)


def _solve_lowest(
    K: NDArray[np.float64], M: NDArray[np.float64], k: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The k lowest (omega, vectors) of K v = omega**2 M v."""
    n = K.shape[0]
    mu, vec = eigh(M, K, subset_by_index=[n - k, n - 1])  # as beam_fe: lowest modes stable
    return 1.0 / np.sqrt(mu[::-1]), vec[:, ::-1]


def beam_pillar_modes(
    pillar: Pillar,
    gondola_mass: float,
    n_modes: int,
    theory: str = "timoshenko",
    elements: int = 40,
    gondola_inertia: float = 0.0,
    base: BaseSprings | None = None,
) -> PillarModes:
    """The first ``n_modes`` modes of the 1D beam with the gondola on top.

    The gondola is a rigid mass at the tip (``gondola_mass``, kg) (and, if given, a rotary inertia
    about the tip); the rotor is not included: the modal model attaches it
    through the shaft.  ``base``: the foundation's springs (None: clamped);
    the base's translation and rotation per mode are then in ``shapes[0]``
    and ``base_rotation``.
    """
    if theory not in THEORIES:
        raise InputError(f"modal_model.theory = {theory!r}: must be one of {', '.join(THEORIES)}")
    line = beam_line(pillar, elements)
    K, M = assemble(line, elements, theory, gondola_mass, gondola_inertia, base)
    f = first_free_dof(base)
    k = min(n_modes, K.shape[0])
    omega, vec = _solve_lowest(K, M, k)
    tip = vec[-2]  # (w, psi) per node: tip w
    still = np.flatnonzero(np.abs(tip) < 1e-12 * np.max(np.abs(vec), axis=0))
    if still.size:
        # a gondola far heavier than the tube holds the tip still in the higher modes: they
        # cannot be tip-scaled, and the rotor, at the tip, does not move them; the modes
        # before the first of them are the candidates
        if still[0] == 0:
            raise InputError(
                f"gondola.mass = {gondola_mass:g} kg holds the tip of the pillar still in its first "
                "mode: no modal model can hang the rotor there (a lighter gondola, a stiffer pillar)"
            )
        k = int(still[0])
        omega, vec, tip = omega[:k], vec[:, :k], tip[:k]
    phi = vec / tip
    r = np.zeros(K.shape[0])
    r[0::2] = 1.0
    mj = np.einsum("ij,ik,kj->j", phi, M, phi)
    Lj = phi.T @ M @ r
    heights = line.nodes
    full = np.zeros((2 * (elements + 1), k))
    full[f:] = phi
    shapes = full[0::2]
    shear, moment = section_forces(line, elements, theory, full)
    return PillarModes(
        omega,
        mj,
        Lj,
        float(r @ M @ r),
        f"beam:{theory}:{elements}",
        None,
        heights,
        shapes,
        {"gondola_mass": gondola_mass, "gondola_inertia": gondola_inertia},
        heights,
        moment,
        shear,
        None if base is None else full[1],
    )


def modes_in_band(omega: ArrayLike, band_top: float, minimum: int = 1) -> int:
    """How many modes lie below ``band_top`` (at least ``minimum``)."""
    return max(minimum, int(np.sum(np.asarray(omega) <= band_top)))


def beam_tip_reduction(
    pillar: Pillar, theory: str = "timoshenko", elements: int = 40, base: BaseSprings | None = None
) -> tuple[float, float, float]:
    """Eq. 2 on the bare beam's first mode: (m_r in kg, c1 = m_r omega**2 in N/m, omega in rad/s).

    The first mode of the bare cantilever (no gondola; on the foundation's
    springs when ``base`` is given), tapered or stepped as the tube is, scaled
    to a unit tip deflection; m_r = phi^T M phi is its kinetic energy referred
    to the tip, which for the continuous uniform Euler-Bernoulli beam is m_col / 4.

    >>> from rotorpillar.scene import load_scene
    >>> m_r, c1, w = beam_tip_reduction(load_scene("paper").pillar, "euler", 40)
    >>> from rotorpillar.reduced.pillar import section_of
    >>> p = load_scene("paper").pillar
    >>> round(m_r / (section_of(p).mass_per_length * p.height / 4), 6)
    1.0
    """
    if theory not in THEORIES:
        raise InputError(f"modal_model.theory = {theory!r}: must be one of {', '.join(THEORIES)}")
    K, M = assemble(beam_line(pillar, elements), elements, theory, 0.0, 0.0, base)
    omega, vec = _solve_lowest(K, M, 1)
    phi = vec[:, 0] / vec[-2, 0]
    m_r = float(phi @ M @ phi)
    return m_r, m_r * float(omega[0]) ** 2, float(omega[0])
