"""The problem protocol (docs/adding-a-problem.md), enforced for every registered problem: each rule
here is written there, and a message names what a problem's module lacks ("sliding_ladder: no
MISTAKES"). A made-up problem built from a real one with parts taken away proves that each check
can fail (a positive control)."""
from __future__ import annotations

import importlib
import re
from pathlib import Path
from types import ModuleType, SimpleNamespace

import pytest

from solvers import registry
from solvers.core import Answer, Choice, Number
from solvers.diagram import Diagram, DiagramSlip
from solvers.protocol import About, Mistake, RegimeQuestion, Variants
from solvers.specs import validate_params
from viz.catalog import OnRequest
from viz.common import thumbnail

ROOT = Path(__file__).resolve().parents[2]


def _optional_module(name: str) -> ModuleType | None:
    try:
        return importlib.import_module(name)
    except ModuleNotFoundError as error:
        if error.name != name:
            raise  # the module exists but imports something missing: show that, not "no module"
        return None


def _answer_names(solver) -> set[str]:
    names = {a.name for a in getattr(solver, "ANSWERS", ()) if isinstance(a, Answer)}
    picker = getattr(solver, "answers_for", None)
    if callable(picker):
        for choice in (p for p in getattr(solver, "PARAMS", ()) if isinstance(p, Choice)):
            for option in choice.options:
                names |= {a.name for a in picker(option)}
    return names


def _tuple_of(value, kind) -> bool:
    return isinstance(value, tuple) and all(isinstance(v, kind) for v in value)


def solver_lacks(pid: str, solver) -> list[str]:
    """What ``solvers/<pid>.py`` lacks of the protocol, one message each."""
    if solver is None:
        return [f"{pid}: no solver module solvers/{pid}.py"]
    missing = []
    about = getattr(solver, "ABOUT", None)
    if not isinstance(about, About):
        missing.append(f"{pid}: no ABOUT (a solvers.protocol.About)")
    params = getattr(solver, "PARAMS", None)
    if not params or not _tuple_of(params, (Number, Choice)):
        missing.append(f"{pid}: no PARAMS (a tuple of Number and Choice)")
        params = ()
    names = {p.name for p in params}
    if isinstance(about, About) and not set(about.primary) <= names:
        missing.append(f"{pid}: ABOUT.primary names what is not a parameter: {sorted(set(about.primary) - names)}")
    if not getattr(solver, "ANSWERS", None) or not _tuple_of(solver.ANSWERS, Answer):
        missing.append(f"{pid}: no ANSWERS (a tuple of Answer)")
    if not _tuple_of(getattr(solver, "ERRATA", None), str):
        missing.append(f"{pid}: no ERRATA (a tuple of str, empty if the worked solution has no slips)")
    mistakes = getattr(solver, "MISTAKES", None)
    if not mistakes or not _tuple_of(mistakes, Mistake):
        missing.append(f"{pid}: no MISTAKES (a non-empty tuple of Mistake)")
    else:
        unknown = {m.answer for m in mistakes} - _answer_names(solver)
        if unknown:
            missing.append(f"{pid}: MISTAKES name what is not an answer: {sorted(unknown)}")
    variants = getattr(solver, "VARIANTS", None)
    if not isinstance(variants, Variants):
        missing.append(f"{pid}: no VARIANTS (a solvers.protocol.Variants)")
    elif not {*variants.angles_deg, *variants.derived} <= names:
        missing.append(f"{pid}: VARIANTS name what is not a parameter: "
                       f"{sorted({*variants.angles_deg, *variants.derived} - names)}")
    labels = getattr(solver, "LIMIT_LABELS", None)
    if not isinstance(labels, dict) or not all(isinstance(v, tuple) and len(v) == 2 for v in labels.values()):
        missing.append(f"{pid}: no LIMIT_LABELS (a dict: attribute -> (label, dimension), empty if no limit)")
    room = getattr(solver, "ROOM_QUESTIONS", ())  # optional: what the room may be asked besides the answers
    if not _tuple_of(room, RegimeQuestion) or len({q.key for q in room}) != len(room):
        missing.append(f"{pid}: ROOM_QUESTIONS is not a tuple of solvers.protocol.RegimeQuestion with distinct keys")
    elif callable(getattr(solver, "solve", None)):
        default = dict(validate_params(params, {}))
        for q in room:
            if q.regime(default) not in dict(q.choices):
                missing.append(f"{pid}: ROOM_QUESTIONS {q.key!r} says {q.regime(default)!r}, none of its choices")
    warm = getattr(solver, "WARM", None)
    if not _tuple_of(warm, dict):
        missing.append(f"{pid}: no WARM (a tuple of parameter dicts, may be empty)")
    for name in ("SYMBOLS", "DIMENSIONS"):
        if not isinstance(getattr(solver, name, None), dict):
            missing.append(f"{pid}: no {name} (a dict)")
    for name in ("solve", "derivation_of", "motion", "_checks"):
        if not callable(getattr(solver, name, None)):
            missing.append(f"{pid}: no {name}()")
    declare = getattr(solver, "free_body_diagrams", None)
    if not callable(declare):
        missing.append(f"{pid}: no free_body_diagrams(params) (the course's Step 2: a tuple of solvers.diagram.Diagram)")
    elif callable(getattr(solver, "solve", None)):
        diagrams = declare(solver.solve().params)
        if not diagrams or not _tuple_of(diagrams, Diagram):
            missing.append(f"{pid}: free_body_diagrams() gives no Diagram (a non-empty tuple of solvers.diagram.Diagram)")
        else:
            missing += _diagram_slips_lacks(pid, solver, diagrams)
    return missing


