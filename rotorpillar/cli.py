"""The `rotorpillar` command: parse, call the library, write results.

Every command takes a scene (a TOML path or an embedded scene's name,
default ``paper``), ``--set section.key=value`` overrides, ``--out DIR``
(default ``out/<scene>/``) and ``--json``.  It writes ``DIR/<command>.json``
atomically, with the resolved scene, the versions and the timings, and
prints a readable summary, or with ``--json`` that same JSON and nothing else
on stdout.  Bad input: one line on stderr, exit code 2, nothing written.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import time
from pathlib import Path

from . import __version__
from .errors import ComputationError, InputError, StageError
from .provenance import Timings, machine, to_json, versions, write_json
from .commands import is_root_rank, out_dir
from .scene import Scene, embedded_scenes, load_scene

# name -> (module, function, help).  A command function takes
# (scene, args, timings) and returns (result: dict, summary: str).
COMMANDS = {
    "analyze": ("rotorpillar.commands.analyze", "analyze_command",
                "closed forms, reduced system modes, averaging, paper comparison"),
    "converge": ("rotorpillar.commands.converge", "converge_command",
                 "mesh convergence, speed against accuracy, and the cheapest model a scene needs"),
    "modal": ("rotorpillar.commands.modal", "modal_command",
              "3D tube (Gmsh, dolfinx, SLEPc): modes bare and with the top mass, tip reduction"),
    "report": ("rotorpillar.commands.report", "report_command",
               "the HTML validation report, its charts, mode-shape pictures and animations"),
    "run": ("rotorpillar.commands.run", "run_command",
            "the main job: every analysis of the scene, then the report"),
    "simulate": ("rotorpillar.commands.simulate", "simulate_command",
                 "transients of the reduced models: run-up, run-down, sweep, earthquake"),
    "integrators": ("rotorpillar.commands.integrators", "integrators_command",
                    "time integrators: error against cost, where each fails"),
    "study": ("rotorpillar.commands.study", "study_command",
              "design study on Dask: capture maps of run-ups, earthquake IDA curves"),
}


def _report_arguments(parser) -> None:
    from .commands.report import add_arguments
    add_arguments(parser)


def _run_arguments(parser) -> None:
    from .commands.run import add_arguments
    _report_arguments(parser)
    add_arguments(parser)


# Extra arguments of a command: name -> callable(parser)
EXTRA_ARGUMENTS = {
    "converge": lambda p: importlib.import_module("rotorpillar.commands.converge").add_arguments(p),
    "modal": lambda p: importlib.import_module("rotorpillar.commands.converge").add_modal_arguments(p),
    "report": _report_arguments,
    "run": _run_arguments,
    "simulate": lambda p: importlib.import_module("rotorpillar.commands.simulate").add_arguments(p),
    "integrators": lambda p: importlib.import_module("rotorpillar.commands.integrators").add_arguments(p),
    "study": lambda p: importlib.import_module("rotorpillar.commands.study").add_arguments(p),
}


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("scene", nargs="?", default="paper",
                   help=f"scene file (.toml) or embedded scene: {', '.join(embedded_scenes())} "
                        "(default: paper)")
    p.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                   help="override a scene key, e.g. --set shaft.stiffness=5e6 (repeatable)")
    p.add_argument("--out", type=Path, default=None, metavar="DIR",
                   help="output directory (default: out/<scene>/)")
    p.add_argument("--json", action="store_true",
                   help="print the result JSON on stdout and nothing else there")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="rotorpillar",
        description="Dynamics of a heavy eccentric rotor on a tall flexible pillar.")
    parser.add_argument("--version", action="version", version=f"rotorpillar {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name, (_, _, help_) in COMMANDS.items():
        p = sub.add_parser(name, help=help_, description=help_)
        _common(p)
        if name in EXTRA_ARGUMENTS:
            EXTRA_ARGUMENTS[name](p)
    return parser


def execute(name: str, scene: Scene, args) -> dict:
    """Run one command on a scene, write ``<out>/<name>.json``, return the result."""
    module, func, _ = COMMANDS[name]
    fn = getattr(importlib.import_module(module), func)
    timings = Timings()
    start = time.perf_counter()
    result, text = fn(scene, args, timings)
    timings["total"] = time.perf_counter() - start
    doc = {"command": name, "scene_source": str(args.scene), "overrides": list(args.overrides),
           "scene": scene.to_dict(), **result,
           "versions": versions(), "machine": machine(), "timings": dict(timings)}
    if is_root_rank():
        path = write_json(out_dir(scene, args) / f"{name}.json", doc)
        doc["_path"] = str(path)
        doc["_summary"] = text
    return doc


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        scene = load_scene(args.scene, args.overrides)
        doc = execute(args.command, scene, args)
    except InputError as exc:
        print(f"rotorpillar {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except StageError as exc:
        print(f"rotorpillar {args.command}: failed: {exc}", file=sys.stderr)
        return 1
    except ComputationError as exc:
        print(f"rotorpillar {args.command}: failed: {exc}; nothing was written", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"rotorpillar {args.command}: interrupted; finished outputs are complete, "
              "none is half-written", file=sys.stderr)
        return 130
    if is_root_rank():
        path, text = doc.pop("_path"), doc.pop("_summary")
        if args.json:
            print(to_json(doc))
        else:
            print(text)
            print(f"\nwrote {path}")
            report = doc.get("report")
            if isinstance(report, str):     # the last line: the page to open
                print(f"report: {Path(report).resolve()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
