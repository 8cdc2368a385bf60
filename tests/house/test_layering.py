"""Layering: the physics (solvers/), the practice logic (practice/) and the records (assignments/,
migrations/) never import the pages (ui/),
the drawings (viz/) or Streamlit, in any form: ``import``, ``from … import``, relative imports and
``importlib.import_module`` / ``__import__`` with a literal or f-string name. Imports are read from
the syntax tree, not grepped; a positive control proves each form is caught."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
LOWER = ("solvers", "practice", "assignments", "migrations", "room")
FORBIDDEN = {"ui", "viz", "streamlit", "plotly"}


def _dynamic_name(call: ast.Call) -> str | None:
    """The module name an ``import_module(...)`` or ``__import__(...)`` call asks for, as far as
    it is written literally (an f-string's leading text: f"viz.{pid}" -> "viz.")."""
    func = call.func
    name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
    if name not in ("import_module", "__import__") or not call.args:
        return None
    first = call.args[0]
    if isinstance(first, ast.Constant) and isinstance(first.value, str):
        return first.value
    if isinstance(first, ast.JoinedStr) and first.values and isinstance(first.values[0], ast.Constant):
        return str(first.values[0].value)
    return None


def imports_in(source: str, module: str) -> set[str]:
    """Every module name ``source`` (the module ``module``, e.g. "solvers.core") imports, absolute."""
    package = module.rsplit(".", 1)[0] if "." in module else ""
    found = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".") if package else []
                base = ".".join(parts[: len(parts) - node.level + 1])
                target = ".".join(p for p in (base, node.module) if p)
            else:
                target = node.module or ""
            found.add(target)
            found |= {f"{target}.{alias.name}" if target else alias.name for alias in node.names}
        elif isinstance(node, ast.Call):
            name = _dynamic_name(node)
            if name is not None:
                found.add(name.lstrip(".") if not name.startswith(".") else
                          ".".join(p for p in (package, name.lstrip(".")) if p))
    return {name for name in found if name}


def forbidden_imports(source: str, module: str) -> set[str]:
    return {name for name in imports_in(source, module) if name.split(".")[0] in FORBIDDEN}


def lower_modules():
    for top in LOWER:
        for path in sorted((ROOT / top).rglob("*.py")):
            yield ".".join(path.relative_to(ROOT).with_suffix("").parts).removesuffix(".__init__"), path


@pytest.mark.parametrize("module,path", list(lower_modules()), ids=lambda v: v if isinstance(v, str) else "")
def test_solvers_and_practice_never_import_ui_viz_or_streamlit(module, path):
    assert forbidden_imports(path.read_text(), module) == set()


@pytest.mark.parametrize("source,found", [
    ("import streamlit as st", {"streamlit"}),
    ("import ui.units", {"ui.units"}),
    ("from ui import units", {"ui", "ui.units"}),
    ("from viz.common import COLORS", {"viz.common", "viz.common.COLORS"}),
    ("from ... import ui", {"ui"}),  # from solvers/a/b.py, three levels up is the root
    ("from ...viz import common", {"viz", "viz.common"}),
    ("import importlib\nimportlib.import_module('ui.page')", {"ui.page"}),
    ("from importlib import import_module\nimport_module(f'viz.{pid}')", {"viz."}),
    ("__import__('streamlit')", {"streamlit"}),
    ("def later():\n    import streamlit\n", {"streamlit"}),
    ("from . import core\nfrom .units import unit\nimportlib.import_module(f'solvers.{pid}')", set()),
])
def test_each_form_of_import_is_caught(source, found):
    assert forbidden_imports(source, "solvers.a.b") == found


# --- the whole project's import graph ---------------------------------------------------------------
# The pages' side in layers a reader can see (issue 52): the kit (shared pieces) imports the domain and
# other kit pieces only; each feature imports the kit and the domain, never another feature or the
# composer; the composer (one problem page from the features) and the entry points (app.py, app_pages/) above
# them all. The server's edge (edge/) and the LMS (lti/) import nothing from the pages or the drawings.
KIT = {"ui", "ui.equations", "ui.figure", "ui.live", "ui.params", "ui.results", "ui.session",
       "ui.stylesheet", "ui.documents", "ui.notebook", "ui.thumbnails", "ui.diagram_exercise", "ui.exercise"}
