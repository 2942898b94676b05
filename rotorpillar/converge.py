"""Mesh convergence and speed versus accuracy: which model does a scene need?

A ladder of pillar models, each refined in steps, computes the bare tube's
first bending and first ovalling frequencies:

- the closed forms: Eq. 1 for bending, the inextensional ring for ovalling;
- 1D beam FE, Euler-Bernoulli (Hermite cubics) and Timoshenko (linear,
  reduced shear), n elements: bending only, a beam has no shell modes;
- the shell model of the mid-surface (rotorpillar.fem3d.shell), quadratic
  quadrilaterals and triangles;
- the 3D solid model (rotorpillar.fem3d.modal_analysis), P1 and P2,
  hexahedra and tetrahedra;
- two side sweeps that refine only around the circumference, to show where
  too few elements around fail the ovalling mode.

Each run records its frequencies, DOFs, wall time and peak memory, and is
cached on disk under a hash of everything it depends on (model, mesh,
degree, cell type, geometry, material and the source of the model's code),
written atomically: an interrupted study resumes where it stopped and
computes nothing twice.  The finite-element runs each run in a fresh
subprocess, whose peak resident memory (ru_maxrss) is the run's; the
pure-Python models run in-process and report tracemalloc's peak.

From the runs: reference values by Richardson extrapolation of the finest
runs of the most complete family (observed order beside the theoretical
one, error estimate by Roache's grid convergence index), each run's error
against them, the Pareto fronts of error against DOFs and against wall
time, and the cheapest model on the front that meets a tolerance over the
frequency band the scene needs (its highest excitation frequency times a
margin).

>>> p = richardson([1/8, 1/16, 1/32], [1.0 + 8.0**-2, 1.0 + 16.0**-2, 1.0 + 32.0**-2])
>>> round(p["order"], 6), round(p["value"], 9)
(2.0, 1.0)
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Optional

import numpy as np
from scipy.optimize import brentq

from .provenance import write_json
from .reduced.beam_fe import BeamProperties, beam_modes
from .reduced.cylinder import ring_frequency
from .reduced.pillar import cowper_shear_coefficient, omega_euler_bernoulli, section_of

QUANTITIES = ("bending", "ovalling")
"""What each run reports: the first bending and the first ovalling frequency."""

CACHE_VERSION = 2
"""Bump to invalidate every cached run (the layout of a cached result changed)."""

GCI_SAFETY = 1.25
"""Roache's safety factor of the grid convergence index for three-grid studies."""

AROUND_LEVELS = (8, 12, 16, 24, 32, 48, 64, 96)
"""Elements around the circumference of the shell ladders."""
ALONG_PER_AROUND = 1.25
"""Shell: elements along per element around (uniform cells, about 2:1)."""
SOLID_AROUND_LEVELS = (32, 64, 96, 128, 160, 192, 224, 256)
"""Elements around of the 3D ladders; along and through follow the scene's [mesh]
in proportion (64 x 10 x 1 graded: multiples of 32 around keep along whole)."""
SWEEP_AROUND = (4, 6, 8, 12, 16)
"""Elements around of the shell's side sweep (elements along fixed)."""
SOLID_SWEEP_AROUND = (4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128)
"""Elements around of the 3D side sweep, at the scene's [mesh] along: the
shell modes need cells around, the bending mode cells along."""
SWEEP_ALONG = 40
"""Shell sweep: elements along (the 3D sweep keeps the scene's [mesh] along)."""
EULER_LEVELS = (1, 2, 4, 8, 16, 32)
TIMOSHENKO_LEVELS = (2, 4, 8, 16, 32, 64, 128, 256, 512)
N_MODES = 12
"""Modes computed per finite-element run: enough to reach the first n = 2 pair."""


# --------------------------------------------------------------------------
# The ladder


@dataclass(frozen=True)
class Family:
    """A model and a way to refine it."""
    name: str
    label: str
    model: str
    """"closed_form", "beam", "shell" or "solid" """
    quantities: tuple
    """which of QUANTITIES the model can have at all"""
    order: Optional[float]
    """theoretical order p of the frequency error ~ h**p (None: not refined)"""
    sweep: bool = False
    """refined around the circumference only: shows a failure, no extrapolation"""
    fidelity: int = 0
    """preference as the reference family (highest with enough runs wins)"""
    parent: Optional[str] = None
    """a sweep's refined family: the same model, whose limit splits its errors"""


FAMILIES = {f.name: f for f in [
    Family("closed_form", "Eq. 1 + ring (closed forms)", "closed_form", QUANTITIES, None),
    Family("beam_euler", "beam Euler-Bernoulli (Hermite)", "beam", ("bending",), 4.0),
    Family("beam_timoshenko", "beam Timoshenko (linear)", "beam", ("bending",), 2.0),
    Family("shell_quad", "shell Q2 quadrilaterals", "shell", QUANTITIES, 4.0, fidelity=2),
    Family("shell_tri", "shell P2 triangles", "shell", QUANTITIES, 4.0, fidelity=1),
    Family("shell_quad_around", "shell Q2, around only (40 along)", "shell", QUANTITIES, None, True,
           parent="shell_quad"),
    Family("solid_hex_p1", "3D P1 hexahedra", "solid", QUANTITIES, 2.0),
    Family("solid_tet_p1", "3D P1 tetrahedra", "solid", QUANTITIES, 2.0),
    Family("solid_hex_p2", "3D P2 hexahedra", "solid", QUANTITIES, 4.0, fidelity=4),
    Family("solid_tet_p2", "3D P2 tetrahedra", "solid", QUANTITIES, 4.0, fidelity=3),
    Family("solid_hex_p2_around", "3D P2 hexahedra, around only", "solid",
           QUANTITIES, None, True, parent="solid_hex_p2"),
]}


