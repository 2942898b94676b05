"""tools/house_check.py catches what it claims to, on small synthetic packages.

Each test writes a package ``rotorpillar`` into a temporary directory that
breaks one rule (an import circle, a long module, a lazy fem3d import in
reduced/, an eager pyvista import, a lost equation tag, a new dict result) and
checks that exactly that rule fails; a clean package passes them all.  The
real tree is checked by ``make check``.
"""

from __future__ import annotations

import importlib.util
import json
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _load_tool():
    spec = importlib.util.spec_from_file_location("house_check", ROOT / "tools" / "house_check.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules["house_check"] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod


hc = _load_tool()

INDEX = '''"""Reduced.

Eq. 1    rotorpillar.reduced.pillar.omega
Eq. 2    rotorpillar.reduced.pillar.tip_mass
Eq. 4    rotorpillar.reduced.pillar.rhs
Eq. 5    rotorpillar.reduced.pillar.pair
Eq. 19   rotorpillar.reduced.pillar.Averaged.amplitude
Eq. 23   rotorpillar.reduced.pillar.stable
"""
'''

PILLAR = '''"""Closed forms."""
from ..scene import Scene


def omega(scene: Scene) -> float:
    """Eq. 1: the first bending frequency (rad/s)."""
    return 1.0


def tip_mass() -> float:
    """Eq. 2: the tip mass (kg)."""
    return 1.0


def rhs() -> float:
    """Eq. 4: the right-hand side."""
    return 0.0


def pair() -> float:
    """Eq. 5: the pair."""
    return 0.0


class Averaged:
    def amplitude(self) -> float:
        """Eq. 19: the amplitude (m)."""
        return 0.0


def stable() -> bool:
    """Eq. 23: stability."""
    return True
'''


def _package(tmp_path: Path, **files: str) -> Path:
    """A clean package, then ``files`` (path under rotorpillar/ -> text; "" deletes)."""
    base = {
        "__init__.py": '"""Root."""\n',
        "scene/__init__.py": '"""Scene."""\n\nclass Scene:\n    pass\n',
        "reduced/__init__.py": INDEX,
        "reduced/pillar.py": PILLAR,
        "fem3d/__init__.py": '"""3D."""\n',
        "fem3d/modal.py": '"""Modes."""\nimport numpy\nfrom ..reduced import pillar\n',
        "postprocess/__init__.py": '"""Plots."""\n',
        "postprocess/charts.py": '"""Charts."""\n\ndef chart():\n    import matplotlib\n',
    }
    base.update(files)
    for rel, text in base.items():
        path = tmp_path / "rotorpillar" / rel
        if text == "":
            path.unlink(missing_ok=True)
            continue
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    return tmp_path


def _failing(tmp_path: Path, baseline: dict | None = None) -> list[str]:
    path = tmp_path / "baseline.json"
    path.write_text(json.dumps(baseline or {}))
    return [v.text for v in hc.run(tmp_path, path) if not v.ok]


def test_a_clean_package_passes(tmp_path):
    assert _failing(_package(tmp_path)) == []


def test_the_real_tree_passes():
    assert [v.text for v in hc.run() if not v.ok] == []


def test_an_import_circle_is_found(tmp_path):
    pkg = _package(tmp_path, **{"fem3d/a.py": "from . import b\n", "fem3d/b.py": "from .a import x\n"})
    (fail,) = _failing(pkg)
    assert "import circles: 1" in fail and "rotorpillar.fem3d.a <-> rotorpillar.fem3d.b" in fail


def test_a_package_reexporting_its_submodule_is_no_circle(tmp_path):
    pkg = _package(
        tmp_path,
        **{
            "fem3d/__init__.py": "from .modal import numpy\n",
            "fem3d/modal.py": "from . import other\n",
            "fem3d/other.py": "x = 1\n",
        },
    )
    assert _failing(pkg) == []


def test_a_long_module_is_found(tmp_path):
    pkg = _package(tmp_path, **{"fem3d/long.py": "x = 1\n" * 801})
    (fail,) = _failing(pkg)
    assert "over 800 lines: 1" in fail and "fem3d/long.py" in fail


@pytest.mark.parametrize(
    "line",
    [
        "def f():\n    from ..fem3d import modal\n",  # lazy, relative
        "import rotorpillar.fem3d.modal\n",  # absolute
        "def f():\n    import dolfinx\n",  # the dolfinx world
        "import importlib\nm = importlib.import_module('rotorpillar.fem3d')\n",
    ],
)
def test_reduced_reaching_for_the_3d_side_is_found(tmp_path, line):
    (fail,) = _failing(_package(tmp_path, **{"reduced/bad.py": line}))
    assert fail.startswith("reduced/ imports only") and "reduced/bad.py" in fail


@pytest.mark.parametrize(
    "rel, text",
    [
        ("fem3d/plot.py", "def f():\n    import pyvista\n"),  # outside postprocess/
        ("postprocess/eager.py", "import matplotlib.pyplot as plt\n"),  # at module level
    ],
)
def test_plotting_outside_postprocess_or_at_import_is_found(tmp_path, rel, text):
    (fail,) = _failing(_package(tmp_path, **{rel: text}))
    assert fail.startswith("pyvista/matplotlib/vtk") and rel in fail


def test_an_equation_tag_moved_off_the_first_line_is_found(tmp_path):
    pillar = PILLAR.replace('"""Eq. 23: stability."""', '"""Stability.\n\n    Eq. 23.\n    """')
    (fail,) = _failing(_package(tmp_path, **{"reduced/pillar.py": pillar}))
    assert "Eq. 23: rotorpillar.reduced.pillar.stable lacks the tag" in fail


def test_a_missing_equation_in_the_index_is_found(tmp_path):
    index = INDEX.replace("Eq. 19   rotorpillar.reduced.pillar.Averaged.amplitude\n", "")
    (fail,) = _failing(_package(tmp_path, **{"reduced/__init__.py": index}))
    assert "missing Eq. 19" in fail


def test_an_indexed_function_that_does_not_exist_is_found(tmp_path):
    index = INDEX.replace("pillar.pair", "pillar.pairs")
    (fail,) = _failing(_package(tmp_path, **{"reduced/__init__.py": index}))
    assert "pillar.pairs not found" in fail


NEW_DICTS = """
def summary(scene) -> dict:
    return {"a": 1}

def numbers():
    return {"b": 2}

def to_json(self) -> dict:        # a serialiser: not counted
    return {"c": 3}

def builds() -> list:
    def inner():
        return {"d": 4}           # inner's result, not builds'
    return [inner()]
"""


def test_new_dict_results_and_untyped_scenes_are_counted_against_the_baseline(tmp_path):
    pkg = _package(tmp_path, **{"fem3d/modal_summary.py": NEW_DICTS})
    assert hc.ratchet_counts(hc.load_modules(pkg)["rotorpillar.fem3d.modal_summary"]) == {
        "dict_results": 3,
        "untyped_scene": 1,
    }
    fails = _failing(pkg)
    assert len(fails) == 2 and all("rotorpillar/fem3d/modal_summary.py 0->" in f for f in fails)
    # the same counts on record pass; one fewer than recorded asks for a lower baseline
    at = {"rotorpillar/fem3d/modal_summary.py": {"dict_results": 3, "untyped_scene": 1}}
    assert _failing(pkg, at) == []
    above = {"rotorpillar/fem3d/modal_summary.py": {"dict_results": 4, "untyped_scene": 1}}
    assert _failing(pkg, above) == []
    texts = [v.text for v in hc.run(pkg, tmp_path / "baseline.json")]
    assert any("lower the baseline" in t for t in texts)
