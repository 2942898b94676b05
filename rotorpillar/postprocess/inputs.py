"""The results the report renders, as other commands write them to ``out/<scene>/``.

Contracts (field names are the writers'; we read, never write, them):

- ``analyze.json`` (`rotorpillar analyze`): ``pillar``, ``reduction``,
  ``system``, ``resonances[i]`` with ``curves`` {z, omega, a, a_linear, dL,
  L, L_all, Md}, ``drive``, ``paper_comparison`` rows; where present,
  ``paper_model`` (``system``, ``resonances``, ``drive`` of the paper's Eq. 4
  beside the headline model's) and ``pillar_model`` {kind, mesh, dofs,
  source, verified} (:mod:`rotorpillar.postprocess.report.models`); any
  number of resonances, each with its ``direction`` (X or Y).
- ``modal.json`` (`rotorpillar modal`): ``modes`` and ``modes_with_top``
  lists ({omega, frequency_hz, kind, n_circumferential, normalisation,
  modal_mass}), ``reduction``, ``mesh``, ``axes``; mode shapes in
  ``modes_bare.vtu`` and ``modes_top.vtu`` as point arrays ``mode_000``,
  ``mode_001``, ... (3-vectors), in the order of the JSON lists.
- ``simulate_<case>.json`` and ``.npz`` (`rotorpillar simulate`), cases
  runup, rundown, sweep, earthquake: arrays ``t``, ``Omega``, ``tip_x``,
  ``rotor_x``, ``rotor_y``, ``ground_x`` and, for the modal model,
  ``modal_coordinates`` (n_t x k: pillar-tip displacement of each of the
  first k bending modes of ``modes_top.vtu``).
  Per model also ``simulate_<case>_<model>.json`` / ``.npz`` (``model``,
  ``warnings``, ``dofs``, ``wall_seconds``, ``full_order`` for fem3d/beam;
  arrays ``tip_x_relative``, ``tip_x_absolute``, ``shaft_deflection_x``).
- ``compare_<case>.json`` (`rotorpillar compare`): ``models_run``,
  ``reference``, ``excitation``, ``per_model.<model>`` {peak_tip_relative,
  peak_tip_absolute, peak_shaft_deflection, omega_final, wall_seconds, dofs,
  ok, warnings, json, npz}, ``errors.<model>`` {tip_history_error,
  peak_tip_difference, omega_final_difference}, ``cost_ratio.<model>``,
  ``chart``, and for the earthquake ``spectrum`` {period, psa (m/s**2),
  mode_periods, spectral_peak_tip, computed_peak_tip}: read by
  :func:`rotorpillar.postprocess.compare_reader.read_comparison`.
- ``convergence.json`` (`rotorpillar converge`), ``integrators.json``.
- Any PNG in ``out/<scene>/`` (or a direct subfolder) is embedded in the
  report, in the section its file name suggests
  (:data:`rotorpillar.postprocess.report.figures.FIGURE_GROUPS`).  Its caption
  comes from a ``figures`` list in any JSON there, entries
  ``{"file": "name.png", "caption": "..."}``, else from the file name.

A missing file is not an error: every reader returns None and the report
says which command would produce it.

Each result file is read by ONE function (:func:`read_analysis`,
:func:`read_modal`, :func:`read_convergence`, :func:`read_case`); the
report reads the records with attribute access named as the JSON keys
(``analysis.pillar.omega_col1``), so a typed result with the same names
(``AnalysisResult.from_json``) replaces the SimpleNamespace there in one line.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from ..scene import CASES as CASES  # re-exported: the cases, in the order the report shows them
from .shapes import json_type, require, shape_error  # noqa: F401  (require: build.py uses it)

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
def not_computed(command: str, scene_arg: str) -> str:
    """The sentence every section shows when its input is missing.

    >>> not_computed("modal", "paper")
    'not computed: run `rotorpillar modal paper`'
    """
    return f"not computed: run `rotorpillar {command} {scene_arg}`".replace("  ", " ").rstrip()


def read_json(path: str | Path) -> dict | None:
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


def namespace(doc):
    """JSON-shaped data with every object as a SimpleNamespace (lists kept).

    >>> namespace({"pillar": {"omega_col1": 31.3}, "modes": [{"kind": "x"}]}).modes[0].kind
    'x'
    """
    if isinstance(doc, dict):
        return SimpleNamespace(**{k: namespace(v) for k, v in doc.items()})
    if isinstance(doc, list):
        return [namespace(v) for v in doc]
    return doc


def plain(obj):
    """Back to JSON-shaped dicts and lists, from SimpleNamespaces, dataclasses
    (their ``to_dict()`` if they have one) or dicts: for the tables that show
    a whole record.

    >>> plain(namespace({"a": {"b": [1, {"c": 2}]}}))
    {'a': {'b': [1, {'c': 2}]}}
    """
    if hasattr(obj, "to_dict") and not isinstance(obj, type):
        return plain(obj.to_dict())
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {f.name: plain(getattr(obj, f.name)) for f in dataclasses.fields(obj)}
    if isinstance(obj, SimpleNamespace):
        obj = vars(obj)
    if isinstance(obj, dict):
        return {k: plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [plain(v) for v in obj]
    return obj


def entries(mapping) -> list[tuple[str, object]]:
    """(key, value) pairs of a mapping read from JSON (a dict or a SimpleNamespace).

    >>> entries(namespace({"bending": 1, "ovalling": 2}))
    [('bending', 1), ('ovalling', 2)]
    """
    if mapping is None:
        return []
    return list((vars(mapping) if isinstance(mapping, SimpleNamespace) else mapping).items())


class Loaded:
    """A command's result as the report reads it: the typed record, and the
    document it came from (the scene, versions and timings written beside).

    Attributes are the record's, then the document's (the versions and
    timings the command wrote beside); a section kept as plain JSON (a dict,
    or a list of dicts) reads with attribute access too.
    ``to_dict()`` gives the whole document (for :func:`plain`).
    """

    def __init__(self, record, doc: dict):
        self._record, self._doc = record, doc

    def __getattr__(self, name):
        try:
            return _view(getattr(self._record, name))
        except AttributeError:
            if name.startswith("_") or name not in self._doc:
                raise
            return _view(self._doc[name])       # what the command wrote beside: timings, scene...

    def to_dict(self) -> dict:
        return self._doc


def _view(value):
    if isinstance(value, dict):
        return namespace(value)
    if isinstance(value, (list, tuple)) and any(isinstance(v, dict) for v in value):
        return [_view(v) for v in value]
    return value


def read_record(path: str | Path, record_type):
    """The JSON at ``path`` read through its typed record, or None if there is none.

    A document of another shape (another version wrote it, or it was cut
    short) is read as plain attributes instead: every section that finds
    its fields still renders, and the others fail one by one, each naming
    the key it missed.
    """
    doc = read_json(path)
    if doc is None:
        return None
    wrong = shape_error(record_type, doc)
    if wrong:
        raise TypeError(f"{Path(path).name}: {wrong}")
    try:
        return Loaded(record_type.from_json(doc), doc)
    except (KeyError, TypeError, ValueError, AttributeError) as exc:
        required = [f.name for f in dataclasses.fields(record_type)
                    if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING]
        if not any(k in doc for k in required):      # no version of this record: damaged
            missing = exc.args[0] if isinstance(exc, KeyError) and exc.args else required[0]
            raise KeyError(f"{Path(path).name} has no key {missing!r}") from None
        return namespace(doc)


def read_analysis(path: str | Path):
    """``analyze.json`` (an :class:`~rotorpillar.analysis.AnalysisResult`), or None."""
    from ..analysis.results import AnalysisResult
    return read_record(path, AnalysisResult)


def read_modal(path: str | Path):
    """``modal.json`` (a :class:`~rotorpillar.fem3d.modal_summary.ModalSummary`), or None."""
    from ..fem3d.modal_summary import ModalSummary
    return read_record(path, ModalSummary)


def read_convergence(path: str | Path):
    """``convergence.json`` (a :class:`~rotorpillar.converge.ConvergenceStudy`), or None."""
    from ..converge.result import ConvergenceStudy
    return read_record(path, ConvergenceStudy)


def read_case(path: str | Path) -> dict | None:
    """``simulate_<case>.json``: one transient run's summary, or None.

    A plain dict: its fields differ by model and the report shows most of
    them as a generic table; one without its case and model is damaged (KeyError)."""
    doc = read_json(path)
    return None if doc is None else require(doc, {"case": str, "model": str}, Path(path).name)


def read_npz(path: str | Path) -> dict[str, np.ndarray] | None:
    """The arrays of an NPZ file, or None if there is none."""
    path = Path(path)
    if not path.is_file():
        return None
    with np.load(path, allow_pickle=False) as data:
        return {k: np.asarray(data[k]) for k in data.files}


# --------------------------------------------------------------------------
# Axes of the 3D model


@dataclass(frozen=True)
class TubeAxes:
    """Which axis of the 3D model is what (indices 0, 1, 2 = x, y, z)."""
    axial: int
    """along the tube, base to top"""
    x: int
    """the paper's X: the direction the pillar bends in"""

    @property
    def y(self) -> int:
        """the remaining lateral axis"""
        return 3 - self.axial - self.x


