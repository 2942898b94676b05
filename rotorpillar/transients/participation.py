"""How much each mode of the loaded tube takes part in a transient case's loads.

A transient loads the pillar in a few ways only: the ground's acceleration
along x (the earthquake: -M r a_g, r the rigid x translation of the tube
and its top), and the rotor's shaft force on the top plate along x and
along the tube's axis z (the run-up; the earthquake too, through the
rotor's own inertia).  Mode j takes part in a load as much as the load
does work on it:

- base x: its effective mass L_j**2 / m_j with L_j = phi_j^T M r, as a
  share of the mass the base carries (tube and top);
- plate x, plate z: phi_j(plate)**2 / (m_j omega_j**2), its part of the
  plate's static compliance along x (the cantilever's H**3 / (3 E I)) or z
  (H / (E A)); over all modes they sum to the 3D model's own compliance.

Both are computed from the 3D modes of the loaded tube (modal.json's
``modes_with_top`` when it matches the scene, else ``modal_analysis(scene,
top=True)`` on the scene's [mesh], which resolves every mode of the band,
shell modes included), never assumed.  By the tube's symmetry the n = 2
ovalling pairs, torsion and the bending in y take no part (shares ~1e-20,
round-off), the axial modes only through plate z.  transients.references
chooses the 3D reference mesh from these.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .. import records
from ..fem3d.modal import ModeRow  # numpy-only: the 3D model's table of modes
from ..records import Record

if TYPE_CHECKING:
    from collections.abc import Sequence

    from ..scene import Scene

PARTICIPATION_FLOOR = 1e-6
"""A mode whose largest share of a case's loads is below this takes no part (-);
symmetry leaves the others at round-off, ~1e-20, and bending at 0.2 - 0.6."""
LOADS = {"earthquake": ("base_x", "plate_x"), "runup": ("plate_x", "plate_z")}
"""The loads of each case: the ground's acceleration along x, the shaft force on the plate."""
QUANTITY_OF: dict[tuple[str, int | None], str] = {("bending_x", 0): "bending", ("ovalling", 0): "ovalling"}
"""(kind, n_axial) of a loaded mode -> the study's frequency that bounds its error
(the study measures the first bending and the first n = 2 ovalling of the bare tube)."""


class ModeParticipation(Record):
    """One mode of the loaded tube and its part in a case's loads."""

    index: int
    kind: str
    """bending_x, bending_y, ovalling, torsion, axial, breathing or other"""
    n_circumferential: int | None
    n_axial: int | None
    omega: float
    """(rad/s)"""
    modal_mass: float
    """phi^T M phi of the normalised shape (kg)"""
    effective_mass_x: float | None
    """L_x**2 / m_j for a base acceleration along x (kg)"""
    shares: dict
    """load -> share (-): base_x of the base's mass, plate_x / plate_z of the plate's
    static compliance (closed form: H**3 / (3 E I) along x, H / (E A) along z)"""
    in_band: bool
    participates: bool


class ParticipationTable(Record):
    """The loaded tube's modes and which of them a case's loads excite."""

    case: str
    loads: tuple[str, ...]
    band_top: float
    """the case's band: margin x its fastest forcing (rad/s)"""
    floor: float
    """share below which a mode takes no part (-)"""
    total_mass: float
    """the mass a base acceleration moves: tube and top (kg)"""
    source: str
    """modal.json (its loaded modes) or computed (modal_analysis on the scene's mesh)"""
    mesh: dict
    """the mesh the modes were computed on"""
    modes: tuple[ModeParticipation, ...]
    participating: tuple[int, ...]
    """indices of the modes in the band that take part"""
    left_out: tuple[int, ...]
    """indices of the modes in the band that take no part"""
    quantities: tuple[str, ...]
    """the study's frequencies that bound the participating modes' errors"""
    uncovered: tuple[str, ...]
    """participating modes in the band no study frequency covers (their error is unbounded)"""
    statement: str


