"""Section properties along the tower's height: the one function every model reads.

The tube (``Pillar.segments()``: one cylinder, or the cans of a tapered or
stepped tower) has at each height z a circular annulus of outer diameter
D0(z) and inner diameter D1(z), each linear in z within a segment:

- area                A   = pi/4 (D0**2 - D1**2)                        (m**2)
- second moment       I   = pi/64 (D0**4 - D1**4), about a diameter     (m**4)
- torsion constant    J   = 2 I (a closed circular section)             (m**4)
- mass per length     m   = rho A                                       (kg/m)
- shear coefficient   kappa of Cowper (1966) for the hollow circle     (-)

At a joint between two cans the section may jump (a step in the wall):
``side`` says which side a height exactly at a joint takes.  The beam puts
its nodes on the joints, so no element straddles one, and integrates each
element's section by Gauss-Legendre quadrature, exact for these polynomials
in z (A quadratic, I quartic).

Whether a foundation can hold the machine up at all (``check_foundation_holds``) needs the
machine's weight and heights, so it lives here with the tube's masses.

>>> from rotorpillar.scene import load_scene
>>> p = load_scene("paper").pillar
>>> s = sections_along(p, [0.0, 20.0])
>>> s.second_moment.round(4).tolist(), round(tower_mass(p), 1)
([0.061, 0.061], 20153.9)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eigh

from ..errors import InputError
from ..scene import Pillar, Scene, Segment, segment_index
from .beam_fe import GAUSS_POINTS as BEAM_GAUSS
from .beam_fe import BaseSprings, BeamLine
from .excitation import STANDARD_GRAVITY
from .foundation import FoundationStiffness, foundation_stiffness
from .pillar import (
    TubeSection,
    cantilever_curvature,
    cantilever_mode_stable,
    cantilever_slope,
    cowper_shear_coefficient,
)

#: Gauss-Legendre points and weights on [0, 1]: 5 points integrate degree 9 exactly
#: (a Hermite beam element's mass term rho A N N is degree 8 in z on a cone).
_XG, _WG = np.polynomial.legendre.leggauss(5)  # type: ignore[no-untyped-call]  # numpy's polynomial stubs leave leggauss untyped
GAUSS_POINTS: NDArray[np.float64] = 0.5 * (np.asarray(_XG) + 1.0)
GAUSS_WEIGHTS: NDArray[np.float64] = 0.5 * np.asarray(_WG)


@dataclass(frozen=True, eq=False)
class SectionsAlong:
    """The tube's sections at heights z (arrays of the heights' shape)."""

    z: NDArray[np.float64]
    """heights (m)"""
    outer_diameter: NDArray[np.float64]
    """D0 (m)"""
    inner_diameter: NDArray[np.float64]
    """D1 (m)"""
    density: float
    """rho (kg/m**3)"""
    poisson_ratio: float
    """nu (-)"""

    @property
    def wall_thickness(self) -> NDArray[np.float64]:
        """t = (D0 - D1) / 2 (m)"""
        return (self.outer_diameter - self.inner_diameter) / 2

    @property
    def area(self) -> NDArray[np.float64]:
        """A (m**2)"""
        return math.pi / 4 * (self.outer_diameter**2 - self.inner_diameter**2)

    @property
    def second_moment(self) -> NDArray[np.float64]:
        """I about a diameter (m**4)"""
        return math.pi / 64 * (self.outer_diameter**4 - self.inner_diameter**4)

    @property
    def torsion_constant(self) -> NDArray[np.float64]:
        """J = 2 I, the polar moment of the closed circular section (m**4)"""
        return 2 * self.second_moment

    @property
    def mass_per_length(self) -> NDArray[np.float64]:
        """rho A (kg/m)"""
        return self.density * self.area

    @property
    def shear_coefficient(self) -> NDArray[np.float64]:
        """Cowper's kappa (-)"""
        # Cowper's formula is arithmetic: arrays pass through it
        kappa = cowper_shear_coefficient(self.outer_diameter, self.inner_diameter, self.poisson_ratio)  # type: ignore[arg-type]
        return np.asarray(kappa, dtype=float)


def sections_along(pillar: Pillar, z: ArrayLike, side: str = "above") -> SectionsAlong:
    """The sections at heights ``z`` (m); at a joint, the segment ``side`` of it."""
    segs = pillar.segments()
    zs = np.atleast_1d(np.asarray(z, dtype=float))
    idx = segment_index(segs, zs, side)
    d0, d1 = np.empty_like(zs), np.empty_like(zs)
    for i, s in enumerate(segs):
        on = idx == i
        if on.any():
            d0[on], d1[on] = s.outer_diameter(zs[on]), s.inner_diameter(zs[on])
    return SectionsAlong(zs, d0, d1, pillar.density, pillar.poisson_ratio)


