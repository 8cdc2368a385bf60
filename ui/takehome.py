"""Take it home: a problem page's downloads (the derivation as LaTeX and as Markdown, a notebook and
a script that re-derive it) and the link that reproduces the page, printed with it.

The files are made only when asked for (Streamlit's deferred downloads: a run registers the
buttons, a click runs the function), so a change of a parameter costs no LaTeX or notebook. Before
"Show the solution" (Practice, an assignment link) the files are the exercise: the statement and
the method, with no answer, and no notebook (it would print the answers).
"""
from __future__ import annotations

import html
import urllib.parse

import streamlit as st

from solvers.core import Solution
from ui import documents, notebook
from ui.catalog import Problem


def page_link(problem: Problem) -> str:
    """This page's address with the query the page keeps (its parameters, view, variant): the
    browser's URL where Streamlit knows it, else the page's path."""
    base = (st.context.url or f"/{problem.id}").split("?")[0]
    query = urllib.parse.urlencode({k: st.query_params.get(k) for k in st.query_params.keys()})
    return base + (f"?{query}" if query else "")


def print_link(problem: Problem) -> str:
    """HTML for the page's heading: the link that reproduces this page, shown only on paper
    (ui/page.py PRINT_CSS)."""
    link = html.escape(page_link(problem))
    return f'\n\n<p class="dl-print-only dl-print-link">This page, with these numbers: <a href="{link}">{link}</a></p>'


def files(problem: Problem, solution: Solution, answers, system: str, link: str,
          exercise: bool = False) -> list[tuple[str, str, str, object]]:
    """(button label, file name, MIME type, a function that makes the file's text) per download."""
    doc = lambda: documents.document(problem, solution, answers, system, link, exercise)  # noqa: E731
    stem = f"{problem.id}-{'exercise' if exercise else 'derivation'}"
    what = "The exercise" if exercise else "The derivation"
    out = [(f"{what} as LaTeX", f"{stem}.tex", "application/x-tex", lambda: documents.latex(doc())),
           (f"{what} as Markdown", f"{stem}.md", "text/markdown", lambda: documents.markdown(doc()))]
    if not exercise:
        out += [("A notebook that re-derives it", f"{problem.id}.ipynb", "application/x-ipynb+json",
                 lambda: notebook.notebook(problem, solution, link)),
                ("The same as a Python script", f"{problem.id}.py", "text/x-python",
                 lambda: notebook.script(problem, solution, link))]
    return out


HELP = {True: "The statement with your givens and the method's steps, without the solution (LaTeX compiles with "
              "pdflatex). To print the page itself, use the browser's Print: it prints without the controls.",
        False: "LaTeX (amsmath; compiles with pdflatex as it is), Markdown with $$ math, or a Jupyter notebook "
               "and a script that rebuild the derivation with sympy for these numbers and print the answers. "
               "To print the page itself, use the browser's Print: it prints without the controls."}


def downloads(problem: Problem, solution: Solution, answers, system: str, exercise: bool = False) -> None:
    """The page's downloads in one row (made on click)."""
    link = page_link(problem)
    row = st.container(horizontal=True, key=f"{problem.id}__takehome")
    for n, (label, name, mime, make) in enumerate(files(problem, solution, answers, system, link, exercise)):
        row.download_button(label, make, file_name=name, mime=mime, on_click="ignore", icon=":material/download:",
                            key=f"{problem.id}__takehome_{n}", help=HELP[exercise])
