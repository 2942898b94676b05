"""Scenes from TOML files or the embedded ones, and --set overrides."""

from __future__ import annotations

import errno
import os
import re
import stat
import sys
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from .sections import Scene, SceneError
from .validation import range_of, scene_from_dict

#: A run of digits longer than Python reads as an integer (4300 by default).
LONG_NUMBER = re.compile(rf"\d{{{sys.get_int_max_str_digits() + 1}}}")


def embedded_scenes() -> list[str]:
    """Names of the scenes shipped inside the package."""
    return sorted(p.name[:-5] for p in resources.files("rotorpillar.scenes").iterdir() if p.name.endswith(".toml"))


def what_is_there(path: str | Path) -> str | None:
    """None when ``path`` is a regular file (or a link to one), else what is wrong, as the
    end of a sentence about it ("is a directory, not a file", "not found", ...).

    Checked before a file is opened: a FIFO would block the read until a writer
    comes, a device would be read without end.

    >>> what_is_there("/dev/null"), what_is_there("/")
    ('is a character device, not a file', 'is a directory, not a file')
    """
    try:
        mode = os.stat(path).st_mode
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            return "is a loop of symbolic links"
        if os.path.islink(path):
            return f"is a symbolic link to {os.readlink(path)!r}, which does not exist"
        if exc.errno in (errno.ENOENT, errno.ENOTDIR):
            return "not found"
        return f"cannot be read: {exc.strerror or exc}"
    if stat.S_ISREG(mode):
        return None
    for test, what in (
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISFIFO, "a FIFO (named pipe)"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return f"is {what}, not a file"
    return "is not a regular file"


def read_text_file(path: Path, what: str) -> str:
    """A text input read as UTF-8, or one line saying why it cannot be.

    >>> import tempfile, os
    >>> f = tempfile.NamedTemporaryFile(suffix=".toml", delete=False); _ = f.write(b"\\xff\\xfe"); f.close()
    >>> read_text_file(Path(f.name), "scene file")
    Traceback (most recent call last):
    ...
    rotorpillar.scene.fields.SceneError: scene file ... is not UTF-8 text (byte 0xff at offset 0); save it as UTF-8
    >>> os.unlink(f.name)
    """
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise SceneError(f"{what} {str(path)!r} cannot be read: {exc.strerror or exc}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise SceneError(
            f"{what} {str(path)!r} is not UTF-8 text (byte 0x{data[exc.start]:02x} at "
            f"offset {exc.start}); save it as UTF-8"
        ) from None
    if "\x00" in text:
        raise SceneError(f"{what} {str(path)!r} is binary, not text")
    return text


def read_scene_toml(spec: str | Path) -> tuple[dict[str, Any], str]:
    """The raw TOML of a scene given by file path or embedded name."""
    path = Path(spec)
    if path.suffix == ".toml" or path.exists() or "/" in str(spec):
        there = what_is_there(path)
        if there is not None:
            raise SceneError(
                f"scene file {str(spec)!r} {there} (give a .toml file or one of: {', '.join(embedded_scenes())})"
            )
        text, name = read_text_file(path, "scene file"), path.stem
    else:
        if str(spec) not in embedded_scenes():
            raise SceneError(
                f"scene {str(spec)!r}: no such file or embedded scene (embedded: {', '.join(embedded_scenes())})"
            )
        text = resources.files("rotorpillar.scenes").joinpath(f"{spec}.toml").read_text("utf-8")
        name = str(spec)
    try:
        return tomllib.loads(text), name
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"scene {str(spec)!r} is not valid TOML: {exc}") from None
    except ValueError:  # Python's limit on integer strings (sys.get_int_max_str_digits)
        line = next((i for i, t in enumerate(text.splitlines(), 1) if LONG_NUMBER.search(t)), 0)
        raise SceneError(
            f"scene {str(spec)!r}, line {line}: an integer of more than {sys.get_int_max_str_digits()} "
            "digits, past every key's range"
        ) from None


def parse_assignment(text: str) -> tuple[list[str], Any]:
    """``section.key=value`` -> (["section", "key"], value), value read as TOML."""
    if "=" not in text:
        raise SceneError(f"--set {text!r}: expected KEY=VALUE, e.g. shaft.stiffness=5e6")
    key, raw = text.split("=", 1)
    path = key.strip().split(".")
    if len(path) != 2 or not all(path):
        raise SceneError(f"--set {text!r}: KEY must be section.key, e.g. shaft.stiffness")
    raw = raw.strip()
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw  # a bare word: a string such as cell_type=tetrahedron
    except ValueError:  # Python's limit on integer strings (sys.get_int_max_str_digits)
        key = ".".join(path)
        raise SceneError(
            f"--set {key}=: an integer of {len(raw)} characters is out of range"
            + (f": must be {range_of(key)}" if range_of(key) else "")
        ) from None
    return path, value


def apply_overrides(data: dict[str, Any], assignments: list[str]) -> dict[str, Any]:
    """Apply ``--set`` assignments to a raw scene document (a copy)."""
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in data.items()}
    for text in assignments:
        (sec, key), value = parse_assignment(text)
        data.setdefault(sec, {})
        if not isinstance(data[sec], dict):
            raise SceneError(f"--set {text!r}: [{sec}] is not a table")
        data[sec][key] = value
    return data


def load_scene(spec: str | Path = "paper", overrides: list[str] | None = None) -> Scene:
    """Read, override and validate a scene (file path or embedded name)."""
    data, name = read_scene_toml(spec)
    return scene_from_dict(apply_overrides(data, overrides or []), name=name)


def override(scene: Scene, assignments: list[str]) -> Scene:
    """A validated copy of ``scene`` with ``--set`` style assignments applied."""
    data = scene.to_dict()
    name = data.pop("name")
    data = {k: {kk: vv for kk, vv in v.items()} if isinstance(v, dict) else v for k, v in data.items()}
    return scene_from_dict(apply_overrides(data, assignments), name=name)
