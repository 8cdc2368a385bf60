"""A ladder slides down a smooth wall onto a smooth floor (a classic beyond the worked solutions).

Model: uniform slender rod (mass m, length L, I_G = m L²/12), its top A against a smooth vertical
wall at x = 0, its foot B on a smooth floor at y = 0, released from rest at θ0 (θ between the ladder
and the floor). While both contacts hold, G = ((L/2) cos θ, (L/2) sin θ) moves on a circle about the
corner, the ladder turns about its instantaneous centre C (where the normals at A and B meet, L/2
from G), and energy gives θ̇² = (3g/L)(sin θ0 − sin θ). The wall can only push: N_A = m ẍ_G falls to
zero at sin θ = ⅔ sin θ0 and the top leaves the wall. From then on no horizontal force acts, so
ẋ_G keeps its value; the foot stays on the floor (y_G = (L/2) sin θ) and energy with that
constraint alone carries θ to 0, where the ladder lands flat. The two times are integrals with no
elementary closed form (elliptic integrals): they are evaluated by quadrature. Every answer is
checked against an integration of the Newton–Euler equations (forces from a linear solve at each
instant) with an event where the wall's reaction reaches zero.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp
from scipy.integrate import odeint, quad, solve_ivp

from .kept import kept_pickled
from .core import (
    Answer,
    Check,
    Derivation,
    Number,
    OutOfModelRangeError,
    Result,
    Solution,
    Step,
    latex,
    latex_eq,
    latex_number,
    plain_number,
    presentable,
    relative_tolerance,
    validate_params,
    within_model_range,
    per_solution,
)
from . import units
from .diagram import Body, DiagramSlip, Diagram, Load, Rod, balance, balance_steps, fbd_steps
from .live import Case, Integrated, Leg, Live, frame_instants
from .protocol import About, Mistake, Variants

ABOUT = About(
    title="Ladder sliding down a smooth wall",
    group="Newton–Euler",
    blurb="A ladder slips on a smooth wall and floor: when does its top leave the wall, and how does it land?",
    icon=":material/stairs:",
    source="a classic of rigid-body dynamics, beyond the worked solutions",
    primary=("theta0", "L"),
)

PARAMS = (
    Number("m", 10.0, "ladder mass", "mass", "m", low=0, ui_low=0.5, ui_high=100.0, step=0.5),
    Number("L", 4.0, "ladder length", "length", "L", low=0, ui_low=0.5, ui_high=12.0, step=0.1),
    Number("theta0", math.radians(60), "release angle from the floor", "angle", r"\theta_0", low=0,
           high=math.pi / 2, ui_low=5, ui_high=89, step=1.0,
           help="The angle between the ladder and the floor when it is let go, at rest."),
    Number("g", 9.81, "gravity", "acceleration", "g", low=0, ui_low=0.5, ui_high=30.0, step=0.01),
)

# Every release angle the slider offers (whole degrees), solved and drawn at server start: the
# integration behind the checks and the animation depends on θ₀ alone (units m = g = L = 1), so a
# move of the slider, or of L, m or g, then finds it cached in every session (BENCHMARKS.md §1).
_SLIDER = next(p for p in PARAMS if p.name == "theta0")
WARM: tuple[dict, ...] = tuple(
    {"theta0": units.to_si(float(degrees), "angle")}
    for degrees in range(int(_SLIDER.ui_low), int(_SLIDER.ui_high) + 1, int(_SLIDER.step)))

ANSWERS = (
    Answer("theta_leave", "angle when the top leaves the wall", r"\theta_\ell", "angle"),
    Answer("omega_leave", "angular speed when the top leaves the wall", r"\lvert\dot\theta_\ell\rvert",
           "angular_speed"),
    Answer("vx_leave", "speed of G away from the wall then (constant afterwards)", r"\dot x_{G\ell}", "speed"),
    Answer("t_leave", "time from release until the top leaves the wall", r"t_\ell", "time"),
    Answer("omega_floor", "angular speed when the ladder lands flat", r"\lvert\dot\theta_f\rvert", "angular_speed"),
    Answer("t_floor", "time from release until the ladder lands flat", r"t_f", "time"),
    Answer("N_wall0", "wall's reaction just after release", r"N_{A0}", "force"),
    Answer("N_floor0", "floor's reaction just after release", r"N_{B0}", "force"),
)

ERRATA: tuple[str, ...] = ()  # not in the worked solutions
LIMIT_LABELS: dict[str, tuple[str, str]] = {}
VARIANTS = Variants(angles_deg={"theta0": (30, 80)})

m, L, g = sp.symbols("m L g", positive=True)
theta0 = sp.Symbol(r"theta_0", positive=True)
theta = sp.Symbol(r"theta", positive=True)
thetadot = sp.Symbol(r"\dot{\theta}", real=True)
thetaddot = sp.Symbol(r"\ddot{\theta}", real=True)
th_l, w_l, v_l, t_l, w_f, t_f, N_A0, N_B0 = sp.symbols(
    r"theta_ell |\dot{\theta}_\ell| \dot{x}_{G\ell} t_\ell |\dot{\theta}_f| t_f N_{A0} N_{B0}", positive=True)
# The two phases' times in units of sqrt(L/g): integrals evaluated by quadrature (chain inputs), and
# the time to the floor if the wall held all the way down (only for the slip of that name).
tau_1, tau_2, tau_held = sp.symbols(r"tau_1 tau_2 tau_held", positive=True)
TIME_INTEGRALS = {"tau_1": tau_1, "tau_2": tau_2, "tau_held": tau_held}

SYMBOLS = {"m": m, "L": L, "theta0": theta0, "g": g}
DIMENSIONS = {p.name: p.dimension for p in PARAMS} | {name: "dimensionless" for name in TIME_INTEGRALS}

# ---------------------------------------------------------------------------------------------
# Step 2: the ladder's free-body diagrams, before and after the top leaves the wall, in the stage's
# coordinates (the corner at the origin, x along the floor away from the wall, y up). θ is the angle
# from the floor, so the ladder's anticlockwise angular acceleration is −θ̈.

x_G, xdd_G, ydd_G = sp.symbols(r"x_G \ddot{x}_G \ddot{y}_G", real=True)
N_A, N_B = sp.symbols("N_A N_B", real=True)
_G_SYMBOLS = (x_G, xdd_G, ydd_G)  # (the derivation names its own x_G: G's position in time)
I_G = m * L**2 / 12


def _ladder(name_points: dict) -> Body:
    return Body("the ladder", points=name_points, centre="G", about="G",
                kinetic=(m * xdd_G, m * ydd_G, -I_G * thetaddot),
                kinetic_latex=(r"m\ddot{x}_G", r"m\ddot{y}_G", r"-I_G\,\ddot{\theta}"),
                outline=(Rod(("A", "B")),))


_POINTS = {"G": (x_G, L / 2 * sp.sin(theta)), "A": (x_G - L / 2 * sp.cos(theta), L * sp.sin(theta)),
           "B": (x_G + L / 2 * sp.cos(theta), 0)}
_WEIGHT = Load("m g", "the weight", "gravity", "the ladder", at="G", direction=(0, -1), size=m * g)
_FLOOR = Load("N_B", "the floor's normal force", "the floor", "the ladder", at="B", direction=(0, 1), size=N_B)
_WALL = Load("N_A", "the wall's normal force", "the wall", "the ladder", at="A", direction=(1, 0), size=N_A)


def _release_values(solution) -> dict:
    """Just after release (θ = θ₀, θ̇ = 0): the reactions are the solver's answers; θ̈ is the textbook's
    −(3g/2L) cos θ (PROBLEMS.md), G's acceleration its kinematics on the circle."""
    p, a = solution.params, solution.answers
    th, angular = p["theta0"], -1.5 * p["g"] / p["L"] * math.cos(p["theta0"])
    return {m: p["m"], g: p["g"], L: p["L"], theta: th, thetaddot: angular, x_G: p["L"] / 2 * math.cos(th),
            xdd_G: -p["L"] / 2 * math.sin(th) * angular, ydd_G: p["L"] / 2 * math.cos(th) * angular,
            N_A: a["N_wall0"], N_B: a["N_floor0"]}


