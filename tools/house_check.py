"""The house rules of rotorpillar, checked by reading the source (nothing is imported or run).

Run from anywhere: ``python tools/house_check.py`` (``make check`` does).  One
line per rule, ``ok`` or ``FAIL``; exit status 1 when a rule does not hold.

Rules that hold for the whole package:

- no import circle between the package's modules (a package's ``__init__``
  re-exporting its own submodules is not a circle);
- no module over 800 lines;
- ``reduced/`` imports only ``reduced/``, ``scene``, ``errors``, ``provenance``
  (and the package root), and none of the dolfinx world (dolfinx, ufl,
  basix, ffcx, petsc4py, slepc4py, mpi4py, gmsh, meshio): not at the top of a
  module, not inside a function, not by ``importlib.import_module("...")``;
- pyvista, matplotlib and vtk are imported only under ``postprocess/``, and
  there only inside functions (``import rotorpillar`` stays light);
- the equation index in the docstring of ``rotorpillar/reduced/__init__.py``
  (lines ``Eq. N   rotorpillar.module.function``) names at least Eq. 1, 2, 4,
  5, 19 and 23, and every function it names exists and carries its ``Eq. N``
  on the first line of its docstring.

Rules for new code, held by a ratchet (``tools/house_baseline.json`` records
each module's count today; a module may go down, never up; a new module
starts at zero):

- ``dict_results``: functions whose result is a dict (annotated ``-> dict``,
  ``-> dict[...]``, ``Dict``, ``Mapping``, or returning a dict literal):
  results are records (rotorpillar.records).  Serialisers (``to_json``, ``to_dict``, ...)
  are not counted: a dict is their job;
- ``untyped_scene``: parameters named ``scene`` without an annotation
  (``scene: Scene``).

After lowering a count, ``python tools/house_check.py --write-baseline``
records the new numbers (the diff shows them for review).
"""

from __future__ import annotations

import argparse
import ast
import json
import re
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = "rotorpillar"
BASELINE = Path(__file__).with_name("house_baseline.json")

MAX_LINES = 800
REDUCED = f"{PACKAGE}.reduced"
#: What reduced/ may import from the package (besides itself).
REDUCED_MAY_IMPORT = (f"{PACKAGE}.scene", f"{PACKAGE}.errors", f"{PACKAGE}.provenance")
#: Third-party packages of the finite-element side, which reduced/ never imports.
DOLFINX_WORLD = ("dolfinx", "ufl", "basix", "ffcx", "petsc4py", "slepc4py", "mpi4py", "gmsh", "meshio")
PLOTTING = ("pyvista", "matplotlib", "vtk", "vtkmodules")
POSTPROCESS = f"{PACKAGE}.postprocess"
#: The equations the index must name (the paper's model and its averaging theory).
REQUIRED_EQUATIONS = ("1", "2", "4", "5", "19", "23")
INDEX_LINE = re.compile(rf"^Eq\. (\d+)\s+({PACKAGE}\.[\w.]+)\s*$", re.M)
SERIALISERS = {"to_json", "to_dict", "as_dict", "_asdict", "__getstate__", "json_fields"}
DICT_ANNOTATIONS = re.compile(
    r"^(dict|Dict|typing\.Dict|Mapping|typing\.Mapping|"
    r"collections\.abc\.Mapping)(\[.*\])?$"
)


@dataclass(frozen=True)
class Import:
    """One import statement's target, as written in a module."""

    target: str
    """Dotted name imported (a module, or ``module.name`` for ``from module import name``)."""
    line: int
    """Line of the statement (1-based)."""
    lazy: bool
    """True when the statement is inside a function (runs on call, not on import)."""


@dataclass
class Module:
    """A module of the package, parsed."""

    name: str
    """Dotted name (``rotorpillar.reduced.pillar``; a package is named by its ``__init__``)."""
    path: Path
    """File on disk."""
    source: str
    """Its text."""
    rel: str
    """Path from the repository's root (``rotorpillar/reduced/pillar.py``)."""
    tree: ast.Module = field(repr=False)
    """Its syntax tree."""
    _imports: list[Import] | None = field(default=None, repr=False)

    @property
    def is_package(self) -> bool:
        return self.path.name == "__init__.py"


