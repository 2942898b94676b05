"""Load a scene, change one key, and read the closed-form analysis as typed results.

The same as ``rotorpillar analyze paper --set shaft.stiffness=5e6``, in a
notebook: the result is an :class:`rotorpillar.AnalysisResult` whose fields
are analyze.json's keys.
"""

from rotorpillar import analyze, load_scene, override

paper = load_scene("paper")
stiff = override(paper, ["shaft.stiffness=5e6"])          # the paper's stiff shaft

for name, scene in (("elastic shaft", paper), ("stiff shaft", stiff)):
    result = analyze(scene)
    w1, w2 = result.system.omega
    print(f"{name:>13}: omega_1 = {w1:.2f}, omega_2 = {w2:.2f} rad/s (X), "
          f"omega_3 = {result.system.omega3:.2f} rad/s (Y)")

# The pillar alone: Eq. 1 and the tip reduction of Eq. 2 (m_col/4 in the limit).
p = analyze(paper).pillar
print(f"Eq. 1: omega_col1 = {p.omega_col1:.3f} rad/s; Timoshenko {p.omega_col1_timoshenko:.3f}; "
      f"Eq. 2 limit m_r = {p.tip_mass_limit:.0f} kg (the paper states 9.7e3)")
for row in analyze(paper).paper_comparison:
    if row.flag:
        print(f"  flagged: {row.quantity}: paper {row.paper:.4g}, ours {row.computed:.4g}")
