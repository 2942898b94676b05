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

import argparse
import dataclasses
import os
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from .. import records
from ..errors import StageError
from ..provenance import Provenance
from ..records import Record
from ..transients.compare import COMPARISONS
from . import Done, progress


class RunStage(Record):
    """One stage of `rotorpillar run`: the command it launches and the wave it runs in."""

    command: str
    """the stage's command, its first word the CLI's command ("compare --case earthquake")"""
    what: str
    """what it does, in the progress line"""
    wave: int
    """its wave: the stages of one wave depend only on the waves before and run side by side"""
    arguments: tuple[str, ...] = ()
    """its own arguments, after the command; its own ``--set`` go before the user's, so the user's win"""
    passes: tuple[str, ...] = ()
    """run's own flags it takes, passed on as run got them (the report's ``--max-frames``, ...)"""

    @property
    def name(self) -> str:
        """The CLI's command it runs, the name ``--skip`` takes: the command's first word."""
        return self.command.split()[0]

    @property
    def stem(self) -> str:
        """The JSON the stage leaves that run.json points to: <command>.json, or per case for
        simulate and compare.

        >>> [RunStage(c, "", 0).stem for c in ("simulate --case runup", "compare --case earthquake", "modal")]
        ['simulate_runup', 'compare_earthquake', 'modal']
        >>> RunStage("compare --case earthquake --components 3", "", 0).stem
        'compare_earthquake_components'
        """
        words = self.command.split()
        if words[0] == "compare" and "--components" in words:
            return "compare_earthquake_components"
        if words[0] in ("simulate", "compare") and "--case" in words:
            return f"{words[0]}_{words[words.index('--case') + 1]}"
        return words[0]

    @property
    def sets(self) -> list[str]:
        """Its own ``--set`` assignments, in order.

        >>> RunStage("compare", "", 0, ("--models", "modal", "--set", "excitation.start=1")).sets
        ['excitation.start=1']
        """
        return [self.arguments[i + 1] for i, a in enumerate(self.arguments[:-1]) if a == "--set"]

    def passed_on(self, args) -> list[str]:
        """Run's flags it takes (:attr:`passes`), as run got them: a switch when it is on, a
        flag with its value when it has one.

        >>> from types import SimpleNamespace
        >>> st = RunStage("report", "", 4, passes=("--max-frames", "--no-animations", "--strict"))
        >>> st.passed_on(SimpleNamespace(max_frames=3, no_animations=True, strict=False))
        ['--max-frames', '3', '--no-animations']
        """
        words: list[str] = []
        for flag in self.passes:
            value = getattr(args, flag.lstrip("-").replace("-", "_"), None)
            if value is True:
                words.append(flag)
            elif value is not None and value is not False:
                words += [flag, str(value)]
        return words


