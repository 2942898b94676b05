"""What the closed forms and the averaging theory say about a scene: :func:`analyze`.

The headline model is the validated ROM (rotorpillar.analysis.rom: the chain's
pillar modes with the rotor on its shaft): its resonances and quasi-normal
coefficients, the averaging curves, stationary speeds, stability and jumps
(Eq. 19-24), each headline number with its error bar.  Beside it, in its own
block, the paper's model: Eq. 4 with its stated tip reduction (Eq. 5-7 and the
same averaging), and the paper's printed numbers set against it.  The pillar's
closed forms (Eq. 1-2 with a Timoshenko check) come first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..chain import ChainModes
from ..chain.choice import choose
from ..chain.modes import chain_modes, rom_band_top
from ..reduced import averaging as av
from ..reduced.foundation import base_springs
from ..reduced.reduction import pillar_closed_forms, resolve_reduction
from ..reduced.system import linear_modes, reduced_system
from ..scene import Scene
from .machine import machine_checks
from .paper import compare_with_paper
from .results import (
    AnalysisResult,
    CoupledModes,
    DriveBars,
    DriveRegimes,
    PaperModel,
    PillarClosedForms,
    ResonanceAnalysis,
    ResonanceBars,
    ResonanceCurves,
    RomSystem,
    TipReductionUsed,
)
from .rom import RomVariants, bars, drive_quantity, resonance_quantity, rom_of, rom_variants
from .tower import tower_findings

CURVE_POINTS = 201
CURVE_SPAN = 0.5  # z from 1 - span to 1 + span


def _curves(r, others, ch: av.Characteristic) -> dict:
    z = np.linspace(1 - CURVE_SPAN, 1 + CURVE_SPAN, CURVE_POINTS)
    W = z * r.omega
    dL = av.resistance_increment(W, r)
    return {
        "z": z,
        "omega": W,
        "a": av.amplitude(W, r),
        "a_linear": av.amplitude_linear(W, r),
        "dL": dL,
        "L": ch.load(W) + dL,
        "L_all": av.total_resistance(W, ch.load_coefficient, others),
        "Md": ch.drive(W),
    }


def _statement(r, jumps, ch, s_crit, e_factor, e) -> str:
    if r.nu == 0:
        return (
            f"Resonance {r.index} ({r.omega:.2f} rad/s) is undamped (nu = 0): its steady "
            "amplitude at Omega = omega is unbounded and, off it, it draws no average "
            "torque; the averaging theory predicts no steady regime there."
        )
    if jumps:
        parts = []
        for j in jumps:
            name = "run-up A->B" if j.direction == "up" else "run-down D->C"
            parts.append(f"{name}: {j.omega_from:.2f} -> {j.omega_to:.2f} rad/s at M0 = {j.torque_at_zero:.1f} N*m")
        return f"Resonance {r.index} ({r.omega:.2f} rad/s) jumps: " + "; ".join(parts) + "."
    dL_slope = -min(0.0, float(np.min(av.resistance_increment_slope(r.omega * (1 + r.nu * np.linspace(0, 3, 301)), r))))
    text = (
        f"No jumps at resonance {r.index} ({r.omega:.2f} rad/s) with this drive: dL_{r.index} "
        f"falls at most {dL_slope:.3g} N*m*s while Mc' + slope is "
        f"{2 * ch.load_coefficient * r.omega + ch.slope:.3g} N*m*s there."
    )
    if s_crit > 0:
        text += f" A motor characteristic flatter than slope {s_crit:.3g} N*m*s would cause them"
    else:
        text += f" No falling motor characteristic can cause them (critical slope {s_crit:.3g} N*m*s < 0)"
    if math.isfinite(e_factor):
        text += f"; with this motor, an eccentricity above {e * e_factor:.3g} m ({e_factor:.3g} x e) would."
    else:
        text += "."
    return text


def _resonance(
    r, others, ch: av.Characteristic, eccentricity: float, c2e: float, drive, top: float, uncertainty=None
) -> ResonanceAnalysis:
    a_max = float(av.amplitude(r.omega, r))
    dL_max = float(av.resistance_increment(r.omega, r))
    Mc = float(ch.load(r.omega))
    s_crit = av.critical_slope(ch.load_coefficient, r, top)
    e_factor = av.critical_eccentricity_factor(ch, r, top)
    jumps = [j for j in drive.jumps if j.resonance == r.index]
    return ResonanceAnalysis(
        index=r.index,
        direction=r.direction,
        omega=r.omega,
        forcing=r.forcing,
        coupling=r.coupling,
        two_n=r.two_n,
        nu=r.nu,
        modal_mass=r.modal_mass,
        shape=tuple(r.shape),
        a_max=a_max,
        rotor_relative_amplitude_max=(a_max * abs(r.shape[1] - r.shape[0]) if r.direction == "X" else a_max),
        a_max_as_printed=float(av.amplitude_as_printed(r.omega, r)),
        dL_max=dL_max,
        Mc_at_omega=Mc,
        dL_max_over_Mc=dL_max / Mc if Mc > 0 else None,
        dL_max_over_Mc_as_printed=(c2e / 2 * a_max / Mc) if Mc > 0 else None,
        stationary=tuple(s for s in drive.stationary if abs(s.omega - r.omega) < 5 * r.nu * r.omega + 1e-12),
        jumps=tuple(jumps),
        critical_slope=s_crit,
        critical_eccentricity=eccentricity * e_factor,
        statement=_statement(r, jumps, ch, s_crit, e_factor, eccentricity),
        curves=ResonanceCurves(**{k: tuple(map(float, v)) for k, v in _curves(r, others, ch).items()}),
        uncertainty=uncertainty,
    )


def averaging_results(
    resonances, ch: av.Characteristic, eccentricity: float, c2e: float, bars_of=None, drive_bars=None
):
    """Per-resonance averaging results and the drive's stationary regimes
    (``bars_of(i, r)``: the error bars of resonance i, or None)."""
    res = list(resonances)
    drive = av.analyse_drive(ch, res)
    out = [
        _resonance(r, res, ch, eccentricity, c2e, drive, drive.grid_top, bars_of(i, r) if bars_of else None)
        for i, r in enumerate(res)
    ]
    idx = drive.captured_index
    captured = next((r for r in res if r.index == idx), None) if idx is not None else None
    drive_out = DriveRegimes(
        torque_at_zero=ch.torque_at_zero,
        slope=ch.slope,
        load_coefficient=ch.load_coefficient,
        free_speed=ch.free_speed(),
        stationary=tuple(drive.stationary),
        jumps=tuple(drive.jumps),
        runup_speed=drive.runup_speed,
        rundown_speed=drive.rundown_speed,
        captured_index=idx,
        captured_resonance=None if captured is None else captured.omega,
        captured_at=drive.runup_speed if captured is not None else None,
        uncertainty=drive_bars,
    )
    return tuple(out), drive_out


def _rom_bars(v: RomVariants, ch: av.Characteristic):
    """The error bars of the ROM's resonances and stationary speeds."""
    base = v.base.quasi_normal()

    def of(i, r):
        q = lambda fn: resonance_quantity(i, base, fn)
        return ResonanceBars(
            omega=bars(r.omega, q(lambda m: m.omega), v, "rad/s"),
            a_max=bars(float(av.amplitude(r.omega, r)), q(lambda m: float(av.amplitude(m.omega, m))), v, "m"),
            dL_max=bars(
                float(av.resistance_increment(r.omega, r)),
                q(lambda m: float(av.resistance_increment(m.omega, m))),
                v,
                "N*m",
            ),
        )

    d = av.analyse_drive(ch, base)
    drive = DriveBars(
        *(
            None if getattr(d, w) is None else bars(getattr(d, w), drive_quantity(ch, w), v, "rad/s")
            for w in ("runup_speed", "rundown_speed")
        )
    )
    return of, drive


