"""Take it home: a problem page's downloads (the derivation as LaTeX and as Markdown, a notebook and
a script that re-derive it) and the link that reproduces the page, printed with it.

The files are made only when asked for (Streamlit's deferred downloads: a run registers the
buttons, a click runs the function), so a change of a parameter costs no LaTeX or notebook. Before
"Show the solution" (Practice, an assignment link) the files are the exercise: the statement and
the method, with no answer, and no notebook (it would print the answers).
"""
from __future__ import annotations

import html
import re
import urllib.parse

import streamlit as st

from edge import base_path
from solvers.core import Solution
from ui import documents, notebook
from solvers.catalog import Problem
from edge.streamlit_dom import css


def page_link(problem: Problem) -> str:
    """This page's address with the query the page keeps (its parameters, view, variant): the
    browser's URL where Streamlit knows it, else the page's path."""
    return (st.context.url or f"/{problem.id}").split("?")[0] + _query()


def _query() -> str:
    """The page's query as its address carries it ("?e=0.5&units=us"), or "" if it has none."""
    query = urllib.parse.urlencode({k: st.query_params.get(k) for k in st.query_params.keys()})
    return f"?{query}" if query else ""


PRINT_WORDS = "This page, with these numbers:"


def print_link(problem: Problem) -> str:
    """HTML for the page's heading: the link that reproduces this page, shown only on paper
    (ui/stylesheet.py PRINT_CSS)."""
    link = html.escape(page_link(problem))
    return f'\n\n<p class="dl-print-only dl-print-link">{PRINT_WORDS} <a href="{link}">{link}</a></p>'


def catalogue(problem: Problem, exercise: bool = False) -> list[tuple[str, str, str, str]]:
    """(label, file name, MIME type, what it is) per download: "latex", "markdown", "notebook", "script"."""
    stem = f"{problem.id}-{'exercise' if exercise else 'derivation'}"
    what = "The exercise" if exercise else "The derivation"
    out = [(f"{what} as LaTeX", f"{stem}.tex", "application/x-tex", "latex"),
           (f"{what} as Markdown", f"{stem}.md", "text/markdown", "markdown")]
    if not exercise:
        out += [("A notebook that re-derives it", f"{problem.id}.ipynb", "application/x-ipynb+json", "notebook"),
                ("The same as a Python script", f"{problem.id}.py", "text/x-python", "script")]
    return out


def maker(problem: Problem, solution: Solution, answers, system: str, link: str, kind: str, exercise: bool = False):
    """A function that makes the text of the download of ``kind`` (``catalogue``'s last field)."""
    doc = lambda: documents.document(problem, solution, answers, system, link, exercise)  # noqa: E731
    return {"latex": lambda: documents.latex(doc()), "markdown": lambda: documents.markdown(doc()),
            "notebook": lambda: notebook.notebook(problem, solution, link),
            "script": lambda: notebook.script(problem, solution, link)}[kind]


def files(problem: Problem, solution: Solution, answers, system: str, link: str,
          exercise: bool = False) -> list[tuple[str, str, str, object]]:
    """(button label, file name, MIME type, a function that makes the file's text) per download."""
    return [(label, name, mime, maker(problem, solution, answers, system, link, kind, exercise))
            for label, name, mime, kind in catalogue(problem, exercise)]


HELP = {True: "The statement with your givens and the method's steps, without the solution (LaTeX compiles with "
              "pdflatex). To print the page itself, use the browser's Print: it prints without the controls.",
        False: "LaTeX (amsmath; compiles with pdflatex as it is), Markdown with $$ math, or a Jupyter notebook "
               "and a script that rebuild the derivation with sympy for these numbers and print the answers. "
               "To print the page itself, use the browser's Print: it prints without the controls."}