# The stages of `rotorpillar run`, in order.  Stages of one wave depend only on the waves
# before and run side by side; each wave waits for the one before.  The comparisons write
# compare_<case>_<model>.*, apart from the scene's own runs (simulate_<case>_<model>.*).
RUN_STAGES: tuple[RunStage, ...] = (
    # minutes the first time, then read from its cache: it chooses the pillar model
    RunStage("converge", "mesh convergence, speed against accuracy: the pillar model the band needs", wave=0),
    RunStage("modal", "3D modes of the tube on the chosen mesh, bare and with its top mass", wave=1),
    RunStage("analyze", "the headline model (the ROM) and the paper's, averaging", wave=2),
    # El Centro on the ROM and the 3D full order (the study's reference mesh for the modes
    # the load excites), with the speed-against-accuracy study.  On one process: beside the
    # wave's other slot a Dask worker for the study's 3D runs made three busy processes on
    # two cores, and cost its start-up (measured, torque rerun of paper: the stage 33.6 ->
    # 24-26 s of CPU, the wave's stages 96 -> 82-89 s summed, the rerun 64.6 -> 62.1 s)
    RunStage(
        "compare --case earthquake",
        "a recorded earthquake: the ROM against the 3D full order",
        wave=3,
        arguments=(*COMPARISONS["earthquake"], "--workers", "1"),
    ),
    RunStage(
        "compare --case runup",
        "run-up through the resonances: the ROM against the 3D full order",
        wave=3,
        arguments=COMPARISONS["runup"],
    ),
    # A wave's stages start in this order, two at a time: the longest first, so that
    # the two slots end together (paper, measured: integrators 16 s, harmonic 7 s, each
    # simulate 2-3 s; integrators after the two simulate runs left one slot idle 2.5 s
    # longer, and the whole wave waited for it).  The earthquake after the run-up, as
    # before: simulate.json is the last case run.
    # run --quick goes on to it as its own --quick (commands.integrators): its shorter ladders
    RunStage("integrators", "time integrators: error against cost, where each fails", wave=3, passes=("--quick",)),
    # the ROM's and the 3D model's unbalance response, the margins to the loaded tube's modes
    RunStage("harmonic", "unbalance response (Bode) and separation margins (API 684)", wave=3),
    # the Campbell diagram, the ROM's beside the 3D model's (~35 s; after harmonic, so that it
    # fills the slot integrators leaves: measured on paper, the wave ends ~18 s later, not ~35).
    # The 3D on the scene's [mesh]: the chain's chosen mesh (paper: 128 x 20, ~94k DOFs) costs
    # ~140 s (its assembly, the damping's modes, the pencil), past the run's budget; the JSON
    # and stderr say so
    RunStage(
        "campbell",
        "Campbell diagram: the ROM against the 3D model, the critical speeds",
        wave=3,
        arguments=("--model", "both", "--fem3d-mesh", "scene"),
    ),
    # El Centro in three components (180, 270, UP) on the spatial ROM over the whole record
    # and the 3D full order over 4 s from the start (paper: the ROM's largest base moment at
    # 3.3 s; the 3D run ~25 s), the six base reactions
    RunStage(
        "compare --case earthquake --components 3",
        "El Centro in three components: the spatial ROM against the 3D full order, six base reactions",
        wave=3,
        arguments=(
            "--set",
            "excitation.kind=record",
            "--set",
            "excitation.record=elcentro",
            "--set",
            "excitation.start=1",
            "--set",
            "full_order.earthquake_duration=4",
        ),
    ),
    # each uncertain input at the ends of its range on the ROM (paper: 18 runs, ~7 s)
    RunStage("tornado", "how much the checks depend on the uncertain inputs: the tornado chart", wave=3),
    RunStage("simulate --case runup", "run-up from rest on the headline model", wave=3),
    RunStage(
        "simulate --case earthquake",
        "the paper's case: its pulse on Eq. 4 as published",
        wave=3,
        arguments=("--model", "paper"),
    ),
    # the report's own flags that run takes (commands.report.add_arguments) go on to it
    RunStage(
        "report",
        "charts, mode shapes, animations, report.html",
        wave=4,
        passes=("--max-frames", "--mode-pictures", "--no-animations", "--strict"),
    ),
)


def stage_argv(stage: RunStage, args, out: Path) -> list[str]:
    """The command line that launches one stage (its own process, as a user would run it):
    the command, its own arguments, run's scene, ``--out``, the user's overrides (after
    the stage's own --set: the user's win) and run's flags it takes."""
    argv = [sys.executable, "-m", "rotorpillar", *stage.command.split(), *stage.arguments, str(args.scene)]
    argv += ["--out", str(out)]
    for o in args.overrides:
        argv += ["--set", o]
    return argv + stage.passed_on(args)


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


def stage_scene(stage: RunStage, scene: Scene, overrides: Sequence[str]) -> Scene:
    """The scene a stage sees: run's scene (the user's overrides in it) with the stage's own
    --set applied and then the user's again, as its command line puts them: the user's win."""
    from ..errors import InputError
    from ..scene import override

    if not stage.sets:
        return scene
    try:
        return override(scene, [*stage.sets, *overrides])
    except InputError as exc:
        raise InputError(f"stage {stage.command!r}: {exc}") from None


def stage_arguments(
    stage: RunStage, args, out: Path, parser: argparse.ArgumentParser | None = None
) -> argparse.Namespace:
    """A stage's own arguments as its command parses them (``parser``: the CLI's, built when
    not given), for its pre-flight checks: its command, its own flags, run's flags it takes,
    run's scene and ``--out`` (its scene, overrides in, is :func:`stage_scene`'s: the
    namespace has no --set)."""
    from .parser import build_parser
    from .stage_keys import command_words

    words = [*command_words(stage.command, stage.arguments, stage.passed_on(args)), str(args.scene), "--out", str(out)]
    return (parser or build_parser()).parse_args(words)


