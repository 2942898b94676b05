"""The `rotorpillar` command: parse, call the library, write results.

Every command takes a scene (a TOML path or an embedded scene's name,
default ``paper``), ``--set section.key=value`` overrides, ``--out DIR``
(default ``out/<scene>/``) and ``--json``.  It writes ``DIR/<command>.json``
atomically, with the resolved scene, the versions and the timings, and
prints a readable summary, or with ``--json`` that same JSON and nothing else
on stdout.  Bad input: one line on stderr, exit code 2, nothing written.
"""

from __future__ import annotations

import atexit
import importlib
import io
import logging
import os
import signal
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from . import records
from .commands import Done, is_root_rank, out_dir, progress
from .commands.folder_lock import output_lock
from .commands.parser import COMMANDS, EXTRA_ARGUMENTS, OneLineParser, build_parser, command_named  # noqa: F401
from .errors import RECEIVED, ComputationError, InputError, StageError, Terminated, stopped
from .provenance import Timings, with_provenance, write_result
from .scene import Scene, load_scene, what_is_there


@dataclass(frozen=True)
class Executed:
    """A command run: its result as written, where, and its summary."""

    done: Done
    """the command's record, summary and exit status"""
    document: dict[str, Any]
    """the result file's document (the record with its provenance), as --json prints it"""
    path: Path | None
    """the file written (None off MPI rank 0)"""


def execute(name: str, scene: Scene, args) -> Executed:
    """Run one command on a scene, write ``<out>/<name>.json``, return what it did."""
    module, func, _ = COMMANDS[name]
    fn = getattr(importlib.import_module(module), func)
    timings = Timings()
    start = time.perf_counter()
    done = Done(*fn(scene, args, timings))
    stopped()  # a signal a library caught on the way: no result file, the signal's exit
    timings["total"] = time.perf_counter() - start
    head = {
        "command": name,
        "scene_source": str(args.scene),
        "overrides": list(args.overrides),
        "scene": scene.to_dict(),
    }
    doc = with_provenance(done.result, head, dict(timings))
    path = write_result(out_dir(scene, args) / f"{name}.json", doc) if is_root_rank() else None
    return Executed(done, doc, path)


#: Exit codes (README, "Exit codes"): the class of a failure, for scripts.
EXIT_OK, EXIT_FAILED, EXIT_INPUT, EXIT_INTERNAL, EXIT_INTERRUPTED, EXIT_TERMINATED = 0, 1, 2, 70, 130, 143


#: Commands that share their work between MPI ranks; the others run on one process.
#: simulate and compare share the 3D full order's (and refuse mpirun without it).
MPI_COMMANDS = ("modal", "simulate", "compare")


def mpi_world_size() -> int:
    """Ranks of the MPI job this process belongs to (1 outside mpirun), from the launcher's env."""
    for key in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MPI_LOCALNRANKS"):
        value = os.environ.get(key, "")
        if value.isdigit():
            return int(value)
    return 1


def mpi_world_rank() -> int:
    """This process's rank in its MPI job (0 outside mpirun), from the launcher's env."""
    for key in ("OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"):
        value = os.environ.get(key, "")
        if value.isdigit():
            return int(value)
    return 0


def check_output_dir(path: Path) -> None:
    """Refuse, before any work, an output directory that cannot take files.

    Nothing is created here: refused input leaves no trace.
    """
    if os.path.lexists(path) and not path.is_dir():
        there = what_is_there(path) or "is a file"
        raise InputError(f"--out {str(path)!r}: {there.removesuffix(', not a file')}, not a directory")
    probe = path
    while not probe.exists():
        if probe.parent == probe:
            break
        probe = probe.parent
    if probe.is_dir() and not os.access(probe, os.W_OK | os.X_OK):
        raise InputError(f"--out {str(path)!r}: {str(probe)!r} is not writable")
    if not probe.is_dir():
        raise InputError(f"--out {str(path)!r}: {str(probe)!r} is not a directory")


def open_file_of(exc: BaseException) -> str | None:
    """The file an OSError without a name was raised on: the innermost frame of its
    traceback that holds an open file object (a library's ``f.write`` on a full disk)."""
    tb, found = exc.__traceback__, None
    while tb is not None:
        for value in tb.tb_frame.f_locals.values():
            name = getattr(value, "name", None) if isinstance(value, io.IOBase) else None
            if isinstance(name, str):
                found = name
        tb = tb.tb_next
    return found


def quiet_third_party_logs(debug: bool = False) -> None:
    """Other libraries' log records reach stderr at WARNING and above (INFO with ``--debug``).

    ffcx calls ``logging.basicConfig()`` when imported (a root handler that
    passes everything) and setuptools, building a form's C extension, lowers
    the root logger to INFO: the compiler's command lines would reach the
    console.  A root handler installed first, with its own threshold, takes
    both (``basicConfig`` does nothing once the root has a handler).
    """
    root = logging.getLogger()
    if not root.handlers:
        logging.basicConfig()
    for handler in root.handlers:
        handler.setLevel(logging.INFO if debug else logging.WARNING)


def _terminate(signum, frame):
    RECEIVED.append(signum)
    raise Terminated() if signum == signal.SIGTERM else KeyboardInterrupt()


