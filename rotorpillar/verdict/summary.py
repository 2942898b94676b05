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

Headlines beside the checks: the loaded tube's first frequency, the running
speed's margin, the earthquake's peaks, the run-up, and from campbell.json
(the ROM's Campbell diagram and the 3D model's beside it) each model's first
forward and first backward critical speed and the first one the static
unbalance excites.

The earthquake in two or three components (compare_earthquake_components.json:
the spatial ROM over the whole record, the 3D full order over its window)
adds its base stress checks and leads the earthquake headlines
(rotorpillar.verdict.earthquake3d); the one-component runs stay beside it,
the model comparison.

Each check's governing row is its largest utilisation over the models and
cases; a check without a capacity (or a demand) is "not assessed", and the
verdict says so instead of passing it.  The paper model (Eq. 4 with the
stated reduction) has no sections and stays out of the checks.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..fem3d.modal_summary import ModalSummary
    from ..reduced.excitation import ExcitationSizes
    from ..scene import Scene
    from ..transients.model_run import RunRecord

import math
import re
from dataclasses import dataclass
from pathlib import Path

from .. import records
from ..analysis.machine import MachineChecks
from ..records import Record
from ..reduced.capacity import FAIL, GAMMA_M0, NOT_ASSESSED, PASS, Check, MeridionalBuckling, check
from ..reduced.participation import EffectiveMassTable
from ..scene import CASES, MODELS
from .harmonic import HarmonicResult
from .headline import Headline
from .headline import base_buckling as _buckling
from .machine import FoundationLoads
from .tower_checks import can_checks, foundation_checks, order_checks


class EngineeringSummary(Record):
    """summary.json: the verdict first, then the numbers a reader came for."""

    scene: str
    verdict: str
    """"pass" (every assessed check passes), "fail" (one fails) or "incomplete" (none assessed)"""
    checks: tuple[Check, ...]
    """per check, its governing model and case (the largest utilisation)"""
    check_details: tuple[Check, ...]
    """every model and case each check was evaluated on"""
    headlines: tuple[Headline, ...]
    buckling: MeridionalBuckling | None
    """the tube's design buckling stress at the governing demand"""
    not_assessed: tuple[str, ...]
    """the checks without a capacity or a demand, and what to state or run"""
    inputs: tuple[str, ...]
    """the files read"""
    machine_checks: MachineChecks | None = None
    """analyze.json's machine checks: balance grade, vibration at speed, modal mass (verdict.machine)"""
    effective_masses: tuple[EffectiveMassTable, ...] = ()
    """the loaded tube's 3D modes' effective masses along x, y, z (modal.json)"""
    foundation: tuple[FoundationLoads, ...] = ()
    """each run's design reactions at the base: each extreme with the others at its instant"""


#: the models whose runs the checks read (the paper's Eq. 4 has no sections)
CHECKED_MODELS = ("modal", "beam", "fem3d")
MODEL_NAMES = {"modal": "ROM", "beam": "1D beam, full order", "fem3d": "3D, full order", "paper": "the paper's Eq. 4"}
MODE_SOURCES = {"modal": "the ROM's coupled system", "fem3d": "the loaded tube's 3D modes"}
#: a model's run of a case: simulate's, or compare's (compare_<case>_<model> where compare names its own)
_RUN_FILE = re.compile(rf"(simulate|compare)_({'|'.join(CASES)})_({'|'.join(MODELS)})\.json")


@dataclass(frozen=True)
class RunFile:
    """A model's run of a case as a file in the out folder holds it."""

    file: str
    """the JSON's name"""
    run: RunRecord

    @property
    def label(self) -> str:
        """The case as a reader names it (:func:`case_name`)."""
        return case_name(self.run.case, self.run.excitation)


def case_name(case: str, excitation: ExcitationSizes | None) -> str:
    """The case as a reader names it: "earthquake (elcentro)", "runup"."""
    name = getattr(excitation, "name", None)
    if case == "earthquake" and name:
        return f"earthquake ({name})"
    return case


