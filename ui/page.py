"""One problem page, the same for every problem: controls -> solve -> answers, figure, derivation."""
from __future__ import annotations

import contextlib
import functools
import math
from concurrent.futures.process import BrokenProcessPool

import orjson
import streamlit as st

from assignments.identity import LINK_KEYS, parameters
from practice.variants import variant
from solvers.core import PhysicalLimitError, Solution, within_model_range
from solvers import units
from solvers.catalog import BY_ID, Problem
from viz import diagram, on_request
from viz.catalog import drawings
from edge import widget_values
from edge.streamlit_dom import KEYS
from ui import assignments, figure, live, results, room, takehome
from ui.figure import show as show_figure
from ui.params import (MAX_URL_VALUE, check_in_range, fixed_parameters, lesson_parameters, mirror_to_url,
                       more_parameters, parameter_panel, refused_values_notice, unknown_in_link)
from ui.practice import method as practice_method, practice_panel, seed_from_url
from ui.results import literal
from ui.session import is_instructor
from ui.stylesheet import LECTURE_CSS, PHONE_CSS, PRINT_CSS, RUN_CSS, STAGE_CSS, Stylesheet
from ui.variants import variants_export

STYLES = {lecture: Stylesheet(RUN_CSS + PHONE_CSS + STAGE_CSS + PRINT_CSS + takehome.TAKEHOME_CSS + (LECTURE_CSS if lecture else ""))
          for lecture in (False, True)}

HEADING = "# {p.title}\n:gray[{p.blurb} Source: {p.source}.]"
VIEWS = ("Study", "Lecture", "Practice")
VIEW_HELP = ("Study: answers, animation and derivation. Lecture: large type and the animation first, for "
             "a projector. Practice: the answers are hidden; type your own and get feedback.")
VARIANT_HELP = ("A variant link (?seed=N) or an assignment link opens in Practice: its answers appear with "
                "“Show the solution”. Instructors with the key can switch a variant link's view.")


# What a page's address may carry besides its problem's parameters: the page's own flags, an assignment
# link's keys, an LMS launch's hand-off, the instructor key (taken out at once), Streamlit's embedding.
LINK_FLAGS = frozenset(("units", "lecture", "practice", "instructor", "lti", *LINK_KEYS, "embed", "embed_options"))


FORCES_FLAG = "forces"  # ?forces=1: the stage's Forces switch (a button in the motion's row, figure.js) on


def _has_forces_overlay(problem: Problem) -> bool:
    """Whether the stage can lay the diagram's forces on the motion (the diagrams declare their frames)."""
    return _overlaid(problem.id)


@functools.cache
def _overlaid(problem_id: str) -> bool:
    solver = BY_ID[problem_id].solver
    return bool(diagram.overlaid(solver, solver.solve().params))


def _forces_key(problem: Problem) -> str:
    return f"{problem.id}__forces"


def _forces_on(problem: Problem) -> bool | None:
    """The stage's Forces switch: on or off (from the link at first, ``FORCES_FLAG``), or None where the
    problem's stage cannot show them."""
    if not _has_forces_overlay(problem):
        return None
    key = _forces_key(problem)
    if key not in st.session_state:
        st.session_state[key] = st.query_params.get(FORCES_FLAG) == "1"
    return bool(st.session_state[key])


def _unknown_in_link(problem: Problem) -> str | None:
    """What the page says of a link's names it does not know and of its flags' values it does not take."""
    asked = drawings(problem.id).on_request
    switches = ("lecture", "practice", *([asked.flag] if asked else []),
                *([FORCES_FLAG] if _has_forces_overlay(problem) else []))
    said = [unknown_in_link(problem, st.query_params.keys(), LINK_FLAGS | set(switches))]
    units_asked = st.query_params.get("units", "si")
    if not problem.us_units and units_asked != "si":  # (?units=us on an SI-only page)
        said.append("This problem is stated in SI units only: the link's units are left out.")
    elif units_asked not in ("si", "us"):
        said.append(f"The link's units “{literal(units_asked[:MAX_URL_VALUE])}” are neither si nor us: SI is used.")
    said += [f"The link's {flag}=“{literal(st.query_params[flag][:MAX_URL_VALUE])}” is not 1 (on) or 0 (off): "
             "taken as off." for flag in switches if st.query_params.get(flag, "0") not in ("0", "1", "")]
    return " ".join(filter(None, said)) or None