def participation_table(
    rows: Sequence[ModeRow],
    case: str,
    band_top: float,
    total_mass: float,
    compliance: tuple[float, float],
    *,
    source: str,
    mesh: dict,
    floor: float = PARTICIPATION_FLOOR,
) -> ParticipationTable:
    """Which modes the case's loads excite, from the loaded modes' table rows
    (``ModalResult.modes_table()`` or modal.json's ``modes_with_top``: omega, kind,
    modal_mass, participation, top_plate_motion); ``compliance``: the plate's static
    compliance along x and z that the plate shares are parts of (m/N)."""
    loads = LOADS[case]
    w = np.array([r.omega for r in rows], float)
    m = np.array([r.modal_mass for r in rows], float)
    plate = np.array([(r.top_plate_motion or (0.0,) * 6)[:3] for r in rows], float)
    Lx = np.array([(r.participation or (math.nan,) * 3)[0] for r in rows], float)
    stiff = np.maximum(m * w**2, 1e-300)
    shares = {
        "base_x": Lx**2 / m / total_mass,
        "plate_x": plate[:, 0] ** 2 / stiff / compliance[0],
        "plate_z": plate[:, 2] ** 2 / stiff / compliance[1],
    }
    if np.any(~np.isfinite(shares["base_x"])) and "base_x" in loads:
        raise ValueError("the loaded modes carry no participation (modal.json from before it?)")
    modes: list[ModeParticipation] = []
    part: list[int] = []
    left: list[int] = []
    for i, r in enumerate(rows):
        s = {k: float(shares[k][i]) for k in loads}
        inside = bool(w[i] <= band_top)
        takes = max(s.values()) >= floor
        modes.append(
            ModeParticipation(
                index=int(r.index),
                kind=r.kind,
                n_circumferential=r.n_circumferential,
                n_axial=r.n_axial,
                omega=float(w[i]),
                modal_mass=float(m[i]),
                effective_mass_x=None if not math.isfinite(Lx[i]) else float(Lx[i] ** 2 / m[i]),
                shares=s,
                in_band=inside,
                participates=bool(takes),
            )
        )
        if inside:
            (part if takes else left).append(i)
    quantities, uncovered = [], []
    for i in part:
        q = QUANTITY_OF.get((rows[i].kind, rows[i].n_axial))
        if q is None:
            uncovered.append(f"{rows[i].kind} at {w[i]:.2f} rad/s")
        elif q not in quantities:
            quantities.append(q)
    return ParticipationTable(
        case=case,
        loads=loads,
        band_top=float(band_top),
        floor=floor,
        total_mass=float(total_mass),
        source=source,
        mesh=dict(mesh),
        modes=tuple(modes),
        participating=tuple(part),
        left_out=tuple(left),
        quantities=tuple(quantities),
        uncovered=tuple(uncovered),
        statement=_participation_statement(case, modes, part, left, band_top, floor, uncovered),
    )


def _participation_statement(case, modes, part, left, band_top, floor, uncovered) -> str:
    def name(p):
        extra = f" n = {p.n_circumferential}" if p.kind == "ovalling" else ""
        return f"{p.kind}{extra} ({p.omega:.2f} rad/s)"

    loads = " and ".join(
        {
            "base_x": "the ground's acceleration along x",
            "plate_x": "the shaft force on the plate along x",
            "plate_z": "along the axis",
        }[k]
        for k in LOADS[case]
    )
    text = f"In the band up to {band_top:.1f} rad/s, {loads} excite " + (
        ", ".join(f"{name(modes[i])}, share {max(modes[i].shares.values()):.2g}" for i in part) or "no mode"
    )
    if left:
        worst = max(max(modes[i].shares.values()) for i in left)
        text += (
            "; " + ", ".join(name(modes[i]) for i in left) + f" take no part (largest share "
            f"{worst:.1e}, below {floor:g}: the tube's symmetry leaves them unloaded), so their "
            "frequencies, however coarse the mesh, do not enter the response"
        )
    if uncovered:
        text += (
            "; the study bounds no frequency of "
            + ", ".join(uncovered)
            + ": its error is not part of the reference's bound"
        )
    return text + "."


class LoadedModes(Record):
    """modal.json as far as the participation reads it: the loaded tube's modes."""

    modes_with_top: tuple[ModeRow, ...]
    """the modes of the tube with its top mass, lowest first"""


def loaded_mode_rows(scene: Scene, study_dir: Path | None) -> tuple[list[ModeRow], str, dict]:
    """The loaded tube's mode table: from modal.json when it is this scene's modes
    and carries the participation, else computed on the scene's [mesh]."""
    from ..provenance import Provenance

    mine = scene.to_dict()
    found = None
    if study_dir is not None:
        path = Path(study_dir) / "modal.json"
        try:
            found, written = records.read(path, LoadedModes), records.read(path, Provenance)
        except (OSError, ValueError):  # missing or damaged: computed below
            found = None
    if (
        found is not None
        and isinstance(written.scene, dict)
        and all(
            written.scene.get(k) == mine[k] for k in ("pillar", "gondola", "mesh", "modal", "converge", "drive", "load")
        )
    ):
        rows = list(found.modes_with_top)
        if rows and all(r.participation is not None for r in rows):
            return rows, "modal.json", dict(mine["mesh"])
    from ..fem3d import modal_analysis

    result = modal_analysis(scene, top=True)
    return result.modes_table(), "computed", dict(vars(scene.mesh))


def case_band_top(scene: Scene, case: str, motion=None) -> float:
    """The band a case excites: converge.margin x its fastest forcing (the drive's
    free speed; the ground motion's band for the earthquake) (rad/s)."""
    from ..reduced.band import excitation_band

    top = excitation_band(scene.drive, scene.load, scene.converge).omega_max
    if case == "earthquake" and motion is not None:
        top = max(top, scene.converge.margin * motion.band())
    return float(top)


def load_participation(scene: Scene, case: str, study_dir: Path | None = None, motion=None) -> ParticipationTable:
    """The participation of the loaded tube's modes in ``case``."""
    from ..reduced.pillar import section_of

    rows, source, mesh = loaded_mode_rows(scene, study_dir)
    p, sec = scene.pillar, section_of(scene.pillar)
    total = sec.mass_per_length * p.height + scene.gondola.mass
    compliance = (p.height**3 / (3 * p.youngs_modulus * sec.second_moment), p.height / (p.youngs_modulus * sec.area))
    return participation_table(
        rows, case, case_band_top(scene, case, motion), total, compliance, source=source, mesh=mesh
    )
