"""`rotorpillar run` runs a stage again only when its key changes (commands.stage_keys).

- A stage's key follows the scene sections it reads: the drive's stall torque
  changes the key of analyze, of every transient and of the report; the ground
  motion's amplitude leaves the convergence study's and modal's keys alone
  (they read the tube, the mesh and the band, not the excitation).  Both read
  the band, whose top is the drive's free speed (reduced.band.excitation_band),
  by what it does to them: the study by the modes inside it (chain.choice), modal
  by where it cuts its modes (commands.run.modal_band).  Without their files on
  disk any new torque moves both keys.
- A changed input file (convergence.json) changes the keys of the stages after
  the study, not the study's own.
- The code hash follows every file of the package, not its compiled caches.
- Only a stage that succeeded is kept: a failing one is not, and a kept stage
  whose JSON was rewritten since (a command run by hand) is run again.
- The whole main job run again into a copy of its folder (nothing, then with the
  ground motion changed every stage but modal, then --force) is test_main_job's
  (it starts from the shared ``run_paper``).
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import sys

import pytest
from conftest import shell_runs

from rotorpillar.commands import stage_keys
from rotorpillar.commands.parser import build_parser
from rotorpillar.commands.run import RUN_STAGES, key_of, plan_stages, run_wave
from rotorpillar.errors import StageError
from rotorpillar.scene import load_scene, override


def keys_for(out, *sets: str, flags: tuple[str, ...] = ()) -> dict[str, str]:
    """Every stage's key for `run paper --out OUT --set ... FLAGS`."""
    words = ["run", "paper", "--out", str(out), *[a for s in sets for a in ("--set", s)], *flags]
    args = build_parser().parse_args(words)
    plans = plan_stages(RUN_STAGES, load_scene(args.scene, args.overrides), args, out)
    return {p.stage.command: key_of(p, out) for p in plans}


def changed(a: dict[str, str], b: dict[str, str]) -> set[str]:
    return {command for command in a if a[command] != b[command]}


def test_the_same_job_has_the_same_keys(tmp_path):
    assert keys_for(tmp_path) == keys_for(tmp_path)
    assert keys_for(tmp_path, "drive.torque_at_zero=6000") == keys_for(tmp_path, "drive.torque_at_zero=6000")


def test_run_quick_changes_the_integrator_studys_key_only(tmp_path):
    # --quick goes on to integrators (its command line, so its key); the report's key moves
    # only through integrators.json once that stage has written it (an input file, below)
    assert changed(keys_for(tmp_path), keys_for(tmp_path, flags=("--quick",))) == {"integrators"}


def test_the_drives_torque_changes_the_keys_of_the_stages_that_read_the_drive(tmp_path):
    base = keys_for(tmp_path)
    moved = changed(base, keys_for(tmp_path, f"drive.torque_at_zero={load_scene('paper').drive.torque_at_zero * 1.1}"))
    transients = {st.command for st in RUN_STAGES if st.name in ("simulate", "compare", "integrators")}
    assert transients and transients <= moved
    assert {"analyze", "harmonic", "campbell", "report"} <= moved
    # the band's top is the drive's free speed: modal's mode count reads it, and the study
    # without a study on disk to tell which modes the band holds
    assert {"converge", "modal"} <= moved


def test_a_new_stall_torque_leaves_the_study_alone_when_its_band_holds_the_same_modes(tmp_path):
    """With the study on disk (paper's band holds bending and ovalling), a stall torque 10 %
    higher keeps both in the band: the study's key stays (its choice stands: chain.choice),
    modal's and the transients' move.  A torque that drops ovalling from the band moves it."""
    from test_chain import SOLID, _run, _study_doc

    from rotorpillar.reduced.band import excitation_band

    s = load_scene("paper")
    chosen = _run("3D P2 hexahedra, 128x20x1", "solid_hex_p2", "solid", SOLID, 94464, 6.4, 3e-4, 6e-4)
    doc = _study_doc(s, chosen, [chosen])
    top = excitation_band(s.drive, s.load, s.converge).omega_max
    doc["selection"]["needed"] = [q for q in ("bending", "ovalling") if doc["reference"][q]["value"] <= top]
    (tmp_path / "convergence.json").write_text(json.dumps(doc))
    base = keys_for(tmp_path)
    moved = changed(base, keys_for(tmp_path, f"drive.torque_at_zero={s.drive.torque_at_zero * 1.1}"))
    assert "converge" not in moved and {"modal", "analyze", "compare --case runup"} <= moved
    assert "converge" in changed(base, keys_for(tmp_path, f"drive.torque_at_zero={s.drive.slope * 50}"))


