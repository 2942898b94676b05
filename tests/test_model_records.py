"""The closed forms, the tip reduction and how each reduced model was built, as records
(issue 18.1): they write the JSON the dicts they replaced wrote, and a union of records
is read back as the one record its keys fit.

Sources: the old dicts are rebuilt here, key by key, from the same formulas of
rotorpillar.reduced.pillar (as the code before the records built them); no tolerance:
the same floats pass through both ways.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import pytest

from rotorpillar.provenance import JsonRecord
from rotorpillar.reduced import pillar as pl
from rotorpillar.reduced.models import BeamModelInfo, ModalModelInfo, ModelInfo, PaperModelInfo, build_model
from rotorpillar.reduced.reduction import LUMPINGS, pillar_closed_forms, resolve_reduction
from rotorpillar.scene import load_scene


def _closed_forms_as_dict(p) -> dict:
    """pillar_closed_forms as the code before its record wrote it."""
    sec = pl.section_of(p)
    I, A, m_rho = sec.second_moment, sec.area, sec.mass_per_length
    mass = m_rho * p.height
    w1 = pl.omega_euler_bernoulli(p.youngs_modulus, I, m_rho, p.height)
    kappa = pl.cowper_shear_coefficient(p.outer_diameter, p.inner_diameter, p.poisson_ratio)
    w_timo = pl.omega_timoshenko(p.youngs_modulus, p.poisson_ratio, kappa, p.density, A, I, p.height)
    m_inf = pl.tip_mass_continuous(mass)
    rayleigh = []
    for shape in ("uniform_load", "tip_load"):
        r = pl.rayleigh_reduction(mass, p.youngs_modulus, I, p.height, shape)
        rayleigh.append(
            {
                "shape": shape,
                "tip_mass": r.tip_mass,
                "tip_stiffness": r.tip_stiffness,
                "omega": r.omega,
                "omega_error": r.omega / w1 - 1,
            }
        )
    return {
        "area": A,
        "second_moment": I,
        "mass_per_length": m_rho,
        "mass": mass,
        "wall_thickness": sec.wall_thickness,
        "diameter_to_thickness": p.outer_diameter / sec.wall_thickness,
        "slenderness": p.height / sec.radius_of_gyration,
        "omega_col1": w1,
        "frequency_col1_hz": w1 / (2 * math.pi),
        "cantilever_root": pl.cantilever_root(1),
        "omega_euler_bernoulli": [pl.omega_euler_bernoulli(p.youngs_modulus, I, m_rho, p.height, k) for k in (1, 2, 3)],
        "shear_coefficient": kappa,
        "omega_col1_timoshenko": w_timo,
        "timoshenko_correction": w_timo / w1 - 1,
        "tip_mass_lumped": [
            {"n": n, "tip_mass": pl.tip_mass_lumped(mass, n), "tip_stiffness": pl.tip_mass_lumped(mass, n) * w1**2}
            for n in LUMPINGS
        ],
        "tip_mass_limit": m_inf,
        "tip_stiffness_limit": m_inf * w1**2,
        "rayleigh": rayleigh,
    }


@pytest.mark.parametrize("name", ["paper", "paper-stiff", "sommerfeld"])
def test_closed_forms_write_the_dict_they_replaced(name):
    p = load_scene(name).pillar
    closed = pillar_closed_forms(p)
    # json.dumps: key order included
    assert json.dumps(closed.to_json()) == json.dumps(_closed_forms_as_dict(p))
    assert type(closed).from_json(closed.to_json()) == closed


def _reduction_as_dict(red, closed) -> dict:
    """resolve_reduction (closed-form source) as the code before its record wrote it."""
    computed = {"tip_mass": closed.tip_mass_limit, "tip_stiffness": closed.tip_stiffness_limit}
    out = {"source": red.source}
    for key in ("tip_mass", "tip_stiffness"):
        stated = getattr(red, key)
        if stated is not None and red.source in ("auto", "stated"):
            out[key], out[f"{key}_source"] = stated, "stated"
        else:
            out[key], out[f"{key}_source"] = computed[key], "closed_form"
        out[f"{key}_computed"] = computed[key]
    out["computed_source"] = "closed_form"
    return out


@pytest.mark.parametrize(
    "overrides",
    [
        [],  # the paper's stated m_r, c1 (auto)
        ["reduction.source=closed_form"],  # Eq. 2's limit for both
        ["reduction.source=stated", "reduction.tip_mass=3000", "reduction.tip_stiffness=2e7"],
    ],
)
def test_tip_reduction_writes_the_dict_it_replaced(overrides):
    scene = load_scene("paper", overrides)
    closed = pillar_closed_forms(scene.pillar)
    red = resolve_reduction(scene, closed)
    assert json.dumps(red.to_json()) == json.dumps(_reduction_as_dict(scene.reduction, closed))


@dataclass(frozen=True)
class _Built(JsonRecord):
    info: ModelInfo | None


@pytest.mark.parametrize(
    "which,record", [("paper", PaperModelInfo), ("beam", BeamModelInfo), ("modal", ModalModelInfo)]
)
def test_each_model_info_reads_back_as_its_own_record(which, record):
    scene = load_scene("paper", ["full_order.beam_elements=8", "modal_model.source=beam"])
    model, info = build_model(scene, which, band_top=400.0)
    assert isinstance(info, record)
    doc = json.loads(json.dumps(_Built(info).to_json()))  # through text, as a file is read
    back = _Built.from_json(doc)
    assert back == _Built(info) and isinstance(back.info, record)
    if which == "beam":
        assert info.elements == 8 and info.dofs == model.n and info.element_source == "full_order.beam_elements"


def test_a_union_of_records_refuses_keys_that_fit_none():
    # a schema error is named, never passed on as a dict the reader would index
    with pytest.raises(KeyError, match="fit 0 of PaperModelInfo, BeamModelInfo, ModalModelInfo"):
        _Built.from_json({"info": {"elements": 8, "theory": "timoshenko"}})
    assert _Built.from_json({"info": None}) == _Built(None)
