"""What the 3D modal analysis found, as `rotorpillar modal` writes it (modal.json).

:class:`ModalSummary` is the typed record of modal.json: the mode tables
(bare, with the top mass), the top's model, the tip reduction done on the
3D first bending mode beside the closed forms, the shell modes below the
second bending mode, the mesh and the timings (the command adds the files
it wrote and, with ``--tolerance``, the model selection).  Every section is a
record down to its numbers (the keys are documented in docs/fem3d.md).  No dolfinx here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import math

from ..chain.record import PillarModel
from ..records import Record
from ..reduced.reduction import PillarClosedForms
from .modal import AXES, ModeRow
from .reduction import tip_reduction


class ModalMesh(Record):
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


class ModalComparison(Record):
    """The 3D first bending mode against the closed forms, as relative differences (-)."""

    omega_bending_over_euler_bernoulli: float
    """3D bare first bending frequency over Eq. 1's omega_col1, minus 1 (-)"""
    omega_bending_over_timoshenko: float
    """3D bare first bending frequency over the Timoshenko beam's, minus 1 (-)"""
    m_reduced_over_closed_form: float
    """Eq. 2's reduced mass on the 3D mode over the closed form m_col/4, minus 1 (-)"""


class ModalAxes(Record):
    """The axes of the 3D model, in words (modal.json's ``axes``: fem3d.modal.AXES)."""

    tube_axis: str
    """the tube's axis and where its base and top are"""
    x: str
    """what the model's x is (the paper's X, the rotor's plane)"""
    y: str
    """what the model's y is (the paper's Z, the rotor's spin axis)"""
    z: str
    """what the model's z is (the paper's Y, vertical)"""
    origin: str
    """where the origin is"""


class ModalTop(Record):
    """What the tube carries on top in the loaded configuration (modal.json's ``top``)."""

    model: str | None
    """the top's model: "rigid" (a rigid plate, 6 dofs) or "ring_mass\""""
    mass: float
    """mass on top (kg)"""
    carries: str
    """the scene's ``modal.top_mass``: what the mass is (gondola, ...)"""
    mass_centre: tuple[float, ...]
    """where the mass sits, (x, y, z) (m)"""
    omega_bending: float | None
    """first bending_x frequency of the loaded tube (rad/s), None if not found"""
    omega_bending_reduced_model: float
    """the paper's tip model of the loaded tube, sqrt(c1 / (m_r + m_top)) (rad/s)"""
    note: str
    """the top's models, in words"""


class ClosedFormReduction(Record):
    """The pillar's closed forms beside the 3D tip reduction."""

    m_reduced: float
    """Eq. 2's reduced tip mass of the continuous first mode (kg)"""
    tip_stiffness: float
    """its tip stiffness (N/m)"""
    omega_col1: float
    """Eq. 1's first bending frequency, Euler-Bernoulli (rad/s)"""
    omega_col1_timoshenko: float
    """the Timoshenko beam's first bending frequency (rad/s)"""


class StatedReduction(Record):
    """The tip mass and stiffness the scene states (``[reduction]``), None where it states none."""

    m_reduced: float | None
    """the scene's ``reduction.tip_mass`` (kg)"""
    tip_stiffness: float | None
    """the scene's ``reduction.tip_stiffness`` (N/m)"""


class ModalReduction(Record):
    """Eq. 2 on the 3D first bending mode of the bare tube (modal.json's ``reduction``)."""

    m_reduced: float
    """reduced tip mass m_r (kg)"""
    tip_stiffness: float
    """tip stiffness c1 = m_r omega^2 (N/m)"""
    omega_bending: float
    """the bare tube's first bending frequency (rad/s)"""
    m_reduced_beam_line: float
    """Eq. 2 on the deflection line (mean u_x per height level) (kg)"""
    method: str
    """how, in words"""
    closed_form: ClosedFormReduction
    """the closed forms beside it"""
    stated: StatedReduction
    """what the scene states"""


class ShellModes(Record):
    """The non-bending modes below the second bending mode of one configuration."""

    omega_second_bending: float | None
    """the second bending_x frequency (rad/s), None if not among the modes computed"""
    modes: tuple[ModeRow, ...]
    """the non-bending modes below it (all of them without a second bending)"""


class ShellModesBelow(Record):
    """modal.json's ``shell_modes_below_second_bending``, per configuration."""

    bare: ShellModes
    with_top: ShellModes


class ModalSolver(Record):
    """How SLEPc (or the block solver) found one configuration's modes."""

    iterations: int
    """outer iterations (-)"""
    tolerance: float
    """the relative tolerance asked (-)"""
    shift: float
    """the shift of shift-invert (rad**2/s**2)"""
    max_error_estimate: float
    """the largest relative error estimate of the modes returned (-)"""
    computed: int
    """eigenpairs computed (-)"""
    type: str
    """the method, spectral transform and factorisation"""
    solves: int
    """linear solves with the shifted operator (-)"""
    ranks: int
    """MPI ranks (-)"""


