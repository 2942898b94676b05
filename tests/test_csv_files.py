"""Every CSV the package writes is plain: the header on the first line, then one row per line.

A comment line before the header (``# rotorpillar ...``) is what
``csv.DictReader``, spreadsheets and ``pandas.read_csv`` take for the header;
the provenance belongs in the JSON beside the CSV.  Each file here is read
with ``csv.DictReader`` exactly as a user would: the field names must be the
columns the writer documents, and every row must have a value for each,
parsing as a number (the study's text columns aside) equal to the run's own
record: the NPZ beside a run's CSV, the StudyResult of a study.
The main job's CSVs (the ``run_paper`` fixture) are checked in test_main_job.py.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from rotorpillar.executor import Executor
from rotorpillar.scene import load_scene
from rotorpillar.studies import design_study
from rotorpillar.studies.study import CSV_RESULTS
from rotorpillar.transients.files import CSV_COLUMNS, write_model_files
from rotorpillar.transients.model_run import run_model

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule)
pytestmark = pytest.mark.slow


def _read(path: Path) -> tuple[list[str], list[dict[str, str]]]:
    with open(path, newline="") as fh:
        reader = csv.DictReader(fh)
        rows = list(reader)
        return list(reader.fieldnames or []), rows


def check_run_csv(path: Path) -> None:
    """A run's CSV (simulate_<case>[_<model>].csv) against the NPZ written beside it."""
    fields, rows = _read(path)
    assert fields[0] == "t", (path.name, fields[:3])
    assert all(f.isidentifier() for f in fields), fields
    assert [f for f in fields if f in CSV_COLUMNS] == [c for c in CSV_COLUMNS if c in fields]
    assert {"t", "Omega", "tip_x"} <= set(fields)
    npz = np.load(path.with_suffix(".npz"))
    assert len(rows) == len(npz["t"])
    for name in fields:
        column = np.array([float(r[name]) for r in rows])
        # written with 10 significant digits: equal to the NPZ's doubles to 1e-9 relative
        want = npz[name] if name in npz else npz["modal_coordinates"][:, int(name[3:]) - 1]
        # (numpy's check: pytest.approx compares 20,000 rows one Python object at a time)
        np.testing.assert_allclose(column, want, rtol=1e-9, atol=1e-300, err_msg=name)
    # each value as Python's f"{x:.10g}" writes the NPZ's double (files._write_csv formats
    # whole rows with "%.10g": the same formatter), here on every 97th row
    lines = path.read_text().splitlines()[1:]
    for i in range(0, len(lines), 97):
        want = [npz[n][i] if n in npz else npz["modal_coordinates"][i, int(n[3:]) - 1] for n in fields]
        assert lines[i] == ",".join(f"{x:.10g}" for x in want), (path.name, i)


def test_a_runs_csv_is_plain(tmp_path):
    """The run's CSV and its copy, as `simulate` writes them (without the chart); the modal
    model's carries its modal coordinates eta1..."""
    scene = load_scene("paper", ["simulate.duration=2"])
    run = run_model(scene, "runup", "modal")
    write_model_files(tmp_path, scene, run, provenance={})
    for path in (tmp_path / "simulate_runup.csv", tmp_path / "simulate_runup_modal.csv"):
        check_run_csv(path)
        assert "eta1" in _read(path)[0]


def test_a_studys_csv_is_plain(tmp_path):
    vary = ["drive.torque_at_zero=560,700"]
    with Executor(processes=False) as ex:
        result = design_study(
            load_scene("sommerfeld"), "runup", "paper", vary, out_dir=tmp_path, executor=ex, show_progress=False
        )
    fields, rows = _read(tmp_path / "study.csv")
    assert fields == ["index", "drive.torque_at_zero", *CSV_RESULTS]
    assert len(rows) == len(result.runs) == 2
    for row, run in zip(rows, result.runs):  # the records study.json holds
        assert int(row["index"]) == run.index
        assert float(row["drive.torque_at_zero"]) == run.params["drive.torque_at_zero"]
        for name in CSV_RESULTS:
            want, got = getattr(run, name), row[name]
            if want is None:
                assert got == "", name
            elif isinstance(want, bool):
                assert got == ("true" if want else "false"), name
            elif isinstance(want, (int, float)):
                assert math.isclose(float(got), want, rel_tol=1e-9), name  # 10 digits written
            else:
                assert got == str(want), name
    assert result.files.csv == str(tmp_path / "study.csv")
