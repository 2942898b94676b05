"""Which stages of `rotorpillar run` must run again: each stage's key, kept once it succeeded.

A stage's key (:func:`stage_key`) hashes what its result depends on:

- its command line as run, less the scene, the ``--set`` overrides (the
  resolved scene stands for them) and ``--out`` (the folder the key is kept in);
- the resolved scene the stage sees (its own ``--set`` before the user's),
  less the sections it is known not to read (:data:`SECTIONS_NOT_READ`; a
  stage not listed there reads the whole scene);
- the files it reads from the output folder: the JSON of every stage of an
  earlier wave, by content (a missing one counts as missing).  This is the
  conservative reading: every JSON carries its provenance (its time), so an
  earlier stage that ran again changes the keys of every stage after it;
- the code: every file of the rotorpillar package and the libraries' versions
  (:func:`code_hash`).

Once a stage has succeeded, run keeps ``<out>/stages/<stem>.json``
(:func:`remember`, atomically): its key, when it finished, what it took and
the hash of the JSON it left.  The file is removed before the stage starts
(:func:`forget`), so a stage that fails or is interrupted is never taken for
done.  A stage is reused (:func:`recall`) when the kept key is its key now and
its files are still the ones it left: a command run by hand into the same
folder since then does not pass.

>>> import tempfile
>>> out = Path(tempfile.mkdtemp())
>>> _ = (out / "modal.json").write_text("{}")
>>> _ = remember(out, "modal", "k1", 29.0)
>>> recall(out, "modal", "k1").seconds, recall(out, "modal", "k2")
(29.0, None)
>>> _ = (out / "modal.json").write_text('{"by": "hand"}')
>>> recall(out, "modal", "k1") is None
True
"""

from __future__ import annotations

import datetime
import functools
import hashlib
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import msgspec

from .. import records
from ..cache import Entry, cache_key, file_hash
from ..provenance import write_json
from ..records import Record

#: Layout of a stage's key: a change here makes every kept key a miss.
KEY_VERSION = 1

#: Where run keeps its stages' keys, inside the output folder.
STAGES_FOLDER = "stages"

#: Scene sections a stage does not read, by its command's first word; a stage not
#: listed reads the whole scene.  Only the early stages (the expensive ones) are
#: listed, from their code: the convergence study and `modal` read the tube, its
#: foundation, the masses on top, the mesh ladder, the study's limits and the band
#: (the drive's free speed: [drive] and [load]), never the transients' settings, the
#: ground motion, the 3D full order's or the published numbers.  The study takes the
#: band by the modes inside it, not by [drive] and [load] (commands.run.band_modes,
#: chain.choice.STUDY_INPUTS): a new stall torque whose band holds the same modes
#: leaves it alone.  modal takes it by how many of its modes lie inside it
#: (commands.run.modal_band), the same way.
SECTIONS_NOT_READ: Mapping[str, frozenset[str]] = {
    "converge": frozenset(
        {"simulate", "excitation", "sweep", "full_order", "reference", "description", "drive", "load"}
    ),
    "modal": frozenset({"simulate", "excitation", "sweep", "full_order", "reference", "description", "drive", "load"}),
}


class StageDone(Record):
    """A stage that succeeded: what `run` keeps of it under its key."""

    finished: str
    """when it finished (UTC, ISO 8601)"""
    seconds: float
    """its wall time then (s)"""
    outputs: dict[str, str]
    """the files it left, by name in the output folder -> their content hash"""


def package_hash(root: Path) -> str:
    """Hash of every file under ``root`` (its path there and its bytes), compiled caches aside."""
    h = hashlib.sha256()
    for f in sorted(p for p in Path(root).rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        h.update(f.relative_to(root).as_posix().encode() + b"\0")
        h.update(f.read_bytes())
        h.update(b"\0")
    return h.hexdigest()[:16]


@functools.lru_cache(maxsize=1)
def code_hash() -> str:
    """The code every stage runs: the rotorpillar package's files (its sources, scenes
    and templates; ~2 MB read once a run, 0.06 s) and the versions of Python and of the
    libraries it relies on (provenance.versions: an upgraded dolfinx runs every stage again)."""
    from ..provenance import versions

    own = package_hash(Path(__file__).resolve().parent.parent)
    return cache_key(versions(), version=KEY_VERSION, code=own)[:16]


def command_words(command: str, own: Sequence[str], extra: Sequence[str] = ()) -> list[str]:
    """A stage's command line as it bears on the result: the command, its own
    arguments and run's flags for it, without the --set overrides (the scene has them).

    >>> command_words("compare --case earthquake", ("--set", "excitation.start=1", "--models", "modal"))
    ['compare', '--case', 'earthquake', '--models', 'modal']
    """
    words, rest = command.split(), [*own, *extra]
    i = 0
    while i < len(rest):
        if rest[i] == "--set":
            i += 2
            continue
        words.append(rest[i])
        i += 1
    return words


def stage_key(
    command: str,
    words: Sequence[str],
    scene_dict: Mapping[str, Any],
    inputs: Iterable[Path],
    code: str | None = None,
) -> str:
    """The key of a stage: its command line (:func:`command_words`), the scene sections it
    reads, the content of the files it reads and the code (:func:`code_hash`)."""
    not_read = SECTIONS_NOT_READ.get(command.split()[0], frozenset())
    doc = {
        "command": list(words),
        "scene": {k: v for k, v in scene_dict.items() if k not in not_read},
        "inputs": {Path(p).name: file_hash(Path(p)) for p in sorted(inputs, key=lambda p: Path(p).name)},
    }
    return cache_key(doc, version=KEY_VERSION, code=code_hash() if code is None else code)


def _path(out: Path, stem: str) -> Path:
    return Path(out) / STAGES_FOLDER / f"{stem}.json"


def forget(out: Path, stem: str) -> None:
    """Drop a stage's kept key: called before it runs, so that only its success keeps one."""
    _path(out, stem).unlink(missing_ok=True)


def remember(out: Path, stem: str, key: str, seconds: float, others: Sequence[str] = ()) -> Path:
    """Keep a stage that has just succeeded: its key, now, its time and the content hash of
    the files it left: its ``<stem>.json`` and ``others`` (names in ``out``; one missing is
    left out)."""
    now = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    outputs = {name: file_hash(Path(out) / name) for name in [f"{stem}.json", *others]}
    kept = {name: digest for name, digest in outputs.items() if digest is not None}
    return write_json(_path(out, stem), Entry(key, StageDone(now, seconds, kept)))


def recall(out: Path, stem: str, key: str) -> StageDone | None:
    """The kept record of a stage when its key is ``key`` and its files are still the ones
    it left; None (run it) otherwise: no record, an unreadable one, another key, a file
    gone or rewritten since."""
    try:
        entry = records.decode(_path(out, stem).read_bytes(), Entry[StageDone])
    except (OSError, msgspec.DecodeError, msgspec.ValidationError):
        return None
    done: StageDone = entry.value
    if entry.key != key:
        return None
    if f"{stem}.json" not in done.outputs:  # it left no JSON: nothing to reuse
        return None
    for name, digest in done.outputs.items():
        if file_hash(Path(out) / name) != digest:
            return None
    return done


def since(done: StageDone) -> str:
    """When a kept stage finished, in local time to the minute ("2026-11-27 19:02")."""
    return datetime.datetime.fromisoformat(done.finished).astimezone().strftime("%Y-%m-%d %H:%M")
