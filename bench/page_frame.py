"""The browser benchmark's second baseline: a problem page's frame with none of its content. The
app's navigation and, on each problem's page, the same sidebar (the view control and the problem's
parameter panel, so a change runs the same widgets) and its title, but no answers, figure or
derivation. What a change costs here is what any Streamlit page with these controls costs, before
the problem shows anything (``bench/browser.py --frame``). The problem is chosen by ``?problem=<id>``
and shown as the default page, at the root (a deep link to a page given as a function shows
Streamlit's "page not found" dialog on the first visit)."""
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import streamlit as st  # noqa: E402

from solvers.catalog import GROUPS, PROBLEMS  # noqa: E402
from ui.page import VIEWS  # noqa: E402
from ui.stylesheet import RUN_CSS  # noqa: E402
from ui.params import parameter_panel  # noqa: E402


def frame(problem):
    def page():
        st.sidebar.segmented_control("View", VIEWS, key=f"{problem.id}__view", default="Study", required=True)
        st.html(RUN_CSS)
        st.sidebar.markdown("### Parameters")
        parameter_panel(problem, "si")
        st.markdown(f"# {problem.title}")
    page.__name__ = f"frame_{problem.id}"
    return page


st.set_page_config(page_title="Dynamics Lab (frame only)", layout="wide")
shown = st.query_params.get("problem", PROBLEMS[0].id)
pages = {group: [st.Page(frame(p), title=p.title, icon=p.icon, url_path=p.id, default=p.id == shown)
                 for p in PROBLEMS if p.group == group] for group in GROUPS}
st.navigation(pages).run()
