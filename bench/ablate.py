"""What fewer elements would buy (issue 28): a page's AppTest run with pieces of the lesson replaced,
against the empty one-slider page interleaved in the same process, as ``bench/interaction.py`` pairs
them. Not the app: a measurement of what a rewrite would save before it is written.

    python bench/ablate.py [--changes 40] [--pages PAGE ...] [--variant as-is|controls|live|controls+live]

Variants: ``as-is``; ``controls``: the lesson's Streamlit controls replaced by one components-v2
element carrying their values (what one controls element of our own would cost: values set through
session state, as the browser's element would); ``live``: the live view's data left out of the answers;
``separate``: the answers, the companion figures, the derivation and the links each in an element of
its own, as before they rode together (what ``ui.figure.together`` saved); ``stage``: the motion on
the stage carried in that element too (what drawing the stage's figure with the rest would save; drawn
in the wrong place, a measurement only); combined with "+". Every variant sets the lesson control through session state, so they differ only
in what the page draws. Prints the median page and empty times and the median of the paired ratios.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


def _replaced(variant: str) -> None:
    import orjson
    import streamlit as st

    import ui.live as live
    import ui.page as page
    import ui.params as params
    from ui import figure

    if "controls" in variant:
        drawn = page.lesson_parameters

        def lesson_parameters(problem, system, base, stage):
            """The page's own, with each control's value read from its state instead of drawn, and one
            element carrying them all."""
            control, params._control = params._control, lambda p, problem, system, _: st.session_state[
                params.control_key(problem, system, p.name)]
            try:
                values = drawn(problem, system, base, stage)
            finally:
                params._control = control
            first, _ = params._split(problem)
            with stage:
                figure.declared(figure.DERIVATION)(data=orjson.dumps({"controls": [[p.name, params._label(p, system),
                                                                                    values[p.name]] for p in first]}),
                                                   key="dl_controls")
            return values
        page.lesson_parameters = lesson_parameters
    if "live" in variant:
        live.payload = lambda *a, **k: None
    if "separate" in variant:
        from ui import results, takehome

        def separate(problem, solution, answers, system, figures, all_figures, lecture, fit_first=False, live_view=None,
                     links=None):
            if lecture:
                for n, drawn in enumerate(figures):
                    figure.show(drawn, page=all_figures, lecture=True, fit_screen=fit_first and n == 0)
            results.answer_section(solution, answers, system, live_view)
            if not lecture:
                for drawn in figures:
                    figure.show(drawn, page=all_figures)
            page._on_request(problem, solution, all_figures)
            page._derivation(problem.solver, solution)
            if links is not None:
                takehome.lesson_links(problem)
        page._results = separate
    if "stage" in variant:
        show, results_of = page.show_figure, page._results
        page.show_figure = lambda drawn, page=(), lecture=False, fit_screen=False: None if fit_screen else show(
            drawn, page=page, lecture=lecture, fit_screen=fit_screen)
        page._results = lambda problem, solution, answers, system, figures, all_figures, lecture, fit_first=False, \
            live_view=None, links=None: results_of(problem, solution, answers, system,
                                                   all_figures if live_view is not None else figures, all_figures,
                                                   lecture, fit_first, live_view, links)


def measure(pid: str, variant: str, changes: int) -> tuple[float, float, float]:
    from streamlit.testing.v1 import AppTest

    from bench.controls import changes_of, lesson_control

    key, _, _, _ = lesson_control(pid)
    page = AppTest.from_file(str(ROOT / "app_pages" / f"{pid}.py"), default_timeout=120).run()
    empty = AppTest.from_file(str(ROOT / "bench" / "empty_page.py"), default_timeout=120).run()
    page_times, empty_times = [], []
    values = changes_of(pid, changes)
    for i, value in enumerate(values, start=1):
        page.session_state[key] = value
        began = time.perf_counter()
        page.run()
        page_times.append(time.perf_counter() - began)
        assert not page.exception and not page.error, (pid, value)
        empty.session_state["x"] = round(0.9 - 0.5 * i / len(values), 6)
        began = time.perf_counter()
        empty.run()
        empty_times.append(time.perf_counter() - began)
    ratios = [p / e for p, e in zip(page_times, empty_times)]
    return statistics.median(page_times), statistics.median(empty_times), statistics.median(ratios)


def main() -> None:
    from solvers import registry

    parser = argparse.ArgumentParser()
    parser.add_argument("--changes", type=int, default=40)
    parser.add_argument("--pages", nargs="*", default=list(registry.PROBLEM_IDS))
    parser.add_argument("--variant", default="as-is", help="as-is, controls, live, separate, stage or a combination (controls+live)")
    args = parser.parse_args()
    from serve import warm
    warm()
    _replaced(args.variant)
    print("| page | variant | page ms | empty ms | × empty |\n|---|---|---|---|---|")
    for pid in args.pages:
        p, e, ratio = measure(pid, args.variant, args.changes)
        print(f"| {pid} | {args.variant} | {1000 * p:.1f} | {1000 * e:.1f} | {ratio:.2f} |", flush=True)


if __name__ == "__main__":
    main()
