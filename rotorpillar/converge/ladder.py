"""The ladder: the pillar models of the study, and the rungs each is refined on.

- the closed forms: the paper's Eq. 1 for bending, the inextensional
  ring for ovalling;
- 1D beam FE, Euler-Bernoulli (Hermite cubics) and Timoshenko (linear,
  reduced shear), n elements: bending only, a beam has no shell modes;
- the shell model of the mid-surface (rotorpillar.fem3d.naghdi), quadratic
  quadrilaterals and triangles;
- the 3D solid model (rotorpillar.fem3d.modal_analysis), P1 and P2,
  hexahedra and tetrahedra;
- two side sweeps that refine only around the circumference, to show where
  too few elements around fail the ovalling mode;
- a side family of 3D P2 hexahedra refined only along the height, with few
  elements around (``ALONG_FAMILY_AROUND``): enough for the n = 1 bending
  modes a horizontal load excites, far too few for the shell modes, so it
  measures what a cheap mesh makes of bending alone (the transients'
  full-order references come from it, rotorpillar.converge.selection
  ``select_reference``).

Each rung is a :class:`Case`; :func:`ladder` lists them for a scene, and
:func:`estimated_seconds` guesses their cost for the progress bar.

The counts along the height were set on the paper's tube (20 m, 2 m
across: 10 diameters tall).  A taller, more slender tower needs as many
more cells along for the same cell shape and the same resolution of its
bending mode: the shell's and the bending-only family's elements along
scale by the tower's height over its mean diameter, over the paper's 10
(``along_scale``; 1 for the paper's scenes; the 3D families follow the
scene's own [mesh] in proportion).  On a flexible foundation the shell
families leave the ladder: the shell model has no base springs (the 3D
model's base plate carries them, rotorpillar.fem3d.rigid_faces); a tower
of several cans needs a beam element per can at least, and its lower
rungs are left out.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import msgspec

from ..scene import CELL_TYPES, SHELL_CELL_TYPES, Mesh, Scene
from .result import ConvergenceRun

QUADRILATERAL, TRIANGLE = SHELL_CELL_TYPES
HEXAHEDRON, TETRAHEDRON = CELL_TYPES

QUANTITIES = ("bending", "ovalling")
"""What each run reports: the first bending and the first ovalling frequency."""

AROUND_LEVELS = (8, 12, 16, 24, 32, 48, 64, 96)
"""Elements around the circumference of the shell ladders."""
ALONG_PER_AROUND = 1.25
"""Shell: elements along per element around (uniform cells, about 2:1)."""
SOLID_AROUND_LEVELS = (32, 64, 96, 128, 160, 192, 224, 256)
"""Elements around of the 3D ladders; along and through follow the scene's [mesh]
in proportion (64 x 10 x 1 graded: multiples of 32 around keep along whole)."""
SWEEP_AROUND = (4, 6, 8, 12, 16)
"""Elements around of the shell's side sweep (elements along fixed)."""
SOLID_SWEEP_AROUND = (4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128)
"""Elements around of the 3D side sweep, at the scene's [mesh] along: the
shell modes need cells around, the bending mode cells along."""
SWEEP_ALONG = 40
"""Shell sweep: elements along (the 3D sweep keeps the scene's [mesh] along)."""
ALONG_FAMILY_AROUND = 8
"""Elements around of the bending-only 3D family.  On the paper's tube at 10 along
(the around-only sweep) the first bending frequency moves by 1.7e-4 from 8 to
64 around and by 1e-5 from 16: 8 around keeps the n = 1 section within a
fifth of a 1e-3 tolerance at half the DOFs of 16 around, and the family's
own limit against the reference (its model error) carries that 1.7e-4 into
every bound, so the choice never credits it."""
ALONG_LEVELS = (5, 10, 15, 20, 30, 40)
"""Elements along of the bending-only 3D family (its three finest give its limit)."""
EULER_LEVELS = (1, 2, 4, 8, 16, 32)
TIMOSHENKO_LEVELS = (2, 4, 8, 16, 32, 64, 128, 256, 512)
N_MODES = 12
"""Modes computed per finite-element run: enough to reach the first n = 2 pair."""
N_MODES_FIRST = 6
"""Modes asked first (rotorpillar.converge.compute.compute_fe): past the first
n = 2 pair on every mesh of 24 or more elements around; N_MODES where not."""


@dataclass(frozen=True)
class Family:
    """A model and a way to refine it."""

    name: str
    label: str
    model: str
    """"closed_form", "beam", "shell" or "solid" """
    quantities: tuple
    """which of QUANTITIES the model can have at all"""
    order: float | None
    """theoretical order p of the frequency error ~ h**p (None: not refined)"""
    sweep: bool = False
    """refined around the circumference only: shows a failure, no extrapolation"""
    fidelity: int = 0
    """preference as the reference family (highest with enough runs wins)"""
    parent: str | None = None
    """a sweep's refined family: the same model, whose limit splits its errors"""


