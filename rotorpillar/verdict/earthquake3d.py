"""summary.json's checks of the earthquake in two or three components (issues 26.6, 29.4).

Read from ``compare_earthquake_components.json`` (the run's stage `compare
--case earthquake --components 3`, rotorpillar.transients.components.
ComponentsComparison): the spatial ROM over the whole record and the 3D full
order over its window, each with the base stress from the resultant moment
and the axial force at each instant,

    sigma(t) = sqrt(M_x(t)**2 + M_y(t)**2) c / I + N(t) / A,

c the base section's outer radius, I its second moment, A its area, N
compression positive (the file's ``peaks`` "stress": the largest |sigma|).
The checks, beside the one-component ones (the model comparison):

- base stress vs yield: sigma against f_yk / gamma_M0;
- base stress vs shell buckling: sigma against sigma_x,Rd of EN 1993-1-6
  (``headline.base_buckling``), its C_x at the axial share
  s_N / (s_N + s_M) = min(1, max|N| / A / max|sigma|).  The file keeps the
  peaks, not N at the instant of the largest stress: max|N| bounds N there
  from above, so the share is an upper bound, and a larger share lowers a long
  cylinder's C_x (C_x = C_x,N s + (1 - s), C_x,N <= 1): the capacity is never
  overstated by it.

Each for the spatial ROM over the whole record (``peaks[stress].modal``) and
the 3D full order over its window (``peaks[stress].fem3d``), the window said
in the case's words.  The headlines: the resultant base moment and the top's
largest displacement in the rotor's plane and along the spin axis, the ROM's
over the whole record, then the 3D's over its window with the ROM's over the
same window beside it (like against like).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .. import records
from ..reduced.capacity import GAMMA_M0, Check, check
from ..reduced.tower import base_section
from .headline import Headline, base_buckling

if TYPE_CHECKING:
    from ..scene import Scene
    from ..transients.components import ComponentPeak, ComponentsComparison

#: the stage's file (rotorpillar.commands.compare.COMPONENTS_STEM)
COMPONENTS_FILE = "compare_earthquake_components.json"
#: the built-in records as a reader names them
RECORD_NAMES = {"elcentro": "El Centro"}


def resultant_stress(
    moment_x: ArrayLike, moment_y: ArrayLike, axial: ArrayLike, outer_radius: float, second_moment: float, area: float
) -> np.ndarray:
    """The base's extreme-fibre stress at each instant from the resultant moment (Pa):
    sqrt(M_x**2 + M_y**2) c / I + N / A (moments N*m, N in N compression positive, c m,
    I m**4, A m**2)."""
    m = np.hypot(np.asarray(moment_x, dtype=float), np.asarray(moment_y, dtype=float))
    return m * outer_radius / second_moment + np.asarray(axial, dtype=float) / area  # type: ignore[no-any-return]


def summed_maxima_stress(
    moment_x: ArrayLike, moment_y: ArrayLike, axial: ArrayLike, outer_radius: float, second_moment: float, area: float
) -> float:
    """What adding the two moments' maxima would claim (Pa): (max|M_x| + max|M_y|) c / I +
    max N / A; never below the largest :func:`resultant_stress` (the hypotenuse is at most the
    sum of its legs, each at most its maximum)."""
    mx, my = np.abs(np.asarray(moment_x, dtype=float)), np.abs(np.asarray(moment_y, dtype=float))
    return float((mx.max() + my.max()) * outer_radius / second_moment + np.max(axial) / area)


def axial_share_bound(axial_peak: float | None, area: float, stress_peak: float) -> float:
    """An upper bound of s_N / (s_N + s_M) at the largest stress (-): max|N| / A over it, at most
    1 (1 where the axial peak is unknown: uniform compression, the lowest C_x).

    >>> round(axial_share_bound(2.38e5, 0.1244, 19.6e6), 4)
    0.0976
    """
    if axial_peak is None or not stress_peak > 0:
        return 1.0
    return min(1.0, abs(axial_peak) / area / stress_peak)


def case_words(q: ComponentsComparison) -> str:
    """The case as a reader names it: "earthquake (El Centro, 3 components)"."""
    first = q.components[0] if q.components else "a record"
    return f"earthquake ({RECORD_NAMES.get(first, first)}, {len(q.components)} components)"


@dataclass(frozen=True)
class Earthquake3d:
    """What the verdict takes from the components file (not written: its parts are)."""

    checks: tuple[Check, ...]
    headlines: tuple[Headline, ...]
    shares: dict[tuple[str, str], float]
    """(model, case) -> the axial share its buckling check used (-)"""


def read_components(out: Path, damaged: dict[str, str]) -> ComponentsComparison | None:
    """The components file of ``out``, or None (none there; a damaged one named in
    ``damaged``: file -> why)."""
    from ..transients.components import ComponentsComparison

    path = Path(out) / COMPONENTS_FILE
    if not path.is_file():
        return None
    try:
        return records.read(path, ComponentsComparison)
    except (ValueError, OSError) as exc:
        damaged[COMPONENTS_FILE] = str(exc)
        return None


def earthquake3d(scene: Scene, q: ComponentsComparison) -> Earthquake3d:
    """The checks and headlines of the module text from one comparison."""
    peaks = {p.name: p for p in q.peaks}
    case = case_words(q)
    whole = f"{case}, whole record ({q.modal_duration:.3g} s)"
    window = f"{case}, the run's first {q.window:g} s"
    checks: list[Check] = []
    shares: dict[tuple[str, str], float] = {}
    stress, axial = peaks.get("stress"), peaks.get("axial_force")
    if stress is not None:
        left_out = any("vertical component's inertia" in w for w in q.warnings)
        rom_note = "; its axial force leaves out the vertical component's inertia (the file's warnings)" * left_out
        for model, field, demand, n, run_case, what in (
            ("modal", "modal", stress.modal, None if axial is None else axial.modal, whole, "the spatial ROM"),
            ("fem3d", "fem3d", stress.fem3d, None if axial is None else axial.fem3d, window, "the 3D full order"),
        ):
            if demand is None:  # the 3D full order did not run (the file's fem3d_model says so)
                continue
            note = rom_note if model == "modal" else ""
            src = f"{COMPONENTS_FILE}: peaks[stress].{field} ({what}{note})"
            rows, shares[(model, run_case)] = _stress_checks(scene, demand, n, model, run_case, src)
            checks += rows
    return Earthquake3d(tuple(checks), tuple(_headlines(q, case, whole, window, peaks)), shares)


def _stress_checks(
    scene: Scene, demand: float, axial: float | None, model: str, case: str, src: str
) -> tuple[list[Check], float]:
    """Base stress against yield and against shell buckling (EN 1993-1-6) at the share bound;
    and that share (-)."""
    mat = scene.material
    share = axial_share_bound(axial, base_section(scene.pillar).area, demand)
    b = base_buckling(scene, share)
    how = "the resultant moment sqrt(M_x**2 + M_y**2) and the axial force at each instant"
    rows = [
        check(
            "base stress vs yield",
            "base_stress",
            "Pa",
            demand,
            mat.yield_strength / GAMMA_M0,
            model,
            case,
            f"{src}, from {how}; f_yk = material.yield_strength, gamma_M0 = {GAMMA_M0:g}",
        ),
        check(
            "base stress vs shell buckling",
            "base_stress",
            "Pa",
            demand,
            b.design_stress,
            model,
            case,
            f"{src}, from {how}; sigma_x,Rd of EN 1993-1-6 (class {mat.fabrication_class}, C_x {b.cx:.3g} at "
            f"the axial share {share:.3g} = max|N| / A / max|sigma| from peaks[axial_force], an upper bound "
            "of the share at the stress's peak: the larger share gives the smaller C_x)",
        ),
    ]
    return rows, share


#: the headline quantities: (peak name, where, words, the text's scale and format)
_QUANTITIES = (
    ("moment", "peaks", "resultant base moment", 1e-6, "{:.3f} MN m"),
    ("tip_x", "peak_tip", "peak tip displacement in the rotor's plane", 1e3, "{:.2f} mm"),
    ("tip_y", "peak_tip", "peak tip displacement along the spin axis", 1e3, "{:.2f} mm"),
)


def _headlines(q: ComponentsComparison, case: str, whole: str, window: str, peaks) -> list[Headline]:
    tips = {p.name: p for p in q.peak_tip}
    found: dict[str, ComponentPeak] = {**peaks, **tips}
    out = []
    rows = (
        ("modal", "modal", "whole record", whole, "the spatial ROM"),
        ("fem3d", "fem3d", f"the run's first {q.window:g} s", window, "the 3D full order"),
        ("modal", "modal_window", f"the run's first {q.window:g} s", window, "the spatial ROM"),
    )
    for name, where, words, scale, fmt in _QUANTITIES:
        p = found.get(name)
        if p is None:
            continue
        for model, field, span, run_case, what in rows:
            v = getattr(p, field)
            if v is None:
                continue
            out.append(
                Headline(
                    f"earthquake3d_{name}_{model}" + ("_window" if field == "modal_window" else ""),
                    f"{case}: {words}, {span}",
                    float(v),
                    p.unit,
                    model,
                    run_case,
                    f"{COMPONENTS_FILE}: {where}[{name}].{field}",
                    f"{case.capitalize()}, {words} over {span}: {fmt.format(float(v) * scale)} ({what}).",
                )
            )
    return out
