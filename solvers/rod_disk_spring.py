"""A rod and disk fall against a torsional spring (Hibbeler 18-9, "the O'Reilly way").

Model: slender rod (m1, length L) pinned at a fixed, frictionless pivot O where a linear torsional
spring (stiffness k, untwisted at θ = 0) acts; a uniform disk (m2, radius R) is attached at the
rod's far end, its centre a distance L + R from O. θ is measured from the upward vertical; the
assembly is released from rest at θ1 and falls (θ increasing). disk = "welded": the disk turns with
the rod; "pinned": it rides on a frictionless pin and does not rotate, so only its translation
carries kinetic energy. The pivot does no work; gravity and the spring do.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp
from scipy.optimize import brentq

from .kept import kept_pickled
from .core import (
    within_model_range,
    plain_number,
    Answer,
    Check,
    Choice,
    Derivation,
    Number,
    PhysicalLimitError,
    Result,
    Solution,
    Step,
    latex,
    latex_eq,
    presentable,
    relative_tolerance,
    require,
    validate_params,
    per_solution,
)
from .diagram import Body, DiagramSlip, Circle, Diagram, Load, Rod, balance, balance_steps, fbd_steps
from .live import Case, Integrated, Leg as Phase, Live, Stops, frame_instants
from .protocol import About, Mistake, Variants
from .swing import Leg, crossing_time, drawn_to_turn, hermite_on_knots, integrate_leg, quintic, slope

ABOUT = About(
    title="Rod and disk on a torsional spring",
    group="Work–energy",
    blurb="Gravity pulls, the spring resists: how fast is it turning at θ₂?",
    icon=":material/rotate_right:",
    source="Hibbeler 18-9",
    primary=("k", "theta2", "disk"),  # always shown; the rest sit behind "More parameters"
)

PARAMS = (
    Number("m1", 6.0, "rod mass", "mass", "m_1", low=0, ui_low=0.1, ui_high=30.0, step=0.1),
    Number("m2", 9.0, "disk mass", "mass", "m_2", low=0, ui_low=0.1, ui_high=30.0, step=0.1),
    Number("k", 20.0, "spring stiffness", "stiffness", "k", low=0, low_inclusive=True, ui_low=0.0,
           ui_high=100.0, step=1.0),  # (the defaults reach θ₂ up to k ≈ 48 N/m)
    Number("L", 0.45, "rod length", "length", "L", low=0, ui_low=0.05, ui_high=2.0, step=0.01),
    Number("R", 0.075, "disk radius", "length", "R", low=0, ui_low=0.01, ui_high=0.5, step=0.005),
    Number("theta1", 0.0, "release angle from the upward vertical", "angle", r"\theta_1", low=0,
           high=2 * math.pi, low_inclusive=True, ui_low=0, ui_high=359, step=1.0,
           help="0 is upright: read it as released with a nudge."),
    Number("theta2", math.pi / 2, "angle at which the speed is wanted", "angle", r"\theta_2", low=0,
           high=2 * math.pi, ui_low=1, ui_high=359, step=1.0),
    Number("g", 9.81, "gravity", "acceleration", "g", low=0, ui_low=0.5, ui_high=30.0, step=0.01),
    Choice("disk", "welded", "how the disk is attached", ("welded", "pinned"),
           ("welded: turns with the rod (the worked solution)", "pinned: free to spin, so it does not rotate")),
)

ANSWERS = (
    Answer("omega2", "angular speed at θ₂", r"\lvert\dot\theta_2\rvert", "angular_speed"),
    Answer("I_O", "moment of inertia about O (of what turns)", r"I_O", "inertia"),
    Answer("T2", "kinetic energy at θ₂", r"T_2", "energy"),
    Answer("U_gravity", "work done by gravity", r"U_g", "energy"),
    Answer("U_spring", "work done by the spring", r"U_s", "energy"),
)

ERRATA = (
    r"The worked solution's kinetic-energy line has $\tfrac14 m_1 L^2\dot\theta^2$ for the rod's centre's motion, "
    r"$\tfrac12 m_1 v_{G_1}^2$; with $v_{G_1} = (L/2)\dot\theta$ it is $\tfrac18 m_1 L^2\dot\theta^2$ (its turning "
    r"adds $\tfrac12 I_{G,1}\dot\theta^2 = \tfrac1{24} m_1 L^2\dot\theta^2$: the rod's $\tfrac16 m_1 L^2\dot\theta^2$ in all).",
    r"The worked solution writes the disk's $I_G$ as $\tfrac12 m_2 B^2$ with $B = L + R$; it is "
    r"$\tfrac12 m_2 R^2$.",
    r"The spring work is evaluated at $\theta_2 = \pi/8$ in one line; it is $\pi/2$ "
    r"($U_s = -k\pi^2/8$, as the worked solution's number $-24.67$ J says).",
    r"The worked solution's $\mathbf{X}_2$ has a sign flip; its numbers ($T = 1.455\,\dot\theta^2$, "
    r"4.90 rad/s) are right.",
)

m1, m2, k, L, R, g = sp.symbols("m_1 m_2 k L R g", positive=True)
theta, theta1, theta2 = sp.symbols(r"theta theta_1 theta_2", real=True)
thetadot = sp.Symbol(r"\dot{\theta}", real=True)
I_O, U_g, U_s, T2, w2 = sp.symbols(r"I_O U_g U_s T_2 |\dot{\theta}_2|", real=True)
SYMBOLS = {"m1": m1, "m2": m2, "k": k, "L": L, "R": R, "g": g, "theta1": theta1, "theta2": theta2}
DIMENSIONS = {p.name: p.dimension for p in PARAMS if isinstance(p, Number)}

NUDGE = 1e-6  # rad/s: the push that starts a release at or near upright in the integration
NEAR_UPRIGHT = 1e-3  # rad: below this release angle the integration starts with the nudge
ESCAPE = 1e-4  # rad: how far a nudged release follows its linearised motion before integrating


class SpringStopsRodError(PhysicalLimitError):
    """The spring stops the assembly before θ2; ``theta_max`` is the largest angle reached."""


# What a PhysicalLimitError's attribute is, for the page that shows it: (label, dimension).
LIMIT_LABELS = {"theta_max": ("largest angle the rod reaches", "angle")}


# ---------------------------------------------------------------------------------------------
# Step 2: the rod and disk isolated together from the pin O and the spring, in the stage's coordinates
# (viz/rod_disk_spring.py and ``motion``: O at the origin, x horizontal, y up; θ from the upward vertical
# toward +x, so θ grows clockwise and the anticlockwise (E_z) angular acceleration is −θ̈). The spring's
# couple on the rod opposes its twist: −kθ in θ's sense, +kθ about E_z.

thetaddot = sp.Symbol(r"\ddot{\theta}", real=True)
O_x, O_y = sp.symbols("O_x O_y", real=True)
_MASS = m1 + m2
_ARM = m1 * L / 2 + m2 * (L + R)  # Σ m_i ρ_i: the mass times G's distance from O


def _points() -> dict:
    """O, the rod's centre G_1, the mass centre G, the rod's end A and the disk's centre G_2, at θ."""
    along = lambda rho: (rho * sp.sin(theta), rho * sp.cos(theta))  # noqa: E731  a point of the rod's line
    return {"O": (0, 0), "G_1": along(L / 2), "G": along(_ARM / _MASS), "A": along(L), "G_2": along(L + R)}


