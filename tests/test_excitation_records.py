"""The excitation side's results as records: the JSON they write is the dict the code wrote before.

Each test runs the real function (embedded scenes, the built-in El Centro record) and
compares ``to_json()`` with the dict the old code built from the same inputs, rebuilt
here key by key in the old order (absent keys stay absent), then reads it back:
``from_json(x.to_json()).to_json() == x.to_json()``.  Equality is exact: the same
arithmetic on the same numbers.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from rotorpillar import load_scene
from rotorpillar.provenance import to_json
from rotorpillar.reduced.band import ExcitationBand, excitation_band
from rotorpillar.reduced.base_forcing import AMPLIFICATION_LIMIT, BaseForcingFinding, base_forcing_finding
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import (
    STANDARD_GRAVITY,
    GroundMotion,
    load_record,
    no_motion,
    record_from_arrays,
    response_spectrum,
    unrealistic_record,
)
from rotorpillar.reduced.excitation_records import (
    NoMotionSizes,
    PulseSizes,
    RecordSizes,
    SpectralOrdinates,
    excitation_sizes_from_json,
)
from rotorpillar.reduced.integration import EnergyBalance, Settings, simulate
from rotorpillar.reduced.models import build_model, scene_motion


def _round_trip(record, from_json):
    d = record.to_json()
    assert from_json(d).to_json() == d
    # through the JSON text a command writes, too
    assert from_json(json.loads(to_json(d))).to_json() == json.loads(to_json(d))
    return d


# --------------------------------------------------------------------------
# GroundMotion.sizes(): the dicts the old sizes() built


def _old_sizes(g: GroundMotion) -> dict:
    """GroundMotion.sizes() as it was (commit 5202ea9), for the same motion."""
    if g.kind == "none":
        return {"kind": "none"}
    if g.kind == "pulse":
        A, w = g.amplitude, g.frequency
        u0 = A * (math.cos(w * g.start) - 1)
        return {
            "kind": "pulse",
            "law": "q5 = A*(cos(omega*t) - 1) for start <= t < end, 0 outside",
            "amplitude": A,
            "frequency": w,
            "start": g.start,
            "end": g.end,
            "displacement_step_at_start": u0,
            "peak_displacement": float(2 * A) if w * (g.end - g.start) >= math.pi else abs(u0),
            "peak_velocity": A * w,
            "peak_acceleration": A * w * w,
            "peak_acceleration_g": A * w * w / STANDARD_GRAVITY,
            "inertial_final_displacement": float(g.inertial_displacement(g.end)),
            "realistic": False,
            "statement": (
                f"The paper's pulse as written: the ground jumps {u0:.3g} m at t = "
                f"{g.start:g} s and swings {2 * A:.3g} m at {w / (2 * math.pi):.3g} Hz "
                f"with a peak acceleration of {A * w * w / STANDARD_GRAVITY:.3g} g. "
                "This is not a realistic earthquake (strong records: 0.3-1 g, "
                'ground displacements of decimetres); use kind = "record" for one.'
            ),
        }
    pga = float(np.max(np.abs(g.acceleration)))
    sizes = {
        "kind": "record",
        "name": g.name,
        "source": g.source,
        "time_step": g.time_step,
        "start": g.start,
        "end": g.end,
        "samples": int(len(g.acceleration)),
        "peak_acceleration": pga,
        "peak_acceleration_g": pga / STANDARD_GRAVITY,
        "peak_velocity": float(np.max(np.abs(g.velocity))),
        "peak_displacement": float(np.max(np.abs(g.displacement))),
        "band": g.band(),
    }
    why = unrealistic_record(sizes)
    sizes["realistic"] = not why
    if why:
        sizes["statement"] = (
            "This record is not a realistic earthquake: "
            + "; ".join(why)
            + " (check its time column's unit and its acceleration unit)."
        )
    return sizes


def _motions() -> dict[str, GroundMotion]:
    paper = load_scene("paper")
    t = np.arange(0.0, 400.0, 10.0)  # a 10 s step: beyond REALISTIC's 0.1 s
    return {
        "none": no_motion(),
        "paper": scene_motion(paper),  # the paper scene's [excitation]: its pulse
        "elcentro": load_record("elcentro"),  # BUILTIN_RECORDS
        "slow": record_from_arrays(t, 0.3 * np.sin(0.05 * t), units="g", name="slow"),
    }


MOTIONS = _motions()


@pytest.mark.parametrize("name", list(MOTIONS))
def test_sizes_write_the_old_json(name):
    g = MOTIONS[name]
    sizes = g.sizes()
    expected = {"none": NoMotionSizes, "paper": PulseSizes, "elcentro": RecordSizes, "slow": RecordSizes}[name]
    assert type(sizes) is expected
    old = _old_sizes(g)
    d = _round_trip(sizes, excitation_sizes_from_json)
    assert d == old and list(d) == list(old)  # the same keys in the same order, the same values
    assert excitation_sizes_from_json(d) == sizes


def test_a_realistic_record_writes_no_statement_and_an_unrealistic_one_does():
    elcentro, slow = MOTIONS["elcentro"].sizes(), MOTIONS["slow"].sizes()
    assert isinstance(elcentro, RecordSizes) and isinstance(slow, RecordSizes)
    assert elcentro.realistic and "statement" not in elcentro.to_json()
    assert not slow.realistic and "time step 10 s > 0.1 s" in (slow.statement or "")


def test_sizes_of_an_unknown_kind_are_refused():
    with pytest.raises(ValueError, match="excitation.kind = 'quake'"):
        excitation_sizes_from_json({"kind": "quake"})


# --------------------------------------------------------------------------
# response_spectrum


@pytest.mark.parametrize("name", ["paper", "elcentro"])
def test_response_spectrum_is_the_old_dict(name):
    import eqsig

    g = MOTIONS[name]
    periods = np.geomspace(0.1, 5.0, 7)
    rs = response_spectrum(g, periods, damping=0.05)
    assert isinstance(rs, SpectralOrdinates)
    # the old dict, from eqsig directly (a pulse sampled at 1/200 of its period over its window)
    if g.kind == "record":
        acc, dt = g.acceleration.copy(), g.time_step
    else:
        dt = 2 * math.pi / g.frequency / 200
        t = g.start + dt * np.arange(int(math.ceil((g.end - g.start) / dt)) + 1)
        acc = np.asarray(g.evaluate(t)[2], dtype=float)
    sig = eqsig.AccSignal(acc, dt)
    sig.generate_response_spectrum(response_times=periods, xi=0.05)
    old = {"periods": periods, "damping": 0.05, "s_a": np.asarray(sig.s_a), "s_d": np.asarray(sig.s_d)}
    d = _round_trip(rs, SpectralOrdinates.from_json)
    assert list(d) == list(old)
    assert d == {k: v.tolist() if isinstance(v, np.ndarray) else v for k, v in old.items()}
    assert isinstance(rs.s_d, np.ndarray) and np.array_equal(rs.s_d, old["s_d"])  # arrays, as before


# --------------------------------------------------------------------------
# excitation_band


@pytest.mark.parametrize("scene_name", ["paper", "sommerfeld"])
def test_excitation_band_writes_the_old_json(scene_name):
    from rotorpillar.converge import ExcitationBand as FromConverge
    from rotorpillar.reduced.averaging import Characteristic

    s = load_scene(scene_name)
    band = excitation_band(s.drive, s.load, s.converge)
    assert isinstance(band, ExcitationBand) and FromConverge is ExcitationBand  # one definition
    free = Characteristic(s.drive.torque_at_zero, s.drive.slope, s.load.coefficient).free_speed()
    cv = s.converge
    old = {
        "free_speed": free,
        "earthquake_frequency": cv.earthquake_frequency,
        "margin": cv.margin,
        "omega_max": cv.margin * max(free, cv.earthquake_frequency),
        "driver": "drive free speed" if free >= cv.earthquake_frequency else "earthquake",
    }
    d = _round_trip(band, ExcitationBand.from_json)
    assert d == old and list(d) == list(old)


# --------------------------------------------------------------------------
# Transient.energy_balance


def test_energy_balance_writes_the_old_json():
    scene = load_scene("paper")
    model, _ = build_model(scene, "paper")
    d_ = scene.drive
    run = simulate(
        model,
        DriveSchedule.constant(d_.torque_at_zero, d_.slope, scene.load.coefficient),
        MOTIONS["paper"],
        6.0,
        settings=Settings("dp5", rtol=1e-6, samples=301),
    )
    eb = run.energy_balance()
    assert isinstance(eb, EnergyBalance)
    # the old dict: E(t) - E(0) against the work (free rotor: the drive's work)
    T, P = run.model.energy(run.q, run.v)
    E, w = T + P, run.work
    resid = (E - E[0]) - (w[:, 0] - w[:, 2] + w[:, 3])
    scale = max(
        np.max(np.abs(E - E[0])), np.max(np.abs(w[:, 0])), np.max(np.abs(w[:, 2])), np.max(np.abs(w[:, 3])), 1e-300
    )
    old = {
        "energy_change": float(E[-1] - E[0]),
        "work_drive_minus_load": float(w[-1, 0]),
        "work_shaft_on_structure": float(w[-1, 1]),
        "dissipated": float(w[-1, 2]),
        "work_base": float(w[-1, 3]),
        "max_abs_residual": float(np.max(np.abs(resid))),
        "scale": float(scale),
        "relative_error": float(np.max(np.abs(resid)) / scale),
    }
    d = _round_trip(eb, EnergyBalance.from_json)
    assert d == old and list(d) == list(old)
    assert w[-1, 3] != 0.0  # the pulse started at 5 s: the ground did work, a field that can differ


# --------------------------------------------------------------------------
# base_forcing_finding


@pytest.mark.parametrize("scene_name", ["paper", "sommerfeld"])
def test_base_forcing_finding_writes_the_old_json(scene_name):
    s = load_scene(scene_name)
    c1, c2, b1, b2 = 9.6e6, s.shaft.stiffness, s.pillar.damping, s.shaft.damping
    f = base_forcing_finding(c1, c2, b1, b2)
    gain = (c1 + 2 * c2) / c1
    old = {
        "published": {
            "q1": f"c0 q5 + b0 q5' = {c1 + c2:.4g} q5 + {b1 + b2:.4g} q5'",
            "q2": f"c2 q5 + b2 q5' = {c2:.4g} q5 + {b2:.4g} q5'",
        },
        "consistent": {
            "q1": f"c1 q5 + b1 q5' = {c1:.4g} q5 + {b1:.4g} q5'",
            "q2": "0",
            "relative_coordinates": "-M r a_g (m_A a_g on q1, m_C a_g on q2)",
        },
        "static_gain_published": gain,
        "static_gain_consistent": 1.0,
        "amplification": gain,
        "amplifies": gain > AMPLIFICATION_LIMIT,
        "limit": AMPLIFICATION_LIMIT,
    }
    d = _round_trip(f, BaseForcingFinding.from_json)
    assert d == old and list(d) == list(old) and list(d["published"]) == ["q1", "q2"]


def test_analyze_writes_the_finding_as_before():
    """analyze.json's eq4_base_forcing row carries the finding under ``details``, read back as a record."""
    from rotorpillar import analyze
    from rotorpillar.analysis.results import PaperRow

    row = {r.key: r for r in analyze(load_scene("paper")).paper_comparison}["eq4_base_forcing"]
    assert isinstance(row.details, BaseForcingFinding)
    d = _round_trip(row, PaperRow.from_json)
    assert d["details"] == row.details.to_json() and isinstance(PaperRow.from_json(d).details, BaseForcingFinding)


