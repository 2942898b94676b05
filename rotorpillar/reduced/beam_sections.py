"""The pillar's cross-sections as a 1D model sees them, one row per element.

``tube_sections(pillar, n_elements)`` is the one place the 1D models of the
spatial pillar (rotorpillar.reduced.spatial_beam) read the tube from: per
element its length, material and section constants.  Today every element
is the scene's uniform tube; a tapered or stepped tube only has to fill
these arrays differently (and foundation springs enter at the assembly's
base, rotorpillar.reduced.beam_line).

For a thin or thick circular tube (outer and inner diameter D0, D1):

- area                  A   = pi/4 (D0**2 - D1**2)                  (m**2)
- second moment         I   = pi/64 (D0**4 - D1**4), about either diameter (m**4)
- torsion constant      J_t = pi/32 (D0**4 - D1**4) = 2 I: Saint-Venant's for a
                        circular section, which does not warp (m**4)
- polar moment          I_p = 2 I: the section's mass moment per length is rho I_p (m**4)
- shear coefficient     kappa: Cowper's (1966) for a hollow circle (-)

>>> from rotorpillar.scene import load_scene
>>> s = tube_sections(load_scene("paper").pillar, 4)
>>> s.count, round(float(s.torsion_constant[0] / s.second_moment[0]), 12)
(4, 2.0)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..scene import Pillar
from .pillar import cowper_shear_coefficient


@dataclass(frozen=True, eq=False)
class BeamSections:
    """Per element (base first): the constants the 1D element matrices take."""

    length: NDArray[np.float64]
    """(n,) element lengths, summing to the pillar's height (m)"""
    youngs_modulus: NDArray[np.float64]
    """(n,) E (Pa)"""
    shear_modulus: NDArray[np.float64]
    """(n,) G = E / (2 (1 + nu)) (Pa)"""
    density: NDArray[np.float64]
    """(n,) rho (kg/m**3)"""
    area: NDArray[np.float64]
    """(n,) A (m**2)"""
    second_moment: NDArray[np.float64]
    """(n,) I about a diameter, the same about x and y: the tube is round (m**4)"""
    torsion_constant: NDArray[np.float64]
    """(n,) Saint-Venant's J_t (m**4)"""
    polar_moment: NDArray[np.float64]
    """(n,) I_p, the polar second moment of the section's area (m**4)"""
    shear_coefficient: NDArray[np.float64]
    """(n,) kappa (-)"""

    @property
    def count(self) -> int:
        return len(self.length)

    @property
    def heights(self) -> NDArray[np.float64]:
        """(n + 1,) node heights, base (0) first (m)"""
        out: NDArray[np.float64] = np.r_[0.0, np.cumsum(self.length)]
        return out

    @property
    def mass(self) -> float:
        """The pillar's mass (kg)"""
        return float(np.sum(self.density * self.area * self.length))

    @property
    def polar_mass_inertia(self) -> float:
        """The pillar's mass moment of inertia about its axis, sum rho I_p L (kg*m**2)"""
        return float(np.sum(self.density * self.polar_moment * self.length))


def tube_sections(pillar: Pillar, n_elements: int) -> BeamSections:
    """The scene's uniform tube as ``n_elements`` equal elements."""
    if n_elements < 1:
        raise ValueError("n_elements must be >= 1")
    p = pillar
    D0, D1 = p.outer_diameter, p.inner_diameter
    area = math.pi / 4 * (D0**2 - D1**2)
    second = math.pi / 64 * (D0**4 - D1**4)
    kappa = cowper_shear_coefficient(D0, D1, p.poisson_ratio)

    def each(value: float) -> NDArray[np.float64]:
        return np.full(n_elements, float(value))

    return BeamSections(
        length=each(p.height / n_elements),
        youngs_modulus=each(p.youngs_modulus),
        shear_modulus=each(p.youngs_modulus / (2 * (1 + p.poisson_ratio))),
        density=each(p.density),
        area=each(area),
        second_moment=each(second),
        torsion_constant=each(2 * second),
        polar_moment=each(2 * second),
        shear_coefficient=each(kappa),
    )
