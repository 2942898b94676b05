"""Error bars on a ROM run's headline numbers: peak tip, peak shaft deflection, speeds.

Three more runs of the same case, each moving one source of error:

- discretisation: the chain's pillar modes with their frequencies moved by the
  convergence study's error bound on the first bending frequency (none when
  the pillar model is unverified: the source is then "unassessed");
- truncation: one more pillar mode (none when the mode source offers no more);
- integration: a hundredth of the integrator's tolerance (adaptive) or half
  its step (fixed step).

Each number's error is the sum of the sources' magnitudes
(``chain.Uncertain``: ``{value, error, sources}`` in the JSON).
"""

from __future__ import annotations

import math
from dataclasses import fields

from ..chain import ChainModes, Uncertain
from ..errors import InputError
from ..records import Record
from ..scene import ADAPTIVE_INTEGRATORS, SCIPY_METHODS, Scene, Simulate, with_values

#: the numbers that get error bars, and their units
HEADLINE = {"peak_tip_relative": "m", "peak_shaft_deflection": "m", "omega_final": "rad/s", "captured_at": "rad/s"}


class HeadlineNumbers(Record):
    """A ROM run's numbers that get error bars (the names and units of ``HEADLINE``)."""

    peak_tip_relative: float
    """largest |tip X| relative to the ground (m)"""
    peak_shaft_deflection: float
    """largest |shaft deflection X| over the sampled series (m)"""
    omega_final: float
    """mean speed over the last 5 % of the run (rad/s)"""
    captured_at: float | None
    """the speed the rotor settled at below a resonance (rad/s), or None"""

    def value(self, name: str) -> float | None:
        """The number called ``name`` (a key of ``HEADLINE``)."""
        value: float | None = getattr(self, name)
        return value


def headline_numbers(res) -> HeadlineNumbers:
    """A ROM CaseResult's headline numbers (the modal model is relative to the ground)."""
    s = res.summary
    return HeadlineNumbers(
        peak_tip_relative=s.max_abs["tip_x"],
        peak_shaft_deflection=s.max_abs["shaft_deflection_x_sampled"],
        omega_final=s.omega_final_mean,
        captured_at=s.captured_at,
    )


def _finer(scene: Scene, integrator: str | None) -> Scene:
    """The scene integrated finer (rtol / 100, or half the step), within the keys' ranges;
    ``scene`` itself when it cannot be (an automatic step, a step at its floor)."""
    sim = scene.simulate
    method = integrator or sim.integrator
    if method in ADAPTIVE_INTEGRATORS + SCIPY_METHODS:
        return with_values(scene, {"simulate.rtol": max(sim.rtol / 100, 1e-13)})
    floor = next(f for f in fields(Simulate) if f.name == "time_step").metadata["ge"]
    if sim.time_step / 2 >= floor:
        return with_values(scene, {"simulate.time_step": sim.time_step / 2})
    return scene  # an automatic step: the integrator study measures it, not this check


def uncertainty(
    scene: Scene, case: str, integrator, motion, chain: ChainModes, base, progress=None
) -> dict[str, Uncertain]:
    """``{name: Uncertain}`` for the headline numbers of ``base`` (a modal CaseResult); a
    mapping by quantity name, not a record: a number without a finite value has no entry."""
    from .cases import run_case

    # the planar ROM's variants: only its runs get them (the spatial ROM's have neither)
    quiet = with_values(scene, {"simulate.threshold": False, "modal_model.planes": "planar"})
    k = base.model.pillar_modes.count
    values = headline_numbers(base)

    def run(sc, modes, pillar_modes):
        try:
            res = run_case(
                sc, case, "modal", integrator, modes, truncation=False, motion=motion, pillar_modes=pillar_modes
            )
        except InputError:  # the variant's run past simulate.max_steps: no estimate from it
            return None
        return headline_numbers(res)

    delta = chain.pillar_model.bending_error
    if progress:
        progress(
            f"error bars: the {case} again with the pillar frequencies moved, one more mode, and a finer integration"
        )
    variants = {
        "discretisation": (None if delta is None else run(quiet, k, chain.modes.scaled(1 + delta))),
        "truncation": run(quiet, k + 1, chain.modes) if chain.modes.count > k else None,
        "integration": (
            run(_finer(quiet, integrator), k, chain.modes) if _finer(quiet, integrator) is not quiet else None
        ),
    }
    # keyed by the quantity's name: the JSON's "uncertainty" object, one entry per number
    out: dict[str, Uncertain] = {}
    for name, unit in HEADLINE.items():
        v = values.value(name)
        if v is None or not math.isfinite(v):
            continue
        sources = {}
        for src, nums in variants.items():
            other = None if nums is None else nums.value(name)
            sources[src] = None if other is None else other - v
        out[name] = Uncertain.of(v, unit, **sources)
    return out
