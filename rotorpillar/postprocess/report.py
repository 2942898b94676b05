"""`rotorpillar report`: every figure its inputs allow, then one HTML page.

Reads what the other commands left in ``out/<scene>/`` (see
:mod:`.inputs`), renders what it can (charts, mode shapes, animations),
embeds the PNGs the other chart modules wrote there, and writes
``report.html``: the scene, the modal validation (Eq. 1 against the 3D
model, the reduction, Table 1 and every number the paper prints, flagged),
the averaging analysis, the runs, the earthquake, the model choice, and the
versions and timings.  A section whose input is missing says which command
produces it; a figure that fails to render says why, and the rest of the
report is still written.
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys
import time
import traceback
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

from .. import __version__
from ..provenance import machine, to_json, versions, write_text
from . import html as h
from .inputs import CASES, INPUTS, SIMULATE_COMMAND, ModeSet, not_computed, read_json, read_simulation

FIGURES_DIR = "figures"
MODES_DIR = "modes"
ANIMATIONS_DIR = "animations"
OWN_DIRS = (FIGURES_DIR, MODES_DIR, ANIMATIONS_DIR)
#: The runs that get an animation.
ANIMATED = ("runup", "earthquake")


@dataclass(frozen=True)
class ReportOptions:
    """What `rotorpillar report` renders."""
    animations: bool = True
    """render the run-up and earthquake animations"""
    max_frames: int = 180
    """frames per animation (-)"""
    modes: int = 8
    """mode shapes rendered per set, and on the contact sheet (-)"""


@dataclass
class Product:
    """A file the report made or found, with its caption."""
    path: Path
    caption: str
    kind: str = "figure"       # figure | video
    group: str = ""
    poster: Path | None = None


@dataclass
class Build:
    """Everything the page is assembled from."""
    scene: object
    out: Path
    scene_cli: str
    options: ReportOptions
    analyze: dict | None = None
    modal: dict | None = None
    convergence: dict | None = None
    integrators: dict | None = None
    simulations: dict = field(default_factory=dict)
    products: dict = field(default_factory=dict)     # key -> Product or list of Products
    failures: dict = field(default_factory=dict)     # key -> message
    render_seconds: dict = field(default_factory=dict)
    render_window: str = ""

    def hint(self, command: str) -> str:
        return not_computed(command, self.scene_cli)


def _say(message: str) -> None:
    print(f"[rotorpillar] report: {message}", file=sys.stderr, flush=True)


def _attempt(build: Build, key: str, fn):
    """Run one rendering step; on failure record why and carry on."""
    start = time.perf_counter()
    try:
        return fn()
    except Exception as exc:  # a broken figure must not cost the whole report
        build.failures[key] = f"{type(exc).__name__}: {exc}"
        _say(f"{key} failed: {build.failures[key]}")
        traceback.print_exc(file=sys.stderr)
        return None
    finally:
        build.render_seconds[key] = build.render_seconds.get(key, 0.0) + time.perf_counter() - start


# --------------------------------------------------------------------------
# Rendering


def _render_charts(build: Build) -> None:
    from . import charts
    fig = build.out / FIGURES_DIR
    if build.analyze is not None:
        p = _attempt(build, "drive_chart",
                     lambda: charts.drive_chart(build.analyze, fig / "drive_resistance.png"))
        if p:
            build.products["drive_chart"] = Product(p, (
                "Motor torque Md and total resistance L = Mc + sum dL_i against the speed "
                "(the paper's Figs. 3-4). L is solid where a stationary regime there is stable "
                "(d(Md - L)/dOmega < 0, Eq. 23) and dashed where it is not; jumps A->B (run-up) and "
                "D->C (run-down) are drawn on the motor lines through them. Below: near each "
                "resonance, against z = Omega/omega_i, with L - Mc on the right axis; dots are the "
                "curves stored in analyze.json."))
        p = _attempt(build, "amplitude_chart",
                     lambda: charts.amplitude_chart(build.analyze, fig / "resonance_amplitudes.png"))
        if p:
            build.products["amplitude_chart"] = Product(p, (
                "Amplitude a_i of each quasi-normal coordinate near its resonance: the averaging "
                "result (Eq. 19 with omega_i**2 restored) against the exact steady state of the "
                "linear mode at constant speed."))
    quake = build.simulations.get("earthquake")
    if quake is not None and quake.arrays.get("t") is not None:
        p = _attempt(build, "earthquake_chart", lambda: charts.earthquake_chart(
            quake.arrays, fig / "earthquake_response.png",
            title=f"Earthquake response ({quake.meta.get('model', 'model not stated')})"))
        if p:
            build.products["earthquake_chart"] = Product(p, (
                "Earthquake: ground displacement (the shaded interval is when the ground moves), "
                "elastic tip deflection, radius of the rotor's orbit about the pillar top, and "
                "the rotor speed."))


def _mode_sets(build: Build) -> dict[str, ModeSet | None]:
    from .inputs import load_modes
    sets = {}
    m = build.modal or {}
    for name, key in (("bare", "modes"), ("top", "modes_with_top")):
        vtu = build.out / INPUTS[f"modes_{name}"][0]
        if build.modal is not None and vtu.is_file():
            sets[name] = _attempt(build, f"load_modes_{name}",
                                  lambda vtu=vtu, key=key: load_modes(vtu, m.get(key, []), m.get("axes")))
        else:
            sets[name] = None
    return sets


def _render_modes(build: Build, sets: dict) -> None:
    from .modeshapes import render_modes
    captions = {"bare": "the bare tube (clamped base, free top)",
                "top": "the tube with the gondola and rotor at its top"}
    for name, ms in sets.items():
        if ms is None:
            continue
        _say(f"mode shapes of {captions[name]}")
        r = _attempt(build, f"modes_{name}",
                     lambda ms=ms, name=name: render_modes(ms, build.out / MODES_DIR, name,
                                                           build.options.modes))
        if r:
            from .inputs import mode_label
            build.products[f"modes_{name}"] = [
                Product(p, mode_label(ms.modes[i], i), group=name) for i, p in enumerate(r["modes"])]
            build.products[f"sheet_{name}"] = Product(r["sheet"], (
                f"The first {len(r['modes'])} modes of {captions[name]} (3D model, {Path(ms.source).name}): "
                "deformed shape coloured by |u| / max |u| over the undeformed outline; the scale "
                "factor is on each view."), group=name)


def _render_animations(build: Build, sets: dict) -> None:
    from .animation import animate
    from .inputs import cantilever_tube
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
        _say(f"animation of the {case} ({build.options.max_frames} frames at most)")
        title = {"runup": "Run-up", "earthquake": "Earthquake"}.get(case, case)
        r = _attempt(build, f"animation_{case}", lambda sim=sim, ms=ms, title=title, case=case: animate(
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


def external_figures(out: Path) -> list[tuple[Path, str]]:
    """PNGs other commands wrote in ``out`` (and its direct subfolders, not ours),
    with the caption a JSON beside them gives in a ``figures`` list
    ({"file" or "path", "caption"}), else one made from the file name."""
    captions = {}
    for js in sorted(out.glob("*.json")):
        try:
            doc = json.loads(js.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        figs = doc.get("figures") if isinstance(doc, dict) else None
        if isinstance(figs, list):
            for f in figs:
                if isinstance(f, dict) and (f.get("file") or f.get("path")):
                    name = Path(str(f.get("file") or f.get("path"))).name
                    captions[name] = str(f.get("caption", ""))
        elif isinstance(figs, dict):
            for k, v in figs.items():
                if isinstance(v, dict):
                    name = Path(str(v.get("file") or v.get("path") or k)).name
                    captions[name] = str(v.get("caption", ""))
                elif isinstance(v, str):
                    captions[Path(v).name] = str(k).replace("_", " ")
    found = []
    # the folder itself and its direct subfolders only: --out may point
    # anywhere, and a deep search could sweep up unrelated pictures
    for p in sorted([*out.glob("*.png"), *out.glob("*/*.png")]):
        rel = p.relative_to(out)
        if rel.parts[0] in OWN_DIRS or any(part.startswith(".") for part in rel.parts):
            continue
        found.append((p, captions.get(p.name) or p.stem.replace("_", " ")))
    return found


#: Where a PNG from another module goes, by words in its name (first match).
FIGURE_GROUPS = [
    ("earthquake", ("earthquake", "quake", "seismic")),
    ("convergence", ("convergence", "pareto", "ladder", "refinement", "accuracy")),
    ("integrators", ("integrator", "solver", "step")),
    ("runs", ("runup", "run_up", "rundown", "run_down", "sweep", "transient", "omega",
              "amplitude", "simulate", "speed", "averaging")),
    ("modal", ("modal", "mode", "frequency")),
]


def figure_group(name: str) -> str:
    """The report section for a figure file name.

    >>> figure_group("pareto_front.png"), figure_group("runup_omega.png"), figure_group("x.png")
    ('convergence', 'runs', 'other')
    """
    n = name.lower()
    for group, words in FIGURE_GROUPS:
        if any(w in n for w in words):
            return group
    return "other"


# --------------------------------------------------------------------------
# Sections


def _product_image(build: Build, key: str) -> str:
    p = build.products[key]
    return h.image(p.path, p.caption)


def _figures(build: Build, group: str) -> list[str]:
    return [h.image(p.path, p.caption) for p in build.products.get("external", [])
            if p.group == group]


def _failure(build: Build, key: str) -> list[str]:
    if key in build.failures:
        return [h.tag("p", f"{key}: could not be rendered: {build.failures[key]}", class_="failed")]
    return []


def _note(doc: dict | None) -> list[str]:
    """An input's own top-level ``note`` (e.g. "synthetic fixture"), shown as is."""
    if isinstance(doc, dict) and isinstance(doc.get("note"), str) and doc["note"]:
        return [h.tag("p", f"Note from the input: {doc['note']}", class_="warn")]
    return []