def _newton_euler_at(p, states, wall: bool) -> dict:
    """The symbols at integrated states (units m = g = L = 1, one per row), scaled to SI: the second
    method's accelerations and reactions (the integration's own linear solve)."""
    states = np.atleast_2d(np.asarray(states, dtype=float))
    solved = reactions_and_accelerations(states, wall) if len(states) else np.empty((0, 5 if wall else 4))
    mg, rate = p["m"] * p["g"], p["g"] / p["L"]
    out = {m: p["m"], g: p["g"], L: p["L"], theta: states[:, 2], x_G: states[:, 0] * p["L"],
           xdd_G: solved[:, 0] * p["g"], ydd_G: solved[:, 1] * p["g"], thetaddot: solved[:, 2] * rate,
           N_B: solved[:, 3] * mg}
    if wall:
        out[N_A] = solved[:, 4] * mg
    return out


def _leaving_values(solution) -> dict:
    """Just after the top leaves the wall, from the Newton–Euler integration's state there."""
    run = integrated(solution.params["theta0"])
    return {k: (float(v[0]) if isinstance(v, np.ndarray) else v)
            for k, v in _newton_euler_at(solution.params, [run["leave"]], wall=False).items()}


def _frames(wall: bool):
    def per_frame(solution, motion) -> dict:
        """Each frame's symbols while this phase lasts (NaN in the other's frames)."""
        frames, states, _, _, _, t1, _, _ = _sampled(solution.params["theta0"])
        mine = frames <= t1 if wall else frames > t1
        here = _newton_euler_at(solution.params, states[mine], wall)
        out = {}
        for sym, value in here.items():
            column = np.full(len(frames), np.nan)
            column[mine] = value
            out[sym] = column
        return out
    return per_frame


def _leaving_key(p, a) -> dict:
    """At the stage's key frame, the top leaving the wall (still against it there): θ from the live values,
    G on its circle, the wall's push zero and the floor's mg/4 (viz.sliding_ladder: whatever θ₀)."""
    th = a["theta_leave"]
    return {m: p["m"], g: p["g"], L: p["L"], theta: th, x_G: p["L"] / 2 * sp.cos(th), N_A: 0, N_B: p["m"] * p["g"] / 4}


BOTH_CONTACTS = Diagram(
    "both_contacts", "Against the wall", "force", bodies=(_ladder(_POINTS),), loads=(_WEIGHT, _WALL, _FLOOR),
    values=_release_values, frames=_frames(True), key=_leaving_key,
    note="The wall and the floor are smooth: each pushes along its normal only.")
FLOOR_ONLY = Diagram(
    "floor_only", "After the top leaves the wall", "force", bodies=(_ladder(_POINTS),), loads=(_WEIGHT, _FLOOR),
    values=_leaving_values, frames=_frames(False),
    note="No horizontal force is left: $\\dot x_G$ keeps its value.")


def free_body_diagrams(params) -> tuple[Diagram, ...]:
    """Both phases' diagrams (the same for every parameter set)."""
    return (BOTH_CONTACTS, FLOOR_ONLY)


