"""``rotorpillar ARGS...`` in the test's own process: conftest's ``cli`` without a child.

:func:`cli_here` calls rotorpillar.cli.main, the CLI's one error boundary (what
``python -m rotorpillar`` calls), with stdout and stderr caught, and returns a
CompletedProcess as ``cli`` does: its exit code, what it printed on stdout (``--json``)
and on stderr (the progress lines, the one-line refusals).  A test that checks a
command's files, exit code and messages checks them so without an interpreter, its
imports and its compiled kernels to load per command (issue 30: test_hostile's run-ups
9.3 -> 4.4 s of CPU, test_run_accuracy's 11 commands 38.0 -> 17.9 s).

What needs the child stays on ``cli``: a signal (Ctrl-C), an environment or a
launcher (mpirun), a crash the process must survive, the start-up itself.
"""

from __future__ import annotations

import contextlib
import io
import subprocess

from rotorpillar.cli import main


def cli_here(*args) -> subprocess.CompletedProcess:
    """``rotorpillar ARGS...`` through rotorpillar.cli.main in this process."""
    words = [str(a) for a in args]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(words)
        except SystemExit as exc:  # argparse's refusal (an unknown choice): the process's exit
            code = exc.code if isinstance(exc.code, int) else 1
    return subprocess.CompletedProcess(words, code, out.getvalue(), err.getvalue())