def _swing_values_at(p, inertia: float, theta_, omega_, xp=np) -> dict:
    """The symbols at θ, θ̇ (numbers, or arrays of a frame each): θ̈ from the solver's equation of motion
    (``equation_of_motion``, as ``simulate`` integrates it: I_O θ̈ = Q sin θ − kθ with Q = ``weight_moment``),
    the pin's components from the two force laws, (m₁ + m₂) a_G less the weights (the solver has no
    formula for them: the moment law about O, against the solver's θ̈, is the independent check)."""
    alpha = (weight_moment(p) * xp.sin(theta_) - p["k"] * theta_) / inertia
    arm = weight_moment(p) / p["g"]  # Σ m_i ρ_i = (m₁ + m₂) × G's distance from O
    ax = arm * (xp.cos(theta_) * alpha - xp.sin(theta_) * omega_**2)
    ay = arm * (-xp.sin(theta_) * alpha - xp.cos(theta_) * omega_**2)
    return {m1: p["m1"], m2: p["m2"], k: p["k"], L: p["L"], R: p["R"], g: p["g"], I_O: inertia, theta: theta_,
            thetadot: omega_, thetaddot: alpha, O_x: ax, O_y: ay + (p["m1"] + p["m2"]) * p["g"]}


def _swing_values(solution) -> dict:
    """Passing θ₂ on the fall, where the speed is asked for: θ̇ = +|θ̇₂|, the answer (``motion`` has a frame
    there, at the same numbers)."""
    p, a = solution.params, solution.answers
    return _swing_values_at(p, a["I_O"], p["theta2"], a["omega2"])


def _swing_key(p, a) -> dict:
    """At the stage's key frame, passing θ₂ (as ``_swing_values``)."""
    return _swing_values_at(p, a["I_O"], p["theta2"], a["omega2"], xp=sp)


def _swing_frames(solution, motion) -> dict:
    angles, rates = np.asarray(motion["theta"], dtype=float), np.asarray(motion["omega"], dtype=float)
    values = _swing_values_at(solution.params, solution.answers["I_O"], angles, rates)
    return {s: np.broadcast_to(np.asarray(v, dtype=float), angles.shape).copy() for s, v in values.items()}


