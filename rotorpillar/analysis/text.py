"""The readable text of an analysis (what `rotorpillar analyze` prints)."""

from __future__ import annotations

from ..reduced.reduction import PillarClosedForms
from .machine import machine_text
from .results import AnalysisResult


def summary(result: AnalysisResult) -> str:
    """A readable report of an analyze result."""
    s = result.system
    lines = [
        *pillar_text(result.pillar),
        f"Pillar model (the chain): {result.pillar_model.describe()}",
        f"  {result.pillar_model.note}",
        f"  Eq. 2 on its first bending mode: m_r = {s.tip_reduction.m_reduced:.5g} kg, "
        f"c1 = {s.tip_reduction.tip_stiffness:.5g} N/m, omega = {s.tip_reduction.omega_bending:.4f} rad/s",
        f"Headline model (ROM): {s.modes} pillar mode(s) of {s.mode_source} below "
        f"{s.band_top:.4g} rad/s, the rotor on its shaft",
        f"  {'i':>2} {'dir':>3} {'omega [rad/s]':>19} {'I_i [kg]':>11} {'f_i':>10} {'2n_i':>8} "
        f"{'nu_i':>7} {'a_max [m]':>10} {'dL/Mc':>8}   paper's Eq. 4",
    ]
    paper = {(r.direction, n): r for n, r in _numbered(result.paper_model.resonances)}
    for n, r in _numbered(result.resonances):
        bar = r.uncertainty.omega.text(".4f") if r.uncertainty else f"{r.omega:.4f}"
        p_r = paper.get((r.direction, n))
        beside = f"{p_r.omega:.4f}" if p_r else "-"
        lines.append(
            f"  {r.index:>2} {r.direction:>3} {bar:>19} {r.modal_mass:>11.5g} "
            f"{r.forcing:>10.4g} {r.two_n:>8.4g} {r.nu:>7.4f} {r.a_max:>10.4g} "
            f"{_ratio(r.dL_max_over_Mc):>8}   {beside}"
        )
    lines.append(f"  error bars: {s.error_note}")
    red = result.paper_model.reduction
    lines.append(
        f"Paper's model (Eq. 4): m_r = {red.tip_mass:.5g} kg ({red.tip_mass_source}), "
        f"c1 = {red.tip_stiffness:.5g} N/m ({red.tip_stiffness_source})"
    )
    d = result.drive
    lines.append(
        f"Drive M0 = {d.torque_at_zero:g} N*m, slope {d.slope:g}: stationary speeds "
        + (", ".join(f"{x.omega:.3f} ({'stable' if x.stable else 'unstable'})" for x in d.stationary) or "none")
        + (
            f"; captured below resonance {d.captured_index} ({d.captured_resonance:.3f} "
            f"rad/s) at {d.captured_at:.3f} rad/s"
            if d.captured_index is not None
            else ""
        )
    )
    for r in result.resonances:
        lines.append("  " + r.statement)
    lines += machine_text(result.machine_checks)
    lines += _spatial_lines(result)
    if result.tower is not None:
        lines += tower_lines(result.tower)
    lines += [f"warning: {w}" for w in result.warnings]
    if not result.paper_comparison:
        return "\n".join(lines)
    lines.append("Paper's printed numbers against ours (* = differs by more than 2 %)")
    lines.append(f"  {'quantity':<34} {'paper':>11} {'computed':>11} {'diff':>8}")
    for row in result.paper_comparison:
        flag = "*" if row.flag else " "
        lines.append(f"{flag} {row.quantity:<34} {row.paper:>11.5g} {row.computed:>11.5g} {100 * row.rel_diff:>+7.1f}%")
    notes = [r for r in result.paper_comparison if r.flag and r.note]
    if notes:
        lines.append("Likely causes of the flagged differences:")
        for row in notes:
            lines.append(f"  {row.quantity}: {row.note}")
    return "\n".join(lines)


