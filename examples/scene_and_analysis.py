"""Load a scene, change one key, and read the analysis as typed results.

The same as ``rotorpillar analyze paper --set shaft.stiffness=5e6``, in a
notebook: the result is an :class:`rotorpillar.AnalysisResult` whose fields
are analyze.json's keys.  Its headline model is the ROM on the chain's pillar
modes (no study here: the scene's own model); the paper's Eq. 4 with its
stated reduction sits beside it in ``paper_model``.
"""

from rotorpillar import analyze, load_scene, with_values

paper = load_scene("paper")
stiff = with_values(paper, {"shaft.stiffness": 5e6})  # the paper's stiff shaft

for name, scene in (("elastic shaft", paper), ("stiff shaft", stiff)):
    result = analyze(scene)
    rom = ", ".join(f"{r.uncertainty.omega.text('.2f')} ({r.direction})" for r in result.resonances)
    pm = result.paper_model.system
    print(
        f"{name:>13}: ROM {rom}; the paper's Eq. 4: omega_1 = {pm.omega[0]:.2f}, "
        f"omega_2 = {pm.omega[1]:.2f} (X), omega_3 = {pm.omega3:.2f} rad/s (Y)"
    )

# The pillar alone: Eq. 1 and the tip reduction of Eq. 2 (m_col/4 in the limit).
a = analyze(paper)
p = a.pillar
print(
    f"Eq. 1: omega_col1 = {p.omega_col1:.3f} rad/s; Timoshenko {p.omega_col1_timoshenko:.3f}; "
    f"Eq. 2 limit m_r = {p.tip_mass_limit:.0f} kg (the paper states 9.7e3); on the chain's "
    f"model m_r = {a.system.tip_reduction.m_reduced:.0f} kg"
)
for row in a.paper_comparison:
    if row.flag:
        print(f"  flagged: {row.quantity}: paper {row.paper:.4g}, ours {row.computed:.4g}")