def _scene_differs(build: Build, doc: dict | None) -> list[str]:
    """A warning when an input was computed for another version of the scene
    (and the input's own note, if it has one)."""
    if not doc or "scene" not in doc:
        return _note(doc)
    now = json.loads(to_json(build.scene.to_dict()))
    then = doc["scene"]
    diffs = [f"{k}.{kk}" for k, v in now.items() if isinstance(v, dict)
             for kk in v if not isinstance(then.get(k), dict) or then[k].get(kk) != v[kk]]
    if not diffs:
        return _note(doc)
    return _note(doc) + [h.tag("p", "Warning: this input was computed for a different scene ("
                  + ", ".join(diffs[:8]) + (" ..." if len(diffs) > 8 else "")
                  + f" differ); re-run {doc.get('command', 'its command')} on this scene.",
                  class_="warn")]


def section_summary(build: Build) -> str:
    a, m = build.analyze, build.modal
    items = []
    if a:
        p = a["pillar"]
        text = (f"First bending mode of the bare tube: Eq. 1 gives {p['omega_col1']:.3f} rad/s "
                f"({p['frequency_col1_hz']:.3f} Hz); Timoshenko {pct_(p['timoshenko_correction'])}")
        bx = _bending(m.get("modes", []), "bending_x") if m else []
        if bx:
            w = bx[0]["omega"]
            text += f"; the 3D model {w:.3f} rad/s ({w / p['omega_col1'] - 1:+.2%} against Eq. 1)."
        else:
            text += "; the 3D model: " + build.hint(INPUTS["modal"][1]) + "."
        items.append(text)
        r = a["reduction"]
        items.append(f"Pillar reduced to its tip: m_r = {r['tip_mass']:.4g} kg ({r['tip_mass_source']}), "
                     f"c1 = {r['tip_stiffness']:.4g} N/m ({r['tip_stiffness_source']}).")
        s = a["system"]
        items.append(f"Rotor-pillar system: omega_1 = {s['omega'][0]:.3f}, "
                     f"omega_2 = {s['omega'][1]:.3f} rad/s "
                     f"(X), omega_3 = {s['omega3']:.3f} rad/s (Y).")
        rows = a.get("paper_comparison", [])
        items.append(f"{sum(1 for x in rows if x['flag'])} of the {len(rows)} numbers the paper prints "
                     "differ from ours by more than 2 %; each has its likely cause below.")
        d = a["drive"]
        st = ", ".join(f"{x['omega']:.2f} rad/s ({'stable' if x['stable'] else 'unstable'})"
                       for x in d["stationary"]) or "none"
        items.append(f"Stationary speed(s) with the scene's motor: {st}. "
                     + (f"{len(d['jumps'])} jump(s) in a quasi-static run-up/run-down."
                        if d["jumps"] else "No jumps (no Sommerfeld effect) with this drive."))
        for res in a["resonances"]:
            items.append(res["statement"])
    else:
        items.append("Closed forms and averaging: " + build.hint(INPUTS["analyze"][1]) + ".")
    for case in CASES:
        sim = build.simulations.get(case)
        if sim is not None and sim.meta:
            wf = sim.meta.get("omega_final")
            items.append(f"Run {case}: final speed {h.num(wf, 4)} rad/s"
                         + (f", captured at resonance {sim.meta['captured_at']}"
                            if sim.meta.get("captured_at") is not None else "") + ".")
    if not build.simulations:
        items.append("Transients: " + build.hint(SIMULATE_COMMAND) + ".")
    chosen = _chosen(build.convergence) if build.convergence else None
    if chosen:
        items.append(f"Model chosen: {chosen[0]}" + (f" - {chosen[1]}" if chosen[1] else "") + ".")
    lis = []
    for it in items:
        if "not computed: run `" in it:
            pre, rest = it.split("not computed: run `", 1)
            cmd, post = rest.split("`", 1)
            lis.append(h.tag("li", [pre, "not computed: run ", h.tag("code", cmd), post]))
        else:
            lis.append(h.tag("li", it))
    return h.section("summary", "Summary", [h.tag("ul", lis, class_="findings")])


