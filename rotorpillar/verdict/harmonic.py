"""`rotorpillar harmonic`: the unbalance response (Bode) and the separation margins (API 684).

- the ROM (the modal model on the scene's pillar modes, the same the
  transients use) at every speed up to the band's edge: its steady
  unbalance response (rotorpillar.reduced.bode), with the averaging's
  Eq. 19 curves near each X resonance;
- the 3D model's harmonic response (rotorpillar.fem3d.harmonic) on the 3D
  full order's mesh ([full_order], as the 3D transients): fewer speeds,
  concentrated at the resonances, each one real-block LU;
- the spatial ROM's unbalance response in every direction (issue 26:
  rotorpillar.reduced.spatial_response, Bode curves and orbits of the shaft,
  the rotor and the top), on the chain's pillar modes in every direction;
- the running speeds (the ROM's stable stationary speeds with the scene's
  drive) against every critical speed of the spatial ROM (where the 1x line
  crosses a mode) and every mode of the loaded tube in the band from
  modal.json, ovalling and torsion included.  API 684 as API 684 does it:
  each one's AF is the half-power AF of the unbalance response's peak near
  it (the spatial ROM's response, and for the 3D modes the 3D response's
  too: the larger AF); a mode the response shows no peak at needs no margin,
  and its row says so (rotorpillar.reduced.margins.separation_from_response).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..fem3d.modal_summary import ModalSummary
    from ..scene import Scene

import time
from pathlib import Path

from .. import records
from ..chain.record import PillarModel
from ..records import Record
from ..reduced import bode
from ..reduced.bode import AveragingCurve, BodeCurve
from ..reduced.margins import ExcitationOrders, ModeEntry, SeparationRow, order_margins, separation_from_response
from ..reduced.spatial_response import SpatialResponse
from ..reduced.spatial_rotor import PlanesChoice


class PeakComparison(Record):
    """One resonance's Bode peak on the ROM, on the 3D model and by Eq. 19."""

    omega: float
    """the ROM's omega_i (rad/s)"""
    rom_speed: float | None
    """speed of the ROM's tip peak near omega_i (rad/s); None: no peak (heavily damped)"""
    rom_amplitude: float | None
    """its tip amplitude (m)"""
    fem3d_speed: float | None
    """the 3D curve's peak near omega_i (rad/s), or None"""
    fem3d_amplitude: float | None
    """(m)"""
    averaging_amplitude: float
    """Eq. 19 at omega_i: |f_i| / (2 omega_i**2 nu_i) (m)"""
    amplitude_difference: float | None
    """fem3d / ROM - 1 at the peaks (-)"""


class HarmonicResult(Record, omit_defaults=True):
    """What `rotorpillar harmonic` found (harmonic.json)."""

    running_speeds: tuple[float, ...]
    """the stable stationary speeds of the ROM with the scene's drive (rad/s)"""
    running_speed_source: str
    band_top: float
    """the band checked: converge.margin x the highest excitation (rad/s)"""
    rom: BodeCurve
    fem3d: BodeCurve | None
    """the 3D model's harmonic response (None when dolfinx is missing)"""
    averaging: tuple[AveragingCurve, ...]
    peaks: tuple[PeakComparison, ...]
    modes: tuple[ModeEntry, ...]
    """the structural modes in the band: the ROM's coupled system and the 3D loaded tube"""
    separation: tuple[SeparationRow, ...]
    """every running speed against every mode (API 684)"""
    rom_model: str
    """the ROM's pillar modes (source, count)"""
    fem3d_model: str
    """the 3D harmonic response's mesh and dofs, or why there is none"""
    rom_seconds_per_speed: float
    """(s)"""
    fem3d_seconds_per_speed: float | None
    """one real-block assembly, LU and solve (s)"""
    notes: tuple[str, ...]
    pillar_model: PillarModel | None = None
    """the chain's pillar model the ROM's modes come from (rotorpillar.chain)"""
    spatial: SpatialResponse | None = None
    """the spatial ROM's unbalance response in every direction: Bode curves, their peaks and
    half-power AFs, the orbits of the shaft, the rotor and the top (issue 26)"""
    planes: PlanesChoice | None = None
    """modal_model.planes resolved, with its reason"""
    orders: ExcitationOrders | None = None
    """a bladed rotor (rotor.blades > 0): the first tower mode against 1P and the
    blade-passing order (soft-stiff), the lines a Campbell diagram draws"""