ERROR_NOTE = (
    "discretisation: the change when every pillar mode's frequency moves by the "
    "convergence study's error bound on the first bending frequency (the study measures "
    "the first bending and ovalling; the higher bending modes are taken at the same "
    "relative error); truncation: the ROM against itself with one more pillar mode"
)


def headline_analysis(scene: Scene, chain: ChainModes, ch: av.Characteristic, c2e: float):
    """(RomSystem, resonances, drive) of the validated ROM with its error bars."""
    top = rom_band_top(scene)
    v = rom_variants(scene, chain, top)
    of, drive_bars = _rom_bars(v, ch)
    resonances, drive = averaging_results(v.base.quasi_normal(), ch, scene.rotor.eccentricity, c2e, of, drive_bars)
    damped = tuple(v.base.damped_frequencies())
    x = [r for r in resonances if r.direction == "X"]
    y = [r for r in resonances if r.direction == "Y"]
    system = RomSystem(
        modes=v.modes,
        band_top=top,
        mode_source=chain.modes.source,
        candidate_omega=tuple(map(float, chain.modes.omega)),
        omega=tuple(r.omega for r in x),
        omega_vertical=y[0].omega,
        frequency_hz=tuple(r.omega / (2 * math.pi) for r in resonances),
        damped=damped,
        f4=c2e,
        tip_reduction=chain.reduction,
        truncation_modes=None if v.truncated is None else v.modes + 1,
        frequency_error=v.frequency_error,
        error_note=ERROR_NOTE,
    )
    return system, resonances, drive, v.base


def running_speed(model, scene: Scene) -> float | None:
    """The highest stable stationary speed of the planar ROM with the scene's drive (rad/s), or None."""
    from ..reduced.stationary import stationary_exact

    d, L = scene.drive, scene.load
    stable = [s.omega for s in stationary_exact(model, d.torque_at_zero, d.slope, L.coefficient) if s.stable]
    return max(stable) if stable else None