#: The command under way in this process (``main``), for ``_exit_as_signalled``.
_RUNNING: list[str] = []


def _exit_as_signalled() -> None:
    """At the interpreter's exit while a command is still under way after a signal: a
    library ended the process from inside the command (VTK's observer calls exit(1) on a
    KeyboardInterrupt): the exit is the signal's, with its one line."""
    if _RUNNING and RECEIVED:
        print(
            f"rotorpillar {_RUNNING[-1]}: interrupted: finished outputs are complete, none is half-written",
            file=sys.stderr,
            flush=True,
        )
        os._exit(EXIT_TERMINATED if RECEIVED[-1] == signal.SIGTERM else EXIT_INTERRUPTED)


def main(argv: list[str] | None = None) -> int:
    """The one error boundary: every expected failure is one line and an exit code.

    2: bad input (nothing written); 1: a solver, a tool or the machine failed
    (file system, memory; finished outputs stay complete); 70: a bug (one line;
    ``--debug`` shows the traceback); 130, 143: interrupted (Ctrl-C, SIGTERM), also
    when a library caught the interrupt (``stopped``, ``_exit_as_signalled``).
    """
    words = sys.argv[1:] if argv is None else list(argv)
    args = build_parser(only=command_named(words) or "").parse_args(words)
    atexit.unregister(_exit_as_signalled)  # once per process, however many commands it runs
    atexit.register(_exit_as_signalled)
    _RUNNING.append(args.command)
    try:
        return _main(args)
    finally:
        _RUNNING.pop()


def _main(args) -> int:
    quiet_third_party_logs(args.debug)
    RECEIVED.clear()
    signal.signal(signal.SIGTERM, _terminate)
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:  # not when ignored (nohup, &)
        signal.signal(signal.SIGINT, _terminate)
    if args.debug:
        os.environ["ROTORPILLAR_DEBUG"] = "1"  # run's stages and the report see it too
    say = lambda kind, text: print(f"rotorpillar {args.command}: {kind}: {text}", file=sys.stderr)
    # what every rank meets alike (bad input, a signal): said once, by rank 0
    say_once = say if mpi_world_rank() == 0 else lambda kind, text: None
    try:
        if mpi_world_size() > 1 and args.command not in MPI_COMMANDS:
            raise InputError(
                f"{args.command} runs on one process (only {', '.join(MPI_COMMANDS)} "
                "shares its work between MPI ranks): start it without mpirun"
            )
        scene = load_scene(args.scene, args.overrides)
        if scene.excitation.kind == "record":
            from .reduced.excitation import check_record

            check_record(scene.excitation.record)  # a missing record: now, not at a late stage
        if scene.foundation.kind != "clamped":
            from .reduced.tower import check_foundation_holds

            check_foundation_holds(scene)  # a base that cannot hold the machine up: before any work
        check_output_dir(out_dir(scene, args))
        with output_lock(out_dir(scene, args), args.command, progress):
            ran = execute(args.command, scene, args)
    except InputError as exc:
        say_once("error", exc)
        return EXIT_INPUT
    except StageError as exc:
        say("failed", exc)
        return EXIT_FAILED
    except ComputationError as exc:
        if args.debug:
            raise
        say("failed", f"{exc}; nothing was written")
        return EXIT_FAILED
    except KeyboardInterrupt as exc:
        say_once("interrupted", "finished outputs are complete, none is half-written")
        return EXIT_TERMINATED if isinstance(exc, Terminated) else EXIT_INTERRUPTED
    except OSError as exc:
        if args.debug:
            raise
        file = getattr(exc, "filename", None) or open_file_of(exc)
        where = f" {file!r}" if file else ""
        say(
            "failed",
            f"the file system refused{where}: {exc.strerror or exc}; files written "
            "before are intact, none is half-written",
        )
        return EXIT_FAILED
    except MemoryError:
        if args.debug:
            raise
        say("failed", "out of memory; use a coarser mesh or a shorter run (README, Limits)")
        return EXIT_FAILED
    except Exception as exc:  # a bug: one line, the traceback on request
        if RECEIVED and not args.debug:
            # the signal's exception raised inside a C extension's initialisation comes out as
            # that import's error (petsc4py: "ImportError: initialization failed"): the command
            # was stopped by the signal, not by a bug
            say_once("interrupted", "finished outputs are complete, none is half-written")
            return EXIT_TERMINATED if RECEIVED[-1] == signal.SIGTERM else EXIT_INTERRUPTED
        if args.debug:
            raise
        say(
            "internal error",
            f"{type(exc).__name__}: {exc} (run again with --debug for the traceback, and please report it)",
        )
        return EXIT_INTERNAL
    if is_root_rank():
        if args.json:
            print(records.encode_pretty(ran.document).decode())
        else:
            print(ran.done.summary)
            print(f"\nwrote {ran.path}")
            report = getattr(ran.done.result, "report", None)
            if isinstance(report, str):  # the last line: the page to open
                print(f"report: {Path(report).resolve()}")
    return ran.done.exit_status


if __name__ == "__main__":
    sys.exit(main())