#: a response peak counts for a mode within this share of the mode's frequency (-)
PEAK_WIDTH = 0.15


def running_speeds(model, scene: Scene) -> list[float]:
    """The ROM's stable stationary speeds with the scene's drive (rad/s)."""
    from ..reduced.stationary import stationary_exact

    d, L = scene.drive, scene.load
    return sorted(s.omega for s in stationary_exact(model, d.torque_at_zero, d.slope, L.coefficient) if s.stable)


def rom_modes(model) -> list[ModeEntry]:
    """The coupled system's modes (X: state-space eigenvalues; Y: the rotor on its shaft)."""
    out, i = [], 0
    for row in model.damped_frequencies():
        i += row.direction == "X"
        kind = f"coupled X {i}" if row.direction == "X" else "rotor Y on its shaft"
        out.append(
            ModeEntry(
                row.omega,
                row.damping_ratio,
                kind,
                "modal",
                "damping ratio of the coupled system's eigenvalue (b1 at the tip, b2)",
            )
        )
    return out


def fem3d_modes(modal_doc: ModalSummary, tip_damping: float) -> list[ModeEntry]:
    """The loaded tube's 3D modes (modal.json's modes_with_top) with their damping.

    bending_x: zeta = b1 / (2 m_j omega_j), m_j the mass referred to the tip
    (the dashpot at the plate's X, as the 3D transient has it); every other
    mode: 0 (the model leaves it undamped; API 684 then asks the most).
    """
    out: list = []
    for row in modal_doc.modes_with_top:
        kind = row.kind
        n = row.n_circumferential
        label = f"{kind} n={n}" if kind == "ovalling" and n is not None else kind
        if out and out[-1].kind.startswith(label) and abs(out[-1].omega - row.omega) <= 1e-6 * row.omega:
            out[-1] = ModeEntry(out[-1].omega, out[-1].damping_ratio, f"{label} (pair)", "fem3d", out[-1].note)
            continue
        if kind == "bending_x":
            zeta = tip_damping / (2 * row.modal_mass * row.omega)
            note = "b1 at the tip on the mode's tip-scaled mass (the rotor not on it)"
        else:
            zeta, note = 0.0, "undamped in the model: the tip dashpot does not move it"
        out.append(ModeEntry(float(row.omega), float(zeta), label, "fem3d", note))
    return out


def _open_top_note(modal_doc: ModalSummary, speeds) -> list[str]:
    """The bare tube's first ovalling mode against the running speeds: where the top
    does not hold the section round (modal.top_model = "ring_mass"), it is the one."""
    rows = [r for r in modal_doc.modes if r.kind == "ovalling"]
    if not rows or not speeds:
        return []
    w = float(rows[0].omega)
    near = min(speeds, key=lambda s: abs(s - w))
    return [
        f"the bare tube's first ovalling mode (n = {rows[0].n_circumferential}) is at "
        f"{w:.4g} rad/s, {100 * abs(w - near) / near:.1f} % {'below' if w < near else 'above'} the "
        f"running speed {near:.4g} rad/s: the loaded tube's is higher only because its rigid top "
        "plate holds the top section round (modal.top_model); a top that does not would bring "
        "it back"
    ]


