"""sliding_ladder against things independent of its code: the classic closed forms worked by hand,
an integration of the textbook's equations of motion written here (a different formulation from
the solver's Newton–Euler linear solve), energy conservation, the limit θ0 → 90°, and what is drawn."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from practice.judge import Judge
from solvers import sliding_ladder as ladder
from viz import sliding_ladder as ladder_viz

CONTRACT = {  # PROBLEMS.md §7, typed independently of the solver module
    "defaults": {"m": 10.0, "L": 4.0, "theta0": math.radians(60), "g": 9.81},
    "answers": {"theta_leave", "omega_leave", "vx_leave", "t_leave", "omega_floor", "t_floor", "N_wall0",
                "N_floor0"},
    "out_of_range": (("theta0", 0.0), ("theta0", math.pi / 2), ("theta0", -0.2), ("m", 0.0), ("L", -4.0),
                     ("g", 0.0)),
    "too_large": (dict(m=1e300, g=1e300), dict(L=1e300), dict(L=1e-300)),
}


def pos(lo, hi):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


VALID = st.fixed_dictionaries({"m": pos(0.1, 500), "L": pos(0.1, 50), "theta0": pos(math.radians(1), math.radians(89)),
                                "g": pos(0.5, 30)})


def test_the_contract():
    s = ladder.solve()
    assert {p.name: p.default for p in ladder.PARAMS} == pytest.approx(CONTRACT["defaults"])
    assert set(s.answers) == CONTRACT["answers"] == {a.name for a in ladder.ANSWERS}


def test_the_classic_numbers_worked_by_hand():
    """m = 10 kg, L = 4 m, θ0 = 60°: sin θ_ℓ = ⅔ sin 60° = 1/√3; ω_ℓ² = (3g/L)(sin θ0 − sin θ_ℓ) =
    (g/L) sin θ0; ẋ_G = (L/2) sin θ_ℓ ω_ℓ = ⅓ sin θ0 √(gL sin θ0); just after release N_A = m ẍ_G =
    ¾ mg sin θ0 cos θ0 and N_B = mg (1 − ¾ cos² θ0) = 13/16 mg; landing, energy with ẋ_G fixed:
    ω_f² = (g/L) sin θ0 (3 − sin² θ0 / 3)."""
    a = ladder.solve().answers
    g, L, m, s0 = 9.81, 4.0, 10.0, math.sin(math.radians(60))
    assert math.degrees(a["theta_leave"]) == pytest.approx(35.264, abs=5e-4)  # asin(1/√3)
    assert a["omega_leave"] == pytest.approx(math.sqrt(g / L * s0), rel=1e-12)  # 1.457 rad/s
    assert a["vx_leave"] == pytest.approx(s0 / 3 * math.sqrt(g * L * s0), rel=1e-12)  # 1.683 m/s
    assert a["N_wall0"] == pytest.approx(0.75 * m * g * s0 * 0.5, rel=1e-12)  # 31.86 N
    assert a["N_floor0"] == pytest.approx(13 / 16 * m * g, rel=1e-12)  # 79.71 N
    assert a["omega_floor"] == pytest.approx(math.sqrt(g / L * s0 * (3 - s0**2 / 3)), rel=1e-12)  # 2.417 rad/s
    assert a["omega_floor"] == pytest.approx(2.4168, abs=1e-4)


# ----------------------------------------------------------------------------------------------
# An integration written here: the textbook's θ̈ = −(3g/2L) cos θ until N_A = m ẍ_G = 0, then
# Lagrange's equation for θ with the foot on the floor and x_G free (ẋ_G constant).


def integrate_by_hand(p):
    m, L, g, th0 = p["m"], p["L"], p["g"], p["theta0"]

    def wall_push(t, y):
        th, w = y
        alpha = -1.5 * g / L * math.cos(th)
        return -m * L / 2 * (math.cos(th) * w * w + math.sin(th) * alpha)  # m ẍ_G
    wall_push.terminal, wall_push.direction = True, -1
    T = math.sqrt(L / g)
    one = solve_ivp(lambda t, y: [y[1], -1.5 * g / L * math.cos(y[0])], (0, 100 * T), [th0, 0.0],
                    events=wall_push, rtol=1e-11, atol=1e-12 * min(th0, math.pi / 2 - th0) / T, method="LSODA")
    t1, (th1, w1) = one.t_events[0][0], one.y_events[0][0]
    vx = -L / 2 * math.sin(th1) * w1

    def lagrange(t, y):  # M(θ) θ̈ + ½ M'(θ) θ̇² + g (L/2) cos θ = 0, M = L²cos²θ/4 + L²/12
        th, w = y
        M = L**2 * math.cos(th) ** 2 / 4 + L**2 / 12
        return [w, (L**2 / 4 * math.cos(th) * math.sin(th) * w * w - g * L / 2 * math.cos(th)) / M]

    def flat(t, y):
        return y[0]
    flat.terminal, flat.direction = True, -1
    two = solve_ivp(lagrange, (t1, t1 + 100 * T), [th1, w1], events=flat, rtol=1e-11, atol=1e-13, method="LSODA")
    t2, (_, w2) = two.t_events[0][0], two.y_events[0][0]
    return {"theta_leave": th1, "omega_leave": -w1, "vx_leave": vx, "t_leave": t1, "omega_floor": -w2, "t_floor": t2}


@settings(max_examples=25, deadline=None)
@given(VALID)
def test_every_answer_agrees_with_an_integration_written_here(p):
    a = ladder.solve(**p).answers
    by_hand = integrate_by_hand(p)
    for name, value in by_hand.items():
        assert a[name] == pytest.approx(value, rel=1e-6), name


@settings(max_examples=40, deadline=None)
@given(VALID)
def test_the_two_thirds_rule_for_any_mass_length_and_gravity(p):
    s = ladder.solve(**p)
    assert math.sin(s.answers["theta_leave"]) == pytest.approx(2 / 3 * math.sin(p["theta0"]), rel=1e-12)
    assert s.answers["omega_leave"] ** 2 == pytest.approx(p["g"] / p["L"] * math.sin(p["theta0"]), rel=1e-10)
    assert all(c.ok for c in s.checks), [c for c in s.checks if not c.ok]


def test_the_rule_does_not_depend_on_mass_length_or_gravity():
    base = ladder.solve().answers["theta_leave"]
    for change in ({"m": 0.3}, {"L": 17.0}, {"g": 1.62}):
        assert ladder.solve(**change).answers["theta_leave"] == pytest.approx(base, rel=1e-14)


# ----------------------------------------------------------------------------------------------
# The solver's own integration, against conservation and the constraints


@settings(max_examples=15, deadline=None)
@given(pos(math.radians(2), math.radians(88.5)))
def test_energy_is_conserved_through_both_phases_and_the_contacts_behave(theta0):
    run = ladder.integrated(theta0)  # units m = g = L = 1
    energy0 = 0.5 * math.sin(theta0)
    t1, t2 = run["t_leave"], run["t_floor"]
    for phase, times in (("phase1", np.linspace(0, t1, 60)), ("phase2", np.linspace(t1, t2, 60))):
        y = np.array([run[phase](t) for t in times])
        x, yG, th, vx, vy, w = y.T
        energy = 0.5 * (vx**2 + vy**2) + w**2 / 24 + yG
        assert np.allclose(energy, energy0, rtol=0, atol=1e-9), phase
        y_foot = yG - 0.5 * np.sin(th)
        assert np.allclose(y_foot, 0, atol=1e-9)  # the foot stays on the floor
        x_top = x - 0.5 * np.cos(th)
        if phase == "phase1":
            assert np.allclose(x_top, 0, atol=1e-9)  # the top on the wall
        else:
            assert np.allclose(vx, vx[0], rtol=0, atol=1e-10)  # ẋ_G constant once the top has left
            assert np.all(x_top >= -1e-10)  # it never re-enters the wall
            assert np.all(np.diff(x_top) >= -1e-10)  # it moves away
            assert np.all(np.diff(th) < 0)


@settings(max_examples=15, deadline=None)
@given(pos(0.01, math.pi / 2 - 0.01), pos(-10, 10), st.booleans())
def test_the_integrators_closed_form_equals_the_linear_system_solved_numerically(theta, omega, wall):
    """The integration's right-hand side is the Newton–Euler system solved once by sympy; at any
    state it gives what numpy's solve of the same 5 × 5 (or 4 × 4) system gives."""
    closed = ladder._solved_in_closed_form(wall)(theta, omega)
    numeric = ladder.reactions_and_accelerations([0.0, 0.0, theta, 0.0, 0.0, omega], wall)
    assert np.allclose(closed, numeric, rtol=1e-9, atol=1e-9 * (1 + omega * omega))


