"""stick_ball against the seed's numbers and the conservation laws about an arbitrary fixed point."""
import importlib
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings, strategies as st

from solvers import stick_ball
from solvers.diagram import balance, residuals, resultant
from tests.strategies import pos
from tests.drawing import DRAWN, EXAMPLES, circle, distance_to_segment, drawn, figures

# The solver contract, typed from PROBLEMS.md independently of the solver module (tests/physics/test_contract.py
# checks every registered problem against its CONTRACT): parameter defaults (SI, radians), answer names,
# and values the solver must refuse in plain words.
CONTRACT = {
    "defaults": dict(m_ball=1.0, m_stick=1.0, l=1.0, v=1.0, s=0.5, mode="stick", e=0.5),
    "answers": {"I_cm", "T_after", "T_before", "d_cm", "distance_per_rev", "energy_loss", "omega", "v_cm"},
    "out_of_range": (("s", 0.6), ("s", 0.0), ("e", 2.0)),
    "too_large": ({"l": 1e300}, {"v": 1e300}, {"m_ball": 1e300}),
}


@st.composite
def valid_params(draw):
    l = draw(pos(0.05, 5))
    return {"m_ball": draw(pos(0.01, 20)), "m_stick": draw(pos(0.01, 20)), "l": l,
            "v": draw(pos(0.01, 20)), "s": draw(pos(0.01, 0.5)) * l,
            "mode": draw(st.sampled_from(["stick", "bounce"])), "e": draw(pos(0, 1))}


VALID = valid_params()  # random valid parameters (SI, radians) for property tests

# Cases of the shared tests in test_what_students_see.py beyond the defaults.
IN_VIEW = ({"mode": "bounce", "s": 0.25},)  # the bounce that swings round into the ball
EDGE_LINKS = ({"mode": "bounce", "e": "1"},)  # links whose numbers could read −0
CHECK_CASES = ({"mode": "bounce", "s": 0.25},)  # beyond the defaults: every shown check can fail here too


def mistake_params(params: dict) -> dict:
    """Where every listed slip of practice mode applies and differs from the answer: the ball hits
    short of the stick's end."""
    return {"s": 0.4 * params.get("l", 1.0)}


def test_seed_numbers_equal_masses_end_hit():
    m, l, v = 1.0, 1.0, 1.0
    a = stick_ball.solve().answers
    assert a["d_cm"] == pytest.approx(l / 4)
    assert a["v_cm"] == pytest.approx(v / 2)
    assert a["omega"] == pytest.approx(6 * v / (5 * l))
    assert a["I_cm"] == pytest.approx(5 / 24 * m * l**2)
    assert a["T_before"] == pytest.approx(0.5 * m * v**2)
    assert a["T_after"] == pytest.approx(0.4 * m * v**2)
    assert a["distance_per_rev"] == pytest.approx(5 * math.pi * l / 6)


def test_default_s_is_the_end_of_whatever_stick():
    a = stick_ball.solve(l=2.0).answers
    assert a["d_cm"] == pytest.approx(0.5)  # l/4 with l = 2


def velocities_after(p, a):
    """(stick midpoint velocity, ball velocity, stick ω) after the impact."""
    if p["mode"] == "stick":
        return (a["v_cm"] - a["omega"] * a["d_cm"], a["v_cm"] + a["omega"] * (p["s"] - a["d_cm"]), a["omega"])
    return a["v_stick"], a["v_ball"], a["omega"]


