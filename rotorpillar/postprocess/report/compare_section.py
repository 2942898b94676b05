"""The models of one case side by side (``compare_<case>.json``): the
overlay, the table of error and cost, each model's notes and warnings; and
the record's response spectrum with the coupled modes marked.

The builders read the comparison's records (``transients.compare.CompareResult``
and each model's run) and make the view records the partials
``templates/sections/comparison.html.j2`` and ``spectrum.html.j2`` print.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ... import records
from ...records import Record
from ...reduced.excitation import PulseSizes, RecordSizes
from ...transients.compare import comparison_command, comparison_overrides
from .page import model_name, render
from .parts import differing_keys
from .state import Build

if TYPE_CHECKING:
    from ...transients.compare import CompareResult
    from ..compare_reader import Comparison


class Picture(Record):
    """A picture on the page and its caption."""

    path: str
    caption: str


class CostRow(Record):
    """One model of a comparison: its size, cost, peaks and errors against the reference."""

    model: str
    reference: bool
    dofs: int | None
    wall_seconds: float | None
    """warm wall time (s)"""
    compile_seconds: float | None
    """compilation, apart (s)"""
    peak_tip: float | None
    """peak tip displacement relative to the ground (m)"""
    peak_shaft: float | None
    """peak shaft deflection (m)"""
    omega_final: float | None
    """final rotor speed (rad/s)"""
    history_error: float | None
    """tip history error against the reference (-)"""
    envelope_error: float | None
    """tip envelope error against the reference (-)"""
    peak_difference: float | None
    """peak tip difference against the reference (-)"""
    angle_drift: float | None
    """largest rotor angle drift from the reference (rad)"""
    cost_ratio: float | None
    """warm wall time over the reference's (-)"""
    lead: str | None
    """the error measure that fits the case: "history" or "envelope\""""
    lead_why: str
    """why that measure"""
    ok: bool
    warnings: tuple[str, ...]
    full_order: str | None
    """what the full-order model was, as run (mesh or elements, duration, step)"""


class ComparisonView(Record):
    """What the page shows of one comparison."""

    case: str
    command: str
    """the command that makes it"""
    found: bool
    differs: tuple[str, ...] = ()
    """scene keys it was computed with other values of"""
    excitation: str | None = None
    """a sentence on the ground motion"""
    window: tuple[float, float] = (0.0, 0.0)
    """the interval every model ran over (s)"""
    window_why: str = ""
    figure: Picture | None = None
    figure_failed: str | None = None
    reference: str = ""
    rows: tuple[CostRow, ...] = ()
    own_charts: tuple[Picture, ...] = ()


def excitation_text(ex) -> str | None:
    """One sentence on the ground motion a run used (its excitation block)."""
    if isinstance(ex, (PulseSizes, RecordSizes)) and ex.statement is not None:
        return ex.statement
    if not isinstance(ex, RecordSizes):
        return None
    return (
        f"Ground motion: the record {ex.name}" + (f" ({ex.source})" if ex.source else "") + f": peak acceleration "
        f"{ex.peak_acceleration_g:.3g} g, peak velocity {ex.peak_velocity:.3g} m/s, peak displacement "
        f"{ex.peak_displacement:.3g} m, from t = {ex.start:.4g} s."
    )


def full_order_text(run) -> str | None:
    """What a full-order run was (mesh or elements, duration, step) and its note."""
    from ...transients.model_run import BeamFullOrder, Fem3dPlan

    fo = run.full_order if run is not None else None
    if isinstance(fo, Fem3dPlan):
        mesh = ", ".join(f"{k.replace('_', ' ')} {v}" for k, v in records.to_builtins(fo.mesh).items())
        said = [f"mesh {mesh}", f"duration {fo.duration:.4g} s"]
    elif isinstance(fo, BeamFullOrder):
        said = [f"{fo.elements} {fo.theory} beam elements", f"duration {fo.duration:.4g} s"]
    else:
        return None
    said.append(f"time step {fo.time_step:.3g} s")
    return "; ".join(said) + (f". {fo.note}" if fo.note else "")