def _page_flags(problem: Problem, practice_only: bool = False) -> tuple[str, str]:
    """Unit system and view (Study, Lecture or Practice): sidebar controls, initialised from
    ?units=us, ?lecture=1 and ?practice=1. ``practice_only``: a student's variant link, whose
    answers only "Show the solution" reveals."""
    us_key, view_key = f"{problem.id}__us", f"{problem.id}__view"
    if practice_only:
        st.session_state[view_key] = "Practice"
    if view_key not in st.session_state:
        st.session_state[view_key] = ("Practice" if st.query_params.get("practice") == "1" else
                                      "Lecture" if st.query_params.get("lecture") == "1" else "Study")
    system = "si"
    if problem.us_units:
        if us_key not in st.session_state:
            st.session_state[us_key] = st.query_params.get("units") == "us"
        us = st.sidebar.toggle("US customary units (lb, ft)", key=us_key,
                               help="The textbook states this problem in lb and ft; off: SI (kg, m).")
        system = "us" if us else "si"
    if practice_only:  # plain text: a disabled control's grey label fails AA contrast (axe-core)
        st.sidebar.markdown("**View:** Practice", help=VARIANT_HELP)
        return system, "Practice"
    view = st.sidebar.segmented_control("View", VIEWS, key=view_key, required=True, help=VIEW_HELP)
    return system, view


@functools.lru_cache(maxsize=256)
@within_model_range  # the drawing too: scales like b / (m g) overflow where the answers did not
def _computed(problem_id: str, key: tuple, system: str, forces: bool = False, in_browser: bool = False):
    """Solution and figures for one state, shared by every session of this process: in a lecture
    many students ask for the same numbers. Refusals (ValueError) are not cached. ``forces``: the
    stage figure with the free-body diagram's forces on the motion (viz.diagram.overlay);
    ``in_browser``: the stage's frames left to the browser (ui.live.in_browser)."""
    solver = BY_ID[problem_id].solver
    solution = solver.solve(**dict(key))
    figures = tuple(drawings(problem_id).figures(solution, system, **({"in_browser": True} if in_browser else {})))
    if forces:
        stage = figures[0]
        x_range = stage.spec["layout"]["xaxis"]["range"]
        traces, scales = diagram.overlay(solver, solution, solver.motion(solution), float(x_range[1] - x_range[0]),
                                         units.to_display(1.0, "length", system))
        figures = (diagram.with_overlay(stage, traces, scales), *figures[1:])
    for drawn in figures:
        drawn.json_bytes()  # serialise once, here
    return solution, figures


def _solve_and_draw(problem: Problem, params: dict, system: str, forces: bool = False, in_browser: bool = False):
    if any(isinstance(v, float) and math.isnan(v) for v in params.values()):
        return problem.solver.solve(**params), ()  # refused with the solver's message
    return _computed(problem.id, tuple(sorted(params.items())), system, forces, in_browser)


def _on_request(problem: Problem, solution, figures) -> None:
    """A costly extra figure some problems offer (e.g. Euler's disk running down), drawn only when
    asked for, in a worker process (viz.on_request), and kept by parameters across sessions; drawn
    with the plotly.js of the page's ``figures``."""
    asked = drawings(problem.id).on_request
    if asked and st.toggle(asked.label, key=f"{problem.id}__on_request"):
        ahead = on_request.waiting()  # (a figure already drawn is shown at once: the spinner never appears)
        words = ("Integrating the equations of motion: usually 5 to 15 s"
                 + (f", after {ahead} run{'s' if ahead > 1 else ''} other students asked for first" if ahead else "") + "…")
        with st.spinner(words, show_time=True):
            try:
                drawn = on_request.figure(problem.id, tuple(sorted(solution.params.items())))
            except BrokenProcessPool:  # its worker died twice (killed, out of memory): said, never a traceback
                st.error(f"“{asked.label}” could not be computed: its worker process stopped twice. Switch it off "
                         "and on again to retry.", icon=":material/error:")
                return
        show_figure(drawn, page=figures)


