"""Other libraries' logs stay off the console unless --debug (README, Limits of the output).

What put the C compiler's command lines on a fresh machine's console: ffcx
calls ``logging.basicConfig()`` when imported, and setuptools, building a
form's extension, lowers the root logger to INFO and logs each command at
INFO.  The child processes below do exactly that after the CLI's set-up
(:func:`rotorpillar.cli.quiet_third_party_logs`), then log at WARNING: the
INFO line must be gone and the WARNING kept; with ``debug`` both show.  The
slow test compiles a form for real, in a fresh FFCx cache, through a command.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from conftest import cli

CHILD = """
import logging, sys
from rotorpillar.cli import quiet_third_party_logs
quiet_third_party_logs(debug={debug})
import ffcx                                    # its basicConfig()
logging.getLogger().setLevel(logging.INFO)     # what setuptools does while building
logging.info("x86_64-linux-gnu-gcc -c libffcx_forms_0.c")
logging.getLogger("ffcx").warning("a real warning")
"""


@pytest.mark.parametrize("debug", [False, True])
def test_compiler_lines_are_quiet_unless_debug(debug):
    p = subprocess.run([sys.executable, "-c", CHILD.format(debug=debug)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert "a real warning" in p.stderr
    assert ("x86_64-linux-gnu-gcc" in p.stderr) is debug


@pytest.mark.slow  # compiles two FFCx forms from nothing (~20 s)
def test_a_first_3d_run_prints_no_compiler_lines(tmp_path):
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path / "cache"))  # an empty FFCx cache
    p = cli(
        "simulate",
        "paper",
        "--case",
        "earthquake",
        "--model",
        "fem3d",
        "--out",
        tmp_path / "out",
        "--set",
        "mesh.elements_around=8",
        "--set",
        "mesh.elements_along=4",
        "--set",
        "full_order.elements_around=8",
        # the paper's pulse at 0.5 s, not 5 s, and a run of 0.7 s, not 5.2: the same ten FFCx
        # libraries compiled (listed in both fresh caches), the run's steps 3091 -> 416;
        # this test's command 8.8 -> 7.5 s of CPU (perf task-clock, 2026-11-29)
        *("--set", "excitation.start=0.5", "--set", "full_order.earthquake_duration=0.7"),
        env=env,
        timeout=600,
    )
    assert p.returncode == 0, p.stderr[-2000:]
    assert list((tmp_path / "cache" / "fenics").glob("libffcx_forms_*.so")), "nothing compiled"
    assert "INFO:" not in p.stderr and "gcc" not in p.stderr, p.stderr[-2000:]