@functools.cache
def swing_diagram(disk: str) -> Diagram:
    """The rod and disk during the fall (the disk welded, or pinned and not turning)."""
    body = Body("the rod and disk", points=_points(), centre="G", about="O",
                kinetic=(_ARM * (sp.cos(theta) * thetaddot - sp.sin(theta) * thetadot**2),
                         _ARM * (-sp.sin(theta) * thetaddot - sp.cos(theta) * thetadot**2), -I_O * thetaddot),
                kinetic_latex=(r"(m_1 + m_2)\,\ddot{x}_G", r"(m_1 + m_2)\,\ddot{y}_G", r"-I_O\ddot{\theta}"),
                outline=(Rod(("O", "A")), Circle("G_2", R)))
    loads = (Load("m_1 g", "the rod's weight", "gravity", "the rod and disk", at="G_1", direction=(0, -1), size=m1 * g),
             Load("m_2 g", "the disk's weight", "gravity", "the rod and disk", at="G_2", direction=(0, -1), size=m2 * g),
             Load(r"k\theta", "the spring's couple", "the torsional spring", "the rod and disk", at="O", kind="couple",
                  size=k * theta),
             Load("O", "the pin's reaction", "the pin", "the rod and disk", at="O", components=(O_x, O_y)))
    if disk == "pinned":
        note = ("Rod and disk are isolated together: the frictionless pin at $G_2$ between them is internal and "
                "exerts no moment about $G_2$, so the disk's spin does not change (it does not turn): it counts "
                "as its mass at $G_2$ alone, its own $I_G$ drops out of $I_O$.")
    else:
        note = "The disk is welded to the rod: one rigid body, turning about O at θ̇."
    return Diagram("swing", "During the fall", "force", (body,), loads, _swing_values, frames=_swing_frames,
                   key=_swing_key, note=note)


def free_body_diagrams(params) -> tuple[Diagram, ...]:
    """The fall's diagram for this disk (drawn passing θ₂)."""
    return (swing_diagram(params["disk"]),)


# The classic slips in drawing this diagram (practice/diagram_judge.py), as MISTAKES are the answers':
# each a load the physics does not put there, with a tutor's words that never show the diagram.
DIAGRAM_SLIPS = (
    DiagramSlip("centripetal force", "a centripetal force is not a force of its own: it is what the real forces' "
                "components toward O add up to.", at="G", direction=(-sp.sin(theta), -sp.cos(theta))),
    DiagramSlip("force of motion", "no force carries the body along its velocity: the weights, the spring and the "
                "pin are all that act on it.", at="G", direction=(sp.cos(theta), -sp.sin(theta)), either_way=True),
)



@functools.cache
@kept_pickled
def derivation(disk: str) -> Derivation:
    diagram = swing_diagram(disk)
    points = diagram.body("the rod and disk").points
    x1, x2 = sp.Matrix(points["G_1"]), sp.Matrix(points["G_2"])  # the centres of mass, as the diagram places them
    v1, v2 = sp.diff(x1, theta) * thetadot, sp.diff(x2, theta) * thetadot
    I_G1, I_G2 = m1 * L**2 / 12, m2 * R**2 / 2
    spin_disk = 1 if disk == "welded" else 0
    T = (m1 * v1.dot(v1) / 2 + I_G1 * thetadot**2 / 2
         + m2 * v2.dot(v2) / 2 + spin_disk * I_G2 * thetadot**2 / 2)
    T = sp.simplify(T)
    inertia = sp.factor_terms(sp.expand(sp.simplify(2 * T / thetadot**2)))
    # The works from the diagram's loads: each weight's force dotted with its point's displacement per
    # dθ, and the spring's couple in θ's sense (θ turns about E_z with the sign of r × ∂r/∂θ).
    rate = lambda name: sp.Matrix(points[name]).diff(theta)  # noqa: E731  ∂r/∂θ
    weights = [l for l in diagram.loads if l.by == "gravity"]
    work_gravity = sp.simplify(sp.integrate(
        sum(sp.Matrix(l.vector).dot(rate(l.at)) for l in weights), (theta, theta1, theta2)))
    work_gravity = sp.factor(work_gravity)
    tip = sp.Matrix(points["A"])
    sense = sp.sign(sp.simplify(tip[0] * rate("A")[1] - tip[1] * rate("A")[0]))  # −1: θ grows clockwise
    spring_moment = sense * next(l for l in diagram.loads if l.kind == "couple").size  # −kθ in θ's sense
    work_spring = sp.factor_terms(sp.integrate(spring_moment, (theta, theta1, theta2)))  # k(θ₁² − θ₂²)/2
    speed = sp.solve(sp.Eq(I_O * thetadot**2 / 2, T2), thetadot)
    speed = [s_ for s_ in speed if s_.subs({I_O: 1, T2: 1}).is_positive][0]
    # Step 3's moment law about O, −Σ M_O = I_O θ̈ in θ's sense, integrated from θ₁ (θ̈ dθ = θ̇ dθ̇) is the
    # work–energy equation: the same works.
    moment_law = balance(diagram, "the rod and disk")[2]
    presentable(sp.integrate(sense * moment_law.lhs, (theta, theta1, theta2)), work_gravity + work_spring)

    steps = [
        Step(r"Origin at the pin O; θ from the upward vertical, growing clockwise as the assembly falls; basis "
             r"$\mathbf{E}_x$ horizontal, $\mathbf{E}_y$ up, $\mathbf{E}_z$ out of the page. Centres of mass from O: "
             r"the rod's $G_1$ at L/2 and the disk's $G_2$ at L + R",
             r"\mathbf{x}_1 = " + latex(x1.T) + r",\quad \mathbf{x}_2 = " + latex(x2.T), part=1),
        Step("Their velocities, turning about O at θ̇", r"\dot{\mathbf{x}}_1 = " + latex(v1.T)
             + r",\quad \dot{\mathbf{x}}_2 = " + latex(v2.T), part=1),
        Step("Kinetic energy: translation of each centre plus rotation about it"
             + (" (the disk turns with the rod)" if disk == "welded" else
                r" (the pinned disk does not rotate: no $\tfrac12 I_G\dot\theta^2$ for it)"),
             latex_eq(sp.Symbol("T"), T) + r" = \tfrac12 I_O \dot\theta^2", part=1),
        Step("Hence the moment of inertia about O", latex_eq(I_O, inertia), part=1),
        *fbd_steps(diagram),
        *balance_steps(diagram),
        Step("Work of gravity from θ₁ to θ₂: ∫ F·dx for each weight",
             latex_eq(U_g, work_gravity)),
        Step("Work of the torsional spring: its couple ($k\\theta$ about $\\mathbf{E}_z$, $-k\\theta$ in θ's sense) times dθ, integrated",
             latex_eq(U_s, sp.Integral(spring_moment, (theta, theta1, theta2))) + " = " + latex(work_spring)),
        Step(r"Work–energy from rest, $T_2 - 0 = U_g + U_s$: the moment law about O integrated over θ "
             r"($\ddot\theta\,d\theta = \dot\theta\,d\dot\theta$)", latex_eq(T2, U_g + U_s)
             + r"\;\Rightarrow\;" + latex_eq(w2, speed)),
    ]
    chain = [
        Result("I_O", I_O, inertia, "inertia"),
        Result("U_gravity", U_g, work_gravity, "energy"),
        Result("U_spring", U_s, work_spring, "energy"),
        Result("T2", T2, U_g + U_s, "energy"),
        Result("omega2", w2, speed, "angular_speed"),
    ]
    return Derivation(SYMBOLS, DIMENSIONS, steps, chain, {a.name: a.label for a in ANSWERS})


