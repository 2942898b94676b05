"""The two rotor-pillar models of the transients, in one generic form.

Both are a linear structure in X (coordinates z), the rotor centre's Y
coordinate y and the rotor angle theta, coupled through the shaft spring c2
acting on the shaft deflection d.z - e cos(theta) (X) and y - e sin(theta)
(Y).  Energies:

    T = 1/2 z'^T M z' + 1/2 m_C y'**2 + 1/2 J theta'**2
    P = 1/2 z^T Ks z + 1/2 c2 (d.z - e cos theta)**2 + 1/2 c2 (y - e sin theta)**2

and forces C z' (structure), b2 y' (rotor Y), the base forcing
kb u_g + cb v_g + mb a_g on z, and the motor and machine torques on theta
(rotorpillar.reduced.rhs writes the equations out).

**paper** (``paper_model``): the paper's Eq. 4 as published, z = (q1, q2):
M = diag(m_A, m_C), Ks = diag(c1, 0), d = (-1, 1), so Ks + c2 d d^T is
Eq. 4's [[c0, -c2], [-c2, c2]]; damping diag(b0, b2) with b0 = b1 + b2
(Eq. 4 prints b0 on q1 and an absolute b2 on q2; its own dissipation function
Phi = 1/2 (b1 q1'**2 + b2 q2'**2 + b3 q3'**2) would give b1 on q1); base
forcing c0 q5 + b0 q5' on q1 and c2 q5 + b2 q5' on q2, as printed.  The
coordinates are absolute.

**modal** (``modal_model``): the pillar by its first k modes (PillarModes,
tip-scaled, gondola included) and the rotor centre in X, z = (eta_1..eta_k,
x_r), all relative to the ground, tip X = sum eta_j:
M = diag(m_1..m_k, m_C), Ks = diag(k_1..k_k, 0), d = (-1, ..., -1, 1);
the pillar damping is the scene's b1 as a dashpot at the tip (C = b1 on every
pair of modes, since the tip moves as sum eta_j), or modal ratios if the
modes carry them; b2 acts on the rotor centre's velocity relative to the
ground in X and Y, as the paper's Phi has it.  The base excitation is
physical: relative coordinates forced by the ground's inertia, -L_j a_g on
mode j and -m_C a_g on the rotor.  With one mode of mass m_A and stiffness
c1 this is Eq. 4 except for the b2 that Eq. 4 adds on q1 and the base terms.

Quasi-normal data of either model (``quasi_normal``) are the Resonance
records of rotorpillar.reduced.system, so the averaging of
rotorpillar.reduced.averaging applies to both.
"""

from __future__ import annotations

import hashlib
import math
import pickle
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eig, eigh

from ..provenance import Record
from .drive import DriveSchedule
from .excitation import GroundMotion
from .ground3d import SpatialGroundMotion
from .pillar_modes import ModesDescription, PillarModes
from .rhs import Packed
from .system import DampedMode, ReducedSystem, Resonance

FRAMES = ("absolute", "relative_to_ground")


