"""The earthquake: first a real record on the physically consistent models
(the ROM and the 3D full order overlaid, their error and cost, the record's
response spectrum), then the paper's case (its pulse on Eq. 4 as
published), its excitation's size and the base-forcing flaw stated."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...reduced.excitation import PulseSizes, RecordSizes
from ...transients.compare import comparison_models
from .. import html as h
from ..directions import direction
from ..readers import INPUTS, SIMULATE_COMMAND, Simulation
from .compare_section import comparison_block, spectrum_block
from .page import model_name
from .parts import animation_video, failure, figures_of, key_results, product_image, scene_differs
from .references import pareto_block
from .state import Build

if TYPE_CHECKING:
    from ...transients.model_run import RunRecord

#: Standard gravity, to state accelerations in g (m/s**2).
STANDARD_GRAVITY = 9.80665
#: The paper comparison's row on Eq. 4's base forcing (analysis/paper.py).
BASE_FORCING_KEY = "eq4_base_forcing"


def base_forcing_finding(analysis):
    """The ``eq4_base_forcing`` row of analyze.json's paper comparison, or None."""
    for r in getattr(analysis, "paper_comparison", None) or []:
        if getattr(r, "key", None) == BASE_FORCING_KEY:
            return r
    return None


def _size(sim: Simulation) -> str:
    """How large the run's ground motion is: from its excitation block, else its arrays."""
    ex = sim.excitation
    g, a = sim.arrays.ground_x, sim.arrays.ground_acceleration
    said = []
    if isinstance(ex, PulseSizes):
        said.append(f"the ground steps {abs(ex.displacement_step_at_start):.3g} m at t = {h.num(ex.start, 4)} s")
    if isinstance(ex, (PulseSizes, RecordSizes)):
        said.append(f"its acceleration reaches {ex.peak_acceleration_g:.3g} g")
    elif a is not None and len(a):
        said.append(f"its acceleration reaches {np.abs(a).max() / STANDARD_GRAVITY:.3g} g")
    if g is not None and len(g):
        said.append(f"largest ground displacement {np.abs(g).max():.3g} m")
    return ("Size of the excitation: " + ", ".join(said) + ".") if said else ""


def _tip(sim: Simulation) -> str:
    """The largest tip displacement relative to the ground, beside the absolute one."""
    frame = sim.run.tip_x_frame if sim.run is not None else None
    rel = sim.arrays.tip_to_ground(frame)
    if rel is None or not len(rel):
        return ""
    text = f" Largest tip displacement relative to the ground: {h.num(float(np.abs(rel).max()), 4)} m"
    absolute = sim.arrays.tip_x_absolute
    if absolute is None and not str(frame or "").startswith("relative"):
        absolute = sim.arrays.tip_x
    if absolute is not None and len(absolute):
        text += f" (absolute, the ground's motion included: {h.num(float(np.abs(absolute).max()), 4)} m)"
    return text + "."


def _flaw(build: Build) -> list[str]:
    """Eq. 4's published base forcing, in one sentence with a link to
    the finding (stated once, in the paper's section)."""
    if build.analysis is None:
        return [h.missing("the base-forcing finding is " + build.hint(INPUTS["analyze"][1]) + " (no analyze.json)")]
    r = base_forcing_finding(build.analysis)
    if r is None:
        return [
            h.tag(
                "p",
                f"analyze.json has no {BASE_FORCING_KEY} finding (an older rotorpillar wrote it): re-run analyze.",
                class_="meta",
            )
        ]
    gain = r.paper
    return [
        h.tag(
            "p",
            [
                h.tag("strong", "The base-forcing flaw: "),
                f"Eq. 4 as published forces the rotor's shaft from the ground as well as "
                f"the pillar: under a slow ground displacement it moves the tip "
                f"{h.num(gain, 3)} times as far as the ground (the consistent forcing: 1). ",
                h.link("The finding", "paper-findings"),
                " states it in full.",
            ],
            class_="warn",
        )
    ]


