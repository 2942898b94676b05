"""A run-up through resonance: is the motor strong enough, or is the rotor captured?

The `sommerfeld` scene is an unbalanced fan with a weak motor.  The averaging
theory (the paper's equations 19-23) predicts the stall torque needed to pass
the pillar's first resonance; two run-ups of the reduced model, just below
and just above it, show the Sommerfeld effect.  The summary is a typed
CaseSummary (the fields of simulate_runup.json).
"""

from rotorpillar import load_scene, with_values
from rotorpillar.transients.cases import run_case

scene = with_values(load_scene("sommerfeld"), {"simulate.threshold": False})  # one run each, no batch
first = run_case(scene, "runup", "paper", truncation=False)
# the averaging theory's fold: the quasi-static run-up jumps past resonance 1 above this M0
fold = min(j.torque_at_zero for j in first.summary.prediction.jumps if j.direction == "up" and j.resonance == 1)
print(
    f"averaging theory: a run-up passes resonance 1 with M0 above {fold:.1f} N*m "
    f"(the scene's motor: {scene.drive.torque_at_zero:g} N*m)"
)

for M0 in (600.0, 660.0):
    s = run_case(with_values(scene, {"drive.torque_at_zero": M0}), "runup", "paper", truncation=False).summary
    where = (
        f"captured at {s.captured_at:.2f} rad/s below the resonance at {s.captured_resonance:.2f} rad/s"
        if s.captured_at is not None
        else s.speed_state
    )
    print(
        f"M0 = {M0:5.0f} N*m: final speed {s.omega_final:6.2f} rad/s, {where}; "
        f"largest tip {1e3 * s.max_abs['tip_x']:.1f} mm"
    )
