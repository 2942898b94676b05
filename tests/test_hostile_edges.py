"""Every accepted value runs, or it is refused (issue 31.1): each numeric key of the scene
at both ends of its range, through the commands that consume it.

The walk is over ``scene.SECTIONS``: a key added later is covered when it lands (its
section's consumers below, or its own in ``KEY_CONSUMERS``; a section without
consumers fails ``test_every_numeric_key_has_a_consumer``).  Each case runs the
command in this process (``cli.main``: the CLI's one error boundary, without a
Python start-up per case) and holds it to what a user may see:

- exit 0, or 4 with ``ok: false`` and its failed checks in the JSON (a run that means
  nothing says so), or 2 with one line and nothing written (refused before any work);
  never 1 (a tool or the machine failed) nor 70 (a bug);
- nothing else on stderr than the command's own ``[rotorpillar]`` lines: no Python
  warning (numpy's overflow, matplotlib's), no library's message.

A case sets every key of one section at the same end of its range at once (the
smallest tube, the stiffest shaft, ...): one run consumes them all.  When that
combination is refused (exit 2: one of its cross-checks, a run's estimate), each
key is run at that end alone, so that every key is seen to run or to be refused by
itself.  The other keys keep the scene's values; the runs are short
(``simulate.duration`` 2 s, the ROM on the beam's modes) and ``simulate.max_steps``
is 2e5, so that the long end of a duration is refused by its estimate at once
instead of running for minutes: the refusal is what that end must meet on this
budget.  The 3D commands' wall-time budgets (``modal.max_seconds``,
``simulate.max_seconds``) are 10 s for the same reason: the finest end of a mesh key
(4096 elements around, 100 through) or a 3D run-up of the case's 80 s is refused by
its estimate before any meshing.  Each case but analyze's takes seconds (a whole command, its charts): marked slow.
Not run here: the lower ends of the convergence ladder's keys and
``converge.tolerance`` (they only shorten or loosen the ladder that
tests/test_converge*.py run whole, minutes each; the ladder's tops run at the loosest
tolerance, 0.5, and on a [mesh] of 1 along, see ``CONSUMERS``); ``full_order.pareto_along`` (compare
--pareto: its estimate and refusal, tests/test_hostile.py).
"""

from __future__ import annotations

import dataclasses
import json
import warnings

import pytest
from conftest import QUIET_WARNINGS

from rotorpillar.scene import SECTIONS


def _sets(*assignments: str) -> list[str]:
    return [a for s in assignments for a in ("--set", s)]