@given(VALID)
def test_the_reactions_never_pull_and_the_wall_lets_go_once(p):
    s = ladder.solve(**p)
    m = ladder.motion(s)
    assert np.all(m["N_wall"] >= -1e-9 * p["m"] * p["g"])
    assert np.all(m["N_floor"] > 0)  # the foot never lifts
    # After leaving, a wall that kept the top on it would have to pull. With both contacts, Newton–Euler
    # written here (G on a circle of radius L/2: θ̈ = −(3g/2L) cos θ) asks N_A = m ẍ_G =
    # (mL/2) cos θ ((3g/2L) sin θ − θ̇²); in the solver's units m = g = L = 1, for its phase-2 states:
    run = ladder.integrated(p["theta0"])
    th, w = np.array([run["phase2"](t) for t in np.linspace(run["t_leave"], run["t_floor"], 40)[1:]])[:, [2, 5]].T
    assert np.all(0.5 * np.cos(th) * (1.5 * np.sin(th) - w**2) <= 1e-9)
    # in phase 1, against the closed form written by hand: N_B = (mg/4)((3 sin θ − sin θ0)² + 1 − sin² θ0) > 0
    assert m["N_floor"][0] == pytest.approx(s.answers["N_floor0"], rel=1e-9)
    assert m["N_wall"][0] == pytest.approx(s.answers["N_wall0"], rel=1e-9)


