"""A run's time series as the report reads them from its ``.npz``.

`simulate` and `compare` write each run's arrays beside its JSON
(:func:`rotorpillar.transients.case_summary.run_arrays` and the 3D full order's
writer).  Which columns a file holds depends on the model: the frame of its
displacements, its drive, its modes.  :class:`RunArrays` gives the series the page
draws as typed fields, None where the file has none, and keeps every array of the
file by its name (:meth:`RunArrays.series`) so that nothing written is lost.
"""

from __future__ import annotations

import zipfile
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np


def _float(a: np.ndarray | None) -> np.ndarray | None:
    return None if a is None else np.asarray(a, dtype=float)


@dataclass(frozen=True, eq=False)
class RunArrays:
    """One run's arrays: the series the report reads, and all of them by name.

    Displacements are along the paper's X (horizontal, in the rotor's plane) unless a
    field says otherwise.  Every field holds one value per time step of ``t``; each is
    None where the run did not write it.
    """

    t: np.ndarray | None = None
    """the times of the steps (s)"""
    Omega: np.ndarray | None = None
    """the rotor's speed (rad/s)"""
    ground_x: np.ndarray | None = None
    """the ground's displacement (m)"""
    ground_acceleration: np.ndarray | None = None
    """the ground's acceleration (m/s**2)"""
    tip_x: np.ndarray | None = None
    """the pillar tip's displacement, in the frame the run's JSON names (``tip_x_frame``) (m)"""
    tip_x_relative: np.ndarray | None = None
    """the pillar tip's displacement relative to the ground (m)"""
    tip_x_absolute: np.ndarray | None = None
    """the pillar tip's displacement in the fixed frame (m)"""
    rotor_x: np.ndarray | None = None
    """the rotor centre's displacement, in the same frame as ``tip_x`` (m)"""
    rotor_y: np.ndarray | None = None
    """the rotor centre's displacement along the paper's Y (vertical) (m)"""
    modal_coordinates: np.ndarray | None = None
    """the pillar's modal coordinates, one column per mode, each mode scaled to a unit
    tip displacement (m)"""
    named: Mapping[str, np.ndarray] = field(default_factory=dict, repr=False)
    """every array of the file by its name, the fields' own included, as stored"""

    @classmethod
    def of(cls, arrays: Mapping[str, np.ndarray]) -> RunArrays:
        """The series of a mapping by column name (an NPZ's, a writer's), as floats.

        >>> a = RunArrays.of({"t": np.array([0, 1]), "work": np.array([0.0, 2.0])})
        >>> a.t.dtype.name, a.Omega is None, a.series("work").tolist()
        ('float64', True, [0.0, 2.0])
        """
        named = {k: np.asarray(v) for k, v in arrays.items()}
        return cls(
            t=_float(named.get("t")),
            Omega=_float(named.get("Omega")),
            ground_x=_float(named.get("ground_x")),
            ground_acceleration=_float(named.get("ground_acceleration")),
            tip_x=_float(named.get("tip_x")),
            tip_x_relative=_float(named.get("tip_x_relative")),
            tip_x_absolute=_float(named.get("tip_x_absolute")),
            rotor_x=_float(named.get("rotor_x")),
            rotor_y=_float(named.get("rotor_y")),
            modal_coordinates=_float(named.get("modal_coordinates")),
            named=named,
        )

    def series(self, name: str) -> np.ndarray | None:
        """Any array of the file by its name (as stored), or None where it has none."""
        return self.named.get(name)

    @property
    def names(self) -> list[str]:
        """The names of the file's arrays, in the file's order."""
        return list(self.named)

    def tip_to_ground(self, frame: str | None) -> np.ndarray | None:
        """The tip's X displacement relative to the ground (m), or None.

        ``tip_x_relative`` where the run wrote it, else ``tip_x`` corrected for the run's
        ``frame`` (:func:`relative_to_ground`).
        """
        if self.tip_x_relative is not None:
            return self.tip_x_relative
        return relative_to_ground(self.tip_x, self.ground_x, frame)

    def rotor_to_ground(self, frame: str | None) -> np.ndarray | None:
        """The rotor centre's X displacement relative to the ground (m), or None."""
        return relative_to_ground(self.rotor_x, self.ground_x, frame)


def relative_to_ground(x: np.ndarray | None, ground: np.ndarray | None, frame: str | None) -> np.ndarray | None:
    """A displacement ``x`` relative to the ground: itself when ``frame`` says it already
    is (``relative_to_ground``), else ``x`` minus the ground's ``ground`` where there is
    one; None without ``x``.

    >>> x, g = np.array([6.0, 7.0]), np.array([6.0, 6.5])
    >>> relative_to_ground(x, g, "absolute").tolist(), relative_to_ground(x, g, "relative_to_ground").tolist()
    ([0.0, 0.5], [6.0, 7.0])
    """
    if x is None:
        return None
    if str(frame or "").startswith("relative") or ground is None:
        return x
    return x - ground


def read_npz(path: str | Path | None) -> RunArrays | None:
    """The arrays of an NPZ file, or None if there is none; a damaged one (truncated, not
    a zip, an array that is not one, a series the page reads that is not numbers)
    raises ValueError naming the file."""
    if path is None or not Path(path).is_file():
        return None
    path = Path(path)
    try:
        with np.load(path, allow_pickle=False) as data:
            return RunArrays.of({k: np.asarray(data[k]) for k in data.files})
    except (ValueError, OSError, EOFError, KeyError, zipfile.BadZipFile) as exc:
        raise ValueError(f"{path.name}: not a readable NPZ ({type(exc).__name__}: {exc})") from None
