"""The report's "ROM against the full order" rows compare like against like (issue 29.3).

The run-up's ROM from `simulate` runs the whole case from rest (80 s), the 3D
full order of `compare` a short window from a speed near the resonance, and
compare runs the ROM over that same window.  The rows must set the full
order beside the ROM run of its own window, and say what each row covers;
where no ROM run covers it, say that the difference is not the ROM's error
alone.  Synthetic records (peaks chosen so the pairing is visible in the
percentages: exact arithmetic on them, 1e-12).
"""

from __future__ import annotations

import re

import pytest

from rotorpillar.postprocess.report.engineering import _differences
from rotorpillar.postprocess.report.force_runs import ForcesRun, like_pairs
from rotorpillar.transients.forces import BaseReactions, InternalForcesSummary, ShaftDemand


def _forces(model: str, moment: float, shear: float) -> InternalForcesSummary:
    base = BaseReactions(moment, 1.0, shear, 1.0, 1e5, 1e5, moment * 1e-3, 1.0, 0.1)
    shaft = ShaftDemand(4e-3, 1.0, 1e4, 1e4, 1.0, False)
    return InternalForcesSummary(model, "synthetic", (0.0,), (moment,), (shear,), (1e5,), base, shaft)


def _run(file: str, model: str, moment: float, shear: float, duration: float, start: float | None) -> ForcesRun:
    return ForcesRun("runup", file, _forces(model, moment, shear), duration, start)


#: the whole run-up on the ROM, the 3D window, and the ROM over that window
WHOLE = _run("simulate_runup_modal.json", "modal", 85_613.0, 5_569.0, 80.0, None)
FULL = _run("compare_runup_fem3d.json", "fem3d", 83_026.0, 5_282.0, 0.688, 10.42)
WINDOW = _run("compare_runup_modal.json", "modal", 82_740.0, 5_257.0, 0.688, 10.42)


def _rows(html: str) -> list[list[str]]:
    body = html.split("<tbody>", 1)[1]
    return [re.findall(r"<td>(.*?)</td>", r) for r in body.split("</tr>") if "<td>" in r]


@pytest.mark.parametrize("order", [(WINDOW, WHOLE, FULL), (WHOLE, WINDOW, FULL), (FULL, WHOLE, WINDOW)])
def test_the_full_order_meets_the_rom_over_its_own_window(order):
    (pair,) = like_pairs(list(order))
    assert pair.rom is WINDOW and pair.reference is FULL and pair.same_window
    rows = _rows("".join(_differences([pair])))
    by = {r[1]: r for r in rows}
    # -0.34 % and -0.48 %, the two comparison runs' peaks, not the 80 s run's +3.1 % and +5.4 %
    assert by["|M(0)| max"][3] == f"{100 * (82_740.0 / 83_026.0 - 1):+.2f} %"
    assert by["|V(0)| max"][3] == f"{100 * (5_257.0 / 5_282.0 - 1):+.2f} %"
    assert all(r[4] == "both: 0.688 s from 10.42 rad/s" for r in rows)


def test_without_the_window_the_rows_say_what_each_run_covers():
    (pair,) = like_pairs([WHOLE, FULL])
    assert pair.rom is WHOLE and not pair.same_window
    rows = _rows("".join(_differences([pair])))
    assert rows[0][3] == f"{100 * (85_613.0 / 83_026.0 - 1):+.2f} %"
    cover = rows[0][4]
    assert "ROM: 80 s from the case&#x27;s start" in cover and "0.688 s from 10.42 rad/s" in cover
    assert "not the same window" in cover


def test_a_case_without_a_full_order_or_a_rom_has_no_row():
    assert like_pairs([WHOLE, WINDOW]) == [] and like_pairs([FULL]) == []
    assert _differences([]) == []


def test_the_last_of_two_alike_rom_runs_wins():
    again = _run("simulate_runup_modal.json", "modal", 1.0, 1.0, 0.688, 10.42)
    # both cover the window: the one from compare (the full order's own command) wins
    assert like_pairs([WINDOW, again, FULL])[0].rom is WINDOW
    assert like_pairs([again, FULL])[0].rom is again
