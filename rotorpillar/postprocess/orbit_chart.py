"""orbits.png: the spatial ROM's steady unbalance response in both lateral directions (a
rotorpillar.reduced.spatial_response.SpatialResponse in, a PNG out; matplotlib Agg, lazy).

Left: the Bode amplitudes of the top and of the rotor centre in the rotor's plane and along
the spin axis against the rotor's speed (what API 684's amplification factors are read from,
in both lateral directions).  Right: each orbit's semi-major and semi-minor axes against the
speed (the shaft's deflection and the rotor centre in the plane normal to the spin axis, the
pillar's top in the horizontal plane), the line style its whirl: a semi-minor axis of zero is
a line, no whirl.  The running speed is marked on both.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .campbell_chart import WHIRL_STYLE
from .style import CYCLE, figure, save

#: the Bode curves drawn, in the SpatialResponse's names, with their words
BODE_CURVES = (
    ("tip_x", "top, in the rotor's plane"),
    ("tip_y", "top, along the spin axis"),
    ("rotor_x", "rotor centre, in the rotor's plane"),
    ("rotor_y", "rotor centre, along the spin axis"),
)
#: amplitudes below this share of a panel's largest are not drawn (a log axis down to round-off
#: would hide the curves that matter)
FLOOR_SHARE = 1e-6


def _positive(y: np.ndarray, floor: float) -> np.ndarray:
    """``y`` with values at or below ``floor`` as NaN (gaps on a log axis, not a plunge)."""
    out = np.asarray(y, dtype=float).copy()
    out[~(out > floor)] = np.nan
    return out


def _nil(y: np.ndarray) -> str:
    """A legend's note for a curve with nothing to draw."""
    return " (nil: not excited)" if not np.any(np.isfinite(y)) else ""


def orbit_chart(path, response, running_speed: float | None = None, title: str = "", size=(1060, 460)) -> Path:
    """Write the chart of the module text for ``response`` (a SpatialResponse)."""
    speeds = np.asarray(response.speeds, dtype=float)
    fig, (bode, orbit) = figure(*size, ncols=2)
    curves = {c.name: c for c in response.curves}
    drawn = [(curves[n], words) for n, words in BODE_CURVES if n in curves]
    top = max((float(np.max(c.amplitude)) for c, _ in drawn), default=1.0)
    for (c, words), colour in zip(drawn, CYCLE):
        y = _positive(c.amplitude, FLOOR_SHARE * top)
        bode.plot(speeds, y, color=colour, lw=1.3, label=words + _nil(y))
    bode.set_yscale("log")
    bode.set_xlabel("rotor speed Omega [rad/s]")
    bode.set_ylabel("steady amplitude [m]")
    bode.set_title("unbalance response, both lateral directions", fontsize=10)
    top = max((float(np.max(o.semi_major)) for o in response.orbits), default=1.0)
    for o, colour in zip(response.orbits, CYCLE):
        major = _positive(o.semi_major, FLOOR_SHARE * top)
        minor = _positive(o.semi_minor, FLOOR_SHARE * top)
        whirls = sorted(set(o.whirl))
        style = WHIRL_STYLE.get(whirls[0], "-") if len(whirls) == 1 else "-"
        label = f"{o.name}: semi-major ({'/'.join(whirls)})"
        orbit.plot(speeds, major, color=colour, lw=1.4, ls=style, label=label + _nil(major))
        orbit.plot(
            speeds, minor, color=colour, lw=0.9, ls=style, alpha=0.6, label=f"{o.name}: semi-minor" + _nil(minor)
        )
    orbit.set_yscale("log")
    orbit.set_xlabel("rotor speed Omega [rad/s]")
    orbit.set_ylabel("orbit semi-axis [m]")
    orbit.set_title("orbit semi-axes (line style: whirl)", fontsize=10)
    for ax in (bode, orbit):
        if running_speed is not None:
            ax.axvline(running_speed, color="#555555", lw=1.0, ls="-.", label=f"running {running_speed:.1f} rad/s")
        ax.set_xlim(float(speeds[0]), float(speeds[-1]))
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(loc="lower right", fontsize=7)
    if title:
        fig.suptitle(title, fontsize=11)
    return save(fig, Path(path))