class ModalConfiguration(Record):
    """The size, the solver and the timings of one configuration's modal run."""

    dofs: int
    """global unknowns (-)"""
    cells: int
    """cells of the tube's mesh (-)"""
    solver: ModalSolver
    timings: dict[str, float]
    """wall-clock seconds per stage: mesh, assembly, solve, postprocess (s)"""


class ModalConfigurations(Record):
    """modal.json's ``configurations``: the bare tube and the tube with its top."""

    bare: ModalConfiguration
    with_top: ModalConfiguration


class ModalSummary(Record, omit_defaults=True):
    """The content of modal.json (SI units: rad/s, Hz, kg, N/m)."""

    axes: ModalAxes
    """the axes of the 3D model, in words"""
    modes: tuple[ModeRow, ...]
    """the bare tube's modes, lowest first"""
    modes_with_top: tuple[ModeRow, ...]
    """the modes of the tube with its top mass, lowest first"""
    top: ModalTop
    """what the tube carries on top"""
    reduction: ModalReduction
    """Eq. 2 on the 3D first bending mode, beside the closed forms"""
    comparison: ModalComparison
    """the 3D first bending mode against the closed forms"""
    shell_modes_below_second_bending: ShellModesBelow
    """the non-bending modes below the second bending mode"""
    mesh: ModalMesh
    """the mesh the modes were computed on"""
    configurations: ModalConfigurations
    """per configuration: size, solver, timings"""
    pillar_model: PillarModel | None = None
    """the chain's 3D mesh the modes were computed on, where it came from and its error
    (`modal` adds it after ``files``)"""


def _configuration(result) -> ModalConfiguration:
    s = result.solver
    return ModalConfiguration(
        dofs=result.dofs,
        cells=result.cells,
        solver=ModalSolver(
            iterations=s["iterations"],
            tolerance=s["tolerance"],
            shift=s["shift"],
            max_error_estimate=s["max_error_estimate"],
            computed=s["computed"],
            type=s["type"],
            solves=s["solves"],
            ranks=s["ranks"],
        ),
        timings=dict(result.timings),
    )


def shell_modes_below_second_bending(result) -> ShellModes:
    """The second bending frequency and the non-bending modes below it."""
    i2 = result.index("bending_x", n_axial=1)
    w2 = None if i2 is None else float(result.omega[i2])
    rows = tuple(
        m for m in result.modes_table() if m.kind not in ("bending_x", "bending_y") and (w2 is None or m.omega < w2)
    )
    return ShellModes(omega_second_bending=w2, modes=rows)


def modal_summary(scene: Scene, bare, loaded, closed: PillarClosedForms) -> ModalSummary:
    """What `rotorpillar modal` found (modal.json, less the files and what the CLI adds).

    ``bare`` and ``loaded`` are the :class:`~.modal.ModalResult` of the bare
    tube and of the tube with its top mass; ``closed`` the pillar's closed
    forms (:func:`rotorpillar.reduced.reduction.pillar_closed_forms`).
    """
    red = tip_reduction(bare, scene.pillar)
    i1 = loaded.index("bending_x", n_axial=0)
    m_top = loaded.top_mass
    # The paper's model of the loaded tube: m_r + m* on c1.
    w_reduced_top = math.sqrt(red.tip_stiffness / (red.m_reduced + m_top))
    ms = scene.mesh
    return ModalSummary(
        axes=ModalAxes(**AXES),
        modes=tuple(bare.modes_table()),
        modes_with_top=tuple(loaded.modes_table()),
        top=ModalTop(
            model=loaded.top_model,
            mass=m_top,
            carries=scene.modal.top_mass,
            mass_centre=(0.0, 0.0, scene.pillar.height),
            omega_bending=None if i1 is None else float(loaded.omega[i1]),
            omega_bending_reduced_model=w_reduced_top,
            note="rigid: a rigid plate on the whole top face carries the mass at the "
            "top centre (6 dofs appended after the tube's); ring_mass: the mass "
            "spread on the top face, no stiffening",
        ),
        reduction=ModalReduction(
            m_reduced=red.m_reduced,
            tip_stiffness=red.tip_stiffness,
            omega_bending=red.omega_bending,
            m_reduced_beam_line=red.m_reduced_beam_line,
            method="kinetic energy of the 3D first bending mode at unit mean tip "
            "displacement (Eq. 2), c1 = m_r omega^2; m_reduced_beam_line: Eq. 2 on "
            "the deflection line (mean u_x per height level)",
            closed_form=ClosedFormReduction(
                m_reduced=closed.tip_mass_limit,
                tip_stiffness=closed.tip_stiffness_limit,
                omega_col1=closed.omega_col1,
                omega_col1_timoshenko=closed.omega_col1_timoshenko,
            ),
            stated=StatedReduction(m_reduced=scene.reduction.tip_mass, tip_stiffness=scene.reduction.tip_stiffness),
        ),
        comparison=ModalComparison(
            omega_bending_over_euler_bernoulli=red.omega_bending / closed.omega_col1 - 1,
            omega_bending_over_timoshenko=red.omega_bending / closed.omega_col1_timoshenko - 1,
            m_reduced_over_closed_form=red.m_reduced / closed.tip_mass_limit - 1,
        ),
        shell_modes_below_second_bending=ShellModesBelow(
            bare=shell_modes_below_second_bending(bare), with_top=shell_modes_below_second_bending(loaded)
        ),
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
        configurations=ModalConfigurations(bare=_configuration(bare), with_top=_configuration(loaded)),
    )


