"""Pieces every section uses: a product's image, a failure notice, the
figures of a group, the warning that an input is from another scene, and
the tables of a run's JSON."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ... import records
from .. import html as h
from .page import bare, model_name, plain, shown_unit
from .state import Build

if TYPE_CHECKING:
    from ...provenance import Provenance
    from ...transients.model_run import RunRecord


def product_image(build: Build, key: str) -> str:
    p = build.products[key]
    return h.image(p.path, p.caption)


def figures_of(build: Build, group: str) -> list[str]:
    """The other commands' figures that belong to ``group``."""
    return [h.image(p.path, p.caption) for p in build.external if p.group == group]


def failure(build: Build, key: str) -> list[str]:
    if key in build.failures:
        return [h.tag("p", f"{key}: could not be rendered: {build.failures[key]}", class_="failed")]
    return []


def animation_video(build: Build, key: str) -> list[str]:
    v = build.products.get(key)
    return [h.video(v.path, build.out, v.caption, v.poster)] if v else []


@dataclass(frozen=True)
class SceneChange:
    """A scene key an input was computed with another value of."""

    key: str
    """the key, dotted: ``section.key``"""
    then: Any
    """the value the input's command ran with (None: its scene had no such key)"""


def scene_changes(
    build: Build, provenance: Provenance | None, ignore: tuple[str, ...] | list[str] = ()
) -> tuple[SceneChange, ...]:
    """The scene keys an input was computed with other values of, and those values.
    ``provenance``: what its command wrote beside the record, or None; ``ignore``: dotted
    keys its command set on purpose (the comparisons' record).  The input's scene is read
    as the JSON it is (another version's scene may have other keys), key by key."""
    if provenance is None or not isinstance(provenance.scene, dict):
        return ()
    now = records.to_builtins(build.scene.to_dict())
    out = []
    for k, v in now.items():
        if not isinstance(v, dict):
            continue
        section = provenance.scene.get(k)
        for kk in v:
            then = section.get(kk) if isinstance(section, dict) else None
            if (not isinstance(section, dict) or then != v[kk]) and f"{k}.{kk}" not in ignore:
                out.append(SceneChange(f"{k}.{kk}", then))
    return tuple(out)


def differing_keys(
    build: Build, provenance: Provenance | None, ignore: tuple[str, ...] | list[str] = ()
) -> tuple[str, ...]:
    """The dotted scene keys of :func:`scene_changes`."""
    return tuple(c.key for c in scene_changes(build, provenance, ignore))


def band_keys(build: Build) -> tuple[str, ...]:
    """The scene's keys the band's top reads ([drive], [load]: chain.choice.BAND_INPUTS), dotted:
    what a stage that reads the band only by the modes inside it may differ in."""
    from ...chain.choice import BAND_INPUTS

    return tuple(f"{k}.{f.name}" for k in BAND_INPUTS for f in dataclasses.fields(getattr(build.scene, k)))


def scene_differs(build: Build, provenance: Provenance | None, ignore: tuple[str, ...] | list[str] = ()) -> list[str]:
    """A warning when an input was computed for another version of the scene."""
    diffs = differing_keys(build, provenance, ignore)
    if not diffs or provenance is None:
        return []
    return [
        h.tag(
            "p",
            "Warning: this input was computed for a different scene ("
            + ", ".join(diffs[:8])
            + (" ..." if len(diffs) > 8 else "")
            + f" differ); re-run {provenance.command or 'its command'} on this scene.",
            class_="warn",
        )
    ]


#: A run's peaks (max_abs keys) in words, in the order shown; the first name
#: of a group of equal values is the one shown.
PEAK_WORDS = {
    "tip_x_relative": "tip, horizontal (X), relative to the ground",
    "tip_x_absolute": "tip, horizontal (X), absolute",
    "tip_x": "tip, horizontal (X), in the model's frame",
    "rotor_x": "rotor centre, horizontal (X)",
    "rotor_y": "rotor centre, vertical (Y)",
    "shaft_deflection": "shaft deflection (rotor minus tip), radial",
}


def _peaks(mx: dict[str, float | None]) -> list[list]:
    """Rows of a run's largest displacements, each value once: names with
    the same value are one row (the words of the first, the others beside)."""
    items = [(k, float(v)) for k, v in mx.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    order = {k: i for i, k in enumerate(PEAK_WORDS)}
    items.sort(key=lambda kv: order.get(kv[0], len(order)))
    groups: list[list] = []
    for k, v in items:
        for g in groups:
            if abs(g[1] - v) <= 1e-12 * max(abs(v), 1e-300):
                g[2].append(k)
                break
        else:
            groups.append([k, v, []])
    # in mm to 4 digits, as every other table of peaks on the page
    return [[f"largest |{PEAK_WORDS[k]}| ({shown_unit('m')})", bare(v, "m")] for k, v, _ in groups if k in PEAK_WORDS]


def key_results(run: RunRecord) -> str:
    """The few numbers of a run a reader looks for first, each value once; a run that
    failed its own checks says so first."""
    from ...transients.case_summary import CaseSummary

    got = run
    rows = []
    if got.ok is False:
        rows.append(["FAILED: not a solution", "; ".join(got.failed_checks or ["the run reports ok: false"])])
    rows.append(["model", model_name(run.model)])
    pm = run.pillar_model
    rows.append(["pillar modes", plain(pm.describe() + (f"; {pm.note}" if pm.note else ""))])
    for value, label in (
        (got.omega_final, "final speed (rad/s)"),
        (got.captured_at, "captured at (rad/s)"),
        (got.captured_resonance, "held by the resonance at (rad/s)"),
        (None if got.speed_state is None else got.speed_state.replace("_", " "), "speed at the end"),
    ):
        if value is not None:
            rows.append([label, h.num(value)])
    if isinstance(got, CaseSummary):  # the 3D run has no jumps
        rows.append(["jumps", str(len(got.jumps))])
    error = got.energy_balance.relative_error
    if isinstance(error, (int, float)):
        rows.append(["energy balance: relative error (-)", h.num(error, 3)])
    rows += _peaks(run.max_abs)
    return h.table(["", ""], rows)
