"""The command line's parser: the commands, their arguments, errors on one line.

``build_parser()`` is what `rotorpillar` parses with, and what `run` parses
each of its stages' own arguments with, for their pre-flight checks
(``commands.run.stage_arguments``).  The
command modules are named, not imported, here: each adds its own arguments
when the parser is built.
"""

from __future__ import annotations

import argparse
import importlib
from pathlib import Path

from .. import __version__
from ..scene import embedded_scenes

# name -> (module, function, help).  A command function takes
# (scene, args, timings) and returns (result: dict, summary: str).
COMMANDS = {
    "analyze": (
        "rotorpillar.commands.analyze",
        "analyze_command",
        "closed forms, reduced system modes, averaging, paper comparison",
    ),
    "converge": (
        "rotorpillar.commands.converge",
        "converge_command",
        "mesh convergence, speed against accuracy, and the cheapest model a scene needs",
    ),
    "modal": (
        "rotorpillar.commands.modal",
        "modal_command",
        "3D tube (Gmsh, dolfinx, SLEPc): modes bare and with the top mass, tip reduction",
    ),
    "report": (
        "rotorpillar.commands.report",
        "report_command",
        "the HTML validation report, its charts, mode-shape pictures and animations",
    ),
    "run": ("rotorpillar.commands.run", "run_command", "the main job: every analysis of the scene, then the report"),
    "simulate": (
        "rotorpillar.commands.simulate",
        "simulate_command",
        "transients: run-up, run-down, sweep, earthquake on the paper, modal, 3D or beam model",
    ),
    "compare": (
        "rotorpillar.commands.compare",
        "compare_command",
        "several transient models on one case: tip histories, errors and cost against the most complete",
    ),
    "integrators": (
        "rotorpillar.commands.integrators",
        "integrators_command",
        "time integrators: error against cost, where each fails",
    ),
    "study": (
        "rotorpillar.commands.study",
        "study_command",
        "design study on Dask: capture maps of run-ups, earthquake IDA curves",
    ),
    "tornado": (
        "rotorpillar.commands.tornado",
        "tornado_command",
        "how much the checks depend on the uncertain inputs: a one-at-a-time study on the ROM",
    ),
    "harmonic": (
        "rotorpillar.commands.harmonic",
        "harmonic_command",
        "unbalance response against speed (Bode: ROM, 3D, Eq. 19) and separation margins (API 684)",
    ),
    "campbell": (
        "rotorpillar.commands.campbell",
        "campbell_command",
        "Campbell diagram: every mode's frequency, whirl and log decrement against speed, the critical speeds",
    ),
}


def _arguments(*modules: str):
    """A command's extra arguments: each module's ``add_arguments`` (modules by name:
    `run` parses its stages' arguments with this parser, so no command module is imported here)."""
    return lambda p: [importlib.import_module(f"rotorpillar.commands.{m}").add_arguments(p) for m in modules]


# Extra arguments of a command: name -> callable(parser)
EXTRA_ARGUMENTS = {
    "converge": _arguments("converge"),
    "modal": lambda p: importlib.import_module("rotorpillar.commands.converge").add_modal_arguments(p),
    "report": _arguments("report"),
    "run": _arguments("report", "run"),
    "simulate": _arguments("simulate"),
    "integrators": _arguments("integrators"),
    "compare": _arguments("compare"),
    "study": _arguments("study"),
    "tornado": _arguments("tornado"),
    "harmonic": _arguments("harmonic"),
    "campbell": _arguments("campbell"),
}


def output_dir(text: str) -> Path:
    """``--out``'s value: a path; an empty one is refused (``Path("")`` is the working
    directory, which would take every file of the command)."""
    if not text.strip():
        raise argparse.ArgumentTypeError(f"{text!r} is an empty path: give a directory, e.g. --out out/paper")
    return Path(text)


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "scene",
        nargs="?",
        default="paper",
        help=f"scene file (.toml) or embedded scene: {', '.join(embedded_scenes())} (default: paper)",
    )
    p.add_argument(
        "--set",
        dest="overrides",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a scene key, e.g. --set shaft.stiffness=5e6 (repeatable)",
    )
    p.add_argument(
        "--out", type=output_dir, default=None, metavar="DIR", help="output directory (default: out/<scene>/)"
    )
    p.add_argument("--json", action="store_true", help="print the result JSON on stdout and nothing else there")
    p.add_argument("--debug", action="store_true", help="show the Python traceback of a failure instead of one line")


class OneLineParser(argparse.ArgumentParser):
    """argparse with its errors on one line (exit 2): the command, the flag and what it
    allows, instead of the usage block; ``--help`` still shows the usage."""

    def error(self, message: str):
        message = " ".join(message.split())
        # "argument --case: invalid choice: 'sweep' (choose from 'earthquake', 'runup')"
        if message.startswith("argument ") and "invalid choice:" in message:
            flag, rest = message[len("argument ") :].split(": invalid choice: ", 1)
            value, _, allowed = rest.partition(" (choose from ")
            message = f"{flag.split('/')[-1]} {value}: must be one of {allowed.rstrip(')')}"
        elif message.startswith("argument "):
            flag, _, why = message[len("argument ") :].partition(": ")
            message = f"{flag.split('/')[-1]}: {why}"
        elif message.endswith("required: COMMAND"):
            message = "give a COMMAND, one of " + ", ".join(COMMANDS)
        self.exit(2, f"{self.prog}: error: {message}\n")  # cli.EXIT_INPUT


def command_named(argv: list[str]) -> str | None:
    """The command an argument list runs: its first word that is no option (the top level's
    options, --help and --version, take no value), or None.

    >>> command_named(["simulate", "paper", "--case", "runup"]), command_named(["--version"])
    ('simulate', None)
    """
    return next((a for a in argv if not a.startswith("-")), None)


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser.  ``only``: the command it will parse, whose own arguments
    alone are added (each command's module is imported to add them: all twelve take ~0.6 s
    of CPU, a quick command or a refused input most of its time); the other commands keep
    their name and help, so the top level's --help and an unknown command read the same.
    None: every command's arguments (`run`, which parses its stages' arguments with it)."""
    parser = OneLineParser(
        prog="rotorpillar", description="Dynamics of a heavy eccentric rotor on a tall flexible pillar."
    )
    parser.add_argument("--version", action="version", version=f"rotorpillar {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name, (_, _, help_) in COMMANDS.items():
        p = sub.add_parser(name, help=help_, description=help_)
        _common(p)
        if name in EXTRA_ARGUMENTS and only in (None, name):
            EXTRA_ARGUMENTS[name](p)
    return parser
