"""Every page under Streamlit's AppTest: it runs, its controls drive the derivation and the answers,
its state round-trips through the URL, and bad input of any kind ends in a plain message."""
from __future__ import annotations

import html
import math
import re
from pathlib import Path

import orjson
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as hst
from streamlit.runtime.media_file_manager import MediaFileManager
from streamlit.testing.v1 import AppTest, app_test

from solvers import units
from solvers.catalog import BY_ID, PROBLEMS
from viz.catalog import drawings
from ui import takehome
from ui.figure import ANSWERS, DERIVATION, LESSON, LINKS

IDS = [p.id for p in PROBLEMS]
TIMEOUT = 60
ROOT = Path(__file__).resolve().parents[2]


def run_page(pid: str, query: dict | None = None) -> AppTest:
    at = AppTest.from_file(str(ROOT / "app_pages" / f"{pid}.py"), default_timeout=TIMEOUT)
    at.query_params.update(query or {})
    return at.run()


def sent(at: AppTest) -> list[tuple[str, bytes]]:
    """(component's name, data) of each element of ours in the main area, in order; the parts of a
    lesson element (ui/figure.together) each as the element of its own it stands for."""
    elements = []
    for e in at.main:
        if getattr(e, "type", None) != "bidi_component":
            continue
        if e.proto.component_name == LESSON:
            elements += [(part["component"], orjson.dumps(part["data"])) for part in orjson.loads(e.proto.bytes)["parts"]]
        else:
            elements.append((e.proto.component_name, e.proto.bytes))
    return elements


def shown(at: AppTest, component: str) -> list[dict]:
    """What the page sends to each of its elements named ``component`` (ui/results.py), in its own
    element or as a part of a lesson element."""
    return [orjson.loads(data) for name, data in sent(at) if name == component]


class _KeptMediaFiles(MediaFileManager):
    """AppTest's media files, kept after the run: a page's downloads are made on click (deferred),
    and the tests make them as a click would, from the run's own registry."""
    last: MediaFileManager | None = None

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        _KeptMediaFiles.last = self


app_test.MediaFileManager = _KeptMediaFiles  # every AppTest run keeps its media files for downloads_shown


def downloads_shown(at: AppTest) -> dict[str, str]:
    """Every download the page offers after its last run, by file name, made as a click makes it:
    a download button's function, or a download link's file as serve.py's route makes it."""
    registry = _KeptMediaFiles.last._deferred_callables
    files = {}
    for button in at.get("download_button"):
        entry = registry[button.proto.deferred_file_id]
        data = entry["callable"]()
        files[entry["filename"]] = data.decode() if isinstance(data, bytes) else data
    links = [(html.unescape(href), name) for element in at.get("html")
             for href, name in re.findall(r'<a href="([^"]+)" download="([^"]+)"', element.proto.body)]
    links += [(href, name) for component, data in sent(at) if component == LINKS
              for _, href, name in orjson.loads(data)["downloads"]]  # in the lesson's element (ui/figure.together)
    for href, name in links:
        path, _, query = href.partition("?")
        status, _, body = takehome.made(*takehome.DOWNLOAD.search(path).groups(), query, "/page")
        assert status == 200, body
        files[name] = body.decode()
    return files


def answers_shown(at: AppTest) -> dict | None:
    """The answer section as sent to its element: heading, answers ([symbol, quantity, value] each),
    notes, ledger ([quantity, before, after, conserved, why]) and checks ([ok, name, closed form,
    second method, why]); None where the page shows no answers."""
    sections = shown(at, ANSWERS)
    assert len(sections) <= 1, f"{len(sections)} answer sections"
    return sections[0] if sections else None


def answers_text(at: AppTest) -> str:
    """The answers table as text, a row per line ("" where the page shows no answers)."""
    section = answers_shown(at)
    return answers_text_of(section) if section else ""


def answer_section_text(section: dict) -> str:
    """Every word and number of an answer section, as a student reads them."""
    parts = [section["heading"], answers_text_of(section), *section["notes"]]
    if section["ledger"]:
        parts += [section["ledger_heading"], *(f"{q} {b} {a} {'conserved' if c else 'changes'}: {why}"
                                               for q, b, a, c, why in section["ledger"])]
    parts += [section["checks_heading"], *(f"{'' if ok else 'differs '}{name}: {closed} vs {second} {why}"
                                           for ok, name, closed, second, why in section["checks"])]
    return "\n".join(parts)


def answers_text_of(section: dict) -> str:
    return "\n".join(" | ".join(row) for row in section["answers"])


def derivations_shown(at: AppTest) -> list[dict]:
    """Each derivation as the page sends it to its element (ui/results.py): heading, caption, steps
    ([title, LaTeX] each) and the worked solution's slips."""
    return shown(at, DERIVATION)


