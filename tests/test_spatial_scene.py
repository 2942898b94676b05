"""The spatial model on a scene: the Campbell diagram, three-component ground motion, energy,
which planes a scene needs (issue 26).

- **Two methods for the critical speeds**: on the undamped model, each critical speed of
  the Hermitian pencil K v = Omega**2 (M - i G) v lies where a tracked Campbell branch
  crosses the 1x line; the branches are sampled every 0.5 rad/s and the crossing found
  on the piecewise-linear branch, whose error is h**2 |f''| / 8 with frequencies nearly
  flat in Omega: 1e-4 relative.
- **Superposition of the ground's components**: with no unbalance and the speed held,
  the model is linear, so the run under El Centro's three components is the sum of the
  three runs under each alone; dp5 at rtol 1e-10 on each, checked at 1e-6 of the peak.
- **The horizontal pair turns with excitation.angle**: the ground along x, y at angle a
  is the rotation by a of the pair at 0 (exact arithmetic: 1e-12 of the peak).
- **Energy**: the work integrals the kernel carries (the motor with its reaction on the
  gondola, the couple unbalance and its counter-torque, dissipation, the ground) close
  the energy balance of a spatial run-up with a flexible tilt and a couple unbalance at
  the integrator's tolerance (relative residual 1e-5 at rtol 1e-9), and of a
  three-component El Centro (1e-4 at rtol 1e-8: the record's linear interpolation).
- **modal_model.planes = auto**: the paper's machine keeps the plane (ground in the
  plane, no couple unbalance, rotor at the top, nothing out of the plane responds,
  the first axial mode above the band); a couple unbalance, a second ground
  component or a rotor above the top make it spatial, and the reason says which.
"""

import dataclasses
import math

import numpy as np
import pytest

from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import no_motion
from rotorpillar.reduced.ground3d import scene_spatial_motion, spatial_ground_motion
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.spatial_linear import campbell, critical_speeds
from rotorpillar.reduced.spatial_model import spatial_model
from rotorpillar.reduced.spatial_scene import resolve_planes, scene_spatial_model, scene_spatial_modes
from rotorpillar.scene import load_scene, override

BAND = 180.0


def test_campbell_crossings_are_the_critical_speeds():
    s = load_scene("paper")
    shaft = dataclasses.replace(s.shaft, damping=0.0, tilt_stiffness=2e5)
    modes = scene_spatial_modes(s).below(BAND)
    m = spatial_model(modes, s.rotor, shaft, 0.0, damping_ratio=0.0)
    speeds = np.linspace(0.0, BAND, 361)
    d = campbell(m, speeds)
    crit = [c for c in critical_speeds(m) if c.speed < BAND * 0.95]
    assert len(crit) >= 5
    for c in crit:
        crossings = []
        for b in d.modes:
            g = np.asarray(b.frequency) - speeds
            for i in np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:])):
                crossings.append(speeds[i] - g[i] * (speeds[i + 1] - speeds[i]) / (g[i + 1] - g[i]))
        assert min(abs(x / c.speed - 1) for x in crossings) < 1e-4, c


def test_ground_components_superpose_and_turn():
    s = override(load_scene("paper"), ["excitation.kind=record", "excitation.components=3", "excitation.start=0"])
    motion = scene_spatial_motion(s.excitation)
    assert motion.count == 3 and [c.time_step for c in motion.components] == [0.01] * 3
    t = np.linspace(0.0, 20.0, 4001)
    turned = scene_spatial_motion(dataclasses.replace(s.excitation, angle=30.0)).evaluate(t)
    at_zero = motion.evaluate(t)
    a = math.radians(30.0)
    R = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    np.testing.assert_allclose(turned, np.einsum("ij,kjt->kit", R, at_zero), atol=1e-12 * np.max(np.abs(at_zero)))
    m = scene_spatial_model(s, BAND)
    m = dataclasses.replace(m, eccentricity=0.0, reaction=np.zeros(m.nz))
    v0 = np.zeros(m.n)
    v0[-1] = 50.0
    d = DriveSchedule.constant(0.0, 0.0, 0.0)
    st = Settings("dp5", rtol=1e-10, samples=801)

    def run(mo):
        r = simulate(m, d, mo, 8.0, None, v0, settings=st, prescribed_speed=True)
        assert r.ok
        return r.q[:, : m.nz]

    whole = run(motion)
    parts = sum(run(spatial_ground_motion([c], [dr])) for c, dr in zip(motion.components, motion.directions))
    assert np.max(np.abs(whole - parts)) < 1e-6 * np.max(np.abs(whole))
    # each direction moved the machine: the top in x and y (the horizontal records), the rotor
    # vertically (the vertical one; the pillar's first axial mode lies above the band)
    tip = {k: np.max(np.abs(whole @ m.outputs[k])) for k in ("tip_x", "tip_y", "rotor_z")}
    assert min(tip.values()) > 0


def test_energy_closes_with_reaction_couple_and_three_components():
    s = override(
        load_scene("paper"), ["rotor.couple_unbalance=0.05", "shaft.tilt_stiffness=2e6", "shaft.tilt_damping=100"]
    )
    m = scene_spatial_model(s, BAND)
    d = DriveSchedule.constant(s.drive.torque_at_zero, s.drive.slope, s.load.coefficient)
    run = simulate(m, d, no_motion(), 20.0, settings=Settings("dp5", rtol=1e-9))
    assert run.ok and run.energy_balance().relative_error < 1e-5
    assert abs(run.work[-1, 0]) > 0 and np.max(np.abs(run.q[:, : m.nz] @ m.outputs["rotor_pitch"])) > 0
    q = override(s, ["excitation.kind=record", "excitation.components=3", "excitation.start=0"])
    quake = simulate(m, d, scene_spatial_motion(q.excitation), 10.0, settings=Settings("dp5", rtol=1e-8))
    assert quake.ok and quake.energy_balance().relative_error < 1e-4


@pytest.mark.parametrize(
    "sets, planes, why",
    [
        ([], "planar", "planar: the ground moves in the rotor's plane only"),
        (["rotor.couple_unbalance=0.01"], "spatial", "couple unbalance"),
        (["excitation.kind=record", "excitation.components=2"], "spatial", "out of the rotor's plane"),
        (["rotor.height=0.5"], "spatial", "lever"),
        (["modal_model.planes=spatial"], "spatial", "as the scene states"),
    ],
)
def test_planes(sets, planes, why):
    s = override(load_scene("paper"), sets)
    choice = resolve_planes(s, BAND, scene_spatial_modes(s))
    assert choice.planes == planes and why in choice.reason
