"""Streamlit's navigation as the app needs it from its first visit (a kit piece: app.py, the problem
pages, Assignments and Handouts call it)."""
from __future__ import annotations

import streamlit as st


def leave_legacy_pages_mode() -> None:
    """Streamlit runs a deep-linked ``pages/<id>.py`` by itself (its legacy pages-folder mode) until
    app.py has called st.navigation once in the process, so a student opening a shared link on a
    freshly started server would get a page without the app's navigation and layout (streamlit
    issues #9624, #10276). st.navigation clears this process-wide flag on its first call; clear it
    here and rerun, so app.py runs and serves the same page from the very first visit."""
    from streamlit.runtime.pages_manager import PagesManager

    if PagesManager.uses_pages_directory:
        PagesManager.uses_pages_directory = False
        st.rerun()
