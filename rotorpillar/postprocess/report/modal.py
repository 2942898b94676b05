"""The scene, the modal validation (the closed forms against the 3D model,
the reduction to the tip) and the paper's printed numbers against ours."""

from __future__ import annotations

import dataclasses
import math

from .. import html as h
from ..inputs import INPUTS, entries, plain
from .parts import failure, figures_of, scene_differs
from .state import Build


def bending(modes: list, kind: str) -> list:
    """The modes of one kind ("bending_x", "bending_y") in their order."""
    return [m for m in modes if str(m.kind) == kind]


def _mode_rows(modes: list) -> list:
    return [[i + 1, m.kind, h.num(m.n_circumferential), h.num(m.frequency_hz), h.num(m.omega),
             h.num(getattr(m, "modal_mass", None)), m.normalisation] for i, m in enumerate(modes)]


def section_scene(build: Build) -> str:
    from ...scene import SECTIONS
    d = build.scene.to_dict()
    rows = []
    for sec, cls in SECTIONS.items():
        values = d.get(sec)
        if not isinstance(values, dict):
            continue
        for f in dataclasses.fields(cls):
            rows.append([f"{sec}.{f.name}", h.num(values.get(f.name)), f.metadata.get("doc", "")])
    parts = [h.tag("p", [h.tag("strong", build.scene.name), ": ", build.scene.description or ""]),
             h.tag("p", ["Invoked as ", h.tag("code", f"rotorpillar report {build.scene_cli}"),
                         ". SI units throughout."], class_="meta"),
             h.table(["key", "value", "meaning (unit)"], rows)]
    return h.section("scene", "The scene", parts)


def _closed_forms_against_3d(a, modes: list) -> list[str]:
    """The table of the bare tube's frequencies: Euler-Bernoulli, Timoshenko, 3D."""
    p = a.pillar
    bx, by = bending(modes, "bending_x"), bending(modes, "bending_y")
    rows = []
    for k, w_eb in enumerate(p.omega_euler_bernoulli, start=1):
        w3 = bx[k - 1].omega if k - 1 < len(bx) else None
        timo = p.omega_col1_timoshenko if k == 1 else None
        rows.append([f"bending {k}, paper X", h.num(w_eb), h.num(timo), h.num(w3),
                     h.pct(w3 / w_eb - 1) if w3 else "-",
                     h.pct(w3 / timo - 1) if (w3 and timo) else "-"])
    if by and bx:
        rows.append(["bending 1, other direction", "-", "-", h.num(by[0].omega),
                     "-", h.pct(by[0].omega / bx[0].omega - 1) + " vs X"])
    shells = [x for x in modes if not str(x.kind).startswith(("bending", "axial"))]
    if shells:
        s = shells[0]
        rows.append([f"first {s.kind} mode (n = {s.n_circumferential})",
                     "none in beam theory", "-", h.num(s.omega), "-", "-"])
    return [h.table(["mode", "Eq. 1, Euler-Bernoulli (rad/s)", "Timoshenko (rad/s)",
                     "3D model (rad/s)", "3D vs Eq. 1", "3D vs Timoshenko"], rows)]


def _reduction(build: Build) -> list[str]:
    """The tip mass and stiffness: stated, closed form, 3D, and the ones used."""
    a, m = build.analysis, build.modal
    p, r = a.pillar, a.paper_model.reduction
    red3 = m.reduction if m is not None else None
    chain = a.system.tip_reduction
    stated = build.scene.reduction
    cols = [("stated in the scene", stated.tip_mass, stated.tip_stiffness),
            ("Eq. 2, continuous first mode", p.tip_mass_limit, p.tip_stiffness_limit),
            ("3D model", red3.m_reduced if red3 else None, red3.tip_stiffness if red3 else None),
            (f"the chain: {chain.source}", chain.m_reduced, chain.tip_stiffness),
            (f"the paper's model uses (m_r: {r.tip_mass_source}, c1: {r.tip_stiffness_source})",
             r.tip_mass, r.tip_stiffness)]
    rows = []
    for name, mr, c1 in cols:
        w = math.sqrt(c1 / mr) if (mr and c1) else None
        rows.append([name, h.num(mr), h.num(c1), h.num(w),
                     h.pct(w / p.omega_col1 - 1) if w else "-"])
    return [h.table(["source", "m_r (kg)", "c1 (N/m)", "sqrt(c1/m_r) (rad/s)", "vs Eq. 1"], rows),
            h.tag("p", "Eq. 2 lumped into n masses: " + ", ".join(
                f"n = {x.n}: {x.tip_mass:.4g} kg" for x in p.tip_mass_lumped) + ".", class_="meta")]


