"""Time integration of a one-degree-of-freedom swing, θ̈ = f(θ), with events; and legs drawn from
the energy integral where they are only drawn.

Used as the second method for the work-energy answers (pendulum, rod and spring) and to produce the
trajectories the animations draw. The integrator is scipy's odeint (LSODA, compiled), run over a
time grid in chunks: a crossing (θ reaches an angle, or θ̇ reverses) is bracketed on the grid,
located on the cubic Hermite interpolant of the grid states, and the state at the event comes from
a checked Taylor step from the nearest grid point, or else one short, tight integration to that
instant (Newton then moves it onto the event by Taylor steps of the equation itself). Given an
estimate of the leg's duration (``crossing_time``, or a drawn leg's), the first chunk ends just
past it, so LSODA runs once without restarts and the event sits a Taylor step from a grid point.
Tolerances are tight (rtol 1e-11) so a check against a closed form can use a tolerance that would
catch a wrong factor. A leg that is only drawn, up to a turning point, comes from the first
integral θ̇² = F(θ) by quadrature instead (``drawn_to_turn``): no integration at all.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.integrate import odeint
from scipy.optimize import brentq

RTOL, ATOL = 1e-11, 1e-12  # for a leg that checks an answer
DRAWING = 1e-8, 1e-10  # (rtol, atol) for a leg that is only drawn: far below a pixel
GRID = 48  # grid points per chunk


@dataclass(frozen=True)
class Leg:
    """One leg of a swing: samples of t, θ, θ̇ and where/when it ended."""

    t: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    ended_by_event: bool

    @property
    def end(self) -> tuple[float, float, float]:
        return float(self.t[-1]), float(self.theta[-1]), float(self.omega[-1])


def _hermite_basis(s):
    """The cubic Hermite basis (h00, h10, h01, h11) at the fraction ``s`` of an interval (a number or an array)."""
    return 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2


def _hermite(t0, t1, y0, y1, d0, d1):
    """Cubic Hermite interpolant through (t0, y0, y0'), (t1, y1, y1')."""
    h = t1 - t0

    def value(t):
        h00, h10, h01, h11 = _hermite_basis((t - t0) / h)
        return h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1
    return value


def hermite_on_knots(t: np.ndarray, y: np.ndarray, dy: np.ndarray, times: np.ndarray,
                     ddy: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The piecewise cubic Hermite curve through the knots (t, y, y') (t increasing) and its
    derivative at ``times`` (within [t[0], t[-1]]): each time on the interval it falls in, the
    last one closed; ``_hermite`` on every interval at once. What scipy's CubicHermiteSpline gives,
    evaluated in a few whole-array steps (its construction costs more than a new state's whole
    drawing on the pendulum's page). With ``ddy`` (y'' at the knots: the equation of motion gives it),
    the quintic through (y, y', y'') instead: a drawn frame then agrees with the integration to its
    tolerance, where the cubic was 2e-6 rad off between knots a tenth of a second apart."""
    i = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 2)
    h = t[i + 1] - t[i]
    s = (times - t[i]) / h
    y0, y1, d0, d1 = y[i], y[i + 1], dy[i], dy[i + 1]
    if ddy is not None:
        value, rate = quintic(s, h, y0, y1, d0, d1, ddy[i], ddy[i + 1])
        end = s == 1  # (the last knot: its own state, not Horner's rounding of it)
        return np.where(end, y1, value), np.where(end, d1, rate)
    h00, h10, h01, h11 = _hermite_basis(s)
    value = h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1
    rate = (6 * s**2 - 6 * s) * (y0 - y1) / h + (3 * s**2 - 4 * s + 1) * d0 + (3 * s**2 - 2 * s) * d1  # d/dt of value
    return value, rate


def quintic(s, h, y0, y1, d0, d1, dd0, dd1):
    """(value, d/dt) of the quintic through (y, y', y'') at both ends of an interval of length ``h``, at the
    fraction ``s`` of it: numbers or arrays alike (one interval's scalars cost a root finder microseconds,
    where a whole-array evaluation per call cost it tenths of a millisecond). In powers of ``s`` by Horner's
    rule: y0 + h d0 s + a0 s²/2 + c3 s³ + c4 s⁴ + c5 s⁵, with a = y'' h² and c3…c5 fixed by the end's y, y', y''."""
    a0, a1 = dd0 * h**2, dd1 * h**2
    rise, slope0, slope1 = y1 - y0, h * d0, h * d1
    c3 = 10 * rise - 6 * slope0 - 4 * slope1 - (3 * a0 - a1) / 2
    c4 = -15 * rise + 8 * slope0 + 7 * slope1 + (3 * a0 - 2 * a1) / 2
    c5 = 6 * rise - 3 * (slope0 + slope1) - (a0 - a1) / 2
    value = y0 + s * (slope0 + s * (a0 / 2 + s * (c3 + s * (c4 + s * c5))))
    rate = (slope0 + s * (a0 + s * (3 * c3 + s * (4 * c4 + s * (5 * c5))))) / h
    return value, rate


