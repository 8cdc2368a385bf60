"""The code Streamlit's page loads on first use that every page of the app needs at once, named to the
browser before it asks: ``st.html``'s element, which carries the app's stylesheets (ui/stylesheet.py).

Streamlit's index.html preloads its main bundle's modules; the element ``st.html`` draws is a module
of its own, imported when the first run's first ``st.html`` arrives, after the page's JavaScript has
started and the websocket has opened. Until it has loaded (up to two seconds after the run on a busy
2-core machine) Streamlit shows a placeholder in its place, and the page is drawn without the app's
styles: the phone's type, the stage's layout, the keyboard's focus rings, the printed page's breaks.
A ``Link: <…>; rel=modulepreload`` header on the HTML has the browser fetch and compile it beside the
main bundle."""
from __future__ import annotations

import functools
import re
from pathlib import Path

# Streamlit's frontend modules, by the name its build gives them (``Html.<hash>.js``)
FIRST_USED = ("Html",)
_IMPORTS = re.compile(r"""(?:from|import)\s*["'`]\./([\w.-]+\.js)["'`]""")


def _static() -> Path:
    import streamlit

    return Path(streamlit.__file__).parent / "static"


@functools.cache
def early_modules() -> tuple[str, ...]:
    """The paths (``static/js/…``, relative to a page's address, as index.html writes them) of
    ``FIRST_USED``'s modules and the modules they import, less those index.html already preloads."""
    js = _static() / "static" / "js"
    preloaded = set(re.findall(r'href="\./static/js/([\w.-]+\.js)"', (_static() / "index.html").read_text()))
    found: list[str] = []
    todo = [path.name for name in FIRST_USED for path in sorted(js.glob(f"{name}.*.js"))]
    while todo:
        name = todo.pop(0)
        if name in found or name in preloaded:
            continue
        found.append(name)
        todo += _IMPORTS.findall((js / name).read_text(encoding="utf-8"))
    return tuple(f"static/js/{name}" for name in found)


def is_page(path: str, base: str) -> bool:
    """Whether ``path`` is the address of one of the app's pages under ``base`` (edge.base_path: "" or
    "/prefix"): the root ("/prefix/") or one page ("/prefix/disk_wall"), where index.html's own
    ``./static/`` is the server's static folder. Not the LTI tool's pages (/lti/launch), whose HTML is
    the app's own and for which ``./static/`` would name nothing."""
    if not path.startswith(base + "/"):
        return False
    rest = path[len(base) + 1:]
    return "/" not in rest and not rest.startswith("_stcore")


def link_header() -> bytes:
    """The ``Link`` header's value that preloads ``early_modules`` (empty where Streamlit has none)."""
    return ", ".join(f"<./{path}>; rel=modulepreload; crossorigin" for path in early_modules()).encode()