def test_a_new_stall_torque_leaves_modal_alone_while_its_cuts_stand(tmp_path):
    """modal keeps 8 modes, doubled while the last kept lies inside the band's edge
    (reduced.band.cut_count).  With modal.json on disk, a stall torque that moves the edge
    but not past its last listed mode keeps modal's key (its modes would be the same); one
    that moves the edge past it changes the key.  The ROM's modes from the beam here, so
    that the key holds no 3D solve (chain.modes.cached_solve: -1)."""
    from rotorpillar.reduced.band import excitation_band

    s = load_scene("paper")
    beam = "modal_model.source=beam"

    def edge(factor: float) -> float:
        d = override(s, [f"drive.torque_at_zero={s.drive.torque_at_zero * factor}"]).drive
        return excitation_band(d, s.load, s.converge).omega_max

    e0, e1, e2 = edge(1.0), edge(1.1), edge(1.5)
    assert e0 < e1 < e2  # a stronger motor runs free faster: the band widens
    last = 0.5 * (e1 + e2)  # past the edge at +10 %, inside it at +50 %
    listed = [0.2 * e0] * 2 + [0.6 * e0] * 2 + [0.9 * e0] * 2 + [last] * 2

    def rows(omegas):
        return [{"omega": w} for w in omegas]

    (tmp_path / "modal.json").write_text(json.dumps({"modes": rows(listed), "modes_with_top": rows(listed)}))
    base = keys_for(tmp_path, beam)
    torque = s.drive.torque_at_zero
    stronger = changed(base, keys_for(tmp_path, beam, f"drive.torque_at_zero={torque * 1.1}"))
    assert "modal" not in stronger and {"analyze", "compare --case runup"} <= stronger
    assert "modal" in changed(base, keys_for(tmp_path, beam, f"drive.torque_at_zero={torque * 1.5}"))
    # without modal.json the key takes the band's tops: any new torque moves it
    (tmp_path / "modal.json").unlink()
    assert "modal" in changed(
        keys_for(tmp_path, beam), keys_for(tmp_path, beam, f"drive.torque_at_zero={torque * 1.1}")
    )


def test_the_ground_motion_leaves_the_study_and_modal_alone(tmp_path):
    base = keys_for(tmp_path)
    moved = changed(base, keys_for(tmp_path, "excitation.amplitude=2.5", "full_order.earthquake_duration=3"))
    assert "converge" not in moved and "modal" not in moved
    assert {
        "analyze",
        "simulate --case earthquake",
        "simulate --case runup",
        "compare --case earthquake",
        "report",
    } <= moved


def test_an_input_file_changes_the_keys_of_the_stages_after_it(tmp_path):
    base = keys_for(tmp_path)
    (tmp_path / "convergence.json").write_text('{"selection": "a"}')
    first = keys_for(tmp_path)
    (tmp_path / "convergence.json").write_text('{"selection": "b"}')
    second = keys_for(tmp_path)
    after = {st.command for st in RUN_STAGES if st.command != "converge"}
    assert changed(base, first) == after and changed(first, second) == after
    # modal.json is read by the stages after modal, not by modal itself
    (tmp_path / "modal.json").write_text("{}")
    assert changed(second, keys_for(tmp_path)) == after - {"modal"}


def test_the_code_hash_follows_every_file_but_the_compiled_caches(tmp_path):
    pkg = tmp_path / "pkg"
    shutil.copytree(stage_keys.Path(stage_keys.__file__).parent, pkg, ignore=shutil.ignore_patterns("__pycache__"))
    before = stage_keys.package_hash(pkg)
    (pkg / "__pycache__").mkdir(exist_ok=True)
    (pkg / "__pycache__" / "run.cpython-311.pyc").write_bytes(b"\0")
    assert stage_keys.package_hash(pkg) == before
    (pkg / "run.py").write_text((pkg / "run.py").read_text() + "\n# a comment\n")
    assert stage_keys.package_hash(pkg) != before
    assert len(stage_keys.code_hash()) == 16