@dataclasses.dataclass(frozen=True)
class StagePlan:
    """One stage as run launches it: the scene it sees, its arguments, its command line."""

    stage: RunStage
    """the stage"""
    scene: Scene
    """the scene it sees (:func:`stage_scene`)"""
    args: argparse.Namespace
    """its arguments as its command parses them, for its pre-flight checks (:func:`stage_arguments`)"""
    passed_on: tuple[str, ...]
    """run's flags it takes, as run got them (:meth:`RunStage.passed_on`)"""
    argv: tuple[str, ...]
    """the command line that launches it (:func:`stage_argv`)"""


def plan_stages(stages: Sequence[RunStage], scene: Scene, args, out: Path) -> list[StagePlan]:
    """Each stage's :class:`StagePlan` for run's scene, flags and output folder."""
    from .parser import build_parser

    parser = build_parser()  # once: ~20 ms each
    return [
        StagePlan(
            st,
            stage_scene(st, scene, args.overrides),
            stage_arguments(st, args, out, parser),
            tuple(st.passed_on(args)),
            tuple(stage_argv(st, args, out)),
        )
        for st in stages
    ]


def preflight(plans: Sequence[StagePlan]) -> None:
    """Every stage's own pre-flight checks (``preflight(scene, args)`` of its command's
    module), on the scene and arguments that stage will see.  Called before the first
    stage, so a stage that would refuse its input refuses `run`, with nothing written."""
    import importlib

    from ..errors import InputError
    from .parser import COMMANDS

    # every stage is checked; those that read a record (seconds: a library's imports) last,
    # so that what a cheaper stage also refuses is refused at once
    for plan in sorted(plans, key=lambda p: p.scene.excitation.kind == "record"):
        check = getattr(importlib.import_module(COMMANDS[plan.stage.name][0]), "preflight", None)
        try:
            if check is not None:
                check(plan.scene, plan.args)
        except InputError as exc:
            raise InputError(f"stage {plan.stage.command!r}: {exc}") from None


def add_arguments(parser) -> None:
    """run's own flags, beside the report's (which it passes on)."""
    names = sorted({st.name for st in RUN_STAGES} - {"report"})
    parser.add_argument(
        "--skip",
        action="append",
        default=[],
        metavar="STAGE",
        help=f"leave out a stage ({', '.join(names)}); repeatable",
    )
    parser.add_argument(
        "--quick",
        action="store_true",
        help="a first look: the integrator study's shorter ladders (integrators --quick: every other "
        "tolerance and step, up to 5 pillar modes, 20 s of drift; about half its time); every other "
        "stage as without it",
    )
    parser.add_argument(
        "--force",
        action="store_true",
        help="run every stage, also those whose inputs and code are unchanged since they last ran here",
    )


#: What a stage writes beside ``<stem>.json`` that the stages after it read: the
#: convergence study's record, which the chain reads (chain.choice.study_on_disk).
READ_AFTER = {"converge": ("convergence.json",)}


def _inputs(stage: RunStage, out: Path) -> list[Path]:
    """The files a stage reads from the output folder, for its key: the JSON of every stage
    of an earlier wave and what READ_AFTER names of them (conservative: modal reads
    convergence.json, analyze modal's too, the later waves the chain's files, the report
    all of them)."""
    earlier = [st for st in RUN_STAGES if st.wave < stage.wave]
    names = [f"{st.stem}.json" for st in earlier] + [n for st in earlier for n in READ_AFTER.get(st.command, ())]
    return [out / name for name in names]


def key_of(plan: StagePlan, out: Path) -> str:
    """A stage's key (commands.stage_keys.stage_key): its command line, the sections of the
    scene it sees that it reads, the earlier stages' JSON in ``out``, the code."""
    from .stage_keys import command_words, stage_key

    stage = plan.stage
    scene_dict = plan.scene.to_dict()
    if stage.command == "converge":
        scene_dict["band_modes"] = band_modes(plan.scene, out)
    elif stage.command == "modal":
        scene_dict["band_modes"] = modal_band(plan.scene, out)
    words = command_words(stage.command, stage.arguments, plan.passed_on)
    return stage_key(stage.command, words, scene_dict, _inputs(stage, out))


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