SHORT = _sets("simulate.duration=2", "simulate.max_steps=200000", "simulate.samples=500", "modal_model.source=beam")
# the 3D runs' wall-time budgets at 10 s: the cheap meshes below are estimated under a
# second, a mesh or a run that would take minutes is refused by its estimate at once
FEM3D = _sets(
    "full_order.elements_around=8",
    "full_order.elements_along=2",
    "simulate.max_steps=200000",
    "simulate.max_seconds=10",
)
# analyze's chain solves the ROM's 3D modes on the scene's [mesh] (paper: 64 x 10, 24k
# DOFs) for every new tube or base, enough to pass the band: at a key's end (E = 1e6 Pa, a
# 1 cm tube) hundreds of modes lie below it, and one key took 20-60 s, pillar-low-analyze
# 162 s.  At 8 x 4 the same path (the 3D modes, the doubling, the cache) runs in a second.
# simulate.duration (2 s, as the simulate consumers' SHORT) is analyze's only run: the drive
# reaction's run-up on the spatial ROM (rotorpillar.reduced.spatial_scene), 80 s on the scene;
# at E = 1e6 Pa (pillar-low) its two dp5 runs took 7 s of the case's 12 s of CPU (now 4 s).
# Its refusal for stiffness (stiff_runup) compares steps over the same duration on both sides,
# unchanged; every analyze, springs and footing case, together and key by key, exits as it did
# at 80 s (measured: the same 0/2 codes in all 20 cases)
SMALL_MESH = _sets("mesh.elements_around=8", "mesh.elements_along=4", "simulate.duration=2")
#: name -> (command, its arguments, slow): the commands that consume keys, as cheap as they come
CONSUMERS = {
    "analyze": ("analyze", SMALL_MESH, False),
    # the foundation's keys act only on a base that is not clamped: on springs, and a footing,
    # each with the keys its kind requires set to a plausible base (a case's own values follow
    # them on the command line, and the last --set wins), so that a key alone is run, not
    # refused for a missing neighbour
    "springs": (
        "analyze",
        SMALL_MESH
        + _sets(
            "foundation.kind=springs",
            "foundation.horizontal_stiffness=1e9",
            "foundation.rocking_stiffness=1e11",
            "foundation.vertical_stiffness=1e10",
            "foundation.torsional_stiffness=1e11",
        ),
        False,
    ),
    "footing": (
        "analyze",
        SMALL_MESH
        + _sets(
            "foundation.kind=footing",
            "foundation.soil_shear_modulus=5e7",
            "foundation.soil_poisson_ratio=0.3",
            "foundation.radius=3",
        ),
        False,
    ),
    "rom": ("simulate", ["--model", "modal", "--no-threshold", *SHORT], True),
    "paper": ("simulate", ["--model", "paper", "--no-threshold", *SHORT], True),
    # the budget itself, alone: at its top the others' long ends would run for minutes
    "budget": ("simulate", ["--model", "paper", "--no-threshold", *SHORT], True),
    # 0.05 s: the beam's step costs ~dofs**3, seconds a step at 200 elements
    "beam": ("simulate", ["--model", "beam", "--no-threshold", *SHORT, *_sets("simulate.duration=0.05")], True),
    "rundown": (
        "simulate",
        ["--case", "rundown", "--model", "paper", *SHORT, *_sets("simulate.rundown_motor=weaker")],
        True,
    ),
    "fixed-step": (
        "simulate",
        ["--model", "modal", "--no-threshold", *SHORT, *_sets("simulate.integrator=newmark")],
        True,
    ),
    # the pulse from 0 s for 1 s, not 5 s to 12 s: the run (to 5 s after the pulse) is 6 s, not
    # 17 s, and the pulse still acts whole inside it; the ends of start and duration still make a
    # run of 1e5 s, refused by its estimate.  excitation-high-quake (omega = 1e4 rad/s through the
    # pulse): its run 5.7 -> 1.6 s of CPU, every quake case 10.1 -> 6.2 s; each key's exit
    # code is the one it had (start and duration alone: 2, the others 0)
    "quake": (
        "simulate",
        ["--case", "earthquake", "--model", "modal", *SHORT, *_sets("excitation.start=0", "excitation.duration=1")],
        True,
    ),
    "record": (
        "simulate",
        ["--case", "earthquake", "--model", "paper", *SHORT, *_sets("excitation.kind=record")],
        True,
    ),
    "sweep": (
        "simulate",
        ["--case", "sweep", "--model", "paper", *SHORT, *_sets("sweep.rate=500", "sweep.settle=1")],
        True,
    ),
    "modal": ("modal", _sets("mesh.elements_around=8", "mesh.elements_along=4", "modal.max_seconds=10"), True),
    "fem3d-runup": (
        "simulate",
        ["--model", "fem3d", "--case", "runup", *FEM3D, *_sets("full_order.runup_duration=0.1")],
        True,
    ),
    # the pulse from 1 s for 1 s (the scene's from 5 s for 7 s): the zero end (the case's own
    # length, 5 s past the pulse) and the top (1e5 s, held to that length) run 7 s of 3D steps,
    # not 17 s (10106 -> 4161 steps); the low end (1 ms) still ends before the ground moves and
    # is refused with the same line; exit codes as before (low 2, high 0, zero 0), the three
    # cases' CPU 8.8 -> 5.3 s
    "fem3d-quake": (
        "simulate",
        [
            "--model",
            "fem3d",
            "--case",
            "earthquake",
            *FEM3D,
            *_sets("full_order.earthquake_duration=5.1", "excitation.start=1", "excitation.duration=1"),
        ],
        True,
    ),
    "report": ("report", ["--no-animations"], True),
    # the ladder's tops at 4096 cap nothing finer than the ladder's own rungs (256 around): the
    # study runs as on the scene's values, here at its loosest tolerance (0.5, the key's top),
    # which the first rungs of every family meet, so the refinement stops at its first rounds
    # (paper: 43 runs, the finest 3D P2 96 around, instead of 50 up to 160 around); the 3D rungs
    # follow [mesh] in proportion, here 1 along (the key's low end; the scene's 10) for 64
    # around: 1 to 3 cells along on the 3D rungs, the same ladder (the same families and rungs
    # listed, each 3D family still refined over three rungs or more, exit 0); the case's CPU
    # 20.7 s at 5 along -> 14.1 s (of what is left, a third is the bending-only family, 8
    # around at its own counts along, and a quarter the two charts: no key here changes them);
    # on one worker (--workers 1): a Dask cluster's start is not what the keys are checked for
    "converge": (
        "converge",
        ["--no-progress", "--workers", "1", *_sets("converge.tolerance=0.5", "mesh.elements_along=1")],
        True,
    ),
}
#: The consumers of a section's keys.
SECTION_CONSUMERS = {
    "pillar": ["analyze", "rom", "modal"],
    "gondola": ["analyze", "paper", "rom"],
    "rotor": ["analyze", "paper"],
    "shaft": ["analyze", "paper"],
    "reduction": ["analyze", "paper"],
    "drive": ["analyze", "paper"],
    "load": ["analyze", "paper"],
    "material": ["report"],
    "mesh": ["modal"],
    "modal": ["modal"],
    "converge": ["converge"],
    "simulate": ["paper"],
    "excitation": ["quake"],
    "sweep": ["sweep"],
    "modal_model": ["rom"],
    "full_order": ["beam", "fem3d-runup"],
    # a base on springs or a footing (on paper's tube); the published frequencies: analyze
    # compares the tower's own with them on any scene
    "foundation": ["springs", "footing"],
    "reference": ["analyze"],
}
#: Keys whose consumers differ from their section's.
KEY_CONSUMERS = {
    "rotor.clearance": ["report"],
    "shaft.force_limit": ["report"],
    "converge.margin": ["modal"],
    "converge.earthquake_frequency": ["modal"],
    "simulate.time_step": ["fixed-step", "fem3d-runup"],
    "simulate.max_steps": ["budget"],
    "simulate.max_seconds": ["fem3d-runup"],
    "simulate.rundown_torque_at_zero": ["rundown"],
    "simulate.earthquake_duration": ["quake"],
    "excitation.record_scale": ["record"],
    "modal_model.gondola_inertia": ["rom", "beam"],
    "full_order.elements_around": ["fem3d-runup"],
    "full_order.elements_along": ["fem3d-runup"],
    "full_order.earthquake_duration": ["fem3d-quake"],
    "full_order.runup_duration": ["fem3d-runup"],
    "full_order.pareto_along": [],
    "converge.tolerance": [],
}
#: The ends a key is run at, where not all of them (see the module text).
KEY_ENDS = {f"converge.{k}": ("high",) for k in ("shell_max_around", "shell_tri_max_around")} | {
    f"converge.{k}": ("high",) for k in ("solid_p1_max_around", "solid_p2_max_around", "solid_tet_p2_max_around")
}


