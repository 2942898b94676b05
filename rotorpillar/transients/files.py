"""A model run's files: ``simulate_<case>_<model>.{json,npz,csv,png}`` and, for the
last run of `simulate`, the same as ``simulate_<case>.*`` (existing scripts read those).

NPZ: every series of ``ModelRun.data`` plus the scalars ``tip_x_frame``,
``model``, ``case`` and the coordinate names; CSV: plain (the header is the
first line), ``CSV_COLUMNS`` (those a model has), then the modal coordinates
eta1.. of the modal model, in SI units (s, rad/s, m, m/s2): ``tip_x`` and
``rotor_x`` in the frame the JSON's ``tip_x_frame`` names, ``tip_x_relative``
relative to the ground, ``tip_x_absolute`` absolute, ``shaft_deflection_x`` =
rotor X - tip X - e cos(theta).  Charts by rotorpillar.postprocess.transient_charts.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import io
import shutil
from pathlib import Path
from typing import Any

import numpy as np

from ..provenance import atomic_path, write_result, write_text
from ..records import Figure, replace
from ..reduced.rotor_models import StructureDescription
from .model_run import Fem3dRun, ModelFiles, ModelRun, ReducedRun, RunFiles

CSV_COLUMNS = (
    "t",
    "Omega",
    "tip_x",
    "rotor_x",
    "rotor_y",
    "ground_x",
    "ground_acceleration",
    "tip_x_relative",
    "tip_x_absolute",
    "shaft_deflection_x",  # the old ones first
    "base_moment",
    "base_shear",
    "base_axial",
    "base_stress",
    "bearing_force",
)
NPZ_SCALARS = ("tip_x_frame", "model", "case")


def model_stem(case: str, model: str) -> str:
    return f"simulate_{case}_{model}"


def write_model_files(
    out: Path,
    scene: Scene,
    run: ModelRun,
    provenance: dict[str, Any],
    timings: dict[str, float] | None = None,
    last_run: bool = True,
    charts=None,
    stem: str | None = None,
) -> ReducedRun | Fem3dRun:
    """Write the model's files (and with ``last_run`` the ``simulate_<case>.*`` copies);
    returns the run's record with its ``files`` and ``figures`` (those of the generic
    names when ``last_run``, else the model's) and ``model_files``.

    ``charts(out, scene, run, stem) -> [Figure]`` draws the run's figures
    (``rotorpillar.postprocess.transient_charts.model_run_charts``; handed in, since
    drawing lives above this layer); None draws none.  ``stem`` replaces
    ``simulate_<case>_<model>`` (compare: ``compare_<case>_<model>``).
    """
    out = Path(out)
    stem = stem or model_stem(run.case, run.model)
    files = RunFiles(npz=str(_write_npz(out / f"{stem}.npz", run)), csv=str(_write_csv(out / f"{stem}.csv", run)))
    figures: tuple[Figure, ...] = tuple(charts(out, scene, run, stem)) if charts is not None else ()
    own = ModelFiles(
        npz=Path(files.npz).name, csv=Path(files.csv).name, json=f"{stem}.json", figures=tuple(f.file for f in figures)
    )
    record = replace(run.record, files=files, figures=figures, model_files=own)
    head = {"command": "simulate", **provenance, "scene": scene.to_dict()}
    write_result(out / f"{stem}.json", record, head, timings)
    if not last_run:
        return record
    generic = f"simulate_{run.case}"
    gfiles = RunFiles(
        npz=str(_copy(Path(files.npz), out / f"{generic}.npz")), csv=str(_copy(Path(files.csv), out / f"{generic}.csv"))
    )
    gfigures = []
    for fig in figures:
        name = fig.file[:-4].removesuffix(f"_{run.model}") + ".png"
        _copy(out / fig.file, out / name)
        gfigures.append(replace(fig, file=name))
    record = replace(record, files=gfiles, figures=tuple(gfigures))
    write_result(out / f"{generic}.json", record, head, timings)
    return record


def _copy(src: Path, dst: Path) -> Path:
    with atomic_path(dst) as tmp:
        shutil.copyfile(src, tmp)
    return dst


def _write_npz(path: Path, run: ModelRun) -> Path:
    arrays = {k: np.asarray(v) for k, v in run.data.items()}
    arrays["tip_x_frame"] = np.array(run.record.tip_x_frame)
    arrays["model"] = np.array(run.model)
    arrays["case"] = np.array(run.case)
    desc = run.record.model_description
    if isinstance(desc, StructureDescription):
        arrays["coordinates"] = np.array(desc.coordinates)
    buf = io.BytesIO()  # built in memory: a full disk fails one write, not the zip's own close
    # uncompressed: zlib takes 13 % off a run's doubles for 20 times the time (0.3 s)
    np.savez(buf, **arrays)
    with atomic_path(path) as tmp:
        tmp.write_bytes(buf.getvalue())
    return path


def _write_csv(path: Path, run: ModelRun) -> Path:
    data = run.data
    cols = [c for c in CSV_COLUMNS if c in data]
    block = [np.asarray(data[c]) for c in cols]
    if "modal_coordinates" in data:
        mc = np.asarray(data["modal_coordinates"])
        cols += [f"eta{j + 1}" for j in range(mc.shape[1])]
        block += [mc[:, j] for j in range(mc.shape[1])]
    # No comment line before the header: csv.DictReader, spreadsheets and pandas would
    # take it for the header.  The columns' meaning is in the module docstring; the
    # run's provenance and tip_x_frame in its JSON.
    # one %-format a row on Python floats: the same text as f"{x:.10g}" value by value (one
    # formatter), in under half the time (a run of 10**6 samples: ~9 s of its 13); the rows
    # zipped from each column's list, not a 2D array's rows made tuples: 10**6 rows of 13
    # columns 5.4 -> 4.0 s of CPU, the same text
    line = ",".join(["%.10g"] * len(cols))
    rows = (line % row for row in zip(*(np.asarray(c, dtype=float).tolist() for c in block)))
    text = ",".join(cols) + "\n" + "\n".join(rows)
    return write_text(path, text + "\n")
