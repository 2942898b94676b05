"""The scene as a value: ``with_values`` derives a scene from typed values.

References, independent of ``with_values``: the ``--set`` text path
(``override``: the values formatted, parsed as TOML, the whole document
validated again) and a scene file (``scene_from_dict`` of an edited TOML
document).  Scenes are compared exactly, by ``==`` and by ``repr`` (``repr``
tells 0 from 0.0, so a value's type counts too); no tolerance, since no
arithmetic happens on either path.  A bad value must give the very line the
``--set`` path gives.  Last, a scan of the package's syntax trees: no library
module formats ``--set`` text or calls the text path.
"""

from __future__ import annotations

import ast
import copy
import dataclasses
import re
from pathlib import Path

import pytest

from rotorpillar.scene import (
    SECTIONS,
    Can,
    SceneError,
    load_scene,
    override,
    read_scene_toml,
    scene_from_dict,
    with_values,
)


def same(a, b) -> bool:
    return a == b and repr(a) == repr(b)


#: (key, typed value, the same value as --set text): one of each kind of field
KINDS = [
    ("shaft.stiffness", 5e6, "5e6"),  # float
    ("simulate.rtol", 1 / 3 * 1e-7, repr(1 / 3 * 1e-7)),  # a float with every digit
    ("simulate.runup_initial_speed", 0, "0"),  # an integer into a float field: 0.0 both ways
    ("mesh.elements_around", 16, "16"),  # int
    ("excitation.components", 3, "3"),  # int with choices
    ("modal_model.source", "beam", "beam"),  # str (a bare word on the command line)
    ("excitation.record", "elcentro", '"elcentro"'),  # str, quoted
    ("simulate.threshold", False, "false"),  # bool
]


@pytest.mark.parametrize("key, value, text", KINDS, ids=[k for k, _, _ in KINDS])
def test_a_typed_value_gives_the_scene_the_text_gives(key, value, text):
    paper = load_scene("paper")
    assert same(with_values(paper, {key: value}), override(paper, [f"{key}={text}"]))


def test_many_values_at_once():
    paper = load_scene("paper")
    typed = with_values(paper, {k: v for k, v, _ in KINDS})
    assert same(typed, override(paper, [f"{k}={t}" for k, _, t in KINDS]))
    assert typed != paper and with_values(paper, {}) is paper


def test_tuple_of_cans_as_objects_or_tables():
    """The tower's cans: new ones (same total height, so pillar.height agrees) as
    ``Can`` objects or as tables, against the same array of tables as --set text."""
    tower = load_scene("nrel5mw")
    (can,) = tower.pillar.cans
    lower = dataclasses.replace(can, height=40.0, outer_diameter_top=5.0, wall_thickness_top=None)
    upper = dataclasses.replace(can, height=47.6, outer_diameter_bottom=5.0)
    text = (
        f"pillar.cans=[{{height = 40.0, outer_diameter_bottom = {can.outer_diameter_bottom!r}, "
        f"outer_diameter_top = 5.0, wall_thickness = {can.wall_thickness!r}}}, "
        f"{{height = 47.6, outer_diameter_bottom = 5.0, outer_diameter_top = {can.outer_diameter_top!r}, "
        f"wall_thickness = {can.wall_thickness!r}, wall_thickness_top = {can.wall_thickness_top!r}}}]"
    )
    by_text = override(tower, [text])
    assert same(with_values(tower, {"pillar.cans": (lower, upper)}), by_text)
    assert same(with_values(tower, {"pillar.cans": [dataclasses.asdict(lower), dataclasses.asdict(upper)]}), by_text)
    assert all(isinstance(c, Can) for c in by_text.pillar.cans) and len(by_text.pillar.cans) == 2


def test_optional_none_as_a_scene_file_leaves_it_out():
    """The uniform tube made a stack of cans: its diameters and height set to None
    (left out), against the paper's scene file edited the same way.  --set cannot
    say None (TOML has no null), so the file is the reference here."""
    data, name = read_scene_toml("paper")
    paper = scene_from_dict(data, name=name)
    p = paper.pillar
    assert p.outer_diameter is not None and p.inner_diameter is not None
    t = (p.outer_diameter - p.inner_diameter) / 2
    cans = (
        Can(height=12.0, outer_diameter_bottom=p.outer_diameter, outer_diameter_top=p.outer_diameter, wall_thickness=t),
        Can(
            height=8.0,
            outer_diameter_bottom=p.outer_diameter,
            outer_diameter_top=p.outer_diameter,
            wall_thickness=t / 2,
        ),
    )
    typed = with_values(
        paper,
        {"pillar.height": None, "pillar.outer_diameter": None, "pillar.inner_diameter": None, "pillar.cans": cans},
    )
    doc = copy.deepcopy(data)
    for key in ("height", "outer_diameter", "inner_diameter"):
        doc["pillar"].pop(key, None)
    doc["pillar"]["cans"] = [{k: v for k, v in dataclasses.asdict(c).items() if v is not None} for c in cans]
    assert same(typed, scene_from_dict(doc, name=name))
    assert typed.pillar.height == 20.0 and typed.pillar.outer_diameter is None