def weight_moment(p) -> float:
    """Q with the gravity moment about O equal to Q sin θ: (m1 L/2 + m2 (L + R)) g."""
    return (p["m1"] * p["L"] / 2 + p["m2"] * (p["L"] + p["R"])) * p["g"]


def kinetic_energy_at(p, angles: np.ndarray | float) -> np.ndarray:
    """T(θ) = U_g + U_s from θ1 to θ, for released-from-rest motion (vectorised; a float gives a
    numpy scalar)."""
    Q, th1 = weight_moment(p), p["theta1"]
    return Q * (math.cos(th1) - np.cos(angles)) - p["k"] / 2 * (angles**2 - th1**2)


def largest_angle(p) -> float | None:
    """The angle at which the spring stops the fall, if it is reached before θ2, else None."""
    Q, th1, th2 = weight_moment(p), p["theta1"], p["theta2"]
    start_torque = Q * math.sin(th1) - p["k"] * th1
    if th1 == 0.0 and Q <= p["k"]:
        return th1  # upright is stable: a nudge does not make it fall
    if th1 > 0.0 and start_torque <= 0.0:
        return th1  # the spring already wins at release: it swings back, never past θ1
    return _first_stop(p, th1, th2, 4097)


def _first_stop(p, start: float, end: float, points: int) -> float | None:
    """The first angle after ``start`` (up to ``end``) where the kinetic energy is spent: found
    on a grid of ``points``, then to 1e-14 rad by Brent's method; None if there is none."""
    grid = np.linspace(start, end, points)
    stopped = np.nonzero(kinetic_energy_at(p, grid[1:]) <= 0.0)[0]
    if not len(stopped):
        return None
    i = stopped[0] + 1
    T = lambda q: float(kinetic_energy_at(p, q))  # noqa: E731
    return brentq(T, grid[i - 1], grid[i], xtol=1e-14) if T(grid[i - 1]) > 0 else float(grid[i])


def _validate(params) -> dict:
    p = validate_params(PARAMS, params)
    require(p["theta1"] < p["theta2"],
            f"θ₂ must be past the release angle θ₁ (θ₁ < θ₂); got θ₁ = {plain_number(math.degrees(p['theta1']))}°, "
            f"θ₂ = {plain_number(math.degrees(p['theta2']))}°.")
    return p



