"""The rotor on its elastic shaft at the 3D tube's top plate: the scalar part of a step.

Numpy only.  The rotor's mass centre (x_r, y_r) hangs on the shaft springs
c2 from the plate's reference point (U_x, U_z), each stretched by the
eccentricity: the shaft deflections are x_r - U_x - e cos(theta) and
y_r - U_z - e sin(theta), as in the paper's Eq. 4 with its tip q1 = U_x
and the ground anchor of its q3 replaced by the plate's axial U_z (the
paper's Y is the tube's axis z).  b2 acts on the rotor centre's velocity
relative to the ground, as the modal model has it.

The step is the generalized-alpha method (Chung & Hulbert 1993; ``Step``):
Newmark's updates with the equilibrium taken between the old and the new
time, inertia weighted by alpha_m and every other force by alpha_f (the
forces, not the states, are weighted: the unbalance then enters the new
time through cos and sin of the new theta only).  Newmark's average
acceleration is alpha_m = alpha_f = 0, beta = 1/4, gamma = 1/2; HHT-alpha
(Hilber, Hughes & Taylor 1977) alpha_m = 0.  Within one implicit step the
rotor centre condenses onto the plate (it couples to U_x and U_z only),
and the tube's response to the unbalance force is c2 e (cos theta,
sin theta) times two fixed vectors of the factorised operator.  So every
plate and rotor quantity at the new time is affine in (cos theta,
sin theta), and the step closes with one scalar equation, the spin
equation, solved here by Newton: the whole coupled system is integrated
implicitly with one factorisation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class RotorOnTop:
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
    def from_scene(cls, scene) -> RotorOnTop:
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


@dataclass(frozen=True)
class Step:
    """One generalized-alpha step of length h (Chung & Hulbert 1993), SI.

    (1 - alpha_m) M a1 + alpha_m M a0 + (1 - alpha_f) f(1) + alpha_f f(0) = 0 for
    every force f but inertia, with Newmark's x1 = x~ + beta h**2 a1,
    v1 = v~ + gamma h a1 (``predict``: x~, v~).  Second order when
    gamma = 1/2 - alpha_m + alpha_f; parameters by
    rotorpillar.reduced.fixed_step.genalpha_parameters.
    """

    h: float
    """the step (s)"""
    alpha_m: float = 0.0
    alpha_f: float = 0.0
    beta: float = 0.25
    gamma: float = 0.5

    @property
    def mass_coefficient(self) -> float:
        """(1 - alpha_m) / (beta h**2): inertia's share of the step's stiffness (1/s**2)."""
        return (1 - self.alpha_m) / (self.beta * self.h**2)

    @property
    def damping_coefficient(self) -> float:
        """(1 - alpha_f) gamma / (beta h): a dashpot's share of the step's stiffness (1/s)."""
        return (1 - self.alpha_f) * self.gamma / (self.beta * self.h)

    @property
    def new_weight(self) -> float:
        """1 - alpha_f: the weight of the new time's forces (-)."""
        return 1 - self.alpha_f

    def predict(self, x: float, v: float, a: float) -> tuple[float, float]:
        """(x~, v~): the new displacement and velocity without the new acceleration."""
        h = self.h
        return x + h * v + h * h * (0.5 - self.beta) * a, v + h * (1 - self.gamma) * a

    def update(self, x1: float, xt: float, vt: float) -> tuple[float, float]:
        """(v1, a1) from the new displacement and the prediction."""
        a1 = (x1 - xt) / (self.beta * self.h**2)
        return vt + self.gamma * self.h * a1, a1

    def history(self, mass: float, damping: float, x: float, v: float, a: float, old_force: float) -> float:
        """The known part of a scalar dof's step equation (N): the new x times
        ``stiffness`` = history + the new-time coupling forces.  ``old_force``:
        the old time's elastic and external forces acting on it (N)."""
        xt, vt = self.predict(x, v, a)
        return (
            mass * (self.mass_coefficient * xt - self.alpha_m * a)
            + damping * (self.damping_coefficient * xt - self.new_weight * vt - self.alpha_f * v)
            + self.alpha_f * old_force
        )


def rotor_step_stiffness(rotor: RotorOnTop, step: Step) -> float:
    """The rotor centre's effective stiffness in a step (N/m):
    (1 - af) c2 + (1 - af) gamma / (beta h) b2 + (1 - am) / (beta h**2) m."""
    return (
        step.new_weight * rotor.shaft_stiffness
        + step.damping_coefficient * rotor.shaft_damping
        + step.mass_coefficient * rotor.mass
    )


def rotor_start(rotor: RotorOnTop, theta0: float, speed0: float) -> tuple[float, float, float, float]:
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


