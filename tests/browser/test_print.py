"""Every problem page printed from Chromium (``page.pdf``, which fires the browser's beforeprint and
afterprint as a person's Print does), turned into images with pdftoppm and into text with pdftotext:
no sidebar, control or button is left, every page is numbered, the link that reproduces the page is
there, each animation is drawn at its key instant with its caption, and nothing is cut (no ink on
the edges of a page's text block, no equation wider than its box). One server and one browser for
the module. Skipped without Chromium or poppler-utils on a workstation; in CI their absence fails.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from scripts.live_app import CHROMIUM, wait_until_idle
from tests.browser.test_browser import watched_context
from tests.conftest import INSTRUCTOR_KEY as KEY
from solvers.catalog import PROBLEMS

pytestmark = pytest.mark.browser

for tool, why in ((CHROMIUM, "apt-get install chromium"), ("pdftoppm", "apt-get install poppler-utils")):
    if not (Path(tool).exists() or shutil.which(tool)):
        if os.environ.get("CI"):
            raise RuntimeError(f"CI needs {tool} (.ci/run installs it)")
        pytest.skip(f"no {tool}: {why}", allow_module_level=True)

DPI = 72  # one image pixel per point: enough to see ink at an edge, quick to make
MM = DPI / 25.4
A4 = (210 * MM, 297 * MM)
MARGINS = {"top": 14 * MM, "right": 12 * MM, "bottom": 16 * MM, "left": 12 * MM}  # ui/stylesheet.py PRINT_CSS
PAPER_TEXT_WIDTH = 703  # CSS px: 186 mm, the A4 text block the print layout fills
INK = 200  # a pixel darker than this (0-255 grey) is ink


def printed(page, path: Path) -> tuple[list[np.ndarray], str]:
    """The page as A4 PDF: its pages as grey images, and its text."""
    page.pdf(path=str(path), format="A4", prefer_css_page_size=True, print_background=True)
    subprocess.run(["pdftoppm", "-r", str(DPI), "-gray", str(path), str(path.with_suffix(""))], check=True)
    pages = sorted(path.parent.glob(f"{path.stem}-*.pgm"), key=lambda p: int(p.stem.rsplit("-", 1)[1]))
    text = subprocess.run(["pdftotext", "-layout", str(path), "-"], capture_output=True, text=True, check=True).stdout
    return [read_pgm(p) for p in pages], text


def read_pgm(path: Path) -> np.ndarray:
    data = path.read_bytes()
    header = re.match(rb"P5\s+(\d+)\s+(\d+)\s+(\d+)\s", data)
    width, height = int(header.group(1)), int(header.group(2))
    return np.frombuffer(data[header.end():], dtype=np.uint8)[: width * height].reshape(height, width)


def cut_edges(image: np.ndarray) -> list[str]:
    """Where something runs on past the text block: ink on its top or bottom row (an element sliced
    between two pages continues from the very edge), or in the side margins two pixels out (an
    element wider than the page)."""
    height, width = image.shape
    top, bottom = round(MARGINS["top"]), height - round(MARGINS["bottom"]) - 1
    left, right = round(MARGINS["left"]) - 2, width - round(MARGINS["right"]) + 1
    edges = {"top": image[top, left:right], "bottom": image[bottom, left:right],
             "left": image[top:bottom, left], "right": image[top:bottom, right]}
    return [f"{name} ({int((row < INK).sum())} px)" for name, row in edges.items() if (row < INK).sum() > 0]


def screen_chrome(page) -> set[str]:
    """The texts of the page's controls as the screen shows them: the sidebar's lines, buttons,
    labels of inputs, the figure's Play and Pause."""
    texts = page.evaluate("""() => {
      const seen = new Set();
      const add = (t) => t && t.split('\\n').map(s => s.trim()).filter(s => s.length > 3 && /[A-Za-z]/.test(s))
        .forEach(s => seen.add(s));
      add(document.querySelector("[data-testid='stSidebar']")?.innerText);
      for (const el of document.querySelectorAll("[data-testid='stMain'] button, [data-testid='stMain'] label, "
                                                 + "[data-testid='stMain'] summary, .dl-hint"))
        add(el.innerText);
      // What the main area says besides its controls (a page's title is also its navigation link).
      const content = [...document.querySelectorAll("[data-testid='stMain'] [data-testid='stMarkdownContainer'], "
                                                   + ".dl-text, .dl-figure .dl-title, .dl-figure .dl-description, .dl-figure .dl-key")]
        .map(el => el.innerText).join("\\n")
        + [...document.querySelectorAll(".dl-graph text")].map(el => el.textContent).join("\\n");  // legends, axes
      return [...seen].filter(s => !content.includes(s));
    }""")
    return set(texts)


