"""The passage through resonance as the run-ups ran it: for each run and
each resonance it crossed, when, how fast (Omega-dot and Omega-dot /
omega**2, how far from quasi-static), and the transient's peak beside the
averaging's stationary amplitude a_max.

Read from each run's JSON (``passages``: the crossing time and the peak
near it; ``prediction.resonances``: a_max and nu of the same model) and its
arrays (Omega-dot from the stored speed).  The averaging's a_max is a
steady state: it is reached only if the speed crosses the resonance's
half-power band (2 nu omega wide) in many of its decay times (1 / (nu
omega)), i.e. if crossing / decay = 2 nu**2 omega**2 / Omega-dot >> 1.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from .. import html as h
from ..directions import short
from .state import Build

if TYPE_CHECKING:
    from ...reduced.stationary import AveragingPrediction
    from ...transients.case_summary import Passage
    from ...transients.model_run import RunRecord
    from ..run_arrays import RunArrays


def _acceleration(arrays: RunArrays, at: float) -> float | None:
    """dOmega/dt at time ``at`` from a run's stored speed (rad/s**2)."""
    t, W = arrays.t, arrays.Omega
    if t is None or W is None or len(t) < 3:
        return None
    return float(np.interp(at, t, np.gradient(W, t)))


def passage_rows(
    model: str, passages: Sequence[Passage], prediction: AveragingPrediction, arrays: RunArrays
) -> list[list]:
    """One row per resonance the run crossed (``prediction``: the run's averaging
    prediction, its ``resonances`` carrying nu and a_max)."""
    pred = {r.index: r for r in prediction.resonances}
    rows = []
    for p in passages:
        if not p.crossed or p.time is None:
            continue
        w, tc = float(p.omega), float(p.time)
        acc = _acceleration(arrays, tc)
        r = pred.get(p.index)
        nu, a_max = (None, None) if r is None else (r.nu, r.a_max)
        vertical = str(p.direction).upper() == "Y"
        peak = p.peak_rotor_y_near if vertical else p.peak_tip_near
        ratio = acc / w**2 if acc else None
        crossing = (2 * nu**2 * w**2 / acc) if (acc and nu) else None
        rows.append(
            [
                model,
                f"{p.index}: {short(p.direction)}",
                h.num(w, 4),
                h.num(tc, 3),
                h.num(acc, 3),
                h.num(ratio, 2),
                h.num(2 * nu**2, 2) if nu else "-",
                h.num(crossing, 2),
                ("rotor " if vertical else "tip ") + h.num(1e3 * peak, 3) if peak else "-",
                h.num(1e3 * a_max, 3) if a_max else "-",
                h.num(peak / a_max, 2) if (peak and a_max) else "-",
            ]
        )
    return rows


HEADERS = [
    "model",
    "resonance",
    "omega_i, undamped (rad/s)",
    "crossed at t (s)",
    "Omega-dot (rad/s^2)",
    "Omega-dot / omega^2 (-)",
    "2 nu^2 (quasi-static needs Omega-dot / omega^2 far below it)",
    "crossing / decay time (-)",
    "transient peak near it (mm)",
    "a_max, averaging (mm)",
    "peak / a_max (-)",
]


def passage_block(build: Build) -> list[str]:
    """The table over every run-up the page has (the comparison's models, the
    scene's own run), and what it says."""
    from ...transients.model_run import ReducedRun

    runs: list[tuple[str, RunRecord | None, RunArrays]] = []
    c = build.comparisons.get("runup")
    if c is not None:
        runs += [(m, c.runs.get(m), c.arrays_of(m)) for m in c.models]
    sim = build.simulations.get("runup")
    if sim is not None and sim.run is not None:
        runs.append((f"{sim.run.model} (the scene's run)", sim.run, sim.arrays))
    rows = [
        row
        for m, run, arrays in runs
        if isinstance(run, ReducedRun)  # the 3D run records no passages
        for row in passage_rows(m, run.passages, run.prediction, arrays)
    ]
    if not rows:
        return []
    slow = [r for r in rows if r[7] != "-" and float(r[7]) > 10]
    text = (
        "The run-ups cross the resonances in a fraction of a second. The averaging's a_max "
        "is a steady state, reached only when the speed crosses a resonance's half-power "
        "band (2 nu omega wide) in many of its decay times (1 / (nu omega)): crossing / "
        "decay time = 2 nu^2 omega^2 / Omega-dot much above 1. "
        + (
            "Here it is of order 1 or below at every crossing: the passage is far from "
            "quasi-static, and the transient peaks differ from the averaging's a_max (last "
            "column); the averaging's jumps and stationary amplitudes describe the slow "
            "(quasi-static) limit, not this run-up."
            if not slow
            else f"{len(slow)} of the {len(rows)} crossings are slow enough to approach the steady state."
        )
    )
    return [h.tag("p", text), h.table(HEADERS, rows)]
