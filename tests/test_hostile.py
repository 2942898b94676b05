"""Hostile input, as a careless or hostile user gives it: one line, the right exit code,
nothing written (issue: hardening).  Each case runs the cheapest command it applies to.

Exit codes (README, "Exit codes"): 2 bad input; 1 a solver, tool or the machine
failed; 70 a bug (one line; --debug shows the traceback).

A case runs the command in this process (the ``here`` fixture: rotorpillar.cli.main, what a
user sees on stderr included) unless a child is the point: a signal, a kill, ``ulimit``,
mpirun, a FIFO or a device that would block or fill the process, a Dask cluster, two
commands at once (``cli``).
"""

import json
import os
import socket
import subprocess
import sys
import threading
import time

import pytest
from conftest import cli, sigint_as_in_the_foreground

LATIN1 = "[pillar]\nheight = 20.0 # Höhe\n".encode("latin-1")


def one_line(p):
    lines = [l for l in p.stderr.strip().splitlines() if not l.startswith("[rotorpillar]")]
    assert len(lines) == 1, p.stderr
    return lines[0]


@pytest.mark.parametrize(
    "content, words",
    [
        (b"\x00\x01\x02binary\xff", "not UTF-8"),
        (LATIN1, "not UTF-8"),
        (b"[pillar\nheight = ", "not valid TOML"),
    ],
    ids=["binary", "latin-1", "broken-toml"],
)
@pytest.mark.parametrize("command", ["analyze", "simulate", "modal", "report"])
def test_a_scene_file_that_is_not_text_is_refused(tmp_path, content, words, command, here):
    scene = tmp_path / "scene.toml"
    scene.write_bytes(content)
    out = tmp_path / "out"
    p = here(command, scene, "--out", out)
    assert p.returncode == 2
    assert words in one_line(p) and "scene.toml" in one_line(p)
    assert not out.exists()


@pytest.mark.parametrize("target", ["file", "/dev/null"])
@pytest.mark.parametrize("command", ["analyze", "simulate", "report", "integrators"])
def test_an_output_path_that_is_not_a_directory_is_refused(tmp_path, target, command, here):
    out = tmp_path / "taken"
    if target == "file":
        out.write_text("keep me")
    else:
        out = "/dev/null"
    p = here(command, "paper", "--out", out)
    assert p.returncode == 2 and "--out" in one_line(p)
    if target == "file":
        assert out.read_text() == "keep me"


@pytest.mark.parametrize("name", ["../escape", "a/b", ".hidden"])
def test_a_scene_name_cannot_leave_the_output_tree(tmp_path, name, here):
    from importlib import resources

    paper = resources.files("rotorpillar.scenes").joinpath("paper.toml").read_text("utf-8")
    scene = tmp_path / "scene.toml"
    scene.write_text(f'name = "{name}"\n' + "\n".join(l for l in paper.splitlines() if not l.startswith("name")))
    p = here("analyze", scene, cwd=tmp_path)
    assert p.returncode == 2 and "name" in one_line(p)
    assert not (tmp_path / "out").exists() and not (tmp_path.parent / "escape").exists()


def test_an_accelerogram_that_is_not_utf8_is_refused(tmp_path, here):
    rec = tmp_path / "acc.txt"
    rec.write_bytes(b"0 0\n0.01 \xff\n")
    out = tmp_path / "out"
    p = here(
        "simulate",
        "paper",
        "--case",
        "earthquake",
        "--out",
        out,
        "--set",
        "excitation.kind=record",
        "--set",
        f"excitation.record='{rec}'",
    )
    assert p.returncode == 2 and "not UTF-8" in one_line(p)
    assert not out.exists()


# within every key's range (scene.sections), each mesh far past any machine's memory:
# 2.3e7 DOFs (258 GiB) and more
@pytest.mark.parametrize(
    "keys",
    [
        ["mesh.elements_along=10000"],
        ["mesh.elements_through=100", "mesh.elements_along=1000"],
        ["mesh.elements_around=4096", "mesh.elements_along=1000"],
    ],
    ids=["along", "through", "around"],
)
@pytest.mark.parametrize("command", ["modal", "run"])
def test_a_mesh_this_machine_cannot_hold_is_refused_before_any_work(tmp_path, keys, command, here):
    out = tmp_path / "out"
    p = here(command, "paper", *(a for k in keys for a in ("--set", k)), "--out", out)
    assert p.returncode == 2
    line = one_line(p)
    assert "DOFs" in line and "GiB" in line  # the estimate and the limit, in one line
    assert not out.exists()


