"""An explicit adaptive run's steps are bounded below by its stability limit, and the
budget uses that bound (rotorpillar.reduced.integration.stability_step_count).

A stiff mode holds Dormand-Prince's step near the edge of its region of absolute
stability, |h lambda| <= 3.40, whatever the tolerance: Hairer & Wanner, *Solving
ODEs II*, IV.2 (the step-size control of an explicit method on a stiff problem
oscillates about the stability limit).  The references here are dp5's own step
counts on oscillators whose rates are known in closed form.
"""

import math

import numpy as np
import pytest

from rotorpillar.errors import InputError
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import no_motion
from rotorpillar.reduced.explicit_limit import spin_rate, stability_step_count
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.pillar_modes import PillarModes
from rotorpillar.reduced.rotor_models import modal_model


def machine(shaft_stiffness=4e5, shaft_damping=50.0, rotor_inertia=14.0):
    """A one-mode pillar (30 rad/s) with a 100 kg rotor on a shaft of ``shaft_stiffness``."""
    modes = PillarModes(np.array([30.0]), np.array([1e4]), np.array([1e4]), 1e4, "test")
    return modal_model(modes, 100.0, rotor_inertia, 1e-3, shaft_stiffness, shaft_damping, 1e3)


DRIVE = DriveSchedule.constant(500.0, 10.0, 0.0)


def dp5_steps(m, duration):
    run = simulate(m, DRIVE, no_motion(), duration, settings=Settings("dp5", rtol=1e-7))
    assert run.ok
    return run.stats.steps


@pytest.mark.parametrize("shaft_stiffness, shaft_damping", [(1e8, 1e6), (1e8, 1e7), (1e12, 1e9)])
def test_an_overdamped_shaft_holds_dp5_to_its_stability_limit(shaft_stiffness, shaft_damping):
    """An overdamped shaft's fast root, about -c/m (not sqrt(k/m)), sets the steps: on the
    negative real axis dp5's region reaches 3.31, so it takes the bound (3.40) to 1.3 times it
    (measured 1.03-1.21: the step control sits just inside the edge)."""
    m = machine(shaft_stiffness, shaft_damping)
    assert m.fastest_rate() == pytest.approx(shaft_damping / 100.0, rel=0.02)
    bound = stability_step_count(m, 0.2, "dp5", DRIVE)
    assert bound <= dp5_steps(m, 0.2) <= 1.3 * bound


@pytest.mark.parametrize("shaft_stiffness", [1e8, 1e12])
def test_a_lightly_damped_stiff_shaft_needs_more_than_the_bound(shaft_stiffness):
    """Its eigenvalue sits by the imaginary axis, where dp5's region is thin: the bound holds
    (it is a lower bound by construction) and dp5 takes 15-25 times it (measured 18.6-19.9)."""
    m = machine(shaft_stiffness)
    assert m.fastest_rate() == pytest.approx(math.sqrt(shaft_stiffness / 100.0), rel=0.05)
    bound = stability_step_count(m, 0.2, "dp5", DRIVE)
    assert 15 * bound <= dp5_steps(m, 0.2) <= 25 * bound


def test_a_light_rotor_holds_dp5_to_the_spin_rate():
    """The spin's equation I Omega' = M0 - s Omega relaxes at s / I: a rotor of 1e-5 kg m**2
    on a slope of 10 N m s makes it 1e6 1/s, far above the shaft's mode (63 rad/s); a real
    eigenvalue, so the bound is tight (measured 1.03)."""
    m = machine(rotor_inertia=1e-5)
    assert spin_rate(m, DRIVE) == pytest.approx(10.0 / 1e-5)
    bound = stability_step_count(m, 0.05, "dp5", DRIVE)
    assert bound <= dp5_steps(m, 0.05) <= 1.3 * bound


def test_the_budget_refuses_a_stiff_explicit_run_before_it_starts():
    """Over the budget by its stability bound alone: refused at once, naming the implicit way."""
    m = machine(1e12)
    with pytest.raises(InputError, match="stability limit"):
        simulate(m, DRIVE, no_motion(), 10.0, settings=Settings("dp5", max_steps=100_000))


def test_an_implicit_run_is_not_bound_by_it():
    assert stability_step_count(machine(1e12), 10.0, "Radau", DRIVE) == 0.0


def test_analyze_leaves_a_stiff_reaction_run_up_out_and_says_why():
    """paper with the stiffest, most damped shaft of the scene's range: dp5 would take
    ~1e10 steps for the shaft's overdamped root (c/m = 1e12 / 2000 kg); analyze keeps the
    reaction's statics and says why the run-up is missing instead of running for minutes."""
    from rotorpillar.reduced.band import excitation_band
    from rotorpillar.reduced.spatial_scene import drive_reaction_analysis
    from rotorpillar.scene.files import load_scene

    scene = load_scene("paper", ["shaft.stiffness=1e14", "shaft.damping=1e12"])
    top = excitation_band(scene.drive, scene.load, scene.converge).omega_max
    result = drive_reaction_analysis(scene, top)
    assert result.runup is None and result.runup_skipped and "not run" in result.runup_skipped
    assert result.tip_displacement != 0.0
    plain = drive_reaction_analysis(load_scene("paper"), top)
    assert plain.runup is not None and plain.runup_skipped is None
