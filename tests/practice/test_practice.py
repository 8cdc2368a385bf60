"""“Try it yourself”: for every problem, a correct answer (as an expression and as a number), an
equivalent expression written differently, and each listed common mistake are judged correctly;
seed links reproduce the same numbers in every process."""
from __future__ import annotations

import importlib
import itertools
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from practice import instructor
import sympy as sp
from streamlit.testing.v1 import AppTest

from hypothesis import assume, given, settings, strategies as hst

from practice.mistakes import mistakes_for
from practice.judge import CALCULATOR_HINTS, Judge, _number_in_si
from practice.parser import MAX_LENGTH, MAX_TOKENS, tokenize
from solvers import registry
from practice.variants import MAX_SEED, variant, variants_csv
from solvers import units
from tests import strategies
from tests.pages.test_pages import (answer_section_text, answers_shown, answers_text, derivation_text, derivations_shown,
                              downloads_shown, shown)
from ui.figure import ANSWERS
from solvers.core import Answer, Choice, latex
from practice.worker import SimplifyWorker
from practice.method import flat_latex

ROOT = Path(__file__).resolve().parents[2]
IDS = registry.PROBLEM_IDS
for _pid in IDS:  # each problem's own test module, imported here: imported first inside a @given test (this
    strategies.problem_tests(_pid)  # file run alone), hypothesis took its import for a nested @given


def mistake_params(pid: str, params: dict) -> dict:
    """``params`` changed so that every listed mistake of the problem applies and differs from the
    answer, as the problem's own test module says (its optional ``mistake_params``)."""
    return params | getattr(strategies.problem_tests(pid), "mistake_params", lambda p: {})(params)


def setup(pid, **params):
    solver = importlib.import_module(f"solvers.{pid}")
    solution = solver.solve(**params)
    answers = solver.answers_for(solution.regime) if hasattr(solver, "answers_for") else solver.ANSWERS
    return solver, solution, Judge(solution, solver.derivation_of(solution), answers), {a.name: a for a in answers}


def typed(expr: sp.Expr, judge: Judge) -> str | None:
    """How a student would type ``expr`` (in the givens): each symbol under the name the judge lists."""
    names = {sym: name for name, sym in judge.typeable_symbols().items()}
    if any(s not in names for s in expr.free_symbols):
        return None
    text = sp.sstr(expr.subs({s: sp.Symbol(names[s]) for s in expr.free_symbols}))
    return re.sub(r"\bE\b", "exp(1)", text.replace("Abs(", "abs("))


def shown_number(value: float, dimension: str) -> str:
    return f"{units.to_display(value, dimension):.4g}"


def honest_forms(expr: sp.Expr) -> list[sp.Expr]:
    """The answer as different students write it: as derived, expanded, with trig expanded, over a
    common denominator, and scaled by 2/2."""
    forms = [expr, sp.expand(expr), sp.expand(sp.expand_trig(expr)), sp.together(expr), 2 * expr / 2]
    return list(dict.fromkeys(forms))


def check_page(pid, params):
    """Every answer of page ``pid`` at ``params``: its honest forms and its number are right, its
    own name and the other answers' names are refused as not given."""
    solver, solution, judge, answers = setup(pid, **params)
    for name, answer in answers.items():
        correct = judge.derivation.expression_of(name)
        for form in honest_forms(correct):
            text = typed(form, judge)
            if text is None or len(text) > 200:
                continue  # a chain input (the slip direction) or too long to type
            verdict = judge.check(answer, text)
            assert verdict.correct and "not the general answer" not in verdict.message, (name, text, verdict.message)
        value = solution.answers[name]
        assert judge.check(answer, shown_number(value, answer.dimension)).correct, (name, value)
        si = units.unit(answer.dimension, "si")
        if si and answer.dimension != "angle":
            assert judge.check(answer, f"{value:.6g} {si}").correct, (name, value, si)
        for own in {n for n in (name, judge.typed_name(judge.results[name])) if re.fullmatch(r"\w+", n)}:
            verdict = judge.check(answer, own)
            assert not verdict.correct and "the unknown you are asked for" in verdict.message, (own, verdict.message)
            assert judge.givens_text() in verdict.message
        for other in answers:
            if other != name and judge.derivation.expression_of(other) != correct:
                verdict = judge.check(answer, f"2*{other}")
                assert not verdict.correct and "not a given" in verdict.message, (other, verdict.message)


@pytest.mark.parametrize("pid", IDS)
def test_right_answers_in_honest_forms_and_the_unknowns_refused_at_the_textbooks_numbers(pid):
    check_page(pid, {})


@pytest.mark.parametrize("pid", IDS)
@settings(max_examples=4, deadline=None)
@given(seed=hst.integers(0, MAX_SEED))
def test_right_answers_in_honest_forms_and_the_unknowns_refused_for_any_variant(pid, seed):
    check_page(pid, variant(importlib.import_module(f"solvers.{pid}"), pid, seed))


def test_no_answer_or_intermediate_result_is_typeable():
    for pid in IDS:
        _, _, judge, answers = setup(pid)
        givens = set(judge.typeable_symbols().values())
        assert givens and not givens & set(judge.results.values()), pid
        first = next(iter(answers.values()))
        for symbol in judge.results.values():
            name = judge.typed_name(symbol)
            if re.fullmatch(r"\w+", name):
                verdict = judge.check(first, f"1 + {name}")
                assert not verdict.correct and "not a given" in verdict.message, (pid, name, verdict.message)


def check_slips(pid, params, everywhere: bool = True):
    """Each listed slip that applies at ``params`` is named, typed as a number or as an expression
    (with ``everywhere``; else only slips whose value lies beyond the tolerance, which a random
    variant may not keep apart)."""
    solver, solution, judge, answers = setup(pid, **params)
    mistakes = [m for m in registry.solver(pid).MISTAKES if m.answer in answers and m.applies(dict(solution.params))]
    assert mistakes, "every problem lists its common mistakes"
    wrongs = {id(m): judge.derivation.in_parameters(m.wrong(dict(solution.params))) for m in mistakes}
    values = {key: judge._value_of(wrong) for key, wrong in wrongs.items()}
    for mistake in mistakes:
        answer = answers[mistake.answer]
        wrong, value = wrongs[id(mistake)], values[id(mistake)]
        assert value is not None
        if not everywhere and abs(value - solution.answers[mistake.answer]) <= 0.02 * abs(value):
            continue
        if not everywhere and any(abs(values[id(other)] - value) <= 0.02 * abs(value) for other in mistakes
                                  if other is not mistake and other.answer == mistake.answer):
            continue  # two slips that give the same number here: either name is fair
        verdict = judge.check(answer, shown_number(value, answer.dimension))
        assert not verdict.correct and mistake.feedback in verdict.message, (mistake.feedback, verdict.message)
        text = typed(wrong, judge)
        if text:
            verdict = judge.check(answer, text)
            assert not verdict.correct and mistake.feedback in verdict.message, (text, verdict.message)


@pytest.mark.parametrize("pid", IDS)
def test_each_listed_mistake_gets_its_feedback(pid):
    check_slips(pid, mistake_params(pid, {}))


