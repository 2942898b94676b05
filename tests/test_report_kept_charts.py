"""The charts kept under their content key (rotorpillar.postprocess.report.kept.chart).

- A second report on the same inputs draws none of its charts again: it says so
  (report.json's ``reused``, the timings appendix), leaves every PNG as the first
  wrote it (same bytes, same modification time), and its page is the page of a
  fresh report on the same inputs in another folder, byte for byte (the
  provenance appendix aside: it holds the clock and the timings).
- A changed input draws the charts drawn from it, and only those: a new run-up
  comparison redraws comparison_runup, not the earthquake's charts.
- A kept PNG rewritten or deleted since is drawn again.

The inputs are the synthetic comparisons of tests/fixtures.py (no modes, no
animations): the report draws comparison_earthquake, comparison_runup and
response_spectrum from them.
"""

from __future__ import annotations

import json
import re
import shutil

import fixtures

from rotorpillar import cli

CHARTS = {"chart_comparison_earthquake", "chart_comparison_runup", "chart_response_spectrum"}


def _inputs(out, n_runup: int = 1200) -> None:
    fixtures.write_comparison_fixture(out, "earthquake", ("modal", "fem3d"))
    fixtures.write_comparison_fixture(out, "runup", ("modal", "beam"), n=n_runup)


def _report(out) -> dict:
    assert cli.main(["report", "paper", "--out", str(out), "--no-animations"]) == 0
    return json.loads((out / "report.json").read_text())


def _pngs(out) -> dict[str, tuple[bytes, int]]:
    return {p.name: (p.read_bytes(), p.stat().st_mtime_ns) for p in sorted((out / "figures").glob("*.png"))}


def _page(out) -> str:
    """report.html without its provenance appendix (the clock, the timings, what was reused),
    the out folder named OUT (the page names it in its hints)."""
    text = (out / "report.html").read_text().replace(str(out), "OUT")
    cut = re.sub(r'<section id="provenance".*?</section>', "", text, flags=re.S)
    assert cut != text  # the appendix was there and is cut
    return cut


def test_a_second_report_reuses_its_charts_and_writes_the_same_page(tmp_path):
    fresh = tmp_path / "fresh"
    out = tmp_path / "out"
    for d in (fresh, out):
        d.mkdir()
        _inputs(d)
    first = _report(out)
    assert first["failures"] == {} and first["reused"] == {}
    drawn = _pngs(out)
    assert {"comparison_earthquake.png", "comparison_runup.png", "response_spectrum.png"} <= set(drawn)

    second = _report(out)
    assert set(second["reused"]) == CHARTS
    assert not CHARTS & {f"chart_{k}" for k in second["render_seconds"]}  # none drawn
    assert _pngs(out) == drawn  # bytes and modification times
    assert "reused, unchanged: chart_" in (out / "report.html").read_text()
    assert sorted(second["figures"]) == sorted(first["figures"])

    # the page of a report that drew every chart, in a folder of its own
    assert _report(fresh)["reused"] == {}
    assert _page(out) == _page(fresh)
    assert {k: v[0] for k, v in _pngs(out).items()} == {k: v[0] for k, v in _pngs(fresh).items()}


def test_a_changed_input_draws_its_charts_only(tmp_path):
    _inputs(tmp_path)
    _report(tmp_path)
    drawn = _pngs(tmp_path)
    # another run-up (fewer samples): its comparison changes, the earthquake's do not
    fixtures.write_comparison_fixture(tmp_path, "runup", ("modal", "beam"), n=900)
    again = _report(tmp_path)
    assert set(again["reused"]) == {"chart_comparison_earthquake", "chart_response_spectrum"}
    assert "comparison_runup" in again["render_seconds"]
    now = _pngs(tmp_path)
    assert now["comparison_runup.png"][0] != drawn["comparison_runup.png"][0]
    for name in ("comparison_earthquake.png", "response_spectrum.png"):
        assert now[name] == drawn[name]


def test_a_kept_chart_rewritten_or_deleted_since_is_drawn_again(tmp_path):
    _inputs(tmp_path)
    _report(tmp_path)
    drawn = _pngs(tmp_path)
    (tmp_path / "figures" / "comparison_runup.png").write_bytes(b"not the chart drawn")
    (tmp_path / "figures" / "response_spectrum.png").unlink()
    again = _report(tmp_path)
    assert set(again["reused"]) == {"chart_comparison_earthquake"}
    now = _pngs(tmp_path)
    # drawn again from the same inputs: the same bytes as the first time
    for name in ("comparison_runup.png", "response_spectrum.png"):
        assert now[name][0] == drawn[name][0]


def test_a_damaged_keep_file_is_a_miss(tmp_path):
    _inputs(tmp_path)
    _report(tmp_path)
    (tmp_path / "figures" / "comparison_earthquake_chart.json").write_text("{not json")
    shutil.copy(tmp_path / "report.json", tmp_path / "first.json")
    again = _report(tmp_path)
    assert set(again["reused"]) == {"chart_comparison_runup", "chart_response_spectrum"}