def test_the_limit_near_upright():
    """θ0 → 90°: sin θ_ℓ → ⅔, ω_ℓ² → g/L, N_A0 → 0, N_B0 → mg; and the start is an inverted
    pendulum ψ̈ = (3g/2L) ψ (ψ = 90° − θ), so each tenfold smaller ψ0 adds ln 10 / √(3g/2L) to the
    time to leave (and to land)."""
    g, L = 9.81, 4.0
    near = [ladder.solve(theta0=math.pi / 2 - psi).answers for psi in (1e-4, 1e-5)]
    assert math.sin(near[1]["theta_leave"]) == pytest.approx(2 / 3, abs=1e-8)
    assert near[1]["omega_leave"] ** 2 == pytest.approx(g / L, rel=1e-8)
    assert near[1]["N_wall0"] == pytest.approx(0.75 * 10 * g * 1e-5, rel=1e-6)
    assert near[1]["N_floor0"] == pytest.approx(10 * g, rel=1e-7)
    decade = math.log(10) / math.sqrt(1.5 * g / L)
    for name in ("t_leave", "t_floor"):
        assert near[1][name] - near[0][name] == pytest.approx(decade, rel=1e-5)


def test_the_limit_near_flat():
    """θ0 → 0: the ladder hardly turns; θ̈ ≈ −3g/2L, so the time to fall θ0 − θ_ℓ = θ0/3 is
    √(2 (θ0/3) / (3g/2L)) to leading order."""
    theta0 = 1e-3
    a = ladder.solve(theta0=theta0).answers
    assert a["t_leave"] == pytest.approx(math.sqrt(2 * theta0 / 3 / (1.5 * 9.81 / 4)), rel=1e-3)


