"""The page's first section: the findings in a few sentences, each input
that is missing named with the command that makes it."""

from __future__ import annotations

from .. import html as h
from ..comparisons import COMPARISONS, compare_command
from ..inputs import CASES, INPUTS, SIMULATE_COMMAND
from .comparison import speed_accuracy
from .convergence import chosen
from .modal import bending, is_finding
from .state import Build


def _analysis_findings(build: Build) -> list[str]:
    a, m = build.analysis, build.modal
    p = a.pillar
    text = (f"First bending mode of the bare tube: Eq. 1 gives {p.omega_col1:.3f} rad/s "
            f"({p.frequency_col1_hz:.3f} Hz); Timoshenko {h.pct(p.timoshenko_correction)}")
    bx = bending(m.modes, "bending_x") if m is not None else []
    if bx:
        w = bx[0].omega
        text += f"; the 3D model {w:.3f} rad/s ({w / p.omega_col1 - 1:+.2%} against Eq. 1)."
    else:
        text += "; the 3D model: " + build.hint(INPUTS["modal"][1]) + "."
    items = [text]
    s, pm = a.system, a.pillar_model
    items.append(f"Pillar model (the chain): {pm.describe()}.")
    bars = [res.uncertainty.omega.text(".3f") if res.uncertainty else f"{res.omega:.3f} rad/s"
            for res in a.resonances]
    items.append("Headline model, the ROM (" + f"{s.modes} pillar mode(s) of {s.mode_source} with "
                 "the rotor on its shaft): resonances " + ", ".join(
                     f"{b} ({res.direction})" for b, res in zip(bars, a.resonances))
                 + f"; error bars: {s.error_note}.")
    ps, r = a.paper_model.system, a.paper_model.reduction
    items.append(f"The paper's model (Eq. 4 with m_r = {r.tip_mass:.4g} kg from {r.tip_mass_source}, "
                 f"c1 = {r.tip_stiffness:.4g} N/m from {r.tip_stiffness_source}): omega_1 = "
                 f"{ps.omega[0]:.3f}, omega_2 = {ps.omega[1]:.3f} rad/s (X), omega_3 = "
                 f"{ps.omega3:.3f} rad/s (Y); shown beside the headline model, never instead of it.")
    rows = [x for x in a.paper_comparison if not is_finding(x)]
    items.append(f"{sum(1 for x in rows if x.flag)} of the {len(rows)} numbers the paper prints "
                 "differ from ours by more than 2 %; each has its likely cause below.")
    for x in a.paper_comparison:
        if is_finding(x):
            items.append(f"Finding {x.key} ({x.where}): {x.note}")
    d = a.drive
    st = ", ".join(f"{x.omega:.2f} rad/s ({'stable' if x.stable else 'unstable'})"
                   for x in d.stationary) or "none"
    items.append(f"Stationary speed(s) with the scene's motor: {st}. "
                 + (f"{len(d.jumps)} jump(s) in a quasi-static run-up/run-down."
                    if d.jumps else "No jumps (no Sommerfeld effect) with this drive."))
    items += [res.statement for res in a.resonances]
    return items


def _item(text: str) -> str:
    """A list item, its "not computed: run `...`" command set as code."""
    if "not computed: run `" in text:
        pre, rest = text.split("not computed: run `", 1)
        cmd, post = rest.split("`", 1)
        return h.tag("li", [pre, "not computed: run ", h.tag("code", cmd), post])
    return h.tag("li", text)


def section_summary(build: Build) -> str:
    if build.analysis:
        items = _analysis_findings(build)
    else:
        items = ["Closed forms and averaging: " + build.hint(INPUTS["analyze"][1]) + "."]
    for case in CASES:
        sim = build.simulations.get(case)
        if sim is not None and sim.meta:
            wf = sim.meta.get("omega_final")
            items.append(f"Run {case}: final speed {h.num(wf, 4)} rad/s"
                         + (f", captured at {h.num(sim.meta['captured_at'], 4)} rad/s below the "
                            f"resonance at {h.num(sim.meta.get('captured_resonance'), 4)} rad/s"
                            if sim.meta.get("captured_at") is not None else "")
                         + (", still escaping a resonance at the end of the run"
                            if sim.meta.get("speed_state") == "escaping" else "") + ".")
    if not build.simulations:
        items.append("Transients: " + build.hint(SIMULATE_COMMAND) + ".")
    for case in COMPARISONS:
        c = build.comparisons.get(case)
        if c is None:
            items.append(f"The reduced model against the full order on the {case}: not computed: "
                         f"run `rotorpillar {compare_command(case)} {build.scene_cli}`.")
        else:
            said = speed_accuracy(c.doc, c.models)
            items.append(f"The {case}, models compared ({', '.join(c.models)}): "
                         + (" ".join(said) if said else "no error against a reference recorded."))
    what = chosen(build.convergence) if build.convergence else None
    if what:
        items.append(f"Model chosen: {what[0]}" + (f" - {what[1]}" if what[1] else "") + ".")
    return h.section("summary", "Summary", [h.tag("ul", [_item(it) for it in items],
                                                  class_="findings")])
