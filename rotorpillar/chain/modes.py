"""The ROM's pillar modes from the chain's pillar model, computed once and cached on disk.

For a 3D choice: the SLEPc modes of that mesh with the gondola on the rigid
top (every X bending mode among them, enough to pass the ROM's band and one
more, for its truncation check), and the paper's Eq. 2 on the bare tube's
first bending mode of the same mesh; from the same solve, every mode in
every direction as the spatial model's SpatialPillarModes (``spatial``:
bending both ways, torsion, axial, ovalling, each with the top plate's six
components, rotorpillar.fem3d.spatial_modes).  For a beam: the beam's modes and its
Eq. 2.  A 3D result is cached as one JSON file under the user's cache
(``$ROTORPILLAR_CACHE``, else ``~/.cache/rotorpillar``), keyed by a hash of the
tube, the gondola, the top model, the mesh, the eigen-solver's tolerance and
the source of the code that computes it: every stage, test or study that needs
the same modes on this machine solves them once.
"""

from __future__ import annotations

import contextlib
import math
import time
from dataclasses import dataclass
from pathlib import Path

import msgspec
import numpy as np

from ..cache import DiskCache, cache_key, source_hash, user_cache_root
from ..records import Record
from ..reduced.pillar_modes import PillarModes
from ..reduced.spatial_modes import SpatialPillarModes
from ..scene import Scene
from ..scene.tower import foundation_key, pillar_key
from .choice import Choice, solid_mesh_section
from .record import MeshValue, PillarModel

#: 2: an Entry of a ModesEntry record (msgspec); 3: with the spatial modes; 4: keyed
#: without the damping ratio (set on the modes as they are read)
CACHE_VERSION = 4
#: the most X bending modes the ROM picks from
MAX_CANDIDATES = 12
#: modes first asked of the loaded tube (doubled until enough X bending modes are found)
FIRST_SOLVE = 32


class TipReductionOf(Record):
    """Eq. 2 on the chain model's bare first bending mode."""

    m_reduced: float
    """m_r: the first mode's mass referred to the tip, unit tip deflection (kg)"""
    tip_stiffness: float
    """c1 = m_r omega**2 (N/m)"""
    omega_bending: float
    """the bare tube's first bending frequency on this model (rad/s)"""
    source: str
    """the model it was computed on"""


class ModesEntry(Record, eq=False):
    """A 3D result as the modes cache stores it."""

    label: str
    """the pillar model's label"""
    mesh: dict[str, MeshValue]
    """its discretisation"""
    modes: PillarModes
    reduction: TipReductionOf
    seconds: float
    """time the solve took (s)"""
    loaded_modes: int
    """modes of the loaded tube the 3D solve asked for (-)"""
    spatial: SpatialPillarModes
    """every mode of the loaded tube in every direction (the spatial model's)"""


@dataclass(frozen=True, eq=False)
class ChainModes:
    """The chain's pillar model and the ROM's candidate modes from it."""

    pillar_model: PillarModel
    modes: PillarModes
    """the X bending modes of the pillar with the gondola on top, ascending, tip-scaled"""
    reduction: TipReductionOf
    cache_file: str | None = None
    """where a 3D result was cached (None for a beam)"""
    seconds: float = 0.0
    """time spent computing (0 when read from the cache) (s)"""
    loaded_modes: int = 0
    """how many modes of the loaded tube the 3D solve asked for (0: not a 3D source), so
    that `modal` reuses that very solve"""
    spatial: SpatialPillarModes | None = None
    """every mode of the loaded tube in every direction from the same 3D solve (None for a
    beam: the spatial model takes its beam modes itself)"""

    def count_below(self, band_top: float) -> int:
        """How many candidate modes lie at or below ``band_top`` (rad/s), at least one."""
        return max(1, int(np.sum(np.asarray(self.modes.omega) <= band_top)))


