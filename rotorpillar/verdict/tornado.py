"""tornado.json: how much the verdict's checks depend on the inputs nobody knows well.

A one-at-a-time sensitivity on the ROM (the planar modal model on the chain's
pillar modes, the model of the headline and of the machine's checks): each
uncertain input at the low and the high end of its range, every other key at
the scene's value, and at each end

- the machine's checks exactly as `analyze` makes them (rotorpillar.analysis.machine:
  the balance grade, the shaft's steady orbit against API 617, the top's
  velocity against ISO 20816-3, the modal mass against EN 1998-1), at the
  running speed the averaging theory gives for that end's drive and ROM;
- the separation margins (API 684) and the excitation orders as `harmonic`
  makes them on the ROM (rotorpillar.verdict.harmonic, without its 3D
  response: ~0.2 s an end), modal.json's loaded-tube modes included when the
  out folder holds one;
- the ROM's run-up from rest and its earthquake (the scene's record, whole),
  through the design study's batch loop (rotorpillar.studies.design_study, one
  study per end and case): their peak shaft deflection
  against ``rotor.clearance`` where the scene states one, and the peaks
  themselves as responses (no capacity).

The default inputs and their ranges (``default_inputs``; ``--vary KEY=LO,HI``
replaces one or adds another):

- ``pillar.damping`` (b1), half to twice the scene's, and the spatial
  model's ``pillar.damping_ratio`` by the same factor (``SCALED_WITH``): the
  paper itself gives b1 only as a range, 10e3 to 50e3 N s/m (Section 2.5), a
  third to five thirds of its midpoint, and measured damping of welded steel
  towers scatters by a factor of two about the one value codes tabulate per
  type (EN 1991-1-4 Annex F gives one logarithmic decrement per structure type);
- ``rotor.eccentricity``, one balance grade either way: ISO 21940-11's
  grades step by a factor of 2.5 (G 1, 2.5, 6.3, 16, 40, ...), and a
  rotor balanced to a grade may sit anywhere within its step;
- ``shaft.stiffness`` (c2), +-20 %: an assumption (bearing and pedestal
  stiffnesses are estimates; no source here gives their scatter);
- ``modal_model.source``, the top plate's model: the 1D beam's point mass at
  the tip (``beam``) against the 3D model's rigid top plate (``fem3d``), each
  end its own chain of pillar modes (the 3D modes cached per machine).

What would change the verdict: for every check, the input value where its
utilisation reaches 1, linear between the scene's value and the end on that
side ("interpolated" when inside the range, "extrapolated" beyond it: a hint,
not a computed point).  Left out: the stress and buckling checks (the batch
loop records no section forces; on the paper's machine they use about 1 % of
their capacity) and the 3D harmonic response, which the record's ``left_out``
names.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from ..records import Figure, Record, replace
from ..reduced.capacity import FAIL, NOT_ASSESSED, PASS, Check, check
from ..scene import Scene, with_values

if TYPE_CHECKING:
    from ..studies.result import StudyRun

#: one balance grade of ISO 21940-11 (the grades step by this factor)
GRADE_STEP = 2.5
#: the pillar's damping: half to twice the scene's
DAMPING_FACTOR = 2.0
#: the shaft's stiffness: +-20 %
STIFFNESS_SPREAD = 0.20
#: the farthest an extrapolated crossing is reported, in lengths of the half-range it
#: extends (beyond, a line through two points says nothing: the responses are not linear)
MAX_REACH = 5.0
#: the top plate's models in words (modal_model.source's words)
SOURCE_WORDS = {"beam": "the 1D beam's point mass", "fem3d": "the 3D model's rigid top plate"}
#: the transient cases each end runs, as the design study names them
CASES = ("runup", "earthquake")
#: the transients' responses: (name, case, StudyRun field, unit)
RESPONSES = (
    ("run-up: peak shaft deflection", "runup", "peak_shaft_deflection", "m"),
    ("earthquake: peak tip displacement", "earthquake", "peak_tip", "m"),
    ("earthquake: peak shaft deflection", "earthquake", "peak_shaft_deflection", "m"),
)
LEFT_OUT = (
    "the base stress against yield and shell buckling, the cans' and the foundation's checks: "
    "the design study's batch loop records no section forces",
    "the 3D model's harmonic response: the separation margins' amplification factors here are the "
    "spatial ROM's alone (the verdict's margins take the larger of the two for the 3D modes)",
)

Param = bool | int | float | str
"""A value of a scene key (a number, or a word such as a mode source)."""


class TornadoInput(Record):
    """One uncertain input: a scene key, its value in the scene and the two ends of its range."""

    key: str
    """section.key of the scene"""
    label: str
    """what it is, in words"""
    unit: str
    """of base, low and high ("-" for a word)"""
    base: Param
    """the scene's value"""
    low: Param
    """the range's low end (for a word: the first choice)"""
    high: Param
    """the range's high end (the second choice)"""
    why: str
    """where the range comes from"""


