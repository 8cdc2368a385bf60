"""The app's stylesheets for Streamlit's page (the lesson's run, the phone, the stage, print, the lecture
view), and ``Stylesheet``: one for ``st.html``, prepared once. Streamlit dedents and strips a plain string on every
run (70 µs for the lesson page's 5 kB, most of what its ``st.html`` costs); an object's
``_repr_html_`` it takes as it is, so the same text is prepared here, once per process."""
from __future__ import annotations

import textwrap

from edge.streamlit_dom import css


class Stylesheet:
    def __init__(self, html: str):
        self._html = textwrap.dedent(html).strip()  # what Streamlit does to a string (string_util.clean_text)

    def _repr_html_(self) -> str:
        return self._html


LECTURE_CSS = css("""
<style>
  $mainBlock { font-size: 1.3rem; padding-top: 3.5rem; }
  /* Streamlit's Markdown sets its paragraphs in 1rem: the blurb and Practice's text follow the projector's size */
  $mainBlock $markdown { font-size: inherit; }
  $mainBlock h1 { font-size: 2.4rem; padding-top: 0; }
  $mainBlock .katex { font-size: 1.45em; }
  $mainBlock table { font-size: 1.25rem; }
  /* a physical limit's label beside a refusal (ui/results.refused: a metric's small label) */
  $mainBlock $metricLabel p { font-size: 18px !important; }
  /* the lesson's controls on the stage, read from the back of the room like the figure beside them */
  $stageControls $widgetLabel p, $stageControls [role='radiogroup'] p,
  $stageControls input, $stageControls $sliderThumbValue,
  $stageControls $sliderTickBar div {
    font-size: 18px !important; line-height: 1.35; }
  $stageControls $slider $widgetLabel { margin-bottom: 1.1rem; }  /* the value above the thumb clears it */
  /* the free-body diagram's labels in projector type too (the SVG scales with its width) */
  .dl-text figure.dl-fbd-figure { width: min(100%, 44rem); }
  /* a question put to the room (ui/room.py): its code read from the back row, its QR code a phone's reach */
  $mainBlock p.dl-room-code { font-size: 3.6rem; font-weight: 700; letter-spacing: 0.3em; line-height: 1.1;
    font-family: ui-monospace, "DejaVu Sans Mono", monospace; margin: 0; }
  $mainBlock img[alt^="A QR code"] { width: min(100%, 13rem); image-rendering: pixelated; }
</style>
""")


# Phones: display equations a step smaller (ui/equations.py breaks a long one over rows that fit
# this size), and tables (the ledger has four columns) in smaller type and tighter cells, which wrap
# between words only: a number, a unit and a word are never broken inside ("0.943 / 2 N·s").
PHONE_CSS = css("""
<style>
  @media (max-width: 640px) {
    $mainBlock { padding-top: 3.75rem; }  /* below the header and its » */
    $mainBlock h1 { font-size: 1.65rem !important; padding-top: 0 !important; padding-bottom: 0.25rem !important; }
    $mainBlock .katex-display { font-size: 0.9em; }
    $mainBlock table { font-size: 0.85rem; }
    $mainBlock th, $mainBlock td { padding: 0.3rem 0.35rem; }
  }
</style>
""")


# The stage (Study and Lecture): the motion with the lesson's controls beside it in a narrow column,
# which a phone stacks below the figure; there the controls stand two to a row, so that the figure,
# Play and the controls share the first screen (a finger drags anywhere on a track's 40 px). On paper
# the motion takes the page's width and the controls are left out.
STAGE_CSS = css("""
<style>
  /* the stage is a row: the motion 7 parts, the controls 3 (Streamlit wraps each in a layout wrapper) */
  $stage > $layoutWrapper { min-width: 0; }
  $stage > $layoutWrapper:has(> $motion) { flex: 7 1 0%; }
  $stage > $layoutWrapper:has(> $stageControls) { flex: 3 1 0%; }
  @media (max-width: 640px) {
    $stage { flex-direction: column !important; gap: 0.5rem !important; }
    $stage > $layoutWrapper { flex: none !important; width: 100%; }
    $stageControls { display: grid !important; grid-template-columns: 1fr 1fr; column-gap: 14px; row-gap: 0; }
    $stageControls > div { min-width: 0; width: auto !important; }
    /* two sliders in a row: their tracks and −/+ level, whichever label wraps to a second line */
    $stageControls > div:has($slider) { align-self: end; }
    /* the track is short beside its −/+: its end values stay whole numbers ("1.00", never "1.0 / 0") */
    $stageControls $sliderTickBar div { white-space: nowrap; }
    $stageControls $widgetLabel p { font-size: 0.8rem; line-height: 1.25; }
    $stageControls $radio [role='radiogroup'] p { font-size: 0.85rem; line-height: 1.3; }
    $stage .dl-figure h4.dl-title { font-size: 1.05rem; margin: 0 0 0.2rem 0; }
  }
  /* a short phone (360×740): the blurb a step smaller, so the stage starts higher */
  @media (max-width: 640px) and (max-height: 800px) {
    $mainBlock h1 { font-size: 1.5rem !important; }
    $mainBlock h1 + p, $mainBlock $heading + p { font-size: 0.9rem; }
  }
  @media print {
    $stage { display: block !important; }
    $stageControls { display: none !important; }
  }
</style>
""")


