"""A stylesheet for ``st.html``, prepared once. Streamlit dedents and strips a plain string on every
run (70 µs for the lesson page's 5 kB, most of what its ``st.html`` costs); an object's
``_repr_html_`` it takes as it is, so the same text is prepared here, once per process."""
from __future__ import annotations

import textwrap


class Stylesheet:
    def __init__(self, html: str):
        self._html = textwrap.dedent(html).strip()  # what Streamlit does to a string (string_util.clean_text)

    def _repr_html_(self) -> str:
        return self._html
