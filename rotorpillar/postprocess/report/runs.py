"""The passage through resonance (drive curves, stationary speeds, jumps,
the resonances) and the transient runs (run-up, with the reduced model
against a full-order model; run-down, sweep)."""

from __future__ import annotations

from .. import html as h
from ..comparisons import COMPARISONS
from ..inputs import CASES, INPUTS, SIMULATE_COMMAND
from .comparison import comparison_block
from .parts import failure, figures_of, key_results, product_image, run_table, scene_differs, video
from .state import Build

#: Section titles of the runs other than the earthquake.
RUN_TITLES = {"runup": "Run-up", "rundown": "Run-down", "sweep": "Sweep"}


def _stationary_and_jumps(d) -> list[str]:
    parts = [h.tag("h3", "Stationary speeds and jumps")]
    rows = [[h.num(s.omega), "stable" if s.stable else "unstable", h.num(s.margin)]
            for s in d.stationary]
    parts.append(h.table(["Omega (rad/s)", "stability (Eq. 23)", "d(Md - L)/dOmega (N*m*s)"], rows)
                 if rows else h.tag("p", "No stationary speed."))
    if d.jumps:
        name = {"up": "A->B (run-up)", "down": "D->C (run-down)"}
        rows = [[name.get(j.direction, j.direction), h.num(j.omega_from), h.num(j.omega_to),
                 h.num(j.torque_at_zero), h.num(j.resonance)] for j in d.jumps]
        parts.append(h.table(["jump", "from (rad/s)", "to (rad/s)", "at M0 (N*m)", "resonance"], rows))
    else:
        parts.append(h.tag("p", "No jumps: a quasi-static run-up and run-down pass every resonance "
                                "without the Sommerfeld effect with this drive."))
    parts.append(h.tag("p", f"Run-up ends at {h.num(d.runup_speed)} rad/s, run-down at "
                            f"{h.num(d.rundown_speed)} rad/s"
                            + (f"; captured below resonance {d.captured_index} "
                               f"({h.num(d.captured_resonance)} rad/s) at {h.num(d.captured_at)} rad/s."
                               if d.captured_index is not None else ".")))
    return parts


def section_averaging(build: Build) -> str:
    a = build.analysis
    if a is None:
        return h.section("averaging", "Passage through resonance (averaging)",
                         [h.missing(build.hint(INPUTS["analyze"][1]))])
    parts = scene_differs(build, a)
    d = a.drive
    parts.append(h.tag("p", f"Motor Md = {d.torque_at_zero:g} - {d.slope:g} Omega, load "
                            f"Mc = {d.load_coefficient:g} Omega^2 (Eq. 22)."))
    parts += failure(build, "drive_chart")
    if "drive_chart" in build.products:
        parts.append(product_image(build, "drive_chart"))
    parts.append(h.tag("ul", [h.tag("li", r.statement) for r in a.resonances], class_="findings"))
    parts += _stationary_and_jumps(d)
    parts.append(h.tag("h3", "The resonances"))
    rows = [[r.index, r.direction, h.num(r.omega), h.num(r.modal_mass), h.num(r.forcing),
             h.num(r.two_n), h.num(r.nu), h.num(r.a_max), h.num(r.dL_max),
             h.num(r.dL_max_over_Mc), h.num(r.critical_slope), h.num(r.critical_eccentricity)]
            for r in a.resonances]
    parts.append(h.table(["i", "dir", "omega_i (rad/s)", "I_i (kg)", "f_i (m/s^2)", "2n_i (1/s)", "nu_i",
                          "a_max (m)", "dL_max (N*m)", "dL_max/Mc", "critical slope (N*m*s)",
                          "critical e (m)"], rows))
    parts += failure(build, "amplitude_chart")
    if "amplitude_chart" in build.products:
        parts.append(product_image(build, "amplitude_chart"))
    return h.section("averaging", "Passage through resonance (averaging, Eq. 19-24)", parts)


def section_runs(build: Build) -> str:
    parts = []
    if not any(c in build.simulations for c in CASES if c != "earthquake"):
        parts.append(h.missing(build.hint(SIMULATE_COMMAND)))
    for case in CASES:
        if case == "earthquake":
            continue
        sim = build.simulations.get(case)
        parts.append(h.tag("h3", RUN_TITLES[case]))
        if case in COMPARISONS:
            parts.append(h.tag("h4", f"{RUN_TITLES[case]}: the reduced model against a full-order model"))
            parts += comparison_block(build, case)
            parts.append(h.tag("h4", f"{RUN_TITLES[case]}: the scene's own run (simulate_{case}.json)"))
        if sim is None:
            parts.append(h.missing(f"not computed: run `rotorpillar {SIMULATE_COMMAND} --case {case} "
                                   f"{build.scene_cli}` (no simulate_{case}.json)"))
            continue
        parts += scene_differs(build, sim.meta)
        key = key_results(sim.meta)
        if key:
            parts.append(key)
        parts.append(h.details(f"simulate_{case}.json: results, energy balance, integrator",
                               run_table(sim.meta)) if sim.meta
                     else h.tag("p", "no JSON summary", class_="meta"))
        for p in build.products.get("external", []):
            if p.group == "runs" and case in p.path.name.lower():
                parts.append(h.image(p.path, p.caption))
                p.group = "used"
        parts += failure(build, f"animation_{case}")
        parts += video(build, f"animation_{case}")
    parts += figures_of(build, "runs")
    return h.section("runs", "The runs", parts)
