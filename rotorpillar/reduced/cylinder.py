"""Closed forms of a thin circular cylindrical shell's free vibration.

Two references for the shell and 3D models of the tube:

- Sanders' first-order shell theory with shear-diaphragm ends (simply
  supported: v = w = 0 and no axial moment at x = 0, L).  The modes
  u = A cos(lam x) cos(n th), v = B sin(lam x) sin(n th),
  w = C sin(lam x) cos(n th), lam = m pi / L, are exact; the energy then
  reduces to a 3x3 eigenproblem per (m, n) whose lowest root is the
  flexural frequency (Leissa, Vibration of Shells, NASA SP-288, 1973,
  sec. 2.3-2.4; Sanders' strains from Leissa's Eq. 1.39-1.40).
- The inextensional ring (plane strain): the limit of a very long tube's
  n >= 2 ovalling modes (Soedel, Vibrations of Shells and Plates, 3rd ed.,
  2004, sec. 5.3)::

      omega_n**2 = D / (rho t R**4) * n**2 (n**2 - 1)**2 / (n**2 + 1),
      D = E t**3 / (12 (1 - nu**2)).

Units SI: m, Pa, kg/m**3, rad/s.

>>> round(ring_frequency(2, 2.1e11, 0.3, 8.1e3, 0.99, 0.02), 2)
84.37
>>> round(sanders_frequency(1, 2, 2.1e11, 0.3, 8.1e3, 0.99, 0.02, 20.0), 2)
89.18
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh


def ring_frequency(n: int, E: float, nu: float, rho: float, R: float, t: float) -> float:
    """Inextensional ovalling of a long tube, plane strain (rad/s); n >= 2."""
    if n < 2:
        raise ValueError("ring ovalling needs n >= 2")
    D = E * t**3 / (12 * (1 - nu**2))
    return math.sqrt(D / (rho * t * R**4) * n**2 * (n**2 - 1) ** 2 / (n**2 + 1))


def sanders_frequencies(
    m: int, n: int, E: float, nu: float, rho: float, R: float, t: float, L: float
) -> NDArray[np.float64]:
    """The three frequencies (rad/s) of mode (m, n) of a simply supported cylinder.

    Sanders' strains of the mode, per amplitude (A, B, C) of (u, v, w); each
    strain is a coefficient times sin or cos products whose squares integrate
    to the same pi R L / 2 (n >= 1), so that factor cancels:
    eps_x = u_x, eps_th = (v_th + w)/R, gam = v_x + u_th/R,
    kap_x = -w_xx, kap_th = (v_th - w_thth)/R**2,
    tau = (-2 w_xth + 3/2 v_x - u_th/(2R))/R.
    """
    if m < 1 or n < 1:
        raise ValueError("need m >= 1 and n >= 1")
    lam = m * math.pi / L
    eps_x = np.array([-lam, 0.0, 0.0])
    eps_th = np.array([0.0, n, 1.0]) / R
    gam = np.array([-n / R, lam, 0.0])
    kap_x = np.array([0.0, 0.0, lam**2])
    kap_th = np.array([0.0, n, n**2]) / R**2
    tau = np.array([n / (2 * R), 1.5 * lam, 2 * n * lam]) / R
    K_m = E * t / (1 - nu**2)
    D = E * t**3 / (12 * (1 - nu**2))

    def energy(a: NDArray[np.float64], b: NDArray[np.float64], c: NDArray[np.float64]) -> NDArray[np.float64]:
        form: NDArray[np.float64] = (
            np.outer(a, a) + np.outer(b, b) + nu * (np.outer(a, b) + np.outer(b, a)) + (1 - nu) / 2 * np.outer(c, c)
        )
        return form

    K = K_m * energy(eps_x, eps_th, gam) + D * energy(kap_x, kap_th, tau)
    w2: NDArray[np.float64] = eigh(K, rho * t * np.eye(3), eigvals_only=True)  # scipy: no stubs
    return np.sqrt(w2)


def sanders_frequency(m: int, n: int, E: float, nu: float, rho: float, R: float, t: float, L: float) -> float:
    """The lowest (flexural) frequency of mode (m, n) (rad/s)."""
    return float(sanders_frequencies(m, n, E, nu, rho, R, t, L)[0])