def _on_request_flag(problem: Problem) -> dict[str, str]:
    """The URL flag that keeps a problem's on-request figure open (its viz module's ``ON_REQUEST.flag``,
    e.g. ?rundown=1): the switch starts from the link and the link follows the switch."""
    asked = drawings(problem.id).on_request
    if asked is None:
        return {}
    flag = asked.flag
    key = f"{problem.id}__on_request"
    if key not in st.session_state:
        st.session_state[key] = st.query_params.get(flag) == "1"
    return {flag: "1" if st.session_state[key] else ""}


def _figures(figures) -> None:
    """Figures, each in an element of its own with the text a screen reader gets (they share one
    plotly.js bundle)."""
    for drawn in figures:
        show_figure(drawn, page=figures)


def _solved_or_refused(problem: Problem, params: dict, system: str, refused_in=None, practice: bool = False,
                       lecture: bool = False, forces: bool = False, in_browser: bool = False):
    """(solution, figures) for ``params``; or None, once the refusal is said (in ``refused_in``, the
    stage's motion column, if given, with the figures a physical limit keeps, where the motion would
    be) with the method a physical limit keeps below it."""
    try:
        check_in_range(problem, params, system)
        return _solve_and_draw(problem, params, system, forces, in_browser)
    except ValueError as error:
        limit = isinstance(error, PhysicalLimitError)
        with refused_in or contextlib.nullcontext():
            results.refused(error, system, problem.solver.LIMIT_LABELS)
            if limit:
                _limit_figures(problem, params, system, lecture, on_stage=refused_in is not None)
        if limit:
            _method_beside_refusal(problem, params, practice)
        return None


def _limit_figures(problem: Problem, params: dict, system: str, lecture: bool, on_stage: bool) -> None:
    """The figures that show why a physical limit stops the model (``at_limit`` in the problem's viz
    module, where it has one); the first fitted to a laptop's first screen where it stands on the stage
    (not under a refusal in projector type: too little of the screen is left)."""
    at_limit = drawings(problem.id).at_limit
    figures = at_limit(params, system) if at_limit else []
    for n, drawn in enumerate(figures):
        show_figure(drawn, page=figures, lecture=lecture, fit_screen=on_stage and n == 0 and not lecture)


def _results(problem: Problem, solution, answers, system: str, figures, page, lecture: bool, fit_first: bool = False,
             live_view: dict | None = None, links: dict | None = None) -> None:
    """The answers and ``figures`` (before the answers on the projector, after them in Study), the
    costly figure on request and the derivation, in one element (``figure.together``; two, with the
    figure on request's switch between them). ``page``: every figure of the page; ``live_view``: what
    makes the answers follow a dragged lesson control (ui.live.payload); ``links``: the lesson's
    downloads and print link, last (ui.takehome.lesson_links_data)."""
    drawn = [figure.part(figure.NAME, f.key, figure.data(f, page, lecture, fit_first and n == 0))
             for n, f in enumerate(figures)]
    told = figure.part(figure.ANSWERS, "answers", results.answers_data(solution, answers, system, live_view))
    parts = [*drawn, told] if lecture else [told, *drawn]
    last = [figure.part(figure.DERIVATION, "derivation", _derivation_data(problem.solver, solution))]
    if links is not None:
        last.append(figure.part(figure.LINKS, "links", orjson.dumps(links)))
    if not drawings(problem.id).on_request:
        figure.together([*parts, *last], key="dl_results")
        return
    figure.together(parts, key="dl_results")
    _on_request(problem, solution, page)
    figure.together(last, key="dl_derivation")