@pytest.mark.slow  # seconds: the campbell command up to its 3D side
def test_sigterm_stops_campbell_in_its_3d_side_and_writes_nothing(tmp_path):
    """`campbell --model both` (issue 26's command, added after the hostile suite): SIGTERM once
    its 3D side has started: exit 143, one line, and no campbell.json or campbell.png."""
    import signal

    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-m", "rotorpillar", "campbell", "paper", "--model", "both", "--fem3d-mesh", "scene"]
        + ["--set", "modal_model.source=beam", "--out", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    lines = []
    assert proc.stderr is not None
    for line in proc.stderr:  # blocks until the command says something
        lines.append(line)
        if "3D" in line:
            break
    proc.send_signal(signal.SIGTERM)
    _, rest = proc.communicate(timeout=120)
    assert proc.returncode == 143, "".join(lines) + rest
    assert not (out / "campbell.json").exists() and not (out / "campbell.png").exists()
    assert len([x for x in rest.splitlines() if not x.startswith("[rotorpillar]")]) <= 1, rest


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
def test_sigterm_stops_run_and_its_stage(tmp_path):
    import signal
    import subprocess
    import sys

    out = tmp_path / "out"
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "rotorpillar",
            "run",
            "paper",
            "--out",
            str(out),
            "--skip",
            "converge",
            "--skip",
            "integrators",
            "--skip",  # analyze first (3 s, not modal's 20): the signal lands as the
            "modal",  # side-by-side stages start, several children to stop at once
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.time() + 120
    while not (out / "analyze.json").exists() and time.time() < deadline:
        time.sleep(0.2)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 143, err
    time.sleep(0.5)
    # no stage of this run is left running
    ps = subprocess.run(["ps", "-eo", "args"], capture_output=True, text=True).stdout
    assert str(out) not in ps
    import json

    for f in out.glob("*.json"):
        json.loads(f.read_text())  # every file on disk is whole


def test_a_killed_writers_part_file_is_removed_by_the_next_write(tmp_path):
    from rotorpillar.provenance import write_json

    stale = tmp_path / ".result.json.999999999.abc.part.json"  # no such process
    stale.write_text("{")
    write_json(tmp_path / "result.json", {"a": 1})
    assert not stale.exists() and (tmp_path / "result.json").exists()


@pytest.mark.parametrize("frames", ["1", "-5", "100000"])
def test_run_refuses_bad_max_frames_before_any_stage(tmp_path, frames, here):
    out = tmp_path / "out"
    p = here("run", "paper", "--max-frames", frames, "--out", out)
    assert p.returncode == 2 and "--max-frames" in one_line(p)
    assert not out.exists()


def test_zero_shaft_damping_is_the_undamped_limit_without_nan_or_warnings(tmp_path, here):
    """b2 = 0 leaves the Y mode undamped: unbounded amplitude (null in JSON), no torque, no NaN.

    In this process (``here``: a child's start-up and imports saved, 1.8 -> 0.4 s): a child under ``-W error``
    made any warning an exception (exit 70); here every warning the command raises is recorded
    (caught by the product or not) and written to stderr, where none may be."""
    import json

    p = here("analyze", "paper", "--set", "shaft.damping=0", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    said = [l for l in p.stderr.splitlines() if l.strip() and not l.startswith("[rotorpillar]")]
    assert not said, p.stderr
    doc = json.loads((tmp_path / "analyze.json").read_text())
    y = [r for r in doc["resonances"] if r["direction"] == "Y"][0]
    assert y["nu"] == 0 and y["a_max"] is None and y["dL_max"] == 0
    assert "undamped" in y["statement"]
    assert all(v is not None for v in y["curves"]["dL"])


@pytest.mark.parametrize(
    "sets, key",
    [
        (["shaft.stiffness=1e300"], "shaft.stiffness"),
        (["rotor.mass=1e300"], "rotor.mass"),
        (["gondola.mass=1e300"], "gondola.mass"),
        (["rotor.inertia=1e-300"], "rotor.inertia"),
        (["pillar.youngs_modulus=1e30"], "pillar.youngs_modulus"),
        (["pillar.density=1e30"], "pillar.density"),
        (["drive.slope=0", "load.coefficient=0"], "drive.slope"),
    ],
)
@pytest.mark.parametrize("command", ["analyze", "simulate"])
def test_values_that_break_the_formulas_are_refused(tmp_path, sets, key, command, here):
    out = tmp_path / "out"
    p = here(command, "paper", *[a for s in sets for a in ("--set", s)], "--out", out)
    assert p.returncode == 2 and key in one_line(p)
    assert not out.exists()


def test_a_micrometre_tube_is_refused_before_gmsh(tmp_path, here):
    p = here("modal", "paper", "--set", "pillar.height=1e-6", "--out", tmp_path / "out")
    assert p.returncode == 2 and "height" in one_line(p)


@pytest.fixture(scope="module")
def computed(tmp_path_factory):
    """analyze and a short run-up, written as the commands write them (in this process:
    rotorpillar.cli.main, its failure on the captured stderr)."""
    from rotorpillar.cli import main

    out = tmp_path_factory.mktemp("computed")
    for args in (["analyze"], ["simulate", "--case", "runup", "--set", "simulate.duration=5"]):
        assert main([args[0], "paper", *args[1:], "--out", str(out)]) == 0, args
    return out


def _truncated(text):
    return text[:100]


def _emptied(text):
    return ""


def _binary(text):
    return "\x00\x01binary"


def _wrong_shape(text):
    return "[1, 2]"


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
@pytest.mark.parametrize(
    "damages",
    [
        # file: (damage, the command that rebuilds it); None: bytes that are no NPZ.  Several
        # inputs damaged at once, each of another kind: each named, none hiding another.
        {
            "analyze.json": (_truncated, "analyze"),
            "simulate_runup.npz": (None, "simulate"),
            "modal.json": (_wrong_shape, "modal"),
        },
        {"analyze.json": (_emptied, "analyze"), "simulate_runup.json": (_binary, "simulate")},
    ],
    ids=["truncated-json+binary-npz+wrong-shape", "empty-json+binary-json"],
)
def test_the_report_survives_damaged_inputs(tmp_path, computed, damages, here):
    import html
    import shutil

    out = tmp_path / "out"
    shutil.copytree(computed, out)
    for name, (damage, _) in damages.items():
        f = out / name
        if damage is None:
            f.write_bytes(b"\x00\x01\x02 not an npz")
        else:
            f.write_text(damage(f.read_text() if f.exists() else ""))
    p = here("report", "paper", "--out", out, "--no-animations")
    assert p.returncode == 0, p.stderr
    page = html.unescape((out / "report.html").read_text())
    failures = json.loads((out / "report.json").read_text())["failures"]
    for name, (_, command) in damages.items():
        said = [v for k, v in failures.items() if k.startswith(f"input {name.rsplit('.', 1)[0]}.")]
        assert len(said) == 1 and "is damaged" in said[0] and f"rotorpillar {command} paper" in said[0], failures
        assert said[0].split(": rebuild")[0] in page  # the page says it too
    if "modal.json" in damages:  # --strict's exit, once (the damage detected is the same code path)
        p = here("report", "paper", "--out", out, "--no-animations", "--strict")
        assert p.returncode == 1 and (out / "report.html").is_file()


@pytest.mark.parametrize("command", ["analyze", "simulate", "report", "run", "integrators"])
def test_only_modal_runs_under_mpirun(tmp_path, command, here):
    """Under mpirun every rank would do the whole job and write: refused, one line per rank.
    (The launcher's environment is what mpirun sets for each rank: here, set for the command.)"""
    out = tmp_path / "out"
    p = here(command, "paper", "--out", out, env={"OMPI_COMM_WORLD_SIZE": "2"})
    assert p.returncode == 2 and "without mpirun" in one_line(p)
    assert not out.exists()


def test_a_run_past_its_stability_limit_is_a_failure_not_a_success(tmp_path, here):
    """Central difference with h = 1 s on modes of ~30 rad/s: h omega = 29 > 2 (its limit)."""
    import json

    p = here(
        "simulate",
        "paper",
        "--case",
        "runup",
        "--out",
        tmp_path,
        "--set",
        "simulate.integrator=central_difference",
        "--set",
        "simulate.time_step=1",
    )
    assert p.returncode == 4, p.stderr
    doc = json.loads((tmp_path / "simulate.json").read_text())
    assert doc["ok"] is False
    assert any("stability limit" in c for c in doc["failed_checks"])
    assert any("energy balance" in c for c in doc["failed_checks"])


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
@pytest.mark.parametrize("case", ["runup", "rundown", "earthquake"])
def test_a_good_run_passes_its_checks(tmp_path, case, here):
    import json

    p = here("simulate", "paper", "--case", case, "--out", tmp_path, "--set", "simulate.duration=10")
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "simulate.json").read_text())
    assert doc["ok"] is True and "failed_checks" not in doc


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
def test_captured_at_is_the_settled_speed_and_an_escaping_run_is_not_captured(tmp_path):
    """sommerfeld: at M0 = 600 N*m the rotor settles below omega_1 (captured); a run that
    ends while the rotor is still rising through omega_1 (escaping) is not captured (issue:
    clear semantics).  The second run stops half a second after a passing motor's speed
    crosses omega_1, which the first of the two runs measures.

    The three runs in this process (rotorpillar.cli.main, the CLI's one error boundary, as
    tests/test_hostile_edges.py runs its cases): what is checked is simulate.json, not the
    terminal; no Python start-up, imports and compiled kernels to load per run: 9.3 -> 4.4 s
    of CPU."""
    import json

    from rotorpillar.cli import main

    def run(*args):  # conftest's cli, in this process: its exit code
        return main([str(a) for a in args])

    assert run("simulate", "sommerfeld", "--case", "runup", "--no-threshold", "--out", tmp_path) == 0
    d = json.loads((tmp_path / "simulate.json").read_text())
    assert d["speed_state"] == "captured" and "passing_torque" not in d
    assert d["captured_at"] == pytest.approx(d["omega_final_mean"])
    assert d["captured_at"] < d["captured_resonance"]  # held below the resonance
    assert d["captured_index"] == 1
    strong = ("--set", "drive.torque_at_zero=800")
    assert run("simulate", "sommerfeld", "--case", "runup", "--no-threshold", "--out", tmp_path, *strong) == 0
    d = json.loads((tmp_path / "simulate.json").read_text())
    assert d["speed_state"] == "at_speed"
    crossing = d["passages"][0]["time"]
    code = run(
        "simulate",
        "sommerfeld",
        "--case",
        "runup",
        "--no-threshold",
        "--out",
        tmp_path,
        *strong,
        "--set",
        f"simulate.duration={crossing + 0.5}",
    )
    assert code == 0
    d = json.loads((tmp_path / "simulate.json").read_text())
    assert d["speed_state"] == "escaping" and d["captured_at"] is None
    assert d.get("captured_resonance") is None and d.get("captured_index") is None