FAMILIES = {
    f.name: f
    for f in [
        Family("closed_form", "Eq. 1 + ring (closed forms)", "closed_form", QUANTITIES, None),
        Family("beam_euler", "beam Euler-Bernoulli (Hermite)", "beam", ("bending",), 4.0),
        Family("beam_timoshenko", "beam Timoshenko (linear)", "beam", ("bending",), 2.0),
        Family("shell_quad", "shell Q2 quadrilaterals", "shell", QUANTITIES, 4.0, fidelity=2),
        Family("shell_tri", "shell P2 triangles", "shell", QUANTITIES, 4.0, fidelity=1),
        Family(
            "shell_quad_around",
            "shell Q2, around only (40 along)",
            "shell",
            QUANTITIES,
            None,
            True,
            parent="shell_quad",
        ),
        Family("solid_hex_p1", "3D P1 hexahedra", "solid", QUANTITIES, 2.0),
        Family("solid_tet_p1", "3D P1 tetrahedra", "solid", QUANTITIES, 2.0),
        Family("solid_hex_p2", "3D P2 hexahedra", "solid", QUANTITIES, 4.0, fidelity=4),
        Family("solid_tet_p2", "3D P2 tetrahedra", "solid", QUANTITIES, 4.0, fidelity=3),
        Family(
            "solid_hex_p2_around",
            "3D P2 hexahedra, around only",
            "solid",
            QUANTITIES,
            None,
            True,
            parent="solid_hex_p2",
        ),
        Family(
            "solid_hex_p2_along",
            f"3D P2 hexahedra, {ALONG_FAMILY_AROUND} around, along only",
            "solid",
            ("bending",),
            4.0,
        ),
    ]
}


ORDER_NOTES = {
    ("solid_hex_p2", "bending"): "the clamp's 3D boundary layer under the base rim, about a wall thickness deep, is "
    "much finer than the smallest cell at the base (11 cm at 20 along with grading 30); "
    "with grading 200 the order returns to 4 (tests/test_converge_solid.py)",
    ("solid_tet_p2", "bending"): "as for the P2 hexahedra: the clamp's boundary layer",
    ("shell_tri", "bending"): "P2 triangles lock: their error falls far slower than the "
    "quadrilaterals' at the same DOFs",
    ("solid_hex_p2_along", "bending"): "as for the P2 hexahedra: the clamp's boundary layer",
}
"""Why a family's observed order departs from theory, where we checked it."""


@dataclass(frozen=True)
class Case:
    """One run: a family at one refinement ``level`` (elements, or elements around)."""

    family: str
    level: int
    params: tuple
    """the model's discretisation as sorted (key, value) pairs"""

    @property
    def settings(self) -> dict:
        return dict(self.params)

    @property
    def label(self) -> str:
        s = self.settings
        fam = FAMILIES[self.family]
        if fam.model == "closed_form":
            return fam.label
        if fam.model == "beam":
            return f"{fam.label}, {s['elements']} el."
        mesh = f"{s['elements_around']}x{s['elements_along']}"
        if fam.model == "solid":
            mesh += f"x{s['elements_through']}"
        return f"{fam.label}, {mesh}"


def _case(family: str, level: int, **params) -> Case:
    return Case(family, level, tuple(sorted(params.items())))


#: the paper's tube: height over diameter, the slenderness the counts along were set on
PAPER_SLENDERNESS = 10.0


def along_scale(scene: Scene) -> float:
    """How many times the paper's counts along a tower needs: its height over its mean
    outer diameter over the paper's 10, at least 1 (-)."""
    p = scene.pillar
    segs = p.segments()
    mean_d = sum(s.length * (s.outer_bottom + s.outer_top) / 2 for s in segs) / p.height
    return max(1.0, p.height / mean_d / PAPER_SLENDERNESS)


def _along(around: int, scale: float = 1.0) -> int:
    return max(1, int(round(ALONG_PER_AROUND * around * scale)))


def levels(scene: Scene, family: str) -> tuple[int, ...]:
    """The rungs of a family on a scene's ladder (its refinement levels, coarse to
    fine; within the scene's ``[converge]`` limits)."""
    cv = scene.converge
    # a tower of cans needs an element per can at least; the shells have no base springs,
    # so they leave the ladder on a flexible foundation
    cans, shells = len(scene.pillar.segments()), scene.foundation.kind == "clamped"
    if family == "closed_form":
        return (0,)
    if family == "beam_euler":
        return tuple(n for n in EULER_LEVELS if n >= cans)
    if family == "beam_timoshenko":
        return tuple(n for n in TIMOSHENKO_LEVELS if n >= cans)
    if family in ("shell_quad", "shell_tri"):
        top = cv.shell_max_around if family == "shell_quad" else cv.shell_tri_max_around
        return tuple(n for n in AROUND_LEVELS if n <= top and shells)
    if family == "shell_quad_around":
        return SWEEP_AROUND if shells else ()
    if not cv.solid:
        return ()
    if family == "solid_hex_p2_around":
        return tuple(n for n in SOLID_SWEEP_AROUND if n <= cv.solid_p2_max_around)
    if family == "solid_hex_p2_along":
        return tuple(n for n in ALONG_LEVELS if n * along_scale(scene) >= cans)
    top = {
        "solid_hex_p1": cv.solid_p1_max_around,
        "solid_tet_p1": cv.solid_p1_max_around,
        "solid_hex_p2": cv.solid_p2_max_around,
        "solid_tet_p2": cv.solid_tet_p2_max_around,
    }[family]
    return tuple(n for n in SOLID_AROUND_LEVELS if n <= top)