def section_at(pillar: Pillar, z: float, side: str = "above") -> TubeSection:
    """The section at one height as a :class:`~rotorpillar.reduced.pillar.TubeSection`."""
    s = sections_along(pillar, [z], side)
    return TubeSection(float(s.outer_diameter[0]), float(s.inner_diameter[0]), pillar.density)


def base_section(pillar: Pillar) -> TubeSection:
    """The section at the base (z = 0): what the base's stress and the foundation carry."""
    return section_at(pillar, 0.0)


def joints(pillar: Pillar) -> tuple[float, ...]:
    """Heights of the joints between segments (m), base and top excluded."""
    return tuple(s.top for s in pillar.segments()[:-1])


def _segment_integral(s: Segment, density: float, power: int) -> float:
    """integral of rho A(z) (power 2) or rho I(z) (power 4) over one segment (exact)."""
    z = s.bottom + GAUSS_POINTS * s.length
    d0, d1 = s.outer_diameter(z), s.inner_diameter(z)
    f = density * math.pi / (4 if power == 2 else 64) * (d0**power - d1**power)
    return float(np.sum(GAUSS_WEIGHTS * f) * s.length)


def tower_mass(pillar: Pillar) -> float:
    """The tube's mass, integral of rho A over the height (kg)."""
    return sum(_segment_integral(s, pillar.density, 2) for s in pillar.segments())


def mass_above(pillar: Pillar, z: ArrayLike) -> NDArray[np.float64]:
    """The tube's mass above each height z (kg): what its self-weight puts on that section."""
    return _above(pillar, z, 0)


def first_moment_above(pillar: Pillar, z: ArrayLike) -> NDArray[np.float64]:
    """int_z^H rho A(s) (s - z) ds at each height z (kg*m): the lever of the mass above
    about that section (what a unit horizontal acceleration of it bends the section by)."""
    return _above(pillar, z, 1)


def _above(pillar: Pillar, z: ArrayLike, power: int) -> NDArray[np.float64]:
    """int_z^H rho A(s) (s - z)**power ds at each z (exact: Gauss on each segment's part above z)."""
    zs = np.atleast_1d(np.asarray(z, dtype=float))
    out: NDArray[np.float64] = np.zeros_like(zs)
    for s in pillar.segments():
        a = np.clip(zs, s.bottom, s.top)[:, None]
        zq = a + GAUSS_POINTS[None, :] * (s.top - a)
        f = pillar.density * math.pi / 4 * (s.outer_diameter(zq) ** 2 - s.inner_diameter(zq) ** 2)
        out += np.sum(GAUSS_WEIGHTS[None, :] * f * (zq - zs[:, None]) ** power, axis=1) * (s.top - a[:, 0])
    return out


def element_nodes(pillar: Pillar, n_elements: int) -> NDArray[np.float64]:
    """Node heights of a beam of ``n_elements`` along the tube (m), a node on every joint.

    Each segment gets elements in proportion to its length (at least one),
    equal within it: the uniform tube's nodes are today's equal spacing.
    """
    segs = pillar.segments()
    if n_elements < len(segs):
        raise ValueError(f"a beam along {len(segs)} cans needs at least {len(segs)} elements")
    H = pillar.height
    share = np.array([s.length / H for s in segs]) * n_elements
    counts = np.maximum(1, np.floor(share).astype(int))
    # the elements left go to the segments whose share lost most to the floor
    while counts.sum() < n_elements:
        counts[int(np.argmax(share - counts))] += 1
    while counts.sum() > n_elements:
        counts[int(np.argmax(np.where(counts > 1, counts - share, -np.inf)))] -= 1
    if len(segs) == 1:
        return np.asarray(np.linspace(0.0, H, n_elements + 1), dtype=float)
    parts = [np.linspace(s.bottom, s.top, c + 1)[:-1] for s, c in zip(segs, counts)]
    return np.asarray(np.r_[np.concatenate(parts), H], dtype=float)