# The lesson page's downloads are links (``lesson_links``), served by ``DownloadServer`` at
# <base>/download/<problem>/<file name>?<the page's query>.
DOWNLOAD = re.compile(r"/download/([a-z_]{1,40})/([A-Za-z0-9_.-]{1,80})$")
MAX_QUERY = 4096  # bytes: a page's query is a few hundred
DOWNLOAD_RATE, DOWNLOAD_BURST = 4.0, 40  # files a second per client address: a class behind one NAT, not a script
ICON = '<span aria-hidden="true" class="dl-download-icon">↓</span>'  # st.html's sanitiser drops an inline SVG
TAKEHOME_CSS = css("""
<style>
  .dl-downloads { display: flex; flex-wrap: wrap; gap: 0.5rem; }
  .dl-downloads a { display: inline-flex; align-items: center; gap: 0.4rem; padding: 0.25rem 0.75rem; min-height: 2.5rem;
    border: 1px solid rgba(49, 51, 63, 0.2); border-radius: 0.5rem; color: inherit; text-decoration: none; }
  .dl-download-icon { font-weight: 700; }
  .dl-downloads a:hover { border-color: var(--primary-color, #005A8C); color: var(--primary-color, #005A8C); }
  .dl-downloads a:focus-visible { outline: 2px solid var(--primary-color, #005A8C); outline-offset: 2px; }
  @media print {
    .dl-downloads { display: none !important; }
    /* the lesson's print link comes last in its fragment (lesson_links): on paper, first, under the
       title, in room the fragment keeps at its top (two lines: a long query wraps once) */
    $verticalBlock:has(> $elementContainer .dl-lesson-links) {
      position: relative !important; padding-top: 2.8rem; }
    $elementContainer:has(.dl-lesson-links) { position: static !important; }
    .dl-lesson-links { position: absolute !important; top: 0; left: 0; right: 0; }
  }
</style>
""")


def lesson_links(problem: Problem, downloads: bool = True) -> None:
    """The lesson page's links that carry its state, in one element at its end (``lesson_links_data``;
    a lesson run that has its answers carries them in its element of answers and figures instead, as
    drawn by plotly_component/lesson.js). ``downloads=False``: the print link alone (a state the model
    refuses has no files)."""
    links = lesson_links_data(problem, downloads)
    anchors = "".join(f'<a href="{html.escape(href)}" download="{html.escape(name)}" title="{html.escape(links["title"])}">'
                      f'{ICON}{html.escape(label)}</a>' for label, href, name in links["downloads"])
    st.html((f'<div class="dl-downloads" role="group" aria-label="Downloads">{anchors}</div>' if downloads else "")
            + f'<div class="dl-lesson-links">{print_link(problem).strip()}</div>')


def lesson_links_data(problem: Problem, downloads: bool = True) -> dict:
    """The lesson page's downloads, links with the page's own query (every parameter, the units), so a
    run registers no widget for them and a click makes the file from the very link the file cites
    (``DownloadServer``): [label, address, file name] each, and what they all are (``title``); and the
    link that reproduces the page (``print``), shown only on paper, where TAKEHOME_CSS puts it first
    (under the title, which stays outside the lesson's fragment: it does not change with the controls)."""
    prefix, query = base_path(), _query()
    return {"downloads": [[label, f"{prefix}/download/{problem.id}/{name}{query}", name]
                          for label, name, _, _ in catalogue(problem)] if downloads else [],
            "title": HELP[False], "print": page_link(problem), "print_words": PRINT_WORDS}