def modal_band(scene: Scene, out: Path) -> list[Any]:
    """What modal's key takes of the band (it does not read [drive] and [load] otherwise,
    commands.stage_keys.SECTIONS_NOT_READ).  modal cuts the bare and the loaded tube's modes
    at the band's edge (reduced.band.cut_count: a step function of how many modes lie
    below it) and takes the ROM's modes from the chain's cache, which serves any band its
    modes pass.  So: the cuts of modal.json on disk where they stand at this band's edge
    (reduced.band.cut_stands), and the cached solve the ROM's band reads.  Without
    modal.json, or where a cut or the cached solve would change, the band's tops (rad/s)."""
    from ..chain import choose, rom_band_top
    from ..chain.modes import cached_solve
    from ..reduced.band import cut_stands
    from .modal import band_edge

    edge, rom_top = band_edge(scene), rom_band_top(scene)
    tops = ["band tops", edge, rom_top]
    try:
        done = records.read(Path(out) / "modal.json", ModalModes)
        solve = cached_solve(scene, choose(scene, Path(out)), rom_top)
    except (OSError, ValueError):
        return tops
    listed = [[m.omega for m in modes] for modes in (done.modes, done.modes_with_top)]
    if solve is None or not all(cut_stands(omega, edge) for omega in listed):
        return tops
    return ["modes cut", *(len(omega) for omega in listed), "ROM solve", solve]


class ModeFrequency(Record):
    """One mode's angular frequency in modal.json."""

    omega: float
    """(rad/s)"""


class ModalModes(Record):
    """The part of modal.json that modal's key reads (:func:`modal_band`)."""

    modes: tuple[ModeFrequency, ...]
    """the bare tube's modes, ascending"""
    modes_with_top: tuple[ModeFrequency, ...]
    """the loaded tube's, ascending"""


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

    skip = set(getattr(args, "skip", []))
    force = bool(getattr(args, "force", False))
    known = {st.name for st in RUN_STAGES} - {"report"}
    if skip - known:
        raise InputError(f"--skip {sorted(skip - known)[0]}: must be one of {', '.join(sorted(known))}")
    out = out_dir(scene, args)
    todo = plan_stages([st for st in RUN_STAGES if st.name not in skip], scene, args, out)
    preflight(todo)  # every stage's bad input: refused now, not late
    stages, lines, report = {}, [], None
    waves = sorted({p.stage.wave for p in todo})
    slots = max(1, min(os.cpu_count() or 1, MAX_SIDE_BY_SIDE))
    n, ran = 0, False
    for wave in waves:
        group = {p.stage.command: p for p in todo if p.stage.wave == wave}
        # each stage's key, once the waves before it have written what it reads
        check_start = time.perf_counter()
        key = {command: key_of(p, out) for command, p in group.items()}
        reused = {}
        for command, p in group.items():
            # the report shows every stage: it runs again whenever one of them did
            if not force and not (command == "report" and ran):
                done = keys.recall(out, p.stage.stem, key[command])
                if done is not None:
                    reused[command] = done
        check = (time.perf_counter() - check_start) / len(group)
        runs = [p for command, p in group.items() if command not in reused]
        for command, p in group.items():
            n += 1
            if command in reused:
                done = reused[command]
                progress(f"{command}: unchanged since {keys.since(done)}, {check:.1f} s (it took {done.seconds:.1f} s)")
            else:
                side = " [side by side]" if len(runs) > 1 else ""
                progress(f"run {n}/{len(todo)}: {command} ({p.stage.what})" + side)
        for p in runs:
            keys.forget(out, p.stage.stem)  # only a success keeps a key

        def done_now(
            command: str, seconds: float, key: dict[str, str] = key, group: dict[str, StagePlan] = group
        ) -> None:
            if command in ("converge", "modal"):  # its key by what it has just written (band_modes)
                key[command] = key_of(group[command], out)
            others = list(READ_AFTER.get(command, ()))
            if command == "report":
                from ..postprocess.report import ReportResult

                others += _page(records.read(out / "report.json", ReportResult).report, out)
            keys.remember(out, group[command].stage.stem, key[command], seconds, others)

        cpu: dict[str, float] = {}
        seconds = run_wave([(p.stage.command, list(p.argv)) for p in runs], slots, cpu, done_now)
        ran = ran or bool(runs)
        for command, p in group.items():
            path = out / f"{p.stage.stem}.json"
            written = records.read(path, Provenance)
            first = reused.get(command)
            timings[command] = check if first else seconds[command]
            stages[p.stage.stem] = Stage(
                json=str(path),
                seconds=timings[command],
                cpu_seconds=None if first else cpu.get(command),
                command=command,
                arguments=p.stage.arguments,
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
            if p.stage.name == "report":
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
