"""The 3D full order's step follows the band (issue 15.8), its checks (19.4), and mpirun (15.9).

References and tolerances:

- stiff shaft (c2 = 1e10 N/m, e = 0, b2 = 0: the rotor's bounce on its shaft at
  2,500 rad/s, far above El Centro's band of 62 rad/s): the run at the band's
  step (generalized-alpha, rho_inf 0.8, 2.44 ms) against Newmark at a quarter of
  it (the average acceleration's error falls as h**2: 16 x smaller; issue 30: it
  was a sixth, 1.8 s more CPU; on the 8 x 6 tube Newmark's peaks at h/4, h/6,
  h/12 differed in the ratio 1.63, h**2's 1.67, so the shaft's mode, 4 steps a
  period at h/4 and barely struck with e = 0 and b2 = 0, does not reach the
  peak, and the reference's own error was 4.2e-5, 17 x below the band step's
  7.0e-4), peak tip within 0.5 % (the issue's target; measured 0.08 % on the
  scene's 8 x 10 mesh over 15 s).  Issue 30: on an 8 x 4 tube, not 8 x 6 (CPU
  4.2 -> 2.8 s): the band step's peak -5.7e-4, -6.0e-4, -6.2e-4 from the
  reference's at h/4, h/6, h/12 (the reference at h/4 within 4.8e-5 of h/12's,
  12 x below), the peak at the same 3.12 s;
  the step does not depend on c2 (the same as with the scene's soft shaft);
- second order: the tip, the rotor and its speed at h, h/2, h/4, h/8 (a smooth
  pulse; the rotor free on its shaft), the fitted log-log slope of the
  differences of successive steps, |x(h) - x(h/2)| at h, h/2, h/4, in [1.8, 2.2]
  (with an error C h**p the difference is C h**p (1 - 2**-p): the same slope p,
  no reference run; second order: 2, measured 1.93-2.00; the coarsest step sits
  at 28 steps per period of the unbalance's rotation).  Issue 30: the ladder was
  400, 800, 1600 steps against 6400 (slopes 1.91-2.05), then 200, 400, 800
  against 3200 (1.90-2.05; 4,600 steps), now 200 ... 1600 (3,000 steps);
  400, 800, 1600 against 3200 would bias it (2.06-2.21);
- a step that swallows the record: ok false, exit 4, the named checks;
- mpirun -n 2 against the serial run: the same numbers to 1e-7 (MUMPS on two
  ranks orders its sums differently; the run's own error is 1e-3); simulate and compare
  under one mpirun (issue 30: the test's CPU 37.7 -> 20.6 s, loaded machine).
"""

from __future__ import annotations

import json
import math
import os
import shutil

import numpy as np
import pytest
from conftest import cli_here

from rotorpillar.scene import load_scene

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(__import__("importlib").util.find_spec("dolfinx") is None, reason="needs dolfinx"),
]

COARSE = ["mesh.elements_around=8", "mesh.elements_along=6", "mesh.degree=2"]
STIFF = ["excitation.kind=record", "shaft.stiffness=1e10", "rotor.eccentricity=0", "shaft.damping=0"]


