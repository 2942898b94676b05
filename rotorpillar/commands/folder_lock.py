"""One writer per output folder: a command holds ``<out>/.rotorpillar.lock`` while it runs.

Two commands writing into one folder at once would leave a mix of both
scenes' files, each file whole and the set meaningless.  The lock is an
advisory ``flock`` on a file in the folder, which the kernel releases when
its holder ends however it ends; the file names the holder (command,
process, start).  A second command is refused (InputError, exit 2) naming
it.  A lock file nobody holds was left by a process killed before it could
remove it (SIGKILL, a crash of the machine): it is taken over, and said so.

The stages of ``rotorpillar run`` write into their parent's folder: the
parent names the folder it holds in the environment (:data:`HELD`), and a
command started with that folder does not lock it again.  Under mpirun only
rank 0 locks (every rank runs the same command on the same folder).  A
command refused before its work leaves no trace: the lock file, and the
folders made to hold it, are removed when they are left empty.
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import os
import time
from collections.abc import Callable, Iterator
from pathlib import Path

from ..errors import InputError

LOCK_NAME = ".rotorpillar.lock"
#: The environment variable naming the output folder a parent command holds.
HELD = "ROTORPILLAR_HELD_OUT"


def _rank() -> int:
    for key in ("OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"):
        value = os.environ.get(key, "")
        if value.isdigit():
            return int(value)
    return 0


def _missing_dirs(path: Path) -> list[Path]:
    """The folders ``mkdir -p path`` would create, deepest first."""
    out = []
    while not path.exists() and path.parent != path:
        out.append(path)
        path = path.parent
    return out


def _read(fd: int) -> str:
    os.lseek(fd, 0, os.SEEK_SET)
    return os.read(fd, 4096).decode("utf-8", "replace").strip()


def _acquire(lock: Path) -> tuple[int, str]:
    """(descriptor holding the lock, what the file said before: a stale holder or "")."""
    while True:
        fd = os.open(lock, os.O_RDWR | os.O_CREAT, 0o666)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            holder = _read(fd) or "another rotorpillar command"
            os.close(fd)
            if exc.errno not in (errno.EAGAIN, errno.EACCES):
                raise
            raise InputError(
                f"--out {str(lock.parent)!r} is in use by {holder}: one command writes into a "
                "folder at a time; wait for it to end or give another --out"
            ) from None
        try:  # the holder before us may have removed the file as we opened it: lock the new one
            same = os.stat(lock).st_ino == os.fstat(fd).st_ino
        except FileNotFoundError:
            same = False
        if same:
            return fd, _read(fd)
        os.close(fd)


@contextlib.contextmanager
def output_lock(out: Path, command: str, say: Callable[[str], None]) -> Iterator[None]:
    """Hold ``out``'s lock for the length of the block (see the module text)."""
    folder = Path(os.path.abspath(out))
    if os.environ.get(HELD) == str(folder) or _rank() != 0:
        yield
        return
    made = _missing_dirs(folder)
    folder.mkdir(parents=True, exist_ok=True)
    lock = folder / LOCK_NAME
    try:
        fd, stale = _acquire(lock)
    except BaseException:
        _remove_empty(made)
        raise
    if stale:
        say(f"took over the lock of {folder} left by {stale}, which no longer runs")
    os.ftruncate(fd, 0)
    os.lseek(fd, 0, os.SEEK_SET)
    os.write(fd, f"rotorpillar {command} (process {os.getpid()}, started {time.strftime('%H:%M:%S')})\n".encode())
    os.environ[HELD] = str(folder)
    try:
        yield
    finally:
        del os.environ[HELD]
        with contextlib.suppress(OSError):
            lock.unlink()
        os.close(fd)
        _remove_empty(made)


def _remove_empty(made: list[Path]) -> None:
    """Remove the folders made for the lock, deepest first, as long as they are empty."""
    for d in made:
        try:
            d.rmdir()
        except OSError:
            return