def derivation_shown(at: AppTest) -> dict:
    """The page's one derivation."""
    shown = derivations_shown(at)
    assert len(shown) == 1, f"{len(shown)} derivation elements"
    return shown[0]


def latex_text(at: AppTest) -> list[str]:
    """The derivation's display equations, in order."""
    return [tex for _, tex, *_ in derivation_shown(at)["steps"]]  # (the phone's rows; a wide column's beside some)


def derivation_text(at: AppTest, d: dict | None = None) -> str:
    d = d or derivation_shown(at)
    parts = [d["heading"], d["caption"], *(f"{title}\n\n{tex}" for title, tex, *_ in d["steps"])]
    return "\n\n".join(parts + ([d["slips_heading"], *d["slips"]] if d["slips"] else []))


def first_number_control(at: AppTest, pid: str):
    """The first numeric control always on show (a primary parameter)."""
    spec = next(p for p in BY_ID[pid].solver.PARAMS
                if hasattr(p, "dimension") and not p.allow_inf and p.name in BY_ID[pid].primary)
    key = f"{pid}__si__{spec.name}"
    for widget in [*at.number_input, *at.slider]:
        if widget.key == key:
            return widget, spec
    raise AssertionError(f"no control for {key}")


def show_more(at: AppTest, pid: str) -> AppTest:
    """Open "More parameters" (masses, lengths, g)."""
    return at.toggle(key=f"{pid}__more").set_value(True).run()


def assert_clean(at: AppTest) -> None:
    assert not at.exception, [e.value for e in at.exception]


@pytest.mark.parametrize("pid", IDS)
def test_page_runs_with_answers_derivation_and_checks(pid):
    at = run_page(pid)
    assert_clean(at)
    assert not at.error
    assert any(m.value.startswith(f"# {BY_ID[pid].title}") for m in at.markdown)
    symbols = [symbol for symbol, _, _ in answers_shown(at)["answers"]]
    for answer in BY_ID[pid].solver.ANSWERS:
        assert answer.symbol in symbols
    assert len(latex_text(at)) >= 6
    derivation = derivation_text(at)
    errata = BY_ID[pid].solver.ERRATA  # may be empty: a problem not in the worked solutions
    assert ("Common slips in the worked solution" in derivation) == bool(errata)
    assert derivation_shown(at)["slips"] == list(errata), "the worked solution's slips follow it"
    assert answers_shown(at)["checks"], "the checks are shown"


@pytest.mark.parametrize("pid", IDS)
def test_moving_a_control_changes_the_derivation_and_the_answers(pid):
    at = run_page(pid)
    before_answers, before_latex = answers_text(at), latex_text(at)
    symbolic = BY_ID[pid].solver.solve().symbolic_steps
    widget, spec = first_number_control(at, pid)
    widget.set_value(widget.value * 1.1).run()
    assert_clean(at)
    assert not at.error
    assert answers_text(at) != before_answers
    assert latex_text(at) != before_latex
    # Only the steps with numbers change: the browser leaves the symbolic steps as they are.
    assert 0 < symbolic < len(before_latex)
    assert latex_text(at)[:symbolic] == before_latex[:symbolic] and latex_text(at)[symbolic:] != before_latex[symbolic:]
    assert pid and spec.name in at.query_params


@pytest.mark.parametrize("pid", IDS)
def test_url_round_trip_restores_the_same_answers(pid):
    at = run_page(pid)
    widget, _ = first_number_control(at, pid)
    widget.set_value(widget.value * 0.9).run()
    for box in at.radio:  # also move an option, where the problem has one
        options = [o for o in box.options if o != box.value]
        if options and pid != "pendulum_rebound":
            box.set_value(box.options[1] if box.value == box.options[0] else box.options[0]).run()
            break
    assert not at.error
    query = dict(at.query_params)
    assert query
    again = run_page(pid, query)
    assert_clean(again)
    assert answers_text(again) == answers_text(at)
    assert latex_text(again) == latex_text(at)
    assert not again.warning


BAD_VALUES = ["abc", "nan", "NaN", "-inf", "1e999", "-5", "1" * 200, "__import__('os')", "<script>x</script>", ""]


@pytest.mark.parametrize("pid", IDS)
@pytest.mark.parametrize("bad", BAD_VALUES)
def test_bad_url_values_fall_back_to_the_default_with_a_warning(pid, bad):
    spec = next(p for p in BY_ID[pid].solver.PARAMS if hasattr(p, "dimension") and p.low == 0)
    at = run_page(pid, {spec.name: bad})
    assert_clean(at)
    assert any(f"**{spec.name}**" in w.value for w in at.warning), [w.value for w in at.warning]
    assert answers_text(at) == answers_text(run_page(pid))  # the default's answers