def made(problem_id: str, name: str, query_string: str, page_url: str) -> tuple[int, str, bytes]:
    """(HTTP status, content type, body) for GET /download/<problem_id>/<name>?<query_string>: the
    file the lesson page offers for the parameters of its address (``page_url``: the page's own
    address, which the file cites), or a plain-text refusal. No Streamlit."""
    from solvers.core import within_model_range
    from solvers.catalog import BY_ID
    from ui.params import read_link

    plain_text = "text/plain; charset=utf-8"
    problem = BY_ID.get(problem_id)
    listed = {n: (mime, kind) for _, n, mime, kind in catalogue(problem)} if problem else {}
    if name not in listed:
        return 404, plain_text, b"No such file: the page's download links name the files there are."
    if len(query_string) > MAX_QUERY:
        return 400, plain_text, b"This link is too long to be a page's address."
    query = dict(urllib.parse.parse_qsl(query_string, keep_blank_values=True))  # the last value wins, as on the page
    system = "us" if query.get("units") == "us" and problem.us_units else "si"
    values, linked, refusals = read_link(problem, query, system, markdown=False)
    if refusals:
        return 400, plain_text, ("This link's numbers cannot be made into a file:\n" + "\n".join(refusals)).encode()
    try:
        solution = within_model_range(problem.solver.solve)(**values)
    except ValueError as error:
        return 400, plain_text, f"These numbers have no solution in this model: {error}".encode()
    mime, kind = listed[name]
    # The file cites the page with the numbers it was made from, and nothing else of the link: a name the
    # problem does not know (?x=)](https://elsewhere) made a Markdown link that showed this app's address
    # and went elsewhere) or an assignment link's (whose numbers are not these) is left out.
    cited = {k: v if isinstance(v, str) else f"{v:g}" for k, v in linked.items()} | ({"units": "us"} if system == "us" else {})
    page_url = page_url + ("?" + urllib.parse.urlencode(cited) if cited else "")
    text = maker(problem, solution, problem.answers_of(solution), system, page_url, kind)()
    return 200, f"{mime}; charset=utf-8", text.encode() if isinstance(text, str) else text


class DownloadServer:
    """ASGI middleware (installed by serve.py): the lesson page's download links. Each file is made
    in a worker thread when asked for; each client address may ask for ``DOWNLOAD_RATE`` a second
    (bursts of ``DOWNLOAD_BURST``), so a script asking for thousands stalls nobody."""

    def __init__(self, app):
        from edge.fair_share import AddressBuckets

        self.app = app
        self.budget = AddressBuckets(DOWNLOAD_RATE, DOWNLOAD_BURST)

    async def __call__(self, scope, receive, send):
        match = DOWNLOAD.search(scope["path"]) if scope["type"] == "http" and scope["method"] in ("GET", "HEAD") else None
        if match is None:
            return await self.app(scope, receive, send)
        from anyio import to_thread

        from edge.fair_share import client_address

        bucket = self.budget(client_address(scope))
        if bucket.wait() > 0:
            status, kind, body = 429, "text/plain; charset=utf-8", b"Too many downloads at once: try again in a few seconds."
        else:
            bucket.take()
            status, kind, body = await to_thread.run_sync(made, *match.groups(), scope.get("query_string", b"").decode("latin-1"),
                                                          page_url(scope, match.group(1)))
        headers = [(b"content-type", kind.encode()), (b"content-length", str(len(body)).encode()),
                   (b"cache-control", b"no-store")]
        if status == 200:
            headers.append((b"content-disposition", f'attachment; filename="{match.group(2)}"'.encode()))
        elif status == 429:
            headers.append((b"retry-after", b"5"))
        await send({"type": "http.response.start", "status": status, "headers": headers})
        await send({"type": "http.response.body", "body": b"" if scope["method"] == "HEAD" else body})


def page_url(scope, problem_id: str) -> str:
    """The lesson page's address a download link came from: this server and the page's path (the
    download's, with /download/<id>/<file> replaced by /<id>); ``made`` adds the numbers."""
    headers = dict(scope.get("headers") or [])
    host = headers.get(b"host", b"").decode("latin-1")
    path = DOWNLOAD.sub(f"/{problem_id}", scope["path"])
    origin = f"{scope.get('scheme', 'http')}://{host}" if host else ""
    return origin + path


def downloads(problem: Problem, solution: Solution, answers, system: str, exercise: bool = False) -> None:
    """The page's downloads in one row (made on click)."""
    link = page_link(problem)
    row = st.container(horizontal=True, key=f"{problem.id}__takehome")
    for n, (label, name, mime, make) in enumerate(files(problem, solution, answers, system, link, exercise)):
        row.download_button(label, make, file_name=name, mime=mime, on_click="ignore", icon=":material/download:",
                            key=f"{problem.id}__takehome_{n}", help=HELP[exercise])