def check_printout(browser, url: str, name: str, tmp_path: Path, wait_for: tuple[str, ...] = (),
                   links: tuple[str, ...] | None = None) -> str:
    """Print ``url`` once ``wait_for`` (selectors) are drawn, and check it; returns the printed text.
    ``links``: the links it must print (by default the page's own address)."""
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(url)
    wait_until_idle(page)
    for drawn in wait_for:  # the page's own elements draw after the run (KaTeX, plotly.js load first)
        page.locator(drawn).first.wait_for(timeout=30_000)
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(300)
    chrome = screen_chrome(page)
    assert chrome, "the screen shows controls"
    link = page.evaluate("location.href")

    # The print layout at the paper's width, as the browser's Print sets it (print media).
    page.set_viewport_size({"width": PAPER_TEXT_WIDTH, "height": 1000})
    page.emulate_media(media="print")
    if page.locator(".dl-figure .js-plotly-plot").count():
        page.wait_for_function("() => document.documentElement.dataset.dlPrinting === '1'", timeout=10_000)  # (a function: a bare expression is eval'd, which the app's CSP forbids)
    clipped = page.evaluate("""() => [...document.querySelectorAll('.katex-display, .dl-text table, .dl-figure .main-svg, '
                                      + "[data-testid='stMarkdownContainer'] table")]
        .filter(el => el.getBoundingClientRect().width > 0)
        .filter(el => el.scrollWidth > el.clientWidth + 1 || el.getBoundingClientRect().right > innerWidth + 1)
        .map(el => el.className.baseVal ?? el.className)""")
    assert not clipped, f"{name}: wider than the paper: {clipped}"
    # Each animation drawn at its key instant: its time readout is the caption's time.
    for figure in page.locator(".dl-figure").all():
        caption = figure.locator(".dl-key").inner_text()
        if caption:
            shown = figure.locator(".dl-readout").text_content()
            assert caption.startswith(f"Printed at {shown}:"), (name, caption, shown)

    images, text = printed(page, tmp_path / f"{name}.pdf")
    assert not errors, errors
    context.close()

    flat = re.sub(r"\s+", " ", text)
    for n, image in enumerate(images, start=1):
        assert image.shape[1] == pytest.approx(A4[0], abs=2) and image.shape[0] == pytest.approx(A4[1], abs=2)
        assert not cut_edges(image), f"{name}, page {n}: ink on the text block's edge: {cut_edges(image)}"
        assert f"Page {n} of {len(images)}" in flat, f"{name}: page {n} is not numbered"
    left = sorted(c for c in chrome if c in text)
    assert not left, f"{name}: controls printed: {left}"
    for printed_link in (link,) if links is None else links:
        assert printed_link in flat.replace(" ", ""), f"{name}: no link {printed_link}"
    return text


@pytest.fixture(scope="module")
def app_url(shipped_server):
    """The shared server as shipped, with its instructor key (the handouts), even when APP_URL names another."""
    return shipped_server.url


def test_the_cut_check_sees_ink_on_an_edge():
    """Positive control: an image with a stroke through the bottom edge of the text block."""
    image = np.full((round(A4[1]), round(A4[0])), 255, dtype=np.uint8)
    assert cut_edges(image) == []
    image[-round(MARGINS["bottom"]) - 3: -round(MARGINS["bottom"]) + 3, 100:120] = 0
    assert cut_edges(image) == ["bottom (20 px)"]


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
def test_every_page_prints_cleanly(browser, app_url, problem, tmp_path):
    text = check_printout(browser, f"{app_url}/{problem.id}", problem.id, tmp_path,
                          (".dl-answers .katex", ".dl-derivation .katex-display", ".dl-figure .main-svg"))
    assert problem.title in re.sub(r"\s+", " ", text)
    assert "Derivation, step by step" in text and "Printed at t =" in text


def test_the_practice_view_prints_the_exercise(browser, app_url, tmp_path):
    text = check_printout(browser, f"{app_url}/disk_wall?seed=17", "practice", tmp_path,
                          ("[data-testid='stMarkdownContainer'] .katex",))
    assert "The problem" in text and "The method" in text and "Derivation, step by step" not in text


@pytest.mark.parametrize("what", ["statements", "key"])
def test_a_handout_prints_each_student_from_a_new_sheet(browser, app_url, what, tmp_path):
    url = f"{app_url}/handouts?instructor={KEY}&problem=stick_ball&first=3&last=5&what={what}"
    text = check_printout(browser, url, f"handout-{what}", tmp_path, ("[data-testid='stMarkdownContainer'] .katex",),
                          links=tuple(f"/stick_ball?seed={seed}" for seed in (3, 4, 5)))
    pages = text.split("\f")
    starts = [n for n, page in enumerate(pages) for seed in (3, 4, 5) if page.lstrip().startswith(f"Variant {seed}")]
    assert len(starts) == 3, [page.strip()[:40] for page in pages]  # each variant opens a sheet
    assert all(page.split("Page")[0].strip() for page in pages if page.strip()), "a page left empty"
    if what == "statements":
        assert len([p for p in pages if p.strip()]) == 3, [p.strip()[:60] for p in pages]
        assert "Your work" in text and "Answers" not in text
    else:
        assert text.count("Derivation, step by step") == 3