@pytest.mark.parametrize("pid", IDS)
@pytest.mark.parametrize("magnitude", ["1e300", "1e-300"])
def test_every_parameter_at_an_extreme_magnitude_gives_answers_or_a_plain_message(pid, magnitude):
    """?L=1e300 and the like used to end in an OverflowError's traceback."""
    numeric = [p.name for p in BY_ID[pid].solver.PARAMS if hasattr(p, "dimension")]
    at = run_page(pid, {name: magnitude for name in numeric})
    assert_clean(at)
    assert answers_text(at) or (at.error and "Traceback" not in at.error[0].value)


@pytest.mark.parametrize("pid,query", [
    ("disk_wall", {"V": "1e200"}), ("disk_wall", {"omega": "1e200"}), ("pendulum_rebound", {"L": "1e300"}),
    ("stick_ball", {"l": "1e300"}), ("stick_ball", {"v": "1e300"}), ("stick_ball", {"m_ball": "1e300"}),
])
def test_the_reviewed_huge_url_values_show_a_plain_message(pid, query):
    at = run_page(pid, query)
    assert_clean(at)
    (name,) = query
    # Beyond the magnitudes a model is meant for, the link's value is dropped with a warning that
    # names it (the textbook's value is used); an error would do too. Never a traceback.
    named = [w.value for w in at.warning if name in w.value] + [e.value for e in at.error]
    assert named and all("Traceback" not in text for text in named), answers_text(at)


@pytest.mark.parametrize("pid", IDS)
def test_a_stated_range_names_only_limits_that_hold(pid):
    """A refusal states the range the value must be in: each limit it names is one the model keeps (a
    value past it is refused, one within it is not), a size ("at most 5000 rad/s in size") only for a
    quantity that may be negative, and no limit beside a tighter one (e's range said "at least 0 and at
    most 1, at most 600 in size")."""
    from ui.params import shown_range
    from solvers.core import Number, ParameterError

    for p in BY_ID[pid].solver.PARAMS:
        if not isinstance(p, Number):
            continue
        said = shown_range(p, "si")
        assert "in size" not in said or p.low is None or p.low < 0, said
        tops = [float(re.sub(r"\s", "", t)) for t in re.findall(r"at most (\d[\d\s]*(?:\.\d+)?)", said)]  # 20 000
        assert len(tops) <= 1, said  # one top, not two
        for top in tops:  # (in SI: the unit these parameters show is SI's own, degrees aside)
            if p.dimension == "angle":
                continue
            p.validate(top)  # the top itself is kept
            with pytest.raises(ParameterError):
                p.validate(top * 1.01 + 1e-9)


@pytest.mark.parametrize("pid", IDS)
def test_bad_option_in_url_is_named(pid):
    choice = next((p for p in BY_ID[pid].solver.PARAMS if hasattr(p, "options")), None)
    if choice is None:
        pytest.skip("no option parameter on this page")
    at = run_page(pid, {choice.name: "DROP TABLE"})
    assert_clean(at)
    assert any(choice.name in w.value for w in at.warning)


@pytest.mark.parametrize("pid,query,limit_label", [
    ("driven_cart", {"drive": "rear", "mu": "3"}, "front wheels lift"),
    ("driven_cart", {"drive": "all", "mu": "6"}, "front wheels lift"),
    ("rod_disk_spring", {"k": "100"}, "largest angle"),
    ("rod_disk_spring", {"k": "40", "theta2": "300"}, "largest angle"),
    ("pendulum_rebound", {"theta0": "-60"}, "sphere touches"),
])
def test_refused_combinations_explain_the_limit(pid, query, limit_label):
    at = run_page(pid, query)
    assert_clean(at)
    assert at.error and "Traceback" not in at.error[0].value
    assert any(limit_label in m.label for m in at.metric)


@pytest.mark.parametrize("pid,name,value", [
    ("stick_ball", "l", 0.6),  # a stick too short for s = 0.5: off it
    ("pendulum_rebound", "d", 0.01),  # floor above the sphere
    ("disk_wall", "m", -1.0),  # a negative mass
    ("eulers_disk", "m", 0.0),
])
def test_bad_control_values_show_a_plain_message(pid, name, value):
    at = show_more(run_page(pid), pid)
    key = f"{pid}__si__{name}"
    next(w for w in [*at.number_input, *at.slider] if w.key == key).set_value(value).run()
    assert_clean(at)
    assert at.error
    assert name in at.error[0].value or "must" in at.error[0].value


def test_no_slip_toggle_gives_finite_mu_control():
    at = run_page("disk_wall")
    at.toggle(key="disk_wall__si__mu__inf").set_value(False).run()
    at.slider(key="disk_wall__si__mu").set_value(0.02).run()
    assert_clean(at)
    assert at.query_params.get("mu") == "0.02"
    assert "Slides" in " ".join(answers_shown(at)["notes"])


