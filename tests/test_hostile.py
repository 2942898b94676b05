"""Hostile input, as a careless or hostile user gives it: one line, the right exit code,
nothing written (issue: hardening).  Each case runs the cheapest command it applies to.

Exit codes (README, "Exit codes"): 2 bad input; 1 a solver, tool or the machine
failed; 70 a bug (one line; --debug shows the traceback).
"""

import pytest
from conftest import cli

LATIN1 = "[pillar]\nheight = 20.0 # Höhe\n".encode("latin-1")


def one_line(p):
    lines = [l for l in p.stderr.strip().splitlines() if not l.startswith("[rotorpillar]")]
    assert len(lines) == 1, p.stderr
    return lines[0]


@pytest.mark.parametrize("content, words", [
    (b"\x00\x01\x02binary\xff", "not UTF-8"),
    (LATIN1, "not UTF-8"),
    (b"[pillar\nheight = ", "not valid TOML"),
], ids=["binary", "latin-1", "broken-toml"])
@pytest.mark.parametrize("command", ["analyze", "simulate", "modal", "report"])
def test_a_scene_file_that_is_not_text_is_refused(tmp_path, content, words, command):
    scene = tmp_path / "scene.toml"
    scene.write_bytes(content)
    out = tmp_path / "out"
    p = cli(command, scene, "--out", out)
    assert p.returncode == 2
    assert words in one_line(p) and "scene.toml" in one_line(p)
    assert not out.exists()


@pytest.mark.parametrize("target", ["file", "/dev/null"])
@pytest.mark.parametrize("command", ["analyze", "simulate", "report", "integrators"])
def test_an_output_path_that_is_not_a_directory_is_refused(tmp_path, target, command):
    out = tmp_path / "taken"
    if target == "file":
        out.write_text("keep me")
    else:
        out = "/dev/null"
    p = cli(command, "paper", "--out", out)
    assert p.returncode == 2 and "--out" in one_line(p)
    if target == "file":
        assert out.read_text() == "keep me"


@pytest.mark.parametrize("name", ["../escape", "a/b", ".hidden"])
def test_a_scene_name_cannot_leave_the_output_tree(tmp_path, name):
    from importlib import resources
    paper = resources.files("rotorpillar.scenes").joinpath("paper.toml").read_text("utf-8")
    scene = tmp_path / "scene.toml"
    scene.write_text(f'name = "{name}"\n' + "\n".join(
        l for l in paper.splitlines() if not l.startswith("name")))
    p = cli("analyze", scene, cwd=tmp_path)
    assert p.returncode == 2 and "name" in one_line(p)
    assert not (tmp_path / "out").exists() and not (tmp_path.parent / "escape").exists()


def test_an_accelerogram_that_is_not_utf8_is_refused(tmp_path):
    rec = tmp_path / "acc.txt"
    rec.write_bytes(b"0 0\n0.01 \xff\n")
    out = tmp_path / "out"
    p = cli("simulate", "paper", "--case", "earthquake", "--out", out,
            "--set", "excitation.kind=record", "--set", f"excitation.record='{rec}'")
    assert p.returncode == 2 and "not UTF-8" in one_line(p)
    assert not out.exists()


@pytest.mark.parametrize("key", ["mesh.elements_along=100000", "mesh.elements_through=1000",
                                 "mesh.elements_around=100000"])
@pytest.mark.parametrize("command", ["modal", "run"])
def test_a_mesh_this_machine_cannot_hold_is_refused_before_any_work(tmp_path, key, command):
    out = tmp_path / "out"
    p = cli(command, "paper", "--set", key, "--out", out)
    assert p.returncode == 2
    line = one_line(p)
    assert "DOFs" in line and "GiB" in line      # the estimate and the limit, in one line
    assert not out.exists()


def test_sigterm_stops_run_and_its_stage(tmp_path):
    import signal
    import subprocess
    import sys
    import time
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "rotorpillar", "run", "paper", "--out", str(out),
                             "--skip", "converge", "--skip", "integrators"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
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
        json.loads(f.read_text())                 # every file on disk is whole


def test_a_killed_writers_part_file_is_removed_by_the_next_write(tmp_path):
    from rotorpillar.provenance import write_json
    stale = tmp_path / ".result.json.999999999.abc.part.json"   # no such process
    stale.write_text("{")
    write_json(tmp_path / "result.json", {"a": 1})
    assert not stale.exists() and (tmp_path / "result.json").exists()


