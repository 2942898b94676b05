"""What several test modules share: the CLI as a user runs it, one `run`, the tiers, VTK hygiene.

- :func:`cli` runs ``python -m rotorpillar ARGS...`` in a child process, as a
  user would, and returns the CompletedProcess (text stdout and stderr).
- :func:`cli_here` and the ``here`` fixture run the same command in the test's process (rotorpillar.cli.main)
  and return what ``cli`` would (``here`` catches the file descriptors, warnings
  and log records too, as a child's stderr would show them): for the cases where a child is not the point (no
  signal, kill, ``ulimit``, mpirun, blocking device or cluster); a Python start-up and
  the imports per command are what it saves.
- ``run_paper`` (session fixture): one ``rotorpillar run paper`` with
  :data:`RUN_PAPER_FLAGS` (converge and compare skipped, 12 frames per animation,
  three mode pictures a set, --quick, a 16 x 4 mesh) into a temporary directory, shared by the tests
  of what the main job writes (all in tests/test_main_job.py, so that one xdist worker
  runs them and the other never idles on the fixture's lock), instead of one run each (the
  comparisons run the 3D full order: tests/test_run_compare.py runs that
  stage alone); under pytest-xdist, shared by the workers too
  (:func:`once_per_session`).
- :func:`shell_runs`: the paper tube's shell rungs in a run cache, once a session, that the
  convergence tests and test_run_keys copy instead of computing them each.
- The tiers (README): ``make test-fast`` runs ``-m "not slow"``; both it and
  ``make test`` run on two processes (pytest-xdist).
  Mark ``@pytest.mark.slow`` a test that runs a 3D or shell model at size, a
  whole ``run``, a study (a convergence ladder, a design study), the set-up,
  or anything else that takes seconds; a test that asks for a fixture of
  :data:`SLOW_FIXTURES` (``run_paper``: the whole main job) is marked here.
- VTK hygiene, after pyvista's own suite (its ``check_gc``): a test marked
  ``@pytest.mark.renders`` (it renders with pyvista in this process) fails
  when VTK objects it created outlive it: a render window, a plotter, a mesh
  held by a cycle or a module global.  Every other test fails when it leaves a
  pyvista plotter open (cheap: no garbage-collector scan).
"""

from __future__ import annotations

import fcntl
import gc
import json
import os
import signal
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
if str(TESTS) not in sys.path:  # tests import their helpers (imagecheck, fixtures)
    sys.path.insert(0, str(TESTS))

#: Fixtures that make a test slow by themselves: each runs the whole main job.
SLOW_FIXTURES = frozenset({"run_paper"})


def sigint_as_in_the_foreground() -> None:
    """``preexec_fn`` of a command a test interrupts: SIGINT back to its default.

    A shell without job control starts a background job with SIGINT ignored, and the
    ignore is inherited by every process below it (`make test &` in a script, some CI
    runners); a Python started so installs no KeyboardInterrupt and runs through a
    Ctrl-C.  A user's Ctrl-C reaches a command in the foreground, whose SIGINT is the
    default: that is the command the test interrupts."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def cli(*args, env=None, cwd=None, prefix=(), timeout=None) -> subprocess.CompletedProcess:
    """``rotorpillar ARGS...`` in a child process; ``prefix`` goes before it (mpirun)."""
    return subprocess.run(
        [*prefix, sys.executable, "-m", "rotorpillar", *map(str, args)],
        capture_output=True,
        text=True,
        env=env,
        cwd=cwd,
        timeout=timeout,
    )


#: The warnings a child Python's default filters keep off stderr: what ``here`` and
#: tests/test_hostile_edges.py's in-process cases leave out of what a user would see.
QUIET_WARNINGS = (DeprecationWarning, PendingDeprecationWarning, ImportWarning, ResourceWarning)


def main_exit_code(argv: list[str]) -> int:
    """``rotorpillar.cli.main(argv)`` in this process; argparse's refusal (SystemExit) is
    its exit code, as the child's would be."""
    from rotorpillar.cli import main

    try:
        return main(argv)
    except SystemExit as exc:  # argparse's refusal: its message is on stderr
        return exc.code if isinstance(exc.code, int) else 1


def cli_here(*args) -> subprocess.CompletedProcess:
    """``cli`` in this process with stdout and stderr caught as Python text: for a test
    (or a module fixture, where ``here``'s capfd is not at hand) that checks a command's
    files, exit code and messages; what needs a child (a signal, mpirun, an environment,
    a crash the process must survive, the start-up itself) stays on ``cli``.  No Python
    start-up, imports and compiled kernels to load per command: test_run_accuracy's 11
    commands 38.0 -> 17.9 s of CPU."""
    import contextlib
    import io

    words = [str(a) for a in args]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main_exit_code(words)
    return subprocess.CompletedProcess(words, code, out.getvalue(), err.getvalue())


class Overtime(BaseException):
    """A command run by ``here`` past its time limit (not an Exception: the CLI's error
    boundary lets it through, and the test fails naming the command)."""


