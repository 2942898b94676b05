"""The report's own pictures: the analysis charts, the earthquake chart, the
mode shapes and the animations, each step recorded and allowed to fail."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from ..comparisons import relative_to_ground
from ..inputs import INPUTS, ModeSet, entries, plain
from .state import ANIMATIONS_DIR, FIGURES_DIR, MODES_DIR, Build, Product, attempt, say

#: The runs that get an animation.
ANIMATED = ("runup", "earthquake")


def render_charts(build: Build) -> None:
    from .. import charts, transient_charts
    fig = build.out / FIGURES_DIR
    if build.analysis is not None:
        p = attempt(build, "drive_chart",
                    lambda: charts.drive_chart(build.analysis, fig / "drive_resistance.png"))
        if p:
            build.products["drive_chart"] = Product(p, (
                "Motor torque Md and total resistance L = Mc + sum dL_i against the speed "
                "(the paper's Figs. 3-4). L is solid where a stationary regime there is stable "
                "(d(Md - L)/dOmega < 0, Eq. 23) and dashed where it is not; jumps A->B (run-up) and "
                "D->C (run-down) are drawn on the motor lines through them. Below: near each "
                "resonance, against z = Omega/omega_i, with L - Mc on the right axis; dots are the "
                "curves stored in analyze.json."))
        p = attempt(build, "amplitude_chart",
                    lambda: charts.amplitude_chart(build.analysis, fig / "resonance_amplitudes.png"))
        if p:
            build.products["amplitude_chart"] = Product(p, (
                "Amplitude a_i of each quasi-normal coordinate near its resonance: the averaging "
                "result (Eq. 19 with omega_i**2 restored) against the exact steady state of the "
                "linear mode at constant speed."))
    quake = build.quake_case
    if quake is not None and quake.arrays.get("t") is not None:
        # relative to the ground: under the paper's pulse the absolute tip is
        # the ground's 6 m step and hides the pillar's response
        frame = str(quake.meta.get("tip_x_frame") or "")
        tip = relative_to_ground(quake.arrays, "tip_x", frame)
        rotor = relative_to_ground(quake.arrays, "rotor_x", frame)
        model = quake.meta.get("model", "model not stated")
        p = attempt(build, "earthquake_chart", lambda: transient_charts.earthquake_chart(
            fig / "earthquake_response.png", quake.get("t"), quake.get("ground_acceleration"),
            tip, rotor, quake.get("Omega"), title=f"Earthquake response ({model} model)",
            frame="relative to the ground"))
        if p:
            build.products["earthquake_chart"] = Product(p, (
                f"Earthquake on the {model} model: ground acceleration (the shaded interval is "
                "when the ground moves), the X displacement of the pillar's tip and of the rotor "
                "relative to the ground, and the rotor speed."))


def render_comparisons(build: Build) -> None:
    """Each comparison's tip histories overlaid with their differences, and
    the record's response spectrum."""
    from .. import comparison_charts as cc
    fig = build.out / FIGURES_DIR
    for case, c in build.comparisons.items():
        series = [(m, *s) for m in c.models for s in [c.tip_relative(m)] if s is not None]
        if not series:
            continue
        ref = c.reference or series[0][0]
        p = attempt(build, f"comparison_{case}", lambda c=c, case=case, series=series, ref=ref:
                    cc.comparison_chart(fig / f"comparison_{case}.png", series, ref,
                                        title=f"{case}: {', '.join(m for m, _, _ in series)}"))
        if p:
            lacking = [m for m in c.models if m not in {s[0] for s in series}]
            build.products[f"comparison_{case}"] = Product(p, (
                f"The {case} on each model: the pillar tip's X relative to the ground, overlaid "
                f"(the reference, {ref}, solid); below, each model minus {ref}."
                + (f" No arrays for {', '.join(lacking)}." if lacking else "")))
    c = build.comparisons.get("earthquake")
    spec = c.doc.get("spectrum") if c is not None else None
    if isinstance(spec, dict) and spec.get("period") is not None and spec.get("psa") is not None:
        damping = spec.get("damping", spec.get("damping_ratio", 0.05))
        p = attempt(build, "response_spectrum", lambda: cc.spectrum_chart(
            fig / "response_spectrum.png", spec["period"], spec["psa"],
            spec.get("mode_periods") or (), damping,
            title=f"Response spectrum of the record ({_record_name(c.doc)})"))
        if p:
            build.products["response_spectrum"] = Product(p, (
                f"Pseudo-acceleration response spectrum of the record ({_record_name(c.doc)}, "
                f"{100 * float(damping):g} % damping, eqsig), the pillar's modal periods marked "
                "(dashed)."))


