"""`rotorpillar simulate`: a transient case on one model.

``rotorpillar simulate [SCENE] --case runup|rundown|sweep|earthquake
[--model paper|modal|fem3d|beam] [--integrator NAME] [--modes K]`` (defaults
from the scene's [simulate]; fem3d runs earthquake and runup on the mesh and
over the duration of [full_order]).  rotorpillar.transients runs the model
and writes into ``out/<scene>/``:

- ``simulate_<case>_<model>.{json,npz,csv,png}``: the model's run; the NPZ/CSV
  series (at most ``simulate.samples`` rows): t, Omega, theta, tip_x (as
  before: absolute for paper, relative to the ground otherwise),
  tip_x_relative, tip_x_absolute, rotor_x, rotor_y, ground_x,
  ground_acceleration, shaft_deflection_x (rotor X - tip X - e cos theta), and
  for the modal model modal_coordinates, mode_heights, mode_shapes;
- ``simulate_<case>.{json,npz,csv,png}``: copies of the last run, and ``simulate.json``;
- ``simulate_sweep_az.png`` (and ``simulate_sweep_az_<model>.png``) for the sweep.

Every JSON has model, case, ok, warnings (also on stderr: the paper model's
earthquake when Eq. 4's published base forcing amplifies the ground by
more than 10 %), max_abs (tip_x_relative, tip_x_absolute, ...), omega_final,
captured_at, energy_balance, integrator, dofs, wall_seconds, and for fem3d
and beam full_order (mesh or elements, duration, time_step, note).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene
    from ..transients.model_run import Fem3dRun, ReducedRun

from ..scene import CASES, INTEGRATORS, MODELS
from . import EXIT_CHECKS, Done


def add_arguments(p) -> None:
    p.add_argument("--case", choices=CASES, default=None, help="which transient (default: the scene's simulate.case)")
    p.add_argument(
        "--model",
        choices=MODELS,
        default=None,
        help="paper: Eq. 4 as published; modal: the pillar by its modes (the ROM); "
        "fem3d: the 3D tube at full order (earthquake, runup; mesh and duration from "
        "[full_order]); beam: the 1D Timoshenko beam at full order "
        "(default: the scene's simulate.model)",
    )
    p.add_argument(
        "--integrator",
        default=None,
        choices=INTEGRATORS,
        help="time integrator (default: the scene's simulate.integrator)",
    )
    p.add_argument(
        "--modes",
        type=int,
        default=None,
        metavar="K",
        help="modal model: keep K pillar modes (default: the scene's modal_model.modes, 0 = from the frequency band)",
    )
    p.add_argument(
        "--no-threshold",
        dest="overrides",
        action="append_const",
        const="simulate.threshold=false",
        help="run-up: skip the batch that finds the torque needed to pass the resonance "
        "(the scene's simulate.threshold = false)",
    )


def check_run(
    scene: Scene,
    case: str,
    which: str,
    integrator: str | None = None,
    modes: int | None = None,
    motion=None,
    duration: float | None = None,
) -> None:
    """Refuse (InputError) a run of one model that its own code would refuse, before any
    work: the 3D model's mesh memory and step budget (fem3d.full_order_plan, before
    meshing), the beam full order's step budget (transients.cases.check_full_order_budget),
    or a reduced model's step budget (transients.cases.check_case: the case's model built
    and its start found as run_case finds them, simulate's own checks; nothing integrated).  A modal model whose modes would come from the 3D model
    is estimated on the 1D beam's modes (the estimate's inputs from the modes, the
    operating speed and the fastest mode in the band, agree within the beam's error; the
    run checks again on its own modes)."""
    from ..reduced.excitation import no_motion
    from ..scene import with_values
    from ..transients.cases import check_case, check_full_order_budget
    from ..transients.run_plan import fem3d_plan, own_duration, with_duration

    if which == "fem3d":
        from ..mesh import tube_params

        tube_params(scene.pillar, fem3d_plan(scene, case, motion, duration).mesh)  # its memory
        check_fem3d_budget(scene, case, motion, duration)
        return
    if duration is not None:
        scene = with_duration(scene, case, duration)  # as run_model shortens a run
    if case == "earthquake":
        own_duration(scene, case, motion)  # a run that ends before the ground moves: refused
    if which == "beam":
        check_full_order_budget(scene, case, motion or no_motion(), integrator)
        return
    if which == "modal" and scene.modal_model.source != "beam":
        scene = with_values(scene, {"modal_model.source": "beam"})
    check_case(scene, case, which, integrator, modes, motion)


def preflight(scene: Scene, args):
    """What `simulate` refuses before any work (`run` calls it for its stages too): its
    flags, MPI, the record, and the run's plan or step budget (``check_run``: before the
    chain's pillar modes, which may take a 3D solve).  Returns the ground motion of an
    earthquake (read once), else None."""
    from ..errors import InputError
    from ..reduced.models import scene_motion
    from . import launched_ranks

    case = getattr(args, "case", None) or scene.simulate.case
    which = getattr(args, "model", None) or scene.simulate.model
    modes = getattr(args, "modes", None)
    if modes is not None and modes < 1:
        raise InputError(f"--modes {modes}: must be >= 1")
    if launched_ranks() > 1 and which != "fem3d":
        raise InputError(
            f"simulate --model {which} runs on one process (under mpirun only the 3D "
            "full order, --model fem3d, shares its work): start it without mpirun"
        )
    motion = scene_motion(scene) if case == "earthquake" else None
    check_run(scene, case, which, getattr(args, "integrator", None), modes, motion)
    return motion


def simulate_command(scene: Scene, args, timings):
    from . import is_root_rank, mpi_progress, out_dir

    motion = preflight(scene, args)  # bad input: before any work
    from ..postprocess.transient_charts import model_run_charts
    from ..transients.files import write_model_files
    from ..transients.model_run import run_model

    case = getattr(args, "case", None) or scene.simulate.case
    which = getattr(args, "model", None) or scene.simulate.model
    modes = getattr(args, "modes", None)
    progress = mpi_progress()
    progress(f"simulate {scene.name}: {case}, {which} model")
    chain = None
    if which in ("modal", "fem3d"):
        from ..chain import resolve

        with timings("pillar_modes"):
            chain = resolve(scene, out_dir(scene, args), motion=motion, progress=progress)
    with timings(case):
        run = run_model(
            scene,
            case,
            which,
            getattr(args, "integrator", None),
            modes,
            progress=progress,
            motion=motion,
            chain=chain,
            field_dir=out_dir(scene, args),
            study_dir=out_dir(scene, args),
        )
    record = run.record
    for warning in record.warnings:
        progress(f"warning: {warning}")
    if is_root_rank():
        with timings("write"):
            provenance = {"scene_source": str(args.scene), "overrides": list(args.overrides)}
            record = write_model_files(
                out_dir(scene, args), scene, run, provenance, dict(timings), charts=model_run_charts
            )
    status = 0
    if not record.ok:  # written, and marked: the exit code says so too
        status = EXIT_CHECKS
        for line in record.failed_checks or ():
            progress(f"simulate: check failed: {line}")
    return Done(record, _summary(scene, record), status)


def check_fem3d_budget(scene: Scene, case: str, motion, duration: float | None = None) -> None:
    """Refuse, before any meshing, a 3D run above ``simulate.max_steps`` (InputError
    naming the keys; fem3d.full_order_plan), on the plan's mesh, duration and step."""
    from ..fem3d.full_order_plan import case_setup, check_budget, estimate, step_rule
    from ..transients.run_plan import fem3d_plan

    plan = fem3d_plan(scene, case, motion, duration)
    # the start speed 0: the step follows the drive's free speed, which the operating
    # speed never passes, so the rule's step is the run's without solving for it
    motion, drive, length, _, _ = case_setup(scene, case, motion, None, plan.duration, 0.0)
    check_budget(scene, case, estimate(scene, length, step_rule(scene, drive, motion, 0.0, plan.time_step), plan.mesh))


