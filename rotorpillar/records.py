"""Results as typed records: msgspec Structs, encoded and decoded by msgspec.

A result that crosses a layer (a command's JSON, a cache entry, the report's
input) is a frozen ``Record``: a msgspec Struct whose fields carry their unit
in their docstring.  msgspec writes it to JSON and reads it back, checking
every field's type and naming the path of a bad one
(``Expected `float`, got `str` - at `$.system.omega[0]```), so no record
writes its own ``to_json`` or ``from_json``.

- numpy arrays and scalars are encoded as lists and numbers; a field
  annotated ``Array`` is decoded back into a float ndarray;
- a float that is not finite (a NaN, an infinity) is written as ``null``, as
  strict JSON needs: a field that may hold one is typed ``float | None``;
- a union of records is told apart by a tag: declare each member with
  ``tag_field="kind"`` and its ``tag``
  (``class Pulse(Record, tag_field="kind", tag="pulse")``), or another tag
  field where the record already has a field named ``kind``.

Why msgspec rather than pydantic: the records are plain frozen data, and
msgspec decodes into them directly from JSON bytes with the error path,
several times faster and with no dependency beyond itself (docs/architecture.md).

>>> class Peak(Record):
...     omega: float
...     amplitude: float
>>> encode(Peak(1.5, float("nan")))
b'{"omega":1.5,"amplitude":null}'
>>> decode(b'{"omega":1.5,"amplitude":"x"}', Peak)
Traceback (most recent call last):
...
msgspec.ValidationError: Expected `float`, got `str` - at `$.amplitude`
"""

from __future__ import annotations

import dataclasses
import math
import re
import typing
from pathlib import Path
from typing import Annotated, Any, TypeVar

import msgspec
import numpy as np


@typing.dataclass_transform(field_specifiers=(msgspec.field,), frozen_default=True)
class Record(msgspec.Struct, frozen=True):
    """A typed, immutable result (a frozen msgspec Struct; its subclasses are frozen too,
    which ``frozen_default`` tells the type checker)."""


R = TypeVar("R")


class ArrayMarker:
    """Marks a field decoded into a float ndarray (``Array``)."""


#: A field that holds a float ndarray: a JSON list (nested for 2-D) on disk.
Array = Annotated[np.ndarray, ArrayMarker]


def enc_hook(obj: Any) -> Any:
    """What msgspec cannot encode by itself: numpy arrays and scalars, paths."""
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.floating):
        return float(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, Path):
        return str(obj)
    raise NotImplementedError(f"cannot encode {type(obj).__name__}")


def dec_hook(type_: type, obj: Any) -> Any:
    """What msgspec cannot decode by itself: a list into a float ndarray."""
    if type_ is np.ndarray or typing.get_origin(type_) is np.ndarray:  # Array or NDArray[...]
        if not isinstance(obj, list):
            raise TypeError(f"Expected `array`, got `{type(obj).__name__}`")
        return np.asarray([math.nan if v is None else v for v in obj] if _flat(obj) else obj, dtype=float)
    if type_ is Path:
        return Path(obj)
    raise TypeError(f"cannot decode {type_}")


def _flat(obj: Any) -> bool:
    return isinstance(obj, list) and not any(isinstance(v, list) for v in obj)


_ENCODER = msgspec.json.Encoder(enc_hook=enc_hook)


def encode(obj: Any) -> bytes:
    """Compact JSON of a record (or of any builtins and records)."""
    return _ENCODER.encode(obj)


def encode_pretty(obj: Any) -> bytes:
    """JSON of a record, indented by two spaces, as the commands write it."""
    return msgspec.json.format(_ENCODER.encode(obj), indent=2)


def to_builtins(obj: Any) -> Any:
    """A record as dicts, lists and numbers (non-finite floats as None)."""
    return msgspec.json.decode(_ENCODER.encode(obj))


def decode(data: bytes | str, type_: type[R]) -> R:
    """A record from JSON text; msgspec.ValidationError names the bad field's path."""
    return msgspec.json.decode(data, type=type_, dec_hook=dec_hook)


def convert(obj: Any, type_: type[R]) -> R:
    """A record from builtins (a dict read from JSON)."""
    return msgspec.convert(obj, type=type_, dec_hook=dec_hook)


def read(path: str | Path, type_: type[R]) -> R:
    """The record in the JSON file at ``path``; a damaged file raises
    ValueError naming the file and the path of the bad field."""
    path = Path(path)
    data = path.read_bytes()
    try:
        return decode(data, type_)
    except msgspec.ValidationError as err:
        raise ValueError(f"{path.name}: {err}") from None
    except msgspec.DecodeError as err:
        raise ValueError(f"{path.name}: not JSON ({where_malformed(data, str(err))})") from None


def where_malformed(data: bytes, message: str) -> str:
    r"""msgspec's message on malformed JSON with the place in words: its line and column
    and the text there (a NaN or Infinity a hand or another tool wrote, a stray comma).

    >>> where_malformed(b'{"a": [1,\n NaN]}', "JSON is malformed: invalid character (byte 11)")
    "JSON is malformed: invalid character at line 2, column 2: 'NaN]}'"
    """
    found = re.search(r" \(byte (\d+)\)$", message)
    if found is None:
        return message
    at = int(found.group(1))
    line = data.count(b"\n", 0, at) + 1
    column = at - (data.rfind(b"\n", 0, at) + 1) + 1
    text = data[at : at + 12].split(b"\n")[0].decode("utf-8", "replace")
    return f"{message[: found.start()]} at line {line}, column {column}: {text!r}"


S = TypeVar("S")


def replace(obj: S, /, **changes: Any) -> S:
    """A copy of a record (or of a frozen dataclass) with the given fields changed."""
    if isinstance(obj, msgspec.Struct):
        return msgspec.structs.replace(obj, **changes)
    return dataclasses.replace(obj, **changes)  # type: ignore[type-var]


def tag(record: msgspec.Struct) -> str:
    """The tag of a record of a tagged union (its ``kind``, or the union's other tag field)."""
    value = type(record).__struct_config__.tag
    if not isinstance(value, str):
        raise TypeError(f"{type(record).__name__} is no tagged record")
    return value


class Figure(Record):
    """A chart a command drew: its file and what it shows."""

    file: str
    """the PNG's name, in the command's output folder"""
    caption: str
    """what it shows, in a sentence or two"""
