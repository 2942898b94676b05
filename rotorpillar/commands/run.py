"""`rotorpillar run`: the main job, every stage on one scene, then the report.

Each stage runs as its own ``rotorpillar <stage>`` process, exactly as a user
would run it.  Stages hand their results over through the files they write;
a fresh process per stage returns the 3D model's memory, keeps MPI, PETSc,
Gmsh and VTK state apart, and a crash in one stage leaves the finished
stages' files in place.

The order is the chain of models (rotorpillar.chain): the convergence study
chooses the pillar model for the scene's band; `modal` computes the 3D tube
on that mesh (and caches the ROM's pillar modes); `analyze` sets the ROM
beside the paper's model; then the comparisons, the scene's own runs and
the integrator study, which depend only on what came before and not on each
other, run side by side on the machine's cores; the report comes last.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..scene import Scene

import os
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

from .. import records
from ..errors import StageError
from ..provenance import Provenance
from ..records import Record
from ..transients.compare import COMPARISONS
from . import Done, progress


def _report_flags(args) -> list[str]:
    flags = []
    if getattr(args, "max_frames", None) is not None:
        flags += ["--max-frames", str(args.max_frames)]
    if getattr(args, "no_animations", False):
        flags.append("--no-animations")
    if getattr(args, "strict", False):
        flags.append("--strict")
    return flags


# The stages of `rotorpillar run`, in order: (command, what it does, extra
# arguments from run's own, the stage's own arguments, its wave).  A stage's
# own arguments go before the user's --set, so the user's win.  Stages of one
# wave depend only on the waves before and run side by side; each wave waits
# for the one before.  The comparisons write compare_<case>_<model>.*, apart
# from the scene's own runs (simulate_<case>_<model>.*).
RUN_STAGES = [
    # minutes the first time, then read from its cache: it chooses the pillar model
    ("converge", "mesh convergence, speed against accuracy: the pillar model the band needs", None, (), 0),
    ("modal", "3D modes of the tube on the chosen mesh, bare and with its top mass", None, (), 1),
    ("analyze", "the headline model (the ROM) and the paper's, averaging", None, (), 2),
    # El Centro on the ROM and the 3D full order (the study's reference mesh for the modes
    # the load excites), with the speed-against-accuracy study
    (
        "compare --case earthquake",
        "a recorded earthquake: the ROM against the 3D full order",
        None,
        COMPARISONS["earthquake"],
        3,
    ),
    (
        "compare --case runup",
        "run-up through the resonances: the ROM against the 3D full order",
        None,
        COMPARISONS["runup"],
        3,
    ),
    # A wave's stages start in this order, two at a time: the longest first, so that
    # the two slots end together (paper, measured: integrators 16 s, harmonic 7 s, each
    # simulate 2-3 s; integrators after the two simulate runs left one slot idle 2.5 s
    # longer, and the whole wave waited for it).  The earthquake after the run-up, as
    # before: simulate.json is the last case run.
    ("integrators", "time integrators: error against cost, where each fails", None, (), 3),
    # the ROM's and the 3D model's unbalance response, the margins to the loaded tube's modes
    ("harmonic", "unbalance response (Bode) and separation margins (API 684)", None, (), 3),
    # the Campbell diagram, the ROM's beside the 3D model's (~35 s; after harmonic, so that it
    # fills the slot integrators leaves: measured on paper, the wave ends ~18 s later, not ~35).
    # The 3D on the scene's [mesh]: the chain's chosen mesh (paper: 128 x 20, ~94k DOFs) costs
    # ~140 s (its assembly, the damping's modes, the pencil), past the run's budget; the JSON
    # and stderr say so
    (
        "campbell",
        "Campbell diagram: the ROM against the 3D model, the critical speeds",
        None,
        ("--model", "both", "--fem3d-mesh", "scene"),
        3,
    ),
    # El Centro in three components (180, 270, UP) on the spatial ROM over the whole record
    # and the 3D full order over 4 s from the start (paper: the ROM's largest base moment at
    # 3.3 s; the 3D run ~25 s), the six base reactions
    (
        "compare --case earthquake --components 3",
        "El Centro in three components: the spatial ROM against the 3D full order, six base reactions",
        None,
        (
            "--set",
            "excitation.kind=record",
            "--set",
            "excitation.record=elcentro",
            "--set",
            "excitation.start=1",
            "--set",
            "full_order.earthquake_duration=4",
        ),
        3,
    ),
    # each uncertain input at the ends of its range on the ROM (paper: 18 runs, ~7 s)
    ("tornado", "how much the checks depend on the uncertain inputs: the tornado chart", None, (), 3),
    ("simulate --case runup", "run-up from rest on the headline model", None, (), 3),
    ("simulate --case earthquake", "the paper's case: its pulse on Eq. 4 as published", None, ("--model", "paper"), 3),
    ("report", "charts, mode shapes, animations, report.html", _report_flags, (), 4),
]


def stage_argv(command: str, args, extra=None, own=()) -> list[str]:
    """The command line of one stage: the command, its own arguments, run's
    scene, --out and overrides (after the stage's own --set: the user's win)."""
    from . import out_dir

    argv = [
        sys.executable,
        "-m",
        "rotorpillar",
        *command.split(),
        *own,
        str(args.scene),
        "--out",
        str(out_dir(args._scene, args)),
    ]
    for o in args.overrides:
        argv += ["--set", o]
    return argv + (extra(args) if extra else [])


def stage_stem(command: str) -> str:
    """The JSON a stage leaves that run.json points to: <command>.json, or
    per case for simulate and compare.

    >>> stage_stem("simulate --case runup"), stage_stem("compare --case earthquake"), stage_stem("modal")
    ('simulate_runup', 'compare_earthquake', 'modal')
    >>> stage_stem("compare --case earthquake --components 3")
    'compare_earthquake_components'
    """
    words = command.split()
    if words[0] == "compare" and "--components" in words:
        return "compare_earthquake_components"
    if words[0] in ("simulate", "compare") and "--case" in words:
        return f"{words[0]}_{words[words.index('--case') + 1]}"
    return words[0]


#: At most this many stages at once (each is single-threaded or nearly: more
#: than the cores would only share them).
MAX_SIDE_BY_SIDE = 2


def _reap(proc: subprocess.Popen) -> tuple[int | None, float]:
    """(exit code or None while it runs, its processor time: user + system of the stage
    and of the processes it waited for, s)."""
    pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
    if pid == 0:
        return None, 0.0
    proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait for it
    return proc.returncode, usage.ru_utime + usage.ru_stime


def run_wave(
    jobs: list[tuple[str, list[str]]],
    slots: int,
    cpu: dict[str, float] | None = None,
    on_done: Callable[[str, float], None] | None = None,
) -> dict[str, float]:
    """Run the stage processes of one wave, ``slots`` at a time; each one's wall time (s),
    and into ``cpu`` each one's processor time (s: on a shared machine the steadier
    measure of its work).  ``on_done(command, seconds)`` is called as each stage
    succeeds (exit 0), at once: a later failure in the wave does not undo it.

    A stage that fails stops the wave once the stages already running have
    finished (their files stay whole); Ctrl-C or SIGTERM kills every stage
    still running.
    """
    running: dict = {}
    failed: list = []
    pending, seconds = list(jobs), {}
    cpu = {} if cpu is None else cpu
    try:
        while pending or running:
            while pending and len(running) < slots and not failed:
                command, argv = pending.pop(0)
                # the stage's summary goes to stderr: stdout may carry run's --json
                running[command] = (subprocess.Popen(argv, stdout=sys.stderr), time.perf_counter())
            if not running:
                break
            time.sleep(0.05)
            for command, (proc, start) in list(running.items()):
                code, cpu[command] = _reap(proc)
                if code is None:
                    continue
                seconds[command] = time.perf_counter() - start
                del running[command]
                if code != 0:
                    failed.append((command, code))
                elif on_done is not None:
                    on_done(command, seconds[command])
    except BaseException:
        for proc, _ in running.values():
            proc.kill()
        for proc, _ in running.values():
            proc.wait()
        raise
    if failed:
        command, code = failed[0]
        raise StageError(f"stage {command!r} failed (exit {code}); the stages before it finished and wrote their files")
    return seconds


def stage_scenes(stages, args) -> list[tuple[str, Scene, Any]]:
    """(command, the scene it sees, its parsed arguments) of each stage: its command line
    parsed by the CLI's parser, its own --set before the user's."""
    from ..errors import InputError
    from ..scene import load_scene
    from .parser import build_parser

    parser = build_parser()
    out = []
    for command, _, extra, own, *_ in stages:
        stage_args = parser.parse_args(stage_argv(command, args, extra, own)[3:])
        try:
            out.append((command, load_scene(stage_args.scene, stage_args.overrides), stage_args))
        except InputError as exc:
            raise InputError(f"stage {command!r}: {exc}") from None
    return out


def preflight(scene: Scene, stages, args, checks: list[tuple[str, Scene, Any]] | None = None) -> None:
    """Every stage's own pre-flight checks (``preflight(scene, args)`` of its command's
    module), on the scene and arguments that stage will see (``checks``: its
    :func:`stage_scenes`, computed when not given).  Called before the first stage, so a
    stage that would refuse its input refuses `run`, with nothing written."""
    import importlib

    from ..errors import InputError
    from .parser import COMMANDS

    checks = stage_scenes(stages, args) if checks is None else checks
    # every stage is checked; those that read a record (seconds: a library's imports) last,
    # so that what a cheaper stage also refuses is refused at once
    for command, stage_scene, stage_args in sorted(checks, key=lambda c: c[1].excitation.kind == "record"):
        check = getattr(importlib.import_module(COMMANDS[stage_args.command][0]), "preflight", None)
        try:
            if check is not None:
                check(stage_scene, stage_args)
        except InputError as exc:
            raise InputError(f"stage {command!r}: {exc}") from None


def add_arguments(parser) -> None:
    """run's own flags, beside the report's (which it passes on)."""
    names = sorted({st[0].split()[0] for st in RUN_STAGES} - {"report"})
    parser.add_argument(
        "--skip",
        action="append",
        default=[],
        metavar="STAGE",
        help=f"leave out a stage ({', '.join(names)}); repeatable",
    )
    parser.add_argument(
        "--force",
        action="store_true",
        help="run every stage, also those whose inputs and code are unchanged since they last ran here",
    )


#: What a stage writes beside ``<stem>.json`` that the stages after it read: the
#: convergence study's record, which the chain reads (chain.choice.study_on_disk).
READ_AFTER = {"converge": ("convergence.json",)}


def _inputs(stage, out: Path) -> list[Path]:
    """The files a stage reads from the output folder, for its key: the JSON of every stage
    of an earlier wave and what READ_AFTER names of them (conservative: modal reads
    convergence.json, analyze modal's too, the later waves the chain's files, the report
    all of them)."""
    earlier = [st[0] for st in RUN_STAGES if st[4] < stage[4]]
    names = [f"{stage_stem(c)}.json" for c in earlier] + [n for c in earlier for n in READ_AFTER.get(c, ())]
    return [out / name for name in names]


def key_of(stage, args, stage_scene: Scene, out: Path) -> str:
    """A stage's key (commands.stage_keys.stage_key): its command line, the sections of the
    scene it sees that it reads, the earlier stages' JSON in ``out``, the code."""
    from .stage_keys import command_words, stage_key

    command, _, extra, own, _ = stage
    scene_dict = stage_scene.to_dict()
    if command == "converge":
        scene_dict["band_modes"] = band_modes(stage_scene, out)
    return stage_key(
        command, command_words(command, own, extra(args) if extra else ()), scene_dict, _inputs(stage, out)
    )


