"""The integrators' known properties, each against its textbook statement.

Sources: Hughes, *The Finite Element Method* (2000), ch. 9; Chung & Hulbert
(1993), J. Appl. Mech. 60:371; Hairer, Norsett & Wanner, *Solving ODEs I*.

- central difference on an undamped oscillator is stable for h*omega < 2
  and grows without bound beyond (Hughes 9.3): at 0.95 x the limit the
  amplitude stays within 1/sqrt(1 - (h w/2)**2) x x0, at 1.05 x it exceeds
  1e3 x0 within 400 steps;
- Newmark average acceleration conserves the energy of an undamped linear
  oscillator exactly (to round-off, 1e-12 over 2000 steps) and lengthens its
  period: omega_num h = 2 arctan(omega h / 2) (measured from the phase of the
  last cycles: 1e-6 relative);
- generalized-alpha follows Chung & Hulbert's one-step amplification matrix
  exactly (1e-10, or 100 (w h)**2 eps for stiff steps), and its spectral radius at omega h -> infinity is rho_inf (1e-3);
- the compiled Dormand-Prince reproduces scipy's RK45 (same tableau, same
  step control): the same number of accepted steps within 2 % and the same
  answer within their tolerance on a run-up;
- the batch loop gives, run by run, the same answers as single runs (1e-12);
- the batch on several threads gives bit for bit the serial batch (each run
  is the same sequence of floating-point operations, whichever thread runs it).
"""

import math
from pathlib import Path

import numpy as np
import pytest

from rotorpillar.reduced.batch import simulate_batch
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import no_motion
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.pillar_modes import PillarModes
from rotorpillar.reduced.rotor_models import modal_model, paper_model
from rotorpillar.reduced.system import paper_example

IDLE = DriveSchedule.constant(0.0, 0.0, 0.0)


def oscillator(w=30.0, m=1000.0, c=0.0):
    modes = PillarModes(np.array([w]), np.array([m]), np.array([m]), m, "test")
    return modal_model(modes, 1.0, 1.0, 0.0, 0.0, 0.0, c)


def start(model, x0=0.01):
    q0 = np.zeros(model.n)
    q0[0] = x0
    return q0


@pytest.mark.parametrize("factor, stable", [(0.95, True), (1.05, False)])
def test_central_difference_stability_limit(factor, stable):
    w = 30.0
    model = oscillator(w)
    h = factor * 2.0 / w
    run = simulate(
        model,
        IDLE,
        no_motion(),
        400 * h,
        start(model),
        settings=Settings("central_difference", time_step=h, samples=401),
        speed_scale=1.0,
    )
    peak = np.nanmax(run.peak[:, 0]) if run.ok else math.inf
    if stable:
        assert peak <= 0.01 / math.sqrt(1 - (h * w / 2) ** 2) * (1 + 1e-9)
    else:
        assert (not run.ok) or peak > 1e3 * 0.01


def test_newmark_conserves_energy_and_lengthens_the_period():
    w, m = 30.0, 1000.0
    model = oscillator(w, m)
    h = 0.02  # w h = 0.6: about 10 steps per period
    n = 2000
    run = simulate(
        model,
        IDLE,
        no_motion(),
        n * h,
        start(model),
        settings=Settings("newmark", time_step=h, samples=n + 1),
        speed_scale=1.0,
    )
    E = 0.5 * m * run.v[:, 0] ** 2 + 0.5 * m * w**2 * run.q[:, 0] ** 2
    assert np.max(np.abs(E / E[0] - 1)) < 1e-12
    w_num = 2 * math.atan(w * h / 2) / h
    # the numerical solution is exactly x0 cos(w_num t) at the steps
    assert np.max(np.abs(run.q[:, 0] - 0.01 * np.cos(w_num * run.t))) < 1e-6 * 0.01
    assert w_num < w


def amplification(wh, am, af, beta, gamma):
    """One step of generalized-alpha on x'' = -w**2 x, h = 1, as Chung &
    Hulbert write it: (x, v, a)_{n+1} = A (x, v, a)_n."""
    w2 = wh**2
    lhs = np.array([[(1 - af) * w2, 0.0, 1 - am], [1.0, 0.0, -beta], [0.0, 1.0, -gamma]])
    rhs = np.array([[-af * w2, 0.0, -am], [1.0, 1.0, 0.5 - beta], [0.0, 1.0, 1 - gamma]])
    return np.linalg.solve(lhs, rhs)


@pytest.mark.parametrize("wh", [0.5, 1e4])
def test_generalized_alpha_follows_chung_hulbert(wh):
    rho = 0.8
    am, af = (2 * rho - 1) / (rho + 1), rho / (rho + 1)
    gamma, beta = 0.5 - am + af, 0.25 * (1 - am + af) ** 2
    A = amplification(wh, am, af, beta, gamma)
    # spectral radius -> rho_inf at infinite frequency (a triple root there:
    # it converges as (w h)**(-2/3), hence the very large w h)
    A_inf = amplification(1e9, am, af, beta, gamma)
    assert max(abs(np.linalg.eigvals(A_inf))) == pytest.approx(rho, abs=1e-3)
    model = oscillator(wh)
    n = 40
    run = simulate(
        model,
        IDLE,
        no_motion(),
        float(n),
        start(model),
        settings=Settings("generalized_alpha", time_step=1.0, samples=n + 1, rho_inf=rho),
        speed_scale=1.0,
    )
    y = np.array([0.01, 0.0, -(wh**2) * 0.01])
    expect = [y[0]]
    for _ in range(n):
        y = A @ y
        expect.append(y[0])
    # round-off grows with the conditioning of the step, ~ (w h)**2 eps
    tol = max(1e-10, 100 * wh**2 * np.finfo(float).eps)
    assert np.allclose(run.q[:, 0], expect, rtol=tol, atol=1e-12 * 0.01)