def _peaks(model, rom_curve, fem_curve, top) -> list[PeakComparison]:
    from ..reduced import averaging as av

    out = []
    for r in model.quasi_normal():
        if r.direction != "X" or not (0 < r.omega < top):
            continue
        a = bode.peak_near(rom_curve, r.omega, 0.15)
        b = bode.peak_near(fem_curve, r.omega, 0.15) if fem_curve is not None else None
        out.append(
            PeakComparison(
                float(r.omega),
                None if a is None else a[0],
                None if a is None else a[1],
                None if b is None else b[0],
                None if b is None else b[1],
                float(av.amplitude(r.omega, r)),
                None if (a is None or b is None) else b[1] / a[1] - 1,
            )
        )
    return out


def harmonic_analysis(scene: Scene, out: Path, progress=None, with_fem3d: bool = True, chain=None) -> HarmonicResult:
    """The Bode curves and the separation margins of the scene (see the module text);
    ``chain``: the chain's pillar model and modes (rotorpillar.chain.resolve; None: resolved
    here for ``out``)."""
    from ..fem3d.modal_summary import ModalSummary
    from ..reduced.band import forcing_top
    from ..reduced.models import build_model

    say = progress or (lambda m: None)
    if chain is None:
        from ..chain import resolve

        chain = resolve(scene, out, progress=progress)
    # the ROM of the transients: its band is band_factor x the fastest rotor speed
    top = scene.modal_model.band_factor * forcing_top(scene.drive, scene.load, scene.sweep, "runup", None)
    model, info = build_model(scene, "modal", top, pillar_modes=chain.modes)
    speeds = running_speeds(model, scene)
    start = time.perf_counter()
    grid = bode.speed_grid(model.quasi_normal(), top)
    rom_curve = bode.unbalance_response(model, grid)
    rom_cost = (time.perf_counter() - start) / len(grid)
    notes = []
    fem_curve, fem_cost, fem_text = None, None, "not computed"
    if with_fem3d:
        fem_curve, fem_cost, fem_text = _fem3d_curve(scene, model, top, say)
    else:
        notes.append("the 3D harmonic response was not asked for (--no-fem3d)")
    from ..reduced.spatial_scene import resolve_planes, scene_spatial_model, scene_spatial_modes

    say("harmonic: the spatial ROM's unbalance response in every direction")
    spatial_modes = scene_spatial_modes(scene, getattr(chain, "spatial", None))
    spatial = scene_spatial_model(scene, top, spatial_modes)
    planes = resolve_planes(scene, top, spatial_modes)
    modes, spatial_response, sampled, moved = spatial_modes_and_response(spatial, grid, fem_curve)
    modal_path = Path(out) / "modal.json"
    if modal_path.is_file():
        doc = records.read(modal_path, ModalSummary)
        loaded = fem3d_modes(doc, scene.pillar.damping)
        modes += loaded
        highest = max((m.omega for m in loaded), default=0.0)
        if highest < top:
            notes.append(
                f"modal.json's loaded-tube modes reach {highest:.4g} rad/s, below the band's "
                f"{top:.4g}: a 3D mode between them is not checked (raise modal.n_modes)"
            )
        notes += _open_top_note(doc, speeds)
    else:
        notes.append(
            "no modal.json beside: the loaded tube's 3D modes (ovalling, torsion) are not "
            "checked; run `rotorpillar modal` first"
        )
    modes = [m for m in modes if m.omega <= top]
    rows = separation_rows(speeds, modes, spatial_response, sampled, moved)
    notes.append(
        "API 684's AF of each mode from the half-power bandwidth of the unbalance response's peak within "
        f"{100 * PEAK_WIDTH:.0f} % of it, on the curves the mode moves (the spatial ROM's response; for the 3D "
        "modes also the 3D response's, the larger AF); no peak: no margin required. The modes' damping ratios "
        "are listed beside"
    )
    first = next((m for m in rom_modes(model) if m.kind == "coupled X 1"), None)
    orders = (
        None
        if first is None or not speeds or scene.rotor.blades == 0
        else order_margins(speeds, first, scene.rotor.blades, scene.rotor.order_margin)
    )
    pm = model.pillar_modes
    assert pm is not None  # the modal model carries its pillar modes
    return HarmonicResult(
        running_speeds=tuple(speeds),
        running_speed_source="the stable stationary speeds of the ROM with the scene's drive "
        "(Md = Mc + the structure's averaged torque)",
        band_top=float(top),
        rom=rom_curve,
        fem3d=fem_curve,
        averaging=bode.averaging_curves(model, top),
        peaks=tuple(_peaks(model, rom_curve, fem_curve, top)),
        modes=tuple(modes),
        separation=rows,
        rom_model=f"modal ROM: {pm.count} pillar modes ({pm.source}) + the rotor on its shaft",
        fem3d_model=fem_text,
        rom_seconds_per_speed=float(rom_cost),
        fem3d_seconds_per_speed=None if fem_cost is None else float(fem_cost),
        notes=tuple(notes),
        pillar_model=chain.pillar_model,
        spatial=spatial_response,
        planes=planes,
        orders=orders,
    )


