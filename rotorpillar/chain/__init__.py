"""One chain of models: the pillar model the convergence study chose feeds every stage.

``modal_model.source = "auto"`` (the default): `converge` chooses the
cheapest pillar model whose frequencies in the scene's band meet the
tolerance; `modal` runs the 3D tube on that mesh; the reduced-order model
(ROM) of `analyze`, `simulate`, `compare`, `study` and the report takes its
pillar modes from it (the SLEPc modes of that mesh with the gondola on top,
or the beam's), and every JSON names it as ``pillar_model``.  Without a study
on disk the stages use the scene's own [mesh] and say so.

- :mod:`.record`: ``PillarModel`` (the JSON block), ``Uncertain`` (a number with
  its error bar);
- :mod:`.choice`: which model (``choose``);
- :mod:`.modes`: the ROM's candidate modes from it, cached (``chain_modes``);
- :func:`resolve`: both at once, for a stage.

Layers: this package sits above converge/, fem3d/ (imported lazily) and
reduced/, below analysis/, transients/ and commands/.
"""

from __future__ import annotations

from pathlib import Path

from ..scene import Scene
from .choice import Choice, choose, solid_mesh_section, study_on_disk
from .modes import ChainModes, TipReductionOf, chain_modes, rom_band_top
from .record import PillarModel, Uncertain

__all__ = [
    "ChainModes",
    "Choice",
    "PillarModel",
    "TipReductionOf",
    "Uncertain",
    "chain_modes",
    "choose",
    "resolve",
    "rom_band_top",
    "solid_mesh_section",
    "study_on_disk",
]


def resolve(
    scene: Scene, out_dir: Path | None, *, motion=None, comm=None, progress=None, cache_dir: Path | None = None
) -> ChainModes:
    """The chain's pillar model for ``scene`` and the ROM's candidate modes from it.

    ``motion``: the ground motion the stage runs (its band widens the ROM's);
    ``out_dir``: where the scene's results (and its convergence.json) are; None: no
    study, the scene's own model.
    """
    choice = choose(scene, None if out_dir is None else Path(out_dir), cache_dir)
    return chain_modes(scene, choice, rom_band_top(scene, motion), comm=comm, progress=progress)