class StructureDescription(Record, eq=False):  # arrays: no elementwise ==
    """A rotor-structure model as a run's JSON describes it (SI units, by coordinate)."""

    name: str
    """paper, modal or beam"""
    coordinates: tuple[str, ...]
    """the coordinates' names, structure (X) first, then the rotor's y and theta"""
    frame: str
    """"absolute" or "relative_to_ground\""""
    nx: int
    """X coordinates (-)"""
    mass: NDArray[np.float64]
    """(nx, nx) mass matrix (kg)"""
    stiffness: NDArray[np.float64]
    """(nx, nx) stiffness without the shaft (N/m)"""
    stiffness_with_shaft: NDArray[np.float64]
    """(nx, nx) with the shaft's c2 (N/m)"""
    damping: NDArray[np.float64]
    """(nx, nx) damping matrix (N*s/m)"""
    shaft: NDArray[np.float64]
    """(nx,) the shaft's deflection per coordinate (-)"""
    tip: NDArray[np.float64]
    """(nx,) the tip's X per coordinate (-)"""
    base_displacement: NDArray[np.float64]
    """(nx,) the ground displacement's force per metre (N/m)"""
    base_velocity: NDArray[np.float64]
    """(nx,) the ground velocity's force (N*s/m)"""
    base_acceleration: NDArray[np.float64]
    """(nx,) the ground acceleration's force (kg)"""
    rotor_mass: float
    """m_C (kg)"""
    rotor_inertia: float
    """J_C (kg*m**2)"""
    eccentricity: float
    """e (m)"""
    shaft_stiffness: float
    """c2 (N/m)"""
    shaft_damping: float
    """b2 (N*s/m)"""
    pillar_modes: ModesDescription | None
    """the modal model's pillar modes"""
    notes: dict[str, Any]
    """the model's equations and what its builder states, in words and numbers"""


