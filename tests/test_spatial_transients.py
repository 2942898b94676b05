"""The transients on the spatial ROM (issue 26, items 2 and 7): `simulate --model modal` runs
its case on the spatial model where modal_model.planes resolves to spatial.

- **The planar restriction is today's run-up**: the spatial model restricted to the rotor's
  plane (planes="planar", b2 to the ground, no structural ratio, no motor reaction) on the
  planar ROM's own modes, run through the same case code (cases._run_on) as today's planar
  ROM, gives the same summary: peak tip, final speed, passage times, the speed it sticks at;
  and under El Centro from the operating speed, the same start and peaks.
  The two runs integrate the same packed arrays (tests/test_spatial.py checks them equal), so
  the states agree to round-off; the resonances come from two eigensolves (the planar X block,
  and the restriction's with the decoupled vertical beside it), equal to ~1e-13: every number
  is compared at 1e-9 (relative), far below any physical difference and far above round-off.
- **The drive's reaction in a run-up**: a rotor so heavy (J_C = 1e5 kg*m**2) that 10 s after
  the motor starts it still turns below 1 rad/s, far below the first resonance: the structure
  answers the motor's reaction quasi-statically (the step's transient has decayed as
  exp(-zeta omega t) ~ 1e-6 by then), so the top moves by M H**2 / (2 E I) with
  M = M0 - s Omega the motor's torque (the tip moment of a uniform clamped cantilever; pure
  bending: Timoshenko's shear adds nothing).  The ROM keeps the pillar's bending modes below
  the band (two in the rotor's plane), and the mode-displacement method misses what the
  omitted modes carry of a tip moment's static deflection: 1.3 % of it on `paper` (it falls
  to 0.1 %, the beam's own discretisation, with every mode kept, checked below): 2 % bounds
  it.  The planar ROM cannot receive the reaction: its top stays at the unbalance's own
  steady unbalance response at that speed (b2 to the ground: b2 e Omega over the tip's
  stiffness, 3 % of the reaction's), 5 % over it for the speed's slow rise; so the spatial run
  minus the planar one is the reaction's contribution, within 2 % and that response.
- **The CLI** (slow): `simulate paper --set modal_model.planes=spatial --case runup` runs end
  to end and its JSON names the spatial model and why.
"""

import dataclasses
import json
import math

import numpy as np
import pytest

from rotorpillar.reduced.excitation import no_motion
from rotorpillar.reduced.models import build_model
from rotorpillar.reduced.rotor_models import modal_model
from rotorpillar.reduced.spatial_beam import beam_spatial_modes
from rotorpillar.reduced.spatial_model import spatial_model
from rotorpillar.reduced.spatial_modes import BENDING_IN_PLANE
from rotorpillar.reduced.spatial_rotor import SpatialRotor
from rotorpillar.reduced.spatial_scene import scene_spatial_model, scene_spatial_modes, transient_model
from rotorpillar.scene import load_scene
from rotorpillar.transients.cases import _run_on, run_case

BEAM = ['modal_model.source="beam"', "simulate.threshold=false"]
#: the summaries' numbers agree at this (relative): see the module text
SAME = 1e-9


def _pair(scene, modes=3):
    """Today's planar ROM and the spatial model restricted to its plane, on the same beam modes."""
    g = dataclasses.replace(scene.gondola, roll_inertia=0.0, pitch_inertia=0.0, yaw_inertia=0.0)
    sm = beam_spatial_modes(scene.pillar, g, 6, "timoshenko", 40)
    r, sh = scene.rotor, scene.shaft
    old = modal_model(
        sm.planar().truncate(modes), r.mass, r.inertia, r.eccentricity, sh.stiffness, sh.damping, scene.pillar.damping
    )
    inplane = sm.select(sm.of_kind(BENDING_IN_PLANE)[:modes])
    new = spatial_model(
        inplane,
        r,
        sh,
        scene.pillar.damping,
        damping_ratio=0.0,
        damping_law="ground",
        planes="planar",
        drive_reaction=False,
    )
    return old, SpatialRotor.of(new)