# --------------------------------------------------------------------------
# the records that carry the sizes: read back typed


@pytest.mark.parametrize("name", ["paper", "elcentro", "slow"])
def test_run_records_read_the_sizes_back_as_records(name, tmp_path):
    """simulate's run records (reduced and 3D) and compare's result carry the sizes as
    the old dict and read them back typed, by their ``kind``."""
    import fixtures

    from rotorpillar.transients.records import CompareResult
    from rotorpillar.transients.run_records import Fem3dRun, ReducedRun

    sizes = MOTIONS[name].sizes()
    t, Omega = np.linspace(0.0, 1.0, 11), np.linspace(0.0, 10.0, 11)
    peaks = {"tip_x": 1e-3, "rotor_x": 2e-3, "rotor_y": 1e-3}
    reduced = fixtures.reduced_run(
        "earthquake",
        "modal",
        t,
        Omega,
        peaks,
        tip_x_frame="relative_to_ground",
        dofs=6,
        wall_seconds=0.1,
        excitation=sizes,
    )
    full = fixtures.fem3d_run("earthquake", t, Omega, peaks, dofs=99, wall_seconds=1.0, excitation=sizes)
    for run, cls in ((reduced, ReducedRun), (full, Fem3dRun)):
        d = json.loads(to_json(run.to_json()))
        assert d["excitation"] == _old_sizes(MOTIONS[name])
        back = cls.from_json(d)
        ex = back.summary.excitation if isinstance(back, ReducedRun) else back.excitation
        assert type(ex) is type(sizes) and ex == sizes
        assert back.to_json() == d
    assert isinstance(ReducedRun.from_json(reduced.to_json()).summary.energy_balance, EnergyBalance)
    doc = fixtures.write_comparison_fixture(tmp_path, "earthquake", ("beam", "modal"))
    doc["excitation"] = sizes.to_json()
    result = CompareResult.from_json(doc)
    assert result.excitation == sizes and result.to_json()["excitation"] == _old_sizes(MOTIONS[name])