# The classic slips in drawing this diagram (practice/diagram_judge.py), as MISTAKES are the answers':
# each a load the physics does not put there, with a tutor's words that never show the diagram.
DIAGRAM_SLIPS = (
    DiagramSlip("friction on a smooth surface", "the wall is smooth: it pushes along its normal only, with no "
                "friction along it.", at="A", direction=(0, 1), either_way=True),
    DiagramSlip("friction on a smooth surface", "the floor is smooth: it pushes along its normal only, with no "
                "friction along it.", at="B", direction=(1, 0), either_way=True),
    DiagramSlip("centripetal force", "a centripetal force is not a force of its own: G moves on a circle because "
                "of the real forces, which is what they add up to.", at="G",
                direction=(-sp.cos(theta), -sp.sin(theta))),
)



# Released nearer the floor or the wall than this, the motion is too small or its start too slow
# (an unstable equilibrium) for the arithmetic; the refusal says so. (1e-6 rad = 5.7e-5°)
CLOSEST_TO_REST = 1e-6


@functools.cache
def derivation() -> tuple[Derivation, dict]:
    """Both phases, derived once (``_derived``), with θ̇²(θ) of each phase as plain functions in units
    g = L = 1, for the time quadratures."""
    derived, rates = _derived()
    return derived, {name: sp.lambdify(args, expr, "math") for name, (args, expr) in rates.items()}


