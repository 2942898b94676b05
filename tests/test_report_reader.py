"""The report as a reader sees it: the page rendered in headless Chromium.

What a reader needs, checked on the page as the browser lays it out (a
1280 x 1000 window, every <details> opened so that the pictures inside are
laid out too):

- no two embedded images are identical (sha-256 of their bytes);
- every image sits in a <figure> with a non-empty caption;
- every section and every subsection (<h3>) is in the contents list;
- no text problem the chart code can detect: every embedded PNG carries
  the legibility record its writer measured (rotorpillar.postprocess.style:
  texts off the figure, overlapping texts, labels place_labels could not
  place), and that record lists none;
- the smallest font of each picture, scaled to the width the browser shows
  it at, is at least 9 px (style.MIN_FONT_PX).

The browser: Debian's Chromium (tools/setup.sh installs it), headless, on a
copy of report.html with a script appended that waits for the load event,
opens every <details>, measures and writes its verdict into the DOM, read
back with --dump-dom.  Skipped, with the reason, where Chromium is missing.

Pages: a report on synthetic inputs of every kind (tests/fixtures.py, fast)
and, in test_main_job.py, the page the main job writes (the shared ``run_paper``).
"""

import base64
import hashlib
import html
import json
import re
import shutil
import subprocess
from pathlib import Path

import fixtures
import pytest

from rotorpillar import cli
from rotorpillar.postprocess.style import MIN_FONT_PX, png_layout

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule)
pytestmark = pytest.mark.slow

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="chromium not installed (tools/setup.sh installs it)")
#: The reader's window (px): a laptop's, the page's 1100 px column fits in it.
WINDOW = (1280, 1000)

PROBE = """<pre id="__reader">pending</pre><script>
window.addEventListener('load', function () {
  document.querySelectorAll('details').forEach(function (d) { d.open = true; });
  setTimeout(function () {
    var imgs = Array.prototype.slice.call(document.images).map(function (im, k) {
      var fig = im.closest('figure'), cap = fig ? fig.querySelector('figcaption') : null;
      return {index: k, alt: (im.alt || '').slice(0, 80), natural: im.naturalWidth,
              shown: im.getBoundingClientRect().width, in_figure: !!fig,
              caption: cap ? cap.textContent.trim().length : 0};
    });
    var figures = Array.prototype.slice.call(document.querySelectorAll('figure'));
    var nav = {};
    document.querySelectorAll('nav a[href^="#"]').forEach(function (a) {
      nav[a.getAttribute('href').slice(1)] = true; });
    var parts = [];
    document.querySelectorAll('section[id]').forEach(function (s) {
      parts.push(s.id);
      s.querySelectorAll('h3').forEach(function (h) { parts.push(h.id || '(no id) ' + h.textContent); });
    });
    document.getElementById('__reader').textContent = JSON.stringify({
      width: window.innerWidth, images: imgs,
      uncaptioned_figures: figures.filter(function (f) {
        var c = f.querySelector('figcaption'); return !c || !c.textContent.trim(); }).length,
      not_in_contents: parts.filter(function (p) { return !nav[p]; })});
  }, 500);
});
</script></body>"""


