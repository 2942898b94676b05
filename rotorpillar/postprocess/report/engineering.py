"""The engineer's sections: the verdict that opens the Summary, the internal
forces and stresses, the unbalance response (Bode), the Campbell diagram and
the separation margins.

Read through their records: summary.json (``verdict.summary.EngineeringSummary``,
written by `rotorpillar report` before the page), harmonic.json
(``HarmonicResult``) and each run's ``internal_forces``
(``transients.forces.InternalForcesSummary``, read with its run's record) with
its NPZ histories.
Charts by :mod:`rotorpillar.postprocess.engineering_charts`.
"""

from __future__ import annotations

from ... import records
from ...verdict.harmonic import HarmonicResult
from ...verdict.summary import EngineeringSummary
from .. import html as h
from .force_runs import ForcePair, ForcesRun, every_forces_run, forces_runs, history, like_pairs
from .page import plain
from .state import FIGURES_DIR, Build

NAMES = {"modal": "ROM", "fem3d": "3D full order", "beam": "1D beam full order", "paper": "paper Eq. 4"}
#: where a mode of the separation table comes from
MODE_SOURCES = {"modal": "ROM, coupled system", "fem3d": "3D, loaded tube"}
UNITS = {"Pa": (1e-6, "MPa"), "m": (1e3, "mm"), "N": (1e-3, "kN"), "N*m": (1e-6, "MN m"), "-": (100, "%")}


def _read(build: Build, name: str, record, command: str | None = None):
    """The record in ``name``, or None (missing, or damaged: named in the report's failures,
    and under ``command``, the one that rebuilds it, in its ``damaged``)."""
    path = build.out / name
    if not path.is_file():
        return None
    try:
        return records.read(path, record)
    except (ValueError, OSError) as exc:
        build.failures[f"input {name}"] = f"{type(exc).__name__}: {exc}"
        if command is not None:
            build.damaged[command] = f"{name} is damaged ({str(exc).removeprefix(f'{name}: ')})"
        return None


def _sentence(text: str) -> str:
    """``text`` with its first letter a capital (the rest as it is: file names, keys).

    >>> _sentence("not computed: run `rotorpillar harmonic paper`")
    'Not computed: run `rotorpillar harmonic paper`'
    """
    return text[:1].upper() + text[1:]


def _value(x, unit: str, digits: int = 4) -> str:
    if x is None:
        return "-"
    scale, shown = UNITS.get(unit, (1.0, unit))
    return f"{h.num(scale * x, digits)} {shown}"


def _check_rows(checks) -> list[list]:
    rows = []
    for c in checks:
        demand = _value(c.demand, c.unit) if c.unit != "-" else h.pct(c.demand).lstrip("+")
        cap = (
            (_value(c.capacity, c.unit) if c.unit != "-" else h.pct(c.capacity).lstrip("+"))
            if c.capacity is not None
            else "not stated"
        )
        util = "-" if c.utilisation is None else f"{c.utilisation:.3f}"
        names = MODE_SOURCES if c.quantity == "separation_margin" else NAMES
        rows.append(
            [
                c.name,
                demand,
                cap,
                util,
                h.tag("strong", c.status) if c.status == "fail" else c.status,
                names.get(c.model, c.model or "-"),
                c.case or "-",
            ]
        )
    return rows


# --------------------------------------------------------------------------
# Forces and stresses


