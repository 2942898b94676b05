"""The package's lines by kind (docs/architecture.md, "Size by kind").

``python tools/line_kinds.py [ROOT]``: every line of ``ROOT/rotorpillar/**/*.py``
(physical lines, docstrings and comments included, as ``wc -l`` counts them)
in one of six kinds, printed as a table, *records and serialisation* split
into its two parts.  How a line is classified, in order:

1. *records and serialisation*:
   - serialisation: the whole of a module that only encodes, decodes or
     checks records (``records.py``, ``postprocess/readers.py``,
     ``postprocess/shapes.py``, ``postprocess/compare_reader.py``), the
     home-made layer's class (``JsonRecord``), and every top-level function or
     method whose name says it serialises (``json`` in it, ``to_dict``,
     ``to_builtins``, ``_record_*``: ``to_json``, ``from_json``,
     ``excitation_sizes_from_json`` ...);
   - record declarations: a top-level class that is a record (a subclass of
     ``Record``, ``JsonRecord`` or ``msgspec.Struct``, or of another such class
     of the package): its header, docstring, fields and their docstrings; its
     other methods (a record's physics: ``PillarModes.truncate``) count with
     the module's kind;
2. the rest of a module by its path: ``cli.py``, ``commands/`` and the
   ``__main__`` modules: *CLI*; ``postprocess/``: *plotting and the page*;
   ``scene/`` and ``errors.py`` (the scene's fields, ranges and checks):
   *validation*; ``provenance.py``, ``cache.py`` and ``executor.py``:
   *provenance and caching* (with the executor the caches serve);
   everything else: *physics and numerics*.

Nothing is imported: the source is read with ``ast``.
"""

from __future__ import annotations

import ast
import re
import sys
from collections import Counter
from pathlib import Path

PACKAGE = "rotorpillar"
KINDS = (
    "physics and numerics",
    "records and serialisation",
    "validation",
    "plotting and the page",
    "CLI",
    "provenance and caching",
)
DECLARATIONS, SERIALISATION = "  record declarations", "  serialisation"
RECORD_BASES = {"Record", "JsonRecord", "Struct"}
#: Modules that only encode, decode or check records (counted whole).
SERIAL_MODULES = re.compile(r"^(records|postprocess/readers|postprocess/shapes|postprocess/compare_reader)\.py$")


def serialiser(name: str) -> bool:
    return "json" in name.lower() or name in ("to_dict", "to_builtins", "JsonRecord") or name.startswith("_record_")


def base_names(node: ast.ClassDef) -> list[str]:
    out = []
    for b in node.bases:
        if isinstance(b, ast.Attribute):
            out.append(b.attr)
        elif isinstance(b, ast.Name):
            out.append(b.id)
    return out


def module_kind(rel: str) -> str:
    parts = rel.split("/")
    if rel in ("cli.py",) or parts[0] == "commands" or parts[-1] == "__main__.py":
        return "CLI"
    if parts[0] == "postprocess":
        return "plotting and the page"
    if parts[0] == "scene" or rel == "errors.py":
        return "validation"
    if rel in ("provenance.py", "cache.py", "executor.py"):
        return "provenance and caching"
    return "physics and numerics"


def span(node: ast.AST) -> range:
    first = min([node.lineno] + [d.lineno for d in getattr(node, "decorator_list", [])])  # type: ignore[attr-defined]
    return range(first, node.end_lineno + 1)  # type: ignore[attr-defined]


def classify(root: Path) -> dict[str, Counter[str]]:
    """Lines per kind (and per part of records and serialisation), per module."""
    trees = {}
    for path in sorted((root / PACKAGE).rglob("*.py")):
        rel = path.relative_to(root / PACKAGE).as_posix()
        text = path.read_text(encoding="utf-8")
        trees[rel] = (text.count("\n") + (0 if text.endswith("\n") or not text else 1), ast.parse(text))
    records = set(RECORD_BASES)
    while True:  # a subclass of a record is a record, wherever its base lives
        found = {
            n.name
            for _, tree in trees.values()
            for n in tree.body
            if isinstance(n, ast.ClassDef) and set(base_names(n)) & records
        }
        if found <= records:
            break
        records |= found
    out: dict[str, Counter[str]] = {}
    for rel, (lines, tree) in trees.items():
        count: Counter[str] = Counter()
        if SERIAL_MODULES.search(rel):
            count[SERIALISATION] = lines
            out[rel] = count
            continue
        serial: set[int] = set()
        declared: set[int] = set()
        for n in tree.body:
            if isinstance(n, ast.ClassDef) and serialiser(n.name):
                serial.update(span(n))
            elif isinstance(n, ast.ClassDef):
                is_record = bool(set(base_names(n)) & records)
                methods: set[int] = set()
                for m in n.body:
                    if isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef)):
                        if serialiser(m.name):
                            serial.update(span(m))
                        methods.update(span(m))
                if is_record:
                    declared.update(set(span(n)) - methods)
            elif isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and serialiser(n.name):
                serial.update(span(n))
        declared -= serial
        count[SERIALISATION] = len(serial)
        count[DECLARATIONS] = len(declared)
        count[module_kind(rel)] += lines - len(serial) - len(declared)
        out[rel] = count
    return out


def main(argv: list[str]) -> int:
    root = Path(argv[1]) if len(argv) > 1 else Path(__file__).resolve().parents[1]
    per_module = classify(root)
    total: Counter[str] = Counter()
    for c in per_module.values():
        total.update(c)
    width = max(map(len, KINDS))
    for kind in KINDS:
        if kind == "records and serialisation":
            print(f"{kind:{width}s} {total[DECLARATIONS] + total[SERIALISATION]:7d}")
            for part in (DECLARATIONS, SERIALISATION):
                print(f"{part:{width}s} {total[part]:7d}")
        else:
            print(f"{kind:{width}s} {total[kind]:7d}")
    print(f"{'all':{width}s} {sum(total.values()):7d}  ({len(per_module)} modules)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
