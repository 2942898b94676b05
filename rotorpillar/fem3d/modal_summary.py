"""What the 3D modal analysis found, as `rotorpillar modal` writes it (modal.json).

:class:`ModalSummary` is the typed record of modal.json: the mode tables
(bare, with the top mass), the top's model, the tip reduction done on the
3D first bending mode beside the closed forms, the shell modes below the
second bending mode, the mesh and the timings (the command adds the files
it wrote and, with ``--tolerance``, the model selection).  Its nested sections stay
JSON dicts (their keys are documented in docs/fem3d.md).  No dolfinx here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import math
from dataclasses import dataclass, field

from ..provenance import JsonRecord
from .modal import AXES
from .reduction import tip_reduction


@dataclass(frozen=True)
class ModalMesh(JsonRecord):
    """The 3D mesh the modes were computed on (modal.json's ``mesh``)."""

    cells: int
    """number of cells of the tube's mesh (-)"""
    dofs: int
    """degrees of freedom of the bare tube (-)"""
    dofs_with_top: int
    """degrees of freedom with the top's model (-)"""
    cell_type: str
    """the scene's ``mesh.cell_type`` (hexahedron, tetrahedron, ...)"""
    degree: int
    """polynomial degree of the displacement (-)"""
    elements_around: int
    """elements around the circumference (-)"""
    elements_along: int
    """elements along the height (-)"""
    elements_through: int
    """elements through the wall (-)"""
    grading: float
    """the ratio of the axial element sizes, base over top (-)"""


@dataclass(frozen=True)
class ModalComparison(JsonRecord):
    """The 3D first bending mode against the closed forms, as relative differences (-)."""

    omega_bending_over_euler_bernoulli: float
    """3D bare first bending frequency over Eq. 1's omega_col1, minus 1 (-)"""
    omega_bending_over_timoshenko: float
    """3D bare first bending frequency over the Timoshenko beam's, minus 1 (-)"""
    m_reduced_over_closed_form: float
    """Eq. 2's reduced mass on the 3D mode over the closed form m_col/4, minus 1 (-)"""


@dataclass(frozen=True)
class ModalSummary(JsonRecord):
    """The content of modal.json (SI units: rad/s, Hz, kg, N/m)."""

    axes: dict
    modes: tuple[dict, ...]
    """the bare tube's modes, lowest first (index, kind, n_circumferential, n_axial, omega, ...)"""
    modes_with_top: tuple[dict, ...]
    top: dict
    reduction: dict
    comparison: ModalComparison
    shell_modes_below_second_bending: dict
    mesh: ModalMesh
    configurations: dict
    pillar_model: dict | None = field(default=None, metadata={"omit_if_none": True})
    """the chain's 3D mesh the modes were computed on, where it came from and its error
    (rotorpillar.chain.PillarModel as JSON; `modal` adds it)"""


def _config_dict(result) -> dict:
    return {"dofs": result.dofs, "cells": result.cells, "solver": result.solver, "timings": result.timings}


def shell_modes_below_second_bending(result) -> tuple[float | None, list[dict]]:
    """The second bending frequency and the non-bending modes below it."""
    i2 = result.index("bending_x", n_axial=1)
    w2 = None if i2 is None else float(result.omega[i2])
    rows = [
        m
        for m in result.modes_table()
        if m["kind"] not in ("bending_x", "bending_y") and (w2 is None or m["omega"] < w2)
    ]
    return w2, rows


def modal_summary(scene: Scene, bare, loaded, closed: dict) -> ModalSummary:
    """What `rotorpillar modal` found (modal.json, less the files and what the CLI adds).

    ``bare`` and ``loaded`` are the :class:`~.modal.ModalResult` of the bare
    tube and of the tube with its top mass; ``closed`` the pillar's closed
    forms (:func:`rotorpillar.reduced.reduction.pillar_closed_forms`).
    """
    red = tip_reduction(bare, scene.pillar)
    w2_bare, shell_bare = shell_modes_below_second_bending(bare)
    w2_top, shell_top = shell_modes_below_second_bending(loaded)
    i1 = loaded.index("bending_x", n_axial=0)
    m_top = loaded.top_mass
    # The paper's model of the loaded tube: m_r + m* on c1.
    w_reduced_top = math.sqrt(red.tip_stiffness / (red.m_reduced + m_top))
    ms = scene.mesh
    return ModalSummary(
        axes=AXES,
        modes=tuple(bare.modes_table()),
        modes_with_top=tuple(loaded.modes_table()),
        top={
            "model": loaded.top_model,
            "mass": m_top,
            "carries": scene.modal.top_mass,
            "mass_centre": [0.0, 0.0, scene.pillar.height],
            "omega_bending": None if i1 is None else float(loaded.omega[i1]),
            "omega_bending_reduced_model": w_reduced_top,
            "note": "rigid: a rigid plate on the whole top face carries the mass at the "
            "top centre (6 dofs appended after the tube's); ring_mass: the mass "
            "spread on the top face, no stiffening",
        },
        reduction={
            "m_reduced": red.m_reduced,
            "tip_stiffness": red.tip_stiffness,
            "omega_bending": red.omega_bending,
            "m_reduced_beam_line": red.m_reduced_beam_line,
            "method": "kinetic energy of the 3D first bending mode at unit mean tip "
            "displacement (Eq. 2), c1 = m_r omega^2; m_reduced_beam_line: Eq. 2 on "
            "the deflection line (mean u_x per height level)",
            "closed_form": {
                "m_reduced": closed["tip_mass_limit"],
                "tip_stiffness": closed["tip_stiffness_limit"],
                "omega_col1": closed["omega_col1"],
                "omega_col1_timoshenko": closed["omega_col1_timoshenko"],
            },
            "stated": {"m_reduced": scene.reduction.tip_mass, "tip_stiffness": scene.reduction.tip_stiffness},
        },
        comparison=ModalComparison(
            omega_bending_over_euler_bernoulli=red.omega_bending / closed["omega_col1"] - 1,
            omega_bending_over_timoshenko=red.omega_bending / closed["omega_col1_timoshenko"] - 1,
            m_reduced_over_closed_form=red.m_reduced / closed["tip_mass_limit"] - 1,
        ),
        shell_modes_below_second_bending={
            "bare": {"omega_second_bending": w2_bare, "modes": shell_bare},
            "with_top": {"omega_second_bending": w2_top, "modes": shell_top},
        },
        mesh=ModalMesh(
            cells=bare.cells,
            dofs=bare.dofs,
            dofs_with_top=loaded.dofs,
            cell_type=ms.cell_type,
            degree=ms.degree,
            elements_around=ms.elements_around,
            elements_along=ms.elements_along,
            elements_through=ms.elements_through,
            grading=ms.grading,
        ),
        configurations={"bare": _config_dict(bare), "with_top": _config_dict(loaded)},
    )


def _table(title: str, result) -> list[str]:
    lines = [
        title,
        f"  {'#':>3} {'kind':<10} {'n':>3} {'m':>3} {'omega [rad/s]':>14} {'f [Hz]':>9} "
        f"{'modal mass [kg]':>16} {'norm':>9}",
    ]
    for row in result.modes_table():
        n = "-" if row["n_circumferential"] is None else row["n_circumferential"]
        m = "-" if row["n_axial"] is None else row["n_axial"]
        lines.append(
            f"  {row['index']:>3} {row['kind']:<10} {n:>3} {m:>3} {row['omega']:>14.4f} "
            f"{row['frequency_hz']:>9.4f} {row['modal_mass']:>16.6g} {row['normalisation']:>9}"
        )
    return lines


def summary(doc: dict, bare, loaded) -> str:
    """The readable text of `rotorpillar modal`: both mode tables, Eq. 1 and the tip reduction beside them."""
    red, cmp_, top = doc["reduction"], doc["comparison"], doc["top"]
    cf = red["closed_form"]
    mesh = doc["mesh"]
    lines = [
        f"3D pillar: {mesh['cells']} {mesh['cell_type']} cells, degree {mesh['degree']}, "
        f"{mesh['dofs']} dofs ({mesh['elements_around']} around x {mesh['elements_along']} "
        f"along x {mesh['elements_through']} through, grading {mesh['grading']:g})"
    ]
    lines.append(
        "(n: waves around the circumference; m: sign changes along the height; x is the rotor's plane, z the tube axis)"
    )
    lines += _table("Bare tube (clamped base, free top)", bare)
    lines += _table(f"With {top['carries'].replace('_', ' ')} on top ({top['mass']:g} kg, {top['model']} top)", loaded)
    lines.append(
        f"First bending, bare: {red['omega_bending']:.4f} rad/s; Eq. 1 "
        f"{cf['omega_col1']:.4f} ({100 * cmp_['omega_bending_over_euler_bernoulli']:+.2f} %), "
        f"Timoshenko {cf['omega_col1_timoshenko']:.4f} "
        f"({100 * cmp_['omega_bending_over_timoshenko']:+.2f} %)"
    )
    if top["omega_bending"] is not None:
        lines.append(
            f"First bending with top: {top['omega_bending']:.4f} rad/s; the tip model "
            f"c1/(m_r + m_top) gives {top['omega_bending_reduced_model']:.4f}"
        )
    lines.append(
        f"Tip reduction (Eq. 2 on the 3D mode): m_r = {red['m_reduced']:.5g} kg "
        f"(beam line {red['m_reduced_beam_line']:.5g}; closed form m_col/4 = "
        f"{cf['m_reduced']:.5g}, {100 * cmp_['m_reduced_over_closed_form']:+.2f} %), "
        f"c1 = {red['tip_stiffness']:.5g} N/m"
    )
    for key, label in (("bare", "bare"), ("with_top", "with top")):
        s = doc["shell_modes_below_second_bending"][key]
        w2 = s["omega_second_bending"]
        found = ", ".join(
            f"{m['omega']:.2f} ({m['kind']}" + (f" n={m['n_circumferential']}" if m["kind"] == "ovalling" else "") + ")"
            for m in s["modes"]
        )
        if w2 is None:
            lines.append(
                f"Second bending ({label}) not among the {len(bare.omega)} modes computed; "
                f"non-bending modes found: {found or 'none'}"
            )
        else:
            lines.append(f"Below the second bending ({label}, {w2:.2f} rad/s): {found or 'no shell mode'}")
    t = doc["configurations"]
    lines.append(
        "Timings [s]: "
        + "; ".join(
            f"{k}: mesh {v['timings']['mesh']:.2f}, assembly {v['timings']['assembly']:.2f}, "
            f"solve {v['timings']['solve']:.2f}"
            for k, v in t.items()
        )
    )
    return "\n".join(lines)
