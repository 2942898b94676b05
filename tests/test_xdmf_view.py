"""The XDMF time series' linear view of the quadratic fields (rotorpillar.fem3d.xdmf_view).

Sources and tolerances
----------------------
- A quadratic field (x**2, y z, z) and x z + y**2, interpolated on the tube's degree-2
  space, is exact at the space's nodes; the view copies those nodal values onto the
  linear mesh through the same nodes, so at every node of the linear mesh the view's
  values are the analytic ones to round-off (1e-12 relative to the field's size: the
  coordinates are ~20 m, their squares ~400).
- The linear mesh has 8 cells a quadratic cell and one node a node of the space, and
  its cells are whole hexahedra: its volume is the quadratic tube's less the chords'
  shortfall, which for 16 elements around (32 nodes on each circle) is
  1 - sin(2 pi / 32) / (2 pi / 32) = 0.641 % of it (the inscribed polygon against
  the circle).  Measured 0.636 %: within 2 % of that share, the quadratic cells' arcs
  being close to, not on, the circle; a cell with its corners out of order would not be.
- The XDMF file then names linear hexahedra, and both fields at each time.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorpillar.scene import load_scene
from rotorpillar.scene.sections import Mesh


@pytest.fixture(scope="module")
def fields():
    from dolfinx import fem

    from rotorpillar.fem3d import assemble_pillar

    scene = load_scene("paper")
    model = assemble_pillar(scene, top=True, mesh=Mesh(elements_around=16, elements_along=4))
    u = fem.Function(model.V, name="displacement")
    vm = fem.Function(fem.FunctionSpace(model.mesh, ("Lagrange", 2)), name="von_mises")
    u.interpolate(lambda x: np.stack([x[0] ** 2, x[1] * x[2], x[2]]))
    vm.interpolate(lambda x: x[0] * x[2] + x[1] ** 2)
    return model, u, vm


def test_the_linear_view_holds_the_quadratic_fields_nodal_values(fields):
    from rotorpillar.fem3d.xdmf_view import linear_view

    model, u, vm = fields
    view = linear_view(u, vm)
    assert view is not None
    cells = model.mesh.topology.index_map(3).size_local
    assert view.mesh.topology.index_map(3).size_local == 8 * cells
    assert view.mesh.geometry.x.shape[0] == vm.function_space.dofmap.index_map.size_local
    import ufl
    from dolfinx import fem

    volume = [fem.assemble_scalar(fem.form(1.0 * ufl.dx(domain=m))) for m in (model.mesh, view.mesh)]
    chords = 1.0 - np.sin(2 * np.pi / 32) / (2 * np.pi / 32)
    assert 1.0 - volume[1] / volume[0] == pytest.approx(chords, rel=0.02)
    view.vector.x.array[:] = 0.0  # written by write() below, from the quadratic fields
    view.scalar.x.array[:] = 0.0

    class NoFile:
        def write_function(self, f, t):
            pass

    view.write(NoFile(), 0.0, u, vm)
    X = view.vector.function_space.tabulate_dof_coordinates()
    expected = np.stack([X[:, 0] ** 2, X[:, 1] * X[:, 2], X[:, 2]], axis=1)
    np.testing.assert_allclose(
        view.vector.x.array.reshape(-1, 3), expected, rtol=0, atol=1e-12 * np.abs(expected).max()
    )
    Xs = view.scalar.function_space.tabulate_dof_coordinates()
    scalar = Xs[:, 0] * Xs[:, 2] + Xs[:, 1] ** 2
    np.testing.assert_allclose(view.scalar.x.array, scalar, rtol=0, atol=1e-12 * np.abs(scalar).max())


def test_the_time_series_is_written_on_the_linear_view(fields, tmp_path):
    from rotorpillar.fem3d.stress import VonMisesProjection, _Writer

    model, _, _ = fields
    scene = load_scene("paper")
    projection = VonMisesProjection(model, scene.pillar, 0.0)
    writer = _Writer(tmp_path / "run.xdmf", model, projection)
    assert writer.view is not None
    for t in (0.0, 0.5):
        writer.write(t, projection)
    writer.close()
    text = (tmp_path / "run.xdmf").read_text()
    assert 'TopologyType="Hexahedron"' in text and "Hexahedron_27" not in text
    assert text.count('Name="displacement"') >= 2 and text.count('Name="von_mises"') >= 2
    assert (tmp_path / "run.h5").is_file()