def numeric_fields():
    """(key, field) of every numeric key (a number without a list of choices)."""
    for section, cls in SECTIONS.items():
        for f in dataclasses.fields(cls):
            kind = f.type if isinstance(f.type, str) else f.type.__name__
            if f.metadata.get("choices") is None and ("float" in kind or kind == "int"):
                yield f"{section}.{f.name}", f


def ends(f) -> dict[str, object]:
    """The ends of a field's range by name: low, high, and zero where 0 means chosen or off."""
    m = f.metadata
    out = {"low": m["ge"], "high": m["le"]}
    if m.get("or_zero"):
        out["zero"] = 0
    return out


def test_every_numeric_key_has_a_closed_range():
    """Both ends stated and reachable (>=, <=): an open end (> 0) lets 1e-300 in, where
    the formulas stopped meaning anything (a run of 1e-200 s divided by zero)."""
    open_ends = [k for k, f in numeric_fields() if f.metadata["ge"] is None or f.metadata["le"] is None]
    assert not open_ends


def test_every_numeric_key_has_a_consumer():
    """A new section needs its consumers here (a key of it would go unwalked)."""
    for key, _ in numeric_fields():
        assert key in KEY_CONSUMERS or key.split(".")[0] in SECTION_CONSUMERS, key


def groups() -> dict[tuple[str, str, str], dict[str, object]]:
    """(consumer, section, end) -> {key: value}: the keys one run sets at one end."""
    out: dict[tuple[str, str, str], dict[str, object]] = {}
    for key, f in numeric_fields():
        section = key.split(".")[0]
        for consumer in KEY_CONSUMERS.get(key, SECTION_CONSUMERS.get(section, [])):
            for end, value in ends(f).items():
                if end in KEY_ENDS.get(key, ("low", "high", "zero")):
                    out.setdefault((consumer, section, end), {})[key] = value
    return out


