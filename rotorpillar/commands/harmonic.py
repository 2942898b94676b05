"""`rotorpillar harmonic`: the unbalance response against speed and the separation margins.

``rotorpillar harmonic [SCENE] [--no-fem3d]`` writes harmonic.json
(rotorpillar.verdict.harmonic.HarmonicResult): the steady unbalance response
(amplitude and phase of the tip and of the shaft deflection) of the ROM and
of the 3D model on the [full_order] mesh, the averaging's Eq. 19 beside them,
and every running speed against every structural mode in the band (API 684),
the loaded tube's 3D modes read from modal.json when it is there.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

from . import progress


def add_arguments(p) -> None:
    p.add_argument("--no-fem3d", action="store_true", help="the ROM only: skip the 3D model's harmonic response")


def preflight(scene: Scene, args) -> None:
    """What `harmonic` refuses before any work (`run` calls it for its stage too): a 3D mesh
    this machine cannot hold, and a drive with no stable running speed."""
    from ..reduced.models import build_model
    from ..reduced.stationary import operating_speed
    from ..scene import with_values

    if not getattr(args, "no_fem3d", False):
        import importlib.util

        if importlib.util.find_spec("dolfinx") is not None:
            from .simulate import check_run

            check_run(scene, "runup", "fem3d")
    # the running speed on the beam's modes: within the beam's error of the chain's ROM
    model, _ = build_model(with_values(scene, {"modal_model.source": "beam"}), "modal", modes=1)
    d, L = scene.drive, scene.load
    operating_speed(model, d.torque_at_zero, d.slope, L.coefficient)


def harmonic_command(scene: Scene, args, timings):
    from ..verdict.harmonic import harmonic_analysis, summary_text
    from . import Done, out_dir

    preflight(scene, args)
    progress(f"harmonic {scene.name}: unbalance response and separation margins")
    with timings("harmonic"):
        result = harmonic_analysis(
            scene, out_dir(scene, args), progress, with_fem3d=not getattr(args, "no_fem3d", False)
        )
    return Done(result, summary_text(result))