def test_pendulum_in_us_customary_units():
    at = show_more(run_page("pendulum_rebound", {"units": "us"}), "pendulum_rebound")
    assert_clean(at)
    mass = at.number_input(key="pendulum_rebound__us__m_s")
    assert mass.value == pytest.approx(10.0, rel=1e-4)  # the textbook's 10 lb sphere
    length = at.number_input(key="pendulum_rebound__us__L")
    assert length.value == pytest.approx(2.0, rel=1e-4)  # 2 ft rod
    assert "ft·lbf" in answers_text(at)
    si = run_page("pendulum_rebound")
    # the same physics: the angle rows are identical in either system, the energy converts
    angle_rows = lambda t: [r for r in t.splitlines() if "°" in r]  # noqa: E731
    assert angle_rows(answers_text(at)) and angle_rows(answers_text(at)) == angle_rows(answers_text(si))
    assert at.query_params.get("units") == "us" and at.query_params.get("m_s") is None  # default, in lb


def test_the_units_switch_converts_the_shown_values_and_keeps_the_physics():
    at = run_page("pendulum_rebound")
    si_answers = answers_text(at)
    at.toggle(key="pendulum_rebound__us").set_value(True).run()
    assert_clean(at)
    assert "ft·lbf" in answers_text(at) and at.query_params.get("units") == "us"
    at.toggle(key="pendulum_rebound__us").set_value(False).run()
    assert answers_text(at) == si_answers and at.query_params.get("units") is None


def test_lecture_view_from_the_url():
    at = run_page("stick_ball", {"lecture": "1"})
    assert_clean(at)
    view = next(w for w in at.get("button_group") if w.key == "stick_ball__view")
    assert view.value == "Lecture" or view.value == ["Lecture"]
    assert at.query_params.get("lecture") == "1"


def test_one_view_control_switches_between_study_lecture_and_practice():
    at = run_page("disk_wall", {"practice": "1"})
    assert at.query_params.get("practice") == "1"
    assert answers_shown(at) is None  # practice hides the answers
    at.session_state["disk_wall__view"] = "Lecture"
    at.run()
    assert_clean(at)
    assert at.query_params.get("lecture") == "1" and at.query_params.get("practice") is None
    assert answers_shown(at) is not None
    at.session_state["disk_wall__view"] = "Study"
    at.run()
    assert at.query_params.get("lecture") is None and at.query_params.get("practice") is None


def test_home_lists_every_problem_by_group():
    at = AppTest.from_file(str(ROOT / "app.py"), default_timeout=TIMEOUT).run()
    assert_clean(at)
    text = " ".join(m.value for m in at.markdown) + " ".join(s.value for s in at.subheader)
    for group in ("Impacts", "Work–energy", "Newton–Euler"):
        assert group in text
    assert len(at.get("page_link")) == len(PROBLEMS)


def test_home_shows_every_problem_of_a_group_however_many(monkeypatch):
    """A group of more than two problems takes more than one row of cards (it once dropped the third)."""
    import dataclasses

    import ui.home
    one_group = tuple(dataclasses.replace(p, group="Impacts") for p in PROBLEMS)
    monkeypatch.setattr(ui.home, "PROBLEMS", one_group)
    monkeypatch.setattr(ui.home, "GROUPS", ("Impacts",))
    at = AppTest.from_file(str(ROOT / "app.py"), default_timeout=TIMEOUT).run()
    assert_clean(at)
    labels = [link.proto.label for link in at.get("page_link")]
    assert labels == [f"**{p.title}**" for p in PROBLEMS]


def test_answers_use_degrees_for_angles():
    at = run_page("pendulum_rebound")
    answers = answers_text(at)
    assert f"{math.degrees(-0.6221593851089576):.4g}".replace("-", "−") + "°" in answers


@pytest.mark.parametrize("pid", ["disk_wall", "stick_ball", "pendulum_rebound"])
def test_impact_pages_show_the_ledger_across_the_impact(pid):
    at = run_page(pid)
    section = answers_shown(at)
    assert section["ledger_heading"] == "Across the impact"
    rows = {quantity: (conserved, why) for quantity, _, _, conserved, why in section["ledger"]}
    assert "kinetic energy" in rows and all(why for _, why in rows.values())


