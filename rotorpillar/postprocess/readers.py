"""The results the report renders, as other commands write them to ``out/<scene>/``,
each file read by ONE function into its record.

Contracts (field names are the writers'; we read, never write, them):

- ``analyze.json`` (`rotorpillar analyze`): an
  :class:`~rotorpillar.analysis.results.AnalysisResult` (``pillar``,
  ``reduction``, ``system``, ``resonances`` with their ``curves``, ``drive``,
  ``paper_comparison``, ``paper_model``, ``pillar_model``).
- ``modal.json`` (`rotorpillar modal`): a
  :class:`~rotorpillar.fem3d.modal_summary.ModalSummary` (``modes`` and
  ``modes_with_top`` tuples of :class:`~rotorpillar.fem3d.modal.ModeRow`, ``top``,
  ``reduction``, ``mesh``, ``axes``: records to the leaves); mode
  shapes in ``modes_bare.vtu`` and ``modes_top.vtu``, point arrays
  ``mode_000``, ``mode_001``, ... in the order of the lists
  (:mod:`rotorpillar.postprocess.geometry`).
- ``convergence.json`` (`rotorpillar converge`): a
  :class:`~rotorpillar.converge.result.ConvergenceStudy`.
- ``study.json`` (`rotorpillar study`): a
  :class:`~rotorpillar.studies.result.StudyResult`.
- ``simulate_<case>.json`` and ``.npz`` (`rotorpillar simulate`), cases
  runup, rundown, sweep, earthquake: the JSON a
  :class:`~rotorpillar.transients.run_records.ReducedRun` (paper, modal, beam) or a
  :class:`~rotorpillar.transients.run_records.Fem3dRun` (the 3D full order);
  arrays ``t``, ``Omega``, ``tip_x``, ``rotor_x``, ``rotor_y``, ``ground_x`` and, for
  the modal model, ``modal_coordinates``; per model also
  ``simulate_<case>_<model>.*`` (:class:`Simulation`, by :func:`read_run`).
- ``compare_<case>.json`` (`rotorpillar compare`): a
  :class:`~rotorpillar.transients.records.CompareResult`, read with the runs it
  names by :func:`rotorpillar.postprocess.compare_reader.read_comparison`.
- ``integrators.json`` (`rotorpillar integrators`): an
  :class:`~rotorpillar.transients.integrator_records.IntegratorStudy` (its
  ``accuracy``, ``stability`` and ``energy_drift`` blocks).

A missing file is not an error: every reader returns None and the report
says which command would produce it.  A damaged one (not JSON, not an object,
a key missing, a value of the wrong kind for its record) raises
ValueError, KeyError or TypeError naming the file and the key: the report
names it damaged, never renders a part of it.  A record read here comes with
its document (:class:`Read`): what the command wrote beside the record (the
scene, versions, timings, a note) is there.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Generic, TypeVar

import numpy as np

from ..scene import CASES as CASES  # re-exported: the cases, in the order the report shows them
from .shapes import json_type, require, shape_error

if TYPE_CHECKING:
    from ..analysis.results import AnalysisResult
    from ..converge.result import ConvergenceStudy
    from ..fem3d.modal_summary import ModalSummary
    from ..reduced.excitation_records import ExcitationSizes
    from ..studies.result import StudyResult
    from ..transients.case_summary import CaseSummary
    from ..transients.integrator_records import IntegratorStudy
    from ..transients.run_records import Fem3dRun, RunRecord

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


def read_json(path: str | Path) -> dict[str, Any] | None:
    """The parsed JSON object at ``path``, or None if there is no such file.

    A file that holds anything but an object (``null``, a list, a number) is
    damaged, not missing: ValueError naming it (every command writes an object)."""
    path = Path(path)
    if not path.is_file():
        return None
    doc = json.loads(path.read_text(encoding="utf-8"))
    if not isinstance(doc, dict):
        raise ValueError(f"{path.name} holds a JSON {json_type(doc)}, not an object")
    return doc


@dataclass(frozen=True)
class Read(Generic[R]):
    """A command's result as read: its record, and the document it came from."""

    record: R
    doc: dict[str, Any]
    """the whole JSON object: the record's fields and what the command wrote beside
    them (scene, versions, machine, timings, a note)"""


def read_record(path: str | Path, record_type: type[R]) -> Read[R] | None:
    """The JSON at ``path`` read through its record, or None if there is none.

    A document its record cannot be built from (a key missing, a value of the
    wrong kind: cut short, or written by another version) is damaged:
    KeyError or TypeError naming the file and the key, nothing read."""
    doc = read_json(path)
    if doc is None:
        return None
    return Read(record_of(doc, record_type, Path(path).name), doc)


def record_of(doc: dict[str, Any], record_type: type[R], name: str) -> R:
    """``doc`` (the JSON of file ``name``) as a ``record_type``; KeyError or TypeError
    naming the file and the key when it cannot be one."""
    wrong = shape_error(record_type, doc)
    if wrong:
        raise TypeError(f"{name}: {wrong}")
    try:
        record: R = record_type.from_json(doc)  # type: ignore[attr-defined]  # R: any record
    except KeyError as exc:
        key = exc.args[0] if exc.args else "?"
        raise KeyError(f"{name} has no key {key!r}") from None
    except (TypeError, ValueError, AttributeError) as exc:
        missing = [
            f.name
            for f in dataclasses.fields(record_type)  # type: ignore[arg-type]
            if f.name not in doc and f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
        ]
        if missing:
            raise KeyError(f"{name} has no key {missing[0]!r}") from None
        raise TypeError(f"{name}: {exc}") from None
    return record


