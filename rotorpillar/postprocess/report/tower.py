"""The tower's section: its first frequencies (3D, beam, Rayleigh-Ritz, the ROM) clamped and on
its foundation, the published ones beside ours and why they differ, the first mode against the
excitation orders (soft-stiff), and each can's stress and buckling check.

Read through records: analyze.json's ``tower`` (rotorpillar.analysis.tower.TowerFindings),
modal.json's loaded modes, harmonic.json's ``orders`` and summary.json's per-can and
foundation checks.  Left out for a scene that is no tower (a uniform tube on a clamp with no
published numbers of its own).
"""

from __future__ import annotations

import math

from ...reduced.spatial_modes import BENDING_ACROSS, BENDING_IN_PLANE
from ...verdict.harmonic import HarmonicResult
from ...verdict.summary import EngineeringSummary
from .. import html as h
from .engineering import _read
from .state import Build


def _hz(x: float | None) -> str:
    return "-" if x is None else f"{x:.4f} Hz"


def section_tower(build: Build) -> str | None:
    a = build.analysis
    t = None if a is None else a.tower
    if t is None:
        return None
    parts = [
        h.tag(
            "p",
            f"{t.cans} can{'s' if t.cans > 1 else ''}, {h.num(t.tower_mass)} kg of steel, {h.num(t.top_mass)} kg on top (gondola and "
            "rotor). First bending frequencies, each model on a clamp and on the scene's foundation:",
        )
    ]
    rows = [
        [f.model, _hz(f.clamped), _hz(f.on_foundation), "-" if f.shift is None else h.pct(f.shift)]
        for f in t.frequencies
    ]
    m = build.modal
    if m is not None:
        for kind, name in (("bending_x", "side-side (X)"), ("bending_y", "fore-aft (Y)")):
            w = next((r.omega for r in m.modes_with_top if r.kind == kind), None)
            if w is not None:
                where = "on the scene's foundation" if t.foundation is not None else "clamped"
                label = f"3D model, {name}, the gondola on its rigid top ({where}; the rotor on its shaft left out)"
                rows.append(
                    [
                        label,
                        _hz(w / (2 * math.pi)) if t.foundation is None else "-",
                        _hz(w / (2 * math.pi)) if t.foundation is not None else "-",
                        "-",
                    ]
                )
    sp = a.spatial if a is not None else None
    if sp is not None:
        # the 3D rows above carry the gondola alone; the spatial ROM on the same modes carries the
        # rotor too (on its shaft, its diametral inertia riding on the top's tilt): the whole
        # assembly's mass on the chain's model, beside the beam's rigid assembly and the published
        for kind, name in ((BENDING_ACROSS, "fore-aft (Y)"), (BENDING_IN_PLANE, "side-side (X)")):
            w = next((r.omega for r in sp.resonances if r.kind == kind), None)
            if w is not None:
                f = _hz(w / (2 * math.pi))
                rows.append(
                    [
                        f"the spatial ROM's first mode, {name}, on {sp.mode_source} (gondola and rotor, the rotor "
                        "on its shaft)",
                        "-" if t.foundation is not None else f,
                        f if t.foundation is not None else "-",
                        "-",
                    ]
                )
    rows.append(
        [
            "the headline ROM's first coupled mode, X (the rotor on its shaft), on the chain's model",
            "-" if t.foundation is not None else _hz(t.rom_first),
            _hz(t.rom_first) if t.foundation is not None else "-",
            "-",
        ]
    )
    parts.append(h.table(["model", "clamped", "on the foundation", "shift"], rows))
    if t.foundation is not None:
        k = t.foundation
        parts.append(h.tag("h3", "The foundation"))
        parts.append(
            h.tag(
                "p",
                f"{k.kind}: K_H = {h.num(k.horizontal)} N/m, K_R = {h.num(k.rocking)} N m/rad, K_HR = "
                f"{h.num(k.coupling)} N/rad, K_V = {h.num(k.vertical)} N/m, K_T = {h.num(k.torsional)} N m/rad at "
                f"the tower's base ({k.source}). It moves the first frequency by "
                f"{h.pct(t.foundation_shift)} (the beam, clamped against on the springs).",
            )
        )
    if t.published:
        parts.append(h.tag("h3", "The published frequencies beside ours"))
        parts.append(
            h.table(
                ["quantity", "published", "ours", "our model", "difference"],
                [[r.quantity, _hz(r.published), _hz(r.computed), r.model, h.pct(r.difference, 1)] for r in t.published],
            )
        )
        parts.append(h.tag("p", f"Published: {t.source}."))
        if t.note:
            parts.append(h.tag("p", [h.tag("strong", "Why they differ: "), t.note]))
    parts.append(h.tag("p", t.symmetry, class_="meta"))
    harmonic = _read(build, "harmonic.json", HarmonicResult)
    if harmonic is not None and harmonic.orders is not None:
        o = harmonic.orders
        parts.append(h.tag("h3", "The first tower mode against the excitation orders"))
        parts.append(
            h.tag(
                "p",
                f"{o.first_mode.kind} at {_hz(o.first_mode.omega / (2 * math.pi))}: {o.regime}; orders "
                f"{', '.join(f'{k}P' for k in o.orders)}, each kept {h.pct(o.margin).lstrip('+')} away: {o.status}.",
            )
        )
        parts.append(
            h.table(
                ["running speed", "order", "excitation", "mode", "margin", "required", "status"],
                [
                    [
                        f"{r.running_speed * 60 / (2 * math.pi):.2f} rpm",
                        f"{r.order}P",
                        _hz(r.excitation / (2 * math.pi)),
                        r.position,
                        h.pct(r.actual).lstrip("+"),
                        h.pct(r.required).lstrip("+"),
                        r.status,
                    ]
                    for r in o.rows
                ],
            )
        )
    summary = _read(build, "summary.json", EngineeringSummary)
    if summary is not None:
        cans = [c for c in summary.checks if c.quantity in ("can_stress", "foundation_rotation")]
        if cans:
            parts.append(h.tag("h3", "Each can's stress and buckling, the foundation's rotation"))
            parts.append(
                h.table(
                    ["check", "demand", "capacity", "utilisation", "status", "model", "case"],
                    [
                        [
                            c.name,
                            h.num(c.demand),
                            "not stated" if c.capacity is None else h.num(c.capacity),
                            "-" if c.utilisation is None else f"{c.utilisation:.3f}",
                            c.status,
                            c.model or "-",
                            c.case or "-",
                        ]
                        for c in cans
                    ],
                )
            )
    return h.section("tower", "The tower", parts)
