"""`rotorpillar simulate`: a transient case of the reduced models.

``rotorpillar simulate [SCENE] --case runup|rundown|sweep|earthquake
[--model paper|modal] [--integrator NAME] [--modes K]`` (defaults from the
scene's [simulate]).  Writes into ``out/<scene>/``:

- ``simulate_<case>.npz`` and ``.csv``: the time series (at most
  ``simulate.samples`` rows): t, Omega, theta, tip_x, rotor_x, rotor_y,
  ground_x, ground_acceleration, M0, and for the modal model
  modal_coordinates (n_t x k, the tip displacement of each pillar mode, m),
  tip_x_absolute, rotor_x_absolute, mode_heights, mode_shapes;
  ``tip_x_frame`` says whether tip_x is absolute (paper) or relative to the
  ground (modal);
- ``simulate.json`` (the case just run) and its copy ``simulate_<case>.json``;
- ``simulate_<case>.png`` (and ``simulate_sweep_az.png`` for the sweep).
"""

from __future__ import annotations

import numpy as np

from . import progress
from ..scene import CASES, MODELS
from ..provenance import atomic_path, machine, versions, write_json, write_text

NPZ_SCALARS = ("tip_x_frame", "model", "case")
CSV_COLUMNS = ("t", "Omega", "tip_x", "rotor_x", "rotor_y", "ground_x", "ground_acceleration")


def add_arguments(p) -> None:
    p.add_argument("--case", choices=CASES, default=None,
                   help="which transient (default: the scene's simulate.case)")
    p.add_argument("--model", choices=MODELS, default=None,
                   help="the paper's Eq. 4 as published, or the pillar by its modes "
                        "(default: the scene's simulate.model)")
    p.add_argument("--integrator", default=None,
                   choices=("dp5", "RK45", "DOP853", "Radau", "BDF", "LSODA", "newmark", "hht",
                            "generalized_alpha", "central_difference"),
                   help="time integrator (default: the scene's simulate.integrator)")
    p.add_argument("--modes", type=int, default=None, metavar="K",
                   help="modal model: keep K pillar modes (default: the scene's modal_model.modes, "
                        "0 = from the frequency band)")


def simulate_command(scene, args, timings):
    from . import is_root_rank, out_dir
    from ..errors import InputError
    from ..reduced.cases import run_case
    from ..reduced.models import scene_motion
    from ..reduced.summaries import series
    case = getattr(args, "case", None) or scene.simulate.case
    which = getattr(args, "model", None) or scene.simulate.model
    modes = getattr(args, "modes", None)
    if modes is not None and modes < 1:
        raise InputError(f"--modes {modes}: must be >= 1")
    motion = scene_motion(scene) if case == "earthquake" else None    # bad input: refused before any output
    progress(f"simulate {scene.name}: {case}, {which} model")
    with timings(case):
        res = run_case(scene, case, which, getattr(args, "integrator", None), modes, progress=progress,
                       motion=motion, pillar_modes=pillar_modes_for(scene, which))
    data = series(res.run, scene.simulate.samples)
    out = out_dir(scene, args)
    result = {"case": case, "model": which, **res.summary.to_json(),
              "model_description": res.model.describe(), "model_info": res.extra.get("model_info"),
              "resonances": [vars(r) for r in res.model.quasi_normal()],
              "damped_frequencies": res.model.damped_frequencies(),
              "tip_x_frame": res.model.frame}
    for key in ("initial_speed", "excitation_in_model"):
        if key in res.extra:
            result[key] = res.extra[key]
    files, figures = {}, []
    if is_root_rank():
        with timings("write"):
            files["npz"] = str(_write_npz(out / f"simulate_{case}.npz", data, res))
            files["csv"] = str(_write_csv(out / f"simulate_{case}.csv", data, res))
        with timings("charts"):
            figures = _charts(out, scene, case, res, data)
    result["files"] = files
    result["figures"] = figures
    if is_root_rank():
        copy_doc = {"command": "simulate", "scene_source": str(args.scene),
                    "overrides": list(args.overrides), "scene": scene.to_dict(), **result,
                    "versions": versions(), "machine": machine(), "timings": dict(timings)}
        write_json(out / f"simulate_{case}.json", copy_doc)
    return result, summary(scene, result)