def _summary(scene: Scene, r: ReducedRun | Fem3dRun) -> str:
    from ..transients.model_run import ReducedRun

    lines = [
        f"rotorpillar simulate {scene.name}: case {r.case}, {r.model} model "
        f"({r.tip_x_frame.replace('_', ' ')} coordinates)"
    ]
    it = r.integrator
    lines.append(
        f"  integrator {it.method}: {it.status}, {it.steps} steps, "
        + (f"{it.nfev} force evaluations, " if it.nfev else "")
        + f"{it.wall_seconds:.3f} s; {r.dofs} dofs, {r.wall_seconds:.3f} s in all"
    )
    if r.full_order is not None:
        lines.append(f"  full order: {r.full_order.note}")
    if isinstance(r, ReducedRun) and r.planes is not None and "spatial" in (r.planes.planes, r.planes.requested):
        lines.append(f"  planes: {r.planes.planes} ({r.planes.reason})")
    for w in r.warnings:
        lines.append(f"  WARNING: {w}")
    lines.append(
        f"  final speed {r.omega_final:.4f} rad/s; captured at "
        + (f"{r.captured_at:.3f} rad/s" if r.captured_at else "no resonance")
    )
    ma = r.max_abs
    lines.append(
        f"  max |tip X| {_g(ma.get('tip_x_relative'))} m relative to the ground, "
        f"{_g(ma.get('tip_x_absolute'))} m absolute; |rotor X| {_g(ma.get('rotor_x'))} m, "
        f"|rotor Y| {_g(ma.get('rotor_y'))} m"
    )
    if ma.get("base_moment") is not None:
        lines.append(
            f"  base: |M| {_g(ma.get('base_moment'))} N m, |V| {_g(ma.get('base_shear'))} N, stress "
            f"{_g((ma.get('base_stress') or 0.0) / 1e6)} MPa (|M| c/I + N/A)"
            + (f"; von Mises {_g((ma.get('von_mises') or 0.0) / 1e6)} MPa" if ma.get("von_mises") else "")
            + f"; shaft {_g(ma.get('shaft_deflection'))} m, bearing force {_g(ma.get('bearing_force'))} N"
        )
    lines.append(f"  energy balance: relative error {r.energy_balance.relative_error:.2e}")
    if not isinstance(r, ReducedRun):
        return "\n".join(lines)
    from ..transients.case_summary import NoTruncationEstimate  # here: it brings the integrators (numba)

    t = r.truncation
    if isinstance(t, NoTruncationEstimate):
        lines.append("  " + t.statement)
    elif t is not None:
        lines.append(
            f"  modes: {t.modes} (effective mass {100 * t.effective_mass_fraction:.1f} %); "
            f"with {t.modes_check}: tip max changes {100 * (t.tip_x_max_rel_diff or 0):+.3f} %, "
            f"tip series {100 * t.tip_series_max_rel_diff:.3f} %"
        )
    if r.passing_torque is not None:
        lines.append("  " + r.passing_torque.statement)
    if r.case == "sweep" and r.sweep is not None:
        if r.jumps:
            for j in r.jumps:
                lines.append(
                    f"  jump {j.direction}: {j.omega_from:.3f} -> {j.omega_to:.3f} rad/s "
                    f"at M0 = {j.torque_at_zero:.1f} N*m"
                )
            rows = r.sweep.rate_convergence.rows if r.sweep.rate_convergence is not None else ()
            for row in rows:
                lim = row.torque_at_zero_limit
                if lim is not None and row.predicted_torque_at_zero:
                    lines.append(
                        f"    {row.direction}: M0 at rates {', '.join(f'{x:g}' for x in row.rates)} "
                        f"N*m/s -> {', '.join(f'{x:.1f}' for x in row.torque_at_zero if x)}; "
                        f"limit {lim:.1f} vs Eq. 19-23 {row.predicted_torque_at_zero:.1f} "
                        f"({100 * (row.rel_error_limit_vs_predicted or 0.0):+.2f} %)"
                    )
        else:
            lines.append("  " + (r.sweep.no_jump_reason or "no jumps"))
        for a in r.sweep.amplitudes:
            lines.append(
                f"  amplitude near omega_{a.index} ({a.sweep}): numeric peak "
                f"{a.numeric_peak:.4g} m; Eq. 19 median error {100 * a.rel_error_eq19_median:.1f} %, "
                f"exact linear {100 * a.rel_error_exact_median:.2f} %"
            )
    if r.case == "earthquake" and r.excitation is not None:
        statement = getattr(r.excitation, "statement", None)
        if statement:
            lines.append("  " + statement)
        lines.append(f"  ground motion applied: {r.excitation_in_model or ''}")
    return "\n".join(lines)


def _g(x: float | None) -> str:
    """A number of a run's ``max_abs`` (None: not finite, or not computed)."""
    return "-" if x is None else f"{x:.4g}"