def spatial_modes_and_response(spatial, grid, fem_curve):
    """(ModeEntry per critical speed of the spatial ROM, its unbalance response, the sampled
    peaks of the 3D response) on ``grid`` (rad/s) refined near the critical speeds."""
    import numpy as np

    from ..reduced.spatial_linear import critical_speed_modes, critical_speeds, damped_modes
    from ..reduced.spatial_response import curves_moved, peaks_from_samples, unbalance_response

    shapes = critical_speed_modes(spatial)[1].T
    pairs = [(c, v) for c, v in zip(critical_speeds(spatial), shapes) if c.speed <= grid[-1]]
    crit = [c for c, _ in pairs]
    fine = [np.linspace(0.9 * c.speed, min(1.1 * c.speed, grid[-1]), 41) for c in crit]
    response = unbalance_response(spatial, np.unique(np.concatenate([np.asarray(grid)] + fine)))
    modes = []
    curves = {}
    for c, v in pairs:
        dm = damped_modes(spatial, c.speed)
        zeta = float(dm.damping_ratio[int(np.argmin(np.abs(dm.frequency - c.speed)))])
        modes.append(
            ModeEntry(
                float(c.speed),
                zeta,
                c.label,
                "modal",
                f"critical speed of the spatial ROM ({c.whirl} whirl, excited by {c.excited_by}); zeta of its damped mode",
            )
        )
        curves[round(float(c.speed), 9)] = curves_moved(spatial, v)
    sampled = ()
    if fem_curve is not None:
        sampled = peaks_from_samples("3D tip X", np.asarray(fem_curve.speeds), np.asarray(fem_curve.tip_amplitude))
        sampled += peaks_from_samples(
            "3D shaft deflection X", np.asarray(fem_curve.speeds), np.asarray(fem_curve.shaft_amplitude)
        )
    return modes, response, sampled, curves


#: the spatial ROM's curves a 3D mode of each kind moves (modal.json's kinds)
FEM3D_CURVES = {
    "bending_x": ("tip_x", "rotor_x", "shaft_x"),
    "bending_y": ("tip_y", "top_pitch"),
    "torsion": ("top_yaw",),
    "axial": ("tip_z", "rotor_z", "shaft_z"),
}


def separation_rows(running, modes, response, sampled, curves) -> tuple:
    """Every running speed against every mode, the AF read off the response's peak near the mode
    on the curves the mode moves (a critical speed of the spatial ROM: its shape's; a 3D mode: by
    its kind, and the 3D response's curves)."""
    from ..reduced.spatial_response import peak_near

    rows = []
    for m in modes:
        if m.model == "modal":
            moved = curves.get(round(float(m.omega), 9), ())
        else:
            moved = FEM3D_CURVES.get(m.kind.split(" ")[0], ())
        best = peak_near(response, m.omega, PEAK_WIDTH, moved) if moved else None
        # the 3D response is the tip's and the shaft's in the rotor's plane: the modes it can show
        if m.model == "fem3d" and m.kind.split(" ")[0] not in ("bending_y", "torsion", "axial"):
            near = [
                p
                for p in sampled
                if p.amplification_factor is not None and abs(p.speed - m.omega) <= PEAK_WIDTH * m.omega
            ]
            if near:
                top = max(near, key=lambda p: p.amplification_factor or 0.0)
                if best is None or (top.amplification_factor or 0.0) > (best.amplification_factor or 0.0):
                    best = top
        where = (
            "" if best is None else f"{best.curve}, the spatial ROM" if not best.curve.startswith("3D") else best.curve
        )
        for w in running:
            rows.append(
                separation_from_response(
                    w,
                    m,
                    None if best is None else best.amplification_factor,
                    None if best is None else best.speed,
                    where,
                )
            )
    return tuple(rows)


