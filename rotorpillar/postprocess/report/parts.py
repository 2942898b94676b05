"""Pieces every section uses: a product's image, a failure notice, the
figures of a group, the warning that an input is from another scene, and
the tables of a run's JSON."""

from __future__ import annotations

import json

from ...provenance import to_json
from .. import html as h
from ..inputs import plain
from .state import Build


def product_image(build: Build, key: str) -> str:
    p = build.products[key]
    return h.image(p.path, p.caption)


def figures_of(build: Build, group: str) -> list[str]:
    """The other commands' figures that belong to ``group``."""
    return [h.image(p.path, p.caption) for p in build.products.get("external", [])
            if p.group == group]


def failure(build: Build, key: str) -> list[str]:
    if key in build.failures:
        return [h.tag("p", f"{key}: could not be rendered: {build.failures[key]}", class_="failed")]
    return []


def video(build: Build, key: str) -> list[str]:
    v = build.products.get(key)
    return [h.video(v.path, build.out, v.caption, v.poster)] if v else []


def _note(doc: dict | None) -> list[str]:
    """An input's own top-level ``note`` (e.g. "synthetic fixture"), shown as is."""
    if isinstance(doc, dict) and isinstance(doc.get("note"), str) and doc["note"]:
        return [h.tag("p", f"Note from the input: {doc['note']}", class_="warn")]
    return []


def scene_differs(build: Build, result, ignore=()) -> list[str]:
    """A warning when an input was computed for another version of the scene
    (and the input's own note, if it has one).  ``result``: a result as read
    (a record or a dict), or None; ``ignore``: dotted keys its command set
    on purpose (the comparisons' record)."""
    doc = plain(result)
    if not doc or "scene" not in doc:
        return _note(doc)
    now = json.loads(to_json(build.scene.to_dict()))
    then = doc["scene"]
    diffs = [f"{k}.{kk}" for k, v in now.items() if isinstance(v, dict)
             for kk in v if (not isinstance(then.get(k), dict) or then[k].get(kk) != v[kk])
             and f"{k}.{kk}" not in ignore]
    if not diffs:
        return _note(doc)
    return _note(doc) + [h.tag("p", "Warning: this input was computed for a different scene ("
                  + ", ".join(diffs[:8]) + (" ..." if len(diffs) > 8 else "")
                  + f" differ); re-run {doc.get('command', 'its command')} on this scene.",
                  class_="warn")]


def key_results(meta: dict) -> str | None:
    """The few numbers of a run a reader looks for first, where the JSON has them;
    a run that failed its own checks says so first."""
    rows = []
    if meta.get("ok") is False:
        rows.append(["FAILED: not a solution", "; ".join(meta.get("failed_checks") or
                                                        ["the run reports ok: false"])])
    for key, label in (("model", "model"), ("omega_final", "final speed (rad/s)"),
                       ("captured_at", "captured at (rad/s)"),
                       ("captured_resonance", "held by the resonance at (rad/s)"),
                       ("speed_state", "speed at the end")):
        if key in meta:
            rows.append([label, h.num(meta[key])])
    if isinstance(meta.get("jumps"), list):
        rows.append(["jumps", str(len(meta["jumps"]))])
    for k, v in h.flatten(meta):
        if "energy" in k.lower() and isinstance(v, (int, float)):
            rows.append([k, h.num(v)])
    mx = meta.get("max_abs")
    if isinstance(mx, dict):
        rows += [[f"max |{k}| (m)", h.num(v)] for k, v in mx.items() if isinstance(v, (int, float))]
    return h.table(["", ""], rows) if rows else None


def run_table(result) -> str:
    """Every field of a result (a record or a dict) but its provenance, as a table."""
    meta = plain(result)
    keep = [(k, v) for k, v in h.flatten({k: v for k, v in meta.items()
                                          if k not in ("scene", "versions", "machine", "figures",
                                                       "command", "scene_source", "overrides")})]
    return h.table(["field", "value"], [[k, h.num(v)] for k, v in keep])
