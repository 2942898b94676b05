"""The passage through resonance (drive curves, stationary speeds, jumps,
the resonances) and the transient runs (run-up, with the reduced model
against a full-order model; run-down, sweep)."""

from __future__ import annotations

from ...transients.compare import COMPARISONS
from .. import html as h
from ..directions import direction
from ..readers import CASES, INPUTS, SIMULATE_COMMAND
from .compare_section import comparison_block
from .models import model_views, resonance_table
from .page import model_name
from .parts import animation_video, failure, figures_of, key_results, product_image, scene_differs
from .passage import passage_block
from .state import Build

#: Section titles of the runs other than the earthquake.
RUN_TITLES = {"runup": "Run-up", "rundown": "Run-down", "sweep": "Sweep"}


def _stationary_and_jumps(d) -> list[str]:
    parts = [h.tag("h3", "Stationary speeds and jumps")]
    rows = [[h.num(s.omega), "stable" if s.stable else "unstable", h.num(s.margin)] for s in d.stationary]
    parts.append(
        h.table(["Omega (rad/s)", "stability (Eq. 23)", "d(Md - L)/dOmega (N*m*s)"], rows)
        if rows
        else h.tag("p", "No stationary speed.")
    )
    if d.jumps:
        name = {"up": "A->B (run-up)", "down": "D->C (run-down)"}
        rows = [
            [
                name.get(j.direction, j.direction),
                h.num(j.omega_from),
                h.num(j.omega_to),
                h.num(j.torque_at_zero),
                h.num(j.resonance),
            ]
            for j in d.jumps
        ]
        parts.append(h.table(["jump", "from (rad/s)", "to (rad/s)", "at M0 (N*m)", "resonance"], rows))
    else:
        parts.append(
            h.tag(
                "p",
                "No jumps: a quasi-static run-up and run-down pass every resonance "
                "without the Sommerfeld effect with this drive.",
            )
        )
    # quasi-static: M0 raised (or lowered) slowly, as in the paper's Figs. 3-4; not the
    # scene's run-down, whose motor may be switched off
    said = f"A quasi-static run-up (M0 raised slowly) settles at {h.num(d.runup_speed)} rad/s"
    if d.rundown_speed is not None and d.rundown_speed != d.runup_speed:
        said += f"; a quasi-static run-down (M0 lowered slowly from above) at {h.num(d.rundown_speed)} rad/s"
    captured = getattr(d, "captured_index", None)
    parts.append(
        h.tag(
            "p",
            said
            + (
                f"; captured below resonance {captured} "
                f"({h.num(d.captured_resonance)} rad/s) at "
                f"{h.num(d.captured_at)} rad/s."
                if captured is not None
                else "."
            ),
        )
    )
    return parts


def _resonance_rows(resonances) -> str:
    rows = [
        [
            r.index,
            direction(r.direction),
            h.num(r.omega),
            h.num(r.modal_mass),
            h.num(r.forcing),
            h.num(r.two_n),
            h.num(r.nu),
            h.num(r.a_max),
            h.num(r.dL_max),
            h.num(r.dL_max_over_Mc),
            h.num(r.critical_slope),
            h.num(r.critical_eccentricity),
        ]
        for r in resonances
    ]
    return h.table(
        [
            "i",
            "direction",
            "omega_i, undamped (rad/s)",
            "I_i (kg)",
            "f_i (m/s^2)",
            "2n_i (1/s)",
            "nu_i (-)",
            "a_max (m)",
            "dL_max (N*m)",
            "dL_max/Mc (-)",
            "critical slope (N*m*s)",
            "critical e (m)",
        ],
        rows,
    )


def section_averaging(build: Build) -> str:
    a = build.analysis
    if a is None:
        return h.section(
            "averaging", "Passage through resonance (averaging)", [h.missing(build.hint(INPUTS["analyze"][1]))]
        )
    parts = scene_differs(build, build.provenance.analyze)
    views = model_views(a)
    d = a.drive
    parts.append(
        h.tag(
            "p",
            f"On {views[0].title}. Motor Md = {d.torque_at_zero:g} - {d.slope:g} "
            f"Omega, load Mc = {d.load_coefficient:g} Omega^2 (Eq. 22).",
        )
    )
    # where the numbers below are the paper's formulation's rather than this machine's (analyze's warnings)
    parts += [h.tag("p", f"Warning: {w}", class_="warn") for w in a.warnings]
    parts.append(resonance_table(views))
    parts += failure(build, "drive_chart")
    if "drive_chart" in build.products:
        parts.append(product_image(build, "drive_chart"))
    parts.append(h.tag("ul", [h.tag("li", r.statement) for r in a.resonances], class_="findings"))
    parts += _stationary_and_jumps(d)
    parts.append(h.tag("h3", "The resonances"))
    for v in views:
        table = _resonance_rows(v.resonances)
        parts.append(
            h.tag("p", f"On {v.title}:", class_="meta") if v.headline else h.details(f"the same on {v.title}", table)
        )
        if v.headline:
            parts.append(table)
    parts += failure(build, "amplitude_chart")
    if "amplitude_chart" in build.products:
        parts.append(product_image(build, "amplitude_chart"))
    return h.section("averaging", "Passage through resonance (averaging, Eq. 19-24)", parts)


def _own_charts(build: Build, case: str) -> list[str]:
    """The charts of the case's runs other commands drew (simulate's), each picture
    once (the generic simulate_<case>.png is a copy of the model's:
    figures.external_figures dropped the copy)."""
    out = []
    for p in build.external:
        if p.group == "runs" and p.case == case:
            out.append(h.image(p.path, p.caption))
            p.group = "used"
    return out


def section_runs(build: Build) -> str:
    parts = []
    if not any(c in build.simulations for c in CASES if c != "earthquake"):
        parts.append(h.missing(build.hint(SIMULATE_COMMAND)))
    not_run = []
    for case in CASES:
        if case == "earthquake":
            continue
        sim = build.simulations.get(case)
        if sim is None and case not in COMPARISONS:  # not what the main job runs
            not_run.append(case)
            continue
        parts.append(h.tag("h3", RUN_TITLES[case]))
        if case in COMPARISONS:
            parts.append(h.tag("h4", f"{RUN_TITLES[case]}: the reduced model against a full-order model"))
            parts += comparison_block(build, case)
        if case == "runup":
            block = passage_block(build)
            if block:
                parts.append(h.tag("h4", "The passage through the resonances"))
                parts += block
        if sim is None:
            continue
        model = sim.run.model if sim.run is not None else "?"
        run = sim.run
        span = f", {h.num(run.duration, 3)} s" if run is not None and run.duration else ""
        start = " from rest" if case == "runup" and run is not None and not run.initial_speed else ""
        parts.append(h.tag("h4", f"{RUN_TITLES[case]}{start}{span}: the scene's own run ({model_name(model)})"))
        parts += scene_differs(build, sim.provenance)
        if sim.run is not None:
            parts.append(key_results(sim.run))
        parts += _own_charts(build, case)
        parts += failure(build, f"animation_{case}")
        parts += animation_video(build, f"animation_{case}")
    if not_run and build.simulations:
        said = ["Not run by this job: "]
        for k, case in enumerate(not_run):
            said += (["; "] if k else []) + [
                RUN_TITLES[case].lower(),
                " (",
                h.tag("code", f"rotorpillar {SIMULATE_COMMAND} --case {case} {build.scene_cli}"),
                ")",
            ]
        parts.append(h.tag("p", said + ["."], class_="meta"))
    parts += figures_of(build, "runs")
    return h.section("runs", "The runs", parts)
