"""`rotorpillar modal`: the 3D tube's modes, bare and with its masses on top.

Writes modal.json (through the CLI), ``modes_bare.vtu`` and
``modes_top.vtu`` (ParaView, pyvista, meshio) beside it, and prints a table.
Runs under MPI (``mpirun -n 2 rotorpillar modal``): every rank computes,
rank 0 writes and prints.
"""

from __future__ import annotations

import math

from . import progress

#: Mode-shape files, in the output directory.
SHAPE_FILES = {"bare": "modes_bare.vtu", "top": "modes_top.vtu"}


def quiet_jit_logging() -> None:
    """Keep the compiler's INFO lines (setuptools, on the first JIT of a form) off stderr.

    ffcx installs a root handler at import; setuptools raises the root level
    to INFO while it builds.  A WARNING threshold on the handler keeps the
    console to our own progress lines.
    """
    import logging
    root = logging.getLogger()
    if not root.handlers:
        logging.basicConfig()
    for h in root.handlers:
        h.setLevel(max(h.level, logging.WARNING))


def _rank0() -> bool:
    from mpi4py import MPI
    return MPI.COMM_WORLD.rank == 0


def _config_dict(result) -> dict:
    return {"dofs": result.dofs, "cells": result.cells, "solver": result.solver,
            "timings": result.timings}


def shell_modes_below_second_bending(result) -> tuple[float | None, list[dict]]:
    """The second bending frequency and the non-bending modes below it."""
    i2 = result.index("bending_x", n_axial=1)
    w2 = None if i2 is None else float(result.omega[i2])
    rows = [m for m in result.modes_table()
            if m["kind"] not in ("bending_x", "bending_y") and (w2 is None or m["omega"] < w2)]
    return w2, rows


def modal_result(scene, bare, loaded, closed: dict) -> dict:
    """The JSON document of `rotorpillar modal` (less what the CLI adds)."""
    from ..fem3d import AXES, tip_reduction
    red = tip_reduction(bare, scene.pillar)
    w2_bare, shell_bare = shell_modes_below_second_bending(bare)
    w2_top, shell_top = shell_modes_below_second_bending(loaded)
    i1 = loaded.index("bending_x", n_axial=0)
    m_top = loaded.top_mass
    # The paper's model of the loaded tube: m_r + m* on c1.
    w_reduced_top = math.sqrt(red.tip_stiffness / (red.m_reduced + m_top))
    ms = scene.mesh
    return {
        "axes": AXES,
        "modes": bare.modes_table(),
        "modes_with_top": loaded.modes_table(),
        "top": {"model": loaded.top_model, "mass": m_top, "carries": scene.modal.top_mass,
                "mass_centre": [0.0, 0.0, scene.pillar.height],
                "omega_bending": None if i1 is None else float(loaded.omega[i1]),
                "omega_bending_reduced_model": w_reduced_top,
                "note": "rigid: a rigid plate on the whole top face carries the mass at the "
                        "top centre (6 dofs appended after the tube's); ring_mass: the mass "
                        "spread on the top face, no stiffening"},
        "reduction": {
            "m_reduced": red.m_reduced, "tip_stiffness": red.tip_stiffness,
            "omega_bending": red.omega_bending, "m_reduced_beam_line": red.m_reduced_beam_line,
            "method": "kinetic energy of the 3D first bending mode at unit mean tip "
                      "displacement (Eq. 2), c1 = m_r omega^2; m_reduced_beam_line: Eq. 2 on "
                      "the deflection line (mean u_x per height level)",
            "closed_form": {"m_reduced": closed["tip_mass_limit"],
                            "tip_stiffness": closed["tip_stiffness_limit"],
                            "omega_col1": closed["omega_col1"],
                            "omega_col1_timoshenko": closed["omega_col1_timoshenko"]},
            "stated": {"m_reduced": scene.reduction.tip_mass,
                       "tip_stiffness": scene.reduction.tip_stiffness},
        },
        "comparison": {
            "omega_bending_over_euler_bernoulli": red.omega_bending / closed["omega_col1"] - 1,
            "omega_bending_over_timoshenko": red.omega_bending / closed["omega_col1_timoshenko"] - 1,
            "m_reduced_over_closed_form": red.m_reduced / closed["tip_mass_limit"] - 1,
        },
        "shell_modes_below_second_bending": {
            "bare": {"omega_second_bending": w2_bare, "modes": shell_bare},
            "with_top": {"omega_second_bending": w2_top, "modes": shell_top}},
        "mesh": {"cells": bare.cells, "dofs": bare.dofs, "dofs_with_top": loaded.dofs,
                 "cell_type": ms.cell_type, "degree": ms.degree,
                 "elements_around": ms.elements_around, "elements_along": ms.elements_along,
                 "elements_through": ms.elements_through, "grading": ms.grading},
        "configurations": {"bare": _config_dict(bare), "with_top": _config_dict(loaded)},
    }


def _table(title: str, result) -> list[str]:
    lines = [title,
             f"  {'#':>3} {'kind':<10} {'n':>3} {'m':>3} {'omega [rad/s]':>14} {'f [Hz]':>9} "
             f"{'modal mass [kg]':>16} {'norm':>9}"]
    for row in result.modes_table():
        n = "-" if row["n_circumferential"] is None else row["n_circumferential"]
        m = "-" if row["n_axial"] is None else row["n_axial"]
        lines.append(f"  {row['index']:>3} {row['kind']:<10} {n:>3} {m:>3} {row['omega']:>14.4f} "
                     f"{row['frequency_hz']:>9.4f} {row['modal_mass']:>16.6g} {row['normalisation']:>9}")
    return lines


