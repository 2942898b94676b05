"""What the main job writes: one ``rotorpillar run paper`` (the shared
``run_paper`` fixture, converge and compare skipped, 12 frames per animation),
checked for its stages, its files, its CSVs, its page and its last line.

Every test of that run lives in this one module: under pytest-xdist's
worksteal a module's tests go to one worker, so the other worker is never
left waiting for the run while it is computed (the fixture is shared through
a lock file: a second worker asking for it would idle until it is done).
Sources: the stages and file names are the README's contract; the CSVs'
shape and values are checked against the runs' own NPZ (test_csv_files);
the page is read as a reader would (test_report_reader).
"""

import json

import pytest
from test_csv_files import check_run_csv
from test_report_reader import designer_problems, governing_check, needs_chromium, reader_problems

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