class Crossing(Record):
    """Where a check's utilisation reaches 1 along one input (linear between two computed points)."""

    value: float
    """the input's value there (the input's unit)"""
    kind: str
    """"interpolated" (inside the range computed) or "extrapolated" (beyond it: a hint)"""
    side: str
    """"low" or "high": the end the line runs to"""


class TornadoBar(Record):
    """One quantity at the two ends of one input's range."""

    key: str
    """the input's scene key"""
    low: float | None
    """the quantity at the low end (its unit; None: not computed)"""
    high: float | None
    """at the high end"""
    low_status: str | None = None
    """a check's "pass", "fail" or "not assessed" at the low end (None: a response)"""
    high_status: str | None = None
    """at the high end"""
    crossing: Crossing | None = None
    """a check: where its utilisation reaches 1 along this input (None: nowhere the line goes)"""

    @property
    def swing(self) -> float:
        """|high - low| (0 where an end is missing): the bar's length."""
        return 0.0 if self.low is None or self.high is None else abs(self.high - self.low)


class TornadoQuantity(Record):
    """A check's utilisation, or a response, over every input."""

    name: str
    """e.g. "shaft vibration (API 617)" or "earthquake: peak tip displacement\""""
    kind: str
    """"check" (the value is a utilisation, demand over capacity) or "response" (no capacity)"""
    unit: str
    """"-" for a utilisation, else the response's (m)"""
    base: float | None
    """at the scene's values"""
    base_status: str | None
    """a check's status at the scene's values (None: a response)"""
    model: str
    """the model, in words"""
    case: str
    """the case it comes from (running speed, run-up, earthquake)"""
    bars: tuple[TornadoBar, ...]
    """one per input, the longest first"""


class VerdictChange(Record):
    """What one input would have to do to change the verdict over the tornado's checks."""

    key: str
    """the input's scene key"""
    verdict: str
    """the verdict it would turn to, "pass" or "fail\""""
    value: Param
    """the input's value where it turns (for a word: the choice that turns it)"""
    kind: str
    """"interpolated", "extrapolated" (a linear hint beyond the range) or "computed" (an end of the range)"""
    checks: tuple[str, ...]
    """the checks that cross"""


class TornadoResult(Record):
    """tornado.json: the governing checks' utilisations at the ends of each uncertain input's range."""

    scene_name: str
    verdict: str
    """over the tornado's checks at the scene's values: "pass", "fail" or "incomplete" (none assessed)"""
    inputs: tuple[TornadoInput, ...]
    quantities: tuple[TornadoQuantity, ...]
    """the assessed checks, the governing first, then the responses"""
    changes: tuple[VerdictChange, ...]
    """per input, the value that would turn the verdict (none: no line reaches it)"""
    sentence: str
    """what would change the verdict, in words (the report prints it)"""
    left_out: tuple[str, ...]
    """the checks and inputs not in the tornado, and why"""
    runs: int
    """transient runs of the ROM (-)"""
    wall_seconds: float
    """the whole sensitivity (s)"""
    notes: tuple[str, ...] = ()
    """runs that failed their checks or were captured, in words"""
    figures: tuple[Figure, ...] = ()
    """the chart"""


# --------------------------------------------------------------------------
# The inputs


