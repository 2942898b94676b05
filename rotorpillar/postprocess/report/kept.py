"""The mode pictures kept under a content key: drawn again only when what they show changes.

The pictures of a set of modes (one PNG a mode and the contact sheet, 10-30 s of
rendering a set) depend on the modes alone: their rows of modal.json, its axes
and their VTU, how many are drawn, and the code that draws them
(:func:`drawing_code`).  The drive, the runs and the rest of the scene do not
enter: a new stall torque leaves them as they were.

Once a set is drawn the report keeps ``modes/<name>_pictures.json``
(:func:`keep`, atomically): the key (:func:`modes_key`), when it was drawn, what
it took and the content hash of every PNG.  The next report whose key is the
same and whose PNGs are still the ones kept puts them on the page without
drawing them (:func:`recall`), and says so (stderr, report.json's ``reused``,
the timings appendix).  Another key, a PNG gone or rewritten since, or an
unreadable file: the set is drawn again.  The file is removed before a set is
drawn (:func:`forget`), so a drawing that fails or is interrupted is never taken
for done.

The report's charts (matplotlib PNGs under figures/) are kept the same way, one
``figures/<stem>_chart.json`` a chart (:func:`chart`): its key is the arguments
the chart is drawn from (the records and arrays its function is called with,
encoded as the records are), the function's name and the code of the whole
postprocess package (:func:`chart_code`); a chart of the convergence study or of
the modes is not drawn again when a new stall torque changes only the runs.

>>> import tempfile
>>> d = Path(tempfile.mkdtemp())
>>> _ = (d / "bare_mode_01.png").write_bytes(b"png 1")
>>> _ = (d / "bare_modes_sheet.png").write_bytes(b"sheet")
>>> _ = keep(d, "bare", "k1", [d / "bare_mode_01.png"], d / "bare_modes_sheet.png", 12.0, "vtkOSOpenGLRenderWindow")
>>> recall(d, "bare", "k1").seconds, recall(d, "bare", "k2")
(12.0, None)
>>> _ = (d / "bare_mode_01.png").write_bytes(b"drawn by another")
>>> recall(d, "bare", "k1") is None
True
"""

from __future__ import annotations

import datetime
import functools
import time
from collections.abc import Callable, Sequence
from importlib import metadata
from pathlib import Path

import msgspec

from ... import records
from ...cache import Entry, cache_key, file_hash, source_hash
from ...provenance import write_json
from ...records import Record
from .parallel import ModeFiles
from .state import Build, attempt, say

#: Layout of a key: a change here makes every kept set a miss.
KEY_VERSION = 1

_POSTPROCESS = Path(__file__).resolve().parent.parent

#: The code a set of mode pictures is drawn by: the job (report/parallel.py), the
#: renderer and what it reads and labels with, and this module.
DRAWING_FILES = (
    _POSTPROCESS / "report" / "parallel.py",
    _POSTPROCESS / "report" / "kept.py",
    _POSTPROCESS / "modeshapes.py",
    _POSTPROCESS / "geometry.py",
    _POSTPROCESS / "directions.py",
    _POSTPROCESS / "offscreen.py",
    _POSTPROCESS / "style.py",
)

#: The libraries whose version changes the pixels.
DRAWING_LIBRARIES = ("pyvista", "vtk", "matplotlib", "numpy")


class KeptPictures(Record):
    """A set of mode pictures drawn and kept under its key."""

    finished: str
    """when it was drawn (UTC, ISO 8601)"""
    seconds: float
    """its drawing's wall time then (s)"""
    window: str
    """the VTK render window class it was drawn with"""
    modes: tuple[str, ...]
    """one PNG a mode, the first mode first (names in the folder)"""
    sheet: str
    """the contact sheet (name in the folder)"""
    hashes: dict[str, str]
    """PNG name -> its content hash"""


class KeptChart(Record):
    """A chart drawn and kept under its key."""

    finished: str
    """when it was drawn (UTC, ISO 8601)"""
    seconds: float
    """its drawing's wall time then (s)"""
    chart: str
    """the PNG (name in the folder)"""
    hash: str
    """its content hash"""


def _libraries() -> tuple[tuple[str, str], ...]:
    """(library, its version or "absent") of each of :data:`DRAWING_LIBRARIES`."""
    found = []
    for name in DRAWING_LIBRARIES:
        try:
            found.append((name, metadata.version(name)))
        except metadata.PackageNotFoundError:
            found.append((name, "absent"))
    return tuple(found)


@functools.lru_cache(maxsize=1)
def drawing_code() -> str:
    """The code part of a key: :data:`DRAWING_FILES` and the versions of :data:`DRAWING_LIBRARIES`."""
    return cache_key(dict(_libraries()), version=KEY_VERSION, code=source_hash(DRAWING_FILES))[:16]


@functools.lru_cache(maxsize=1)
def chart_code() -> str:
    """The code part of a chart's key: every module of the postprocess package (the
    chart functions, the styles, the report's steps) and the versions of
    :data:`DRAWING_LIBRARIES`."""
    files = sorted(_POSTPROCESS.rglob("*.py"), key=lambda f: f.relative_to(_POSTPROCESS).as_posix())
    return cache_key(dict(_libraries()), version=KEY_VERSION, code=source_hash(files))[:16]