@pytest.mark.parametrize("pid", IDS)
def test_more_parameters_are_hidden_until_asked_for_and_keep_their_values(pid):
    problem = BY_ID[pid]
    hidden = [p for p in problem.solver.PARAMS if p.name not in problem.primary and hasattr(p, "dimension")]
    if not problem.primary or not hidden:
        pytest.skip("every parameter of this problem is on show")
    spec = hidden[0]
    key = f"{pid}__si__{spec.name}"
    at = run_page(pid)
    keys = {w.key for w in [*at.number_input, *at.slider, *at.radio, *at.toggle]}
    on_show = {f"{pid}__si__{p.name}" + ("__inf" if getattr(p, "allow_inf", False) else "")
               for p in problem.solver.PARAMS if p.name in problem.primary}
    assert on_show <= keys and key not in keys
    default_answers = answers_text(at)
    show_more(at, pid).number_input(key=key).set_value(spec.default * 1.2).run()
    assert_clean(at)
    changed = answers_text(at)
    assert changed != default_answers and at.query_params.get(spec.name)
    at.toggle(key=f"{pid}__more").set_value(False).run()
    at.run()  # a second run: the hidden control's widget state is gone, the value is not
    assert key not in {w.key for w in at.number_input}
    assert answers_text(at) == changed and at.query_params.get(spec.name)
    assert show_more(at, pid).number_input(key=key).value == pytest.approx(spec.default * 1.2)


def test_a_link_that_changes_a_hidden_parameter_opens_more_parameters():
    at = run_page("pendulum_rebound", {"m_s": "3"})
    assert_clean(at)
    assert at.toggle(key="pendulum_rebound__more").value is True
    assert at.number_input(key="pendulum_rebound__si__m_s").value == pytest.approx(3.0)
    assert run_page("pendulum_rebound").toggle(key="pendulum_rebound__more").value is False


# -- a variant link, US units and a link's range (issue 29) ------------------------------------

def _control_keys(at: AppTest, pid: str) -> set[str]:
    """The keys of the controls of the page's givens (pid__si__name or pid__us__name)."""
    return {w.key for w in [*at.number_input, *at.slider, *at.radio, *at.toggle, *at.selectbox]
            if w.key and len(w.key.split("__")) >= 3 and w.key.split("__")[1] in ("si", "us")}


@pytest.mark.parametrize("pid", IDS)
def test_a_variant_links_givens_cannot_change_and_the_page_says_whose_they_are(pid):
    """At ?seed=7 nothing can move a given: a student who nudges a control would work another
    problem under the variant's name. The sidebar says they are fixed and lists them; the link
    stays as it came, with the student's views and the instructor's alike."""
    from practice.variants import variant

    at = run_page(pid, {"seed": "7", "practice": "1"})
    assert_clean(at)
    assert _control_keys(at, pid) == set(), _control_keys(at, pid)
    sidebar = "\n".join(m.value for m in at.sidebar.markdown)
    assert "variant 7" in sidebar and "Fixed by the variant link" in sidebar, sidebar
    params = variant(BY_ID[pid].solver, pid, 7)
    for p in BY_ID[pid].solver.PARAMS:
        if p.name in params:
            assert units.format_quantity(params[p.name], p.dimension) in sidebar, (p.name, sidebar)
    assert dict(at.query_params) == {"seed": "7", "practice": "1"}
    at.run()
    assert dict(at.query_params) == {"seed": "7", "practice": "1"}


def test_a_variant_link_with_a_given_of_its_own_says_so(monkeypatch):
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", "test-instructor-key-15")
    at = run_page("pendulum_rebound", {"seed": "7", "theta0": "40", "instructor": "test-instructor-key-15"})
    assert_clean(at)
    assert _control_keys(at, "pendulum_rebound") == set()  # the instructor's Study view too
    sidebar = "\n".join(m.value for m in at.sidebar.markdown)
    assert "variant 7" in sidebar and "θ₀ = 40°" in sidebar and "from the link" in sidebar, sidebar
    assert dict(at.query_params) == {"seed": "7", "theta0": "40"}


def test_us_units_show_the_textbooks_round_values():
    """The textbook's 10 lb sphere, 4 lb rod, 2 ft and 0.3 ft, g = 32.2 ft/s²: not 10.0002 lb or
    3.99919 lb, converted back from the SI defaults' four figures; a switch back to SI gives the
    same SI values as before."""
    at = show_more(run_page("pendulum_rebound", {"units": "us"}), "pendulum_rebound")
    shown = {w.key.split("__")[-1]: w.value for w in at.number_input}
    assert shown == {"m_s": 10, "m_r": 4, "L": 2, "r": 0.3, "d": 1.64, "g": 32.2}, shown
    assert at.query_params.get("units") == "us" and set(at.query_params) == {"units"}
    at.toggle(key="pendulum_rebound__us").set_value(False).run()
    shown = {w.key.split("__")[-1]: w.value for w in at.number_input}
    assert shown == {"m_s": 4.536, "m_r": 1.814, "L": 0.6096, "r": 0.09144, "d": 0.5, "g": 9.81}, shown