def _first_event(grid, y, acceleration, angle, at_rest, direction, first_chunk):
    """(time, kind) of the first event between grid points, located on the cubic Hermite
    interpolant of the grid states; (None, "") if there is none. Sign tests, not products, which
    can underflow to 0. An angle reached in ``direction`` between two grid points short of it, where the
    swing turns just past it and comes back before the next (the turn's angle on the interpolant), counts."""
    found = []
    peak = {}  # interval -> the turn's time, where the angle is crossed on the way to it
    if angle is not None:
        f = y[:, 0] - angle
        s = np.sign(f)
        hit = (s[:-1] * s[1:] <= 0) & (f[:-1] != f[1:])
        if direction:
            hit &= np.sign(f[1:] - f[:-1]) == direction
            w = y[:, 1]
            turned = ((w[:-1] > 0) != (w[1:] > 0)) & (s[:-1] == -direction) & (s[1:] == -direction)
            for j in np.nonzero(turned)[0]:
                if hit.any() and j >= int(np.argmax(hit)):
                    break
                t0, t1, a, b = grid[j], grid[j + 1], y[j], y[j + 1]
                rate = _hermite(t0, t1, a[1], b[1], acceleration(a[0]), acceleration(b[0]))
                if rate(t0) * rate(t1) > 0:
                    continue
                t_turn = brentq(rate, t0, t1, xtol=1e-15)
                if (_hermite(t0, t1, a[0], b[0], a[1], b[1])(t_turn) - angle) * direction > 0:
                    hit[j] = True
                    peak[j] = t_turn
                    break
        if first_chunk and f[0] == 0:
            hit[0] = False  # starting on the angle is not reaching it
        if hit.any():
            found.append((int(np.argmax(hit)) + 1, 0, "angle"))
    if at_rest:
        w = y[:, 1]
        hit = (w[:-1] != 0) & ((w[1:] == 0) | ((w[:-1] > 0) != (w[1:] > 0)))
        if hit.any():
            found.append((int(np.argmax(hit)) + 1, 1, "rest"))
    if not found:
        return None, ""
    i, _, kind = min(found)  # the earlier interval; at the same one, the angle first
    t0, t1, a, b = grid[i - 1], grid[i], y[i - 1], y[i]
    if kind == "angle":
        interp = _hermite(t0, t1, a[0], b[0], a[1], b[1])
        return brentq(lambda t: interp(t) - angle, t0, peak.get(i - 1, t1), xtol=1e-15), kind
    interp = _hermite(t0, t1, a[1], b[1], acceleration(a[0]), acceleration(b[0]))
    return brentq(interp, t0, t1, xtol=1e-15), kind


def slope(acceleration: Callable[[float], float], q: float, eps: float = 1e-7) -> float:
    """dθ̈/dθ at q, by a central difference of step eps."""
    return (acceleration(q + eps) - acceleration(q - eps)) / (2 * eps)


def _taylor(acceleration, state, dt: float) -> np.ndarray:
    """The state dt later by a third-order Taylor step of θ̈ = f(θ) (dt is tiny here)."""
    q, w = state
    f = acceleration(q)
    df = slope(acceleration, q, eps=1e-7 * max(1.0, abs(q)))
    return np.array([q + w * dt + f * dt**2 / 2 + df * w * dt**3 / 6,
                     w + f * dt + df * w * dt**2 / 2])


def _stepped(acceleration, state, dt: float) -> np.ndarray | None:
    """The state dt away by a Taylor step, if one step and two half steps agree to rounding
    (dt is tiny next to the motion's time scale); else None."""
    whole = _taylor(acceleration, state, dt)
    halves = _taylor(acceleration, _taylor(acceleration, state, dt / 2), dt / 2)
    return whole if np.all(np.abs(whole - halves) <= 1e-14 * max(1.0, *np.abs(whole))) else None