def modes_key(name: str, files: ModeFiles, count: int) -> str:
    """The key of the pictures of set ``name``: its VTU's content, its rows of modal.json
    and the axes, the modes drawn and the code (:func:`drawing_code`)."""
    args = {
        "name": name,
        "vtu": file_hash(files.vtu),
        "modes": records.to_builtins(list(files.modes)),
        "axes": records.to_builtins(files.axes),
        "count": count,
    }
    return cache_key(args, version=KEY_VERSION, code=drawing_code())


def _path(directory: Path, name: str) -> Path:
    return Path(directory) / f"{name}_pictures.json"


def forget(directory: Path, name: str) -> None:
    """Drop a set's kept key: called before it is drawn."""
    _path(directory, name).unlink(missing_ok=True)


def keep(directory: Path, name: str, key: str, modes: Sequence[Path], sheet: Path, seconds: float, window: str) -> Path:
    """Keep a set just drawn: its key, now, its time and the hash of each of its PNGs."""
    now = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    names = [Path(p).name for p in modes]
    hashes = {n: file_hash(Path(directory) / n) for n in [*names, Path(sheet).name]}
    kept = KeptPictures(now, seconds, window, tuple(names), Path(sheet).name, {n: h for n, h in hashes.items() if h})
    return write_json(_path(directory, name), Entry(key, kept))


def recall(directory: Path, name: str, key: str) -> KeptPictures | None:
    """The kept set when its key is ``key`` and its PNGs are still the ones drawn; None
    (draw it) otherwise."""
    try:
        entry = records.decode(_path(directory, name).read_bytes(), Entry[KeptPictures])
    except (OSError, msgspec.DecodeError, msgspec.ValidationError):
        return None
    kept: KeptPictures = entry.value
    if entry.key != key or set(kept.hashes) != {*kept.modes, kept.sheet}:
        return None
    for png, digest in kept.hashes.items():
        if file_hash(Path(directory) / png) != digest:
            return None
    return kept


def since(kept: KeptPictures | KeptChart) -> str:
    """When a kept set was drawn, in local time to the minute ("2026-11-27 19:02")."""
    return datetime.datetime.fromisoformat(kept.finished).astimezone().strftime("%Y-%m-%d %H:%M")


def chart_key(draw: Callable, args: Sequence, kwargs: dict) -> str:
    """The key of the chart ``draw(*args, **kwargs)`` draws: the function's name, its
    arguments (records, arrays, paths, numbers, encoded as the records are: every
    value of every array) and the code (:func:`chart_code`)."""
    what = {"draw": f"{draw.__module__}.{draw.__qualname__}", "args": list(args), "kwargs": kwargs}
    return cache_key({"draws": records.encode(what).decode()}, version=KEY_VERSION, code=chart_code())


def _chart_path(png: Path) -> Path:
    return Path(png).with_name(f"{Path(png).stem}_chart.json")


def recall_chart(png: Path, key: str) -> KeptChart | None:
    """The kept chart when its key is ``key`` and ``png`` is still the one drawn; None
    (draw it) otherwise."""
    try:
        entry = records.decode(_chart_path(png).read_bytes(), Entry[KeptChart])
    except (OSError, msgspec.DecodeError, msgspec.ValidationError):
        return None
    kept: KeptChart = entry.value
    if entry.key != key or kept.chart != Path(png).name or file_hash(png) != kept.hash:
        return None
    return kept


def keep_chart(png: Path, key: str, seconds: float) -> Path | None:
    """Keep a chart just drawn: its key, now, its time and its PNG's hash."""
    digest = file_hash(png)
    if digest is None:
        return None
    now = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    return write_json(_chart_path(png), Entry(key, KeptChart(now, seconds, Path(png).name, digest)))


def chart(build: Build, key: str, png: Path, draw: Callable[..., Path], *args, **kwargs) -> Path | None:
    """The chart ``draw(*args, **kwargs)`` writes to ``png`` (one of ``args``), drawn as
    an :func:`.state.attempt` step named ``key``, or the one an earlier report drew from
    the same arguments with the same code, unchanged since: then said (stderr,
    ``build.reused["chart_<key>"]``) and not drawn.

    The key is every argument whole, never a list of the fields a chart is thought to
    read: a chart given a record with timings in it (analyze.json's) is drawn every time,
    which costs a second; a field left out of such a list would show a stale chart."""
    try:
        k: str | None = chart_key(draw, args, kwargs)
    except (TypeError, ValueError, NotImplementedError):  # an argument the records cannot encode: drawn
        k = None
    if k is not None:
        was = recall_chart(png, k)
        if was is not None:
            say(f"{key}: unchanged since {since(was)}, reused")
            build.reused[f"chart_{key}"] = was.finished
            return Path(png)
    _chart_path(png).unlink(missing_ok=True)
    start = time.perf_counter()
    p = attempt(build, key, lambda: draw(*args, **kwargs))
    if p is not None and k is not None and Path(p) == Path(png):
        keep_chart(png, k, time.perf_counter() - start)
    return p