def _modes_3d(build: Build) -> list[str]:
    """The 3D modes of both configurations, with their pictures."""
    m = build.modal
    parts = []
    for key, title, name in (("modes", "Modes of the bare tube (3D)", "bare"),
                             ("modes_with_top", "Modes with the gondola and rotor on top (3D)", "top")):
        parts.append(h.tag("h3", title))
        modes = getattr(m, key, None) or []
        parts.append(h.table(["#", "kind", "n", "f (Hz)", "omega (rad/s)", "modal mass (kg)",
                              "normalisation"], _mode_rows(modes)) if modes
                     else h.tag("p", f"modal.json has no {key}.", class_="meta"))
        parts += failure(build, f"modes_{name}") + failure(build, f"load_modes_{name}")
        sheet = build.products.get(f"sheet_{name}")
        if sheet:
            parts.append(h.image(sheet.path, sheet.caption))
            singles = build.products.get(f"modes_{name}", [])
            gallery = "".join(h.image(x.path, x.caption) for x in singles)
            parts.append(h.details(f"each mode separately ({len(singles)} pictures)",
                                   f'<div class="gallery">{gallery}</div>'))
        elif not (build.out / INPUTS[f"modes_{name}"][0]).is_file():
            parts.append(h.missing(f"mode shapes not computed: run `rotorpillar modal {build.scene_cli}` "
                                   f"(no {INPUTS[f'modes_{name}'][0]})"))
    extra = [(k, v) for k, v in h.flatten({"mesh": plain(m.mesh), "axes": dict(entries(m.axes)),
                                            "timings": plain(m.timings)}) if v is not None]
    if extra:
        parts.append(h.details("3D model: mesh, axes, timings",
                               h.table(["field", "value"], [[k, h.num(v)] for k, v in extra])))
    return parts


def section_modal(build: Build) -> str:
    a, m = build.analysis, build.modal
    parts = []
    if m is None:
        parts.append(h.missing(build.hint(INPUTS["modal"][1])))
    parts += scene_differs(build, m)
    parts.append(h.tag("h3", "Eq. 1 against the 3D model (bare tube)"))
    if a is None:
        parts.append(h.missing(build.hint(INPUTS["analyze"][1])))
    else:
        parts += _closed_forms_against_3d(a, m.modes if m is not None else [])
        if m is None:
            parts.append(h.tag("p", "3D column empty: the 3D model has not run.", class_="meta"))
    parts.append(h.tag("h3", "The pillar reduced to its tip (Eq. 2)"))
    if a is None:
        parts.append(h.missing(build.hint(INPUTS["analyze"][1])))
    else:
        parts += _reduction(build)
    if m is not None:
        parts += _modes_3d(build)
    parts += figures_of(build, "modal")
    return h.section("modal", "Modal validation", parts)


def is_finding(row) -> bool:
    """A paper-comparison row that states a finding (it carries ``details``,
    e.g. eq4_base_forcing) rather than a number the paper prints."""
    return bool(getattr(row, "details", None))


def section_paper(build: Build) -> str:
    a = build.analysis
    if a is None:
        return h.section("paper", "The paper's numbers against ours",
                         [h.missing(build.hint(INPUTS["analyze"][1]))])
    rows, cls = [], []
    for r in a.paper_comparison:
        rows.append(["*" if r.flag else "", r.quantity, h.num(r.paper), h.num(r.computed),
                     h.pct(r.rel_diff, 1), r.where, getattr(r, "note", "")])
        cls.append("flag" if r.flag else "ok")
    found = [r for r in a.paper_comparison if is_finding(r)]
    printed = [r for r in a.paper_comparison if not is_finding(r)]
    n = sum(1 for r in printed if r.flag)
    parts = scene_differs(build, a) + [
        h.tag("p", f"Every number the paper prints that we compute, ours from first principles "
                   f"(never tuned to match). * = differs by more than 2 % ({n} of {len(printed)} "
                   "printed numbers); the last column gives the likely cause. Table 1's rows are "
                   "those marked 'Table 1'."
                   + (f" The last {len(found)} row(s) are findings on the paper's formulation "
                      "(the paper's column: as published; ours: the consistent one)." if found else "")),
        h.table(["", "quantity", "paper", "ours", "difference", "printed in", "likely cause"],
                rows, row_classes=cls)]
    if found:
        parts.append(h.tag("h3", "Findings on the paper's formulation"))
        parts.append(h.tag("ul", [h.tag("li", [h.tag("strong", f"{r.key} ({r.where}): "), r.note])
                                  for r in found], class_="findings"))
    return h.section("paper", "The paper's numbers against ours (Table 1 and the rest)", parts)
