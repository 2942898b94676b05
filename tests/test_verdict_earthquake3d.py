"""The verdict's checks of the earthquake in two or three components (rotorpillar.verdict.earthquake3d).

What is checked, and against what:
- a synthetic comparison file (compare_earthquake_components.json, its peaks chosen here) in a
  tmp directory: each base stress check's capacity against the yield strength and against
  EN 1993-1-6's sigma_x,Rd worked by hand below (Annex D.1.2, 8.5.2: the long cylinder's C_x at
  the axial share max|N| / A / max|sigma|), utilisation = stress / capacity; the case named in
  words, the 3D's window in its case; the headlines read back from the file's fields;
- the governing row: the three-component row when it is the largest utilisation, the
  one-component row when that is (verdict.summary's own rule over both lists);
- a property on random series: the base stress from the resultant moment at each instant is
  never above the stress from the two moments' maxima added (the hypotenuse is at most the
  sum of its legs);
- a damaged components file is named in the verdict, its checks left out.

Tolerances: 1e-12 relative where the same floating-point operations are repeated in another
order (a handful of roundings of 1e-16 each); the random-series property is exact up to 1e-12
of the stress (the hypotenuse of two equal legs rounds).
"""

import dataclasses
import math

import numpy as np
import pytest

from rotorpillar.provenance import write_result
from rotorpillar.reduced.capacity import check
from rotorpillar.reduced.tower import base_section
from rotorpillar.scene import load_scene
from rotorpillar.transients.components import ComponentPeak, ComponentsComparison, ComponentSeries
from rotorpillar.verdict.earthquake3d import (
    COMPONENTS_FILE,
    axial_share_bound,
    resultant_stress,
    summed_maxima_stress,
)
from rotorpillar.verdict.summary import _governing, engineering_summary

#: the synthetic peaks: the ROM's whole-record stress, the 3D's over its window (Pa), the axial forces (N)
ROM_STRESS, FEM3D_STRESS = 250e6, 150e6
ROM_AXIAL, FEM3D_AXIAL = 2.4e5, 2.6e5


def _peak(name, unit, modal, window, fem3d):
    return ComponentPeak(name, name, unit, modal, window, fem3d, None if fem3d is None else (window - fem3d) / fem3d)


