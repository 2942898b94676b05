"""Where many independent runs go: a Dask cluster, local or remote.

``Executor`` is a context manager around a ``dask.distributed.Client``:

- by default a ``LocalCluster`` on this machine, one worker process per core
  (``threads_per_worker=1``: the compiled loops and the finite-element
  subprocesses are single-threaded), no dashboard, listening on the
  loopback interface only;
- ``Executor(scheduler="tcp://HOST:PORT")``: a cluster someone started
  (``dask scheduler`` and ``dask worker``; the README shows how); the
  workers must import this package.  Before Dask is handed the address,
  ``probe_scheduler`` reads the greeting a Dask scheduler sends on
  connection, within ``HANDSHAKE_SECONDS`` in all: nothing listening, a
  silent server or a server of another kind is refused at once (InputError,
  exit 2), naming what was found; a real scheduler then has
  ``WORKERS_SECONDS`` to show a worker;
- ``Executor(processes=False)``: one worker thread inside this process (the
  in-process scheduler: for tests and debugging).

``ex.map(fn, items)`` submits ``fn(item)`` for every item, longest first
if the caller orders them so, and yields ``(index, result)`` as each
finishes, so the caller can write it to disk at once.  Leaving the ``with``
block (Ctrl-C included) cancels what has not finished and closes the
cluster it started.

Local workers are at most the cores this process may run on
(``check_workers``): each worker runs one single-threaded run at a time, so
more only share the cores, and each costs a process's start and memory.

>>> describe_workers({"workers": {"a": {"nthreads": 1}, "b": {"nthreads": 1}}})
(2, 2)
"""

from __future__ import annotations

import logging
import socket
import struct
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any, TypeVar

from .errors import ComputationError, InputError
from .provenance import usable_cores
from .records import Record

T = TypeVar("T")
R = TypeVar("R")

#: The whole probe of a scheduler's address (connect and its greeting), seconds.
HANDSHAKE_SECONDS = 5.0
#: How long a scheduler that answered may take to show its first worker (s).
WORKERS_SECONDS = 20.0
#: A Dask greeting is a few dozen bytes; a length past this is another protocol.
GREETING_MAX_BYTES = 1 << 16


def default_workers() -> int:
    """One worker per core this process may run on."""
    return usable_cores()


def check_workers(workers: int | None, flag: str = "--workers") -> None:
    """Refuse (InputError) a number of local workers below 1 or above the usable cores."""
    if workers is None:
        return
    cores = usable_cores()
    if workers < 1:
        raise InputError(f"{flag} {workers}: must be >= 1")
    if workers > cores:
        raise InputError(
            f"{flag} {workers}: this process may run on {cores} cores; at most "
            f"{cores} local workers (each runs one single-threaded run at a time: "
            "more only share the cores); use --scheduler for more machines"
        )


def _address(scheduler: str) -> tuple[str, int]:
    rest = scheduler.split("://", 1)[1]
    host, _, port = rest.rpartition(":")
    host = host.strip("[]")
    if not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise InputError(f"--scheduler {scheduler!r}: expected tcp://HOST:PORT, e.g. tcp://127.0.0.1:8786")
    return host, int(port)


def _shown(data: bytes) -> str:
    text = data[:40].decode("ascii", "replace")
    return "".join(c if c.isprintable() else "." for c in text)