def pct_(x) -> str:
    return h.pct(x)


def section_scene(build: Build) -> str:
    from ..scene import SECTIONS
    d = build.scene.to_dict()
    rows = []
    for sec, cls in SECTIONS.items():
        values = d.get(sec)
        if not isinstance(values, dict):
            continue
        for f in dataclasses.fields(cls):
            rows.append([f"{sec}.{f.name}", h.num(values.get(f.name)), f.metadata.get("doc", "")])
    parts = [h.tag("p", [h.tag("strong", build.scene.name), ": ", build.scene.description or ""]),
             h.tag("p", ["Invoked as ", h.tag("code", f"rotorpillar report {build.scene_cli}"),
                         ". SI units throughout."], class_="meta"),
             h.table(["key", "value", "meaning (unit)"], rows)]
    return h.section("scene", "The scene", parts)


def _bending(modes: list, kind: str) -> list:
    return [m for m in modes if str(m.get("kind", "")) == kind]


def _mode_rows(modes: list) -> list:
    return [[i + 1, m.get("kind", "?"), h.num(m.get("n_circumferential")),
             h.num(m.get("frequency_hz")), h.num(m.get("omega")), h.num(m.get("modal_mass")),
             m.get("normalisation", "-")] for i, m in enumerate(modes)]


