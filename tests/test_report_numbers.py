"""Each quantity once, with one definition: the report's pieces built from records (no run).

- The response spectrum's section (templates/sections/spectrum.html.j2) from a
  ResponseSpectrum made by the estimate's own code on a two-storey shear frame:
  the estimate in the text is the SRSS of the table's per-mode peaks, the table's
  modes are the estimate's (one set, each at its own damping), the ratio printed
  is computed / estimate, and the pillar-only estimate is named as such.
- The mesh's error bound: the pillar model's line (chain PillarModel.describe),
  the convergence section's "its bounds" (report.convergence.chosen), the
  selection's reason and a rejected run's why (converge.selection) all state
  |model error| + |discretisation error| + the reference's uncertainty, with the
  same digits.
- A run's key results: the shaft deflection is the radial one, in mm, and each
  peak's value once.
Tolerances: the page prints 4 significant digits (3 for the ratio); a printed
number is compared with the record's to half a unit of its last digit.
"""

from __future__ import annotations

import math
import re
from html.parser import HTMLParser
from types import SimpleNamespace

import numpy as np
import pytest

from rotorpillar.reduced.spectral import spectral_terms, srss
from rotorpillar.transients.case_summary import SpectralMode
from rotorpillar.transients.compare import ResponseSpectrum

#: 4 significant digits printed: half a unit of the last digit, relative (-)
FOUR_DIGITS = 5e-4
#: 3 significant digits printed (-)
THREE_DIGITS = 5e-3


class _Tables(HTMLParser):
    """Every table of a fragment: (headers, rows of cell texts)."""

    def __init__(self) -> None:
        super().__init__()
        self.tables: list[tuple[list[str], list[list[str]]]] = []
        self._cell: list[str] | None = None
        self._row: list[str] = []
        self._head = False

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append(([], []))
        elif tag == "tr":
            self._row = []
        elif tag in ("td", "th"):
            self._cell, self._head = [], tag == "th"

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self._row.append(" ".join("".join(self._cell).split()))
            self._cell = None
        elif tag == "tr" and self.tables:
            heads, rows = self.tables[-1]
            if self._head:
                heads.extend(self._row)
            else:
                rows.append(self._row)

    def handle_data(self, data):
        if self._cell is not None:
            self._cell.append(data)


def tables(fragment: str):
    p = _Tables()
    p.feed(fragment)
    return p.tables


def text_of(fragment: str) -> str:
    return " ".join(re.sub(r"<[^>]+>", " ", fragment).split())


def shear_frame_spectrum() -> ResponseSpectrum:
    """The estimate's own records for a two-storey frame under a made-up spectrum."""
    m, k, a, b = 2.0e3, 8.0e5, 0.3, 2.0e-3
    M, K = m * np.eye(2), k * np.array([[2.0, -1.0], [-1.0, 1.0]])
    terms = spectral_terms(M, K, a * M + b * K, -M @ np.ones(2), np.array([0.0, 1.0]), lambda T, z: 0.02 * T)
    modes = tuple(
        SpectralMode(j, t.period, t.damping_ratio, t.participation, t.s_d, t.contribution)
        for j, t in enumerate(terms, start=1)
    )
    T = np.geomspace(0.02, 10.0, 50)
    return ResponseSpectrum(
        period=tuple(T.tolist()),
        psa=tuple((0.02 * T * (2 * math.pi / T) ** 2).tolist()),
        damping=0.05,
        mode_periods=tuple(t.period for t in terms),
        spectral_peak_tip=srss(terms),
        computed_peak_tip=0.9 * srss(terms),
        modes=modes,
        note="",
        pillar_modes_only=1.3 * srss(terms),
    )


def test_the_spectrum_states_one_set_of_modes_and_one_estimate():
    from rotorpillar.postprocess.report.page import render

    spec = shear_frame_spectrum()
    html_ = str(
        render(
            "sections/spectrum.html.j2",
            found=True,
            command="",
            spec=spec,
            model="modal",
            picture=None,
            failed=None,
            horizontal="in the rotor's plane",
        )
    )
    (heads, rows), *others = tables(html_)
    assert not others  # one table of modes, not the pillar's beside the coupled ones
    col = {h: i for i, h in enumerate(heads)}
    assert [float(r[col["period (s)"]]) for r in rows] == pytest.approx([m.period for m in spec.modes], rel=FOUR_DIGITS)
    assert [float(r[col["damping ratio (%)"]]) for r in rows] == pytest.approx(
        [100 * m.damping_ratio for m in spec.modes], rel=THREE_DIGITS
    )
    omega = [float(r[col["undamped natural frequency (rad/s)"]]) for r in rows]
    assert omega == pytest.approx([2 * math.pi / m.period for m in spec.modes], rel=FOUR_DIGITS)
    peaks = [1e-3 * float(r[col["peak tip in this mode (mm)"]]) for r in rows]
    text = text_of(html_)
    (estimate,) = re.findall(r"Spectral estimate of the peak tip: ([\d.]+) mm", text)
    # the estimate stated is the SRSS of the peaks the table lists
    assert 1e-3 * float(estimate) == pytest.approx(math.sqrt(sum(p * p for p in peaks)), rel=2 * FOUR_DIGITS)
    (ratio,) = re.findall(r"computed / estimate = ([\d.]+)", text)
    assert float(ratio) == pytest.approx(0.9, rel=THREE_DIGITS)
    (alone,) = re.findall(r"pillar's own modes, the rotor a separate mass, would read ([\d.]+) mm", text)
    assert 1e-3 * float(alone) == pytest.approx(spec.pillar_modes_only, rel=FOUR_DIGITS)
    assert "the difference is the coupling" in text


