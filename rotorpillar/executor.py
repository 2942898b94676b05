"""Where many independent runs go: a Dask cluster, local or remote.

``Executor`` is a context manager around a ``dask.distributed.Client``:

- by default a ``LocalCluster`` on this machine, one worker process per core
  (``threads_per_worker=1``: the compiled loops and the finite-element
  subprocesses are single-threaded), no dashboard, listening on the
  loopback interface only;
- ``Executor(scheduler="tcp://HOST:PORT")``: a cluster someone started
  (``dask scheduler`` and ``dask worker``; the README shows how); the
  workers must import this package;
- ``Executor(processes=False)``: one worker thread inside this process (the
  in-process scheduler: for tests and debugging).

``ex.map(fn, items)`` submits ``fn(item)`` for every item, longest first
if the caller orders them so, and yields ``(index, result)`` as each
finishes, so the caller can write it to disk at once.  Leaving the ``with``
block (Ctrl-C included) cancels what has not finished and closes the
cluster it started.

>>> describe_workers({"workers": {"a": {"nthreads": 1}, "b": {"nthreads": 1}}})
(2, 2)
"""

from __future__ import annotations

import logging
import os
from typing import Callable, Iterable, Iterator

from .errors import InputError


def default_workers() -> int:
    """One worker per core."""
    return max(1, os.cpu_count() or 1)


def describe_workers(info: dict) -> tuple[int, int]:
    """(workers, threads) of a scheduler's ``identity()``."""
    ws = info.get("workers", {})
    return len(ws), sum(int(w.get("nthreads", 1)) for w in ws.values())


class Executor:
    """A Dask client on a local cluster (default) or on ``scheduler``."""

    def __init__(self, workers: int | None = None, scheduler: str | None = None, *,
                 processes: bool = True, timeout: float = 30.0):
        if workers is not None and workers < 1:
            raise InputError(f"--workers {workers}: must be >= 1")
        if scheduler is not None and not scheduler.startswith(("tcp://", "tls://", "inproc://")):
            raise InputError(f"--scheduler {scheduler!r}: expected an address such as "
                             "tcp://127.0.0.1:8786")
        self.workers = workers
        self.scheduler = scheduler
        self.processes = processes
        self.timeout = timeout
        self.client = None
        self.cluster = None

    # ------------------------------------------------------------ lifetime
    def __enter__(self) -> "Executor":
        from distributed import Client, LocalCluster
        if self.scheduler is not None:
            try:
                self.client = Client(self.scheduler, timeout=self.timeout)
            except (OSError, TimeoutError) as exc:
                raise InputError(f"--scheduler {self.scheduler}: cannot connect ({exc})") from None
            if self.workers:
                self.client.wait_for_workers(1, timeout=self.timeout)
            return self
        n = self.workers or default_workers()
        # no dashboard; the scheduler's bare HTTP endpoint on a free loopback port
        quiet = dict(threads_per_worker=1, dashboard_address=None, silence_logs=logging.ERROR,
                     scheduler_kwargs={"dashboard_address": "127.0.0.1:0"})
        if self.processes:
            self.cluster = LocalCluster(n_workers=n, processes=True, host="127.0.0.1",
                                        memory_limit=0, **quiet)
        else:
            self.cluster = LocalCluster(n_workers=1, processes=False, **quiet)
        self.client = Client(self.cluster)
        return self

    def __exit__(self, *exc) -> None:
        for thing in (self.client, self.cluster):
            if thing is not None:
                try:
                    thing.close()
                except Exception:      # closing after Ctrl-C must not hide the Ctrl-C
                    pass
        self.client = self.cluster = None

    # ------------------------------------------------------------ what it is
    def describe(self) -> dict:
        """The scheduler and the workers used (for the results' provenance)."""
        workers, threads = describe_workers(self.client.scheduler_info())
        kind = ("scheduler" if self.scheduler else
                "LocalCluster" if self.processes else "in-process")
        return {"kind": kind, "scheduler": self.client.scheduler.address, "workers": workers,
                "threads": threads}

    # ------------------------------------------------------------ work
    def map(self, fn: Callable, items: Iterable, *, pure: bool = False) -> Iterator[tuple[int, object]]:
        """``(index, fn(item))`` for every item, in the order they finish.

        An exception in ``fn`` is raised here when its result comes up; the
        futures not yet finished are cancelled when the caller stops
        iterating (an exception, Ctrl-C, or ``break``)."""
        from distributed import as_completed
        items = list(items)
        futures = [self.client.submit(fn, item, pure=pure, key=f"{fn.__name__}-{i}-{id(self)}")
                   for i, item in enumerate(items)]
        index = {f.key: i for i, f in enumerate(futures)}
        try:
            for fut in as_completed(futures):
                yield index[fut.key], fut.result()
        finally:
            pending = [f for f in futures if not f.done()]
            if pending and self.client is not None:
                try:
                    self.client.cancel(pending)
                except Exception:
                    pass