def band_modes(scene: Scene, out: Path) -> list[Any]:
    """What the convergence study's key takes of the band (it does not read [drive] and
    [load], commands.stage_keys.SECTIONS_NOT_READ): the modes inside it, by the study on
    disk when it was run for this tube and ladder (chain.choice: its choice stands for any
    band that holds the same modes); without one, the band's top itself (rad/s)."""
    from ..chain.choice import study_mismatch
    from ..converge.result import ConvergenceStudy
    from ..converge.selection import needed_quantities
    from ..reduced.band import excitation_band

    band = excitation_band(scene.drive, scene.load, scene.converge)
    try:
        study = records.read(Path(out) / "convergence.json", ConvergenceStudy)
    except (OSError, ValueError):
        return ["band top", band.omega_max]
    if study_mismatch(scene, study.scene or {}) is not None:
        return ["band top", band.omega_max]
    return ["modes", *needed_quantities(study.reference, band)]


def _page(report: str | None, out: Path) -> list[str]:
    """The report's page as a name in ``out`` (kept with its key: a page removed since is
    made again)."""
    if not report:
        return []
    page = Path(report)
    page = page if page.is_absolute() else Path.cwd() / page
    try:
        return [str(page.resolve().relative_to(out.resolve()))]
    except ValueError:
        return []