def test_the_handouts_address_keeps_the_answer_key(browser, app_url):
    """Issue 54: choosing Answer key left what=statements in the address; the link now reopens the key."""
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    page.goto(f"{app_url}/handouts?instructor={KEY}&problem=stick_ball&first=3&last=4")
    wait_until_idle(page)
    page.get_by_text("Variant 4", exact=True).first.wait_for(timeout=30_000)
    assert "what=statements" in page.url and "first=3" in page.url
    page.get_by_text("Answer key", exact=True).click()
    page.get_by_text("Derivation, step by step").first.wait_for(timeout=30_000)
    for _ in range(50):
        if "what=key" in page.url:
            break
        page.wait_for_timeout(100)
    assert "what=key" in page.url and "problem=stick_ball" in page.url and "last=4" in page.url, page.url
    again = context.new_page()  # the address as a link, in a new tab (a session of its own: the key asked)
    again.goto(page.url.replace("?", f"?instructor={KEY}&", 1))
    wait_until_idle(again)
    again.get_by_text("Derivation, step by step").first.wait_for(timeout=30_000)
    assert again.get_by_role("radio", name="Answer key").is_checked()
    context.close()


# A heading, and a step's title over its equation, each marked at its end and the element after it marked
# at its top (absolutely placed, so no line moves): on paper the two marks must fall on one page.
MARK_HEADINGS = """() => {
  const heads = [...document.querySelectorAll("[data-testid='stMain'] [data-testid='stMarkdownContainer'] > *")]
    .filter(el => !el.parentElement.querySelector('.dl-screen-only'))  // (the page's own title: not printed)
    .filter(el => el.nextElementSibling && (el.matches("[data-testid='stHeadingWithActionElements']")
                                            || (el.matches('p') && el.nextElementSibling.matches('.katex-display'))));
  const titles = heads.map(el => el.innerText.trim().slice(0, 60));
  heads.forEach((el, n) => {
    const end = document.createElement('span');
    end.textContent = ` HEADEND${n}X`;
    end.style.fontSize = '4px';
    (el.querySelector('h1, h2, h3, h4') || el).append(end);
    const next = el.nextElementSibling, top = document.createElement('span');
    top.textContent = `NEXTTOP${n}X`;
    Object.assign(top.style, {position: 'absolute', top: '0', left: '0', fontSize: '4px'});
    if (getComputedStyle(next).position === 'static') next.style.position = 'relative';
    next.prepend(top);
  });
  return titles;
}"""


def headings_left_at_a_foot(page, path: Path) -> list[str]:
    """The headings (and steps' titles) printed at the foot of one page while what follows them is on the next."""
    heads = page.evaluate(MARK_HEADINGS)
    assert heads, "no headings to check"
    page.set_viewport_size({"width": PAPER_TEXT_WIDTH, "height": 1000})
    page.emulate_media(media="print")
    wait_until_idle(page)
    for _ in range(50):  # laid out at the paper's width (not shrunk to fit a wider page: nothing would break)
        if page.evaluate("() => document.documentElement.scrollWidth <= innerWidth + 1"):
            break
        page.wait_for_timeout(100)
    else:
        raise AssertionError("the page is wider than the paper")
    page.pdf(path=str(path), format="A4", prefer_css_page_size=True, print_background=True)
    text = subprocess.run(["pdftotext", str(path), "-"], capture_output=True, text=True, check=True).stdout
    on_page = {}
    for number, sheet in enumerate(text.split("\f")):
        for kind, n in re.findall(r"(HEADEND|NEXTTOP)(\d+)X", sheet.replace(" ", "")):
            on_page[kind, int(n)] = number
    assert len(on_page) == 2 * len(heads), "a mark was not printed"
    return [f"{title!r} on page {on_page['HEADEND', n] + 1}" for n, title in enumerate(heads)
            if on_page["HEADEND", n] != on_page["NEXTTOP", n]]


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
def test_a_handouts_answer_key_keeps_each_heading_with_what_follows(browser, app_url, problem, tmp_path):
    """Issue 54: the answer key left a step's title at the foot of one page and its equation on the next
    (and may a heading). On paper each stays with what follows it."""
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    page.goto(f"{app_url}/handouts?instructor={KEY}&problem={problem.id}&first=1&last=3&what=key")
    wait_until_idle(page)
    page.locator("[data-testid='stMarkdownContainer'] .katex-display").first.wait_for(timeout=30_000)
    page.wait_for_load_state("networkidle")
    assert headings_left_at_a_foot(page, tmp_path / "key.pdf") == []
    context.close()
