"""Linear isotropic elasticity: the material law and the two bilinear forms.

Small strain eps(u) = sym(grad u), Hooke's law sigma = lambda tr(eps) I +
2 mu eps, stiffness a(u, v) = int sigma(u) : eps(v) dx, mass m(u, v) =
int rho u . v dx.  SI units throughout (Pa, kg/m**3, m).

>>> lam, mu = lame_parameters(2.1e11, 0.3)
>>> round(lam / 1e9, 3), round(mu / 1e9, 3)
(121.154, 80.769)
"""

from __future__ import annotations


def lame_parameters(youngs_modulus: float, poisson_ratio: float) -> tuple[float, float]:
    """(lambda, mu) in Pa from E (Pa) and nu (-)."""
    E, nu = youngs_modulus, poisson_ratio
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def epsilon(u):
    """Small-strain tensor sym(grad u) (-)."""
    import ufl

    return ufl.sym(ufl.grad(u))


def sigma(u, youngs_modulus: float, poisson_ratio: float):
    """Cauchy stress of an isotropic linear material (Pa)."""
    import ufl

    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    eps = epsilon(u)
    return lam * ufl.tr(eps) * ufl.Identity(len(u)) + 2 * mu * eps


def stiffness_form(u, v, youngs_modulus: float, poisson_ratio: float, dx):
    """a(u, v) = int sigma(u) : eps(v) dx (J per unit displacements)."""
    import ufl

    return ufl.inner(sigma(u, youngs_modulus, poisson_ratio), epsilon(v)) * dx


def mass_form(u, v, density: float, dx):
    """m(u, v) = int rho u . v dx (kg)."""
    import ufl

    return density * ufl.inner(u, v) * dx
