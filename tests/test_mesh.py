"""The Gmsh tube builder: counts, geometry, symmetry, bad input, crash isolation.

References are exact: a structured tube of N x L x T hexahedra (6 tetrahedra
each) has (N p)(L p + 1)(T p + 1) nodes at degree p; every node lies on
r in [r_i, r_o], z in [0, H]; second-order nodes sit on their circles to
round-off (1e-12 m), because the builder maps them from the vertices in
cylindrical coordinates; a mesh with N % 4 == 0 is invariant under a quarter
turn (node sets equal to 1e-9 m: Gmsh spaces the arc nodes to ~1e-10 m).  A crash of the meshing child process
(here a stand-in that kills itself with SIGSEGV) must surface as one
ComputationError naming Gmsh, not kill the caller.
"""

import math
import os
import stat

import numpy as np
import pytest

from rotorpillar.errors import ComputationError, InputError
from rotorpillar.mesh import BASE, TOP, WALL, TubeMeshParams, layer_heights, tube_mesh_data, tube_params
from rotorpillar.scene import Mesh, load_scene


def params(**kw):
    base = dict(
        height=20.0,
        outer_radius=1.0,
        inner_radius=0.98,
        elements_around=16,
        elements_along=6,
        elements_through=2,
        order=2,
        cell_type="hexahedron",
        grading=5.0,
    )
    base.update(kw)
    return TubeMeshParams(**base)


@pytest.mark.parametrize(
    "cell_type, order", [("hexahedron", 1), ("hexahedron", 2), ("tetrahedron", 1), ("tetrahedron", 2)]
)
def test_counts_and_geometry(cell_type, order):
    p = params(cell_type=cell_type, order=order)
    d = tube_mesh_data(p, isolated=False)
    N, L, T = p.elements_around, p.elements_along, p.elements_through
    assert len(d.cells) == (N * L * T if cell_type == "hexahedron" else 6 * N * L * T)
    assert len(d.points) == (N * order) * (L * order + 1) * (T * order + 1)
    assert d.cell_type == cell_type and d.order == order
    r = np.hypot(d.points[:, 0], d.points[:, 1])
    layers = p.inner_radius + (p.outer_radius - p.inner_radius) * np.arange(T * order + 1) / (T * order)
    assert np.min(np.abs(r[:, None] - layers[None, :]), axis=1).max() < 1e-12
    assert d.points[:, 2].min() == pytest.approx(0, abs=1e-12)
    assert d.points[:, 2].max() == pytest.approx(p.height, abs=1e-12)
    faces = 1 if cell_type == "hexahedron" else 2
    counts = np.bincount(d.facet_markers, minlength=4)
    assert counts[BASE] == counts[TOP] == faces * N * T
    assert counts[WALL] == faces * 2 * N * L
    # every cell has positive volume on the sampled corner-tetrahedron test
    c = d.points[d.corner_cells()]
    v = np.einsum(
        "ij,ij->i",
        np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]),
        c[:, 3 if cell_type == "tetrahedron" else 4] - c[:, 0],
    )
    assert np.all(np.abs(v) > 0)


def test_quarter_turn_symmetry_and_grading():
    p = params(elements_around=16)
    d = tube_mesh_data(p, isolated=False)
    from scipy.spatial import cKDTree

    rot = d.points @ np.array([[0, 1, 0], [-1, 0, 0], [0, 0, 1.0]])
    dist, _ = cKDTree(d.points).query(rot)
    assert dist.max() < 1e-9  # Gmsh spaces the arc nodes to ~1e-10 m
    z = np.unique(np.round(d.points[:, 2], 9))
    first, last = z[2] - z[0], z[-1] - z[-3]  # degree 2: 2 node spacings per cell
    assert last / first == pytest.approx(p.grading, rel=1e-6)
    assert layer_heights(p)[-1] == pytest.approx(1.0)


def test_isolated_equals_in_process():
    p = params(elements_along=3)
    a, b = tube_mesh_data(p, isolated=True), tube_mesh_data(p, isolated=False)
    assert np.array_equal(a.cells, b.cells) and np.allclose(a.points, b.points, atol=0)
    assert np.array_equal(a.facet_markers, b.facet_markers)


