"""The full-order beam model, the base-forcing warning and the comparison record.

References and tolerances:

- beam static limit: a ground acceleration ramped smoothly (half cosine over
  3 s, ~15 periods of the first mode) to a0 and held, the rotor without
  eccentricity at rest: the tip's final X relative to the ground equals the
  closed form of a Timoshenko cantilever under its own inertia load
  w = -rho A a0 and the tip load P = -(m* + m_C) a0:
  w L^4/(8 EI) + w L^2/(2 kappa G A) + P L^3/(3 EI) + P L/(kappa G A)
  (independent of the finite elements).  Tolerance 2e-3: the ramp's residual
  oscillation, damped by b1 and b2 over the 12 s (10 elements are exact for
  the static cantilever to ~1e-6).  Integrated by dp5 here: Newmark's Newton
  reports failure on this zero-drive, prescribed-speed start (noted, not
  this test's subject); the beam's cases below run Newmark.
- energy balance: Newmark's energy identity is exact for the linear part; the
  unbalance coupling leaves an O(h**2) residual, measured 5e-5 (41 s) and
  1.1e-4 (12 s: a smaller work scale) at 40 steps per forcing period:
  tolerance 3e-4.
- beam against the modal ROM on the same case: the ROM keeps 2 modes of a
  40-element beam, the full order has every mode of a 10-element one; the
  difference (measured 0.4 %) is truncation and discretisation: tolerance 2 %.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from rotorpillar import records
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import GroundMotion
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.models import build_model
from rotorpillar.reduced.pillar_modes import beam_properties
from rotorpillar.scene import load_scene


def ramp_motion(a0: float, ramp: float, end: float, dt: float = 1e-3) -> GroundMotion:
    t = np.arange(0.0, end + dt / 2, dt)
    a = np.where(t < ramp, 0.5 * a0 * (1 - np.cos(math.pi * t / ramp)), a0)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)])
    d = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)])
    return GroundMotion("record", 0.0, 0.0, 0.0, float(t[-1]), dt, d, v, a, name="ramp")


def test_beam_static_limit_against_the_cantilever_closed_form():
    scene = load_scene("paper", ["rotor.eccentricity=0"])
    model, info = build_model(scene, "beam")
    assert info.elements == scene.full_order.beam_elements and model.n == info.dofs
    a0 = 0.5
    motion = ramp_motion(a0, 3.0, 12.0)
    run = simulate(
        model,
        DriveSchedule.constant(0.0, 0.0, 0.0),
        motion,
        12.0,
        settings=Settings("dp5", rtol=1e-8, samples=1201),
        prescribed_speed=True,
    )
    bp = beam_properties(scene.pillar)
    L, EI, kGA = bp.length, bp.youngs_modulus * bp.second_moment, bp.shear_coefficient * bp.shear_modulus * bp.area
    w, P = -bp.density * bp.area * a0, -(scene.gondola.mass + scene.rotor.mass) * a0
    ref = w * L**4 / (8 * EI) + w * L**2 / (2 * kGA) + P * L**3 / (3 * EI) + P * L / kGA
    last = run.t >= run.t[-1] - 1.0
    assert np.mean(run.tip()[last]) == pytest.approx(ref, rel=2e-3)
    assert run.ok and run.energy_balance().relative_error < 1e-5


@pytest.mark.parametrize("case", ["earthquake", "runup"])
def test_beam_case_energy_and_against_the_rom(case):
    from rotorpillar.transients.cases import run_case

    # the ROM on the beam's own modes: the full-order beam is then its unreduced model
    scene = load_scene(
        "paper",
        [
            "excitation.kind=record",
            "simulate.earthquake_duration=12",
            "simulate.duration=12",
            "modal_model.source=beam",
        ],
    )
    beam = run_case(scene, case, "beam")
    rom = run_case(scene, case, "modal", truncation=False)
    assert beam.run.stats.method == scene.full_order.beam_integrator
    assert beam.summary.ok and beam.summary.energy_balance.relative_error < 3e-4
    assert rom.summary.energy_balance.relative_error < 1e-4
    tip = np.interp(rom.run.t, beam.run.t, beam.run.tip())
    assert np.max(np.abs(rom.run.tip() - tip)) / np.max(np.abs(tip)) < 2e-2
    assert beam.summary.omega_final == pytest.approx(rom.summary.omega_final, rel=1e-5)


def test_published_forcing_warning_threshold():
    from rotorpillar.reduced.base_forcing import AMPLIFICATION_LIMIT, published_forcing_warning

    c1 = 9.6e6
    assert published_forcing_warning(c1, 0.4e6) is None  # the paper scene: 1.083
    assert published_forcing_warning(c1, 5e6)  # paper-stiff: 2.04
    c2_edge = (AMPLIFICATION_LIMIT - 1) * c1 / 2
    assert published_forcing_warning(c1, 0.99 * c2_edge) is None
    assert "1.1" in published_forcing_warning(c1, 1.01 * c2_edge)


def test_compare_result_round_trip():
    from rotorpillar.reduced.excitation import paper_pulse
    from rotorpillar.transients.compare import (
        ComparedModel,
        CompareResult,
        CompareWindow,
        ModelErrors,
        ResponseSpectrum,
        SpectralMode,
        reference_of,
    )

    def model(dofs):
        return ComparedModel(1e-3, 1.1e-3, 2e-3, 80.0, 0.5, 1.0, dofs, True, (), None, "a.json", "a.npz")

    r = CompareResult(
        case="earthquake",
        models_run=("modal", "fem3d"),
        reference=reference_of(("modal", "fem3d")),
        excitation=paper_pulse().sizes(),
        per_model={"modal": model(5), "fem3d": model(3033)},
        errors={"modal": ModelErrors(0.0066, 0.01, 0.0, 0.005, 0.4, 1e-4, -1e-5, "history", "in phase")},
        cost_ratio={"modal": 0.03, "fem3d": 1.0},
        chart="compare_earthquake.png",
        window=CompareWindow(0.0, 15.0, 15.0, "own"),
        spectrum=ResponseSpectrum(
            (0.1, 1.0), (1.0, 2.0), 0.05, (0.25,), 0.1, None, (SpectralMode(1, 0.25, 0.08, 1.39, 0.08, 0.11),), ""
        ),
    )
    doc = json.loads(json.dumps(records.to_builtins(r)))
    assert records.convert(doc, CompareResult) == r and records.to_builtins(records.convert(doc, CompareResult)) == doc
    assert r.reference == "fem3d" and reference_of(("paper", "beam", "modal")) == "beam"
    no_spec = records.convert({**doc, "spectrum": None}, CompareResult)
    assert "spectrum" not in records.to_builtins(no_spec)
