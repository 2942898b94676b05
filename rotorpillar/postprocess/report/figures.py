"""The PNGs other commands left in the out folder, and the section each belongs to."""

from __future__ import annotations

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
    found = []
    # the folder itself and its direct subfolders only: --out may point
    # anywhere, and a deep search could sweep up unrelated pictures
    for p in sorted([*out.glob("*.png"), *out.glob("*/*.png")]):
        rel = p.relative_to(out)
        if rel.parts[0] in OWN_DIRS or any(part.startswith(".") for part in rel.parts):
            continue
        found.append((p, captions.get(p.name) or p.stem.replace("_", " ")))
    return found


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
