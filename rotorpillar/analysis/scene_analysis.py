"""What the paper's closed-form model says about a scene: :func:`analyze`.

Pillar closed forms (equations 1-2, with a Timoshenko check), the tip reduction
actually used (stated, closed form or fem3d), the reduced system's modes and
quasi-normal coefficients (equations 5-7), the averaging curves, stationary speeds,
stability and jumps (equations 19-24), and the paper's printed numbers beside ours.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..reduced import averaging as av
from ..reduced.reduction import pillar_closed_forms, resolve_reduction
from ..reduced.system import linear_modes, reduced_system
from ..scene import Scene
from .paper import compare_with_paper
from .results import AnalysisResult

CURVE_POINTS = 201
CURVE_SPAN = 0.5          # z from 1 - span to 1 + span


def _curves(r, others, ch: av.Characteristic) -> dict:
    z = np.linspace(1 - CURVE_SPAN, 1 + CURVE_SPAN, CURVE_POINTS)
    W = z * r.omega
    dL = av.resistance_increment(W, r)
    return {"z": z, "omega": W, "a": av.amplitude(W, r), "a_linear": av.amplitude_linear(W, r),
            "dL": dL, "L": ch.load(W) + dL,
            "L_all": av.total_resistance(W, ch.load_coefficient, others), "Md": ch.drive(W)}


def _statement(r, jumps, ch, s_crit, e_factor, e) -> str:
    if r.nu == 0:
        return (f"Resonance {r.index} ({r.omega:.2f} rad/s) is undamped (nu = 0): its steady "
                "amplitude at Omega = omega is unbounded and, off it, it draws no average "
                "torque; the averaging theory predicts no steady regime there.")
    if jumps:
        parts = []
        for j in jumps:
            name = "run-up A->B" if j.direction == "up" else "run-down D->C"
            parts.append(f"{name}: {j.omega_from:.2f} -> {j.omega_to:.2f} rad/s at M0 = "
                         f"{j.torque_at_zero:.1f} N*m")
        return f"Resonance {r.index} ({r.omega:.2f} rad/s) jumps: " + "; ".join(parts) + "."
    dL_slope = -min(0.0, float(np.min(av.resistance_increment_slope(
        r.omega * (1 + r.nu * np.linspace(0, 3, 301)), r))))
    text = (f"No jumps at resonance {r.index} ({r.omega:.2f} rad/s) with this drive: dL_{r.index} "
            f"falls at most {dL_slope:.3g} N*m*s while Mc' + slope is "
            f"{2 * ch.load_coefficient * r.omega + ch.slope:.3g} N*m*s there.")
    if s_crit > 0:
        text += f" A motor characteristic flatter than slope {s_crit:.3g} N*m*s would cause them"
    else:
        text += " No falling motor characteristic can cause them (critical slope "\
                f"{s_crit:.3g} N*m*s < 0)"
    if math.isfinite(e_factor):
        text += f"; with this motor, an eccentricity above {e * e_factor:.3g} m ({e_factor:.3g} x e) would."
    else:
        text += "."
    return text


def averaging_results(modes, ch: av.Characteristic, eccentricity: float,
                      c2e: float) -> tuple[list[dict], dict]:
    """Per-resonance averaging results and the drive's stationary regimes."""
    res = modes.resonances
    drive = av.analyse_drive(ch, res)
    top = drive.grid_top
    out = []
    for r in res:
        a_max = float(av.amplitude(r.omega, r))
        dL_max = float(av.resistance_increment(r.omega, r))
        Mc = float(ch.load(r.omega))
        s_crit = av.critical_slope(ch.load_coefficient, r, top)
        e_factor = av.critical_eccentricity_factor(ch, r, top)
        jumps = [j for j in drive.jumps if j.resonance == r.index]
        out.append({
            "index": r.index, "direction": r.direction, "omega": r.omega,
            "forcing": r.forcing, "coupling": r.coupling, "two_n": r.two_n, "nu": r.nu,
            "modal_mass": r.modal_mass, "shape": list(r.shape),
            "a_max": a_max,
            "rotor_relative_amplitude_max": a_max * abs(r.shape[1] - r.shape[0]) if r.direction == "X" else a_max,
            "a_max_as_printed": float(av.amplitude_as_printed(r.omega, r)),
            "dL_max": dL_max,
            "Mc_at_omega": Mc,
            "dL_max_over_Mc": dL_max / Mc if Mc > 0 else None,
            "dL_max_over_Mc_as_printed": (c2e / 2 * a_max / Mc) if Mc > 0 else None,
            "stationary": [vars(s) for s in drive.stationary
                           if abs(s.omega - r.omega) < 5 * r.nu * r.omega + 1e-12],
            "jumps": [vars(j) for j in jumps],
            "critical_slope": s_crit,
            "critical_eccentricity": eccentricity * e_factor,
            "statement": _statement(r, jumps, ch, s_crit, e_factor, eccentricity),
            "curves": _curves(r, res, ch),
        })
    drive_out = {
        "torque_at_zero": ch.torque_at_zero, "slope": ch.slope,
        "load_coefficient": ch.load_coefficient, "free_speed": ch.free_speed(),
        "stationary": [vars(s) for s in drive.stationary],
        "jumps": [vars(j) for j in drive.jumps],
        "runup_speed": drive.runup_speed, "rundown_speed": drive.rundown_speed,
        "captured_at": drive.captured_at,
    }
    return out, drive_out


def analyze(scene: Scene, fem3d_reduction=None) -> AnalysisResult:
    """Everything the closed forms say about a scene.

    ``fem3d_reduction``, a callable scene -> (m_reduced, tip_stiffness), is
    the 3D model's equation 2 (``rotorpillar.fem3d.reduction_from_scene``), needed
    when ``reduction.source = "fem3d"``; this layer never builds it.
    """
    closed = pillar_closed_forms(scene)
    red = resolve_reduction(scene, closed, fem3d_reduction)
    sys_ = reduced_system(scene, red["tip_mass"], red["tip_stiffness"])
    modes = linear_modes(sys_)
    ch = av.Characteristic(scene.drive.torque_at_zero, scene.drive.slope, scene.load.coefficient)
    c2e = scene.shaft.stiffness * scene.rotor.eccentricity
    resonances, drive = averaging_results(modes, ch, scene.rotor.eccentricity, c2e)
    x = modes.resonances[:2]
    system = {
        "tip_mass_total": sys_.tip_mass, "c0": sys_.c0, "b0": sys_.b0,
        "omega": [x[0].omega, x[1].omega],
        "omega3": modes.resonances[2].omega,
        "frequency_hz": [w / (2 * math.pi) for w in modes.omega],
        "modal_vectors": [list(r.shape) for r in x],
        "modal_masses": [r.modal_mass for r in modes.resonances],
        "forcing": [r.forcing for r in modes.resonances],
        "coupling": [r.coupling for r in modes.resonances],
        "two_n": [r.two_n for r in modes.resonances],
        "nu": [r.nu for r in modes.resonances],
        "f4": c2e,
    }
    result = AnalysisResult.from_json({"pillar": closed, "reduction": red, "system": system,
                                       "resonances": resonances, "drive": drive})
    return dataclasses.replace(result, paper_comparison=compare_with_paper(scene, result))