@pytest.mark.parametrize("pid", IDS)
@settings(max_examples=4, deadline=None)
@given(seed=hst.integers(0, MAX_SEED))
def test_each_listed_mistake_is_named_for_any_variant(pid, seed):
    params = mistake_params(pid, variant(importlib.import_module(f"solvers.{pid}"), pid, seed))
    check_slips(pid, params, everywhere=False)


@pytest.mark.parametrize("pid", IDS)
def test_slip_hints_never_state_the_right_value(pid):
    """A hint names the slip; it never gives the answer's number (to 2–4 figures, in any unit the
    page shows) or the answer's closed form as sympy writes it."""
    for params in ({}, mistake_params(pid, {})):
        solver, solution, judge, answers = setup(pid, **params)
        for mistake in registry.solver(pid).MISTAKES:
            if mistake.answer not in answers:
                continue
            value = solution.answers[mistake.answer]
            dimension = answers[mistake.answer].dimension
            for system in ("si", "us"):
                shown = units.to_display(value, dimension, system)
                for sig in (2, 3, 4):
                    number = f"{abs(shown):.{sig}g}"
                    if len(number.replace(".", "").lstrip("0")) >= 2:
                        assert number not in mistake.feedback, (mistake.feedback, number)
            closed = sp.sstr(judge.derivation.expression_of(mistake.answer))
            assert closed not in mistake.feedback


def test_the_pinned_disk_slip_is_named_inside_the_tolerance():
    _, solution, judge, answers = setup("rod_disk_spring")
    right, slip = solution.answers["omega2"], 4.92  # the pinned disk: 4.92 rad/s, 0.4 % from the answer
    assert abs(slip - right) < 5e-3 * right
    assert "pinned" in judge.check(answers["omega2"], "4.92").message
    assert judge.check(answers["omega2"], "4.90").correct


@pytest.mark.parametrize("pid, params, elsewhere, answer, text, special", [
    ("disk_wall", {"e": 1.0}, {"e": 0.5}, "v1y", "-V*cos(theta)", "e = 1"),
    ("disk_wall", {"omega": 0.0}, {"omega": 3.0}, "v1x", "2/3*V*sin(theta)", "ω = 0"),
    ("stick_ball", {"m_ball": 0.5, "m_stick": 0.5}, {"m_ball": 0.5, "m_stick": 1.0}, "v_cm", "v/2", "m_b = 0.5 kg"),
])
def test_right_for_these_numbers_is_right_with_one_line_saying_so(pid, params, elsewhere, answer, text, special):
    _, _, judge, answers = setup(pid, **params)
    verdict = judge.check(answers[answer], text)
    assert verdict.correct and "not the general answer" in verdict.message and special in verdict.message
    _, _, judge, answers = setup(pid, **elsewhere)
    assert not judge.check(answers[answer], text).correct


def test_a_given_put_in_as_its_value_is_not_called_rounded():
    _, solution, judge, answers = setup("rod_disk_spring", theta1=0.0)
    correct = judge.derivation.expression_of("omega2").subs(judge.givens["theta1"], 0)
    verdict = judge.check(answers["omega2"], typed(correct, judge))
    assert verdict.correct and "rounded" not in verdict.message


def test_generic_slips_sign_units_and_angle_mode():
    _, solution, judge, answers = setup("pendulum_rebound")
    rebound = solution.answers["theta_rebound"]
    assert judge.check(answers["theta_rebound"], f"{rebound:.4f} rad").correct
    assert "radians" in judge.check(answers["theta_rebound"], f"{rebound:.4f}").message
    assert judge.check(answers["I_O"], "2.469 kg m^2").correct
    assert "is a unit of speed" in judge.check(answers["I_O"], "2.469 m/s").message
    assert "but this answer is an angle" in judge.check(answers["theta_rebound"], "0.5 m/s").message  # (was "a angle")
    assert "but this answer is an angular speed" in judge.check(answers["omega_impact"], "-4.158 m/s").message
    assert "sign" in judge.check(answers["omega_impact"], "4.158").message
    _, solution, judge, answers = setup("disk_wall", omega=2.0)
    assert "rounded" in judge.check(answers["v1x"], "0.667*V*sin(theta) + R*omega/3").message


@pytest.mark.parametrize("text, says", [
    ("1/0", "divides by zero"),
    ("(V + R*omega", "not closed"),
    ("V)", "no matching '('"),
    ("2/3*V*sin(theta) + w*R/3", "did you mean omega"),
    ("2/3*V*sinθ^2 + R*omega/3", "ambiguous"),
    ("2/3*V*sin2θ + R*omega/3", "sin(2θ) with brackets"),
    ("1.0.8", "one decimal point (the second is at position 4)"),
    ("3..2", "one decimal point (the second is at position 3)"),
    ("0,83", "decimal comma"),
    ("1e-400", "too small to tell from zero"),
    ("2/3*V*1e-400", "too small to tell from zero"),
    ("2\\3", "The character '\\' (U+005C) at position 2"),
    ("2\u200b3", "The character '\\u200b' (U+200B)"),
    ("2/3*V*sin(theta) + R*omega/3 kg", "is a unit of mass"),
    ("2/3*V*sin(thet) + R*omega/3", "did you mean theta"),
    ("0.8 J", "unit of energy"),
    ("0.8 M/s", "Unknown unit 'M/s'"),
    ("0.8 furlongs", "Unknown unit 'furlongs'"),
    ("0.8 kg*m", "'kg*m' is not a unit of this answer, which is a speed: write it in m/s"),
    ("0.8 N/s", "'N/s' is not a unit of this answer"),
    ("v1y/3", "another answer of this problem"),
    ("P_t + 1", "not a given"),
])
def test_messages_say_what_is_actually_wrong(text, says):
    _, _, judge, answers = setup("disk_wall")
    verdict = judge.check(answers["v1x"], text)
    assert not verdict.correct and says in verdict.message, verdict.message
    assert "v_{1x}" not in verdict.message and "sigma" not in verdict.message
    assert "you gave" not in verdict.message  # nothing was misread as a number


@pytest.mark.parametrize("answer, text, says", [
    ("omega1", "4.9 Hz", "'Hz' counts turns per second, a frequency f; this answer is an angular speed, ω = 2πf"),
    ("energy_loss", "2 kg·m", "'kg·m' is not a unit of this answer, which is an energy: write it in J"),
    ("impulse_t", "2 kg*m^2", "'kg*m^2' is a unit of inertia, but this answer is an impulse"),
])
def test_a_unit_of_another_kind_is_named_as_one_not_as_unknown(answer, text, says):
    """kg·m for an inertia and Hz for an angular speed were "Unknown unit": a student who knows their
    units reads that as a typo, when the quantity is what is wrong."""
    _, _, judge, answers = setup("disk_wall")
    verdict = judge.check(answers[answer], text)
    assert not verdict.correct and says in verdict.message and "Unknown" not in verdict.message, verdict.message


@pytest.mark.parametrize("text", ["(Rω+2Vsinθ)/3", "2/3 Vsinθ + Rω/3", "(R*omega + 2*V*sin(theta))/3 m/s",
                                  "2/3*V*sinθ + R*omega/3", "(2Vsin(θ) + Rω)/3 m/s"])
