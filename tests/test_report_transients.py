"""The report's transients (issue 9): the earthquake section shows a real
record on the physically consistent models first (the ROM and the 3D full
order overlaid, their error and cost, the record's response spectrum), then
the paper's case with its excitation's size and Eq. 4's base-forcing
flaw; the run-up overlays the ROM and a full-order model; the findings list
eq4_base_forcing.

Inputs: a real `rotorpillar analyze paper` (its eq4_base_forcing row) and
synthetic comparisons and runs shaped by the compare contract
(tests/fixtures.py).  The report reads and never recomputes: every number
it shows is checked against the JSON the fixtures wrote, within the
rounding of its printed digits (stated at each check).  Charts: PNG header
size and non-blank pixels (tests/imagecheck.py).
"""

import html
import json
import re
from html.parser import HTMLParser

import fixtures
import numpy as np
import pytest
from imagecheck import assert_real_png

from rotorpillar import cli
from rotorpillar.postprocess.html import num as h_num
from rotorpillar.postprocess.report.page import model_name
from rotorpillar.transients.compare import COMPARISONS, comparison_command

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule)
pytestmark = pytest.mark.slow

# 5 significant digits (html.num's default) round a value by at most 5e-6 of
# it... up to half a unit in the 5th digit: 5e-5 relative at worst.
FIVE_DIGITS = 5e-5
# percentages and ratios shown with 3 significant digits: 5e-3 relative.
THREE_DIGITS = 5e-3
# 4 significant digits: 5e-4 relative.
FOUR_DIGITS = 5e-4


def run_cli(*args):
    assert cli.main([str(a) for a in args]) == 0


class _Tables(HTMLParser):
    """Every table of a piece of HTML: (header cells, body rows of cell text)."""

    def __init__(self):
        super().__init__()
        self.tables, self._cell, self._row = [], None, None

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append(([], []))
        elif tag == "tr":
            self._row = []
        elif tag in ("td", "th"):
            self._cell = []

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self._row.append("".join(self._cell).strip())
            self._cell = None
        elif tag == "tr" and self._row is not None:
            head, body = self.tables[-1]
            (head.extend(self._row) if not head else body.append(self._row))
            self._row = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell.append(data)


def section(text: str, ident: str) -> str:
    m = re.search(rf'<section id="{ident}"[^>]*>(.*?)</section>', text, re.S)
    assert m, f"no section {ident}"
    return m.group(1)


def h3(fragment: str, title: str) -> int:
    """Where the subsection ``title`` starts (its <h3>, with or without an id), or -1."""
    m = re.search(rf"<h3[^>]*>{re.escape(title)}", fragment)
    return m.start() if m else -1


def plain_text(fragment: str) -> str:
    """The text of a piece of HTML, tags dropped, entities decoded."""
    return html.unescape(re.sub(r"<[^>]+>", "", fragment))


def tables(fragment: str) -> list:
    p = _Tables()
    p.feed(fragment)
    return p.tables


def cost_table(fragment: str) -> dict:
    """The speed-accuracy table of a comparison, as {model: {header: cell}}."""
    found = [(h_, rows) for h_, rows in tables(fragment) if h_[:2] == ["model", "degrees of freedom"]]
    assert len(found) == 1, f"{len(found)} cost tables"
    head, rows = found[0]
    return {r[0].replace(" (reference)", ""): dict(zip(head, r)) for r in rows}


def number(cell: str) -> float:
    return float(cell.replace("%", "").strip())


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    """A report on the analysis, both comparisons and the paper's case."""
    out = tmp_path_factory.mktemp("transients")
    run_cli("analyze", "paper", "--out", out)
    docs = {
        "earthquake": fixtures.write_comparison_fixture(
            out, "earthquake", ("modal", "fem3d"), warnings={"fem3d": ["synthetic warning <one line>"]}
        ),
        "runup": fixtures.write_comparison_fixture(out, "runup", ("modal", "beam")),
    }
    paper = fixtures.write_simulation_fixture(
        out,
        "earthquake",
        modal=False,
        per_model=True,
        warnings=["the published base forcing amplifies the ground 1.6 times"],
    )
    fixtures.write_simulation_fixture(out, "runup")
    run_cli("report", "paper", "--out", out, "--no-animations")
    return {
        "out": out,
        "text": (out / "report.html").read_text(encoding="utf-8"),
        "compare": docs,
        "paper": paper,
        "analyze": json.loads((out / "analyze.json").read_text()),
        "report": json.loads((out / "report.json").read_text()),
    }


