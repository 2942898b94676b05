"""summary.json: the checks against the scene's capacities and the numbers a reader came for.

Read from what the stages wrote in ``out/<scene>/`` (every
``simulate_<case>_<model>.json`` of the ROM, the beam and the 3D model,
harmonic.json, modal.json); every number names the model and the case it
came from.  The checks (rotorpillar.reduced.capacity):

- base stress |M| c / I + N / A against the yield strength (gamma_M0 = 1);
- the same against the tube's shell buckling resistance sigma_x,Rd
  (EN 1993-1-6, its C_x from that demand's share of axial stress);
- the 3D model's peak von Mises stress against the yield strength;
- the radial shaft deflection against ``rotor.clearance``;
- the shaft's force (spring and damper, the larger of |c2 d| and |c2 d +
  b2 v|) against ``shaft.force_limit``;
- each running speed's separation from every mode in the band (API 684):
  utilisation = the margin required / the margin there is.

Each check's governing row is its largest utilisation over the models and
cases; a check without a capacity (or a demand) is "not assessed", and the
verdict says so instead of passing it.  The paper model (Eq. 4 with the
stated reduction) has no sections and stays out of the checks.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..fem3d.modal_summary import ModalSummary
    from ..scene import Scene

import json
import math
import re
from pathlib import Path

from ..reduced.capacity import FAIL, GAMMA_M0, NOT_ASSESSED, PASS, Check, check, meridional_buckling
from ..reduced.pillar import section_of
from ..scene import CASES, MODELS
from .records import EngineeringSummary, HarmonicResult, Headline

#: the models whose runs the checks read (the paper's Eq. 4 has no sections)
CHECKED_MODELS = ("modal", "beam", "fem3d")
MODEL_NAMES = {"modal": "ROM", "beam": "1D beam, full order", "fem3d": "3D, full order", "paper": "the paper's Eq. 4"}
MODE_SOURCES = {"modal": "the ROM's coupled system", "fem3d": "the loaded tube's 3D modes"}
#: a model's run of a case: simulate's, or compare's (compare_<case>_<model> where compare names its own)
_RUN_FILE = re.compile(rf"(simulate|compare)_({'|'.join(CASES)})_({'|'.join(MODELS)})\.json")


def case_label(doc: dict) -> str:
    """The case of a run's JSON document as a reader names it (:func:`case_name`)."""
    return case_name(doc.get("case", "?"), doc.get("excitation"))


def case_name(case: str, excitation: dict | None) -> str:
    """The case as a reader names it: "earthquake (elcentro)", "runup"."""
    ex = excitation or {}
    if case == "earthquake" and ex.get("name"):
        return f"earthquake ({ex['name']})"
    if case == "earthquake" and ex.get("kind") == "paper":
        return "earthquake (the paper's pulse)"
    return case


def model_runs(out: Path) -> list[dict]:
    """The runs' JSON documents of ``out``, one per (case as named by ``case_label``,
    model): the newest file where simulate and compare both ran it."""
    found: dict[tuple, tuple] = {}
    for path in sorted(Path(out).glob("*_*_*.json")):
        if not _RUN_FILE.fullmatch(path.name):
            continue
        try:
            doc = json.loads(path.read_text(encoding="utf-8"))
            when = path.stat().st_mtime
        except (OSError, ValueError):
            continue
        if not isinstance(doc, dict) or "model" not in doc:
            continue
        doc["_file"] = path.name
        key = (case_label(doc), doc["model"])
        if key not in found or when > found[key][0]:
            found[key] = (when, doc)
    return [doc for _, doc in sorted(found.values(), key=lambda x: x[1]["_file"])]