def test_a_stiff_shaft_takes_the_bands_step_and_keeps_the_peak():
    from rotorpillar.fem3d.full_order import simulate_fem3d
    from rotorpillar.reduced.excitation import load_record

    motion = load_record("elcentro", start=0.5)
    tube = COARSE + ["mesh.elements_along=4"]  # 8 x 4 (the module text, issue 30)
    stiff = load_scene("paper", tube + STIFF)
    soft = load_scene("paper", tube + STIFF[:1] + STIFF[2:])
    # 4 s of the record from 0.5 s: the tip peaks at 3.12 s (over 5 s the same peak), and the
    # fine reference takes 4 x 1640 steps instead of 6 x 2050; peak error measured -7.0e-4
    # against h/4, -7.3e-4 against h/6, -7.4e-4 against h/12 (-9.4e-4 over 5 s) on 8 x 6; on this
    # 8 x 4 tube -5.7e-4 against h/4
    r = simulate_fem3d(stiff, "earthquake", motion=motion, duration=4.0, samples=401)
    assert r.ok, r.failed_checks
    h = r.integrator.time_step
    rule = r.integrator.step_rule
    assert rule is not None
    assert rule.scheme == "generalized_alpha"
    assert rule.spectral_radius_infinity == pytest.approx(0.8, abs=1e-3)
    assert rule.forcing == {"ground_motion_band": pytest.approx(motion.band())}
    assert rule.band_edge == pytest.approx(2.0 * motion.band())
    assert math.sqrt(1e10 / 1600.0) * h > 5  # the shaft's mode is not resolved
    from rotorpillar.fem3d.full_order_plan import case_setup, step_rule

    mo, drive, _, W0, _ = case_setup(soft, "earthquake", motion, None, 4.0, None)
    assert step_rule(soft, drive, mo, W0).time_step == pytest.approx(rule.time_step, rel=1e-12)
    fine = load_scene("paper", tube + STIFF + ["full_order.integrator=newmark"])
    f = simulate_fem3d(fine, "earthquake", motion=motion, duration=4.0, time_step=h / 4, samples=401)
    assert r.max_abs["tip_x"] == pytest.approx(f.max_abs["tip_x"], rel=5e-3)
    assert r.integrator.factorisations == 1


@pytest.mark.parametrize(
    "eccentricity, start, T, keys",
    [
        (0.0, 0.5, 1.0, ("tip_x", "rotor_x")),
        (0.002, 0.0, 0.5, ("rotor_x", "Omega")),
    ],
    ids=["ground-only", "whirl-and-spin"],
)
def test_the_3d_generalized_alpha_is_second_order(eccentricity, start, T, keys):
    """ground-only: the pulse starts where its acceleration is zero (a_g continuous), so
    the tube is not struck; whirl-and-spin: the rotor whirls from t = 0 and its spin is
    free, so the Newton-closed coupling is in every step (the tip there carries the
    tube's high modes, struck by the whirl's force at t = 0 and not yet resolved at these
    steps: the rotor and its speed are the measures)."""
    from rotorpillar.fem3d.full_order import simulate_fem3d
    from rotorpillar.reduced.excitation import paper_pulse

    scene = load_scene("paper", COARSE + ["mesh.elements_along=4", f"rotor.eccentricity={eccentricity}"])
    motion = paper_pulse(0.05, math.pi, start, 10.0)
    runs = {
        n: simulate_fem3d(
            scene, "earthquake", motion=motion, duration=T, time_step=T / n, samples=201, initial_speed=89.0
        )
        for n in (200, 400, 800, 1600)
    }
    assert runs[200].integrator.method == "generalized_alpha"
    hs = [T / n for n in (200, 400, 800)]
    for key in keys:
        diffs = [np.max(np.abs(getattr(runs[n], key) - getattr(runs[2 * n], key))) for n in (200, 400, 800)]
        s = float(np.polyfit(np.log(hs), np.log(diffs), 1)[0])
        assert 1.8 <= s <= 2.2, (key, diffs, s)


def test_a_step_that_swallows_the_record_is_not_a_success(tmp_path):
    p = cli_here(
        "simulate",
        "paper",
        "--model",
        "fem3d",
        "--case",
        "earthquake",
        "--out",
        tmp_path,
        "--set",
        "excitation.kind=record",
        "--set",
        # the range's top (10 s), over a 9 s run (the ground moves from 5 s): one step for it all, far coarser
        # than the record's 0.02 s samples
        "full_order.time_step=10",
        "--set",
        "full_order.earthquake_duration=9",
        "--set",
        "full_order.elements_along=4",
    )
    assert p.returncode == 4, p.stderr
    doc = json.loads((tmp_path / "simulate.json").read_text())
    assert doc["ok"] is False
    names = {c.split(":")[0] for c in doc["failed_checks"]}
    assert {"step_accuracy", "step_swallows_run", "step_swallows_ground_motion"} <= names
    assert doc["integrator"]["step_rule"]["source"] == "full_order.time_step"