def _record_name(doc: dict) -> str:
    ex = doc.get("excitation") or {}
    return str(ex.get("name") or ex.get("record") or ex.get("kind") or "the scene's excitation")


def mode_sets(build: Build) -> dict[str, ModeSet | None]:
    """The bare and the topped tube's mode shapes, where modal.json and its VTU exist."""
    from ..inputs import load_modes
    sets = {}
    m = build.modal
    for name, key in (("bare", "modes"), ("top", "modes_with_top")):
        vtu = build.out / INPUTS[f"modes_{name}"][0]
        if m is not None and vtu.is_file():
            modes = plain(getattr(m, key, None)) or []
            axes = dict(entries(getattr(m, "axes", None))) or None
            sets[name] = attempt(build, f"load_modes_{name}",
                                 lambda vtu=vtu, modes=modes, axes=axes: load_modes(vtu, modes, axes))
        else:
            sets[name] = None
    return sets


def render_modes(build: Build, sets: dict) -> None:
    from ..inputs import mode_label
    from ..modeshapes import render_modes as render
    captions = {"bare": "the bare tube (clamped base, free top)",
                "top": "the tube with the gondola and rotor at its top"}
    for name, ms in sets.items():
        if ms is None:
            continue
        say(f"mode shapes of {captions[name]}")
        r = attempt(build, f"modes_{name}",
                    lambda ms=ms, name=name: render(ms, build.out / MODES_DIR, name,
                                                    build.options.modes))
        if r:
            build.products[f"modes_{name}"] = [
                Product(p, mode_label(ms.modes[i], i), group=name) for i, p in enumerate(r["modes"])]
            build.products[f"sheet_{name}"] = Product(r["sheet"], (
                f"The first {len(r['modes'])} modes of {captions[name]} (3D model, {Path(ms.source).name}): "
                "deformed shape coloured by |u| / max |u| over the undeformed outline; the scale "
                "factor is on each view."), group=name)


def render_animations(build: Build, sets: dict) -> None:
    from ..animation import animate
    from ..inputs import cantilever_tube
    top = sets.get("top")
    for case in ANIMATED:
        sim = build.simulations.get(case)
        if sim is None or sim.arrays.get("t") is None:
            continue
        if top is None and "fallback_tube" not in build.products:
            p = build.scene.pillar
            build.products["fallback_tube"] = cantilever_tube(p.height, p.outer_diameter,
                                                              p.inner_diameter)
        ms = top if top is not None else build.products["fallback_tube"]
        say(f"animation of the {case} ({build.options.max_frames} frames at most)")
        title = {"runup": "Run-up", "earthquake": "Earthquake"}.get(case, case)
        r = attempt(build, f"animation_{case}", lambda sim=sim, ms=ms, title=title, case=case: animate(
            sim, ms, build.out / ANIMATIONS_DIR / f"{case}.mp4", title=f"{title}: {build.scene.name}",
            max_frames=build.options.max_frames,
            poster=build.out / ANIMATIONS_DIR / f"{case}_poster.png"))
        if r:
            build.products[f"animation_{case}"] = Product(r.path, (
                f"{title}: the pillar deformed by {r.source}; elastic deflection and the rotor's "
                f"orbit exaggerated x{r.factor:g}"
                + ("; ground motion at true scale" if case == "earthquake" else "")
                + f". {r.frames} frames at {r.fps} frames/s sampling the run uniformly "
                "(stroboscopic: the pillar's vibration at the rotor speed aliases; the orbit "
                f"trail uses every stored sample). {r.writer}."), kind="video", poster=r.poster)
            build.products[f"animation_{case}_info"] = dataclasses.asdict(r)