def test_the_record_comes_first_then_the_paper_case(page):
    eq = section(page["text"], "earthquake")
    spectrum = h3(eq, "Response spectrum of the record")
    assert spectrum >= 0
    # the overlay is the first picture of the section; the paper's case is an appendix, after it
    first_img = eq.find("<img")
    assert 0 < first_img < spectrum and "overlaid" in eq[first_img:spectrum]
    assert page["text"].index('<section id="earthquake"') < page["text"].index('<section id="paper-earthquake"')
    assert page["report"]["failures"] == {}
    assert page["report"]["inputs"]["compare_earthquake"] and page["report"]["inputs"]["compare_runup"]


@pytest.mark.parametrize("case, where", [("earthquake", "earthquake"), ("runup", "runs")])
def test_the_cost_table_shows_the_comparison_as_written(page, case, where):
    doc = page["compare"][case]
    rows = cost_table(section(page["text"], where))
    ref = doc["reference"]
    assert list(rows) == [model_name(m) for m in doc["models_run"]]
    for m in doc["models_run"]:
        r, p = rows[model_name(m)], doc["per_model"][m]
        assert int(r["degrees of freedom"]) == p["dofs"]
        assert number(r["wall time, warm (s)"]) == pytest.approx(p["wall_seconds"], rel=FOUR_DIGITS)
        # in mm, 4 significant digits
        assert 1e-3 * number(r["peak tip, relative to the ground (mm)"]) == pytest.approx(
            p["peak_tip_relative"], rel=FOUR_DIGITS
        )
        assert 1e-3 * number(r["peak shaft deflection, radial (mm)"]) == pytest.approx(
            p["peak_shaft_deflection"], rel=FOUR_DIGITS
        )
        assert number(r[f"wall time / the {model_name(ref)}'s (-)"]) == pytest.approx(
            doc["cost_ratio"][m], rel=FOUR_DIGITS
        )
        # the errors' headers name their window: t = start .. end s of the comparison
        over = f"t = {h_num(doc['window']['start'], 4)} .. {h_num(doc['window']['end'], 4)} s"
        err = r[f"tip history error against the {model_name(ref)}, {over} (%)"]
        if m == ref:
            assert err == "reference"
        else:  # shown in percent ("(leads)" beside the measure that fits the case)
            assert number(err.replace("(leads)", "")) / 100 == pytest.approx(
                doc["errors"][m]["tip_history_error"], rel=THREE_DIGITS
            )
            # 3 significant digits of a percent
            assert number(r[f"peak tip difference, {over} (%)"]) / 100 == pytest.approx(
                doc["errors"][m]["peak_tip_difference"], rel=THREE_DIGITS
            )


def test_the_full_order_runs_and_their_warnings_are_stated(page):
    eq = section(page["text"], "earthquake")
    assert "synthetic fem3d: coarsened for the fixture" in eq
    assert "3D full order: synthetic warning &lt;one line&gt;" in eq
    w = page["compare"]["earthquake"]["window"]
    assert f"Every model ran over t = {w['start']:g} .. {w['end']:g} s ({w['why']})." in plain_text(eq)
    runs = section(page["text"], "runs")
    assert "<h4>Run-up: the reduced model against a full-order model</h4>" in runs
    assert "synthetic beam: coarsened for the fixture" in runs