@dataclass(frozen=True)
class Verdict:
    """One rule's outcome: a line for the console."""

    ok: bool
    text: str

    def line(self) -> str:
        return f"{'ok' if self.ok else 'FAIL'} {self.text}"


def load_modules(root: Path, package: str = PACKAGE) -> dict[str, Module]:
    """Every ``.py`` file under ``root/package``, by dotted name."""
    mods = {}
    for path in sorted((root / package).rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        parts = list(path.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        source = path.read_text(encoding="utf-8")
        name = ".".join(parts)
        mods[name] = Module(
            name, path, source, path.relative_to(root).as_posix(), ast.parse(source, filename=str(path))
        )
    return mods


def _function_spans(tree: ast.Module) -> list[tuple[int, int]]:
    return [
        (n.lineno, n.end_lineno or n.lineno)
        for n in ast.walk(tree)
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
    ]


def imports(mod: Module) -> list[Import]:
    """The module's imports, relative ones resolved, with ``importlib.import_module("x")`` too."""
    if mod._imports is None:
        mod._imports = list(_scan_imports(mod))
    return mod._imports


def _scan_imports(mod: Module) -> Iterator[Import]:
    spans = _function_spans(mod.tree)

    def lazy(line: int) -> bool:
        return any(a < line <= b for a, b in spans)

    pkg = mod.name if mod.is_package else mod.name.rpartition(".")[0]
    for node in ast.walk(mod.tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield Import(alias.name, node.lineno, lazy(node.lineno))
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = pkg.split(".")
                up = up[: len(up) - (node.level - 1)]
                base = ".".join(up + ([base] if base else []))
            for alias in node.names:
                yield Import(f"{base}.{alias.name}" if alias.name != "*" else base, node.lineno, lazy(node.lineno))
        elif (
            isinstance(node, ast.Call)
            and node.args
            and isinstance(node.args[0], ast.Constant)
            and isinstance(node.args[0].value, str)
            and (
                (isinstance(node.func, ast.Attribute) and node.func.attr == "import_module")
                or (isinstance(node.func, ast.Name) and node.func.id in ("import_module", "__import__"))
            )
        ):
            yield Import(node.args[0].value, node.lineno, lazy(node.lineno))


def _owner(target: str, mods: dict[str, Module]) -> str | None:
    """The package module an import lands in (``a.b.name`` -> ``a.b``), or None if outside."""
    while target and target not in mods:
        if "." not in target:
            return None
        target = target.rpartition(".")[0]
    return target or None


def import_graph(mods: dict[str, Module]) -> dict[str, set[str]]:
    """Module -> the package modules it imports (itself excluded)."""
    graph: dict[str, set[str]] = {m: set() for m in mods}
    for name, mod in mods.items():
        for imp in imports(mod):
            owner = _owner(imp.target, mods)
            if owner is not None and owner != name:
                graph[name].add(owner)
    return graph


def _is_reexport(a: str, b: str, mods: dict[str, Module]) -> bool:
    return mods[a].is_package and b.startswith(a + ".")


def import_circles(mods: dict[str, Module]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    graph = {a: sorted(b for b in bs if not _is_reexport(a, b, mods)) for a, bs in import_graph(mods).items()}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    circles: list[list[str]] = []
    counter = 0
    for start in graph:
        if start in index:
            continue
        work = [(start, iter(graph[start]))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            v, children = work[-1]
            for w in children:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(graph[w])))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    comp = []
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        comp.append(w)
                        if w == v:
                            break
                    if len(comp) > 1:
                        circles.append(sorted(comp))
    return sorted(circles)


def check_circles(mods: dict[str, Module]) -> Verdict:
    circles = import_circles(mods)
    text = "; ".join(" <-> ".join(c) for c in circles)
    return Verdict(not circles, f"import circles: {len(circles)}" + (f": {text}" if text else ""))


def check_sizes(mods: dict[str, Module]) -> Verdict:
    big = sorted((len(m.source.splitlines()), m.rel) for m in mods.values() if len(m.source.splitlines()) > MAX_LINES)
    largest = max((len(m.source.splitlines()), m.rel) for m in mods.values())
    return Verdict(
        not big,
        f"modules over {MAX_LINES} lines: {len(big)} "
        + (str(big) if big else f"(largest: {largest[1]}, {largest[0]})"),
    )


def _top(target: str) -> str:
    return target.partition(".")[0]


def check_reduced(mods: dict[str, Module]) -> Verdict:
    bad = []
    for name, mod in mods.items():
        if not (name == REDUCED or name.startswith(REDUCED + ".")):
            continue
        for imp in imports(mod):
            owner = _owner(imp.target, mods)
            where = f"{mod.rel}:{imp.line} {imp.target}{' (lazy)' if imp.lazy else ''}"
            if owner is not None:
                allowed = (
                    owner == PACKAGE
                    or owner == REDUCED
                    or owner.startswith(REDUCED + ".")
                    or any(owner == a or owner.startswith(a + ".") for a in REDUCED_MAY_IMPORT)
                )
                if not allowed:
                    bad.append(where)
            elif _top(imp.target) in DOLFINX_WORLD:
                bad.append(where)
    return Verdict(
        not bad,
        "reduced/ imports only reduced/, scene, errors, provenance and no "
        f"dolfinx-world package: {len(bad)}" + (f" {bad[:8]}" if bad else ""),
    )


def check_plotting(mods: dict[str, Module]) -> Verdict:
    outside, eager = [], []
    for name, mod in mods.items():
        for imp in imports(mod):
            if _top(imp.target) not in PLOTTING:
                continue
            where = f"{mod.rel}:{imp.line} {imp.target}"
            if not (name == POSTPROCESS or name.startswith(POSTPROCESS + ".")):
                outside.append(where)
            elif not imp.lazy:
                eager.append(where)
    bad = outside + eager
    return Verdict(
        not bad,
        "pyvista/matplotlib/vtk imported only in postprocess/, inside "
        f"functions: {len(outside)} outside, {len(eager)} at module level" + (f" {bad[:8]}" if bad else ""),
    )


def _first_doc_line(node: ast.AST) -> str:
    if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.Module)):
        return ""
    doc = ast.get_docstring(node) or ""
    return doc.strip().split("\n")[0]


def _definition(dotted: str, mods: dict[str, Module]) -> ast.AST | None:
    """The function or class a dotted path names, found in the syntax trees (not imported)."""
    owner = _owner(dotted, mods)
    if owner is None:
        return None
    node: ast.AST = mods[owner].tree
    for part in dotted[len(owner) + 1 :].split(".") if dotted != owner else []:
        body = getattr(node, "body", [])
        found = [
            n for n in body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and n.name == part
        ]
        if not found:
            return None
        node = found[0]
    return node


def check_equation_index(mods: dict[str, Module]) -> Verdict:
    index_mod = mods.get(REDUCED)
    doc = ast.get_docstring(index_mod.tree) if index_mod else None
    entries = INDEX_LINE.findall(doc or "")
    named = {n for n, _ in entries}
    missing = [n for n in REQUIRED_EQUATIONS if n not in named]
    untagged = []
    for n, dotted in entries:
        node = _definition(dotted, mods)
        if node is None:
            untagged.append(f"Eq. {n}: {dotted} not found")
        elif not re.search(rf"\bEq\. {n}\b(?!\.\d)", _first_doc_line(node)):
            untagged.append(f"Eq. {n}: {dotted} lacks the tag on its first docstring line")
    ok = not missing and not untagged
    return Verdict(
        ok,
        f"equation index in reduced/__init__: {len(entries)} entries, names "
        f"Eq. {', '.join(sorted(named, key=int))}"
        + (f"; missing Eq. {', '.join(missing)}" if missing else "")
        + (f"; {untagged[:6]}" if untagged else "; every named function tagged"),
    )


# -- the ratchet ---------------------------------------------------------------------------


def _is_dict_annotation(node: ast.expr | None) -> bool:
    if node is None:
        return False
    text = ast.unparse(node).strip("'\"")
    return bool(DICT_ANNOTATIONS.match(text))


def _own_returns(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> Iterator[ast.Return]:
    """The return statements of ``fn`` itself (not of functions nested in it)."""
    todo: list[ast.AST] = list(fn.body)
    while todo:
        node = todo.pop()
        if isinstance(node, ast.Return):
            yield node
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            todo.extend(ast.iter_child_nodes(node))


def ratchet_counts(mod: Module) -> dict[str, int]:
    """This module's counts of the ratcheted habits (see the module docstring)."""
    dict_results = untyped_scene = 0
    for node in ast.walk(mod.tree):
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        if node.name not in SERIALISERS and (
            _is_dict_annotation(node.returns)
            or any(isinstance(r.value, (ast.Dict, ast.DictComp)) for r in _own_returns(node))
        ):
            dict_results += 1
        args = node.args
        untyped_scene += sum(
            1 for a in (*args.posonlyargs, *args.args, *args.kwonlyargs) if a.arg == "scene" and a.annotation is None
        )
    return {"dict_results": dict_results, "untyped_scene": untyped_scene}


def all_counts(mods: dict[str, Module]) -> dict[str, dict[str, int]]:
    counts = {}
    for mod in mods.values():
        c = ratchet_counts(mod)
        if any(c.values()):
            counts[mod.rel] = c
    return dict(sorted(counts.items()))


def check_ratchet(mods: dict[str, Module], baseline: dict[str, dict[str, int]]) -> list[Verdict]:
    counts = all_counts(mods)
    verdicts = []
    for key, what in (
        ("dict_results", "functions returning a dict (results are records)"),
        ("untyped_scene", "`scene` parameters without `: Scene`"),
    ):
        grew, fell = [], []
        for rel in sorted(set(counts) | set(baseline)):
            now = counts.get(rel, {}).get(key, 0)
            was = baseline.get(rel, {}).get(key, 0)
            if now > was:
                grew.append(f"{rel} {was}->{now}")
            elif now < was:
                fell.append(rel)
        total = sum(c.get(key, 0) for c in counts.values())
        text = f"no new {what}: {total} today, none added"
        if grew:
            text = f"new {what}: {grew[:8]} (baseline {BASELINE.name})"
        elif fell:
            text += f"; lower the baseline for {fell[:4]} (--write-baseline)"
        verdicts.append(Verdict(not grew, text))
    return verdicts


def run(root: Path = ROOT, baseline_path: Path = BASELINE) -> list[Verdict]:
    mods = load_modules(root)
    baseline = json.loads(baseline_path.read_text()) if baseline_path.exists() else {}
    return [
        check_circles(mods),
        check_sizes(mods),
        check_reduced(mods),
        check_plotting(mods),
        check_equation_index(mods),
        *check_ratchet(mods, baseline),
    ]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0] if __doc__ else None)
    parser.add_argument(
        "--write-baseline", action="store_true", help=f"record today's ratchet counts in {BASELINE.name} and exit"
    )
    args = parser.parse_args(argv)
    if args.write_baseline:
        counts = all_counts(load_modules(ROOT))
        rows = [f" {json.dumps(rel)}: {json.dumps(c)}" for rel, c in counts.items()]
        BASELINE.write_text("{\n" + ",\n".join(rows) + "\n}\n")  # a line a module: small diffs
        print(f"wrote {BASELINE.relative_to(ROOT)}: {len(counts)} modules")
        return 0
    verdicts = run()
    for v in verdicts:
        print(v.line())
    return 0 if all(v.ok for v in verdicts) else 1


if __name__ == "__main__":
    sys.exit(main())