def section_internal_forces(build: Build) -> str:
    runs = forces_runs(build)
    if not runs:
        return h.section(
            "forces",
            "Internal forces and stresses",
            [
                h.missing(
                    f"No run with internal forces: run `rotorpillar compare {build.scene_cli} --case "
                    "earthquake` (or `simulate`)"
                )
            ],
        )
    parts = [
        h.tag(
            "p",
            "Section forces of the pillar (V, M along the rotor's plane X; N axial, "
            "compression positive) and the base's extreme-fibre stress |M| c/I + N/A, "
            "peaks over each run. The ROM superposes its modes' section resultants with "
            "at least as many modes as the base moment needs for 1 % over its band and as "
            "carry 90 % of the machine's mass along X (EN 1998-1); the "
            "full orders read their own element forces. Self-weight, gondola and rotor "
            "enter N(z) under g. The shaft: its radial deflection |d|, the force its spring "
            "carries c2 |d| and the force on the bearing, spring and damper together "
            "|c2 d + b2 v|; the shaft force check takes the larger of the two forces.",
        )
    ]
    rows = []
    for r in runs:
        f, b = r.forces, r.forces.base
        rows.append(
            [
                NAMES.get(f.model, f.model),
                r.case,
                _value(b.moment, "N*m"),
                _value(b.shear, "N"),
                f"{_value(b.axial_min, 'N')} ... {_value(b.axial_max, 'N')}",
                _value(b.stress, "Pa"),
                h.num(b.moment_time, 4),
                _value(f.shaft.deflection, "m"),
                _value(f.shaft.spring_force, "N"),
                _value(f.shaft.bearing_force, "N"),
                "-" if f.modes is None else f.modes,
                r.window,
            ]
        )
    parts.append(h.tag("h3", "Base reactions and shaft demand, side by side"))
    parts.append(
        h.table(
            [
                "model",
                "case",
                "|M(0)| max",
                "|V(0)| max",
                "N(0)",
                "base stress",
                "at t (s)",
                "shaft deflection, radial |d|",
                "shaft spring force c2 |d|",
                "bearing force |c2 d + b2 v|",
                "modes",
                "run covers",
            ],
            rows,
        )
    )
    parts += _differences(like_pairs(every_forces_run(build)))
    by_case: dict[str, list[ForcesRun]] = {}
    for r in runs:
        by_case.setdefault(r.case, []).append(r)
    from .. import engineering_charts as ec
    from . import kept

    fig = build.out / FIGURES_DIR
    for case, items in by_case.items():
        stem = case.split(" ")[0]
        key = f"envelope_{stem}"
        p = kept.chart(
            build,
            key,
            fig / f"forces_{stem}.png",
            ec.envelope_chart,
            fig / f"forces_{stem}.png",
            [
                (NAMES.get(f.model, f.model), f.model, f.heights, f.moment_envelope, f.shear_envelope)
                for f in (r.forces for r in items)
            ],
            title=f"{case}: envelopes along the height",
        )
        if p:
            parts.append(
                h.image(p, f"{case}: the largest |M(z)| and |V(z)| over the run at each section height, per model.")
            )
        series = [
            (NAMES.get(r.forces.model, r.forces.model), r.forces.model, *hist)
            for r in items
            for hist in [history(build, r, "base_moment")]
            if hist is not None
        ]
        if series:
            p = kept.chart(
                build,
                f"base_moment_{stem}",
                fig / f"base_moment_{stem}.png",
                ec.history_chart,
                fig / f"base_moment_{stem}.png",
                series,
                "base moment [MN m]",
                1e-6,
                title=f"{case}: the base moment",
            )
            if p:
                parts.append(h.image(p, f"{case}: the base moment M(0, t), per model overlaid."))
    parts += _truncation(runs) + _von_mises(runs) + _buckling_and_details(build)
    return h.section("forces", "Internal forces and stresses", parts)


def _differences(pairs: list[ForcePair]) -> list[str]:
    rows = []
    for p in pairs:
        rom, ref = p.rom.forces, p.reference.forces
        window = (
            f"both: {p.rom.window}"
            if p.same_window
            else f"ROM: {p.rom.window}; {NAMES[ref.model]}: {p.reference.window} (not the same window: "
            "the difference is not the ROM's error alone)"
        )
        for key, label in (("moment", "|M(0)| max"), ("shear", "|V(0)| max"), ("stress", "base stress")):
            a, b = getattr(rom.base, key), getattr(ref.base, key)
            rows.append([p.rom.case, label, NAMES[ref.model], h.pct(a / b - 1 if b else None), window])
        rows.append(
            [
                p.rom.case,
                "shaft deflection",
                NAMES[ref.model],
                h.pct(rom.shaft.deflection / ref.shaft.deflection - 1 if ref.shaft.deflection else None),
                window,
            ]
        )
    if not rows:
        return []
    return [
        h.tag("h3", "The ROM against the full order"),
        h.tag(
            "p",
            "Each row sets the ROM's peak beside the full order's over the same stretch of the case "
            "(compare's runs over the full order's window), where one was run; the last column says what "
            "each run covers.",
        ),
        h.table(["case", "quantity", "reference", "ROM - reference", "window compared"], rows),
    ]


