"""`make bench`: run every benchmark in bench/ and write bench/results.json.

``bench/run.py MODULE ...`` runs those modules only and replaces their
entries in an existing results.json, keeping the others'.

``bench/run.py --quick [MODULE ...]`` (`make bench-quick`, CI) runs every
benchmark once at a small size and writes bench/results-quick.json: it checks
that each benchmark still runs and writes its entries, not its speed (its
numbers mean nothing).  A benchmark that raises, or returns no entry, or an
entry without a finite ``value``, fails it (exit 1).

Each benchmark module defines ``run(quick: bool = False) -> list[dict]``,
entries with at least ``name``, ``compares`` (what against what), ``value``
and ``unit``.  Ratios are measured side by side in this one run; the machine
is recorded once and in each entry.  Speed lives here, never in tests.
"""

from __future__ import annotations

import argparse
import importlib
import json
import math
import sys
import time
import traceback
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from rotorpillar.cli import quiet_third_party_logs  # noqa: E402
from rotorpillar.provenance import machine, versions, write_json  # noqa: E402

REQUIRED = ("name", "compares", "value", "unit")
"""The keys every entry has."""


def entry_problem(e: Any) -> str | None:
    """What is wrong with a benchmark's entry, or None.

    >>> entry_problem({"name": "x", "compares": "a / b", "value": 2.0, "unit": "x"}) is None
    True
    >>> entry_problem({"name": "x", "compares": "a / b", "value": float("nan"), "unit": "x"})
    'x: value nan is not a finite number'
    """
    if not isinstance(e, dict):
        return f"an entry is a {type(e).__name__}, not a dict"
    missing = [k for k in REQUIRED if k not in e]
    if missing:
        return f"{e.get('name', '?')}: no {', '.join(missing)}"
    v = e["value"]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        return f"{e['name']}: value {v!r} is not a finite number"
    return None


def main(argv: list[str] | None = None) -> int:
    mods = sorted(p.stem for p in HERE.glob("bench_*.py"))
    ap = argparse.ArgumentParser(prog="bench/run.py", description=__doc__.splitlines()[0])
    ap.add_argument("modules", nargs="*", metavar="MODULE", help=f"one of {', '.join(mods)} (default: all)")
    ap.add_argument("--quick", action="store_true", help="each benchmark once at a small size: does it still run")
    args = ap.parse_args(argv)
    only = set(args.modules)
    if only - set(mods):
        # an unknown name would otherwise run nothing and overwrite results.json with nothing
        print(
            f"usage: bench/run.py [--quick] [MODULE ...] with MODULE one of {', '.join(mods)} "
            f"(got {', '.join(sorted(only - set(mods)))})",
            file=sys.stderr,
        )
        return 2
    quiet_third_party_logs()  # dask's nannies and schedulers talk at INFO; the CLI keeps them quiet too
    host = machine()
    entries: list[dict] = []
    timings: dict[str, float] = {}
    problems: list[str] = []
    failed: set[str] = set()
    for name in mods:
        if only and name not in only:
            continue
        print(f"[bench] {name}{' (quick)' if args.quick else ''} ...", file=sys.stderr, flush=True)
        t0 = time.perf_counter()
        try:
            mod = importlib.import_module(name)
            got = mod.run(quick=args.quick)
        except Exception:
            if not args.quick:
                raise
            # the quick run reports every broken benchmark, not the first one only
            problems.append(f"{name}: raised\n{traceback.format_exc()}")
            failed.add(name)
            continue
        finally:
            timings[name] = time.perf_counter() - t0
        if not got:
            problems.append(f"{name}: no entry")
            failed.add(name)
        for e in got:
            bad = entry_problem(e)
            if bad is not None:
                problems.append(f"{name}: {bad}")
                continue
            e.setdefault("module", name)
            e["machine"] = host
            entries.append(e)
            print(
                f"[bench]   {e['name']}: {e['value']:.4g} {e.get('unit', '')}  ({e['compares']})",
                file=sys.stderr,
                flush=True,
            )
    out = HERE / ("results-quick.json" if args.quick else "results.json")
    if only and out.is_file() and not args.quick:
        # a subset run replaces its modules' entries and keeps the others'
        # (each entry carries its module and machine)
        try:
            old = json.loads(out.read_text())
            kept = [e for e in old.get("benchmarks", []) if e.get("module") not in only]
            entries = kept + entries
            timings = {**{k: v for k, v in old.get("timings", {}).items() if k not in only}, **timings}
        except (ValueError, AttributeError, TypeError):
            pass
    doc = {"benchmarks": entries, "machine": host, "versions": versions(), "timings": timings, "quick": args.quick}
    write_json(out, doc)
    if args.quick:
        # read back what was written: every module that ran has its entries there
        written = {e.get("module") for e in json.loads(out.read_text())["benchmarks"]}
        ran = {m for m in mods if not only or m in only}
        problems += [f"{m}: no entry in {out.name}" for m in sorted(ran - written - failed)]
    print(f"wrote {out}")
    for p in problems:
        print(f"[bench] FAILED {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.path.insert(0, str(HERE))
    sys.exit(main())
