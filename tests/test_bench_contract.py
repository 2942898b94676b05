"""bench/run.py calls every benchmark as ``run(quick=...)``; CI's ``make bench-quick`` does.

A benchmark whose ``run`` does not take ``quick`` fails only in CI, after the
whole suite (it did once: the two Campbell entries).  Read from the source's
syntax tree, so nothing heavy is imported.
"""

import ast
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "bench"
MODULES = sorted(BENCH.glob("bench_*.py"))


def test_there_are_benchmarks():
    assert len(MODULES) >= 5, MODULES


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.stem)
def test_every_benchmark_takes_quick(path):
    tree = ast.parse(path.read_text())
    runs = [n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "run"]
    assert runs, f"{path.name} has no top-level run()"
    args = runs[0].args
    names = [a.arg for a in args.args + args.kwonlyargs]
    assert "quick" in names, f"{path.name}: run() must accept quick (bench/run.py passes it)"
