"""Write docs/schema.md: every result file's record, and every record's fields, from the types.

``python tools/schema_doc.py`` rewrites the page; ``--check`` exits 1 when the
page on disk is not what the types give (tests/test_schema_doc.py runs it).
Each record is a ``rotorpillar.records.Record`` (a msgspec Struct): its JSON
key, type and required-ness come from ``msgspec.structs.fields`` and
``msgspec.inspect`` (which resolves every annotation, so a type msgspec
cannot decode fails here first), its words from the docstring under each
field in the source.
"""

from __future__ import annotations

import argparse
import ast
import functools
import importlib
import inspect
import sys
from pathlib import Path

import msgspec
from msgspec import inspect as msgspec_inspect

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "schema.md"
PACKAGE = "rotorpillar"

#: The files the commands write, and the record each holds (its provenance beside it).
FILES = (
    ("analyze.json", "rotorpillar.analysis.results", "AnalysisResult"),
    ("modal.json", "rotorpillar.commands.modal", "ModalRun"),
    ("convergence.json", "rotorpillar.converge.result", "ConvergenceStudy"),
    ("converge.json", "rotorpillar.commands.converge", "ConvergeRun"),
    ("simulate_<case>[_<model>].json", "rotorpillar.transients.model_run", "RunRecord"),
    ("compare_<case>.json", "rotorpillar.transients.compare", "CompareResult"),
    ("compare_earthquake_components.json", "rotorpillar.transients.components", "ComponentsComparison"),
    ("integrators.json", "rotorpillar.transients.integrator_study", "IntegratorStudy"),
    ("harmonic.json", "rotorpillar.verdict.harmonic", "HarmonicResult"),
    ("campbell.json", "rotorpillar.reduced.campbell", "CampbellDiagram"),
    ("summary.json", "rotorpillar.verdict.summary", "EngineeringSummary"),
    ("study.json", "rotorpillar.studies.result", "StudyResult"),
    ("tornado.json", "rotorpillar.verdict.tornado", "TornadoResult"),
    ("report.json", "rotorpillar.postprocess.report.build", "ReportResult"),
    ("run.json", "rotorpillar.commands.run", "RunResult"),
)