@dataclass(frozen=True, eq=False)
class RotorStructure:
    """A linear structure in X with the rotor on its shaft (see the module text)."""

    name: str
    """"paper" or "modal\""""
    coordinates: tuple[str, ...]
    """names of the X coordinates z"""
    mass: NDArray[np.float64]
    """(nx, nx) M (kg)"""
    stiffness: NDArray[np.float64]
    """(nx, nx) Ks, the structure without the shaft (N/m)"""
    damping: NDArray[np.float64]
    """(nx, nx) C (N*s/m)"""
    shaft: NDArray[np.float64]
    """(nx,) d: shaft deflection in X = d.z - e cos(theta)"""
    tip: NDArray[np.float64]
    """(nx,) tip X displacement = tip.z"""
    rotor_x: int
    """index of the rotor centre in z"""
    shaft_stiffness: float
    """c2 = c3 (N/m)"""
    shaft_damping: float
    """b2 = b3: rotor centre damping in Y (and in X, inside C) (N*s/m)"""
    eccentricity: float
    """e (m)"""
    rotor_mass: float
    """m_C (kg)"""
    rotor_inertia: float
    """J_C (kg*m**2)"""
    base_displacement: NDArray[np.float64]
    """(nx,) kb: force per metre of ground displacement (N/m)"""
    base_velocity: NDArray[np.float64]
    """(nx,) cb: force per m/s of ground velocity (N*s/m)"""
    base_acceleration: NDArray[np.float64]
    """(nx,) mb: force per m/s**2 of ground acceleration (kg)"""
    frame: str
    """"absolute" (paper) or "relative_to_ground" (modal)"""
    pillar_modes: PillarModes | None = None
    notes: dict[str, Any] = field(default_factory=dict)

    # ------------------------------------------------------------ sizes
    @property
    def nx(self) -> int:
        return len(self.shaft)

    @property
    def n(self) -> int:
        """all coordinates: z, y, theta"""
        return self.nx + 2

    @property
    def names(self) -> list[str]:
        return list(self.coordinates) + ["rotor_y", "theta"]

    def stiffness_full(self) -> NDArray[np.float64]:
        """Ks + c2 d d^T: the X stiffness with the shaft (N/m)."""
        return self.stiffness + self.shaft_stiffness * np.outer(self.shaft, self.shaft)

    def mass_inverse(self, prescribed_speed: bool = False) -> NDArray[np.float64]:
        """Minv; with a prescribed speed theta's row is zero (theta'' = 0)."""
        Minv = np.zeros((self.n, self.n))
        Minv[: self.nx, : self.nx] = np.linalg.inv(self.mass)
        Minv[self.nx, self.nx] = 1.0 / self.rotor_mass
        if not prescribed_speed:
            Minv[-1, -1] = 1.0 / self.rotor_inertia
        return Minv

    # ------------------------------------------------------------ kernels
    def pack(
        self,
        drive: DriveSchedule,
        motion: GroundMotion | SpatialGroundMotion,
        prescribed_speed: bool = False,
        **overrides: float,
    ) -> Packed:
        """The tuple P of rotorpillar.reduced.rhs; a SpatialGroundMotion only with one
        component in the rotor's plane (the planar model has no other direction)."""
        if isinstance(motion, SpatialGroundMotion) and (motion.count != 1 or motion.directions[0] != (1.0, 0.0, 0.0)):
            raise ValueError("the planar model takes one ground-motion component, in the rotor's plane")
        gpar, gtab = motion.pack()

        def c(a: ArrayLike) -> NDArray[np.float64]:
            return np.ascontiguousarray(a, dtype=float)

        scal = np.array(
            [
                overrides.get("shaft_stiffness", self.shaft_stiffness),
                overrides.get("eccentricity", self.eccentricity),
                0.0,
                drive.load_coefficient,
            ],
            dtype=float,
        )
        return (
            c(self.mass_inverse(prescribed_speed)),
            *generic_arrays(self),
            scal,
            c(drive.table()),
            c(gpar),
            c(gtab),
        )

    # ------------------------------------------------------------ energy
    def energy(self, q: NDArray[np.float64], v: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Eq. 3 generalised: kinetic and potential energy per row of q, v (J); structure only
        when the last column (theta') is excluded by the caller."""
        nx = self.nx
        z, vz = q[:, :nx], v[:, :nx]
        y, vy, th, W = q[:, nx], v[:, nx], q[:, nx + 1], v[:, nx + 1]
        T = 0.5 * np.einsum("ti,ij,tj->t", vz, self.mass, vz) + 0.5 * self.rotor_mass * vy**2
        T = T + 0.5 * self.rotor_inertia * W**2
        e, c2 = self.eccentricity, self.shaft_stiffness
        P = (
            0.5 * np.einsum("ti,ij,tj->t", z, self.stiffness, z)
            + 0.5 * c2 * (z @ self.shaft - e * np.cos(th)) ** 2
            + 0.5 * c2 * (y - e * np.sin(th)) ** 2
        )
        return T, P

    # ------------------------------------------------------------ linear analysis
    def undamped_modes_x(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """omega (ascending) and tip-scaled shapes (nx, nx) of the X structure."""
        lam, U = eigh(self.stiffness_full(), self.mass)
        tipv = self.tip @ U
        scale = np.where(np.abs(tipv) > 1e-9 * np.max(np.abs(U), axis=0), tipv, U[self.rotor_x] if self.nx else 1.0)
        return np.sqrt(np.maximum(lam, 0.0)), U / scale

    def quasi_normal(self) -> list[Resonance]:
        """Resonance records (the paper's Eq. 7 generalised): X modes with u.tip = 1, then Y."""
        c2, e = self.shaft_stiffness, self.eccentricity
        om, U = self.undamped_modes_x()
        out = []
        for i in range(self.nx):
            u = U[:, i]
            I = float(u @ self.mass @ u)
            g = float(c2 * e * (self.shaft @ u))
            out.append(
                Resonance(
                    i + 1,
                    "X",
                    float(om[i]),
                    (float(self.tip @ u), float(u[self.rotor_x])),
                    I,
                    g / I,
                    g,
                    float(u @ self.damping @ u) / I,
                )
            )
        out.append(
            Resonance(
                self.nx + 1,
                "Y",
                math.sqrt(c2 / self.rotor_mass),
                (0.0, 1.0),
                self.rotor_mass,
                c2 * e / self.rotor_mass,
                c2 * e,
                self.shaft_damping / self.rotor_mass,
            )
        )
        return out

    def damped_frequencies(self) -> list[DampedMode]:
        """Damped natural frequencies and damping ratios of the linear structure
        (X from the state-space eigenproblem, Y as one oscillator)."""
        nx = self.nx
        Minv = np.linalg.inv(self.mass)
        A = np.block([[np.zeros((nx, nx)), np.eye(nx)], [-Minv @ self.stiffness_full(), -Minv @ self.damping]])
        lam = eig(A, right=False)
        lam = lam[lam.imag > 0]
        out = [DampedMode("X", float(abs(l)), float(l.imag), float(-l.real / abs(l))) for l in sorted(lam, key=abs)]
        m, c, k = self.rotor_mass, self.shaft_damping, self.shaft_stiffness
        w = math.sqrt(k / m)
        z = c / (2 * math.sqrt(k * m))
        out.append(DampedMode("Y", w, w * math.sqrt(max(0.0, 1 - z * z)), z))
        return out

    def steady_state(self, Omega: float) -> tuple[NDArray[np.complex128], complex]:
        """Complex amplitudes (Z, Y) of the response to a rotor turning at
        constant Omega, theta = Omega t: z = Re(Z e^{i theta}), y = Re(Y e^{i theta})."""
        c2e = self.shaft_stiffness * self.eccentricity
        D = self.stiffness_full() - Omega**2 * self.mass + 1j * Omega * self.damping
        Z = np.linalg.solve(D, c2e * self.shaft.astype(complex))
        Y = -1j * c2e / (self.shaft_stiffness - self.rotor_mass * Omega**2 + 1j * Omega * self.shaft_damping)
        return Z, Y

    def steady_torque(self, Omega: ArrayLike) -> NDArray[np.float64]:
        """Averaged shaft torque on the rotor at constant Omega (N*m); negative:
        the structure resists.  -steady_torque is the exact counterpart of
        the paper's Eq. 20 summed over dL_i."""
        W = np.atleast_1d(np.asarray(Omega, dtype=float)).ravel()
        c2e = self.shaft_stiffness * self.eccentricity
        # steady_state at every speed at once (one stacked solve)
        D = (
            self.stiffness_full()[None]
            - (W**2)[:, None, None] * self.mass[None]
            + 1j * W[:, None, None] * self.damping[None]
        )
        rhs = np.broadcast_to(c2e * self.shaft.astype(complex), (len(W), self.nx))[..., None]
        Z = np.linalg.solve(D, rhs)[..., 0]
        # Re Y = -c2e b/(a^2 + b^2) written out: an undamped shaft at resonance gives 0, not 0/0
        a, b = self.shaft_stiffness - self.rotor_mass * W**2, W * self.shaft_damping
        y_real = np.divide(-c2e * b, a**2 + b**2, out=np.zeros_like(W), where=a**2 + b**2 > 0)
        out = c2e * ((Z @ self.shaft).imag + y_real) / 2
        torque: NDArray[np.float64] = out.reshape(np.shape(Omega))
        return torque

    def steady_amplitudes(self, Omega: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """Exact steady amplitudes at constant Omega: tip and rotor X, rotor Y (m)."""
        W = np.atleast_1d(np.asarray(Omega, dtype=float))
        tip, rx, ry = (np.empty_like(W) for _ in range(3))
        for i, w in enumerate(W):
            Z, Y = self.steady_state(w)
            tip[i], rx[i], ry[i] = abs(self.tip @ Z), abs(Z[self.rotor_x]), abs(Y)
        return {"tip_x": tip, "rotor_x": rx, "rotor_y": ry}

    def steady_initial_state(self, Omega: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(q0, v0) on the steady response at speed Omega with theta = 0."""
        Z, Y = self.steady_state(Omega)
        q0 = np.zeros(self.n)
        v0 = np.zeros(self.n)
        q0[: self.nx] = Z.real
        v0[: self.nx] = -Omega * Z.imag
        q0[self.nx] = Y.real
        v0[self.nx] = -Omega * Y.imag
        v0[-1] = Omega
        return q0, v0

    def held_whirl_state(self, Omega: float, theta0: float = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(q0, v0): the structure at rest, the rotor in its steady whirl at speed
        Omega on it as if it were held (the 3D full order's start, rotorpillar.fem3d.
        rotor_top.rotor_start): X = c2 e / (c2 - m_C Omega**2 + i Omega b2),
        x_r + i y_r = X exp(i theta0)."""
        c2, m, b = self.shaft_stiffness, self.rotor_mass, self.shaft_damping
        X = c2 * self.eccentricity / complex(c2 - m * Omega**2, Omega * b)
        z = X * complex(math.cos(theta0), math.sin(theta0))
        q0, v0 = np.zeros(self.n), np.zeros(self.n)
        q0[self.rotor_x], q0[self.nx], q0[-1] = z.real, z.imag, theta0
        v0[self.rotor_x], v0[self.nx], v0[-1] = -Omega * z.imag, Omega * z.real, Omega
        return q0, v0

    def stiffest_frequency(self) -> float:
        """The highest undamped natural frequency of the structure and shaft (rad/s)."""
        return float(max(self.undamped_modes_x()[0].max(), math.sqrt(self.shaft_stiffness / self.rotor_mass)))

    def fastest_rate(self) -> float:
        """The largest |eigenvalue| at rest of the structure and of the rotor's y on its
        shaft (1/s): an explicit integrator's stability limit (reduced.explicit_limit)."""
        from .explicit_limit import first_order_rate

        m, c, k = self.rotor_mass, self.shaft_damping, self.shaft_stiffness
        y = max(abs(r) for r in np.roots([m, c, k])) if m > 0 else 0.0
        return max(first_order_rate(self.mass, self.stiffness_full(), self.damping), float(y))

    def describe(self) -> StructureDescription:
        """The model's matrices and coordinates (a run's ``model_description``)."""
        return StructureDescription(
            name=self.name,
            coordinates=tuple(self.names),
            frame=self.frame,
            nx=self.nx,
            mass=self.mass,
            stiffness=self.stiffness,
            stiffness_with_shaft=self.stiffness_full(),
            damping=self.damping,
            shaft=self.shaft,
            tip=self.tip,
            base_displacement=self.base_displacement,
            base_velocity=self.base_velocity,
            base_acceleration=self.base_acceleration,
            rotor_mass=self.rotor_mass,
            rotor_inertia=self.rotor_inertia,
            eccentricity=self.eccentricity,
            shaft_stiffness=self.shaft_stiffness,
            shaft_damping=self.shaft_damping,
            pillar_modes=None if self.pillar_modes is None else self.pillar_modes.describe(),
            notes=dict(self.notes),
        )


def generic_arrays(
    m: RotorStructure,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """(K, C, G, shaft, base) of rotorpillar.reduced.rhs for a planar model: Z = (z, y),
    K = diag(Ks, 0), C = diag(C, b2), no gyroscopic term, d_x = (d, 0), d_v = (0, 1),
    one ground component (kb, cb, mb), the tip, no motor reaction, no couple unbalance."""
    nx = m.nx
    nz = nx + 1
    K = np.zeros((nz, nz))
    K[:nx, :nx] = m.stiffness
    C = np.zeros((nz, nz))
    C[:nx, :nx] = m.damping
    C[nx, nx] = m.shaft_damping
    shaft = np.zeros((2, nz))
    shaft[0, :nx] = m.shaft
    shaft[1, nx] = 1.0
    base = np.zeros((7, nz))
    base[0, :nx], base[1, :nx], base[2, :nx], base[3, :nx] = (
        m.base_displacement,
        m.base_velocity,
        m.base_acceleration,
        m.tip,
    )
    return K, C, np.zeros((nz, nz)), shaft, base


# --------------------------------------------------------------------------
# Builders


def paper_model(s: ReducedSystem) -> RotorStructure:
    """The paper's Eq. 4 as published (absolute coordinates q1, q2, q3, q4)."""
    c0, c2, b0, b2 = s.c0, s.shaft_stiffness, s.b0, s.shaft_damping
    return RotorStructure(
        name="paper",
        coordinates=("q1_tip_x", "q2_rotor_x"),
        mass=s.mass_matrix(),
        stiffness=np.diag([s.pillar_stiffness, 0.0]),
        damping=s.damping_matrix(),
        shaft=np.array([-1.0, 1.0]),
        tip=np.array([1.0, 0.0]),
        rotor_x=1,
        shaft_stiffness=c2,
        shaft_damping=b2,
        eccentricity=s.eccentricity,
        rotor_mass=s.rotor_mass,
        rotor_inertia=s.rotor_inertia,
        base_displacement=np.array([c0, c2]),
        base_velocity=np.array([b0, b2]),
        base_acceleration=np.zeros(2),
        frame="absolute",
        notes={
            "equations": "paper Eq. 4 as published: damping diag(b0, b2), base forcing "
            "c0 q5 + b0 q5' on q1 and c2 q5 + b2 q5' on q2",
            "tip_mass": s.tip_mass,
            "pillar_stiffness": s.pillar_stiffness,
            "pillar_damping": s.pillar_damping,
        },
    )


def modal_model(
    modes: PillarModes,
    rotor_mass: float,
    rotor_inertia: float,
    eccentricity: float,
    shaft_stiffness: float,
    shaft_damping: float,
    tip_damping: float,
) -> RotorStructure:
    """The pillar by its modes, the rotor on its shaft at the tip, relative to the ground.

    ``tip_damping`` is the pillar's b1 as a dashpot at the tip, used unless
    the modes carry damping ratios.
    """
    k = modes.count
    nx = k + 1
    M = np.zeros((nx, nx))
    M[:k, :k] = np.diag(modes.modal_mass)
    M[k, k] = rotor_mass
    Ks = np.zeros((nx, nx))
    Ks[:k, :k] = np.diag(modes.modal_stiffness)
    C = np.zeros((nx, nx))
    if modes.damping_ratio is not None:
        C[:k, :k] = np.diag(2 * np.asarray(modes.damping_ratio) * modes.omega * modes.modal_mass)
        damping_law = "modal damping ratios from the mode source"
    else:
        C[:k, :k] = tip_damping  # b1 (sum eta')**2 / 2: every pair of modes
        damping_law = "pillar: the scene's b1 as a dashpot at the tip"
    C[k, k] = shaft_damping
    d = np.r_[-np.ones(k), 1.0]
    tip = np.r_[np.ones(k), 0.0]
    mb = -np.r_[modes.participation, rotor_mass]
    return RotorStructure(
        name="modal",
        coordinates=tuple(f"eta{j + 1}" for j in range(k)) + ("rotor_x",),
        mass=M,
        stiffness=Ks,
        damping=C,
        shaft=d,
        tip=tip,
        rotor_x=k,
        shaft_stiffness=shaft_stiffness,
        shaft_damping=shaft_damping,
        eccentricity=eccentricity,
        rotor_mass=rotor_mass,
        rotor_inertia=rotor_inertia,
        base_displacement=np.zeros(nx),
        base_velocity=np.zeros(nx),
        base_acceleration=mb,
        frame="relative_to_ground",
        pillar_modes=modes,
        notes={
            "equations": "pillar modes + rotor, relative to the ground; base forcing -M r a_g",
            "damping_law": damping_law + "; b2 on the rotor centre's velocity relative to the ground",
            "modes": k,
        },
    )


def model_digest(model: object) -> str | None:
    """A digest of a model in every field (its type and its pickle: arrays by their bytes,
    numbers, modes, notes): equal models give equal digests, any other another.  None where
    the model does not pickle (a caller then computes again rather than reuse)."""
    try:
        blob = pickle.dumps((type(model).__module__, type(model).__qualname__, model), protocol=5)
    except (pickle.PicklingError, TypeError, AttributeError):
        return None
    return hashlib.sha256(blob).hexdigest()[:24]