def test_only_a_stage_that_succeeded_is_kept(tmp_path):
    def job(name, code):
        script = f"import pathlib; pathlib.Path({str(tmp_path)!r}, '{name}.json').write_text('{{}}'); raise SystemExit({code})"
        return name, [sys.executable, "-c", script]

    kept = []

    def keep(command, seconds):
        stage_keys.remember(tmp_path, command, "k", seconds)
        kept.append(command)

    with pytest.raises(StageError, match="'bad' failed"):
        run_wave([job("good", 0), job("bad", 1)], slots=2, on_done=keep)
    assert kept == ["good"]
    assert stage_keys.recall(tmp_path, "good", "k") is not None
    assert stage_keys.recall(tmp_path, "bad", "k") is None
    # forgotten before a stage runs again: an interrupted run leaves nothing to reuse
    stage_keys.forget(tmp_path, "good")
    assert stage_keys.recall(tmp_path, "good", "k") is None


def _stages(out) -> dict[str, bool]:
    """run.json's stages: stem -> reused."""
    return {stem: st["reused"] for stem, st in json.loads((out / "run.json").read_text())["stages"].items()}


@contextlib.contextmanager
def one_core():
    """This thread, and the processes it starts, on one of its cores: `converge` takes its
    workers from the cores it may run on (provenance.usable_cores), so its stage runs on one
    worker, with no Dask cluster and one serving process (as a user limits it with taskset)."""
    cores = os.sched_getaffinity(0)
    os.sched_setaffinity(0, {min(cores)})
    try:
        yield
    finally:
        os.sched_setaffinity(0, cores)


@pytest.mark.slow
def test_run_keeps_the_study_through_a_stall_torque_that_keeps_its_modes(tmp_path, tmp_path_factory, here):
    """The main job with only the study (a shell-only ladder: the Q2 quadrilaterals' three
    rungs up to 16 around, whose Richardson reference puts bending and ovalling in the band)
    and the report: run again with a stall torque 10 % higher, the study is not run again
    (its band still holds bending and ovalling); at that torque, and with one that drops
    ovalling, its key is asked as run asks it (key_of, then stage_keys.recall on the study's
    kept key and files): kept, and not kept, so run would run it again.

    Asked of the keys, not by more runs: a stage whose key is not the kept one runs again by
    the same code for every stage (test_main_job's ground-motion run shows it), and a third
    run at the higher torque made the same recall as ``kept`` below.  The two runs in this
    process (conftest's ``here``: `run` starts its stages as children either way) and on one
    core (the study's Dask cluster and its second serving process are not the point here).
    Measured (issue 30, user+system CPU of the test): three `run` children, the study on two
    workers with the triangles to 16 around, 16.1 s; two runs here, one core, the triangles'
    one rung (8 around), 8.7 s."""
    out = tmp_path / "out"
    # the study's shell rungs from the session's run cache (conftest.shell_runs: the
    # same runs by the same runner), in its cache beforehand: the stage reads them all
    shutil.copytree(shell_runs(tmp_path_factory), out / "cache")
    others = ("modal", "analyze", "compare", "integrators", "harmonic", "campbell", "tornado", "simulate")
    skips = [a for s in others for a in ("--skip", s)]
    ladder = ("converge.solid=false", "converge.shell_max_around=16", "converge.shell_tri_max_around=8")
    small = [*(a for s in ladder for a in ("--set", s)), "--no-animations"]
    torque = load_scene("paper").drive.torque_at_zero

    def run(*more):
        with one_core():
            p = here("run", "paper", "--out", out, *skips, *small, *more, timeout=600)
        assert p.returncode == 0, p.stderr
        return p, _stages(out)

    _, first = run()
    assert first["converge"] is False
    p, stronger = run("--set", f"drive.torque_at_zero={torque * 1.1}")
    assert stronger["converge"] is True and "converge: unchanged since " in p.stderr

    def kept(torque_at_zero: float) -> bool:
        """Would run reuse the study at this stall torque (its key, the kept key and files)?"""
        key = keys_for(out, *ladder, f"drive.torque_at_zero={torque_at_zero}", flags=("--no-animations",))
        return stage_keys.recall(out, "converge", key["converge"]) is not None

    assert kept(torque * 1.1)  # what the run above found, asked the same way: a third run would reuse it
    assert not kept(load_scene("paper").drive.slope * 50)