def read_analysis(path: str | Path) -> Read[AnalysisResult] | None:
    """``analyze.json``, or None."""
    from ..analysis.results import AnalysisResult

    return read_record(path, AnalysisResult)


def read_modal(path: str | Path) -> Read[ModalSummary] | None:
    """``modal.json``, or None."""
    from ..fem3d.modal_summary import ModalSummary

    return read_record(path, ModalSummary)


def read_convergence(path: str | Path) -> Read[ConvergenceStudy] | None:
    """``convergence.json``, or None."""
    from ..converge.result import ConvergenceStudy

    return read_record(path, ConvergenceStudy)


def read_study(path: str | Path) -> Read[StudyResult] | None:
    """``study.json``, or None."""
    from ..studies.result import StudyResult

    return read_record(path, StudyResult)


def read_integrators(path: str | Path) -> Read[IntegratorStudy] | None:
    """``integrators.json``, or None."""
    from ..transients.integrator_records import IntegratorStudy

    return read_record(path, IntegratorStudy)


def read_run(path: str | Path) -> Read[RunRecord] | None:
    """``simulate_<case>.json`` (or ``simulate_<case>_<model>.json``) through its record:
    a ``Fem3dRun`` for the 3D full order, else a ``ReducedRun``; None if there is none.

    A ``ReducedRun``'s case summary leads its JSON: a key of it missing or of the
    wrong kind is damage too (KeyError or TypeError naming the file and the key)."""
    from ..transients.case_summary import CaseSummary
    from ..transients.run_records import Fem3dRun, ReducedRun

    doc = read_json(path)
    if doc is None:
        return None
    name = Path(path).name
    require(doc, {"case": str, "model": str}, name)
    if doc["model"] == "fem3d":
        return Read(record_of(doc, Fem3dRun, name), doc)
    wrong = shape_error(CaseSummary, doc)
    if wrong:
        raise TypeError(f"{name}: {wrong}")
    for f in dataclasses.fields(CaseSummary):
        if f.default is dataclasses.MISSING and f.name not in doc:
            raise KeyError(f"{name} has no key {f.name!r}")
    return Read(record_of(doc, ReducedRun, name), doc)


def outcome(run: RunRecord) -> CaseSummary | Fem3dRun:
    """Where a run's outcome is (``ok``, ``failed_checks``, ``omega_final``,
    ``captured_at``, ``captured_resonance``, ``speed_state``, ``excitation``, ``max_abs``,
    ``energy_balance``): a reduced model's case summary, the 3D run itself."""
    from ..transients.run_records import Fem3dRun

    return run if isinstance(run, Fem3dRun) else run.summary


def read_npz(path: str | Path | None) -> dict[str, np.ndarray] | None:
    """The arrays of an NPZ file, or None if there is none."""
    if path is None or not Path(path).is_file():
        return None
    with np.load(Path(path), allow_pickle=False) as data:
        return {k: np.asarray(data[k]) for k in data.files}


@dataclass
class Simulation:
    """One case of `rotorpillar simulate`: its run's record, its arrays and its document."""

    case: str
    run: RunRecord | None
    """the JSON's record (:func:`read_run`), None without a JSON"""
    arrays: dict[str, np.ndarray]
    doc: dict[str, Any] = field(default_factory=dict)
    """the whole JSON document: the record's fields and what the writer put beside them
    (scene, files, figures, a note, versions, timings); empty without a JSON (or where
    the run came with its comparison, which keeps the record only)"""

    def get(self, name: str) -> np.ndarray | None:
        a = self.arrays.get(name)
        return None if a is None else np.asarray(a, dtype=float)

    @property
    def excitation(self) -> ExcitationSizes | None:
        """The run's ground motion's sizes (the earthquake's ``excitation``), or None."""
        return outcome(self.run).excitation if self.run is not None else None


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
        return Simulation(case, None, arrays or {})
    return Simulation(case, got.record, arrays or {}, got.doc)


def plain(obj: Any) -> Any:
    """JSON-shaped dicts and lists, from records (dataclasses) or dicts: for the
    tables that show a whole record.

    >>> from rotorpillar.analysis.results import Lumping
    >>> plain({"a": [Lumping(n=2, tip_mass=1.5, tip_stiffness=3.0)]})
    {'a': [{'n': 2, 'tip_mass': 1.5, 'tip_stiffness': 3.0}]}
    """
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {f.name: plain(getattr(obj, f.name)) for f in dataclasses.fields(obj)}
    if isinstance(obj, dict):
        return {k: plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [plain(v) for v in obj]
    return obj


def part(value: Any, name: str, default: Any = None) -> Any:
    """``value``'s field ``name``, whether ``value`` is a record or a JSON object
    (a nested section a record keeps as a dict today, a record tomorrow).

    >>> part({"omega": 3.0}, "omega"), part({"omega": 3.0}, "kind", "?")
    (3.0, '?')
    """
    if isinstance(value, dict):
        return value.get(name, default)
    return getattr(value, name, default)
