"""The home page: what the app is, and the six problems grouped by method."""
from __future__ import annotations

import streamlit as st

from ui.catalog import GROUPS, PROBLEMS
from ui.results import plain
from ui.thumbnails import thumbnail_markdown


def home() -> None:
    st.title("Dynamics Lab")
    st.markdown(
        "Six worked problems of undergraduate rigid-body dynamics, alive: change a parameter and "
        "the derivation, the numbers and the motion follow. Every answer is checked a second way "
        "(a conservation law, a time integration, a linear solve), and where the original worked "
        "solutions slipped, the page says so."
    )
    for group in GROUPS:
        st.subheader(group)
        cols = st.columns(2)
        for col, problem in zip(cols, [p for p in PROBLEMS if p.group == group]):
            with col.container(border=True):
                # A Markdown image carries its text alternative (st.image gives an <img> without alt).
                st.markdown(thumbnail_markdown(problem.id))
                st.page_link(problem.page_path, label=f"**{problem.title}**", icon=problem.icon)
                st.markdown(f":gray[{plain(problem.blurb)}]")  # st.caption's grey fails contrast
