"""The ROM's pillar modes for a design study: the chain's, solved once in the study's process.

A study on the modal model (the ROM) runs on the chain's pillar modes
(rotorpillar.chain), as `simulate` does.  The workers never solve them: the
study resolves them here, once per distinct pillar (a study that varies the
tube, the gondola or the mesh needs one set per value; every other axis
shares one), and ships them in each batch's spec as plain arrays, so a batch's
cache key holds the modes it ran on.
"""

from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

from ..chain.record import PillarModel
from ..records import replace
from ..reduced.pillar_modes import PillarModes
from ..scene import Scene

#: Scene keys that change the pillar's modes (every other key leaves them alone).
MODE_KEYS = (
    "pillar.height",
    "pillar.outer_diameter",
    "pillar.inner_diameter",
    "pillar.cans",
    "pillar.youngs_modulus",
    "pillar.poisson_ratio",
    "pillar.density",
    "gondola.mass",
    "modal.top_model",
    "modal.top_mass",
    "modal.tolerance",
    "modal_model.source",
    "modal_model.theory",
    "modal_model.elements",
    "modal_model.gondola_inertia",
)


def affects_modes(key: str) -> bool:
    return (
        key in MODE_KEYS
        or key.startswith("mesh.")
        or (key.startswith("foundation.") and key != "foundation.rotation_limit")
    )


def mode_params(base: Scene, scene: Scene) -> dict:
    """The keys that change the pillar's modes where ``scene`` differs from ``base``."""
    out = {}
    for key in MODE_KEYS:
        section, name = key.split(".")
        value = getattr(getattr(scene, section), name)
        if getattr(getattr(base, section), name) != value:
            out[key] = [asdict(c) for c in value] if key == "pillar.cans" else value
    for section in ("mesh", "foundation"):
        for name, value in vars(getattr(scene, section)).items():
            if getattr(getattr(base, section), name) != value and f"{section}.{name}" != "foundation.rotation_limit":
                out[f"{section}.{name}"] = value
    return out


def mode_key(base: Scene, scene: Scene) -> str:
    """``mode_params`` as a stable string: the key of a pillar's modes in a study."""
    return json.dumps(sorted(mode_params(base, scene).items()))


class StudyModes:
    """The pillar modes of a study's scenes, each pillar resolved once (rotorpillar.chain)."""

    def __init__(self, base: Scene, out_dir: Path | None, log=None):
        self.base, self.out_dir, self.log = base, out_dir, log
        self.table: dict[str, PillarModes] = {}
        self.pillar_model: PillarModel | None = None

    def key(self, scene: Scene) -> str:
        return mode_key(self.base, scene)

    def __call__(self, scene: Scene) -> PillarModes:
        """The ROM's candidate modes for ``scene`` (solved once per distinct pillar)."""
        from ..chain import resolve

        key = self.key(scene)
        if key not in self.table:
            varied = key != "[]"
            # the base pillar may use the study on disk; a varied pillar has none of its own
            chain = resolve(scene, None if varied else self.out_dir, progress=self.log)
            self.table[key] = chain.modes
            if not varied or self.pillar_model is None:
                pm = chain.pillar_model
                if varied:
                    pm = replace(
                        pm,
                        note="the pillar varies across the study: each value's own model (the scene's [mesh]); "
                        + pm.note,
                    )
                self.pillar_model = pm
        return self.table[key]