@pytest.mark.parametrize(
    "args, words",
    [
        (
            ["simulate", "--set", "simulate.integrator=newmark", "--set", "simulate.time_step=1e-9"],
            "simulate.max_steps",
        ),
        # the slowest ramp and the longest settle the ranges allow (sweep.rate >= 1e-3,
        # sweep.settle <= 1e5 s): each past the default step budget
        (["simulate", "--case", "sweep", "--set", "sweep.rate=1e-3"], "simulate.max_steps"),
        (["simulate", "--case", "sweep", "--set", "sweep.settle=1e5"], "simulate.max_steps"),
        (["simulate", "--case", "sweep", "--set", "sweep.bins=100000"], "sweep.bins"),
        (["simulate", "--set", "simulate.rtol=1e-300"], "simulate.rtol"),
        (["integrators", "--duration", "1000"], "--duration"),
    ],
    ids=["tiny-step", "slow-sweep", "long-settle", "many-bins", "rtol-underflow", "long-study"],
)
def test_work_that_cannot_finish_is_refused_with_its_estimate(tmp_path, args, words, here):
    out = tmp_path / "out"
    p = here(args[0], "paper", *args[1:], "--out", out, timeout=120)
    assert p.returncode == 2 and words in one_line(p)
    assert not out.exists()


@pytest.mark.parametrize("command", ["analyze", "run"])
def test_a_missing_record_is_noticed_before_any_work(tmp_path, command, here):
    out = tmp_path / "out"
    p = here(
        command,
        "paper",
        "--set",
        "excitation.kind=record",
        "--set",
        f"excitation.record='{tmp_path / 'nope.txt'}'",
        "--out",
        out,
    )
    assert p.returncode == 2 and "excitation.record" in one_line(p)
    assert not out.exists()


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
def test_a_record_timed_in_milliseconds_is_flagged_not_realistic(tmp_path, here):
    """Times read as seconds that were milliseconds: a 10 s step and tens of metres of ground."""
    import json

    rec = tmp_path / "ms.txt"
    rec.write_text("0 0\n10 0.3\n20 -0.3\n30 0.2\n40 0\n")
    p = here(
        "simulate",
        "paper",
        "--case",
        "earthquake",
        "--model",
        "modal",
        "--out",
        tmp_path,
        "--set",
        "excitation.kind=record",
        "--set",
        f"excitation.record='{rec}'",
    )
    doc = json.loads((tmp_path / "simulate.json").read_text())
    assert doc["excitation"]["realistic"] is False and "time step" in doc["excitation"]["statement"]
    assert any("not a realistic earthquake" in w for w in doc["warnings"])
    assert "not a realistic earthquake" in p.stderr


def _whole(cache) -> list:
    """The cache's finished entries: not a killed writer's temporary part
    (``.<name>.<pid>.<random>.part.json``), which pathlib's glob matches too (it does not skip
    dot files): damaged in its place, it was the file the rerun removes (seen once in a suite
    run, a FileNotFoundError after the rerun)."""
    return sorted(f for f in cache.glob("*.json") if not f.name.startswith("."))


