"""`rotorpillar modal`: the files and fields others rely on, MPI, failures.

- modal.json carries the contract fields (modes / modes_with_top with omega,
  frequency_hz, kind, n_circumferential, normalisation, modal_mass,
  modal_stiffness; reduction; mesh; axes; timings of mesh, assembly,
  solve), ascending frequencies, and frequency_hz = omega / 2 pi exactly.
- modes_bare.vtu / modes_top.vtu hold one 3-vector point array per mode, in
  modal.json's order; a "unit_tip" bending mode has mean top-node
  displacement 1 in its direction (1e-3: the normalisation's own average
  over the top section may weight the nodes otherwise), a "unit_max" mode
  max |u| <= 1.  The cells are the quadratic ones (VTK 29, triquadratic
  hexahedra), one point per node of the P2 space (dofs / 3), in VTK's node
  order, on the tube (tests/fixtures.check_tube_vtu says how and to what
  tolerance).
- MPI: `mpirun -n 2` gives the serial frequencies to 1e-8 (eigenpairs to
  a residual of 1e-8, frequencies within ~5e-10 of the exact ones; MUMPS
  round-off differs between the two factorisations) and the
  same kinds and tip reduction (1e-7).
- Failures: bad mesh input exits 2, a SLEPc failure (forced by PETSc
  options) or a Gmsh crash exits 1, each with one line naming what failed,
  and nothing is written.
- reduction.source = "fem3d": analyze uses the 3D tip reduction.
"""

import json
import math
import os
import shutil
import stat

import numpy as np
import pytest
from conftest import cli, cli_here

from rotorpillar import records

SMALL = ["--set", "mesh.elements_around=16", "--set", "mesh.elements_along=4", "--set", "modal.n_modes=8"]


@pytest.fixture(scope="module")
def small_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("modal")
    # in this process (conftest.cli_here): the serial run the contract and mpirun's ranks are
    # checked against; a child added only its start-up and dolfinx's imports
    p = cli_here("modal", "paper", *SMALL, "--out", out)
    assert p.returncode == 0, p.stderr
    return out, json.loads((out / "modal.json").read_text()), p.stdout


@pytest.mark.slow  # the 3D modal command
def test_modal_json_contract(small_run):
    out, doc, stdout = small_run
    assert {"modes", "modes_with_top", "reduction", "mesh", "axes", "timings", "top"} <= doc.keys()
    for key in ("modes", "modes_with_top"):
        modes = doc[key]
        assert len(modes) == 8
        w = [m["omega"] for m in modes]
        assert w == sorted(w)
        for m in modes:
            assert m["frequency_hz"] == pytest.approx(m["omega"] / (2 * math.pi), rel=1e-14)
            assert m["kind"] in ("bending_x", "bending_y", "ovalling", "torsion", "axial", "breathing", "other")
            assert m["normalisation"] == ("unit_tip" if m["kind"].startswith("bending") else "unit_max")
            # to 1e-7: a degenerate pair shares the mean of its two quotients
            assert m["modal_stiffness"] == pytest.approx(m["omega"] ** 2 * m["modal_mass"], rel=1e-7)
            if m["kind"] == "ovalling":
                assert m["n_circumferential"] >= 2
    red = doc["reduction"]
    assert red["tip_stiffness"] == pytest.approx(red["m_reduced"] * red["omega_bending"] ** 2)
    assert red["omega_bending"] == doc["modes"][0]["omega"]
    assert {"cells", "dofs", "cell_type", "degree"} <= doc["mesh"].keys()
    assert doc["mesh"]["cells"] == 16 * 4
    assert {"mesh", "assembly", "solve"} <= doc["timings"].keys()
    assert "Bare tube" in stdout and "Tip reduction" in stdout
    first_top = doc["modes_with_top"][0]
    assert first_top["pillar_modal_mass"] == pytest.approx(first_top["modal_mass"] - 2300.0)


@pytest.mark.slow  # the 3D modal command
def test_modal_json_round_trips_through_its_record(small_run):
    # modal.json as `modal` wrote it, read through ModalSummary and written back: the
    # same document, key for key and in the same order (the record loses nothing and adds
    # nothing); what the command writes beside the record (scene, files, versions) is left out
    import msgspec

    from rotorpillar.chain import PillarModel
    from rotorpillar.fem3d.modal import ModeRow
    from rotorpillar.fem3d.modal_summary import ModalSummary, ModalTop, ShellModes

    _, doc, _ = small_run
    names = {f.encode_name for f in msgspec.structs.fields(ModalSummary)}
    mine = {k: v for k, v in doc.items() if k in names}
    back = records.convert(doc, ModalSummary)
    assert json.dumps(records.to_builtins(back)) == json.dumps(mine)
    # typed to the leaves: rows, sections and the chain's pillar model are records
    assert all(isinstance(r, ModeRow) for r in back.modes + back.modes_with_top)
    assert isinstance(back.top, ModalTop) and isinstance(back.pillar_model, PillarModel)
    assert isinstance(back.shell_modes_below_second_bending.bare, ShellModes)
    assert back.reduction.omega_bending == back.modes[0].omega
    assert back.configurations.bare.solver.ranks == 1