def test_planar_restriction_runs_todays_el_centro():
    """The earthquake case too: the same operating speed (the exact torque balance on both), the
    same start on the steady whirl, the same peaks under El Centro in the rotor's plane."""
    from rotorpillar.reduced.models import scene_motion

    s = load_scene("paper", BEAM + ["excitation.kind=record", "excitation.record=elcentro", "excitation.start=1"])
    old, new = _pair(s)
    motion = scene_motion(s)
    a, b = (_run_on(s, "earthquake", m, motion, None) for m in (old, new))
    assert a.summary.ok and b.summary.ok
    assert b.initial_speed == pytest.approx(a.initial_speed, rel=SAME)
    for key in ("tip_x", "rotor_x", "rotor_y"):
        assert b.summary.max_abs[key] == pytest.approx(a.summary.max_abs[key], rel=SAME)
    assert b.summary.omega_final == pytest.approx(a.summary.omega_final, rel=SAME)


def test_earthquake_words_say_whether_the_motors_reaction_acts():
    """The run's ``excitation_in_model`` says the motor's reaction acts on the gondola only on
    a model that carries it (the planar restriction leaves it off: spatial_model's
    ``drive_reaction=False``)."""
    from rotorpillar.reduced.models import scene_motion
    from rotorpillar.transients.cases import spatial_excitation

    s = load_scene("paper", BEAM + ["excitation.kind=record", "excitation.record=elcentro"])
    _, off = _pair(s)
    on = SpatialRotor.of(dataclasses.replace(off.structure, reaction=np.ones_like(off.structure.reaction)))
    run = object()  # one component: the run comes back as it went in
    words_off, same = spatial_excitation(off, scene_motion(s), run)
    words_on, _ = spatial_excitation(on, scene_motion(s), run)
    assert same is run
    assert "reaction on the gondola acting" in words_on
    assert "reaction on the gondola acting" not in words_off
    assert "no motor reaction on the gondola" in words_off


@pytest.mark.parametrize(
    "name, expect",
    [("paper", "at_speed"), ("sommerfeld", "captured")],
)
def test_planar_restriction_runs_todays_runup(name, expect):
    s = load_scene(name, BEAM)
    old, new = _pair(s)
    a, b = (_run_on(s, "runup", m, no_motion(), None).summary for m in (old, new))
    assert a.ok and b.ok
    assert a.speed_state == b.speed_state == expect
    for key in ("tip_x", "rotor_x", "rotor_y"):
        assert b.max_abs[key] == pytest.approx(a.max_abs[key], rel=SAME)
    assert b.omega_final == pytest.approx(a.omega_final, rel=SAME)
    if expect == "captured":
        assert b.captured_at == pytest.approx(a.captured_at, rel=SAME)
        assert b.captured_resonance == pytest.approx(a.captured_resonance, rel=SAME)
    assert len(a.passages) == len(b.passages)
    for p, q in zip(a.passages, b.passages):
        assert (p.direction, p.crossed, p.time) == (q.direction, q.crossed, q.time)
        assert q.omega == pytest.approx(p.omega, rel=SAME)
    assert b.prediction.runup_speed == pytest.approx(a.prediction.runup_speed, rel=SAME)


#: the ROM's truncation of a tip moment's static deflection (1.3 % on paper) bounded: module text
TRUNCATION = 0.02


def test_runup_carries_the_drives_reaction():
    heavy = BEAM + ["rotor.inertia=1e5", "simulate.duration=12"]
    spatial = load_scene("paper", heavy + ["modal_model.planes=spatial"])
    planar = load_scene("paper", heavy + ["modal_model.planes=planar"])
    a, b = run_case(spatial, "runup", "modal", truncation=False), run_case(planar, "runup", "modal", truncation=False)
    assert isinstance(a.model, SpatialRotor) and a.planes.planes == "spatial"
    assert not isinstance(b.model, SpatialRotor) and b.planes.planes == "planar"
    p = spatial.pillar
    EI = p.youngs_modulus * math.pi / 64 * (p.outer_diameter**4 - p.inner_diameter**4)
    i = int(np.searchsorted(a.run.t, 10.0))
    W = float(a.run.Omega[i])
    assert W < 1.0  # far below the first resonance (~15 rad/s): quasi-static
    M = spatial.drive.torque_at_zero - spatial.drive.slope * W
    closed = M * p.height**2 / (2 * EI)
    tip_a = float(a.run.tip()[i])
    tip_b = float(np.interp(a.run.t[i], b.run.t, b.run.tip()))
    assert tip_a == pytest.approx(closed, rel=TRUNCATION)
    # the planar ROM: the unbalance's steady response alone (b2 to the ground pulls the top by
    # b2 e Omega over its stiffness), 5 % over it for the speed's slow rise
    unbalance = float(b.model.steady_amplitudes(W)["tip_x"])
    assert abs(tip_b) <= 1.05 * unbalance < 0.05 * closed
    assert abs(tip_a - tip_b - closed) <= TRUNCATION * closed + 1.05 * unbalance
    # the truncation is the modes': with every mode of the beam kept, the static tip is the closed form
    # to the beam's own discretisation (0.1 %)
    full = SpatialRotor.of(scene_spatial_model(spatial, 1e9, scene_spatial_modes(spatial)))
    tip_full = float(full.reaction_deflection(M)[:-1] @ full.structure.outputs["tip_x"])
    assert tip_full == pytest.approx(closed, rel=2e-3)
    assert abs(tip_a / closed - 1) > abs(tip_full / closed - 1)


