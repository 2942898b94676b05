"""The transients as the user runs them: every model on one case, its files, and the comparison.

Above rotorpillar.reduced (the paper, modal and beam models) and
rotorpillar.fem3d (the 3D tube at full order), this package runs one model
of a case the same way for `simulate` and `compare`
(``model_run.run_model`` -> ``ModelRun``; ``run_plan`` its length and the
3D plan), writes its files (``files.write_model_files``:
``simulate_<case>_<model>.{json,npz,csv,png}``), and compares models on one
case (``compare.compare_models`` -> ``records.CompareResult``,
``compare_<case>.json`` and ``compare_<case>.png``).  Charts are drawn by
rotorpillar.postprocess; ``records`` imports nothing but provenance, so the
report can read the comparison back.
"""