def _diagram_slips_lacks(pid: str, solver, diagrams) -> list[str]:
    """DIAGRAM_SLIPS (the drawing exercise's slips) name bodies, points and phases the diagrams have;
    EXERCISE_DIAGRAM, if given, names a phase."""
    slips = getattr(solver, "DIAGRAM_SLIPS", None)
    if not _tuple_of(slips, DiagramSlip):
        return [f"{pid}: no DIAGRAM_SLIPS (a tuple of solvers.diagram.DiagramSlip, may be empty)"]
    out = []
    bodies = {b.name: b for d in diagrams for b in d.bodies}
    for slip in slips:
        if slip.on and slip.on not in bodies:
            out.append(f"{pid}: DIAGRAM_SLIPS name a body no diagram has: {slip.on!r}")
        elif slip.at and not any(slip.at in b.points for b in ([bodies[slip.on]] if slip.on else bodies.values())):
            out.append(f"{pid}: DIAGRAM_SLIPS name a point no body has: {slip.at!r}")
    wanted = getattr(solver, "EXERCISE_DIAGRAM", "")
    if wanted and wanted not in {d.phase for d in diagrams}:
        out.append(f"{pid}: EXERCISE_DIAGRAM names no diagram's phase: {wanted!r}")
    return out


def viz_lacks(pid: str, viz) -> list[str]:
    if viz is None:
        return [f"{pid}: no viz module viz/{pid}.py"]
    missing = []
    if not callable(getattr(viz, "figures", None)):
        missing.append(f"{pid}: viz has no figures()")
    if not callable(getattr(viz, "sketch", None)):
        missing.append(f"{pid}: viz has no sketch(params) (the problem's sketch: viz/sketch.py)")
    sketch = getattr(viz, "THUMBNAIL", None)
    if not isinstance(sketch, str):
        missing.append(f"{pid}: viz has no THUMBNAIL")
    elif not ('role="img"' in sketch and re.search(r'aria-label="[^"]+"', sketch)):
        missing.append(f'{pid}: viz THUMBNAIL has no role="img" and aria-label (use viz.common.thumbnail)')
    if hasattr(viz, "ON_REQUEST") and not isinstance(viz.ON_REQUEST, OnRequest):
        missing.append(f"{pid}: viz's ON_REQUEST is not a viz.catalog.OnRequest")
    return missing


def own_tests_lack(pid: str, tests) -> list[str]:
    if tests is None:
        return [f"{pid}: no tests/physics/test_{pid}.py"]
    contract = getattr(tests, "CONTRACT", None)
    if not isinstance(contract, dict):
        return [f"{pid}: tests/physics/test_{pid}.py has no CONTRACT"]
    return [f"{pid}: tests/physics/test_{pid}.py's CONTRACT has no {key!r}" for key in ("defaults", "answers")
            if key not in contract]


def page_lacks(pid: str, source: str | None) -> list[str]:
    if source is None:
        return [f"{pid}: no page app_pages/{pid}.py"]
    if f'problem_page("{pid}")' not in source:
        return [f'{pid}: app_pages/{pid}.py does not call problem_page("{pid}")']
    return []


