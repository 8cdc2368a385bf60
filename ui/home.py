"""The home page: what the app is, and every registered problem, grouped by method."""
from __future__ import annotations

import streamlit as st

from edge.streamlit_dom import css
from solvers.catalog import GROUPS, PROBLEMS
from ui.results import plain
from ui.stylesheet import Stylesheet
from ui.thumbnails import thumbnail_markdown

CARDS_PER_ROW = 2  # on a phone Streamlit stacks the columns: one card per row
# A card's title (its link) above its blurb in size too: Streamlit sets a page link's label smaller than Markdown.
HOME_CSS = Stylesheet(css("<style> $mainBlock $pageLink p { font-size: 1.1rem; } </style>"))
COUNT_WORDS = {5: "Five", 6: "Six", 7: "Seven", 8: "Eight", 9: "Nine", 10: "Ten", 11: "Eleven", 12: "Twelve"}


def home() -> None:
    st.html(HOME_CSS)
    st.title("Dynamics Lab")
    count = COUNT_WORDS.get(len(PROBLEMS), str(len(PROBLEMS)))
    st.markdown(
        f"{count} worked problems of undergraduate rigid-body dynamics, alive: change a parameter and "
        "the derivation, the numbers and the motion follow. Every answer is checked a second way "
        "(a conservation law, a time integration, a linear solve), and where the original worked "
        "solutions slipped, the page says so."
    )
    for group in GROUPS:
        st.subheader(group)
        members = [p for p in PROBLEMS if p.group == group]
        for first in range(0, len(members), CARDS_PER_ROW):  # a row of cards at a time: none is dropped
            row = members[first:first + CARDS_PER_ROW]
            for col, problem in zip(st.columns(CARDS_PER_ROW), row):
                with col.container(border=True):
                    # A Markdown image carries its text alternative (st.image gives an <img> without alt).
                    st.markdown(thumbnail_markdown(problem.id))
                    st.page_link(problem.page_path, label=f"**{problem.title}**", icon=problem.icon)
                    st.markdown(f":gray[{plain(problem.blurb)}]")  # st.caption's grey fails contrast
