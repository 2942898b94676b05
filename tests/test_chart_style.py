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


def _chart_with_labels(freeze):
    """A two-panel chart with a suptitle and a legend, laid out and frozen by ``freeze``,
    then labelled on that layout as the run-up chart is."""
    fig, axes = style.figure(700, 420, ncols=2)
    t = np.linspace(0, 10, 300)
    for k, ax in enumerate(axes):
        ax.plot(t, np.sin((k + 1) * t), label=f"mode {k + 1}")
        ax.set_xlabel("t [s]")
        ax.set_ylabel("tip X [m]")
        ax.legend(loc="upper right")
    fig.suptitle("run-up through the first resonance")
    freeze(fig)
    style.place_labels(axes[0], [{"xy": (5.0, np.sin(5.0)), "text": "passage"}], lines=axes[0].lines, drawn=True)
    return fig, axes


def _draw_and_freeze(fig):
    fig.canvas.draw()
    fig.set_layout_engine("none")


def test_freeze_layout_is_the_layout_a_draw_gives(tmp_path):
    """freeze_layout runs the layout engine alone where the charts drew the whole figure
    first: the axes must sit where the draw put them, the labels placed on them where the
    draw's would be, and the saved picture must be the same bytes (pixels and legibility)."""
    drawn, drawn_axes = _chart_with_labels(_draw_and_freeze)
    frozen, frozen_axes = _chart_with_labels(style.freeze_layout)
    for a, b in zip(drawn_axes, frozen_axes):
        assert a.get_position().bounds == b.get_position().bounds
    assert [t.get_position() for t in drawn_axes[0].texts] == [t.get_position() for t in frozen_axes[0].texts]
    style.save(drawn, tmp_path / "drawn.png")
    style.save(frozen, tmp_path / "frozen.png")
    assert (tmp_path / "drawn.png").read_bytes() == (tmp_path / "frozen.png").read_bytes()
