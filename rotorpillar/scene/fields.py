"""A scene field: its docstring (with unit), its allowed range, and the error that names it."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import field
from typing import Any

from ..errors import InputError


class SceneError(InputError):
    """Bad scene input; the message is one line naming the key and the range."""


def param(
    doc: str,
    default: Any = dataclasses.MISSING,
    *,
    gt: float | None = None,
    ge: float | None = None,
    lt: float | None = None,
    le: float | None = None,
    choices: Sequence[Any] | None = None,
    optional: bool = False,
    or_zero: bool = False,
    table: type | None = None,
) -> Any:
    """A scene field: its docstring (with unit) and its allowed range; ``or_zero``: 0 is
    allowed besides the range (the docstring says what 0 means: chosen, off).

    ``table``: the field is an array of tables (``[[section.key]]`` in TOML), each
    built and checked as that section class; ``ge`` / ``le`` then bound their count.
    """
    meta = dict(doc=doc, gt=gt, ge=ge, lt=lt, le=le, choices=choices, optional=optional, or_zero=or_zero, table=table)
    return field(default=default, metadata=meta)


def _range_text(meta: Mapping[str, Any]) -> str:
    if meta["choices"] is not None:
        return "one of " + ", ".join(repr(c) for c in meta["choices"])
    lo = f"> {meta['gt']:g}" if meta["gt"] is not None else f">= {meta['ge']:g}" if meta["ge"] is not None else None
    hi = f"< {meta['lt']:g}" if meta["lt"] is not None else f"<= {meta['le']:g}" if meta["le"] is not None else None
    parts = [p for p in (lo, hi) if p]
    text = " and ".join(parts) if parts else "any finite value"
    return f"0 or {text}" if meta.get("or_zero") else text
