"""The convergence study as a typed result: what ``convergence.json`` holds.

:class:`ConvergenceStudy` is the study the command writes and the report
reads (``records.read(path, ConvergenceStudy)``).  Inside it, typed to the
leaves: each run of the ladder (:class:`ConvergenceRun`), the Richardson
extrapolations and references (:class:`Extrapolation`,
:class:`ReferenceValue`), the band (:class:`ExcitationBand`), the choice
(:class:`ModelSelection`, its runs as :class:`RunBrief`), the fronts
(:class:`ParetoFronts`) and the counts (:class:`StudyCounts`); beside it,
modal.json's ``model_selection`` (:class:`ModalModelSelection`).  Frequencies
are circular (rad/s); errors are relative (-).
"""

from __future__ import annotations

from typing import Any

import msgspec

from ..records import Record
from ..reduced.band import ExcitationBand  # noqa: F401  (defined where the band is computed; read here)
from .refinement import LadderRefinement

Param = int | float | str
"""A value of a run's discretisation (elements, degree, cell type, grading...)."""

ERROR_KINDS = ("error", "model_error", "discretisation_error", "error_bound")
"""A run's errors per frequency: ``{quantity}_{kind}`` (rotorpillar.converge.selection.attach_errors)."""


class RunErrors:
    """A run's frequencies and their errors read by quantity name ("bending", "ovalling"):
    the fields ``{q}`` and ``{q}_{kind}`` of :class:`ConvergenceRun` and :class:`RunBrief`."""

    __slots__ = ()  # a mixin of msgspec Structs

    def frequency(self, quantity: str) -> float | None:
        """The run's first ``quantity`` frequency (rad/s), None where not resolved."""
        value: float | None = getattr(self, quantity)
        return value

    def relative_error(self, quantity: str, kind: str = "error") -> float | None:
        """The run's relative error of that kind (ERROR_KINDS) on ``quantity`` (-)."""
        value: float | None = getattr(self, f"{quantity}_{kind}")
        return value

    def error_bound(self, quantity: str) -> float | None:
        """|model error| + |discretisation error| on ``quantity`` (-), None without one."""
        return self.relative_error(quantity, "error_bound")


class FamilyInfo(Record):
    """A family of the ladder as the study records it (rotorpillar.converge.ladder.Family)."""

    label: str
    model: str
    """"closed_form", "beam", "shell" or "solid" """
    order_theory: float | None
    """theoretical order p of the frequency error ~ h**p (None: not refined)"""
    quantities: tuple[str, ...]
    """the frequencies the model can have at all (bending, ovalling)"""
    sweep: bool
    """refined around the circumference only"""


class Mode(Record):
    """One mode of a run's solve."""

    omega: float
    """circular frequency (rad/s)"""
    kind: str
    """the mode's name (bending_x, ovalling, ...)"""
    n: int | None
    """circumferential wave number (None: not a shell mode)"""


class OvallingAlias(Record):
    """An "ovalling" mode with more waves than the nodes around carry: an alias."""

    omega: float | None
    """its frequency (rad/s; None where the run's family does not resolve ovalling,
    rotorpillar.converge.ladder.resolved_only)"""
    n: int
    """the wave number it was read with (-)"""


