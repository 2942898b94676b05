"""The models of one case compared: ``compare_<case>.json`` (`rotorpillar
compare`, a :class:`~rotorpillar.transients.compare.CompareResult`) and the
per-model runs it names, as the report reads them; a run's X displacements
relative to the ground.  Contracts in :mod:`.readers`."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..transients.compare import CompareResult
from .readers import read_npz, read_record, read_run

if TYPE_CHECKING:
    from ..provenance import Provenance
    from ..transients.model_run import RunRecord


def relative_to_ground(arrays: dict[str, Any], name: str = "tip_x", frame: str | None = None) -> np.ndarray | None:
    """The X displacement ``name`` (tip_x or rotor_x) relative to the ground:
    the ``<name>_relative`` column where the run wrote one, else the column
    itself when ``frame`` says it is already relative, else the column minus
    ``ground_x``; None if the arrays hold neither.

    >>> a = {"tip_x": np.array([6.0, 7.0]), "ground_x": np.array([6.0, 6.5])}
    >>> relative_to_ground(a).tolist(), relative_to_ground(a, frame="relative_to_ground").tolist()
    ([0.0, 0.5], [6.0, 7.0])
    """
    if arrays.get(f"{name}_relative") is not None:
        return np.asarray(arrays[f"{name}_relative"], dtype=float)
    x = arrays.get(name)
    if x is None:
        return None
    x = np.asarray(x, dtype=float)
    if str(frame or "").startswith("relative"):
        return x
    g = arrays.get("ground_x")
    return x if g is None else x - np.asarray(g, dtype=float)


@dataclass
class Comparison:
    """``compare_<case>.json`` and the runs it names: each model's JSON and arrays."""

    case: str
    record: CompareResult
    provenance: Provenance | None
    """what compare wrote beside the record (the scene, versions, timings)"""
    runs: dict[str, RunRecord] = field(default_factory=dict)
    """model -> the record of its simulate_<case>_<model>.json (missing: absent)"""
    arrays: dict[str, dict[str, np.ndarray]] = field(default_factory=dict)
    """model -> its simulate_<case>_<model>.npz arrays (missing: absent)"""

    @property
    def models(self) -> list[str]:
        """The models run, in the order given to compare."""
        return [str(m) for m in (self.record.models_run or list(self.record.per_model))]

    @property
    def reference(self) -> str | None:
        return self.record.reference

    def tip_relative(self, model: str) -> tuple[np.ndarray, np.ndarray] | None:
        """(t, tip X relative to the ground) of one model, or None."""
        a = self.arrays.get(model)
        if not a or a.get("t") is None:
            return None
        run = self.runs.get(model)
        y = relative_to_ground(a, "tip_x", run.tip_x_frame if run is not None else None)
        return None if y is None else (np.asarray(a["t"], dtype=float), y)


def _beside(out: Path, name: Any) -> Path | None:
    """A file a JSON names (absolute, or a name in ``out``)."""
    if not name:
        return None
    p = Path(str(name))
    return p if p.is_absolute() and p.is_file() else out / p.name


def read_comparison(out: str | Path, case: str) -> Comparison | None:
    """``compare_<case>.json`` with the per-model JSON and NPZ it names, or None."""
    out = Path(out)
    got = read_record(out / f"compare_{case}.json", CompareResult)
    if got is None:
        return None
    c = Comparison(case, got.record, got.provenance)
    per = got.record.per_model
    for m in c.models:
        row = per.get(m)
        path = _beside(out, (row.json if row else "") or f"simulate_{case}_{m}.json")
        run = read_run(path) if path is not None else None
        arrays = read_npz(_beside(out, (row.npz if row else "") or f"simulate_{case}_{m}.npz"))
        if run is not None:
            c.runs[m] = run.record
        if arrays is not None:
            c.arrays[m] = arrays
    return c