def record_modules() -> list[str]:
    """The package's modules that define a record (read as text: nothing heavy imported)."""
    out = []
    for path in sorted((ROOT / PACKAGE).rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        if "Record" in text and "class " in text:
            rel = path.relative_to(ROOT).with_suffix("")
            parts = list(rel.parts)
            if parts[-1] == "__init__":
                parts.pop()
            out.append(".".join(parts))
    return out


@functools.cache
def _class_nodes(module: str) -> dict[str, ast.ClassDef]:
    """Qualified name -> the class's node, for every class a module's source defines.
    Each module is parsed once: inspect.getsource(cls) parses the whole module again for
    each class it is asked (1,349 times here: 3 of the page's 5.5 s)."""
    try:
        tree = ast.parse(inspect.getsource(sys.modules[module]))
    except (OSError, TypeError, KeyError):
        return {}
    out: dict[str, ast.ClassDef] = {}

    def visit(nodes: list[ast.stmt], prefix: str) -> None:
        for node in nodes:
            if isinstance(node, ast.ClassDef):
                out[prefix + node.name] = node
                visit(node.body, f"{prefix}{node.name}.")

    visit(tree.body, "")
    return out


def _class_node(cls: type) -> ast.ClassDef | None:
    return _class_nodes(cls.__module__).get(cls.__qualname__)


def field_docs(cls: type) -> dict[str, str]:
    """Field name -> the docstring written under it in the class's source."""
    node = _class_node(cls)
    body = node.body if node is not None else []
    docs = {}
    for a, b in zip(body, body[1:] + [None]):
        if isinstance(a, ast.AnnAssign) and isinstance(a.target, ast.Name):
            if isinstance(b, ast.Expr) and isinstance(b.value, ast.Constant) and isinstance(b.value.value, str):
                docs[a.target.id] = " ".join(b.value.value.split())
    return docs


def field_annotations(cls: type) -> dict[str, str]:
    """Field name -> its annotation as written (the class and its bases)."""
    out: dict[str, str] = {}
    for klass in reversed(cls.__mro__):
        out.update({k: str(v) for k, v in getattr(klass, "__annotations__", {}).items()})
    return out


def records_of(modules: list[str]) -> list[type]:
    """Every Record subclass the modules define, in module then source order."""
    from rotorpillar.records import Record

    found = []
    for name in modules:
        mod = importlib.import_module(name)
        classes = [
            c
            for c in vars(mod).values()
            if inspect.isclass(c) and issubclass(c, Record) and c is not Record and c.__module__ == name
        ]
        classes.sort(key=lambda c: getattr(_class_node(c), "lineno", 0))
        found += classes
    return found


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def record_section(cls: type) -> list[str]:
    msgspec_inspect.type_info(cls)  # resolves every annotation: an unknown type fails here
    config = cls.__struct_config__  # type: ignore[attr-defined]  # a Struct class
    head = f"### `{cls.__name__}`"
    doc = " ".join((inspect.getdoc(cls) or "").split())
    lines = [head, "", doc] if doc else [head]
    if config.tag_field is not None and isinstance(config.tag, str):
        lines += ["", f'Tagged: `{config.tag_field}` = `"{config.tag}"`.']
    bases = [b.__name__ for b in cls.__bases__ if b.__name__ != "Record"]
    if bases:
        lines += ["", "Extends " + ", ".join(f"`{b}`" for b in bases) + " (its fields first)."]
    docs: dict[str, str] = {}
    for klass in reversed(cls.__mro__):
        docs.update(field_docs(klass))
    notes = field_annotations(cls)
    rows = []
    for f in msgspec.structs.fields(cls):
        required = f.required
        omitted = not required and config.omit_defaults
        when = "yes" if required else ("absent at its default" if omitted else "no")
        rows.append(
            f"| `{f.encode_name}` | `{_cell(notes.get(f.name, '?'))}` | {when} | {_cell(docs.get(f.name, ''))} |"
        )
    if rows:
        lines += ["", "| key | type | required | what (unit) |", "|---|---|---|---|", *rows]
    return lines + [""]


def render() -> str:
    modules = record_modules()
    classes = records_of(modules)
    lines = [
        "# The result files and their records",
        "",
        "GENERATED by `tools/schema_doc.py` from the record types (rotorpillar.records: msgspec",
        "Structs); do not edit: run `python tools/schema_doc.py` after changing a record",
        "(tests/test_schema_doc.py fails while this page is stale).",
        "",
        "Every result file is one record's JSON with its provenance beside it",
        "(`rotorpillar.provenance.Provenance`: `scene`, `versions`, `machine`, `timings`, and",
        "`command`, `scene_source`, `overrides` where a command wrote it).  A record decodes",
        "back with `rotorpillar.records.read(path, Type)`, which names the file and the path of",
        "a field at fault.  A union of records carries a tag (`kind`, or `model` for a run)",
        "naming its member.  Non-finite numbers are written as `null`.",
        "",
        "## Files",
        "",
        "| file | record |",
        "|---|---|",
    ]
    for file, module, name in FILES:
        lines.append(f"| `{file}` | `{name}` ({module}) |")
    lines.append("")
    by_module: dict[str, list[type]] = {}
    for c in classes:
        by_module.setdefault(c.__module__, []).append(c)
    for module, members in by_module.items():
        lines += [f"## {module}", ""]
        for c in members:
            lines += record_section(c)
    return "\n".join(lines).rstrip() + "\n"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--check", action="store_true", help="exit 1 when docs/schema.md is stale")
    args = p.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    text = render()
    if args.check:
        if not PAGE.is_file() or PAGE.read_text(encoding="utf-8") != text:
            print(f"{PAGE.relative_to(ROOT)} is stale: run python tools/schema_doc.py", file=sys.stderr)
            return 1
        return 0
    PAGE.write_text(text, encoding="utf-8")
    print(f"wrote {PAGE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