@kept_pickled
def _derived() -> tuple[Derivation, dict]:
    """Both phases: energy, the reactions from Newton's law for G, the instant the wall's reaction
    vanishes, then energy with the floor constraint alone; and θ̇²(θ) of each phase in units g = L = 1
    (its arguments, its expression)."""
    t = sp.Symbol("t")
    q = sp.Function(r"theta")(t)
    x_G, y_G = L / 2 * sp.cos(q), L / 2 * sp.sin(q)
    I_G = m * L**2 / 12
    as_symbols = lambda e: e.subs({q.diff(t, 2): thetaddot, q.diff(t): thetadot}).subs(q, theta)  # noqa: E731

    # Phase 1: both contacts. Kinetic energy of G's motion plus the turning about G.
    v_sq = sp.simplify(as_symbols(x_G.diff(t) ** 2 + y_G.diff(t) ** 2))
    T1 = sp.simplify(m * v_sq / 2 + I_G * thetadot**2 / 2)
    I_C = sp.simplify(2 * T1 / thetadot**2)
    energy1 = sp.Eq(T1, m * g * L / 2 * (sp.sin(theta0) - sp.sin(theta)))
    W = sp.Symbol("W", positive=True)  # θ̇², solved for
    rate_sq = sp.solve(energy1.subs(thetadot**2, W), W)[0]
    accel = sp.simplify(sp.diff(rate_sq, theta) / 2)  # d(θ̇²)/dt = 2 θ̇ θ̈ = (d θ̇²/dθ) θ̇
    x_acc, y_acc = as_symbols(x_G.diff(t, 2)), as_symbols(y_G.diff(t, 2))
    # The reactions and θ̈ from the balance laws written from the diagram (Step 3), G on its circle;
    # θ̈ from them must be the energy method's.
    at_G, acc_x, acc_y = _G_SYMBOLS
    laws = [(law.lhs - law.rhs).subs({acc_x: x_acc, acc_y: y_acc, at_G: as_symbols(x_G)})
            for law in balance(BOTH_CONTACTS, "the ladder")]
    (newton_euler,) = sp.solve(laws, [N_A, N_B, thetaddot], dict=True)
    assert sp.simplify(newton_euler[thetaddot].subs(thetadot**2, rate_sq) - accel) == 0, "θ̈: energy ≠ Newton–Euler"
    wall = sp.factor(sp.simplify(newton_euler[N_A].subs(thetadot**2, rate_sq)))
    floor = sp.factor(sp.simplify(newton_euler[N_B].subs(thetadot**2, rate_sq)))
    s = sp.Symbol("s", positive=True)
    (leaving_sin,) = sp.solve(sp.factor(wall / sp.cos(theta)).subs(sp.sin(theta), s), s)  # cos θ > 0 here
    leave_angle = sp.asin(leaving_sin)
    wall_0 = presentable(sp.simplify(wall.subs(theta, theta0)), 3 * m * g * sp.sin(theta0) * sp.cos(theta0) / 4)
    floor_0 = sp.factor(sp.simplify(floor.subs(theta, theta0)))
    omega_l = sp.sqrt(rate_sq.subs(theta, th_l))
    omega_leave = omega_l.subs(th_l, leave_angle).simplify()  # √(g sin θ₀ / L)
    speed_l = sp.simplify(as_symbols(x_G.diff(t)).subs(theta, th_l).subs(thetadot, -w_l))

    # Phase 2: the floor alone. ẋ_G keeps its value; y_G = (L/2) sin θ still; energy from leaving.
    T2 = m * (v_l**2 + as_symbols(y_G.diff(t)) ** 2) / 2 + I_G * thetadot**2 / 2
    T_l = I_C * w_l**2 / 2
    energy2 = sp.Eq(T2, T_l + m * g * L / 2 * (sp.sin(th_l) - sp.sin(theta)))
    rate2_sq = presentable(sp.solve(energy2.subs(thetadot**2, W), W)[0],
                           sp.Mul(4 / (1 + 3 * sp.cos(theta) ** 2),
                                  w_l**2 - 3 * v_l**2 / L**2 + 3 * g / L * (sp.sin(th_l) - sp.sin(theta)),
                                  evaluate=False))
    omega_f = sp.sqrt(sp.expand(rate2_sq.subs(theta, 0)))
    omega_f = presentable(omega_f, sp.sqrt(w_l**2 + 3 * g / L * sp.sin(th_l) - 3 * v_l**2 / L**2))

    time_1 = sp.Integral(1 / sp.sqrt(rate_sq.subs({g: 1, L: 1})), (theta, th_l, theta0))
    time_2 = sp.Integral(1 / sp.Function(r"\hat{\omega}_2")(theta), (theta, 0, th_l))
    steps = [
        Step(r"Origin at the corner O where the wall meets the floor; $\mathbf{E}_x$ along the floor away from the "
             r"wall, $\mathbf{E}_y$ up; θ the ladder's angle from the floor (its anticlockwise rotation is $-\dot\theta$). "
             "Both contacts hold: G moves on a circle of radius L/2 about the corner",
             r"x_G = " + latex(x_G.subs(q, theta)) + r",\quad y_G = " + latex(y_G.subs(q, theta)), part=1),
        *fbd_steps(BOTH_CONTACTS), *fbd_steps(FLOOR_ONLY),
        *balance_steps(BOTH_CONTACTS), *balance_steps(FLOOR_ONLY),
        Step(r"Kinetic energy: G's motion plus the turning about G ($I_G = mL^2/12$); the ladder turns about "
             "its instantaneous centre C, L/2 from G",
             r"T = \tfrac12 m v_G^2 + \tfrac12 I_G \dot\theta^2 = " + latex(T1)
             + r" = \tfrac12 I_C \dot\theta^2,\quad I_C = " + latex(I_C)),
        Step("Energy from rest (the smooth wall and floor do no work)",
             latex(energy1, order="rev-lex") + r"\;\Rightarrow\;" + latex_eq(thetadot**2, rate_sq, order="rev-lex")),
        Step("Its rate of change, d(θ̇²)/dt = 2θ̇θ̈, gives the angular acceleration",
             latex_eq(thetaddot, accel)),
        Step(r"From $\sum F_x$ of Step 3, G on its circle: the wall's push is the only horizontal force, $N_A = m\ddot x_G$",
             r"N_A = m\,\ddot x_G = " + latex(sp.factor(m * x_acc)) + " = " + latex(wall)),
        Step(r"The floor carries the weight and G's vertical acceleration: $N_B = m(\ddot y_G + g)$",
             r"N_B = " + latex(floor)),
        Step("Just after release (θ = θ₀, θ̇ = 0)",
             latex_eq(N_A0, wall_0) + r",\quad " + latex_eq(N_B0, floor_0)),
        Step("The wall cannot pull: the top leaves the wall where $N_A$ reaches zero", r"N_A = 0 \;\Rightarrow\; \sin\theta_\ell = " + latex(leaving_sin)
             + r",\quad " + latex_eq(w_l, omega_leave)),
        Step("G's speed away from the wall then (θ̇ < 0 while it falls)",
             latex_eq(v_l, speed_l)),
        Step("Time to leave: dt = dθ / |θ̇|, in units of √(L/g) (an elliptic integral, by quadrature)",
             latex_eq(tau_1, time_1, order="rev-lex") + r",\quad t_\ell = \tau_1 \sqrt{L/g}"),
        Step(r"After leaving no horizontal force acts: $\dot x_G$ stays at its value; the foot stays on the floor, "
             r"so $y_G = (L/2)\sin\theta$ still; energy from the moment of leaving",
             latex(energy2, order="rev-lex") + r"\;\Rightarrow\;" + latex_eq(thetadot**2, rate2_sq, order="rev-lex")),
        Step("Flat on the floor, θ = 0", latex_eq(w_f, omega_f)),
        Step("Time from leaving to the floor, in units of √(L/g) with ω̂₂ = |θ̇| √(L/g) from the energy "
             "above (by quadrature)", latex_eq(tau_2, time_2) + r",\quad t_f = t_\ell + \tau_2 \sqrt{L/g}"),
    ]
    chain = [
        Result("theta_leave", th_l, leave_angle, "angle"),
        Result("omega_leave", w_l, omega_leave, "angular_speed"),  # (the numbers put in where Step 4 shows it)
        Result("vx_leave", v_l, speed_l, "speed"),
        Result("t_leave", t_l, tau_1 * sp.sqrt(L / g), "time"),
        Result("omega_floor", w_f, omega_f, "angular_speed"),
        Result("t_floor", t_f, t_l + tau_2 * sp.sqrt(L / g), "time"),
        Result("N_wall0", N_A0, wall_0, "force"),
        Result("N_floor0", N_B0, floor_0, "force"),
    ]
    symbols = SYMBOLS | TIME_INTEGRALS
    derived = Derivation(symbols, DIMENSIONS, steps, chain, {a.name: a.label for a in ANSWERS})
    rates = {"phase1": ((theta, theta0), rate_sq.subs({g: 1, L: 1})),
             "phase2": ((theta, th_l, w_l, v_l), rate2_sq.subs({g: 1, L: 1}))}
    return derived, rates


def derivation_of(solution: Solution) -> Derivation:
    """The derivation behind ``solution`` (one for every parameter set)."""
    return derivation()[0]


# --------------------------------------------------------------------------------------------
# The times: quadratures in units of sqrt(L/g), as functions of θ0 alone