def _truncation(runs) -> list[str]:
    f = next((r.forces for r in runs if r.forces.truncation is not None), None)
    if f is None:
        return []
    t = f.truncation
    need = lambda k: str(k) if k is not None else f"more than the {t.modes_available} available"
    rows = [
        [r.modes, h.pct(r.tip, 3).lstrip("+"), h.pct(r.base_moment, 3).lstrip("+"), h.pct(r.base_shear, 3).lstrip("+")]
        for r in t.rows
    ]
    return [
        h.tag("h3", "How many modes the forces need"),
        h.tag(
            "p",
            f"{plain(t.statement)}. For {100 * t.tolerance:g} % the tip needs {need(t.modes_needed_tip)}, "
            f"the base moment {need(t.modes_needed_base_moment)}, the base shear "
            f"{need(t.modes_needed_base_shear)} modes: the forces use {f.modes}, with which "
            f"the base shear's error is {h.pct(t.rows[f.modes - 1].base_shear, 1).lstrip('+')}"
            f" (the modes left out carry mass the shear feels). "
            + ("" if f.mass is None else f"The ROM for forces keeps {plain(f.mass.reason)}. ")
            + f.note,
        ),
        h.details("errors per number of modes", h.table(["modes", "tip", "base moment", "base shear"], rows)),
    ]


def _von_mises(runs: list[ForcesRun]) -> list[str]:
    out = []
    for r in runs:
        f = r.forces
        vm = f.von_mises
        if vm is None:
            continue
        rows = []
        for label, p in (
            ("peak", vm.peak),
            (f"at the clamp (z <= {vm.clamp_zone:.3f} m)", vm.clamp),
            ("above the clamp's boundary layer", vm.away_from_clamp),
        ):
            rows.append(
                [
                    label,
                    _value(p.value, "Pa"),
                    f"({p.position[0]:.3f}, {p.position[1]:.3f}, {p.position[2]:.3f})",
                    h.num(p.time, 4),
                    _value(p.nominal, "Pa"),
                    h.num(p.ratio, 4),
                ]
            )
        out += [
            h.tag("h3", f"Stresses in the 3D tube: {r.case}"),
            h.tag(
                "p",
                f"Von Mises stress of the 3D full order ({r.file}), {vm.space}; "
                f"{vm.gravity}; over {vm.instants} instants (the time series' frames and "
                "the peaks of base moment and shear). The ratio at the clamp is its stress "
                "concentration over the section's nominal stress |M| c/I + N/A there; a "
                "linear elastic corner makes it mesh-dependent, the nominal stress is not."
                + (f" ParaView: {f.stress_field} (displacement and von Mises)." if f.stress_field else ""),
            ),
            h.table(["where", "von Mises", "position (x, y, z) (m)", "t (s)", "nominal", "ratio (-)"], rows),
        ]
    return out


def _buckling_and_details(build: Build) -> list[str]:
    s = _read(build, "summary.json", EngineeringSummary)
    if s is None:
        return []
    out = []
    b = s.buckling
    if b is not None:
        out += [
            h.tag("h3", "Shell buckling resistance (EN 1993-1-6)"),
            h.tag(
                "p",
                f"{b.clause}: r = {b.radius:.4g} m, t = {b.thickness:.4g} m, l = {b.length:.4g} m, "
                f"omega = {b.omega:.4g} ({b.length_class} cylinder), C_x = {b.cx:.4g}, "
                f"sigma_x,Rcr = {_value(b.critical_stress, 'Pa')}; class {b.quality_class}: "
                f"alpha_x = {b.alpha:.4g}, lambda_x = {b.slenderness:.4g}, lambda_p = "
                f"{b.plastic_slenderness:.4g}, chi = {b.chi:.4g}; sigma_x,Rk = "
                f"{_value(b.characteristic_stress, 'Pa')}, sigma_x,Rd = "
                f"{_value(b.design_stress, 'Pa')} (gamma_M1 = {b.gamma_m1:g}).",
            ),
        ]
    out.append(
        h.details(
            "every check on every model and case",
            h.table(
                ["check", "demand", "capacity", "utilisation (-)", "status", "model", "case"],
                _check_rows(s.check_details),
            ),
        )
    )
    return out


# --------------------------------------------------------------------------
# Unbalance response and margins


