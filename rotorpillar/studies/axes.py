"""The axes of a design study: ``--vary KEY=START:STOP:N`` and ``--vary KEY=v1,v2,...``.

An axis is a scene key (``section.key``) and its values; the study runs the
product of its axes.  The product's size is checked first, from the counts
alone (``START:STOP:N`` gives N, a list its items), before any value is
built; then every value is checked as ``--set KEY=VALUE`` would check it
(the key's type and range, the scene's cross-checks), and every point of the
product builds a valid scene, before anything runs: bad input is one line
naming the key and its range (InputError, exit 2).  A point is checked by
its own values and the scene's checks across keys only (the base scene's
other keys passed when it was loaded), a few microseconds each, so that
``MAX_RUNS`` points take well under a second.

>>> from rotorpillar.scene import load_scene
>>> a = parse_vary("drive.torque_at_zero=560:700:3", load_scene("sommerfeld"))
>>> a.key, a.values
('drive.torque_at_zero', (560.0, 630.0, 700.0))
>>> parse_vary("excitation.record=elcentro", load_scene("paper")).values
('elcentro',)
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import tomllib
from pathlib import Path

from ..errors import InputError
from ..records import Record
from ..scene import CASES, SECTIONS, Scene, SceneError, check_combinations, check_field, with_values

#: keys a study sets itself (by --case and --model) or does not use: the
#: batch loop integrates with the compiled dp5 at the scene's rtol
NOT_VARIED = {
    "simulate.case": "give --case",
    "simulate.model": "give --model",
    "simulate.integrator": "a study integrates with the compiled batch loop (dp5)",
    "simulate.time_step": "a study integrates with the compiled batch loop (dp5)",
    "simulate.samples": "a study keeps its own output grid",
    "reduction.source": "a study runs the reduced models only (the 3D reduction is not run)",
    "modal_model.source": "a study runs the reduced models only (the 3D modes are not run)",
}
#: the most runs one study may hold
MAX_RUNS = 100_000


Param = bool | int | float | str
"""A value of a scene key a study varies (a number, a word, a record's file)."""


class Axis(Record):
    """One axis of a study: a scene key and its values."""

    key: str
    """section.key of the scene"""
    values: tuple[Param, ...]
    """the values run, in order (numbers, or strings such as record files)"""
    spec: str
    """the --vary text it came from"""


def _field(key: str):
    parts = key.split(".")
    if len(parts) != 2 or parts[0] not in SECTIONS:
        raise InputError(f"--vary {key}: unknown key; KEY is section.key with section one of " + ", ".join(SECTIONS))
    fields = {f.name: f for f in dataclasses.fields(SECTIONS[parts[0]])}
    if parts[1] not in fields:
        raise InputError(f"--vary {key}: unknown key; [{parts[0]}] takes " + ", ".join(fields))
    if key in NOT_VARIED:
        raise InputError(f"--vary {key}: not a study axis ({NOT_VARIED[key]})")
    return fields[parts[1]]


def _cut(text: str) -> str:
    """The user's text as a message quotes it: at most 60 characters."""
    return text if len(text) <= 60 else f"{text[:40]}... ({len(text)} characters)"


def _count(n: int) -> str:
    return f"{n:,}" if n < 10**15 else f"{float(n):.3g}" if n.bit_length() < 1000 else "more than 1e300"


def _number(text: str, what: str, key: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise InputError(f"--vary {key}: {what} {_cut(text)!r} is not a number") from None
    if not math.isfinite(x):
        raise InputError(f"--vary {key}: {what} {_cut(text)!r} must be finite")
    return x


def _range(key: str, body: str, is_int: bool) -> tuple:
    parts = body.split(":")
    if len(parts) != 3 or not all(p.strip() for p in parts):
        raise InputError(f"--vary {key}={_cut(body)}: expected START:STOP:N")
    a, b = _number(parts[0], "START", key), _number(parts[1], "STOP", key)
    try:
        n = int(parts[2])
    except ValueError:
        raise InputError(f"--vary {key}={_cut(body)}: N = {_cut(parts[2])!r} must be an integer >= 1") from None
    if n < 1:
        raise InputError(f"--vary {key}={_cut(body)}: N = {n} must be >= 1")
    if n > 1 and a == b:
        raise InputError(f"--vary {key}={_cut(body)}: empty range (START = STOP with N = {n})")
    vals = [a] if n == 1 else [a + (b - a) * i / (n - 1) for i in range(n)]
    if is_int:
        if any(abs(v - round(v)) > 1e-9 * max(1.0, abs(v)) for v in vals):
            raise InputError(
                f"--vary {key}={_cut(body)}: {key} takes integers; START:STOP:N gives {', '.join(f'{v:g}' for v in vals)}"
            )
        vals = [int(round(v)) for v in vals]
        if len(set(vals)) < len(vals):
            raise InputError(f"--vary {key}={_cut(body)}: repeated values")
    return tuple(vals)


def _list(key: str, body: str) -> tuple:
    items = [t.strip() for t in body.split(",")]
    if not body.strip() or not all(items):
        raise InputError(f"--vary {key}={_cut(body)}: empty value in the list v1,v2,...")
    vals = []
    for t in items:
        try:
            vals.append(tomllib.loads(f"v = {t}")["v"])
        except tomllib.TOMLDecodeError:
            vals.append(t)  # a bare word or a path
        except ValueError:  # Python's limit on integer strings
            raise InputError(f"--vary {key}: an integer of {len(t)} characters is out of range") from None
    if len(set(map(repr, vals))) < len(vals):
        raise InputError(f"--vary {key}={_cut(body)}: repeated values")
    return tuple(vals)


def _split(text: str) -> tuple[str, str]:
    if "=" not in text:
        raise InputError(f"--vary {_cut(text)!r}: expected KEY=START:STOP:N or KEY=v1,v2,...")
    key, body = (s.strip() for s in text.split("=", 1))
    _field(key)  # an unknown key: InputError naming it
    if not body:
        raise InputError(f"--vary {key}=: empty range; expected START:STOP:N or v1,v2,...")
    return key, body


def _is_range(f, body: str) -> bool:
    want = f.type if isinstance(f.type, str) else f.type.__name__
    return ":" in body and "str" not in want


def axis_size(text: str) -> int:
    """How many values one ``--vary`` gives, from its text alone (nothing built).

    >>> axis_size("drive.torque_at_zero=560:700:1000000"), axis_size("rotor.mass=1,2,3")
    (1000000, 3)
    """
    key, body = _split(text)
    if not _is_range(_field(key), body):
        return len(body.split(","))
    parts = body.split(":")
    if len(parts) != 3 or not all(p.strip() for p in parts):
        raise InputError(f"--vary {key}={_cut(body)}: expected START:STOP:N")
    try:
        n = int(parts[2])
    except ValueError:
        raise InputError(f"--vary {key}={_cut(body)}: N = {_cut(parts[2])!r} must be an integer >= 1") from None
    if n < 1:
        raise InputError(f"--vary {key}={_cut(body)}: N = {n} must be >= 1")
    return n


def _checked(scene: Scene, key: str, value):
    """``value`` for ``key`` checked as ``--set`` checks it: the field's type and range,
    then the scene's checks across keys with this value in place."""
    try:
        v = check_field(key, value)
        check_combinations(_with(scene, {key: v}))
    except SceneError as exc:
        raise InputError(f"--vary {key}: {exc}") from None
    return v


def _copy(obj, changes: dict):
    """A copy of a frozen dataclass with ``changes`` set (no ``__init__`` run)."""
    out = object.__new__(type(obj))
    out.__dict__.update(obj.__dict__)
    out.__dict__.update(changes)
    return out


def _with(scene: Scene, params: dict) -> Scene:
    """The scene with checked values in place (no field re-checked: see the module text).

    A copy with the attributes set, not ``dataclasses.replace``: the sections have no
    ``__post_init__`` (their checks are ``check_field`` and ``check_combinations``), and
    such a copy costs a microsecond where replace costs ten (MAX_RUNS points, each checked).
    """
    by_section: dict[str, dict] = {}
    for key, v in params.items():
        sec, name = key.split(".", 1)
        by_section.setdefault(sec, {})[name] = v
    return _copy(
        scene,
        {
            sec: (SECTIONS[sec](**vals) if getattr(scene, sec) is None else _copy(getattr(scene, sec), vals))
            for sec, vals in by_section.items()
        },
    )


def parse_vary(text: str, scene: Scene) -> Axis:
    """One ``--vary`` argument, checked against the scene's key and its range."""
    key, body = _split(text)
    f = _field(key)
    if _is_range(f, body):
        want = f.type if isinstance(f.type, str) else f.type.__name__
        vals = _range(key, body, "int" in want)
    else:
        vals = _list(key, body)
    if key == "excitation.record":
        vals = tuple(str(Path(v).resolve()) if Path(str(v)).is_file() else v for v in vals)
    for v in vals:
        _checked(scene, key, v)
    return Axis(key, vals, text)


def parse_axes(texts: list[str], scene: Scene) -> tuple[Axis, ...]:
    """Every ``--vary``; at least one, each key once, at most MAX_RUNS points (checked
    from the counts before any value is built)."""
    if not texts:
        raise InputError("study: give at least one --vary KEY=START:STOP:N or KEY=v1,v2,...")
    keys = [_split(t)[0] for t in texts]
    for k in keys:
        if keys.count(k) > 1:
            raise InputError(f"--vary {k}: given twice (one axis per key)")
    sizes = [axis_size(t) for t in texts]
    n = math.prod(sizes)
    if n > MAX_RUNS:
        raise InputError(
            f"--vary: {_count(n)} runs in the product ("
            + " x ".join(f"{k} {_count(m)}" for k, m in zip(keys, sizes))
            + f"); a study holds at most {MAX_RUNS:,}"
        )
    return tuple(parse_vary(t, scene) for t in texts)


def implied_settings(axes: tuple[Axis, ...], case: str, scene: Scene) -> dict:
    """Keys the study sets because of its axes: varying a record or its scale
    makes the earthquake a record (``excitation.kind = "record"``); varying the ground's
    direction or its components (``SPATIAL_AXES``) runs every point on the spatial ROM
    (``modal_model.planes = "spatial"``), so that one model covers the whole axis (with
    "auto" the point in the rotor's plane would run the planar ROM and the next one the
    spatial, and the difference of the models would read as the angle's)."""
    if case not in CASES:
        raise InputError(f"--case {case!r}: must be one of {', '.join(CASES)}")
    keys = {a.key for a in axes}
    out = {}
    if (
        case == "earthquake"
        and keys & {"excitation.record", "excitation.record_scale", "excitation.record_units"}
        and "excitation.kind" not in keys
        and scene.excitation.kind != "record"
    ):
        out["excitation.kind"] = "record"
    if keys & SPATIAL_AXES and "modal_model.planes" not in keys and scene.modal_model.planes == "auto":
        out["modal_model.planes"] = "spatial"
    return out


#: axes whose values only the spatial ROM can tell apart
SPATIAL_AXES = frozenset({"excitation.angle", "excitation.components", "excitation.record_y", "excitation.record_z"})


def points(axes: tuple[Axis, ...]) -> list[dict]:
    """The product of the axes: one {key: value} per run, the last axis fastest."""
    return [dict(zip((a.key for a in axes), combo)) for combo in itertools.product(*(a.values for a in axes))]


def run_scene(scene: Scene, params: dict, implied: dict | None = None) -> Scene:
    """The scene of one run (validated, cross-checks included)."""
    return with_values(scene, {**(implied or {}), **params})


def check_points(scene: Scene, axes: tuple[Axis, ...], implied: dict) -> list[dict]:
    """Every point of the product, each checked to build a valid scene (as
    ``run_scene`` builds it; the values were checked one by one in ``parse_vary``)."""
    base = _with(scene, {k: check_field(k, v) for k, v in implied.items()}) if implied else scene
    keys = [a.key for a in axes]
    converted = [[check_field(a.key, v) for v in a.values] for a in axes]
    for combo, raw in zip(itertools.product(*converted), itertools.product(*(a.values for a in axes))):
        try:
            check_combinations(_with(base, dict(zip(keys, combo))))
        except SceneError as exc:
            raise InputError(
                f"--vary: the point {', '.join(f'{k}={v}' for k, v in zip(keys, raw))} is not a valid scene: {exc}"
            ) from None
    return points(axes)