def _falling_time(start: float, end: float) -> float:
    """∫ dθ / √(3 (sin θ0 − sin θ)) from ``end`` up to ``start`` = θ0 (released at rest there).

    With θ = θ0 − u² the endpoint's 1/√ singularity goes (sin θ0 − sin θ = 2 cos(θ0 − u²/2) sin(u²/2)
    is written without cancellation); near upright the integrand peaks over u ≲ √cos θ0, where
    quad is told to look."""
    def integrand(u: float) -> float:
        if u == 0.0:
            return 2.0 / math.sqrt(3.0 * math.cos(start))
        return 2.0 * u / math.sqrt(6.0 * math.cos(start - u * u / 2) * math.sin(u * u / 2))

    top = math.sqrt(start - end)
    peak = min(math.sqrt(math.cos(start)), top / 2)
    value, _ = quad(integrand, 0.0, top, points=[peak], limit=200, epsabs=0.0, epsrel=1e-12)
    return value


@functools.lru_cache(maxsize=1024)
def time_integrals(theta_0: float) -> dict[str, float]:
    """τ₁ (release to leaving), τ₂ (leaving to flat) and τ_held (release to flat if the wall held)."""
    _, rates = derivation()
    leave = math.asin(2.0 / 3.0 * math.sin(theta_0))
    w_leave = math.sqrt(rates["phase1"](leave, theta_0))
    v_leave = 0.5 * math.sin(leave) * w_leave
    phase2 = lambda q: 1.0 / math.sqrt(rates["phase2"](q, leave, w_leave, v_leave))  # noqa: E731
    tau2, _ = quad(phase2, 0.0, leave, epsabs=0.0, epsrel=1e-12, limit=200)
    return {"tau_1": _falling_time(theta_0, leave), "tau_2": tau2, "tau_held": _falling_time(theta_0, 0.0)}


# --------------------------------------------------------------------------------------------
# The second method: Newton–Euler, integrated (units m = g = L = 1)


def _newton_euler(s, c, w, one, zero, wall: bool) -> tuple[list, list]:
    """The rows and right-hand side of m a_G = ΣF, I_G α = ΣM_G and the contacts' kinematics (A on the
    wall, B on the floor) for the unknowns [ẍ_G, ÿ_G, θ̈, N_B, N_A] in units m = g = L = 1, at
    sin θ = s, cos θ = c, θ̇ = w (numbers, arrays or symbols). θ is the rod's angle from the floor, so
    its anticlockwise rotation is −θ̇. Without the wall, N_A and its kinematic row go."""
    rows = [
        [one, zero, zero, zero, -one],            # m ẍ = N_A
        [zero, one, zero, -one, zero],            # m ÿ = N_B − m g
        [zero, zero, one / 12, c / 2, -s / 2],    # I_G θ̈ = (L/2)(N_A sin θ − N_B cos θ)
        [zero, one, -c / 2, zero, zero],          # B on the floor: y_G = (L/2) sin θ
        [one, zero, s / 2, zero, zero],           # A on the wall: x_G = (L/2) cos θ
    ]
    rhs = [zero, -one, zero, -s * w * w / 2, -c * w * w / 2]
    if not wall:
        return [row[:4] for row in rows[:4]], rhs[:4]
    return rows, rhs


def reactions_and_accelerations(state, wall: bool) -> np.ndarray:
    """[ẍ_G, ÿ_G, θ̈, N_B, N_A] (N_A only with the wall), the Newton–Euler system solved numerically
    as one linear system. ``state`` may also be many states (one per row): one system each, solved
    together (one row per result)."""
    if np.ndim(state) == 2:
        th, w = np.asarray(state, dtype=float)[:, 2], np.asarray(state, dtype=float)[:, 5]
        rows, rhs = _newton_euler(np.sin(th), np.cos(th), w, np.ones_like(th), np.zeros_like(th), wall)
        matrices = np.moveaxis(np.array(rows, dtype=float), -1, 0)  # state, row, column
        return np.linalg.solve(matrices, np.array(rhs, dtype=float).T[..., None])[..., 0]
    th, w = state[2], state[5]
    rows, rhs = _newton_euler(math.sin(th), math.cos(th), w, 1.0, 0.0, wall)
    return np.linalg.solve(np.array(rows, dtype=float), np.array(rhs))


@functools.cache
def _newton_euler_solved(wall: bool) -> tuple[tuple[sp.Symbol, sp.Symbol], list]:
    """The same linear system solved once by sympy (Gaussian elimination on the symbols): (θ, θ̇) and
    [ẍ_G, ÿ_G, θ̈, N_B, N_A] as expressions in them (units m = g = L = 1; N_A only with the wall)."""
    th, w = sp.symbols("theta omega")
    rows, rhs = _newton_euler(sp.sin(th), sp.cos(th), w, sp.Integer(1), sp.Integer(0), wall)
    return (th, w), [sp.simplify(e) for e in sp.Matrix(rows).LUsolve(sp.Matrix(rhs))]


@functools.cache
def _solved_in_closed_form(wall: bool, xp=math):
    """``_newton_euler_solved`` as a plain function of (θ, θ̇): the integrator calls it a few hundred
    times per release angle, where solving the 5 × 5 system numerically each time cost most of the
    integration. ``xp``: the functions it is written with (math here; numpy, or solvers.live's symbols for
    the browser's integration)."""
    symbols, solved = _newton_euler_solved(wall)
    if xp is math:
        return sp.lambdify(symbols, solved, "math", cse=True)
    return sp.lambdify(symbols, solved, [{"sin": xp.sin, "cos": xp.cos}])