@pytest.mark.parametrize("frames", ["1", "-5", "100000"])
def test_run_refuses_bad_max_frames_before_any_stage(tmp_path, frames):
    out = tmp_path / "out"
    p = cli("run", "paper", "--max-frames", frames, "--out", out)
    assert p.returncode == 2 and "--max-frames" in one_line(p)
    assert not out.exists()


def test_zero_shaft_damping_is_the_undamped_limit_without_nan_or_warnings(tmp_path):
    """b2 = 0 leaves the Y mode undamped: unbounded amplitude (null in JSON), no torque, no NaN."""
    import json
    import subprocess
    import sys
    p = subprocess.run([sys.executable, "-W", "error", "-m", "rotorpillar", "analyze", "paper",
                        "--set", "shaft.damping=0", "--out", str(tmp_path)],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "analyze.json").read_text())
    y = [r for r in doc["resonances"] if r["direction"] == "Y"][0]
    assert y["nu"] == 0 and y["a_max"] is None and y["dL_max"] == 0
    assert "undamped" in y["statement"]
    assert all(v is not None for v in y["curves"]["dL"])


@pytest.mark.parametrize("sets, key", [
    (["shaft.stiffness=1e300"], "shaft.stiffness"),
    (["rotor.mass=1e300"], "rotor.mass"),
    (["gondola.mass=1e300"], "gondola.mass"),
    (["rotor.inertia=1e-300"], "rotor.inertia"),
    (["pillar.youngs_modulus=1e30"], "pillar.youngs_modulus"),
    (["pillar.density=1e30"], "pillar.density"),
    (["drive.slope=0", "load.coefficient=0"], "drive.slope"),
])
@pytest.mark.parametrize("command", ["analyze", "simulate"])
def test_values_that_break_the_formulas_are_refused(tmp_path, sets, key, command):
    out = tmp_path / "out"
    p = cli(command, "paper", *[a for s in sets for a in ("--set", s)], "--out", out)
    assert p.returncode == 2 and key in one_line(p)
    assert not out.exists()


def test_a_micrometre_tube_is_refused_before_gmsh(tmp_path):
    p = cli("modal", "paper", "--set", "pillar.height=1e-6", "--out", tmp_path / "out")
    assert p.returncode == 2 and "height" in one_line(p)


@pytest.fixture(scope="module")
def computed(tmp_path_factory):
    """analyze and a short run-up, written as the commands write them."""
    out = tmp_path_factory.mktemp("computed")
    for args in (["analyze"], ["simulate", "--case", "runup", "--set", "simulate.duration=5"]):
        p = cli(args[0], "paper", *args[1:], "--out", out)
        assert p.returncode == 0, p.stderr
    return out


@pytest.mark.parametrize("name, damage, command", [
    ("analyze.json", lambda t: t[:100], "analyze"),
    ("analyze.json", lambda t: "", "analyze"),
    ("simulate_runup.json", lambda t: "\x00\x01binary", "simulate"),
    ("simulate_runup.npz", None, "simulate"),
    ("modal.json", lambda t: "[1, 2]", "modal"),
], ids=["truncated", "empty", "binary-json", "binary-npz", "wrong-shape"])
def test_the_report_survives_a_damaged_input(tmp_path, computed, name, damage, command):
    import html
    import shutil
    out = tmp_path / "out"
    shutil.copytree(computed, out)
    f = out / name
    if damage is None:
        f.write_bytes(b"\x00\x01\x02 not an npz")
    else:
        f.write_text(damage(f.read_text() if f.exists() else ""))
    p = cli("report", "paper", "--out", out, "--no-animations")
    assert p.returncode == 0, p.stderr
    page = html.unescape((out / "report.html").read_text())
    assert "is damaged" in page and f"rotorpillar {command} paper" in page
    p = cli("report", "paper", "--out", out, "--no-animations", "--strict")
    assert p.returncode == 1 and (out / "report.html").is_file()


@pytest.mark.parametrize("command", ["analyze", "simulate", "report", "run", "integrators"])
def test_only_modal_runs_under_mpirun(tmp_path, command):
    """Under mpirun every rank would do the whole job and write: refused, one line per rank.
    (The launcher's environment is what mpirun sets for each rank.)"""
    import os
    out = tmp_path / "out"
    p = cli(command, "paper", "--out", out, env=dict(os.environ, OMPI_COMM_WORLD_SIZE="2"))
    assert p.returncode == 2 and "without mpirun" in one_line(p)
    assert not out.exists()


