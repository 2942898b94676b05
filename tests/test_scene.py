"""Scenes: embedded ones load, overrides apply, every class of bad input is
refused with one line naming the key and the allowed range."""

import pytest

from rotorpillar.scene import SceneError, embedded_scenes, load_scene, override


def test_embedded_scenes_load():
    assert {"paper", "paper-stiff"} <= set(embedded_scenes())
    s = load_scene("paper")
    assert (s.shaft.stiffness, s.shaft.damping) == (0.4e6, 11e3)
    assert (s.reduction.tip_mass, s.reduction.tip_stiffness) == (9.7e3, 9.6e6)
    st = load_scene("paper-stiff")
    assert (st.shaft.stiffness, st.shaft.damping) == (5e6, 25e3)


def test_overrides_are_typed_and_repeatable():
    s = load_scene(
        "paper", ["shaft.stiffness=5e6", "shaft.damping=25e3", "mesh.cell_type=tetrahedron", "mesh.elements_around=16"]
    )
    assert s.shaft.stiffness == 5e6 and s.mesh.cell_type == "tetrahedron"
    assert s.mesh.elements_around == 16 and isinstance(s.mesh.elements_around, int)
    assert override(s, ["rotor.eccentricity=0.01"]).rotor.eccentricity == 0.01


BAD = [
    (["pillar.inner_diameter=2.5"], "pillar.inner_diameter", "< pillar.outer_diameter"),
    (["pillar.inner_diameter=2.0"], "pillar.inner_diameter", "< pillar.outer_diameter"),
    (["rotor.mass=-1"], "rotor.mass", ">= 0.001"),
    (["gondola.mass=0"], "gondola.mass", ">= 1e-09"),
    (["pillar.height=0"], "pillar.height", ">= 0.1"),
    (["pillar.poisson_ratio=0.5"], "pillar.poisson_ratio", "<= 0.49"),
    (["pillar.poisson_ratio=-1"], "pillar.poisson_ratio", ">= -0.9"),
    (["pillar.inner_diameter=1.9999"], "pillar.inner_diameter", "D0/t <= 1000"),
    (["modal_model.gondola_inertia=1"], "modal_model.gondola_inertia", 'modal_model.source = "beam"'),
    (["full_order.elements_around=3"], "full_order.elements_around", "0 or >= 6"),
    (["simulate.time_step=1e-12"], "simulate.time_step", "0 or >= 1e-09 and <= 10"),
    (["modal.n_modes=" + "9" * 5000], "modal.n_modes", "an integer of 5000 characters is out of range"),
    (["pillar.height=1" + "0" * 400], "pillar.height", "an integer of 401 digits"),
    (['shaft.stiffness="stiff"'], "shaft.stiffness", "must be a number"),
    (["mesh.elements_around=12.5"], "mesh.elements_around", "must be an integer"),
    (["mesh.degree=3"], "mesh.degree", "one of 1, 2"),
    (["mesh.elements_along=0"], "mesh.elements_along", ">= 1"),
    (["rotor.colour=1"], "rotor.colour", "unknown key"),
    (["turbine.mass=1"], "[turbine]", "unknown section"),
    (["shaft.damping=nan"], "shaft.damping", "finite"),
    (["shaftstiffness"], "shaftstiffness", "KEY=VALUE"),
    (["stiffness=1"], "stiffness=1", "section.key"),
    (['reduction.source="guess"'], "reduction.source", "one of"),
    # issue 26's keys of the spatial model
    (["rotor.diametral_inertia=0"], "rotor.diametral_inertia", ">= 1e-06"),
    (["rotor.height=-1"], "rotor.height", ">= 0"),
    (["rotor.couple_unbalance=-0.1"], "rotor.couple_unbalance", ">= 0"),
    (["shaft.axial_stiffness=0"], "shaft.axial_stiffness", ">= 1"),
    (["shaft.tilt_stiffness=0.5"], "shaft.tilt_stiffness", ">= 1"),
    (["shaft.tilt_damping=-1"], "shaft.tilt_damping", ">= 0"),
    (["gondola.yaw_inertia=-1"], "gondola.yaw_inertia", ">= 0"),
    (["gondola.height=-1"], "gondola.height", ">= 0"),
    (["pillar.damping_ratio=1"], "pillar.damping_ratio", "<= 0.5"),
    (['modal_model.planes="3d"'], "modal_model.planes", "one of 'auto', 'planar', 'spatial'"),
    (["excitation.components=4"], "excitation.components", "one of 1, 2, 3"),
    (["excitation.angle=400"], "excitation.angle", "<= 360"),
]


def test_spatial_keys_default_to_todays_model():
    """Issue 26: a scene that states none of the spatial keys keeps today's plane model:
    the rotor and the gondola at the top, no couple unbalance, no tilt spring (the rotor
    tilts with the gondola), one horizontal ground-motion component along the rotor's
    plane; the structural damping ratio's default is EN 1991-1-4 Table F.2's log
    decrement 0.012 for a welded steel stack, over 2 pi."""
    s = load_scene("sommerfeld")
    assert (s.rotor.height, s.gondola.height, s.rotor.couple_unbalance) == (0.0, 0.0, 0.0)
    assert s.rotor.diametral_inertia is None and s.shaft.tilt_stiffness is None and s.shaft.axial_stiffness is None
    assert (s.excitation.components, s.excitation.angle, s.modal_model.planes) == (1, 0.0, "auto")
    assert s.pillar.damping_ratio == pytest.approx(0.012 / (2 * 3.141592653589793), rel=1e-12)


@pytest.mark.parametrize("sets, key, rng", BAD, ids=[b[1] + ":" + b[2] for b in BAD])
def test_bad_values_are_refused_with_key_and_range(sets, key, rng):
    with pytest.raises(SceneError) as err:
        load_scene("paper", sets)
    msg = str(err.value)
    assert "\n" not in msg and key in msg and rng in msg


def test_missing_file_and_bad_toml(tmp_path):
    with pytest.raises(SceneError, match="not found"):
        load_scene(tmp_path / "nope.toml")
    with pytest.raises(SceneError, match="no such file or embedded scene"):
        load_scene("no-such-scene")
    bad = tmp_path / "bad.toml"
    bad.write_text("[pillar\nheight = 1")
    with pytest.raises(SceneError, match="not valid TOML"):
        load_scene(bad)


def test_missing_key_and_section(tmp_path):
    from rotorpillar.scene import read_scene_toml, scene_from_dict

    data, _ = read_scene_toml("paper")
    del data["rotor"]["inertia"]
    with pytest.raises(SceneError, match=r"rotor.inertia: missing"):
        scene_from_dict(data)
    data, _ = read_scene_toml("paper")
    del data["shaft"]
    with pytest.raises(SceneError, match=r"\[shaft\]: missing section"):
        scene_from_dict(data)


def test_scene_file_round_trip(tmp_path):
    from importlib import resources

    text = resources.files("rotorpillar.scenes").joinpath("paper.toml").read_text()
    f = tmp_path / "mine.toml"
    f.write_text(text.replace("eccentricity = 0.002", "eccentricity = 0.004"))
    s = load_scene(f)
    assert s.rotor.eccentricity == 0.004 and s.name == "paper"  # the file's own name wins