def _table(title: str, result) -> list[str]:
    lines = [
        title,
        f"  {'#':>3} {'kind':<10} {'n':>3} {'m':>3} {'omega [rad/s]':>14} {'f [Hz]':>9} "
        f"{'modal mass [kg]':>16} {'norm':>9}",
    ]
    for row in result.modes_table():
        n = "-" if row.n_circumferential is None else row.n_circumferential
        m = "-" if row.n_axial is None else row.n_axial
        lines.append(
            f"  {row.index:>3} {row.kind:<10} {n:>3} {m:>3} {row.omega:>14.4f} "
            f"{row.frequency_hz:>9.4f} {row.modal_mass:>16.6g} {row.normalisation:>9}"
        )
    return lines


def summary(doc: ModalSummary, bare, loaded) -> str:
    """The readable text of `rotorpillar modal`: both mode tables, Eq. 1 and the tip reduction beside them."""
    red, cmp_, top, mesh = doc.reduction, doc.comparison, doc.top, doc.mesh
    cf = red.closed_form
    lines = [
        f"3D pillar: {mesh.cells} {mesh.cell_type} cells, degree {mesh.degree}, "
        f"{mesh.dofs} dofs ({mesh.elements_around} around x {mesh.elements_along} "
        f"along x {mesh.elements_through} through, grading {mesh.grading:g})"
    ]
    lines.append(
        "(n: waves around the circumference; m: sign changes along the height; x is the rotor's plane, z the tube axis)"
    )
    # on a flexible foundation the 3D base stands on a rigid plate on its springs (fem3d.model)
    base = "clamped base" if getattr(bare, "base_plate", None) is None else "base on the foundation's springs"
    lines += _table(f"Bare tube ({base}, free top)", bare)
    lines += _table(f"With {top.carries.replace('_', ' ')} on top ({top.mass:g} kg, {top.model} top)", loaded)
    lines.append(
        f"First bending, bare: {red.omega_bending:.4f} rad/s; Eq. 1 "
        f"{cf.omega_col1:.4f} ({100 * cmp_.omega_bending_over_euler_bernoulli:+.2f} %), "
        f"Timoshenko {cf.omega_col1_timoshenko:.4f} "
        f"({100 * cmp_.omega_bending_over_timoshenko:+.2f} %)"
    )
    if top.omega_bending is not None:
        lines.append(
            f"First bending with top: {top.omega_bending:.4f} rad/s; the tip model "
            f"c1/(m_r + m_top) gives {top.omega_bending_reduced_model:.4f}"
        )
    lines.append(
        f"Tip reduction (Eq. 2 on the 3D mode): m_r = {red.m_reduced:.5g} kg "
        f"(beam line {red.m_reduced_beam_line:.5g}; closed form m_col/4 = "
        f"{cf.m_reduced:.5g}, {100 * cmp_.m_reduced_over_closed_form:+.2f} %), "
        f"c1 = {red.tip_stiffness:.5g} N/m"
    )
    shells = doc.shell_modes_below_second_bending
    for s, label in ((shells.bare, "bare"), (shells.with_top, "with top")):
        w2 = s.omega_second_bending
        found = ", ".join(
            f"{m.omega:.2f} ({m.kind}" + (f" n={m.n_circumferential}" if m.kind == "ovalling" else "") + ")"
            for m in s.modes
        )
        if w2 is None:
            lines.append(
                f"Second bending ({label}) not among the {len(bare.omega)} modes computed; "
                f"non-bending modes found: {found or 'none'}"
            )
        else:
            lines.append(f"Below the second bending ({label}, {w2:.2f} rad/s): {found or 'no shell mode'}")
    configs = doc.configurations
    lines.append(
        "Timings [s]: "
        + "; ".join(
            f"{k}: mesh {v.timings['mesh']:.2f}, assembly {v.timings['assembly']:.2f}, solve {v.timings['solve']:.2f}"
            for k, v in (("bare", configs.bare), ("with_top", configs.with_top))
        )
    )
    return "\n".join(lines)
