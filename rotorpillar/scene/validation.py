"""A parsed scene document checked field by field and as a whole, then built."""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Mapping
from dataclasses import fields
from typing import Any

from .sections import OPTIONAL_SECTIONS, SECTIONS, Pillar, Scene, SceneError, _range_text
from .tower import check_cans, check_foundation


def _check_table(key: str, value: Any, meta: Any) -> tuple[Any, ...]:
    """An array of tables ([[section.key]]): each built as its section class, their count in range."""
    if not isinstance(value, (list, tuple)) or not all(isinstance(v, dict) for v in value):
        raise SceneError(f"{key} must be an array of tables ([[{key}]] in TOML) ({meta['doc']})")
    lo, hi = meta["ge"], meta["le"]
    if (lo is not None and len(value) < lo) or (hi is not None and len(value) > hi):
        raise SceneError(f"{key}: {len(value)} tables is out of range: must be {_range_text(meta)} ({meta['doc']})")
    return tuple(_build_section(f"{key}[{i}]", meta["table"], dict(v)) for i, v in enumerate(value))


def shown(value: Any) -> str:
    """A value as a message shows it: a long number shortened, a long text cut.

    >>> shown(10**5000), shown(2.5), shown("x" * 100)[-15:]
    ('an integer of 5001 digits', '2.5', '... (102 chars)')
    """
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 60:
        digits = len(str(abs(value))) if value.bit_length() < 10_000 else int(value.bit_length() * math.log10(2)) + 1
        return f"an integer of {digits} digits"
    text = repr(value)
    return text if len(text) <= 80 else f"{text[:60]}... ({len(text)} chars)"


def _check_value(key: str, value: Any, f: dataclasses.Field[Any]) -> Any:
    meta = f.metadata
    want = f.type if isinstance(f.type, str) else f.type.__name__
    if meta.get("table") is not None:
        return _check_table(key, value, meta)
    if value is None:
        if meta.get("optional"):
            return None
        raise SceneError(f"{key}: a value is required ({meta['doc']}; {_range_text(meta)})")
    if "float" in want:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SceneError(f"{key} = {shown(value)}: must be a number ({meta['doc']}; {_range_text(meta)})")
        try:
            value = float(value)
        except OverflowError:  # an integer past the largest double
            raise SceneError(
                f"{key} = {shown(value)} is out of range: must be {_range_text(meta)} ({meta['doc']})"
            ) from None
        if not math.isfinite(value):
            raise SceneError(f"{key} = {value!r}: must be finite ({meta['doc']}; {_range_text(meta)})")
    elif "int" in want:
        if isinstance(value, bool) or not isinstance(value, int):
            raise SceneError(f"{key} = {shown(value)}: must be an integer ({meta['doc']}; {_range_text(meta)})")
    elif "bool" in want:
        if not isinstance(value, bool):
            raise SceneError(f"{key} = {shown(value)}: must be true or false ({meta['doc']})")
        return value
    elif "str" in want:
        if not isinstance(value, str):
            raise SceneError(f"{key} = {shown(value)}: must be a string ({meta['doc']}; {_range_text(meta)})")
    if meta["choices"] is not None:
        if value not in meta["choices"]:
            raise SceneError(f"{key} = {shown(value)}: must be {_range_text(meta)} ({meta['doc']})")
        return value
    if meta.get("or_zero") and value == 0:
        return value
    ok = (
        (meta["gt"] is None or value > meta["gt"])
        and (meta["ge"] is None or value >= meta["ge"])
        and (meta["lt"] is None or value < meta["lt"])
        and (meta["le"] is None or value <= meta["le"])
    )
    if not ok:
        raise SceneError(f"{key} = {shown(value)} is out of range: must be {_range_text(meta)} ({meta['doc']})")
    return value


