"""The pillar model each transient run names (a rotorpillar.chain.PillarModel).

``reduced_pillar_model``: the chain's (modal), the scene's beam at full order
(beam) or the paper's tip reduction (paper); ``solid_pillar_model``: the 3D
full order's mesh, its source and error the reference's.  Moved out of
rotorpillar.transients.model_run, which puts them in every run's record.
"""

from __future__ import annotations

from ..chain import ChainModes, PillarModel
from ..reduced.models import BeamModelInfo, ModelInfo, PaperModelInfo
from ..scene import Mesh
from .references import FullOrderReference


def reduced_pillar_model(which: str, chain: ChainModes | None, info: ModelInfo | None) -> PillarModel:
    """The pillar model a reduced model ran on: the chain's (modal), the scene's beam at
    full order (beam), or the paper's stated tip reduction (paper: not the validated chain)."""
    if which == "modal":
        if chain is None:
            raise ValueError("the modal model's pillar model is the chain's: none handed in")
        return chain.pillar_model
    if which == "beam":
        assert isinstance(info, BeamModelInfo)  # build_model's for "beam"
        n, theory = info.elements, info.theory
        return PillarModel(
            "beam",
            f"beam {theory}, {n} el. (full order)",
            {"theory": theory, "elements": n},
            2 * n,
            "scene",
            False,
            None,
            {},
            f"the full-order 1D {theory} beam of {info.element_source}",
            None,
        )
    assert isinstance(info, PaperModelInfo)  # build_model's for "paper"
    red = info.reduction
    return PillarModel(
        "reduction",
        "Eq. 4: one tip mass and spring",
        {"tip_mass": red.tip_mass, "tip_stiffness": red.tip_stiffness},
        1,
        "scene",
        False,
        None,
        {},
        f"the paper's model: m_r ({red.tip_mass_source}) and c1 "
        f"({red.tip_stiffness_source}) at the tip; not the validated chain",
        None,
    )


def solid_pillar_model(mesh: Mesh, dofs: int, reference: FullOrderReference, note: str) -> PillarModel:
    """The 3D full order's mesh as a PillarModel, its source and error the reference's."""
    from ..chain.choice import solid_run_of

    run = solid_run_of(mesh)
    errors = {q: e.error_bound for q, e in reference.errors.items() if e.error_bound is not None}
    return PillarModel(
        "solid",
        run.label + " (full order)",
        run.params,
        int(dofs),
        reference.source,
        reference.verified,
        reference.tolerance,
        errors,
        note + ("; " + reference.statement if reference.statement else ""),
        reference.study,
    )