def _old_excitation_text(ex) -> str | None:
    """postprocess.report.compare_section.excitation_text as it was, on the JSON block."""
    from rotorpillar.postprocess import html as h

    if not isinstance(ex, dict):
        return None
    if isinstance(ex.get("statement"), str):
        return ex["statement"]
    if ex.get("kind") != "record":
        return None
    what = [f"peak acceleration {h.num(ex.get('peak_acceleration_g'), 3)} g"]
    if ex.get("peak_velocity") is not None:
        what.append(f"peak velocity {h.num(ex['peak_velocity'], 3)} m/s")
    if ex.get("peak_displacement") is not None:
        what.append(f"peak displacement {h.num(ex['peak_displacement'], 3)} m")
    start = f", from t = {h.num(ex['start'], 4)} s" if ex.get("start") is not None else ""
    name = f"Ground motion: the record {ex.get('name', '?')}" + (f" ({ex['source']})" if ex.get("source") else "")
    return name + ": " + ", ".join(what) + start + "."


@pytest.mark.parametrize("name", list(MOTIONS))
def test_the_report_states_the_motion_as_before(name):
    from rotorpillar.postprocess.report.compare_section import excitation_text

    sizes = MOTIONS[name].sizes()
    assert excitation_text(sizes) == _old_excitation_text(sizes.to_json())
    assert excitation_text(None) is None
