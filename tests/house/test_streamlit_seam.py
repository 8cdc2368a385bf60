"""The one seam to Streamlit's DOM (edge/streamlit_dom.py): no selector of Streamlit's page is written
anywhere else in what ships (the app, its scripts and benchmarks), every name the JavaScript reads from the
seam is in it, and every test id in it is one the pinned Streamlit's frontend draws. (That each one still
matches in a real page: tests/browser/test_streamlit_seam_browser.py.) And the pages live where Streamlit's
navigation expects them, with nothing of Streamlit's private state touched."""
from __future__ import annotations

import re
from pathlib import Path

import streamlit

from edge import streamlit_dom

ROOT = Path(__file__).resolve().parents[2]
SEAM = ROOT / "edge" / "streamlit_dom.py"
SHIPPED = ("app.py", "serve.py", "app_pages", "ui", "edge", "lti", "viz", "solvers", "practice", "assignments",
           "scripts", "bench", "deploy")
SUFFIXES = {".py", ".js", ".css", ".html", ".conf", ".yaml"}
# Streamlit's marks: a test id or its attribute, a keyed element's class, a class or test id of its own
# (stSlider, stMainBlockContainer), its script-state and stale attributes.
STREAMLIT_MARK = re.compile(r"data-testid|st-key-|\bst[A-Z][A-Za-z]+|data-test-script-state|data-stale")


def shipped_files() -> list[Path]:
    files = []
    for top in SHIPPED:
        path = ROOT / top
        candidates = [path] if path.is_file() else sorted(path.rglob("*"))
        files += [p for p in candidates if p.suffix in SUFFIXES and p.is_file() and "plotly_bundles" not in p.parts
                  and "node_modules" not in p.parts and "__pycache__" not in p.parts]
    return files


def marks_in(text: str) -> list[str]:
    """``line: mark`` for each of Streamlit's marks in ``text``."""
    return [f"{number}: {m.group()}" for number, line in enumerate(text.splitlines(), 1)
            for m in STREAMLIT_MARK.finditer(line)]


def test_streamlits_page_is_selected_only_through_the_seam():
    files = shipped_files()
    assert {ROOT / "app.py", ROOT / "ui" / "stylesheet.py", ROOT / "ui" / "plotly_component" / "live.js",
            ROOT / "edge" / "inline_scripts.py", SEAM} <= set(files)  # it read what ships
    found = {str(p.relative_to(ROOT)): marks for p in files if p != SEAM and (marks := marks_in(p.read_text()))}
    assert found == {}


def test_a_selector_written_outside_the_seam_is_found():
    """Positive control: each kind of mark (st.App, Streamlit's Python API, is not one)."""
    sample = ("a = \"[data-testid='stSlider']\"\nb = '.st-key-dl_stage'\nc = '.stMainBlockContainer h1'\n"
              "d = app.getAttribute('data-test-script-state')\ne = '[data-stale]'\nf = st.App(app)")
    assert marks_in(sample) == ["1: data-testid", "1: stSlider", "2: st-key-", "3: stMainBlockContainer",
                                "4: data-test-script-state", "5: data-stale"]


def test_every_name_the_javascript_reads_from_the_seam_is_in_it():
    given = streamlit_dom.as_data()
    read = {}
    for path in sorted((ROOT / "ui" / "plotly_component").glob("*.js")) + [ROOT / "bench" / "browser.py"]:
        for name in re.findall(r"\bDOM\.([A-Za-z]+)", path.read_text()):
            read.setdefault(name, path.name)
    assert {"stage", "stageControls", "slider", "keyPrefix", "app"} <= set(read)  # it read the modules
    assert {name: where for name, where in read.items() if name not in given} == {}


def test_the_seam_names_each_thing_once_and_every_test_id_is_one_the_pinned_streamlit_draws():
    selectors = streamlit_dom.SELECTORS
    assert len(set(selectors.values())) == len(selectors)
    frontend = "".join(p.read_text(errors="replace")
                       for p in (Path(streamlit.__file__).parent / "static" / "static" / "js").glob("*.js"))
    assert len(frontend) > 1_000_000  # it read the frontend
    drawn = set(re.findall(r"[\"'`]([A-Za-z-]+)[\"'`]", frontend))  # every quoted word (the bundle quotes with `)
    assert {"stApp", "stSlider"} <= drawn
    assert [tid for tid in streamlit_dom.TEST_IDS.values() if tid not in drawn] == []
    assert [cls for cls in streamlit_dom.CLASSES.values() if cls not in drawn] == []
    assert [a for a in streamlit_dom.ATTRIBUTES.values() if a.removeprefix("data-") not in frontend] == []


def test_the_pages_live_where_streamlits_navigation_expects_them():
    """Not in a pages/ folder beside app.py (Streamlit's legacy pages mode, which the app once left by
    writing Streamlit's private ``PagesManager.uses_pages_directory``), and nothing writes that state."""
    assert not (ROOT / "pages").exists() and (ROOT / "app_pages").is_dir()
    writers = [str(p.relative_to(ROOT)) for p in shipped_files() if p.suffix == ".py"
               and "PagesManager" in p.read_text()]
    assert writers == []
