"""Cost of the closed forms against the 1D beam FE they replace.

The closed form Eq. 1 and a 1D Euler-Bernoulli model converged to 1e-7 give
the same first frequency; this measures how much cheaper the closed form is,
side by side in one run.  ``quick``: one call of each (does it run).
"""

import time

from rotorpillar.reduced.beam_fe import BeamProperties, beam_modes
from rotorpillar.reduced.pillar import omega_euler_bernoulli, tube_section


def _best(fn, repeat=5, number=20):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best


def run(quick: bool = False) -> list[dict]:
    repeat, number = (1, 1) if quick else (5, 20)
    sec = tube_section(2.0, 1.96, 8.1e3)
    p = BeamProperties(2.1e11, 0.3, 0.53, 8.1e3, sec.area, sec.second_moment, 20.0)
    t_closed = _best(
        lambda: omega_euler_bernoulli(2.1e11, sec.second_moment, sec.mass_per_length, 20.0), repeat, number
    )
    t_fe = _best(lambda: beam_modes(p, 16, "euler", 1), repeat, number)
    return [
        {
            "name": "eq1_vs_beam_fe16",
            "compares": "1D EB FE (16 elements, error 1.3e-7) time / Eq. 1 time",
            "value": t_fe / t_closed,
            "unit": "x",
            "closed_form_s": t_closed,
            "beam_fe_s": t_fe,
        }
    ]