@pytest.fixture
def here(capfd, monkeypatch):
    """``cli`` in this process: ``rotorpillar.cli.main`` (the CLI's one error boundary, as
    tests/test_hostile_edges.py runs its cases), for the cases where a child process is not
    the point (no signal, no kill, no ``ulimit``, no mpirun, no blocking device, no cluster).
    A child costs a Python start-up and the imports (0.15 s for a refusal, seconds for a
    command that loads dolfinx) per case; here they are paid once per test process.

    It returns what ``cli`` returns (a CompletedProcess: the exit code, stdout, stderr), and
    stderr holds what a user would see on it: the file descriptor's text (``capfd``), and
    what in a child would have reached stderr through Python, written as Python writes it:
    each warning the command raised (the child's default filters: deprecations and resource
    warnings left out) and each log record at WARNING or above (the child's
    ``quiet_third_party_logs`` threshold).  So ``one_line`` fails here as it did on a child's
    stderr.  argparse's refusal (SystemExit 2) is its exit code.  ``timeout`` is the child's
    (None: none): a command past it (a hang) is stopped by SIGALRM and the test fails.  ``env`` is what
    the child's environment adds (mpirun's), ``cwd`` its working directory; both are undone
    after the command."""
    import logging
    import signal
    import warnings

    class Logged(logging.Handler):
        def __init__(self):
            super().__init__(logging.WARNING)
            self.lines: list[str] = []

        def emit(self, record):
            self.lines.append(f"{record.levelname}:{record.name}:{record.getMessage()}\n")

    def run(*args, env=None, cwd=None, timeout=None) -> subprocess.CompletedProcess:
        argv = [str(a) for a in args]

        def overtime(signum, frame):
            raise Overtime(f"rotorpillar {' '.join(argv)}: still running after {timeout} s")

        logged, root = Logged(), logging.getLogger()
        with monkeypatch.context() as m:
            for key, value in (env or {}).items():
                m.setenv(key, value)
            if cwd is not None:
                m.chdir(cwd)
            capfd.readouterr()
            previous = signal.signal(signal.SIGALRM, overtime)
            signal.setitimer(signal.ITIMER_REAL, timeout or 0)  # 0: no limit, as cli's None
            root.addHandler(logged)
            try:
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    code = main_exit_code(argv)
            finally:
                root.removeHandler(logged)
                signal.setitimer(signal.ITIMER_REAL, 0)
                signal.signal(signal.SIGALRM, previous)
            out, err = capfd.readouterr()
        said = [
            warnings.formatwarning(w.message, w.category, w.filename, w.lineno)
            for w in caught
            if not issubclass(w.category, QUIET_WARNINGS)
        ]
        return subprocess.CompletedProcess(argv, code, out, err + "".join(said + logged.lines))

    return run


class RunOutput:
    """The finished ``run paper`` with :data:`RUN_PAPER_FLAGS`: its directory and process."""

    def __init__(self, out: Path, process: subprocess.CompletedProcess):
        self.out, self.process = out, process


