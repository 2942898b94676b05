"""The scene, the modal validation (the closed forms against the 3D model,
the reduction to the tip) and the paper's printed numbers against ours."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from ... import records
from .. import html as h
from ..directions import axes_legend, direction, mode_name, ordinal
from ..readers import INPUTS
from .page import plain
from .parts import band_keys, failure, figures_of, scene_differs
from .state import Build

if TYPE_CHECKING:
    from ...analysis.results import AnalysisResult
    from ...fem3d.modal import ModeRow
    from ...fem3d.modal_summary import ModalSummary, ModalTop
    from ...scene import Scene


def bending(modes: Sequence[ModeRow], kind: str) -> list[ModeRow]:
    """The modes of one kind ("bending_x", "bending_y") in their order (modal.json's rows)."""
    return [m for m in modes if m.kind == kind]


def _mode_rows(modes: Sequence[ModeRow]) -> list[list[Any]]:
    return [
        [
            i + 1,
            mode_name(m.kind, m.n_axial, m.n_circumferential),
            h.num(m.n_circumferential),
            h.num(m.n_axial),
            h.num(m.frequency_hz),
            h.num(m.omega),
            h.num(m.modal_mass),
        ]
        for i, m in enumerate(modes)
    ]


MODE_HEADERS = [
    "#",
    "mode",
    "waves around",
    "nodes along the height",
    "f (Hz)",
    "omega (rad/s)",
    "modal mass (kg)",
]


def base_words(foundation) -> str:
    """How the 3D tube's base stands (the scene's ``[foundation]``): "clamped base", or the
    base on the foundation's springs (the 3D model ties it to a rigid plate on them).

    >>> from rotorpillar.scene import load_scene
    >>> base_words(load_scene("paper").foundation), base_words(load_scene("nrel5mw").foundation)
    ('clamped base', "base on the footing's springs")
    """
    return "clamped base" if foundation.kind == "clamped" else f"base on the {foundation.kind}'s springs"


def top_words(top: ModalTop | None) -> tuple[str, str]:
    """(what the tube's top carries, why), from modal.json's ``top`` block (None: unknown).

    >>> from rotorpillar.fem3d.modal_summary import ModalTop
    >>> top_words(ModalTop("rigid", 2300.0, "gondola", (0.0, 0.0, 20.0), None, 25.6, ""))[0]
    'the gondola (2300 kg) on a rigid top plate'
    """
    if top is None:
        return "its top mass", ""
    carries = (top.carries or "its top mass").replace("_", " ")
    mass = top.mass
    how = {"rigid": "on a rigid top plate", "ring_mass": "spread on the top face"}.get(str(top.model or ""), "")
    what = (
        f"the {carries}" + (f" ({mass:.4g} kg)" if isinstance(mass, (int, float)) else "") + (f" {how}" if how else "")
    )
    why = (
        "The rotor is not on it: it hangs on its elastic shaft, which the reduced model adds "
        "to these modes (stiffness c2), so the coupled rotor-pillar resonances are the reduced "
        "model's, not these."
        if "rotor" not in carries
        else "The rotor sits on the top rigidly here: its shaft's elasticity is left out."
    )
    return what, why


def _as_written(value: Any) -> Any:
    """A scene field's value as the scene's TOML writes it: a tuple of sections (the tower's
    cans) as a list of their keys and values, anything else as it is."""
    if isinstance(value, tuple) and all(dataclasses.is_dataclass(v) for v in value):
        return [dataclasses.asdict(v) for v in value]
    return value


def section_scene(build: Build) -> str:
    from ...scene import SECTIONS
    from .scene_runs import earthquake_stages, ran_with, stages_table

    stages = earthquake_stages(build)
    beside = dict(ran_with(stages))  # what the earthquake stages ran with instead, key by key
    rows = []
    for sec, cls in SECTIONS.items():
        section = getattr(build.scene, sec)
        for f in dataclasses.fields(cls):
            key = f"{sec}.{f.name}"
            value = h.num(_as_written(getattr(section, f.name)))
            if key in beside:
                value += f" (the scene's; the earthquake stages ran with {beside[key]}: see below)"
            rows.append([key, value, f.metadata.get("doc", "")])
    parts = [
        h.tag("p", [h.tag("strong", build.scene.name), ": ", build.scene.description or ""]),
        h.tag(
            "p",
            [
                "Invoked as ",
                h.tag("code", f"rotorpillar report {build.scene_cli}"),
                ". SI units throughout. ",
                axes_legend(),
            ],
            class_="meta",
        ),
        h.details(f"every key of the scene ({len(rows)})", h.table(["key", "value (SI)", "meaning (unit)"], rows)),
        *stages_table(stages),
    ]
    return h.section("scene", "The scene", parts)


def timoshenko_orders(scene: Scene, count: int) -> list[float | None]:
    """The first ``count`` Timoshenko frequencies of the bare tube (rad/s;
    None where the closed form does not resolve one): the closed form of
    ``reduced.pillar`` on the scene's tube, shear and rotary inertia included."""
    from ...reduced.pillar import cowper_shear_coefficient, omega_timoshenko, section_of

    p = scene.pillar
    if not p.is_uniform or scene.foundation.kind != "clamped":
        return [None] * count  # a uniform tube's on a clamp (analyze.json's closed forms say what stands instead)
    sec = section_of(p)
    kappa = cowper_shear_coefficient(sec.outer_diameter, sec.inner_diameter, p.poisson_ratio)
    out: list[float | None] = []
    for k in range(1, count + 1):
        try:
            out.append(
                omega_timoshenko(
                    p.youngs_modulus, p.poisson_ratio, kappa, p.density, sec.area, sec.second_moment, p.height, k
                )
            )
        except (ValueError, RuntimeError):
            out.append(None)
    return out


def _closed_forms_against_3d(build: Build, a: AnalysisResult, modes: Sequence[ModeRow]) -> list[str]:
    """The table of the bare tube's frequencies: Euler-Bernoulli, Timoshenko, 3D."""
    p = a.pillar
    bx, by = bending(modes, "bending_x"), bending(modes, "bending_y")
    timo = timoshenko_orders(build.scene, len(p.omega_euler_bernoulli))
    rows = []
    for k, w_eb in enumerate(p.omega_euler_bernoulli, start=1):
        w3 = bx[k - 1].omega if k - 1 < len(bx) else None
        t = timo[k - 1]
        rows.append(
            [
                f"{ordinal(k)} bending, {direction('X')}",
                h.num(w_eb),
                h.num(t),
                h.num(w3),
                h.pct(w3 / w_eb - 1) if w3 else "-",
                h.pct(t / w_eb - 1) if t else "-",
                h.pct(w3 / t - 1) if (w3 and t) else "-",
            ]
        )
    if by and bx:
        w_y, w_x = by[0].omega, bx[0].omega
        rows.append([f"1st bending, {direction('Z')}", "-", "-", h.num(w_y), "-", "-", h.pct(w_y / w_x - 1) + " vs X"])
    shells = [x for x in modes if not x.kind.startswith(("bending", "axial"))]
    if shells:
        s0 = shells[0]
        rows.append(
            [
                mode_name(s0.kind, s0.n_axial, s0.n_circumferential),
                "none in beam theory",
                "-",
                h.num(s0.omega),
                "-",
                "-",
                "-",
            ]
        )
    parts = [
        h.table(
            [
                "mode",
                "Eq. 1, Euler-Bernoulli (rad/s)",
                "Timoshenko (rad/s)",
                "3D model (rad/s)",
                "3D vs Eq. 1",
                "Timoshenko vs Eq. 1",
                "3D vs Timoshenko",
            ],
            rows,
        )
    ]
    if len(bx) >= 2 and len(timo) >= 2 and timo[1]:
        w3, t, eb = bx[1].omega, timo[1], p.omega_euler_bernoulli[1]
        parts.append(
            h.tag(
                "p",
                f"The 2nd bending mode's {h.pct(w3 / eb - 1)} against Eq. 1 is "
                f"shear deformation and rotary inertia, which Eq. 1 leaves out: "
                f"Timoshenko's beam, which has them, is {h.pct(t / eb - 1)} from "
                f"Eq. 1, and the 3D model lies within {h.pct(w3 / t - 1)} of it.",
                class_="meta",
            )
        )
    return parts


def _reduction(build: Build, a: AnalysisResult) -> list[str]:
    """The tip mass and stiffness: stated, closed form, 3D, and the ones used."""
    m = build.modal
    p, r = a.pillar, a.paper_model.reduction
    red3 = m.reduction if m is not None else None
    chain = a.system.tip_reduction
    stated = build.scene.reduction
    cols = [
        ("stated in the scene", stated.tip_mass, stated.tip_stiffness),
        ("Eq. 2, continuous first mode", p.tip_mass_limit, p.tip_stiffness_limit),
        ("3D model", None if red3 is None else red3.m_reduced, None if red3 is None else red3.tip_stiffness),
        (f"the ROM's reduction: {chain.source}", chain.m_reduced, chain.tip_stiffness),
        (
            f"the paper's model uses (m_r: {r.tip_mass_source}, c1: {r.tip_stiffness_source})",
            r.tip_mass,
            r.tip_stiffness,
        ),
    ]
    rows = []
    for name, mr, c1 in cols:
        w = math.sqrt(c1 / mr) if (mr and c1) else None
        rows.append([name, h.num(mr), h.num(c1), h.num(w), h.pct(w / p.omega_col1 - 1) if w else "-"])
    return [
        h.table(["source", "m_r (kg)", "c1 (N/m)", "sqrt(c1/m_r) (rad/s)", "vs Eq. 1"], rows),
        h.tag(
            "p",
            "Eq. 2 lumped into n masses: "
            + ", ".join(f"n = {x.n}: {x.tip_mass:.4g} kg" for x in p.tip_mass_lumped)
            + ".",
            class_="meta",
        ),
    ]


def _modes_3d(build: Build, m: ModalSummary) -> list[str]:
    """The 3D modes of both configurations, with their pictures."""
    parts = []
    carries, why = top_words(m.top)
    for key, title, name in (
        ("modes", f"Modes of the bare tube (3D), {base_words(build.scene.foundation)}, free top", "bare"),
        ("modes_with_top", f"Modes of the tube carrying {carries} (3D)", "top"),
    ):
        parts.append(h.tag("h3", title))
        if name == "top" and why:
            parts.append(h.tag("p", why, class_="meta"))
        modes: Sequence[ModeRow] = getattr(m, key)
        parts.append(
            h.table(MODE_HEADERS, _mode_rows(modes))
            if modes
            else h.tag("p", f"modal.json has no {key}.", class_="meta")
        )
        parts += failure(build, f"modes_{name}") + failure(build, f"load_modes_{name}")
        sheet = build.products.get(f"sheet_{name}")
        if sheet:
            parts.append(h.image(sheet.path, sheet.caption))
            singles = build.mode_pictures.get(name, [])
            gallery = "".join(h.image(x.path, x.caption) for x in singles)
            parts.append(
                h.details(f"each mode separately ({len(singles)} pictures)", f'<div class="gallery">{gallery}</div>')
            )
        elif not (build.out / INPUTS[f"modes_{name}"][0]).is_file():
            parts.append(
                h.missing(
                    f"mode shapes not computed: run `rotorpillar modal {build.scene_cli}` "
                    f"(no {INPUTS[f'modes_{name}'][0]})"
                )
            )
    written = build.provenance.modal
    timings = written.timings if written is not None else None
    extra = [
        (k, v)
        for k, v in h.flat_items(
            {"mesh": records.to_builtins(m.mesh), "axes": records.to_builtins(m.axes), "timings": timings}
        )
        if v is not None
    ]
    parts.append(
        h.tag(
            "p",
            axes_legend() + " Every picture carries a triad with the paper's "
            "symbols: X horizontal in the rotor's plane, Z along the shaft, Y up.",
            class_="meta",
        )
    )
    if extra:
        parts.append(
            h.details(
                "3D model: mesh, axes, timings", h.table(["field", "value (SI)"], [[k, h.num(v)] for k, v in extra])
            )
        )
    return parts


def _same_cut(build: Build) -> tuple[str, ...]:
    """[drive] and [load]'s keys when modal.json's modes are also the cut at this scene's
    band edge (modal ran for another drive: `run` keeps it then, commands.run.modal_band);
    none otherwise, so that the warning names them."""
    from ...reduced.band import cut_stands, excitation_band

    m = build.modal
    if m is None:
        return ()
    edge = excitation_band(build.scene.drive, build.scene.load, build.scene.converge).omega_max
    listed = [[row.omega for row in rows] for rows in (m.modes, m.modes_with_top)]
    return band_keys(build) if all(cut_stands(omega, edge) for omega in listed) else ()


def section_modal(build: Build) -> str:
    a, m = build.analysis, build.modal
    parts = []
    if m is None:
        parts.append(h.missing(build.hint(INPUTS["modal"][1])))
    parts += scene_differs(build, build.provenance.modal, _same_cut(build))
    parts.append(h.tag("h3", "Eq. 1 against the 3D model (bare tube)"))
    if a is None:
        parts.append(h.missing(build.hint(INPUTS["analyze"][1])))
    else:
        parts += _closed_forms_against_3d(build, a, m.modes if m is not None else ())
        if m is None:
            parts.append(h.tag("p", "3D column empty: the 3D model has not run.", class_="meta"))
    parts.append(h.tag("h3", "The pillar reduced to its tip (Eq. 2)"))
    if a is None:
        parts.append(h.missing(build.hint(INPUTS["analyze"][1])))
    else:
        parts += _reduction(build, a)
    if m is not None:
        parts += _modes_3d(build, m)
    parts += figures_of(build, "modal")
    return h.section("modal", "Modal validation", parts)


def is_finding(row) -> bool:
    """A paper-comparison row that states a finding (it carries ``details``,
    e.g. eq4_base_forcing) rather than a number the paper prints."""
    return bool(getattr(row, "details", None))


#: How analysis/paper.py appends the case a row is computed on to where it is printed.
OURS = "; ours: "


def _fe_note(build: Build, r) -> str:
    """The 3D tube with its top beside the paper's FE model (its first X bending)."""
    if not str(r.key).startswith("fe_omega") or build.modal is None:
        return ""
    bx = bending(build.modal.modes_with_top, "bending_x")
    if not bx or r.key != "fe_omega1":
        return ""
    carries, _ = top_words(build.modal.top)
    w = bx[0].omega
    return (
        f" Our 3D tube carrying {carries}, without the rotor: {w:.2f} rad/s "
        f"({w / r.paper - 1:+.1%} against the printed value)."
    )


def section_paper(build: Build) -> str:
    a = build.analysis
    if a is None:
        return h.section("paper", "The paper's numbers against ours", [h.missing(build.hint(INPUTS["analyze"][1]))])
    found = [r for r in a.paper_comparison if is_finding(r)]
    printed = [r for r in a.paper_comparison if not is_finding(r)]
    rows, cls = [], []
    for r in a.paper_comparison:
        where, _, ours = plain(r.where).partition(OURS)
        note = getattr(r, "note", "") or ""
        if is_finding(r):
            note = h.Raw(h.esc("a finding on the paper's formulation: ") + h.link("see below", "paper-findings"))
        else:
            note = plain(note + _fe_note(build, r))
        rows.append(
            [
                "*" if r.flag else "",
                r.quantity,
                h.num(r.paper),
                h.num(r.computed),
                h.pct(r.rel_diff, 1),
                where,
                ours or "this scene",
                note,
            ]
        )
        cls.append("flag" if r.flag else "ok")
    n = sum(1 for r in printed if r.flag)
    parts = scene_differs(build, build.provenance.analyze) + [
        h.tag(
            "p",
            f"Every number the paper prints that we compute, ours from first principles "
            f"(never tuned to match), each computed on the case the paper's text gives it: "
            f"Table 1 and Eq. 24 with the stiff shaft, the Sec. 3 finite-element model's "
            f"with the rotor on that shaft. * = differs by more than 2 % ({n} of "
            f"{len(printed)} printed numbers); the last column gives the likely cause.",
        ),
        h.table(
            [
                "",
                "quantity",
                "paper (its unit)",
                "ours (same unit)",
                "difference",
                "printed in",
                "ours computed on",
                "likely cause",
            ],
            rows,
            row_classes=cls,
        ),
    ]
    if found:
        parts.append(h.tag("h3", "Findings on the paper's formulation", id="paper-findings"))
        parts.append(
            h.tag(
                "ul",
                [h.tag("li", [h.tag("strong", f"{r.quantity} ({r.where}): "), r.note]) for r in found],
                class_="findings",
            )
        )
    return h.section("paper", "The paper's numbers against ours (Table 1 and the rest)", parts)