def test_the_spectrum_shows_the_modes_and_the_rom_estimate(page):
    eq = section(page["text"], "earthquake")
    spec = page["compare"]["earthquake"]["spectrum"]
    part = eq[h3(eq, "Response spectrum of the record") :]
    m = re.search(
        r"Spectral estimate of the peak tip: ([\d.e+-]+) mm, .*?the time history's peak "
        r"on the same model: ([\d.e+-]+) mm",
        " ".join(plain_text(part).split()),  # the template's line breaks are spaces
        re.S,
    )
    assert m, part[:2000]
    # in mm, 4 significant digits
    assert 1e-3 * float(m.group(1)) == pytest.approx(spec["spectral_peak_tip"], rel=FOUR_DIGITS)
    assert 1e-3 * float(m.group(2)) == pytest.approx(spec["computed_peak_tip"], rel=FOUR_DIGITS)
    # what the ratio means, and where the record acts
    assert "SRSS is an estimate, not a bound" in plain_text(part)
    assert "horizontal, in the rotor's plane (the paper's X)" in plain_text(part)
    assert "synthetic spectrum: an estimate, not a bound" in part
    # one set of modes: the table's are the estimate's, the chart marks the same
    periods = [
        t
        for h_, rows in tables(part)
        if h_[:3] == ["coupled mode", "undamped natural frequency (rad/s)", "period (s)"]
        for t in rows
    ]
    assert [float(r[2]) for r in periods] == pytest.approx([m["period"] for m in spec["modes"]], rel=FOUR_DIGITS)
    assert [float(r[3]) for r in periods] == pytest.approx([100 * m["damping_ratio"] for m in spec["modes"]], rel=1e-3)


def test_the_paper_case_states_its_size_the_flaw_and_the_warnings(page):
    eq = section(page["text"], "paper-earthquake")
    part = plain_text(eq)
    ex = page["paper"]["excitation"]
    assert "The paper's pulse on Eq. 4 as published." in part
    assert f"the ground steps {abs(ex['displacement_step_at_start']):.3g} m" in part
    assert f"its acceleration reaches {ex['peak_acceleration_g']:.3g} g" in part
    row = next(r for r in page["analyze"]["paper_comparison"] if r["key"] == "eq4_base_forcing")
    # the flaw in one sentence with its number and a link; the finding is stated once, elsewhere
    assert (
        f"The base-forcing flaw: Eq. 4 as published forces the rotor's shaft from the ground "
        f"as well as the pillar: under a slow ground displacement it moves the tip "
        f"{row['paper']:.3g} times as far as the ground"
    ) in part
    assert row["note"] not in part and 'href="#paper-findings"' in eq
    assert "the published base forcing amplifies the ground 1.6 times" in part
    # the tip relative to the ground: the fixture's tip_x is absolute (ground + relative)
    a = np.load(page["out"] / "simulate_earthquake_paper.npz")
    rel = np.abs(a["tip_x"] - a["ground_x"]).max()
    m = re.search(r"Largest tip displacement relative to the ground: ([\d.e+-]+) m", part)
    assert float(m.group(1)) == pytest.approx(rel, rel=FOUR_DIGITS)
    assert rel < 0.01 * np.abs(a["tip_x"]).max()  # the ground dominates the absolute tip
    assert "relative to the ground, and the rotor speed" in part


def test_the_findings_list_eq4_base_forcing(page):
    row = next(r for r in page["analyze"]["paper_comparison"] if r["key"] == "eq4_base_forcing")
    case = plain_text(section(page["text"], "paper-earthquake"))
    # the paper's earthquake names the finding in words and links it: no internal id, no formula
    assert "eq4_base_forcing" not in case and row["note"] not in case
    assert "forces the rotor's shaft from the ground" in case
    paper = plain_text(section(page["text"], "paper"))
    assert "Findings on the paper's formulation" in paper and f"{row['quantity']} (Eq. 4): " in paper
    assert page["text"].count(html.escape(row["note"])) == 1  # stated once in the page
    printed = [r for r in page["analyze"]["paper_comparison"] if not r.get("details")]
    assert f"({sum(r['flag'] for r in printed)} of {len(printed)} printed numbers)" in paper
    # the speed-accuracy point beside the comparison's table
    assert "The ROM against the 3D full order: judged on the tip's history" in section(page["text"], "earthquake")


@pytest.mark.parametrize(
    "name, size",
    [
        ("comparison_earthquake.png", (1060, 700)),
        ("comparison_runup.png", (1060, 700)),
        ("response_spectrum.png", (900, 540)),
        ("earthquake_response.png", (900, 800)),
    ],
)
def test_the_charts_are_real_pngs(page, name, size):
    path = page["out"] / "figures" / name
    assert str(path) in page["report"]["figures"]
    assert_real_png(path, size)