# ----------------------------------------------------------------------------------------------
# What is drawn


@settings(max_examples=10, deadline=None)
@given(VALID)
def test_the_drawn_ladder_never_enters_the_wall_or_the_floor(p):
    s = ladder.solve(**p)
    fig = ladder_viz.figures(s)[0]
    anim = fig.spec["animation"]
    body = next(i for i, j in enumerate(anim["traces"]) if fig.spec["data"][j]["name"] == "ladder")
    xs, ys = np.asarray(anim["coords"][body]["x"]), np.asarray(anim["coords"][body]["y"])
    tolerance = 1e-4 * max(1.0, p["L"])  # the figure's coordinates are rounded to 4 decimals
    assert xs.min() >= -tolerance and ys.min() >= -tolerance
    assert len(xs) >= 30
    m = ladder.motion(s)
    assert np.allclose(m["y_B"], 0, atol=1e-8 * p["L"])  # the foot on the floor in every frame
    assert np.all(m["x_A"] >= -1e-8 * p["L"])  # the top never behind the wall
    assert m["t"][m["leave_frame"]] == pytest.approx(m["t_leave"])  # a frame at the moment it leaves
    assert m["theta"][-1] == pytest.approx(0, abs=1e-9)  # the last frame lies flat


def test_the_descriptions_say_the_leaving_and_the_landing():
    s = ladder.solve()
    motion_fig, reactions = ladder_viz.figures(s)
    assert "35.26°" in motion_fig.description and "0.6501 s" in motion_fig.description
    assert "2.417 rad/s" in motion_fig.description
    assert "31.86 N" in reactions.description and "79.71 N" in reactions.description


def test_the_thumbnail_is_labelled():
    assert 'role="img"' in ladder_viz.THUMBNAIL and 'aria-label="A ladder' in ladder_viz.THUMBNAIL


# ----------------------------------------------------------------------------------------------
# Refusals


@pytest.mark.parametrize("bad", [dict(theta0=0.0), dict(theta0=-0.1), dict(theta0=math.pi / 2), dict(theta0=2.0),
                                 dict(m=0.0), dict(m=-1.0), dict(L=0.0), dict(g=-9.81), dict(g=math.nan),
                                 dict(theta0=math.nan), dict(L=math.inf), dict(m=True), dict(L="4")])
def test_bad_values_are_refused_in_plain_words(bad):
    (name,) = bad
    with pytest.raises(ValueError) as err:
        ladder.solve(**bad)
    assert name in str(err.value) and "Traceback" not in str(err.value)


def test_an_unknown_name_is_a_value_error_naming_it():
    with pytest.raises(ValueError, match="bogus"):
        ladder.solve(bogus=1)


@pytest.mark.parametrize("theta0", [1e-9, math.pi / 2 - 1e-9])
def test_releases_at_rest_too_close_to_flat_or_upright_are_refused_with_the_range(theta0):
    with pytest.raises(ValueError, match="theta0.*Use an angle from"):
        ladder.solve(theta0=theta0)


# ----------------------------------------------------------------------------------------------
# Practice


def judge_for(**params):
    s = ladder.solve(**params)
    return s, Judge(s, ladder.derivation_of(s), ladder.ANSWERS), {a.name: a for a in ladder.ANSWERS}


def test_every_answer_is_judged_right_as_a_number_and_the_closed_forms_as_expressions():
    s, judge, answers = judge_for()
    for name, answer in answers.items():
        shown = math.degrees(s.answers[name]) if answer.dimension == "angle" else s.answers[name]
        assert judge.check(answer, f"{shown:.5g}").correct, name
    assert judge.check(answers["omega_leave"], "sqrt(g*sin(theta_0)/L)").correct
    assert judge.check(answers["theta_leave"], "asin(2/3*sin(theta_0))").correct
    assert judge.check(answers["N_floor0"], "m*g*(1 - 3/4*cos(theta_0)^2)").correct
    assert judge.check(answers["vx_leave"], "sin(theta_0)/3*sqrt(g*L*sin(theta_0))").correct
    assert not judge.check(answers["omega_leave"], "sqrt(3*g*sin(theta_0)/L)").correct


