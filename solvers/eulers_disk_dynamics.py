"""Euler's disk beyond steady precession: the full rolling-disk equations of motion.

Derived with sympy.physics.mechanics (Kane's method), as in the classic rolling-disc example:
frames N (table) → Y (yaw q1 about N.z) → L (lean q2 about Y.x, q2 = 0 upright) → R (spin q3
about L.y, the disk's axis); generalised speeds are the components of the disk's angular velocity
in L. The disk rolls without slip: its contact point C has zero velocity, so the centre G, at
r L.z from C, moves with ω × r L.z. Forces: the weight at G (the table's force at C does no work
and is eliminated by Kane's method). The disk's tilt from the table is θ = π/2 − q2.

Two uses:
- the second method for the steady-precession page: started from the closed-form steady state
  (lean π/2 − θ, ω along L.z with |ω| = ω_p sin θ, G at rest) the integration must stay steady
  and precess at ω_p;
- dissipation: with a resisting torque −c ω on the disk (a simple stand-in for rolling and air
  resistance; Moffatt's air-layer model, Nature 404, 2000, is a refinement) the energy drains,
  the tilt falls and the precession rate grows toward the finite-time singularity.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp
from scipy.integrate import odeint, solve_ivp
from sympy.physics import mechanics as me

q1, q2, q3, u1, u2, u3 = me.dynamicsymbols("q1 q2 q3 u1 u2 u3")
r, m, g, c = sp.symbols("r m g c", positive=True)


@functools.cache
def equations():
    """The state's rate [q̇; u̇] (Kane's equations solved for u̇, the kinematic ones for q̇) and the
    precession rate q̇1, each compiled once: ``rate(y, r, m, g, c)`` for y = [q1, q2, q3, u1, u2, u3]."""
    N = me.ReferenceFrame("N")
    Y = N.orientnew("Y", "Axis", [q1, N.z])
    L = Y.orientnew("L", "Axis", [q2, Y.x])
    R = L.orientnew("R", "Axis", [q3, L.y])
    w_qd = R.ang_vel_in(N)
    R.set_ang_vel(N, u1 * L.x + u2 * L.y + u3 * L.z)
    C = me.Point("C")
    C.set_vel(N, 0)  # rolling: the contact point is at rest
    G = C.locatenew("G", r * L.z)
    G.v2pt_theory(C, N, R)
    inertia = me.inertia(L, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4)
    kinematic = [me.dot(R.ang_vel_in(N) - w_qd, uv) for uv in L]
    disk = me.RigidBody("disk", G, R, m, (inertia, G))
    loads = [(G, -m * g * Y.z), (R, -c * (u1 * L.x + u2 * L.y + u3 * L.z))]
    kane = me.KanesMethod(N, q_ind=[q1, q2, q3], u_ind=[u1, u2, u3], kd_eqs=kinematic)
    kane.kanes_equations([disk], loads)
    q_dot = kane.kindiffdict()
    rates = [q_dot[q.diff()] for q in (q1, q2, q3)] + list(kane.mass_matrix.LUsolve(kane.forcing))
    y = sp.symbols("q1:4 u1:4")  # plain symbols for the state, in its order
    plain = dict(zip((q1, q2, q3, u1, u2, u3), y))
    args = (y, r, m, g, c)
    # scalar code (math, common subexpressions once), M's inverse worked out: a run-down calls it some
    # 250,000 times (a numeric solve of M [q̇; u̇] = f at each call took 7× as long)
    rate = sp.lambdify(args, [e.subs(plain) for e in rates], modules="math", cse=True)
    precession = sp.lambdify(args, rates[0].subs(plain), modules="numpy")
    return rate, precession


def _rate(params: dict, damping: float):
    """The state's rate for these parameters, f(y, t) (odeint's order)."""
    rate, _ = equations()
    consts = (params["r"], params["m"], params["g"], damping)

    def rate_of(y, t):
        return rate(y, *consts)
    return rate_of


def steady_state(params: dict, omega_p: float) -> np.ndarray:
    """The closed-form steady precession as an initial state: G at rest needs ω ∥ L.z."""
    tilt = params["theta"]
    return np.array([0.0, math.pi / 2 - tilt, 0.0, 0.0, 0.0, omega_p * math.sin(tilt)])


def precession_rate(params: dict, state: np.ndarray):
    """q̇1 at a state, or at each column of states (one per instant)."""
    _, precession = equations()
    return precession(state, params["r"], params["m"], params["g"], 0.0)


def integrate_steady(params: dict, omega_p: float, periods: float = 2.0) -> dict:
    """Integrate the full equations from the steady state; return the drift of the tilt and the
    precession rate along the way."""
    y0 = steady_state(params, omega_p)
    span = periods * 2 * math.pi / omega_p
    # odeint (compiled LSODA) costs a fraction of solve_ivp's Python stepping; same tolerances.
    y = odeint(_rate(params, 0.0), y0, np.linspace(0.0, span, 9), rtol=1e-11, atol=1e-12).T
    tilt = math.pi / 2 - y[1]
    rates = [float(precession_rate(params, y[:, i])) for i in range(y.shape[1])]
    return {"tilt_drift": float(np.max(np.abs(tilt - params["theta"]))), "precession": rates,
            "yaw_turned": float(y[0, -1])}


def decay(params: dict, damping: float, t_max: float = 60.0, stop_tilt: float = math.radians(1.0)) -> dict:
    """With a resisting torque −c ω: the tilt, precession rate and energy against time, until the
    tilt falls to ``stop_tilt`` (the disk's clatter and stop) or ``t_max``; a start at or below
    ``stop_tilt``: the start alone, at t = 0."""
    key = tuple(sorted((k, float(v)) for k, v in params.items() if k in ("m", "r", "theta", "g")))
    return _decay(key, float(damping), float(t_max), float(stop_tilt))


@functools.lru_cache(maxsize=64)
def _decay(key: tuple, damping: float, t_max: float, stop_tilt: float):
    params = dict(key)
    omega_p = math.sqrt(4 * params["g"] / (params["r"] * math.sin(params["theta"])))
    y0 = steady_state(params, omega_p)
    rate = _rate(params, damping)

    def flat(t, y):
        return (math.pi / 2 - y[1]) - stop_tilt
    flat.terminal, flat.direction = True, -1
    # solve_ivp for its events, looked for after every step: the tilt nods as it falls, below 1° for
    # a few ms within one nod (an integration sampled every few ms missed such dips)
    if params["theta"] <= stop_tilt:  # it starts where a run-down ends: nothing to integrate (the event
        # below never fires, and 120 s of whirling at 0.5° held the one worker for minutes)
        t, y, reached = np.zeros(1), np.asarray(y0, dtype=float)[:, None], True
    else:
        sol = solve_ivp(lambda t, y: rate(y, t), (0.0, t_max), y0, method="LSODA", rtol=1e-8, atol=1e-10,
                        events=flat, dense_output=True)
        t = np.linspace(0.0, sol.t[-1], 200)
        y, reached = sol.sol(t), bool(sol.t_events[0].size)
    tilt = math.pi / 2 - y[1]
    rates = np.asarray(precession_rate(params, y), dtype=float)
    kinetic = 0.5 * params["m"] * params["r"] ** 2 * (y[3] ** 2 / 4 + y[4] ** 2 / 2 + y[5] ** 2 / 4)
    # G's velocity is ω × r L.z: add its translational energy, and the weight's potential energy
    kinetic += 0.5 * params["m"] * params["r"] ** 2 * (y[3] ** 2 + y[4] ** 2)
    energy = kinetic + params["m"] * params["g"] * params["r"] * np.sin(tilt)
    return {"t": t, "tilt": tilt, "precession": np.abs(rates), "energy": energy,
            "reached": reached, "time_to_stop": float(t[-1])}