# A rerun without the fade: Streamlit marks every element stale while a run is under way and gives
# it an opacity transition, which makes the browser repaint the whole page twice on every change
# (about 20 ms each in software rendering, more than the run itself takes; BENCHMARKS.md §6). A run
# here takes tens of milliseconds, so the fade would never show; Streamlit's running indicator in
# the header still says a run is under way.
RUN_CSS = css("""
<style>
  $stale { transition: none !important; opacity: 1 !important; }
  /* Keyboard focus seen (in either theme: the text's own colour): a switch showed it only as a label
     background 1.1:1 against the page, and the main area (Streamlit's skip link's target) not at all. */
  $checkbox label:has(input:focus-visible) { outline: 2px solid currentColor; outline-offset: 3px;
    border-radius: 4px; }
  $main:focus-visible { outline: 2px solid currentColor; outline-offset: -4px; }
</style>
""")


# Paper (the browser's Print): the page without Streamlit's frame and controls, flowing over A4 or
# Letter pages numbered at the foot, no equation, table row, figure or alert cut across two pages,
# the figures at their key instant (plotly_component/figure.js), and the link that reproduces the
# page under its heading (ui/takehome.print_link). tests/browser/test_print.py prints every page.
PRINT_CSS = css("""
<style>
  .dl-print-only { display: none; }
  /* the problem's sketch (a Markdown image: ui/exercise.sketch_image, the handouts): whole; on paper beside the
     givens' table, so that a student's sheet keeps its statement and room to work on one page */
  $markdown img[src^="data:image/svg+xml"] { max-width: 100%; height: auto; }
  @media print {
    $markdown img[src^="data:image/svg+xml"] { float: right; max-height: 5cm !important; max-width: 42% !important;
      width: auto !important; margin: 0 0 0.5rem 1rem; }
    @page { margin: 14mm 12mm 16mm 12mm;
      @bottom-center { content: "Page " counter(page) " of " counter(pages); font: 9pt sans-serif; color: #555; } }
    /* (the header holds Streamlit's toolbar, its running man and the sidebar's expand button) */
    $sidebar, $header, $form, $button, $downloadButton,
    $expander, $numberInput, $textInput, $selectbox, $slider, $checkbox,
    $buttonGroup, $radio { display: none !important; }
    html, body, $appClass, $appView, $main {
      height: auto !important; min-height: 0 !important; overflow: visible !important; position: static !important; }
    html { font-size: 13px !important; }  /* paper: about 10 pt where the screen has 16 px */
    $mainBlock { padding: 0 !important; max-width: none !important; }
    $mainBlock .katex-display { overflow: visible !important; }
    .dl-print-only { display: block; }
    .dl-print-link { font-size: 0.85rem; overflow-wrap: anywhere; }
    .dl-math, .katex-display, table, tr, li, $alert, figure { break-inside: avoid; }
    h1, h2, h3, h4, .dl-text .dl-caption, .dl-text p:has(+ .dl-math) { break-after: avoid; }
    /* the same in Markdown (a handout's key, the Practice method): a heading's box and a step's title over its
       equation; Streamlit's flex box around Markdown a block on paper (Chromium keeps nothing together in a flex item) */
    $heading, $markdown p:has(+ .katex-display) { break-after: avoid; }
    div:has(> $markdown) { display: block !important; }
    /* a step's title may carry inline math taller than its line (½ m R²): room above it at a page's top */
    .dl-text p:has(+ .dl-math) { padding-top: 6px; }
    /* and so may a list item's (the slips' −kπ²/8) */
    .dl-text li { padding-top: 4px; }
    /* a display equation in Markdown (the Practice method's) may open a page: room above its tallest row
       there (a margin is dropped at a page's top, padding is not) */
    $markdown .katex-display { padding-top: 6px; }
  }
</style>
""")


# The page's styles, prepared once for each view (ui.stylesheet): Study and Practice, and Lecture.
