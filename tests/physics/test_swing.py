"""solvers.swing's energy-drawn legs and time estimates against solve_ivp (an integrator of its own:
DOP853, not the odeint that swing uses), for pendulum-like and spring-like swings."""
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from solvers.swing import crossing_time, drawn_to_turn


def swing(a: float, b: float, k: float):
    """θ̈ = a sin θ − b cos θ − k θ (gravity at any phase, plus a spring), and its first integral
    from (θ0, θ̇0): θ̇² = θ̇0² + 2[−a cos − b sin − k θ²/2] from θ0 to θ."""
    acc = lambda q: a * math.sin(q) - b * math.cos(q) - k * q  # noqa: E731
    potential = lambda q: -a * np.cos(q) - b * np.sin(q) - k * q**2 / 2  # noqa: E731  −V
    return acc, potential


def reference(acc, theta0, omega0, until_rest: bool, angle=None):
    """(t, θ(t) as a dense function) by DOP853 at tight tolerances, to the turn or to ``angle``."""
    event = (lambda t, y: y[1]) if until_rest else (lambda t, y: y[0] - angle)
    event.terminal = True
    # max_step: a grazing crossing (up past the angle and straight back) inside one long step
    # would hide from the event search.
    sol = solve_ivp(lambda t, y: [y[1], acc(y[0])], (0, 1e3), [theta0, omega0], method="DOP853",
                    events=event, dense_output=True, rtol=1e-12, atol=1e-13, max_step=0.01)
    return sol.t_events[0][0], sol.sol


@settings(max_examples=60, deadline=None)
@given(a=st.floats(-20, 20), b=st.floats(0.5, 20), k=st.floats(0, 30), theta0=st.floats(-1.2, 0.3),
       omega0=st.floats(0.3, 6))
def test_drawn_leg_follows_the_equation_to_its_turn(a, b, k, theta0, omega0):
    acc, minus_v = swing(a, b, k)
    rate_squared = lambda q: omega0**2 + 2 * (minus_v(q) - minus_v(theta0))  # noqa: E731
    grid = theta0 + np.linspace(0, 2 * math.pi, 20001)
    spent = np.nonzero(rate_squared(grid) <= 0)[0]
    assume(len(spent) and spent[0] > 0)
    from scipy.optimize import brentq
    turn = brentq(rate_squared, grid[spent[0] - 1], grid[spent[0]], xtol=1e-15)
    assume(acc(turn) < -1e-3)  # a true turn: θ̈ points back (degenerate turns return None)
    leg = drawn_to_turn(rate_squared, acc, theta0, turn, t0=2.0)
    assume(leg is not None)  # a sum that does not settle is left to the integrator (rare; see below)
    assert leg.ended_by_event
    t_turn, path = reference(acc, theta0, omega0, until_rest=True)
    assert leg.t[0] == 2.0 and leg.theta[0] == pytest.approx(theta0) and leg.omega[0] == pytest.approx(omega0)
    assert leg.t[-1] - 2.0 == pytest.approx(t_turn, rel=1e-7)
    assert leg.theta[-1] == pytest.approx(path(t_turn)[0], abs=1e-9)
    # every drawn sample lies on the integrated motion, far below a pixel
    assert np.abs(leg.theta - path(leg.t - 2.0)[0]).max() < 1e-7 * max(1.0, abs(turn - theta0))
    assert np.abs(leg.omega - path(leg.t - 2.0)[1]).max() < 1e-6 * omega0


def test_a_turn_at_an_equilibrium_is_left_to_the_integrator():
    acc, minus_v = swing(0.0, 1.0, 0.0)  # θ̈ = −cos θ: an equilibrium at θ = π/2
    assert drawn_to_turn(lambda q: 2 * (minus_v(q) - minus_v(0.0)) + 2.0, acc, 0.0, math.pi / 2, 0.0) is None
    assert drawn_to_turn(lambda q: 1.0 + 0 * q, acc, 0.3, 0.3, 0.0) is None  # no way to go


@settings(max_examples=60, deadline=None)
@given(a=st.floats(0.5, 40), k=st.floats(0, 10), start=st.floats(0.0, 0.5), omega0=st.floats(0.0, 2.0))
def test_crossing_time_estimates_the_integrated_time(a, k, start, omega0):
    """An inverted pendulum with a spring, from near upright (a slow start) to π/2."""
    acc, minus_v = swing(a, 0.0, k)
    rate_squared = lambda q: omega0**2 + 2 * (minus_v(q) - minus_v(start))  # noqa: E731
    qs = np.linspace(start, math.pi / 2, 2001)[1:]
    assume((rate_squared(qs) > 1e-6).all() and (omega0 > 1e-2 or acc(start) > 1e-3))
    t_cross, _ = reference(acc, start, omega0, until_rest=False, angle=math.pi / 2)
    assert crossing_time(rate_squared, start, math.pi / 2) == pytest.approx(t_cross, rel=0.02)