@pytest.mark.slow  # two convergence studies per case
@pytest.mark.parametrize("sig", ["SIGTERM", "SIGKILL"])
def test_converge_killed_leaves_whole_files_and_resumes(tmp_path, sig, here):
    """Killed mid-study (SIGTERM: stops its runs; SIGKILL: no chance to clean up): every
    JSON on disk parses, and the rerun computes only what is missing.  After the SIGKILL,
    two cached runs are also damaged (they parse to another shape: null, a list): the
    rerun treats them as absent, recomputes and rewrites them, instead of failing.

    A short ladder chooses no model without an error estimate: no 3D model and an
    8-around shell, so no family converges, there is no reference and no run has an error
    estimate; the finished study says so instead of choosing the closed forms.  Checked on
    the rerun's convergence.json (the study a fresh run of the same flags writes: the
    selection reads the 23 runs' records, computed or read back alike), not on a third study
    of its own (it was test_a_short_ladder_chooses_no_model_without_an_error_estimate: the
    same flags from nothing, 5.0 s of CPU, its serving process 2.7 of them)."""
    import json
    import signal
    import subprocess
    import sys

    args = [
        "converge",
        "paper",
        "--set",
        "converge.solid=false",
        "--set",
        "converge.shell_max_around=8",
        "--set",
        "converge.shell_tri_max_around=8",
        "--no-progress",
        "--workers",
        "1",
        "--out",
        str(tmp_path),
    ]
    proc = subprocess.Popen(
        [sys.executable, "-m", "rotorpillar", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    cache, deadline = tmp_path / "cache", time.time() + 120
    while time.time() < deadline and proc.poll() is None:
        if cache.exists() and len(_whole(cache)) >= 5:
            break
        time.sleep(0.05)
    proc.send_signal(getattr(signal, sig))
    proc.communicate(timeout=60)
    for f in tmp_path.rglob("*.json"):
        if not f.name.startswith("."):  # a killed writer's temporary part
            json.loads(f.read_text())  # whole, or not there
    done = _whole(cache)
    damaged = done[:2] if sig == "SIGKILL" else []
    for f, content in zip(damaged, ["null", "[1, 2]"]):
        f.write_text(content)
    p = here(*args, "--json", timeout=600)  # the rerun in this process: the kill was the child's
    assert p.returncode == 0, p.stderr
    study = json.loads(p.stdout)["study"]
    # a run killed while being written may be missing (-1); the damaged ones are recomputed
    assert study["cached"] >= len(done) - len(damaged) - 1
    assert study["computed"] == study["runs"] - study["cached"]
    for f in damaged:
        assert json.loads(f.read_text())["value"]["status"] == "ok"  # recomputed and rewritten (a cache.Entry)
    assert not list(cache.glob(".*.part*"))  # a killed writer's part is gone
    sel = json.loads((tmp_path / "convergence.json").read_text())["selection"]
    assert sel["chosen"] is None and "no converged reference" in sel["reason"]  # the short ladder


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
@pytest.mark.renders  # the top's mode picture is drawn in this process
def test_a_damaged_vtu_costs_its_pictures_quietly(tmp_path, here, monkeypatch):
    """No VTK parser errors on the terminal, no traceback: one failure naming the file and
    the command that rebuilds it.

    The modal inputs alone (modal.json and its two VTUs): the VTUs are read and rendered by
    the same jobs with or without analyze's and a run-up's inputs, whose charts (the drive's,
    6 s of the report's 10) were most of the cost; the report's CPU 8.6 -> 6.2 s, and with
    nothing else to fail the failure is the only one.

    The jobs in this process (parallel.WORKERS = 1, as tests/test_report.py draws): the same
    run_job reads the damaged VTU (refused from its first bytes, before VTK parses it) and
    draws the sound one, and ``here`` reads this process's stderr as it read the workers'
    (they wrote to the same file descriptor); two render workers each importing pyvista and
    VTK were 6.0 of the test's 6.9 s of CPU.  One picture of the sound set (--mode-pictures 1,
    not 8): the top's job still loads, draws and succeeds, which the single failure checks.
    The workers' own handling of a failing job is test_report_parallel's; the test's CPU
    6.9 -> 1.9 s (pyvista's import in this process included)."""
    import json

    import fixtures

    from rotorpillar.postprocess.report import parallel

    monkeypatch.setattr(parallel, "WORKERS", 1)
    out = tmp_path / "out"
    out.mkdir()
    fixtures.write_modal_fixture(out, around=24, along=16)
    (out / "modes_bare.vtu").write_text("garbage")
    p = here("report", "paper", "--out", out, "--no-animations", "--mode-pictures", "1")
    assert p.returncode == 0, p.stderr
    assert "Traceback" not in p.stderr and "vtkXML" not in p.stderr
    failures = json.loads((out / "report.json").read_text())["failures"]
    assert len(failures) == 1, failures
    assert any("modes_bare.vtu is damaged" in v and "rotorpillar modal" in v for v in failures.values())


# --------------------------------------------------------------------------
# Issue 19 (hardening, second pass): refuse before work whatever the size, memory
# limits of the process, Dask addresses and workers, one line with the right word.
# No test asserts a time (TEAM.md): a subprocess timeout only turns a hang into a failure.


def _nothing_written(out):
    assert not out.exists() or not any(out.iterdir())


@pytest.mark.parametrize(
    "vary",
    [
        ["drive.torque_at_zero=560:700:1000000"],
        ["drive.torque_at_zero=560:700:1000", "rotor.eccentricity=0.01:0.02:1000"],
        ["drive.torque_at_zero=560:700:1000000000000"],
    ],
    ids=["one-axis", "product", "1e12"],
)
def test_a_study_too_large_is_refused_from_its_counts(tmp_path, vary, here):
    """The 100,000-run limit from the axes' counts, before any value is built or checked
    (it hung: each of the 1e6 values was checked first)."""
    out = tmp_path / "out"
    p = here("study", "sommerfeld", *[a for v in vary for a in ("--vary", v)], "--out", out, timeout=60)
    assert p.returncode == 2 and "at most 100,000" in one_line(p)
    _nothing_written(out)


def test_a_bad_point_of_a_large_study_is_named():
    """Every point is checked (the scene's checks across keys), the bad one named."""
    from rotorpillar.errors import InputError
    from rotorpillar.scene import load_scene
    from rotorpillar.studies.axes import check_points, parse_axes

    scene = load_scene("paper", ["pillar.inner_diameter=1.0"])
    # each value passes alone (against the other key's 1.0 and 2.0); 1.95 inside 1.91 does not
    axes = parse_axes(["pillar.inner_diameter=0.5:1.95:1000", "pillar.outer_diameter=2.0:1.91:100"], scene)
    with pytest.raises(
        InputError,
        match=r"the point pillar.inner_diameter=1\.9.*, "
        r"pillar.outer_diameter=1\.9.* is not a valid scene: "
        r"pillar.inner_diameter",
    ):
        check_points(scene, axes, {})


NANO_RECORD = "0 0\n1e-9 0.1\n0.01 0.2\n10 0\n"


@pytest.mark.parametrize(
    "args",
    [
        ["simulate", "--case", "earthquake"],
        ["simulate", "--case", "earthquake", "--model", "fem3d"],
        ["compare", "--case", "earthquake"],
        ["study", "--case", "earthquake", "--model", "modal", "--vary", "excitation.record_scale=0.5,1"],
        ["run"],
    ],
    ids=["simulate", "simulate-fem3d", "compare", "study", "run"],
)
def test_a_record_with_a_nanosecond_step_is_refused_before_any_allocation(tmp_path, args, here):
    """Resampled to its smallest step it would hold 1e10 samples (out of memory before):
    refused by every command that reads records, naming the file and its step."""
    rec = tmp_path / "nano.txt"
    rec.write_text(NANO_RECORD)
    out = tmp_path / "out"
    p = here(
        args[0],
        "paper",
        *args[1:],
        "--set",
        "excitation.kind=record",
        "--set",
        f"excitation.record='{rec}'",
        "--out",
        out,
        timeout=120,
    )
    assert p.returncode == 2, p.stderr
    line = one_line(p)
    assert "nano.txt" in line and "1e-09 s" in line and "simulate.max_steps" in line
    _nothing_written(out)


def test_a_record_is_refused_by_the_memory_it_would_need():
    """Above the process's memory (not simulate.max_steps) a record names the limit."""
    import numpy as np

    from rotorpillar.errors import InputError
    from rotorpillar.reduced.excitation import check_record_size

    t = np.array([0.0, 1e-9, 1000.0])  # 1e12 samples: 200 TB at 200 B each
    with pytest.raises(InputError, match="GiB.*this process may use"):
        check_record_size(t, "accelerogram 'x.txt'")


@pytest.mark.parametrize(
    "sets, stage, words",
    [
        (["simulate.integrator=newmark", "simulate.time_step=1e-9"], "", "simulate.max_steps"),
        (["modal.n_modes=500", "mesh.elements_around=8", "mesh.elements_along=2"], "modal", "modal.n_modes"),
        (["converge.solid_p2_max_around=256", "mesh.elements_along=640"], "", "GiB"),
    ],
    ids=["tiny-step", "too-many-modes", "huge-ladder"],
)
def test_run_refuses_what_a_later_stage_would_before_its_first(tmp_path, sets, stage, words, here):
    """run checks every stage's scene with that stage's own pre-flight checks before the
    first stage: nothing written (before, analyze.json was, and a later stage exited 1)."""
    out = tmp_path / "out"
    p = here("run", "paper", *[a for s in sets for a in ("--set", s)], "--out", out, timeout=300)
    assert p.returncode == 2, p.stderr
    line = one_line(p)
    assert "stage '" + stage in line and words in line
    assert not out.exists()


def test_every_stage_of_run_has_the_preflight_its_command_calls():
    """run calls each stage's own checks: every command module it runs has one."""
    import importlib

    from rotorpillar.commands.parser import COMMANDS
    from rotorpillar.commands.run import RUN_STAGES

    for stage in RUN_STAGES:
        name = stage.name
        if name == "analyze":  # nothing beyond the scene itself
            continue
        assert callable(getattr(importlib.import_module(COMMANDS[name][0]), "preflight", None)), name


@pytest.mark.parametrize(
    "sets",
    [
        ["modal.n_modes=500", "mesh.elements_around=8", "mesh.elements_along=2"],
        ["modal.n_modes=500", "mesh.elements_around=8", "mesh.elements_along=1", "modal.top_model=ring_mass"],
    ],
    ids=["rigid-top", "ring-mass"],
)
def test_more_modes_than_the_mesh_has_are_refused_before_the_solve(tmp_path, sets, here):
    out = tmp_path / "out"
    p = here("modal", "paper", *[a for s in sets for a in ("--set", s)], "--out", out)
    assert p.returncode == 2
    line = one_line(p)
    assert "modal.n_modes = 500" in line and "unknowns" in line
    assert not out.exists()


# -------------------------------------------------------------- memory limits


def _fake_proc(tmp_path, cgroup_lines, mounts, files):
    proc = tmp_path / "proc"
    proc.mkdir()
    (proc / "cgroup").write_text("\n".join(cgroup_lines) + "\n")
    (proc / "mountinfo").write_text("\n".join(mounts) + "\n")
    for rel, text in files.items():
        f = tmp_path / rel
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_text(text)
    return proc


def test_the_memory_limit_is_a_cgroup_v2_memory_max(tmp_path):
    """The process's group says max (no limit); its parent says 1 GiB: the parent's applies."""
    from rotorpillar.provenance import memory_limit

    root = tmp_path / "cg2"
    proc = _fake_proc(
        tmp_path,
        ["0::/batch/job7"],
        [f"41 23 0:38 / {root} rw,relatime - cgroup2 cgroup2 rw"],
        {"cg2/batch/job7/memory.max": "max\n", "cg2/batch/memory.max": f"{2**30}\n"},
    )
    lim = memory_limit(proc)
    assert lim.bytes == 2**30 and "memory.max" in lim.source and "batch" in lim.source


def test_the_memory_limit_is_a_cgroup_v1_limit_in_bytes(tmp_path):
    """v1: the memory controller's hierarchy, its group's memory.limit_in_bytes; the
    page-rounded 2**63 of 'unlimited' is no limit."""
    from rotorpillar.provenance import memory_limit

    root = tmp_path / "cg1"
    proc = _fake_proc(
        tmp_path,
        ["9:name=systemd:/", "4:memory:/docker/abc", "0::/"],
        [f"35 31 0:32 / {root} rw,relatime - cgroup cgroup rw,memory"],
        {
            "cg1/docker/abc/memory.limit_in_bytes": f"{3 * 2**30}\n",
            "cg1/docker/memory.limit_in_bytes": "9223372036854771712\n",
        },
    )
    lim = memory_limit(proc)
    assert lim.bytes == 3 * 2**30 and "memory.limit_in_bytes" in lim.source


def test_without_a_cgroup_limit_the_machine_or_ulimit_applies(tmp_path):
    from rotorpillar.provenance import memory_limit

    proc = _fake_proc(tmp_path, ["0::/"], ["41 23 0:38 / /nonexistent rw - cgroup2 cgroup2 rw"], {})
    assert memory_limit(proc).source in ("physical memory", "RLIMIT_AS (ulimit -v)")


@pytest.mark.parametrize(
    "args",
    [
        ["modal", "--set", "mesh.elements_along=50"],
        ["converge", "--no-progress"],
    ],
    ids=["modal", "converge"],
)
def test_ulimit_v_is_the_limit_a_mesh_is_refused_against(tmp_path, args):
    """Under `ulimit -v` 3 GB (budget 2.4 GB) a 116 k-DOF modal mesh (2.8 GB for its two
    solves) and the convergence study's finest run (286 k DOFs, 3.4 GB) are refused,
    naming RLIMIT_AS; on this machine's memory alone both are accepted."""
    out = tmp_path / "out"
    cmd = " ".join([sys.executable, "-m", "rotorpillar", args[0], "paper", *args[1:], "--out", str(out)])
    p = subprocess.run(["bash", "-c", f"ulimit -v 3000000 && exec {cmd}"], capture_output=True, text=True, timeout=120)
    assert p.returncode == 2, p.stderr
    line = one_line(p)
    assert "RLIMIT_AS" in line and "GiB" in line and "DOFs" in line
    _nothing_written(out)


# -------------------------------------------------------------- Dask addresses


def _listener(chatty: bool):
    """A loopback server that accepts and stays silent, or that sends an SSH banner."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    held = []

    def serve():
        while True:
            try:
                conn, _ = srv.accept()
            except OSError:
                return
            held.append(conn)
            if chatty:
                conn.sendall(b"SSH-2.0-OpenSSH_9.2p1 Debian-2\r\n")

    threading.Thread(target=serve, daemon=True).start()
    return srv, held


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(params=["silent", "chatty", "closed"])
def bad_address(request):
    if request.param == "closed":
        yield f"tcp://127.0.0.1:{_closed_port()}", "nothing listening"
        return
    srv, held = _listener(request.param == "chatty")
    words = "says nothing within" if request.param == "silent" else "not a Dask scheduler"
    yield f"tcp://127.0.0.1:{srv.getsockname()[1]}", words
    srv.close()
    for c in held:
        c.close()


def test_the_probe_names_what_is_at_a_bad_address(bad_address):
    from rotorpillar.errors import InputError
    from rotorpillar.executor import probe_scheduler

    address, words = bad_address
    with pytest.raises(InputError, match=words):
        probe_scheduler(address, timeout=1.0)


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
def test_study_refuses_a_bad_scheduler_in_one_line(tmp_path, bad_address, here, monkeypatch):
    """Exit 2 naming what was found (never 'out of memory'), within the bounded handshake
    (before: past a minute on a silent port, 31 s on a closed one).  The handshake's bound is
    1 s here, not the command's 5 s: the silent case waited it out whole, 5 s of a worker's
    wall at no CPU; the words and the exit are the same at any bound."""
    from rotorpillar import executor

    monkeypatch.setattr(executor, "HANDSHAKE_SECONDS", 1.0)
    address, words = bad_address
    out = tmp_path / "out"
    p = here(
        "study",
        "sommerfeld",
        "--vary",
        "drive.torque_at_zero=600,700",
        "--scheduler",
        address,
        "--out",
        out,
        "--no-progress",
        timeout=60,
    )
    assert p.returncode == 2, p.stderr
    line = one_line(p)
    assert words in line and address in line and "memory" not in line


def test_the_probe_accepts_a_dask_scheduler():
    from distributed import LocalCluster

    from rotorpillar.executor import probe_scheduler

    with LocalCluster(
        n_workers=0,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
        scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
    ) as cluster:
        probe_scheduler(cluster.scheduler_address)


@pytest.mark.parametrize("command", ["study", "converge"])
def test_more_local_workers_than_cores_are_refused(tmp_path, command, here):
    from rotorpillar.provenance import usable_cores

    out = tmp_path / "out"
    extra = ["--vary", "drive.torque_at_zero=600,700"] if command == "study" else []
    p = here(command, "sommerfeld" if command == "study" else "paper", *extra, "--workers", "1000", "--out", out)
    assert p.returncode == 2
    line = one_line(p)
    assert "--workers 1000" in line and f"{usable_cores()} cores" in line
    _nothing_written(out)


# -------------------------------------------------------------- one line, the right word


@pytest.mark.parametrize(
    "args, allowed",
    [
        (["compare", "--case", "sweep"], "'earthquake', 'runup'"),
        (["simulate", "--case", "quake"], "'runup', 'rundown', 'sweep', 'earthquake'"),
        (["simulate", "--model", "fe"], "'paper', 'modal', 'fem3d', 'beam'"),
        (["simulate", "--integrator", "euler"], "'dp5'"),
        (["study", "--case", "sweep"], "'runup'"),
        (["study", "--model", "fem3d"], "'paper', 'modal', 'beam'"),
        (["integrators", "--duration", "ten"], "invalid float value"),
        (["run", "--skip", "everything"], "analyze"),
        (["frobnicate"], "analyze"),
    ],
    ids=lambda a: "-".join(a) if isinstance(a, list) else None,
)
def test_every_choice_error_is_one_line_naming_the_allowed_values(tmp_path, args, allowed, here):
    p = here(*args, "--out", tmp_path / "out")
    assert p.returncode == 2
    assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert allowed in p.stderr and "usage:" not in p.stderr


REPORT_INPUTS = {
    "analyze.json": "analyze",
    "modal.json": "modal",
    "convergence.json": "converge",
    "integrators.json": "integrators",
    "simulate_runup.json": "simulate",
    "compare_runup.json": "compare",
    "study.json": "study",
}
DAMAGES = {"null": "null", "empty-object": "{}", "list": "[1, 2]", "truncated": '{"a": [1, ', "wrong-types": None}


def _damaged(computed, tmp_path, name, damage):
    import shutil

    out = tmp_path / "out"
    shutil.copytree(computed, out)
    f = out / name
    text = DAMAGES[damage]
    if text is None:  # every key a real file of it has (or a few), each of the wrong kind
        keys = list(json.loads(f.read_text())) if f.exists() else ["modes", "runs", "accuracy", "case", "model", "axes"]
        text = json.dumps({k: 12345 for k in keys if k not in ("scene", "versions", "machine", "timings", "command")})
    f.write_text(text)
    return out


@pytest.mark.parametrize("damage", list(DAMAGES))
@pytest.mark.parametrize("name", list(REPORT_INPUTS))
def test_the_report_reads_every_damaged_input_as_damaged(tmp_path, computed, name, damage):
    """Each input the report reads, damaged five ways, through the report's reader: a
    failed input naming the file and the command that rebuilds it, never 'not computed'
    (null) nor a bare KeyError without the file ({})."""
    from rotorpillar.postprocess.report.build import load_inputs
    from rotorpillar.postprocess.report.state import Build, ReportOptions
    from rotorpillar.scene import load_scene

    out = _damaged(computed, tmp_path, name, damage)
    build = Build(load_scene("paper"), out, "paper", ReportOptions(animations=False))
    load_inputs(build)
    named = [v for k, v in build.failures.items() if name in k]
    assert named and "is damaged" in named[0], build.failures
    assert f"`rotorpillar {REPORT_INPUTS[name]} paper`" in named[0]
    assert REPORT_INPUTS[name] in build.damaged


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
@pytest.mark.parametrize(
    "name, damage, words",
    [
        # records.read's words (msgspec's, with the file's name and the field's path)
        ("analyze.json", "null", "analyze.json: Expected `object`, got `null`"),
        ("modal.json", "empty-object", "modal.json: Object missing required field `"),
    ],
)
def test_the_report_page_says_which_input_is_damaged(tmp_path, computed, name, damage, words, here):
    """The issue's two examples through the command: exit 0, the page and report.json
    name the file, the key and the command; the input is present, not 'not computed'."""
    import html

    out = _damaged(computed, tmp_path, name, damage)
    p = here("report", "paper", "--out", out, "--no-animations")
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    doc = json.loads((out / "report.json").read_text())
    failure = doc["failures"][f"input {name}"]
    assert words in failure and f"rotorpillar {REPORT_INPUTS[name]} paper" in failure
    assert doc["inputs"][name.rsplit(".", 1)[0]] is True
    page = html.unescape((out / "report.html").read_text())
    assert words in page


# --- issue 19.1 (developer integ): the full orders refuse before work, whatever the size.
# The 3D and the beam full order estimate their steps from the scene alone (no mesh, no
# assembly) and refuse above simulate.max_steps, naming the keys that change it.  The
# timeout guards against the old behaviour (minutes of work, or "out of memory").

FULL_ORDER_KEYS = ("full_order.time_step", "simulate.max_steps")


@pytest.mark.parametrize(
    "args, words",
    [
        (
            [
                "simulate",
                "--model",
                "fem3d",
                "--case",
                "runup",
                "--set",
                "full_order.runup_duration=1e5",
                "--set",
                "simulate.duration=1e5",
            ],
            FULL_ORDER_KEYS + ("full_order.runup_duration", "simulate.duration"),
        ),
        (
            ["simulate", "--model", "fem3d", "--case", "earthquake", "--set", "full_order.time_step=1e-9"],
            FULL_ORDER_KEYS + ("full_order.earthquake_duration",),
        ),
        (["compare", "--case", "earthquake", "--set", "full_order.time_step=1e-9"], FULL_ORDER_KEYS),
        (["compare", "--case", "runup", "--set", "full_order.time_step=1e-9"], FULL_ORDER_KEYS),
        (
            ["simulate", "--model", "beam", "--case", "runup", "--set", "full_order.time_step=1e-9"],
            FULL_ORDER_KEYS + ("simulate.duration",),
        ),
        (
            [
                "simulate",
                "--model",
                "beam",
                "--case",
                "earthquake",
                "--set",
                "simulate.earthquake_duration=1e5",
                "--set",
                "full_order.time_step=1e-6",
            ],
            FULL_ORDER_KEYS + ("simulate.earthquake_duration",),
        ),
    ],
    ids=[
        "fem3d-long-runup",
        "fem3d-tiny-step",
        "compare-earthquake-tiny-step",
        "compare-runup-tiny-step",
        "beam-tiny-step",
        "beam-long-earthquake",
    ],
)
def test_a_full_order_too_long_is_refused_before_any_meshing(tmp_path, args, words, here):
    # the tiny steps are full_order.time_step's floor (1e-9 s): within its range, yet
    # 1e10 steps of the shortest case, past simulate.max_steps
    out = tmp_path / "out"
    p = here(args[0], "paper", *args[1:], "--out", out, timeout=120)
    line = one_line(p)
    assert p.returncode == 2, p.stderr
    assert all(w in line for w in words), line
    assert "steps" in line and ("3D" in line or "beam" in line)
    assert not out.exists()


# The 3D commands' wall-time budgets: a mesh whose run is estimated (from its DOFs alone)
# past modal.max_seconds or simulate.max_seconds is refused in one line naming the key, its
# estimate and the way under it.  4096 around (x 4 along for modal, x 2 for the 3D run)
# is within mesh.elements_around's range and this process's memory, and is estimated at ~5 min for modal, ~2.5 min for the 3D run-up
# (measured: 243 s and ~4 min): past a 60 s budget by a factor 2.5 at least.  The timeout
# guards against the run starting instead (minutes); the cheap meshes under the budget
# are run by tests/test_hostile_edges.py (each budget at both ends of its range).
FINE_AROUND = [
    "--set",
    "mesh.elements_around=4096",
    "--set",
    "modal.max_seconds=60",
    "--set",
    "simulate.max_seconds=60",
]


@pytest.mark.parametrize(
    "args, key",
    [
        (["modal", *FINE_AROUND, "--set", "mesh.elements_along=4"], "modal.max_seconds"),
        (["run", *FINE_AROUND, "--set", "mesh.elements_along=4"], "modal.max_seconds"),
        (
            ["simulate", "--model", "fem3d", "--case", "runup", *FINE_AROUND]
            + ["--set", "full_order.elements_around=4096", "--set", "full_order.elements_along=2"],
            "simulate.max_seconds",
        ),
    ],
    ids=["modal", "run", "fem3d"],
)
def test_a_3d_run_past_its_wall_time_budget_is_refused_before_any_meshing(tmp_path, args, key, here):
    out = tmp_path / "out"
    p = here(args[0], "paper", *args[1:], "--out", out, timeout=120)
    line = one_line(p)
    assert p.returncode == 2, p.stderr
    assert f"{key} = 60 s" in line and "estimate" in line and "fewer elements" in line, line
    assert not out.exists()


def test_simulate_under_mpirun_shares_only_the_3d_full_order(tmp_path, here):
    """simulate and compare run under mpirun for the 3D full order; the reduced models,
    which would only repeat their work on every rank, are refused with one line."""
    out = tmp_path / "out"
    env = {"OMPI_COMM_WORLD_SIZE": "2"}
    for args in (["simulate", "--model", "modal"], ["compare", "--case", "runup"]):
        p = here(args[0], "paper", *args[1:], "--out", out, env=env)
        assert p.returncode == 2 and "without mpirun" in one_line(p)
    assert not out.exists()


# --------------------------------------------------------------------------
# Issue 31 (hardening, third pass): paths, I/O errors, runs that cannot mean anything.


def _fifo(tmp_path):
    import os

    path = tmp_path / "pipe.toml"
    os.mkfifo(path)
    return path


def _loop(tmp_path):
    path = tmp_path / "loop.toml"
    path.symlink_to(path.name)
    return path


def _dangling(tmp_path):
    path = tmp_path / "gone.toml"
    path.symlink_to("nowhere.toml")
    return path


@pytest.mark.parametrize(
    "make, words",
    [
        (lambda tmp: tmp, "is a directory, not a file"),
        (_fifo, "is a FIFO (named pipe), not a file"),
        (lambda tmp: "/dev/zero", "is a character device, not a file"),
        (_loop, "is a loop of symbolic links"),
        (_dangling, "is a symbolic link to 'nowhere.toml', which does not exist"),
        (lambda tmp: tmp / "nope.toml", "not found"),
    ],
    ids=["directory", "fifo", "device", "symlink-loop", "dangling-link", "missing"],
)
def test_a_scene_path_that_is_no_file_says_what_it_is(tmp_path, make, words, here):
    """Each named, never opened (a FIFO would block the read, a device never end it);
    the accelerogram's path is read by the same check.  The FIFO and the device in a child
    (were one opened, the child would block or fill its memory, not the test's process, and
    its timeout ends it); the others in this process (``here``)."""
    run = cli if words.startswith(("is a FIFO", "is a character device")) else here
    path = make(tmp_path)
    out = tmp_path / "out"
    p = run("analyze", path, "--out", out, timeout=60)
    assert p.returncode == 2 and words in one_line(p) and str(path) in one_line(p)
    sets = ["--set", "excitation.kind=record", "--set", f"excitation.record='{path}'"]
    p = run("simulate", "paper", "--case", "earthquake", *sets, "--out", out, timeout=60)
    assert p.returncode == 2 and words in one_line(p) and "excitation.record" in one_line(p)
    assert not out.exists()


@pytest.mark.parametrize("command", ["analyze", "simulate", "report", "run", "campbell"])
def test_an_empty_output_path_is_refused(tmp_path, command, here):
    """``--out ""`` is Path(""): the working directory, which would take every file."""
    p = here(command, "paper", "--out", "", cwd=tmp_path)
    assert p.returncode == 2 and "--out" in one_line(p) and "empty" in one_line(p)
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("kind", ["fifo", "symlink-loop"])
def test_an_output_path_that_is_no_directory_says_what_it_is(tmp_path, kind, here):
    out = _fifo(tmp_path) if kind == "fifo" else _loop(tmp_path)
    p = here("analyze", "paper", "--out", out)
    assert p.returncode == 2 and "--out" in one_line(p) and "not a directory" in one_line(p)
    assert ("FIFO" if kind == "fifo" else "loop of symbolic links") in one_line(p)


FULL_DISK = [
    ["analyze"],  # analyze.json
    ["simulate", "--model", "paper", "--no-threshold", "--set", "simulate.duration=10"],  # its .npz
    ["integrators", "--duration", "2", "--quick"],  # numba's compiled kernel (below)
    ["compare", "--case", "runup", "--models", "paper,beam", "--set", "simulate.duration=2"],  # its .npz
    ["campbell", "--speeds", "0:150:51", "--set", "modal_model.source=beam"],  # campbell.png
]


@pytest.mark.parametrize("args", FULL_DISK, ids=lambda a: a[0])
def test_a_full_disk_is_one_line_naming_the_file(tmp_path, args):
    """The file system refuses to grow a file (``ulimit -f``, SIGXFSZ ignored: write(2)
    fails as on a full disk): exit 1, one line naming the file, and nothing after it (before:
    no file named, then numpy's zip writer's "Exception ignored ... Traceback").

    integrators on a machine whose kernel cache is empty (NUMBA_CACHE_DIR, which the product
    takes before its own ~/.cache folder, a fresh folder here): its first write is numba's
    compiled kernel, the write of a user's first run on a full disk.  Before, the case read
    whatever ~/.cache held: with the kernels there, the study ran whole (10 integrators, 5
    stiffness steps, 20 s of energy drift: 7.9 s of the test's 8.0 s of CPU) to fail on
    integrators.png, the PNG write campbell's case fails on; with them absent (a checkout
    whose kernels were never compiled) on numba's file, as now, always: 1.3 s of CPU."""
    out = tmp_path / "out"
    cmd = " ".join([sys.executable, "-m", "rotorpillar", args[0], "paper", *args[1:], "--out", str(out)])
    kernels = tmp_path / "kernels"
    env = dict(os.environ, NUMBA_CACHE_DIR=str(kernels)) if args[0] == "integrators" else None
    # 8 KiB: more than a scene's JSON head, less than any command's results
    p = subprocess.run(
        ["bash", "-c", f"trap '' XFSZ; ulimit -f 8 && exec {cmd}"], capture_output=True, text=True, timeout=300, env=env
    )
    assert p.returncode == 1, p.stderr
    line = one_line(p)
    assert "the file system refused '/" in line, line
    if env is not None:
        assert f"refused '{kernels}/" in line, line  # numba's own file, named
    assert "Traceback" not in p.stderr and "Exception ignored" not in p.stderr
    for f in out.glob("*.json"):
        json.loads(f.read_text())  # what was written is whole


@pytest.mark.parametrize(
    "args, key",
    [
        (
            ["simulate", "--model", "fem3d", "--set", "full_order.earthquake_duration=3"],
            "full_order.earthquake_duration",
        ),
        (["compare", "--set", "full_order.earthquake_duration=3"], "full_order.earthquake_duration"),
        (["compare", "--set", "simulate.earthquake_duration=5"], "simulate.earthquake_duration"),
        (["simulate", "--model", "beam", "--set", "simulate.earthquake_duration=3"], "simulate.earthquake_duration"),
        (["simulate", "--model", "paper", "--set", "simulate.earthquake_duration=4.9"], "simulate.earthquake_duration"),
        (["study", "--model", "paper", "--vary", "simulate.earthquake_duration=3,4"], "simulate.earthquake_duration"),
    ],
    ids=["fem3d", "compare-fem3d", "compare", "beam", "paper", "study"],
)
def test_an_earthquake_run_that_ends_before_the_ground_moves_is_refused(tmp_path, args, key, here):
    """The paper's pulse starts at 5 s: a run of 3 s sees no earthquake (it was ok: true).
    Refused before any work, naming the key the user set."""
    out = tmp_path / "out"
    p = here(args[0], "paper", "--case", "earthquake", *args[1:], "--out", out, timeout=120)
    assert p.returncode == 2, p.stderr
    assert f"{key} = " in one_line(p) and "before the ground motion starts" in one_line(p)
    _nothing_written(out)


def test_mpirun_says_a_refusal_once(tmp_path):
    """Every rank refuses alike: rank 0 says it (it was said once per rank)."""
    import os
    import shutil

    if shutil.which("mpirun") is None:
        pytest.skip("mpirun not installed")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    sets = ("--set", "full_order.earthquake_duration=3")
    p = cli("compare", "paper", *sets, "--out", tmp_path / "out", prefix=["mpirun", "-n", "2"], env=env, timeout=120)
    said = [l for l in p.stderr.splitlines() if l.startswith("rotorpillar compare:")]
    assert len(said) == 1 and "full_order.earthquake_duration = 3" in said[0], p.stderr


class _InProcess:
    """A study's executor that runs its batches here, and says whether it was started."""

    started = False

    def describe(self) -> dict:
        return {"kind": "in-process (test)", "scheduler": None, "workers": 1, "threads": 1}

    def map(self, fn, items):
        self.started = True
        for i, item in enumerate(items):
            yield i, fn(item)


def _integer_study_axes():
    """Every integer key a study may vary: two values from its range, as a list and as
    START:STOP:N (the key's lower bound and the next integer; defaults where the bound
    is open)."""
    import dataclasses

    from rotorpillar.scene import SECTIONS
    from rotorpillar.studies.axes import NOT_VARIED

    for section, cls in SECTIONS.items():
        for f in dataclasses.fields(cls):
            key = f"{section}.{f.name}"
            if f.type != "int" or key in NOT_VARIED or f.metadata["choices"] is not None:
                continue
            lo = f.metadata["ge"] if f.metadata["ge"] is not None else f.default
            yield key, f"{lo},{lo + 1}"
            yield key, f"{lo}:{lo + 1}:2"


@pytest.mark.parametrize("key, values", list(_integer_study_axes()), ids=lambda v: str(v))
def test_an_integer_axis_runs_or_is_refused_before_the_cluster(tmp_path, key, values):
    """Integer axes were refused as "must be an integer" after the cluster started (the
    predicted boundary's grid made floats of them).  Each integer key either runs to the
    end or is refused with the executor never started."""
    from rotorpillar.errors import InputError
    from rotorpillar.scene import load_scene
    from rotorpillar.studies import design_study

    base = load_scene("sommerfeld", ["simulate.duration=2", "modal_model.source=beam"])
    ex = _InProcess()
    try:
        res = design_study(
            base, "runup", "modal", [f"{key}={values}"], out_dir=tmp_path, executor=ex, show_progress=False
        )
    except InputError as exc:
        assert not ex.started, f"refused after the cluster started: {exc}"
        assert key in str(exc)
        return
    assert len(res.runs) == 2 and ex.started
    assert sorted({type(v) for v in res.axes[0].values}, key=str) == [int]


# -- one writer per output folder (issue 31.8)


def _all_commands() -> list[str]:
    """Every command the CLI has (a command added later is covered when it lands)."""
    from rotorpillar.commands.parser import COMMANDS

    return sorted(COMMANDS)


ALL_COMMANDS = _all_commands()


@pytest.mark.parametrize("command", ALL_COMMANDS)
def test_a_folder_in_use_is_refused_naming_its_holder(tmp_path, command, here):
    """A live holder (this test, by the lock's own flock): exit 2 naming it, before any
    work, the folder as it was."""
    import fcntl
    import os

    out = tmp_path / "out"
    out.mkdir()
    (out / "mine.txt").write_text("keep")
    with open(out / ".rotorpillar.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        lock.write(f"rotorpillar simulate (process {os.getpid()}, started 12:00:00)\n")
        lock.flush()
        p = here(command, "paper", "--out", out, timeout=60)
    assert p.returncode == 2, p.stderr
    assert f"in use by rotorpillar simulate (process {os.getpid()}" in one_line(p)
    assert sorted(f.name for f in out.iterdir()) == [".rotorpillar.lock", "mine.txt"]


@pytest.mark.slow  # seconds: two whole commands
def test_two_commands_into_one_folder_the_second_is_refused(tmp_path, here):
    """Half a second apart (both exited 0, the folder a mix of both scenes' files)."""
    import subprocess
    import sys

    out = tmp_path / "out"
    first = subprocess.Popen(
        [sys.executable, "-m", "rotorpillar", "simulate", "paper", "--no-threshold", "--out", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.time() + 60
    while not (out / ".rotorpillar.lock").exists() and time.time() < deadline:
        time.sleep(0.05)
    time.sleep(0.5)
    p = here("analyze", "sommerfeld", "--out", out, timeout=60)
    _, err = first.communicate(timeout=300)
    assert first.returncode == 0, err
    assert p.returncode == 2 and f"(process {first.pid}," in one_line(p)
    assert {json.loads(f.read_text())["scene"]["name"] for f in out.glob("*.json")} == {"paper"}
    assert not (out / ".rotorpillar.lock").exists()


def test_a_lock_left_by_a_killed_command_is_taken_over_and_said_so(tmp_path, here):
    out = tmp_path / "out"
    out.mkdir()
    (out / ".rotorpillar.lock").write_text("rotorpillar run (process 999999999, started 03:14:15)\n")
    p = here("analyze", "paper", "--out", out, timeout=60)
    assert p.returncode == 0, p.stderr
    assert "took over the lock" in p.stderr and "process 999999999" in p.stderr
    assert (out / "analyze.json").is_file() and not (out / ".rotorpillar.lock").exists()


def test_the_lock_of_a_refused_command_leaves_no_trace(tmp_path, here):
    """Refused after the lock was taken (the command's own checks): no lock file, and
    the folders made for it removed (nothing written)."""
    out = tmp_path / "a" / "b"
    sets = ["--set", "simulate.integrator=newmark", "--set", "simulate.time_step=1e-9"]
    p = here("simulate", "paper", *sets, "--out", out, timeout=60)
    assert p.returncode == 2 and "simulate.max_steps" in one_line(p)
    assert not (tmp_path / "a").exists()


# -- every expensive command estimates first (issue 31.10)


@pytest.mark.slow  # seconds: the start of a compare, then its SIGTERM
def test_the_pareto_study_estimates_its_3d_runs_before_any_work(tmp_path):
    """compare --pareto with its finest 3D run at 8 x 400 (the key's upper end): the
    estimate of its 3D runs (steps, dofs, time) is the first thing said, before compare's
    own models start (it ran past 40 s without one); SIGTERM then stops it (143)."""
    import signal

    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-m", "rotorpillar", "compare", "paper", "--pareto"]
        + ["--set", "full_order.pareto_along=400", "--out", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    lines = []
    for line in proc.stderr:  # blocks until the command says something
        lines.append(line)
        if "model 1 of" in line or "speed against accuracy:" in line:
            break
    proc.send_signal(signal.SIGTERM)
    _, rest = proc.communicate(timeout=120)
    estimate = lines[-1]
    assert "speed against accuracy: 4 3D runs" in estimate and "8x400" in estimate, "".join(lines) + rest
    assert "steps each" in estimate and "dofs" in estimate and "min of work" in estimate
    assert proc.returncode == 143


def test_the_pareto_study_refuses_a_3d_run_this_machine_cannot_hold(tmp_path):
    """Under `ulimit -v` 1.5 GB (budget 1.14 GiB) the finest run, 8 x 400 (115 k dofs,
    1.29 GiB), is refused before any work; compare's own 3D run (8 x 10) fits."""
    out = tmp_path / "out"
    cmd = " ".join(
        [sys.executable, "-m", "rotorpillar", "compare", "paper", "--pareto"]
        + ["--set", "full_order.pareto_along=400", "--out", str(out)]
    )
    p = subprocess.run(["bash", "-c", f"ulimit -v 1500000 && exec {cmd}"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 2, p.stderr
    line = one_line(p)
    assert "compare --pareto: the run 3D 8x400" in line and "RLIMIT_AS" in line and "GiB" in line
    _nothing_written(out)


# -- a signal stops the command wherever it lands (issue 31.3)

SWALLOWING = """
import os, signal, sys
import rotorpillar.commands.analyze as analyze

original = analyze.analyze_command


class Finaliser:
    def __del__(self):  # Python prints what a finaliser raises, and carries on
        os.kill(os.getpid(), getattr(signal, SIG))
        sum(range(1000))  # the handler runs here


def vtk_observer():  # VTK's Python callbacks: it calls exit(1) on a KeyboardInterrupt
    import vtkmodules.vtkCommonCore as vtk

    obj = vtk.vtkObject()

    def callback(caller, event):
        os.kill(os.getpid(), getattr(signal, SIG))
        sum(range(1000))

    obj.AddObserver("ModifiedEvent", callback)
    obj.Modified()


def swallowing(scene, args, timings):
    if WHERE == "finaliser":
        Finaliser()
    else:
        vtk_observer()
    return original(scene, args, timings)


analyze.analyze_command = swallowing
from rotorpillar.cli import main

sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize("where", ["finaliser", "vtk-observer"])
@pytest.mark.parametrize("sig, code", [("SIGTERM", 143), ("SIGINT", 130)])
def test_a_signal_a_library_catches_still_stops_the_command(tmp_path, where, sig, code):
    """The signal lands inside code that catches what it raises: a finaliser (Python prints
    "Exception ignored" and carries on: the report's SIGTERM was swallowed so, exit 0 and a
    full report, 2 of 6 tries) or a VTK observer (VTK ends the process with exit 1).  The
    command still ends with the signal's exit, one line, and its result is not written."""
    script = f"SIG, WHERE = {sig!r}, {where!r}\n" + SWALLOWING
    out = tmp_path / "out"
    p = subprocess.run(
        [sys.executable, "-c", script, "analyze", "paper", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
        preexec_fn=sigint_as_in_the_foreground,
    )
    assert p.returncode == code, p.stderr
    assert "rotorpillar analyze: interrupted" in p.stderr
    assert not (out / "analyze.json").exists()


@pytest.mark.slow  # a study on a local cluster
def test_a_study_over_the_ends_of_its_keys_is_quiet(tmp_path, here):
    """Both axes over their keys' whole ranges (the capture map, the predicted boundary
    beside it): exit 0 and nothing on stderr but the command's own lines (no numpy or
    matplotlib warning, no Dask worker's farewell).

    0.5 s runs (2 s before): the stiff shaft's (1e14 N/m) two runs are all the study's work,
    dp5 held at its stability limit (16 M evaluations each at 2 s); at 0.5 s every corner
    ends as at 2 s (at_speed, passed, none captured, the stiff corners' peak tips the same
    to 3 digits: the shaft's static deflection), the command's CPU 9.2 -> 5.5 s.

    The command in this process (``here``), its cluster's workers children all the same: what
    they print reaches the same file descriptor, and each warning and log record of this
    process is counted (a child's filters show a warning once; ``here`` every time); no Python
    start-up and imports of the study's own process, the test's CPU 6.2 -> 5.2 s."""
    out = tmp_path / "out"
    vary = ["--vary", "drive.torque_at_zero=0,1e9", "--vary", "shaft.stiffness=1,1e14"]
    p = here(
        "study",
        "sommerfeld",
        *vary,
        "--model",
        "paper",
        "--no-progress",
        "--set",
        "simulate.duration=0.5",
        "--out",
        out,
    )
    assert p.returncode == 0, p.stderr
    assert [l for l in p.stderr.splitlines() if l.strip() and not l.startswith("[rotorpillar]")] == []