def probe_scheduler(scheduler: str, timeout: float | None = None) -> None:
    """Check that a Dask scheduler answers at ``tcp://HOST:PORT``, within ``timeout`` s in all
    (None: ``HANDSHAKE_SECONDS``, read when called).

    A Dask scheduler greets every connection first: an 8-byte length, then its
    frames (one msgpack dict naming its compression, Python and pickle
    protocol).  Anything else is refused with one line saying what was found:
    nothing listening, no answer, a server that says nothing or that is not a
    Dask scheduler (with its first bytes).  Only ``tcp://`` is probed (a TLS
    address greets after the TLS handshake).
    """
    if not scheduler.startswith("tcp://"):
        return
    if timeout is None:
        timeout = HANDSHAKE_SECONDS
    host, port = _address(scheduler)
    where = f"--scheduler {scheduler}"
    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except ConnectionRefusedError:
        raise InputError(f"{where}: nothing listening there (connection refused)") from None
    except socket.gaierror as exc:
        raise InputError(f"{where}: unknown host {host!r} ({exc.strerror})") from None
    except TimeoutError:
        raise InputError(
            f"{where}: no answer within {timeout:g} s (the connection was not accepted: a wrong host, or a firewall)"
        ) from None
    except OSError as exc:
        raise InputError(f"{where}: cannot connect ({exc.strerror or exc})") from None
    with sock:
        try:
            data, closed = _greeting(sock, deadline)
        except OSError as exc:
            raise InputError(f"{where}: the connection failed ({exc.strerror or exc})") from None
    if not data:
        raise InputError(
            f"{where}: a server that "
            + (
                "closed the connection without a word"
                if closed
                else f"accepts the connection but says nothing within {timeout:g} s"
            )
            + ": not a Dask scheduler"
        )
    size = struct.unpack("<Q", data[:8])[0] if len(data) >= 8 else None
    greeting = data[8 : 8 + size] if size is not None else b""
    if (
        size is None
        or size > GREETING_MAX_BYTES
        or len(greeting) < size
        or b"compression" not in greeting
        or b"python" not in greeting
    ):
        raise InputError(f"{where}: a server that is not a Dask scheduler (it sent {_shown(data)!r})")


def _greeting(sock: socket.socket, deadline: float) -> tuple[bytes, bool]:
    """(what the peer sent, whether it closed): read until its first message (8-byte
    length, then that many bytes) is whole, it grows past a greeting, the peer closes,
    or the deadline passes."""
    data = b""
    while True:
        need = 8 if len(data) < 8 else 8 + struct.unpack("<Q", data[:8])[0]
        left = deadline - time.monotonic()
        if len(data) >= need or need > 8 + GREETING_MAX_BYTES or left <= 0:
            return data, False
        sock.settimeout(left)
        try:
            chunk = sock.recv(4096)
        except TimeoutError:
            return data, False
        if not chunk:
            return data, True
        data += chunk


def describe_workers(info: dict) -> tuple[int, int]:
    """(workers, threads) of a scheduler's ``identity()``."""
    ws = info.get("workers", {})
    return len(ws), sum(int(w.get("nthreads", 1)) for w in ws.values())


class ExecutorInfo(Record):
    """Where a study's batches ran (``Executor.describe``)."""

    kind: str
    """LocalCluster, scheduler, in-process, or none (every batch on disk)"""
    scheduler: str | None
    """the scheduler's address"""
    workers: int
    """worker processes (-)"""
    threads: int
    """threads over the workers (-)"""