def cases():
    for (consumer, section, end), values in groups().items():
        # a new tube makes analyze solve the chain's 3D modes again (~10 s a key): slow, as the
        # tiers define it (README), like every consumer marked slow above
        slow = CONSUMERS[consumer][2] or (CONSUMERS[consumer][0] == "analyze" and section == "pillar")
        marks = [pytest.mark.slow] if slow else []
        yield pytest.param(consumer, values, marks=marks, id=f"{section}-{end}-{consumer}")


@pytest.fixture(scope="module")
def report_inputs(tmp_path_factory):
    """What the report reads for the verdict's checks of the report's keys: a short run-up
    of the ROM (on the beam's modes, SHORT).  The keys the report consumes are capacities of
    the run checks (material.yield_strength: base stress vs yield and vs shell buckling;
    rotor.clearance: the shaft's deflection; shaft.force_limit: its force), which read the
    runs of the modal, beam and 3D models only (verdict.summary.CHECKED_MODELS): the paper
    model's run-up read before made no check of them (the keys were loaded, never used).
    analyze's files are left out: its machine checks (balance, vibration, modal mass) read
    none of these keys, and its two charts were most of each report (a report's CPU as a
    command: 2.4 s on analyze and the paper run-up, 1.3-1.5 s on the ROM's run-up)."""
    from rotorpillar.cli import main

    out = tmp_path_factory.mktemp("report_inputs")
    assert main(["simulate", "paper", "--model", "modal", "--no-threshold", *SHORT, "--out", str(out)]) == 0
    return out


def run_at(tmp_path, capfd, request, consumer: str, values: dict) -> int:
    """One run of ``consumer`` with ``values`` set, held to the module's rules; its exit code."""
    import shutil

    from rotorpillar.cli import main

    command, extra, _ = CONSUMERS[consumer]
    out = tmp_path / "-".join(values)[:100]
    if command == "report":
        shutil.copytree(request.getfixturevalue("report_inputs"), out)
    argv = [command, "paper", *extra, *_sets(*(f"{k}={v!r}" for k, v in values.items())), "--out", str(out)]
    where = f"{command} with {values}"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        code = main(argv)
    _, err = capfd.readouterr()
    said = [line for line in err.splitlines() if line.strip() and not line.startswith("[rotorpillar]")]
    seen = [
        f"{w.category.__name__}: {w.message} ({w.filename}:{w.lineno})"
        for w in caught
        if not issubclass(w.category, QUIET_WARNINGS)
    ]
    assert not seen, f"{where}: Python warnings would reach the user: {seen}"
    assert code in (0, 2, 4), f"{where}: exit {code}: {err}"
    if code == 2:
        assert len(said) == 1 and ": error: " in said[0], f"{where}: {err}"
        if command != "report":
            assert not out.exists() or not any(out.iterdir()), f"{where}: refused, yet written"
        return code
    assert not said, f"{where}: stderr beyond the command's own lines: {said}"
    if code == 4:
        doc = json.loads((out / f"{command}.json").read_text())
        assert doc["ok"] is False and doc["failed_checks"], where
    if command == "report":  # each key is read: its value is a check's capacity (gamma_M0 = 1)
        details = json.loads((out / "summary.json").read_text())["check_details"]
        capacities = {c["capacity"] for c in details}
        assert all(float(v) in capacities for v in values.values()), f"{where}: a key no check read: {details}"
    return code


@pytest.mark.parametrize("consumer, values", list(cases()))
def test_keys_at_the_ends_of_their_ranges_run_or_are_refused(tmp_path, capfd, request, consumer, values):
    if run_at(tmp_path, capfd, request, consumer, values) == 2 and len(values) > 1:
        for key, value in values.items():  # refused together: each alone
            run_at(tmp_path, capfd, request, consumer, {key: value})