def section_modal(build: Build) -> str:
    a, m = build.analyze, build.modal
    parts = []
    if m is None:
        parts.append(h.missing(build.hint(INPUTS["modal"][1])))
    parts += _scene_differs(build, m)
    # Eq. 1 against the 3D model
    parts.append(h.tag("h3", "Eq. 1 against the 3D model (bare tube)"))
    if a is None:
        parts.append(h.missing(build.hint(INPUTS["analyze"][1])))
    else:
        p = a["pillar"]
        modes = (m or {}).get("modes", [])
        bx, by = _bending(modes, "bending_x"), _bending(modes, "bending_y")
        rows = []
        for k, w_eb in enumerate(p["omega_euler_bernoulli"], start=1):
            w3 = bx[k - 1]["omega"] if k - 1 < len(bx) else None
            timo = p["omega_col1_timoshenko"] if k == 1 else None
            rows.append([f"bending {k}, paper X", h.num(w_eb), h.num(timo), h.num(w3),
                         h.pct(w3 / w_eb - 1) if w3 else "-",
                         h.pct(w3 / timo - 1) if (w3 and timo) else "-"])
        if by and bx:
            rows.append(["bending 1, other direction", "-", "-", h.num(by[0]["omega"]),
                         "-", h.pct(by[0]["omega"] / bx[0]["omega"] - 1) + " vs X"])
        shells = [x for x in modes if not str(x.get("kind", "")).startswith(("bending", "axial"))]
        if shells:
            s = shells[0]
            rows.append([f"first {s.get('kind')} mode (n = {s.get('n_circumferential', '?')})",
                         "none in beam theory", "-", h.num(s.get("omega")), "-", "-"])
        parts.append(h.table(["mode", "Eq. 1, Euler-Bernoulli (rad/s)", "Timoshenko (rad/s)",
                              "3D model (rad/s)", "3D vs Eq. 1", "3D vs Timoshenko"], rows))
        if m is None:
            parts.append(h.tag("p", "3D column empty: the 3D model has not run.", class_="meta"))
    # the reduction
    parts.append(h.tag("h3", "The pillar reduced to its tip (Eq. 2)"))
    if a is None:
        parts.append(h.missing(build.hint(INPUTS["analyze"][1])))
    else:
        p, r = a["pillar"], a["reduction"]
        red3 = (m or {}).get("reduction") or {}
        stated = build.scene.reduction
        cols = [("stated in the scene", stated.tip_mass, stated.tip_stiffness),
                ("Eq. 2, continuous first mode", p["tip_mass_limit"], p["tip_stiffness_limit"]),
                ("3D model", red3.get("m_reduced"), red3.get("tip_stiffness")),
                (f"used (m_r: {r['tip_mass_source']}, c1: {r['tip_stiffness_source']})",
                 r["tip_mass"], r["tip_stiffness"])]
        rows = []
        for name, mr, c1 in cols:
            w = math.sqrt(c1 / mr) if (mr and c1) else None
            rows.append([name, h.num(mr), h.num(c1), h.num(w),
                         h.pct(w / p["omega_col1"] - 1) if w else "-"])
        parts.append(h.table(["source", "m_r (kg)", "c1 (N/m)", "sqrt(c1/m_r) (rad/s)",
                              "vs Eq. 1"], rows))
        parts.append(h.tag("p", "Eq. 2 lumped into n masses: " + ", ".join(
            f"n = {x['n']}: {x['tip_mass']:.4g} kg" for x in p["tip_mass_lumped"]) + ".",
            class_="meta"))
    # the 3D modes
    if m is not None:
        for key, title, name in (("modes", "Modes of the bare tube (3D)", "bare"),
                                 ("modes_with_top", "Modes with the gondola and rotor on top (3D)", "top")):
            parts.append(h.tag("h3", title))
            modes = m.get(key) or []
            parts.append(h.table(["#", "kind", "n", "f (Hz)", "omega (rad/s)", "modal mass (kg)",
                                  "normalisation"], _mode_rows(modes)) if modes
                         else h.tag("p", f"modal.json has no {key}.", class_="meta"))
            parts += _failure(build, f"modes_{name}") + _failure(build, f"load_modes_{name}")
            sheet = build.products.get(f"sheet_{name}")
            if sheet:
                parts.append(h.image(sheet.path, sheet.caption))
                singles = build.products.get(f"modes_{name}", [])
                gallery = "".join(h.image(x.path, x.caption) for x in singles)
                parts.append(h.details(f"each mode separately ({len(singles)} pictures)",
                                       f'<div class="gallery">{gallery}</div>'))
            elif not (build.out / INPUTS[f"modes_{name}"][0]).is_file():
                parts.append(h.missing(f"mode shapes not computed: run `rotorpillar modal {build.scene_cli}` "
                                       f"(no {INPUTS[f'modes_{name}'][0]})"))
        extra = [(k, v) for k, v in h.flatten({"mesh": m.get("mesh"), "axes": m.get("axes"),
                                                "timings": m.get("timings")}) if v is not None]
        if extra:
            parts.append(h.details("3D model: mesh, axes, timings",
                                   h.table(["field", "value"], [[k, h.num(v)] for k, v in extra])))
    parts += _figures(build, "modal")
    return h.section("modal", "Modal validation", parts)


