"""Layering: the physics (solvers/), the practice logic (practice/) and the records (assignments/,
migrations/) never import the pages (ui/),
the drawings (viz/) or Streamlit, in any form: ``import``, ``from … import``, relative imports and
``importlib.import_module`` / ``__import__`` with a literal or f-string name. Imports are read from
the syntax tree, not grepped; a positive control proves each form is caught."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LOWER = ("solvers", "practice", "assignments", "migrations")
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