def _fem3d_curve(scene: Scene, model, top: float, say):
    """The 3D harmonic response on the [full_order] mesh, or (None, None, why not)."""
    import importlib.util

    if importlib.util.find_spec("dolfinx") is None:
        return None, None, "not computed: dolfinx is not installed here"
    from ..fem3d import assemble_pillar
    from ..fem3d.harmonic import harmonic_response, harmonic_speeds
    from ..fem3d.rotor_top import RotorOnTop
    from ..transients.run_plan import fem3d_plan

    mesh = fem3d_plan(scene, "runup").mesh
    res = [r.omega for r in model.quasi_normal() if r.direction == "X"]
    speeds = harmonic_speeds(res, top)
    say(f"harmonic: the 3D model on {mesh.elements_around} x {mesh.elements_along} elements at {len(speeds)} speeds")
    pillar = assemble_pillar(scene, top=True, mesh=mesh)
    try:
        h = harmonic_response(pillar, RotorOnTop.from_scene(scene), scene.pillar.damping, speeds)
    finally:
        pillar.K.destroy()
        pillar.M.destroy()
    curve = bode.curve("fem3d", speeds, h.tip, h.shaft)
    text = (
        f"3D tube, {mesh.elements_around} x {mesh.elements_along} x {mesh.elements_through} "
        f"elements of degree {mesh.degree} ([full_order], the 3D transients' mesh), "
        f"{h.dofs} unknowns (one real LDL^T of K - Omega^2 M a speed; the plate's two rows in closed form)"
    )
    return curve, h.seconds_per_speed, text


def summary_text(r: HarmonicResult) -> str:
    """The readable text of `rotorpillar harmonic`."""
    lines = [f"unbalance response up to {r.band_top:.1f} rad/s: {r.rom_model}; {r.fem3d_model}"]
    for p in r.peaks:
        rom = (
            "no peak (damped)"
            if p.rom_speed is None or p.rom_amplitude is None
            else f"{p.rom_amplitude * 1e3:.4g} mm at {p.rom_speed:.3f}"
        )
        fem = (
            "-"
            if p.fem3d_speed is None or p.fem3d_amplitude is None
            else f"{p.fem3d_amplitude * 1e3:.4g} mm at {p.fem3d_speed:.3f}"
        )
        lines.append(
            f"  resonance {p.omega:.3f} rad/s: ROM {rom}; 3D {fem}; Eq. 19 {p.averaging_amplitude * 1e3:.4g} mm"
        )
    lines.append(
        "separation margins (API 684), running speeds " + ", ".join(f"{w:.3f}" for w in r.running_speeds) + " rad/s:"
    )
    for row in r.separation:
        af = "no peak" if row.amplification_factor is None else f"{row.amplification_factor:.3g}"
        lines.append(
            f"  {row.mode.model:>5} {row.mode.kind:<22} {row.mode.omega:9.3f} rad/s  AF {af:>6}  "
            f"{row.position:<5} required {100 * row.required:5.1f} %  actual "
            f"{100 * row.actual:6.1f} %  {row.status}"
        )
    for n in r.notes:
        lines.append("  note: " + n)
    return "\n".join(lines)


def nearest(rows) -> object | None:
    """The row with the smallest actual margin, or None."""
    return min(rows, key=lambda r: r.actual) if rows else None