def _polished(rhs, acceleration, start, t_start, event, kind, angle, tol, near=None):
    """(time, state) of the event: the state at the event, by a Taylor step from the grid point
    ``near`` (t, state) when it is close enough, else integrated from the grid point before it;
    then Newton on that state, moving along the solution by Taylor steps while the correction is
    tiny (a fresh integration otherwise), so an event costs at most one short integration."""
    exact = _stepped(acceleration, near[1], event - near[0]) if near is not None else None
    if exact is None:
        exact = odeint(rhs, start, [t_start, event], rtol=tol[0], atol=tol[1])[-1]
    for _ in range(4):
        residual, rate = ((exact[0] - angle, exact[1]) if kind == "angle" else (exact[1], acceleration(exact[0])))
        if rate == 0 or abs(residual) <= 1e-14 * max(1.0, abs(exact[0]), abs(exact[1])):
            break
        step = -residual / rate
        event += step
        stepped = _stepped(acceleration, exact, step)
        exact = stepped if stepped is not None else odeint(rhs, start, [t_start, event], rtol=tol[0], atol=tol[1])[-1]
    return event, exact


def drawn_to_turn(
    rate_squared: Callable[[np.ndarray], np.ndarray],
    acceleration: Callable[[float], float],
    theta0: float,
    theta_turn: float,
    t0: float,
    tolerance: float = 1e-8,
) -> Leg | None:
    """The leg from θ0 (moving) to its turning point θ_turn, drawn from the first integral
    θ̇² = rate_squared(θ) (vectorised) instead of integrated: for a leg that is only drawn.

    t = ∫ dθ/|θ̇|, and θ = θ_turn − d w² (d = θ_turn − θ0, w from 1 down to 0) removes the
    square-root singularity at the turn: dt = 2|d| w dw / |θ̇| is smooth in w, with the limit
    2|d| / √(−2 θ̈(θ_turn) d) at the turn. Simpson's rule sums it on a grid that doubles until the
    times agree to ``tolerance`` of the leg's duration (a slow passage near an equilibrium needs
    more points). None when the turn is degenerate (θ̈ = 0 there: the approach would take forever)
    or the sum does not settle, for the caller to integrate instead."""
    d = theta_turn - theta0
    pull = -2.0 * acceleration(theta_turn) * d  # > 0 at a true turn: θ̈ points back
    if d == 0 or not pull > 0 or not math.isfinite(pull):
        return None
    previous = None
    for n in _LEVELS:
        w, w2 = _unit_grid(n)  # from the turn (w = 0) back to the start (w = 1)
        theta = theta_turn - d * w2
        rate = np.sqrt(np.maximum(rate_squared(theta), 0.0))
        dt_dw = np.empty_like(w)
        dt_dw[0] = 2 * abs(d) / math.sqrt(pull)
        with np.errstate(over="ignore"):  # θ̇ = 0 short of the turn: an infinite time, left to the integrator
            dt_dw[1:] = 2 * abs(d) * w[1:] / np.maximum(rate[1:], np.finfo(float).tiny)
        from_turn = _simpson_cumulative(dt_dw, w[1])  # time from w[::2] to the turn
        if not np.isfinite(from_turn[-1]):
            return None
        if previous is not None and np.abs(from_turn[::2] - previous).max() <= tolerance * from_turn[-1]:
            t = t0 + (from_turn[-1] - from_turn)
            return Leg(t[::-1], theta[::2][::-1], math.copysign(1.0, d) * rate[::2][::-1], True)
        previous = from_turn
    return None


_LEVELS = (65, 129, 257, 513, 1025, 2049, 4097, 8193)


@functools.cache
def _unit_grid(n: int) -> tuple[np.ndarray, np.ndarray]:
    """n evenly spaced points on [0, 1] and their squares (made once; read only)."""
    u = np.linspace(0.0, 1.0, n)
    u.flags.writeable = False
    u2 = u**2
    u2.flags.writeable = False
    return u, u2


def _simpson_cumulative(f: np.ndarray, h: float) -> np.ndarray:
    """∫ f from the first sample to every other sample (f on an odd number of points spaced h),
    by Simpson's rule panel by panel."""
    panels = h / 3 * (f[0:-2:2] + 4 * f[1:-1:2] + f[2::2])
    return np.concatenate([[0.0], np.cumsum(panels)])


