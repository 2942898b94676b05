"""The convergence study's serving process (rotorpillar.converge.service).

Its runs give what a fresh process gives: the same frequencies (bit for
bit: the same code on the same inputs; the run does not see the run
before), and a peak memory within 15 % of the fresh process's ru_maxrss
(the estimate is imports + the run's own growth of the resident set; 15 %
covers what a fresh process's allocator keeps that a reused one does not,
measured at 3-10 % on the paper's ladder).  A run that raises is reported
and the process serves on; a process that dies is reported with the end of
its stderr, and the next run gets a new one.
"""

import json
import subprocess
import sys

import pytest

from rotorpillar.converge.ladder import ladder
from rotorpillar.converge.service import Service, reset_peak_memory
from rotorpillar.scene import load_scene


def _case_file(tmp_path, case, scene, name):
    f = tmp_path / f"{name}.json"
    f.write_text(
        json.dumps({"family": case.family, "level": case.level, "params": list(case.params), "scene": scene.to_dict()})
    )
    return f


@pytest.mark.slow  # shell and 3D runs, served and fresh
def test_served_runs_equal_fresh_runs_and_failures_are_reported(tmp_path):
    # Linux 4.0+: the per-run high-water mark; without it the process serves one run
    reused = reset_peak_memory()
    scene = load_scene("paper")
    cases = {(c.family, c.level): c for c in ladder(scene)}
    small = [cases["shell_quad", 8], cases["solid_hex_p1", 32]]
    fresh = []
    for i, c in enumerate(small):
        out = tmp_path / f"fresh{i}.out.json"
        subprocess.run(
            [sys.executable, "-m", "rotorpillar.converge", str(_case_file(tmp_path, c, scene, f"fresh{i}")), str(out)],
            check=True,
        )
        fresh.append(json.loads(out.read_text()))
    s = Service()
    try:
        bad = tmp_path / "bad.json"
        bad.write_text(json.dumps({"family": "no_such_family", "level": 1, "params": [], "scene": scene.to_dict()}))
        reply = s.run(bad, tmp_path / "bad.out.json")
        assert reply.status == "error" and "no_such_family" in reply.error
        # the same process serves on; or, serving one run only, its successor is started at once
        assert s.proc is not None and s.proc.poll() is None
        pid = s.proc.pid if reused else None
        for i, (c, ref) in enumerate(zip(small, fresh)):
            out = tmp_path / f"served{i}.out.json"
            assert s.run(_case_file(tmp_path, c, scene, f"served{i}"), out).status == "ok"
            got = json.loads(out.read_text())
            assert (got["bending"], got["ovalling"]) == (ref["bending"], ref["ovalling"])
            assert got["peak_memory"] == pytest.approx(ref["peak_memory"], rel=0.15)
        if reused:
            assert s.proc.pid == pid
            s.proc.kill()  # dead between runs: replaced
            s.proc.wait()
        reply = s.run(_case_file(tmp_path, small[0], scene, "again"), tmp_path / "again.out.json")
        assert reply.status == "ok" and (not reused or s.proc.pid != pid)
    finally:
        s.close()
    assert s.proc is None


def test_a_process_that_dies_in_a_run_is_reported_with_its_stderr(tmp_path, monkeypatch):
    s = Service()
    start = Service._start

    def dying(self):
        start(self)
        self.proc.kill()
        self.proc.wait()
        self.proc = subprocess.Popen(
            [sys.executable, "-c", "import sys; sys.stderr.write('boom')"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self.log,
            text=True,
        )

    monkeypatch.setattr(Service, "_start", dying)
    try:
        reply = s.run(tmp_path / "case.json", tmp_path / "out.json")
        assert reply.status == "error" and "worker ended" in reply.error and "boom" in reply.error
        assert s.proc is None
    finally:
        s.close()


def test_what_a_run_prints_stays_out_of_the_replies(tmp_path):
    """A library printing to stdout (Python or C) must not break the protocol:
    the serving process answers on its original stdout and sends fd 1 to stderr."""
    import textwrap

    script = tmp_path / "noisy.py"
    script.write_text(
        textwrap.dedent("""
        import os, sys
        from rotorpillar.converge import runner
        def noisy(case_file, out_file, baseline, *, per_run_peak):
            print("python noise")
            os.write(1, b"C noise\\n")
            open(out_file, "w").write("{}")
        runner.run_one = noisy
        runner.import_models = lambda: 0
        sys.exit(runner.serve())
    """)
    )
    p = subprocess.run(
        [sys.executable, str(script)],
        input='{"case": "c", "out": "%s"}\n' % (tmp_path / "o.json"),
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert p.returncode == 0
    reply = json.loads(p.stdout)  # the reply alone on stdout
    assert reply["status"] == "ok" and "python noise" in p.stderr and "C noise" in p.stderr


@pytest.mark.slow  # three 3D runs in this process (1.2 s)
def test_a_compilation_seen_in_the_cache_leaves_the_runs_peak_its_own(tmp_path, monkeypatch):
    # The runner tells a first, compiling run by FFCx's cache growing, and times the run
    # again warm.  Another process compiling into the same cache trips that count too; the
    # warm run's peak must then be its own, not the two runs' together (the suite once saw
    # a served peak 19 % above the fresh process's for that reason).
    from rotorpillar.converge import runner

    if not reset_peak_memory():
        pytest.skip("this kernel cannot reset a process's memory high-water mark")
    scene = load_scene("paper")
    case = {(c.family, c.level): c for c in ladder(scene)}["solid_hex_p1", 32]
    job = _case_file(tmp_path, case, scene, "job")
    runner.run_one(str(job), str(tmp_path / "warm.json"), 0, per_run_peak=True)  # compiles if need be
    runner.run_one(str(job), str(tmp_path / "plain.json"), 0, per_run_peak=True)
    counts = iter(range(1000))
    monkeypatch.setattr(runner, "_jit_files", lambda: next(counts))  # every count larger: "compiled"
    runner.run_one(str(job), str(tmp_path / "tripped.json"), 0, per_run_peak=True)
    plain, tripped = (json.loads((tmp_path / f"{n}.json").read_text()) for n in ("plain", "tripped"))
    assert tripped["first_run_with_compilation"] is not None
    # baseline 0: the peaks are the runs' own growth, 6.9-7.0 MB for this case (measured);
    # with the first run's result held through the warm one it was 10.4 MB (+51 %), so
    # 25 % tells the two apart and leaves room for what the allocator keeps between runs
    assert tripped["peak_memory"] == pytest.approx(plain["peak_memory"], rel=0.25)