def _code_hash() -> str:
    """The source of everything a cached 3D result depends on."""
    root = Path(__file__).resolve().parent.parent
    files = sorted((root / "fem3d").glob("*.py")) + sorted((root / "mesh").glob("*.py"))
    files += [root / "reduced" / "pillar_modes.py", Path(__file__).resolve()]
    return source_hash(files)


def modes_key(scene: Scene, mesh: dict) -> str:
    """Hash of what the loaded tube's 3D modes depend on.  Not the structural damping
    ratio: it is a label on each spatial mode, not part of the solve, and is set on the
    modes as they are read (a tornado that varies the pillar's damping solves once)."""
    p, md = scene.pillar, scene.modal
    args = {
        "mesh": mesh,
        "pillar": pillar_key(p),
        **foundation_key(scene.foundation),
        "gondola": scene.gondola.mass,
        # the gondola as a rigid body (issue 26's keys; absent in an older scene: 0, as today)
        "gondola_body": [
            getattr(scene.gondola, k, 0.0) for k in ("pitch_inertia", "roll_inertia", "yaw_inertia", "height")
        ],
        "top_model": md.top_model,
        "top_mass": md.top_mass,
        "rotor_body": [
            scene.rotor.mass,
            getattr(scene.rotor, "diametral_inertia", 0.0),
            getattr(scene.rotor, "height", 0.0),
        ]
        if md.top_mass == "gondola_and_rotor"
        else None,
        "tolerance": md.tolerance,
    }
    return cache_key(args, version=CACHE_VERSION, code=_code_hash())


def _enough(omega, band_top: float) -> bool:
    """The modes pass the band and hold one more for the truncation check."""
    omega = np.asarray(omega, dtype=float)
    return len(omega) >= MAX_CANDIDATES or len(omega) > int(np.sum(omega <= band_top))


def _solid(
    scene: Scene, pm: PillarModel, band_top: float, comm
) -> tuple[PillarModes, TipReductionOf, int, SpatialPillarModes]:
    """The loaded tube's X bending modes, all its modes, and the bare tube's Eq. 2 on the
    chain's mesh."""
    from ..fem3d import modal_analysis, tip_reduction
    from ..fem3d.beside import start as start_beside
    from ..fem3d.pillar_modes import pillar_modes_from_fem3d
    from ..fem3d.spatial_modes import spatial_modes_from_fem3d

    mesh = solid_mesh_section(pm.mesh)
    # the bare tube in a second process while this one solves the loaded tube: the two are
    # independent, and a serial run leaves the second core idle (fem3d.beside)
    beside = start_beside(scene, top=False, n_modes=8, mesh=mesh, comm=comm)
    with beside or contextlib.nullcontext():
        n = FIRST_SOLVE
        while True:
            loaded = modal_analysis(scene, top=True, n_modes=n, mesh=mesh, comm=comm)
            bx = [w for w, k in zip(loaded.omega, loaded.kind) if k == "bending_x"]
            if _enough(bx, band_top) or len(loaded.omega) < n or n >= 256:
                break
            n *= 2
        bare = beside.result() if beside else modal_analysis(scene, top=False, n_modes=8, mesh=mesh, comm=comm)
    modes = red = spatial = None
    if comm is None or comm.rank == 0:
        modes = pillar_modes_from_fem3d(loaded, scene.pillar, min(len(bx), MAX_CANDIDATES))
        modes = msgspec.structs.replace(modes, source=f"fem3d:{pm.label}")
        spatial = spatial_modes_from_fem3d(loaded, scene.pillar.damping_ratio, f"fem3d:{pm.label}")
        t = tip_reduction(bare, scene.pillar)
        red = TipReductionOf(
            t.m_reduced, t.tip_stiffness, t.omega_bending, f"Eq. 2 on the bare tube's first bending mode, {pm.label}"
        )
    if comm is not None and comm.size > 1:
        modes, red, spatial = comm.bcast((modes, red, spatial), root=0)
    assert modes is not None and red is not None and spatial is not None, "rank 0 computes them, then broadcasts"
    return modes, red, n, spatial