def read_as_a_reader(page: Path, tmp: Path) -> dict:
    """The probe's verdict on ``page`` in headless Chromium."""
    probe = tmp / f"reader_{page.stem}.html"
    probe.write_text(page.read_text(encoding="utf-8").replace("</body>", PROBE, 1), encoding="utf-8")
    p = subprocess.run(
        [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--mute-audio",
            f"--user-data-dir={tmp / 'chromium-reader'}",
            f"--window-size={WINDOW[0]},{WINDOW[1]}",
            "--virtual-time-budget=20000",
            "--dump-dom",
            probe.resolve().as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    m = re.search(r'<pre id="__reader">(.*?)</pre>', p.stdout, re.S)
    assert m and m.group(1) != "pending", f"no verdict from chromium: {p.stderr[-2000:]}"
    return json.loads(html.unescape(m.group(1)))


def embedded_images(page: Path) -> list[bytes]:
    """The bytes of every <img> of the page, in document order."""
    text = page.read_text(encoding="utf-8")
    out = []
    for src in re.findall(r'<img[^>]*\ssrc="([^"]*)"', text):
        m = re.match(r"data:[\w/+.-]+;base64,(.*)", src, re.S)
        assert m, f"an image not embedded: {src[:80]}"
        out.append(base64.b64decode(m.group(1)))
    return out


def reader_problems(page: Path, tmp: Path) -> list[str]:
    """Everything a reader would stumble on, as sentences (empty: none)."""
    v = read_as_a_reader(page, tmp)
    assert v["width"] == WINDOW[0]
    raw = embedded_images(page)
    assert len(raw) == len(v["images"]) and raw, "the browser and the HTML disagree on the images"
    problems = []
    seen = {}
    for k, b in enumerate(raw):
        d = hashlib.sha256(b).hexdigest()
        if d in seen:
            problems.append(f"image {k} ({v['images'][k]['alt']!r}) repeats image {seen[d]}")
        seen.setdefault(d, k)
    for im, b in zip(v["images"], raw):
        name = repr(im["alt"])
        if not im["in_figure"] or not im["caption"]:
            problems.append(f"image {im['index']} {name} has no caption")
        if not b.startswith(b"\x89PNG"):
            continue
        rec = png_layout(b)
        if rec is None:
            problems.append(f"image {im['index']} {name}: no legibility record (not drawn through postprocess.style)")
            continue
        problems += [
            f"image {im['index']} {name}: {x}" for x in rec["problems"] if not x.startswith("smallest text")
        ]  # measured below, as shown
        shown = im["shown"] * rec["font_px"] / im["natural"] if im["natural"] else 0.0
        if shown < MIN_FONT_PX:
            problems.append(
                f"image {im['index']} {name}: smallest text {shown:.1f} px as shown "
                f"({im['shown']:.0f} of {im['natural']} px), below {MIN_FONT_PX:g}"
            )
    if v["uncaptioned_figures"]:
        problems.append(f"{v['uncaptioned_figures']} figure(s) without a caption")
    problems += [f"not in the contents: {x}" for x in v["not_in_contents"]]
    return problems


def run_cli(*args):
    assert cli.main([str(a) for a in args]) == 0


@pytest.fixture(scope="module")
def synthetic_page(tmp_path_factory) -> Path:
    """A report on every kind of input: the analysis, 3D modes, both
    comparisons, the paper's case and the scene's run-up (no animations)."""
    out = tmp_path_factory.mktemp("reader")
    run_cli("analyze", "paper", "--out", out)
    fixtures.write_modal_fixture(out, around=24, along=16)
    fixtures.write_comparison_fixture(out, "earthquake", ("modal", "fem3d"))
    fixtures.write_comparison_fixture(out, "runup", ("modal", "beam"))
    fixtures.write_simulation_fixture(out, "earthquake", modal=False, per_model=True)
    fixtures.write_simulation_fixture(out, "runup")
    # the mode pictures drawn in this process (parallel.WORKERS = 1), not in two worker
    # interpreters started for them: the page is what is read here, and the workers draw
    # what one process draws (test_report_parallel); this module 23.5 -> 14.8 s of CPU
    # (perf task-clock, 2026-11-29)
    from rotorpillar.postprocess.report import parallel

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(parallel, "WORKERS", 1)
        run_cli("report", "paper", "--out", out, "--no-animations")
    return out / "report.html"


@needs_chromium
def test_a_reader_finds_every_figure_legible_captioned_once_and_listed(synthetic_page, tmp_path):
    assert reader_problems(synthetic_page, tmp_path) == []


@needs_chromium
def test_the_reader_check_finds_what_it_looks_for(synthetic_page, tmp_path):
    """The check fails where a reader would stumble: a picture twice, a figure
    without caption, a section missing from the contents, a chart whose
    text runs together, a wide chart squeezed until its text is tiny."""
    import numpy as np

    from rotorpillar.postprocess import html as h
    from rotorpillar.postprocess.style import figure, save

    fig, ax = figure(900, 400)
    ax.plot(np.arange(3))
    ax.set_title("a title " * 20)  # runs off the figure
    ax.text(0.5, 0.5, "one", transform=ax.transAxes)
    ax.text(0.5, 0.5, "two", transform=ax.transAxes)  # on top of "one"
    crowded = save(fig, tmp_path / "crowded.png")
    fig, ax = figure(3000, 400)  # shown at ~1060 px: 8 pt -> 5 px
    ax.plot(np.arange(3))
    wide = save(fig, tmp_path / "wide.png")
    text = synthetic_page.read_text(encoding="utf-8")
    first = re.search(r"<figure>.*?</figure>", text, re.S).group(0)
    extra = (
        first
        + h.image(crowded, "")
        + h.image(wide, "wide")
        + '<section id="stray"><h2>Stray</h2><h3 id="stray-part">part</h3></section>'
    )
    bad = tmp_path / "bad.html"
    bad.write_text(text.replace("</body>", extra + "</body>", 1), encoding="utf-8")
    found = "\n".join(reader_problems(bad, tmp_path))
    assert "repeats image" in found
    assert "has no caption" in found
    assert "not in the contents: stray" in found and "not in the contents: stray-part" in found
    assert "off the figure: 'a title" in found and "overlap: 'one' / 'two'" in found
    assert re.search(r"'wide': smallest text [\d.]+ px as shown", found)


# --------------------------------------------------------------------------
# The page a designer signs (issue 29): the answer on the first screen, each
# heading once, a unit on every number column, no internal id in the text.

#: The designer's screen (px): what "the first screen" means.
SCREEN = (1400, 900)

#: Words of the code, not of the reader: record keys, mode normalisations,
#: speed states, model labels, the names of the machinery (issue 29's list,
#: and the keys that stood beside them on the page).
INTERNAL_IDS = (
    "beam:timoshenko:",
    "unit_tip",
    "plate_x",
    "plate_z",
    "base_x",
    "eta1",
    "eta2",
    "at_speed",
    "the chain",
    "the ladder",
    "run 2",
    "max_abs.",
)

FIRST_SCREEN = """<pre id="__screen">pending</pre><script>
window.addEventListener('load', function () {
  var H = __HEIGHT__, seen = [];
  var walk = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (var n = walk.nextNode(); n; n = walk.nextNode()) {
    var r = document.createRange(); r.selectNodeContents(n);
    var b = r.getBoundingClientRect();
    if (b.width > 0 && b.height > 0 && b.top < H && b.bottom > 0) seen.push(n.textContent);
  }
  document.querySelectorAll('details').forEach(function (d) { d.open = true; });
  var tables = Array.prototype.slice.call(document.querySelectorAll('table')).map(function (t) {
    return {head: Array.prototype.slice.call(t.querySelectorAll('thead th')).map(function (c) { return c.innerText.trim(); }),
            rows: Array.prototype.slice.call(t.querySelectorAll('tbody tr')).map(function (tr) {
              return Array.prototype.slice.call(tr.children).map(function (c) { return c.innerText.trim(); }); })};
  });
  var heads = Array.prototype.slice.call(document.querySelectorAll('h1, h2, h3, h4')).map(function (x) {
    return x.innerText.trim(); });
  document.getElementById('__screen').textContent = JSON.stringify({
    width: window.innerWidth, height: window.innerHeight, first_screen: seen.join(' '), headings: heads, tables: tables,
    text: document.body.innerText});
});
</script></body>"""

_NUMBER = re.compile(r"[+\-\u2212]?(\d+\.?\d*|\.\d+)(e[+\-]?\d+)?")
_UNIT = re.compile(r"\([^()]+\)\s*$|\[[^\]]+\]\s*$")


def read_first_screen(page: Path, tmp: Path) -> dict:
    """What Chromium lays out 1400 px wide: the text of the first 900 px, then
    (every <details> opened) the headings, the tables and the page's text."""
    probe = tmp / f"screen_{page.stem}.html"
    script = FIRST_SCREEN.replace("__HEIGHT__", str(SCREEN[1]))
    probe.write_text(page.read_text(encoding="utf-8").replace("</body>", script, 1), encoding="utf-8")
    p = subprocess.run(
        [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            f"--user-data-dir={tmp / 'chromium-screen'}",
            # taller than the screen: headless Chromium takes its own toolbar's
            # height off the window; the probe counts the first SCREEN[1] px itself
            f"--window-size={SCREEN[0]},{SCREEN[1] + 300}",
            "--virtual-time-budget=20000",
            "--dump-dom",
            probe.resolve().as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    m = re.search(r'<pre id="__screen">(.*?)</pre>', p.stdout, re.S)
    assert m and m.group(1) not in ("", "pending"), f"no verdict from chromium: {p.stderr[-2000:]}"
    return json.loads(html.unescape(m.group(1)))


def unitless_number_columns(tables: list[dict]) -> list[str]:
    """The headers of table columns that hold numbers but name no unit.  A
    column holds numbers when most of its filled cells are bare numbers and
    not all of them whole: counts and indices (whole numbers) have no unit.
    A unit is a parenthesis or bracket closing the header: "(mm)", "(-)"."""
    out = []
    for t in tables:
        for k, head in enumerate(t["head"]):
            cells = [r[k] for r in t["rows"] if k < len(r) and r[k] not in ("", "-")]
            bare = [c for c in cells if _NUMBER.fullmatch(c.replace(",", ""))]
            if not bare or 2 * len(bare) < len(cells) or all(re.fullmatch(r"\d+", c) for c in bare):
                continue
            if not _UNIT.search(head):
                out.append(f"{head!r} (e.g. {bare[0]})")
    return out


def designer_problems(page: Path, tmp: Path, governing_name: str | None, utilisation: float | None) -> list[str]:
    """What keeps a designer from signing the page, as sentences (empty: none).
    ``governing_name`` None: no check assessed, the verdict alone must be on top."""
    v = read_first_screen(page, tmp)
    assert v["width"] == SCREEN[0] and v["height"] >= SCREEN[1], (v["width"], v["height"])
    first = " ".join(v["first_screen"].split())
    problems = [
        f"not on the first screen: {what}"
        for what in ("Verdict:", *(() if governing_name is None else (governing_name, f"{utilisation:.2f}")))
        if what not in first
    ]
    seen: set[str] = set()
    for head in v["headings"]:
        if head in seen:
            problems.append(f"heading repeats: {head!r}")
        seen.add(head)
    problems += [f"number column without a unit: {x}" for x in unitless_number_columns(v["tables"])]
    text = v["text"]
    for word in INTERNAL_IDS:
        at = text.find(word)
        if at >= 0:
            problems.append(f"internal id {word!r} in the text: ...{text[max(0, at - 60) : at + 40]!r}...")
    return problems


def governing_check(out: Path) -> tuple[str | None, float | None]:
    """The check with the largest utilisation in summary.json (read here, not by the
    page's code), or (None, None) when no check is assessed."""
    doc = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assessed = [c for c in doc["checks"] if c["utilisation"] is not None]
    if not assessed:
        return None, None
    top = max(assessed, key=lambda c: c["utilisation"])
    return top["name"], top["utilisation"]


@needs_chromium
def test_a_designer_finds_the_answer_first(synthetic_page, tmp_path):
    name, utilisation = governing_check(synthetic_page.parent)
    assert designer_problems(synthetic_page, tmp_path, name, utilisation) == []


@needs_chromium
def test_the_screen_check_finds_what_it_looks_for(tmp_path):
    """The check fails on a page without the answer on top, with a repeated heading,
    a number column without a unit and an internal id in its text."""
    page = tmp_path / "bad.html"
    filler = "<p>filler</p>" * 80
    page.write_text(
        "<!DOCTYPE html><html><body><h2>Runs</h2><h2>Runs</h2>"
        "<table><thead><tr><th>peak tip</th><th>#</th></tr></thead><tbody>"
        "<tr><td>10.29</td><td>1</td></tr></tbody></table><p>speed state at_speed</p>"
        f"{filler}<p>Verdict: fail, base stress 0.06</p></body></html>",
        encoding="utf-8",
    )
    found = "\n".join(designer_problems(page, tmp_path, "base stress", 0.06))
    assert "not on the first screen: Verdict:" in found and "not on the first screen: base stress" in found
    assert "heading repeats: 'Runs'" in found
    assert "number column without a unit: 'peak tip'" in found and "'#'" not in found
    assert "internal id 'at_speed'" in found
