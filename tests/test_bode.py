"""The ROM's unbalance response (rotorpillar.reduced.bode) against the averaging's closed form.

Reference: near resonance i, the averaging theory's amplitude (Eq. 19,
a_i = |f_i| / (2 omega_i**2 sqrt((1 - z)**2 + nu_i**2))) is the first-order
expansion of the exact linear response of quasi-normal mode i; the other
modes add their off-resonant response, O(nu_i) of the peak.  On the paper's
ROM with its damping cut 100-fold (nu_i < 3e-3):
- the Bode peak lies at omega_i to within nu_i omega_i (the half-power
  half-width);
- its height equals Eq. 19's a_i(omega_i) within 10 nu_i (< 3 %);
- the phase lag at omega_i is 90 deg off the in-phase value (90 or 270 by
  the sign of the mode's forcing) within 1 deg.
And the doctest's paper-model amplitudes are the closed form of the 2-dof
chain (checked in rotorpillar.reduced.bode's doctest).
"""

import numpy as np
import pytest

from rotorpillar.reduced import averaging as av
from rotorpillar.reduced.bode import averaging_curves, peak_near, speed_grid, unbalance_response
from rotorpillar.reduced.models import build_model
from rotorpillar.scene import load_scene, override


@pytest.fixture(scope="module")
def rom():
    # the ROM on the beam's modes (any mode source has the closed forms below)
    scene = override(load_scene("paper"), ["pillar.damping=300", "shaft.damping=110", "modal_model.source=beam"])
    return build_model(scene, "modal", 186.0)[0]


def test_rom_bode_against_eq19_near_each_resonance(rom):
    xs = [r for r in rom.quasi_normal() if r.direction == "X"]
    assert len(xs) == 3
    for r in xs:
        assert r.nu < 3e-3
        # 100 points per half-power half-width: the parabola through the top three is exact to 1e-4
        curve = unbalance_response(rom, np.linspace(1 - 3 * r.nu, 1 + 3 * r.nu, 601) * r.omega)
        peak = peak_near(curve, r.omega, 0.05)
        assert peak is not None
        assert peak[0] == pytest.approx(r.omega, abs=r.nu * r.omega)
        assert peak[1] == pytest.approx(float(av.amplitude(r.omega, r)), rel=10 * r.nu)
        at = unbalance_response(rom, np.array([r.omega]))
        assert min(abs(at.tip_phase[0] - 90), abs(at.tip_phase[0] - 270)) < 1.0
    grid = speed_grid(rom.quasi_normal(), 186.0)
    assert all(np.any(np.abs(grid - r.omega) < 0.011 * r.omega) for r in xs)
    overlay = averaging_curves(rom, 186.0)
    assert [c.index for c in overlay] == [r.index for r in xs]