@pytest.mark.parametrize("query, says, never", [
    ({"theta0": "100"}, "less than 90°", "rad"),
    ({"theta0": "-100"}, "greater than −90°", "rad"),
    ({"units": "us", "m_s": "1e9"}, units.format_quantity(4536, "mass", "us"), " kg"),
    ({"units": "us", "L": "-3"}, "ft", " m "),
])
def test_a_links_out_of_range_value_is_named_in_the_controls_unit(query, says, never):
    at = run_page("pendulum_rebound", query)
    assert_clean(at)
    (warning,) = [w.value for w in at.warning]
    assert says in warning and never not in warning, warning


@pytest.mark.parametrize("view", [{}, {"lecture": "1"}, {"practice": "1"}, {"seed": "7"}])
@pytest.mark.parametrize("pid", IDS)
def test_a_links_unknown_name_is_said_and_left_out(pid, view):
    """A link's key that is no parameter of the problem (a typo's ``theta0x``, another problem's ``V``) is
    named once, with the name it is nearest to, and left out of the address; the page's own flags (units,
    views, a variant, an extra figure's switch) are never called unknown."""
    solver = BY_ID[pid].solver
    first = solver.ABOUT.primary[0]
    asked = drawings(pid).on_request
    flag = asked.flag if asked else None
    known = {**view, **({"units": "us"} if BY_ID[pid].us_units else {}), **({flag: "1"} if flag else {})}
    assert [w.value for w in run_page(pid, known).warning] == []
    at = run_page(pid, {**known, f"{first}x": "1", "Vz": "nan"})
    assert_clean(at)
    (said,) = [w.value for w in at.warning]
    assert f"“{first}x” and “Vz”" in said and "left out" in said and first in said.split("parameters:")[1], said
    assert f"{first}x" not in at.query_params and "Vz" not in at.query_params
    for typo in (f"{first}x", first.swapcase()):
        (said,) = [w.value for w in run_page(pid, {**known, typo: "1"}).warning]
        assert f"did you mean **{first}**?" in said, (typo, said)


@pytest.mark.parametrize("query", [{"[a](https://ev.il)": "1"}, {"theta0": "[a](https://ev.il)"},
                                   {"theta0": "https://ev.il"}, {"seed": "www.ev.il/<b>x</b>"}])
def test_what_a_link_says_is_shown_as_typed_never_as_a_link(query):
    """A link's names and values are repeated in the page's warnings character for character: Markdown
    never makes a link, an address, a tag or emphasis of them (a shared link is anybody's text)."""
    at = run_page("pendulum_rebound", query)
    assert_clean(at)
    (said,) = [w.value for w in at.warning]
    for raw in query.items():
        for text in raw:
            if text not in ("1", "theta0", "seed"):
                unescaped = re.sub(r"\\(.)", r"\1", said)
                assert text[:20] in unescaped, said
                assert not re.search(r"(?<!\\)[\[\]()<>:/.]", said.split("“", 1)[1].split("”", 1)[0]), said


@pytest.mark.parametrize("pid, query, says", [
    ("disk_wall", {"V": "1_0"}, "“1\\_0”, is not a number"),  # Python's float: 10
    ("disk_wall", {"V": "\u0663"}, "is not a number"),  # an Arabic-Indic three: float takes it as 3
    ("disk_wall", {"V": "nan"}, "is not a number"),
    ("pendulum_rebound", {"theta0": "89.9999"}, "rounds to 90 on its control, which is out of range"),
    ("eulers_disk", {"theta": "89.99"}, "rounds to 90.0 on its control, which is out of range"),
])
def test_a_links_value_is_a_number_as_written_and_its_rounding_is_said(pid, query, says):
    """A link's number is ASCII digits, a point and an exponent (or infinity where the model allows it); a
    value within range that its control's rounding puts out of range is said so, not called out of range
    as typed (89.9999 < 90)."""
    at = run_page(pid, query)
    assert_clean(at)
    (warning,) = [w.value for w in at.warning]
    assert says in warning, warning
    assert not at.query_params, at.query_params  # the default, as said


@pytest.mark.parametrize("pid, query, says", [
    ("rod_disk_spring", {"theta2": "30.5"}, "“30\\.5”, is finer than its slider, which writes whole degrees; using 30° instead"),
    ("pendulum_rebound", {"e": "0.001"}, "“0\\.001”, is finer than its slider, which writes to 0.01; using 0.00 instead"),
    ("eulers_disk", {"theta": "30.04"}, "is finer than its slider, which writes to 0.1°; using 30.0° instead"),
    ("disk_wall", {"V": "1.23456789"}, "is finer than its box, which writes six significant figures; using 1.23457 m/s instead"),
])
def test_a_links_value_finer_than_its_control_writes_is_rounded_and_said(pid, query, says):
    """?theta2=30.5 on a slider of whole degrees was taken as 30 without a word: the page now says so, and
    its address and its answers follow the value it used."""
    at = run_page(pid, query)
    assert_clean(at)
    (warning,) = [w.value for w in at.warning]
    assert says in warning, warning
    ((name, raw),) = query.items()
    used = says.rsplit("using ", 1)[1].split(" instead")[0].rstrip("°").split(" ")[0]
    assert float(at.query_params[name]) == float(used), at.query_params
    assert float(used) != float(raw)


