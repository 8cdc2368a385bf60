"""What a run sends, counted (issue 13): the elements of a page and the bytes of its figures.

Every element is re-rendered by Streamlit's frontend on every run, and every byte crosses the
websocket while the browser is busy with the first of them: a page in the study view is one
Markdown element for the heading, one element for the answers, ledger and checks, one per figure,
and one for the derivation. Each is a components-v2 element of ui/figure.py carrying its data once
(a figure's JSON; the answers' and the derivation's text), with the module that draws it imported
by the browser (once per page load) rather than sent with every run. No timing here: the times are
measured in bench/browser.py.
"""
from __future__ import annotations

import importlib

import orjson
import pytest

from tests.pages.test_pages import IDS, assert_clean, first_number_control, run_page, sent
from ui import figure as component

STUB_BYTES = 400  # the module a run carries: an import of plotly_component/figure.<hash>.js


def counted(at) -> tuple[int, int, list, list, list]:
    """(Markdown elements, elements of ours, figures, answers, derivations) in the main area: each
    figure, answers and derivation as what its part of an element is sent (tests.pages.test_pages.sent)."""
    markdown = sum(1 for e in at.main if getattr(e, "type", None) == "markdown")
    elements = sum(1 for e in at.main if getattr(e, "type", None) == "bidi_component")
    parts = sent(at)
    figures, answers, derivations, links = ([data for name, data in parts if name == wanted]
                                            for wanted in (component.NAME, component.ANSWERS, component.DERIVATION, component.LINKS))
    assert len(figures) + len(answers) + len(derivations) + len(links) == len(parts)
    assert len(links) <= 1 and (not links or parts[-1][0] == component.LINKS)  # the lesson's links come last
    return markdown, elements, figures, answers, derivations


@pytest.mark.parametrize("pid", IDS)
def test_a_run_sends_the_heading_the_answers_the_derivation_and_each_figure_once(pid):
    """In two elements of ours (three where a figure on request's switch stands between the companion
    figures and the derivation): the motion on the stage, and the rest below it together
    (ui/figure.together), each part carrying what its own element would."""
    from ui.live import in_browser

    at = run_page(pid)
    solution = importlib.import_module(f"solvers.{pid}").solve()
    # (the stage's frames left to the browser where its motion is generated for it)
    shown = importlib.import_module(f"viz.{pid}").figures(solution, **({"in_browser": True} if in_browser(pid) else {}))
    text_module = f"/text.{component.module('text.js')[0].split('.')[1]}.js"
    live_module = f"/live.{component.module('live.js')[0].split('.')[1]}.js"
    figure_module = f"/figure.{component.module()[0].split('.')[1]}.js"
    lesson_module = f"/lesson.{component.module('lesson.js')[0].split('.')[1]}.js"
    on_request = hasattr(importlib.import_module(f"viz.{pid}"), "on_request")
    for state in ("first run", "after a change"):
        assert_clean(at)
        markdown, elements, figures, answers, derivations = counted(at)
        assert markdown == 1, (pid, state, markdown)  # the heading
        assert elements == (3 if on_request else 2), (pid, state, elements)
        ours = [e.proto for e in at.main if getattr(e, "type", None) == "bidi_component"]
        for proto in ours:  # each carries a stub that imports its module, never the module itself
            assert len(proto.js_content) <= STUB_BYTES and not proto.isolate_styles, len(proto.js_content)
            assert (figure_module if proto.component_name == component.NAME else lesson_module) in proto.js_content
        for proto in ours[1:]:
            for part in orjson.loads(proto.bytes)["parts"]:
                if part["component"] != component.LINKS:  # (drawn by lesson.js itself)
                    assert part["module"].endswith(figure_module if part["component"] == component.NAME else text_module)
        assert all('class="dl-downloads"' not in e.proto.body for e in at.get("html"))  # in ours
        assert len(figures) == len(shown), (pid, state)
        assert len(answers) == 1 and len(derivations) == 1
        # the live values ride with the answers (no element of their own): live.js's path, and its data
        # (the generated function, the followed controls, the answers' units) a few kB
        live = orjson.loads(answers[0])["live"]
        assert live["module"].endswith(live_module) and len(orjson.dumps(live["data"])) <= 8_000
        assert "live" not in orjson.loads(derivations[0])
        if state == "first run":
            # The defaults' figures, byte for byte, each with only its title, description, height
            # and bundle around it.
            for data, figure in zip(figures, shown):
                assert figure.json_bytes() in data
                assert len(data) - len(figure.json_bytes()) <= 200 + len(figure.title) + 3 * len(figure.description.encode())
            widget, spec = first_number_control(at, pid)
            widget.set_value(widget.value * 0.9 if widget.value else 0.1).run()


def test_the_payload_is_one_json_object_around_the_figure():
    solution = importlib.import_module("solvers.disk_wall").solve()
    figure = importlib.import_module("viz.disk_wall").figures(solution)[0]
    sent = orjson.loads(component.payload(figure, "/b.js", component.LECTURE))
    assert sent["spec"] == orjson.loads(figure.json_bytes())
    assert (sent["title"], sent["description"], sent["height"], sent["bundle"], sent["style"]) == (
        figure.title, figure.description, figure.height, "/b.js", component.LECTURE)