def spatial_blocks(scene: Scene, chain: ChainModes, planar) -> tuple:
    """analyze.json's ``spatial``, ``drive_reaction`` (issue 26) and the damping law's warnings
    (rotorpillar.analysis.damping_law), on the chain's modes in every direction when it has them
    (3D), else the beam's."""
    from ..reduced.spatial_scene import drive_reaction_analysis, scene_spatial_modes, spatial_analysis
    from .damping_law import ground_law_warnings

    top = rom_band_top(scene)
    modes = scene_spatial_modes(scene, getattr(chain, "spatial", None))
    spatial = spatial_analysis(scene, planar, top, running_speed(planar, scene), modes)
    return spatial, drive_reaction_analysis(scene, top, modes), ground_law_warnings(scene, top, modes)


def paper_model_analysis(
    scene: Scene, closed: PillarClosedForms, ch: av.Characteristic, c2e: float, fem3d_reduction=None
) -> PaperModel:
    """Eq. 4 with the scene's stated tip reduction (or Eq. 2), analysed as the paper does."""
    red = resolve_reduction(scene, closed, fem3d_reduction)
    sys_ = reduced_system(
        scene.rotor, scene.shaft, scene.gondola.mass, scene.pillar.damping, red.tip_mass, red.tip_stiffness
    )
    modes = linear_modes(sys_)
    resonances, drive = averaging_results(modes.resonances, ch, scene.rotor.eccentricity, c2e)
    x = modes.resonances[:2]
    system = CoupledModes(
        tip_mass_total=sys_.tip_mass,
        c0=sys_.c0,
        b0=sys_.b0,
        omega=(x[0].omega, x[1].omega),
        omega3=modes.resonances[2].omega,
        frequency_hz=tuple(w / (2 * math.pi) for w in modes.omega),
        modal_vectors=tuple(tuple(r.shape) for r in x),
        modal_masses=tuple(r.modal_mass for r in modes.resonances),
        forcing=tuple(r.forcing for r in modes.resonances),
        coupling=tuple(r.coupling for r in modes.resonances),
        two_n=tuple(r.two_n for r in modes.resonances),
        nu=tuple(r.nu for r in modes.resonances),
        f4=c2e,
    )
    return PaperModel(
        red,
        system,
        resonances,
        drive,
        "the paper's Eq. 4 as published, with the tip reduction the scene states "
        "(m_r, c1; Eq. 2 where it states none): the paper's own model, beside the "
        "headline model, never instead of it",
    )


@dataclass(frozen=True)
class _PaperView:
    """What rotorpillar.analysis.paper reads: the pillar and the paper model's blocks."""

    pillar: PillarClosedForms
    reduction: TipReductionUsed
    system: CoupledModes
    resonances: tuple
    drive: DriveRegimes


def analyze(scene: Scene, chain: ChainModes | None = None, fem3d_reduction=None) -> AnalysisResult:
    """Everything the closed forms and the averaging theory say about a scene.

    ``chain``: the chain's pillar model and modes (rotorpillar.chain.resolve);
    None takes the scene's own model (no study: its [mesh], or the beam
    without dolfinx).  ``fem3d_reduction``, a callable scene -> (m_reduced,
    tip_stiffness), is the 3D model's Eq. 2 for the paper model when
    ``reduction.source = "fem3d"``; by default the chain's own Eq. 2 when the
    chain's model is 3D.
    """
    if chain is None:
        chain = chain_modes(scene, choose(scene, None), rom_band_top(scene))
    if fem3d_reduction is None and chain.pillar_model.kind == "solid":
        fem3d_reduction = lambda _scene: (chain.reduction.m_reduced, chain.reduction.tip_stiffness)
    closed = pillar_closed_forms(scene.pillar, base_springs(scene.foundation))
    ch = av.Characteristic(scene.drive.torque_at_zero, scene.drive.slope, scene.load.coefficient)
    c2e = scene.shaft.stiffness * scene.rotor.eccentricity
    system, resonances, drive, planar = headline_analysis(scene, chain, ch, c2e)
    spatial, reaction, warnings = spatial_blocks(scene, chain, planar)
    paper = paper_model_analysis(scene, closed, ch, c2e, fem3d_reduction)
    # a scene of another machine, with published numbers of its own, is not set against the paper's
    own = scene.reference.stated
    rows = (
        ()
        if own
        else compare_with_paper(scene, _PaperView(closed, paper.reduction, paper.system, paper.resonances, paper.drive))
    )
    tower = tower_findings(scene, system.omega[0], chain.pillar_model.label)
    return AnalysisResult(
        pillar=closed,
        pillar_model=chain.pillar_model,
        system=system,
        resonances=resonances,
        drive=drive,
        paper_model=paper,
        paper_comparison=rows,
        spatial=spatial,
        drive_reaction=reaction,
        tower=tower,
        machine_checks=machine_checks(scene, rom_of(scene, chain, system.modes), chain.modes, drive.runup_speed),
        warnings=warnings,
    )