def lacks(pid: str) -> list[str]:
    """Everything the registered problem ``pid`` lacks of the protocol."""
    page = ROOT / "app_pages" / f"{pid}.py"
    return (solver_lacks(pid, _optional_module(f"solvers.{pid}")) + viz_lacks(pid, _optional_module(f"viz.{pid}"))
            + own_tests_lack(pid, _optional_module(f"tests.physics.test_{pid}"))
            + page_lacks(pid, page.read_text() if page.exists() else None))


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_each_registered_problem_follows_the_protocol(pid):
    assert lacks(pid) == []


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_warm_states_are_valid_parameter_sets(pid):
    for params in registry.solver(pid).WARM:
        registry.solver(pid).solve(**params)


# ----------------------------------------------------------------------------------------------
# The positive control: a made-up problem, copied from a real one, with parts taken away


def copied(module: ModuleType, without: tuple[str, ...] = (), **changed) -> SimpleNamespace:
    return SimpleNamespace(**({k: v for k, v in vars(module).items() if k not in without} | changed))


def test_a_complete_copy_lacks_nothing():
    pid = registry.PROBLEM_IDS[0]
    solver, viz = registry.solver(pid), importlib.import_module(f"viz.{pid}")
    assert solver_lacks("sliding_ladder", copied(solver)) == []
    assert viz_lacks("sliding_ladder", copied(viz)) == []
    assert own_tests_lack("sliding_ladder", SimpleNamespace(CONTRACT={"defaults": {}, "answers": set()})) == []


def test_what_a_problem_lacks_is_named():
    pid = registry.PROBLEM_IDS[0]
    solver, viz = registry.solver(pid), importlib.import_module(f"viz.{pid}")
    assert solver_lacks("sliding_ladder", copied(solver, without=("MISTAKES",))) == ["sliding_ladder: no MISTAKES (a non-empty tuple of Mistake)"]
    assert solver_lacks("sliding_ladder", copied(solver, MISTAKES=())) == ["sliding_ladder: no MISTAKES (a non-empty tuple of Mistake)"]
    for name in ("ABOUT", "PARAMS", "ANSWERS", "ERRATA", "VARIANTS", "LIMIT_LABELS", "WARM", "SYMBOLS",
                 "DIMENSIONS", "solve", "derivation_of", "motion", "_checks", "free_body_diagrams"):
        found = solver_lacks("sliding_ladder", copied(solver, without=(name,)))
        assert any(m.startswith(f"sliding_ladder: no {name}") for m in found), (name, found)
    assert "gives no Diagram" in solver_lacks("sliding_ladder", copied(solver, free_body_diagrams=lambda p: ()))[0]
    assert solver_lacks("sliding_ladder", copied(solver, without=("DIAGRAM_SLIPS",))) == [
        "sliding_ladder: no DIAGRAM_SLIPS (a tuple of solvers.diagram.DiagramSlip, may be empty)"]
    assert solver_lacks("sliding_ladder", copied(solver, DIAGRAM_SLIPS=(DiagramSlip("k", "m", on="the moon"),))) == [
        "sliding_ladder: DIAGRAM_SLIPS name a body no diagram has: 'the moon'"]
    assert solver_lacks("sliding_ladder", copied(solver, DIAGRAM_SLIPS=(DiagramSlip("k", "m", at="Z"),))) == [
        "sliding_ladder: DIAGRAM_SLIPS name a point no body has: 'Z'"]
    assert solver_lacks("sliding_ladder", copied(solver, EXERCISE_DIAGRAM="nowhere")) == [
        "sliding_ladder: EXERCISE_DIAGRAM names no diagram's phase: 'nowhere'"]
    wrong = Mistake("no_such_answer", "feedback", lambda p: 0)
    assert solver_lacks("sliding_ladder", copied(solver, MISTAKES=(wrong,))) == [
        "sliding_ladder: MISTAKES name what is not an answer: ['no_such_answer']"]
    assert "not a parameter" in solver_lacks("sliding_ladder", copied(solver, VARIANTS=Variants(
        derived={"no_such_parameter": lambda p: 1.0})))[0]
    twice = RegimeQuestion("k", "?", (("a", "A"),), lambda p: "a")
    assert "distinct keys" in solver_lacks("sliding_ladder", copied(solver, ROOM_QUESTIONS=(twice, twice)))[0]
    assert solver_lacks("sliding_ladder", copied(solver, ROOM_QUESTIONS=(RegimeQuestion("k", "?", (("a", "A"),), lambda p: "b"),))) == [
        "sliding_ladder: ROOM_QUESTIONS 'k' says 'b', none of its choices"]
    assert solver_lacks("sliding_ladder", None) == ["sliding_ladder: no solver module solvers/sliding_ladder.py"]

    assert viz_lacks("sliding_ladder", copied(viz, without=("THUMBNAIL",))) == ["sliding_ladder: viz has no THUMBNAIL"]
    bare = '<svg xmlns="http://www.w3.org/2000/svg"></svg>'
    assert "aria-label" in viz_lacks("sliding_ladder", copied(viz, THUMBNAIL=bare))[0]
    assert viz_lacks("sliding_ladder", copied(viz, without=("figures",))) == ["sliding_ladder: viz has no figures()"]
    assert viz_lacks("sliding_ladder", None) == ["sliding_ladder: no viz module viz/sliding_ladder.py"]

    assert own_tests_lack("sliding_ladder", SimpleNamespace()) == ["sliding_ladder: tests/physics/test_sliding_ladder.py has no CONTRACT"]
    assert own_tests_lack("sliding_ladder", None) == ["sliding_ladder: no tests/physics/test_sliding_ladder.py"]
    assert page_lacks("sliding_ladder", 'problem_page("ladder")') == [
        'sliding_ladder: app_pages/sliding_ladder.py does not call problem_page("sliding_ladder")']
    assert lacks("no_such_problem")[0] == "no_such_problem: no solver module solvers/no_such_problem.py"


