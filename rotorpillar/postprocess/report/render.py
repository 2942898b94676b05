"""The report's own pictures: the analysis charts, the earthquake chart, the
mode shapes and the animations, each step recorded and allowed to fail."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ...reduced.excitation import ExcitationSizes, PulseSizes, RecordSizes
from ..directions import direction
from ..readers import INPUTS, Simulation
from .page import model_name
from .parallel import ModeFiles
from .state import ANIMATIONS_DIR, FIGURES_DIR, MODES_DIR, Build, Product, debugging, say

if TYPE_CHECKING:
    from ..modeshapes import ModePictures

#: The animations the report makes (:func:`animated_runs`).
ANIMATED = ("runup", "earthquake", "earthquake_paper", "earthquake_scene")


def render_charts(build: Build) -> None:
    from .. import charts, transient_charts
    from . import kept

    fig = build.out / FIGURES_DIR
    analysis = build.analysis
    if analysis is not None:
        png = fig / "drive_resistance.png"
        p = kept.chart(build, "drive_chart", png, charts.drive_chart, analysis, png)
        if p:
            build.products["drive_chart"] = Product(
                p,
                (
                    "Motor torque Md and total resistance L = Mc + sum dL_i against the speed "
                    "(the paper's Figs. 3-4). L is solid where a stationary regime there is stable "
                    "(d(Md - L)/dOmega < 0, Eq. 23) and dashed where it is not; jumps A->B (run-up) and "
                    "D->C (run-down) are drawn on the motor lines through them. Below: near each "
                    "resonance, against z = Omega/omega_i, with L - Mc on the right axis; dots are the "
                    "curves stored in analyze.json."
                ),
            )
        png = fig / "resonance_amplitudes.png"
        p = kept.chart(build, "amplitude_chart", png, charts.amplitude_chart, analysis, png)
        if p:
            build.products["amplitude_chart"] = Product(
                p,
                (
                    "Amplitude a_i of each quasi-normal coordinate near its resonance: the averaging "
                    "result (Eq. 19 with omega_i**2 restored) against the exact steady state of the "
                    "linear mode at constant speed."
                ),
            )
    quake = build.quake_case
    if quake is not None and quake.arrays.t is not None:
        # relative to the ground: under the paper's pulse the absolute tip is
        # the ground's 6 m step and hides the pillar's response
        run = quake.run
        frame = run.tip_x_frame if run is not None else ""
        tip = quake.arrays.tip_to_ground(frame)
        rotor = quake.arrays.rotor_to_ground(frame)
        model = run.model if run is not None else "model not stated"
        ex = quake.excitation
        unreal = isinstance(ex, (PulseSizes, RecordSizes)) and not ex.realistic
        what = ": the paper's pulse as written, not a realistic earthquake" if unreal else ""
        p = kept.chart(
            build,
            "earthquake_chart",
            fig / "earthquake_response.png",
            transient_charts.earthquake_chart,
            fig / "earthquake_response.png",
            quake.arrays.t,
            quake.arrays.ground_acceleration,
            tip,
            rotor,
            quake.arrays.Omega,
            title=f"Earthquake response ({model} model){what}",
            frame="relative to the ground",
        )
        if p:
            build.products["earthquake_chart"] = Product(
                p,
                (
                    f"Earthquake on the {model} model: ground acceleration (the shaded interval is "
                    "when the ground moves), the X displacement of the pillar's tip and of the rotor "
                    "relative to the ground, and the rotor speed."
                ),
            )


def render_comparisons(build: Build) -> None:
    """Each comparison's tip histories overlaid with their differences, and
    the record's response spectrum."""
    from .. import compare_charts as cc
    from . import kept

    fig = build.out / FIGURES_DIR
    for case, c in build.comparisons.items():
        series = [(m, *s) for m in c.models for s in [c.tip_relative(m)] if s is not None]
        if not series:
            continue
        ref = c.reference or series[0][0]
        zoom = passage_of(c, ref) if case != "earthquake" else None
        p = kept.chart(
            build,
            f"comparison_{case}",
            fig / f"comparison_{case}.png",
            cc.comparison_chart,
            fig / f"comparison_{case}.png",
            series,
            ref,
            zoom=zoom,
            title=f"{CASE_TITLES.get(case, case)}: {', '.join(m for m, _, _ in series)}",
        )
        if p:
            lacking = [m for m in c.models if m not in {s[0] for s in series}]
            build.products[f"comparison_{case}"] = Product(
                p,
                (
                    f"The {CASE_TITLES.get(case, case).lower()} on each model: the pillar tip's "
                    f"displacement {direction('X')}, relative to the ground, overlaid (the reference, "
                    f"{ref}, solid); below, each model minus {ref}."
                    + (
                        f" Right: zoomed on the passage through the resonances, {zoom[0]:.3g} .. "
                        f"{zoom[1]:.3g} s of the {c.record.window.end:g} s run."
                        if zoom
                        else ""
                    )
                    + (f" No arrays for {', '.join(lacking)}." if lacking else "")
                ),
            )
    quake = build.comparisons.get("earthquake")
    spec = quake.record.spectrum if quake is not None else None
    if quake is not None and spec is not None:
        c = quake
        damping = spec.damping
        # the modes of the estimate (the coupled rotor-pillar modes in X), each marked at its
        # own damping: its pseudo-acceleration omega**2 S_d(T, zeta), not the drawn curve's
        marks: list = [
            (f"mode {m.mode}, {100 * m.damping_ratio:.3g} % damping", m.period, m.s_d * (2 * math.pi / m.period) ** 2)
            for m in spec.modes
        ]
        what = (
            f"the coupled rotor-pillar modes of the {model_name('modal')} in the record's direction "
            "(horizontal, in the rotor's plane), each at its pseudo-acceleration for its own damping ratio"
        )
        p = kept.chart(
            build,
            "response_spectrum",
            fig / "response_spectrum.png",
            cc.spectrum_chart,
            fig / "response_spectrum.png",
            spec.period,
            spec.psa,
            marks,
            damping,
            title=f"Response spectrum of the record ({_record_name(c.record.excitation)})",
        )
        if p:
            build.products["response_spectrum"] = Product(
                p,
                (
                    f"Pseudo-acceleration response spectrum of the record ({_record_name(c.record.excitation)}, "
                    f"the curve at {100 * float(damping):g} % damping, eqsig); marked, with their values: {what} "
                    "(a point off the curve where a mode's damping differs from the curve's)."
                ),
            )


