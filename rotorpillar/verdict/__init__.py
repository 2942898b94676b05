"""The engineer's answers assembled from the models' results.

- :mod:`.harmonic`: the unbalance response (Bode: the ROM, the 3D model,
  Eq. 19) and the separation margins (API 684) -> harmonic.json
  (`rotorpillar harmonic`);
- :mod:`.summary`: the checks (stresses, buckling, clearance, bearing force,
  margins) against the scene's capacities and the numbers a reader came
  for, each naming its model and case -> summary.json (`rotorpillar report`);
- :mod:`.machine`: the machine's checks in summary.json (balance grade,
  vibration at speed, modal mass, from analyze.json) and the foundation's
  design reactions of each run;

each beside its records (``HarmonicResult``, ``EngineeringSummary``).
"""
