"""What a phone's answer to a question put to the room counts as (room/questions.py), on every problem at
hypothesis-drawn parameters: the solver's value counts as right, a named slip's value as that slip (each
a bar of the projector's histogram), anything else as other, text the judge cannot read as nothing; a
regime question's right choice agrees with the physics at its limits (PROBLEMS.md), not with the code
that answers it. The histogram counts every answer once."""
from __future__ import annotations

import math
from collections import Counter

import pytest
from hypothesis import assume, given, settings, strategies as st

from practice.judge import Judge
from room import questions
from solvers import registry
from solvers.catalog import BY_ID
from tests.strategies import valid
from viz.room import histogram


VALID = {pid: valid(pid) for pid in registry.PROBLEM_IDS}  # (each problem's test module imported once, here)


def typed(answer, value: float) -> str:
    """A value as a student types it: an angle in degrees with its sign, anything else alone, read in SI."""
    return f"{math.degrees(value):.9g}°" if answer.dimension == "angle" else f"{value:.9g}"


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
@settings(max_examples=6, deadline=None)
@given(data=st.data())
def test_the_solver_s_value_is_right_a_slip_s_is_that_slip_and_a_typo_counts_nothing(pid, data):
    params = data.draw(VALID[pid])
    try:
        solution = BY_ID[pid].solver.solve(**params)
    except ValueError:
        assume(False)
    params = dict(solution.params)
    judge = Judge(solution, BY_ID[pid].solver.derivation_of(solution), ())
    asked = [q for q in questions.questions(pid, params) if q.answer is not None]
    assert {q.answer.name for q in asked} == {a.name for a in BY_ID[pid].answers_of(solution)}
    for q in asked:
        value = solution.answers[q.answer.name]
        bars = [c for c, _ in questions.categories(pid, params, q.key)]
        assert bars[0] == questions.RIGHT and bars[-1] == questions.OTHER
        right = questions.respond(pid, params, "si", q.key, typed(q.answer, value))
        assert (right.counted, right.category) == (True, questions.RIGHT), (q.key, typed(q.answer, value))
        assert "right" not in right.message.lower()  # the phone is not told before the reveal
        for mistake in BY_ID[pid].solver.MISTAKES:
            if mistake.answer != q.answer.name or not mistake.applies(params):
                continue
            wrong = judge._value_of(judge.derivation.in_parameters(mistake.wrong(params)))
            if wrong is None or math.isclose(wrong, value, rel_tol=0.02, abs_tol=1e-9):
                continue  # not told apart from the answer at these numbers
            said = questions.respond(pid, params, "si", q.key, typed(q.answer, wrong))
            assert said.counted and said.category in bars and said.category != questions.RIGHT, (q.key, mistake.feedback)
        for text in ("2 +* 3", "5 furlongs", "1.5 kg·m²·s", "", "x" * 5000):
            assert not questions.respond(pid, params, "si", q.key, text).counted, (q.key, text)


def test_a_slip_is_named_by_its_feedback_s_first_sentence_cut_at_a_word():
    assert questions.slip_name("A sign: the rod reverses. Then more.") == "A sign: the rod reverses"
    long = questions.slip_name("word " * 40)
    assert len(long) <= questions.SLIP_NAME_LENGTH and long.endswith("…") and not long.endswith(" …")


def test_a_regime_choice_that_is_not_offered_counts_nothing():
    params = dict(registry.solver("disk_wall").solve().params)
    said = questions.respond("disk_wall", params, "si", "regime:stick_or_slip", "<script>alert(1)</script>")
    assert not said.counted and "Choose one" in said.message


@settings(max_examples=60, deadline=None)
@given(mu=st.floats(0.05, 3), a=st.floats(0.1, 2.5), b=st.floats(0.2, 2.5), drive=st.sampled_from(["front", "rear", "all"]))
def test_the_front_wheels_lift_where_the_physics_says(mu, a, b, drive):
    """PROBLEMS.md: with the rear wheels driven (all four too) the front ones lift once μa ≥ b; a front-driven
    car unloads its driven wheels as it accelerates and never lifts them."""
    assume(abs(mu * a - b) > 1e-6)
    params = {**registry.solver("driven_cart").solve().params, "mu": mu, "a": a, "b": b, "drive": drive}
    word = questions.right_category("driven_cart", params, "regime:front_wheels")
    assert word == ("lift" if drive != "front" and mu * a > b else "stay")
    assert any(k == "regime:front_wheels" for k in (q.key for q in questions.questions("driven_cart", params)))


def test_the_disk_sticks_on_a_wall_with_infinite_friction_and_slides_on_a_nearly_smooth_one():
    base = dict(registry.solver("disk_wall").solve().params)
    assert questions.right_category("disk_wall", {**base, "mu": math.inf}, "regime:stick_or_slip") == "stick"
    # a glancing approach with no spin slides at B: a wall with μ → 0 cannot stop it
    assert questions.right_category("disk_wall", {**base, "mu": 1e-3, "omega": 0.0}, "regime:stick_or_slip") == "slip"


@given(st.dictionaries(st.integers(1, 3), st.dictionaries(st.sampled_from(["right", "A slip", "other", "stray"]),
                                                          st.integers(0, 300), max_size=4), max_size=3))
def test_the_histogram_shows_every_answer_once(counts):
    counts = {n: Counter(c) for n, c in counts.items()}
    bars = (("right", "Right"), ("A slip", "A slip"), ("other", "Other"))
    figure = histogram(bars, counts, right="right")
    drawn = {trace["name"]: sum(trace["x"]) for trace in figure.spec["data"]}
    from viz.room import round_name
    for n, c in counts.items():
        assert drawn[round_name(n)] == sum(c.values())  # the stray category counts as other, once
    assert figure.height <= 440  # beside the code, in a projector's first screen