#: How the report names a case.
CASE_TITLES = {"runup": "Run-up", "rundown": "Run-down", "sweep": "Sweep", "earthquake": "Earthquake"}


def passage_of(c, model: str):
    """The window around the passage through the resonances of ``model``'s
    run in comparison ``c`` (its speed and its JSON's resonances), or None."""
    from ..transient_charts import crossings, passage_window

    a, run = c.arrays_of(model), c.runs.get(model)
    if a.t is None or a.Omega is None:
        return None
    res = [(f"omega_{r.index}", float(r.omega)) for r in (run.resonances if run is not None else ())]
    return passage_window(a.t, crossings(a.t, a.Omega, res))


def _record_name(ex: ExcitationSizes | None) -> str:
    """The ground motion a comparison ran on, by its name (a record's) or its kind."""
    if isinstance(ex, RecordSizes) and ex.name:
        return ex.name
    return ex.kind if ex is not None else "the scene's excitation"


def mode_files(build: Build) -> list[tuple[str, ModeFiles]]:
    """The bare ("bare") and the topped tube's ("top") mode shapes, where modal.json and
    its VTU exist (read by the job that draws them: :mod:`.parallel`)."""
    m = build.modal
    if m is None:
        return []
    out = []
    for name, key in (("bare", "modes"), ("top", "modes_with_top")):
        vtu = build.out / INPUTS[f"modes_{name}"][0]
        if vtu.is_file():
            out.append((name, ModeFiles(vtu, list(getattr(m, key)), m.axes)))
    return out


