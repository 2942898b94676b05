"""Building blocks of the report page: every text escaped, every image
embedded, nothing fetched from anywhere.

The page stands alone: images are embedded as ``data:`` URIs, so
report.html can be mailed as one file; videos are embedded too when they are
small (:data:`EMBED_VIDEO_BYTES`) and always linked to the file beside the
page.  Links point only at files that exist beside it (the tests check).

>>> table(["a", "b<"], [[1, "x&y"]])
'<table><thead><tr><th>a</th><th>b&lt;</th></tr></thead><tbody><tr><td>1</td><td>x&amp;y</td></tr></tbody></table>'
"""

from __future__ import annotations

import base64
import html
import math
import os
import re
from pathlib import Path

#: Videos up to this size are embedded in the page as well as linked.
EMBED_VIDEO_BYTES = 12 * 2**20

_MIME = {
    ".png": "image/png",
    ".gif": "image/gif",
    ".jpg": "image/jpeg",
    ".jpeg": "image/jpeg",
    ".svg": "image/svg+xml",
    ".mp4": "video/mp4",
    ".webm": "video/webm",
}


class Raw(str):
    """HTML that is already safe: not escaped again (here, nor by a template)."""

    def __html__(self) -> str:
        return str(self)


def esc(value) -> str:
    """Escaped text of any value (Raw passes through).

    >>> esc('<b> & "q"'), esc(Raw("<b>"))
    ('&lt;b&gt; &amp; &quot;q&quot;', '<b>')
    """
    if hasattr(value, "__html__"):  # Raw, or a rendered template (markupsafe.Markup)
        return str(value.__html__())
    return html.escape(str(value), quote=True)


def num(x, digits: int = 5) -> str:
    """A number for a table: ``digits`` significant digits, '-' for none.

    >>> num(31.3333333), num(None), num(1.23e-7), num(True), num(float("nan"))
    ('31.333', '-', '1.23e-07', 'yes', '-')
    """
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        if not math.isfinite(x):
            return "-"
        return f"{x:.{digits}g}"
    return str(x)


def pct(x, digits: int = 2) -> str:
    """A relative difference in percent, signed.

    >>> pct(-0.01634), pct(None)
    ('-1.63 %', '-')
    """
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return f"{100 * x:+.{digits}f} %"


def tag(name: str, content="", **attrs) -> str:
    """``<name attrs>content</name>``; attribute names ending in _ lose it (class_)."""
    parts = [name]
    for k, v in attrs.items():
        if v is None or v is False:
            continue
        k = k.rstrip("_").replace("_", "-")
        parts.append(k if v is True else f'{k}="{esc(v)}"')
    inner = "".join(esc(c) for c in content) if isinstance(content, (list, tuple)) else esc(content)
    return Raw(f"<{' '.join(parts)}>{inner}</{name}>")


def table(header, rows, classes=None, row_classes=None) -> str:
    """A table of escaped cells (Raw cells pass through); a header of empty
    cells is left out (a key/value table needs none).

    >>> table(["", ""], [["k", 1]])
    '<table class="kv"><tbody><tr><td>k</td><td>1</td></tr></tbody></table>'
    """
    head = "".join(f"<th>{esc(h)}</th>" for h in header)
    if not any(str(h).strip() for h in header):
        head, classes = "", classes or "kv"
    body = []
    for i, row in enumerate(rows):
        cls = row_classes[i] if row_classes else None
        attr = f' class="{esc(cls)}"' if cls else ""
        body.append(f"<tr{attr}>" + "".join(f"<td>{esc(c)}</td>" for c in row) + "</tr>")
    cls = f' class="{esc(classes)}"' if classes else ""
    thead = f"<thead><tr>{head}</tr></thead>" if head else ""
    return Raw(f"<table{cls}>{thead}<tbody>{''.join(body)}</tbody></table>")


def data_uri(path: str | Path) -> str:
    path = Path(path)
    mime = _MIME.get(path.suffix.lower(), "application/octet-stream")
    return f"data:{mime};base64," + base64.b64encode(path.read_bytes()).decode("ascii")


