"""The page's first section: the findings in a few plain sentences (no
internal ids, no formulas: each points to the section that holds the
detail), each input that is missing named with the command that makes it."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ...reduced.excitation import PulseSizes, RecordSizes
from ...transients.compare import COMPARISONS, comparison_command
from .. import html as h
from ..readers import CASES, INPUTS, SIMULATE_COMMAND
from .compare_section import speed_accuracy
from .convergence import chosen
from .engineering import verdict_block
from .modal import bending, is_finding
from .models import model_views, resonance_words
from .state import Build

if TYPE_CHECKING:
    from ...analysis.results import AnalysisResult
    from ...chain.record import Uncertain

#: Where the detail of each finding is (section or subsection ids).
FINDINGS_ANCHOR = "paper-findings"


def _pillar(build: Build, a: AnalysisResult) -> str:
    m = build.modal
    p = a.pillar
    text = (
        f"First bending mode of the bare tube: Eq. 1 gives {p.omega_col1:.3f} rad/s "
        f"({p.frequency_col1_hz:.3f} Hz); Timoshenko {h.pct(p.timoshenko_correction)}"
    )
    bx = bending(m.modes, "bending_x") if m is not None else []
    if bx:
        w = bx[0].omega
        text += f"; the 3D model {w:.3f} rad/s ({w / p.omega_col1 - 1:+.2%} against Eq. 1)."
    else:
        text += "; the 3D model: " + build.hint(INPUTS["modal"][1]) + "."
    return text


def _drive(a: AnalysisResult, eccentricity: float) -> list[str]:
    d = a.drive
    st = ", ".join(f"{x.omega:.2f} rad/s ({'stable' if x.stable else 'unstable'})" for x in d.stationary) or "none"
    items = [
        f"Stationary speed(s) with the scene's motor: {st}. "
        + (
            f"{len(d.jumps)} jump(s) in a quasi-static run-up or run-down."
            if d.jumps
            else "No jumps (no Sommerfeld effect) with this drive."
        )
    ]
    items += [r.statement for r in a.resonances if r.jumps]
    calm = [r for r in a.resonances if not r.jumps and r.critical_eccentricity > 0]
    if calm:
        e = min(calm, key=lambda r: r.critical_eccentricity)
        items.append(
            f"No jumps at {'any' if len(calm) == len(a.resonances) else 'the other'} "
            f"resonance with this drive; the first to show them would be resonance "
            f"{e.index} ({e.omega:.2f} rad/s), above an eccentricity of "
            f"{e.critical_eccentricity:.3g} m (the scene's: {eccentricity:.3g} m)."
        )
    return items


def _analysis_findings(build: Build, a: AnalysisResult) -> list[str | h.Raw]:
    items: list[str | h.Raw] = [_pillar(build, a)]
    views = model_views(a)
    for v in views:
        items.append(f"Rotor-pillar resonances, {v.title}: {resonance_words(v.resonances)}.")
    items.append(f"The headline model's pillar: {a.pillar_model.describe()}; its error bars: {a.system.error_note}.")
    r = a.paper_model.reduction
    items.append(
        f"Pillar reduced to its tip in the paper's model: m_r = {r.tip_mass:.4g} kg "
        f"({r.tip_mass_source}), c1 = {r.tip_stiffness:.4g} N/m ({r.tip_stiffness_source})."
    )
    rows = [x for x in a.paper_comparison if not is_finding(x)]
    items.append(
        h.Raw(
            h.esc(
                f"{sum(1 for x in rows if x.flag)} of the {len(rows)} numbers the "
                "paper prints differ from ours by more than 2 %, each compared with "
                "the case it belongs to; "
            )
            + h.link("the table", "paper")
            + h.esc(" gives each one's likely cause.")
        )
    )
    if any(is_finding(x) for x in a.paper_comparison):
        items.append(
            h.Raw(
                h.esc(
                    "The paper's Eq. 4 forces the rotor's shaft from the ground as "
                    "well as the pillar; our reduced models use the consistent "
                    "forcing ("
                )
                + h.link("the finding", FINDINGS_ANCHOR)
                + h.esc(").")
            )
        )
    items += _drive(a, build.scene.rotor.eccentricity)
    return items


def _item(text: str | h.Raw) -> str:
    """A list item, its "not computed: run `...`" command set as code."""
    if isinstance(text, h.Raw):
        return h.tag("li", [text])
    if "not computed: run `" in text:
        pre, rest = text.split("not computed: run `", 1)
        cmd, post = rest.split("`", 1)
        return h.tag("li", [pre, "not computed: run ", h.tag("code", cmd), post])
    return h.tag("li", text)


def _bar(bars: dict[str, Uncertain] | None, key: str, value: Any, scale: float, unit: str) -> str:
    """A run's number with its error bar where the run carries one (the headline model's:
    ``uncertainty``), ``scale`` converting SI to ``unit``; what was not assessed is said."""
    u = (bars or {}).get(key)
    if not isinstance(value, (int, float)):
        return "-"
    if u is None or not isinstance(u.error, (int, float)):
        return f"{h.num(scale * value, 4)} {unit}"
    text = f"{h.num(scale * value, 4)} ± {scale * u.error:.2g} {unit}"
    if u.unassessed:
        text += f" ({', '.join(u.unassessed)} not assessed)"
    return text


def _runs(build: Build) -> list[str | h.Raw]:
    from ...transients.model_run import ReducedRun

    items: list[str | h.Raw] = []
    for case in CASES:
        sim = build.simulations.get(case)
        if sim is None or sim.run is None:
            continue
        run = sim.run
        got = run
        model = run.model
        if case == "earthquake":
            ex = got.excitation
            if isinstance(ex, (PulseSizes, RecordSizes)) and not ex.realistic:
                step = abs(
                    (ex.displacement_step_at_start if isinstance(ex, PulseSizes) else 0.0) or ex.peak_displacement
                )
                items.append(
                    h.Raw(
                        h.esc(
                            f"The paper's own earthquake ({model} model) is a "
                            f"{step:.3g} m ground step at "
                            f"{ex.peak_acceleration_g:.3g} g, "
                            "not an earthquake: "
                        )
                        + h.link("see the earthquake section", "earthquake")
                        + h.esc(" for a recorded one.")
                    )
                )
            continue
        peak = run.max_abs.get("tip_x_relative")
        name = {"runup": "run-up", "rundown": "run-down"}.get(case, case)
        text = f"The scene's {name} ({model} model): "
        bars = run.uncertainty if isinstance(run, ReducedRun) else None  # the 3D run has none
        if got.captured_at is not None:
            text += (
                f"captured at {_bar(bars, 'captured_at', got.captured_at, 1.0, 'rad/s')} "
                f"below the resonance at {h.num(got.captured_resonance, 4)} rad/s"
            )
        else:
            text += f"ends at {_bar(bars, 'omega_final', got.omega_final, 1.0, 'rad/s')}"
        if got.speed_state == "escaping":
            text += ", still escaping a resonance at the end of the run"
        if isinstance(peak, (int, float)):
            text += f"; largest tip displacement {_bar(bars, 'peak_tip_relative', peak, 1e3, 'mm')}"
        items.append(text + ".")
    if not build.simulations:
        items.append("Transients: " + build.hint(SIMULATE_COMMAND) + ".")
    return items


def section_summary(build: Build) -> str:
    items: list[str | h.Raw]
    if build.analysis:
        items = _analysis_findings(build, build.analysis)
    else:
        items = ["Closed forms and averaging: " + build.hint(INPUTS["analyze"][1]) + "."]
    items += _runs(build)
    for case in COMPARISONS:
        c = build.comparisons.get(case)
        name = {"runup": "run-up", "rundown": "run-down"}.get(case, case)
        if c is None:
            items.append(
                f"The reduced model against the full order on the {name}: not computed: "
                f"run `rotorpillar {comparison_command(case)} {build.scene_cli}`."
            )
        else:
            said = speed_accuracy(c.record, c.models)
            items.append(
                f"The {name}, models compared ({', '.join(c.models)}): "
                + (" ".join(said) if said else "no error against a reference recorded.")
            )
    what = chosen(build.convergence) if build.convergence else None
    if what:
        items.append(f"Model chosen for the scene's band: {what[0]}.")
    return h.section(
        "summary", "Summary", verdict_block(build) + [h.tag("ul", [_item(it) for it in items], class_="findings")]
    )