FEATURES = {"ui.practice", "ui.assignments", "ui.takehome", "ui.handouts", "ui.home", "ui.variants", "ui.room"}
COMPOSER = {"ui.page"}
APART_FROM_THE_PAGES = ("edge", "lti")
SKIPPED = {".venv", "tests", "bench", "scripts", "node_modules", "migrations"}


def project_modules() -> dict[str, Path]:
    """Every module the app ships (its tests, benchmarks and scripts aside), by dotted name."""
    found = {}
    for path in sorted(ROOT.rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        if SKIPPED & set(parts) or parts[0].startswith("."):
            continue
        found[".".join(parts).removesuffix(".__init__")] = path
    return found


def import_graph(modules: dict[str, str]) -> dict[str, set[str]]:
    """module -> the project's modules it imports (anywhere in it: a function's own import counts), from
    each module's source; a name imported from a module (``from ui.results import plain``) is that module."""
    graph = {}
    for module, source in modules.items():
        own = module + ".__init__" if any(m.startswith(module + ".") for m in modules) else module
        targets = set()
        for name in imports_in(source, own):
            while name and name not in modules:
                name = name.rpartition(".")[0]
            if name and name != module:
                targets.add(name)
        graph[module] = targets
    return graph


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Every import circle (a strongly connected set of two modules or more), Tarjan's way."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def layer_faults(graph: dict[str, set[str]]) -> list[str]:
    """What breaks the layers above, in words."""
    faults = []
    for module, targets in sorted(graph.items()):
        top = module.split(".")[0]
        if top == "ui" and module not in KIT | FEATURES | COMPOSER:
            faults.append(f"{module}: in no layer (the kit, a feature or the composer)")
        for target in sorted(targets):
            if top in APART_FROM_THE_PAGES and target.split(".")[0] in ("ui", "viz"):
                faults.append(f"{module} imports {target}")
            if module in KIT and target in FEATURES | COMPOSER:
                faults.append(f"{module} (the kit) imports {target}")
            if module in FEATURES and target in FEATURES | COMPOSER:
                faults.append(f"{module} (a feature) imports {target}")
    return faults


def test_the_project_has_no_import_circle():
    graph = import_graph({m: p.read_text() for m, p in project_modules().items()})
    assert {"ui.page", "solvers.core", "edge.headers", "lti.routes", "app"} <= set(graph)  # it read the project
    assert circles(graph) == []


def test_the_pages_keep_their_layers_and_the_edge_and_the_lms_keep_apart_from_them():
    graph = import_graph({m: p.read_text() for m, p in project_modules().items()})
    assert layer_faults(graph) == []


def test_a_circle_and_a_broken_layer_are_found():
    """Positive controls: a circle through a function's own import, a feature importing a feature, the
    kit importing the composer, the edge importing the pages, and a ui module in no layer."""
    modules = {"ui.page": "from ui import assignments",
               "ui.assignments": "from ui.practice import practice_panel\n",
               "ui.practice": "def later():\n    from ui.page import problem_page\n",
               "ui.results": "from ui.page import VIEWS", "edge.headers": "from ui.stylesheet import PRINT_CSS",
               "ui.stylesheet": "", "ui.new_room": "", "ui": ""}
    graph = import_graph(modules)
    assert circles(graph) == [["ui.assignments", "ui.page", "ui.practice"]]
    assert layer_faults(graph) == [
        "edge.headers imports ui.stylesheet", "ui.assignments (a feature) imports ui.practice",
        "ui.new_room: in no layer (the kit, a feature or the composer)", "ui.practice (a feature) imports ui.page",
        "ui.results (the kit) imports ui.page"]