def _axis_index(value) -> int | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, int) and 0 <= value <= 2:
        return value
    if isinstance(value, str):
        s = value.strip().lower().lstrip("+-")
        if s in ("x", "y", "z"):
            return "xyz".index(s)
        if s in ("0", "1", "2"):
            return int(s)
    if isinstance(value, (list, tuple)) and len(value) == 3:
        try:
            v = np.abs(np.asarray(value, dtype=float))
        except (TypeError, ValueError):
            return None
        return int(np.argmax(v))
    return None


def tube_axes(meta, bounds=None) -> TubeAxes:
    """Read ``modal.json``'s ``axes`` (strings "x"/"y"/"z", indices or unit
    vectors, under keys naming the tube axis and the paper's X), falling back
    to the longest extent of ``bounds`` (xmin, xmax, ymin, ymax, zmin, zmax)
    for the tube and the first other axis for X.

    >>> tube_axes({"tube": "z", "paper_x": "x"})
    TubeAxes(axial=2, x=0)
    >>> tube_axes({"axial": [0, 1, 0], "X": 2})
    TubeAxes(axial=1, x=2)
    >>> tube_axes(None, (-1, 1, -1, 1, 0, 20))
    TubeAxes(axial=2, x=0)
    """
    axial = x = None
    if isinstance(meta, dict):
        for key, value in meta.items():
            k = key.lower()
            if axial is None and any(w in k for w in ("tube", "axial", "along", "height", "vertical")):
                axial = _axis_index(value)
            elif x is None and (k in ("x", "paper_x", "paperx", "paper x", "bending", "bending_x")
                                or (k.startswith("paper") and k.endswith("x"))):
                x = _axis_index(value)
    if axial is None:
        if bounds is not None:
            ext = [bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]]
            axial = int(np.argmax(ext))
        else:
            axial = 2
    if x is None or x == axial:
        x = 0 if axial != 0 else 1
    return TubeAxes(axial, x)