def section_paper(build: Build) -> str:
    a = build.analyze
    if a is None:
        return h.section("paper", "The paper's numbers against ours",
                         [h.missing(build.hint(INPUTS["analyze"][1]))])
    rows, cls = [], []
    for r in a["paper_comparison"]:
        rows.append(["*" if r["flag"] else "", r["quantity"], h.num(r["paper"]), h.num(r["computed"]),
                     h.pct(r["rel_diff"], 1), r["where"], r.get("note", "")])
        cls.append("flag" if r["flag"] else "ok")
    n = sum(1 for r in a["paper_comparison"] if r["flag"])
    parts = _scene_differs(build, a) + [
        h.tag("p", f"Every number the paper prints that we compute, ours from first principles "
                   f"(never tuned to match). * = differs by more than 2 % ({n} of {len(rows)}); "
                   "the last column gives the likely cause. Table 1's rows are those marked "
                   "'Table 1'."),
        h.table(["", "quantity", "paper", "ours", "difference", "printed in", "likely cause"],
                rows, row_classes=cls)]
    return h.section("paper", "The paper's numbers against ours (Table 1 and the rest)", parts)


def section_averaging(build: Build) -> str:
    a = build.analyze
    if a is None:
        return h.section("averaging", "Passage through resonance (averaging)",
                         [h.missing(build.hint(INPUTS["analyze"][1]))])
    parts = _scene_differs(build, a)
    d = a["drive"]
    parts.append(h.tag("p", f"Motor Md = {d['torque_at_zero']:g} - {d['slope']:g} Omega, load "
                            f"Mc = {d['load_coefficient']:g} Omega^2 (Eq. 22)."))
    parts += _failure(build, "drive_chart")
    if "drive_chart" in build.products:
        parts.append(_product_image(build, "drive_chart"))
    parts.append(h.tag("ul", [h.tag("li", r["statement"]) for r in a["resonances"]], class_="findings"))
    parts.append(h.tag("h3", "Stationary speeds and jumps"))
    rows = [[h.num(s["omega"]), "stable" if s["stable"] else "unstable", h.num(s["margin"])]
            for s in d["stationary"]]
    parts.append(h.table(["Omega (rad/s)", "stability (Eq. 23)", "d(Md - L)/dOmega (N*m*s)"], rows)
                 if rows else h.tag("p", "No stationary speed."))
    if d["jumps"]:
        name = {"up": "A->B (run-up)", "down": "D->C (run-down)"}
        rows = [[name.get(j["direction"], j["direction"]),
                 h.num(j["omega_from"]), h.num(j["omega_to"]), h.num(j["torque_at_zero"]),
                 h.num(j.get("resonance"))] for j in d["jumps"]]
        parts.append(h.table(["jump", "from (rad/s)", "to (rad/s)", "at M0 (N*m)", "resonance"], rows))
    else:
        parts.append(h.tag("p", "No jumps: a quasi-static run-up and run-down pass every resonance "
                                "without the Sommerfeld effect with this drive."))
    parts.append(h.tag("p", f"Run-up ends at {h.num(d.get('runup_speed'))} rad/s, run-down at "
                            f"{h.num(d.get('rundown_speed'))} rad/s"
                            + (f"; captured at resonance {d['captured_at']}."
                               if d.get("captured_at") is not None else ".")))
    parts.append(h.tag("h3", "The resonances"))
    rows = [[r["index"], r["direction"], h.num(r["omega"]), h.num(r["modal_mass"]), h.num(r["forcing"]),
             h.num(r["two_n"]), h.num(r["nu"]), h.num(r["a_max"]), h.num(r["dL_max"]),
             h.num(r["dL_max_over_Mc"]), h.num(r["critical_slope"]), h.num(r["critical_eccentricity"])]
            for r in a["resonances"]]
    parts.append(h.table(["i", "dir", "omega_i (rad/s)", "I_i (kg)", "f_i (m/s^2)", "2n_i (1/s)", "nu_i",
                          "a_max (m)", "dL_max (N*m)", "dL_max/Mc", "critical slope (N*m*s)",
                          "critical e (m)"], rows))
    parts += _failure(build, "amplitude_chart")
    if "amplitude_chart" in build.products:
        parts.append(_product_image(build, "amplitude_chart"))
    return h.section("averaging", "Passage through resonance (averaging, Eq. 19-24)", parts)