def problem_page(problem_id: str) -> None:
    problem = BY_ID[problem_id]
    link = assignments.student_link(problem)  # None unless opened with a signed assignment link
    unknown = _unknown_in_link(problem) if link is None else None  # (before the page writes its own address)
    seed, seed_warning = (link.identity.seed, None) if link and link.identity else seed_from_url()
    instructor = is_instructor()  # before mirror_to_url drops ?instructor=KEY from the address
    system, view = _page_flags(problem, practice_only=(seed is not None and not instructor) or link is not None)
    lecture, practice = view == "Lecture", view == "Practice"
    if lecture:  # the projector: the stage gets the screen, one click brings the sidebar back
        st.set_page_config(initial_sidebar_state="collapsed")
    st.html(STYLES[lecture])
    heading = HEADING.format(p=problem)
    if link is not None:  # an assignment: its variant, fixed, and the link kept as it came
        _heading(problem, heading, [])
        if link.refused:
            st.error(link.refused, icon=":material/link_off:")
            assignments.refused_links(link)
            return
        _assignment(problem, link, system)
        return
    if seed is None and not practice:  # the lesson page: the stage and all that follows it in a fragment
        st.sidebar.markdown("### Parameters")
        warnings = more_parameters(problem, system, None, st.sidebar)
        _heading(problem, heading, (seed_warning, unknown, *warnings), print_link=False)  # (the fragment's)
        if lecture and instructor and room.projector(problem, system):
            return  # a question put to the room keeps the motion hidden until its reveal
        _lesson(problem.id, system, lecture)
        return
    head = st.container()  # the title, filled once the state is known
    if seed is None:  # Practice: the controls in the sidebar
        st.sidebar.markdown("### Parameters")
        base = {}
        params, warnings = parameter_panel(problem, system)
    else:  # a variant's givens are fixed, as on an assignment link: a nudged control would be another problem
        base = variant(problem.solver, problem.id, seed)
        params, warnings = fixed_parameters(problem, system, base, seed)
    _mirror(problem, params, system, lecture, practice, seed, base)
    solved = _solved_or_refused(problem, params, system, practice=practice)
    with head:
        _heading(problem, heading, (seed_warning, unknown, *warnings))
    if solved is None:
        return
    solution, figures = solved
    answers = problem.answers_of(solution)
    if practice and not practice_panel(problem, solution, answers, system):
        takehome.downloads(problem, solution, answers, system, exercise=True)  # the statement and the method
        variants_export(problem)  # the statement, the method and the answer box, nothing more
        return
    # fitted to the first screen where the view puts the motion first (Lecture), not below the answers
    _results(problem, solution, answers, system, figures, figures, lecture, fit_first=lecture)
    takehome.downloads(problem, solution, answers, system)
    if practice:
        variants_export(problem)


def _mirror(problem: Problem, params: dict, system: str, lecture: bool, practice: bool, seed, base: dict,
            forces: bool = False) -> None:
    mirror_to_url(problem, params, system, {"units": "us" if system == "us" else "",
                                            **({FORCES_FLAG: "1" if forces else ""} if _has_forces_overlay(problem) else {}),
                                            "lecture": "1" if lecture else "", "practice": "1" if practice else "",
                                            "seed": str(seed) if seed is not None else "",
                                            **_on_request_flag(problem)}, base)


@st.fragment
def _lesson(problem_id: str, system: str, lecture: bool) -> None:
    """The lesson (Study and Lecture): the stage, the motion with the lesson's controls beside it
    (below it on a phone), then the answers, the companion figures, the derivation and the downloads.
    A fragment: moving a lesson control reruns this alone, not the page's navigation, view, units
    and sidebar (what a change does not touch); those run it again when they change."""
    problem = BY_ID[problem_id]
    if widget_values.take_refusals():
        refused_values_notice()
    forces = _forces_on(problem)  # (the stage's own switch: its press reruns this fragment)
    stage = st.container(key=KEYS["stage"], horizontal=True, wrap=False, gap="medium")  # a row (STAGE_CSS), not columns: two elements fewer a run
    motion_column = stage.container(key=KEYS["motion"])
    params = lesson_parameters(problem, system, None, stage.container(key=KEYS["stageControls"]))
    _mirror(problem, params, system, lecture, False, None, {}, bool(forces))
    # the stage's frames computed by the browser where the problem's motion is generated for it (not under
    # the Forces overlay, whose arrows the server draws); the lesson page only: the generated code carries the answers
    in_browser = not forces and live.in_browser(problem.id)
    solved = _solved_or_refused(problem, params, system, motion_column, lecture=lecture, forces=bool(forces),
                                in_browser=in_browser)
    if solved is None:
        takehome.lesson_links(problem, downloads=False)
        return
    solution, figures = solved
    answers = problem.answers_of(solution)
    with motion_column:  # the motion on the stage, fitted to the first screen; its companions below
        show_figure(figures[0], page=figures, lecture=lecture, fit_screen=True, forces=forces,
                    on_forces=None if forces is None else functools.partial(_set_forces, problem),
                    motion=live.motion_module(problem.id, solution.params, system) if in_browser else None)
    # the answers follow a dragged control (never in Practice)
    _results(problem, solution, answers, system, figures[1:], figures, lecture,
             live_view=live.payload(problem, solution, answers, system, figures[0]),
             links=takehome.lesson_links_data(problem))