def pillar_modes_for(scene, which: str):
    """The 3D model's candidate pillar modes when the modal model takes its
    modes from it (``modal_model.source = "fem3d"``), else None (the reduced
    package computes the beam's itself)."""
    if which != "modal" or scene.modal_model.source != "fem3d":
        return None
    from ..fem3d.pillar_modes import candidate_pillar_modes
    return candidate_pillar_modes(scene)


def _write_npz(path, data, res):
    arrays = {k: np.asarray(v) for k, v in data.items()}
    arrays["tip_x_frame"] = np.array(res.model.frame)
    arrays["model"] = np.array(res.model.name)
    arrays["case"] = np.array(res.case)
    arrays["coordinates"] = np.array(res.model.names)
    with atomic_path(path) as tmp:
        np.savez_compressed(tmp, **arrays)
    return path


def _write_csv(path, data, res):
    cols = list(CSV_COLUMNS)
    block = [np.asarray(data[c]) for c in cols]
    if "modal_coordinates" in data:
        mc = np.asarray(data["modal_coordinates"])
        cols += [f"eta{j + 1}" for j in range(mc.shape[1])]
        block += [mc[:, j] for j in range(mc.shape[1])]
    header = (f"# rotorpillar simulate {res.case}, {res.model.name} model; SI units (s, rad/s, m, "
              f"m/s2); tip_x and rotor_x {res.model.frame.replace('_', ' ')}\n" + ",".join(cols))
    text = header + "\n" + "\n".join(",".join(f"{x:.10g}" for x in row) for row in np.column_stack(block))
    return write_text(path, text + "\n")


def _charts(out, scene, case, res, data) -> list[dict]:
    from ..postprocess import transient_charts as tc
    m = res.model
    resonances = [(f"omega_{r.index} ({r.direction})", r.omega) for r in m.quasi_normal()
                  if r.omega <= 1.2 * max(np.max(data["Omega"]), 1.0)]
    title = f"{scene.name}: {case}, {m.name} model"
    figs = []
    path = out / f"simulate_{case}.png"
    if case == "earthquake":
        tc.earthquake_chart(path, data["t"], data["ground_acceleration"], data["tip_x"], data["rotor_x"],
                            data["Omega"], title, frame=m.frame.replace("_", " "))
        caption = (f"Earthquake on the {m.name} model: ground acceleration, tip and rotor X "
                   f"({m.frame.replace('_', ' ')}), rotor speed.")
    else:
        extra = []
        pt = res.summary.passing_torque or {}
        if pt.get("bracket_series"):
            bs = pt["bracket_series"]
            for row, W, pk, f in zip(pt["bracket_runs"], bs["Omega"], bs["tip_peak"], (0.95, 1.05)):
                extra.append((f"M0 = {row['torque_at_zero']:.0f} N*m ({f:g} x the predicted "
                               f"{pt['predicted']:.0f})", bs["t"], W, pk))
        tc.runup_chart(path, data["t"], data["Omega"], data["peak"][:, -1], resonances, title, extra,
                       label=f"M0 = {scene.drive.torque_at_zero:g} N*m (the scene's motor)"
                       if case == "runup" else "this run")
        caption = {"runup": "Run-up from rest: rotor speed and tip envelope" + (
                            " (dashed: motors 5 % below and above the torque the analysis says is "
                            "needed to pass)." if extra else "."),
                   "rundown": "Run-down from the operating speed: rotor speed and tip envelope.",
                   "sweep": "Quasi-static sweep of M0 up and down: rotor speed and tip envelope."}[case]
    figs.append({"file": path.name, "caption": caption})
    if case == "sweep":
        ex = res.extra
        labels = [(f"{r.direction}{r.index}", r.omega, r.direction) for r in m.quasi_normal()]
        # the resonance with the largest numeric amplitude first
        labels.sort(key=lambda L: -max((a["numeric_peak"] for a in ex["amplitudes"]
                                        if f"{a['direction']}{a['index']}" == L[0]), default=0.0))
        p2 = out / "simulate_sweep_az.png"
        tc.sweep_chart(p2, ex["up"], ex["down"], ex["curves"], labels, ex["numeric_jumps"],
                       ex["predicted_jumps"], f"{scene.name}: quasi-static sweep against Eq. 19-23")
        figs.append({"file": p2.name, "caption": "Quasi-static sweep against the averaging theory: "
                                                 "stationary curve M0(Omega) with the jumps (left), "
                                                 "amplitude against z = Omega/omega_i (right)."})
    return figs


