"""The convergence study as a typed result: what ``convergence.json`` holds.

:class:`ConvergenceStudy` is the study the command writes and the report
reads; ``to_json()`` is exactly the document on disk and ``from_json`` its
inverse.  The records inside (each run, each reference value, the
selection) stay the plain dicts they are in the file.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, fields
from pathlib import Path

_KEYS = {"json_file": "json"}
"""Attributes whose key in the document differs from their name."""


@dataclass(frozen=True)
class ConvergenceStudy:
    """Every run of the ladder, the reference values, the fronts, the choice and the failures."""

    scene_name: str
    scene: dict
    """the scene as ``Scene.to_dict()`` gives it"""
    tolerance: float
    """relative frequency tolerance of the choice"""
    cache_dir: str
    families: dict
    """per family name: label, model, order_theory, quantities, sweep"""
    runs: tuple
    """one dict per run: key, family, model, label, level, params, status, the frequencies
    (``bending``, ``ovalling``), dofs, wall_time, peak_memory, errors (``{q}_error``,
    ``{q}_model_error``, ``{q}_discretisation_error``, ``{q}_error_bound``), cached..."""
    reference: dict
    """per quantity: Richardson on the finest runs of the best family (value, order,
    order_theory, error_estimate, family, runs, check)"""
    extrapolations: dict
    """per refined family, per quantity: Richardson on its three finest runs"""
    band: dict
    """the excitation band (free_speed, earthquake_frequency, margin, omega_max, driver)"""
    selection: dict
    """the choice: tolerance, band, needed, chosen (a run's brief or None), reason,
    rejected_cheaper, rule..."""
    pareto: dict
    """per cost ("dofs", "wall_time"), per error ("bending", "ovalling", "band"): labels"""
    failures: tuple
    """where methods fail, one sentence each"""
    study: dict
    """counts (runs, cached, computed, failed, unavailable), compute_seconds, wall_time"""
    charts: dict | None = None
    """chart name -> path (absent when no charts were drawn)"""
    versions: dict | None = None
    machine: dict | None = None
    timings: dict | None = None
    json_file: str | None = None
    """where the study was written (key ``json``; never in the file itself)"""

    @property
    def chosen(self) -> dict | None:
        """The chosen run's brief (label, family, params, dofs, errors...), or None."""
        return self.selection.get("chosen")

    def to_json(self) -> dict:
        """The document as written to convergence.json (optional parts left out when None)."""
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None and f.default is None:
                continue
            out[_KEYS.get(f.name, f.name)] = list(value) if isinstance(value, tuple) else value
        return out

    @classmethod
    def from_json(cls, doc: dict) -> ConvergenceStudy:
        names = {_KEYS.get(f.name, f.name): f.name for f in fields(cls)}
        unknown = set(doc) - set(names)
        if unknown:
            raise ValueError(f"convergence study: unknown keys {sorted(unknown)}")
        kwargs = {names[k]: v for k, v in doc.items()}
        kwargs["runs"] = tuple(kwargs.get("runs", ()))
        kwargs["failures"] = tuple(kwargs.get("failures", ()))
        return cls(**kwargs)

    @classmethod
    def read(cls, path: str | Path) -> ConvergenceStudy:
        """The study in a ``convergence.json``."""
        return cls.from_json(json.loads(Path(path).read_text(encoding="utf-8")))