def _beam(scene: Scene, pm: PillarModel) -> tuple[PillarModes, TipReductionOf]:
    from ..reduced.foundation import base_springs
    from ..reduced.pillar_modes import beam_pillar_modes, beam_tip_reduction

    theory, elements = str(pm.mesh["theory"]), int(pm.mesh["elements"])
    base = base_springs(scene.foundation)
    modes = beam_pillar_modes(
        scene.pillar, scene.gondola.mass, MAX_CANDIDATES, theory, elements, scene.modal_model.gondola_inertia, base
    )
    m_r, c1, w = beam_tip_reduction(scene.pillar, theory, elements, base)
    return modes, TipReductionOf(m_r, c1, w, f"Eq. 2 on the bare beam's first mode, {pm.label}")


def chain_modes(
    scene: Scene, choice: Choice, band_top: float, *, comm=None, root: Path | None = None, progress=None
) -> ChainModes:
    """The ROM's candidate modes from ``choice.rom``, enough to pass ``band_top`` (rad/s) and
    one more; a 3D result is read from, or written to, the cache (see the module text)."""
    pm = choice.rom
    if pm.kind != "solid":
        start = time.perf_counter()
        modes, red = _beam(scene, pm)
        return ChainModes(pm, modes, red, None, time.perf_counter() - start)
    key = modes_key(scene, pm.mesh)
    cache = DiskCache((user_cache_root() if root is None else Path(root)) / "modes")
    path = cache.path(key)
    got = cache.read(key, ModesEntry)
    if got is not None and _enough(got.modes.omega, band_top):
        spatial = got.spatial.with_damping_ratio(scene.pillar.damping_ratio)
        return ChainModes(pm, got.modes, got.reduction, str(path), 0.0, got.loaded_modes, spatial)
    if progress:
        progress(f"chain: the 3D modes of {pm.label} for the ROM (cached after this)")
    start = time.perf_counter()
    modes, red, asked, spatial = _solid(scene, pm, band_top, comm)
    seconds = time.perf_counter() - start
    if comm is None or comm.rank == 0:
        try:
            cache.write(key, ModesEntry(pm.label, pm.mesh, modes, red, seconds, asked, spatial))
        except OSError:
            pass  # a read-only cache costs the next stage a solve, nothing else
    return ChainModes(pm, modes, red, str(path), seconds, asked, spatial)


def cached_solve(scene: Scene, choice: Choice, band_top: float, root: Path | None = None) -> int | None:
    """How many modes of the loaded tube the cached 3D result of ``choice.rom`` was solved
    with, when that result holds enough modes for ``band_top`` (rad/s; :func:`chain_modes`
    then reads it, whatever the band); None when there is none or it falls short, or the
    ROM's choice is no 3D model (-1: a beam's modes are no solve)."""
    pm = choice.rom
    if pm.kind != "solid":
        return -1
    cache = DiskCache((user_cache_root() if root is None else Path(root)) / "modes")
    got = cache.read(modes_key(scene, pm.mesh), ModesEntry)
    return got.loaded_modes if got is not None and _enough(got.modes.omega, band_top) else None


def rom_band_top(scene: Scene, motion=None) -> float:
    """The band the ROM keeps modes below (rad/s): modal_model.band_factor x the highest
    forcing frequency of the scene's cases (the drive's free speed, the sweep's top, the
    ground motion's band)."""
    from ..reduced.band import forcing_top

    d, L, w = scene.drive, scene.load, scene.sweep
    top = max(
        forcing_top(d, L, w, "sweep", None), forcing_top(d, L, w, "earthquake", motion) if motion is not None else 0.0
    )
    if not math.isfinite(top):
        top = 0.0
    return scene.modal_model.band_factor * top