def _comparison(fem3d=True) -> ComponentsComparison:
    t = np.linspace(0.0, 1.0, 5)
    z = np.zeros(5)
    series = ComponentSeries(t, z, z, z, z, z)
    f = (lambda v: v) if fem3d else (lambda v: None)
    return ComponentsComparison(
        case="earthquake",
        components=("elcentro", "elcentro 270 deg", "elcentro vertical (UP)"),
        directions=((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
        angle=0.0,
        operating_speed=89.7,
        modal_duration=54.77,
        window=4.0,
        peaks=(
            _peak("axial_force", "N", ROM_AXIAL, ROM_AXIAL, f(FEM3D_AXIAL)),
            _peak("moment", "N*m", 1.1e6, 1.0e6, f(1.05e6)),
            _peak("stress", "Pa", ROM_STRESS, 0.9 * ROM_STRESS, f(FEM3D_STRESS)),
        ),
        sum_of_maxima=_peak("sum_of_maxima", "N*m", 1.8e6, 1.7e6, f(1.8e6)),
        peak_tip=(_peak("tip_x", "m", 0.010, 0.009, f(0.0101)), _peak("tip_y", "m", 0.007, 0.006, f(0.0076))),
        modal=series,
        fem3d=series if fem3d else None,
        modal_model="spatial ROM",
        fem3d_model="3D full order" if fem3d else "not run",
        modal_seconds=0.1,
        fem3d_seconds=20.0 if fem3d else None,
    )


def _write(d, q):
    head = {"command": "compare", "scene_source": "paper", "overrides": [], "scene": {"name": "paper"}}
    write_result(d / COMPONENTS_FILE, q, head)


def _sigma_rd_by_hand(scene, share):
    """EN 1993-1-6 D.1.2 and 8.5.2 for the base section, class of the scene, C_xb = 1, gamma_M1 = 1.1."""
    sec = base_section(scene.pillar)
    r = (sec.outer_diameter + sec.inner_diameter) / 4
    t = (sec.outer_diameter - sec.inner_diameter) / 2
    length, e, fy = scene.pillar.height, scene.pillar.youngs_modulus, scene.material.yield_strength
    omega = length / math.sqrt(r * t)
    assert omega > 0.5 * r / t  # paper's 20 m tube of r/t 49.5 is a long cylinder: C_x depends on the share
    cxn = max(1 + 0.2 * (1 - 2 * omega * t / r), 0.6)
    cx = cxn * share + (1 - share)
    sigma_cr = 0.605 * e * cx * t / r
    q = {"A": 40.0, "B": 25.0, "C": 16.0}[scene.material.fabrication_class]
    alpha = 0.62 / (1 + 1.91 * (math.sqrt(r * t) / q / t) ** 1.44)
    lam, lam0, lam_p = math.sqrt(fy / sigma_cr), 0.2, math.sqrt(alpha / 0.4)
    chi = 1.0 if lam <= lam0 else 1 - 0.6 * (lam - lam0) / (lam_p - lam0) if lam < lam_p else alpha / lam**2
    return chi * fy / 1.1


def test_checks_against_worked_numbers(tmp_path):
    scene = load_scene("paper")
    _write(tmp_path, _comparison())
    s = engineering_summary(scene, tmp_path)
    assert COMPONENTS_FILE in s.inputs
    area = base_section(scene.pillar).area
    fy = scene.material.yield_strength
    rows = {(c.name, c.model): c for c in s.check_details if "3 components" in str(c.case)}
    for model, stress, axial in (("modal", ROM_STRESS, ROM_AXIAL), ("fem3d", FEM3D_STRESS, FEM3D_AXIAL)):
        y, b = rows[("base stress vs yield", model)], rows[("base stress vs shell buckling", model)]
        assert y.demand == stress and y.capacity == fy  # gamma_M0 = 1
        assert y.utilisation == pytest.approx(stress / fy, rel=1e-12)
        share = axial / area / stress
        assert axial_share_bound(axial, area, stress) == pytest.approx(share, rel=1e-12)
        assert b.capacity == pytest.approx(_sigma_rd_by_hand(scene, share), rel=1e-12)
        assert b.utilisation == pytest.approx(stress / _sigma_rd_by_hand(scene, share), rel=1e-12)
        assert b.status == ("pass" if b.utilisation <= 1 else "fail")
        assert f"{COMPONENTS_FILE}: peaks[stress].{model}" in y.source
    # the case in words, the 3D's window in its
    assert rows[("base stress vs yield", "modal")].case == "earthquake (El Centro, 3 components), whole record (54.8 s)"
    assert rows[("base stress vs yield", "fem3d")].case == "earthquake (El Centro, 3 components), the run's first 4 s"
    # the ROM's 250 MPa is the largest here: it governs both, and the buckling record is its
    by = {c.name: c for c in s.checks}
    assert by["base stress vs shell buckling"].model == "modal"
    assert s.buckling is not None
    assert s.buckling.design_stress == pytest.approx(_sigma_rd_by_hand(scene, ROM_AXIAL / area / ROM_STRESS), rel=1e-12)
    # headlines: the file's numbers, the whole record's first
    h = {x.key: x for x in s.headlines}
    assert [x.key for x in s.headlines][:3] == [
        "earthquake3d_moment_modal",
        "earthquake3d_moment_fem3d",
        "earthquake3d_moment_modal_window",
    ]
    assert h["earthquake3d_moment_modal"].value == 1.1e6 and "whole record" in h["earthquake3d_moment_modal"].label
    assert h["earthquake3d_moment_fem3d"].value == 1.05e6 and "first 4 s" in h["earthquake3d_moment_fem3d"].label
    assert h["earthquake3d_tip_x_modal"].value == 0.010 and h["earthquake3d_tip_y_fem3d"].value == 0.0076
    assert h["earthquake3d_tip_y_modal_window"].value == 0.006


def test_without_the_3d_run_the_rom_alone_is_checked(tmp_path):
    _write(tmp_path, _comparison(fem3d=False))
    s = engineering_summary(load_scene("paper"), tmp_path)
    models = {c.model for c in s.check_details if "3 components" in str(c.case)}
    assert models == {"modal"}
    assert not any(x.model == "fem3d" for x in s.headlines)


def test_governing_row_is_the_largest_of_one_and_three_components(tmp_path):
    scene = load_scene("paper")
    _write(tmp_path, _comparison())
    three = [c for c in engineering_summary(scene, tmp_path).check_details if c.name == "base stress vs yield"]
    fy = scene.material.yield_strength
    for one_stress, expect in ((200e6, "earthquake (El Centro, 3 components)"), (300e6, "earthquake (elcentro)")):
        one = check("base stress vs yield", "base_stress", "Pa", one_stress, fy, "fem3d", "earthquake (elcentro)", "")
        (g,) = _governing([one, *three])
        assert str(g.case).startswith(expect)
        assert g.utilisation == pytest.approx(max(one_stress, ROM_STRESS) / fy, rel=1e-12)


def test_resultant_stress_never_above_the_summed_maxima():
    """Random moments (either sign, any phase) and axial forces: the largest stress from the resultant
    at each instant is at most (max|M_x| + max|M_y|) c / I + max N / A, and equal when both moments
    peak at one instant with the largest axial force."""
    rng = np.random.default_rng(26)
    c, inertia, area = 1.0, 0.06097, 0.1244
    for _ in range(300):
        n = int(rng.integers(1, 400))
        scale = 10 ** rng.uniform(3, 7)
        mx, my = scale * rng.standard_normal(n), scale * rng.uniform(0, 3) * rng.standard_normal(n)
        axial = 2.4e5 + 5e4 * rng.standard_normal(n)
        worst = resultant_stress(mx, my, axial, c, inertia, area).max()
        summed = summed_maxima_stress(mx, my, axial, c, inertia, area)
        assert worst <= summed * (1 + 1e-12)
    # both peaks at one instant, on the 45 deg diagonal, with the largest axial force: M c / I is the
    # hypotenuse, sqrt(2) max|M_x| c / I, against the sum 2 max|M_x| c / I
    mx = my = np.array([0.0, 1e6, 0.5e6])
    axial = np.array([1e5, 2e5, 1.5e5])
    assert resultant_stress(mx, my, axial, c, inertia, area).max() == pytest.approx(
        math.sqrt(2) * 1e6 * c / inertia + 2e5 / area, rel=1e-12
    )
    assert summed_maxima_stress(mx, my, axial, c, inertia, area) == pytest.approx(
        2e6 * c / inertia + 2e5 / area, rel=1e-12
    )


@pytest.mark.parametrize("text", ["{not json", '{"case": "earthquake"}'])
def test_a_damaged_components_file_is_named(tmp_path, text):
    (tmp_path / COMPONENTS_FILE).write_text(text)
    s = engineering_summary(load_scene("paper"), tmp_path)
    assert any(m.startswith(f"{COMPONENTS_FILE} is damaged") for m in s.not_assessed)
    assert COMPONENTS_FILE not in s.inputs
    assert not any("3 components" in str(c.case) for c in s.check_details)


def test_the_scene_table_shows_what_the_earthquake_stages_ran(tmp_path):
    """The page's scene table: the scene's excitation.kind (paper) with what the components stage ran
    with beside it (record), and that stage's own overrides in the table below it."""
    from rotorpillar import records
    from rotorpillar.postprocess.report.modal import section_scene
    from rotorpillar.postprocess.report.state import Build
    from rotorpillar.scene import override

    scene = load_scene("paper")
    sets = ["excitation.kind=record", "excitation.components=3", "full_order.earthquake_duration=4"]
    head = {
        "command": "compare",
        "scene_source": "paper",
        "overrides": sets,
        "scene": records.to_builtins(override(scene, sets).to_dict()),
    }
    write_result(tmp_path / COMPONENTS_FILE, _comparison(), head)
    html = section_scene(Build(scene, tmp_path, "paper", None))  # type: ignore[arg-type]  # no report options needed
    assert scene.excitation.kind == "paper"
    assert "<td>paper (the scene&#x27;s; the earthquake stages ran with record: see below)</td>" in html
    table = html[html.index("The earthquake stages ran") :]
    assert "El Centro in three components" in table
    assert "excitation.kind = record; excitation.components = 3; full_order.earthquake_duration = 4" in table
    assert ", ".join(sets) in table


def test_an_inputs_scene_from_another_version_is_compared_key_by_key(tmp_path):
    """parts.scene_changes reads an input's scene as the JSON it is: a key it ran with another
    value of comes with that value, a section it lacks (or holds as no table, as a damaged or
    foreign writer may) makes each of the page's keys there differ, with no value (None)."""
    from rotorpillar import records
    from rotorpillar.postprocess.report.parts import scene_changes
    from rotorpillar.postprocess.report.state import Build
    from rotorpillar.provenance import Provenance

    scene = load_scene("paper")
    build = Build(scene, tmp_path, "paper", None)  # type: ignore[arg-type]  # no report options needed
    theirs = records.to_builtins(scene.to_dict())
    theirs["excitation"]["kind"] = "record"
    theirs["load"] = "not a table"
    del theirs["drive"]
    changes = {c.key: c.then for c in scene_changes(build, Provenance(scene=theirs))}
    drive = [f"drive.{f.name}" for f in dataclasses.fields(scene.drive)]
    load = [f"load.{f.name}" for f in dataclasses.fields(scene.load)]
    assert changes == {"excitation.kind": "record", **dict.fromkeys(drive + load)}
    ignored = scene_changes(build, Provenance(scene=theirs), ignore=["excitation.kind"])
    assert {c.key for c in ignored} == set(drive + load)
    assert scene_changes(build, Provenance(scene="paper")) == ()
