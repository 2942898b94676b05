"""`make bench`: run every benchmark in bench/ and write bench/results.json.

``bench/run.py MODULE ...`` runs those modules only and replaces their
entries in an existing results.json, keeping the others'.

Each benchmark module defines ``run() -> list[dict]``, entries with at least
``name``, ``compares`` (what against what), ``value`` and ``unit``.  Ratios
are measured side by side in this one run; the machine is recorded once and
in each entry.  Speed lives here, never in tests.
"""

from __future__ import annotations

import importlib
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from rotorpillar.cli import quiet_third_party_logs  # noqa: E402
from rotorpillar.provenance import machine, versions, write_json  # noqa: E402


def main(argv=None) -> int:
    only = set(argv if argv is not None else sys.argv[1:])
    mods = sorted(p.stem for p in HERE.glob("bench_*.py"))
    if only - set(mods):
        # an unknown name would otherwise run nothing and overwrite results.json with nothing
        print(
            f"usage: bench/run.py [MODULE ...] with MODULE one of {', '.join(mods)} "
            f"(got {', '.join(sorted(only - set(mods)))})",
            file=sys.stderr,
        )
        return 2
    quiet_third_party_logs()  # dask's nannies and schedulers talk at INFO; the CLI keeps them quiet too
    host = machine()
    entries, timings = [], {}
    for name in mods:
        if only and name not in only:
            continue
        print(f"[bench] {name} ...", file=sys.stderr, flush=True)
        mod = importlib.import_module(name)
        t0 = time.perf_counter()
        for e in mod.run():
            e.setdefault("module", name)
            e["machine"] = host
            entries.append(e)
            print(
                f"[bench]   {e['name']}: {e['value']:.4g} {e.get('unit', '')}  ({e['compares']})",
                file=sys.stderr,
                flush=True,
            )
        timings[name] = time.perf_counter() - t0
    out = HERE / "results.json"
    if only and out.is_file():
        # a subset run replaces its modules' entries and keeps the others'
        # (each entry carries its module and machine)
        import json

        try:
            old = json.loads(out.read_text())
            kept = [e for e in old.get("benchmarks", []) if e.get("module") not in only]
            entries = kept + entries
            timings = {**{k: v for k, v in old.get("timings", {}).items() if k not in only}, **timings}
        except (ValueError, AttributeError, TypeError):
            pass
    write_json(out, {"benchmarks": entries, "machine": host, "versions": versions(), "timings": timings})
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(HERE))
    sys.exit(main())
