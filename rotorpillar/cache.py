"""The one on-disk cache of computed results: key, path, atomic write, tolerant read.

The convergence study's runs (rotorpillar.converge.runner), a design study's
batches (rotorpillar.studies.study), the chain's 3D modes
(rotorpillar.chain.modes) and the speed-against-accuracy study's runs
(rotorpillar.transients.pareto) are each cached as one small JSON file a
result, ``<root>/<key>.json``: an :class:`Entry`, the key beside the record.

- the key hashes the arguments' JSON (sorted keys) with a version and the
  hash of the source files the result depends on, so a changed argument or
  code never reuses a stale file;
- a file is written atomically (:func:`rotorpillar.provenance.write_json`:
  a temporary file renamed over the target), so an interrupted run leaves the
  finished entries whole and no partial one: the next run resumes;
- a read is tolerant: a missing, unreadable, cut-short or foreign file
  (another key, another record's shape: an entry of an older layout, or one
  the caller's ``accept`` refuses) is a miss, and the result is computed again.

>>> import tempfile
>>> from rotorpillar.records import Record
>>> class Peak(Record):
...     omega: float
>>> c = DiskCache(Path(tempfile.mkdtemp()))
>>> k = cache_key({"elements": 8}, version=1, code="abc")
>>> c.read(k, Peak) is None
True
>>> _ = c.write(k, Peak(2.5))
>>> c.read(k, Peak)
Peak(omega=2.5)
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Generic, TypeVar

import msgspec

from . import records
from .provenance import user_cache_root as user_cache_root  # re-exported: the callers of the cache find the root here
from .provenance import write_json

T = TypeVar("T")

KEY_LENGTH = 24
"""hex digits of a key (96 bits)"""


def source_hash(files: Iterable[Path]) -> str:
    """Hash of source files (each one's name and bytes, in the order given; a missing
    file is skipped): the code part of a key."""
    h = hashlib.sha256()
    for f in files:
        f = Path(f)
        if f.exists():
            h.update(f.name.encode())
            h.update(f.read_bytes())
    return h.hexdigest()[:16]


def file_hash(path: Path) -> str | None:
    """The content hash of a file (None when there is none)."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:24]
    except OSError:
        return None


def cache_key(args: Mapping[str, Any], *, version: int, code: str) -> str:
    """The key of a result: the hash of its arguments' JSON, the cache's layout ``version``
    and the ``code`` it was computed by (:func:`source_hash`).  Values JSON cannot hold
    are written as their ``str``."""
    doc = {"args": args, "code": code, "version": version}
    text = json.dumps(doc, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:KEY_LENGTH]


class Entry(records.Record, Generic[T]):
    """One cached result: its key (the read checks it) and its record."""

    key: str
    value: T


@dataclass(frozen=True)
class DiskCache:
    """A folder of cached results, one ``<prefix><key>.json`` file each."""

    root: Path
    """the folder (created on the first write)"""
    prefix: str = ""
    """put before the key in a file's name"""

    def path(self, key: str) -> Path:
        return Path(self.root) / f"{self.prefix}{key}.json"

    def read(self, key: str, type_: type[T], accept: Callable[[T], bool] | None = None) -> T | None:
        """The ``type_`` record stored under ``key``, or None (a miss) when there is none, it
        cannot be read or decoded as one, it holds another key, or ``accept`` refuses it."""
        try:
            entry = records.decode(self.path(key).read_bytes(), Entry[type_])  # type: ignore[valid-type]
        except (OSError, msgspec.DecodeError, msgspec.ValidationError):
            return None
        if entry.key != key:
            return None
        value: T = entry.value
        return value if accept is None or accept(value) else None

    def write(self, key: str, value: Any) -> Path:
        """Store ``value`` (a record) atomically beside its ``key``."""
        return write_json(self.path(key), Entry(key, value))
