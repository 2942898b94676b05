"""A model run's files: ``simulate_<case>_<model>.{json,npz,csv,png}`` and, for the
last run of `simulate`, the same as ``simulate_<case>.*`` (existing scripts read those).

NPZ: every series of ``ModelRun.data`` plus the scalars ``tip_x_frame``,
``model``, ``case`` and the coordinate names; CSV: ``CSV_COLUMNS`` (those a
model has), then the modal coordinates eta1.. of the modal model.  Charts by
rotorpillar.postprocess.transient_charts.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np

from ..provenance import atomic_path, machine, versions, write_json, write_text
from .run import ModelRun

CSV_COLUMNS = ("t", "Omega", "tip_x", "rotor_x", "rotor_y", "ground_x", "ground_acceleration",
               "tip_x_relative", "tip_x_absolute", "shaft_deflection_x")     # the old ones first
NPZ_SCALARS = ("tip_x_frame", "model", "case")


def model_stem(case: str, model: str) -> str:
    return f"simulate_{case}_{model}"


def write_model_files(out: Path, scene, run: ModelRun, provenance: dict, timings: dict | None = None,
                      last_run: bool = True) -> dict:
    """Write the model's files (and with ``last_run`` the ``simulate_<case>.*`` copies);
    returns the result dict with ``files`` and ``figures`` (those of the generic names
    when ``last_run``, else the model's) and ``model_files``."""
    out = Path(out)
    stem = model_stem(run.case, run.model)
    files = {"npz": _write_npz(out / f"{stem}.npz", run), "csv": _write_csv(out / f"{stem}.csv", run)}
    figures = charts(out, scene, run, stem)
    model_files = {k: Path(v).name for k, v in files.items()}
    model_files["json"] = f"{stem}.json"
    model_files["figures"] = [f["file"] for f in figures]
    result = dict(run.result)
    result["model_files"] = model_files
    doc = {"command": "simulate", **provenance, "scene": scene.to_dict(), **result,
           "files": {k: str(v) for k, v in files.items()}, "figures": figures,
           "versions": versions(), "machine": machine(), "timings": dict(timings or {})}
    write_json(out / f"{stem}.json", doc)
    if not last_run:
        result.update(files={k: str(v) for k, v in files.items()}, figures=figures)
        return result
    generic = f"simulate_{run.case}"
    gfiles, gfigures = {}, []
    for kind, path in files.items():
        gfiles[kind] = str(_copy(path, out / f"{generic}.{kind}"))
    for fig in figures:
        name = fig["file"][:-4].removesuffix(f"_{run.model}") + ".png"
        _copy(out / fig["file"], out / name)
        gfigures.append({**fig, "file": name})
    result.update(files=gfiles, figures=gfigures)
    write_json(out / f"{generic}.json", {**doc, "files": gfiles, "figures": gfigures})
    return result


def _copy(src: Path, dst: Path) -> Path:
    with atomic_path(dst) as tmp:
        shutil.copyfile(src, tmp)
    return dst


def _write_npz(path: Path, run: ModelRun) -> Path:
    arrays = {k: np.asarray(v) for k, v in run.data.items()}
    arrays["tip_x_frame"] = np.array(run.result["tip_x_frame"])
    arrays["model"] = np.array(run.model)
    arrays["case"] = np.array(run.case)
    desc = run.result.get("model_description") or {}
    if isinstance(desc, dict) and "coordinates" in desc:
        arrays["coordinates"] = np.array(desc["coordinates"])
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            np.savez_compressed(fh, **arrays)
    return path


def _write_csv(path: Path, run: ModelRun) -> Path:
    data = run.data
    cols = [c for c in CSV_COLUMNS if c in data]
    block = [np.asarray(data[c]) for c in cols]
    if "modal_coordinates" in data:
        mc = np.asarray(data["modal_coordinates"])
        cols += [f"eta{j + 1}" for j in range(mc.shape[1])]
        block += [mc[:, j] for j in range(mc.shape[1])]
    frame = run.result["tip_x_frame"].replace("_", " ")
    header = (f"# rotorpillar simulate {run.case}, {run.model} model; SI units (s, rad/s, m, m/s2); "
              f"tip_x and rotor_x {frame}; tip_x_relative relative to the ground, tip_x_absolute "
              "absolute; shaft_deflection_x = rotor X - tip X - e cos(theta)\n" + ",".join(cols))
    text = header + "\n" + "\n".join(",".join(f"{x:.10g}" for x in row) for row in np.column_stack(block))
    return write_text(path, text + "\n")


def charts(out: Path, scene, run: ModelRun, stem: str) -> list[dict]:
    """The model's charts: the earthquake's histories, the run-up's or run-down's
    speed and tip envelope, the sweep's curves."""
    from ..postprocess import transient_charts as tc
    data, case, name = run.data, run.case, run.model
    frame = run.result["tip_x_frame"].replace("_", " ")
    title = f"{scene.name}: {case}, {name} model"
    path = out / f"{stem}.png"
    if case == "earthquake":
        tc.earthquake_chart(path, data["t"], data["ground_acceleration"], data["tip_x"], data["rotor_x"],
                            data["Omega"], title, frame=frame)
        return [{"file": path.name, "caption": f"Earthquake on the {name} model: ground acceleration, "
                                                f"tip and rotor X ({frame}), rotor speed."}]
    resonances = [(f"omega_{r.index} ({r.direction})", r.omega) for r in run.resonances
                  if r.omega <= 1.2 * max(np.max(data["Omega"]), 1.0)]
    extra = []
    pt = run.result.get("passing_torque") or {}
    if pt.get("bracket_series"):
        bs = pt["bracket_series"]
        for row, W, pk, f in zip(pt["bracket_runs"], bs["Omega"], bs["tip_peak"], (0.95, 1.05)):
            extra.append((f"M0 = {row['torque_at_zero']:.0f} N*m ({f:g} x the predicted "
                          f"{pt['predicted']:.0f})", bs["t"], W, pk))
    tip_peak = data["peak"][:, -1] if data["peak"].ndim == 2 else np.abs(data["tip_x"])
    tc.runup_chart(path, data["t"], data["Omega"], tip_peak, resonances, title, extra,
                   label=f"M0 = {scene.drive.torque_at_zero:g} N*m (the scene's motor)"
                   if case == "runup" else "this run")
    caption = {"runup": "Run-up from rest: rotor speed and tip envelope" + (
                        " (dashed: motors 5 % below and above the torque the analysis says is "
                        "needed to pass)." if extra else "."),
               "rundown": "Run-down from the operating speed: rotor speed and tip envelope.",
               "sweep": "Quasi-static sweep of M0 up and down: rotor speed and tip envelope."}[case]
    figs = [{"file": path.name, "caption": caption}]
    if case == "sweep" and run.case_result is not None:
        ex = run.case_result.extra
        labels = [(f"{r.direction}{r.index}", r.omega, r.direction) for r in run.resonances]
        labels.sort(key=lambda L: -max((a["numeric_peak"] for a in ex["amplitudes"]
                                        if f"{a['direction']}{a['index']}" == L[0]), default=0.0))
        p2 = out / f"{stem}_az.png".replace(f"_{name}_az", f"_az_{name}")
        tc.sweep_chart(p2, ex["up"], ex["down"], ex["curves"], labels, ex["numeric_jumps"],
                       ex["predicted_jumps"], f"{scene.name}: quasi-static sweep against Eq. 19-23")
        figs.append({"file": p2.name, "caption": "Quasi-static sweep against the averaging theory: "
                                                 "stationary curve M0(Omega) with the jumps (left), "
                                                 "amplitude against z = Omega/omega_i (right)."})
    return figs