def accelerations_and_reactions(p, y, xp=np) -> list:
    """[ẍ_G, ÿ_G, θ̈, N_B, N_A] in SI at the state ``y`` (by ``INTEGRATED``'s names): against the wall
    while ``y["wall"]`` is 1, on the floor alone once it is 0 (N_A then 0)."""
    rate, g, L = xp.sqrt(p["g"] / p["L"]), p["g"], p["L"]
    held = _solved_in_closed_form(True, xp)(y["theta"], y["omega"] / rate)
    free = [*_solved_in_closed_form(False, xp)(y["theta"], y["omega"] / rate), 0.0]
    scales = (g, g, g / L, p["m"] * g, p["m"] * g)
    return [(y["wall"] * a + (1 - y["wall"]) * b) * k for a, b, k in zip(held, free, scales)]


def _rates(wall: bool):
    accelerations = _solved_in_closed_form(wall)

    def f(_t, y):
        a = accelerations(y[2], y[5])
        return [y[3], y[4], y[5], a[0], a[1], a[2]]
    return f


def _horizon_units(closest, xp=math):
    """The longest a phase may last, in units of √(L/g), for a release ``closest`` rad from flat or upright
    (the nearer, the slower the start)."""
    return 100.0 + 10 * xp.log(1 / closest)


GRID = 48  # the compiled integrator's output points over a phase's expected length
RTOL = 1e-12  # (LSODA at 1e-11 put the events 1e-10 off the quadratures; DOP853 had 1e-12)


@functools.lru_cache(maxsize=256)
def integrated(theta_0: float) -> dict:
    """Release to landing by Newton–Euler: phase 1 until N_A = 0 (an event), phase 2 until θ = 0.
    Returns the leaving and landing states, the start's reactions and each phase as a function of time
    (``phase1(t)``, ``phase2(t)``: the state at t, or the states at an array of instants, one per column)."""
    start = np.array([0.5 * math.cos(theta_0), 0.5 * math.sin(theta_0), theta_0, 0.0, 0.0, 0.0])
    closest = min(theta_0, math.pi / 2 - theta_0)
    atol = np.array([1e-14, 1e-14, 1e-14 * closest, 1e-14, 1e-14, 1e-14 * closest])
    on_wall = _solved_in_closed_form(True)
    horizon = _horizon_units(closest)
    expected = time_integrals(theta_0)  # (sizes the work only: the integration alone finds each event)
    t1, y1 = _until(True, 0.0, start, lambda y: on_wall(y[2], y[5])[4], expected["tau_1"], horizon, atol)
    t2, y2 = _until(False, t1, y1, lambda y: y[2], expected["tau_2"], horizon, atol)
    first = reactions_and_accelerations(start, True)
    return {"t_leave": t1, "leave": y1, "t_floor": t2, "floor": y2, "N_wall0": first[4], "N_floor0": first[3],
            "phase1": _along(True, (0.0, start), (t1, y1), atol), "phase2": _along(False, (t1, y1), (t2, y2), atol)}


def _until(wall: bool, t0: float, y0, ends, expected: float, horizon: float, atol) -> tuple[float, np.ndarray]:
    """One phase from (t0, y0) until ``ends`` (of the state: positive at the start) falls through zero: the
    compiled LSODA (odeint) over a grid of GRID instants, the first a little past ``expected``, then as long
    again, until ``ends`` changes sign between two of them; the crossing itself by DOP853 with the event
    over that interval. The instant and the state there."""
    rates = _rates(wall)
    span = 1.05 * expected if 0 < expected < horizon else horizon / 10
    t_start, y_start = t0, np.asarray(y0, dtype=float)
    while t_start < t0 + horizon:
        grid = np.linspace(t_start, min(t_start + span, t0 + horizon), GRID)
        states = odeint(rates, y_start, grid, rtol=RTOL, atol=atol, tfirst=True)
        crossed = next((k for k in range(1, GRID) if ends(states[k]) <= 0), None)
        if crossed is not None:
            def event(_t, y):
                return ends(y)
            event.terminal, event.direction = True, -1
            last = solve_ivp(rates, (grid[crossed - 1], grid[crossed]), states[crossed - 1], events=event,
                             method="DOP853", rtol=RTOL, atol=atol)
            if last.t_events[0].size:
                return float(last.t_events[0][0]), last.y_events[0][0]
            return float(grid[crossed]), states[crossed]  # (on the grid point itself)
        t_start, y_start = grid[-1], states[-1]
    raise RuntimeError("the phase never ended")  # pragma: no cover


def _along(wall: bool, begin, end, atol):
    """The phase from ``begin`` to ``end`` (each an instant and the state there) as a function of time: the
    state at ``times`` (a number: one state; an array: one state per column, as scipy's dense solutions
    give them), integrated to them by odeint; at ``end``'s instant, the event's own state (where the top
    leaves the wall, its push is zero there, not a rounding below it)."""
    t0, y0 = begin
    rates = _rates(wall)

    def at(times):
        t = np.atleast_1d(np.asarray(times, dtype=float))
        order = np.argsort(t, kind="stable")
        states = odeint(rates, y0, np.concatenate([[t0], t[order]]), rtol=RTOL, atol=atol, tfirst=True)[1:]
        out = np.empty_like(states)
        out[order] = states
        out[t == end[0]] = end[1]
        return out.T if np.ndim(times) else out[0]
    return at


# The same two phases integrated in the browser (ui/live.py), in SI, the state (G, θ, their rates) and
# whether the top is still against the wall (1, then 0: the rates and reactions of that phase).
_LEAVES = Leg("leave", ends=lambda p, a, y, xp: accelerations_and_reactions(p, y, xp)[4], framed=True,
              then=lambda p, a, y, xp: {**y, "wall": 0.0})
_LANDS = Leg("land", ends=lambda p, a, y, xp: y["theta"])


