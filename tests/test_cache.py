"""The one disk cache (rotorpillar.cache) and the three caches built on it.

Checked: a hit returns what was written; a changed argument, layout version
or source file is a miss; a damaged entry (cut short, not JSON, not an object,
another key, refused by the caller) is a miss and is overwritten by the next
write; a write that fails leaves the previous entry whole and no partial file.
Through the users: the convergence study's run cache recomputes exactly the
damaged run (and, by test_converge.py, resumes after an interruption), a design
study's batch key follows its spec and code, and the chain's modes key follows
the mesh.
"""

import json

import pytest

from rotorpillar.cache import DiskCache, cache_key, source_hash, user_cache_root
from rotorpillar.records import Record


class Run(Record):
    """A cached result as the tests store it."""

    omega: float
    modes: tuple[float, ...] = ()
    status: str = "ok"


def test_hit_after_write_and_miss_before(tmp_path):
    cache = DiskCache(tmp_path / "runs")
    key = cache_key({"elements": 8, "theory": "euler"}, version=1, code="c0")
    assert cache.read(key, Run) is None  # nothing on disk yet
    path = cache.write(key, Run(2.5, (1.0, 2.0)))
    assert path == cache.path(key) and path.parent == tmp_path / "runs"
    assert cache.read(key, Run) == Run(2.5, (1.0, 2.0))
    assert next(iter(json.loads(path.read_text()))) == "key"  # the key first


def test_the_key_follows_arguments_version_and_code():
    args = {"elements": 8, "pillar": {"height": 20.0, "density": 8100.0}}
    k = cache_key(args, version=1, code="c0")
    assert k == cache_key(dict(reversed(list(args.items()))), version=1, code="c0")  # order-free
    assert k != cache_key({**args, "elements": 16}, version=1, code="c0")
    assert k != cache_key(args, version=2, code="c0")
    assert k != cache_key(args, version=1, code="c1")


def test_source_hash_follows_the_files(tmp_path):
    a, b = tmp_path / "a.py", tmp_path / "b.py"
    a.write_text("x = 1\n")
    b.write_text("y = 2\n")
    h = source_hash([a, b])
    assert h == source_hash([a, b, tmp_path / "missing.py"])  # a missing file is skipped
    b.write_text("y = 3\n")
    assert source_hash([a, b]) != h


@pytest.mark.parametrize(
    "damage",
    [
        '{"key": "',
        "not json",
        "[1, 2]",
        "null",
        '{"key": "another", "value": {"omega": 1.0}}',  # another key's entry
        '{"key": "KEY", "omega": 1.0}',  # an older layout (before records): recomputed once
        '{"key": "KEY", "value": {"omega": "fast"}}',  # a field of the wrong type
        "",
    ],
)
def test_a_damaged_entry_is_a_miss_and_is_rewritten(tmp_path, damage):
    cache = DiskCache(tmp_path)
    key = cache_key({"n": 1}, version=1, code="c")
    cache.path(key).write_text(damage.replace("KEY", key))
    assert cache.read(key, Run) is None
    cache.write(key, Run(1.0))
    assert cache.read(key, Run) == Run(1.0)


def test_accept_refuses_an_entry_the_caller_cannot_use(tmp_path):
    cache = DiskCache(tmp_path)
    cache.write("k", Run(1.0, status="failed"))
    assert cache.read("k", Run) is not None
    assert cache.read("k", Run, accept=lambda r: r.status == "ok") is None


def test_a_failed_write_keeps_the_previous_entry(tmp_path):
    cache = DiskCache(tmp_path)
    cache.write("k", Run(1.0))
    with pytest.raises(NotImplementedError):
        cache.write("k", {"omega": object()})  # not serialisable
    assert cache.read("k", Run) == Run(1.0)
    assert [p.name for p in tmp_path.iterdir()] == ["k.json"]  # no partial file


def test_user_cache_root(monkeypatch, tmp_path):
    monkeypatch.setenv("ROTORPILLAR_CACHE", str(tmp_path / "rp"))
    assert user_cache_root() == tmp_path / "rp"
    monkeypatch.delenv("ROTORPILLAR_CACHE")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert user_cache_root() == tmp_path / "xdg" / "rotorpillar"


def test_converge_recomputes_exactly_a_damaged_run(tmp_path):
    from rotorpillar import converge as cv
    from rotorpillar.scene import load_scene

    scene = load_scene("paper")
    cases = [c for c in cv.ladder(scene) if cv.FAMILIES[c.family].model == "beam"][:4]
    first = cv.run_study(cases, scene, tmp_path, progress=False)
    key = cv.case_key(cases[1], scene.pillar, scene.modal.tolerance)
    path = tmp_path / f"{key}.json"
    path.write_text(path.read_text()[:40])  # cut short
    ran = []

    def counting(case, sc):
        ran.append(case.label)
        return cv.run_point(case, sc)

    again = cv.run_study(cases, scene, tmp_path, runner=counting, progress=False)
    assert ran == [cases[1].label]
    assert [r.cached for r in again] == [True, False, True, True]
    assert again[1].bending == first[1].bending  # the same run, recomputed
    assert json.loads(path.read_text())["value"]["status"] == "ok"  # and cached again


def test_study_batch_key_follows_spec_and_code():
    from rotorpillar.records import replace
    from rotorpillar.studies.batch import BatchSpec, PlannedRun
    from rotorpillar.studies.study import batch_key

    spec = BatchSpec({"name": "paper"}, "runup", "paper", {}, (PlannedRun(0, {"a": 1}),))
    k = batch_key(spec, "src")
    assert k == batch_key(replace(spec), "src")
    assert k != batch_key(replace(spec, case="sweep"), "src")
    assert k != batch_key(spec, "src2")


def test_chain_modes_key_follows_the_mesh_and_the_tolerance():
    from rotorpillar.chain.modes import modes_key
    from rotorpillar.scene import load_scene, override

    scene = load_scene("paper")
    mesh = {"elements_around": 32, "elements_along": 10}
    k = modes_key(scene, mesh)
    assert k == modes_key(scene, dict(mesh))
    assert k != modes_key(scene, {**mesh, "elements_around": 64})
    assert k != modes_key(override(scene, ["modal.tolerance=1e-10"]), mesh)
    # the drive does not change the pillar's modes
    assert k == modes_key(override(scene, ["rotor.mass=2000"]), mesh)
    # nor does the structural damping ratio: a label on each mode, set as they are read
    assert k == modes_key(override(scene, ["pillar.damping_ratio=0.03"]), mesh)
    assert k != modes_key(override(scene, ["pillar.density=7000"]), mesh)


def test_the_run_cache_hashes_files_that_exist():
    """A module renamed under the run cache's lists would silently leave (or join) a key."""
    from pathlib import Path

    from rotorpillar.converge import runner

    root = Path(runner.__file__).parent.parent
    for name in (runner.SHELL_MODEL, runner.SHELL_MESH, *runner.SHELL_SOLVER):
        assert (root / (name.replace(".", "/") + ".py")).exists(), name
    for name in runner.SOLID_CONSUMERS:
        assert (root / "fem3d" / f"{name}.py").exists(), name
    shell, solid = runner._source_files("shell"), runner._source_files("solid")
    assert all(f.exists() for f in shell + solid)
    assert root / "fem3d" / "eigensolver.py" in shell and root / "fem3d" / "naghdi.py" not in solid