def summary(scene, r: dict) -> str:
    lines = [f"rotorpillar simulate {scene.name}: case {r['case']}, {r['model']} model "
             f"({r['tip_x_frame'].replace('_', ' ')} coordinates)"]
    it = r["integrator"]
    lines.append(f"  integrator {it['method']}: {it['status']}, {it.get('steps')} steps, "
                 f"{it['nfev']} force evaluations, {it['wall_seconds']:.3f} s")
    lines.append(f"  final speed {r['omega_final']:.4f} rad/s; captured at "
                 + (f"{r['captured_at']:.3f} rad/s" if r["captured_at"] else "no resonance"))
    ma = r["max_abs"]
    lines.append(f"  max |tip X| {ma['tip_x']:.4g} m, |rotor X| {ma['rotor_x']:.4g} m, "
                 f"|rotor Y| {ma['rotor_y']:.4g} m")
    eb = r["energy_balance"]
    lines.append(f"  energy balance: relative error {eb['relative_error']:.2e}")
    if r.get("truncation") and r["truncation"].get("modes_check") is None:
        lines.append("  " + r["truncation"]["statement"])
    elif r.get("truncation"):
        t = r["truncation"]
        lines.append(f"  modes: {t['modes']} (effective mass {100 * t['effective_mass_fraction']:.1f} %); "
                     f"with {t['modes_check']}: tip max changes {100 * (t['tip_x_max_rel_diff'] or 0):+.3f} %, "
                     f"tip series {100 * t['tip_series_max_rel_diff']:.3f} %")
    pt = r.get("passing_torque")
    if pt and pt.get("statement"):
        lines.append("  " + pt["statement"])
    if r["case"] == "sweep":
        if r["jumps"]:
            for j in r["jumps"]:
                lines.append(f"  jump {j['direction']}: {j['omega_from']:.3f} -> {j['omega_to']:.3f} rad/s "
                             f"at M0 = {j['torque_at_zero']:.1f} N*m")
            for row in (r.get("rate_convergence") or {}).get("rows", []):
                lim = row.get("torque_at_zero_limit")
                if lim is not None and row.get("predicted_torque_at_zero"):
                    lines.append(f"    {row['direction']}: M0 at rates {', '.join(f'{x:g}' for x in row['rates'])} "
                                 f"N*m/s -> {', '.join(f'{x:.1f}' for x in row['torque_at_zero'] if x)}; "
                                 f"limit {lim:.1f} vs Eq. 19-23 {row['predicted_torque_at_zero']:.1f} "
                                 f"({100 * row['rel_error_limit_vs_predicted']:+.2f} %)")
        else:
            lines.append("  " + (r.get("no_jump_reason") or "no jumps"))
        for a in r.get("amplitudes") or []:
            lines.append(f"  amplitude near omega_{a['index']} ({a['sweep']}): numeric peak "
                         f"{a['numeric_peak']:.4g} m; Eq. 19 median error {100 * a['rel_error_eq19_median']:.1f} %, "
                         f"exact linear {100 * a['rel_error_exact_median']:.2f} %")
    if r["case"] == "earthquake":
        ex = r["excitation"]
        if ex.get("statement"):
            lines.append("  " + ex["statement"])
        lines.append(f"  ground motion applied: {r.get('excitation_in_model', '')}")
    return "\n".join(lines)