def run_command(scene: Scene, args, timings):
    """Every stage of RUN_STAGES, each writing its own JSON; a stage whose key
    (commands.stage_keys) is the one kept from its last success here is not run again."""
    from ..errors import InputError
    from . import out_dir
    from . import stage_keys as keys

    args._scene = scene
    skip = set(getattr(args, "skip", []))
    force = bool(getattr(args, "force", False))
    known = {st[0].split()[0] for st in RUN_STAGES} - {"report"}
    if skip - known:
        raise InputError(f"--skip {sorted(skip - known)[0]}: must be one of {', '.join(sorted(known))}")
    todo = [st for st in RUN_STAGES if st[0].split()[0] not in skip]
    checks = stage_scenes(todo, args)
    preflight(scene, todo, args, checks)  # every stage's bad input: refused now, not late
    scenes = {command: stage_scene for command, stage_scene, _ in checks}
    out = out_dir(scene, args)
    stages, lines, report = {}, [], None
    waves = sorted({st[4] for st in todo})
    slots = max(1, min(os.cpu_count() or 1, MAX_SIDE_BY_SIDE))
    n, ran = 0, False
    for wave in waves:
        group = [st for st in todo if st[4] == wave]
        # each stage's key, once the waves before it have written what it reads
        check_start = time.perf_counter()
        key = {st[0]: key_of(st, args, scenes[st[0]], out) for st in group}
        reused = {}
        for st in group:
            # the report shows every stage: it runs again whenever one of them did
            if not force and not (st[0] == "report" and ran):
                done = keys.recall(out, stage_stem(st[0]), key[st[0]])
                if done is not None:
                    reused[st[0]] = done
        check = (time.perf_counter() - check_start) / len(group)
        runs = [st for st in group if st[0] not in reused]
        for command, what, *_ in group:
            n += 1
            if command in reused:
                done = reused[command]
                progress(f"{command}: unchanged since {keys.since(done)}, {check:.1f} s (it took {done.seconds:.1f} s)")
            else:
                side = " [side by side]" if len(runs) > 1 else ""
                progress(f"run {n}/{len(todo)}: {command} ({what})" + side)
        for st in runs:
            keys.forget(out, stage_stem(st[0]))  # only a success keeps a key

        def done_now(command: str, seconds: float, key: dict[str, str] = key, group: list = group) -> None:
            if command == "converge":  # its key by the study it has just written (band_modes)
                key[command] = key_of(next(st for st in group if st[0] == command), args, scenes[command], out)
            others = list(READ_AFTER.get(command, ()))
            if command == "report":
                from ..postprocess.report import ReportResult

                others += _page(records.read(out / "report.json", ReportResult).report, out)
            keys.remember(out, stage_stem(command), key[command], seconds, others)

        cpu: dict[str, float] = {}
        seconds = run_wave([(st[0], stage_argv(st[0], args, st[2], st[3])) for st in runs], slots, cpu, done_now)
        ran = ran or bool(runs)
        for command, _what, _extra, own, _ in group:
            stem = stage_stem(command)
            path = out / f"{stem}.json"
            written = records.read(path, Provenance)
            first = reused.get(command)
            timings[command] = check if first else seconds[command]
            stages[stem] = Stage(
                json=str(path),
                seconds=timings[command],
                cpu_seconds=None if first else cpu.get(command),
                command=command,
                arguments=tuple(own),
                wave=wave,
                stage_seconds=written.timings.get("total"),
                key=key[command],
                reused=first is not None,
                first_seconds=first.seconds if first else None,
                finished=first.finished if first else None,
            )
            if first:
                lines.append(
                    f"{command:>26}: unchanged since {keys.since(first)} ({first.seconds:.2f} s then)  -> {path}"
                )
            else:
                lines.append(
                    f"{command:>26}: {timings[command]:8.2f} s ({cpu.get(command, 0.0):7.2f} s cpu)  -> {path}"
                )
            if command.split()[0] == "report":
                from ..postprocess.report import ReportResult

                report = records.read(path, ReportResult).report
    if report:
        lines.append(f"{'page':>26}: {report}")
    return Done(RunResult(stages, report), f"rotorpillar run {scene.name}\n" + "\n".join(lines))


class Stage(Record):
    """One stage of `rotorpillar run`: its command, where it wrote, its time."""

    json: str
    """the JSON the stage left"""
    seconds: float
    """the stage's wall time, as run saw it (s)"""
    cpu_seconds: float | None
    """its processor time: user + system of the stage and of the processes it waited for (s)"""
    command: str
    """the stage's command"""
    arguments: tuple[str, ...]
    """its own arguments"""
    wave: int
    """the wave it ran in (stages of a wave run side by side)"""
    stage_seconds: float | None
    """the stage's own total, from its JSON's timings (s)"""
    key: str | None = None
    """its key (commands.stage_keys): command line, scene sections read, input files, code"""
    reused: bool = False
    """true when it was not run again: its key and files were those of its last success here"""
    first_seconds: float | None = None
    """a reused stage's wall time when it last ran (s; ``seconds`` is then the check's)"""
    finished: str | None = None
    """when a reused stage last finished (UTC, ISO 8601)"""


class RunResult(Record):
    """run.json: the stages run and the report's page."""

    stages: dict[str, Stage]
    """the stage's JSON stem -> the stage"""
    report: str | None
    """report.html, when the report ran"""
