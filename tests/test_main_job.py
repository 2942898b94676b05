"""What the main job writes: one ``rotorpillar run paper`` (the shared
``run_paper`` fixture, converge and compare skipped, 12 frames per animation),
checked for its stages, its files, its CSVs, its page and its last line.

Every test of that run lives in this one module: under pytest-xdist's
worksteal a module's tests go to one worker, so the other worker is never
left waiting for the run while it is computed (the fixture is shared through
a lock file: a second worker asking for it would idle until it is done).
Sources: the stages and file names are the README's contract; the CSVs'
shape and values are checked against the runs' own NPZ (test_csv_files);
the page is read as a reader would (test_report_reader); the stages' keys
(test_run_keys) decide, in a copy of its folder, what a second run runs again.
"""

import json
import shutil

import pytest
from conftest import RUN_PAPER_FLAGS, cli
from test_csv_files import check_run_csv
from test_report_reader import designer_problems, governing_check, needs_chromium, reader_problems

from rotorpillar.commands.run import RUN_STAGES

pytestmark = pytest.mark.slow  # the whole main job (conftest marks run_paper's users too)


def test_run_writes_every_stage(run_paper):
    doc = json.loads((run_paper.out / "run.json").read_text())
    for name in doc["stages"]:
        assert (run_paper.out / f"{name}.json").exists()
    assert (run_paper.out / "analyze.json").exists()
    # run_paper skips converge and compare; every other stage ran
    assert not any(k.startswith(("compare", "converge")) for k in doc["stages"])
    assert {"analyze", "simulate_runup", "simulate_earthquake", "modal", "report"} <= set(doc["stages"])
    for case in ("runup", "earthquake"):
        assert (run_paper.out / f"simulate_{case}.json").exists()
        assert (run_paper.out / f"simulate_{case}.npz").exists()


def test_run_ends_with_the_report_path(run_paper):
    out = run_paper.out
    last = run_paper.process.stdout.strip().splitlines()[-1]
    assert last == f"report: {(out / 'report.html').resolve()}"
    assert (out / "report.html").is_file()
    run = json.loads((out / "run.json").read_text())
    assert list(run["stages"])[-1] == "report"
    # every section written from the real commands' outputs, read through their records
    report = json.loads((out / "report.json").read_text())
    assert report["failures"] == {} and report["damaged"] == {}
    # run's --mode-pictures 3 reached the report: three pictures of each set and its contact sheet
    for name in ("bare", "top"):
        assert len(list((out / "modes").glob(f"{name}_mode_*.png"))) == 3, name
        assert (out / "modes" / f"{name}_modes_sheet.png").is_file()


def test_every_csv_of_the_main_job_is_plain(run_paper):
    paths = sorted(run_paper.out.glob("*.csv"))
    assert {"simulate_runup.csv", "simulate_earthquake.csv"} <= {p.name for p in paths}
    for path in paths:
        check_run_csv(path)


def test_the_main_jobs_integrator_study(run_paper):
    """`integrators --quick` as `run --quick` runs it (its own command's test ran the same study
    again, 6.7 s of CPU: here it reads the main job's).  Central difference blows up once
    h omega_max > 2 (h = 2.5 ms: omega_max > 800 rad/s); the implicit and adaptive methods never
    fail on these modes; the file gives its result part back through its record."""
    from rotorpillar import records
    from rotorpillar.provenance import PROVENANCE_KEYS
    from rotorpillar.transients.integrator_study import IntegratorStudy

    written = json.loads((run_paper.out / "integrators.json").read_text())
    ff = written["stability"]["first_failure"]
    cd = ff["central_difference"]
    assert cd is not None and cd["h_times_omega_max"] > 2
    rows = [r for r in written["stability"]["rows"] if r["method"] == "central_difference" and r["ok"]]
    assert rows and all(r["omega_max"] * 2.5e-3 < 2 for r in rows)
    for m in ("newmark", "Radau", "BDF", "dp5"):
        assert ff[m] is None
    assert (run_paper.out / "integrators.png").exists()
    assert set(PROVENANCE_KEYS) <= set(written)
    result = records.to_builtins(records.convert(written, IntegratorStudy))
    assert result == {k: v for k, v in written.items() if k in result}
    assert set(result) == {"accuracy", "stability", "energy_drift", "pillar_model", "stiffness_probe", "figures"}


@needs_chromium
def test_the_main_jobs_page_reads_well(run_paper, tmp_path):
    assert reader_problems(run_paper.out / "report.html", tmp_path) == []


@needs_chromium
def test_the_page_a_designer_signs(run_paper, tmp_path):
    """The first 1400 x 900 screen holds the verdict, the governing check and its
    utilisation (from summary.json); no heading repeats; every number column has a
    unit; no internal id in the text (test_report_reader.designer_problems)."""
    name, utilisation = governing_check(run_paper.out)
    assert designer_problems(run_paper.out / "report.html", tmp_path, name, utilisation) == []


def _stages(out) -> dict[str, bool]:
    """run.json's stages: stem -> reused."""
    return {stem: st["reused"] for stem, st in json.loads((out / "run.json").read_text())["stages"].items()}


def test_run_reuses_what_has_not_changed(run_paper, tmp_path):
    """In a copy of the main job's folder (its keys and files, copied byte for byte: a key
    holds no path), ``run`` with the same flags runs nothing; with the ground motion
    changed, every stage but modal (here with the third wave left out: the simulate stages'
    keys move with it in test_run_keys, the studies' are not what is checked, and each costs
    seconds); with --force, a stage whose key stands.

    Before (its own four runs into an empty folder, on the 16 x 4 mesh, the wave's studies
    left out: everything, nothing, everything with --force, every stage but modal):
    30.6 s of CPU.  Here the first run is the fixture's own, and --force runs modal and the
    report only (its ``not force`` is one test for every stage; modal is the stage the
    ground motion left alone, so --force alone is what runs it again): 3 runs, 10.5 s of CPU
    (caches warm, 2026-11-29)."""
    out = tmp_path / "out"
    shutil.copytree(run_paper.out, out)
    first = _stages(out)
    ran = {st.stem for st in RUN_STAGES if st.name not in ("converge", "compare")}
    assert set(first) == ran and not any(first.values()), first  # the fixture's run: every stage ran

    def run(*more):
        p = cli("run", "paper", "--out", out, *RUN_PAPER_FLAGS, *more, timeout=600)
        assert p.returncode == 0, p.stderr
        return p, _stages(out)

    p, second = run()
    assert set(second) == set(first) and all(second.values()), second
    assert "modal: unchanged since " in p.stderr and "run 1/" not in p.stderr
    # --no-animations: the report runs again in both runs below (a stage before it ran), and
    # its animations are its dearest figures; they are no part of the keys checked here.
    # The ground motion moves the keys of analyze, both simulate stages and the report
    # (test_run_keys, from the keys); run runs a stage whose key moved by one test for every
    # stage, shown here on analyze and the report, the simulate stages left out with the
    # wave's studies: their runs and the charts the report draws of them again, the three
    # runs 15.7-15.8 -> 10.4-10.6 s of CPU (measured in pairs on one copy of this fixture)
    wave = [a for s in ("integrators", "harmonic", "campbell", "tornado", "simulate") for a in ("--skip", s)]
    quake = ["--set", "excitation.amplitude=2.5", "--no-animations", *wave]
    _, moved = run(*quake)
    assert moved == {"modal": True, "analyze": False, "report": False}
    # the same flags again would run nothing (as above); with --force modal runs again
    _, forced = run(*quake, "--skip", "analyze", "--force")
    assert forced == {"modal": False, "report": False}