def section_unbalance(build: Build) -> str:
    r = _read(build, "harmonic.json", HarmonicResult, "harmonic")
    title = "Unbalance response (Bode) and separation margins"
    if r is None:
        return h.section("unbalance", title, [h.missing(_sentence(build.hint("harmonic")))])
    from .. import engineering_charts as ec
    from . import kept

    fig = build.out / FIGURES_DIR
    curves = [c for c in (r.rom, r.fem3d) if c is not None]
    parts = [
        h.tag(
            "p",
            f"Steady response to the unbalance at constant speed, up to {r.band_top:.4g} rad/s: "
            f"{r.rom_model}; {r.fem3d_model}. The averaging's Eq. 19 near each resonance "
            "(dotted) is the first-order expansion of the ROM's curve about it.",
        )
    ]
    p = kept.chart(
        build, "bode", fig / "bode.png", ec.bode_chart, fig / "bode.png", curves, r.averaging, r.running_speeds
    )
    if p:
        parts.append(
            h.image(
                p,
                "Amplitude and phase lag of the tip (left) and of the shaft deflection "
                "(right) against the rotor speed: the ROM (dashed), the 3D model (dots), "
                "Eq. 19 (dotted); the running speed dash-dotted.",
            )
        )
    rows = [
        [
            h.num(x.omega, 5),
            "-" if x.rom_speed is None else h.num(x.rom_speed, 5),
            _value(x.rom_amplitude, "m"),
            "-" if x.fem3d_speed is None else h.num(x.fem3d_speed, 5),
            _value(x.fem3d_amplitude, "m"),
            _value(x.averaging_amplitude, "m"),
            h.pct(x.amplitude_difference),
        ]
        for x in r.peaks
    ]
    parts.append(
        h.table(
            [
                "omega_i, undamped (rad/s)",
                "ROM peak at (rad/s)",
                "ROM tip",
                "3D peak at (rad/s)",
                "3D tip",
                "Eq. 19 at omega_i",
                "3D / ROM - 1",
            ],
            rows,
        )
    )
    cost = (
        f"Cost of one speed: the ROM {r.rom_seconds_per_speed:.3g} s"
        + (
            f", the 3D model {r.fem3d_seconds_per_speed:.3g} s (one LU of its real block form)"
            if r.fem3d_seconds_per_speed
            else ""
        )
        + " (wall time on a shared machine; bench/ has ratios)."
    )
    parts.append(h.tag("p", cost))
    p = kept.chart(
        build,
        "campbell",
        fig / "campbell.png",
        ec.campbell_chart,
        fig / "campbell.png",
        r.modes,
        r.running_speeds,
        r.band_top,
        orders=() if r.orders is None else r.orders.orders,
    )
    parts.append(h.tag("h3", "Separation margins (API 684)"))
    if p:
        parts.append(
            h.image(
                p,
                "Campbell diagram: each structural mode (the ROM's coupled system dashed, "
                "the loaded tube's 3D modes solid), the 1x line, the running speed, and "
                "the speeds API 684 keeps clear of each mode (red: a running speed inside).",
            )
        )
    rows = [
        [
            MODE_SOURCES.get(x.mode.model, x.mode.model),
            x.mode.kind,
            h.num(x.mode.omega, 5),
            h.num(x.mode.damping_ratio, 3),
            ("no peak" if "no peak" in getattr(x, "af_source", "") else "inf")
            if x.amplification_factor is None
            else h.num(x.amplification_factor, 3),
            x.position,
            h.pct(x.required).lstrip("+"),
            h.pct(x.actual).lstrip("+"),
            h.tag("strong", x.status) if x.status == "fail" else x.status,
        ]
        for x in r.separation
    ]
    parts.append(
        h.table(
            [
                "model",
                "mode",
                "natural frequency, undamped (rad/s)",
                "damping ratio (-)",
                "amplification factor (-)",
                "position",
                "required",
                "actual",
                "status",
            ],
            rows,
            row_classes=["failed" if x.status == "fail" else "" for x in r.separation],
        )
    )
    parts.append(
        h.tag(
            "p",
            "AF: the half-power AF N_c / (N_2 - N_1) of the unbalance response's peak near the "
            "mode, as API 684 reads it (the spatial ROM's response on the curves the mode moves; "
            "for the loaded tube's 3D modes also the 3D response's, the larger); API 684 asks "
            "17 (1 - 1/(AF - 1.5)) % below the running speed and 10 % more above it, nothing "
            "when AF < 2.5, and nothing of a mode the response shows no peak at (no peak). "
            "zeta: the mode's damping ratio (b1 at the tip both ways, pillar.damping_ratio on "
            "every pillar mode, b2 on the rotor relative to the gondola).",
        )
    )
    for n in r.notes:
        parts.append(h.tag("p", n, class_="warn"))
    return h.section("unbalance", title, parts)
