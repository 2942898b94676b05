"""Richardson extrapolation: observed orders, limits and Roache's error estimates.

Per refined family, Richardson on its three finest runs gives the observed
order (beside the theoretical one), the family's limit and an error
estimate by Roache's grid convergence index; the reference values are the
limits of the most complete family, checked against the three runs before.

>>> p = richardson([1/8, 1/16, 1/32], [1.0 + 8.0**-2, 1.0 + 16.0**-2, 1.0 + 32.0**-2])
>>> round(p.order, 6), round(p.value, 9)
(2.0, 1.0)
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from msgspec.structs import asdict
from scipy.optimize import brentq

from .ladder import FAMILIES, QUANTITIES
from .result import ConvergenceRun, Extrapolation, FamilyExtrapolation, ReferenceValue, RichardsonCheck

GCI_SAFETY = 1.25
"""Roache's safety factor of the grid convergence index for three-grid studies."""


def richardson(h, f, order_theory: float | None = None) -> Extrapolation:
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
    return Extrapolation(
        order=p,
        order_theory=order_theory,
        monotone=bool(monotone),
        value=value,
        error_estimate=float(GCI_SAFETY * abs(value - f[2])),
        h=tuple(h.tolist()),
        f=tuple(f.tolist()),
    )


def family_series(runs: Sequence[ConvergenceRun], family: str, quantity: str) -> list[ConvergenceRun]:
    """A family's successful runs that have the quantity, coarse to fine."""
    rows = [r for r in runs if r.family == family and r.status == "ok" and r.frequency(quantity) is not None]
    return sorted(rows, key=lambda r: r.level)


def _richardson_on(rows: Sequence[ConvergenceRun], quantity: str, order_theory: float | None) -> Extrapolation:
    """Richardson on three runs of a family (their sizes 1/level)."""
    return richardson([1.0 / r.level for r in rows], [r.frequency(quantity) for r in rows], order_theory)


def family_extrapolations(runs: Sequence[ConvergenceRun]) -> dict[str, dict[str, FamilyExtrapolation]]:
    """Per refined family and quantity: Richardson on its three finest runs."""
    out: dict[str, dict[str, FamilyExtrapolation]] = {}
    for name, fam in FAMILIES.items():
        if fam.order is None:
            continue
        for q in fam.quantities:
            rows = family_series(runs, name, q)
            if len(rows) < 3:
                continue
            last = rows[-3:]
            ex = _richardson_on(last, q, fam.order)
            out.setdefault(name, {})[q] = FamilyExtrapolation(**asdict(ex), runs=tuple(x.label for x in last))
    return out


def reference_values(
    runs: Sequence[ConvergenceRun], extrapolations: dict[str, dict[str, FamilyExtrapolation]]
) -> dict[str, ReferenceValue]:
    """Per quantity, the Richardson value of the highest-fidelity family that has one.

    ``check``: the same extrapolation from the three runs before the finest,
    and whether the finest (an independent, finer run) lies within its
    error estimate.
    """
    out: dict[str, ReferenceValue] = {}
    ranked = sorted(FAMILIES.values(), key=lambda f: -f.fidelity)
    for q in QUANTITIES:
        for fam in ranked:
            if fam.fidelity <= 0 or q not in extrapolations.get(fam.name, {}):
                continue
            rows = family_series(runs, fam.name, q)
            check = None
            if len(rows) >= 4:
                chk = _richardson_on(rows[-4:-1], q, fam.order)
                finest = rows[-1].frequency(q)
                assert finest is not None  # family_series keeps the runs that have it
                check = RichardsonCheck(
                    **asdict(chk),
                    finer_run=rows[-1].label,
                    finer_value=finest,
                    difference=finest - chk.value,
                    within_estimate=bool(abs(finest - chk.value) <= chk.error_estimate),
                )
            out[q] = ReferenceValue(**asdict(extrapolations[fam.name][q]), family=fam.name, check=check)
            break
    return out