def mpirun_prefix():
    exe = shutil.which("mpirun")
    if exe is None:
        pytest.skip("mpirun not installed")
    env = dict(os.environ)
    if os.geteuid() == 0:  # Open MPI refuses root unless told
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return [exe, "-n", "2"], env


#: both commands' settings: 0.5 s of the record from its start (issue 30: it was 1.5 s, and
#: simulate's 0.5 s alone): 297 steps of the 3D run, every number nonzero (simulate: tip 4.1e-5 m,
#: energy change 5.1e-3 J; compare: peaks 4.6e-5 and 4.1e-5 m, the ROM's tip history error 0.38);
#: the two ranks agreed to 1e-10 there as over 1.5 s
SHORT = [
    "--set",
    "excitation.kind=record",
    "--set",
    "excitation.start=0",
    "--set",
    "full_order.earthquake_duration=0.5",
    "--set",
    "full_order.elements_around=8",
    "--set",
    "full_order.elements_along=4",
    "--json",
]


def numbers(doc: dict) -> dict:
    """The JSON's numbers that the physics sets (not the timings)."""
    return {
        "tip": doc["max_abs"]["tip_x"],
        "tip_abs": doc["max_abs"]["tip_x_absolute"],
        "rotor_x": doc["max_abs"]["rotor_x"],
        "omega_final": doc["omega_final"],
        "energy_change": doc["energy_balance"]["energy_change"],
        "steps": doc["integrator"]["steps"],
    }


#: what each rank runs under one mpirun (test_two_ranks_give_the_serial_numbers): the CLI's
#: ``main`` (``python -m rotorpillar`` is ``sys.exit(main())``) once per command, the rank's
#: stdout and stderr (the file descriptors: Python's and the libraries' writes) to its own
#: files per command, the exit codes to a JSON file per rank
RANKS = """
import json, os, sys
from mpi4py import MPI
from rotorpillar.cli import main
out, runs = sys.argv[1], json.loads(sys.argv[2])
rank, codes = MPI.COMM_WORLD.rank, {}
for name, argv in runs.items():
    saved = [os.dup(1), os.dup(2)]
    for fd, kind in ((1, "out"), (2, "err")):
        f = os.open(os.path.join(out, f"{name}.{rank}.{kind}"), os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
        os.dup2(f, fd)
        os.close(f)
    try:
        codes[name] = main(argv)
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        for fd, old in zip((1, 2), saved):
            os.dup2(old, fd)
            os.close(old)
with open(os.path.join(out, f"codes.{rank}.json"), "w") as f:
    json.dump(codes, f)
"""