# What a drag past the limit says and the release's refusal opens with: one regime, the same words.
NEVER_UPRIGHT = "the rod never reaches θ₂: upright is stable, the spring holds it up (θ₁ = 0°)"
NEVER_SPRING_WINS = "the rod never reaches θ₂: at its release the spring already beats the weights and pushes it back"
NEVER_STOPS = "the rod never reaches θ₂: the spring stops it before and it swings back"


def _live_cases(disk: str) -> tuple[Case, ...]:
    """Where ``largest_angle`` finds the spring stopping the rod before θ₂ (the same three tests: at
    rest upright, the spring winning at release, and T(θ) ≤ 0 on the solver's grid, T(θ) being the
    chain's T₂ with θ₂ → θ), the limit; else the chain. Q, the weights' moment coefficient, is read
    off the chain's work of gravity."""
    d_ = derivation(disk)
    at = sp.Symbol("theta_at")
    energy_at = d_.expression_of("T2").subs(theta2, at)
    Q = sp.simplify(d_.expression_of("U_gravity") / (sp.cos(theta1) - sp.cos(theta2)))
    return (Case("upright", NEVER_UPRIGHT, when=sp.And(sp.Eq(theta1, 0), Q <= k), values=False),
            Case("spring_wins", NEVER_SPRING_WINS, when=sp.And(theta1 > 0, Q * sp.sin(theta1) - k * theta1 <= 0),
                 values=False),
            Case("stops", NEVER_STOPS, when=Stops(energy_at, at, theta1, theta2, 4097), values=False),
            Case(disk, "the rod reaches θ₂", d_))


# Live while dragging (solvers/live.py): the stiffness and the angle asked about.
LIVE = Live(("k", "theta2"), _live_cases)

@within_model_range
def solve(**params) -> Solution:
    p = _validate(params)
    stop = largest_angle(p)
    if stop is not None:
        if stop == p["theta1"] == 0.0:  # upright, both moments vanish: which grows faster near θ = 0 decides
            said, why = NEVER_UPRIGHT, (
                f"the spring's moment kθ grows faster than the weights' Q sin θ (k = {plain_number(p['k'])} N·m/rad "
                f"≥ Q = {plain_number(weight_moment(p))} N·m), so a nudge does not make it fall. Soften the spring "
                "below Q or release it further over")
        elif stop == p["theta1"]:
            said, why = NEVER_SPRING_WINS, (
                f"the spring's moment kθ already beats the weights' Q sin θ (Q = {plain_number(weight_moment(p))} N·m) "
                f"at θ₁ = {plain_number(math.degrees(stop))}°, the largest angle reached. Soften the spring or "
                "release it further over")
        else:
            said, why = NEVER_STOPS, (
                f"it stops at θ = {plain_number(math.degrees(stop))}° (the largest angle reached); ask for θ₂ below "
                "that, or soften the spring")
        raise SpringStopsRodError(f"{said[0].upper()}{said[1:]}. Asked for θ₂ = {plain_number(math.degrees(p['theta2']))}°: "
                                  f"{why}.", theta_max=stop)
    d_ = derivation(p["disk"])
    values = d_.evaluate(p)
    answers = {a.name: values[a.name] for a in ANSWERS}
    steps = list(d_.steps) + d_.numeric_steps(values)
    return Solution("rod_disk_spring", p, answers, tuple(steps), _checks(p, answers), p["disk"],
                    (f"Released at θ₁ = {plain_number(math.degrees(p['theta1']))}°"
                     + (" (upright: an equilibrium, so read it as released with a tiny nudge)."
                        if p["theta1"] == 0 else "."),))


def equation_of_motion(p, I: float):
    """θ̈(θ) for the integrator (``_acceleration``, its moments worked out once)."""
    Q, k_ = weight_moment(p), p["k"]
    return lambda q: _angular_acceleration(Q, k_, I, q, math)


def simulate(p, answers) -> Leg:
    """θ(t) from release until the swing turns: integrated to θ2 (the second method's leg), then
    drawn on to the turn from the energy integral; checks and animation share the legs."""
    to_theta2, beyond = _legs(tuple(sorted(p.items())) + (("I_O", answers["I_O"]),))
    if beyond is None:
        return to_theta2
    return Leg(np.concatenate([to_theta2.t, beyond.t[1:]]), np.concatenate([to_theta2.theta, beyond.theta[1:]]),
               np.concatenate([to_theta2.omega, beyond.omega[1:]]), beyond.ended_by_event)


