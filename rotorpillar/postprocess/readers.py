"""The results the report renders, as other commands write them to ``out/<scene>/``,
each file read by ``records.read`` into its record.

What each file holds is its record's type (docs/schema.md lists them all):
``analyze.json`` an :class:`~rotorpillar.analysis.results.AnalysisResult`,
``modal.json`` a :class:`~rotorpillar.fem3d.modal_summary.ModalSummary` (mode
shapes in ``modes_bare.vtu`` and ``modes_top.vtu``, point arrays ``mode_000``,
``mode_001``, ... in the order of its lists: :mod:`rotorpillar.postprocess.geometry`),
``convergence.json`` a :class:`~rotorpillar.converge.result.ConvergenceStudy`,
``study.json`` a :class:`~rotorpillar.studies.result.StudyResult`,
``integrators.json`` an :class:`~rotorpillar.transients.integrator_study.IntegratorStudy`,
``simulate_<case>[_<model>].json`` a
:data:`~rotorpillar.transients.model_run.RunRecord` (the run's model is its tag) with
its arrays in the ``.npz`` beside it, ``compare_<case>.json`` a
:class:`~rotorpillar.transients.compare.CompareResult`
(:func:`rotorpillar.postprocess.compare_reader.read_comparison` reads the runs it names).
Beside every record: its :class:`~rotorpillar.provenance.Provenance`.

A missing file is not an error: every reader returns None and the report says
which command would produce it.  A damaged one (not JSON, a field missing or of
the wrong type) raises ValueError naming the file and the path of the field at
fault: the report names it damaged, never renders a part of it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from .. import records
from ..provenance import Provenance
from ..scene import CASES as CASES  # re-exported: the cases, in the order the report shows them
from .run_arrays import RunArrays, read_npz

if TYPE_CHECKING:
    from ..reduced.excitation import ExcitationSizes
    from ..transients.model_run import RunRecord

#: Input name -> (file in out/<scene>/, the command that writes it).
INPUTS = {
    "analyze": ("analyze.json", "analyze"),
    "modal": ("modal.json", "modal"),
    "modes_bare": ("modes_bare.vtu", "modal"),
    "modes_top": ("modes_top.vtu", "modal"),
    "convergence": ("convergence.json", "converge"),
    "integrators": ("integrators.json", "integrators"),
}
SIMULATE_COMMAND = "simulate"

R = TypeVar("R")


def not_computed(command: str, scene_arg: str) -> str:
    """The sentence every section shows when its input is missing.

    >>> not_computed("modal", "paper")
    'not computed: run `rotorpillar modal paper`'
    """
    return f"not computed: run `rotorpillar {command} {scene_arg}`".replace("  ", " ").rstrip()


@dataclass(frozen=True)
class Read(Generic[R]):
    """A command's result as read: its record, and what the command wrote beside it."""

    record: R
    provenance: Provenance | None
    """the scene, versions, machine and timings (None: a file without them)"""


def provenance_of(path: str | Path) -> Provenance | None:
    """The provenance written beside a result, or None when the file has none."""
    try:
        return records.read(path, Provenance)
    except ValueError:
        return None


def read_record(path: str | Path, record_type: Any) -> Read[Any] | None:
    """The JSON at ``path`` read as a ``record_type``, or None if there is no such file;
    ValueError naming the file and the field when it is damaged."""
    path = Path(path)
    if not path.is_file():
        return None
    return Read(records.read(path, record_type), provenance_of(path))


def read_run(path: str | Path) -> Read[RunRecord] | None:
    """``simulate_<case>.json`` (or ``simulate_<case>_<model>.json``): its model's run."""
    from ..transients.model_run import RunRecord

    return read_record(path, RunRecord)


@dataclass
class Simulation:
    """One case of `rotorpillar simulate`: its run's record, its arrays and its provenance."""

    case: str
    run: RunRecord | None
    """the JSON's record (:func:`read_run`), None without a JSON"""
    arrays: RunArrays
    """the series of its ``.npz`` (all None without one)"""
    provenance: Provenance | None = field(default=None)
    """what the writer put beside the record; None without a JSON"""

    @property
    def excitation(self) -> ExcitationSizes | None:
        """The run's ground motion's sizes (the earthquake's ``excitation``), or None."""
        return self.run.excitation if self.run is not None else None


def read_simulation(out: str | Path, case: str, model: str | None = None) -> Simulation | None:
    """``simulate_<case>.json`` and ``.npz`` (either may be missing); with
    ``model``, that model's own ``simulate_<case>_<model>.*``."""
    out = Path(out)
    stem = f"simulate_{case}" + (f"_{model}" if model else "")
    got = read_run(out / f"{stem}.json")
    arrays = read_npz(out / f"{stem}.npz")
    if got is None and arrays is None:
        return None
    if got is None:
        return Simulation(case, None, arrays or RunArrays())
    return Simulation(case, got.record, arrays or RunArrays(), got.provenance)
