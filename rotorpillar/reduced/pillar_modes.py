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
model (rotorpillar.fem3d) through ``pillar_modes_from_arrays``.  Nothing here
imports dolfinx.

>>> from rotorpillar.scene import load_scene
>>> pm = beam_pillar_modes(load_scene("paper"), 3, theory="euler", elements=40)
>>> [round(w, 2) for w in pm.omega]
[25.92, 170.57, 491.23]
>>> round(float(pm.effective_mass_fraction(3)), 3)
0.886
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import eigh

from ..errors import InputError
from .beam_fe import THEORIES, BeamProperties, assemble
from .pillar import cowper_shear_coefficient, section_of


@dataclass(frozen=True, eq=False)
class PillarModes:
    """Bending modes of the pillar with the gondola on top, unit tip deflection."""
    omega: np.ndarray
    """(k,) natural angular frequencies, ascending (rad/s)"""
    modal_mass: np.ndarray
    """(k,) m_j with phi_j(tip) = 1 (kg)"""
    participation: np.ndarray
    """(k,) L_j = phi_j^T M r (kg)"""
    total_mass: float
    """r^T M r: everything the base carries in X, pillar and gondola (kg)"""
    source: str
    """where the modes come from, e.g. "beam:timoshenko:40" or "fem3d\""""
    damping_ratio: np.ndarray | None = None
    """(k,) modal damping ratios, if the source gives them (-)"""
    heights: np.ndarray | None = None
    """(n_nodes,) node heights of the shapes (m)"""
    shapes: np.ndarray | None = None
    """(n_nodes, k) lateral deflection along the height, 1 at the tip (m/m)"""
    notes: dict = field(default_factory=dict)

    def __post_init__(self):
        k = len(self.omega)
        for name in ("modal_mass", "participation"):
            if len(getattr(self, name)) != k:
                raise ValueError(f"{name} must have {k} entries")
        if k == 0 or np.any(~np.isfinite(self.omega)) or np.any(np.asarray(self.omega) <= 0):
            raise ValueError("omega must be finite and > 0")
        if np.any(np.diff(self.omega) < 0):
            raise ValueError("modes must be sorted by frequency")

    @property
    def count(self) -> int:
        return len(self.omega)

    @property
    def modal_stiffness(self) -> np.ndarray:
        """k_j = omega_j**2 m_j (N/m)"""
        return np.asarray(self.omega) ** 2 * np.asarray(self.modal_mass)

    def effective_mass_fraction(self, k: int | None = None) -> float:
        """Share of the base-excited mass the first k modes carry (-)."""
        k = self.count if k is None else k
        L, m = np.asarray(self.participation[:k]), np.asarray(self.modal_mass[:k])
        return float(np.sum(L**2 / m) / self.total_mass)

    def truncate(self, k: int) -> "PillarModes":
        """The first k modes."""
        if not 1 <= k <= self.count:
            raise ValueError(f"k must be in 1..{self.count}")
        cut = lambda a: None if a is None else np.asarray(a)[..., :k]
        return PillarModes(np.asarray(self.omega)[:k], np.asarray(self.modal_mass)[:k],
                           np.asarray(self.participation)[:k], self.total_mass, self.source,
                           cut(self.damping_ratio), self.heights, cut(self.shapes), dict(self.notes))

    def scaled(self, factor: float) -> "PillarModes":
        """The same modes with every frequency times ``factor`` (the shapes and
        modal masses kept, so the modal stiffnesses scale by factor**2): how a
        frequency error of the mode source propagates into what the ROM gives."""
        return dataclasses.replace(self, omega=np.asarray(self.omega) * factor,
                                   notes={**self.notes, "frequency_scale": float(factor)})

    def to_json(self) -> dict:
        """Every field, arrays as lists: :meth:`from_json` rebuilds it exactly."""
        out = {}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            out[f.name] = v.tolist() if isinstance(v, np.ndarray) else v
        return out

    @classmethod
    def from_json(cls, doc: dict) -> "PillarModes":
        arrays = {f.name for f in dataclasses.fields(cls) if "ndarray" in str(f.type)}
        known = {f.name for f in dataclasses.fields(cls)}
        return cls(**{k: (None if v is None else np.asarray(v, dtype=float)) if k in arrays else v
                      for k, v in doc.items() if k in known})

    def describe(self) -> dict:
        return {"source": self.source, "count": self.count, "omega": list(map(float, self.omega)),
                "frequency_hz": [float(w) / (2 * math.pi) for w in self.omega],
                "modal_mass": list(map(float, self.modal_mass)),
                "modal_stiffness": list(map(float, self.modal_stiffness)),
                "participation": list(map(float, self.participation)),
                "total_mass": self.total_mass,
                "effective_mass_fraction": self.effective_mass_fraction(),
                "damping_ratio": None if self.damping_ratio is None else list(map(float, self.damping_ratio)),
                **self.notes}