def _key_results(meta: dict) -> str | None:
    """The few numbers of a run a reader looks for first, where the JSON has them."""
    rows = []
    for key, label in (("model", "model"), ("omega_final", "final speed (rad/s)"),
                       ("captured_at", "captured at resonance")):
        if key in meta:
            rows.append([label, h.num(meta[key])])
    if isinstance(meta.get("jumps"), list):
        rows.append(["jumps", str(len(meta["jumps"]))])
    for k, v in h.flatten(meta):
        if "energy" in k.lower() and isinstance(v, (int, float)):
            rows.append([k, h.num(v)])
    mx = meta.get("max_abs")
    if isinstance(mx, dict):
        rows += [[f"max |{k}| (m)", h.num(v)] for k, v in mx.items() if isinstance(v, (int, float))]
    return h.table(["", ""], rows) if rows else None


def _run_table(meta: dict) -> str:
    keep = [(k, v) for k, v in h.flatten({k: v for k, v in meta.items()
                                          if k not in ("scene", "versions", "machine", "figures",
                                                       "command", "scene_source", "overrides")})]
    return h.table(["field", "value"], [[k, h.num(v)] for k, v in keep])


def section_runs(build: Build) -> str:
    parts = []
    if not any(c in build.simulations for c in CASES if c != "earthquake"):
        parts.append(h.missing(build.hint(SIMULATE_COMMAND)))
    for case in CASES:
        if case == "earthquake":
            continue
        sim = build.simulations.get(case)
        parts.append(h.tag("h3", {"runup": "Run-up", "rundown": "Run-down", "sweep": "Sweep"}[case]))
        if sim is None:
            parts.append(h.missing(f"not computed: run `rotorpillar {SIMULATE_COMMAND} --case {case} "
                                   f"{build.scene_cli}` (no simulate_{case}.json)"))
            continue
        parts += _scene_differs(build, sim.meta)
        key = _key_results(sim.meta)
        if key:
            parts.append(key)
        parts.append(h.details(f"simulate_{case}.json: results, energy balance, integrator",
                               _run_table(sim.meta)) if sim.meta
                     else h.tag("p", "no JSON summary", class_="meta"))
        for p in build.products.get("external", []):
            if p.group == "runs" and case in p.path.name.lower():
                parts.append(h.image(p.path, p.caption))
                p.group = "used"
        parts += _failure(build, f"animation_{case}")
        v = build.products.get(f"animation_{case}")
        if v:
            parts.append(h.video(v.path, build.out, v.caption, v.poster))
    parts += _figures(build, "runs")
    return h.section("runs", "The runs", parts)


def section_earthquake(build: Build) -> str:
    sim = build.simulations.get("earthquake")
    if sim is None:
        return h.section("earthquake", "The earthquake",
                         [h.missing(f"not computed: run `rotorpillar {SIMULATE_COMMAND} --case earthquake "
                                    f"{build.scene_cli}` (no simulate_earthquake.json)")]
                         + _figures(build, "earthquake"))
    parts = _scene_differs(build, sim.meta)
    g = sim.get("ground_x")
    excitation = (sim.meta or {}).get("excitation") or {}
    if isinstance(excitation.get("statement"), str):
        parts.append(h.tag("p", excitation["statement"],
                           class_="warn" if excitation.get("realistic") is False else None))
    if g is not None and len(g):
        parts.append(h.tag("p", f"Largest ground displacement: {abs(g).max():.3g} m."))
    parts += _failure(build, "earthquake_chart")
    if "earthquake_chart" in build.products:
        parts.append(_product_image(build, "earthquake_chart"))
    parts += _figures(build, "earthquake")
    parts += _failure(build, "animation_earthquake")
    v = build.products.get("animation_earthquake")
    if v:
        parts.append(h.video(v.path, build.out, v.caption, v.poster))
    if sim.meta:
        key = _key_results(sim.meta)
        if key:
            parts.append(key)
        parts.append(h.details("simulate_earthquake.json", _run_table(sim.meta)))
    return h.section("earthquake", "The earthquake", parts)


def _chosen(doc: dict | None):
    """(what, why) of the model choice in convergence.json's ``selection``, or None."""
    sel = doc.get("selection") if isinstance(doc, dict) else None
    if not isinstance(sel, dict) or not isinstance(sel.get("chosen"), dict):
        return None
    c, band = sel["chosen"], sel.get("band") or {}
    needed = sel.get("needed") or []
    bounds = ", ".join(f"{q} {h.num(c.get(f'{q}_error_bound'), 2)}" for q in needed)
    why = (f"the cheapest run whose error bound meets the tolerance {h.num(sel.get('tolerance'))} on "
           f"every frequency the scene excites: the band up to {h.num(band.get('omega_max'), 4)} rad/s "
           f"({h.num(band.get('margin'))} x the {band.get('driver', 'highest excitation')}) holds "
           f"{', '.join(needed) or 'no mode'}; its bounds: {bounds}")
    return f"{c.get('label')} ({c.get('dofs')} DOFs, {h.num(c.get('wall_time'), 3)} s)", why