@settings(max_examples=80, deadline=None)
@given(knots=st.lists(st.tuples(st.floats(0.01, 2), st.floats(-5, 5), st.floats(-20, 20)), min_size=2, max_size=30),
       fractions=st.lists(st.floats(0, 1), min_size=1, max_size=50))
def test_hermite_on_knots_is_scipy_s_cubic_hermite_spline(knots, fractions):
    """The pendulum's legs are drawn through their knots by hermite_on_knots: the same curve and
    derivative as scipy's CubicHermiteSpline (its own construction, PPoly's evaluation), at the
    knots themselves and between them."""
    from scipy.interpolate import CubicHermiteSpline

    from solvers.swing import hermite_on_knots

    t = np.cumsum([0.0] + [gap for gap, _, _ in knots[1:]])
    y, dy = np.array([v for _, v, _ in knots]), np.array([d for _, _, d in knots])
    times = np.sort(np.concatenate([t, t[0] + (t[-1] - t[0]) * np.array(fractions)]))
    value, rate = hermite_on_knots(t, y, dy, times)
    curve = CubicHermiteSpline(t, y, dy)
    scale = 1 + np.abs(y).max() + np.abs(dy).max() * (t[-1] - t[0])
    assert np.allclose(value, curve(times), rtol=1e-12, atol=1e-12 * scale)
    assert np.allclose(rate, curve(times, 1), rtol=1e-10, atol=1e-10 * scale / np.diff(t).min())
    assert np.allclose(hermite_on_knots(t, y, dy, t)[0], y, rtol=1e-12, atol=1e-12 * scale)  # through every knot


@settings(max_examples=60, deadline=None)
@given(knots=st.lists(st.tuples(st.floats(0.01, 2), st.floats(-5, 5), st.floats(-20, 20), st.floats(-50, 50)),
                      min_size=2, max_size=20),
       fractions=st.lists(st.floats(0, 1), min_size=1, max_size=40))
def test_hermite_on_knots_with_second_derivatives_is_scipy_s_quintic(knots, fractions):
    """Given y'' too, hermite_on_knots draws the quintic through (y, y', y'') at each knot: scipy's
    BPoly.from_derivatives (its own construction), value and derivative."""
    from scipy.interpolate import BPoly

    from solvers.swing import hermite_on_knots

    t = np.cumsum([0.0] + [gap for gap, *_ in knots[1:]])
    y, dy, ddy = (np.array([k[i] for k in knots]) for i in (1, 2, 3))
    times = np.sort(np.concatenate([t, t[0] + (t[-1] - t[0]) * np.array(fractions)]))
    value, rate = hermite_on_knots(t, y, dy, times, ddy)
    curve = BPoly.from_derivatives(t, np.stack([y, dy, ddy], axis=1))
    gap = np.diff(t).min()
    scale = 1 + np.abs(y).max() + np.abs(dy).max() * (t[-1] - t[0]) + np.abs(ddy).max() * (t[-1] - t[0]) ** 2
    assert np.allclose(value, curve(times), rtol=1e-10, atol=1e-10 * scale)
    assert np.allclose(rate, curve(times, 1), rtol=1e-9, atol=1e-9 * scale / gap)


def test_the_quintic_draws_a_swing_to_the_integration_s_tolerance():
    """Knots a tenth of a second apart on a large swing (2.5 rad) of a pendulum, θ̈ = −ω₀² sin θ, ω₀ = 1:
    the quintic through θ, θ̇, θ̈ is within 1e-9 rad of the integration between them, where the cubic
    is some 1e-6 off (its error shrinks as h⁶ against the cubic's h⁴)."""
    from scipy.integrate import solve_ivp

    from solvers.swing import hermite_on_knots

    w0 = 1.0
    run = solve_ivp(lambda t, y: [y[1], -w0**2 * np.sin(y[0])], (0, 3), [2.5, 0.0], method="DOP853",
                    rtol=1e-13, atol=1e-14, dense_output=True)
    knots, between = np.arange(0, 3.0001, 0.1), np.linspace(0, 3, 301)
    theta, omega = run.sol(knots)
    truth = run.sol(between)[0]
    quintic, _ = hermite_on_knots(knots, theta, omega, between, -w0**2 * np.sin(theta))
    cubic, _ = hermite_on_knots(knots, theta, omega, between)
    assert np.abs(quintic - truth).max() < 1e-9 < 1e-7 < np.abs(cubic - truth).max()
