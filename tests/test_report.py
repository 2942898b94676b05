"""The HTML report: complete when its inputs exist, honest when they do not,
and a page a real browser opens with every image loaded.

Sources and checks:
- Inputs: a real `rotorpillar analyze paper`; synthetic 3D modes and runs
  (tests/fixtures.py, labelled as such in the page).
- Browser: Debian's Chromium, headless (``--headless --no-sandbox
  --disable-gpu``), on a copy of report.html with a script appended that
  waits for the load event and writes a verdict into the DOM, read back with
  ``--dump-dom``: every <img> complete with naturalWidth > 0, every <video>
  without error and with its metadata (readyState >= 1).  Skipped, with the
  reason, only where Chromium is not installed (tools/setup.sh installs it).
- Links: every src/href/poster is a data: URI that decodes to the type it
  claims, an in-page anchor that exists, or a file that exists beside the page.
- Text: every number the paper prints appears with its flag; hostile text
  in a scene (markup in its description) comes out escaped.
"""

import base64
import json
import re
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path
from types import SimpleNamespace

import fixtures
import pytest
from convergence_doc import convergence_doc
from imagecheck import PNG_SIGNATURE

from rotorpillar import cli

# seconds each: the report of a whole output directory per test; the slow tier runs it
pytestmark = pytest.mark.slow
# In-process pyvista renders (the 3D modes' pictures and animations): the VTK leak check of
# tests/conftest.py runs after each test marked so: every test on ``full`` (whichever of
# them builds it first on a worker) and the broken modes' report.  The reports on an
# analysis alone never call into pyvista or VTK (traced: no call into a pyvista or vtk
# module from their setup, call or teardown): no VTK object of theirs can outlive them,
# and the check's two scans of every Python object were all they paid for it
renders = pytest.mark.renders

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.refs, self.ids, self.imgs, self.videos = [], set(), 0, 0

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "img":
            self.imgs += 1
        if tag == "video":
            self.videos += 1
        for k in ("src", "href", "poster"):
            if a.get(k):
                self.refs.append((tag, k, a[k]))


def parse(path):
    p = _Links()
    p.feed(Path(path).read_text(encoding="utf-8"))
    return p


def run_cli(*args):
    assert cli.main([str(a) for a in args]) == 0


@pytest.fixture(scope="module", autouse=True)
def _pictures_in_this_process():
    """Every report here draws its 3D pictures in this process (parallel.WORKERS = 1), not
    in two worker interpreters started for each report (each imports pyvista and VTK
    anew): the page, its links and its texts are what is checked here, and the workers
    draw what one process draws (test_report_parallel; the main job's report, in
    test_main_job, runs with them).  This module 32.3 -> 20.9 s of CPU (perf task-clock,
    2026-11-29; test_a_broken_input_costs_one_figure_not_the_report alone 11.2 -> 5.6 s)."""
    from rotorpillar.postprocess.report import parallel

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(parallel, "WORKERS", 1)
        yield


@pytest.fixture(scope="module")
def full(tmp_path_factory):
    """A report on every kind of input, with short animations."""
    out = tmp_path_factory.mktemp("full")
    run_cli("analyze", "paper", "--out", out)
    fixtures.write_modal_fixture(out, around=24, along=16)
    for case in ("runup", "earthquake"):
        fixtures.write_simulation_fixture(out, case, n=1500)
    # a chart another module wrote, captioned in its JSON
    from rotorpillar.postprocess import transient_charts

    a = fixtures.simulation_arrays("runup", n=500)
    transient_charts.earthquake_chart(
        out / "runup_omega.png",
        a["t"],
        a["ground_acceleration"],
        a["tip_x"],
        a["rotor_x"],
        a["Omega"],
        title="external",
    )
    doc = json.loads((out / "simulate_runup.json").read_text())
    doc["figures"] = [{"file": "runup_omega.png", "caption": "Omega(t) of the run-up <external>"}]
    (out / "simulate_runup.json").write_text(json.dumps(doc))
    run_cli("report", "paper", "--out", out, "--max-frames", 8)
    return out


@renders
def test_report_links_only_existing_files(full):
    page = parse(full / "report.html")
    assert page.imgs >= 10 and page.videos == 2
    for tag, attr, ref in page.refs:
        if ref.startswith("data:"):
            mime, b64 = re.match(r"data:([\w/+.-]+);base64,(.*)", ref, re.S).groups()
            raw = base64.b64decode(b64, validate=True)
            if mime == "image/png":
                assert raw[:8] == PNG_SIGNATURE
            elif mime == "video/mp4":
                assert raw[4:8] == b"ftyp"
        elif ref.startswith("#"):
            assert ref[1:] in page.ids, ref
        else:
            assert not re.match(r"[a-z]+://", ref), f"external resource {ref}"
            assert (full / ref).is_file(), f"{tag} {attr}={ref} does not exist"