# --------------------------------------------------------------------------
# Mode shapes


@dataclass
class ModeSet:
    """Mode shapes on the tube's outer surface (a pyvista PolyData)."""
    surface: object
    """pyvista.PolyData with point arrays ``arrays[i]`` (3-vectors)"""
    modes: list[dict]
    """metadata of each mode, from modal.json (kind, frequency_hz, ...)"""
    arrays: list[str]
    axes: TubeAxes
    source: str
    """where the shapes came from (a VTU path, or the closed-form fallback)"""
    notes: list[str] = field(default_factory=list)
    grid: object = None
    """the VTU's cells (pyvista.UnstructuredGrid) the surface was drawn from, or None"""

    def coarser(self, subdivision: int) -> "ModeSet":
        """The same modes on a surface subdivided ``subdivision`` times (quadratic
        cells; an animation's hundreds of frames need fewer points than a picture)."""
        if self.grid is None:
            return self
        return dataclasses.replace(self, surface=tube_surface(self.grid, subdivision))

    def shape(self, i: int) -> np.ndarray:
        """Point displacements of mode i (n_points x 3)."""
        return np.asarray(self.surface.point_data[self.arrays[i]], dtype=float)

    @property
    def height(self) -> float:
        b = self.surface.bounds
        return float(b[2 * self.axes.axial + 1] - b[2 * self.axes.axial])