def key_limits(key: str) -> tuple[float, float]:
    """The range a scene key allows, (lowest, highest) (inclusive; a strict bound taken as the
    bound: the ends here are a factor away from a valid scene value, never on it).

    >>> key_limits("rotor.eccentricity")
    (0.0, 1.0)
    """
    import dataclasses
    import math

    from ..scene import SECTIONS

    section, name = key.split(".")
    meta = next(f.metadata for f in dataclasses.fields(SECTIONS[section]) if f.name == name)
    lo = next((meta[k] for k in ("ge", "gt") if meta.get(k) is not None), -math.inf)
    hi = next((meta[k] for k in ("le", "lt") if meta.get(k) is not None), math.inf)
    return float(lo), float(hi)


def _number(key: str, label: str, unit: str, base: float, low: float, high: float, why: str) -> TornadoInput:
    """A numeric input; an end past the key's own range is cut at its limit, and ``why`` says so."""
    lo_limit, hi_limit = key_limits(key)
    cut: list[str] = []
    if low < lo_limit:
        low, cut = lo_limit, cut + [f"the low end cut at the key's limit, {lo_limit:g}"]
    if high > hi_limit:
        high, cut = hi_limit, cut + [f"the high end cut at the key's limit, {hi_limit:g}"]
    return TornadoInput(key, label, unit, float(base), float(low), float(high), why + "".join(f"; {c}" for c in cut))


def default_inputs(scene: Scene, with_fem3d: bool = True) -> tuple[list[TornadoInput], list[str]]:
    """The uncertain inputs and their ranges (see the module text), and the ones left out and why."""
    out, left = [], []
    b1, e, c2 = scene.pillar.damping, scene.rotor.eccentricity, scene.shaft.stiffness
    if b1 > 0:
        out.append(
            _number(
                "pillar.damping",
                "pillar's damping",
                "N*s/m",
                b1,
                b1 / DAMPING_FACTOR,
                b1 * DAMPING_FACTOR,
                "half to twice the scene's: the paper gives b1 only as a range (10e3 to 50e3 N s/m, "
                "Section 2.5), and measured damping of welded steel towers scatters by about a factor "
                "of two about the one value EN 1991-1-4 Annex F tabulates per type; the spatial "
                "model's modal damping ratio scaled by the same factor",
            )
        )
    else:
        left.append("pillar.damping: 0 in the scene, no range by a factor")
    if e > 0:
        out.append(
            _number(
                "rotor.eccentricity",
                "eccentricity",
                "m",
                e,
                e / GRADE_STEP,
                e * GRADE_STEP,
                f"one balance grade either way: ISO 21940-11's grades step by a factor of {GRADE_STEP:g}",
            )
        )
    else:
        left.append("rotor.eccentricity: 0 in the scene, no range by a factor")
    out.append(
        _number(
            "shaft.stiffness",
            "shaft's stiffness",
            "N/m",
            c2,
            c2 * (1 - STIFFNESS_SPREAD),
            c2 * (1 + STIFFNESS_SPREAD),
            f"+-{100 * STIFFNESS_SPREAD:.0f} %: an assumption (bearing and pedestal stiffnesses are "
            "estimates; no source here gives their scatter)",
        )
    )
    if with_fem3d:
        out.append(
            TornadoInput(
                "modal_model.source",
                "top plate's model",
                "-",
                scene.modal_model.source,
                "beam",
                "fem3d",
                "the 1D beam's point mass at the tip against the 3D model's rigid top plate",
            )
        )
    else:
        left.append("modal_model.source (the top plate's model): dolfinx is not installed, no 3D modes")
    return out, left


def vary_input(text: str, scene: Scene) -> TornadoInput:
    """``--vary KEY=LO,HI``: an input's range, checked as the study checks an axis (bad input:
    InputError naming the key and its range)."""
    from ..errors import InputError
    from ..studies.axes import parse_vary

    axis = parse_vary(text, scene)
    vals = axis.values
    if len(vals) != 2 or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in vals):
        raise InputError(f"--vary {axis.key}: give the two ends of its range as numbers, KEY=LO,HI")
    section, name = axis.key.split(".")
    base = getattr(getattr(scene, section), name)
    if not isinstance(base, (int, float)) or isinstance(base, bool):
        raise InputError(f"--vary {axis.key}: the scene's value {base!r} is not a number")
    lo, hi = sorted(float(v) for v in vals)
    return _number(axis.key, axis.key, "", base, lo, hi, "given on the command line (--vary)")


