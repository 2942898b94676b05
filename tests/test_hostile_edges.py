"""Every accepted value runs, or it is refused (issue 31.1): each numeric key of the scene
at both ends of its range, through the commands that consume it.

The walk is over ``scene.SECTIONS``: a key added later is covered when it lands (its
section's consumers below, or its own in ``KEY_CONSUMERS``).  Each case runs the
command in this process (``cli.main``: the CLI's one error boundary, without a
Python start-up per case) and holds it to what a user may see:

- exit 0, or 4 with ``ok: false`` and its failed checks in the JSON (a run that means
  nothing says so), or 2 with one line and nothing written (refused before any work);
  never 1 (a tool or the machine failed) nor 70 (a bug);
- nothing else on stderr than the command's own ``[rotorpillar]`` lines: no Python
  warning (numpy's overflow, matplotlib's), no library's message.

The other keys keep the scene's values; the runs are short (``simulate.duration`` 2 s,
the ROM on the beam's modes) and ``simulate.max_steps`` is 2e5, so that the long end
of a duration is refused by its estimate in a millisecond instead of running for
minutes: the refusal is what that end must meet on this budget.  The 3D and report
cases take seconds each: marked slow.
"""

from __future__ import annotations

import dataclasses
import json
import warnings

import pytest

from rotorpillar.scene import SECTIONS


def _sets(*assignments: str) -> list[str]:
    return [a for s in assignments for a in ("--set", s)]


SHORT = _sets("simulate.duration=2", "simulate.max_steps=200000", "simulate.samples=500", "modal_model.source=beam")
ANALYZE = ("analyze", [])
ROM = ("simulate", ["--model", "modal", "--no-threshold", *SHORT])
PAPER = ("simulate", ["--model", "paper", "--no-threshold", *SHORT])
# 0.05 s: the beam's step costs ~dofs**3, seconds a step at 200 elements
BEAM = ("simulate", ["--model", "beam", "--no-threshold", *SHORT, *_sets("simulate.duration=0.05")])
RUNDOWN = ("simulate", ["--case", "rundown", "--model", "paper", *SHORT, *_sets("simulate.rundown_motor=weaker")])
FIXED_STEP = ("simulate", ["--model", "modal", "--no-threshold", *SHORT, *_sets("simulate.integrator=newmark")])
QUAKE = ("simulate", ["--case", "earthquake", "--model", "modal", *SHORT])
RECORD = ("simulate", ["--case", "earthquake", "--model", "paper", *SHORT, *_sets("excitation.kind=record")])
SWEEP = ("simulate", ["--case", "sweep", "--model", "paper", *SHORT, *_sets("sweep.rate=500", "sweep.settle=1")])
COARSE = _sets("mesh.elements_around=8", "mesh.elements_along=4")
MODAL = ("modal", COARSE)
FEM3D = _sets("full_order.elements_around=8", "full_order.elements_along=2", "simulate.max_steps=200000")
FEM3D_RUNUP = ("simulate", ["--model", "fem3d", "--case", "runup", *FEM3D, *_sets("full_order.runup_duration=0.1")])
FEM3D_QUAKE = (
    "simulate",
    ["--model", "fem3d", "--case", "earthquake", *FEM3D, *_sets("full_order.earthquake_duration=5.1")],
)
REPORT = ("report", ["--no-animations"])
CONVERGE = ("converge", ["--no-progress"])

