"""The one seam to Streamlit's DOM: every test id, class, attribute and key of Streamlit's page that the app's
CSS and JavaScript rely on, named once, here.

Streamlit's frontend is not an API: an upgrade may rename a ``data-testid`` or a class. Everything the app
selects in Streamlit's page is written here by a name of the app's own, and the CSS and JavaScript take the
selectors from here: the stylesheets and the inline scripts by ``$name`` (``css``: string.Template, so an
unknown name fails when the module is imported), the JavaScript modules as data (``js_prelude``: a
``const DOM = {...}`` put in front of each module when it is served, ui/figure.py). A test fails on a
selector of Streamlit's written anywhere else (tests/house/test_streamlit_seam.py), and a browser test
finds every name below in the pinned Streamlit's page (tests/browser/test_streamlit_seam_browser.py): after
an upgrade, what broke is one list.

Below the UI (edge/ and the pages both use it); plain data, no Streamlit import.
"""
from __future__ import annotations

import json
from string import Template
from types import MappingProxyType

# Streamlit's ``data-testid`` values, by the app's name for each.
TEST_IDS = MappingProxyType({
    # the page's frame
    "app": "stApp", "appView": "stAppViewContainer", "main": "stMain", "header": "stHeader",
    "sidebar": "stSidebar", "sidebarNavLink": "stSidebarNavLink", "pageLink": "stPageLink-NavLink",
    # layout
    "layoutWrapper": "stLayoutWrapper", "verticalBlock": "stVerticalBlock", "elementContainer": "stElementContainer",
    # elements
    "markdown": "stMarkdownContainer", "heading": "stHeadingWithActionElements", "metricLabel": "stMetricLabel",
    "alert": "stAlert", "table": "stTable",
    # the placeholder an element shows while its code (loaded on first use: st.html's, KaTeX's) is on its way
    "skeleton": "stSkeleton",
    # widgets
    "form": "stForm", "button": "stButton", "downloadButton": "stDownloadButton", "expander": "stExpander",
    "numberInput": "stNumberInput", "textInput": "stTextInput", "selectbox": "stSelectbox", "checkbox": "stCheckbox",
    "radio": "stRadio", "buttonGroup": "stButtonGroup", "widgetLabel": "stWidgetLabel",
    "slider": "stSlider", "sliderTickBar": "stSliderTickBar", "sliderThumbValue": "stSliderThumbValue",
})

# Streamlit's own classes.
CLASSES = MappingProxyType({"appClass": "stApp", "mainBlock": "stMainBlockContainer"})

# Streamlit's attributes: an element marked stale while a run is under way; the app's script state.
ATTRIBUTES = MappingProxyType({"stale": "data-stale", "scriptState": "data-test-script-state"})
SCRIPT_IDLE = "notRunning"  # the script state's value once a run is done

# An element given ``key=K`` carries the class ``st-key-K``. The app's containers that its CSS and
# JavaScript select, by key: the stage (a row), the motion in it, and the lesson's controls beside it.
KEY_CLASS_PREFIX = "st-key-"
KEYS = MappingProxyType({"stage": "dl_stage", "motion": "dl_motion", "stageControls": "dl_stage_controls"})


def keyed(key: str) -> str:
    """The selector of the element Streamlit draws for ``key`` (any widget's or container's key)."""
    return f".{KEY_CLASS_PREFIX}{key}"


def _selectors() -> dict[str, str]:
    found = {name: f"[data-testid='{tid}']" for name, tid in TEST_IDS.items()}
    for names in (CLASSES, KEYS, ATTRIBUTES):
        assert not set(names) & set(found), "one name, one thing"
    found |= {name: f".{cls}" for name, cls in CLASSES.items()}
    found |= {name: keyed(key) for name, key in KEYS.items()}
    found |= {name: f"[{attribute}]" for name, attribute in ATTRIBUTES.items()}
    return found


# name -> its CSS selector: "slider" -> "[data-testid='stSlider']", "stage" -> ".st-key-dl_stage".
SELECTORS = MappingProxyType(_selectors())


def css(template: str) -> str:
    """``template`` (CSS or an inline script) with each ``$name`` replaced by its selector (``SELECTORS``);
    ``$keyPrefix`` is ``st-key-``. An unknown name raises KeyError (when the module using it is imported)."""
    return Template(template).substitute(SELECTORS, keyPrefix=KEY_CLASS_PREFIX)


def as_data() -> dict:
    """What the JavaScript modules are given: the selectors by name, and the raw names they compose."""
    return {**SELECTORS, "keyPrefix": KEY_CLASS_PREFIX, "attributes": dict(ATTRIBUTES), "scriptIdle": SCRIPT_IDLE}


def js_prelude() -> str:
    """The line put in front of a JavaScript module that reads ``DOM`` (ui/figure.py)."""
    return f"const DOM = Object.freeze({json.dumps(as_data(), ensure_ascii=False, sort_keys=True)});\n"