def test_a_run_past_its_stability_limit_is_a_failure_not_a_success(tmp_path):
    """Central difference with h = 1 s on modes of ~30 rad/s: h omega = 29 > 2 (its limit)."""
    import json
    p = cli("simulate", "paper", "--case", "runup", "--out", tmp_path,
            "--set", "simulate.integrator=central_difference", "--set", "simulate.time_step=1")
    assert p.returncode == 4, p.stderr
    doc = json.loads((tmp_path / "simulate.json").read_text())
    assert doc["ok"] is False
    assert any("stability limit" in c for c in doc["failed_checks"])
    assert any("energy balance" in c for c in doc["failed_checks"])


@pytest.mark.parametrize("case", ["runup", "rundown", "earthquake"])
def test_a_good_run_passes_its_checks(tmp_path, case):
    import json
    p = cli("simulate", "paper", "--case", case, "--out", tmp_path, "--set", "simulate.duration=10")
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "simulate.json").read_text())
    assert doc["ok"] is True and "failed_checks" not in doc


def test_captured_at_is_the_settled_speed_and_an_escaping_run_is_not_captured(tmp_path):
    """sommerfeld: at M0 = 600 N*m the rotor settles below omega_1 (captured); at 630 N*m it
    is still rising at 80 s (escaping), not captured (issue: clear semantics)."""
    import json
    p = cli("simulate", "sommerfeld", "--case", "runup", "--no-threshold", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    d = json.loads((tmp_path / "simulate.json").read_text())
    assert d["speed_state"] == "captured" and "passing_torque" not in d
    assert d["captured_at"] == pytest.approx(d["omega_final_mean"])
    assert d["captured_at"] < d["captured_resonance"]           # held below the resonance
    p = cli("simulate", "sommerfeld", "--case", "runup", "--no-threshold", "--out", tmp_path,
            "--set", "drive.torque_at_zero=630")
    d = json.loads((tmp_path / "simulate.json").read_text())
    assert d["speed_state"] == "escaping" and d["captured_at"] is None


@pytest.mark.parametrize("args, words", [
    (["simulate", "--set", "simulate.integrator=newmark", "--set", "simulate.time_step=1e-9"],
     "simulate.max_steps"),
    (["simulate", "--case", "sweep", "--set", "sweep.rate=1e-6"], "simulate.max_steps"),
    (["simulate", "--case", "sweep", "--set", "sweep.settle=1e12"], "simulate.max_steps"),
    (["simulate", "--case", "sweep", "--set", "sweep.bins=100000"], "sweep.bins"),
    (["simulate", "--set", "simulate.rtol=1e-300"], "simulate.rtol"),
    (["integrators", "--duration", "1000"], "--duration"),
], ids=["tiny-step", "slow-sweep", "long-settle", "many-bins", "rtol-underflow", "long-study"])
def test_work_that_cannot_finish_is_refused_with_its_estimate(tmp_path, args, words):
    out = tmp_path / "out"
    p = cli(args[0], "paper", *args[1:], "--out", out, timeout=120)
    assert p.returncode == 2 and words in one_line(p)
    assert not out.exists()


@pytest.mark.parametrize("command", ["analyze", "run"])
def test_a_missing_record_is_noticed_before_any_work(tmp_path, command):
    out = tmp_path / "out"
    p = cli(command, "paper", "--set", "excitation.kind=record", "--set",
            f"excitation.record='{tmp_path / 'nope.txt'}'", "--out", out)
    assert p.returncode == 2 and "excitation.record" in one_line(p)
    assert not out.exists()


def test_a_record_timed_in_milliseconds_is_flagged_not_realistic(tmp_path):
    """Times read as seconds that were milliseconds: a 10 s step and tens of metres of ground."""
    import json
    rec = tmp_path / "ms.txt"
    rec.write_text("0 0\n10 0.3\n20 -0.3\n30 0.2\n40 0\n")
    p = cli("simulate", "paper", "--case", "earthquake", "--model", "modal", "--out", tmp_path,
            "--set", "excitation.kind=record", "--set", f"excitation.record='{rec}'")
    doc = json.loads((tmp_path / "simulate.json").read_text())
    assert doc["excitation"]["realistic"] is False and "time step" in doc["excitation"]["statement"]
    assert any("not a realistic earthquake" in w for w in doc["warnings"])
    assert "not a realistic earthquake" in p.stderr


@pytest.mark.slow                       # a convergence study (shell ladder in subprocesses)
def test_a_short_ladder_chooses_no_model_without_an_error_estimate(tmp_path):
    """No 3D model and an 8-around shell: no family converges, so there is no reference and
    no run has an error estimate; the study says so instead of choosing the closed forms."""
    import json
    p = cli("converge", "paper", "--set", "converge.solid=false", "--set",
            "converge.shell_max_around=8", "--set", "converge.shell_tri_max_around=8",
            "--no-progress", "--out", tmp_path, timeout=600)
    assert p.returncode == 0, p.stderr
    sel = json.loads((tmp_path / "convergence.json").read_text())["selection"]
    assert sel["chosen"] is None and "no converged reference" in sel["reason"]


@pytest.mark.slow                       # two convergence studies per case
@pytest.mark.parametrize("content", ["null", "[1, 2]"])
def test_a_damaged_cache_file_is_recomputed_not_fatal(tmp_path, content):
    """A run cache that parses to another shape (or not at all) is treated as absent."""
    import json
    args = ["converge", "paper", "--set", "converge.solid=false", "--set",
            "converge.shell_max_around=8", "--set", "converge.shell_tri_max_around=8",
            "--no-progress", "--workers", "1", "--out", tmp_path]
    assert cli(*args, timeout=600).returncode == 0
    files = sorted((tmp_path / "cache").glob("*.json"))
    files[0].write_text(content)
    p = cli(*args, timeout=600)
    assert p.returncode == 0, p.stderr
    assert json.loads(files[0].read_text())["status"] == "ok"     # recomputed and rewritten


@pytest.mark.slow                       # two convergence studies per case
@pytest.mark.parametrize("sig", ["SIGTERM", "SIGKILL"])
def test_converge_killed_leaves_whole_files_and_resumes(tmp_path, sig):
    """Killed mid-study (SIGTERM: stops its runs; SIGKILL: no chance to clean up): every
    JSON on disk parses, and the rerun computes only what is missing."""
    import json
    import signal
    import subprocess
    import sys
    import time
    args = ["converge", "paper", "--set", "converge.solid=false", "--set",
            "converge.shell_max_around=8", "--set", "converge.shell_tri_max_around=8",
            "--no-progress", "--workers", "1", "--out", str(tmp_path)]
    proc = subprocess.Popen([sys.executable, "-m", "rotorpillar", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    cache, deadline = tmp_path / "cache", time.time() + 120
    while time.time() < deadline and proc.poll() is None:
        if cache.exists() and len(list(cache.glob("*.json"))) >= 5:
            break
        time.sleep(0.05)
    proc.send_signal(getattr(signal, sig))
    proc.communicate(timeout=60)
    for f in tmp_path.rglob("*.json"):
        if not f.name.startswith("."):                     # a killed writer's temporary part
            json.loads(f.read_text())                      # whole, or not there
    done = len(list(cache.glob("*.json")))
    p = cli(*args, "--json", timeout=600)
    assert p.returncode == 0, p.stderr
    study = json.loads(p.stdout)["study"]
    assert study["cached"] >= done - 1 and study["computed"] == study["runs"] - study["cached"]
    assert not list(cache.glob(".*.part*"))                 # a killed writer's part is gone


def test_a_damaged_vtu_costs_its_pictures_quietly(tmp_path, computed):
    """No VTK parser errors on the terminal, no traceback: one failure naming the file and
    the command that rebuilds it."""
    import json
    import shutil
    import fixtures
    out = tmp_path / "out"
    shutil.copytree(computed, out)
    fixtures.write_modal_fixture(out, around=24, along=16)
    (out / "modes_bare.vtu").write_text("garbage")
    p = cli("report", "paper", "--out", out, "--no-animations")
    assert p.returncode == 0, p.stderr
    assert "Traceback" not in p.stderr and "vtkXML" not in p.stderr
    failures = json.loads((out / "report.json").read_text())["failures"]
    assert any("modes_bare.vtu is damaged" in v and "rotorpillar modal" in v for v in failures.values())
