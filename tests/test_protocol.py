"""The problem protocol (docs/adding-a-problem.md): the registry and the types it is built on."""
from __future__ import annotations

from pathlib import Path

import pytest

from solvers import registry
from solvers.protocol import About, Mistake, Variants

ROOT = Path(__file__).resolve().parents[1]


def test_every_registered_problem_has_its_page_and_every_page_is_registered():
    pages = {p.stem for p in (ROOT / "pages").glob("*.py")}
    assert pages == set(registry.PROBLEM_IDS)
    assert len(set(registry.PROBLEM_IDS)) == len(registry.PROBLEM_IDS)


def test_the_registry_imports_each_solver_and_refuses_an_unknown_id():
    modules = registry.solvers()
    assert [m.__name__ for m in modules] == [f"solvers.{pid}" for pid in registry.PROBLEM_IDS]
    with pytest.raises(KeyError, match="not a registered problem"):
        registry.solver("no_such_problem")


def test_protocol_defaults_are_the_documented_general_rule():
    variants = Variants()
    assert variants.fixed == ("g",) and dict(variants.angles_deg) == {} and dict(variants.derived) == {}
    slip = Mistake("x", "feedback", lambda p: 0)
    assert slip.applies({"anything": 1}) is True
    about = About("t", "g", "b", ":material/album:", "s")
    assert about.us_units is False and about.primary == ()


def test_the_shared_thumbnail_helper_gives_an_image_with_its_text_alternative():
    from xml.etree import ElementTree

    from viz.common import thumbnail

    svg = ElementTree.fromstring(thumbnail('<circle cx="10" cy="10" r="5"/>', "A disk"))
    assert svg.get("role") == "img" and svg.get("aria-label") == "A disk"
    with pytest.raises(ValueError, match="label"):
        thumbnail("<g/>", "  ")
