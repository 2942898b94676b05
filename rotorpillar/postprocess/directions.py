"""The directions and the modes, named once, in words, with the paper's symbol beside.

The paper's model is plane: X horizontal (the pillar bends in X, the rotor's
plane), Y vertical (along the pillar; the rotor bouncing on its shaft), and
the shaft's axis, horizontal, normal to that plane (the paper's Z, about which
the rotor turns).  The 3D model's axes (``fem3d.modal.AXES``, written to
modal.json as ``axes``) are x = the paper's X, y = the paper's Z, z = the
paper's Y.  Every page, table and chart of the report names a direction by
:func:`direction` (or :func:`short` where a chart has little room), a mode by
:func:`mode_name`.

>>> direction("X"), direction("Y"), short("Z")
("horizontal, in the rotor's plane (the paper's X)", "vertical (the paper's Y)", 'along the shaft (Z)')
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .geometry import Mode

#: The paper's symbol -> the direction in words.
WORDS = {
    "X": "horizontal, in the rotor's plane",
    "Y": "vertical",
    "Z": "horizontal, along the shaft",
}
#: The same, where a chart's title has little room.
SHORT = {"X": "horizontal", "Y": "vertical", "Z": "along the shaft"}
#: The 3D model's axis -> the paper's symbol (fem3d.modal.AXES).
MODEL_AXIS = {"x": "X", "y": "Z", "z": "Y"}
#: What moves in each of the paper's directions, for the resonance tables.
MOTION = {"X": "pillar tip and rotor swaying together", "Y": "rotor bouncing on its shaft"}


def direction(symbol) -> str:
    """The direction in words with the paper's symbol, e.g. "vertical (the paper's Y)";
    an unknown symbol as given."""
    s = str(symbol).strip().upper()
    return f"{WORDS[s]} (the paper's {s})" if s in WORDS else str(symbol)


def short(symbol) -> str:
    """The direction in a few words with the symbol, for a chart."""
    s = str(symbol).strip().upper()
    return f"{SHORT[s]} ({s})" if s in SHORT else str(symbol)


def ordinal(k: int) -> str:
    """1 -> "1st", 2 -> "2nd", 11 -> "11th".

    >>> [ordinal(k) for k in (1, 2, 3, 4, 11, 22)]
    ['1st', '2nd', '3rd', '4th', '11th', '22nd']
    """
    if 10 <= k % 100 <= 20:
        return f"{k}th"
    return f"{k}{ {1: 'st', 2: 'nd', 3: 'rd'}.get(k % 10, 'th') }"


def mode_name(kind, n_axial=None, n_circumferential=None, short_form: bool = False) -> str:
    """A 3D mode in words: its family and order along the height (``n_axial``
    = sign changes of its profile along the tube, 0 = the first of its
    family), its direction or its waves around.

    >>> mode_name("bending_x", 0)
    "1st bending, horizontal, in the rotor's plane (the paper's X)"
    >>> mode_name("bending_y", 1, short_form=True)
    '2nd bending, along the shaft (Z)'
    >>> mode_name("ovalling", 1, 2)
    '2nd ovalling, n = 2 waves around, 1 node along the height'
    """
    kind = str(kind)
    order = f"{ordinal(int(n_axial) + 1)} " if isinstance(n_axial, int) and n_axial >= 0 else ""
    if kind.startswith("bending_"):
        symbol = MODEL_AXIS.get(kind.split("_", 1)[1], kind)
        where = short(symbol) if short_form else direction(symbol)
        return f"{order}bending, {where}"
    text = f"{order}{kind}"
    if isinstance(n_circumferential, int) and n_circumferential >= 2:
        text += f", n = {n_circumferential}" + (" around" if short_form else " waves around")
    if isinstance(n_axial, int) and not short_form:
        nodes = "no node" if n_axial == 0 else f"{n_axial} node{'s' if n_axial > 1 else ''}"
        text += f", {nodes} along the height"
    return text


def axes_legend() -> str:
    """One sentence naming the 3D model's axes in words."""
    return "3D model axes: x = " + direction("X") + ", y = " + direction("Z") + ", z = " + direction("Y") + "."


def mode_label(mode: Mode, i: int, lines: bool = False) -> str:
    """The mode in words: number, family and order along the height, its
    direction or waves around (:func:`mode_name`),
    frequency; with ``lines``, short and on three lines (for a picture).

    >>> from rotorpillar.postprocess.geometry import ModeLabel
    >>> mode_label(ModeLabel("ovalling", n_circumferential=2, n_axial=0, frequency_hz=7.25), 3)
    'mode 4: 1st ovalling, n = 2 waves around, no node along the height, 7.250 Hz'
    >>> print(mode_label(ModeLabel("bending_x", n_axial=1, frequency_hz=28.4), 6, lines=True))
    mode 7: 2nd bending
    horizontal (X)
    28.400 Hz
    """
    kind = mode.kind
    f = mode.frequency_hz
    if f is None and mode.omega is not None:
        f = mode.omega / (2 * math.pi)
    n_axial, n = mode.n_axial, mode.n_circumferential
    if lines:
        name = mode_name(kind, n_axial, n, short_form=True)
        first, _, second = name.partition(", ")
        text = f"mode {i + 1}: {first}" + (f"\n{second}" if second else "")
    else:
        text = f"mode {i + 1}: {mode_name(kind, n_axial, n)}"
    if f is not None:
        text += ("\n" if lines else ", ") + f"{f:.3f} Hz"
    return text