ORDER_NOTES = {
    ("solid_hex_p2", "bending"):
        "the clamp's 3D boundary layer under the base rim, about a wall thickness deep, is "
        "much finer than the smallest cell at the base (11 cm at 20 along with grading 30); "
        "with grading 200 the order returns to 4 (tests/test_converge_solid.py)",
    ("solid_tet_p2", "bending"): "as for the P2 hexahedra: the clamp's boundary layer",
    ("shell_tri", "bending"): "P2 triangles lock: their error falls far slower than the "
                              "quadrilaterals' at the same DOFs",
}
"""Why a family's observed order departs from theory, where we checked it."""


@dataclass(frozen=True)
class Case:
    """One run: a family at one refinement ``level`` (elements, or elements around)."""
    family: str
    level: int
    params: tuple
    """the model's discretisation as sorted (key, value) pairs"""

    @property
    def settings(self) -> dict:
        return dict(self.params)

    @property
    def label(self) -> str:
        s = self.settings
        fam = FAMILIES[self.family]
        if fam.model == "closed_form":
            return fam.label
        if fam.model == "beam":
            return f"{fam.label}, {s['elements']} el."
        mesh = f"{s['elements_around']}x{s['elements_along']}"
        if fam.model == "solid":
            mesh += f"x{s['elements_through']}"
        return f"{fam.label}, {mesh}"


def _case(family: str, level: int, **params) -> Case:
    return Case(family, level, tuple(sorted(params.items())))


def _along(around: int) -> int:
    return max(1, int(round(ALONG_PER_AROUND * around)))


def ladder(scene) -> list[Case]:
    """Every run of the study for a scene (its ``[converge]`` limits and ``[mesh]`` shape).

    The 3D rungs refine the scene's own [mesh] in proportion: elements along
    = around x along/around of [mesh], the same elements through and grading,
    so that Richardson sees one family of similar meshes.
    """
    cv, ms = scene.converge, scene.mesh
    cases = [_case("closed_form", 0)]
    cases += [_case("beam_euler", n, theory="euler", elements=n) for n in EULER_LEVELS]
    cases += [_case("beam_timoshenko", n, theory="timoshenko", elements=n)
              for n in TIMOSHENKO_LEVELS]
    for name, cell in (("shell_quad", "quadrilateral"), ("shell_tri", "triangle")):
        top = cv.shell_max_around if cell == "quadrilateral" else cv.shell_tri_max_around
        cases += [_case(name, n, elements_around=n, elements_along=_along(n), cell_type=cell,
                        degree=2) for n in AROUND_LEVELS if n <= top]
    cases += [_case("shell_quad_around", n, elements_around=n, elements_along=SWEEP_ALONG,
                    cell_type="quadrilateral", degree=2) for n in SWEEP_AROUND]
    if cv.solid:
        ratio = ms.elements_along / ms.elements_around
        limits = {"solid_hex_p1": cv.solid_p1_max_around, "solid_tet_p1": cv.solid_p1_max_around,
                  "solid_hex_p2": cv.solid_p2_max_around,
                  "solid_tet_p2": cv.solid_tet_p2_max_around}
        for name, top in limits.items():
            cell = "hexahedron" if "hex" in name else "tetrahedron"
            degree = 2 if name.endswith("p2") else 1
            cases += [_case(name, n, elements_around=n,
                            elements_along=max(1, int(round(ratio * n))),
                            elements_through=ms.elements_through, cell_type=cell, degree=degree,
                            grading=ms.grading)
                      for n in SOLID_AROUND_LEVELS if n <= top]
        cases += [_case("solid_hex_p2_around", n, elements_around=n,
                        elements_along=ms.elements_along, elements_through=ms.elements_through,
                        cell_type="hexahedron", degree=2, grading=ms.grading)
                  for n in SOLID_SWEEP_AROUND if n <= cv.solid_p2_max_around]
    return cases


def estimated_dofs(case: Case) -> int:
    """DOFs of a case before it runs (for the progress bar's cost estimate)."""
    s, model = case.settings, FAMILIES[case.family].model
    if model == "closed_form":
        return 1
    if model == "beam":
        return 2 * s["elements"]
    na, nz = s["elements_around"], s["elements_along"]
    k = s["degree"]
    if model == "shell":
        return 5 * (k * na) * (k * nz + 1)
    nt = s["elements_through"]
    return 3 * (k * na) * (k * nz + 1) * (k * nt + 1)


def estimated_seconds(case: Case) -> float:
    """A rough cost model (s, measured on this project's 2-core machine), for the
    progress bar only: tqdm's ETA then follows the measured rate."""
    model = FAMILIES[case.family].model
    n = estimated_dofs(case)
    if model in ("closed_form", "beam"):
        return 0.001 + 2e-9 * n ** 2
    if model == "shell":
        return 1.3 + 1.0e-4 * n
    if case.settings["degree"] == 1:
        return 1.5 + 7e-5 * n
    return 1.5 + (8e-5 if case.settings["cell_type"] == "tetrahedron" else 1.3e-4) * n


# --------------------------------------------------------------------------
# Running one case, and the cache


