"""`rotorpillar integrators`: error against cost of every time integrator, and
where each fails (rotorpillar.transients.integrator_study).  Writes
``integrators.json`` (the tables) and ``integrators.png``."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene
    from ..transients.integrator_study import IntegratorStudy

import math

from ..records import Figure, replace
from . import Done, progress

#: Longest run-up the integrator study takes (s): about 5 minutes of work on 2 cores.
MAX_DURATION = 60.0


def add_arguments(p) -> None:
    p.add_argument(
        "--duration",
        type=float,
        default=10.0,
        metavar="SECONDS",
        help="length of the run-up the accuracy study integrates (default 10 s)",
    )
    p.add_argument("--quick", action="store_true", help="fewer tolerances, steps and modes (for a first look)")


def preflight(scene: Scene, args) -> None:
    """What `integrators` refuses before any work (`run` calls it for its stage too)."""
    from ..errors import InputError

    duration = getattr(args, "duration", 10.0)
    # every integrator at every step size: ~2-6 s of computing per simulated second
    if not (math.isfinite(duration) and 0 < duration <= MAX_DURATION):
        raise InputError(
            f"--duration {duration!r}: must be > 0 and <= {MAX_DURATION:g} (s): the "
            f"study costs about 2-6 s per simulated second on 2 cores"
        )


def integrators_command(scene: Scene, args, timings) -> Done:
    from ..chain import resolve
    from ..reduced.models import beam_candidates
    from ..transients.integrator_study import run_integrator_study
    from . import is_root_rank, out_dir

    preflight(scene, args)
    duration = getattr(args, "duration", 10.0)
    with timings("pillar_modes"):
        chain = resolve(scene, out_dir(scene, args), progress=progress)
    with timings("study"):
        result = run_integrator_study(
            scene,
            duration,
            quick=getattr(args, "quick", False),
            progress=progress,
            pillar_modes=chain.modes,
            probe_modes=beam_candidates(scene),
            cache_dir=out_dir(scene, args) / "cache",
        )
    probe = (
        "the stiffness study adds up to 8 pillar modes of the scene's 1D "
        f"{scene.modal_model.theory} beam ({scene.modal_model.elements} "
        "elements): a probe of how each integrator copes with stiffness, "
        "not the scene's model"
    )
    figures = []
    if is_root_rank():
        from ..postprocess.transient_charts import integrators_chart

        path = out_dir(scene, args) / "integrators.png"
        with timings("chart"):
            integrators_chart(
                path,
                result.accuracy.rows,
                result.stability.rows,
                result.energy_drift.rows,
                f"{scene.name}: time integrators (run-up {duration:g} s, the ROM; stiffness: the beam's modes added)",
            )
        figures.append(
            Figure(
                file=path.name,
                caption="Time integrators: error against wall time on a "
                "run-up (left), cost and failure as pillar modes are added (middle), energy "
                "drift of the undamped, unforced system (right).",
            )
        )
    result = replace(result, pillar_model=chain.pillar_model, stiffness_probe=probe, figures=tuple(figures))
    return Done(result, _summary(scene, result))


def _summary(scene: Scene, r: IntegratorStudy) -> str:
    acc = r.accuracy
    lines = [
        f"rotorpillar integrators {scene.name}: run-up of {acc.duration:g} s, reference dp5 "
        f"rtol 1e-12 (DOP853 1e-12 agrees to {acc.reference.agreement_with_dop853:.1e})",
        f"  {'method':<20} {'s to 1e-3':>10} {'s to 1e-6':>10} {'nfev 1e-6':>10}  fails",
    ]

    def fmt(x: float | None, f: str) -> str:
        return "-" if x is None else format(x, f)

    for m, e in acc.per_method.items():
        lines.append(
            f"  {m:<20} {fmt(e.wall_seconds_at_1e_3, '10.4f')} "
            f"{fmt(e.wall_seconds_at_1e_6, '10.4f')} {fmt(e.nfev_at_1e_6, '10.0f')}  {e.fails}"
        )
    lines.append("  stiffness (modal model, pillar modes added): first failure per method")
    growth = r.stability.cost_growth
    for m, f in r.stability.first_failure.items():
        g = growth.get(m)
        cost = f"; force evaluations x{g.factor:.1f} from {g.modes[0]} to {g.modes[1]} modes" if g else ""
        lines.append(
            f"    {m:<20} "
            + (
                "never"
                if f is None
                else f"{f.modes} modes, omega_max {f.omega_max:.0f} rad/s, h*omega_max = {f.h_times_omega_max:.2f}"
            )
            + cost
        )
    lines.append(
        "  energy drift (undamped, unforced): "
        + ", ".join(
            f"{row.method} {row.drift:.1e}" if row.drift is not None else f"{row.method} failed"
            for row in r.energy_drift.rows
        )
    )
    return "\n".join(lines)