def relative(path: str | Path, base: str | Path) -> str:
    """``path`` relative to directory ``base``, with forward slashes."""
    return Path(os.path.relpath(Path(path).resolve(), Path(base).resolve())).as_posix()


def image(path: str | Path, caption: str, alt: str | None = None, width: int | None = None) -> str:
    """A figure with the image embedded and an escaped caption."""
    img = tag(
        "img", "", src=data_uri(path), alt=alt or caption, loading=None, style=f"max-width:{width}px" if width else None
    )
    img = Raw(img.replace("></img>", ">"))
    return tag("figure", [img, tag("figcaption", caption)])


def video(
    path: str | Path,
    base: str | Path,
    caption: str,
    poster: str | Path | None = None,
    embed_limit: int = EMBED_VIDEO_BYTES,
) -> str:
    """A video: embedded when small enough, and linked to the file beside the page."""
    path = Path(path)
    rel = relative(path, base)
    src = data_uri(path) if path.stat().st_size <= embed_limit else rel
    media: str
    if path.suffix.lower() == ".gif":
        media = Raw(tag("img", "", src=src, alt=caption).replace("></img>", ">"))
    else:
        media = tag(
            "video",
            "Your browser cannot play this video; open the file linked below.",
            src=src,
            controls=True,
            muted=True,
            loop=True,
            preload="metadata",
            playsinline=True,
            poster=data_uri(poster) if poster else None,
        )
    link = tag("a", f"{path.name} ({path.stat().st_size / 2**20:.1f} MB)", href=rel)
    return tag("figure", [media, tag("figcaption", [caption, Raw(" &mdash; file: "), link])], class_="video")


def missing(text: str) -> str:
    """The "not computed: run `rotorpillar X`" notice, the command in <code>; other
    backquotes (a damaged file's field path, as msgspec quotes it) stay as written.

    >>> missing("x.json is damaged (at `$.a`): rebuild it with `rotorpillar x paper`")
    '<p class="missing">x.json is damaged (at `$.a`): rebuild it with <code>rotorpillar x paper</code></p>'
    """
    found = re.search(r"`(rotorpillar [^`]*)`", text)
    if found is not None:
        before, cmd, after = text[: found.start()], found.group(1), text[found.end() :]
        return tag("p", [before, tag("code", cmd), after], class_="missing")
    return tag("p", text, class_="missing")


def details(summary: str, content) -> str:
    """A collapsed block: ``summary`` shown, ``content`` on a click."""
    return tag("details", [tag("summary", summary), Raw(content)])


def link(text: str, anchor: str) -> str:
    """A link to a place in the page (``anchor``: an id, without #)."""
    return tag("a", text, href=f"#{anchor}")


def slug(text: str) -> str:
    """An id made from a title.

    >>> slug("Eq. 1 against the 3D model (bare tube)")
    'eq-1-against-the-3d-model-bare-tube'
    """
    import re

    return re.sub(r"[^a-z0-9]+", "-", str(text).lower()).strip("-")[:60] or "part"


def section(ident: str, title: str, parts) -> str:
    return tag("section", [tag("h2", title)] + [Raw(p) for p in parts], id=ident)


def flat_items(obj, prefix: str = "", limit: int = 200) -> list[tuple[str, object]]:
    """(dotted key, scalar) pairs of a nested JSON value, long lists elided.

    >>> flat_items({"a": {"b": 1, "c": [1, 2]}, "d": "x"})
    [('a.b', 1), ('a.c', '[1, 2]'), ('d', 'x')]
    """
    out: list[tuple[str, object]] = []

    def walk(o, key):
        if len(out) >= limit:
            return
        if isinstance(o, dict):
            for k, v in o.items():
                walk(v, f"{key}.{k}" if key else str(k))
        elif isinstance(o, list):
            if len(o) <= 8 and all(not isinstance(v, (dict, list)) for v in o):
                out.append((key, "[" + ", ".join(num(v) for v in o) + "]"))
            elif all(isinstance(v, dict) for v in o) and len(o) <= 12:
                for i, v in enumerate(o):
                    walk(v, f"{key}[{i}]")
            else:
                out.append((key, f"({len(o)} values)"))
        else:
            out.append((key, o))

    walk(obj, prefix)
    return out
