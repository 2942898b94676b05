"""The earthquake run: its excitation, the chart, the animation, its numbers."""

from __future__ import annotations

from .. import html as h
from ..inputs import SIMULATE_COMMAND
from .parts import failure, figures_of, key_results, product_image, run_table, scene_differs, video
from .state import Build


def section_earthquake(build: Build) -> str:
    sim = build.simulations.get("earthquake")
    if sim is None:
        return h.section("earthquake", "The earthquake",
                         [h.missing(f"not computed: run `rotorpillar {SIMULATE_COMMAND} --case earthquake "
                                    f"{build.scene_cli}` (no simulate_earthquake.json)")]
                         + figures_of(build, "earthquake"))
    parts = scene_differs(build, sim.meta)
    g = sim.get("ground_x")
    excitation = (sim.meta or {}).get("excitation") or {}
    if isinstance(excitation.get("statement"), str):
        parts.append(h.tag("p", excitation["statement"],
                           class_="warn" if excitation.get("realistic") is False else None))
    if g is not None and len(g):
        parts.append(h.tag("p", f"Largest ground displacement: {abs(g).max():.3g} m."))
    parts += failure(build, "earthquake_chart")
    if "earthquake_chart" in build.products:
        parts.append(product_image(build, "earthquake_chart"))
    parts += figures_of(build, "earthquake")
    parts += failure(build, "animation_earthquake")
    parts += video(build, "animation_earthquake")
    if sim.meta:
        key = key_results(sim.meta)
        if key:
            parts.append(key)
        parts.append(h.details("simulate_earthquake.json", run_table(sim.meta)))
    return h.section("earthquake", "The earthquake", parts)