# ----------------------------------------------------------------------------------------------
# The registry and the protocol's types


def test_every_registered_problem_has_its_page_and_every_page_is_registered():
    pages = {p.stem for p in (ROOT / "app_pages").glob("*.py")}
    NOT_PROBLEMS = {"gradebook", "handouts", "lecture_question"}  # the instructors' pages and the room's
    assert pages - NOT_PROBLEMS == set(registry.PROBLEM_IDS)
    # A page script's folder is on sys.path: app_pages/room.py would shadow the room package for every
    # page that imports it (app_pages/assignments.py the assignments package), so no page bears a package's name.
    packages = {p.parent.name for p in ROOT.glob("*/__init__.py")} | {p.stem for p in ROOT.glob("*.py")}
    assert pages & packages == set()
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

    svg = ElementTree.fromstring(thumbnail('<circle cx="10" cy="10" r="5"/>', "A disk"))
    assert svg.get("role") == "img" and svg.get("aria-label") == "A disk"
    with pytest.raises(ValueError, match="label"):
        thumbnail("<g/>", "  ")


# ----------------------------------------------------------------------------------------------
# One place: the app's code names a problem only in the problem's own files and the registry


APP_CODE = ("app.py", "serve.py", "ui", "practice", "solvers", "viz", "app_pages")


def own_files(pid: str) -> set[str]:
    return {f"solvers/{pid}.py", f"viz/{pid}.py", f"app_pages/{pid}.py", f"tests/physics/test_{pid}.py"}


def ids_outside_own_files(sources: dict[str, str], ids) -> list[str]:
    """``path: id`` for each problem id written in a source outside that problem's own files (and
    the registry, which lists them all)."""
    found = []
    for path, text in sources.items():
        if path == "solvers/registry.py":
            continue
        for pid in ids:
            if path not in own_files(pid) and re.search(rf"\b{re.escape(pid)}\b", text):
                found.append(f"{path}: {pid}")
    return found


def app_sources() -> dict[str, str]:
    paths = [ROOT / p for p in APP_CODE if (ROOT / p).is_file()]
    paths += [f for d in APP_CODE if (ROOT / d).is_dir() for f in sorted((ROOT / d).rglob("*.py"))]
    return {p.relative_to(ROOT).as_posix(): p.read_text() for p in paths}


def test_the_app_names_no_problem_outside_its_own_files():
    """Tests, benchmarks and scripts may still pick one problem for a scenario (the cart near a
    wheelie, the pendulum behind the balancer); the app itself iterates over the registry."""
    assert ids_outside_own_files(app_sources(), registry.PROBLEM_IDS) == []


def test_an_id_outside_its_own_files_is_found():
    sources = {"ui/home.py": 'if problem.id == "sliding_ladder":', "solvers/sliding_ladder.py": "sliding_ladder",
               "viz/common.py": "ladder = 1  # sliding_ladders is another word", "solvers/registry.py": '"sliding_ladder",'}
    assert ids_outside_own_files(sources, ["sliding_ladder"]) == ["ui/home.py: sliding_ladder"]
