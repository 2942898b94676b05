"""The kinds of a result's JSON checked before the report reads it: a damaged file
(``null``, a list, values of the wrong kind) is named as damaged, with the key,
instead of failing a section later without its file's name.

>>> from rotorpillar.fem3d.modal_summary import ModalSummary
>>> shape_error(ModalSummary, {"modes": 5})
'modes is a JSON number, not a list'
>>> require({"case": "runup"}, {"case": str, "model": str}, "simulate_runup.json")
Traceback (most recent call last):
...
KeyError: "simulate_runup.json has no key 'model'"
"""

from __future__ import annotations

import dataclasses
import types
import typing
from typing import Any


def json_type(doc: Any) -> str:
    return {type(None): "null", list: "list", dict: "object", str: "string", bool: "boolean"}.get(type(doc), "number")


def require(doc: dict[str, Any], kinds: dict[str, Any], name: str) -> None:
    """Nothing if ``doc`` holds every key of ``kinds`` with a value of that Python type
    (``dict`` for a JSON object, ``list``, ``str``); else KeyError or TypeError naming the
    file and key."""
    for k, kind in kinds.items():
        if k not in doc:
            raise KeyError(f"{name} has no key {k!r}")
        if not isinstance(doc[k], kind):
            raise TypeError(
                f"{name}: {k} is a JSON {json_type(doc[k])}, not "
                + {dict: "an object", list: "a list", str: "a string"}[kind]
            )


_JSON_KINDS = {
    dict: (dict,),
    tuple: (list,),
    list: (list,),
    str: (str,),
    bool: (bool,),
    int: (int,),
    float: (int, float),
}


def _kind_error(hint: Any, value: Any, where: str) -> str | None:
    """Why ``value`` (from JSON) cannot be a ``hint``; None when it can or is unchecked."""
    origin, args = typing.get_origin(hint), typing.get_args(hint)
    if origin in (typing.Union, types.UnionType):
        if value is None and type(None) in args:
            return None
        inner = [a for a in args if a is not type(None)]
        return _kind_error(inner[0], value, where) if len(inner) == 1 else None
    if isinstance(hint, type) and dataclasses.is_dataclass(hint) and hasattr(hint, "from_json"):
        return (
            shape_error(hint, value, where + ".")
            if isinstance(value, dict)
            else f"{where} is a JSON {json_type(value)}, not an object"
        )
    base = origin or hint
    kinds = _JSON_KINDS.get(base) if isinstance(base, type) else None
    if kinds is None or (value is None and base in (float, int)):  # non-finite numbers: null
        return None
    if not isinstance(value, kinds) or (base is not bool and isinstance(value, bool)):
        want = {
            int: "a number",
            float: "a number",
            tuple: "a list",
            list: "a list",
            dict: "an object",
            str: "a string",
            bool: "a boolean",
        }[base]
        return f"{where} is a JSON {json_type(value)}, not {want}"
    if base is tuple and args:
        item = args[0]
        for i, v in enumerate(value if isinstance(value, list) else ()):
            why = _kind_error(item, v, f"{where}[{i}]")
            if why:
                return why
    return None


def shape_error(record_type, doc: dict, where: str = "") -> str | None:
    """The first key of ``doc`` whose JSON kind its record field cannot take (an object
    for a record or dict, a list for a tuple, a number, a string, a boolean), in words;
    None when every key present can (keys missing are another matter: another version)."""
    hints = typing.get_type_hints(record_type)
    for f in dataclasses.fields(record_type):
        key = f.metadata.get("json", f.name)
        if key in doc:
            why = _kind_error(hints.get(f.name), doc[key], where + key)
            if why:
                return why
    return None
