"""The spatial pillar's modes from 1D beams: bending in both planes, torsion, axial.

The round tube clamped at its base, the gondola a rigid body on its top
(its mass, its three moments of inertia about its own centre, its centre
``gondola.height`` above the top), in four lines that do not couple (the
tube is axisymmetric and the gondola's principal axes are the tube's):

- bending in the rotor's plane: deflection u_x and rotation theta_y = psi
  (``theory``: Timoshenko or Euler-Bernoulli), the gondola's roll inertia;
- bending along the spin axis: u_y and theta_x = -psi (psi = du_y/dz), the
  gondola's pitch inertia;
- torsion: theta_z, Saint-Venant's torsion bar, the gondola's yaw inertia;
- axial: u_z, a bar, the gondola's mass.

The gondola's centre moves as u + theta x (0, 0, h): in each bending plane
its translation is w + h psi, so its mass enters the top node as
m [[1, h], [h, h**2]] plus its own inertia on psi.  Each line is solved on
its own (``decoupled blocks``: the two bending planes are degenerate, and
solving them apart keeps their modes apart).  Bending modes are scaled to a
unit tip deflection, torsion to a unit top rotation, axial to a unit top
displacement.  The section constants come per element from
rotorpillar.reduced.beam_sections.tube_sections.

>>> from rotorpillar.scene import load_scene
>>> s = load_scene("paper")
>>> m = beam_spatial_modes(s.pillar, s.gondola, 2, "euler", 40)
>>> [(round(float(w), 3), k) for w, k in zip(m.omega[:3], m.kind[:3])]  # pitch inertia 850 > roll 830
[(25.916, 'bending along the spin axis'), (25.916, "bending in the rotor's plane"), (169.953, 'bending along the spin axis')]
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from ..scene import Gondola, Pillar
from .beam_line import BENDING_THEORIES, line_matrices, line_resultants
from .beam_sections import BeamSections, tube_sections
from .spatial_modes import AXIAL, BENDING_ACROSS, BENDING_IN_PLANE, TORSION, SpatialPillarModes

Matrix = NDArray[np.float64]


def _lowest(K: Matrix, M: Matrix, k: int) -> tuple[NDArray[np.float64], Matrix]:
    """The k lowest modes of K v = omega**2 M v, as beam_fe solves them (M v = mu K v for
    the largest mu keeps the lowest modes accurate on fine meshes)."""
    n = K.shape[0]
    k = min(k, n)
    mu, vec = eigh(M, K, subset_by_index=[n - k, n - 1])
    return 1.0 / np.sqrt(mu[::-1]), vec[:, ::-1]


def _scale_to_top(vec: Matrix, top_row: int, M: Matrix) -> Matrix:
    """Each mode scaled to a unit value of its top dof (positive); a mode whose top
    hardly moves is scaled to a unit modal mass instead."""
    t = vec[top_row]
    mass = np.sqrt(np.einsum("ij,ik,kj->j", vec, M, vec))
    small = np.abs(t) * mass < 1e-9 * np.max(np.abs(vec), axis=0) * mass
    scale = np.where(small, mass, t)
    out: Matrix = vec / scale
    return out


def _gondola_on_bending(M: Matrix, gondola: Gondola, inertia: float) -> None:
    """The gondola on the top node (w, psi) of a bending line: mass m at height h, inertia."""
    m, h = gondola.mass, gondola.height
    M[-2:, -2:] += m * np.array([[1.0, h], [h, h * h]])
    M[-1, -1] += inertia


def beam_spatial_modes(
    pillar: Pillar,
    gondola: Gondola,
    n_modes: int,
    theory: str = "timoshenko",
    elements: int = 40,
    extra_roll_inertia: float = 0.0,
    damping_ratio: float = 0.0,
    sections: BeamSections | None = None,
) -> SpatialPillarModes:
    """The first ``n_modes`` modes of each of the four lines (see the module text), ascending.

    ``extra_roll_inertia`` (kg*m**2) adds to the gondola's roll inertia about the tip
    (the scene's modal_model.gondola_inertia, the planar model's key);
    ``damping_ratio`` is every mode's structural damping ratio (-); ``sections``
    replaces the scene's uniform tube (``elements`` is then its count).
    """
    if theory not in BENDING_THEORIES:
        raise ValueError(f"theory must be one of {BENDING_THEORIES}")
    s = tube_sections(pillar, elements) if sections is None else sections
    nodes = s.count + 1
    z = s.heights
    blocks = []  # (omega, kind, shapes (n, k), K, M, line)
    for kind, line in ((BENDING_IN_PLANE, theory), (BENDING_ACROSS, theory), (TORSION, "torsion"), (AXIAL, "axial")):
        K, M = line_matrices(s, line)
        if kind == BENDING_IN_PLANE:
            _gondola_on_bending(M, gondola, gondola.roll_inertia + extra_roll_inertia)
        elif kind == BENDING_ACROSS:
            _gondola_on_bending(M, gondola, gondola.pitch_inertia)
        elif kind == TORSION:
            M[-1, -1] += gondola.yaw_inertia
        else:
            M[-1, -1] += gondola.mass
        omega, vec = _lowest(K, M, n_modes)
        vec = _scale_to_top(vec, K.shape[0] - (2 if line in BENDING_THEORIES else 1), M)
        blocks.append((omega, kind, vec, K, M, line))

    omega_all, kinds, mass_all, top_all, part_all = [], [], [], [], []
    res: dict[str, list[NDArray[np.float64]]] = {
        name: [] for name in ("shear_x", "shear_y", "axial_force", "moment_x", "moment_y", "torque")
    }
    shapes = []
    total = np.zeros(3)
    flex = np.zeros((6, 6))
    for omega, kind, vec, K, M, line in blocks:
        k = len(omega)
        p = 2 if line in BENDING_THEORIES else 1
        full = np.zeros((p * nodes, k))
        full[p:] = vec
        r = np.zeros(K.shape[0])
        r[0::p] = 1.0  # a rigid translation along the line's direction (w, or u_z)
        mj = np.einsum("ij,ik,kj->j", vec, M, vec)
        L = vec.T @ M @ r
        top = np.zeros((k, 6))
        shape = np.zeros((nodes, k, 6))
        part = np.zeros((k, 3))
        forces = line_resultants(s, line, full)  # (nodes, p, k)
        zero = np.zeros((nodes, k))
        cols = dict.fromkeys(res, zero)
        F = np.linalg.solve(K, np.eye(K.shape[0])[:, -p:])[-p:]  # the top node's static flexibility
        if kind == BENDING_IN_PLANE:
            flex[np.ix_([0, 4], [0, 4])] = F
            top[:, 0], top[:, 4] = vec[-2], vec[-1]
            shape[:, :, 0], shape[:, :, 4] = full[0::2], full[1::2]
            part[:, 0] = L
            total[0] = r @ M @ r
            cols["shear_x"], cols["moment_y"] = forces[:, 0], forces[:, 1]
        elif kind == BENDING_ACROSS:
            flex[np.ix_([1, 3], [1, 3])] = F * np.array([[1.0, -1.0], [-1.0, 1.0]])  # theta_x = -psi
            top[:, 1], top[:, 3] = vec[-2], -vec[-1]
            shape[:, :, 1], shape[:, :, 3] = full[0::2], -full[1::2]
            part[:, 1] = L
            total[1] = r @ M @ r
            # a tip load along +y gives the moment about x -P (H - z): the line's M with its sign turned
            cols["shear_y"], cols["moment_x"] = forces[:, 0], -forces[:, 1]
        elif kind == TORSION:
            flex[5, 5] = F[0, 0]
            top[:, 5] = vec[-1]
            shape[:, :, 5] = full
            cols["torque"] = forces[:, 0]
        else:
            flex[2, 2] = F[0, 0]
            top[:, 2] = vec[-1]
            shape[:, :, 2] = full
            part[:, 2] = L
            total[2] = r @ M @ r
            cols["axial_force"] = forces[:, 0]
        omega_all.append(omega)
        kinds += [kind] * k
        mass_all.append(mj)
        top_all.append(top)
        part_all.append(part)
        shapes.append(shape)
        for name in res:
            res[name].append(cols[name])
    omega = np.concatenate(omega_all)
    order = np.argsort(omega, kind="stable")  # the rotor's plane first where the planes are degenerate

    def cat(parts: list[NDArray[np.float64]], axis: int = 0) -> NDArray[np.float64]:
        out: NDArray[np.float64] = np.take(np.concatenate(parts, axis=axis), order, axis=axis)
        return out

    return SpatialPillarModes(
        omega=omega[order],
        kind=tuple(kinds[i] for i in order),
        modal_mass=cat(mass_all),
        top=cat(top_all),
        participation=cat(part_all),
        total_mass=total,
        damping_ratio=np.full(len(omega), float(damping_ratio)),
        source=f"beam:{theory}:{s.count}",
        section_heights=z,
        shear_x=cat(res["shear_x"], 1),
        shear_y=cat(res["shear_y"], 1),
        axial_force=cat(res["axial_force"], 1),
        moment_x=cat(res["moment_x"], 1),
        moment_y=cat(res["moment_y"], 1),
        torque=cat(res["torque"], 1),
        heights=z,
        shapes=cat(shapes, 1),
        top_compliance=flex,
        notes=(
            "1D beams: bending in both planes, Saint-Venant torsion, axial; the gondola a rigid body on top",
            f"gondola: {gondola.mass:g} kg, inertias roll {gondola.roll_inertia + extra_roll_inertia:g}, pitch "
            f"{gondola.pitch_inertia:g}, yaw {gondola.yaw_inertia:g} kg*m**2, centre {gondola.height:g} m above the top",
        ),
    )