def _convergence_parts(c: dict) -> list:
    parts = []
    chosen = _chosen(c)
    if chosen:
        parts.append(h.tag("p", [h.tag("strong", "Chosen: "), chosen[0]]))
        parts.append(h.tag("p", [h.tag("strong", "Why: "), chosen[1] + "."]))
        rule = (c.get("selection") or {}).get("rule")
        if rule:
            parts.append(h.tag("p", f"Rule: {rule}.", class_="meta"))
        rejected = (c.get("selection") or {}).get("rejected_cheaper") or []
        if rejected:
            parts.append(h.tag("h3", "Cheaper models that do not meet it"))
            parts.append(h.table(["model", "DOFs", "wall time (s)", "why not"],
                                 [[r.get("label"), r.get("dofs"), h.num(r.get("wall_time"), 3),
                                   r.get("why", "")] for r in rejected]))
    else:
        parts.append(h.tag("p", "convergence.json names no chosen model (no run meets the "
                                "tolerance).", class_="meta"))
    ref = c.get("reference") or {}
    if ref:
        parts.append(h.tag("h3", "Reference frequencies (Richardson extrapolation)"))
        rows = []
        for q, r in ref.items():
            if not isinstance(r, dict):
                continue
            chk = r.get("check") or {}
            rows.append([q, h.num(r.get("value"), 7), h.num(r.get("error_estimate"), 2),
                         h.num(r.get("order"), 3), h.num(r.get("order_theory"), 2),
                         ", ".join(r.get("runs") or []),
                         ("yes" if chk.get("within_estimate") else "no") if chk else "-"])
        parts.append(h.table(["mode", "reference (rad/s)", "+- estimate", "observed order",
                              "theory", "from", "three coarser runs predict the finest"], rows))
    failures = c.get("failures") or []
    if failures:
        parts.append(h.tag("h3", "Where each method fails"))
        parts.append(h.tag("ul", [h.tag("li", f) for f in failures]))
    slim = {k: v for k, v in c.items() if k not in ("runs", "families", "selection", "reference",
                                                     "failures", "extrapolations")}
    parts.append(h.details("convergence.json (less its runs)", _run_table(slim)))
    return parts


def section_convergence(build: Build) -> str:
    c = build.convergence
    parts = []
    if c is None:
        parts.append(h.missing(build.hint(INPUTS["convergence"][1])))
        a = build.analyze
        if a is not None:
            r = a["reduction"]
            parts.append(h.tag("p", "Until the study runs, the reduced model is the paper's (Eq. 4) "
                                    f"with m_r from {r['tip_mass_source']} and c1 from "
                                    f"{r['tip_stiffness_source']}."))
    else:
        parts += _scene_differs(build, c)
        parts += _convergence_parts(c)
    parts += _figures(build, "convergence")
    parts.append(h.tag("h3", "Integrators"))
    if build.integrators is None:
        parts.append(h.missing(build.hint(INPUTS["integrators"][1])))
    else:
        parts += _scene_differs(build, build.integrators)
        parts.append(h.details("integrators.json", _run_table(build.integrators)))
    parts += _figures(build, "integrators")
    return h.section("convergence", "Convergence and the model chosen", parts)


def section_other(build: Build) -> str | None:
    figs = _figures(build, "other")
    return h.section("other", "Other figures", figs) if figs else None