def test_each_mistake_differs_from_the_answer_and_is_named(monkeypatch):
    import practice.mistakes as central
    if isinstance(getattr(central, "MISTAKES", None), dict) and "sliding_ladder" not in central.MISTAKES:
        # until practice reads each problem's own MISTAKES (the issue-16 refactor)
        monkeypatch.setitem(central.MISTAKES, "sliding_ladder", ladder.MISTAKES)
    s, judge, answers = judge_for()
    assert ladder.MISTAKES
    for mistake in ladder.MISTAKES:
        wrong = judge._value_of(mistake.wrong(dict(s.params)))
        right = s.answers[mistake.answer]
        assert wrong is not None and abs(wrong - right) > 0.005 * abs(right), mistake.feedback
        answer = answers[mistake.answer]
        shown = math.degrees(wrong) if answer.dimension == "angle" else wrong
        verdict = judge.check(answer, f"{shown:.5g}")
        assert not verdict.correct and mistake.feedback in verdict.message, (mistake.answer, verdict.message)


def test_the_wall_held_all_the_way_predicts_a_faster_landing_and_the_wall_pulling():
    """The common slip, computed here: held to the floor, ω² = (3g/L) sin θ0 (larger), and the
    wall would have to pull (N_A < 0) below sin θ = ⅔ sin θ0."""
    s = ladder.solve()
    g, L, s0 = 9.81, 4.0, math.sin(math.radians(60))
    assert math.sqrt(3 * g / L * s0) > s.answers["omega_floor"]
    below = 0.5 * s.answers["theta_leave"]
    assert 0.75 * 10 * g * math.cos(below) * (3 * math.sin(below) - 2 * s0) < 0


@pytest.mark.parametrize("theta0_deg", [3.0, 45.0, 60.0, 85.0, 89.9])
def test_everything_moving_stays_inside_the_view_and_g_drifts_at_the_answer_s_speed(theta0_deg):
    s = ladder.solve(theta0=math.radians(theta0_deg))
    fig = ladder_viz.figures(s)[0]
    (x_lo, x_hi), (y_lo, y_hi) = fig.spec["layout"]["xaxis"]["range"], fig.spec["layout"]["yaxis"]["range"]
    anim = fig.spec["animation"]
    for j, coords in zip(anim["traces"], anim["coords"]):
        xs, ys = np.asarray(coords["x"], dtype=float), np.asarray(coords["y"], dtype=float)
        if np.isnan(xs).all():
            continue
        assert np.nanmin(xs) >= x_lo and np.nanmax(xs) <= x_hi, fig.spec["data"][j]["name"]
        assert np.nanmin(ys) >= y_lo and np.nanmax(ys) <= y_hi, fig.spec["data"][j]["name"]
    m = ladder.motion(s)
    after = np.arange(len(m["t"])) >= m["leave_frame"]
    slope = np.polyfit(m["t"][after], m["x_G"][after], 1)[0]
    assert slope == pytest.approx(s.answers["vx_leave"], rel=1e-6)  # a straight line at ẋ_G = vx_leave


# ----------------------------------------------------------------------------------------------
# What a move of the slider finds ready (BENCHMARKS.md §1): the integration and its sampling depend
# on θ₀ alone, and every angle the slider offers is solved and drawn at server start (WARM)


def test_warm_lists_every_whole_degree_the_slider_offers():
    assert [round(math.degrees(p["theta0"]), 9) for p in ladder.WARM] == list(range(5, 90))


