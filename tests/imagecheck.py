"""Shared checks of the pictures the postprocess package writes."""

import struct
from pathlib import Path

import numpy as np

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def png_size(path) -> tuple[int, int]:
    """(width, height) from the PNG header itself, independent of any decoder."""
    head = Path(path).read_bytes()[:24]
    assert head[:8] == PNG_SIGNATURE, f"{path} is not a PNG"
    assert head[12:16] == b"IHDR"
    return struct.unpack(">II", head[16:24])


def pixels(path) -> np.ndarray:
    from PIL import Image

    with Image.open(path) as im:
        return np.asarray(im.convert("RGB"), dtype=float)


def assert_real_png(path, size=None, min_std=8.0):
    """A decodable PNG of the requested size whose pixels are not all alike."""
    w, h = png_size(path)
    if size is not None:
        assert (w, h) == tuple(size), f"{path}: {w}x{h}, expected {size[0]}x{size[1]}"
    px = pixels(path)
    assert px.shape[:2] == (h, w)
    assert px.std() > min_std, f"{path} is blank (pixel std {px.std():.2f})"


def labels_overlap(fig) -> list[tuple[str, str]]:
    """Pairs of texts (annotations and texts of one axes; tick labels excluded)
    of ``fig`` whose boxes, as the renderer draws them, intersect (an
    annotation's text box: ``Text.get_window_extent``, its leader line aside)."""
    from rotorpillar.postprocess.style import text_box

    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    pairs = []
    for ax in fig.axes:
        texts = [t for t in ax.texts if t.get_visible() and t.get_text()]
        boxes = [text_box(t, renderer) for t in texts]
        for i in range(len(texts)):
            for j in range(i + 1, len(texts)):
                if boxes[i].overlaps(boxes[j]):
                    pairs.append((texts[i].get_text(), texts[j].get_text()))
    return pairs