def rung(scene: Scene, family: str, level: int) -> Case:
    """A family's case at refinement ``level`` (elements, or elements around; the
    bending-only 3D family's: elements along), on the ladder or past its finest.

    The 3D rungs refine the scene's own [mesh] in proportion: elements along
    = around x along/around of [mesh], the same elements through and grading,
    so that Richardson sees one family of similar meshes.
    """
    ms, n = scene.mesh, level
    scale = along_scale(scene)
    if family == "closed_form":
        return _case("closed_form", 0)
    if family in ("beam_euler", "beam_timoshenko"):
        theory = family.split("_")[1]
        return _case(family, n, theory=theory, elements=n)
    if family in ("shell_quad", "shell_tri"):
        cell = QUADRILATERAL if family == "shell_quad" else TRIANGLE
        return _case(family, n, elements_around=n, elements_along=_along(n, scale), cell_type=cell, degree=2)
    if family == "shell_quad_around":
        sweep_along = max(SWEEP_ALONG, int(round(SWEEP_ALONG * scale)))
        return _case(family, n, elements_around=n, elements_along=sweep_along, cell_type=QUADRILATERAL, degree=2)
    solid = dict(elements_through=ms.elements_through, grading=ms.grading)
    if family == "solid_hex_p2_around":
        return _case(
            family, n, elements_around=n, elements_along=ms.elements_along, cell_type=HEXAHEDRON, degree=2, **solid
        )
    if family == "solid_hex_p2_along":
        return _case(
            family,
            n,
            elements_around=ALONG_FAMILY_AROUND,
            elements_along=max(n, int(round(n * scale))),
            cell_type=HEXAHEDRON,
            degree=2,
            **solid,
        )
    ratio = ms.elements_along / ms.elements_around
    return _case(
        family,
        n,
        elements_around=n,
        elements_along=max(1, int(round(ratio * n))),
        cell_type=HEXAHEDRON if "hex" in family else TETRAHEDRON,
        degree=2 if family.endswith("p2") else 1,
        **solid,
    )


def ladder(scene: Scene) -> list[Case]:
    """Every run of the study for a scene (its ``[converge]`` limits and ``[mesh]`` shape):
    every rung of every family, in the families' order."""
    return [rung(scene, name, n) for name in FAMILIES for n in levels(scene, name)]


def resolved_only(family: str, run: ConvergenceRun) -> ConvergenceRun:
    """A run with the quantities its family does not resolve set to None.

    A bending-only mesh may run the very case of another family (8 around at
    the scene's along is also a rung of the around-only sweep, one cached
    run for both): its ovalling frequency is then that run's, but not a
    quantity of this family."""
    fam = FAMILIES[family]
    drop: dict[str, Any] = {q: None for q in QUANTITIES if q not in fam.quantities and run.frequency(q) is not None}
    return msgspec.structs.replace(run, **drop) if drop else run


def estimated_dofs(case: Case) -> int:
    """DOFs of a case before it runs (for the progress bar's cost estimate)."""
    s, model = case.settings, FAMILIES[case.family].model
    if model == "closed_form":
        return 1
    if model == "beam":
        return 2 * s["elements"]
    na, nz = s["elements_around"], s["elements_along"]
    k = s["degree"]
    if model == "shell":
        return 5 * (k * na) * (k * nz + 1)
    nt = s["elements_through"]
    return 3 * (k * na) * (k * nz + 1) * (k * nt + 1)


def estimated_seconds(case: Case) -> float:
    """A rough cost model (s, measured on this project's 2-core machine), for the
    progress bar only: tqdm's ETA then follows the measured rate."""
    model = FAMILIES[case.family].model
    n = estimated_dofs(case)
    if model in ("closed_form", "beam"):
        return 0.001 + 2e-9 * n**2
    if model == "shell":
        return 1.3 + 1.0e-4 * n
    if case.settings["degree"] == 1:
        return 1.5 + 7e-5 * n
    return 1.5 + (8e-5 if case.settings["cell_type"] == TETRAHEDRON else 1.3e-4) * n


def solid_mesh(case: Case):
    """The scene ``[mesh]`` section of a 3D case."""
    s = case.settings
    return Mesh(
        elements_around=s["elements_around"],
        elements_along=s["elements_along"],
        elements_through=s["elements_through"],
        degree=s["degree"],
        cell_type=s["cell_type"],
        grading=s["grading"],
    )


def study_cases(scene: Scene) -> list[Case]:
    """The study's runs for a scene (the whole ladder)."""
    return ladder(scene)