def inputs_for(scene: Scene, vary: list[str], with_fem3d: bool) -> tuple[list[TornadoInput], list[str]]:
    """The default inputs with ``--vary``'s ranges in place (and added); every range checked."""
    from ..errors import InputError
    from ..studies.axes import parse_vary

    given = [vary_input(t, scene) for t in vary]
    out, left = default_inputs(scene, with_fem3d)
    keys = {g.key for g in given}
    out = [i for i in out if i.key not in keys] + given
    for i in out:
        if isinstance(i.low, float) and isinstance(i.high, float) and i.key not in keys:
            try:  # the ends within the key's range (cut there), and the scene's cross-checks
                parse_vary(f"{i.key}={i.low!r},{i.high!r}", scene)
            except InputError as exc:
                raise InputError(
                    f"tornado: the default range of {i.key}, {i.low:g} to {i.high:g}, makes no valid scene "
                    f"({str(exc).split(': ', 1)[-1]}); give one with --vary {i.key}=LO,HI"
                ) from None
    return out, left


# --------------------------------------------------------------------------
# One end


class _End:
    """What one scene gave: the checks by name and the responses by name."""

    def __init__(self, checks: list[Check], responses: dict[str, float], notes: list[str]):
        self.checks = {c.name: c for c in checks}
        self.responses = responses
        self.notes = notes


def machine_rows(scene: Scene, chain) -> list[Check]:
    """The machine's checks as `analyze` makes them, on ``chain``'s ROM at its running speed."""
    from ..analysis.machine import machine_checks
    from ..analysis.scene_analysis import headline_analysis
    from ..reduced import averaging as av
    from .machine import machine_check_rows

    d, r = scene.drive, scene.rotor
    ch = av.Characteristic(d.torque_at_zero, d.slope, scene.load.coefficient)
    _, _, drive, planar = headline_analysis(scene, chain, ch, scene.shaft.stiffness * r.eccentricity)
    return machine_check_rows(machine_checks(scene, planar, chain.modes, drive.runup_speed))


def margin_rows(scene: Scene, chain, out: Path) -> list[Check]:
    """The separation margins (API 684) and the excitation orders as `harmonic` makes them on the
    ROM (its spatial response; modal.json's loaded-tube modes when ``out`` holds one), the 3D
    harmonic response left out; one row per check, its largest utilisation."""
    from .harmonic import harmonic_analysis
    from .summary import _margin_checks  # summary.json's own rows of harmonic.json

    rows: dict[str, Check] = {}
    for c in _margin_checks(harmonic_analysis(scene, out, with_fem3d=False, chain=chain)):
        if c.name not in rows or (c.utilisation or 0.0) > (rows[c.name].utilisation or 0.0):
            rows[c.name] = c
    return list(rows.values())


def _end(scene: Scene, chain, out: Path, runup: StudyRun, earthquake: StudyRun) -> _End:
    """The checks and responses of one end: the machine's, the margins, and its two study runs'."""
    runs = {"runup": runup, "earthquake": earthquake}
    rows = machine_rows(scene, chain) + margin_rows(scene, chain, out)
    notes, responses = [], {}
    for name, case, field, _ in RESPONSES:
        responses[name] = float(getattr(runs[case], field))
    peaks = {case: float(runs[case].peak_shaft_deflection) for case in CASES}
    worst = max(peaks, key=lambda c: peaks[c])
    rows.append(
        check(
            "shaft deflection vs clearance",
            "shaft_deflection",
            "m",
            peaks[worst],
            scene.rotor.clearance,
            "modal",
            worst,
            "the design study's peak shaft deflection (radial); rotor.clearance",
        )
    )
    for case in CASES:
        run = runs[case]
        if not run.ok:
            notes.append(f"{case}: the integrator did not finish")
        if case == "runup" and run.passed is False:
            notes.append(f"run-up captured at {run.captured_at or 0:.2f} rad/s")
    return _End(rows, responses, notes)


# --------------------------------------------------------------------------
# Crossings and the verdict