@pytest.mark.parametrize(
    "kw, key",
    [
        (dict(elements_around=0), "mesh.elements_around"),
        (dict(elements_along=0), "mesh.elements_along"),
        (dict(elements_through=-1), "mesh.elements_through"),
        (dict(height=-20.0), "pillar.height"),
        (dict(outer_radius=0.0), "pillar.outer_diameter"),
        (dict(inner_radius=0.0), "pillar.inner_diameter"),
        (dict(inner_radius=1.5), "pillar.inner_diameter"),
        (dict(grading=0.5), "mesh.grading"),
        (dict(cell_type="prism"), "mesh.cell_type"),
        (dict(elements_around=2.5), "mesh.elements_around"),
    ],
)
def test_bad_input_is_refused_in_one_line(kw, key):
    with pytest.raises(InputError) as err:
        params(**kw)
    msg = str(err.value)
    assert key in msg and "\n" not in msg


def test_scene_mesh_section_maps_to_params():
    s = load_scene("paper")
    p = tube_params(s.pillar, Mesh(elements_around=8, elements_along=2))
    assert (p.outer_radius, p.inner_radius, p.height) == (1.0, 0.98, 20.0)
    assert (p.elements_around, p.elements_along) == (8, 2)


def test_a_gmsh_crash_is_an_error_not_a_dead_process(tmp_path, monkeypatch):
    fake = tmp_path / "crashing-python"
    fake.write_text("#!/bin/sh\nkill -SEGV $$\n")
    fake.chmod(fake.stat().st_mode | stat.S_IEXEC)
    monkeypatch.setattr("rotorpillar.mesh.isolated.sys.executable", str(fake))
    with pytest.raises(ComputationError) as err:
        tube_mesh_data(params(), isolated=True)
    msg = str(err.value)
    assert "Gmsh" in msg and "signal 11" in msg and "\n" not in msg
    assert os.getpid() > 0 and math.isfinite(1.0)  # we are still here


def test_a_kept_mesh_is_the_arrays_gmsh_gives_and_a_damaged_one_is_meshed_again(tmp_path, monkeypatch):
    """The kept tube (rotorpillar.mesh.cached_tube_mesh_data) is the very arrays a Gmsh run
    gives (exactly: npz is lossless), read back without a Gmsh run; other parameters are
    another file; a damaged file is meshed again and rewritten whole."""
    from rotorpillar.mesh import isolated

    monkeypatch.setenv("ROTORPILLAR_CACHE", str(tmp_path))
    runs = []

    def counted(p, *, isolated=True):
        runs.append(p)
        return tube_mesh_data(p, isolated=False)

    monkeypatch.setattr(isolated, "tube_mesh_data", counted)
    p = params(elements_along=3)
    first = isolated.cached_tube_mesh_data(p)
    again = isolated.cached_tube_mesh_data(p)
    fresh = tube_mesh_data(p, isolated=False)
    assert len(runs) == 1
    for d in (first, again):
        assert np.array_equal(d.points, fresh.points) and np.array_equal(d.cells, fresh.cells)
        assert np.array_equal(d.facets, fresh.facets) and np.array_equal(d.facet_markers, fresh.facet_markers)
        assert (d.gmsh_cell, d.gmsh_facet) == (fresh.gmsh_cell, fresh.gmsh_facet)
    other = params(elements_along=4)
    assert isolated.kept_mesh_path(other) != isolated.kept_mesh_path(p)
    assert len(isolated.cached_tube_mesh_data(other).cells) == other.cells and len(runs) == 2
    path = isolated.kept_mesh_path(p)
    path.write_bytes(path.read_bytes()[:100])  # cut short
    assert np.array_equal(isolated.cached_tube_mesh_data(p).cells, fresh.cells) and len(runs) == 3
    assert np.array_equal(isolated.MeshData.from_bytes(path.read_bytes()).cells, fresh.cells)
