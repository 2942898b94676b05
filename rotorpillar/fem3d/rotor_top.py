"""The rotor on its elastic shaft at the 3D tube's top plate: the scalar part of a step.

Numpy only.  The rotor's mass centre (x_r, y_r) hangs on the shaft springs
c2 from the plate's reference point (U_x, U_z), each stretched by the
eccentricity: the shaft deflections are x_r - U_x - e cos(theta) and
y_r - U_z - e sin(theta), as in the paper's equation 4 with its tip q1 = U_x
and the ground anchor of its q3 replaced by the plate's axial U_z (the
paper's Y is the tube's axis z).  b2 acts on the rotor centre's velocity
relative to the ground, as the modal model has it.

Within one implicit Newmark step (average acceleration) the rotor centre
condenses onto the plate (it couples to U_x and U_z only), and the tube's
response to the unbalance force is c2 e (cos theta, sin theta) times two
fixed vectors of the factorised operator.  So every plate and rotor
quantity at the new time is affine in (cos theta, sin theta), and the step
closes with one scalar equation, the spin equation, solved here by Newton:
the whole coupled system is integrated implicitly with one factorisation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Rotor:
    """The rotor on its shaft (SI)."""
    mass: float
    """m_C (kg)"""
    inertia: float
    """J_C about its spin axis (kg*m**2)"""
    eccentricity: float
    """e (m)"""
    shaft_stiffness: float
    """c2 = c3 (N/m)"""
    shaft_damping: float
    """b2 = b3, on the rotor centre's velocity relative to the ground (N*s/m)"""

    @classmethod
    def from_scene(cls, scene) -> "Rotor":
        r, s = scene.rotor, scene.shaft
        return cls(r.mass, r.inertia, r.eccentricity, s.stiffness, s.damping)


@dataclass(frozen=True)
class Affine:
    """a0 + ac cos(theta) + as_ sin(theta)."""
    a0: float
    ac: float
    as_: float

    def at(self, c: float, s: float) -> float:
        return self.a0 + self.ac * c + self.as_ * s

    def slope(self, c: float, s: float) -> float:
        """d/dtheta"""
        return self.as_ * c - self.ac * s


def newmark_rotor_stiffness(rotor: Rotor, h: float) -> float:
    """k_r = c2 + 2 b2 / h + 4 m / h**2: the rotor centre's effective stiffness in a step (N/m)."""
    return rotor.shaft_stiffness + 2 * rotor.shaft_damping / h + 4 * rotor.mass / h**2


def rotor_start(rotor: Rotor, theta0: float, speed0: float) -> tuple[float, float, float, float]:
    """(x_r, y_r, x_r', y_r'): the rotor's steady whirl at ``speed0`` on a motionless plate.

    X = c2 e / (c2 - m W**2 + i W b2), x_r = Re(X e^{i theta0}),
    y_r = Re(-i X e^{i theta0}) (the modal model's steady state with the
    structure held).  At rest (speed0 = 0) the shaft is unstretched and no
    force acts; spinning, this start leaves out only the tube's share of
    the whirl, a transient of the tube's size, not of the rotor's.
    """
    c2, m, b = rotor.shaft_stiffness, rotor.mass, rotor.shaft_damping
    X = c2 * rotor.eccentricity / complex(c2 - m * speed0**2, speed0 * b)
    z = X * complex(math.cos(theta0), math.sin(theta0))
    return z.real, z.imag, -speed0 * z.imag, speed0 * z.real


def plate_and_rotor(rotor: Rotor, kr: float, ux_hat: float, uz_hat: float, rho_x: float,
                    rho_y: float, gamma: float, g: tuple[float, float, float, float]):
    """(U_x, U_z, x_r, y_r) at the new time as Affine functions of the new theta.

    ``ux_hat``, ``uz_hat``: the plate's motion solved without the unbalance;
    ``g`` = (U_x under a unit load on U_x, U_x under a unit load on U_z,
    U_z under a unit load on U_x, U_z under a unit load on U_z) of the
    factorised operator; ``gamma`` = -c2 e (1 - c2 / k_r), the condensed
    unbalance load on the plate per unit cos/sin (N); ``rho_x``, ``rho_y``
    the rotor centre's Newmark history terms (N).
    """
    c2e = rotor.shaft_stiffness * rotor.eccentricity
    gNN, gZN, gNZ, gZZ = g
    Ux = Affine(ux_hat, gamma * gNN, gamma * gZN)
    Uz = Affine(uz_hat, gamma * gNZ, gamma * gZZ)
    c2 = rotor.shaft_stiffness
    xr = Affine((rho_x + c2 * Ux.a0) / kr, (c2e + c2 * Ux.ac) / kr, c2 * Ux.as_ / kr)
    yr = Affine((rho_y + c2 * Uz.a0) / kr, c2 * Uz.ac / kr, (c2e + c2 * Uz.as_) / kr)
    return Ux, Uz, xr, yr


def coupling_torque(rotor: Rotor, sx: float, sy: float, theta: float) -> float:
    """Torque of the shaft on the rotor, -c2 e sx sin(theta) + c2 e sy cos(theta) (N*m).

    sx = x_r - U_x, sy = y_r - U_z: the rotor centre relative to the plate
    (the last line of the paper's equation 4).
    """
    c2e = rotor.shaft_stiffness * rotor.eccentricity
    return c2e * (sy * math.cos(theta) - sx * math.sin(theta))


def drive_torque(M0: float, slope: float, load: float, W: float) -> float:
    """Md - Mc = M0 - s W - k W |W| (N*m)."""
    return M0 - slope * W - load * W * abs(W)


def solve_spin(rotor: Rotor, h: float, theta_n: float, W_n: float, alpha_n: float,
               sx: Affine, sy: Affine, M0: float, slope: float, load: float,
               tol: float = 1e-12, max_iter: int = 30) -> tuple[float, float, float, int]:
    """The new (theta, Omega, Omega', Newton iterations) of a Newmark step.

    J alpha = Md(Omega) - Mc(Omega) + T_shaft(theta) with Newmark's
    alpha = 4/h**2 (theta - theta_n - h W_n) - alpha_n and
    Omega = 2/h (theta - theta_n) - W_n; sx, sy the rotor centre relative to
    the plate as functions of the new theta.
    """
    J = rotor.inertia
    c2e = rotor.shaft_stiffness * rotor.eccentricity
    th = theta_n + h * W_n + 0.5 * h * h * alpha_n
    for it in range(1, max_iter + 1):
        c, s = math.cos(th), math.sin(th)
        W = 2 / h * (th - theta_n) - W_n
        alpha = 4 / h**2 * (th - theta_n - h * W_n) - alpha_n
        x, y = sx.at(c, s), sy.at(c, s)
        Tc = c2e * (y * c - x * s)
        dTc = c2e * (sy.slope(c, s) * c - y * s - sx.slope(c, s) * s - x * c)
        R = J * alpha - drive_torque(M0, slope, load, W) - Tc
        dR = 4 * J / h**2 + (slope + 2 * load * abs(W)) * 2 / h - dTc
        dth = -R / dR
        th += dth
        if abs(dth) <= tol * max(1.0, abs(th)):
            break
    else:
        raise ArithmeticError(f"the spin equation did not converge in {max_iter} Newton iterations")
    W = 2 / h * (th - theta_n) - W_n
    alpha = 4 / h**2 * (th - theta_n - h * W_n) - alpha_n
    return th, W, alpha, it