@settings(max_examples=100, deadline=None)
@given(VALID, st.floats(-3, 3))
def test_momentum_and_angular_momentum_about_any_fixed_point(p, y0):
    a = stick_ball.solve(**p).answers
    mb, ms, l, v, s = p["m_ball"], p["m_stick"], p["l"], p["v"], p["s"]
    v_mid, v_ball, w = velocities_after(p, a)
    scale = mb * v
    assert ms * v_mid + mb * v_ball == pytest.approx(mb * v, abs=1e-9 * scale)
    # about the fixed point at arm y0 along the stick line: H = Σ m v_x (y − y0) + I ω
    H0 = mb * v * (s - y0)
    H1 = ms * v_mid * (0 - y0) + mb * v_ball * (s - y0) + ms * l**2 / 12 * w
    assert H1 == pytest.approx(H0, abs=1e-9 * scale * (abs(y0) + l))
    T1 = 0.5 * ms * v_mid**2 + 0.5 * ms * l**2 / 12 * w**2 + 0.5 * mb * v_ball**2
    assert a["T_after"] == pytest.approx(T1, rel=1e-9)
    assert a["energy_loss"] == pytest.approx(a["T_before"] - T1, abs=1e-9 * a["T_before"])
    assert a["energy_loss"] >= -1e-12 * a["T_before"]


@settings(max_examples=50, deadline=None)
@given(VALID)
def test_bounce_limits(p):
    plastic = stick_ball.solve(**{**p, "mode": "bounce", "e": 0.0}).answers
    stuck = stick_ball.solve(**{**p, "mode": "stick"}).answers
    # e → 0 ends with the ball moving with the stick's contact point: the same as attaching
    assert plastic["energy_loss"] == pytest.approx(stuck["energy_loss"], rel=1e-9)
    elastic = stick_ball.solve(**{**p, "mode": "bounce", "e": 1.0}).answers
    assert elastic["energy_loss"] == pytest.approx(0.0, abs=1e-9 * elastic["T_before"])
    # restitution: separation speed at the contact is e times the approach speed
    e = p["e"]
    b = stick_ball.solve(**{**p, "mode": "bounce"}).answers
    assert b["v_stick"] + b["omega"] * p["s"] - b["v_ball"] == pytest.approx(e * p["v"], abs=1e-9 * p["v"])


# ----------------------------------------------------------------------------------------------
# What a student sees: the drawing agrees with the physics, the captions with the motion


@EXAMPLES
@given(VALID)
def test_the_stick_never_passes_through_the_ball(p):
    _, (figure,) = figures("stick_ball", **p)
    for (bx, by), (sx, sy) in zip(drawn(figure, "ball"), drawn(figure, "stick")):
        cx, cy, radius = circle(bx, by)
        assert distance_to_segment(cx, cy, sx[0], sy[0], sx[1], sy[1]) >= radius - DRAWN * (1 + p["l"])


def test_the_trial_s_bounce_stops_at_the_second_contact_and_says_so():
    """/stick_ball?mode=bounce&s=0.25: the stick's other half used to sweep through the ball."""
    _, (figure,) = figures("stick_ball", mode="bounce", s=0.25)
    assert "second impact" in figure.description and "stops there" in figure.description
    times = figure.spec["animation"]["times"]
    assert 1.35 < times[-1] < 1.45  # it ends at the contact, about 1.41 s after the impact (the ball drawn 0.06 l)
    (bx, by), (sx, sy) = drawn(figure, "ball")[-1], drawn(figure, "stick")[-1]
    cx, cy, radius = circle(bx, by)
    assert distance_to_segment(cx, cy, sx[0], sy[0], sx[1], sy[1]) == pytest.approx(radius, abs=5 * DRAWN)


@EXAMPLES
@given(VALID)
def test_the_bounce_caption_agrees_with_the_ball_s_direction(p):
    p = {**p, "mode": "bounce"}
    solution, (figure,) = figures("stick_ball", **p)
    anim = figure.spec["animation"]
    impact = int(np.argmin(np.abs(np.asarray(anim["times"]))))
    start = circle(*drawn(figure, "ball")[impact])[0]
    moved = np.array([circle(xs, ys)[0] - start for xs, ys in drawn(figure, "ball")[impact + 1:]])
    text = figure.description
    assume(len(moved) and np.abs(moved).max() > 10 * DRAWN)  # it moves far enough to tell
    if "bounces back" in text:
        assert moved.max() <= DRAWN
    elif "carries on forward" in text:
        assert moved.min() >= -DRAWN
    else:
        assert "stops dead" in text
    (bx, by), (sx, sy) = drawn(figure, "ball")[-1], drawn(figure, "stick")[-1]
    cx, cy, radius = circle(bx, by)
    touching_at_the_end = distance_to_segment(cx, cy, sx[0], sy[0], sx[1], sy[1]) - radius < 5 * DRAWN * (1 + p["l"])
    if "second impact" in text:
        assert touching_at_the_end  # the motion ends where the caption says: at the second contact


