"""The page from templates: one jinja2 environment (autoescape on), the
filters the templates format numbers with, and the page's assembly.

The templates live beside this module (``templates/``, package data): the
page (``page.html.j2``), its macros (``macros.html.j2``: a table, a figure
with its caption, a collapsed block, a warning, a missing input) and one
partial per section (``sections/<name>.html.j2``).  The prose is in the
templates; the Python builds the records they read.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field

from jinja2 import Environment, PackageLoader, StrictUndefined
from markupsafe import Markup

from .. import html as h
from ..directions import direction

#: How the page shows a quantity stated in SI: unit -> (factor, unit shown).
SHOWN = {"Pa": (1e-6, "MPa"), "m": (1e3, "mm"), "N": (1e-3, "kN"), "N*m": (1e-6, "MN m"), "-": (100.0, "%")}

#: How the page names a model (the records' model names are identifiers).
MODEL_NAMES = {
    "modal": "ROM",
    "fem3d": "3D full order",
    "beam": "1D beam full order",
    "paper": "the paper's Eq. 4",
}


def shown_unit(unit: str) -> str:
    """The unit the page shows a quantity stated in ``unit`` in.

    >>> shown_unit("N*m"), shown_unit("rad/s")
    ('MN m', 'rad/s')
    """
    return SHOWN.get(unit, (1.0, unit))[1]


def value(x: float | None, unit: str, digits: int = 4) -> str:
    """A quantity stated in SI ``unit``, in the unit the page shows it in.

    >>> value(19926424.2, "Pa"), value(0.0281, "m"), value(None, "m"), value(0.27, "-")
    ('19.93 MPa', '28.1 mm', '-', '27 %')
    """
    if x is None or not math.isfinite(x):
        return "-"
    scale, unit_shown = SHOWN.get(unit, (1.0, unit))
    return f"{h.num(scale * x, digits)} {unit_shown}"


def bare(x: float | None, unit: str, digits: int = 4) -> str:
    """The number of a quantity stated in SI ``unit``, in the unit the page shows it in
    (a column's header states that unit: :func:`shown_unit`).

    >>> bare(0.0102881, "m"), bare(None, "m"), bare(0.00158, "-", 3)
    ('10.29', '-', '0.158')
    """
    if x is None or not math.isfinite(x):
        return "-"
    return h.num(SHOWN.get(unit, (1.0, unit))[0] * x, digits)


def model_name(model: str | None) -> str:
    """A model's name in words.

    >>> model_name("modal"), model_name(None)
    ('ROM', '-')
    """
    return "-" if model is None else MODEL_NAMES.get(model, model)


#: How the page names a case (the records' case names are identifiers).
CASE_NAMES = {"modal": "modal analysis", "runup": "run-up", "rundown": "run-down", "sweep": "sweep"}


def case_name(case: str | None) -> str:
    """A case's name in words.

    >>> case_name("runup"), case_name("earthquake (elcentro)"), case_name(None)
    ('run-up', 'earthquake (elcentro)', '-')
    """
    return "-" if case is None else CASE_NAMES.get(case, case)


_BEAM_LABEL = re.compile(r"beam:(\w+):(\d+)")


def plain(text: str) -> str:
    """A record's sentence with the model labels it carries in words.

    >>> plain("atop beam:timoshenko:40 pillar modes")
    "atop a 40-element Timoshenko beam's pillar modes"
    >>> plain("3 modes (fem3d:3D P2 hexahedra)")
    '3 modes (3D P2 hexahedra)'
    """
    text = _BEAM_LABEL.sub(lambda m: f"a {m.group(2)}-element {m.group(1).capitalize()} beam's", str(text))
    return text.replace("fem3d:", "").replace("fem3d", "3D full order")


def share(x: float | None) -> str:
    """A non-negative fraction in percent, 3 significant digits.

    >>> share(0.002134), share(None)
    ('0.213 %', '-')
    """
    if x is None or isinstance(x, bool) or not math.isfinite(x):
        return "-"
    return f"{100 * x:.3g} %"


def words(text: str) -> str:
    """An identifier in words (underscores to spaces).

    >>> words("at_speed")
    'at speed'
    """
    return str(text).replace("_", " ")


@functools.cache
def environment() -> Environment:
    """The templates' environment: autoescape on, an undefined name an error."""
    env = Environment(
        loader=PackageLoader("rotorpillar.postprocess.report", "templates"),
        autoescape=True,
        undefined=StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=False,
    )
    env.filters.update(
        num=h.num,
        pct=h.pct,
        share=share,
        value=value,
        bare=bare,
        unit=shown_unit,
        model=model_name,
        case=case_name,
        words=words,
        plain=plain,
        data_uri=h.data_uri,
        direction=direction,
    )
    return env


def render(template: str, **context: object) -> Markup:
    """A template rendered with ``context`` (HTML, safe to insert)."""
    return Markup(environment().get_template(template).render(**context))


@dataclass(frozen=True)
class Section:
    """One section of the page: its anchor, its title and its HTML (a rendered
    partial, or a section still built by ``postprocess.html``)."""

    ident: str
    title: str
    body: Markup
    appendix: bool = False
    """after the answers, collapsed"""
    subsections: list[tuple[str, str]] = field(default_factory=list)
    """(id, title) of its <h3>, for the contents"""


_H3 = re.compile(r'<h3(\s+id="([^"]*)")?>(.*?)</h3>', re.S)


def with_subsections(ident: str, title: str, html_: str, appendix: bool = False) -> Section:
    """A section whose every <h3> has an id (made from its title), listed for the contents.

    >>> s = with_subsections("s", "S", '<h3>A b</h3><h3 id="x">C</h3>')
    >>> str(s.body), s.subsections
    ('<h3 id="s-a-b">A b</h3><h3 id="x">C</h3>', [('s-a-b', 'A b'), ('x', 'C')])
    """
    found: list[tuple[str, str]] = []
    seen: set[str] = set()

    def one(m: re.Match) -> str:
        text = Markup(re.sub(r"<[^>]+>", "", m.group(3))).unescape()
        ident_ = m.group(2) or f"{ident}-{h.slug(text)}"
        base, n = ident_, 2
        while ident_ in seen:
            ident_, n = f"{base}-{n}", n + 1
        seen.add(ident_)
        found.append((ident_, text))
        return f'<h3 id="{h.esc(ident_)}">{m.group(3)}</h3>'

    return Section(ident, title, Markup(_H3.sub(one, str(html_))), appendix, found)


def page(title: str, description: str, sections: Sequence[Section]) -> str:
    """The whole document: the answers, then the contents, then the appendices."""
    return render("page.html.j2", title=title, description=description, sections=sections) + "\n"
