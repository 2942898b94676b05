"""A synthetic ``convergence.json`` for the tests that need a study without running one:
the parts a test states (its runs, reference, choice, band), every other key
convergence.json has filled with neutral values, so that the document reads
through ``ConvergenceStudy`` as a real one does."""

from __future__ import annotations

from typing import Any

from rotorpillar import records
from rotorpillar.converge.ladder import QUANTITIES
from rotorpillar.converge.result import ConvergenceStudy

ERROR_KEYS = tuple(
    f"{q}_{k}" for q in QUANTITIES for k in ("error", "model_error", "discretisation_error", "error_bound")
)
BAND = {
    "free_speed": 89.7,
    "earthquake_frequency": 3.141592653589793,
    "margin": 1.5,
    "omega_max": 134.6,
    "driver": "drive free speed",
}


def run(partial: dict[str, Any]) -> dict[str, Any]:
    """A run of the ladder with the keys a test does not state (None errors, level 0...)."""
    out = {
        "key": partial.get("label", "run"),
        "level": 0,
        "params": {},
        "status": "ok",
        "bending": None,
        "ovalling": None,
        "ovalling_n": None,
        "cached": False,
        **{k: None for k in ERROR_KEYS},
        **partial,
    }
    out.setdefault("family", "solid_hex_p2")
    out.setdefault("model", "solid")
    return out


def brief(partial: dict[str, Any] | None) -> dict[str, Any] | None:
    """A run as the selection names it."""
    if partial is None:
        return None
    r = run(partial)
    keys = ("label", "family", "model", "params", "dofs", "wall_time", "peak_memory", *QUANTITIES, *ERROR_KEYS)
    return {k: r.get(k) for k in keys} | ({"why": partial["why"]} if "why" in partial else {})


def reference(partial: dict[str, Any]) -> dict[str, Any]:
    """A reference value (Richardson) with the keys a test does not state."""
    value = partial["value"]
    return {
        "order": 4.0,
        "order_theory": 4.0,
        "monotone": True,
        "error_estimate": 0.0,
        "h": [],
        "f": [],
        "runs": [],
        "family": "solid_hex_p2",
        **partial,
        "value": value,
    }


def convergence_doc(
    scene,
    runs: list[dict[str, Any]],
    references: dict[str, dict[str, Any]],
    *,
    chosen: dict[str, Any] | None = None,
    band: dict[str, Any] | None = None,
    selection: dict[str, Any] | None = None,
    extrapolations: dict[str, dict[str, dict[str, Any]]] | None = None,
    failures: list[str] | None = None,
    tolerance: float = 1e-3,
) -> dict[str, Any]:
    """The whole document (checked: it reads back through ConvergenceStudy unchanged)."""
    band = {**BAND, **(band or {})}
    sel = {
        "tolerance": tolerance,
        "band": band,
        "needed": ["bending"],
        "reference_uncertainty": {},
        "families": None,
        "candidates": 0 if chosen is None else 1,
        "rule": "cheapest run meeting the tolerance",
        "chosen": chosen,
        "rejected_cheaper": [],
        "reason": "the cheapest",
        **(selection or {}),
    }
    sel["chosen"] = brief(sel["chosen"])
    sel["rejected_cheaper"] = [brief(r) for r in sel["rejected_cheaper"]]
    doc = {
        "scene_name": scene.name,
        "scene": scene.to_dict(),
        "tolerance": tolerance,
        "cache_dir": "cache",
        "families": {},
        "runs": [run(r) for r in runs],
        "reference": {q: reference(r) for q, r in references.items()},
        "extrapolations": {
            fam: {q: {k: v for k, v in reference(r).items() if k != "family"} for q, r in qs.items()}
            for fam, qs in (extrapolations or {}).items()
        },
        "band": band,
        "selection": sel,
        "pareto": {c: {"bending": [], "ovalling": [], "band": []} for c in ("dofs", "wall_time")},
        "failures": list(failures or []),
        "study": {
            "runs": len(runs),
            "workers": 1,
            "cached": 0,
            "computed": len(runs),
            "failed": 0,
            "unavailable": 0,
            "compute_seconds": 0.0,
        },
    }
    records.convert(doc, ConvergenceStudy)  # a document the study's record reads
    return doc