def section_provenance(build: Build, timings: dict) -> str:
    parts = [h.tag("p", f"rotorpillar {__version__}; report written "
                        f"{datetime.now(timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}; off-screen "
                        f"rendering through {build.render_window or 'no 3D render'}.", class_="meta")]
    rows = []
    for js in sorted(build.out.glob("*.json")):
        if js.name in ("report.json", "run.json"):     # written after this page: stale here
            continue
        try:
            doc = json.loads(js.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        t = doc.get("timings", {}) if isinstance(doc, dict) else {}
        if not isinstance(t, dict):
            continue
        stages = ", ".join(f"{k} {v:.2f}" for k, v in t.items()
                           if k != "total" and isinstance(v, (int, float)))
        link = h.tag("a", js.name, href=h.relative(js, build.out))
        rows.append([link, h.num(t.get("total"), 4), stages,
                     datetime.fromtimestamp(js.stat().st_mtime).strftime("%Y-%m-%d %H:%M:%S")])
    own = ", ".join(f"{k} {v:.2f}" for k, v in build.render_seconds.items())
    rows.append(["this report", h.num(sum(build.render_seconds.values()), 4), own, "now"])
    parts.append(h.tag("h3", "Timings (s)"))
    parts.append(h.table(["result", "total", "stages", "written"], rows))
    parts.append(h.tag("h3", "Versions"))
    v = versions()
    parts.append(h.table(["package", "version"], [[k, val] for k, val in v.items()]))
    parts.append(h.tag("h3", "Machine"))
    parts.append(h.table(["", ""], [[k, h.num(val)] for k, val in machine().items()]))
    return h.section("provenance", "Versions, machine and timings", parts)


#: The page, in order: (anchor, title, builder).
SECTIONS = [
    ("summary", "Summary", section_summary),
    ("scene", "The scene", section_scene),
    ("modal", "Modal validation", section_modal),
    ("paper", "The paper's numbers against ours", section_paper),
    ("averaging", "Passage through resonance", section_averaging),
    ("runs", "The runs", section_runs),
    ("earthquake", "The earthquake", section_earthquake),
    ("convergence", "Convergence and the model chosen", section_convergence),
    ("other", "Other figures", section_other),
    ("provenance", "Versions, machine and timings", section_provenance),
]


def _guarded_section(build: Build, ident: str, title: str, fn, timings: dict) -> str | None:
    """A section, or, if its input does not have the shape it expects (an
    older or newer writer), a notice saying so: one section lost, not the page."""
    try:
        return fn(build, timings) if fn is section_provenance else fn(build)
    except Exception as exc:
        key = f"section_{ident}"
        build.failures[key] = f"{type(exc).__name__}: {exc}"
        _say(f"section {title!r} failed: {build.failures[key]}")
        traceback.print_exc(file=sys.stderr)
        return h.section(ident, title, [h.tag(
            "p", f"This section could not be written from its inputs ({build.failures[key]}); "
                 "they may come from another version of rotorpillar: re-run the command that "
                 "wrote them.", class_="failed")])


# --------------------------------------------------------------------------
# The build


def load_inputs(build: Build) -> None:
    out = build.out
    build.analyze = read_json(out / INPUTS["analyze"][0])
    build.modal = read_json(out / INPUTS["modal"][0])
    build.convergence = read_json(out / INPUTS["convergence"][0])
    build.integrators = read_json(out / INPUTS["integrators"][0])
    for case in CASES:
        sim = read_simulation(out, case)
        if sim is not None:
            build.simulations[case] = sim


def build_report(scene, out: str | Path, scene_cli: str, options: ReportOptions | None = None,
                 timings=None) -> dict:
    """Render every figure the inputs in ``out`` allow and write ``out/report.html``."""
    from ..provenance import Timings
    timings = Timings() if timings is None else timings
    build = Build(scene, Path(out), scene_cli, options or ReportOptions())
    with timings("read_inputs"):
        load_inputs(build)
    with timings("charts"):
        _render_charts(build)
    sets = {}
    with timings("mode_shapes"):
        sets = _mode_sets(build)
        _render_modes(build, sets)
    if build.options.animations:
        with timings("animations"):
            _render_animations(build, sets)
    if any(s is not None for s in sets.values()) or any(k.startswith("animation_") for k in build.products):
        from .offscreen import render_window_class
        build.render_window = _attempt(build, "render_window", render_window_class) or ""
    build.products["external"] = [Product(p, c, group=figure_group(p.name))
                                  for p, c in external_figures(build.out)]
    with timings("html"):
        nav, sections = [], []
        for ident, title, fn in SECTIONS:
            html_ = _guarded_section(build, ident, title, fn, dict(timings))
            if html_:
                nav.append((ident, title))
                sections.append(html_)
        title = f"rotorpillar report: {scene.name}"
        header = [h.tag("h1", title),
                  h.tag("p", scene.description or "", class_="meta"),
                  h.tag("p", "Validation report of the rotor on its pillar: the 3D modes against the "
                             "paper's closed forms, the paper's printed numbers against ours, the "
                             "passage through resonance, the transients, and how far to trust each "
                             "number.", class_="meta")]
        document = h.page(title, header, nav, sections)
        path = write_text(build.out / "report.html", document)
    figures = [str(p.path) for k, p in build.products.items()
               if isinstance(p, Product) and p.kind == "figure"]
    figures += [str(x.path) for k, v in build.products.items() if isinstance(v, list)
                for x in v if isinstance(x, Product)]
    animations = {k[len("animation_"):-len("_info")]: {kk: (str(vv) if isinstance(vv, Path) else vv)
                                                       for kk, vv in v.items()}
                  for k, v in build.products.items() if k.startswith("animation_") and k.endswith("_info")}
    present = {name: (build.out / f).is_file() for name, (f, _) in INPUTS.items()}
    present.update({f"simulate_{c}": c in build.simulations for c in CASES})
    return {"report": str(path), "inputs": present, "figures": sorted(figures),
            "animations": animations, "failures": build.failures,
            "render_seconds": build.render_seconds, "render_window": build.render_window,
            "bytes": path.stat().st_size}


def summary_text(result: dict) -> str:
    have = [k for k, v in result["inputs"].items() if v]
    lacking = [k for k, v in result["inputs"].items() if not v]
    lines = [f"report: {len(result['figures'])} figures, {len(result['animations'])} animation(s), "
             f"{result['bytes'] / 2**20:.1f} MB",
             "  inputs found: " + (", ".join(have) or "none"),
             "  not computed: " + (", ".join(lacking) or "nothing")]
    for k, v in result["animations"].items():
        lines.append(f"  animation {k}: {v['frames']} frames, x{v['factor']:g}, "
                     f"{v['seconds']:.1f} s -> {v['path']}")
    for k, v in result["failures"].items():
        lines.append(f"  FAILED {k}: {v}")
    lines.append("  render seconds: " + ", ".join(f"{k} {v:.1f}"
                                                  for k, v in result["render_seconds"].items()))
    return "\n".join(lines)
