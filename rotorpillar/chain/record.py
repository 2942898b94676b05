"""The records of the chain: which pillar model a result used, and how well it is known.

``PillarModel`` is the ``pillar_model`` block every JSON downstream of the
convergence study carries; ``Uncertain`` is a headline number with its error
bar, ``{value, error, sources}`` in the JSON.  Numpy-free records (the report
reads them).
"""

from __future__ import annotations

import math

import msgspec

from ..records import Record

PILLAR_KINDS = ("solid", "shell", "beam", "closed_form")
CHOICE_SOURCES = ("converge", "scene")

MeshValue = int | float | str
"""A value of a model's discretisation (elements, degree, cell type, grading, beam theory;
the paper's reduction: tip mass and stiffness): a run's ``params`` in the convergence
study (rotorpillar.converge.result.Param), here without importing the study."""


class PillarModel(Record):
    """The pillar model a stage used, where the choice came from and its error."""

    kind: str
    """"solid" (the 3D tube, SLEPc modes), "beam" (1D finite elements), "shell" or
    "closed_form\""""
    label: str
    """the ladder's name of the model, e.g. "3D P2 hexahedra, 128x20x1\""""
    mesh: dict[str, MeshValue]
    """its discretisation: elements_around/along/through, degree, cell_type, grading
    (solid, shell), theory and elements (beam), or tip_mass (kg) and tip_stiffness (N/m)
    (the paper's reduction)"""
    dofs: int
    """unknowns of the bare tube's model (-)"""
    source: str
    """"converge": the model the convergence study chose for the scene's band; "scene":
    the scene's own [mesh] (no study on disk, or the study's choice cannot be used)"""
    verified: bool
    """its frequency error is known from a convergence study (a reference and this run)"""
    tolerance: float | None
    """the relative frequency tolerance the study chose it for (-), None without a study"""
    errors: dict[str, float]
    """per frequency the study measured (bending, ovalling, ...): the error bound, model +
    discretisation + the reference's uncertainty (relative, -); empty when unverified"""
    note: str
    """why this model, in words (and what it means when it is not the study's choice)"""
    study: str | None = None
    """the convergence.json the choice was read from"""

    @property
    def bending_error(self) -> float | None:
        """Relative error bound of the first bending frequency, or None (-)."""
        e = self.errors.get("bending")
        return None if e is None or not math.isfinite(e) else float(e)

    def describe(self) -> str:
        """One line: the model, its DOFs, where it came from, its error."""
        err = (
            "error bound " + ", ".join(f"{q} {e:.1e}" for q, e in self.errors.items())
            if self.errors
            else "unverified: no convergence study measured its error"
        )
        return f"{self.label} ({self.dofs:,} DOFs; {self.source}; {err})"


class Uncertain(Record):
    """A headline number with its error bar: the sum of the sources' magnitudes.

    Sources (same unit as the value): ``discretisation`` (the value's change when
    the pillar model's frequencies move by the study's error bound),
    ``truncation`` (the ROM against itself with one more mode), ``integration``
    (the run against one at a hundredth of its tolerance).  A source that was
    not assessed is absent, and ``unassessed`` names it.
    """

    value: float
    """the number (``unit``)"""
    error: float
    """its error bar: the sum of the sources' magnitudes (``unit``)"""
    sources: dict[str, float] = msgspec.field(default_factory=dict)
    """each source's magnitude (``unit``)"""
    unassessed: tuple[str, ...] = ()
    """the sources not assessed"""
    unit: str = ""
    """the value's unit"""

    @classmethod
    def of(cls, value: float, unit: str = "", **sources) -> Uncertain:
        """The value with the magnitudes of the sources given (None: not assessed)."""
        known = {k: abs(float(v)) for k, v in sources.items() if v is not None and math.isfinite(v)}
        missing = tuple(k for k, v in sources.items() if v is None or not math.isfinite(v))
        return cls(float(value), float(sum(known.values())), known, missing, unit)

    def text(self, fmt: str = ".4g") -> str:
        """ "15.36 +- 0.02 rad/s\""""
        unit = f" {self.unit}" if self.unit else ""
        return f"{self.value:{fmt}} ± {self.error:.2g}{unit}"