def top_compliances(
    pillar: Pillar, springs: FoundationStiffness | None = None, elements: int = 64
) -> tuple[float, float]:
    """(horizontal, axial) static compliance of the tube's top (m/N): a horizontal top force on
    the Euler-Bernoulli beam (``elements``, each with its own section; on the foundation's
    rocking and horizontal springs), an axial one through int dz / (E A) (and the vertical
    spring); the uniform clamped tube's H**3 / (3 E I) and H / (E A) to the beam's accuracy."""
    from .beam_fe import assemble

    base = None if springs is None else springs.base_springs()
    K, _ = assemble(tower_line(pillar, elements), elements, "euler", 0.0, 0.0, base)
    f = np.zeros(K.shape[0])
    f[-2] = 1.0
    horizontal = float(np.linalg.solve(K, f)[-2])
    axial = 0.0
    for s in pillar.segments():
        zq = s.bottom + GAUSS_POINTS * s.length
        area = math.pi / 4 * (s.outer_diameter(zq) ** 2 - s.inner_diameter(zq) ** 2)
        axial += float(np.sum(GAUSS_WEIGHTS / area) * s.length) / pillar.youngs_modulus
    if springs is not None and springs.vertical is not None:
        axial += 1.0 / springs.vertical
    return horizontal, axial


def tower_line(pillar: Pillar, n_elements: int) -> BeamLine:
    """The tube as a beam of ``n_elements`` (rotorpillar.reduced.beam_fe), a node on every joint,
    each element's section at its Gauss points."""
    nodes = element_nodes(pillar, n_elements)
    L = np.diff(nodes)
    z = nodes[:-1, None] + BEAM_GAUSS[None, :] * L[:, None]
    # Gauss points lie inside the elements, and no element straddles a joint: no side to choose
    s = sections_along(pillar, z.ravel())
    shape = z.shape
    G = pillar.youngs_modulus / (2 * (1 + pillar.poisson_ratio))
    return BeamLine(
        nodes,
        pillar.youngs_modulus,
        G,
        pillar.density,
        s.area.reshape(shape),
        s.second_moment.reshape(shape),
        s.shear_coefficient.reshape(shape),
    )


# --------------------------------------------------------------------------
# Rayleigh-Ritz: the tapered cantilever's bending modes, an upper bound


#: Gauss-Legendre points per segment of the Ritz integrals: the uniform
#: cantilever's modes up to the 12th have under 12 half-waves, which 40
#: points integrate to round-off.
_RITZ_POINTS = 40


@dataclass(frozen=True, eq=False)
class RitzModes:
    """Euler-Bernoulli bending modes of the tube by Rayleigh-Ritz."""

    omega: NDArray[np.float64]
    """natural angular frequencies, ascending; each an upper bound of the exact (rad/s)"""
    terms: int
    """assumed shapes: the uniform cantilever's first ``terms`` modes (plus the base's
    translation and rotation on springs) (-)"""
    tip_mass: float
    """Eq. 2 on the first mode: its kinetic energy referred to the tip, int rho A phi**2 dz / phi(H)**2 (kg)"""

    @property
    def tip_stiffness(self) -> float:
        """m_r omega_1**2 (N/m)"""
        return self.tip_mass * float(self.omega[0]) ** 2


def rayleigh_ritz(
    pillar: Pillar, terms: int = 10, top_mass: float = 0.0, top_inertia: float = 0.0, base: BaseSprings | None = None
) -> RitzModes:
    """The tube's bending modes (Euler-Bernoulli) by Rayleigh-Ritz on the uniform cantilever's modes.

    The uniform clamped-free beam's modes phi_k(z/H) are complete and meet the
    clamp, so each Ritz frequency bounds the exact one of the tapered or
    stepped beam from above and falls to it as ``terms`` grows (Rayleigh-Ritz's
    theorem): K_kl = int EI phi_k'' phi_l'' dz, M_kl = int rho A phi_k phi_l dz,
    plus the top's mass and rotary inertia.  On springs the base's translation
    and rotation join the shapes (1 and z), with the springs' energy.
    """
    H = pillar.height
    xg, wg = np.polynomial.legendre.leggauss(_RITZ_POINTS)  # type: ignore[no-untyped-call]  # numpy's stubs leave it untyped
    zs, ws = [], []
    for s in pillar.segments():
        zs.append(s.bottom + 0.5 * (np.asarray(xg) + 1) * s.length)
        ws.append(0.5 * np.asarray(wg) * s.length)
    z, w = np.concatenate(zs), np.concatenate(ws)
    sec = sections_along(pillar, z)
    EI, m = pillar.youngs_modulus * sec.second_moment, sec.mass_per_length
    xi = z / H
    phi = [cantilever_mode_stable(xi, k) for k in range(1, terms + 1)]
    d2 = [cantilever_curvature(xi, k) / H**2 for k in range(1, terms + 1)]
    tip = [float(cantilever_mode_stable(np.array([1.0]), k)[0]) for k in range(1, terms + 1)]
    slope = [float(cantilever_slope(np.array([1.0]), k)[0]) / H for k in range(1, terms + 1)]
    if base is not None:
        phi = [np.ones_like(z), z] + phi
        d2 = [np.zeros_like(z), np.zeros_like(z)] + d2
        tip, slope = [1.0, H] + tip, [0.0, 1.0] + slope
    P, D = np.array(phi), np.array(d2)
    K = np.einsum("q,iq,jq->ij", w * EI, D, D)
    M = np.einsum("q,iq,jq->ij", w * m, P, P)
    t, r = np.array(tip), np.array(slope)
    M += top_mass * np.outer(t, t) + top_inertia * np.outer(r, r)
    if base is not None:
        K[:2, :2] += base.matrix()
    lam, vec = eigh(K, M)
    v = vec[:, 0]
    m_tube = float(v @ np.einsum("q,iq,jq->ij", w * m, P, P) @ v)
    return RitzModes(np.sqrt(lam), terms, m_tube / float(t @ v) ** 2)


