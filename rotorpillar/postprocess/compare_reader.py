"""The models of one case compared: ``compare_<case>.json`` (`rotorpillar
compare`, a :class:`~rotorpillar.transients.compare.CompareResult`) and the
per-model runs it names, as the report reads them; each model's tip relative
to the ground.  Contracts in :mod:`.readers`."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..transients.compare import CompareResult
from .readers import read_record, read_run
from .run_arrays import RunArrays, read_npz

if TYPE_CHECKING:
    from ..provenance import Provenance
    from ..transients.model_run import RunRecord


@dataclass
class Comparison:
    """``compare_<case>.json`` and the runs it names: each model's JSON and arrays."""

    case: str
    record: CompareResult
    provenance: Provenance | None
    """what compare wrote beside the record (the scene, versions, timings)"""
    runs: dict[str, RunRecord] = field(default_factory=dict)
    """model -> the record of its simulate_<case>_<model>.json (missing: absent)"""
    arrays: dict[str, RunArrays] = field(default_factory=dict)
    """model -> the series of its simulate_<case>_<model>.npz (missing: absent)"""

    @property
    def models(self) -> list[str]:
        """The models run, in the order given to compare."""
        return [str(m) for m in (self.record.models_run or list(self.record.per_model))]

    @property
    def reference(self) -> str | None:
        return self.record.reference

    def arrays_of(self, model: str) -> RunArrays:
        """The series of one model's run (every field None without its ``.npz``)."""
        return self.arrays.get(model) or RunArrays()

    def tip_relative(self, model: str) -> tuple[np.ndarray, np.ndarray] | None:
        """(t, tip X relative to the ground) of one model, or None."""
        a = self.arrays_of(model)
        if a.t is None:
            return None
        run = self.runs.get(model)
        y = a.tip_to_ground(run.tip_x_frame if run is not None else None)
        return None if y is None else (a.t, y)


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