def cost_rows(result: CompareResult, c: Comparison) -> tuple[CostRow, ...]:
    """Per model run: its size, cost, peaks and errors against the reference."""
    out = []
    for m in c.models:
        if m not in result.per_model:
            continue
        p = result.per_model[m]
        e = result.errors[m] if m in result.errors else None
        is_ref = m == result.reference
        ratio = result.cost_ratio[m] if m in result.cost_ratio else (1.0 if is_ref else None)
        out.append(
            CostRow(
                model=m,
                reference=is_ref,
                dofs=p.dofs,
                wall_seconds=p.wall_seconds,
                compile_seconds=p.compile_seconds,
                peak_tip=p.peak_tip_relative,
                peak_shaft=p.peak_shaft_deflection,
                omega_final=p.omega_final,
                history_error=None if e is None else e.tip_history_error,
                envelope_error=None if e is None else e.tip_envelope_error,
                peak_difference=None if e is None else e.peak_tip_difference,
                angle_drift=None if e is None else e.angle_drift,
                cost_ratio=ratio,
                lead=None if e is None else e.lead,
                lead_why="" if e is None else e.lead_why,
                ok=p.ok,
                warnings=p.warnings,
                full_order=full_order_text(c.runs[m] if m in c.runs else None),
            )
        )
    return tuple(out)


def _claim_figures(build: Build, case: str, models: list[str]) -> list:
    """The other commands' PNGs of this comparison (compare_<case>.png and the
    models' own compare_<case>_<model>.png), taken out of their groups."""
    names = {f"compare_{case}.png"} | {f"compare_{case}_{m}.png" for m in models}
    found = [p for p in build.external if p.path.name in names]
    for p in found:
        p.group = "used"
    return found


def comparison_view(build: Build, case: str) -> ComparisonView:
    """The comparison of the models on ``case`` as the page shows it."""
    command = f"rotorpillar {comparison_command(case)} {build.scene_cli}"
    if case not in build.comparisons:
        return ComparisonView(case, command, found=False)
    c = build.comparisons[case]
    result = c.record
    theirs = _claim_figures(build, case, c.models)
    key = f"comparison_{case}"
    figure: Picture | None
    if key in build.products:
        figure = Picture(str(build.products[key].path), build.products[key].caption)
    else:  # no arrays to draw from: compare's own chart, if it left one
        figure = next((Picture(str(p.path), p.caption) for p in theirs if p.path.name == f"compare_{case}.png"), None)
    own = tuple(
        Picture(str(p.path), f"{model_name(m)}: {p.caption}")
        for m in c.models
        for p in theirs
        if p.path.name == f"compare_{case}_{m}.png"
    )
    return ComparisonView(
        case,
        command,
        found=True,
        differs=differing_keys(build, c.provenance, ignore=comparison_overrides(case)),
        excitation=excitation_text(result.excitation),
        window=(result.window.start, result.window.end),
        window_why=result.window.why,
        figure=figure,
        figure_failed=build.failures[key] if key in build.failures else None,
        reference=result.reference,
        rows=cost_rows(result, c),
        own_charts=own,
    )


def comparison_block(build: Build, case: str) -> list[str]:
    """The comparison of the models on ``case``, or the command that makes it."""
    from .references import reference_block

    view = comparison_view(build, case)
    ref = build.comparisons[case].record.full_order_reference if view.found else None
    return [render("sections/comparison.html.j2", c=view, reference=reference_block(ref))]


def spectrum_block(build: Build) -> list[str]:
    """The record's response spectrum with the coupled modes of the ROM's estimate marked
    at their own damping, the estimate beside the computed peak, and what the coupling
    does to it (the same SRSS over the pillar's own modes, the rotor apart)."""
    from ..directions import direction

    c = build.comparisons["earthquake"] if "earthquake" in build.comparisons else None
    spec = c.record.spectrum if c is not None else None
    figure = None
    if "response_spectrum" in build.products:
        p = build.products["response_spectrum"]
        figure = Picture(str(p.path), p.caption)
    return [
        render(
            "sections/spectrum.html.j2",
            found=c is not None,
            command=f"rotorpillar {comparison_command('earthquake')} {build.scene_cli}",
            spec=spec,
            model="modal",
            picture=figure,
            failed=build.failures["response_spectrum"] if "response_spectrum" in build.failures else None,
            horizontal=direction("X"),
        )
    ]
