"""The report's 3D pictures (mode shapes, animations) rendered in worker processes.

Each picture is drawn by pyvista on one core (VTK's off-screen OSMesa window;
the chart panel by matplotlib, the video by ffmpeg): the jobs go to
``WORKERS`` processes, at most one per core, the longest first, while the
report's own process draws the charts.  A job is read from its files in the
worker (the mode shapes from their VTU), so no VTK object crosses a process
and none is made in the report's own.  A job that fails (or a worker that
dies) costs its picture, said in report.json, not the report.

Ctrl-C or SIGTERM stop the command as everywhere else: the workers ignore
SIGINT, and the report's process ends them before it exits.
"""

from __future__ import annotations

import os
import signal
import sys
import time
import traceback
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ...errors import stopped
from ...fem3d.modal_summary import ModalAxes
from ..geometry import Mode
from ..readers import Simulation

WORKERS = 2
"""Worker processes at most: one per core of the 2-core machine the main job is sized for."""


@dataclass(frozen=True)
class ModeFiles:
    """A set of mode shapes as modal.json and its VTU give them."""

    vtu: Path
    modes: list[Mode]
    """each mode's row of modal.json (kind, frequency_hz, ...)"""
    axes: ModalAxes
    """modal.json's ``axes``"""


@dataclass(frozen=True)
class ModesJob:
    """The pictures of one set of modes and its contact sheet."""

    name: str
    """"bare" or "top" """
    files: ModeFiles
    directory: Path
    count: int
    """modes drawn (-)"""

    @property
    def cost(self) -> float:
        """A rough guess of its time, to start the longest first (s)."""
        return 1.0 * (self.count + 2)


@dataclass(frozen=True)
class AnimationJob:
    """One run's animation on the tube carrying its top."""

    name: str
    sim: Simulation
    title: str
    options: dict[str, Any]
    """animate's own keywords (focus, banner)"""
    top: ModeFiles | None
    """the loaded tube's mode shapes; None (or unreadable): the Euler-Bernoulli cantilever"""
    pillar: tuple[float, float, float]
    """height, outer and inner diameter (m): the cantilever's tube"""
    path: Path
    poster: Path
    max_frames: int

    @property
    def cost(self) -> float:
        return 0.1 * self.max_frames


Job = ModesJob | AnimationJob


@dataclass(frozen=True)
class Outcome:
    """What a job gave back: its result, or why it failed, under the report's key."""

    key: str
    """the report's name of the step (modes_top, load_modes_top, animation_runup, ...)"""
    result: Any
    """a ModePictures (render_modes), a ModeSet (load_modes), an AnimationResult, or None (failed)"""
    error: str | None
    seconds: float
    """its wall time in the worker (s)"""
    window: str = ""
    """the VTK render window class the worker drew with"""
    detail: str = ""
    """a failure's traceback (shown with --debug)"""


def _load(files: ModeFiles):
    """The mode shapes of ``files``, read once a worker while their VTU is the same file
    (the loaded tube's, 1-2 s to read, under every animation a worker draws)."""
    stat = files.vtu.stat()
    key = (str(files.vtu), stat.st_mtime_ns, stat.st_size)
    if _LOADED.get(key) is None or _LOADED[key][0] != files:
        from ..geometry import load_modes

        _LOADED.clear()  # one set at a time: a worker's memory holds no stale tube
        _LOADED[key] = (files, load_modes(files.vtu, files.modes, files.axes))
    return _LOADED[key][1]


#: (VTU path, mtime, size) -> (the files read, the ModeSet): the last set read in this process.
_LOADED: dict[tuple[str, int, int], tuple[ModeFiles, Any]] = {}


def _timed(key: str, fn: Callable[[], Any]) -> Outcome:
    start = time.perf_counter()
    try:
        result, error, detail = fn(), None, ""
    except Exception as exc:  # a broken picture must not cost the report
        result, error, detail = None, f"{type(exc).__name__}: {exc}", traceback.format_exc()
    return Outcome(key, result, error, time.perf_counter() - start, detail=detail)