def _build_section(name: str, cls: type[Any], table: Any) -> Any:
    if not isinstance(table, dict):
        raise SceneError(f"[{name}] must be a table of keys, got {type(table).__name__}")
    known = {f.name: f for f in fields(cls)}
    for key in table:
        if key not in known:
            raise SceneError(f"{name}.{key}: unknown key; [{name}] takes " + ", ".join(known))
    values = {}
    for key, f in known.items():
        if key in table:
            values[key] = _check_value(f"{name}.{key}", table[key], f)
        elif f.default is dataclasses.MISSING:
            raise SceneError(f"{name}.{key}: missing ({f.metadata['doc']}; {_range_text(f.metadata)})")
    return cls(**values)


def _pillar_checks(p: Pillar) -> None:
    """The uniform tube's three keys, or the cans (and then a height, if given, their sum)."""
    uniform = {f.name: f for f in fields(Pillar) if f.name in ("height", "outer_diameter", "inner_diameter")}
    if p.cans:
        check_cans(p.cans)
        for key in ("outer_diameter", "inner_diameter"):
            if getattr(p, key) is not None:
                raise SceneError(f"pillar.{key}: give either the uniform tube's diameters or [[pillar.cans]], not both")
        total = sum(c.height for c in p.cans)
        if abs(p.height - total) > 1e-9 * total:
            raise SceneError(
                f"pillar.height = {p.height:g} is out of range: must equal the sum of the cans' heights, "
                f"{total:g} (m), or be left out"
            )
        return
    for key, f in uniform.items():
        if getattr(p, key) is None:
            raise SceneError(f"pillar.{key}: missing ({f.metadata['doc']}; {_range_text(f.metadata)})")
    assert p.inner_diameter is not None and p.outer_diameter is not None
    if p.inner_diameter >= p.outer_diameter:
        raise SceneError(
            f"pillar.inner_diameter = {p.inner_diameter:g} is out of range: must be "
            f">= 0 and < pillar.outer_diameter = {p.outer_diameter:g} (m)"
        )
    if (p.outer_diameter - p.inner_diameter) / 2 < p.outer_diameter / 2000:
        raise SceneError(
            f"pillar.inner_diameter = {p.inner_diameter:g} is out of range: the wall must be at "
            f"least pillar.outer_diameter / 2000 = {p.outer_diameter / 2000:g} m thick (D0/t <= 1000)"
        )


def _cross_checks(scene: Scene) -> None:
    _pillar_checks(scene.pillar)
    check_foundation(scene.foundation)
    if scene.drive.slope == 0 and scene.load.coefficient == 0:
        raise SceneError(
            "drive.slope = 0 and load.coefficient = 0: nothing limits the speed "
            "(Md = Mc never holds); give drive.slope > 0 or load.coefficient > 0"
        )
    mm = scene.modal_model
    if mm.gondola_inertia > 0 and mm.source != "beam":
        raise SceneError(
            f"modal_model.gondola_inertia = {mm.gondola_inertia:g}: only the 1D beam's modes carry it "
            f'(the 3D model\'s top has its mass, no rotary inertia): set modal_model.source = "beam", or 0'
        )
    w = scene.sweep
    if w.torque_high <= w.torque_low:
        raise SceneError(
            f"sweep.torque_high = {w.torque_high:g} is out of range: must be > "
            f"sweep.torque_low = {w.torque_low:g} (N*m)"
        )


def check_field(key: str, value: Any) -> Any:
    """One ``section.key`` value checked against its field's type and range, as a
    scene file's would be (SceneError naming the key), and returned converted."""
    section, _, name = key.partition(".")
    known = {f.name: f for f in fields(SECTIONS[section])} if section in SECTIONS else {}
    if name not in known:
        raise SceneError(f"{key}: unknown key")
    return _check_value(key, value, known[name])


def range_of(key: str) -> str:
    """The allowed range of ``section.key`` in words ("" for an unknown key)."""
    section, _, name = key.partition(".")
    known = {f.name: f for f in fields(SECTIONS[section])} if section in SECTIONS else {}
    return _range_text(known[name].metadata) if name in known else ""