def _mode_captions(build: Build) -> dict[str, str]:
    from .modal import base_words, top_words

    return {
        "bare": f"the bare tube ({base_words(build.scene.foundation)}, free top)",
        "top": f"the tube carrying {top_words(build.modal.top if build.modal else None)[0]}",
    }


@dataclass(frozen=True)
class ModePicturesKept:
    """A set of mode pictures drawn by an earlier report (:mod:`.kept`), as
    ``modeshapes.ModePictures`` gives a set just drawn."""

    modes: list[Path]
    sheet: Path


def _mode_products(build: Build, files: ModeFiles, name: str, r: ModePictures | ModePicturesKept) -> None:
    """The pictures of one set of modes on the page, each captioned from modal.json."""
    from ..directions import mode_label
    from ..geometry import ModeLabel

    meta = lambda i: files.modes[i] if i < len(files.modes) else ModeLabel()  # noqa: E731  (as load_modes names them)
    caption = _mode_captions(build)[name]
    build.mode_pictures[name] = [Product(p, mode_label(meta(i), i), group=name) for i, p in enumerate(r.modes)]
    build.products[f"sheet_{name}"] = Product(
        r.sheet,
        (
            f"The first {len(r.modes)} modes of {caption} (3D model, {files.vtu.name}): "
            "deformed shape coloured by |u| / max |u| over the undeformed outline; the scale "
            "factor is on each view; the triad names the axes as the paper does (X horizontal, "
            "in the rotor's plane; Z horizontal, along the shaft; Y vertical); an ovalling "
            "mode's cross-sections beside it, seen from above."
        ),
        group=name,
    )


def animated_runs(build: Build) -> list[tuple[str, Simulation, str, dict[str, Any]]]:
    """The runs the report animates: (name, Simulation, title, options).

    - ``runup``: the scene's run-up, time-warped into its passage through the
      resonances;
    - ``earthquake``: the record (El Centro) on the reduced model of the
      earthquake comparison, the model the page's answers come from;
    - ``earthquake_paper``: the paper's pulse on its Eq. 4, the warning that
      it is no earthquake burnt into every frame.
    """
    from ..transient_charts import crossings, passage_window

    out: list[tuple[str, Simulation, str, dict[str, Any]]] = []
    sim = build.simulations.get("runup")
    if sim is not None and sim.arrays.t is not None:
        res = [(f"omega_{r.index}", float(r.omega)) for r in (sim.run.resonances if sim.run is not None else ())]
        t, omega = sim.arrays.t, sim.arrays.Omega
        focus = passage_window(t, crossings(t, omega, res)) if omega is not None else None
        out.append(("runup", sim, "Run-up", {"focus": focus}))
    c = build.comparisons.get("earthquake")
    if c is not None:
        model = next(
            (
                m
                for m in sorted(c.models, key=lambda m: m != "modal")
                if c.arrays_of(m).t is not None and m != c.reference
            ),
            None,
        )
        if model is not None:
            out.append(
                (
                    "earthquake",
                    Simulation("earthquake", c.runs.get(model), c.arrays[model]),
                    f"{_record_name(c.record.excitation)} on the {model} model",
                    {},
                )
            )
    quake = build.quake_case
    if quake is not None and quake.arrays.t is not None:
        ex = quake.excitation
        pulse = isinstance(ex, PulseSizes) or (isinstance(ex, RecordSizes) and not ex.realistic)
        banner = ""
        if isinstance(ex, (PulseSizes, RecordSizes)) and pulse:
            step = abs((ex.displacement_step_at_start if isinstance(ex, PulseSizes) else 0.0) or ex.peak_displacement)
            banner = (
                "NOT AN EARTHQUAKE: the paper's pulse\n"
                f"as written: the ground steps {step:.3g} m,\n"
                f"{ex.peak_acceleration_g:.3g} g (see the report)"
            )
        name = (
            "earthquake_paper"
            if pulse or (quake.run is not None and quake.run.model == "paper")
            else "earthquake_scene"
            if any(n == "earthquake" for n, *_ in out)
            else "earthquake"
        )
        build.quake_case_animation = f"animation_{name}"
        what = "The paper's pulse" if pulse else "The scene's earthquake"
        model = quake.run.model if quake.run is not None else "?"
        out.append((name, quake, f"{what} on the {model} model", {"banner": banner}))
    return out