@pytest.mark.slow
def test_cli_runup_on_the_spatial_rom(tmp_path, here):
    out = tmp_path / "out"
    # in this process (``here``): the command's files and exit are checked, not a start-up
    p = here("simulate", "paper", "--set", "modal_model.planes=spatial", "--case", "runup", "--out", out)
    assert p.returncode == 0, p.stderr
    run = json.loads((out / "simulate_runup_modal.json").read_text())
    assert run["model"] == "modal" and run["model_description"]["name"] == "spatial"
    assert run["planes"] == {
        "requested": "spatial",
        "planes": "spatial",
        "reason": "modal_model.planes = 'spatial' as the scene states",
    }
    # the summary a planar run has, for the report and the checks
    for key in ("ok", "omega_final", "max_abs", "passages", "speed_state", "prediction", "resonances"):
        assert key in run
    assert run["ok"] and run["max_abs"]["tip_x"] > 0
    assert "rotor_axial" in run["model_description"]["coordinates"]
    assert not any("runs the planar ROM" in w for w in run["warnings"])
    # its truncation estimate: the same run-up with the next bending mode in the rotor's plane
    t = run["truncation"]
    assert t["kind"] == "estimate" and t["modes_check"] == t["modes"] + 1
    assert t["omega_added"] > max(r["omega"] for r in run["resonances"] if r["direction"] == "X")


def test_auto_weighs_the_drives_reaction():
    """auto keeps paper's run-up planar (the reaction's static tip ~6 % of the unbalance response, at
    most REACTION_SHARE) and says how large the reaction is; with a tenth of the eccentricity the
    unbalance response is a tenth (the model is linear in e), the share ten times: spatial."""
    from rotorpillar.reduced.band import forcing_top
    from rotorpillar.reduced.spatial_scene import REACTION_SHARE, reaction_share

    shares = []
    e0 = load_scene("paper", BEAM).rotor.eccentricity
    for div in (1.0, 10.0):
        s = load_scene("paper", BEAM + [f"rotor.eccentricity={e0 / div!r}"])
        top = s.modal_model.band_factor * forcing_top(s.drive, s.load, s.sweep, "runup", None)
        planar, _ = build_model(s, "modal", top)
        choice, model = transient_model(s, "runup", top, planar)
        shares.append(reaction_share(s, planar, scene_spatial_modes(s))[0])
        assert "drive's reaction" in choice.reason
        assert (choice.planes == "spatial") == (shares[-1] > REACTION_SHARE) == (model is not None)
    assert shares[0] < REACTION_SHARE < shares[1]
    # the tip amplitude is linear in e: the share scales by exactly 10 (round-off of the steady solves)
    assert shares[1] == pytest.approx(10 * shares[0], rel=1e-9)
    # a sweep stays planar whatever the scene asks (its analysis is the planar averaging's)
    s = load_scene("paper", BEAM + ["modal_model.planes=spatial"])
    planar, _ = build_model(s, "modal", 180.0)
    choice, model = transient_model(s, "sweep", 180.0, planar)
    assert model is None and choice.planes == "planar" and "sweep" in choice.reason


def test_the_grounds_motion_in_the_rotors_plane():
    """The series a multi-component run writes as ground_x: each component times its direction's
    x; at excitation.angle = 90 deg the first component runs along the spin axis and the second
    along -x, so the rotor's plane sees minus the second record, exactly."""
    from rotorpillar.reduced.ground3d import scene_spatial_motion
    from rotorpillar.transients.cases import in_rotor_plane

    s = load_scene("paper", ["excitation.kind=record", "excitation.components=2", "excitation.angle=90"])
    motion = scene_spatial_motion(s.excitation)
    x = in_rotor_plane(motion)
    second = motion.components[1]
    scale = np.max(np.abs(second.acceleration))
    # cos(90 deg) = 6e-17 of the first component leaks in: round-off
    np.testing.assert_allclose(x.acceleration, -second.acceleration, rtol=0, atol=1e-15 * scale)
    np.testing.assert_allclose(
        x.displacement, -second.displacement, rtol=0, atol=1e-15 * np.max(np.abs(second.displacement))
    )