class RunResult(Record, omit_defaults=True):
    """What one run of the ladder computes (rotorpillar.converge.compute) and what it cost
    (rotorpillar.converge.runner): the fields of :class:`ConvergenceRun` after its case, as
    the serving process sends it back and the run cache stores it."""

    bending: float | None
    """first bending frequency (rad/s; None: no bending mode resolved)"""
    ovalling: float | None
    """first ovalling frequency (rad/s; None: none resolved)"""
    ovalling_n: int | None
    """the ovalling mode's wave number (-)"""
    dofs: int
    """degrees of freedom of the bare tube's model (-)"""
    modes: tuple[Mode, ...]
    """the modes the solve found, lowest first"""
    cells: int | None = None
    """cells of the finite-element mesh (-)"""
    timings: dict[str, float] | None = None
    """the model's stages (mesh, assembly, solve, ...): wall time (s)"""
    modes_asked: int | None = None
    """modes the eigen-solve was asked for (-)"""
    first_run_with_compilation: float | None = None
    """wall time of the first run, which compiled forms (s)"""
    wall_time: float | None = None
    """the model's whole time, warm (s)"""
    peak_memory: float | None = None
    """peak memory of the run (bytes; how: ``memory_method``)"""
    baseline_memory: float | None = None
    """resident memory of the worker's imports (bytes)"""
    memory_method: str | None = None
    process_time: float | None = None
    """the run's time as the study waited for it, serving process included (s)"""


class ConvergenceRun(Record, RunErrors, kw_only=True, omit_defaults=True):
    """One run of the ladder: its case, its frequencies, cost and errors against the reference.

    A failed or unavailable run has no result (``bending`` ... ``peak_memory`` absent) but
    ``error``; a frequency not resolved is absent too (None).
    """

    key: str
    """the run cache's key (a hash of what the result depends on)"""
    family: str
    model: str
    label: str
    level: int
    """the rung of the family (elements around, or along, or beam elements)"""
    params: dict[str, Param]
    """the discretisation (elements_around, elements_along, degree, cell_type...; beams: theory, elements)"""
    status: str
    """"ok", "failed" or "unavailable" """
    bending: float | None = None
    """first bending frequency (rad/s; None: no bending mode resolved)"""
    ovalling: float | None = None
    """first ovalling (n = 2) frequency (rad/s; None: none resolved)"""
    ovalling_n: int | None = None
    """the ovalling mode's wave number (-)"""
    dofs: int | None = None
    """degrees of freedom of the bare tube's model (-)"""
    cells: int | None = None
    """cells of the finite-element mesh (-)"""
    modes: tuple[Mode, ...] | None = None
    """the modes the solve found, lowest first"""
    timings: dict[str, float] | None = None
    """the model's stages (mesh, assembly, solve, ...): wall time (s)"""
    modes_asked: int | None = None
    """modes the eigen-solve was asked for (-)"""
    first_run_with_compilation: float | None = None
    """wall time of the first run, which compiled forms (s)"""
    wall_time: float | None = None
    """the model's whole time, warm (s)"""
    peak_memory: float | None = None
    """peak memory of the run (bytes; how: ``memory_method``)"""
    baseline_memory: float | None = None
    """resident memory of the worker's imports (bytes)"""
    memory_method: str | None = None
    process_time: float | None = None
    """the run's time as the study waited for it, serving process included (s)"""
    error: str | None = None
    """why the run failed or did not run"""
    cached: bool
    """loaded from the run cache (not computed by this study); always written"""
    ovalling_alias: OvallingAlias | None = None
    """the aliased "ovalling" mode dropped (rotorpillar.converge.failures.drop_aliases)"""
    bending_error: float | None = None
    """(f - f_ref)/f_ref on the first bending frequency (-)"""
    bending_model_error: float | None = None
    """(L - f_ref)/f_ref, L the family's Richardson limit: what no refinement removes (-)"""
    bending_discretisation_error: float | None = None
    """(f - L)/f_ref (-)"""
    bending_error_bound: float | None = None
    """|model error| + |discretisation error| (-)"""
    ovalling_error: float | None = None
    """as ``bending_error``, on the first ovalling frequency (-)"""
    ovalling_model_error: float | None = None
    ovalling_discretisation_error: float | None = None
    ovalling_error_bound: float | None = None