def crossing(base_x: float, base_u: float, low: tuple[float, float] | None, high: tuple[float, float] | None):
    """Where a utilisation reaches 1 along one input, linear from (base_x, base_u) to an end
    (x, u); inside a range first, else the nearer extrapolation that stays on the input's sign
    and within ``MAX_REACH`` half-ranges of the scene's value.

    >>> crossing(2.0, 4.0, (1.0, 2.0), (4.0, 8.0))
    Crossing(value=0.5, kind='extrapolated', side='low')
    >>> crossing(2.0, 1.5, (1.0, 0.75), (4.0, 3.0)).kind
    'interpolated'
    """
    found = []
    for side, end in (("low", low), ("high", high)):
        if end is None or end[1] == base_u or end[0] == base_x:
            continue
        x = base_x + (1.0 - base_u) * (end[0] - base_x) / (end[1] - base_u)
        t = (x - base_x) / (end[0] - base_x)
        if t <= 0 or t > MAX_REACH or (base_x > 0 and x <= 0):
            continue  # the line reaches 1 on the other side, too far off to mean anything, or past zero
        found.append((t > 1.0, abs(t), Crossing(float(x), "extrapolated" if t > 1.0 else "interpolated", side)))
    return min(found, key=lambda f: (f[0], f[1]))[2] if found else None


def verdict_of(statuses) -> str:
    """ "fail" when an assessed check fails, "pass" when every assessed one passes, else "incomplete"."""
    s = [x for x in statuses if x is not None and x != NOT_ASSESSED]
    return FAIL if FAIL in s else PASS if s else "incomplete"


def _change(inp: TornadoInput, verdict: str, checks: list[TornadoQuantity]) -> VerdictChange | None:
    """The value of ``inp`` that turns ``verdict`` (see the module text)."""
    bars = [(q, next(b for b in q.bars if b.key == inp.key)) for q in checks]
    other = PASS if verdict == FAIL else FAIL
    if not isinstance(inp.base, float):  # a word: the ends as computed
        for side in ("low", "high"):
            statuses = [getattr(b, f"{side}_status") for _, b in bars]
            if verdict_of(statuses) == other:
                names = [q.name for q, b in bars if getattr(b, f"{side}_status") != q.base_status]
                return VerdictChange(inp.key, other, getattr(inp, side), "computed", tuple(names))
        return None
    if verdict == FAIL:
        # every failing check must pass: the farthest of their crossings, all on one side
        failing = [(q.name, b.crossing) for q, b in bars if q.base_status == FAIL]
        found = [x for _, x in failing if x is not None]
        for side in ("low", "high"):
            if not failing or len(found) < len(failing) or any(x.side != side for x in found):
                continue
            far = max(found, key=lambda x: abs(x.value - float(inp.base)))
            kind = "extrapolated" if any(x.kind == "extrapolated" for x in found) else far.kind
            return VerdictChange(inp.key, PASS, far.value, kind, tuple(name for name, _ in failing))
        return None
    # a passing verdict fails at the nearest crossing of any check
    near = [(q.name, b.crossing) for q, b in bars if b.crossing is not None]
    if not near:
        return None
    name, first = min(near, key=lambda p: (p[1].kind != "interpolated", abs(p[1].value - float(inp.base))))
    return VerdictChange(inp.key, FAIL, first.value, first.kind, (name,))


def value_text(x: Param, unit: str) -> str:
    """An input's value as a reader reads it: three digits and its unit, or the word.

    >>> value_text(15000.0, "N*s/m"), value_text("beam", "-")
    ('1.5e+04 N*s/m', "the 1D beam's point mass")
    """
    if isinstance(x, float):
        return f"{x:.3g} {unit}".strip() if unit not in ("", "-") else f"{x:.3g}"
    return SOURCE_WORDS.get(str(x), str(x))


