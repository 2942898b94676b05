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