class Extrapolation(Record):
    """Richardson extrapolation of three runs at sizes h1 > h2 > h3
    (rotorpillar.converge.richardson.richardson)."""

    order: float | None
    """observed order p (None: no monotone convergence, the theoretical one used)"""
    order_theory: float | None
    """the family's theoretical order (-)"""
    monotone: bool
    value: float
    """the extrapolated frequency (rad/s)"""
    error_estimate: float
    """Roache's grid convergence index on ``value`` (rad/s)"""
    h: tuple[float, ...]
    """the runs' relative cell sizes, 1/level (-)"""
    f: tuple[float, ...]
    """the runs' frequencies (rad/s)"""


class FamilyExtrapolation(Extrapolation):
    """A family's extrapolation on its three finest runs."""

    runs: tuple[str, ...]
    """the runs' labels, coarse to fine"""


class RichardsonCheck(Extrapolation):
    """The extrapolation from the three runs before the finest, against the finest."""

    finer_run: str
    finer_value: float
    """the finest run's frequency (rad/s)"""
    difference: float
    """finer_value - value (rad/s)"""
    within_estimate: bool


class ReferenceValue(FamilyExtrapolation, omit_defaults=True):
    """A quantity's reference: the extrapolation of the highest-fidelity family that has one."""

    family: str
    check: RichardsonCheck | None = None
    """absent when the family has fewer than four runs"""


class RunBrief(Record, RunErrors):
    """A run as the choice names it: its case, cost, frequencies and errors."""

    label: str
    family: str
    model: str
    params: dict[str, Param]
    dofs: int
    """degrees of freedom (-)"""
    wall_time: float
    """(s)"""
    peak_memory: float | None
    """(bytes)"""
    bending: float | None
    """first bending frequency (rad/s)"""
    ovalling: float | None
    """first ovalling frequency (rad/s)"""
    bending_error: float | None
    """relative errors (-), as ConvergenceRun's"""
    bending_model_error: float | None
    bending_discretisation_error: float | None
    bending_error_bound: float | None
    ovalling_error: float | None
    ovalling_model_error: float | None
    ovalling_discretisation_error: float | None
    ovalling_error_bound: float | None


class RejectedRun(RunBrief):
    """A run cheaper than the choice that does not meet the tolerance, and why."""

    why: str


class ModelSelection(Record):
    """The choice: the cheapest run whose error bound meets the tolerance over the band."""

    tolerance: float
    """relative frequency tolerance (-)"""
    band: ExcitationBand
    needed: tuple[str, ...]
    """the quantities whose reference lies inside the band"""
    reference_uncertainty: dict[str, float]
    """per needed quantity: the reference's own relative error estimate (-)"""
    families: tuple[str, ...] | None
    """the families the choice was restricted to (None: all)"""
    candidates: int
    """runs that meet the tolerance (-)"""
    rule: str
    chosen: RunBrief | None
    """None: no run meets the tolerance (``reason`` says why)"""
    rejected_cheaper: tuple[RejectedRun, ...]
    """per family, its most accurate run cheaper than the choice"""
    reason: str


class ModalModelSelection(Record):
    """The 3D mesh `rotorpillar modal --tolerance` runs, and why: modal.json's
    ``model_selection`` (rotorpillar.converge.study.model_for_modal)."""

    tolerance: float
    """relative frequency tolerance asked (-)"""
    met: bool
    """a 3D run of the study meets the tolerance (False: the most accurate is run, and `modal` exits 4)"""
    chosen: RunBrief | None
    """the 3D run whose mesh `modal` runs (None: no 3D run has an error estimate; the scene's [mesh])"""
    reason: str
    """why, in words (when not met: why not)"""
    rule: str
    band: ExcitationBand
    needed: tuple[str, ...]
    """the quantities whose reference lies inside the band"""
    reference_uncertainty: dict[str, float]
    """per needed quantity: the reference's own relative error estimate (-)"""
    rejected_cheaper: tuple[RejectedRun, ...]
    """per 3D family, its most accurate run cheaper than the choice"""
    overall_cheapest: RunBrief | None
    """the study's own choice among all its models (a shell or a beam may be cheaper)"""
    convergence_json: str | None
    """the convergence.json written (None: under MPI, the study read from its cache)"""
    text: str
    """the choice in a few lines, as `modal` prints it"""