class Executor:
    """A Dask client on a local cluster (default) or on ``scheduler``."""

    def __init__(
        self,
        workers: int | None = None,
        scheduler: str | None = None,
        *,
        processes: bool = True,
        timeout: float = HANDSHAKE_SECONDS,
    ):
        if scheduler is None:
            check_workers(workers)
        elif workers is not None and workers < 1:
            raise InputError(f"--workers {workers}: must be >= 1")
        if scheduler is not None and not scheduler.startswith(("tcp://", "tls://", "inproc://")):
            raise InputError(f"--scheduler {scheduler!r}: expected an address such as tcp://127.0.0.1:8786")
        if scheduler is not None and scheduler.startswith(("tcp://", "tls://")):
            _address(scheduler)
        self.workers = workers
        self.scheduler = scheduler
        self.processes = processes
        self.timeout = timeout
        self.client: Any = None
        """the distributed.Client while entered, else None"""
        self.cluster: Any = None
        """the distributed.LocalCluster this executor started, else None"""

    # ------------------------------------------------------------ lifetime
    def __enter__(self) -> Executor:
        if self.scheduler is not None:
            probe_scheduler(self.scheduler, self.timeout)  # before Dask's imports: at once
        from distributed import Client, LocalCluster

        if self.scheduler is not None:
            where = f"--scheduler {self.scheduler}"
            try:
                self.client = Client(self.scheduler, timeout=self.timeout)
            except (OSError, TimeoutError) as exc:
                raise InputError(
                    f"{where}: no Dask handshake within {self.timeout:g} s ({type(exc).__name__}: {exc})"
                ) from None
            except MemoryError:  # a length read from a stranger's bytes, never memory
                raise InputError(
                    f"{where}: a server that is not a Dask scheduler (its reply could not be read)"
                ) from None
            try:
                self.client.wait_for_workers(1, timeout=WORKERS_SECONDS)
            except (OSError, TimeoutError):
                self.__exit__()
                raise InputError(
                    f"{where}: a Dask scheduler, but no worker joined it within "
                    f"{WORKERS_SECONDS:g} s: start `dask worker {self.scheduler}`"
                ) from None
            return self
        n = self.workers or default_workers()
        # no dashboard; the scheduler's bare HTTP endpoint on a free loopback port
        quiet = dict(
            threads_per_worker=1,
            dashboard_address=None,
            silence_logs=logging.ERROR,
            scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        )
        if self.processes:
            self.cluster = LocalCluster(n_workers=n, processes=True, host="127.0.0.1", memory_limit=0, **quiet)
        else:
            self.cluster = LocalCluster(n_workers=1, processes=False, **quiet)
        self.client = Client(self.cluster)
        return self

    def __exit__(self, *exc) -> None:
        # a worker slow to stop (a loaded machine) is killed after a few seconds, and the
        # nanny says so at WARNING: the work is done and written, nothing for the user
        nanny = logging.getLogger("distributed.nanny")
        level = nanny.level
        nanny.setLevel(logging.ERROR)
        try:
            for thing in (self.client, self.cluster):
                if thing is not None:
                    try:
                        thing.close()
                    except Exception:  # closing after Ctrl-C must not hide the Ctrl-C
                        pass
        finally:
            nanny.setLevel(level)
        self.client = self.cluster = None

    # ------------------------------------------------------------ what it is
    def describe(self) -> ExecutorInfo:
        """The scheduler and the workers used (for the results' provenance)."""
        workers, threads = describe_workers(self.client.scheduler_info())
        kind = "scheduler" if self.scheduler else "LocalCluster" if self.processes else "in-process"
        return ExecutorInfo(kind, self.client.scheduler.address, workers, threads)

    # ------------------------------------------------------------ work
    def map(self, fn: Callable[[T], R], items: Iterable[T], *, pure: bool = False) -> Iterator[tuple[int, R]]:
        """``(index, fn(item))`` for every item, in the order they finish.

        An exception in ``fn`` is raised here when its result comes up; the
        futures not yet finished are cancelled when the caller stops
        iterating (an exception, Ctrl-C, or ``break``)."""
        import uuid

        from distributed import as_completed

        items = list(items)
        # A key names a task to the scheduler, which hands back the result it still holds
        # under that key instead of running the task again: each call's keys are its own
        # (before, ``fn-i-id(self)``: a second call on the same executor, e.g. the convergence
        # ladder's next round, got the previous round's results, 19 rounds in 20)
        call = uuid.uuid4().hex
        futures = [
            self.client.submit(fn, item, pure=pure, key=f"{fn.__name__}-{i}-{call}") for i, item in enumerate(items)
        ]
        index = {f.key: i for i, f in enumerate(futures)}
        try:
            for fut in as_completed(futures):
                yield index[fut.key], _result(fut, self.scheduler)
        finally:
            pending = [f for f in futures if not f.done()]
            if pending and self.client is not None:
                try:
                    self.client.cancel(pending)
                except Exception:
                    pass


def _result(fut, scheduler: str | None):
    """A future's result; the cluster failing under it is a ComputationError naming the
    cluster, never a memory or file-system failure (CommClosedError is an OSError)."""
    from distributed.comm.core import CommClosedError

    try:
        return fut.result()
    except CommClosedError as exc:
        where = f"the Dask scheduler at {scheduler}" if scheduler else "the local Dask cluster"
        raise ComputationError(f"{where} stopped answering ({exc}); finished work is on disk") from None