def _run_checks(scene: Scene, doc: dict) -> list[Check]:
    """The checks of one run's peaks."""
    model, case = doc.get("model"), case_label(doc)
    src = doc["_file"]
    ma = doc.get("max_abs") or {}
    forces = doc.get("internal_forces") or {}
    mat = scene.material
    out = []
    stress = ma.get("base_stress")
    out.append(
        check(
            "base stress vs yield",
            "base_stress",
            "Pa",
            stress,
            mat.yield_strength / GAMMA_M0,
            model,
            case,
            f"{src}: max_abs.base_stress; f_yk = material.yield_strength, gamma_M0 = {GAMMA_M0:g}",
        )
    )
    share = (forces.get("base") or {}).get("axial_share", 1.0)
    b = _buckling(scene, share)
    out.append(
        check(
            "base stress vs shell buckling",
            "base_stress",
            "Pa",
            stress,
            b.design_stress,
            model,
            case,
            f"{src}: max_abs.base_stress; sigma_x,Rd of EN 1993-1-6 (class "
            f"{mat.fabrication_class}, C_x {b.cx:.3g} at the demand's axial share "
            f"{share:.3g})",
        )
    )
    if model == "fem3d":
        out.append(
            check(
                "von Mises (3D) vs yield",
                "von_mises",
                "Pa",
                ma.get("von_mises"),
                mat.yield_strength / GAMMA_M0,
                model,
                case,
                f"{src}: max_abs.von_mises (the projected field's peak, clamp included)",
            )
        )
    out.append(
        check(
            "shaft deflection vs clearance",
            "shaft_deflection",
            "m",
            ma.get("shaft_deflection"),
            scene.rotor.clearance,
            model,
            case,
            f"{src}: max_abs.shaft_deflection (radial); rotor.clearance",
        )
    )
    shaft = forces.get("shaft") or {}
    force = max(
        [x for x in (shaft.get("spring_force"), shaft.get("bearing_force"), ma.get("bearing_force")) if x is not None],
        default=None,
    )
    out.append(
        check(
            "shaft force vs force limit",
            "bearing_force",
            "N",
            force,
            scene.shaft.force_limit,
            model,
            case,
            f"{src}: the larger of c2 |d| and |c2 d + b2 v|; shaft.force_limit",
        )
    )
    return [c for c in out if c.demand is not None or c.capacity is not None]


def _buckling(scene: Scene, axial_share: float = 1.0):
    p, mat = scene.pillar, scene.material
    sec = section_of(p)
    r = (p.outer_diameter + p.inner_diameter) / 4
    return meridional_buckling(
        p.youngs_modulus, r, sec.wall_thickness, p.height, mat.yield_strength, mat.fabrication_class, axial_share
    )


def _margin_checks(h: HarmonicResult) -> list[Check]:
    out = []
    for row in h.separation:
        req, act = row.required, row.actual
        if req <= 0:
            status, util = PASS, 0.0
        else:
            util = req / act if act > 0 else math.inf
            status = PASS if act >= req else FAIL
        af = _af_text(row)
        out.append(
            Check(
                "separation margin (API 684)",
                "separation_margin",
                "-",
                float(req),
                float(act),
                float(util),
                status,
                row.mode.model,
                f"running at {row.running_speed:.4g} rad/s",
                f"harmonic.json: {row.mode.kind} at {row.mode.omega:.4g} rad/s, {af}, "
                f"{row.position} the running speed; demand = the margin required, "
                "capacity = the margin there is",
            )
        )
    return out


def _af_text(row) -> str:
    """The row's AF in words: from its response peak, none (no peak: no margin), or 1/(2 zeta)."""
    if row.amplification_factor is not None:
        return f"AF {row.amplification_factor:.3g}"
    if "no peak" in getattr(row, "af_source", ""):
        return "no peak in the unbalance response (no margin required)"
    return "AF infinite (undamped)"


def _governing(rows: list[Check]) -> list[Check]:
    """Per check name, the row with the largest utilisation (not assessed: the largest demand)."""
    out: dict[str, Check] = {}
    for c in rows:
        best = out.get(c.name)
        key = (c.utilisation if c.utilisation is not None else -1.0, c.demand or 0.0)
        if best is None or key > (best.utilisation if best.utilisation is not None else -1.0, best.demand or 0.0):
            out[c.name] = c
    return list(out.values())


#: max_abs keys and the error bars a ROM run carries for them (transients.uncertainty)
_BARRED = {"tip_x_relative": "peak_tip_relative"}


