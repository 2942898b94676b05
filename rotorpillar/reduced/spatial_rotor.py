"""The spatial model as the transients' rotor-structure model.

``SpatialRotor`` wraps a SpatialStructure (rotorpillar.reduced.spatial_model)
in the interface the transients read of the planar ROM (rotorpillar.reduced.
rotor_models.RotorStructure): the X block is every coordinate but the rotor
centre's vertical (the integrators' rotor-Y slot), ``shaft`` and ``tip`` are
the shaft's deflection and the top in the rotor's plane on it, and

- ``quasi_normal``: the undamped modes of the structure at rest (the
  gyroscopic coupling left out, as the paper's Eq. 7 leaves the speed out)
  that the unbalance forces, each a Resonance: "X" where the shaft's
  deflection in the rotor's plane moves more than its vertical one, else
  "Y"; the forcing c2 e (d.u) of that direction; the others (bending along
  the spin axis, torsion: the unbalance does not reach them) are left out,
  as the averaging theory has nothing to say of them.  On the planar
  restriction these are the planar ROM's resonances;
- ``steady_state``, ``steady_torque``: the exact steady unbalance response at
  a constant speed (gyroscopic and couple unbalance included,
  rotorpillar.reduced.spatial_response.steady_state) and the shaft's (and
  the couple's) averaged torque on the rotor, as the planar model's;
- ``reaction_deflection``: the static deflection under the motor's reaction
  torque Md on the gondola, K_f Z = r Md: a run that starts at speed starts
  on it.

Which model a transient runs (``transient_planes``, ``transient_model``) is
rotorpillar.reduced.spatial_scene's: "auto" also weighs the drive's reaction
there, which bends the pillar in the rotor's plane and which only the
spatial model receives.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eig

from ..provenance import Record
from .drive import DriveSchedule
from .excitation import GroundMotion
from .ground3d import SpatialGroundMotion
from .rhs import Packed
from .rotor_models import StructureDescription
from .spatial_model import SpatialStructure
from .spatial_response import steady_state as spatial_steady_state
from .spatial_response import steady_states as spatial_steady_states
from .system import DampedMode, Resonance


class PlanesChoice(Record):
    """Which directions the modal model keeps, and why."""

    requested: str
    """modal_model.planes: "auto", "planar" or "spatial" """
    planes: str
    """what is used: "planar" (the rotor's plane, today's ROM) or "spatial" """
    reason: str
    """why, in words"""


#: a mode whose unbalance forcing is below this share of the largest one's is not forced (the
#: modes out of the rotor's plane on a 3D source: round-off couples them at ~1e-11) (-)
FORCED_SHARE = 1e-6


@dataclass(frozen=True, eq=False)
class SpatialRotor:
    """A SpatialStructure seen as a RotorStructure (see the module text)."""

    structure: SpatialStructure
    eccentricity: float
    """e (m): a field (batch runs replace it)"""
    planes: PlanesChoice | None = None
    """the choice that made this model run, with its reason"""
    notes: dict[str, Any] = field(default_factory=dict)

    name = "spatial"
    frame = "relative_to_ground"
    pillar_modes = None
    """no planar PillarModes: the spatial model's modes are ``structure.modes``"""

    @classmethod
    def of(cls, structure: SpatialStructure, planes: PlanesChoice | None = None) -> SpatialRotor:
        notes = {"equations": "the spatial ROM (rotorpillar.reduced.spatial_model)", "model": list(structure.notes)}
        return cls(structure, structure.eccentricity, planes, notes)

    def _s(self) -> SpatialStructure:
        s = self.structure
        return s if self.eccentricity == s.eccentricity else replace(s, eccentricity=self.eccentricity)

    # ------------------------------------------------------------ sizes and vectors
    @property
    def nx(self) -> int:
        return self.structure.nx

    @property
    def n(self) -> int:
        return self.structure.n

    @property
    def coordinates(self) -> tuple[str, ...]:
        """the X block's names"""
        return self.structure.coordinates[: self.nx]

    @property
    def names(self) -> list[str]:
        return self.structure.names

    @property
    def rotor_x(self) -> int:
        return self.structure.coordinates.index("rotor_x")

    @property
    def shaft(self) -> NDArray[np.float64]:
        """(nx,) the shaft's deflection in the rotor's plane on the X block (the vertical slot holds none)"""
        out: NDArray[np.float64] = self.structure.shaft[0, : self.nx]
        return out

    @property
    def tip(self) -> NDArray[np.float64]:
        return self.structure.tip

    @property
    def mass(self) -> NDArray[np.float64]:
        return self.structure.mass

    @property
    def stiffness(self) -> NDArray[np.float64]:
        return self.structure.stiffness

    @property
    def damping(self) -> NDArray[np.float64]:
        return self.structure.damping

    @property
    def shaft_stiffness(self) -> float:
        return self.structure.shaft_stiffness

    @property
    def shaft_damping(self) -> float:
        """b2 on the rotor centre's vertical (N*s/m)"""
        i = self.nx
        return float(self.structure.damping[i, i])

    @property
    def rotor_mass(self) -> float:
        return self.structure.rotor_mass

    @property
    def rotor_inertia(self) -> float:
        return self.structure.rotor_inertia

    # ------------------------------------------------------------ the integrators'
    def pack(
        self,
        drive: DriveSchedule,
        motion: GroundMotion | SpatialGroundMotion,
        prescribed_speed: bool = False,
        **overrides: float,
    ) -> Packed:
        return self.structure.pack(drive, motion, prescribed_speed, **{"eccentricity": self.eccentricity, **overrides})

    def energy(self, q: NDArray[np.float64], v: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        return self._s().energy(q, v)

    def undamped_modes_x(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        return self.structure.undamped_modes_x()

    def stiffest_frequency(self) -> float:
        return self.structure.stiffest_frequency()

    def fastest_rate(self) -> float:
        return self.structure.fastest_rate()

    # ------------------------------------------------------------ linear analysis
    def quasi_normal(self) -> list[Resonance]:
        """Resonance records of the forced modes (see the module text): X ascending, then Y."""
        s = self.structure
        c2, e = s.shaft_stiffness, self.eccentricity
        om, U = forced_basis(s)
        dx, dv = s.shaft
        rows = []
        forced = np.maximum(np.abs(dx @ U), np.abs(dv @ U))  # on the mass-normalised shapes
        top = float(np.max(forced)) if len(om) else 0.0
        for w, u, f in zip(om, U.T, forced):
            if f <= FORCED_SHARE * top:
                continue
            fx, fv = float(dx @ u), float(dv @ u)
            if abs(fx) >= abs(fv):
                scale = float(s.outputs["tip_x"] @ u)
                if abs(scale) <= 1e-9 * float(np.max(np.abs(u))):
                    scale = float(u[self.rotor_x])
                direction = "X"
            else:
                scale, direction = float(u[self.nx]), "Y"
            u = u / scale
            rows.append((direction, float(w), u, float(dx @ u) if direction == "X" else float(dv @ u)))
        rows.sort(key=lambda r: (r[0] != "X", r[1]))
        out = []
        for i, (direction, w, u, d) in enumerate(rows):
            I = float(u @ s.mass @ u)
            g = c2 * e * d
            shape = (float(s.outputs["tip_x"] @ u), float(u[self.rotor_x] if direction == "X" else u[self.nx]))
            out.append(Resonance(i + 1, direction, w, shape, I, g / I, g, float(u @ s.damping @ u) / I))
        return out

    def damped_frequencies(self) -> list[DampedMode]:
        """Damped natural frequencies at rest of the modes ``quasi_normal`` keeps, "X" or "Y" as it
        tells them: each forced undamped mode's nearest eigenvalue of the damped structure."""
        s = self.structure
        nz = s.nz
        Minv = np.linalg.inv(s.mass)
        A = np.block([[np.zeros((nz, nz)), np.eye(nz)], [-Minv @ s.stiffness_full(), -Minv @ s.damping]])
        lam = eig(A, right=False)
        lam = lam[lam.imag > 0]
        out = []
        for r in self.quasi_normal():
            if not len(lam):
                break
            j = int(np.argmin(np.abs(np.abs(lam) - r.omega)))
            l = lam[j]
            lam = np.delete(lam, j)
            out.append(DampedMode(r.direction, float(abs(l)), float(l.imag), float(-l.real / abs(l))))
        return out

    def steady_state(self, Omega: float) -> tuple[NDArray[np.complex128], complex]:
        """Complex amplitudes (X block, rotor vertical) at constant Omega, theta = Omega t."""
        Z = spatial_steady_state(self._s(), Omega)
        return Z[: self.nx], complex(Z[self.nx])

    def steady_torque(self, Omega: ArrayLike) -> NDArray[np.float64]:
        """The averaged torque of the shaft and of the couple unbalance on the rotor at constant
        Omega (N*m), negative where the structure resists: with Z = Re(Z^ e^{i theta}),
        <c2 e (d_v.Z cos - d_x.Z sin)> = c2 e (Re d_v.Z^ + Im d_x.Z^) / 2 and
        <-U_c W b(theta).Z'> = U_c W**2 (Im b_c.Z^ + Re b_s.Z^) / 2 (rotorpillar.reduced.rhs)."""
        s = self._s()
        W = np.atleast_1d(np.asarray(Omega, dtype=float)).ravel()
        dx, dv = s.shaft
        bc, bs = s.couple
        # the speeds in stacked solves (spatial_response.steady_states; 256 at a time bound the
        # memory of a many-DOF model); speed by speed, the stationary speeds' grid of 3000 took
        # ~10 s an earthquake run
        Z = np.concatenate([spatial_steady_states(s, w) for w in np.array_split(W, 1 + len(W) // 256)])
        out = s.shaft_stiffness * s.eccentricity * ((Z @ dv).real + (Z @ dx).imag) / 2
        out += s.couple_unbalance * W**2 * ((Z @ bc).imag + (Z @ bs).real) / 2
        torque: NDArray[np.float64] = out.reshape(np.shape(Omega))
        return torque

    def steady_initial_state(self, Omega: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(q0, v0) on the steady unbalance response at speed Omega with theta = 0."""
        Z = spatial_steady_state(self._s(), Omega)
        q0, v0 = np.zeros(self.n), np.zeros(self.n)
        q0[:-1], v0[:-1] = Z.real, -Omega * Z.imag
        v0[-1] = Omega
        return q0, v0

    def held_whirl_state(self, Omega: float, theta0: float = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(q0, v0): the structure at rest, the rotor in its steady whirl on it as if it were held
        (RotorStructure.held_whirl_state), in the rotor's plane and vertical."""
        c2, m, b = self.shaft_stiffness, self.rotor_mass, self.shaft_damping
        X = c2 * self.eccentricity / complex(c2 - m * Omega**2, Omega * b)
        z = X * complex(math.cos(theta0), math.sin(theta0))
        q0, v0 = np.zeros(self.n), np.zeros(self.n)
        q0[self.rotor_x], q0[self.nx], q0[-1] = z.real, z.imag, theta0
        v0[self.rotor_x], v0[self.nx], v0[-1] = -Omega * z.imag, Omega * z.real, Omega
        return q0, v0

    def reaction_deflection(self, torque: float) -> NDArray[np.float64]:
        """(n,) the static deflection under the motor's torque ``torque`` (N*m) reacting on the
        gondola: K_f Z = r Md, theta's entry zero."""
        s = self.structure
        out = np.zeros(self.n)
        if torque and np.any(s.reaction):
            out[:-1] = np.linalg.solve(s.stiffness_full(), s.reaction * torque)
        return out

    def describe(self) -> StructureDescription:
        """The model's matrices on every structural coordinate (``nx`` + the rotor's vertical)."""
        s = self.structure
        nz = s.nz
        return StructureDescription(
            name=s.name,
            coordinates=tuple(self.names),
            frame=self.frame,
            nx=self.nx,
            mass=s.mass,
            stiffness=s.stiffness,
            stiffness_with_shaft=s.stiffness_full(),
            damping=s.damping,
            shaft=s.shaft[0],
            tip=s.outputs["tip_x"],
            base_displacement=np.zeros(nz),
            base_velocity=np.zeros(nz),
            base_acceleration=s.ground[0],
            rotor_mass=s.rotor_mass,
            rotor_inertia=s.rotor_inertia,
            eccentricity=self.eccentricity,
            shaft_stiffness=s.shaft_stiffness,
            shaft_damping=self.shaft_damping,
            pillar_modes=None,
            notes={
                **self.notes,
                "planes": s.planes,
                "damping_law": s.damping_law,
                "modes": [f"{k} {w:.6g} rad/s" for k, w in zip(s.modes.kind, s.modes.omega)],
                "matrices": "on every structural coordinate (the rotor's vertical last), not only the X block",
            },
        )


def forced_basis(s: SpatialStructure, cluster: float = 1e-4) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The undamped modes at rest (omega ascending, mass-normalised shapes), each cluster of nearly
    equal frequencies (within ``cluster``, relative: the two planes' bending pairs, degenerate to
    ~1e-6) turned within itself so that the unbalance's two forcing vectors d_x, d_v load as few
    of its modes as they can (an SVD of the cluster's forcings): the pair's mode along the spin
    axis then carries none, whatever mix the eigensolver returned."""
    om, U = s.undamped_modes_x()
    U = U.copy()
    F = np.vstack(list(s.shaft)).T  # (nz, 2)
    i = 0
    while i < len(om):
        j = i + 1
        while j < len(om) and om[j] - om[i] <= cluster * max(om[i], 1e-300):
            j += 1
        if j - i > 1:
            A, _, _ = np.linalg.svd(U[:, i:j].T @ F)
            U[:, i:j] = U[:, i:j] @ A
        i = j
    return om, U
