"""A scene field's declaration: its docstring (with unit) and its allowed range."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import field
from typing import Any


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
) -> Any:
    """A scene field: its docstring (with unit) and its allowed range."""
    meta = dict(doc=doc, gt=gt, ge=ge, lt=lt, le=le, choices=choices, optional=optional)
    return field(default=default, metadata=meta)


def _range_text(meta: Mapping[str, Any]) -> str:
    if meta["choices"] is not None:
        return "one of " + ", ".join(repr(c) for c in meta["choices"])
    lo = f"> {meta['gt']:g}" if meta["gt"] is not None else f">= {meta['ge']:g}" if meta["ge"] is not None else None
    hi = f"< {meta['lt']:g}" if meta["lt"] is not None else f"<= {meta['le']:g}" if meta["le"] is not None else None
    parts = [p for p in (lo, hi) if p]
    return " and ".join(parts) if parts else "any finite value"