def _horizon(p, a, xp=np):
    """Each phase's longest time in s (``integrated``'s, in units of √(L/g))."""
    return _horizon_units(xp.minimum(p["theta0"], math.pi / 2 - p["theta0"]), xp) * xp.sqrt(p["L"] / p["g"])


def _rates_of_state(p, a, y, xp):
    ddx, ddy, ddth = accelerations_and_reactions(p, y, xp)[:3]
    return {"x_G": y["vx_G"], "y_G": y["vy_G"], "theta": y["omega"], "vx_G": ddx, "vy_G": ddy, "omega": ddth,
            "wall": 0.0}


# --------------------------------------------------------------------------------------------


def _validate(params) -> dict:
    p = validate_params(PARAMS, params)
    closest = min(p["theta0"], math.pi / 2 - p["theta0"])
    if closest < CLOSEST_TO_REST:
        lowest = plain_number(math.degrees(CLOSEST_TO_REST), 2)
        raise OutOfModelRangeError(
            f"theta0 (release angle from the floor) is closer than {lowest}° to lying flat (0°) or to standing "
            "upright (90°): the motion is too small, or its start too slow, for the model's arithmetic. Use an "
            f"angle from {lowest}° to {plain_number(90 - math.degrees(CLOSEST_TO_REST), 8)}°.")
    return p



def _live_cases() -> tuple[Case, ...]:
    """One regime; the two times need quadratures (τ₁, τ₂), so the browser leaves them to the server."""
    return (Case("", "", derivation()[0]),)


# Live while dragging (solvers/live.py): the release angle and the length; not the times.
LIVE = Live(("theta0", "L"), _live_cases)

@within_model_range
def solve(**params) -> Solution:
    p = _validate(params)
    chain, _ = derivation()
    integrals = time_integrals(p["theta0"])
    values = chain.evaluate(p | integrals)
    answers = {a.name: values[a.name] for a in ANSWERS}
    if not all(math.isfinite(v) and v < 1e300 for v in answers.values()):
        raise OverflowError("an answer overflows")
    steps = (*chain.steps,
             Step("With your numbers: the two time integrals (quadrature)",
                  rf"\tau_1 = {latex_number(integrals['tau_1'], 6)},\quad \tau_2 = {latex_number(integrals['tau_2'], 6)}",  # (as put in below)
                  numeric=True),
             *chain.numeric_steps(values))
    notes = (f"The top leaves the wall at θ = {plain_number(math.degrees(answers['theta_leave']))}°, two-thirds of "
             f"its initial height; from then on only the floor pushes.",)
    return Solution("sliding_ladder", p, answers, steps, _checks(p, answers), notes=notes,
                    extras={"chain_inputs": integrals})


def _checks(p, a) -> tuple[Check, ...]:
    """Each answer against the Newton–Euler integration (scaled from m = g = L = 1), and the energy
    at landing, from the answers, against the potential energy released."""
    run = integrated(p["theta0"])
    time, rate, speed, force = (math.sqrt(p["L"] / p["g"]), math.sqrt(p["g"] / p["L"]), math.sqrt(p["g"] * p["L"]),
                                p["m"] * p["g"])
    rel = 1e-6
    pairs = [
        (r"$\theta_\ell$: $\theta$ at the event $N_A = 0$, integrating $m\mathbf{a}_G = \sum\mathbf{F}$, $I_G\ddot\theta = \sum M_G$", "theta_leave", run["leave"][2], 1.0),
        (r"$\lvert\dot\theta_\ell\rvert$ at that event", "omega_leave", -run["leave"][5], rate),
        (r"$\dot x_G$ at that event", "vx_leave", run["leave"][3], speed),
        (r"$t_\ell$: the time of that event", "t_leave", run["t_leave"], time),
        (r"$\lvert\dot\theta_f\rvert$: integrating on with the floor alone to $\theta = 0$", "omega_floor", -run["floor"][5], rate),
        (r"$t_f$: the time at $\theta = 0$", "t_floor", run["t_floor"], time),
        (r"$N_{A0}$: the force and moment balance at release, solved as one linear system", "N_wall0", run["N_wall0"], force),
        (r"$N_{B0}$: the same linear system", "N_floor0", run["N_floor0"], force),
    ]
    checks = [Check(label, a[name], value * scale, relative_tolerance(a[name], rel))
              for label, name, value, scale in pairs]
    released = p["m"] * p["g"] * p["L"] / 2 * math.sin(p["theta0"])
    landed = p["m"] * a["vx_leave"] ** 2 / 2 + p["m"] * p["L"] ** 2 * a["omega_floor"] ** 2 / 6
    checks.append(Check(r"energy: $\tfrac12 m\dot x_G^2 + \tfrac12 (mL^2/4 + mL^2/12)\,\dot\theta_f^2$ on landing vs $m g (L/2)\sin\theta_0$ released",
                        landed, released, relative_tolerance(released, 1e-9),
                        "the smooth wall and floor do no work"))
    return tuple(checks)


# --------------------------------------------------------------------------------------------
# The motion the figures draw


FRAMES = 90
CURVE_POINTS = 90  # (the reactions' plot: smooth curves, the leaving instant one of the samples)
# (the path of G is drawn through the frames: the browser traces it at the same instants)
INTEGRATED = Integrated(
    state=("x_G", "y_G", "theta", "vx_G", "vy_G", "omega", "wall"),
    start=lambda p, a, xp: {"x_G": p["L"] / 2 * xp.cos(p["theta0"]), "y_G": p["L"] / 2 * xp.sin(p["theta0"]),
                            "theta": p["theta0"], "vx_G": 0.0, "vy_G": 0.0, "omega": 0.0, "wall": 1.0},
    rates=_rates_of_state, legs=(_LEAVES, _LANDS), horizon=_horizon, frames=FRAMES, curve=FRAMES,
    tolerances=(1e-12, 1e-12))