def plate_and_rotor(
    rotor: RotorOnTop,
    kr: float,
    ux_hat: float,
    uz_hat: float,
    rho_x: float,
    rho_y: float,
    gamma: float,
    g: tuple[float, float, float, float],
    weight: float = 1.0,
    coupling: float | None = None,
):
    """(U_x, U_z, x_r, y_r) at the new time as Affine functions of the new theta.

    ``ux_hat``, ``uz_hat``: the plate's motion solved without the unbalance;
    ``g`` = (U_x under a unit load on U_x, U_x under a unit load on U_z,
    U_z under a unit load on U_x, U_z under a unit load on U_z) of the
    factorised operator; ``gamma`` = -w c2 e (1 - w c2 / k_r), the condensed
    unbalance load on the plate per unit cos/sin (N); ``rho_x``, ``rho_y``
    the rotor centre's history terms (N) (``Step.history``); ``weight`` w =
    1 - alpha_f, the new time's share of the shaft force; ``coupling`` kappa, the step's
    stiffness between the rotor centre and the plate (default w c2; w c2 + the dashpot's
    share when b2 acts on the motion relative to the plate).
    """
    c2e = weight * rotor.shaft_stiffness * rotor.eccentricity
    gNN, gZN, gNZ, gZZ = g
    Ux = Affine(ux_hat, gamma * gNN, gamma * gZN)
    Uz = Affine(uz_hat, gamma * gNZ, gamma * gZZ)
    c2 = weight * rotor.shaft_stiffness if coupling is None else coupling
    xr = Affine((rho_x + c2 * Ux.a0) / kr, (c2e + c2 * Ux.ac) / kr, c2 * Ux.as_ / kr)
    yr = Affine((rho_y + c2 * Uz.a0) / kr, c2 * Uz.ac / kr, (c2e + c2 * Uz.as_) / kr)
    return Ux, Uz, xr, yr


def coupling_torque(rotor: RotorOnTop, sx: float, sy: float, theta: float) -> float:
    """Torque of the shaft on the rotor, -c2 e sx sin(theta) + c2 e sy cos(theta) (N*m).

    sx = x_r - U_x, sy = y_r - U_z: the rotor centre relative to the plate
    (the last line of the paper's Eq. 4).
    """
    c2e = rotor.shaft_stiffness * rotor.eccentricity
    return c2e * (sy * math.cos(theta) - sx * math.sin(theta))


def drive_torque(M0: float, slope: float, load: float, W: float) -> float:
    """Md - Mc = M0 - s W - k W |W| (N*m)."""
    return M0 - slope * W - load * W * abs(W)


def solve_spin(
    rotor: RotorOnTop,
    h: float,
    theta_n: float,
    W_n: float,
    alpha_n: float,
    sx: Affine,
    sy: Affine,
    M0: float,
    slope: float,
    load: float,
    tol: float = 1e-12,
    max_iter: int = 30,
    step: Step | None = None,
    old_torque: float = 0.0,
) -> tuple[float, float, float, int]:
    """The new (theta, Omega, Omega', Newton iterations) of a step (Newmark's by default).

    (1 - am) J alpha + am J alpha_n = (1 - af) (Md - Mc + T_shaft)(new)
    + af ``old_torque`` with Newmark's alpha = (theta - theta~) / (beta h**2),
    Omega = Omega~ + gamma h alpha (``step``, h ignored when given); sx, sy the
    rotor centre relative to the plate as functions of the new theta.
    """
    step = step or Step(h)
    J = rotor.inertia
    c2e = rotor.shaft_stiffness * rotor.eccentricity
    am, wf, b, g, hh = step.alpha_m, step.new_weight, step.beta, step.gamma, step.h
    th_t, W_t = step.predict(theta_n, W_n, alpha_n)
    th = theta_n + hh * W_n + 0.5 * hh * hh * alpha_n
    for it in range(1, max_iter + 1):  # noqa: B007 (returned below: the Newton iterations taken)
        c, s = math.cos(th), math.sin(th)
        alpha = (th - th_t) / (b * hh * hh)
        W = W_t + g * hh * alpha
        x, y = sx.at(c, s), sy.at(c, s)
        Tc = c2e * (y * c - x * s)
        dTc = c2e * (sy.slope(c, s) * c - y * s - sx.slope(c, s) * s - x * c)
        R = (
            J * ((1 - am) * alpha + am * alpha_n)
            - wf * (drive_torque(M0, slope, load, W) + Tc)
            - step.alpha_f * old_torque
        )
        dR = (1 - am) * J / (b * hh * hh) + wf * ((slope + 2 * load * abs(W)) * g / (b * hh) - dTc)
        dth = -R / dR
        th += dth
        if abs(dth) <= tol * max(1.0, abs(th)):
            break
    else:
        raise ArithmeticError(f"the spin equation did not converge in {max_iter} Newton iterations")
    alpha = (th - th_t) / (b * hh * hh)
    return th, W_t + g * hh * alpha, alpha, it