def _source_files(model: str) -> list[Path]:
    """The source files a model's results depend on (their hash is in the cache key)."""
    root = Path(__file__).parent
    if model == "closed_form":
        return [root / "reduced" / "pillar.py", root / "reduced" / "cylinder.py"]
    if model == "beam":
        return [root / "reduced" / "beam_fe.py", root / "reduced" / "pillar.py"]
    if model == "shell":
        return [root / "fem3d" / "shell.py", root / "mesh" / "shell.py"]
    # the solid model: every module of fem3d and mesh but the shell's
    files = sorted((root / "fem3d").glob("*.py")) + sorted((root / "mesh").glob("*.py"))
    return [f for f in files if f.name != "shell.py"]


def _source_hash(model: str) -> str:
    h = hashlib.sha256()
    for f in _source_files(model):
        if f.exists():
            h.update(f.name.encode())
            h.update(f.read_bytes())
    return h.hexdigest()[:16]


def case_key(case: Case, pillar) -> str:
    """Hash of everything a run's result depends on."""
    fam = FAMILIES[case.family]
    doc = {"cache_version": CACHE_VERSION, "model": fam.model, "params": case.settings,
           "n_modes": N_MODES if fam.model in ("shell", "solid") else None,
           "pillar": {k: getattr(pillar, k) for k in
                      ("height", "outer_diameter", "inner_diameter", "youngs_modulus",
                       "poisson_ratio", "density")},
           "source": _source_hash(fam.model)}
    text = json.dumps(doc, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def _first(omega, kind, want: str) -> tuple[Optional[float], Optional[int]]:
    for i, (w, k) in enumerate(zip(omega, kind)):
        if (want == "bending" and k.startswith("bending")) or (want == "ovalling" and k == "ovalling"):
            return float(w), i
    return None, None


def solid_mesh(case: Case):
    """The scene ``[mesh]`` section of a 3D case."""
    from .scene import Mesh
    s = case.settings
    return Mesh(elements_around=s["elements_around"], elements_along=s["elements_along"],
                elements_through=s["elements_through"], degree=s["degree"],
                cell_type=s["cell_type"], grading=s["grading"])


def _modal_summary(omega, kind, n_circ) -> dict:
    """The run's quantities from a list of modes."""
    out = {"modes": [{"omega": float(w), "kind": k, "n": None if n is None else int(n)}
                     for w, k, n in zip(omega, kind, n_circ)]}
    for q in QUANTITIES:
        w, i = _first(omega, kind, q)
        out[q] = w
        if q == "ovalling":
            out["ovalling_n"] = None if i is None or n_circ[i] is None else int(n_circ[i])
    return out


def compute_in_process(case: Case, pillar) -> dict:
    """The closed forms and the 1D beam models (numpy only)."""
    sec = section_of(pillar)
    fam = FAMILIES[case.family]
    if fam.model == "closed_form":
        t = (pillar.outer_diameter - pillar.inner_diameter) / 2
        R = (pillar.outer_diameter + pillar.inner_diameter) / 4
        return {"bending": omega_euler_bernoulli(pillar.youngs_modulus, sec.second_moment,
                                                 sec.mass_per_length, pillar.height),
                "ovalling": ring_frequency(2, pillar.youngs_modulus, pillar.poisson_ratio,
                                           pillar.density, R, t),
                "ovalling_n": 2, "dofs": 1, "modes": []}
    s = case.settings
    kappa = cowper_shear_coefficient(pillar.outer_diameter, pillar.inner_diameter,
                                     pillar.poisson_ratio)
    props = BeamProperties(pillar.youngs_modulus, pillar.poisson_ratio, kappa, pillar.density,
                           sec.area, sec.second_moment, pillar.height)
    m = beam_modes(props, s["elements"], s["theory"], n_modes=1)
    return {"bending": float(m.omega[0]), "ovalling": None, "ovalling_n": None,
            "dofs": int(m.dofs), "modes": [{"omega": float(m.omega[0]), "kind": "bending_x", "n": 1}]}


def _run_in_process(case: Case, pillar) -> dict:
    # time without tracemalloc (it slows Python code), then measure memory
    t0 = time.perf_counter()
    out = compute_in_process(case, pillar)
    wall = time.perf_counter() - t0
    tracemalloc.start()
    try:
        compute_in_process(case, pillar)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    out.update(wall_time=wall, peak_memory=peak, memory_method="tracemalloc (Python heap peak)",
               timings={"total": wall})
    return out


def compute_fe(case: Case, scene, fresh: bool = False) -> dict:
    """A shell or solid run, in this process (the subprocess worker calls this).

    ``fresh``: bypass the 3D model's in-process result cache (a second, timed call).
    """
    fam = FAMILIES[case.family]
    pillar = scene.pillar
    s = case.settings
    if fam.model == "shell":
        from .fem3d.shell import ShellDiscretisation, shell_modal_analysis, shell_section_of
        sec, R, H = shell_section_of(pillar)
        disc = ShellDiscretisation(s["elements_around"], s["elements_along"], s["cell_type"],
                                   s["degree"])
        r = shell_modal_analysis(sec, R, H, disc, n_modes=N_MODES)
    else:
        import inspect
        from . import fem3d
        extra = ({"use_cache": False} if fresh and "use_cache" in
                 inspect.signature(fem3d.modal_analysis).parameters else {})
        r = fem3d.modal_analysis(scene, top=False, n_modes=N_MODES, mesh=solid_mesh(case), **extra)
    out = _modal_summary(np.asarray(r.omega), list(r.kind), list(r.n_circumferential))
    out.update(dofs=int(r.dofs), cells=int(r.cells), timings=dict(r.timings))
    return out


def _jit_files() -> int:
    """How many files FFCx's disk cache holds (it grows when a form is compiled)."""
    from .fem3d.dolfinx_import import import_dolfinx
    import_dolfinx()
    from dolfinx.jit import get_parameters
    root = Path(get_parameters()["cache_dir"])
    return sum(1 for _ in root.rglob("*")) if root.exists() else 0


class ModelUnavailable(RuntimeError):
    """The model cannot run here (e.g. the 3D model is not installed)."""


UNAVAILABLE_EXIT = 3
"""Exit code of a worker whose model cannot be imported."""



def worker(case_file: str, out_file: str) -> None:
    """Subprocess entry: run one FE case, write its result JSON to ``out_file``."""
    from .scene import scene_from_dict
    doc = json.loads(Path(case_file).read_text())
    case = Case(doc["family"], doc["level"], tuple((k, v) for k, v in doc["params"]))
    scene_doc = dict(doc["scene"])
    scene = scene_from_dict(scene_doc, name=scene_doc.pop("name"))
    # import what the models import lazily, so that every run is timed in the
    # same state (imports excluded); their memory is the baseline a run adds to
    import importlib
    for name in ("gmsh", "ufl", "basix", "dolfinx", "dolfinx.fem.petsc", "dolfinx.io.gmshio",
                 "petsc4py.PETSc", "slepc4py.SLEPc", "mpi4py.MPI"):
        importlib.import_module(name)
    baseline = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    if FAMILIES[case.family].model == "solid":
        try:
            from .fem3d import modal_analysis  # noqa: F401
        except ImportError as exc:
            print(f"3D model unavailable: {exc}", file=sys.stderr)
            sys.exit(UNAVAILABLE_EXIT)
        importlib.import_module("rotorpillar.mesh")
    else:
        importlib.import_module("rotorpillar.mesh.shell")
    importlib.import_module("rotorpillar.fem3d.shell")
    jit_before = _jit_files()
    t0 = time.perf_counter()
    out = compute_fe(case, scene)
    total = time.perf_counter() - t0
    compiled = _jit_files() > jit_before
    if compiled:
        # FFCx compiled forms in this run (once per machine and form): time it
        # again warm, as every later run of the family will be
        first = total
        t0 = time.perf_counter()
        out = compute_fe(case, scene, fresh=True)
        total = time.perf_counter() - t0
        out["first_run_with_compilation"] = first
    # the model's whole time: mesh, forms, assembly, solve and naming the modes
    out.update(wall_time=total, peak_memory=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
               baseline_memory=baseline,
               memory_method="ru_maxrss of a fresh subprocess (includes ~baseline_memory of imports)")
    write_json(out_file, out)


def _run_in_subprocess(case: Case, scene) -> dict:
    with tempfile.TemporaryDirectory(prefix="rotorpillar-converge-") as tmp:
        case_file, out_file = Path(tmp) / "case.json", Path(tmp) / "result.json"
        case_file.write_text(json.dumps({"family": case.family, "level": case.level,
                                         "params": list(case.params),
                                         "scene": scene.to_dict()}))
        env = dict(os.environ)
        # serial and single-threaded: the runs are timed against each other
        env.setdefault("OMP_NUM_THREADS", "1")
        env.setdefault("OPENBLAS_NUM_THREADS", "1")
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "rotorpillar.converge", str(case_file),
                               str(out_file)], capture_output=True, text=True, env=env)
        elapsed = time.perf_counter() - t0
        if proc.returncode == UNAVAILABLE_EXIT:
            raise ModelUnavailable((proc.stderr or "").strip().splitlines()[-1])
        if proc.returncode != 0 or not out_file.exists():
            tail = (proc.stderr or "").strip().splitlines()[-3:]
            raise RuntimeError(f"{case.label}: worker failed ({proc.returncode}): "
                               + " | ".join(tail))
        out = json.loads(out_file.read_text())
    out["process_time"] = elapsed
    return out


