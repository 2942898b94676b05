"""The PNGs other commands left in the out folder, and the section each belongs to."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from .state import OWN_DIRS


def external_figures(out: Path) -> list[tuple[Path, str]]:
    """PNGs other commands wrote in ``out`` (and its direct subfolders, not ours),
    with the caption a JSON beside them gives in a ``figures`` list
    ({"file" or "path", "caption"}), else one made from the file name."""
    captions = {}
    for js in sorted(out.glob("*.json")):
        try:
            doc = json.loads(js.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        figs = doc.get("figures") if isinstance(doc, dict) else None
        if isinstance(figs, list):
            for f in figs:
                if isinstance(f, dict) and (f.get("file") or f.get("path")):
                    name = Path(str(f.get("file") or f.get("path"))).name
                    captions[name] = str(f.get("caption", ""))
        elif isinstance(figs, dict):
            for k, v in figs.items():
                if isinstance(v, dict):
                    name = Path(str(v.get("file") or v.get("path") or k)).name
                    captions[name] = str(v.get("caption", ""))
                elif isinstance(v, str):
                    captions[Path(v).name] = str(k).replace("_", " ")
    found, seen = [], {}
    # the folder itself and its direct subfolders only: --out may point
    # anywhere, and a deep search could sweep up unrelated pictures
    paths = sorted([*out.glob("*.png"), *out.glob("*/*.png")],
                   key=lambda p: (-len(p.stem), str(p)))   # a model's own name before its copy
    for p in paths:
        rel = p.relative_to(out)
        if rel.parts[0] in OWN_DIRS or any(part.startswith(".") for part in rel.parts):
            continue
        try:
            digest = hashlib.sha256(p.read_bytes()).hexdigest()
        except OSError:
            continue
        if digest in seen:          # the same picture under two names (simulate's copy)
            continue
        seen[digest] = p
        # ours first: integrators.json's caption says wall time where the axis is evaluations
        found.append((p, CAPTIONS.get(p.name) or captions.get(p.name)
                      or p.stem.replace("_", " ")))
    return sorted(found, key=lambda x: str(x[0]))


#: Captions of the charts other commands write without one.
CAPTIONS = {
    "convergence_dofs.png": (
        "Convergence of the pillar models: |relative error| of the first bending frequency, "
        "of the first ovalling frequency, and the error bound on the band's frequencies (what "
        "the choice uses) against the degrees of freedom. Lines: one model family each; circles "
        "(and the grey staircase): the Pareto front, no run both cheaper and more accurate; "
        "star: the model chosen; red dotted line: the tolerance; grey band: the reference's own "
        "uncertainty (errors inside it cannot be told apart); x on the top strip: a run without "
        "that mode."),
    "convergence_time.png": (
        "The same against the wall time per run (on this machine, shared: a noisy measure): "
        "circles: the Pareto front; star: the choice; red dotted line: the tolerance; grey band: "
        "the reference's uncertainty."),
    "integrators.png": (
        "Time integrators. Top: error of the tip history against the number of force "
        "evaluations on a run-up (dashed lines: fixed-step methods; dotted: 10 % error). "
        "Middle: force evaluations as stiffer pillar modes are added (x: the method failed). "
        "Bottom: energy drift of the undamped, unforced system. One colour and marker per "
        "method throughout."),
}


#: Where a PNG from another module goes, by words in its name (first match).
FIGURE_GROUPS = [
    ("earthquake", ("earthquake", "quake", "seismic")),
    ("convergence", ("convergence", "pareto", "ladder", "refinement", "accuracy")),
    ("integrators", ("integrator", "solver", "step")),
    ("runs", ("runup", "run_up", "rundown", "run_down", "sweep", "transient", "omega",
              "amplitude", "simulate", "speed", "averaging")),
    ("modal", ("modal", "mode", "frequency")),
]


def figure_group(name: str) -> str:
    """The report section for a figure file name.

    >>> figure_group("pareto_front.png"), figure_group("runup_omega.png"), figure_group("x.png")
    ('convergence', 'runs', 'other')
    """
    n = name.lower()
    for group, words in FIGURE_GROUPS:
        if any(w in n for w in words):
            return group
    return "other"
