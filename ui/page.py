"""One problem page, the same for all six: controls -> solve -> answers, figure, derivation."""
from __future__ import annotations

import functools
import importlib
import math

import streamlit as st

from practice.variants import variant
from ui import results
from ui.practice import instructor_export, practice_panel, seed_from_url
from ui.catalog import BY_ID, Problem
from ui.figure import show as show_figure
from ui.params import mirror_to_url, parameter_panel

LECTURE_CSS = """
<style>
  .stMainBlockContainer { font-size: 1.3rem; }
  .stMainBlockContainer h1 { font-size: 2.8rem; }
  .stMainBlockContainer .katex { font-size: 1.45em; }
  .stMainBlockContainer table { font-size: 1.25rem; }
</style>
"""


def _page_flags(problem: Problem) -> tuple[str, bool, bool]:
    """Unit system, lecture view and practice mode: sidebar toggles, initialised from ?units=us,
    ?lecture=1 and ?practice=1."""
    units_key, lecture_key = f"{problem.id}__units", f"{problem.id}__lecture"
    practice_key = f"{problem.id}__practice_mode"
    if practice_key not in st.session_state:
        st.session_state[practice_key] = st.query_params.get("practice") == "1"
    if units_key not in st.session_state:
        st.session_state[units_key] = "US customary" if (
            problem.us_units and st.query_params.get("units") == "us") else "SI"
    if lecture_key not in st.session_state:
        st.session_state[lecture_key] = st.query_params.get("lecture") == "1"
    system = "si"
    if problem.us_units:
        choice = st.sidebar.segmented_control("Units", ["SI", "US customary"], key=units_key,
                                              help="The textbook states this problem in lb and ft.")
        system = "us" if choice == "US customary" else "si"
    lecture = st.sidebar.toggle("Lecture view", key=lecture_key,
                                help="Large type and the animation first, for a projector.")
    practice = st.sidebar.toggle("Try it yourself", key=practice_key,
                                 help="Hide the answers, type your own, and get feedback.")
    return system, lecture, practice


def _answers_for(solver, solution):
    picker = getattr(solver, "answers_for", None)
    return picker(solution.regime) if picker else solver.ANSWERS


@functools.lru_cache(maxsize=256)
def _computed(problem_id: str, key: tuple, system: str):
    """Solution and figures for one state, shared by every session of this process: in a lecture
    many students ask for the same numbers. Refusals (ValueError) are not cached."""
    solution = BY_ID[problem_id].solver.solve(**dict(key))
    figures = tuple(importlib.import_module(f"viz.{problem_id}").figures(solution, system))
    for figure in figures:
        figure.json_bytes()  # serialise once, here
    return solution, figures


def _solve_and_draw(problem: Problem, params: dict, system: str):
    if any(isinstance(v, float) and math.isnan(v) for v in params.values()):
        return problem.solver.solve(**params), ()  # refused with the solver's message
    return _computed(problem.id, tuple(sorted(params.items())), system)


def _on_request(problem: Problem, solution) -> None:
    """A costly extra figure some problems offer (e.g. Euler's disk running down), drawn only when
    asked for and cached by parameters across sessions."""
    viz = importlib.import_module(f"viz.{problem.id}")
    if hasattr(viz, "on_request") and st.toggle(viz.on_request.__doc__.split(":")[0],
                                                key=f"{problem.id}__on_request"):
        with st.spinner("Integrating the equations of motion…"):
            show_figure(_requested(problem.id, tuple(sorted(solution.params.items()))))


@functools.lru_cache(maxsize=64)
def _requested(problem_id: str, key: tuple):
    solution = BY_ID[problem_id].solver.solve(**dict(key))
    return importlib.import_module(f"viz.{problem_id}").on_request(solution)


def _figures(figures) -> None:
    """The motion and its companion plots, each with the text a screen reader gets."""
    for figure in figures:
        show_figure(figure)  # title and text description are drawn with it


def _leave_legacy_pages_mode() -> None:
    """Streamlit runs a deep-linked ``pages/<id>.py`` by itself (its legacy pages-folder mode) until
    app.py has called st.navigation once in the process, so a student opening a shared link on a
    freshly started server would get a page without the app's navigation and layout (streamlit
    issues #9624, #10276). st.navigation clears this process-wide flag on its first call; clear it
    here and rerun, so app.py runs and serves the same page from the very first visit."""
    from streamlit.runtime.pages_manager import PagesManager

    if PagesManager.uses_pages_directory:
        PagesManager.uses_pages_directory = False
        st.rerun()


def problem_page(problem_id: str) -> None:
    _leave_legacy_pages_mode()
    problem = BY_ID[problem_id]
    solver = problem.solver
    system, lecture, practice = _page_flags(problem)
    if lecture:
        st.html(LECTURE_CSS)
    st.markdown(f"# {problem.title}\n:gray[{problem.blurb} Source: {problem.source}.]")
    seed, seed_warning = seed_from_url()
    base = variant(solver, problem.id, seed) if seed is not None else {}
    st.sidebar.markdown("### Parameters" + (f" · variant {seed}" if seed is not None else ""))
    params, warnings = parameter_panel(problem, system, base)
    mirror_to_url(problem, params, system, {"units": "us" if system == "us" else "",
                                            "lecture": "1" if lecture else "", "practice": "1" if practice else "",
                                            "seed": str(seed) if seed is not None else ""}, base)
    for warning in [seed_warning, *warnings]:
        if warning:
            st.warning(warning, icon=":material/link_off:")
    try:
        solution, figures = _solve_and_draw(problem, params, system)
    except ValueError as error:
        results.refused(error, system)
        return

    answers = _answers_for(solver, solution)
    if practice and not practice_panel(problem, solution, answers, system):
        _derivation(solver, solution, numeric=False)
        instructor_export(problem)
        return
    if lecture:
        _figures(figures)
    results.answer_section(solution, answers, system)
    if not lecture:
        _figures(figures)
    _on_request(problem, solution)
    _derivation(solver, solution, numeric=True)
    if practice:
        instructor_export(problem)


def _derivation(solver, solution, numeric: bool) -> None:
    derivation_tab, slips_tab = st.tabs(["Derivation, step by step", "Common slips in the worked solution"])
    with derivation_tab:
        if numeric:
            st.caption("Generated from the sympy derivation; the last steps put in your numbers (SI).")
            results.derivation(solution)
        else:
            st.caption("The method, without the numbers: the final steps appear with the solution.")
            results.derivation(solution, symbolic_only=True)
    with slips_tab:
        results.errata(solver.ERRATA)
