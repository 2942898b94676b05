"""The pillar's modes in every direction: the interface between a modal solver and the spatial model.

``SpatialPillarModes`` holds the modes of the pillar clamped at its base
with the gondola on its top (the rotor is not on them: the spatial model
hangs it on its shaft), in every direction: bending in the rotor's plane
and along the spin axis, torsion, axial, and whatever else the source
finds (the 3D model's ovalling and breathing).  Each mode j carries the
top plate's rigid-body motion per unit modal coordinate, in the order of
the 3D model's rigid top plate (rotorpillar.fem3d.model):

    top[j] = (u_x, u_y, u_z, theta_x, theta_y, theta_z)
           = (in the rotor's plane (the paper's X), along the spin axis,
              vertical (the paper's Y), pitch, roll, yaw)

at the centre of the top section (0, 0, H), in m and rad per unit modal
coordinate.  With phi_j the mode (any scaling), M the pillar's mass matrix
with the gondola, and r_d the rigid translation of everything along
direction d (x, y, z):

- modal mass        m_j = phi_j^T M phi_j               (kg, for that scaling)
- participation     L_jd = phi_j^T M r_d                (kg): a base
                    acceleration a_d forces mode j with -L_jd a_d
- total mass        r_d^T M r_d, the same in x, y and z (kg).

Sources: the 1D beam (rotorpillar.reduced.spatial_beam: bending in both
planes with the gondola's inertias, a Saint-Venant torsion bar, an axial
bar) and the 3D model (rotorpillar.fem3d: the rigid top's six dofs of each
SLEPc mode).  ``planar()`` gives the bending modes in the rotor's plane as
today's PillarModes (tip-scaled), which the planar modal model takes.

Nothing here imports dolfinx: the record is numpy arrays and words.

>>> m = spatial_modes_example()
>>> m.count, m.kind[1:]
(3, ('bending along the spin axis', 'torsion'))
>>> p = m.planar()
>>> p.count, float(p.modal_mass[0])
(1, 4000.0)
"""

from __future__ import annotations

from typing import Annotated

import numpy as np
from numpy.typing import NDArray

from ..provenance import ArrayMarker, Record
from .pillar_modes import PillarModes

#: A float ndarray field of a record (``records.Array``, typed for mypy's strict mode).
Array = Annotated[NDArray[np.float64], ArrayMarker]

#: The top plate's six components, in the order of ``SpatialPillarModes.top``: word, symbol.
TOP_COMPONENTS = (
    ("in the rotor's plane", "u_x"),
    ("along the spin axis", "u_y"),
    ("vertical", "u_z"),
    ("pitch", "theta_x"),
    ("roll", "theta_y"),
    ("yaw", "theta_z"),
)
#: Translations of the ground motion, in the order of ``participation``'s columns.
GROUND_DIRECTIONS = ("in the rotor's plane", "along the spin axis", "vertical")

#: The kinds of a mode, in words (the 3D side names ovalling with its wave number:
#: "ovalling n=2").
BENDING_IN_PLANE = "bending in the rotor's plane"
BENDING_ACROSS = "bending along the spin axis"
TORSION = "torsion"
AXIAL = "axial"
OVALLING = "ovalling"
BREATHING = "breathing"
OTHER = "other"
KINDS = (BENDING_IN_PLANE, BENDING_ACROSS, TORSION, AXIAL, OVALLING, BREATHING, OTHER)