def run_case(case: Case, scene) -> dict:
    """Compute one case (in-process or in a subprocess, by model)."""
    if FAMILIES[case.family].model in ("closed_form", "beam"):
        return _run_in_process(case, scene.pillar)
    return _run_in_subprocess(case, scene)


def _record(case: Case, key: str, result: dict) -> dict:
    fam = FAMILIES[case.family]
    return {"key": key, "family": case.family, "model": fam.model, "label": case.label,
            "level": case.level, "params": case.settings, "status": "ok", **result}


def run_study(cases: list[Case], scene, cache_dir: Path, *,
              runner: Callable[[Case, object], dict] = run_case,
              progress: bool = True, log: Callable[[str], None] | None = None) -> list[dict]:
    """Every case, each loaded from ``cache_dir`` or computed and cached.

    A run is written to ``cache_dir/<key>.json`` atomically as soon as it
    finishes, so an interruption (KeyboardInterrupt included) loses at most
    the run under way and leaves no partial file.  A run that fails is
    recorded as failed and not cached (it is tried again next time).
    """
    from tqdm import tqdm

    cache_dir = Path(cache_dir)
    keys = [case_key(c, scene.pillar) for c in cases]
    records: list[Optional[dict]] = [None] * len(cases)
    todo = []
    for i, (c, key) in enumerate(zip(cases, keys)):
        cached = _load_cached(cache_dir / f"{key}.json", key)
        if cached is not None:
            # names follow the code, not the cache (they are not part of the key)
            records[i] = {**cached, "label": c.label, "family": c.family,
                          "model": FAMILIES[c.family].model, "cached": True}
        else:
            todo.append(i)
    if log:
        log(f"converge: {len(cases)} runs, {len(cases) - len(todo)} cached, {len(todo)} to compute")
    weights = [estimated_seconds(cases[i]) for i in todo]
    bar = tqdm(total=sum(weights), disable=not progress or not todo, unit="s~", file=sys.stderr,
               bar_format="{l_bar}{bar}| {n:.0f}/{total:.0f} est. s [{elapsed}<{remaining}] {postfix}")
    unavailable = {}
    try:
        for i, w in zip(todo, weights):
            case, key = cases[i], keys[i]
            model = FAMILIES[case.family].model
            bar.set_postfix_str(case.label)
            if model in unavailable:
                records[i] = {**_record(case, key, {}), "status": "unavailable",
                              "error": unavailable[model], "cached": False}
                bar.update(w)
                continue
            try:
                result = runner(case, scene)
            except ModelUnavailable as exc:
                unavailable[model] = str(exc)
                if log:
                    log(f"converge: skipping the {model} runs: {exc}")
                records[i] = {**_record(case, key, {}), "status": "unavailable",
                              "error": str(exc), "cached": False}
            except (RuntimeError, ValueError, ArithmeticError) as exc:
                records[i] = {**_record(case, key, {}), "status": "failed", "error": str(exc),
                              "cached": False}
            else:
                rec = _record(case, key, result)
                write_json(cache_dir / f"{key}.json", rec)
                records[i] = {**rec, "cached": False}
            bar.update(w)
    finally:
        bar.close()
    return records