def mode_label(mode: dict, i: int, lines: bool = False) -> str:
    """The mode in words: number, family and order along the height, its
    direction or waves around (:func:`rotorpillar.postprocess.directions.mode_name`),
    frequency; with ``lines``, short and on three lines (for a picture).

    >>> mode_label({"kind": "ovalling", "n_circumferential": 2, "n_axial": 0, "frequency_hz": 7.25}, 3)
    'mode 4: 1st ovalling, n = 2 waves around, no node along the height, 7.250 Hz'
    >>> print(mode_label({"kind": "bending_x", "n_axial": 1, "frequency_hz": 28.4}, 6, lines=True))
    mode 7: 2nd bending
    horizontal (X)
    28.400 Hz
    """
    from .directions import mode_name
    kind = str(mode.get("kind", "?"))
    f = mode.get("frequency_hz")
    if f is None and mode.get("omega") is not None:
        f = mode["omega"] / (2 * math.pi)
    n_axial, n = mode.get("n_axial"), mode.get("n_circumferential")
    if lines:
        name = mode_name(kind, n_axial, n, short_form=True)
        first, _, second = name.partition(", ")
        text = f"mode {i + 1}: {first}" + (f"\n{second}" if second else "")
    else:
        text = f"mode {i + 1}: {mode_name(kind, n_axial, n)}"
    if f is not None:
        text += ("\n" if lines else ", ") + f"{f:.3f} Hz"
    return text


#: Recursive subdivisions of each quadratic face on the drawn surface: 1
#: triangulates it through its nodes, 2 adds the quadratic shapes at quarter
#: points between them (needed on the graded default mesh, whose long top
#: cells show the second bending mode's curvature as a kink at 1).
SUBDIVISION = 2


def tube_surface(grid, subdivision: int = SUBDIVISION):
    """The outer surface of a VTU's cells as triangles, the mode arrays on it.

    Quadratic cells (the 3D model's default) are drawn on their curved
    geometry: each face is subdivided ``subdivision`` times through its
    shape functions, so a mode's curvature between the nodes and the circles
    between them show (a bending mode is not kinked at the cell faces).
    Linear cells give their faces.
    """
    linear = {3, 5, 8, 9, 10, 12, 13, 14}      # VTK's linear cell types
    if set(np.unique(np.asarray(grid.celltypes)).tolist()) <= linear:
        return grid.extract_surface(algorithm=None)
    return grid.extract_surface(nonlinear_subdivision=subdivision, algorithm="dataset_surface")


def load_modes(vtu: str | Path, modes: list[dict], axes_meta=None) -> ModeSet | None:
    """The mode shapes of a ``modes_*.vtu`` on its outer surface, with their metadata.

    Point arrays ``mode_000``, ``mode_001``, ... in the order of ``modes``;
    arrays beyond the list get a placeholder label, list entries without an
    array are dropped.
    """
    from .offscreen import pyvista
    vtu = Path(vtu)
    if not vtu.is_file():
        return None
    with open(vtu, "rb") as fh:             # refuse a damaged file ourselves: VTK would print
        head = fh.read(256).lstrip()         # its parser's errors and return an empty grid
    if not (head.startswith(b"<?xml") or head.startswith(b"<VTKFile")):
        raise ValueError(f"{vtu.name} is damaged (not a VTU file): rebuild it with `rotorpillar modal`")
    pv = pyvista()
    grid = pv.read(vtu)
    names = sorted(n for n in grid.point_data.keys() if n.startswith("mode_"))
    if grid.n_points == 0 or not names:
        raise ValueError(f"{vtu.name}: no tube with point arrays mode_000, mode_001, ... "
                         f"({grid.n_points} points, arrays {list(grid.point_data.keys())})")
    surface = tube_surface(grid)
    meta = [modes[i] if i < len(modes) else {"kind": "?"} for i in range(len(names))]
    return ModeSet(surface, meta, names, tube_axes(axes_meta, surface.bounds), str(vtu), grid=grid)