def _set_forces(problem: Problem, wanted: bool) -> None:
    st.session_state[_forces_key(problem)] = wanted


def _assignment(problem: Problem, link, system: str) -> None:
    """A student's assignment: the link's variant with no controls to change it, judged and recorded
    under the assignment's rules (or, with the database down, practice unrecorded, and said so)."""
    params = dict(problem.solver.solve(**parameters(link.identity, problem.solver, problem.id)).params)
    st.sidebar.markdown("### Parameters\nFixed by your assignment link.")  # no number a ?seed link could reuse
    keep = {k: st.query_params.get(k) for k in ("assignment", "seed", "student", "sig")}
    mirror_to_url(problem, params, system, {"units": "us" if system == "us" else "", **keep}, params)
    banner = st.container()  # filled last, so it counts the attempt this run records
    solution, figures = _solve_and_draw(problem, params, system)
    answers = problem.answers_of(solution)
    if link.settings is not None:
        part = link.settings.part(problem.id)
        answers = tuple(a for a in answers if a.name in part.answers)
    recording = assignments.recording(link, solution, system) if link.settings is not None else None
    if practice_panel(problem, solution, answers, system, recording):
        results.answer_section(solution, answers, system)
        _figures(figures)
        _derivation(problem.solver, solution)
        takehome.downloads(problem, solution, answers, system)
    else:
        takehome.downloads(problem, solution, answers, system, exercise=True)
    assignments.your_attempts(link, answers, solution, system)
    with banner:
        assignments.assignment_heading(link)


def _method_beside_refusal(problem: Problem, params: dict, practice: bool = False) -> None:
    """A physical limit is where the lesson is: keep what shows why (beside the problem's figures for
    it, ``at_limit`` in its viz module: the derivation without numbers), where the problem offers it.
    In Practice the derivation would give the answers' closed forms away, so it shows the method as
    the exercise does: titles, and only the equations that show no result."""
    method = getattr(problem.solver, "method", None)
    if method is None:
        return
    steps = Solution(problem.id, params, {}, method(params))
    if practice:
        st.markdown(practice_method(steps.steps, problem.solver.derivation_of(steps)))
    else:
        results.derivation(steps, caption="The method, without numbers: these parameters are past the model's limit.",
                           slips=problem.solver.ERRATA)


def _heading(problem: Problem, heading: str, notices, print_link: bool = True) -> None:
    """The title and blurb, with the link that reproduces the page on paper (the page has mirrored
    its state into the address by now; the lesson's fragment gives its own, takehome.lesson_links),
    and what the address asked that the page could not do (``notices``: the words, or None)."""
    st.markdown(heading + (takehome.print_link(problem) if print_link else ""), unsafe_allow_html=True)
    for notice in filter(None, notices):
        st.warning(notice, icon=":material/link_off:")


DERIVATION_CAPTION = "Generated from the sympy derivation; the last steps put in your numbers (SI)."


def _derivation(solver, solution) -> None:
    """The derivation and the worked solution's slips below it, in one element (tabs would cost a widget's time
    on every run)."""
    results.derivation(solution, caption=DERIVATION_CAPTION, slips=solver.ERRATA)


def _derivation_data(solver, solution) -> bytes:
    return results.derivation_data(solution, caption=DERIVATION_CAPTION, slips=solver.ERRATA)