def once_per_session(name: str, tmp_path_factory, compute: Callable[[Path], dict]) -> tuple[Path, dict]:
    """``compute(directory) -> record`` once for the whole test session, workers included.

    Under pytest-xdist each worker has its own session fixtures: the first to
    get here computes into a directory beside the workers' own (their common
    base) while it holds a lock, and writes the record (JSON); the others wait
    for the lock and read it.  Without xdist it is an ordinary session fixture.
    """
    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent  # shared by the workers of this run
    out, record = base / name, base / f"{name}.json"
    with open(base / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not record.exists():
            out.mkdir(exist_ok=True)
            record.write_text(json.dumps(compute(out)))
    return out, json.loads(record.read_text())


#: ``run_paper``'s flags after ``run paper --out OUT`` (test_main_job's test of the stages'
#: keys runs again into a copy of its folder with them).
#: 12 frames per animation: the animations' wiring, not 180 frames of pyvista (a minute).
#: --quick: the integrator study's shorter ladders (its stage, its record and its report
#: section are the same kinds; the study's numbers are test_integrators'); measured on
#: this fixture, the stage's CPU 16.0 -> 8.5 s (the run 64 -> 61 s of CPU, its wall 46 -> 44 s).
#: --mode-pictures 3: three mode pictures a set, not eight (each set's pictures are drawn by
#: the same code whatever the count; all eight of synthetic modes are test_report's and
#: test_report_reader's); the report on this run's files 17.2-18.0 -> 11.5-12.9 s of CPU.
#: Both, measured in pairs on a loaded machine: the run 73.2 and 70.1 -> 56.7 and 55.1 s
#: of CPU (integrators 19.5, 18.6 -> 8.9, 9.3; report 18.2, 17.4 -> 12.6, 12.0).
#: The 3D tube on a 16 x 4 mesh, not paper's 64 x 10 (the stages that use it, modal, the 3D
#: Campbell diagram and the report's mode pictures, run the same code on fewer elements; the
#: 3D numbers are test_fem3d's and test_campbell_cli's; with no convergence study the chain
#: takes the scene's [mesh] either way): modal 4.3 -> 1.2 s of CPU, campbell 11.6 -> 2.5 s,
#: harmonic 3.4 -> 2.0 s, the run 52.3 -> 38.0 s (caches warm, 2026-11-29).
RUN_PAPER_FLAGS = (
    *("--skip", "converge", "--skip", "compare", "--max-frames", "12", "--mode-pictures", "3", "--quick"),
    *("--set", "mesh.elements_around=16", "--set", "mesh.elements_along=4"),
)


#: The ladder whose shell rungs :func:`shell_runs` computes: test_converge_adaptive's real
#: small ladder (every shell rung of the others' ladders is one of these).
SHELL_LADDER = ("converge.solid=false", "converge.shell_max_around=32", "converge.shell_tri_max_around=24")


def shell_runs(tmp_path_factory) -> Path:
    """A run cache holding the paper tube's shell rungs (Q2 quadrilaterals 8 to 32 around,
    P2 triangles 8 to 24, the Q2 around-only sweep 4 to 16), computed once for the
    session, workers included (:func:`once_per_session`).

    Five slow tests run these very runs: test_converge's shell reference, the real small ladder
    of test_converge_adaptive, the shell limits of test_converge_solid, the studies of
    test_converge_cli's modal test and of test_run_keys' `run`.  A run's cache key is its
    case, the tube and the model's code, so each reads the runs it would have computed (the
    same records, by the same runner) from a copy of this cache and computes only the rest
    (issue 30: each had computed them, in a serving process of its own)."""

    def compute(out: Path) -> dict:
        from rotorpillar import converge as cv
        from rotorpillar.scene import load_scene, override

        scene = override(load_scene("paper"), list(SHELL_LADDER))
        cases = [c for c in cv.ladder(scene) if cv.FAMILIES[c.family].model == "shell"]
        recs = cv.run_study(cases, scene, out, progress=False)
        return {"labels": [r.label for r in recs if r.status == "ok"]}

    out, _ = once_per_session("converge_shell_runs", tmp_path_factory, compute)
    return out


@pytest.fixture(scope="session")
def run_paper(tmp_path_factory) -> RunOutput:
    def run(out: Path) -> dict:
        p = cli("run", "paper", "--out", out, *RUN_PAPER_FLAGS)
        return {"args": p.args, "returncode": p.returncode, "stdout": p.stdout, "stderr": p.stderr}

    out, done = once_per_session("run_paper", tmp_path_factory, run)
    assert done["returncode"] == 0, done["stderr"]
    return RunOutput(out, subprocess.CompletedProcess(**done))


def pytest_collection_modifyitems(config, items) -> None:
    for item in items:
        if SLOW_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)


# -- VTK hygiene ----------------------------------------------------------------------


def vtk_objects() -> dict[int, str]:
    """id -> class name of every VTK object the garbage collector can see.

    An instance of ``vtkObjectBase``, whatever its Python class is called
    (VTK 9.4+ wraps ``vtkPolyData`` as ``vtkmodules.util.data_model.PolyData``).
    """
    core = sys.modules.get("vtkmodules.vtkCommonCore")
    if core is None:  # VTK never imported: no VTK object exists
        return {}
    base = core.vtkObjectBase
    return {id(o): type(o).__name__ for o in gc.get_objects() if isinstance(o, base)}


def open_plotters() -> int:
    """pyvista's plotters not closed yet (0 when pyvista was never imported)."""
    plotter = sys.modules.get("pyvista.plotting.plotter")
    return len(getattr(plotter, "_ALL_PLOTTERS", ()))


def _close_plotters() -> None:
    pv = sys.modules.get("pyvista")
    if pv is not None:
        pv.close_all()


@pytest.fixture(autouse=True)
def vtk_leak_check(request) -> Iterator[None]:
    """Fail the test that leaks VTK objects (``renders``) or leaves a plotter open (any)."""
    full = request.node.get_closest_marker("renders") is not None
    if full:  # no collection first: the scan is what costs
        before = set(vtk_objects())
    plotters = open_plotters()
    yield
    left_open = open_plotters() - plotters
    _close_plotters()  # one test's leak must not fail the next ones
    assert left_open <= 0, f"{left_open} pyvista plotter(s) left open: close them (Plotter.close)"
    if full:
        # a collection only when a new VTK object is there to be collected: it frees objects,
        # never makes one, so with none new before it none is new after it (the same verdict).
        # Most renders tests let theirs go at once; the collection in each teardown was
        # 0.1-0.5 s in a worker holding the suite's objects (the durations of a full run: the
        # renders modules' teardowns 19.5 s in all).  In test_postprocess.py, test_report_kept.py
        # and test_report.py 4 of 47 tests leave a new VTK object to collect; the first two
        # modules 25.6 -> 24.4 s of CPU alone (perf task-clock, 2026-11-29)
        leaked = {i: name for i, name in vtk_objects().items() if i not in before}
        if leaked:
            gc.collect()
            leaked = {i: name for i, name in vtk_objects().items() if i not in before}
        names = sorted(set(leaked.values()))
        assert not leaked, (
            f"{len(leaked)} VTK objects outlive the test (not garbage-collected): "
            f"{', '.join(names[:12])}{' ...' if len(names) > 12 else ''}"
        )