def _headlines(scene: Scene, docs: list[dict], h: HarmonicResult | None, modal: ModalSummary | None) -> list[Headline]:
    out = []
    if modal is not None:
        rows = [r for r in modal.modes_with_top if r.kind == "bending_x"]
        if rows:
            w = rows[0].omega
            mesh = modal.mesh
            # its discretisation error: the study's bound on this mesh's bending frequency
            pm = modal.pillar_model
            rel = None if pm is None else pm.errors.get("bending")
            err = None if rel is None else rel * w / (2 * math.pi)
            bar = (
                f" ± {err:.2g} Hz (the convergence study's bound on this mesh)"
                if err is not None
                else " (unverified: no convergence study measured this mesh)"
            )
            out.append(
                Headline(
                    "loaded_first_frequency",
                    "first bending frequency, gondola on top",
                    w / (2 * math.pi),
                    "Hz",
                    "fem3d",
                    "modal",
                    "modal.json: modes_with_top",
                    f"The loaded tube's first bending mode: "
                    f"{w / (2 * math.pi):.3f} Hz{bar} ({w:.2f} rad/s), 3D model "
                    f"({mesh.elements_around} x {mesh.elements_along} elements), "
                    "modal analysis.",
                    err,
                )
            )
    if h is not None and h.separation:
        row = min(h.separation, key=lambda r: r.actual)
        af = _af_text(row)
        out.append(
            Headline(
                "running_speed_margin",
                "the running speed's margin to the nearest mode",
                100 * row.actual,
                "%",
                row.mode.model,
                f"running at {row.running_speed:.4g} rad/s",
                "harmonic.json: separation",
                f"Running speed {row.running_speed:.2f} rad/s ({row.running_speed / (2 * math.pi):.2f} Hz): "
                f"the nearest mode is the {row.mode.kind} at {row.mode.omega:.2f} rad/s "
                f"({MODE_SOURCES.get(row.mode.model, row.mode.model)}), "
                f"{100 * row.actual:.1f} % {row.position}; API 684 asks "
                f"{100 * row.required:.1f} % ({af}): {row.status}.",
            )
        )
    for doc in docs:
        if doc.get("case") != "earthquake" or (doc.get("excitation") or {}).get("kind") != "record":
            continue
        model, case = doc["model"], case_label(doc)
        ma = doc.get("max_abs") or {}
        name = MODEL_NAMES.get(model, model)
        for key, label, unit, scale, fmt in (
            ("tip_x_relative", "peak tip displacement", "m", 1e3, "{:.2f} mm"),
            ("base_moment", "peak base moment", "N*m", 1e-6, "{:.3f} MN m"),
            ("shaft_deflection", "peak shaft deflection", "m", 1e3, "{:.2f} mm"),
        ):
            v = ma.get(key)
            if v is None:
                continue
            u = (doc.get("uncertainty") or {}).get(_BARRED.get(key, "")) or {}
            err = u.get("error") if isinstance(u, dict) else None
            bar = "" if err is None else f" ± {err * scale:.2g}"
            out.append(
                Headline(
                    f"earthquake_{key}_{model}",
                    f"{case}: {label}",
                    float(v),
                    unit,
                    model,
                    case,
                    f"{doc['_file']}: max_abs.{key}",
                    f"{case.capitalize()}, {label}: {fmt.format(v * scale)}{bar} ({name}).",
                    err,
                )
            )
    runup = _runup(docs)
    if runup is not None:
        model = runup["model"]
        state = runup.get("speed_state")
        if runup.get("captured_at") is not None:
            text = (
                f"captured at {runup['captured_at']:.2f} rad/s below the resonance at "
                f"{runup.get('captured_resonance') or float('nan'):.2f} rad/s"
            )
        else:
            text = f"passes its resonances, {runup['omega_final']:.2f} rad/s at the end ({state})"
        out.append(
            Headline(
                "runup_passage",
                "run-up through the resonances",
                runup.get("captured_at") or runup.get("omega_final"),
                "rad/s",
                model,
                "runup",
                f"{runup['_file']}: captured_at, omega_final",
                f"Run-up from rest ({MODEL_NAMES.get(model, model)}, {runup.get('duration', 0):.0f} s): {text}.",
            )
        )
    return out