@pytest.mark.parametrize("pid", [p.id for p in PROBLEMS if not p.us_units])
def test_units_asked_of_an_si_only_page_are_said_and_left_out(pid):
    """?units=us on a page stated in SI only (the cart, Euler's disk…) was dropped without a word."""
    at = run_page(pid, {"units": "us"})
    assert_clean(at)
    (said,) = [w.value for w in at.warning]
    assert "SI units only" in said and "units" not in at.query_params, said


@pytest.mark.parametrize("pid, query, says", [
    ("disk_wall", {"lecture": "2"}, "lecture=“2” is not 1 (on) or 0 (off)"),
    ("stick_ball", {"practice": "yes"}, "practice=“yes” is not 1 (on) or 0 (off)"),
    ("eulers_disk", {"rundown": "banana"}, "rundown=“banana” is not 1 (on) or 0 (off)"),
    ("pendulum_rebound", {"units": "imperial"}, "units “imperial” are neither si nor us"),
])
def test_a_flags_value_it_does_not_take_is_said(pid, query, says):
    """?lecture=2, ?rundown=banana, ?units=imperial were taken as off (or SI) without a word."""
    at = run_page(pid, query)
    assert_clean(at)
    (said,) = [w.value for w in at.warning]
    assert says in said, said
    assert not at.query_params, at.query_params  # off (SI), as said: the address drops the flag


@pytest.mark.parametrize("query", [{"lecture": "0"}, {"lecture": "1"}, {"units": "us"}, {"units": "si"}, {"practice": ""}])
def test_a_flags_own_values_are_taken_without_a_word(query):
    at = run_page("pendulum_rebound", query)
    assert_clean(at)
    assert not at.warning, [w.value for w in at.warning]


@pytest.mark.parametrize("query, s_shown", [({"s": "99"}, 0.5), ({"s": "0.9", "l": "0.4"}, 0.2), ({"s": "0.3", "l": "0.4"}, 0.2)])
def test_a_links_value_past_a_top_that_follows_another_falls_back_as_out_of_range_does(query, s_shown):
    """?s=99 on the stick (s ≤ l/2): the page refused as a whole, no figure, its s slider stretched to 99
    (while ?s=-1 fell back to the default with a note). Now it falls back too: the default, the stick's end,
    at most l/2 of the link's l; and the page solves."""
    at = run_page("stick_ball", query)
    assert_clean(at)
    (said,) = [w.value.replace("\\", "") for w in at.warning]  # (Markdown's escapes)
    assert f"“{query['s']}”, is past its largest value for this l (s ≤ 0.5 l = " in said, said
    assert said.endswith("using the default instead." if s_shown == 0.5 else  # what the page then uses, said
                         f"using that largest value, {s_shown:g} m, instead."), said
    assert not at.error
    slider = at.slider(key="stick_ball__si__s")
    assert slider.value == pytest.approx(s_shown) and slider.max <= max(2.5 * 0.5, float(query.get("l", 1))) and slider.max < 5


def test_a_name_given_twice_takes_the_last_and_the_address_keeps_only_it():
    """?V=2&V=3: the page takes the last, 3, and writes the address back with 3 alone, so a link copied from
    it says what the page shows (it kept both)."""
    at = AppTest.from_file(str(ROOT / "app_pages" / "disk_wall.py"), default_timeout=TIMEOUT)
    at.query_params["V"] = ["2", "3"]
    at.run()
    assert_clean(at)
    assert at.query_params == {"V": "3"} and at.slider(key="disk_wall__si__V").value == 3


@pytest.mark.parametrize("query, name, value, says, never", [
    ({"units": "us"}, "L", -1.0, "from 0.002 ft to 2000 ft", " m "),
    ({"units": "us"}, "m_s", 1e7, "10 000 lb", " kg"),
    ({}, "m_s", 1e7, "4536 kg", "rad"),
])
def test_a_box_out_of_range_is_named_in_its_own_unit(query, name, value, says, never):
    """A value typed in a box beyond its range is refused in the unit the box shows (the solver's
    own message is in SI: 'L = -0.3048 is out of range' for −1 ft)."""
    pid = "pendulum_rebound"
    at = show_more(run_page(pid, query), pid)
    at.number_input(key=f"{pid}__{query.get('units', 'si')}__{name}").set_value(value).run()
    assert_clean(at)
    message = " ".join(e.value for e in at.error)
    says = says.replace("10 000", units.format_value(10000.0))
    assert says in message and never not in message, message