def _load_cached(path: Path, key: str) -> Optional[dict]:
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return doc if doc.get("key") == key and doc.get("status") == "ok" else None


# --------------------------------------------------------------------------
# Richardson extrapolation


def richardson(h, f, order_theory: Optional[float] = None) -> dict:
    """Observed order and extrapolated value from three runs at sizes h1 > h2 > h3.

    Solves (f1 - f2)/(f2 - f3) = (h1**p - h2**p)/(h2**p - h3**p) for p (any
    refinement ratios), then f_inf = f3 + (f3 - f2)/((h2/h3)**p - 1).  If the
    differences change sign (no monotone convergence) or p falls outside
    (0.3, 12), the theoretical order is used and ``monotone`` is False.
    The error estimate of f_inf is Roache's GCI: 1.25 |f_inf - f3|.
    """
    h = np.asarray(h, dtype=float)
    f = np.asarray(f, dtype=float)
    if len(h) != 3 or not (h[0] > h[1] > h[2] > 0):
        raise ValueError("richardson needs three runs with h1 > h2 > h3 > 0")
    d1, d2 = f[0] - f[1], f[1] - f[2]
    p, monotone = None, False
    if d2 == 0.0:
        p, monotone = order_theory, d1 == 0.0
    elif d1 / d2 > 0:
        ratio = d1 / d2
        g = lambda q: (h[0] ** q - h[1] ** q) / (h[1] ** q - h[2] ** q) - ratio
        lo, hi = 0.3, 12.0
        if g(lo) * g(hi) < 0:
            p, monotone = brentq(g, lo, hi, xtol=1e-12), True
    p_used = p if p is not None else order_theory
    if p_used is None:
        value = float(f[2])
    else:
        value = float(f[2] + (f[2] - f[1]) / ((h[1] / h[2]) ** p_used - 1))
    return {"order": p, "order_theory": order_theory, "monotone": monotone, "value": value,
            "error_estimate": GCI_SAFETY * abs(value - f[2]), "h": h.tolist(), "f": f.tolist()}


def family_series(records: list[dict], family: str, quantity: str) -> list[dict]:
    """A family's successful runs that have the quantity, coarse to fine."""
    rows = [r for r in records if r["family"] == family and r.get("status") == "ok"
            and r.get(quantity) is not None]
    return sorted(rows, key=lambda r: r["level"])


def family_extrapolations(records: list[dict]) -> dict:
    """Per refined family and quantity: Richardson on its three finest runs."""
    out = {}
    for name, fam in FAMILIES.items():
        if fam.order is None:
            continue
        for q in fam.quantities:
            rows = family_series(records, name, q)
            if len(rows) < 3:
                continue
            last = rows[-3:]
            r = richardson([1.0 / x["level"] for x in last], [x[q] for x in last], fam.order)
            r["runs"] = [x["label"] for x in last]
            out.setdefault(name, {})[q] = r
    return out


def reference_values(records: list[dict], extrapolations: dict) -> dict:
    """Per quantity, the Richardson value of the highest-fidelity family that has one.

    ``check``: the same extrapolation from the three runs before the finest,
    and whether the finest (an independent, finer run) lies within its
    error estimate.
    """
    out = {}
    ranked = sorted(FAMILIES.values(), key=lambda f: -f.fidelity)
    for q in QUANTITIES:
        for fam in ranked:
            if fam.fidelity <= 0 or q not in extrapolations.get(fam.name, {}):
                continue
            ref = dict(extrapolations[fam.name][q])
            ref["family"] = fam.name
            rows = family_series(records, fam.name, q)
            if len(rows) >= 4:
                prev = rows[-4:-1]
                chk = richardson([1.0 / x["level"] for x in prev], [x[q] for x in prev], fam.order)
                finest = rows[-1][q]
                chk.update(finer_run=rows[-1]["label"], finer_value=finest,
                           difference=finest - chk["value"],
                           within_estimate=abs(finest - chk["value"]) <= chk["error_estimate"])
                ref["check"] = chk
            out[q] = ref
            break
    return out