@settings(max_examples=10, deadline=None)
@given(pos(0.2, 40), pos(0.5, 30), pos(0.5, 300), st.integers(5, 89))
def test_the_motion_for_any_length_mass_and_gravity_is_the_unit_motion_scaled(L, g, m, degrees):
    """Dimensional analysis, independent of the cache: lengths scale with L, times with √(L/g),
    forces with m g, and the angle not at all."""
    theta0 = math.radians(degrees)
    unit = ladder.motion(ladder.solve(m=1.0, L=1.0, g=1.0, theta0=theta0))
    scaled = ladder.motion(ladder.solve(m=m, L=L, g=g, theta0=theta0))
    T = math.sqrt(L / g)
    assert np.allclose(scaled["theta"], unit["theta"], rtol=0, atol=1e-15)
    for length in ("x_G", "y_G", "x_A", "y_A", "x_B", "y_B"):
        assert np.allclose(scaled[length], unit[length] * L, rtol=1e-12, atol=1e-12 * L)
    assert np.allclose(scaled["t"], unit["t"] * T, rtol=1e-12)
    assert np.allclose(scaled["N_wall"], unit["N_wall"] * m * g, rtol=1e-12, atol=1e-12 * m * g)
    assert scaled["t_leave"] == pytest.approx(unit["t_leave"] * T, rel=1e-12)


def test_the_shared_sampling_cannot_be_changed_by_one_figure():
    m = ladder.motion(ladder.solve())
    with pytest.raises(ValueError):
        m["theta"][0] = 0.0  # a view of the shared, read-only states


def test_a_move_of_the_slider_on_the_page_finds_its_angle_warmed():
    """The page's slider value, converted to SI as the page converts it, is the very key WARM
    solved: after the warm-up a move to any whole degree integrates nothing."""
    from pathlib import Path

    from streamlit.testing.v1 import AppTest

    for params in ladder.WARM:
        ladder_viz.figures(ladder.solve(**params))
    at = AppTest.from_file(str(Path(__file__).resolve().parents[2] / "app_pages" / "sliding_ladder.py"),
                           default_timeout=60).run()
    before = ladder.integrated.cache_info().misses, ladder._sampled.cache_info().misses
    for degrees in (47, 12, 88):
        at.slider(key="sliding_ladder__si__theta0").set_value(float(degrees)).run()
        assert not at.exception
    assert (ladder.integrated.cache_info().misses, ladder._sampled.cache_info().misses) == before


@settings(max_examples=25, deadline=None)
@given(st.floats(math.radians(5), math.radians(89)), st.floats(0.5, 12), st.floats(0.5, 100))
def test_the_floor_pushes_a_quarter_of_the_weight_as_the_top_leaves_the_wall(theta0, length, mass):
    """The integration's reactions where the top leaves the wall, against the figure's closed form
    (viz.sliding_ladder._pushes_leaving: the wall's zero, the floor's mg/4, which the live drag draws)."""
    from viz.sliding_ladder import _pushes_leaving

    solution = ladder.solve(theta0=theta0, L=length, m=mass)
    m, p = ladder.motion(solution), solution.params
    wall, floor = (np.interp(m["t_leave"], m["curve_t"], m[k]) for k in ("N_wall", "N_floor"))
    want_wall, want_floor = _pushes_leaving(p)
    weight = p["m"] * p["g"]
    assert abs(wall - want_wall) <= 1e-9 * weight and abs(floor - want_floor) <= 1e-9 * weight, (wall, floor, weight)


def test_the_method_shown_before_the_solution_does_not_state_where_the_top_leaves():
    """Practice and an assignment show the derivation's step titles before "Show the solution": the
    leaving step said "at two-thirds of its initial height", a graded answer (θ_ℓ) in words."""
    solution = ladder.solve()
    shown = " ".join(step.title for step in solution.steps[: solution.symbolic_steps]).lower()
    assert not any(words in shown for words in ("two-thirds", "2/3", "⅔", "two thirds"))