@renders
def test_report_is_complete(full):
    text = (full / "report.html").read_text(encoding="utf-8")
    a = json.loads((full / "analyze.json").read_text())
    import html

    for row in a["paper_comparison"]:
        assert html.escape(row["quantity"]) in text
    assert text.count('<tr class="flag">') == sum(r["flag"] for r in a["paper_comparison"])
    for title in (
        "The answer",
        "modal validation",
        "Eq. 1 against the 3D model",
        "The pillar reduced to its tip",
        "passage through resonance",
        "The runs",
        "The recorded earthquake",
        "the paper&#39;s earthquake case",
        "versions",
    ):
        assert title in text
    assert "Omega(t) of the run-up &lt;external&gt;" in text
    assert "synthetic fixture" in text  # the inputs' own note is shown
    assert "not computed: run <code>rotorpillar converge paper" in text
    doc = json.loads((full / "report.json").read_text())
    # no comparison here: the run-up and the scene's earthquake run (the paper's pulse)
    assert set(doc["animations"]) == {"runup", "earthquake_paper"}
    assert doc["failures"] == {}


def _browser_verdict(page: Path, tmp: Path) -> dict:
    probe = tmp / f"probe_{page.stem}.html"
    script = """<pre id="__verdict">pending</pre><script>
window.addEventListener('load', function () { setTimeout(function () {
  var imgs = Array.prototype.slice.call(document.images);
  var vids = Array.prototype.slice.call(document.querySelectorAll('video'));
  document.getElementById('__verdict').textContent = JSON.stringify({
    images: imgs.length,
    broken: imgs.filter(function (i) { return !(i.complete && i.naturalWidth > 0); })
                .map(function (i) { return i.alt; }),
    videos: vids.length,
    bad_videos: vids.filter(function (v) { return v.error || v.readyState < 1; })
                    .map(function (v) { return (v.error ? v.error.code : 'state ' + v.readyState); }),
    title: document.title});
}, 1000); });
</script></body>"""
    html_text = page.read_text(encoding="utf-8")
    probe.write_text(html_text.replace("</body>", script, 1), encoding="utf-8")
    p = subprocess.run(
        [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--no-first-run",
            "--mute-audio",
            f"--user-data-dir={tmp / 'chromium-profile'}",
            "--virtual-time-budget=15000",
            "--dump-dom",
            probe.resolve().as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=180,
    )
    m = re.search(r'<pre id="__verdict">(.*?)</pre>', p.stdout, re.S)
    assert m, f"no verdict from chromium: {p.stderr[-2000:]}"
    import html

    return json.loads(html.unescape(m.group(1)))


@pytest.mark.skipif(CHROMIUM is None, reason="chromium not installed (tools/setup.sh installs it)")
@renders
def test_report_opens_in_headless_chromium(full, tmp_path):
    v = _browser_verdict(full / "report.html", tmp_path)
    assert v["title"] == "rotorpillar report: paper"
    assert v["images"] == parse(full / "report.html").imgs and v["images"] >= 10
    assert v["broken"] == []
    assert v["videos"] == 2 and v["bad_videos"] == []


@pytest.mark.parametrize("count", ["0", "65"])
def test_report_and_run_refuse_a_picture_count_outside_its_range(tmp_path, count, capsys):
    # report.MODE_PICTURES_RANGE: 1 ... 64 pictures a set; refused before any work, run's too
    assert cli.main(["report", "paper", "--out", str(tmp_path / "report"), "--mode-pictures", count]) == 2
    assert f"--mode-pictures = {count}: must be 1 ... 64" in capsys.readouterr().err
    assert cli.main(["run", "paper", "--out", str(tmp_path / "run"), "--mode-pictures", count]) == 2
    assert f"stage 'report': --mode-pictures = {count}" in capsys.readouterr().err
    assert not (tmp_path / "report").exists() and not (tmp_path / "run").exists()


def test_report_without_inputs_says_what_to_run(tmp_path):
    run_cli("report", "paper", "--out", tmp_path)
    text = (tmp_path / "report.html").read_text(encoding="utf-8")
    for cmd in ("analyze", "modal", "simulate", "converge", "integrators"):
        assert f"not computed: run <code>rotorpillar {cmd} paper --out" in text, cmd
    page = parse(tmp_path / "report.html")
    assert page.imgs == 0 and page.videos == 0
    for _tag, _attr, ref in page.refs:
        assert ref.startswith("#") and ref[1:] in page.ids


def test_hostile_text_is_escaped(tmp_path):
    from rotorpillar.scene import read_scene_toml

    raw = (Path(cli.__file__).parent / "scenes" / "paper.toml").read_text()
    raw = raw.replace('name = "paper"', 'name = "evil"').replace(
        'description = "', 'description = "<script>alert(1)</script> & <b>x</b> ', 1
    )
    scene = tmp_path / "evil.toml"
    scene.write_text(raw)
    assert read_scene_toml(scene)[0]["name"] == "evil"
    run_cli("analyze", scene, "--out", tmp_path / "o")
    run_cli("report", scene, "--out", tmp_path / "o")
    text = (tmp_path / "o" / "report.html").read_text()
    assert "<script>" not in text and "<b>x</b>" not in text
    assert "&lt;script&gt;alert(1)&lt;/script&gt; &amp; &lt;b&gt;x&lt;/b&gt;" in text


@pytest.mark.filterwarnings("ignore:The VTK reader")  # the broken file, on purpose
@renders
def test_a_broken_input_costs_one_figure_not_the_report(tmp_path):
    run_cli("analyze", "paper", "--out", tmp_path)
    fixtures.write_modal_fixture(tmp_path, around=12, along=6)
    (tmp_path / "modes_top.vtu").write_text("not a VTU")
    run_cli("report", "paper", "--out", tmp_path, "--no-animations")
    text = (tmp_path / "report.html").read_text()
    assert "could not be rendered" in text
    doc = json.loads((tmp_path / "report.json").read_text())
    assert "load_modes_top" in doc["failures"]
    assert any("bare_modes_sheet.png" in f for f in doc["figures"])


def test_inputs_from_another_scene_are_flagged(tmp_path):
    run_cli("analyze", "paper", "--out", tmp_path, "--set", "rotor.eccentricity=0.04")
    run_cli("report", "paper", "--out", tmp_path)
    text = (tmp_path / "report.html").read_text()
    assert "computed for a different scene (rotor.eccentricity differ)" in text


def _analyze_without(tmp_path, *path):
    """analyze.json as `analyze` writes it, less the key at ``path`` (as if another
    version wrote it)."""
    run_cli("analyze", "paper", "--out", tmp_path)
    doc = json.loads((tmp_path / "analyze.json").read_text())
    inner = doc
    for key in path[:-1]:
        inner = inner[key]
    del inner[path[-1]]
    (tmp_path / "analyze.json").write_text(json.dumps(doc))
    run_cli("report", "paper", "--out", tmp_path, "--no-animations")
    return (tmp_path / "report.html").read_text(), json.loads((tmp_path / "report.json").read_text())


def test_an_input_of_another_shape_is_named_damaged(tmp_path):
    """A result its record cannot be read from is damaged, by name, with the command
    that rebuilds it; the page is still written, the other inputs' sections whole."""
    text, report = _analyze_without(tmp_path, "drive")
    assert "analyze.json is damaged (ValueError: analyze.json: Object missing required field `drive`)" in text
    assert "rebuild it with <code>rotorpillar analyze paper" in text
    assert "Appendix B: modal validation" in text and "Appendix J: versions, machine and timings" in text
    assert "drive" in report["damaged"]["analyze"] and report["failures"]["input analyze.json"]


def test_a_key_missing_deep_in_a_record_is_not_read_around(tmp_path):
    """A key missing inside a nested block (the drive's free speed) was read around
    before (the document as plain attributes, every section but the one touching it
    rendered from a record that is not one): now the whole file is damaged, by name,
    and no section shows a number from it."""
    text, report = _analyze_without(tmp_path, "drive", "free_speed")
    assert "free_speed" in report["damaged"]["analyze"]
    assert "is damaged" in text and "rebuild it with <code>rotorpillar analyze paper" in text
    assert "Motor Md =" not in text and "Stationary speeds and jumps" not in text
    assert not [k for k in report["failures"] if k.startswith("section_")]


def test_convergence_section_reads_the_selection(tmp_path):
    """The section shows convergence.json's chosen model, why, and the references,
    as `rotorpillar converge` writes them (selection.chosen, reference.<mode>)."""
    run_cli("analyze", "paper", "--out", tmp_path)
    scene = json.loads((tmp_path / "analyze.json").read_text())["scene"]
    band = {"omega_max": 60.0, "margin": 1.5, "driver": "drive free speed"}
    chosen = {"label": "shell Q2 quadrilaterals, 16x20", "dofs": 6560, "wall_time": 0.45, "bending_error_bound": 3e-4}
    rejected = {"label": "Eq. 1 + ring (closed forms)", "dofs": 1, "wall_time": 1e-4, "why": "bending bound 1.7e-02"}
    check = {"order": 4.0, "order_theory": 4, "monotone": True, "value": 30.81, "error_estimate": 0.01, "h": []}
    check |= {"f": [], "finer_run": "c", "finer_value": 30.818, "difference": 0.008, "within_estimate": True}
    conv = convergence_doc(
        SimpleNamespace(name="paper", to_dict=lambda: scene),
        [],
        {
            "bending": {
                "value": 30.818,
                "error_estimate": 4e-3,
                "order": 1.8,
                "order_theory": 4,
                "runs": ["a", "b", "c"],
                "check": check,
            }
        },
        chosen=chosen,
        band=band,
        selection={"rejected_cheaper": [rejected]},
        failures=["beams have no ovalling mode"],
    )
    (tmp_path / "convergence.json").write_text(json.dumps(conv))
    run_cli("report", "paper", "--out", tmp_path, "--no-animations")
    text = (tmp_path / "report.html").read_text()
    assert "shell Q2 quadrilaterals, 16x20 (6560 DOFs" in text
    # the bound as the rule defines it: the run's plus the reference's uncertainty (none here)
    assert "bending 3.0e-04" in text and "bending bound 1.7e-02" in text
    assert "30.818" in text and "beams have no ovalling mode" in text