def attach_errors(records: list[dict], reference: dict, extrapolations: dict) -> None:
    """Each run's errors per quantity against the reference (in place).

    ``{q}_error``: measured, (f - f_ref)/f_ref.  Split through the family's
    own Richardson limit L: ``{q}_model_error`` = (L - f_ref)/f_ref (what
    no refinement removes) and ``{q}_discretisation_error`` = (f - L)/f_ref.
    ``{q}_error_bound`` = |model| + |discretisation|: no credit for the two
    cancelling on one mesh by luck.  A side sweep splits through its parent
    family's limit (same model).  Without a limit (a closed form, a family
    with fewer than three runs) the bound is |measured|.
    """
    for r in records:
        fam = FAMILIES[r["family"]]
        for q in QUANTITIES:
            v, ref = r.get(q), reference.get(q)
            keys = ("error", "model_error", "discretisation_error", "error_bound")
            if v is None or ref is None or r.get("status") != "ok":
                r.update({f"{q}_{k}": None for k in keys})
                continue
            f_ref = ref["value"]
            err = (v - f_ref) / f_ref
            limit = extrapolations.get(fam.parent or r["family"], {}).get(q, {}).get("value")
            if limit is None:
                model, disc = err, 0.0
            else:
                model, disc = (limit - f_ref) / f_ref, (v - limit) / f_ref
            r.update({f"{q}_error": err, f"{q}_model_error": model,
                      f"{q}_discretisation_error": disc, f"{q}_error_bound": abs(model) + abs(disc)})


# --------------------------------------------------------------------------
# Pareto fronts and the choice of a model


def pareto_front(cost, error) -> list[int]:
    """Indices of the points no other point beats in both cost and |error|, by cost."""
    pts = [(c, abs(e), i) for i, (c, e) in enumerate(zip(cost, error))
           if c is not None and e is not None and math.isfinite(e)]
    pts.sort(key=lambda t: (t[0], t[1]))
    front, best = [], math.inf
    for c, e, i in pts:
        if e < best:
            front.append(i)
            best = e
    return front


def excitation_band(scene) -> dict:
    """The frequencies the scene excites, and the band a model must resolve.

    The rotor runs at most at the drive's free speed (Md = Mc, no resonance
    drag: every stationary speed lies below it); the ground motion reaches
    ``converge.earthquake_frequency``.  The band is the larger times
    ``converge.margin``.
    """
    from .reduced.averaging import Characteristic
    ch = Characteristic(scene.drive.torque_at_zero, scene.drive.slope, scene.load.coefficient)
    free = ch.free_speed()
    cv = scene.converge
    top = max(free, cv.earthquake_frequency)
    return {"free_speed": free, "earthquake_frequency": cv.earthquake_frequency,
            "margin": cv.margin, "omega_max": cv.margin * top,
            "driver": "drive free speed" if free >= cv.earthquake_frequency else "earthquake"}


def reference_uncertainty(reference: dict) -> dict:
    """Per quantity, the reference's own relative error estimate."""
    return {q: r["error_estimate"] / abs(r["value"]) for q, r in reference.items()}


def needed_quantities(reference: dict, band: dict) -> list[str]:
    """The quantities whose reference frequency lies inside the band."""
    return [q for q in QUANTITIES if q in reference and reference[q]["value"] <= band["omega_max"]]


def band_error(record: dict, needed: list[str], ref_unc: dict) -> Optional[float]:
    """What the choice compares with the tolerance: the largest, over the needed
    quantities, of the error bound plus the reference's uncertainty (None: a
    needed mode is missing)."""
    errs = [record.get(f"{q}_error_bound") for q in needed]
    if any(e is None for e in errs):
        return None
    return max((e + ref_unc.get(q, 0.0) for q, e in zip(needed, errs)), default=0.0)


def select_model(records: list[dict], reference: dict, band: dict, tolerance: float,
                 families: Optional[list[str]] = None) -> dict:
    """The cheapest run (wall time) whose needed frequencies all meet ``tolerance``.

    Needed: the quantities whose reference lies inside the band.  A run meets
    the tolerance if, for each, its error bound (model + discretisation, see
    attach_errors) plus the reference's own uncertainty is within it; the
    cheapest such run is on the Pareto front of that band error against wall
    time.  ``families`` restricts the candidates (e.g. to the models a command
    can run).
    """
    needed = needed_quantities(reference, band)
    ref_unc = reference_uncertainty(reference)
    ok_runs = [r for r in records if r.get("status") == "ok"
               and (families is None or r["family"] in families)]
    meets, rejected = [], []
    for r in ok_runs:
        missing = [q for q in needed if r.get(q) is None]
        if missing:
            rejected.append((r, math.inf, "no " + " and no ".join(missing) + " mode"))
            continue
        worst = band_error(r, needed, ref_unc)
        if worst <= tolerance:
            meets.append(r)
        else:
            q = max(needed, key=lambda q: r[f"{q}_error_bound"] + ref_unc[q])
            why = (f"{q} error bound {r[f'{q}_error_bound'] + ref_unc[q]:.1e} > {tolerance:g}: "
                   f"model {r[f'{q}_model_error']:+.1e}, discretisation "
                   f"{r[f'{q}_discretisation_error']:+.1e}, reference {ref_unc[q]:.0e}")
            rejected.append((r, worst, why))
    out = {"tolerance": tolerance, "band": band, "needed": needed,
           "reference_uncertainty": {q: ref_unc[q] for q in needed},
           "families": families, "candidates": len(meets),
           "rule": "cheapest wall time among runs whose error bound (|model error| + "
                   "|discretisation error| + reference uncertainty) meets the tolerance on "
                   "every frequency inside the band"}
    if not meets:
        out.update(chosen=None, rejected_cheaper=[], reason=(
            f"no model in the study meets {tolerance:g} on {', '.join(needed) or 'nothing'} "
            "(error bounds: " + "; ".join(
                f"{FAMILIES[f].label} best {min(w for r, w, _ in rejected if r['family'] == f):.1e}"
                for f in dict.fromkeys(r["family"] for r, _, _ in rejected)) +
            "); refine the ladder ([converge] limits) or loosen the tolerance"))
        return out
    best = min(meets, key=lambda r: (r["wall_time"], r["dofs"]))
    # per family, its most accurate run among those cheaper than the choice
    by_family = {}
    for r, worst, why in sorted(rejected, key=lambda t: t[1]):
        if r["wall_time"] < best["wall_time"]:
            by_family.setdefault(r["family"], (r, why))
    out.update(
        chosen=_brief(best, needed),
        rejected_cheaper=[{**_brief(r, needed), "why": why} for r, why in by_family.values()],
        reason=_reason(best, needed, band, tolerance, reference, by_family))
    return out