def test_an_answer_written_by_hand_is_read_as_meant(text):
    """Juxtaposed givens are a product (R·ω, V·sin θ) and a unit after an expression is its unit."""
    _, _, judge, answers = setup("disk_wall")
    verdict = judge.check(answers["v1x"], text)
    assert verdict.correct and "not the general answer" not in verdict.message, verdict.message


def test_a_unit_after_a_numeric_expression_is_read_with_it():
    _, solution, judge, answers = setup("disk_wall")  # v1x = (Rω + 2V sin θ)/3 = 0.8333 m/s
    verdict = judge.check(answers["v1x"], "(0.1*5 + 2*2*sin(30°))/3 m/s")
    assert verdict.correct and "m/s" in verdict.message, verdict.message
    in_feet = solution.answers["v1x"] / 0.3048
    assert judge.check(answers["v1x"], f"{in_feet:.5g}*1 ft/s").correct
    verdict = judge.check(answers["v1x"], "(0.1*5 + 2*2*sin(30°))/3 mm/s")
    assert not verdict.correct and "mm/s" in verdict.message, verdict.message


def test_degrees_sign_is_read_as_degrees():
    _, solution, judge, answers = setup("disk_wall")  # θ = 30°
    assert judge.check(answers["v1x"], "2/3*V*sin(30°) + R*omega/3").correct
    assert judge.check(answers["v1x"], "2/3*V*sin(30) + R*omega/3").correct is False


def test_prefixed_and_us_units_are_read_case_sensitively():
    _, solution, judge, answers = setup("disk_wall")
    loss = solution.answers["energy_loss"]  # J
    assert judge.check(answers["energy_loss"], f"{loss * 1e3:.5g} mJ").correct
    assert not judge.check(answers["energy_loss"], f"{loss * 1e3:.5g} MJ").correct
    assert judge.check(answers["v1x"], f"{solution.answers['v1x'] * 1e3:.5g} mm/s").correct
    _, solution, judge, answers = setup("driven_cart")
    assert judge.check(answers["accel"], f"{solution.answers['accel'] / 9.80665:.5g} g").correct
    assert judge.check(answers["N_front"], f"{solution.answers['N_front'] / 1e3:.5g} kN").correct
    assert "did you mean kN" in judge.check(answers["N_front"], "2.55 kn").message
    _, solution, judge, answers = setup("pendulum_rebound", **{})
    inertia = solution.answers["I_O"]
    assert judge.check(answers["I_O"], f"{inertia / (0.45359237 * 0.3048**2):.5g} lb*ft^2", "us").correct
    assert judge.check(answers["I_O"], f"{units.to_display(inertia, 'inertia', 'us'):.5g} slug·ft²", "us").correct


@settings(max_examples=60, deadline=None)
@given(value=hst.floats(1e-3, 1e6).map(lambda x: float(f"{x:.6g}")), glued=hst.booleans(),
       power=hst.sampled_from(["^2", "²", "**2"]), dot=hst.sampled_from(["", "*", "·", " "]))
def test_every_accepted_unit_spelling_round_trips(value, glued, power, dot):
    """Every value written with every spelling the judge accepts (glued to the number or not, with
    any power sign, factors joined by any product sign) reads back as value × that unit's size; the
    same letters in another case are refused or a unit of another size (MJ ≠ mJ)."""
    for dimension, table in units.SPELLINGS.items():
        answer = Answer("x", "x", "x", dimension)
        for spelling, factor in table.items():
            written = spelling.replace("^2", power)
            if dot and written.startswith(("kgm", "slugft", "lbft", "lbin", "gcm")):
                written = re.sub(r"^(kg|slug|lb|g)", rf"\1{dot}", written)
            separator = "" if glued and not spelling[0].isdigit() else " "  # 2 1/s, never 21/s
            read = _number_in_si(f"{value}{separator}{written}", answer, "si")
            assert read is not None and read[0] == pytest.approx(value * factor, rel=1e-12), (written, read)
            swapped = spelling.swapcase()
            if swapped != spelling:
                other = units.si_per_unit(swapped, dimension)
                assert other is None or other != factor, (spelling, swapped)


def test_every_unit_the_pages_show_is_accepted_with_its_own_size():
    """The labels the pages print (ft·lbf, slug·ft², m/s², lbf·s …) are read back as exactly the
    size solvers.units converts with, so an answer copied with its unit is right."""
    for system, table in units.SYSTEMS.items():
        for dimension, (label, per_si) in table.items():
            if label and dimension != "angle":
                assert units.si_per_unit(label, dimension) == pytest.approx(1 / per_si, rel=1e-12), label


@pytest.mark.parametrize("text", ["__import__('os')", "9**9**9", "(" * 300, "x" * 10**6, "V.__class__"])
def test_hostile_answers_get_a_plain_refusal(text):
    _, _, judge, answers = setup("disk_wall")
    started = time.perf_counter()
    verdict = judge.check(answers["v1x"], text)
    assert not verdict.correct and verdict.message
    assert time.perf_counter() - started < 1.0