def cantilever_tube(height: float, outer_diameter: float, inner_diameter: float,
                    around: int = 48, along: int = 60) -> ModeSet:
    """The fallback when no 3D mode shapes exist: a tube surface generated by
    pyvista (axis z, X = x) carrying the first Euler-Bernoulli cantilever mode
    (:func:`rotorpillar.reduced.pillar.cantilever_mode`), unit tip."""
    from ..reduced.pillar import cantilever_mode
    from .offscreen import pyvista
    pv = pyvista()
    r_in = max(inner_diameter / 2, 1e-3 * outer_diameter)
    grid = pv.CylinderStructured(radius=[r_in, outer_diameter / 2], height=height,
                                 center=(0, 0, height / 2), direction=(0, 0, 1),
                                 theta_resolution=around, z_resolution=along + 1)
    surface = grid.extract_surface(algorithm=None)
    xi = np.clip(surface.points[:, 2] / height, 0.0, 1.0)
    u = np.zeros((surface.n_points, 3))
    u[:, 0] = cantilever_mode(xi) / cantilever_mode(1.0)
    surface.point_data["mode_000"] = u
    meta = [{"kind": "bending_x", "normalisation": "unit_tip",
             "note": "Euler-Bernoulli cantilever, Eq. 1"}]
    return ModeSet(surface, meta, ["mode_000"], TubeAxes(2, 0),
                   "Euler-Bernoulli cantilever shape on a generated tube (no modes_top.vtu)")


def bending_columns(modes: list[dict], k: int, explicit=None) -> list[int]:
    """Indices into ``modes`` of the k modes a simulation's ``modal_coordinates``
    columns refer to: ``explicit`` if the simulation names them, else the
    first k modes of kind "bending_x" (the paper's X), else the first k
    bending modes of any direction.

    >>> ms = [{"kind": "bending_x"}, {"kind": "bending_y"}, {"kind": "ovalling"}, {"kind": "bending_x"}]
    >>> bending_columns(ms, 2), bending_columns(ms, 1, explicit=[3])
    ([0, 3], [3])
    """
    if explicit is not None:
        idx = [int(i) for i in explicit][:k]
        if len(idx) == k and all(0 <= i < len(modes) for i in idx):
            return idx
    x = [i for i, m in enumerate(modes) if str(m.get("kind", "")) == "bending_x"]
    if len(x) >= k:
        return x[:k]
    anyb = [i for i, m in enumerate(modes) if str(m.get("kind", "")).startswith("bending")]
    return anyb[:k]


# --------------------------------------------------------------------------
# Simulations


@dataclass
class Simulation:
    """One case of `rotorpillar simulate`: its JSON summary and its arrays."""
    case: str
    meta: dict
    arrays: dict

    def get(self, name: str) -> np.ndarray | None:
        a = self.arrays.get(name)
        return None if a is None else np.asarray(a, dtype=float)


def read_simulation(out: str | Path, case: str, model: str | None = None) -> Simulation | None:
    """``simulate_<case>.json`` and ``.npz`` (either may be missing); with
    ``model``, that model's own ``simulate_<case>_<model>.*``."""
    out = Path(out)
    stem = f"simulate_{case}" + (f"_{model}" if model else "")
    meta = read_case(out / f"{stem}.json")
    arrays = read_npz(out / f"{stem}.npz")
    if meta is None and arrays is None:
        return None
    return Simulation(case, meta or {}, arrays or {})