def test_the_stick_s_energy_check_is_a_second_computation():
    """It used to show T_before against max(T_before, T_after): "0.5 vs 0.5" whatever happened."""
    solution = importlib.import_module("solvers.stick_ball").solve()
    energy = next(c for c in solution.checks if "energy" in c.name)
    assert energy.closed_form != pytest.approx(solution.answers["T_before"])
    # the worked solution's numbers: equal masses hit at the end lose 1/5 of ½ m v²
    assert energy.second_method == pytest.approx(0.1, rel=1e-12)


# ----------------------------------------------------------------------------------------------
# The free-body diagram of the impact (solvers/diagram.py): the ball and the stick isolated, the pair J


MODES = st.sampled_from(["stick", "bounce"])


def _impact(solution):
    (d,) = stick_ball.free_body_diagrams(solution.params)
    assert d.phase == "impact" and d.law == "impulse"
    return d


def _number(expr, values) -> float:
    return float(sp.sympify(expr).subs(values))


def _load(d, on: str):
    (load,) = d.loads_on(on)
    return load


@settings(max_examples=60, deadline=None)
@given(VALID, MODES)
def test_each_body_s_impulse_momentum_laws_hold_at_the_solver_s_numbers(p, mode):
    """Σ P̂ = m Δv_G and Σ M̂ = ΔH about each body's own centre, summed from the declared loads, hold at
    the velocities after that the solver's answers give (J from the effective mass at the contact, a
    formula that never uses them), whether the ball attaches or bounces."""
    p = {**p, "mode": mode}
    s = stick_ball.solve(**p)
    d = _impact(s)
    impulse = p["m_ball"] * p["v"]  # J ≤ (1 + e) m* v ≤ 2 m_b v; every term is at most a few times this
    rows = residuals(d, s)
    assert len(rows) == 6
    for law, left, right in rows:
        scale = impulse * (p["l"] if law.endswith("moment") else 1.0)
        assert abs(left - right) <= 1e-9 * scale, (law, left, right, scale)


@settings(max_examples=60, deadline=None)
@given(VALID, MODES)
def test_the_pair_is_equal_and_opposite_and_pushes_the_stick_forward(p, mode):
    """The ball's impulse on the stick is along the ball's approach (+E_x, perpendicular to the stick: a
    smooth contact) and the stick's on the ball its opposite, at one point Q on the stick's line; the stick's
    midpoint then moves forward, the ball slows, and the stick (hit at +s) turns clockwise. Nothing by
    gravity in the plane: the table and gravity act out of it, as the note says."""
    p = {**p, "mode": mode}
    s = stick_ball.solve(**p)
    d = _impact(s)
    values = d.values(s)
    on_stick, on_ball = _load(d, "the stick"), _load(d, "the ball")
    assert on_stick.kind == on_ball.kind == "impulse"
    assert on_stick.pair == on_ball.name and on_ball.pair == on_stick.name
    assert on_stick.by == "the ball" and on_ball.by == "the stick"
    stick_vector = tuple(_number(c, values) for c in on_stick.vector)
    ball_vector = tuple(_number(c, values) for c in on_ball.vector)
    assert stick_vector[0] > 0 and stick_vector[1] == 0  # along the approach, +E_x
    assert ball_vector == (-stick_vector[0], -stick_vector[1])
    # both act at Q, the same place: on the stick's line (x = 0) at s from its midpoint
    q_stick = tuple(_number(c, values) for c in d.body("the stick").points[on_stick.at])
    q_ball = tuple(_number(c, values) for c in d.body("the ball").points[on_ball.at])
    assert q_stick == q_ball == (0.0, pytest.approx(p["s"], rel=1e-12))
    # the approach line passes through the ball's centre: no moment about it (no spin given to the ball)
    assert _number(resultant(d, "the ball")[2], values) == pytest.approx(0.0, abs=1e-12 * p["m_ball"] * p["v"] * p["l"])
    v_mid, v_ball, w = velocities_after(p, s.answers)
    assert v_mid > 0 and v_ball < p["v"] and w > 0  # (velocities_after's ω: clockwise +)
    assert _number(stick_ball.omega_z, values) == pytest.approx(-w, rel=1e-12)
    assert not any(load.by == "gravity" for load in d.loads)
    assert "out of the plane" in d.note