class SpatialPillarModes(Record, eq=False):
    """The pillar's modes with the gondola on top, in every direction (see the module text)."""

    omega: Array
    """(k,) natural angular frequencies, ascending (rad/s)"""
    kind: tuple[str, ...]
    """(k,) each mode's kind in words (``KINDS``; the 3D side writes "ovalling n=2")"""
    modal_mass: Array
    """(k,) m_j = phi_j^T M phi_j for the mode's scaling (kg)"""
    top: Array
    """(k, 6) the top plate's (u_x, u_y, u_z, theta_x, theta_y, theta_z) per unit modal
    coordinate (m and rad per unit)"""
    participation: Array
    """(k, 3) L_jd = phi_j^T M r_d for a base acceleration in the rotor's plane (x), along
    the spin axis (y) and vertical (z) (kg)"""
    total_mass: Array
    """(3,) r_d^T M r_d in x, y, z: everything the base carries, pillar and gondola (kg)"""
    damping_ratio: Array
    """(k,) structural damping ratio of each mode (-); the tip dashpot b1 comes on top, in
    the spatial model"""
    source: str
    """where the modes come from, e.g. "beam:timoshenko:40" or "fem3d:hexahedron:P2:..." """
    section_heights: Array | None = None
    """(n_z,) heights of the sections whose resultants each mode carries, base (0) first (m)"""
    shear_x: Array | None = None
    """(n_z, k) shear force in x the part above a section exerts on the part below, per unit
    modal coordinate (N per unit)"""
    shear_y: Array | None = None
    """(n_z, k) shear force in y, likewise (N per unit)"""
    axial_force: Array | None = None
    """(n_z, k) force in z, likewise (N per unit)"""
    moment_x: Array | None = None
    """(n_z, k) moment about x (bending along the spin axis), about the section's centre,
    likewise (N*m per unit)"""
    moment_y: Array | None = None
    """(n_z, k) moment about y (bending in the rotor's plane: positive for a tip pushed
    along +x, as PillarModes.moment_shapes) (N*m per unit)"""
    torque: Array | None = None
    """(n_z, k) moment about z (torsion), likewise (N*m per unit)"""
    heights: Array | None = None
    """(n_nodes,) heights of the shapes' stations (m)"""
    shapes: Array | None = None
    """(n_nodes, k, 6) the section's rigid-body motion along the height, the top's order (m, rad
    per unit)"""
    top_compliance: Array | None = None
    """(6, 6) the pillar's static flexibility at the top: the top plate's (u, theta) per unit
    force and moment on it, in the top's order (m/N, m/(N*m), rad/N, rad/(N*m)); exact where the
    modes are not (a load at the top excites modes above any band)"""
    notes: tuple[str, ...] = ()
    """how the modes were made, in words"""

    def __post_init__(self) -> None:
        k = len(self.omega)
        if k == 0 or not np.all(np.isfinite(self.omega)) or np.any(self.omega <= 0):
            raise ValueError("omega must be finite and > 0, at least one mode")
        if np.any(np.diff(self.omega) < 0):
            raise ValueError("modes must be sorted by frequency")
        shapes = {
            "kind": (len(self.kind),),
            "modal_mass": np.shape(self.modal_mass),
            "top": np.shape(self.top),
            "participation": np.shape(self.participation),
            "total_mass": np.shape(self.total_mass),
            "damping_ratio": np.shape(self.damping_ratio),
        }
        want = {
            "kind": (k,),
            "modal_mass": (k,),
            "top": (k, 6),
            "participation": (k, 3),
            "total_mass": (3,),
            "damping_ratio": (k,),
        }
        for name, shape in want.items():
            if shapes[name] != shape:
                raise ValueError(f"{name} must have shape {shape}, got {shapes[name]}")
        if np.any(self.modal_mass <= 0):
            raise ValueError("modal_mass must be > 0")
        if np.any(self.damping_ratio < 0):
            raise ValueError("damping_ratio must be >= 0")
        for name in ("shear_x", "shear_y", "axial_force", "moment_x", "moment_y", "torque"):
            a = getattr(self, name)
            if a is not None and (self.section_heights is None or np.shape(a) != (len(self.section_heights), k)):
                raise ValueError(f"{name} must be (len(section_heights), {k})")
        if self.top_compliance is not None and np.shape(self.top_compliance) != (6, 6):
            raise ValueError("top_compliance must be (6, 6)")
        if self.shapes is not None and (self.heights is None or np.shape(self.shapes) != (len(self.heights), k, 6)):
            raise ValueError(f"shapes must be (len(heights), {k}, 6)")

    # ------------------------------------------------------------ views
    @property
    def count(self) -> int:
        return len(self.omega)

    @property
    def modal_stiffness(self) -> NDArray[np.float64]:
        """k_j = omega_j**2 m_j (N per unit modal coordinate**2)"""
        out: NDArray[np.float64] = self.omega**2 * self.modal_mass
        return out

    @property
    def has_resultants(self) -> bool:
        """Whether every mode carries its six section resultants."""
        return all(
            getattr(self, n) is not None
            for n in ("shear_x", "shear_y", "axial_force", "moment_x", "moment_y", "torque")
        )

    def effective_mass_fraction(self, direction: int) -> float:
        """Share of the base-excited mass the modes carry along x (0), y (1) or z (2) (-)."""
        L = self.participation[:, direction]
        return float(np.sum(L**2 / self.modal_mass) / self.total_mass[direction])

    def of_kind(self, *kinds: str) -> NDArray[np.int64]:
        """Indices of the modes whose kind is one of ``kinds`` (a kind matches its
        refinements: "ovalling" matches "ovalling n=2")."""
        idx = [j for j, k in enumerate(self.kind) if any(k == w or k.startswith(w + " ") for w in kinds)]
        return np.asarray(idx, dtype=np.int64)

    def select(self, index: NDArray[np.int64] | list[int]) -> SpatialPillarModes:
        """The modes at ``index`` (kept in ascending order)."""
        idx = np.sort(np.asarray(index, dtype=np.int64))
        if len(idx) == 0:
            raise ValueError("select: no mode")

        def cut(a: NDArray[np.float64] | None, axis: int = 0) -> NDArray[np.float64] | None:
            return None if a is None else np.take(a, idx, axis=axis)

        return SpatialPillarModes(
            omega=self.omega[idx],
            kind=tuple(self.kind[i] for i in idx),
            modal_mass=self.modal_mass[idx],
            top=self.top[idx],
            participation=self.participation[idx],
            total_mass=self.total_mass,
            damping_ratio=self.damping_ratio[idx],
            source=self.source,
            section_heights=self.section_heights,
            shear_x=cut(self.shear_x, 1),
            shear_y=cut(self.shear_y, 1),
            axial_force=cut(self.axial_force, 1),
            moment_x=cut(self.moment_x, 1),
            moment_y=cut(self.moment_y, 1),
            torque=cut(self.torque, 1),
            heights=self.heights,
            shapes=cut(self.shapes, 1),
            top_compliance=self.top_compliance,
            notes=self.notes,
        )

    def below(self, band_top: float, minimum: int = 1) -> SpatialPillarModes:
        """The modes at or below ``band_top`` (rad/s), at least the first ``minimum``."""
        k = max(minimum, int(np.sum(self.omega <= band_top)))
        return self.select(list(range(min(k, self.count))))

    def with_damping_ratio(self, zeta: float) -> SpatialPillarModes:
        """The same modes, each with the structural damping ratio ``zeta`` (-)."""
        from ..provenance import replace

        out: SpatialPillarModes = replace(self, damping_ratio=np.full(self.count, float(zeta)))
        return out

    def planar(self) -> PillarModes:
        """The bending modes in the rotor's plane as PillarModes, each scaled to a unit
        tip deflection u_x = 1 (the planar modal model's input); no structural damping
        ratio (the planar model damps by the tip dashpot b1, as today)."""
        idx = self.of_kind(BENDING_IN_PLANE)
        if len(idx) == 0:
            raise ValueError(f"{self.source}: no bending mode in the rotor's plane")
        s = self.top[idx, 0]
        if np.any(np.abs(s) < 1e-12 * np.max(np.abs(self.top[idx, :3]), axis=1)):
            raise ValueError("a bending mode in the rotor's plane without tip deflection cannot be tip-scaled")

        def scaled(a: NDArray[np.float64] | None) -> NDArray[np.float64] | None:
            return None if a is None else a[:, idx] / s

        shapes = None if self.shapes is None else self.shapes[:, idx, 0] / s
        return PillarModes(
            self.omega[idx],
            self.modal_mass[idx] / s**2,
            self.participation[idx, 0] / s,
            float(self.total_mass[0]),
            self.source,
            None,
            self.heights,
            shapes,
            {"planar_subset_of": "SpatialPillarModes"},
            self.section_heights,
            scaled(self.moment_y),
            scaled(self.shear_x),
        )


def spatial_modes_example() -> SpatialPillarModes:
    """Three made-up modes (for doctests): bending in each plane, torsion.

    >>> spatial_modes_example().effective_mass_fraction(0)
    0.25
    """
    top = np.zeros((3, 6))
    top[0, 0], top[0, 4] = 1.0, 0.075
    top[1, 1], top[1, 3] = 1.0, -0.075
    top[2, 5] = 1.0
    return SpatialPillarModes(
        omega=np.array([25.0, 25.0, 230.0]),
        kind=(BENDING_IN_PLANE, BENDING_ACROSS, TORSION),
        modal_mass=np.array([4000.0, 4000.0, 8000.0]),
        top=top,
        participation=np.array([[2000.0, 0.0, 0.0], [0.0, 2000.0, 0.0], [0.0, 0.0, 0.0]]),
        total_mass=np.full(3, 4000.0),
        damping_ratio=np.zeros(3),
        source="example",
    )