#: A footing is shallow while its embedment does not exceed its width, D <= B = 2 R (the usual
#: definition of a shallow foundation); deeper it is a caisson, outside what Gazetas' footing
#: formulas describe (their coupling K_HR = D K_H / 3 then leaves the springs unable to store
#: energy past D ~ 3 sqrt(K_R / K_H), e.g. D > 30 m under a 3 m footing).
MAX_EMBEDMENT_OVER_WIDTH = 1.0


def overturning_stiffness(scene: Scene) -> float:
    """sum(m g z) of the machine standing on its base (N*m/rad): the tube's first moment of
    mass about the base, the gondola's and the rotor's masses at their centres' heights, times
    g.  Tilting the whole machine rigidly by a small angle phi about the base lowers its
    weight's potential by sum(m g z) phi**2 / 2."""
    H = float(scene.pillar.height)
    tube = float(first_moment_above(scene.pillar, [0.0])[0])
    tops = scene.gondola.mass * (H + scene.gondola.height) + scene.rotor.mass * (H + scene.rotor.height)
    return STANDARD_GRAVITY * (tube + tops)


def check_foundation_holds(scene: Scene) -> None:
    """Refuse (InputError, one line naming the key) a foundation that cannot hold the machine up:
    a footing deeper than it is wide, or base springs whose rocking stiffness, at the ground,
    does not exceed the weight's overturning stiffness sum(m g z).  Below it the machine topples:
    a rigid body on a rocking spring K_R has the potential (K_R - sum(m g z)) phi**2 / 2, and the
    elastic tube only lowers that margin.  The models here carry no gravity stiffness, so they
    would compute modes of a machine that cannot stand (or fail to compute any)."""
    f = scene.foundation
    if f.kind == "clamped":
        return
    if f.kind == "footing":
        assert f.radius is not None
        if f.embedment > MAX_EMBEDMENT_OVER_WIDTH * 2 * f.radius:
            raise InputError(
                f"foundation.embedment = {f.embedment:g} is out of range: must be >= 0 and <= the "
                f"footing's width 2 x foundation.radius = {2 * f.radius:g} (m): deeper, it is a caisson, "
                "not a shallow footing (Gazetas' formulas)"
            )
    springs = foundation_stiffness(f)
    assert springs is not None
    need = overturning_stiffness(scene)
    # the rocking stiffness a rigid tilt about the base meets, with the coupling's share: the
    # smallest of K_R - K_HR**2 / K_H (the base free to slide) would be stricter still; the base
    # pinned against sliding by K_H is the case the tube's own bending sees
    if not springs.rocking > need:
        if f.kind == "springs":
            said = f"foundation.rocking_stiffness = {springs.rocking:g} is out of range: must be"
        else:
            said = (
                f"foundation.radius = {f.radius:g} with foundation.soil_shear_modulus = {f.soil_shear_modulus:g}: "
                f"the footing's rocking stiffness K_R = {springs.rocking:.4g} N*m/rad must be"
            )
        raise InputError(
            f"{said} > the machine's overturning stiffness sum(m g z) = {need:.4g} N*m/rad, or it topples"
            + ("" if f.kind == "springs" else " (give a wider footing or a stiffer soil)")
        )
