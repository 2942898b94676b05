"""The finite-element runs' process: started once, reused for run after run.

A fresh interpreter per run cost 1.4 s of imports and start-up (MPI,
PETSc, dolfinx) against a median run of about 2 s: a third of the cold
study on this machine.  Each process of the study (the study's own, or each
Dask worker's) now starts one ``python -m rotorpillar.converge --serve``
and hands it runs one by one over a pipe; a run is still alone in its
process, with nothing cached in memory from the run before.

Peak memory per run, as a fresh process would have had it: the imports'
resident memory (``baseline_memory``) plus the run's own growth, the
kernel's high-water mark of the resident set (VmHWM, reset before the run
through ``/proc/self/clear_refs``, Linux 4.0+) over the resident set at its
start (after ``gc`` and glibc's ``malloc_trim`` of the run before).  What a
process keeps from its runs (compiled forms' libraries, a big run's heap)
stays out of the next run's figure; once it passes ``RETAINED_LIMIT`` the
process ends after its reply and the next run gets a fresh one, started at
once (its imports overlap the caller's wait for its next run: a round's end).  Where the
reset is not possible the process serves one run only, as before.

Protocol (the serving side is rotorpillar.converge.runner.serve): one JSON
line per run each way, ``{"case": CASE.json, "out": RESULT.json}`` in,
``{"status": "ok" | "unavailable" | "error", "error": ..., "last": bool}``
out ("last": the process ends after this run).  End of input ends it too.
"""

from __future__ import annotations

import atexit
import os
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

from .. import records
from ..records import Record

MODULE = "rotorpillar.converge"
"""What ``python -m`` runs (its ``__main__``: ``--serve``, or one CASE RESULT pair)."""
RETAINED_LIMIT = 256 * 2**20
"""Resident memory a serving process may keep beyond its imports before it is replaced (bytes)."""


def _status_kib(field: str) -> int | None:
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(field + ":"):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def reset_peak_memory() -> bool:
    """Reset this process's resident-set high-water mark; False where Linux does not allow it."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return _status_kib("VmHWM") is not None
    except OSError:
        return False


def peak_memory() -> int | None:
    """This process's resident-set high-water mark since the last reset (bytes)."""
    kib = _status_kib("VmHWM")
    return None if kib is None else 1024 * kib


def resident_memory() -> int | None:
    """This process's resident set now (bytes), after returning what it can to the
    system (``gc``, glibc's ``malloc_trim``)."""
    import ctypes
    import gc

    gc.collect()
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass
    kib = _status_kib("VmRSS")
    return None if kib is None else 1024 * kib


class ServiceJob(Record):
    """One run sent to the serving process: a line of the protocol."""

    case: str
    """the run's case file (a ``CaseFile``)"""
    out: str
    """where to write its ``RunResult``"""


class ServiceReply(Record, omit_defaults=True):
    """The serving process's answer to one run: a line of the protocol."""

    status: str
    """"ok", "unavailable" (the model cannot be imported here) or "error" """
    error: str | None = None
    """why the run did not give a result"""
    exit: int | None = None
    """the exit code of a serving process that ended without a reply"""
    last: bool = False
    """the process ends after this run: the next run gets a new one"""


class Service:
    """The parent's handle on one serving process (started on first use, restarted
    after it ends or dies)."""

    def __init__(self):
        self.proc = None
        self.log = None
        self.idle = False
        """the process has been sent no run yet (a successor started ahead)"""

    def run(self, case_file: Path, out_file: Path) -> ServiceReply:
        """Send one run; its reply (a dead process: status "error" with the end of
        its stderr)."""
        if self.proc is None or self.proc.poll() is not None:
            self._start()
        self.idle = False
        try:
            self.proc.stdin.write(records.encode(ServiceJob(str(case_file), str(out_file))).decode() + "\n")
            self.proc.stdin.flush()
            line = self.proc.stdout.readline()
        except (BrokenPipeError, OSError):
            line = ""
        if not line:
            self.proc.wait()
            code = self.proc.returncode
            self.proc = None
            return ServiceReply(status="error", exit=code, error=f"worker ended ({code}): " + self._tail())
        reply = records.decode(line, ServiceReply)
        if reply.last:  # it ends after this run: the next gets a new one, started now so
            self.proc.wait()  # that its imports (1-2 s) overlap the caller's wait for its next run
            self.proc = None
            self._start()
        return reply

    def _start(self) -> None:
        env = dict(os.environ)
        # single-threaded: the runs are timed against each other
        env.setdefault("OMP_NUM_THREADS", "1")
        env.setdefault("OPENBLAS_NUM_THREADS", "1")
        if self.log is None:
            self.log = tempfile.TemporaryFile(mode="w+", prefix="rotorpillar-converge-")
        self.log.seek(0)
        self.log.truncate()
        self.proc = subprocess.Popen(
            [sys.executable, "-m", MODULE, "--serve"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self.log,
            text=True,
            env=env,
        )
        self.idle = True

    def _tail(self) -> str:
        self.log.flush()
        self.log.seek(0)
        return " | ".join(self.log.read().strip().splitlines()[-3:])

    def close(self) -> None:
        if self.proc is not None:
            try:
                if self.idle:  # a successor that never ran: not worth waiting for its imports
                    self.proc.kill()
                self.proc.stdin.close()
                self.proc.wait(timeout=30)
            except (OSError, subprocess.TimeoutExpired):
                self.proc.kill()
            self.proc = None
        if self.log is not None:
            self.log.close()
            self.log = None


_SERVICES: dict[tuple, Service] = {}


def service() -> Service:
    """This thread's serving process (one per process and thread: a forked copy,
    or a second Dask thread, gets its own)."""
    key = (os.getpid(), threading.get_ident())
    if key not in _SERVICES:
        _SERVICES[key] = Service()
    return _SERVICES[key]


def close_services() -> None:
    """End this process's serving processes (a Dask worker's end when it exits:
    their input closes)."""
    for key in [k for k in _SERVICES if k[0] == os.getpid()]:
        _SERVICES.pop(key).close()


atexit.register(close_services)