def render_3d(build: Build, during: Callable[[], None] | None = None) -> None:
    """The mode shapes and the animations, drawn in worker processes (:mod:`.parallel`)
    while ``during`` (the charts) runs here; each picture on the page as it comes."""
    from . import kept
    from .parallel import AnimationJob, ModesJob, debug_detail, run_jobs

    files = dict(mode_files(build))
    jobs: list[ModesJob | AnimationJob] = []
    captions = _mode_captions(build)
    pictures = build.out / MODES_DIR
    keys = {}
    for name, f in files.items():
        keys[name] = kept.modes_key(name, f, build.options.modes)
        was = kept.recall(pictures, name, keys[name])
        if was is not None:
            say(f"mode shapes of {captions[name]}: unchanged since {kept.since(was)}, reused")
            shown = ModePicturesKept([pictures / n for n in was.modes], pictures / was.sheet)
            _mode_products(build, f, name, shown)
            build.reused[f"modes_{name}"] = was.finished
            build.render_window = build.render_window or was.window
            continue
        kept.forget(pictures, name)
        say(f"mode shapes of {captions[name]}")
        jobs.append(ModesJob(name, f, pictures, build.options.modes))
    titles = {}
    if build.options.animations:
        p = build.scene.pillar
        base = p.segments()[0]  # the tube's base section (a tower's bottom can)
        for name, sim, title, opts in animated_runs(build):
            say(f"animation of the {name} ({build.options.max_frames} frames at most)")
            titles[name] = title
            jobs.append(
                AnimationJob(
                    name,
                    sim,
                    f"{title} (scene {build.scene.name})",
                    opts,
                    files.get("top"),
                    (p.height, base.outer_bottom, base.inner_bottom),
                    build.out / ANIMATIONS_DIR / f"{name}.mp4",
                    build.out / ANIMATIONS_DIR / f"{name}_poster.png",
                    build.options.max_frames,
                )
            )
    for o in run_jobs(jobs, during):
        build.render_seconds[o.key] = build.render_seconds.get(o.key, 0.0) + o.seconds
        build.render_window = build.render_window or o.window
        if o.error is not None:
            build.failures[o.key] = o.error
            say(f"{o.key} failed: {o.error}")
            if debugging():
                debug_detail(o)
        elif o.key.startswith("modes_"):
            name = o.key.removeprefix("modes_")
            _mode_products(build, files[name], name, o.result)
            kept.keep(pictures, name, keys[name], o.result.modes, o.result.sheet, o.seconds, o.window)
        elif o.key.startswith("animation_"):
            name = o.key.removeprefix("animation_")
            _animation_products(build, name, titles[name], o.result)


def _animation_products(build: Build, name: str, title: str, r) -> None:
    """An animation on the page, its caption from what it shows."""
    timing = (
        f"time-warped: {r.frames_in_focus} of its {r.frames} frames in the passage "
        f"through the resonances, {r.focus[0]:.3g} .. {r.focus[1]:.3g} s (slow motion "
        "there, said on the frame), the rest over the remaining run"
        if r.focus
        else "sampling the run uniformly"
    )
    build.products[f"animation_{name}"] = Product(
        r.path,
        (
            f"{title}: the pillar deformed by {r.source}; the pillar's elastic deflection "
            f"exaggerated x{r.factor:g}, the rotor's motion about the pillar top (drawn on its "
            f"shaft) x{r.orbit_factor:g}"
            + ("; ground motion at true scale" if name.startswith("earthquake") else "")
            + f". {r.frames} frames at {r.fps} frames/s, {timing} (stroboscopic: the pillar's "
            "vibration at the rotor speed aliases; the orbit trail uses every stored sample). "
            f"{r.writer}."
        ),
        kind="video",
        poster=r.poster,
    )
    build.animations[name] = r
