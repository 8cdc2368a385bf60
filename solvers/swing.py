"""Time integration of a one-degree-of-freedom swing, θ̈ = f(θ), with scipy's solve_ivp.

Used as the second method for the work-energy answers (pendulum, rod and spring) and to produce
the trajectories the animations draw. Tolerances are tight (rtol 1e-10) so that a check against a
closed form can use a tolerance that would catch a wrong factor.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.integrate import solve_ivp

RTOL, ATOL = 1e-10, 1e-12


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


def integrate_leg(
    acceleration: Callable[[float], float],
    theta0: float,
    omega0: float,
    t0: float,
    t_max: float,
    stop_at_angle: float | None = None,
    stop_at_rest: bool = False,
    direction: int = 0,
    samples: int = 0,
) -> Leg:
    """Integrate from (θ0, θ̇0) until θ reaches ``stop_at_angle``, θ̇ changes sign, or ``t_max``.

    ``direction`` is passed to the event (−1: only when the event function is decreasing).
    ``samples`` > 0 returns that many evenly spaced samples (dense output) instead of the steps.
    """
    events = []
    if stop_at_angle is not None:
        def hit(t, y):
            return y[0] - stop_at_angle
        hit.terminal, hit.direction = True, direction
        events.append(hit)
    if stop_at_rest:
        def rest(t, y):
            return y[1]
        # θ̇ reverses: from + to − when moving forward (or starting from rest toward +θ), and back.
        moving_forward = omega0 > 0 or (omega0 == 0 and acceleration(theta0) >= 0)
        rest.terminal, rest.direction = True, (-1 if moving_forward else 1)
        events.append(rest)

    sol = solve_ivp(
        lambda t, y: (y[1], acceleration(y[0])),
        (t0, t0 + t_max),
        (theta0, omega0),
        method="DOP853",
        rtol=RTOL,
        atol=ATOL,
        events=events or None,
        dense_output=samples > 0,
    )
    ended = any(len(te) for te in (sol.t_events or []))
    t_end = float(sol.t[-1])
    y_end = sol.y[:, -1]
    if ended:
        # Land exactly on the event (solve_ivp already reports the located event state).
        for te, ye in zip(sol.t_events, sol.y_events):
            if len(te):
                t_end, y_end = float(te[0]), ye[0]
                break
    if samples > 0:
        t = np.linspace(t0, t_end, samples)
        y = sol.sol(t)
        y[:, -1] = y_end
        return Leg(t, y[0], y[1], ended)
    t = np.append(sol.t[sol.t < t_end], t_end)
    y = np.column_stack([sol.y[:, sol.t < t_end], y_end])
    return Leg(t, y[0], y[1], ended)