def test_dp5_reproduces_scipy_rk45():
    model = paper_model(paper_example())
    drive = DriveSchedule.constant(5100.0, 12.0, 0.5)
    st = dict(rtol=1e-8, samples=401, wrap_angle=False)
    ours = simulate(model, drive, no_motion(), 10.0, settings=Settings("dp5", **st))
    ref = simulate(model, drive, no_motion(), 10.0, settings=Settings("RK45", **st))
    tight = simulate(model, drive, no_motion(), 10.0, settings=Settings("dp5", rtol=1e-12, samples=401))
    # scipy counts 6 evaluations per step, plus the start
    assert ours.stats.nfev == pytest.approx(ref.stats.nfev, rel=0.02)
    e_ours = np.max(np.abs(ours.tip() - tight.tip()))
    e_ref = np.max(np.abs(ref.tip() - tight.tip()))
    assert e_ours <= 3 * e_ref and e_ref <= 3 * e_ours


def test_batch_equals_single_runs():
    model = paper_model(paper_example(5e6, 25e3))
    drive = DriveSchedule.constant(5100.0, 12.0, 0.5)
    scales = np.array([0.3, 0.6, 1.0])
    b = simulate_batch(model, drive, 6.0, torque_scale=scales, rtol=1e-8, samples=61)
    for i, sc in enumerate(scales):
        d = DriveSchedule.constant(5100.0 * sc, 12.0, 0.5)
        one = simulate(
            model,
            d,
            no_motion(),
            6.0,
            settings=Settings(rtol=1e-8, samples=61),
            speed_scale=drive.free_speed() * math.sqrt(scales.max()),
        )
        assert np.allclose(b.Omega[i], one.Omega, rtol=1e-12, atol=1e-12)
        assert np.allclose(b.tip_peak[i], one.peak[:, -1], rtol=1e-12, atol=1e-15)


def test_threaded_batch_is_bitwise_the_serial_batch():
    model = paper_model(paper_example(5e6, 25e3))
    drive = DriveSchedule.constant(5100.0, 12.0, 0.5)
    scales = np.linspace(0.3, 1.0, 9)
    ecc = np.linspace(0.8, 1.2, 9) * model.eccentricity
    kw = dict(torque_scale=scales, eccentricity=ecc, rtol=1e-8, samples=61)
    serial = simulate_batch(model, drive, 4.0, threads=1, **kw)
    # 3 threads: uneven slices (9 runs in slices of 1), more threads than this machine's cores
    for threads in (2, 3, None):
        par = simulate_batch(model, drive, 4.0, threads=threads, **kw)
        for name in ("t", "Omega", "tip", "tip_peak", "final_state", "status", "nfev"):
            assert np.array_equal(getattr(par, name), getattr(serial, name)), (threads, name)
        assert np.array_equal(par.shaft_deflection, serial.shaft_deflection)
    with pytest.raises(ValueError, match="threads"):
        simulate_batch(model, drive, 4.0, threads=0, **kw)


def test_shaft_deflection_is_the_formula_and_does_not_depend_on_alignment():
    """The batch's shaft deflection is |(d.z - e cos theta, y - e sin theta)|
    (numpy's vector formula, to a few ulp: its SIMD cos/sin and libm's differ
    there, hence rtol 1e-14) and has the same bits wherever the states sit in
    memory (numpy's own cos does not: a study run in another process
    differed by an ulp)."""
    from rotorpillar.reduced.batch import shaft_deflection

    rng = np.random.default_rng(3)
    n, k = 4, 1001
    q = rng.standard_normal((k, n)) * [1e-3, 1e-3, 1e-3, 40.0]
    shaft, e = np.array([-1.0, 1.0]), 2e-3
    size, x = shaft_deflection(q, shaft, e)
    ref_x = q[:, :2] @ shaft - e * np.cos(q[:, 3])
    assert np.allclose(x, ref_x, rtol=1e-14, atol=1e-18)
    assert np.allclose(size, np.hypot(ref_x, q[:, 2] - e * np.sin(q[:, 3])), rtol=1e-14, atol=1e-18)
    buf = np.empty(k * n + 1)
    shifted = buf[1:].reshape(k, n)  # 8 bytes off the allocation's alignment
    shifted[:] = q
    assert np.array_equal(shaft_deflection(shifted, shaft, e)[0], size)


def test_energy_drift_is_kept_and_read_back_for_the_same_model_only(tmp_path, monkeypatch):
    """The drift study reads no drive: a second study of the same model and settings reads
    the first one's rows back (bit for bit, without integrating), and says where from; a
    model that differs in one number (the eccentricity) is integrated again."""
    from rotorpillar.records import replace
    from rotorpillar.transients import integrator_study as study

    model = paper_model(paper_example())
    first = study.drift_study(model, duration=2.0, cache_dir=tmp_path)
    assert first.kept is None and len(first.rows) == len(study.ADAPTIVE + study.FIXED_STEP)

    def no_integration(*args, **kwargs):
        raise AssertionError("the kept study should have been read back")

    with monkeypatch.context() as m:
        m.setattr(study, "simulate", no_integration)
        again = study.drift_study(model, duration=2.0, cache_dir=tmp_path)
    assert again.rows == first.rows and again.kept is not None and Path(again.kept).exists()
    other = replace(model, eccentricity=1.01 * model.eccentricity)
    assert study.model_digest(other) != study.model_digest(model)
    with monkeypatch.context() as m:
        m.setattr(study, "simulate", no_integration)
        with pytest.raises(AssertionError, match="read back"):
            study.drift_study(other, duration=2.0, cache_dir=tmp_path)