def _field_of(key: str) -> dataclasses.Field[Any]:
    """The field of ``section.key``, or the scene file's one line about an unknown key."""
    section, dot, name = key.partition(".")
    if not (section and dot and name) or "." in name:
        raise SceneError(f"{key!r}: a scene key is section.key, e.g. shaft.stiffness")
    if section not in SECTIONS:
        raise SceneError(f"[{section}]: unknown section; a scene has " + ", ".join(f"[{s}]" for s in SECTIONS))
    known = {f.name: f for f in fields(SECTIONS[section])}
    if name not in known:
        raise SceneError(f"{key}: unknown key; [{section}] takes " + ", ".join(known))
    return known[name]


def _file_order(key: str) -> tuple[int, int]:
    """Where a scene file's validation meets ``section.key``: sections, then fields, in order."""
    section, _, name = key.partition(".")
    names = [f.name for f in fields(SECTIONS[section])]
    return list(SECTIONS).index(section), names.index(name)


def with_values(scene: Scene, values: Mapping[str, Any]) -> Scene:
    """A new scene: ``scene`` with each ``section.key`` of ``values`` set to its typed value.

    Each value is checked as a scene file's (its type and range, then the checks
    across keys), and a bad one is the same SceneError line that ``--set`` and
    the file give.  Nothing is formatted as text or parsed: a float arrives as
    the float it is.  An array of tables (``pillar.cans``) takes its section
    objects (``Can``) or their tables.

    >>> from rotorpillar.scene import load_scene
    >>> s = with_values(load_scene("paper"), {"simulate.duration": 10, "modal_model.source": "beam"})
    >>> s.simulate.duration, s.modal_model.source
    (10.0, 'beam')
    >>> with_values(s, {"simulate.duration": 0.0})
    Traceback (most recent call last):
    ...
    rotorpillar.scene.fields.SceneError: simulate.duration = 0.0 is out of range: must be >= 0.001 and <= 100000 ...
    """
    known = {key: _field_of(key) for key in values}
    changes: dict[str, dict[str, Any]] = {}
    for key in sorted(values, key=_file_order):  # the first bad value is the one a scene file names
        value = values[key]
        if known[key].metadata.get("table") is not None and isinstance(value, (list, tuple)):
            value = [
                dataclasses.asdict(v) if dataclasses.is_dataclass(v) and not isinstance(v, type) else v for v in value
            ]
        section, _, name = key.partition(".")
        changes.setdefault(section, {})[name] = _check_value(key, value, known[key])
    if not changes:
        return scene
    sections = {sec: dataclasses.replace(getattr(scene, sec), **kv) for sec, kv in changes.items()}
    new = dataclasses.replace(scene, **sections)
    _cross_checks(new)
    return new


def check_combinations(scene: Scene) -> None:
    """The checks across keys of a scene whose fields each passed ``check_field`` (SceneError)."""
    _cross_checks(scene)


#: A scene's name becomes a directory: no separators, no "..", nothing hidden.
SCENE_NAME = re.compile(r"(?!.*\.\.)[^./\\\x00-\x1f][^/\\\x00-\x1f]{0,99}")


def scene_from_dict(data: dict[str, Any], name: str = "scene") -> Scene:
    """Validate a parsed TOML document and build the scene."""
    data = dict(data)
    description = data.pop("description", "")
    name = data.pop("name", name)
    if not isinstance(name, str) or not isinstance(description, str):
        raise SceneError("name and description must be strings")
    if not SCENE_NAME.fullmatch(name):
        raise SceneError(
            f"name = {name!r}: must be 1-100 characters without '/', '\\\\', '..' or "
            "control characters, not starting with '.' (it names out/<name>/)"
        )
    for key in data:
        if key not in SECTIONS:
            raise SceneError(f"[{key}]: unknown section; a scene has " + ", ".join(f"[{s}]" for s in SECTIONS))
    sections = {}
    for sec, cls in SECTIONS.items():
        if sec not in data:
            if sec in OPTIONAL_SECTIONS:
                continue
            raise SceneError(f"[{sec}]: missing section")
        sections[sec] = _build_section(sec, cls, data[sec])
    scene = Scene(name=name, description=description, **sections)
    _cross_checks(scene)
    return scene