def verdict_sentence(verdict: str, inputs: list[TornadoInput], changes: list[VerdictChange]) -> str:
    """What would change the verdict, in words."""
    by_key = {i.key: i for i in inputs}
    if verdict == "incomplete":
        return "No check of the tornado is assessed at the scene's values: nothing to change."
    inside = [c for c in changes if c.kind in ("interpolated", "computed")]
    beyond = [c for c in changes if c.kind == "extrapolated"]
    parts = []
    for c in inside:
        i = by_key[c.key]
        how = (
            f"set to {value_text(c.value, i.unit)}"
            if c.kind == "computed"
            else f"at about {value_text(c.value, i.unit)} (the scene has {value_text(i.base, i.unit)}; interpolated "
            "linearly between the scene's value and the end of its range)"
        )
        parts.append(f"the {i.label} {how} turns it to {c.verdict} ({', '.join(c.checks)})")
    if parts:
        text = (
            f"Over the checks the tornado covers the verdict is {verdict}; within the inputs' ranges "
            + "; ".join(parts)
            + "."
        )
    else:
        text = f"Over the checks the tornado covers the verdict is {verdict}, and no input within its range changes it."
    for c in beyond:
        i = by_key[c.key]
        ratio = c.value / i.base if isinstance(c.value, float) and isinstance(i.base, float) and i.base else None
        times = (
            ""
            if ratio is None
            else f", 1/{1 / ratio:.3g} of the scene's"
            if ratio < 1
            else f", {ratio:.3g} times the scene's"
        )
        text += (
            f" It would turn to {c.verdict} with the {i.label} at about {value_text(c.value, i.unit)}{times} "
            f"({', '.join(c.checks)}; a linear extrapolation beyond the range computed, a hint only)."
        )
    if not changes:
        text += " No line through the computed ends reaches the capacity."
    return text


# --------------------------------------------------------------------------
# The study


def _study_runs(
    scene: Scene, case: str, key: str, values: tuple, out: Path, cache: Path, executor
) -> tuple[StudyRun, ...]:
    """The ROM's ``case`` at each value of ``key`` (in their order): one design study."""
    from ..studies import design_study

    # design_study takes its axes as `study --vary` takes them (its public interface): the
    # values written as TOML values, strings quoted
    axis = f"{key}=" + ",".join(_vary_text(v) for v in values)
    res = design_study(
        scene,
        case,
        "modal",
        [axis],
        out_dir=out,
        cache_dir=cache,
        show_progress=False,
        executor=executor,
        write_csv=False,
    )
    return tuple(sorted(res.runs, key=lambda r: r.index))  # the index is the axis's order


def _vary_text(v) -> str:
    """One value of a ``--vary`` axis as TOML writes it."""
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, bool):
        return "true" if v else "false"
    return repr(v)


#: keys scaled with an input by the same factor: the pillar's damping is b1 (the planar ROM's
#: tip dashpot) and the modal damping ratio zeta of the spatial model (the separation margins'
#: amplification factors) together
SCALED_WITH = {"pillar.damping": ("pillar.damping_ratio",)}


def end_scene(scene: Scene, inp: TornadoInput, side: str) -> Scene:
    """The scene at one end (``side`` "low" or "high") of ``inp``'s range, every other key the scene's."""
    value = getattr(inp, side)
    values = {inp.key: value}
    if isinstance(value, float) and isinstance(inp.base, float) and inp.base != 0:
        for key in SCALED_WITH.get(inp.key, ()):
            section, name = key.split(".")
            scaled = getattr(getattr(scene, section), name) * value / inp.base
            values[key] = min(max(scaled, key_limits(key)[0]), key_limits(key)[1])
    return with_values(scene, values)


def earthquake_scene(scene: Scene) -> Scene:
    """The scene's earthquake as the tornado runs it: its record (``excitation.record``), whole."""
    return scene if scene.excitation.kind == "record" else with_values(scene, {"excitation.kind": "record"})