@pytest.mark.slow  # the 3D modal command
def test_mode_shape_files(small_run):
    meshio = pytest.importorskip("meshio")
    out, doc, _ = small_run
    for key, name in (("modes", "modes_bare.vtu"), ("modes_with_top", "modes_top.vtu")):
        m = meshio.read(out / name)
        names = sorted(k for k in m.point_data if k.startswith("mode_"))
        assert names == [f"mode_{i:03d}" for i in range(len(doc[key]))]
        top = np.isclose(m.points[:, 2], doc["scene"]["pillar"]["height"])
        for i, mode in enumerate(doc[key]):
            u = m.point_data[f"mode_{i:03d}"]
            assert u.shape == (len(m.points), 3)
            if mode["normalisation"] == "unit_tip":
                axis = 0 if mode["kind"] == "bending_x" else 1
                assert u[top, axis].mean() == pytest.approx(1.0, rel=1e-3)
            else:
                assert np.linalg.norm(u, axis=1).max() <= 1 + 1e-12


@pytest.mark.slow  # the 3D modal command
def test_mode_shapes_are_on_the_quadratic_cells(small_run):
    import fixtures

    out, doc, _ = small_run
    p = doc["scene"]["pillar"]
    for name in ("modes_bare.vtu", "modes_top.vtu"):
        got = fixtures.check_tube_vtu(
            out / name, p["height"], p["outer_diameter"] / 2, p["inner_diameter"] / 2, around=16, through=1
        )
        assert got["vtk_type"] == 29 and got["order"] == 2
        assert got["points"] == doc["mesh"]["dofs"] // 3


def mpirun_prefix():
    exe = shutil.which("mpirun")
    if exe is None:
        pytest.skip("mpirun not installed")
    env = dict(os.environ)
    if os.geteuid() == 0:  # Open MPI refuses root unless told
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return [exe, "-n", "2"], env


@pytest.mark.slow
@pytest.mark.mpi
def test_mpi_two_ranks_equal_serial(tmp_path, small_run):
    prefix, env = mpirun_prefix()
    p = cli("modal", "paper", *SMALL, "--out", tmp_path, "--json", env=env, prefix=prefix)
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)  # rank 0 alone prints: one JSON document
    serial = small_run[1]
    for key in ("modes", "modes_with_top"):
        a = np.array([m["omega"] for m in serial[key]])
        b = np.array([m["omega"] for m in doc[key]])
        assert np.allclose(b, a, rtol=1e-8)
        assert [m["kind"] for m in doc[key]] == [m["kind"] for m in serial[key]]
    assert doc["reduction"]["m_reduced"] == pytest.approx(serial["reduction"]["m_reduced"], rel=1e-7)
    assert doc["configurations"]["bare"]["solver"]["ranks"] == 2


@pytest.mark.parametrize(
    "sets, key",
    [
        (["mesh.elements_around=0"], "mesh.elements_around"),
        (["mesh.elements_through=-2"], "mesh.elements_through"),
        (["mesh.grading=0.5"], "mesh.grading"),
        (["pillar.inner_diameter=0"], "pillar.inner_diameter"),
        (["mesh.cell_type=prism"], "mesh.cell_type"),
    ],
)
def test_bad_mesh_input_exits_2_and_writes_nothing(tmp_path, sets, key):
    out = tmp_path / "out"
    args = [a for s in sets for a in ("--set", s)]
    p = cli_here("modal", "paper", *args, "--out", out)  # in this process (conftest.cli_here)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and key in lines[0]
    assert not out.exists()


@pytest.mark.slow  # the 3D modal command
def test_slepc_failure_exits_1_and_writes_nothing(tmp_path):
    out = tmp_path / "out"
    env = dict(os.environ, PETSC_OPTIONS="-modal_eps_max_it 1 -modal_eps_ncv 12")
    p = cli("modal", "paper", *SMALL, "--out", out, env=env)
    assert p.returncode == 1
    lines = [l for l in p.stderr.strip().splitlines() if not l.startswith("[rotorpillar]")]
    assert len(lines) == 1 and "SLEPc" in lines[0]
    assert not out.exists()


def test_gmsh_crash_exits_1_and_writes_nothing(tmp_path, monkeypatch, capsys):
    from rotorpillar import cli as cli_module

    fake = tmp_path / "crashing-python"
    fake.write_text("#!/bin/sh\nkill -SEGV $$\n")
    fake.chmod(fake.stat().st_mode | stat.S_IEXEC)
    monkeypatch.setattr("rotorpillar.mesh.isolated.sys.executable", str(fake))
    out = tmp_path / "out"
    code = cli_module.main(
        ["modal", "paper", "--set", "mesh.elements_around=12", "--set", "mesh.elements_along=3", "--out", str(out)]
    )
    err = capsys.readouterr().err
    assert code == 1
    lines = [l for l in err.strip().splitlines() if not l.startswith("[rotorpillar]")]
    assert len(lines) == 1 and "Gmsh" in lines[0] and "signal" in lines[0]
    assert not out.exists()


@pytest.mark.slow  # the 3D modal command
def test_analyze_takes_the_3d_reduction(tmp_path, small_run):
    # in this process (conftest.cli_here); the modal run it is checked against is the fixture's
    # child process, so the two reductions are two solves, not one cached result
    p = cli_here("analyze", "paper", *SMALL, "--set", "reduction.source=fem3d", "--json", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    red = json.loads(p.stdout)["paper_model"]["reduction"]
    assert red["tip_mass_source"] == red["tip_stiffness_source"] == "fem3d"
    modal = small_run[1]["reduction"]
    assert red["tip_mass"] == pytest.approx(modal["m_reduced"], rel=1e-8)
    assert red["tip_stiffness"] == pytest.approx(modal["tip_stiffness"], rel=1e-8)
