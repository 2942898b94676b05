"""The mode pictures kept under their content key (rotorpillar.postprocess.report.kept).

- A second report on the same modes draws none of them again: it says so
  (report.json's ``reused``, the timings appendix) and leaves every PNG as the
  first one wrote it (same bytes, same modification time).
- A changed mode input draws that set again, and only that set: the top mass
  of the fixture (tests/fixtures.py) changes the loaded tube's modes and its
  VTU, not the bare tube's.
- A kept PNG rewritten by someone else is not taken for the one drawn.

The inputs are synthetic modes on a coarse tube (tests/fixtures.py), drawn in the
report's own process (``parallel.WORKERS = 1``), without animations: what is kept and
reused is decided in the report's process whoever draws (render.render_3d keeps each
outcome as the jobs end), and that the workers draw what one process draws is
test_report_parallel's.  Two worker interpreters started for each of these five reports
cost 19.0 s of CPU for this module against 10.8 s in one process (measured).
"""

from __future__ import annotations

import json

import fixtures
import pytest

from rotorpillar import cli

# seconds each: reports drawing pictures in worker processes; the slow tier runs them
pytestmark = [pytest.mark.renders, pytest.mark.slow]


@pytest.fixture(autouse=True)
def _in_one_process(monkeypatch):
    from rotorpillar.postprocess.report import parallel

    monkeypatch.setattr(parallel, "WORKERS", 1)


def _report(out) -> dict:
    # three pictures a set, not eight: what is kept, reused and drawn again is decided per set
    # (its content key), whatever the count; bare_mode_03.png, rewritten below, is the third.
    # This module 10.9 -> 7.4 s of CPU (perf task-clock, 2026-11-29)
    assert cli.main(["report", "paper", "--out", str(out), "--no-animations", "--mode-pictures", "3"]) == 0
    return json.loads((out / "report.json").read_text())


def _pngs(out, name: str) -> dict[str, tuple[bytes, int]]:
    return {p.name: (p.read_bytes(), p.stat().st_mtime_ns) for p in sorted((out / "modes").glob(f"{name}_*.png"))}


def test_a_second_report_reuses_the_mode_pictures_a_changed_mode_draws_again(tmp_path):
    fixtures.write_modal_fixture(tmp_path, around=12, along=6)
    first = _report(tmp_path)
    assert first["failures"] == {} and first["reused"] == {}
    images = (tmp_path / "report.html").read_text().count("<img ")
    drawn = {name: _pngs(tmp_path, name) for name in ("bare", "top")}
    for pngs in drawn.values():  # each mode on the page, and the sheet
        assert len(pngs) >= 2 and all(any(f.endswith(f"modes/{n}") for f in first["figures"]) for n in pngs)

    second = _report(tmp_path)
    assert set(second["reused"]) == {"modes_bare", "modes_top"}
    assert not any(k.startswith("modes_") or k.startswith("load_modes_") for k in second["render_seconds"])
    assert {name: _pngs(tmp_path, name) for name in ("bare", "top")} == drawn
    assert sorted(second["figures"]) == sorted(first["figures"])
    page = (tmp_path / "report.html").read_text()
    assert "reused, unchanged: modes_bare" in page
    assert page.count("<img ") == images  # every picture still on the page

    # a heavier top: the loaded tube's modes change, the bare tube's do not
    fixtures.write_modal_fixture(tmp_path, around=12, along=6, top_mass=20e3)
    third = _report(tmp_path)
    assert set(third["reused"]) == {"modes_bare"}
    assert "modes_top" in third["render_seconds"]
    assert _pngs(tmp_path, "bare") == drawn["bare"]
    assert _pngs(tmp_path, "top") != drawn["top"]


def test_a_kept_picture_rewritten_since_is_drawn_again(tmp_path):
    fixtures.write_modal_fixture(tmp_path, around=12, along=6)
    _report(tmp_path)
    (tmp_path / "modes" / "bare_mode_03.png").write_bytes(b"not the picture drawn")
    again = _report(tmp_path)
    assert set(again["reused"]) == {"modes_top"}
    assert (tmp_path / "modes" / "bare_mode_03.png").read_bytes().startswith(b"\x89PNG")