def tornado_study(
    scene: Scene,
    out: Path,
    vary: list[str] | None = None,
    *,
    with_fem3d: bool | None = None,
    executor=None,
    log: Callable[[str], None] | None = None,
) -> TornadoResult:
    """The one-at-a-time sensitivity of the scene's checks (see the module text)."""
    import importlib.util
    import time

    from ..chain import resolve
    from ..executor import Executor
    from ..studies.modes import affects_modes

    start = time.perf_counter()
    if with_fem3d is None:
        with_fem3d = importlib.util.find_spec("dolfinx") is not None
    inputs, left = inputs_for(scene, list(vary or ()), with_fem3d)
    out = Path(out)
    cache = out / "tornado"
    say = log or (lambda _m: None)
    base_chain = resolve(scene, out, progress=log)
    # the top plate's model at the scene's values: what "auto" chose, in words
    inputs = [
        replace(i, base=f"{i.base} ({base_chain.pillar_model.label})")
        if i.key == "modal_model.source" and i.base == "auto"
        else i
        for i in inputs
    ]
    own = executor is None
    ex = Executor(processes=False) if own else executor
    if own:
        ex.__enter__()
    n_runs = 0
    try:

        def at(sc: Scene, chain) -> _End:
            """One end: its scene's two study runs (the eccentricity its axis) and its checks."""
            nonlocal n_runs
            e = (sc.rotor.eccentricity,)
            runup = _study_runs(sc, "runup", "rotor.eccentricity", e, out, cache, ex)
            quake = _study_runs(earthquake_scene(sc), "earthquake", "rotor.eccentricity", e, out, cache, ex)
            n_runs += 2
            return _end(sc, chain, out, runup[0], quake[0])

        base = at(scene, base_chain)
        ends: dict[str, tuple[_End, _End]] = {}
        for inp in inputs:
            say(f"tornado: {inp.key} at {inp.low} and {inp.high}")
            pair = []
            for side in ("low", "high"):
                sc = end_scene(scene, inp, side)
                if inp.key == "modal_model.source":
                    chain = resolve(sc, out, progress=log)
                elif affects_modes(inp.key):
                    chain = resolve(sc, None, progress=log)  # a varied pillar has no study of its own
                else:
                    chain = base_chain
                pair.append(at(sc, chain))
            ends[inp.key] = (pair[0], pair[1])
    finally:
        if own:
            ex.__exit__(None, None, None)
    return _assemble(scene, inputs, left, base, ends, n_runs, time.perf_counter() - start)


def _assemble(scene: Scene, inputs, left, base: _End, ends, n_runs: int, wall: float) -> TornadoResult:
    quantities: list[TornadoQuantity] = []
    left = list(left) + list(LEFT_OUT)
    for name, c in base.checks.items():
        if c.status == NOT_ASSESSED:
            left.append(f"{name}: not assessed at the scene's values (no capacity or no demand)")
            continue
        bars = []
        for inp in inputs:
            lo, hi = (ends[inp.key][i].checks.get(name) for i in (0, 1))
            cross = None
            if isinstance(inp.base, float) and c.utilisation is not None:
                cross = crossing(
                    inp.base,
                    c.utilisation,
                    None if lo is None or lo.utilisation is None else (float(inp.low), lo.utilisation),
                    None if hi is None or hi.utilisation is None else (float(inp.high), hi.utilisation),
                )
            bars.append(
                TornadoBar(
                    inp.key,
                    None if lo is None else lo.utilisation,
                    None if hi is None else hi.utilisation,
                    None if lo is None else lo.status,
                    None if hi is None else hi.status,
                    cross,
                )
            )
        quantities.append(
            TornadoQuantity(
                name,
                "check",
                "-",
                c.utilisation,
                c.status,
                "ROM",
                c.case or "",
                tuple(sorted(bars, key=lambda b: -b.swing)),
            )
        )
    quantities.sort(key=lambda q: -(q.base or 0.0))
    checks = list(quantities)
    for name, case, _, unit in RESPONSES:
        bars = [
            TornadoBar(inp.key, ends[inp.key][0].responses[name], ends[inp.key][1].responses[name]) for inp in inputs
        ]
        quantities.append(
            TornadoQuantity(
                name,
                "response",
                unit,
                base.responses[name],
                None,
                "ROM",
                case,
                tuple(sorted(bars, key=lambda b: -b.swing)),
            )
        )
    verdict = verdict_of(q.base_status for q in checks)
    changes = (
        [ch for inp in inputs if (ch := _change(inp, verdict, checks)) is not None] if verdict != "incomplete" else []
    )
    notes = [f"the scene's values: {n}" for n in base.notes]
    for inp in inputs:
        for side, end in zip(("low", "high"), ends[inp.key]):
            notes += [f"{inp.key} at its {side} end: {n}" for n in end.notes]
    return TornadoResult(
        scene_name=scene.name,
        verdict=verdict,
        inputs=tuple(inputs),
        quantities=tuple(quantities),
        changes=tuple(changes),
        sentence=verdict_sentence(verdict, inputs, changes),
        left_out=tuple(left),
        runs=n_runs,
        wall_seconds=wall,
        notes=tuple(notes),
    )
