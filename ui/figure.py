"""Show a figure (viz.common.Figure) through a small custom component instead of st.plotly_chart.

st.plotly_chart rebuilds and validates every figure through plotly's go.Figure on each call
(tens of milliseconds for an animation; see BENCHMARKS.md). This component takes the figure's
JSON as it is and draws it with the plotly.js that ships inside the plotly package (no network),
keeps an animation running across reruns when the figure is unchanged, and adds real Play/Pause
buttons that work from the keyboard (Space, ← →).
"""
from __future__ import annotations

import shutil
import threading
from pathlib import Path

import plotly
import streamlit.components.v1 as components

from viz.common import Figure

_DIR = Path(__file__).resolve().parent / "plotly_component"
_PLOTLY_JS = Path(plotly.__file__).resolve().parent / "package_data" / "plotly.min.js"


def _ensure_plotly_js() -> None:
    target = _DIR / "plotly.min.js"
    if not target.exists() or target.stat().st_size != _PLOTLY_JS.stat().st_size:
        shutil.copyfile(_PLOTLY_JS, target)


_lock = threading.Lock()
_component = None


def _declared():
    """Declare the component on first use, inside a running app: a declaration made before the
    runtime exists (serve.py imports this module while warming up) would not be registered."""
    global _component
    with _lock:
        if _component is None:
            _ensure_plotly_js()
            _component = components.declare_component("dynamics_lab_figure", path=str(_DIR))
        return _component


# The lecture view on a projector (issue 14): the component raises every text of the figure to at
# least ``min_font`` px, multiplies line widths and marker sizes, and (``fit_screen``, the first
# figure) sizes the graph to what is left of the first screen, so Play and the whole figure show.
# The legend stands in a column at the right: a projector is wide, and a row of legend above a
# figure of equal axes would take the height the drawing needs.
LECTURE = {"min_font": 18, "title_font": 22, "line_scale": 1.8, "marker_scale": 1.6, "legend_right": True}


def show(figure: Figure, lecture: bool = False, fit_screen: bool = False) -> None:
    style = {**LECTURE, "fit_screen": fit_screen} if lecture else None
    # Bytes travel as a binary argument: no second JSON encoding of the figure by Streamlit.
    _declared()(spec=figure.json_bytes(), height=figure.height, title=figure.title,
                description=figure.description, style=style, key=figure.key, default=None)