def every_run(out: Path, damaged: dict[str, str] | None = None) -> list[tuple[float, RunFile]]:
    """Every run file of ``out`` (simulate's and compare's) with its modification time (s),
    by name; a file that cannot be read as a run is left out, and named in ``damaged``
    (file -> why)."""
    from ..transients.model_run import RunRecord

    runs = []
    for path in sorted(Path(out).glob("*_*_*.json")):
        if not _RUN_FILE.fullmatch(path.name):
            continue
        try:
            got = RunFile(path.name, records.read(path, RunRecord))  # type: ignore[arg-type]  # a union
            runs.append((path.stat().st_mtime, got))
        except (OSError, ValueError) as exc:
            if damaged is not None:
                damaged[path.name] = str(exc)
    return runs


def model_runs(out: Path, damaged: dict[str, str] | None = None) -> list[RunFile]:
    """The runs of ``out``, one per (case as a reader names it, model): the newest file
    where simulate and compare both ran it; a file that cannot be read as a run is left
    out, and named in ``damaged`` (file -> why)."""
    found: dict[tuple, tuple[float, RunFile]] = {}
    for when, got in every_run(out, damaged):
        key = (got.label, got.run.model)
        if key not in found or when > found[key][0]:
            found[key] = (when, got)
    return [got for _, got in sorted(found.values(), key=lambda x: x[1].file)]