def _runup(docs: list[dict]) -> dict | None:
    """The run-up a reader reads: the ROM's, else the beam's, else any."""
    runs = {d["model"]: d for d in docs if d.get("case") == "runup"}
    for m in ("modal", "beam", "fem3d", "paper"):
        if m in runs:
            return runs[m]
    return None


def engineering_summary(scene: Scene, out: Path) -> EngineeringSummary:
    """The verdict of the files in ``out`` (see the module text)."""
    from ..fem3d.modal_summary import ModalSummary

    out = Path(out)
    docs = model_runs(out)
    inputs = [d["_file"] for d in docs]
    rows = []
    for doc in docs:
        if doc.get("model") in CHECKED_MODELS:
            rows += _run_checks(scene, doc)
    harmonic = modal = None
    if (out / "harmonic.json").is_file():
        try:
            harmonic = HarmonicResult.read(out / "harmonic.json")
            inputs.append("harmonic.json")
            rows += _margin_checks(harmonic)
        except (KeyError, TypeError, ValueError, OSError):
            harmonic = None
    if (out / "modal.json").is_file():
        try:
            modal = ModalSummary.read(out / "modal.json")
            inputs.append("modal.json")
        except (KeyError, TypeError, ValueError, OSError):
            modal = None
    governing = _governing(rows)
    missing = _not_assessed(scene, governing, harmonic is not None, bool(docs))
    assessed = [c for c in governing if c.status != NOT_ASSESSED]
    verdict = "fail" if any(c.status == FAIL for c in assessed) else "pass" if assessed else "incomplete"
    share = max(
        (c for c in governing if c.name == "base stress vs shell buckling"),
        key=lambda c: c.utilisation or 0.0,
        default=None,
    )
    buckling = None
    if share is not None:
        doc = next((d for d in docs if d.get("model") == share.model and case_label(d) == share.case), {})
        buckling = _buckling(scene, ((doc.get("internal_forces") or {}).get("base") or {}).get("axial_share", 1.0))
    return EngineeringSummary(
        scene.name,
        verdict,
        tuple(governing),
        tuple(rows),
        tuple(_headlines(scene, docs, harmonic, modal)),
        buckling,
        tuple(missing),
        tuple(inputs),
    )


def _not_assessed(scene: Scene, governing: list[Check], have_harmonic: bool, have_runs: bool) -> list[str]:
    out = [
        f"{c.name}: "
        + ("no capacity stated" if c.capacity is None else "no demand computed")
        + (" (state rotor.clearance, m)" if c.quantity == "shaft_deflection" and c.capacity is None else "")
        + (" (state shaft.force_limit, N)" if c.quantity == "bearing_force" and c.capacity is None else "")
        for c in governing
        if c.status == NOT_ASSESSED
    ]
    if not have_runs:
        out.append("stresses, clearance, shaft force: no transient run found (run `rotorpillar compare`)")
    if not have_harmonic:
        out.append("separation margins: harmonic.json not found (run `rotorpillar harmonic`)")
    return out


def write_summary(scene: Scene, out: Path) -> Path | None:
    """Write out/summary.json (atomically) and return its path; None, and nothing
    written, when there is nothing to check (no run, no harmonic.json, no modal.json)."""
    import time

    from ..provenance import write_result

    start = time.perf_counter()
    record = engineering_summary(scene, out)
    if not record.inputs:
        return None
    # its ``scene`` is the scene's name (the record's field); the resolved scene is report.json's
    return write_result(Path(out) / "summary.json", record, timings={"summary": time.perf_counter() - start})


def summary_lines(s: EngineeringSummary) -> list[str]:
    """The verdict in a few lines of text."""
    lines = [f"verdict: {s.verdict}"]
    for c in s.checks:
        u = "-" if c.utilisation is None else f"{c.utilisation:.3f}"
        lines.append(f"  {c.name:<32} {c.status:<13} utilisation {u:>7}  ({c.model}, {c.case})")
    lines += ["  " + x for x in s.not_assessed]
    return lines