def test_seed_gives_the_same_numbers_in_another_process():
    here = {pid: variant(importlib.import_module(f"solvers.{pid}"), pid, 4242) for pid in IDS}
    code = ("import importlib, json; from practice.variants import variant; print(json.dumps({p: variant("
            "importlib.import_module('solvers.' + p), p, 4242) for p in %r}))" % (list(IDS),))
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True,
                         env={"PYTHONHASHSEED": "12345", "PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert json.loads(out.stdout) == here
    first = IDS[0]
    assert here[first] != variant(importlib.import_module(f"solvers.{first}"), first, 4243)


def test_bad_seeds_are_refused():
    solver = importlib.import_module("solvers.stick_ball")
    for bad in (-1, 10**10, 1.5, True, "7"):
        with pytest.raises(ValueError):
            variant(solver, "stick_ball", bad)


def test_instructor_csv_has_parameters_and_answers():
    solver = importlib.import_module("solvers.driven_cart")
    rows = variants_csv(solver, "driven_cart", 10, 14).strip().splitlines()
    assert len(rows) == 6 and rows[0].startswith("seed,param:m") and "answer:accel" in rows[0]
    with pytest.raises(ValueError):
        variants_csv(solver, "driven_cart", 0, 10_000)


def run_page(pid, query):
    at = AppTest.from_file(str(ROOT / "app_pages" / f"{pid}.py"), default_timeout=60)
    at.query_params.update(query)
    return at.run()


KEY = "test-instructor-key-15"


def test_seed_link_reproduces_the_numbers_for_the_instructor(monkeypatch):
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", KEY)
    teacher = {"seed": "31", "instructor": KEY}
    a, b = run_page("rod_disk_spring", teacher), run_page("rod_disk_spring", teacher)
    assert answers_text(a) == answers_text(b) and answers_text(a) != answers_text(run_page("rod_disk_spring", {}))
    assert not a.exception and not a.warning
    assert "instructor" not in a.query_params  # the key does not stay in the address bar
    bad = run_page("rod_disk_spring", {"seed": "abc"})
    assert bad.warning and "variant" in bad.warning[0].value and not bad.exception


@pytest.mark.parametrize("key", [None, "wrong-key-0000"])
def test_a_students_variant_link_shows_its_answers_only_through_show_the_solution(monkeypatch, key):
    if key:
        monkeypatch.setenv("DL_INSTRUCTOR_KEY", KEY)
    at = run_page("rod_disk_spring", {"seed": "31"} | ({"instructor": key} if key else {}))
    assert not answers_text(at) and any("Show the solution" == b.label for b in at.button)
    at.session_state["rod_disk_spring__view"] = "Study"  # switching the link to Study
    at.run()
    assert not answers_text(at) and not at.exception
    statement = next(m.value for m in at.markdown if m.value.startswith("### The problem"))
    params = variant(importlib.import_module("solvers.rod_disk_spring"), "rod_disk_spring", 31)
    assert units.format_quantity(params["m1"], "mass") in statement  # the givens, in the main area
    at.button(key="rod_disk_spring__reveal").click().run()
    assert answers_text(at)


def test_the_variant_export_needs_the_instructor_key(monkeypatch):
    monkeypatch.delenv("DL_INSTRUCTOR_KEY", raising=False)
    at = run_page("driven_cart", {"practice": "1"})
    assert not any(b.label == "Prepare the CSV" for b in at.button)
    assert any("has not set an instructor key" in m.value for m in at.markdown)
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", KEY)
    at = run_page("driven_cart", {"practice": "1"})
    assert not any(b.label == "Prepare the CSV" for b in at.button)
    at.text_input(key="driven_cart__instructor_key").input("guess-guess").run()
    assert at.error and not any(b.label == "Prepare the CSV" for b in at.button)
    assert "next try is possible in 1 s" in at.error[0].value
    at.text_input(key="driven_cart__instructor_key").input(KEY).run()  # too soon: not looked at
    assert "Too soon" in at.error[0].value and not any(b.label == "Prepare the CSV" for b in at.button)
    later = instructor.THROTTLE.clock() + 1.5
    monkeypatch.setattr(instructor.THROTTLE, "clock", lambda: later)
    at.text_input(key="driven_cart__instructor_key").input(KEY).run()
    assert any(b.label == "Prepare the CSV" for b in at.button)
    for link in ({"practice": "1", "instructor": KEY}, {"seed": "7", "practice": "1", "instructor": KEY}):
        at = run_page("driven_cart", link)  # an instructor link, with or without a variant
        assert any(b.label == "Prepare the CSV" for b in at.button), link
        assert "instructor" not in at.query_params, link  # and the key leaves the address bar


def page_text(at) -> str:
    """Everything a Practice page writes: Markdown, captions, help, LaTeX, labels and messages."""
    parts = []
    for kind in ("markdown", "caption", "latex", "info", "success", "error", "warning", "text_input",
                 "selectbox", "button", "expander"):
        for element in getattr(at, kind):
            for attribute in ("value", "label", "help", "body"):
                got = getattr(element, attribute, None)
                if isinstance(got, str):
                    parts.append(got)
            if kind == "selectbox":
                parts += [str(o) for o in element.options]
    parts += [derivation_text(at, d) for d in derivations_shown(at)]  # the derivation's own element
    parts += [answer_section_text(section) for section in shown(at, ANSWERS)]  # and the answers'
    parts += downloads_shown(at).values()  # and every file it offers to take home
    return "\n".join(parts)


def leaks(text: str, solution, answers, judge, system: str = "si") -> list[str]:
    """Any answer's value (as the page formats it, and to 3–4 figures) or closed form in ``text``. A drawing's
    coordinates and stroke widths (an SVG, a TikZ picture) are not values a reader sees: they are left out
    (what the problem's sketch and the drawing exercise's blank show is tested on its own, test_sketch.py and
    test_diagram_judge.py)."""
    text = re.sub(r"\\begin\{tikzpicture\}.*?\\end\{tikzpicture\}|<svg\b.*?</svg>", "", text, flags=re.S)
    found = []
    givens = {units.format_value(units.to_display(v, p.dimension, system), 4)
              for p in importlib.import_module(f"solvers.{solution.problem}").PARAMS
              if not isinstance(v := solution.params[p.name], str)}
    flat = flat_latex(text)
    for a in answers:
        value = solution.answers[a.name]
        shown = units.to_display(value, a.dimension, system)
        candidates = {units.format_quantity(value, a.dimension, system)} | {
            units.format_value(shown, sig) for sig in (3, 4)}
        for number in candidates:
            digits = re.sub(r"[^0-9]", "", number).strip("0")
            if len(digits) >= 2 and number not in givens and re.search(rf"(?<![\d.]){re.escape(number)}(?!\d)", text):
                found.append(f"{a.name} = {number}")
        closed = judge.derivation.expression_of(a.name)
        if len(closed.free_symbols) and flat_latex(latex(closed)) in flat:
            found.append(f"{a.name} as {latex(closed)}")
        symbol = flat_latex(latex(judge.results[a.name]))
        if re.search(rf"{re.escape(symbol)}=", flat):
            found.append(f"{a.name} stated as {symbol} = …")
    return found


# Every page, and every option that changes the derivation (the cart's rear and all-wheel drives
# once wrote N_front's closed form into the lift-off step without naming it).
OPTIONS = [(pid, {}) for pid in IDS] + [
    ("driven_cart", {"drive": "rear"}), ("driven_cart", {"drive": "all"}),
    ("pendulum_rebound", {"sphere": "hollow"}), ("pendulum_rebound", {"sphere": "disk", "surface": "wall"}),
    ("stick_ball", {"mode": "bounce"}), ("rod_disk_spring", {"disk": "pinned"})]


def test_the_leak_check_catches_a_result_stated_by_symbol_or_by_closed_form():
    """Positive controls: the check the page tests rely on finds what it must."""
    for pid, options in OPTIONS:
        _, solution, judge, answers = setup(pid, **options)
        for a in answers.values():
            closed = judge.derivation.expression_of(a.name)
            stated = latex(sp.Eq(judge.results[a.name], closed, evaluate=False))
            assert f"{a.name} stated as" in " ".join(leaks(f"$${stated}$$", solution, [a], judge)), (pid, a.name)
            if closed.free_symbols:
                inequality = rf"$$\\left({latex(closed)}\\right) > 0$$"
                assert f"{a.name} as" in " ".join(leaks(inequality, solution, [a], judge)), (pid, a.name)


@pytest.mark.parametrize("pid, options", OPTIONS, ids=lambda x: str(x))
def test_the_practice_page_gives_no_answer_away(pid, options):
    at = run_page(pid, {"practice": "1", **options})
    solver, solution, judge, answers = setup(pid, **options)
    text = page_text(at)
    assert "### The problem" in text and "### The method" in text and not at.exception
    assert leaks(text, solution, answers.values(), judge) == []
    assert set(downloads_shown(at)) == {f"{pid}-exercise.tex", f"{pid}-exercise.md"}  # no notebook: it prints them
    at.button(key=f"{pid}__reveal").click().run()
    assert leaks(page_text(at), solution, answers.values(), judge)  # the check can find them
    assert leaks(answer_section_text(answers_shown(at)), solution, answers.values(), judge)  # in the answers too
    for name, text in downloads_shown(at).items():  # and in each download, once the solution is shown
        assert leaks(text, solution, answers.values(), judge), name


@pytest.mark.parametrize("pid, options, past_limit", [
    ("driven_cart", {"drive": "rear"}, {"mu": "20"}),
    ("driven_cart", {"drive": "all"}, {"mu": "6"}),
    ("rod_disk_spring", {}, {"k": "100"}),
    ("rod_disk_spring", {"disk": "pinned"}, {"k": "100"}),
    ("pendulum_rebound", {}, {"theta0": "-60"}),
], ids=str)
def test_past_a_physical_limit_practice_shows_the_method_not_the_derivation(pid, options, past_limit):
    """The refusal keeps the method (titles, and equations that show no result), never the closed
    forms the Study view's derivation gives beside it."""
    at = run_page(pid, {"practice": "1", **options, **past_limit})
    assert at.error and not at.exception
    text = page_text(at)
    assert "### The method" in text
    _, solution, judge, answers = setup(pid, **options)  # the same derivation, inside the limit
    found = leaks(text, solution, answers.values(), judge)
    assert not [f for f in found if " as " in f or "stated" in f], found
    study = page_text(run_page(pid, {**options, **past_limit}))
    assert [f for f in leaks(study, solution, answers.values(), judge) if " as " in f or "stated" in f]


def test_practice_mode_hides_answers_until_revealed():
    at = run_page("stick_ball", {"practice": "1"})
    assert not answers_text(at)
    assert any("not a proctored assessment" in i.value for i in at.info)
    at.text_input(key="stick_ball__attempt").input("m_b*v/(m_b + m_s)")
    from solvers.stick_ball import ANSWERS_STICK
    at.selectbox(key="stick_ball__attempt_answer").select_index([a.name for a in ANSWERS_STICK].index("v_cm"))
    at.button[0].click().run()
    assert at.success and not at.exception
    at.button(key="stick_ball__reveal").click().run()
    assert answers_text(at)


def test_answer_headings_keep_their_symbols():
    from solvers.core import Answer as A
    assert A("a", "acceleration of the cm", "a", "acceleration").heading == "Acceleration of the cm"
    assert A("I", "I_O about the pivot", "I_O", "inertia").heading == "I_O about the pivot"


def test_worker_is_killed_when_too_slow_and_comes_back():
    worker = SimplifyWorker()
    try:
        assert worker.warm(wait=10.0)
        x, y, z = sp.symbols("x y z")
        slow = sp.expand((x + y + z + 1) ** 12) / (x + y + z + 1) ** 11 - (x + y + z + 1)
        started = time.perf_counter()
        assert worker.is_zero(slow, timeout=0.01) is None
        assert time.perf_counter() - started < 1.0
        assert worker.warm(wait=10.0)
        assert worker.is_zero(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1, timeout=5.0) is True
        assert worker.is_zero(x - y, timeout=5.0) is False
        killed = worker._proc.pid
        os.kill(killed, signal.SIGKILL)  # as the kernel's OOM killer or an admin would
        worker._proc.wait(5)
        assert worker.is_zero(x - x, timeout=5.0) is None  # the dead one's answer is lost, not waited for
        assert worker._proc.pid != killed and worker.warm(wait=10.0)  # already replaced, warm
        assert worker.is_zero(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1, timeout=5.0) is True
    finally:
        worker.close()


def test_clear_answers_never_queue_for_the_simplification_worker(monkeypatch):
    """Right and plainly wrong expressions are settled by numbers; only an unclear one (too few points
    where it is defined) goes to the worker, which may be busy with someone's slow expression."""
    import practice.judge as judge_module

    asked = []

    class Busy:
        def is_zero(self, expr, timeout=1.0):
            asked.append(expr)
            return None

    monkeypatch.setattr(judge_module, "shared_worker", lambda: Busy())
    _, _, judge, answers = setup("disk_wall", omega=2.0)
    assert judge.check(answers["v1x"], "(R*omega + 2*V*sin(theta))/3").correct
    assert not judge.check(answers["v1x"], "V*sin(theta)").correct
    assert asked == []
    unclear = "2/3*V*sin(theta) + R*omega/3 + sqrt(-(theta - 1)^2)"  # real at no point near these numbers
    judge.check(answers["v1x"], unclear)
    assert asked


@pytest.mark.parametrize("worker_says, correct, says", [
    (None, True, "could not be checked in general in time"),  # busy or out of time: not "wrong"
    (True, True, "Right: that is the answer"),
    (False, True, "but not the general answer"),
])
def test_an_answer_the_numbers_cannot_settle_gets_the_workers_verdict_or_says_it_has_none(
        monkeypatch, worker_says, correct, says):
    """When the numbers are unclear (forced here: rounding-level differences are rare and
    platform-dependent) the worker decides; a busy worker's silence is reported as such, never as
    "not the general answer"."""
    import practice.judge as judge_module

    class Worker:
        def is_zero(self, expr, timeout=1.0):
            return worker_says

    monkeypatch.setattr(judge_module, "shared_worker", lambda: Worker())
    _, _, judge, answers = setup("disk_wall", omega=2.0)
    real = judge._numeric_verdict
    monkeypatch.setattr(judge, "_numeric_verdict", lambda a, b, rtol=1e-9, differ=1e-6:
                        None if rtol == 1e-9 and differ == 1e-6 else real(a, b, rtol, differ))
    verdict = judge.check(answers["v1x"], "(R*omega + 2*V*sin(theta))/3")
    assert verdict.correct is correct and says in verdict.message, verdict.message


@pytest.mark.parametrize("extra", ["1/mu", "V/mu", "exp(-mu)"])
def test_with_mu_infinite_a_term_that_vanishes_there_is_not_the_general_answer(extra):
    """disk_wall's default μ = ∞ (no slip): ∞ times any sampling factor stays ∞, so a term that
    vanishes at ∞ must be caught at finite μ; the answer is then right only for μ = ∞."""
    _, solution, judge, answers = setup("disk_wall")
    assert solution.params["mu"] == float("inf")
    right = "(R*omega + 2*V*sin(theta))/3"
    assert "that is the answer" in judge.check(answers["v1x"], right).message
    verdict = judge.check(answers["v1x"], f"{right} + {extra}")
    assert verdict.correct and "not the general answer" in verdict.message, verdict.message
    assert "μ = ∞" in verdict.message, verdict.message


# -- degrees for radians, in every form a student writes it (issue 29) --------------------------

def _forward_trig_of_angles(expr: sp.Expr, angles: set) -> bool:
    return any(isinstance(f, (sp.sin, sp.cos, sp.tan)) and f.free_symbols & angles
               for f in sp.preorder_traversal(expr))


def _typed_with_numbers(expr: sp.Expr, judge: Judge, params: dict, degrees_in_trig: bool) -> str:
    """``expr`` (in the givens) typed with the page's numbers (six figures, as the boxes show them);
    an angle inside sin, cos or tan as its number of degrees with no ° (sin(50)) when
    ``degrees_in_trig``, else in radians."""
    givens = {sym: name for name, sym in judge.givens.items()}
    spec = {p.name: p for p in registry.solver(judge.solution.problem).PARAMS}
    holders, numbers = {}, {}
    for sym, name in givens.items():
        value = params[name]
        holders[sym] = sp.Symbol(f"Q{len(holders)}Q")
        numbers[holders[sym].name] = f"{value:.6g}"
        if degrees_in_trig and getattr(spec[name], "dimension", "") == "angle":
            inside = sp.Symbol(f"Q{len(holders)}D")
            numbers[inside.name] = f"{math.degrees(value):.6g}"
            expr = expr.replace(lambda f: isinstance(f, (sp.sin, sp.cos, sp.tan)),
                                lambda f, s=sym, d=inside: type(f)(f.args[0].subs(s, d)))
    text = sp.sstr(expr.subs(holders))
    for holder, number in sorted(numbers.items(), key=lambda kv: -len(kv[0])):
        text = text.replace(holder, f"({number})" if number.startswith("-") else number)
    return text.replace("Abs(", "abs(")


def degree_slips(pid: str, params: dict) -> list[tuple[str, str, tuple]]:
    """(answer, what the student types, words the hint must say) for every degree-for-radian slip a
    student can make on page ``pid``: an angle's degrees labelled rad, its radians read as degrees,
    deg/s typed with no unit or labelled rad/s, rad/s labelled deg/s, sin(50) meaning degrees inside
    an expression, and a calculator left in radian mode. A slip whose number cannot be told from the
    answer, from its sign or factor-2 twin or from a listed mistake at these numbers is left out."""
    solver, solution, judge, answers = setup(pid, **params)
    angles = {sym for name, sym in judge.givens.items()
              if getattr(next(p for p in solver.PARAMS if p.name == name), "dimension", "") == "angle"}
    slips = []
    for name, answer in answers.items():
        value = solution.answers[name]
        known = [value, -value, 2 * value, value / 2]
        known += [judge._value_of(judge.derivation.in_parameters(m.wrong(dict(solution.params))))
                  for m in registry.solver(pid).MISTAKES if m.answer == name and m.applies(dict(solution.params))]

        def distinct(wrong: float) -> bool:
            return all(k is None or abs(wrong - k) > 0.03 * max(abs(k), abs(wrong), 1e-9) for k in known)

        deg = math.degrees(value)
        if answer.dimension == "angle" and distinct(deg):
            slips.append((name, f"{deg:.4g} rad", ("degrees", "rad")))
        if answer.dimension == "angle" and distinct(math.radians(value)):
            slips.append((name, f"{value:.4g}", ("radians", "degrees")))
        if answer.dimension == "angular_speed" and distinct(deg):
            slips.append((name, f"{deg:.4g}", ("deg/s", "rad/s")))
            slips.append((name, f"{deg:.4g} rad/s", ("deg/s", "rad/s")))
        if answer.dimension == "angular_speed" and distinct(math.radians(value)):
            slips.append((name, f"{value:.4g} deg/s", ("deg/s", "rad/s")))
        expr = judge.derivation.expression_of(name)
        if not _forward_trig_of_angles(expr, angles):
            continue
        radian_mode = expr.replace(lambda f: isinstance(f, (sp.sin, sp.cos, sp.tan)),
                                   lambda f: type(f)(f.args[0] * 180 / sp.pi))
        wrong = judge._value_of(radian_mode)
        if wrong is None:
            continue
        if answer.dimension == "angle":
            wrong = math.radians(wrong)  # the calculator's number, read as degrees
        if answer.dimension in ("angle", "angular_speed"):  # else it is one of the slips above
            known += [math.degrees(value), math.radians(value)]
        # (a number alone that is also the answer in the other unit system is read as that: the likelier slip)
        known += [units.to_si(units.to_display(value, answer.dimension, "us"), answer.dimension, "si")]
        if distinct(wrong):
            slips.append((name, f"{units.to_display(wrong, answer.dimension):.4g}", ("calculator", "radian")))
            text = _typed_with_numbers(expr, judge, dict(solution.params), degrees_in_trig=True)
            if len(text) <= MAX_LENGTH and len(tokenize(text)) <= MAX_TOKENS:
                # sympy writes sin(−6) as −sin(6): the hint may name either
                calls = {f"{f}({m})" for f, n in re.findall(r"(sin|cos|tan)\(\(?([-\d.e]+)", text) if float(n)
                         for m in (n, n.lstrip("-"))}
                slips.append((name, text, (tuple(calls), "°", "in radians")))
    return slips


ANGULAR_PAGES = [pid for pid in IDS if degree_slips(pid, {})]


def test_degree_slips_can_occur_on_every_page_with_an_angle():
    for pid in IDS:
        solver = registry.solver(pid)
        angular = any(a.dimension in ("angle", "angular_speed") for a in solver.ANSWERS)
        trig = any(p.dimension == "angle" for p in solver.PARAMS if hasattr(p, "dimension"))
        assert (pid in ANGULAR_PAGES) == (angular or trig), pid


def check_degree_slips(pid, params):
    _, _, judge, answers = setup(pid, **params)
    slips = degree_slips(pid, params)
    for name, text, words in slips:
        verdict = judge.check(answers[name], text)
        assert not verdict.correct, (name, text, verdict.message)
        # each word said (or, for a tuple of them, one of them: the sin(50) or cos(30) typed)
        assert all(any(w in verdict.message for w in ((word,) if isinstance(word, str) else word))
                   for word in words), (name, text, words, verdict.message)
        assert verdict.mistake or not verdict.readable, (name, text, verdict.message)  # named as a slip, or not judged
        # a number alone that is the answer in the unit left out is not judged (an assignment does not
        # count it); with a unit typed, or as an expression, it is a wrong answer
        left_out = re.fullmatch(r"-?[\d.e+-]+", text) and "calculator" not in verdict.message
        assert verdict.readable == (not left_out), (name, text, verdict.message)
    return slips


@pytest.mark.parametrize("pid", ANGULAR_PAGES)
def test_every_degree_slip_is_named_at_the_textbooks_numbers(pid):
    assert check_degree_slips(pid, mistake_params(pid, {}))


@pytest.mark.parametrize("pid", ANGULAR_PAGES)
@settings(max_examples=6, deadline=None)
@given(seed=hst.integers(0, MAX_SEED))
def test_every_degree_slip_is_named_for_any_variant(pid, seed):
    check_degree_slips(pid, variant(importlib.import_module(f"solvers.{pid}"), pid, seed))


def test_an_angle_written_with_degrees_inside_an_expression_is_read_in_radians():
    """30° inside an expression and asin's result are radians: an angle answer typed as an
    expression with them is right (the unit the page shows is for a number alone)."""
    _, solution, judge, answers = setup("sliding_ladder")  # θ_ℓ = asin(2/3 sin 60°) = 35.26°
    assert judge.check(answers["theta_leave"], "asin(2/3*sin(60°))").correct
    assert judge.check(answers["theta_leave"], "asin(2/3*sin(60°))*180/pi").correct
    assert judge.check(answers["theta_leave"], "(35 + 0.26)°").correct


def test_one_answer_typed_two_ways_reads_the_same_and_another_does_not():
    """An assignment counts the same answer twice in a row once: the judge's reading is what was read
    (in SI) with its verdict, not the text, and not the text alone either (a bare 5 is m/s in SI, ft/s
    in US units)."""
    _, _, judge, answers = setup("disk_wall")
    v = answers["v1x"]
    reading = {(text, system): judge.check(v, text, system).reading
               for text in ("5", "5 m/s", "5.0m/s", "10/2", "5 ft/s", "5.1") for system in ("si", "us")}
    assert reading["5", "si"] == reading["5 m/s", "si"] == reading["5.0m/s", "si"] == reading["10/2", "si"]
    assert reading["5", "us"] == reading["5 ft/s", "si"] == reading["5 ft/s", "us"]
    assert len({reading["5", "si"], reading["5", "us"], reading["5.1", "si"]}) == 3
    assert judge.check(v, "hello", "si").reading == ""  # not read: no reading
    symbolic = {judge.check(v, text).reading for text in ("2*V/3", "2V/3", "(2/3)*V")}
    assert len(symbolic) == 1 and "" not in symbolic and symbolic != {reading["5", "si"]}


@pytest.mark.parametrize("pid", IDS)
@settings(max_examples=4, deadline=None)
@given(seed=hst.integers(0, MAX_SEED))
def test_the_answer_in_the_other_systems_unit_typed_alone_is_a_unit_left_out(pid, seed):
    """A number alone is read in the unit the page shows: the answer's number in the other system's unit
    (ft/s on an SI page, m/s on a US one) is said to be a unit left out and not judged (an assignment
    counts no attempt); with that unit written after it, it is right."""
    solver = importlib.import_module(f"solvers.{pid}")
    _, solution, judge, answers = setup(pid, **variant(solver, pid, seed))
    for name, answer in answers.items():
        value = solution.answers.get(name)
        if not isinstance(value, float) or answer.dimension not in units.DIMENSIONS or abs(value) < 1e-6:
            continue
        for system, other in (("si", "us"), ("us", "si")):
            meant = units.unit(answer.dimension, other)
            if meant == units.unit(answer.dimension, system):
                continue
            number = f"{units.to_display(value, answer.dimension, other):.6g}"
            assert judge.check(answer, f"{number} {meant}", system).correct, (name, number, meant)
            verdict = judge.check(answer, number, system)
            if not verdict.correct and verdict.mistake not in CALCULATOR_HINTS.values():  # (a coincidence: 1 ft = 0.3 m)
                assert not verdict.readable and meant in verdict.message, (name, number, system, verdict.message)


def test_a_number_in_another_unit_is_said_as_typed_and_as_the_page_shows_it():
    """"Right: 1.708 m/s (read as ft/s)" read as if 1.708 had been typed in ft/s."""
    _, solution, judge, answers = setup("disk_wall")
    v = solution.answers["v1x"]
    typed = f"{v / units.FT:.4g}"
    assert judge.check(answers["v1x"], f"{typed} ft/s").message == \
        f"Right: {typed} ft/s = {units.format_quantity(v, 'speed')}."
    assert judge.check(answers["v1x"], f"{v:.4f} m/s").message == f"Right: {units.format_quantity(v, 'speed')}."


@pytest.mark.parametrize("pid, name, text, says", [
    ("pendulum_rebound", "theta_impact", "-44.9 dge", "did you mean deg?"),  # d·g·e: a length times an acceleration
    ("pendulum_rebound", "omega_impact", "-315.8 deg", "'deg' is a unit of angle"),  # a unit of another kind
    ("stick_ball", "v_cm", "0.5 ms", "To multiply by the given m_s, write 0.5*m_s"),  # a unit, or the given m_s?
    ("stick_ball", "d_cm", "0.25 s", "To multiply by the given s, write 0.25*s"),  # seconds, or the offset s?
    ("stick_ball", "v_cm", "0.5 /s", "'/s' is a unit of angular speed"),  # over s, the offset
    ("rod_disk_spring", "I_O", "1.553 kg m2", "did you mean kg·m²?"),  # k·g·m₂
])
def test_a_unit_typed_as_givens_letters_is_not_judged(pid, name, text, says):
    """A typo in a unit whose letters are givens' names was read as an expression (−44.9·d·g·e), judged
    "not equivalent" and recorded as an attempt, while the same typo on a page without those givens cost
    nothing: a number then letters that are a unit, or whose product's units are not the answer's, is
    explained and not judged."""
    _, _, judge, answers = setup(pid)
    verdict = judge.check(answers[name], text)
    assert not verdict.readable and not verdict.reading, verdict
    assert says in verdict.message, verdict.message
    if text == "-44.9 dge":  # "Read as" shows the givens' product as one (juxtaposed, it read "deg")
        assert r"e \cdot g \cdot d" in verdict.understood, verdict.understood  # (the coefficient e first)


def test_a_number_in_place_of_a_given_is_still_judged():
    """The units check is for a number followed by letters: a formula with 9.81 where g belongs has no units to
    tell (a number's are unknown) and stays "right for these numbers" (the review found it refused)."""
    _, _, judge, answers = setup("pendulum_rebound")
    typed_in = "-sqrt(2*9.81*(L*m_r/2 + m_s*(L + r))*(sin(theta0) - (r-d)/(L + r))/(L^2*m_r/3 + 2*m_s*r^2/5 + m_s*(L + r)^2))"
    verdict = judge.check(answers["omega_impact"], typed_in)
    assert verdict.correct and "for g = 9.81" in verdict.message, verdict.message


def _option_sets(solver):
    """Every combination of a problem's options (sphere, surface, mode, drive …), as parameters."""
    choices = [p for p in solver.PARAMS if isinstance(p, Choice)]
    return [dict(zip((c.name for c in choices), values)) for values in itertools.product(*(c.options for c in choices))]


@settings(max_examples=25, deadline=None)
@given(pid=hst.sampled_from(registry.PROBLEM_IDS), seed=hst.integers(0, MAX_SEED), data=hst.data())
def test_every_derived_answer_and_known_slip_has_the_answer_s_units(pid, seed, data):
    """Each derived expression's powers of mass, length and time, from the givens' dimensions, are its answer's
    (or cannot be told: the ladder's times, an integral): a check of the derivations' units, and of the table the
    units check of a number followed by givens reads; every slip the judge names too (else a typed slip could be
    taken for a unit's typo). Every option of the problem (sphere, surface, mode, drive) is drawn."""
    solver = importlib.import_module(f"solvers.{pid}")
    options = data.draw(hst.sampled_from(_option_sets(solver)))
    params = {**variant(solver, pid, seed), **options}
    try:
        _, solution, judge, answers = setup(pid, **params)
    except ValueError:  # an option these numbers cannot have (a refusal the page explains)
        assume(False)
    for answer in answers.values():
        wanted = units.mlt(answer.dimension)
        right = judge.derivation.expression_of(answer.name)
        assert judge.units_of(right) in (None, wanted), (answer.name, right)
        for mistake in mistakes_for(pid, answer.name, dict(solution.params)):
            wrong = judge.derivation.in_parameters(mistake.wrong(dict(solution.params)))
            assert judge.units_of(wrong) in (None, wanted), (answer.name, mistake.feedback)


def test_typing_slips_that_would_read_as_numbers_nobody_meant_are_not_judged():
    """--35.65 was read as +35.65 and charged with the sign slip; 35.65°° as 35.65 × π/180 degrees; −238.2° for
    an angular speed as −238.2 × π/180 rad/s; º (an ordinal) was a character not allowed: the slips are
    explained and not judged, º reads as °, and kg·m²/s² is a unit of energy."""
    _, solution, judge, answers = setup("pendulum_rebound")
    angle = math.degrees(solution.answers["theta_impact"])
    speed, energy = solution.answers["omega_impact"], solution.answers["energy_loss"]
    for name, text, says in (("theta_impact", f"--{abs(angle):.4g}", "Two signs in a row"),
                             ("theta_impact", f"{angle:.4g} °°", "degree sign twice"),
                             ("omega_impact", f"1 - -{abs(speed):.4g}", "Two signs in a row"),
                             ("omega_impact", f"{math.degrees(speed):.4g} °", "write °/s, deg/s or rad/s")):
        verdict = judge.check(answers[name], text)
        assert not verdict.readable and says in verdict.message, (text, verdict.message)
    assert judge.check(answers["theta_impact"], f"{angle:.4g}º").correct
    assert judge.check(answers["omega_impact"], "2*sin(30°)").readable  # ° inside a function is an angle's
    assert "brackets" in judge.check(answers["omega_impact"], "2*sin 30°").message  # (the parser's word, not a unit's)
    assert judge.check(answers["energy_loss"], f"{energy:.4g} kg m^2/s^2").correct


def test_a_unit_typed_is_said_back_as_the_pages_write_units():
    """"Right: 2.469 kg·m² = 1.821 slug·ft²", not "2.469 kg*m^2": the factors the student separated joined
    by ·, powers as ², no spaces around /; and it is still the unit the student typed (it reads back the same)."""
    _, solution, judge, answers = setup("pendulum_rebound")
    inertia = solution.answers["I_O"]
    for typed in ("kg*m^2", "kg m**2", "kg · m ^ 2"):
        message = judge.check(answers["I_O"], f"{inertia:.4g} {typed}", "us").message
        assert message == f"Right: {inertia:.4g} kg·m² = {units.format_quantity(inertia, 'inertia', 'us')}.", message
    for dimension, table in units.SPELLINGS.items():
        for spelling in table:
            for typed in (spelling, spelling.replace("^2", " ** 2"), re.sub(r"^(kg|slug|lb|g)(?=[a-z])", r"\1 * ", spelling)):
                said = units.written(typed)
                assert units.si_per_unit(said, dimension) == table[spelling], (typed, said)
                assert not re.search(r"[*\s]|\^2|\^3", said), (typed, said)


@pytest.mark.parametrize("units_query, inertia", [({}, "kg·m²"), ({"units": "us"}, "slug·ft²")])
def test_the_answer_box_and_the_statement_name_the_unit_a_number_alone_is_read_in(units_query, inertia):
    """"291.7" for an angular speed in deg/s was a wrong, graded attempt while nothing on the page said a
    number alone is read in rad/s: each answer names it, where it is chosen and in the statement."""
    at = run_page("pendulum_rebound", {"practice": "1", **units_query})
    options = at.selectbox(key="pendulum_rebound__attempt_answer").options
    assert {"Angular velocity just after impact, in rad/s", "Highest angle after the bounce, in degrees",
            f"Moment of inertia about the pivot, in {inertia}"} <= set(options), options
    assert "Highest angle after the bounce, $\\theta_f$, in degrees" in page_text(at)


def test_a_unit_left_out_of_arithmetic_is_not_judged_a_prefix_is_named_and_so_is_a_wrong_label():
    """"9.208*180/pi" (the answer in deg/s, as arithmetic) was a wrong, graded attempt where the bare 527.6
    was not; "2.5506" (the cart's front load in kN) and "80.94" (Euler's disk's period in ms) said nothing of
    the unit; the disk's energy in J labelled ft·lbf was called a calculator in radian mode."""
    _, solution, judge, answers = setup("disk_wall")
    omega = solution.answers["omega1"]
    for text in (f"{omega:.6g}*180/pi", f"{math.degrees(omega) * 2:.6g}/2"):
        verdict = judge.check(answers["omega1"], text)
        assert not verdict.readable and "deg/s" in verdict.message, (text, verdict.message)
    lost = solution.answers["energy_loss"]
    labelled = judge.check(answers["energy_loss"], f"{lost:.6g} ft*lbf")
    assert labelled.readable and not labelled.correct and "the answer in J, not in the unit written" in labelled.message
    assert judge.check(answers["energy_loss"], f"{lost:.6g} ft·lbf").reading == labelled.reading  # one answer
    # a prefix left out (kN where N is read, ms where s) is a wrong number, counted, with the unit named: only
    # the page's own conventions (the other unit system, degrees and radians) are free
    for pid, name, scale, unit in (("driven_cart", "N_front", 1e-3, "kN"), ("eulers_disk", "period", 1e3, "ms")):
        _, solution, judge, answers = setup(pid)
        verdict = judge.check(answers[name], f"{solution.answers[name] * scale:.6g}")
        assert verdict.readable and not verdict.correct and f"the value in {unit}" in verdict.message, (pid, verdict.message)
        assert judge.check(answers[name], f"{solution.answers[name] * scale:.6g} {unit}").correct


def test_practice_keeps_a_tally_and_takes_an_answer_found_right_in_the_next():
    """Issue 54: an answer checked right is kept in a tally above the answer box for these numbers, and
    its symbol may then be written in an answer that follows from it (I_cm with d_cm), judged by its
    value; before it is found, the same symbol is refused as not a given, with the way to use it."""
    from solvers.stick_ball import ANSWERS_STICK

    names = [a.name for a in ANSWERS_STICK]
    at = run_page("stick_ball", {"practice": "1"})
    guess = "m_s*l^2/12 + m_s*d_cm^2 + m_b*(s - d_cm)^2"

    def check(name: str, text: str):
        at.selectbox(key="stick_ball__attempt_answer").select_index(names.index(name))
        at.text_input(key="stick_ball__attempt").input(text)
        at.button(key="stick_ball__check").click().run()
        assert not at.exception
        return " ".join(m.value for m in at.markdown)

    shown = check("I_cm", guess)
    assert any("d_cm" in w.value.replace("\\_", "_") and "not a given" in w.value and "Check it first" in w.value for w in at.warning)
    assert "Right so far" not in shown
    shown = check("d_cm", "m_b*s/(m_b + m_s)")
    assert at.success and "Right so far (1 of 8)" in shown and "Still to check" in shown, shown
    shown = check("I_cm", guess)
    assert at.success and "Right so far (2 of 8)" in shown, shown
    shown = check("I_cm", "m_s*l^2/12 + m_s*d_cm^2")  # a wrong one with the symbol: judged, not refused
    assert at.error and not at.warning and "Right so far (2 of 8)" in shown