@functools.lru_cache(maxsize=256)
def _legs(key: tuple):
    """(release → θ2 integrated, θ2 → turning point drawn from the energy integral, or integrated where it cannot
    be drawn or comes round near upright first), cached."""
    p = dict(key)
    acc = equation_of_motion(p, p["I_O"])
    horizon = 200 * math.sqrt(p["I_O"] / weight_moment(p)) + 10
    escape = _linear_escape(acc, p["theta1"], _start_rate(p))
    t0, q0, w0 = escape.end
    rate_squared = lambda q: 2 * kinetic_energy_at(p, q) / p["I_O"]  # noqa: E731  the first integral
    # One chunk, sized by the energy integral's estimate of the time to θ2, spares the integrator
    # its restarts; the estimate only sizes the work, the integration alone finds θ2.
    first = integrate_leg(acc, q0, w0, t0, horizon, stop_at_angle=p["theta2"], direction=1,
                          expected=crossing_time(rate_squared, q0, p["theta2"]))
    if len(escape.t) > 1:
        first = Leg(np.concatenate([escape.t, first.t[1:]]), np.concatenate([escape.theta, first.theta[1:]]),
                    np.concatenate([escape.omega, first.omega[1:]]), first.ended_by_event)
    if not first.ended_by_event:
        return first, None
    t2, q2, w2 = first.end
    turn = _first_stop(p, q2, q2 + 4 * math.pi, 513)  # the spring always wins within a few turns
    if turn is None or turn >= _upright_again(p):  # no turn before it comes round near upright, where the frames
        # end (integrated, not drawn: they are compared with the browser's)
        return first, integrate_leg(acc, q2, w2, t2, horizon, stop_at_angle=_upright_again(p), direction=1,
                                    expected=crossing_time(rate_squared, q2, _upright_again(p)))
    rest = drawn_to_turn(rate_squared, acc, q2, turn, t2)
    if rest is None:  # (tight, its samples sized by the time to the turn: the frames are compared)
        rest = integrate_leg(acc, q2, w2, t2, horizon, stop_at_rest=True, expected=crossing_time(rate_squared, q2, turn))
    return first, rest


def _linear_escape(acc, theta1: float, omega0: float, samples: int = 12) -> Leg:
    """A nudged release at (or within NEAR_UPRIGHT of) upright creeps away exponentially, which
    costs an integrator hundreds of steps at tight tolerances. Follow the motion linearised about
    the release, θ̈ = f₁ + λ² (θ − θ₁), exactly until θ − θ₁ = ESCAPE; the neglected terms are
    O(ESCAPE³) (sin θ is odd about upright): about 1e-15 of θ̇ at θ₂, far below the check's tolerance, and
    the creep's time as the browser integrates it to a microsecond over a creep of half a minute (at 1e-2
    it was 2 µs off over 3 s). Returns just the release state when there is no nudge or upright is stable."""
    lam2 = slope(acc, theta1)
    if omega0 == 0 or lam2 <= 0:
        return Leg(np.array([0.0]), np.array([theta1]), np.array([omega0]), False)
    lam, shift = math.sqrt(lam2), acc(theta1) / lam2
    away = lambda t: shift * (np.cosh(lam * t) - 1) + omega0 / lam * np.sinh(lam * t)  # noqa: E731
    latest = 1.001 * math.asinh(ESCAPE * lam / omega0) / lam  # shift ≥ 0 here: the nudge alone is slower
    t_end = brentq(lambda t: away(t) - ESCAPE, 0.0, latest)
    t = np.linspace(0.0, t_end, samples)
    theta = theta1 + away(t)
    omega = shift * lam * np.sinh(lam * t) + omega0 * np.cosh(lam * t)
    return Leg(t, theta, omega, False)


def _checks(p, a) -> tuple[Check, ...]:
    omega0 = _start_rate(p)
    leg, _ = _legs(tuple(sorted(p.items())) + (("I_O", a["I_O"]),))
    integrated = leg.end[2] if leg.ended_by_event else float("nan")
    rate_tolerance = relative_tolerance(a["omega2"], 1e-6) + NUDGE
    work = a["U_gravity"] + a["U_spring"]
    # T = ½ I_O θ̇² moves by I_O θ̇ δθ̇ when θ̇ is off by δθ̇ (plus the nudge's own ½ I_O NUDGE²)
    energy_tolerance = a["I_O"] * (abs(a["omega2"]) + rate_tolerance) * rate_tolerance + relative_tolerance(work, 1e-12)
    return (
        Check(rf"$\dot\theta$ at $\theta_2$ by integrating $I_O\ddot\theta = Q\sin\theta - k\theta$ (start nudge {plain_number(NUDGE)} rad/s)"
              if omega0 else r"$\dot\theta$ at $\theta_2$ by integrating $I_O\ddot\theta = Q\sin\theta - k\theta$",
              a["omega2"], integrated, rate_tolerance,
              "work–energy is the first integral of the equation of motion"),
        # Not T₂ against U_g + U_s: T₂ is defined as that sum. The kinetic energy here comes from the
        # integrated θ̇, the work from the positions of the weights and the spring's moment.
        Check(r"energy: $U_g + U_s$ vs $\tfrac12 I_O\dot\theta^2$ with $\dot\theta$ integrated", work, 0.5 * a["I_O"] * integrated**2,
              energy_tolerance, "the pivot does no work"),
    )


VISIBLE = math.radians(1.0)  # how far the rod must move from rest before a student can see it move
MAX_FRAME_TURN = math.radians(10.0)  # the most the rod may turn between two frames
FRAME_RANGE = (45, 150)