@pytest.mark.mpi
def test_two_ranks_give_the_serial_numbers(tmp_path):
    """simulate (the 3D run alone) and compare (the ROM and the 3D run), serially in this
    process (conftest.cli_here) and on two ranks under one mpirun (issue 30: one launch for
    both commands, not one each: the ranks' start-up, imports and compiled forms once)."""
    import subprocess
    import sys

    prefix, env = mpirun_prefix()
    commands = {
        "simulate": ["--model", "fem3d", "--case", "earthquake"],
        # the ROM's 3D modes on a 16 x 4 tube, not the scene's 64 x 10 (issue 30): two ranks
        # give one rank's numbers on any mesh, and the serial run computes these modes (the
        # ranks read them from the cache) in 1 s of CPU instead of 6
        "compare": ["--case", "earthquake", "--set", "mesh.elements_around=16", "--set", "mesh.elements_along=4"],
    }
    two = tmp_path / "two"
    two.mkdir()
    runs = {c: [c, "paper", *SHORT, *args, "--out", str(two / c)] for c, args in commands.items()}
    serial = {c: cli_here(*argv[:-1], tmp_path / "one" / c) for c, argv in runs.items()}
    p = subprocess.run(
        [*prefix, sys.executable, "-c", RANKS, str(two), json.dumps(runs)], capture_output=True, text=True, env=env
    )
    assert p.returncode == 0, p.stderr
    for rank in (0, 1):
        assert json.loads((two / f"codes.{rank}.json").read_text()) == {c: 0 for c in runs}
    for command, p1 in serial.items():
        assert p1.returncode == 0, p1.stderr
        assert (two / f"{command}.1.out").read_text() == ""  # rank 0 alone prints: one document
        a, b = json.loads(p1.stdout), json.loads((two / f"{command}.0.out").read_text())
        if command == "simulate":
            na, nb = numbers(a), numbers(b)
        else:
            na = {m: a["per_model"][m]["peak_tip_relative"] for m in a["models_run"]}
            nb = {m: b["per_model"][m]["peak_tip_relative"] for m in b["models_run"]}
            na["error"] = a["errors"]["modal"]["tip_history_error"]
            nb["error"] = b["errors"]["modal"]["tip_history_error"]
            run = json.loads((two / command / "compare_earthquake_fem3d.json").read_text())  # compare_<case>_<model>
            assert run["ok"] is True
        assert set(na) == set(nb)
        for k in na:
            assert nb[k] == pytest.approx(na[k], rel=1e-7, abs=1e-12), (command, k)
        # rank 0 alone reports (the test before counted simulate's first line in both ranks' stderr)
        assert f"[rotorpillar] {command} " in (two / f"{command}.0.err").read_text()
        assert "[rotorpillar]" not in (two / f"{command}.1.err").read_text()


@pytest.mark.parametrize("spatial", [False, True], ids=["planar", "spatial"])
def test_the_mass_product_steps_as_the_stiffness_product(monkeypatch, spatial):
    """Each step's one product is M u1 on M's nonzeros, K u1 from the step's equation; the
    stepping before took K u1 by the product and M u1 from the equation.  The same run both
    ways (planar: today's compare; spatial: the structural ratio's low-rank term, the motor's
    reaction and its static start) agrees to 1e-8 of each history's largest value.  Measured:
    3e-9 on the tip (8e-13 m: the tip moves 0.3 mm here, the rotor whirls 2 mm), the
    problem's own rounding: a stepping that takes both products differs from the
    stepping before by 1.8e-9 and from this one by 1.2e-9; the spin's histories agree to
    the bit, the energy to 1e-14.  The run's own error is 1e-3."""
    import functools

    from rotorpillar.fem3d import full_order
    from rotorpillar.fem3d.full_order import simulate_fem3d
    from rotorpillar.fem3d.full_order_loop import integrate
    from rotorpillar.reduced.excitation import load_record

    scene = load_scene("paper", COARSE + ["mesh.elements_along=4"])
    motion = load_record("elcentro", start=0.2)
    kw = dict(motion=motion, duration=1.5, samples=2001, initial_speed=89.0)
    if spatial:
        kw.update(damping_law="gondola", damping_ratio=0.02, drive_reaction=True)
    runs = [simulate_fem3d(scene, "earthquake", **kw)]
    monkeypatch.setattr(full_order, "integrate", functools.partial(integrate, mass_product=False))
    runs.append(simulate_fem3d(scene, "earthquake", **kw))
    new, old = runs
    assert new.integrator.steps == old.integrator.steps > 800
    for key in ("tip_x", "rotor_x", "rotor_y", "Omega", "theta", "energy"):
        a, b = getattr(new, key), getattr(old, key)
        assert np.max(np.abs(a - b)) <= 1e-8 * np.max(np.abs(b)), key
    # the peaks likewise; the tip's y and the like are round-off themselves (1e-12 m): against
    # the rotor's 2 mm whirl
    scale = old.max_abs["rotor_x"]
    for key, value in old.max_abs.items():
        assert new.max_abs[key] == pytest.approx(value, rel=1e-8, abs=1e-8 * scale), key