#: The commands that consume a section's keys (the cheapest first); slow ones are marked.
SECTION_CONSUMERS = {
    "pillar": [ANALYZE, ROM, pytest.param(MODAL, marks=pytest.mark.slow)],
    "gondola": [ANALYZE, ROM],
    "rotor": [ANALYZE, ROM],
    "shaft": [ANALYZE, ROM],
    "reduction": [ANALYZE, PAPER],
    "drive": [ANALYZE, ROM],
    "load": [ANALYZE, ROM],
    "material": [pytest.param(REPORT, marks=pytest.mark.slow)],
    "mesh": [pytest.param(MODAL, marks=pytest.mark.slow)],
    "modal": [pytest.param(MODAL, marks=pytest.mark.slow)],
    "converge": [pytest.param(MODAL, marks=pytest.mark.slow)],
    "simulate": [ROM],
    "excitation": [QUAKE],
    "sweep": [SWEEP],
    "modal_model": [ROM],
    "full_order": [BEAM, pytest.param(FEM3D_RUNUP, marks=pytest.mark.slow)],
}
#: Keys whose consumers differ from their section's.
KEY_CONSUMERS = {
    "rotor.clearance": [pytest.param(REPORT, marks=pytest.mark.slow)],
    "shaft.force_limit": [pytest.param(REPORT, marks=pytest.mark.slow)],
    "simulate.time_step": [FIXED_STEP, pytest.param(FEM3D_RUNUP, marks=pytest.mark.slow)],
    "simulate.rundown_torque_at_zero": [RUNDOWN],
    "simulate.earthquake_duration": [QUAKE],
    "excitation.record_scale": [RECORD],
    "modal_model.gondola_inertia": [ROM, BEAM],
    "full_order.elements_around": [pytest.param(FEM3D_RUNUP, marks=pytest.mark.slow)],
    "full_order.elements_along": [pytest.param(FEM3D_RUNUP, marks=pytest.mark.slow)],
    "full_order.earthquake_duration": [pytest.param(FEM3D_QUAKE, marks=pytest.mark.slow)],
    "full_order.runup_duration": [pytest.param(FEM3D_RUNUP, marks=pytest.mark.slow)],
    "full_order.pareto_along": [],  # compare --pareto: tests/test_hostile.py, its estimate
    **{f"converge.{k}": [pytest.param(CONVERGE, marks=pytest.mark.slow)] for k in ("tolerance",)},
}


def numeric_fields():
    """(key, field) of every numeric key (a number without a list of choices)."""
    for section, cls in SECTIONS.items():
        for f in dataclasses.fields(cls):
            kind = f.type if isinstance(f.type, str) else f.type.__name__
            if f.metadata.get("choices") is None and ("float" in kind or kind == "int"):
                yield f"{section}.{f.name}", f


def edges(f) -> list:
    """Both ends of a field's range, and 0 where 0 means chosen or off."""
    m = f.metadata
    out = [m["ge"], m["le"]]
    if m.get("or_zero"):
        out.insert(0, 0)
    return out


def test_every_numeric_key_has_a_closed_range():
    """Both ends stated and reachable (>=, <=): an open end (> 0) lets 1e-300 in, where
    the formulas stopped meaning anything (a run of 1e-200 s divided by zero)."""
    open_ends = [k for k, f in numeric_fields() if f.metadata["ge"] is None or f.metadata["le"] is None]
    assert not open_ends


def cases():
    for key, f in numeric_fields():
        section = key.split(".")[0]
        for consumer in KEY_CONSUMERS.get(key, SECTION_CONSUMERS[section]):
            marks = consumer.marks if hasattr(consumer, "marks") else ()
            command, extra = consumer.values[0] if hasattr(consumer, "values") else consumer
            for value in edges(f):
                yield pytest.param(key, value, command, extra, marks=marks, id=f"{key}={value}-{command}")


@pytest.fixture(scope="module")
def report_inputs(tmp_path_factory):
    """What the report reads for the verdict: analyze and a short run-up."""
    from rotorpillar.cli import main

    out = tmp_path_factory.mktemp("report_inputs")
    for args in (["analyze"], ["simulate", "--model", "paper", "--no-threshold", *SHORT]):
        assert main([args[0], "paper", *args[1:], "--out", str(out)]) == 0
    return out


@pytest.mark.parametrize("key, value, command, extra", list(cases()))
def test_a_key_at_the_end_of_its_range_runs_or_is_refused(tmp_path, capfd, request, key, value, command, extra):
    import shutil

    from rotorpillar.cli import main

    out = tmp_path / "out"
    if command == "report":
        shutil.copytree(request.getfixturevalue("report_inputs"), out)
    argv = [command, "paper", *extra, "--set", f"{key}={value!r}", "--out", str(out)]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        code = main(argv)
    _, err = capfd.readouterr()
    said = [line for line in err.splitlines() if line.strip() and not line.startswith("[rotorpillar]")]
    seen = [
        f"{w.category.__name__}: {w.message} ({w.filename}:{w.lineno})"
        for w in caught
        if not issubclass(w.category, (DeprecationWarning, PendingDeprecationWarning, ImportWarning, ResourceWarning))
    ]
    assert not seen, f"Python warnings would reach the user: {seen}"
    assert code in (0, 2, 4), f"exit {code}: {err}"
    if code == 2:
        assert len(said) == 1 and ": error: " in said[0], err
        if command != "report":
            assert not out.exists() or not any(out.iterdir()), "refused, yet written"
        return
    assert not said, f"stderr beyond the command's own lines: {said}"
    if code == 4:
        doc = json.loads((out / f"{command}.json").read_text())
        assert doc["ok"] is False and doc["failed_checks"]
