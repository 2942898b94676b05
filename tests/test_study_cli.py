"""`rotorpillar study` end to end: bad --vary refused, a real Ctrl-C after the
first batch and the resume, the files written (study.json round-trips through
StudyResult, study.csv, the capture map), and the report's study section.

The numbers are checked in test_study.py against single runs; here the
structure, the counts of cached and computed batches, and the charts being
real PNG images of the expected size (STYLE: data, not pixels)."""

import json
import signal
import subprocess
import sys
import time

import pytest
from conftest import cli_here, sigint_as_in_the_foreground

from rotorpillar import records
from rotorpillar.cli import main

BAD = [
    ("drive.torque=560:700:3", "unknown key"),
    ("nosuch.key=1,2", "unknown key"),
    ("drive.torque_at_zero=600:600:3", "empty range"),
    ("drive.torque_at_zero=", "empty range"),
    ("drive.torque_at_zero=560:700:0", "must be >= 1"),
    ("rotor.eccentricity=-0.01:0.02:3", "out of range"),
    ("pillar.poisson_ratio=0.3,0.6", "out of range"),
    ("drive.torque_at_zero=a:700:3", "not a number"),
]


@pytest.mark.parametrize("vary,words", BAD)
def test_bad_vary_is_refused_with_one_line_and_nothing_written(tmp_path, capsys, vary, words):
    out = tmp_path / "out"
    rc = main(["study", "sommerfeld", "--case", "runup", "--vary", vary, "--out", str(out)])
    err = capsys.readouterr().err.strip()
    assert rc == 2
    assert len(err.splitlines()) == 1 and words in err, err
    assert vary.split("=")[0] in err
    assert not out.exists()


def test_no_vary_and_a_bad_worker_count_are_refused(tmp_path, capsys):
    for extra in ([], ["--vary", "drive.torque_at_zero=600,700", "--workers", "0"]):
        rc = main(["study", "sommerfeld", *extra, "--out", str(tmp_path / "o")])
        assert rc == 2 and len(capsys.readouterr().err.strip().splitlines()) == 1
    assert not (tmp_path / "o").exists()


def _png_size(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


AXES = ["--vary", "drive.torque_at_zero=560:700:8", "--vary", "rotor.eccentricity=0.010:0.020:6"]


@pytest.fixture(scope="module")
def scheduler():
    """The address of a Dask LocalCluster of one worker process that the in-process studies
    below reach with ``--scheduler`` (the resume and the IDA study): one worker's start and
    imports (Dask, numba, scipy: ~1.9 s of CPU) for both, not one each with ``--workers 1``.
    The command's own cluster (``--workers 1``) is what the interrupted child runs on (it
    computes at least one batch on it: the check of the batches it leaves)."""
    from rotorpillar.executor import Executor

    with Executor(workers=1) as ex:
        yield ex.client.scheduler.address


@pytest.mark.slow  # a 48-run study, interrupted and resumed
def test_ctrl_c_keeps_finished_batches_and_the_rerun_computes_the_rest(tmp_path, scheduler):
    out = tmp_path / "out"
    batches = out / "study"
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "rotorpillar",
            "study",
            "sommerfeld",
            "--case",
            "runup",
            *AXES,
            "--workers",
            "1",
            "--out",
            str(out),
            "--no-progress",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=sigint_as_in_the_foreground,
    )
    deadline = time.time() + 300
    while time.time() < deadline and proc.poll() is None:
        if batches.exists() and list(batches.glob("*.json")):
            break
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "interrupted" in err
    done = list(batches.glob("*.json"))
    assert 1 <= len(done) < 6  # 48 runs: 6 batches of 8
    assert not list(batches.glob(".*"))  # no half-written batch
    for f in done:
        assert len(json.loads(f.read_text())["value"]["runs"]) == 8  # a cache.Entry: the key beside the batch
    assert not (out / "study.json").exists()

    # the resume, the rerun and the IDA study below in this process (conftest.cli_here: their
    # files, JSON and exit codes are the checks; the interrupt above needs its child), the
    # resume on the module's cluster of one worker (``scheduler``)
    p = cli_here(
        "study",
        "sommerfeld",
        "--case",
        "runup",
        *AXES,
        "--scheduler",
        scheduler,
        "--out",
        out,
        "--no-progress",
        "--json",
    )
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    assert doc["batches"]["cached"] == len(done)
    assert doc["batches"]["computed"] == 6 - len(done)
    assert doc["performance"]["runs_computed"] == 48 - 8 * len(done)
    assert len(doc["runs"]) == 48 and doc["executor"]["workers"] == 1

    from rotorpillar.studies import StudyResult

    on_disk = json.loads((out / "study.json").read_text())
    rec = records.read(out / "study.json", StudyResult)
    assert records.to_builtins(rec) == {k: on_disk[k] for k in records.to_builtins(rec)}
    assert len((out / "study.csv").read_text().splitlines()) == 1 + 48
    w, h = _png_size(out / "study_capture_map.png")
    assert w >= 1000 and h >= 700
    assert doc["boundary"]["predicted"]["kind"] == "torque" and len(doc["boundary"]["found"]) == 6

    again = json.loads(
        cli_here("study", "sommerfeld", "--case", "runup", *AXES, "--out", out, "--no-progress", "--json").stdout
    )
    assert again["batches"]["computed"] == 0 and again["executor"]["workers"] == 0

    # the report's study section: the map embedded once, the boundary table
    from rotorpillar.postprocess.readers import read_record
    from rotorpillar.postprocess.report.figures import external_figures
    from rotorpillar.postprocess.report.state import Build, Product, ReportOptions
    from rotorpillar.postprocess.report.study import section_study
    from rotorpillar.scene import load_scene

    build = Build(load_scene("sommerfeld"), out, "sommerfeld", ReportOptions())
    read = read_record(out / "study.json", StudyResult)
    build.study, build.provenance.study = read.record, read.provenance
    build.external = [Product(p, c, group=w.group, case=w.case) for p, c, w in external_figures(out)]
    html = section_study(build)
    assert "Design study" in html and "found against predicted" in html
    assert html.count("<img") == 1
    assert not [p for p in build.external if p.path.name.startswith("study_")]


@pytest.mark.slow  # a design study on a Dask cluster (the module's: ``scheduler``)
def test_earthquake_study_draws_the_ida_curves(tmp_path, scheduler):
    p = cli_here(
        "study",
        "paper",
        "--case",
        "earthquake",
        "--model",
        "modal",
        "--vary",
        "excitation.record_scale=0.5:1.5:3",
        "--vary",
        "excitation.record=elcentro",
        "--set",
        "excitation.start=0",
        "--scheduler",
        scheduler,
        "--out",
        tmp_path,
        "--no-progress",
        "--json",
    )
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    assert doc["implied"] == {"excitation.kind": "record"}
    runs = doc["runs"]
    pga = [r["pga"] for r in runs]
    assert pga == sorted(pga) and pga[2] == pytest.approx(3 * pga[0], rel=1e-9)
    tips = [r["peak_tip"] for r in runs]
    assert tips[0] < tips[1] < tips[2]
    w, h = _png_size(tmp_path / "study_ida.png")
    assert w >= 1000 and h >= 500