def run_job(job: Job) -> list[Outcome]:
    """Draw one job (in a worker process)."""
    from ..offscreen import render_window_class

    out: list[Outcome] = []
    if isinstance(job, ModesJob):
        from ..modeshapes import render_modes

        loaded = _timed(f"load_modes_{job.name}", lambda: _load(job.files))
        out.append(loaded)
        if loaded.result is not None:
            ms = loaded.result
            out.append(_timed(f"modes_{job.name}", lambda: render_modes(ms, job.directory, job.name, job.count)))
    else:
        from ..animation import animate
        from ..geometry import cantilever_tube

        def draw():
            ms = None
            if job.top is not None:
                try:
                    ms = _load(job.top)
                except Exception:  # the modes' own job says why; the cantilever stands in
                    ms = None
            if ms is None:
                ms = cantilever_tube(*job.pillar)
            return animate(
                job.sim,
                ms,
                job.path,
                title=job.title,
                max_frames=job.max_frames,
                poster=job.poster,
                progress=False,
                **job.options,
            )

        out.append(_timed(f"animation_{job.name}", draw))
    window = ""
    try:
        window = render_window_class()
    except Exception:
        pass
    return [Outcome(o.key, o.result, o.error, o.seconds, window, o.detail) for o in out]


def _serve(conn) -> None:
    """A worker's loop: a job in, its outcomes out, until the report's process hangs up."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the report's process's to handle
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    while True:
        try:
            job = conn.recv()
        except (EOFError, OSError):
            return
        if job is None:
            return
        conn.send(run_job(job))


def _failed(job: Job, why: str) -> Outcome:
    key = f"modes_{job.name}" if isinstance(job, ModesJob) else f"animation_{job.name}"
    return Outcome(key, None, why, 0.0)


def run_jobs(jobs: Sequence[Job], during: Callable[[], None] | None = None) -> Iterator[Outcome]:
    """Every job's outcomes, as the jobs end; ``during`` runs in this process meanwhile.

    The jobs start the longest first on min(WORKERS, cores, jobs) processes (one or
    none: here, one after the other), each fed its next job when it is free.  The
    workers are fresh interpreters (spawn): no state of this process (VTK, a plotter,
    matplotlib) is shared with them.  A worker that dies costs its job; whatever ends
    this generator (the last job, Ctrl-C, SIGTERM, an error) ends the workers.
    """
    import multiprocessing
    from multiprocessing.connection import wait

    order = sorted(jobs, key=lambda j: -j.cost)
    count = min(WORKERS, os.cpu_count() or 1, len(order))
    if count <= 1:
        try:
            if during is not None:
                during()
            for job in order:
                yield from run_job(job)
        finally:
            _LOADED.clear()  # in the report's own process: no VTK object outlives the report
        return
    ctx = multiprocessing.get_context("spawn")
    workers = []
    try:
        for _ in range(count):
            mine, theirs = ctx.Pipe()
            proc = ctx.Process(target=_serve, args=(theirs,), daemon=True)
            proc.start()
            theirs.close()
            workers.append((proc, mine))
        todo = list(order)
        busy: dict[int, Job] = {}  # worker index -> its job
        for k, (_, conn) in enumerate(workers):
            if todo:
                busy[k] = todo.pop(0)
                conn.send(busy[k])
        if during is not None:
            during()
        while busy:
            # A Ctrl-C or SIGTERM whose exception a library caught while this process drew
            # its charts (``during``) or took a job's outcomes is raised here, before the
            # wait: before, the workers rendered on until a job ended (30 s and more, 3 stops
            # in 45).  A signal during the wait itself interrupts it.
            stopped()
            ready = wait([workers[k][1] for k in busy] + [workers[k][0].sentinel for k in busy])
            for k in list(busy):
                proc, conn = workers[k]
                if conn in ready or conn.poll():
                    try:
                        outcomes = conn.recv()
                    except (EOFError, OSError):
                        outcomes = [_failed(busy[k], f"its worker process ended ({proc.exitcode})")]
                elif proc.sentinel in ready:  # died without a word (a crash in VTK, memory)
                    proc.join()
                    outcomes = [_failed(busy[k], f"its worker process died (exit {proc.exitcode})")]
                else:
                    continue
                del busy[k]
                yield from outcomes
                if todo and proc.is_alive():
                    busy[k] = todo.pop(0)
                    conn.send(busy[k])
            if todo and not busy:  # every worker died: the rest here
                for job in todo:
                    yield from run_job(job)
                todo = []
                _LOADED.clear()
    except BaseException:  # Ctrl-C, SIGTERM, an error, or the caller stopped: at once
        for proc, _ in workers:
            proc.terminate()
        raise
    finally:
        for _, conn in workers:  # a worker that is still there is told to stop
            try:
                conn.send(None)
            except (OSError, ValueError):
                pass
            conn.close()
        for proc, _ in workers:
            proc.join(timeout=5)
            if proc.is_alive():
                proc.terminate()
                proc.join(timeout=5)


def debug_detail(outcome: Outcome) -> None:
    """A failed job's traceback on stderr (``--debug``)."""
    if outcome.detail:
        print(outcome.detail, file=sys.stderr)