def crossing_time(rate_squared: Callable[[np.ndarray], np.ndarray], theta0: float, theta1: float,
                  tolerance: float = 1e-4) -> float:
    """About how long the motion takes from θ0 to θ1 if it does not turn between them:
    ∫ dθ/|θ̇| with θ̇² = rate_squared(θ), by Simpson's rule after θ = θ0 + D (3u² − 2u³), which
    packs the grid towards both ends (a slow start, or a near-stop at θ1) and removes a square-root
    singularity at either; the grid doubles until the estimate settles to ``tolerance``. An
    estimate, for sizing an integration's first chunk."""
    span = theta1 - theta0
    previous = math.nan
    for n in _LEVELS:
        u, u2 = _unit_grid(n)
        theta = theta0 + span * (3 * u2 - 2 * u2 * u)
        rate = np.sqrt(np.maximum(rate_squared(theta), 0.0))
        with np.errstate(divide="ignore", invalid="ignore"):
            integrand = 6 * abs(span) * u * (1 - u) / rate
        for end, inner in ((0, 1), (-1, -2)):  # the ends: 0 while moving, the limit at a standstill
            integrand[end] = 0.0 if rate[end] > 0 else integrand[inner]
        estimate = float(_simpson_cumulative(integrand, u[1])[-1])
        if abs(estimate - previous) <= tolerance * estimate:
            break
        previous = estimate
    return estimate


def integrate_leg(
    acceleration: Callable[[float], float],
    theta0: float,
    omega0: float,
    t0: float,
    t_max: float,
    stop_at_angle: float | None = None,
    stop_at_rest: bool = False,
    direction: int = 0,
    tolerances: tuple[float, float] = (RTOL, ATOL),
    expected: float | None = None,
) -> Leg:
    """Integrate from (θ0, θ̇0) until θ reaches ``stop_at_angle`` (crossing in ``direction``: −1
    decreasing, +1 increasing, 0 either), θ̇ reverses (``stop_at_rest``), or ``t_max`` has passed;
    returns the grid points, integrated a chunk (a quarter of a natural period) at a time.
    ``tolerances`` (rtol, atol) default to the tight ones a check needs (DRAWING for a leg only drawn).
    ``expected``, an estimate of the leg's duration (e.g. from the energy integral), sizes the first
    chunk to end just past it, so the integrator runs once without restarts; it only sizes the work:
    the integration alone finds the event."""
    if stop_at_rest and omega0 == 0:  # already at rest: the turn is here (e.g. a rebound that underflowed)
        return Leg(np.array([t0]), np.array([theta0]), np.array([0.0]), True)
    rhs = lambda y, t: (y[1], acceleration(y[0]))  # noqa: E731
    stiffness = abs(slope(acceleration, theta0, eps=1e-3))
    chunk = 0.25 * 2 * math.pi / math.sqrt(max(stiffness, 1e-6)) if stiffness else 1.0
    chunk = min(max(chunk, 1e-3), t_max)
    ts, ys = [np.array([t0])], [np.array([[theta0, omega0]])]
    t_start, y_start = t0, np.array([theta0, omega0], dtype=float)
    ended = False
    while t_start < t0 + t_max - 1e-15:
        if t_start == t0 and expected is not None and 0 < expected < t_max / 1.05:
            # The expected instant is a grid point: the event lies a Taylor step from it.
            grid = np.append(np.linspace(t0, t0 + expected, GRID), t0 + 1.05 * expected)
        else:
            grid = np.linspace(t_start, min(t_start + chunk, t0 + t_max), GRID)
        t_end = grid[-1]
        y = odeint(rhs, y_start, grid, rtol=tolerances[0], atol=tolerances[1])
        event, kind = _first_event(grid, y, acceleration, stop_at_angle, stop_at_rest, direction,
                                   first_chunk=t_start == t0)
        if event is not None:
            k = max(1, int(np.searchsorted(grid, event)))  # grid[k-1] < event <= grid[k]
            j = k if grid[k] - event < event - grid[k - 1] else k - 1
            event, exact = _polished(rhs, acceleration, y[k - 1], grid[k - 1], event, kind, stop_at_angle,
                                     tolerances, near=(grid[j], y[j]))
            ts.append(np.append(grid[1:k], event))
            ys.append(np.vstack([y[1:k], exact]))
            ended = True
            break
        ts.append(grid[1:])
        ys.append(y[1:])
        t_start, y_start = t_end, y[-1]
    t = np.concatenate(ts)
    y = np.vstack(ys)
    if ended and kind == "angle":
        y[-1, 0] = stop_at_angle  # exactly on the event
    return Leg(t, y[:, 0], y[:, 1], ended)