#: (key, bad typed value, the same as --set text): range, type, choice, finiteness,
#: a check across keys, an unknown key and section
BAD = [
    ("rotor.mass", -1.0, "-1.0"),
    ("mesh.elements_around", 2.5, "2.5"),
    ("shaft.stiffness", True, "true"),
    ("modal_model.source", "nope", "nope"),
    ("simulate.duration", float("inf"), "inf"),
    ("simulate.threshold", 1, "1"),
    ("sweep.torque_high", 50.0, "50.0"),  # below sweep.torque_low: the cross-check
    ("pillar.inner_diameter", 9.0, "9.0"),  # past the outer diameter: the cross-check
    ("shaft.stifness", 1.0, "1.0"),
    ("shafts.stiffness", 1.0, "1.0"),
]


@pytest.mark.parametrize("key, value, text", BAD, ids=[k for k, _, _ in BAD])
def test_a_bad_value_is_the_line_set_gives(key, value, text):
    paper = load_scene("paper")
    with pytest.raises(SceneError) as typed:
        with_values(paper, {key: value})
    line = str(typed.value)
    assert "\n" not in line and (key in line or f"[{key.partition('.')[0]}]" in line)
    with pytest.raises(SceneError) as by_text:
        override(paper, [f"{key}={text}"])
    assert line == str(by_text.value)


def test_none_for_a_required_field():
    with pytest.raises(SceneError, match=r"^rotor\.mass: a value is required \(Mass m_C \(kg\); >= 0\.001"):
        with_values(load_scene("paper"), {"rotor.mass": None})


# -- no library module formats --set text ------------------------------------------------

PACKAGE = Path(__file__).resolve().parents[1] / "rotorpillar"
#: modules that handle --set text on purpose: its parser, the command line that echoes
#: the user's own --set, and run, whose stages pass --set to child processes
ALLOWED = {"scene/files.py", "commands/parser.py", "commands/report.py", "commands/run.py"}
#: module-level names holding a child command's arguments (strings on purpose)
ARGV_CONSTANTS = {("transients/compare.py", "COMPARISONS")}
TEXT_PATH = {"override", "apply_overrides", "parse_assignment"}
ASSIGNMENT = re.compile(r"^(?:--set\b|(?:" + "|".join(SECTIONS) + r"|\{\})\.[\w{}]+=)")


def _literal(node: ast.AST) -> str | None:
    """A string literal's text, an f-string's with ``{}`` for each field."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else "{}" for v in node.values)
    return None


def set_text_in(source: str, rel: str = "") -> list[str]:
    """Where ``source`` builds ``--set`` text or calls the text path, as ``line: what``
    (a command-line flag's own declaration, ``add_argument(...)``, is the parser's)."""
    tree = ast.parse(source)
    skip = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.JoinedStr):  # an f-string is read whole, not by its pieces
            skip |= {id(v) for v in node.values}
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "add_argument":
            skip |= {id(n) for n in ast.walk(node)}
        elif isinstance(node, ast.Compare):  # reading a child's argv (x == "--set") builds nothing
            skip |= {id(n) for n in node.comparators}
    for node in tree.body:
        if isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            if any(isinstance(t, ast.Name) and (rel, t.id) in ARGV_CONSTANTS for t in targets):
                skip |= {id(n) for n in ast.walk(node)}
    found = []
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        if isinstance(node, ast.Call):
            f = node.func
            name = f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else ""
            if name in TEXT_PATH:
                found.append(f"{node.lineno}: calls {name}")
        elif isinstance(node, ast.JoinedStr) or isinstance(node, ast.Constant):
            text = _literal(node)
            if text is not None and ASSIGNMENT.match(text.strip()):
                found.append(f"{node.lineno}: {text.strip()[:40]!r}")
    return found


def test_the_scan_finds_set_text():
    """The scan below can fail: it finds each way of writing --set text."""
    source = (
        "s = override(scene, ['simulate.threshold=false'])\n"
        "t = scene_files.override(scene, [f'simulate.rtol={x!r}'])\n"
        "u = [f'simulate.{key}={d!r}', '--set', f'--set {a}']\n"
    )
    assert len(set_text_in(source)) == 7
    assert not set_text_in("p.add_argument('--set', dest='overrides')\n")  # the parser's flag
    assert not set_text_in("m = f'simulate.duration = {d:g} s is too short'\n")  # a message, not text to parse


def test_no_library_module_formats_set_text():
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).as_posix()
        if rel in ALLOWED:
            continue
        hits = set_text_in(path.read_text(encoding="utf-8"), rel)
        if hits:
            found[rel] = hits
    assert not found, f"--set text in library modules (use rotorpillar.scene.with_values): {found}"