def _brief(r: dict, needed) -> dict:
    return {"label": r["label"], "family": r["family"], "model": r["model"], "params": r["params"],
            "dofs": r["dofs"], "wall_time": r["wall_time"], "peak_memory": r.get("peak_memory"),
            **{q: r.get(q) for q in QUANTITIES},
            **{f"{q}_{k}": r.get(f"{q}_{k}") for q in QUANTITIES
               for k in ("error", "model_error", "discretisation_error", "error_bound")}}


def _reason(best, needed, band, tol, reference, rejected) -> str:
    parts = [f"{best['label']} ({best['dofs']:,} DOFs, {best['wall_time']:.2f} s) is the cheapest "
             f"run whose "]
    parts.append(" and ".join(f"first {q} ({best[q]:.3f} rad/s, error {best[q + '_error']:+.1e}, "
                              f"bound {best[q + '_error_bound']:.1e})" for q in needed))
    parts.append(f" meet {tol:g} against the reference. The band to resolve reaches "
                 f"{band['omega_max']:.1f} rad/s ({band['margin']:g} x the {band['driver']}, "
                 f"{max(band['free_speed'], band['earthquake_frequency']):.1f} rad/s)")
    inside = [f"first {q} {reference[q]['value']:.2f}" for q in needed]
    outside = [f"first {q} {reference[q]['value']:.2f}" for q in QUANTITIES
               if q in reference and q not in needed]
    if inside:
        parts.append(", which contains the " + " and the ".join(inside) + " rad/s")
    if outside:
        parts.append("; " + ", ".join(outside) + " rad/s lie(s) above it")
    parts.append(".")
    if rejected:
        parts.append(" Cheaper runs fail: " + "; ".join(
            (f"{FAMILIES[f].label} ({why})" if r["label"] == FAMILIES[f].label else
             f"{FAMILIES[f].label} (best {r['label'].split(', ')[-1]}: {why})")
            for f, (r, why) in rejected.items()) + ".")
    return "".join(parts)


# --------------------------------------------------------------------------
# The whole study


def _why(name: str, fam: Family, q: str, rows: list[dict], extrapolations: dict,
         reference: dict) -> str:
    """The likely cause of a family's error floor on quantity q, from its data."""
    if fam.model in ("beam", "closed_form"):
        limit = extrapolations.get(name, {}).get(q, {}).get("value", rows[-1].get(q))
        gap = (limit - reference[q]["value"]) / reference[q]["value"]
        return (f"model error: its own limit {limit:.4f} rad/s is {gap:+.1e} from the reference"
                if limit is not None else "model error")
    if fam.sweep and q == "bending":
        along = rows[-1]["params"]["elements_along"]
        return (f"the bending mode is set by the cells along, fixed at {along} here: more "
                "cells around do not help it")
    if fam.sweep:
        coarse = min(rows, key=lambda r: r["level"])
        e = coarse.get(f"{q}_error")
        return (f"too few elements around: {coarse['params']['elements_around']} around gives "
                + ("no such mode" if e is None else f"{e:+.1e}")
                + f" with {coarse['params']['elements_along']} along")
    ex = extrapolations.get(name, {}).get(q)
    slow = ex is not None and ex["order"] is not None and ex["order"] < 0.6 * ex["order_theory"]
    if fam.model == "solid" and case_degree(rows[-1]) == 1:
        return "locking: linear elements across a thin wall are far too stiff in bending"
    if slow:
        return (f"locking: the error falls at order {ex['order']:.1f}, not {ex['order_theory']:g}, "
                "as the wall's bending is over-stiffened")
    if ex is not None and ex["value"] is not None and q in reference:
        gap = (ex["value"] - reference[q]["value"]) / reference[q]["value"]
        if abs(gap) > 0.5 * (ex["error_estimate"] + reference[q]["error_estimate"]) / \
                abs(reference[q]["value"]) and abs(gap) > 1e-4:
            return f"its limit differs from the reference by {gap:+.1e} (model error)"
    return "the meshes of the ladder are too coarse for it"


