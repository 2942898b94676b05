"""The capacities' scene keys: validated like every other key (exit 2, one line
naming the key and its range, nothing written), defaults stated, and the
scene's fabrication classes those of rotorpillar.reduced.capacity."""

import pytest

from rotorpillar.reduced.capacity import QUALITY_CLASSES
from rotorpillar.scene import FABRICATION_CLASSES, load_scene


@pytest.mark.parametrize(
    "assignment, key, range_text",
    [
        # each key's closed range (scene.sections: where the checks still mean something)
        ("material.yield_strength=-355e6", "material.yield_strength", ">= 1e+06 and <= 1e+10"),
        ("material.yield_strength=0", "material.yield_strength", ">= 1e+06 and <= 1e+10"),
        ("rotor.clearance=0", "rotor.clearance", ">= 1e-06 and <= 1"),
        ("rotor.clearance=-0.01", "rotor.clearance", ">= 1e-06 and <= 1"),
        ("shaft.force_limit=0", "shaft.force_limit", ">= 1 and <= 1e+12"),
        ("material.fabrication_class=D", "material.fabrication_class", "'A', 'B', 'C'"),
        ("material.grade=1", "material.grade", "yield_strength"),
    ],
)
def test_bad_capacities_exit_2_one_line_nothing_written(tmp_path, assignment, key, range_text, here):
    # in this process (``here``: what a child would print on stderr, warnings and log records
    # included): a refusal needs no Python start-up, 7 children ~0.6 s of imports each
    out = tmp_path / "out"
    p = here("analyze", "paper", "--set", assignment, "--out", out)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and key in lines[0] and range_text in lines[0]
    assert p.stdout == ""
    assert not out.exists()


def test_defaults_and_classes():
    s = load_scene("paper")
    assert s.material.yield_strength == 355e6 and s.material.fabrication_class == "C"
    # no capacity stated, no check passed silently: the checks say "not assessed"
    assert s.rotor.clearance is None and s.shaft.force_limit is None
    assert FABRICATION_CLASSES == QUALITY_CLASSES