class Fronts(Record):
    """Per error (each frequency's, and the band's), the labels of the runs on the front."""

    bending: tuple[str, ...]
    ovalling: tuple[str, ...]
    band: tuple[str, ...]


class ParetoFronts(Record):
    """The Pareto fronts of error against each cost."""

    dofs: Fronts
    """against degrees of freedom"""
    wall_time: Fronts
    """against wall time (s)"""


class StudyCounts(Record, omit_defaults=True):
    """How the study went: its runs and its time."""

    runs: int
    workers: int
    cached: int
    computed: int
    failed: int
    unavailable: int
    compute_seconds: float
    """the computed runs' time (s)"""
    wall_time: float | None = None
    """the whole study's wall time (s)"""


class ConvergenceStudy(Record, omit_defaults=True):
    """Every run of the ladder, the reference values, the fronts, the choice and the failures."""

    scene_name: str
    scene: dict[str, Any]
    """the scene as ``Scene.to_dict()`` gives it"""
    tolerance: float
    """relative frequency tolerance of the choice (-)"""
    cache_dir: str
    families: dict[str, FamilyInfo]
    """per family name"""
    runs: tuple[ConvergenceRun, ...]
    reference: dict[str, ReferenceValue]
    """per quantity: Richardson on the finest runs of the best family"""
    extrapolations: dict[str, dict[str, FamilyExtrapolation]]
    """per refined family, per quantity: Richardson on its three finest runs"""
    band: ExcitationBand
    selection: ModelSelection
    pareto: ParetoFronts
    failures: tuple[str, ...]
    """where methods fail, one sentence each"""
    study: StudyCounts
    refinement: LadderRefinement | None = None
    """how far each family was refined, and why no further (rotorpillar.converge.adaptive)"""
    charts: dict[str, str] | None = None
    """chart name -> path (absent when no charts were drawn)"""
    json_file: str | None = msgspec.field(default=None, name="json")
    """where the study was written (key ``json``; never in the file itself)"""

    @property
    def chosen(self) -> RunBrief | None:
        """The chosen run's brief (label, family, params, dofs, errors...), or None."""
        return self.selection.chosen


class QuantityErrors(Record):
    """A run's first frequency of one quantity and its errors against the study's reference
    (rotorpillar.converge.selection.attach_errors): a reference mesh's ``errors`` per quantity."""

    value: float | None
    """the run's first frequency of the quantity (rad/s)"""
    error: float | None
    """(f - f_ref)/f_ref (-)"""
    model_error: float | None
    """(L - f_ref)/f_ref, L the family's Richardson limit (-)"""
    discretisation_error: float | None
    """(f - L)/f_ref (-)"""
    error_bound: float | None
    """|model error| + |discretisation error| (-)"""

    @classmethod
    def of(cls, run: RunErrors, quantity: str) -> QuantityErrors:
        """``run``'s frequency and errors (ERROR_KINDS) on ``quantity``."""
        kinds = {kind: run.relative_error(quantity, kind) for kind in ERROR_KINDS}
        return cls(value=run.frequency(quantity), **kinds)


class CaseFile(Record):
    """A run of the ladder as the parent hands it to the serving process (a file)."""

    family: str
    level: int
    params: tuple[tuple[str, Param], ...]
    """the discretisation, as (key, value) pairs"""
    scene: dict[str, Any]
    """the scene (``Scene.to_dict()``)"""


class ModeSourceFloor(Record):
    """The ROM's mode source as the run-up's full-order reference must match it: at least as fine."""

    label: str
    """the study's run of the mode source (a beam or a 3D mesh)"""
    band_error: float | None
    """its error bound plus the reference's uncertainty over the case's quantities (-; None: not measured)"""
