"""The chart helpers' shortcuts against the long way round.

- ``_line_points`` (what a label must not cover) against its definition:
  every vertex of the drawn line, in order, and no two consecutive points
  more than ``step_px`` apart (float rounding: 1e-9 px).
- ``save`` writes the picture its legibility check drew instead of drawing it
  again: the pixels must be matplotlib's own ``savefig``'s, exactly (same
  renderer, same figure), with a frozen layout and with a layout engine.
"""

import numpy as np
import pytest
from PIL import Image

from rotorpillar.postprocess import style


class _Line:
    """A Line2D as _line_points reads it, in display coordinates already."""

    def __init__(self, xy):
        self.xy = np.asarray(xy, float)

    def get_transform(self):
        return self

    def transform(self, xy):
        return xy

    def get_data(self):
        return self.xy.T


@pytest.mark.parametrize("step", [0.5, 2.0, 7.0])
def test_a_lines_points_keep_its_vertices_and_are_step_apart(step):
    rng = np.random.default_rng(7)
    xy = np.cumsum(rng.normal(scale=5.0, size=(60, 2)), axis=0)
    xy[10] = xy[9]  # a zero-length segment
    xy[20] = np.nan  # a gap: not drawn, not a point
    pts = style._line_points(_Line(xy), None, step_px=step)
    gaps = np.hypot(*np.diff(pts, axis=0).T)
    assert gaps.max() <= step + 1e-9
    drawn = xy[np.all(np.isfinite(xy), axis=1)]
    rows = [int(np.flatnonzero(np.all(pts == v, axis=1))[0]) for v in drawn]
    assert rows == sorted(rows) and rows[0] == 0 and rows[-1] == len(pts) - 1


@pytest.mark.parametrize("frozen", [True, False], ids=["frozen-layout", "constrained-layout"])
def test_save_writes_the_pixels_savefig_writes(tmp_path, frozen):
    fig, ax = style.figure(600, 400, layout="constrained")
    t = np.linspace(0, 10, 400)
    ax.plot(t, np.sin(t), label="sin")
    ax.set_xlabel("t [s]")
    ax.legend()
    if frozen:
        fig.canvas.draw()
        fig.set_layout_engine("none")
        style.place_labels(ax, [{"xy": (5.0, np.sin(5.0)), "text": "t = 5 s"}], lines=ax.lines, drawn=True)
    fig.savefig(tmp_path / "savefig.png", dpi=style.DPI)
    style.save(fig, tmp_path / "save.png")
    a, b = (np.asarray(Image.open(tmp_path / f"{n}.png")) for n in ("savefig", "save"))
    assert a.shape == b.shape and np.array_equal(a, b)