def beam_properties(scene, theory: str = "timoshenko") -> BeamProperties:
    """The scene's tube as a 1D beam (Cowper's shear coefficient for Timoshenko)."""
    p = scene.pillar
    sec = section_of(p)
    kappa = cowper_shear_coefficient(p.outer_diameter, p.inner_diameter, p.poisson_ratio)
    return BeamProperties(p.youngs_modulus, p.poisson_ratio, kappa, p.density, sec.area,
                          sec.second_moment, p.height)


def beam_pillar_modes(scene, n_modes: int, theory: str = "timoshenko", elements: int = 40,
                      gondola_inertia: float = 0.0) -> PillarModes:
    """The first ``n_modes`` modes of the 1D beam with the gondola on top.

    The gondola is a rigid mass at the tip (and, if given, a rotary inertia
    about the tip); the rotor is not included: the modal model attaches it
    through the shaft.
    """
    if theory not in THEORIES:
        raise InputError(f"modal_model.theory = {theory!r}: must be one of {', '.join(THEORIES)}")
    bp = beam_properties(scene, theory)
    K, M = assemble(bp, elements, theory, scene.gondola.mass, gondola_inertia)
    n = K.shape[0]
    k = min(n_modes, n)
    mu, vec = eigh(M, K, subset_by_index=[n - k, n - 1])        # as beam_fe: lowest modes stable
    omega = 1.0 / np.sqrt(mu[::-1])
    vec = vec[:, ::-1]
    tip = vec[-2]                                               # (w, psi) per node: tip w
    if np.any(np.abs(tip) < 1e-12 * np.max(np.abs(vec), axis=0)):
        raise RuntimeError("a pillar mode with no tip deflection cannot be tip-scaled")
    phi = vec / tip
    r = np.zeros(n)
    r[0::2] = 1.0
    mj = np.einsum("ij,ik,kj->j", phi, M, phi)
    Lj = phi.T @ M @ r
    heights = np.linspace(0.0, scene.pillar.height, elements + 1)
    shapes = np.zeros((elements + 1, k))
    shapes[1:] = phi[0::2]
    return PillarModes(omega, mj, Lj, float(r @ M @ r), f"beam:{theory}:{elements}",
                       None, heights, shapes,
                       {"gondola_mass": scene.gondola.mass, "gondola_inertia": gondola_inertia})


def pillar_modes_from_arrays(omega, modal_mass, participation, total_mass, source: str = "fem3d",
                             damping_ratio=None, heights=None, shapes=None) -> PillarModes:
    """Modes from another solver (e.g. rotorpillar.fem3d's modal.json), tip-scaled.

    Arrays as documented on PillarModes; bad data raise InputError.
    """
    try:
        return PillarModes(np.asarray(omega, float), np.asarray(modal_mass, float),
                           np.asarray(participation, float), float(total_mass), source,
                           None if damping_ratio is None else np.asarray(damping_ratio, float),
                           None if heights is None else np.asarray(heights, float),
                           None if shapes is None else np.asarray(shapes, float))
    except ValueError as exc:
        raise InputError(f"pillar modes from {source}: {exc}") from None


def modes_in_band(omega, band_top: float, minimum: int = 1) -> int:
    """How many modes lie below ``band_top`` (at least ``minimum``)."""
    return max(minimum, int(np.sum(np.asarray(omega) <= band_top)))


def beam_tip_reduction(scene, theory: str = "timoshenko", elements: int = 40) -> tuple[float, float, float]:
    """Eq. 2 on the bare beam's first mode: (m_r in kg, c1 = m_r omega**2 in N/m, omega in rad/s).

    The first mode of the bare cantilever (no gondola) scaled to a unit tip
    deflection; m_r = phi^T M phi is its kinetic energy referred to the tip,
    which for the continuous Euler-Bernoulli beam is m_col / 4.

    >>> from rotorpillar.scene import load_scene
    >>> m_r, c1, w = beam_tip_reduction(load_scene("paper"), "euler", 40)
    >>> from rotorpillar.reduced.pillar import section_of
    >>> p = load_scene("paper").pillar
    >>> round(m_r / (section_of(p).mass_per_length * p.height / 4), 6)
    1.0
    """
    if theory not in THEORIES:
        raise InputError(f"modal_model.theory = {theory!r}: must be one of {', '.join(THEORIES)}")
    K, M = assemble(beam_properties(scene, theory), elements, theory, 0.0, 0.0)
    n = K.shape[0]
    mu, vec = eigh(M, K, subset_by_index=[n - 1, n - 1])
    omega = 1.0 / math.sqrt(mu[0])
    phi = vec[:, 0] / vec[-2, 0]
    m_r = float(phi @ M @ phi)
    return m_r, m_r * omega**2, omega