def _warnings(run: RunRecord, name: str) -> list[str]:
    w = run.warnings
    if not w:
        return [h.tag("p", f"{name}: simulate raised no warning.", class_="meta")]
    return [
        h.tag("p", f"{name}: simulate warned:", class_="warn"),
        h.tag("ul", [h.tag("li", str(x)) for x in w], class_="warn"),
    ]


def _simulate_charts(build: Build, model: str | None):
    """simulate's own PNG of the paper's case (simulate_earthquake_<model>.png,
    else simulate_earthquake.png), taken out of the earthquake group with its
    copy: one picture of one run."""
    names = ["simulate_earthquake.png"] + ([f"simulate_earthquake_{model}.png"] if model else [])
    found = {p.path.name: p for p in build.external if p.path.name in names}
    for p in found.values():
        p.group = "used"
    return found.get(names[-1]) or found.get(names[0])


def paper_case(build: Build) -> list[str]:
    """The paper's pulse on Eq. 4 as published (``simulate --case earthquake``)."""
    sim = build.quake_case
    if sim is None:
        return [
            h.missing(
                f"not computed: run `rotorpillar {SIMULATE_COMMAND} --case earthquake "
                f"--model paper {build.scene_cli}` (no simulate_earthquake.json)"
            )
        ] + _flaw(build)
    run = sim.run
    model = run.model if run is not None else "model not stated"
    name = f"simulate_earthquake_{model}.json" if run is not None and run.model else "simulate_earthquake.json"
    ex = sim.excitation
    kind = ex.kind if ex is not None else "excitation not stated"
    what = (
        "The paper's pulse on Eq. 4 as published"
        if model == "paper" and kind == "pulse"
        else f"The scene's earthquake run ({model} model, {kind})"
    )
    parts = scene_differs(build, sim.provenance)
    parts.append(h.tag("p", what + ". " + _size(sim) + _tip(sim)))
    if isinstance(ex, (PulseSizes, RecordSizes)) and ex.statement is not None:
        parts.append(h.tag("p", ex.statement, class_="warn" if not ex.realistic else None))
    if model == "paper":
        parts += _flaw(build)
    if run is not None:
        parts += _warnings(run, name)
    parts += failure(build, "earthquake_chart")
    theirs = _simulate_charts(build, run.model if run is not None else None)
    if "earthquake_chart" in build.products:  # simulate's own is the same run: left out
        parts.append(product_image(build, "earthquake_chart"))
    elif theirs:
        parts.append(h.image(theirs.path, theirs.caption))
    parts += figures_of(build, "earthquake")
    mine = build.quake_case_animation or "animation_earthquake_paper"
    parts += failure(build, mine)
    parts += animation_video(build, mine)
    if run is not None:
        parts.append(key_results(run))
    return parts


def section_earthquake(build: Build) -> str:
    """A recorded earthquake on the physically consistent models, and the record's spectrum."""
    c = build.comparisons.get("earthquake")
    models = c.models if c is not None else comparison_models("earthquake")
    parts = [
        h.tag(
            "p",
            f"The models ({', '.join(model_name(m) for m in models)}) force the structure by the "
            "ground's inertia (-M r a_g), the ground moving "
            f"{direction('X')} (why: see the response spectrum below), and report "
            "the tip relative to the ground; the most complete one run is the "
            "reference.",
            class_="meta",
        ),
    ]
    parts += comparison_block(build, "earthquake")
    if build.quake_case_animation != "animation_earthquake":
        parts += failure(build, "animation_earthquake")
        parts += animation_video(build, "animation_earthquake")
    parts.append(h.tag("h3", "Response spectrum of the record"))
    parts += spectrum_block(build)
    return h.section("earthquake", "The recorded earthquake", parts)


def section_fronts(build: Build) -> str:
    """Every model on the record: wall time against the error."""
    return h.section("fronts", "Speed against accuracy", pareto_block(build))


def section_paper_earthquake(build: Build) -> str:
    """The paper's own earthquake case, its warning first."""
    return h.section("paper-earthquake", "The paper's earthquake case", paper_case(build))