def test_steady_torque_over_a_grid_is_the_speed_by_speed_solve():
    """SpatialRotor.steady_torque solves its speeds stacked (spatial_response.steady_states, in
    chunks of 256): the same numbers as the operator built and solved at each speed alone, the
    way the module text's equation reads (written out here, not the package's).  Both are the
    same LAPACK solves on the same entries; only the dot products' summation order may differ,
    so 1e-12 of the largest torque.  On the spatial model with the gyroscopic and the couple
    unbalance on (a couple unbalance of 50 kg*m**2 set, paper has none), over a grid of 600
    speeds across the first resonances (three chunks)."""
    from rotorpillar.reduced.spatial_response import steady_state, unbalance_response

    s = load_scene("paper", BEAM + ["rotor.couple_unbalance=50"])
    model = SpatialRotor.of(scene_spatial_model(s, 1e9))
    m = model.structure
    assert m.couple_unbalance > 0 and np.any(m.gyroscopic)
    W = np.linspace(1.0, 120.0, 600)
    dx, dv = m.shaft
    bc, bs = m.couple
    by_speed = []
    for w in W:
        D = m.stiffness_full() - w**2 * m.mass + 1j * w * (m.damping + w * m.gyroscopic)
        f = m.shaft_stiffness * m.eccentricity * (dx - 1j * dv) + m.couple_unbalance * w**2 * (bc - 1j * bs)
        Z = np.linalg.solve(D, f)
        torque = m.shaft_stiffness * m.eccentricity * ((dv @ Z).real + (dx @ Z).imag) / 2
        by_speed.append(torque + m.couple_unbalance * w**2 * ((bc @ Z).imag + (bs @ Z).real) / 2)
    stacked = model.steady_torque(W)
    assert stacked.shape == W.shape
    assert np.max(np.abs(stacked - by_speed)) <= 1e-12 * np.max(np.abs(by_speed))
    assert float(model.steady_torque(W[300])) == pytest.approx(by_speed[300], rel=1e-12)
    # the Bode curves read the same stacked states: each speed's is its own solve's
    r = unbalance_response(m, W[::50])
    tip = [abs(steady_state(m, w) @ m.outputs["tip_x"]) for w in W[::50]]
    assert np.allclose(r.curve("tip_x").amplitude, tip, rtol=1e-12, atol=0)


def test_operating_speed_is_solved_once_per_model_and_drive(monkeypatch):
    """An earthquake run asks for its operating speed three times (preflight, warm-up, run), on
    models built anew each time: stationary_exact gives an equal model's answer again
    (stationary._MEMO) and solves any other.  The memo's answer is the solve's (the same
    records); a model that differs in one field (the eccentricity) or another drive is solved."""
    from rotorpillar.reduced import stationary
    from rotorpillar.transients.cases import case_model

    monkeypatch.setattr(stationary, "_MEMO", type(stationary._MEMO)())
    solved = []
    solve = stationary._stationary_exact
    monkeypatch.setattr(stationary, "_stationary_exact", lambda *a: solved.append(a) or solve(*a))
    s = load_scene("paper", BEAM)
    d, k = s.drive, s.load.coefficient

    def model(scene):
        return case_model(scene, "earthquake", "modal").model

    first = stationary.stationary_exact(model(s), d.torque_at_zero, d.slope, k)
    again = stationary.operating_speed(model(s), d.torque_at_zero, d.slope, k)
    assert len(solved) == 1 and first == solve(model(s), d.torque_at_zero, d.slope, k, None, 3000)
    assert again == max(x.omega for x in first if x.stable)
    other = load_scene("paper", BEAM + [f"rotor.eccentricity={2 * s.rotor.eccentricity!r}"])
    assert stationary.stationary_exact(model(other), d.torque_at_zero, d.slope, k) != first
    stationary.stationary_exact(model(s), 1.01 * d.torque_at_zero, d.slope, k)
    assert len(solved) == 3