def _run_checks(scene: Scene, rf: RunFile) -> list[Check]:
    """The checks of one run's peaks."""
    run = rf.run
    model, case, src = run.model, rf.label, rf.file
    ma = run.max_abs
    forces = run.internal_forces
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
    share = forces.base.axial_share if forces is not None else 1.0
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
    if forces is not None:
        out += can_checks(scene, forces.cans or (), model, case, src)
        out += foundation_checks(scene, forces.foundation, model, case, src)
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
    shaft = forces.shaft if forces is not None else None
    force = max(
        [
            x
            for x in (
                None if shaft is None else shaft.spring_force,
                None if shaft is None else shaft.bearing_force,
                ma.get("bearing_force"),
            )
            if x is not None
        ],
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
    out += order_checks(h)
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


def _headlines(
    runs: list[RunFile],
    h: HarmonicResult | None,
    modal: ModalSummary | None,
    quake: tuple[Headline, ...] = (),
) -> list[Headline]:
    """The headlines; ``quake``: the multi-component earthquake's (verdict.earthquake3d), which
    lead the earthquakes (the one-component runs after them are the model comparison)."""
    out = []
    # the machine's first mode in the rotor's plane, the rotor on its shaft included (the
    # ROM's coupled system, undamped), first: the frequency the designer keeps clear of; the
    # tube's with the gondola only (below) is a part of it, named by what it includes
    plane = [] if h is None else [c for c in h.averaging if c.direction == "X" and c.omega > 0]
    if plane:
        w = min(c.omega for c in plane)
        out.append(
            Headline(
                "machine_first_frequency",
                "the machine's first natural frequency in the rotor's plane (tube, gondola and rotor)",
                w / (2 * math.pi),
                "Hz",
                "modal",
                "modal",
                "harmonic.json: averaging (the ROM's coupled modes in X, undamped)",
                f"The machine's first mode in the rotor's plane, the rotor on its shaft included: "
                f"{w / (2 * math.pi):.3f} Hz ({w:.2f} rad/s), undamped, ROM.",
            )
        )
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
                    "first bending frequency of the tube with the gondola, rotor apart",
                    w / (2 * math.pi),
                    "Hz",
                    "fem3d",
                    "modal",
                    "modal.json: modes_with_top",
                    f"The tube's first bending mode with the gondola on top, the rotor apart: "
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
    out += quake
    for rf in runs:
        run = rf.run
        if run.case != "earthquake" or getattr(run.excitation, "kind", None) != "record":
            continue
        model, case = run.model, rf.label
        ma = run.max_abs
        name = MODEL_NAMES.get(model, model)
        for key, label, unit, scale, fmt in (
            ("tip_x_relative", "peak tip displacement", "m", 1e3, "{:.2f} mm"),
            ("base_moment", "peak base moment", "N*m", 1e-6, "{:.3f} MN m"),
            ("shaft_deflection", "peak shaft deflection", "m", 1e3, "{:.2f} mm"),
        ):
            v = ma.get(key)
            if v is None:
                continue
            bars = getattr(run, "uncertainty", None) or {}
            u = bars.get(_BARRED.get(key, ""))
            err = None if u is None else u.error
            bar = "" if err is None else f" ± {err * scale:.2g}"
            out.append(
                Headline(
                    f"earthquake_{key}_{model}",
                    f"{case}: {label}",
                    float(v),
                    unit,
                    model,
                    case,
                    f"{rf.file}: max_abs.{key}",
                    f"{case.capitalize()}, {label}: {fmt.format(v * scale)}{bar} ({name}).",
                    err,
                )
            )
    found = _runup(runs)
    if found is not None:
        runup = found.run
        model = runup.model
        if runup.captured_at is not None:
            text = (
                f"captured at {runup.captured_at:.2f} rad/s below the resonance at "
                f"{runup.captured_resonance or float('nan'):.2f} rad/s"
            )
        else:
            text = f"passes its resonances, {runup.omega_final:.2f} rad/s at the end ({runup.speed_state})"
        out.append(
            Headline(
                "runup_passage",
                "run-up through the resonances",
                runup.captured_at or runup.omega_final,
                "rad/s",
                model,
                "runup",
                f"{found.file}: captured_at, omega_final",
                f"Run-up from rest ({MODEL_NAMES.get(model, model)}, {runup.duration:.0f} s): {text}.",
            )
        )
    return out


#: the Campbell headlines: (key, what, the critical speeds it picks from)
_CAMPBELL_FIRSTS = (
    ("first_forward_critical_speed", "first forward critical speed", lambda c: c.whirl == "forward"),
    ("first_backward_critical_speed", "first backward critical speed", lambda c: c.whirl == "backward"),
    (
        "first_unbalance_critical_speed",
        "first critical speed the static unbalance excites",
        lambda c: c.excited_by == "static unbalance",
    ),
)


def _campbell_headlines(d) -> list[Headline]:
    """campbell.json's first forward, first backward and first excited critical speed, per model
    (the ROM's and, beside it, the 3D model's); value None where the range has none."""
    if d is None:
        return []
    out = []
    for diagram, field in ((d, "critical_speeds"), (d.fem3d, "fem3d.critical_speeds")):
        if diagram is None:
            continue
        name = MODEL_NAMES.get(diagram.model, diagram.model) if diagram.model != "modal" else "ROM"
        if diagram.model == "fem3d":
            name = "3D model with the rotor on its top"
        top = float(diagram.speeds[-1])
        for key, what, pick in _CAMPBELL_FIRSTS:
            c = min((c for c in diagram.critical_speeds if pick(c)), key=lambda c: c.speed, default=None)
            if c is None:
                text = f"{what.capitalize()} ({name}): none up to {top:.1f} rad/s"
                if key != "first_unbalance_critical_speed":
                    # e.g. paper: its gondola's roll and pitch inertias split the two bending
                    # planes, so each crossing's orbit is a line
                    text += " (the crossings there whirl the other way or in a line)"
                text += "."
            else:
                whirl = "in a line (no whirl)" if c.whirl == "none" else f"{c.whirl} whirl"
                text = (
                    f"{what.capitalize()} ({name}): {c.speed:.2f} rad/s ({c.speed / (2 * math.pi):.3f} Hz), "
                    f"{c.label}, {whirl}, excited by {c.excited_by}."
                )
            out.append(
                Headline(
                    f"{key}_{diagram.model}",
                    what,
                    None if c is None else c.speed,
                    "rad/s",
                    diagram.model,
                    "campbell",
                    f"campbell.json: {field}",
                    text,
                )
            )
    return out


def _runup(runs: list[RunFile]) -> RunFile | None:
    """The run-up a reader reads: the ROM's, else the beam's, else any."""
    by_model = {rf.run.model: rf for rf in runs if rf.run.case == "runup"}
    for m in ("modal", "beam", "fem3d", "paper"):
        if m in by_model:
            return by_model[m]
    return None


def engineering_summary(scene: Scene, out: Path) -> EngineeringSummary:
    """The verdict of the files in ``out`` (see the module text)."""
    from ..fem3d.modal_summary import ModalSummary
    from .earthquake3d import COMPONENTS_FILE, earthquake3d, read_components
    from .machine import foundation_loads, machine_check_rows, run_mass_rows, tube_effective_masses

    out = Path(out)
    damaged: dict[str, str] = {}  # file -> why it cannot be read (records.read's line)
    runs = model_runs(out, damaged)
    inputs = [rf.file for rf in runs]
    rows = []
    for rf in runs:
        if rf.run.model in CHECKED_MODELS:
            rows += _run_checks(scene, rf)
    # the earthquake in two or three components (the one the page leads with), beside the runs'
    components = read_components(out, damaged)
    quake = None if components is None else earthquake3d(scene, components)
    if quake is not None:
        inputs.append(COMPONENTS_FILE)
        rows += quake.checks
    harmonic = modal = None
    if (out / "harmonic.json").is_file():
        try:
            harmonic = records.read(out / "harmonic.json", HarmonicResult)
            inputs.append("harmonic.json")
            rows += _margin_checks(harmonic)
        except (ValueError, OSError) as exc:  # damaged: its checks are not assessed, and it is named
            harmonic, damaged["harmonic.json"] = None, str(exc)
    if (out / "modal.json").is_file():
        try:
            modal = records.read(out / "modal.json", ModalSummary)
            inputs.append("modal.json")
        except (ValueError, OSError) as exc:
            modal, damaged["modal.json"] = None, str(exc)
    machine = _read_machine(out)
    if machine is not None:
        inputs.append("analyze.json")
        rows += machine_check_rows(machine) + run_mass_rows(machine, runs)
    campbell = None
    if (out / "campbell.json").is_file():
        from ..reduced.campbell import CampbellDiagram

        try:
            campbell = records.read(out / "campbell.json", CampbellDiagram)
            inputs.append("campbell.json")
        except (ValueError, OSError) as exc:  # damaged: no Campbell headlines, and it is named
            campbell, damaged["campbell.json"] = None, str(exc)
    governing = _governing(rows)
    missing = _not_assessed(governing, harmonic is not None, bool(runs) or quake is not None)
    missing += [f"{file} is damaged, not read ({why}): rebuild it" for file, why in damaged.items()]
    if machine is None:
        missing.append("balance, vibration at speed, modal mass: analyze.json not found (run `rotorpillar analyze`)")
    assessed = [c for c in governing if c.status != NOT_ASSESSED]
    verdict = "fail" if any(c.status == FAIL for c in assessed) else "pass" if assessed else "incomplete"
    share = max(
        (c for c in governing if c.name == "base stress vs shell buckling"),
        key=lambda c: c.utilisation or 0.0,
        default=None,
    )
    buckling = None
    if share is not None and quake is not None and (share.model, share.case) in quake.shares:
        buckling = _buckling(scene, quake.shares[(str(share.model), str(share.case))])
    elif share is not None:
        source = next((r for r in runs if r.run.model == share.model and r.label == share.case), None)
        forces = None if source is None else source.run.internal_forces
        buckling = _buckling(scene, forces.base.axial_share if forces is not None else 1.0)
    return EngineeringSummary(
        scene.name,
        verdict,
        tuple(governing),
        tuple(rows),
        tuple(
            _headlines(runs, harmonic, modal, () if quake is None else quake.headlines) + _campbell_headlines(campbell)
        ),
        buckling,
        tuple(missing),
        tuple(inputs),
        machine,
        () if modal is None else tube_effective_masses(scene, modal),
        tuple(foundation_loads(runs)),
    )


def _read_machine(out: Path) -> MachineChecks | None:
    """analyze.json's machine block (None: no file, a damaged one, or one from before it)."""
    from ..analysis.results import AnalysisResult

    try:
        return (
            records.read(out / "analyze.json", AnalysisResult).machine_checks
            if (out / "analyze.json").is_file()
            else None
        )
    except (ValueError, OSError):  # damaged: its checks are not assessed
        return None


def _not_assessed(governing: list[Check], have_harmonic: bool, have_runs: bool) -> list[str]:
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
        out.append("separation margins: no readable harmonic.json (run `rotorpillar harmonic`)")
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