def _visible(p, xp=np):
    """How far the rod turns from rest before the frames start, and how near upright (360°) it may come again
    before they end: VISIBLE, or half the way to θ₂ where θ₂ is nearer."""
    return xp.minimum(VISIBLE, xp.minimum((p["theta2"] - p["theta1"]) / 2, (2 * math.pi - p["theta2"]) / 2))


def _upright_again(p, xp=np):
    """Where the frames end if the swing does not turn before it: within ``_visible`` of upright again, an
    equilibrium, where a swing with no spring (or one too soft to stop it sooner) creeps on for seconds."""
    return 2 * math.pi - _visible(p, xp)


def _fastest(p, a, xp=np):
    """A bound on |θ̇| over the swing in closed form (the frames' count: Integrated.frame_count): all the
    energy above the lowest the weights can reach, ½ I_O θ̇₀² + Q (1 + cos θ₁) + ½ k θ₁², as kinetic."""
    energy = 0.5 * a["I_O"] * _start_rate(p, xp) ** 2 + weight_moment(p) * (1 + xp.cos(p["theta1"])) + 0.5 * p["k"] * p["theta1"] ** 2
    return xp.sqrt(2 * energy / a["I_O"])


def _start_rate(p, xp=np):
    """θ̇ at release: the nudge at or near upright, else 0; for numbers or symbols."""
    if xp is np:
        return NUDGE if p["theta1"] < NEAR_UPRIGHT else 0.0
    return sp.Piecewise((NUDGE, sp.StrictLessThan(p["theta1"], NEAR_UPRIGHT)), (0.0, True))


def _acceleration(p, a, theta, xp=np):
    """θ̈ from I_O θ̈ = Q sin θ − k θ, for numbers (``xp`` math), arrays (numpy) or symbols (sympy): the one
    equation of motion of the checks' integration, the reference motion and the browser's."""
    return _angular_acceleration(weight_moment(p), p["k"], a["I_O"], theta, xp)


def _angular_acceleration(Q, k_, I, theta, xp):
    return (Q * xp.sin(theta) - k_ * theta) / I


# The swing, integrated in the browser (issue 51) from the same equation of motion: the creep until the rod
# has turned ``_visible`` (the frames start there), the fall to θ₂ (framed: the key instant), on to the turn
# (framed) or round to ``_upright_again`` if that comes first (the end), and the return to within
# ``_visible`` of rest (the end). ``motion`` is the reference, from the checks' own legs.
_CREEP = Phase("creep", lambda p, a, y, xp: p["theta1"] + _visible(p, xp) - y["theta"], opens=True)
_FALL = Phase("fall", lambda p, a, y, xp: p["theta2"] - y["theta"], framed=True)
_RISE = Phase("rise", lambda p, a, y, xp: xp.minimum(y["omega"], _upright_again(p, xp) - y["theta"]), framed=True,
              last=lambda p, a, y, xp: xp.less(_upright_again(p, xp) - y["theta"], y["omega"]))  # (round near upright)
_RETURN = Phase("return", lambda p, a, y, xp: y["theta"] - p["theta1"] - _visible(p, xp))

INTEGRATED = Integrated(
    state=("theta", "omega"), start=lambda p, a, xp: {"theta": p["theta1"], "omega": _start_rate(p, xp)},
    rates=lambda p, a, y, xp: {"theta": y["omega"], "omega": _acceleration(p, a, y["theta"], xp)},
    legs=(_CREEP, _FALL, _RISE, _RETURN), horizon=lambda p, a, xp: 200 * xp.sqrt(a["I_O"] / weight_moment(p)) + 10,
    frames=FRAME_RANGE[0], most=FRAME_RANGE[1], turn=MAX_FRAME_TURN, fastest=_fastest, tolerances=(1e-12, 1e-15))