def summary(doc: dict, bare, loaded) -> str:
    red, cmp_, top = doc["reduction"], doc["comparison"], doc["top"]
    cf = red["closed_form"]
    mesh = doc["mesh"]
    lines = [f"3D pillar: {mesh['cells']} {mesh['cell_type']} cells, degree {mesh['degree']}, "
             f"{mesh['dofs']} dofs ({mesh['elements_around']} around x {mesh['elements_along']} "
             f"along x {mesh['elements_through']} through, grading {mesh['grading']:g})"]
    lines.append("(n: waves around the circumference; m: sign changes along the height; "
                 "x is the rotor's plane, z the tube axis)")
    lines += _table("Bare tube (clamped base, free top)", bare)
    lines += _table(f"With {top['carries'].replace('_', ' ')} on top ({top['mass']:g} kg, "
                    f"{top['model']} top)", loaded)
    lines.append(f"First bending, bare: {red['omega_bending']:.4f} rad/s; Eq. 1 "
                 f"{cf['omega_col1']:.4f} ({100 * cmp_['omega_bending_over_euler_bernoulli']:+.2f} %), "
                 f"Timoshenko {cf['omega_col1_timoshenko']:.4f} "
                 f"({100 * cmp_['omega_bending_over_timoshenko']:+.2f} %)")
    if top["omega_bending"] is not None:
        lines.append(f"First bending with top: {top['omega_bending']:.4f} rad/s; the tip model "
                     f"c1/(m_r + m_top) gives {top['omega_bending_reduced_model']:.4f}")
    lines.append(f"Tip reduction (Eq. 2 on the 3D mode): m_r = {red['m_reduced']:.5g} kg "
                 f"(beam line {red['m_reduced_beam_line']:.5g}; closed form m_col/4 = "
                 f"{cf['m_reduced']:.5g}, {100 * cmp_['m_reduced_over_closed_form']:+.2f} %), "
                 f"c1 = {red['tip_stiffness']:.5g} N/m")
    for key, label in (("bare", "bare"), ("with_top", "with top")):
        s = doc["shell_modes_below_second_bending"][key]
        w2 = s["omega_second_bending"]
        found = ", ".join(f"{m['omega']:.2f} ({m['kind']}"
                          + (f" n={m['n_circumferential']}" if m["kind"] == "ovalling" else "") + ")"
                          for m in s["modes"])
        if w2 is None:
            lines.append(f"Second bending ({label}) not among the {len(bare.omega)} modes computed; "
                         f"non-bending modes found: {found or 'none'}")
        else:
            lines.append(f"Below the second bending ({label}, {w2:.2f} rad/s): {found or 'no shell mode'}")
    t = doc["configurations"]
    lines.append("Timings [s]: " + "; ".join(
        f"{k}: mesh {v['timings']['mesh']:.2f}, assembly {v['timings']['assembly']:.2f}, "
        f"solve {v['timings']['solve']:.2f}" for k, v in t.items()))
    return "\n".join(lines)


def modal_command(scene, args, timings, context):
    from ..reduced.reduction import pillar_closed_forms
    from . import out_dir
    from ..fem3d import modal_analysis
    from ..fem3d.output import write_modes_vtu
    from ..mesh import tube_params
    tube_params(scene.pillar, scene.mesh)          # bad input: refused before any work
    quiet_jit_logging()
    say = progress if _rank0() else (lambda message: None)
    selection = None
    if getattr(args, "tolerance", None) is not None:
        from ..converge import model_for_modal
        from ..postprocess.convergence_charts import convergence_charts
        with timings("model_selection"):
            scene, selection = model_for_modal(scene, args.tolerance, out_dir(scene, args),
                                               cache_dir=args.cache, charts=convergence_charts,
                                               log=progress)
        say(selection["text"].splitlines()[0])
    say(f"modal: bare tube, {scene.modal.n_modes} modes")
    bare = modal_analysis(scene, top=False)
    say(f"modal: tube with its top mass ({scene.modal.top_model} top)")
    loaded = modal_analysis(scene, top=True)
    for key in ("mesh", "assembly", "solve", "postprocess"):
        timings[key] = bare.timings.get(key, 0.0) + loaded.timings.get(key, 0.0)
        timings[f"bare.{key}"] = bare.timings.get(key, 0.0)
        timings[f"with_top.{key}"] = loaded.timings.get(key, 0.0)
    doc = modal_result(scene, bare, loaded, pillar_closed_forms(scene))
    files = {}
    if _rank0():
        with timings("write_shapes"):
            d = out_dir(scene, args)
            files["modes_bare"] = str(write_modes_vtu(d / SHAPE_FILES["bare"], bare))
            files["modes_top"] = str(write_modes_vtu(d / SHAPE_FILES["top"], loaded))
    doc["files"] = files
    text = summary(doc, bare, loaded)
    if selection is not None:
        doc["model_selection"] = selection
        text = selection["text"] + "\n\n" + text
    context["modal"] = doc
    return doc, text