def nyquist(record: dict) -> int:
    """The highest circumferential wave number a mesh's nodes around can carry."""
    p = record.get("params", {})
    return int(p.get("elements_around", 10**6) * p.get("degree", 1) // 2)


def case_degree(record: dict) -> int:
    return int(record.get("params", {}).get("degree", 0))


def failures(records: list[dict], extrapolations: dict, reference: dict, tolerance: float) -> list[str]:
    """Where each method fails, in words, from the data."""
    out = []
    no_shell = [FAMILIES[f].label for f in ("beam_euler", "beam_timoshenko")
                if any(r["family"] == f for r in records)]
    if no_shell:
        out.append("no shell modes: " + " and ".join(no_shell) + " have no ovalling mode at all "
                   "(the ring closed form estimates it, for a long tube only)")
    for name, fam in FAMILIES.items():
        rows = sorted((r for r in records if r["family"] == name and r.get("status") == "ok"),
                      key=lambda r: r["level"])
        if not rows:
            continue
        for q in fam.quantities:
            if q not in reference:
                continue
            errs = [(r, r.get(f"{q}_error")) for r in rows]
            found = [abs(e) for _, e in errs if e is not None]
            missing = [r for r, e in errs if e is None]
            aliased = [r for r in rows if q == "ovalling" and r.get("ovalling_alias")]
            if aliased:
                out.append(f"{fam.label}: too few nodes around on "
                           + ", ".join(f"{r['label'].split(', ')[-1]} ({nyquist(r) * 2} nodes: "
                                       f"its 'ovalling' n = {r['ovalling_alias']['n']} is an alias "
                                       "of the bending pair)" for r in aliased)
                           + ": no ovalling mode resolved")
                missing = [r for r in missing if not r.get("ovalling_alias")]
            if missing:
                out.append(f"{fam.label}: no {q} mode among the lowest {N_MODES} on "
                           + ", ".join(r["label"].split(", ")[-1] for r in missing)
                           + " (too coarse or locked: the mode is pushed above the others)")
            if found and min(found) > tolerance:
                best = min((r for r, e in errs if e is not None), key=lambda r: abs(r[f"{q}_error"]))
                out.append(f"{fam.label}: {q} error never below {tolerance:g} (best "
                           f"{best['label'].split(', ')[-1]}: {best[f'{q}_error']:+.1e}) - "
                           + _why(name, fam, q, rows, extrapolations, reference))
    for r in records:
        if r.get("status") == "failed":
            out.append(f"{r['label']}: run failed: {r['error']}")
    for model in sorted({r["model"] for r in records if r.get("status") == "unavailable"}):
        err = next(r["error"] for r in records
                   if r.get("status") == "unavailable" and r["model"] == model)
        out.append(f"the {model} model did not run here ({err}): the reference falls back "
                   "to the best family that ran")
    for name, qs in extrapolations.items():
        for q, ex in qs.items():
            if ex["order"] is None:
                out.append(f"{FAMILIES[name].label}: {q} does not converge monotonically over "
                           "its three finest runs (no observed order)")
            elif ex["order_theory"] and abs(ex["order"] - ex["order_theory"]) > 0.25 * ex["order_theory"]:
                out.append(f"{FAMILIES[name].label}: observed order {ex['order']:.2f} on {q}, "
                           f"theory {ex['order_theory']:g}: not in the asymptotic range"
                           + (f" ({ORDER_NOTES[name, q]})" if (name, q) in ORDER_NOTES else ""))
    return out


def drop_aliases(records: list[dict]) -> None:
    """An "ovalling" mode with more waves than the nodes around can carry is an
    alias (with 8 nodes around, the bending pair reads as n = 7): no ovalling
    mode was resolved (in place; the alias stays as ``ovalling_alias``)."""
    for r in records:
        n = r.get("ovalling_n")
        if r.get("status") == "ok" and n is not None and n > nyquist(r):
            r.update(ovalling_alias={"omega": r["ovalling"], "n": n}, ovalling=None,
                     ovalling_n=None)


def analyse(records: list[dict], scene, tolerance: float) -> dict:
    """Reference values, errors, fronts, failures and the chosen model."""
    drop_aliases(records)
    extrap = family_extrapolations(records)
    reference = reference_values(records, extrap)
    attach_errors(records, reference, extrap)
    band = excitation_band(scene)
    selection = select_model(records, reference, band, tolerance)
    needed, ref_unc = selection["needed"], reference_uncertainty(reference)
    ok = [r for r in records if r.get("status") == "ok"]
    candidates = ok
    fronts = {}
    for cost in ("dofs", "wall_time"):
        fronts[cost] = {}
        for q in QUANTITIES:
            errs = [r.get(f"{q}_error") for r in ok]
            fronts[cost][q] = [ok[i]["label"] for i in pareto_front([r[cost] for r in ok], errs)]
        errs = [band_error(r, needed, ref_unc) for r in candidates]
        fronts[cost]["band"] = [candidates[i]["label"]
                                for i in pareto_front([r[cost] for r in candidates], errs)]
    return {"reference": reference, "extrapolations": extrap, "band": band,
            "selection": selection, "pareto": fronts,
            "failures": failures(records, extrap, reference, tolerance)}


def study_cases(scene) -> list[Case]:
    return ladder(scene)


def _main(argv: list[str]) -> int:
    if len(argv) != 2:
        print("usage: python -m rotorpillar.converge CASE.json RESULT.json", file=sys.stderr)
        return 2
    worker(argv[0], argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(_main(sys.argv[1:]))