@per_solution
def motion(solution: Solution) -> dict:
    """The swing a student can see, with the energy split per frame: kinetic, gravitational (zero
    with the assembly hanging straight down) and spring. The fall is the checks' own legs (``simulate``),
    between their samples the quintic through θ, θ̇ and θ̈; the system is conservative, so the return is its
    mirror in time, unless the swing comes round near upright before it turns (``_upright_again``). A swing
    that turns has a frame at the turn, where it stands at its largest angle.

    A release at upright creeps for seconds on its 1e-6 rad/s nudge; the frames start where the rod has
    turned ``_visible`` from rest and end where it is back within it (or at ``_upright_again``), at
    instants even in time, as many as keep the rod's turn between two under MAX_FRAME_TURN
    (``INTEGRATED.frame_count``: a bound on θ̇ in closed form). The browser integrates the same frames
    itself on the lesson page (``INTEGRATED``).

    One frame is at θ₂ itself, on the fall, at the closed form's numbers (θ₂, |θ̇₂|; the integration agrees
    with them to its tolerance): the key instant, where the speed is asked for and the free-body diagram
    is drawn (the stage's Forces overlay draws its loads on these frames)."""
    p, a = solution.params, solution.answers
    half = simulate(p, a)
    reach, _ = _legs(tuple(sorted(p.items())) + (("I_O", a["I_O"]),))
    t_2 = reach.end[0]  # when the fall passes θ₂ (solve refuses a swing that does not)
    knots, keep = np.unique(half.t, return_index=True)
    angles, rates = half.theta[keep], half.omega[keep]
    accelerations = _acceleration(p, a, angles)

    def on_half(times):
        return hermite_on_knots(knots, angles, rates, np.asarray(times, dtype=float), accelerations)

    def reaches(angle, lo, hi):  # when the fall (θ increasing) reaches ``angle``, between lo and hi: on its knots' interval
        i = int(np.searchsorted(angles, angle))  # (the fall's angles increase)
        lo, hi = max(lo, knots[max(i - 1, 0)]), min(hi, knots[min(i, len(knots) - 1)])
        j = min(max(i - 1, 0), len(knots) - 2)  # that interval's quintic, in numbers
        t0, h = float(knots[j]), float(knots[j + 1] - knots[j])
        ends = [float(v) for v in (angles[j], angles[j + 1], rates[j], rates[j + 1], accelerations[j], accelerations[j + 1])]
        return brentq(lambda t: quintic((t - t0) / h, h, *ends)[0] - angle, lo, hi, xtol=1e-13)
    t_start = reaches(p["theta1"] + _visible(p), 0.0, t_2)
    t_turn = half.t[-1]
    over = bool(half.theta[-1] == _upright_again(p))  # round near upright: the legs end where the frames do
    t_end = t_turn if over else 2 * t_turn - t_start
    count = INTEGRATED.frame_count(p, a, t_end - t_start)
    even = frame_instants(t_start, t_end, count, [t_2] + ([] if over else [t_turn]))
    theta, _ = on_half(np.minimum(even, 2 * t_turn - even))  # the return: the fall mirrored in time
    at_2 = int(np.argmin(np.abs(even - t_2)))
    theta[at_2] = p["theta2"]
    # the rate from the energy integral at each frame's angle (the quintic's slope is an order less accurate
    # than its value), back on the return
    kinetic = np.maximum(kinetic_energy_at(p, theta) + 0.5 * a["I_O"] * _start_rate(p) ** 2, 0.0)
    omega = np.where(even > t_turn, -1.0, 1.0) * np.sqrt(2 * kinetic / a["I_O"])
    omega[at_2] = a["omega2"]
    Q = weight_moment(p)
    return {"t": even, "theta": theta, "omega": omega, "kinetic": 0.5 * a["I_O"] * omega**2,
            "gravity": Q * (1 + np.cos(theta)), "spring": 0.5 * p["k"] * theta**2,
            "start": float(even[0]), "over_the_top": over}


def method(params) -> tuple[Step, ...]:
    """The symbolic steps for ``params`` without numbers, shown beside a refusal (the spring stops
    the rod before θ₂): the work–energy balance that says why."""
    return derivation(validate_params(PARAMS, params)["disk"]).steps


def derivation_of(solution: Solution) -> Derivation:
    """The derivation behind ``solution`` (its option and regime)."""
    return derivation(solution.params["disk"])


# How ?seed=N varies the parameters beyond the general rule (solvers.protocol.Variants).
VARIANTS = Variants(angles_deg={"theta1": None, "theta2": (30, 150)})  # θ₁ stays the textbook's

WARM: tuple[dict, ...] = ()  # every option combination is warmed already


# The typical slips practice mode names: wrong expressions in this module's symbols, each
# with the feedback a tutor would give (the hint never states the right value).
MISTAKES = (
    Mistake("I_O", "I_G where I_O belongs: about the pivot each body adds its mass times the square of "
            "its centre's distance from O.",
            lambda p: m1 * L**2 / 12 + m2 * R**2 / 2),
    Mistake("I_O", "The welded disk also turns about its own centre: its spin inertia belongs in I_O.",
            lambda p: m1 * L**2 / 3 + m2 * (L + R) ** 2, lambda p: p["disk"] == "welded"),
    Mistake("U_spring", "A sign: the spring resists the fall, so its work is negative.",
            lambda p: k * (theta2**2 - theta1**2) / 2),
    Mistake("omega2", "A pinned disk does not turn with the rod; this one is welded, so its own spin "
            "inertia belongs in I_O.", lambda p: sp.sqrt(2 * T2 / (m1 * L**2 / 3 + m2 * (L + R) ** 2)),
            lambda p: p["disk"] == "welded"),
    Mistake("omega2", "I_G where I_O belongs: about the pivot each body adds its mass times the square of "
            "its centre's distance from O.", lambda p: sp.sqrt(2 * T2 / (m1 * L**2 / 12 + m2 * R**2 / 2))),
    Mistake("omega2", "A sign: the spring resists the fall, so its work is negative.",
            lambda p: sp.sqrt(2 * (U_g - U_s) / I_O)),
)
