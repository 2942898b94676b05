"""The models of one case side by side (``compare_<case>.json``): the
overlay, the table of error and cost, each model's notes and warnings; and
the record's response spectrum beside the ROM's peak.  Pieces the
earthquake and the runs sections both use."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from ... import records
from ...reduced.excitation import ExcitationSizes, PulseSizes, RecordSizes
from ...transients.compare import comparison_command, comparison_overrides
from .. import html as h
from .parts import failure, product_image, scene_differs
from .references import reference_block
from .state import Build

if TYPE_CHECKING:
    from ...transients.compare import CompareResult
    from ...transients.model_run import RunRecord
    from ..compare_reader import Comparison

#: The headers of the speed-accuracy table (the reference's name goes in the errors).
COST_HEADERS = (
    "model",
    "DOFs",
    "wall time, warm (s)",
    "compilation, apart (s)",
    "peak tip relative to the ground (m)",
    "peak shaft deflection (m)",
    "final speed (rad/s)",
    "tip history error against {ref}",
    "tip envelope error against {ref}",
    "peak difference against {ref}",
    "rotor angle drift (rad)",
    "cost ratio (warm wall time / {ref}'s)",
)


def share(x) -> str:
    """A non-negative fraction in percent, 3 significant digits.

    >>> share(0.002134), share(None)
    ('0.213 %', '-')
    """
    if not isinstance(x, (int, float)) or isinstance(x, bool) or not math.isfinite(x):
        return "-"
    return f"{100 * x:.3g} %"


def missing_comparison(build: Build, case: str) -> list[str]:
    """The notice naming the command that makes ``compare_<case>.json``."""
    return [
        h.missing(
            f"not computed: run `rotorpillar {comparison_command(case)} {build.scene_cli}` (no compare_{case}.json)"
        )
    ]


def excitation_text(ex: ExcitationSizes | None) -> str | None:
    """One sentence on the ground motion a run used (its excitation block)."""
    if isinstance(ex, (PulseSizes, RecordSizes)) and ex.statement is not None:
        return ex.statement
    if not isinstance(ex, RecordSizes):
        return None
    what = [
        f"peak acceleration {h.num(ex.peak_acceleration_g, 3)} g",
        f"peak velocity {h.num(ex.peak_velocity, 3)} m/s",
        f"peak displacement {h.num(ex.peak_displacement, 3)} m",
    ]
    return (
        f"Ground motion: the record {ex.name}"
        + (f" ({ex.source})" if ex.source else "")
        + ": "
        + ", ".join(what)
        + f", from t = {h.num(ex.start, 4)} s."
    )


def cost_table(result: CompareResult, models: list[str]) -> str:
    """Per model: DOFs, wall time, peaks, the errors against the reference and the cost ratio."""
    ref, ratio = result.reference, result.cost_ratio
    rows, classes = [], []
    for m in models:
        p, e = result.per_model.get(m), result.errors.get(m)
        is_ref = m == ref
        r = 1.0 if is_ref and m not in ratio else ratio.get(m)
        lead = e.lead if e is not None else None
        mark = lambda name, text, lead=lead: f"{text} (leads)" if lead == name else text
        rows.append(
            [
                m + (" (reference)" if is_ref else ""),
                h.num(p.dofs if p else None),
                h.num(p.wall_seconds if p else None, 4),
                h.num(p.compile_seconds if p else None, 3),
                h.num(p.peak_tip_relative if p else None),
                h.num(p.peak_shaft_deflection if p else None),
                h.num(p.omega_final if p else None),
                "reference" if is_ref else "-" if e is None else mark("history", share(e.tip_history_error)),
                "reference" if is_ref else "-" if e is None else mark("envelope", share(e.tip_envelope_error)),
                "reference" if is_ref else h.pct(None if e is None else e.peak_tip_difference),
                "reference" if is_ref else h.num(None if e is None else e.angle_drift, 3),
                h.num(r, 4),
            ]
        )
        classes.append("flag" if p is not None and not p.ok else "ok")
    return h.table([c.format(ref=ref) for c in COST_HEADERS], rows, row_classes=classes)


def speed_accuracy(result: CompareResult, models: list[str]) -> list[str]:
    """The sentence per model: its error against the reference, led by the measure that
    fits the case (compare's ``lead``: the history while the rotors stay in phase, else
    the envelope, with the peak and the rotor angle's drift beside), at what share of the
    (warm) cost."""
    ref, ratio = result.reference, result.cost_ratio
    out = []
    for m in models:
        em = result.errors.get(m)
        if m == ref or em is None:
            continue
        e, r = em.tip_history_error, ratio.get(m)
        env, peak, drift = em.tip_envelope_error, em.peak_tip_difference, em.angle_drift
        if em.lead == "envelope" and env is not None:
            text = (
                f"{m} follows {ref}'s tip envelope within {share(env)} of its largest value "
                f"(peak {h.pct(peak) if peak is not None else '-'}); its history differs by "
                f"{share(e)} because the rotor angles drift apart by up to {h.num(drift, 3)} rad, "
                "a phase error of the whirl, not of the amplitudes"
            )
        else:
            text = f"{m} follows {ref}'s tip history within {share(e)} of its largest value"
            if peak is not None:
                text += f" (peak {h.pct(peak)}"
                text += f"; the rotors stay within {h.num(drift, 2)} rad of each other)" if drift is not None else ")"
        if isinstance(r, (int, float)) and r > 0:
            text += (
                f", at {h.num(r, 3)} of its wall time ({h.num(1 / r, 3)} times faster)"
                if r < 1
                else f", at {h.num(r, 3)} times its wall time"
            )
        out.append(text + ".")
    return out


#: Units of the fields of a full-order run's ``full_order`` block.
FULL_ORDER_UNITS = {"duration": "s", "time_step": "s"}


def _full_order(run: RunRecord | None) -> str | None:
    """What a full-order run was (mesh or elements, duration, step) and its note."""
    from ...transients.model_run import BeamFullOrder, Fem3dPlan

    fo = run.full_order if run is not None else None
    items: list[tuple[str, Any]]
    if isinstance(fo, Fem3dPlan):  # its reference: references.reference_block
        mesh = ", ".join(f"{a} {h.num(b)}" for a, b in records.to_builtins(fo.mesh).items())
        items = [("mesh", mesh), ("duration", fo.duration), ("case_duration", fo.case_duration)]
    elif isinstance(fo, BeamFullOrder):
        items = [("elements", fo.elements), ("theory", fo.theory), ("duration", fo.duration)]
    else:
        return None
    items.append(("time_step", fo.time_step))
    what = [
        f"{k.replace('_', ' ')} {h.num(v)}" + (f" {FULL_ORDER_UNITS[k]}" if k in FULL_ORDER_UNITS else "")
        for k, v in items
        if v is not None
    ]
    return "; ".join(what) + (f". {fo.note}" if fo.note else "")


def _stem(case: str, model: str) -> str:
    """A comparison's per-model files (rotorpillar.transients.compare.compare_stem)."""
    return f"compare_{case}_{model}"


def _claim_figures(build: Build, case: str, models: list[str]) -> list:
    """The other commands' PNGs of this comparison (compare_<case>.png and the
    models' own compare_<case>_<model>.png), taken out of their groups."""
    names = {f"compare_{case}.png"} | {f"{_stem(case, m)}.png" for m in models}
    found = [p for p in build.products.get("external", []) if p.path.name in names]
    for p in found:
        p.group = "used"
    return found


def comparison_block(build: Build, case: str) -> list[str]:
    """The comparison of the models on ``case``, or the command that makes it."""
    c = build.comparisons.get(case)
    if c is None:
        return missing_comparison(build, case)
    models = c.models
    parts = scene_differs(build, c.provenance, ignore=comparison_overrides(case))
    ex = excitation_text(c.record.excitation)
    if ex:
        parts.append(h.tag("p", ex))
    w = c.record.window
    parts.append(
        h.tag(
            "p",
            f"Every model ran over t = {h.num(w.start, 4)} .. {h.num(w.end, 4)} s"
            + (f" ({w.why})" if w.why else "")
            + ".",
            class_="meta",
        )
    )
    theirs = _claim_figures(build, case, models)
    parts += failure(build, f"comparison_{case}")
    if f"comparison_{case}" in build.products:
        parts.append(product_image(build, f"comparison_{case}"))
    else:  # no arrays to draw from: compare's own chart, if it left one
        parts += [h.image(p.path, p.caption) for p in theirs if p.path.name == f"compare_{case}.png"]
    parts.append(cost_table(c.record, models))
    parts += reference_block(c.record.full_order_reference)
    said = speed_accuracy(c.record, models)
    if said:
        parts.append(h.tag("p", " ".join(said)))
    full = [(m, _full_order(c.runs.get(m))) for m in models]
    notes = [h.tag("li", f"{m}: {n}") for m, n in full if n]
    if notes:
        parts.append(h.tag("p", "Full-order models, as run here:", class_="meta"))
        parts.append(h.tag("ul", notes, class_="meta"))
    per = c.record.per_model
    warns = [h.tag("li", f"{m}: {w}") for m in models if m in per for w in per[m].warnings]
    if warns:
        parts.append(h.tag("ul", warns, class_="warn"))
    own = [(m, p) for m in models for p in theirs if p.path.name == f"{_stem(case, m)}.png"]
    if own:
        parts.append(
            h.details(
                f"each model's own chart ({len(own)})", "".join(h.image(p.path, f"{m}: {p.caption}") for m, p in own)
            )
        )
    return parts


def system_modes(c: Comparison | None) -> tuple[str | None, list[dict]]:
    """The coupled rotor-pillar modes of the reduced model a comparison ran
    (its JSON's ``resonances`` with their ``damped_frequencies``): (model,
    [{index, direction, omega, period, damping_ratio}]), the ROM first."""
    if c is None:
        return None, []
    order = sorted(c.models, key=lambda m: (m != "modal", m == c.reference))
    for m in order:
        run = c.runs.get(m)
        if run is None or not run.resonances:
            continue
        damped = run.damped_frequencies
        out = []
        for r in run.resonances:
            w = r.omega
            if w <= 0:
                continue
            near = min((d for d in damped if d.direction == r.direction), key=lambda d: abs(d.omega - w), default=None)
            out.append(
                {
                    "index": r.index,
                    "direction": r.direction,
                    "omega": float(w),
                    "period": 2 * math.pi / w,
                    "damping_ratio": None if near is None else near.damping_ratio,
                }
            )
        return m, out
    return None, []


#: Why the record is applied where it is (the plane model's own direction).
RECORD_DIRECTION = (
    "The record is applied as a ground motion {where}: the direction of the paper's own "
    "earthquake (its q5), and the one horizontal direction of the paper's plane model, in "
    "which the rotor's unbalance and the pillar's bending couple. The modes it excites are "
    "the coupled modes in that direction; the vertical mode (the rotor bouncing on its shaft) "
    "takes no part in a horizontal motion, nor do the tube's ovalling modes (zero participation "
    "by symmetry)."
)


def spectrum_block(build: Build) -> list[str]:
    """The record's response spectrum with the system's modes marked, and the
    ROM's spectral estimate of the peak tip beside the computed one."""
    from ..compare_charts import STANDARD_GRAVITY, spectral_value
    from ..directions import direction

    c = build.comparisons.get("earthquake")
    if c is None:
        return missing_comparison(build, "earthquake")
    spec = c.record.spectrum
    if spec is None:
        return [
            h.tag(
                "p",
                "compare_earthquake.json holds no response spectrum (the excitation "
                "is not a record, or the modal model was not run).",
                class_="meta",
            )
        ]
    parts = [h.tag("p", RECORD_DIRECTION.format(where=direction("X")))]
    parts += failure(build, "response_spectrum")
    if "response_spectrum" in build.products:
        parts.append(product_image(build, "response_spectrum"))
    model, modes = system_modes(c)
    damping = spec.damping
    if modes:
        rows = []
        for m in modes:
            horizontal = str(m["direction"]).upper() == "X"
            S = spectral_value(spec.period, spec.psa, m["period"])
            rows.append(
                [
                    m["index"],
                    direction(m["direction"]),
                    h.num(m["omega"], 4),
                    h.num(m["period"], 3),
                    share(m["damping_ratio"]),
                    h.num(S / STANDARD_GRAVITY, 3) if horizontal and math.isfinite(S) else "-",
                    h.num(1e3 * S / m["omega"] ** 2, 3)
                    if horizontal and math.isfinite(S)
                    else ("not excited by a horizontal record" if not horizontal else "-"),
                ]
            )
        parts.append(
            h.tag(
                "p",
                f"The coupled rotor-pillar modes of the reduced model the "
                f"comparison ran ({model}), read off the curve above "
                f"({100 * float(damping):g} % damping; each mode's own damping "
                "ratio is beside it):",
                class_="meta",
            )
        )
        parts.append(
            h.table(
                [
                    "mode",
                    "direction",
                    "omega (rad/s)",
                    "period T (s)",
                    "damping ratio",
                    "PSA at T (g)",
                    "S_d = PSA / omega^2 (mm)",
                ],
                rows,
            )
        )
    est, num = spec.spectral_peak_tip, spec.computed_peak_tip
    text = (
        f"Spectral estimate of the peak tip: {h.num(est, 4)} m, the square root of the sum "
        f"of the squares (SRSS) of each pillar mode's peak Gamma_j S_d(T_j, zeta_j) at its "
        f"own damping; the time history's peak on the same model: {h.num(num, 4)} m"
    )
    if isinstance(est, (int, float)) and isinstance(num, (int, float)) and est > 0:
        text += f" (computed / estimate = {h.num(num / est, 3)})"
    text += (
        ". SRSS is an estimate, not a bound: it combines the modes' peaks as if they were "
        "independent random maxima, so the true peak may fall on either side of it; a "
        "ratio below 1 says the modes' peaks did not meet in time, above 1 that they added."
    )
    parts.append(h.tag("p", text))
    if spec.note:
        parts.append(h.tag("p", spec.note, class_="meta"))
    terms = spec.modes
    periods = spec.mode_periods
    if terms:
        rows = [
            [
                t.mode,
                h.num(t.period, 4),
                h.num(1 / t.period, 4) if t.period else "-",
                share(t.damping_ratio),
                h.num(t.participation_factor, 4),
                h.num(t.s_d, 4),
                h.num(t.contribution, 4),
            ]
            for t in terms
        ]
        parts.append(
            h.details(
                "the estimate's terms: the pillar's modes (rotor apart)",
                h.table(
                    [
                        "pillar mode",
                        "period T_j (s)",
                        "frequency (Hz)",
                        "damping ratio",
                        "participation Gamma_j",
                        "S_d (m)",
                        "Gamma_j S_d (m)",
                    ],
                    rows,
                ),
            )
        )
    elif periods:
        parts.append(
            h.details(
                "the estimate's terms: the pillar's modes (rotor apart)",
                h.table(
                    ["pillar mode", "period T_j (s)", "frequency (Hz)"],
                    [[j, h.num(T, 4), h.num(1 / T, 4) if T else "-"] for j, T in enumerate(periods, start=1)],
                ),
            )
        )
    return parts