def _brief():
    from rotorpillar.converge.result import RunBrief

    return RunBrief(
        label="3D P2 hexahedra, 128x20x1",
        family="solid_hex_p2",
        model="solid",
        params={},
        dofs=94464,
        wall_time=17.9,
        peak_memory=None,
        bending=30.828,
        ovalling=85.114,
        bending_error=2.6e-4,
        bending_model_error=0.0,
        bending_discretisation_error=2.6e-4,
        bending_error_bound=2.6e-4,
        ovalling_error=6.2e-4,
        ovalling_model_error=0.0,
        ovalling_discretisation_error=6.2e-4,
        ovalling_error_bound=6.2e-4,
    )


def test_the_mesh_error_bound_reads_the_same_everywhere():
    from rotorpillar.chain.choice import model_of_run
    from rotorpillar.converge.selection import _reason, _why
    from rotorpillar.postprocess.report.convergence import chosen

    run = _brief()
    unc = {"bending": 1.9e-4, "ovalling": 3.3e-4}
    bound = {q: f"{getattr(run, f'{q}_error_bound') + unc[q]:.1e}" for q in unc}
    assert bound == {"bending": "4.5e-04", "ovalling": "9.5e-04"}  # what the reader must see

    line = model_of_run(run, unc, 1e-3, "").describe()
    band = SimpleNamespace(
        omega_max=134.6, margin=1.5, driver="drive free speed", free_speed=89.7, earthquake_frequency=0
    )
    study = SimpleNamespace(
        selection=SimpleNamespace(
            chosen=run, band=band, needed=("bending", "ovalling"), tolerance=1e-3, reference_uncertainty=unc
        )
    )
    what = chosen(study)
    assert what is not None
    reference = {
        q: SimpleNamespace(value=v, error_estimate=unc[q] * v) for q, v in (("bending", 30.82), ("ovalling", 85.06))
    }
    reason = _reason(run, ("bending", "ovalling"), band, 1e-3, reference, {})
    for q, b in bound.items():
        said = {
            "pillar model": re.findall(rf"{q} (\d\.\de-\d\d)", line),
            "convergence section": re.findall(rf"{q} (\d\.\de-\d\d) \(", what[1]),
            "selection's reason": re.findall(rf"first {q} \([^)]*error bound (\d\.\de-\d\d)", reason),
        }
        assert all(v == [b] for v in said.values()), said
    # a rejected run's why: the same definition (its own numbers)
    why = _why(run, ("bending",), unc, 1e-4)
    assert f"bending error bound {bound['bending']} > 0.0001" in why


def test_a_runs_peaks_are_radial_and_once():
    from rotorpillar.postprocess.report.parts import _peaks

    rows = _peaks(
        {"tip_x_relative": 8.0333e-4, "tip_x": 8.0333e-4, "shaft_deflection_x": 3.986e-3, "shaft_deflection": 4.6946e-3}
    )
    got = dict(rows)
    assert got == {
        "largest |tip, horizontal (X), relative to the ground| (mm)": "0.8033",
        "largest |shaft deflection (rotor minus tip), radial| (mm)": "4.695",
    }


def test_the_machines_first_frequency_leads_and_says_what_it_includes():
    """The ROM's coupled modes in the rotor's plane give the machine's first frequency (the
    lowest X mode, rotor included), stated before the tube's with the gondola only."""
    from rotorpillar.verdict.summary import _headlines

    modes = [SimpleNamespace(direction="Y", omega=15.81), SimpleNamespace(direction="X", omega=27.14)]
    modes.append(SimpleNamespace(direction="X", omega=14.89))
    first, *_ = _headlines([], SimpleNamespace(averaging=modes, separation=()), None)
    assert first.key == "machine_first_frequency"
    assert first.value == pytest.approx(14.89 / (2 * math.pi), rel=1e-12)
    assert "tube, gondola and rotor" in first.label and first.unit == "Hz"