@settings(max_examples=40, deadline=None)
@given(VALID, MODES)
def test_the_diagram_is_drawn_where_the_stage_draws_the_impact(p, mode):
    """``frames`` gives every symbol at each frame of the motion, NaN but at the impact's, where it is
    ``values``; there the diagram's points are where the stage draws the ball and the stick."""
    p = {**p, "mode": mode}
    s = stick_ball.solve(**p)
    d = _impact(s)
    motion = stick_ball.motion(s)
    count, impact = len(motion["t"]), motion["impact_index"]
    assert motion["t"][impact] == 0.0
    values = d.values(s)
    per_frame = d.frames(s, motion)
    assert set(per_frame) == set(values)
    for symbol, track in per_frame.items():
        track = np.asarray(track, dtype=float)
        assert track.shape == (count,), symbol
        assert track[impact] == pytest.approx(float(values[symbol]), rel=1e-12, abs=0.0), symbol
        assert np.isnan(np.delete(track, impact)).all(), symbol
    used = set().union(*(sp.sympify(c).free_symbols for b in d.bodies for pt in b.points.values() for c in pt),
                       *(sp.sympify(c).free_symbols for l in d.loads for c in l.vector),
                       *(sp.sympify(k).free_symbols for b in d.bodies for k in b.kinetic))
    assert used <= set(values)
    at = {k: float(v) for k, v in values.items()}
    where = {("the ball", "B"): motion["ball"], ("the stick", "M"): motion["mid"], ("the stick", "_top"): motion["top"],
             ("the stick", "_bottom"): motion["bottom"]}
    for (body, name), (xs, ys) in where.items():
        x, y = (_number(c, at) for c in d.body(body).points[name])
        assert (x, y) == (pytest.approx(float(xs[impact]), abs=1e-12 * p["l"]),
                          pytest.approx(float(ys[impact]), abs=1e-12 * p["l"])), name


def test_the_system_s_conservation_laws_are_the_two_bodies_laws_added():
    """The pair cancels when the bodies' generated laws are added (x, and the moments moved to any fixed
    point), which leaves the worked solution's conservation laws: the derivation writes them so."""
    (ball_x, _, _), (stick_x, _, _) = (balance(stick_ball.IMPACT, b) for b in ("the ball", "the stick"))
    assert stick_ball.J not in sp.expand(ball_x.lhs + stick_x.lhs).free_symbols
    point = (sp.Symbol("x_P", real=True), sp.Symbol("y_P", real=True))
    moments = [stick_ball._moment_law_about(b, point) for b in ("the ball", "the stick")]
    assert sp.expand(sum(m for m, _ in moments)) == 0
    stuck = stick_ball.solve()
    steps = [step for step in stuck.steps if step.part == 4 and "added" in step.title]
    assert len(steps) == 2 and all(r"\Rightarrow" in step.latex for step in steps)
    assert [step.part for step in stuck.steps] == sorted(step.part for step in stuck.steps)
    assert "Origin" in stuck.steps[0].title and stuck.steps[0].part == 1
