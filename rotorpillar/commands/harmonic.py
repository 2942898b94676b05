"""`rotorpillar harmonic`: the unbalance response against speed and the separation margins.

``rotorpillar harmonic [SCENE] [--no-fem3d]`` writes harmonic.json
(rotorpillar.verdict.records.HarmonicResult): the steady unbalance response
(amplitude and phase of the tip and of the shaft deflection) of the ROM and
of the 3D model on the [full_order] mesh, the averaging's Eq. 19 beside them,
and every running speed against every structural mode in the band (API 684),
the loaded tube's 3D modes read from modal.json when it is there.
"""

from __future__ import annotations

from . import progress


def add_arguments(p) -> None:
    p.add_argument("--no-fem3d", action="store_true",
                   help="the ROM only: skip the 3D model's harmonic response")


def harmonic_command(scene, args, timings):
    from . import out_dir
    from ..verdict.harmonic import harmonic_analysis, summary_text
    progress(f"harmonic {scene.name}: unbalance response and separation margins")
    with timings("harmonic"):
        result = harmonic_analysis(scene, out_dir(scene, args), progress,
                                   with_fem3d=not getattr(args, "no_fem3d", False))
    return result.to_json(), summary_text(result)