@pytest.mark.parametrize("system", ["si", "us"])
@pytest.mark.parametrize("pid", [p.id for p in PROBLEMS])
def test_a_lesson_slider_spans_valid_round_values_around_the_textbook_s(pid, system):
    """Every number of the lesson is a slider (ui.params.lesson_range): its ends and every step between
    are values the solver takes, on a round step (1, 2, 2.5 or 5 × 10ⁿ of the unit shown, within a
    factor of two of the problem's own step), and the textbook's value lies within its range."""
    from ui.params import is_slider, lesson_range

    problem = BY_ID[pid]
    for p in problem.solver.PARAMS:
        if p.name not in problem.primary or not hasattr(p, "dimension") or is_slider(p):
            continue
        lo, hi, step = lesson_range(p, system)
        factor = units.to_display(1.0, p.dimension, system)
        mantissa = step / 10 ** math.floor(math.log10(step))
        assert any(math.isclose(mantissa, m) for m in (1, 2, 2.5, 5)), step
        assert 0.5 <= step / (p.step * factor) <= 2
        assert lo < hi and (math.isinf(p.default) or lo <= units.to_display(p.default, p.dimension, system) <= hi)
        steps = round((hi - lo) / step)
        assert math.isclose(lo + steps * step, hi, rel_tol=1e-9)
        for value in (lo + k * step for k in range(steps + 1)):
            p.validate(units.to_si(value, p.dimension, system))  # raises if the solver would refuse it


@pytest.mark.parametrize("length", [0.3, 1.0, 2.37, 5.0])
def test_the_impact_point_s_slider_ends_at_the_stick_s_end(length):
    """s's slider (stick and ball) spans the stick's half that l allows (``ui_high_per``): its top
    within a step of l/2, and every value on it one the solver takes for that l; on the page too,
    with l from a link."""
    from solvers import stick_ball
    from ui.params import lesson_range

    s = next(p for p in stick_ball.PARAMS if p.name == "s")
    lo, hi, step = lesson_range(s, "si", {"l": length})
    assert length / 2 - step < hi <= length / 2 + 1e-12
    for k in range(round((hi - lo) / step) + 1):
        stick_ball.solve(l=length, s=lo + k * step)  # raises if off the stick
    at = run_page("stick_ball", {"l": f"{length:g}"})
    slider = next(w for w in at.slider if w.key == "stick_ball__si__s")
    assert slider.proto.max == pytest.approx(max(hi, 0.5))  # (the slider also holds the textbook's s = 0.5)


def test_the_download_route_reads_a_value_past_a_following_top_as_the_page_does():
    """parameters_of_link (the take-home download's reading of a link) falls back as the page does: ?s=99 on
    the stick gives the stick's end, l/2, and says why in plain text."""
    from solvers.catalog import BY_ID
    from ui.params import parameters_of_link
    values, warnings = parameters_of_link(BY_ID["stick_ball"], {"s": "99", "l": "0.4"}, "si", markdown=False)
    assert values["s"] == pytest.approx(0.2) and values["l"] == pytest.approx(0.4)
    assert warnings == ["The link's value for s (impact point from the stick's midpoint), “99”, is past its largest "
                        "value for this l (s ≤ 0.5 l = 0.2 m)."], warnings


US_NUMBERS = [(problem.id, p) for problem in PROBLEMS if problem.us_units for p in problem.solver.PARAMS
              if hasattr(p, "dimension") and units.to_display(1.0, p.dimension, "us") not in (1.0, 180 / math.pi)]


@settings(max_examples=20, deadline=None)
@given(data=hst.data())
def test_a_linked_value_in_us_units_stays_as_typed_on_its_control_and_in_the_link(data):
    """The page reads a link as the download route does (ui.params.read_link) and keeps a value it takes as
    typed: 13.125 lb on its box is 13.125 exactly, and the address the page writes back says 13.125 again, not
    the 13.13 a unit switch would show for those kilograms (nor leaves out a 9.9999 lb as if it were the
    textbook's 10 lb)."""
    from ui.params import as_shown, control_key, parameters_of_link

    pid, p = data.draw(hst.sampled_from(US_NUMBERS))
    problem = BY_ID[pid]
    default = units.shown_value(p.default, p.dimension, "us")
    typed = as_shown(p, default * data.draw(hst.floats(0.5, 1.5)))
    text = f"{typed:g}"
    assume(float(text) != as_shown(p, default))
    at = run_page(pid, {"units": "us", p.name: text})
    assert_clean(at)  # (a combination the model refuses, the floor past the sphere's reach, is said as an error)
    assert not at.warning, [w.value for w in at.warning]
    assert at.session_state[control_key(problem, "us", p.name)] == float(text)
    assert at.query_params.get(p.name) == text
    assert at.session_state[f"{pid}__si"][p.name] == pytest.approx(
        parameters_of_link(problem, {p.name: text}, "us")[0][p.name], rel=1e-12)