@pytest.mark.parametrize("query", [{"practice": "1"}, {"seed": "7"}], ids=["practice", "variant"])
def test_answers_shown_after_show_the_solution_carry_no_live_view(query):
    """The live function would give the answers away before "Show the solution": Practice and a
    variant link send none, before or after the solution is shown; the lesson page does."""
    from tests.pages.test_pages import shown

    assert "live" in shown(run_page("stick_ball"), component.ANSWERS)[0]
    at = run_page("stick_ball", query)
    assert_clean(at)
    assert not shown(at, component.ANSWERS)  # the answers wait for "Show the solution"
    at.button(key="stick_ball__reveal").click().run()
    answers = shown(at, component.ANSWERS)
    assert len(answers) == 1 and "live" not in answers[0]


def test_the_live_view_s_modules_follow_the_base_path_set_after_warming():
    """serve.py warms (every state's values and pose modules generated) before the command line sets
    ``server.baseUrlPath``: the paths a run sends are made with the base path as it is then."""
    from streamlit import config

    from solvers.pendulum_rebound import solve
    from ui import live
    from solvers.catalog import BY_ID

    problem, solution = BY_ID["pendulum_rebound"], solve()
    shown = importlib.import_module("viz.pendulum_rebound").figures(solution)
    answers = problem.answers_of(solution)
    at_root = live.payload(problem, solution, answers, "si", shown[0])  # warmed at the root
    config.set_option("server.baseUrlPath", "dynamics-lab")
    try:
        prefixed = live.payload(problem, solution, answers, "si", shown[0])
    finally:
        config.set_option("server.baseUrlPath", "")
    assert not at_root["module"].startswith("/dynamics-lab/") and not at_root["data"]["pose"]["url"].startswith("/dynamics-lab/")
    assert prefixed["module"].startswith("/dynamics-lab/component/")
    assert prefixed["data"]["pose"]["url"] == "/dynamics-lab" + at_root["data"]["pose"]["url"]
    assert not at_root["data"]["values"].startswith("/dynamics-lab/")
    assert prefixed["data"]["values"] == "/dynamics-lab" + at_root["data"]["values"]


@pytest.mark.parametrize("query", [{"practice": "1"}, {"seed": "7"}], ids=["practice", "variant"])
def test_only_the_lesson_page_s_motion_is_computed_in_the_browser(query):
    """The browser's motion is generated with the live values (ui/live.py: motion_source), which would
    give the answers away: the lesson page's stage names its module and carries no frame; Practice and
    a variant link, after "Show the solution" too, get the server's frames and no module."""
    from tests.pages.test_pages import shown

    lesson = shown(run_page("disk_wall"), component.NAME)
    assert lesson[0]["motion"]["module"].startswith("/component/") and "coords" not in lesson[0]["spec"]["animation"]
    at = run_page("disk_wall", query)
    assert_clean(at)
    at.button(key="disk_wall__reveal").click().run()
    figures = shown(at, component.NAME)
    assert figures and all("motion" not in f and "coords" in f["spec"]["animation"] for f in figures)


@pytest.mark.parametrize("pid", IDS)
def test_a_run_computes_its_motion_at_most_once(pid, monkeypatch):
    """The stage's figure, a free-body diagram drawn at one of the motion's frames and the Forces overlay
    all read one motion (solvers.solution.per_solution): a change costs the server one motion at most,
    whichever of them the page shows. Counted at the solver's own computation, for new values each run."""
    from solvers import registry
    from solvers.solution import per_solution

    module = importlib.import_module(registry.solver(pid).__name__)
    computed, compute = [], module.motion.__wrapped__

    def counted_motion(solution, *args, **kwargs):
        computed.append(solution)
        return compute(solution, *args, **kwargs)
    monkeypatch.setattr(module, "motion", per_solution(counted_motion))
    at = run_page(pid, {"forces": "1"})
    assert_clean(at)
    for change in range(2):
        computed.clear()
        control, _ = first_number_control(at, pid)
        control.set_value(control.value * (1.02 if change else 0.98)).run()
        assert_clean(at)
        assert len(computed) <= 1, f"{len(computed)} motions computed for one change"


def test_a_motion_is_kept_with_its_solution_and_shared_read_only():
    """per_solution keeps a result while its solution lives, and no longer; another solution of the same
    values computes its own; the shared arrays cannot be written through."""
    import gc

    from solvers import pendulum_rebound as solver

    first = solver.solve()
    motion = solver.motion(first)
    assert solver.motion(first) is motion
    assert solver.motion(solver.solve()) is not motion
    with pytest.raises(ValueError):
        motion["theta"][0] = 0.0
    kept = solver.motion.__closure__  # the results dict, found by the solution's id
    results = next(c.cell_contents for c in kept if isinstance(c.cell_contents, dict))
    key = next(k for k in results if k[0] == id(first))
    del first, motion
    gc.collect()
    assert key not in results
