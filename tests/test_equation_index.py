"""The equation indexes and the paper's Eq. 4.

1. The indexes in the docstrings of rotorpillar.reduced and rotorpillar.fem3d
   (lines ``Eq. N   module.function``) name functions that exist and whose
   docstring's first line carries the tag ``Eq. N``: exact, by text.
2. The compiled right-hand side of the paper model (rotorpillar.reduced.rhs,
   ``rhs_first_order``) against ``eq4_rhs``, the paper's Eq. 4 as
   published in plain numpy, at random states with and without the ground
   pulse: the same arithmetic in another order, so to 1e-12 of the largest
   acceleration.
"""

import ast
import importlib
import re
from pathlib import Path

import numpy as np
import pytest

import rotorpillar

ROOT = Path(rotorpillar.__file__).parent
LINE = re.compile(r"^Eq\. (\d+)\s+(rotorpillar\.[\w.]+)\s*$", re.M)


def _index(package: str) -> list[tuple[str, str]]:
    path = ROOT / package / "__init__.py"
    return LINE.findall(ast.get_docstring(ast.parse(path.read_text())) or "")


def _resolve(dotted: str):
    """The object a dotted path names: the longest importable module, then attributes."""
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for name in parts[i:]:
            obj = getattr(obj, name)
        return obj
    raise ImportError(dotted)


def test_reduced_index_names_the_required_equations():
    found = {n for n, _ in _index("reduced")}
    assert {"1", "2", "4", "5", "6", "7", "19", "20", "21", "22", "23", "24"} <= found


@pytest.mark.parametrize("package", ["reduced", "fem3d"])
def test_every_indexed_function_carries_its_tag_on_its_first_docstring_line(package):
    entries = _index(package)
    assert entries
    for n, dotted in entries:
        if package == "fem3d":
            assert dotted.startswith("rotorpillar.fem3d.")
        first = (_resolve(dotted).__doc__ or "").strip().split("\n")[0]
        assert re.search(rf"\bEq\. {n}\b(?!\.\d)", first), (dotted, first)


def test_reduced_names_no_equation_as_eq_parenthesis():
    """The tag's one form: no "Eq. (N)" left in the reduced package."""
    for path in (ROOT / "reduced").glob("*.py"):
        assert "Eq. (" not in path.read_text(), path


def _paper_model_and_params():
    from rotorpillar.reduced.rotor_models import paper_model
    from rotorpillar.reduced.system import paper_example

    s = paper_example(0.4e6, 11e3, 30e3)
    p = (
        s.tip_mass,
        s.rotor_mass,
        s.rotor_inertia,
        s.eccentricity,
        s.pillar_stiffness,
        s.shaft_stiffness,
        s.pillar_damping,
        s.shaft_damping,
    )
    return paper_model(s), p


@pytest.mark.parametrize("with_ground", [False, True])
def test_compiled_rhs_of_the_paper_model_is_equation_4(with_ground):
    from rotorpillar.reduced.drive import DriveSchedule
    from rotorpillar.reduced.excitation import no_motion, paper_pulse
    from rotorpillar.reduced.rhs import N_WORK, eq4_rhs, flatten, rhs_first_order

    model, p = _paper_model_and_params()
    M0, slope, k = 1500.0, 12.0, 0.5
    motion = paper_pulse() if with_ground else no_motion()
    P = model.pack(DriveSchedule.constant(M0, slope, k), motion)
    rng = np.random.default_rng(4)
    for _ in range(50):
        t = rng.uniform(5.0, 12.0) if with_ground else rng.uniform(0.0, 20.0)
        q = np.r_[rng.normal(0, 0.01, 3), rng.uniform(0, 2 * np.pi)]
        v = np.r_[rng.normal(0, 0.5, 3), rng.uniform(-20, 120)]
        y = np.r_[q, v, np.zeros(N_WORK)]
        u5, v5, _ = (float(x) for x in motion.evaluate(t))
        want = eq4_rhs(y[:8], *p, M0, slope, k, q5=u5, q5_rate=v5)
        got = rhs_first_order(t, y, flatten(P))[:8]
        # to round-off of the largest acceleration (a component may cancel to near zero)
        assert got == pytest.approx(want, rel=1e-12, abs=1e-12 * np.max(np.abs(want[4:])))