@per_solution
def motion(solution: Solution) -> dict:
    """Both phases from the integration, scaled to SI: frames evenly in time (one exactly at the
    leaving), the contacts' positions, the reactions at the frames (their arrows) and, for their plot, evenly
    in each phase (the last on the wall at the leaving). The browser integrates the same frames itself on the lesson page (``INTEGRATED``)."""
    p = solution.params
    T, mg, L_ = math.sqrt(p["L"] / p["g"]), p["m"] * p["g"], p["L"]
    frames, states, curve_t, walls, floors, t1, frame_walls, frame_floors = _sampled(p["theta0"])
    x_G, y_G, th = states[:, 0] * L_, states[:, 1] * L_, states[:, 2]
    return {
        "t": frames * T, "theta": th, "x_G": x_G, "y_G": y_G,
        "x_A": x_G - L_ / 2 * np.cos(th), "y_A": y_G + L_ / 2 * np.sin(th),
        "x_B": x_G + L_ / 2 * np.cos(th), "y_B": y_G - L_ / 2 * np.sin(th),
        "curve_t": curve_t * T, "N_wall": walls * mg, "N_floor": floors * mg,
        "frame_N_wall": frame_walls * mg, "frame_N_floor": frame_floors * mg,
        "t_leave": t1 * T, "leave_frame": int(np.argmin(np.abs(frames - t1))),
    }


@functools.lru_cache(maxsize=256)
def _sampled(theta_0: float) -> tuple:
    """The integration sampled for the figures in units m = g = L = 1 (a function of θ₀ alone,
    shared by every L, m and g): frame times, states, the reactions' times and values, t_leave, and
    the reactions at the frames. Read only (the arrays are shared)."""
    run = integrated(theta_0)
    t1, t2 = run["t_leave"], run["t_floor"]
    frames = frame_instants(0.0, t2, FRAMES, [t1])
    # the reactions' plot: evenly in each phase, the leaving instant ending the first (so each phase's curve
    # is its values, its first instant and its step: viz/sliding_ladder.py sends no instants)
    held = min(max(2, round(CURVE_POINTS * t1 / t2)), CURVE_POINTS - 1)
    curve_t = np.concatenate([np.linspace(0.0, t1, held), np.linspace(t1, t2, CURVE_POINTS - held + 1)[1:]])
    # both sets of instants in one integration of each phase (``integrated``'s phase1, phase2)
    times = np.concatenate([frames, curve_t])
    on_wall = times <= t1
    states, walls, floors = np.empty((len(times), 6)), np.zeros(len(times)), np.empty(len(times))
    if on_wall.any():
        states[on_wall] = run["phase1"](times[on_wall]).T
        held_reactions = reactions_and_accelerations(states[on_wall], True)
        walls[on_wall], floors[on_wall] = held_reactions[:, 4], held_reactions[:, 3]
    if (~on_wall).any():
        states[~on_wall] = run["phase2"](times[~on_wall]).T
        floors[~on_wall] = reactions_and_accelerations(states[~on_wall], False)[:, 3]
    n = len(frames)
    frame_walls, frame_floors, walls, floors, states = walls[:n], floors[:n], walls[n:], floors[n:], states[:n]
    for array in (frames, states, curve_t, walls, floors, frame_walls, frame_floors):
        array.flags.writeable = False
    return frames, states, curve_t, walls, floors, t1, frame_walls, frame_floors


# --------------------------------------------------------------------------------------------
# Practice: the typical slips, in the derivation's own symbols

HELD = ("That is the ladder held against the wall all the way down. The wall can only push: its push "
        "reaches zero at sin θ = ⅔ sin θ₀, the top leaves the wall, and from then on ẋ_G stays constant.")
I_G_FOR_I_C = ("I_G = mL²/12 is the inertia about G, but G moves too: the ladder turns about its "
               "instantaneous centre C (L/2 from G), so T = ½ (mL²/3) θ̇², i.e. ½ m v_G² + ½ I_G θ̇².")

MISTAKES = (
    Mistake("omega_floor", HELD, lambda p: sp.sqrt(3 * g * sp.sin(theta0) / L)),
    Mistake("t_floor", HELD, lambda p: tau_held * sp.sqrt(L / g)),
    Mistake("omega_leave", I_G_FOR_I_C, lambda p: sp.sqrt(12 * g / L * (sp.sin(theta0) - sp.sin(th_l)))),
    Mistake("omega_floor", I_G_FOR_I_C, lambda p: sp.sqrt(12 * g * sp.sin(theta0) / L)),
    Mistake("theta_leave", "Two-thirds of the height, not of the angle: the top leaves where sin θ = ⅔ sin θ₀.",
            lambda p: sp.Rational(2, 3) * theta0),
    Mistake("vx_leave", "That is the foot's speed, L sin θ |θ̇|: G is at the middle of the ladder.",
            lambda p: L * sp.sin(th_l) * w_l),
    Mistake("N_wall0", "That is the static balance, but on a smooth wall and floor the ladder cannot stand: "
            "at release it accelerates, and the wall's push is m ẍ_G.",
            lambda p: m * g * sp.cos(theta0) / (2 * sp.sin(theta0))),
    Mistake("N_floor0", "The floor carries less than the weight at release: G accelerates downward, so "
            "N_B = m (g + ÿ_G) with ÿ_G < 0.", lambda p: m * g),
)