def tower_lines(t) -> list[str]:
    """The tower's block: first frequencies clamped and on the foundation, the published beside ours."""
    out = [f"Tower: {t.cans} can{'s' if t.cans > 1 else ''}, {t.tower_mass:.6g} kg, {t.top_mass:.6g} kg on top"]
    for f in t.frequencies:
        on = "" if f.on_foundation is None else f", on the foundation {f.on_foundation:.4f} Hz ({100 * f.shift:+.2f} %)"
        out.append(f"  first bending: {f.clamped:.4f} Hz clamped{on}: {f.model}")
    out.append(f"  the headline ROM's first coupled mode (X): {t.rom_first:.4f} Hz")
    if t.foundation is not None:
        k = t.foundation
        out.append(
            f"  foundation ({k.kind}): K_H = {k.horizontal:.4g} N/m, K_R = {k.rocking:.4g} N*m/rad, "
            f"K_HR = {k.coupling:.4g} N/rad"
        )
    if t.published:
        out.append(f"  published ({t.source}) against ours:")
        for r in t.published:
            out.append(
                f"    {r.quantity}: {r.published:.4f} Hz published, {r.computed:.4f} Hz {r.model} ({100 * r.difference:+.1f} %)"
            )
        if t.note:
            out.append(f"    why they differ: {t.note}")
    out.append(f"  {t.symmetry}")
    return out


def _spatial_lines(result: AnalysisResult) -> list[str]:
    """The machine in three dimensions (issue 26): planes, the other directions, the drive's reaction."""
    sp, dr = result.spatial, result.drive_reaction
    out = []
    if sp is not None:
        out.append(f"In three dimensions ({sp.mode_source}): {sp.planes.reason}")
        out.append(
            "  resonances at rest: "
            + ", ".join(
                f"{r.label} {r.omega:.4g}" for r in sp.resonances if r.omega <= 1.2 * max(result.system.band_top, 1)
            )
        )
        e = sp.planar_error
        out.append(
            f"  the planar model against it: resonances {', '.join(f'{100 * d:+.3g} %' for d in e.relative_difference)}; "
            f"largest tip response {100 * e.peak_tip_difference:+.3g} %"
        )
    if dr is not None:
        out.append(
            f"The drive's reaction: the stall torque {dr.torque:.4g} N*m on the gondola moves the top "
            f"{dr.tip_displacement * 1e3:.3g} mm in the rotor's plane and rolls it {dr.tip_rotation:.3g} rad "
            f"(base moment {dr.base_moment:.4g} N*m)"
            + (
                f"; its run-up is {dr.runup_skipped}"
                if dr.runup_skipped
                else ""
                if dr.runup is None
                else f"; in the run-up it adds up to {dr.runup.peak_reaction_part * 1e3:.3g} mm to the top's motion"
            )
        )
    return out


def _numbered(resonances):
    """(n, r): the n-th resonance of its direction, to set the two models side by side."""
    seen: dict = {}
    for r in resonances:
        seen[r.direction] = seen.get(r.direction, 0) + 1
        yield seen[r.direction], r


def _ratio(x) -> str:
    return "-" if x is None else f"{x:.3g}"


def pillar_text(p: PillarClosedForms) -> list[str]:
    """The bare tube's lines: its section, its first frequency, Eq. 2's tip mass and the
    paper's assumed shapes (a uniform tube's: a tower says it has none)."""
    return [
        "Pillar (bare tube, closed forms)" if p.statement is None else f"Pillar (bare tube): {p.statement}",
        f"  I = {p.second_moment:.5g} m^4, A = {p.area:.5g} m^2, "
        f"m_rho = {p.mass_per_length:.5g} kg/m, mass = {p.mass:.5g} kg, D/t = "
        f"{p.diameter_to_thickness:.0f}",
        f"  omega_col1 = {p.omega_col1:.4f} rad/s ({p.frequency_col1_hz:.4f} Hz) Euler-Bernoulli, "
        f"{p.omega_col1_timoshenko:.4f} Timoshenko ({100 * p.timoshenko_correction:+.2f} %)",
        "  tip mass by Eq. 2: "
        + "".join(f"n={d.n}: {d.tip_mass:.4g}, " for d in p.tip_mass_lumped[:4])
        + f"limit {p.tip_mass_limit:.4g} kg (c1 = {p.tip_stiffness_limit:.4g} N/m)",
        "  Rayleigh: "
        + (
            ", ".join(f"{d.shape}: m = {d.tip_mass:.4g} kg, c = {d.tip_stiffness:.4g} N/m" for d in p.rayleigh)
            # the lumped-mass and assumed-shape studies are the uniform tube's (the paper's Sec. 2)
            or "the paper's assumed shapes are a uniform tube's: not made for this pillar"
        ),
    ]