def test_missing_comparisons_name_the_commands(tmp_path):
    run_cli("analyze", "paper", "--out", tmp_path)
    run_cli("report", "paper", "--out", tmp_path, "--no-animations")
    text = (tmp_path / "report.html").read_text(encoding="utf-8")
    for case, where in (("earthquake", "earthquake"), ("runup", "runs")):
        cmd = f"rotorpillar {comparison_command(case)} paper --out {tmp_path}"
        assert f"not computed: run <code>{cmd}</code>." in section(text, where)
    assert "--set excitation.kind=record" in comparison_command("earthquake")
    eq = section(text, "paper-earthquake")
    assert f"<code>rotorpillar simulate --case earthquake --model paper paper --out {tmp_path}" in eq
    assert "The base-forcing flaw: " in plain_text(eq)  # from analyze.json alone
    assert json.loads((tmp_path / "report.json").read_text())["failures"] == {}


def test_a_comparison_without_arrays_keeps_its_table(tmp_path):
    doc = fixtures.write_comparison_fixture(tmp_path, "earthquake", ("modal", "fem3d"))
    for m in doc["models_run"]:
        (tmp_path / f"simulate_earthquake_{m}.npz").unlink()
    run_cli("report", "paper", "--out", tmp_path, "--no-animations")
    text = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert set(cost_table(section(text, "earthquake"))) == {"ROM", "3D full order"}
    assert not (tmp_path / "figures" / "comparison_earthquake.png").exists()
    assert json.loads((tmp_path / "report.json").read_text())["failures"] == {}


def test_the_record_set_by_the_comparison_is_not_another_scene(tmp_path):
    """compare_earthquake.json's scene has the record the comparison sets
    itself: no warning; any other difference: the warning."""
    run_cli("analyze", "paper", "--out", tmp_path)
    scene = json.loads((tmp_path / "analyze.json").read_text())["scene"]
    doc = fixtures.write_comparison_fixture(tmp_path, "earthquake", ("modal", "fem3d"))
    scene["excitation"].update(kind="record", record="elcentro")
    (tmp_path / "compare_earthquake.json").write_text(json.dumps({**doc, "scene": scene}))
    run_cli("report", "paper", "--out", tmp_path, "--no-animations")
    assert "computed for a different scene" not in section((tmp_path / "report.html").read_text(), "earthquake")
    scene["rotor"]["eccentricity"] *= 2
    (tmp_path / "compare_earthquake.json").write_text(json.dumps({**doc, "scene": scene}))
    run_cli("report", "paper", "--out", tmp_path, "--no-animations")
    assert "computed for a different scene (rotor.eccentricity differ)" in section(
        (tmp_path / "report.html").read_text(), "earthquake"
    )


def test_run_compares_on_the_record_the_user_can_override(tmp_path):
    """run's compare stages: the record set before the user's --set (theirs win)."""
    from types import SimpleNamespace

    from rotorpillar.commands.run import RUN_STAGES, stage_argv

    stages = {st.command: st for st in RUN_STAGES}
    names = [st.command for st in RUN_STAGES]
    for case in COMPARISONS:
        assert f"compare --case {case}" in stages
    # the comparisons write compare_<case>_<model>.*, apart from the scene's own runs, so they
    # run side by side with them (one wave after analyze)
    assert stages["compare --case earthquake"].wave == stages["simulate --case earthquake"].wave
    assert names.index("analyze") < names.index("compare --case runup")
    args = SimpleNamespace(scene="paper", overrides=["excitation.record=my.AT2"])
    argv = stage_argv(stages["compare --case earthquake"], args, tmp_path)
    sets = [argv[i + 1] for i, a in enumerate(argv) if a == "--set"]
    assert sets == [
        "excitation.kind=record",
        "excitation.record=elcentro",
        "excitation.start=1",
        "full_order.earthquake_duration=9",
        "excitation.record=my.AT2",
    ]
    assert argv[argv.index("--models") + 1] == "modal,fem3d"
