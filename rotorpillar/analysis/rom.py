"""The validated ROM of a scene, analysed as the paper analyses its Eq. 4: the headline model.

The ROM is the chain's pillar (k of its X bending modes with the gondola on
top, rotorpillar.chain) with the rotor on its shaft at the tip
(``reduced.rotor_models.modal_model``): k + 1 coupled resonances in X and the
rotor's vertical one.  Its quasi-normal coefficients feed the averaging theory
(Eq. 19-24) exactly as the paper's two-mass model does.

Each headline number carries its error bar (``chain.Uncertain``):

- discretisation: the number's change when the pillar modes' frequencies move
  by the convergence study's error bound on the first bending frequency (the
  study measures the first bending and the first ovalling; the higher bending
  modes are taken at the same relative error, which the report says);
- truncation: the ROM against itself with one more pillar mode.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from ..chain import ChainModes, Uncertain
from ..reduced import averaging as av
from ..reduced.rotor_models import RotorStructure, modal_model
from ..reduced.system import Resonance
from ..scene import Scene


def rom_of(scene: Scene, chain: ChainModes, k: int) -> RotorStructure:
    """The ROM with the first ``k`` of the chain's pillar modes."""
    r, sh = scene.rotor, scene.shaft
    return modal_model(
        chain.modes.truncate(k), r.mass, r.inertia, r.eccentricity, sh.stiffness, sh.damping, scene.pillar.damping
    )


@dataclass(frozen=True, eq=False)
class RomVariants:
    """The ROM and the two variants its error bars come from."""

    base: RotorStructure
    modes: int
    """pillar modes kept (-)"""
    discretised: RotorStructure | None
    """pillar frequencies moved by the study's bending error bound (None: unverified)"""
    truncated: RotorStructure | None
    """one more pillar mode (None: the mode source offers no more)"""
    frequency_error: float | None
    """the relative frequency error bound applied (-)"""


def rom_variants(scene: Scene, chain: ChainModes, band_top: float) -> RomVariants:
    """The ROM on the modes below ``band_top`` (rad/s), and its error-bar variants."""
    k = chain.count_below(band_top)
    base = rom_of(scene, chain, k)
    delta = chain.pillar_model.bending_error
    disc = None
    if delta is not None:
        moved = ChainModes(chain.pillar_model, chain.modes.scaled(1 + delta), chain.reduction)
        disc = rom_of(scene, moved, k)
    trunc = rom_of(scene, chain, k + 1) if chain.modes.count > k else None
    return RomVariants(base, k, disc, trunc, delta)


def matched(base: list[Resonance], other: list[Resonance]) -> list[Resonance | None]:
    """``other``'s resonance that corresponds to each of ``base``'s: Y to Y, the X ones in
    order of frequency, skipping those of ``other`` that ``base`` lacks.

    The truncation variant keeps one more pillar mode, and its resonance may fall between
    two of the base's (a tower's second bending mode below the rotor's own): pairing by
    index then set the rotor's resonance against the tower's next one (``analyze nrel5mw``
    printed 110.8 +- 93 rad/s).  Among the order-keeping pairings the one with the least
    sum of |ln(omega_other / omega_base)| is taken (a small dynamic programme)."""
    bx = [r for r in base if r.direction == "X"]
    ox = [r for r in other if r.direction == "X"]
    by = [r for r in other if r.direction == "Y"]
    pair_x = _aligned([r.omega for r in bx], [r.omega for r in ox])
    out, ix = [], 0
    for r in base:
        if r.direction == "Y":
            out.append(by[0] if by else None)
        else:
            j = pair_x[ix]
            out.append(None if j is None else ox[j])
            ix += 1
    return out


def _aligned(base: list[float], other: list[float]) -> list[int | None]:
    """For each of ``base``'s frequencies (ascending) the index of its partner in ``other``
    (ascending), order kept, ``other``'s surplus skipped, least total log distance; where
    ``other`` has fewer, the last of ``base`` go unmatched (None)."""
    n, m = len(base), len(other)
    if m <= n:
        return [i if i < m else None for i in range(n)]
    cost = lambda i, j: abs(math.log(other[j] / base[i])) if base[i] > 0 and other[j] > 0 else 0.0
    inf = math.inf
    # best[i][j]: least cost of pairing base[:i] within other[:j]
    best = [[inf] * (m + 1) for _ in range(n + 1)]
    best[0] = [0.0] * (m + 1)
    for i in range(1, n + 1):
        for j in range(i, m + 1):
            best[i][j] = min(best[i][j - 1], best[i - 1][j - 1] + cost(i - 1, j - 1))
    pairs: list[int | None] = [None] * n
    i, j = n, m
    while i > 0:
        if best[i][j] == best[i][j - 1] and j > i:
            j -= 1
        else:
            pairs[i - 1] = j - 1
            i, j = i - 1, j - 1
    return pairs


def bars(value: float, quantity: Callable, variants: RomVariants, unit: str = "") -> Uncertain:
    """``value`` with its discretisation and truncation sources, ``quantity(model)`` giving
    the same number on a variant (None where it has no counterpart)."""

    def diff(model):
        if model is None:
            return None
        v = quantity(model)
        return None if v is None or not math.isfinite(v) else v - value

    return Uncertain.of(value, unit, discretisation=diff(variants.discretised), truncation=diff(variants.truncated))


def resonance_quantity(i: int, base_res: list[Resonance], fn: Callable[[Resonance], float]):
    """A function model -> fn(the model's resonance matching base resonance i)."""

    def q(model: RotorStructure):
        m = matched(base_res, model.quasi_normal())[i]
        return None if m is None else fn(m)

    return q


def drive_quantity(ch: av.Characteristic, which: str):
    """A function model -> the averaging's run-up or run-down speed on that model."""

    def q(model: RotorStructure):
        d = av.analyse_drive(ch, model.quasi_normal())
        return getattr(d, which)

    return q
