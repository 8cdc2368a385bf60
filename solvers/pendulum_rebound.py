"""A rod-and-sphere pendulum released from rest strikes the floor and rebounds (Hibbeler 19-56).

Model: rigid slender rod (m_r, L) pinned at a fixed, frictionless pivot O, with a sphere (m_s, r)
fixed at its end, the sphere's centre a distance L + r from O. θ is the rod's angle from the
horizontal, positive upward. The floor (a horizontal plane a depth d below O) or the textbook's
vertical wall is smooth and fixed; the impact is instantaneous and Newton's restitution e acts on
the normal velocity of the contact point. Since the body turns about O, that velocity is
proportional to θ̇, so θ̇⁺ = −e θ̇⁻. Between impacts mechanical energy is conserved.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp

from .kept import kept_pickled
from .core import (
    within_model_range,
    plain_number,
    Answer,
    Check,
    Choice,
    Derivation,
    LedgerRow,
    Number,
    PhysicalLimitError,
    Result,
    Solution,
    Step,
    latex,
    latex_eq,
    presentable,
    relative_tolerance,
    root_with_sign,
    require,
    validate_params,
    per_solution,
)
from .diagram import Body, DiagramSlip, Circle, Diagram, Load, Rod, balance, balance_steps, fbd_steps
from .live import Case, Integrated, Leg, Live, frame_instants
from .protocol import About, Mistake, Variants
from .swing import ATOL, RTOL, crossing_time, drawn_to_turn, hermite_on_knots, integrate_leg

ABOUT = About(
    title="Rod-and-sphere pendulum bounces off the floor",
    group="Work–energy",
    blurb="Release, swing, bounce: each bounce keeps a fraction e² of the swing.",
    icon=":material/height:",
    source="Hibbeler 19-56",
    us_units=True,  # the textbook's data are in lb and ft: the page offers US units
    primary=("e", "theta0"),  # always shown; the rest sit behind "More parameters"
)

PARAMS = (
    Number("m_s", 4.536, "sphere mass", "mass", "m_s", low=0, ui_low=0.1, ui_high=20.0, step=0.1),
    Number("m_r", 1.814, "rod mass", "mass", "m_r", low=0, ui_low=0.1, ui_high=20.0, step=0.1),
    Number("L", 0.6096, "rod length", "length", "L", low=0, ui_low=0.05, ui_high=2.0, step=0.01),
    Number("r", 0.09144, "sphere radius", "length", "r", low=0, ui_low=0.01, ui_high=0.5, step=0.01),
    Number("d", 0.5, "depth of the floor below the pivot", "length", "d", low=0, ui_low=0.01,
           ui_high=2.5, step=0.01, help="Must satisfy r < d < L + 2r (floor only)."),
    Number("e", 0.6, "coefficient of restitution", "dimensionless", "e", low=0, high=1,
           low_inclusive=True, high_inclusive=True, ui_low=0, ui_high=1, step=0.05),
    Number("theta0", 0.0, "release angle above the horizontal", "angle", r"\theta_0",
           low=-math.pi / 2, high=math.pi / 2, ui_low=-89, ui_high=89, step=1.0,
           help="Must be above the impact angle; 90° (upright) is an equilibrium."),
    Number("g", 9.81, "gravity", "acceleration", "g", low=0, ui_low=0.5, ui_high=30.0, step=0.01),
    Choice("sphere", "solid", "the ball's inertia", ("solid", "hollow", "disk"),
           ("solid sphere, ⅖ m r²", "hollow sphere, ⅔ m r²", "disk, ½ m r² (the worked solution)")),
    Choice("surface", "floor", "what the sphere strikes", ("floor", "wall"),
           ("a floor a depth d below O", "a wall where the rod hangs straight down")),
)

ANSWERS = (
    Answer("theta_impact", "angle at impact", r"\theta_I", "angle"),
    Answer("omega_impact", "angular velocity just before impact", r"\dot\theta_I^-", "angular_speed"),
    Answer("omega_after", "angular velocity just after impact", r"\dot\theta_I^+", "angular_speed"),
    Answer("theta_rebound", "highest angle after the bounce", r"\theta_f", "angle"),
    Answer("I_O", "moment of inertia about the pivot", r"I_O", "inertia"),
    Answer("energy_loss", "kinetic energy lost in the impact", r"\Delta T", "energy"),
)

ERRATA = (
    r"The worked solution takes the sphere's own inertia as $\tfrac12 m_s r^2$, a **disk's** value; a solid "
    r"sphere has $\tfrac25 m_s r^2$ (choose *sphere* = disk to reproduce the worked solution).",
    r"The worked solution starts the energy integral at $\theta = 90^\circ$ (an equilibrium), giving "
    r"$(1-\sin\theta)$; released from $\theta_0$ it is $(\sin\theta_0 - \sin\theta)$.",
    r"For a floor below the pivot, $\sin\theta_I = (r-d)/(L+r)$ is **negative**; the worked solution writes "
    r"$(d-r)/(L+r)$.",
    r"The worked solution writes $e = \dot\theta'/\dot\theta$, against its own next line "
    r"$\dot\theta' = -e\dot\theta$: the rod reverses, so $e = -\dot\theta'/\dot\theta$.",
    r"Whatever the masses, $\sin\theta_f - \sin\theta_I = e^2(\sin\theta_0 - \sin\theta_I)$.",
)

# What a PhysicalLimitError's attribute is, for the page that shows it: (label, dimension).
LIMIT_LABELS = {"theta_impact": ("angle at which the sphere touches", "angle")}

SPHERE_INERTIA = {"solid": sp.Rational(2, 5), "hollow": sp.Rational(2, 3), "disk": sp.Rational(1, 2)}

m_s, m_r, L, r, d, e, g = sp.symbols("m_s m_r L r d e g", positive=True)
theta0, theta, theta_I, theta_f = sp.symbols(r"theta_0 theta theta_I theta_f", real=True)
thetadot = sp.Symbol(r"\dot{\theta}", real=True)
w_minus, w_plus = sp.symbols(r"\dot{\theta}_I^- \dot{\theta}_I^+", real=True)
I_O, Q, loss = sp.symbols(r"I_O Q \Delta{T}", real=True)
SYMBOLS = {"m_s": m_s, "m_r": m_r, "L": L, "r": r, "d": d, "e": e, "g": g, "theta0": theta0}
DIMENSIONS = {p.name: p.dimension for p in PARAMS if isinstance(p, Number)}


# ---------------------------------------------------------------------------------------------
# Step 2: the pendulum (rod and sphere: one rigid body) isolated from the pin and the surface, in the
# stage's coordinates (viz/pendulum_rebound.py and ``motion``: O at the origin, x horizontal toward the
# sphere's side at θ = 0, y up; the floor is the line y = −d, the wall the line x = −r, against which
# the sphere hangs at θ = −90°). The pin's reaction has no direction the physics fixes: drawn as its
# components. During the swing the two weights act; at the impact the surface's impulse and the pin's,
# against which gravity's is negligible.

thetaddot = sp.Symbol(r"\ddot{\theta}", real=True)
O_x, O_y, P_surface, Ohat_x, Ohat_y = sp.symbols(r"O_x O_y \hat{P} \hat{O}_x \hat{O}_y", real=True)
_MASS = m_r + m_s
_ARM = m_r * L / 2 + m_s * (L + r)  # Σ m_i ρ_i: the mass times G's distance from O
# The surface's unit normal, out of the surface into the sphere (the floor below it, the wall on its −x side).
SURFACE_NORMAL = {"floor": (0, 1), "wall": (1, 0)}


def _pendulum_points(surface: str) -> dict:
    """O, the rod's centre G_r, the mass centre G, the rod's end A, the sphere's centre S and its point C
    nearest the surface (where it touches at the impact), at θ."""
    along = lambda rho: (rho * sp.cos(theta), rho * sp.sin(theta))  # noqa: E731  a point of the rod's line
    nx, ny = SURFACE_NORMAL[surface]
    centre = along(L + r)
    return {"O": (0, 0), "G_r": along(L / 2), "G": along(_ARM / _MASS), "A": along(L), "S": centre,
            "C": (centre[0] - r * nx, centre[1] - r * ny)}


def _outline() -> tuple:
    return (Rod(("O", "A")), Circle("S", r))


def _frame_at(motion, t: float) -> int:
    return int(np.argmin(np.abs(np.asarray(motion["t"]) - t)))


def _states(solution, motion) -> tuple[np.ndarray, np.ndarray]:
    """θ and θ̇ at each frame of ``motion``; at the first impact's frame, the closed form's θ_I and θ̇⁻ (as
    the stage draws its key pose there: the integration agrees with them to its tolerance)."""
    angles, rates = np.array(motion["theta"], dtype=float), np.array(motion["omega"], dtype=float)
    if len(motion["impact_times"]):
        i = _frame_at(motion, motion["impact_times"][0])
        angles[i], rates[i] = solution.answers["theta_impact"], solution.answers["omega_impact"]
    return angles, rates


def _swing_frame(solution, motion) -> int:
    """The frame the swing's diagram is drawn at: of the first fall's (release to the first impact), the
    one whose θ is nearest halfway between θ₀ and θ_I (a pose with the rod neither upright nor hanging,
    and a speed)."""
    angles, _ = _states(solution, motion)
    last = _frame_at(motion, motion["impact_times"][0]) if len(motion["impact_times"]) else len(angles) - 1
    halfway = (solution.params["theta0"] + solution.answers["theta_impact"]) / 2
    return int(np.argmin(np.abs(angles[: last + 1] - halfway)))


def _swing_values_at(p, inertia: float, theta_, omega_, xp=np) -> dict:
    """The swing's symbols at θ, θ̇ (numbers, or arrays of a frame each): θ̈ from the solver's equation of
    motion, I_O θ̈ = −Q cos θ (``_acceleration``, as integrated), the pin's components from the two force
    laws, (m_r + m_s) a_G less the weights (the solver has no formula for them: the moment law about O,
    against the solver's θ̈, is the independent check)."""
    Q_ = moment_coefficient(p)
    alpha = -Q_ * xp.cos(theta_) / inertia
    arm = Q_ / p["g"]  # Σ m_i ρ_i = (m_r + m_s) × G's distance from O
    ax = arm * (-xp.sin(theta_) * alpha - xp.cos(theta_) * omega_**2)
    ay = arm * (xp.cos(theta_) * alpha - xp.sin(theta_) * omega_**2)
    return {m_s: p["m_s"], m_r: p["m_r"], L: p["L"], r: p["r"], g: p["g"], I_O: inertia, theta: theta_,
            thetadot: omega_, thetaddot: alpha, O_x: ax, O_y: ay + (p["m_r"] + p["m_s"]) * p["g"]}


def _swing_values(solution) -> dict:
    """At the frame of the stage's animation ``_swing_frame`` picks, halfway down the first fall: θ and θ̇
    there as the solver's integration of its equation of motion gives them."""
    m = motion(solution)
    i = _swing_frame(solution, m)
    angles, rates = _states(solution, m)
    return _swing_values_at(solution.params, solution.answers["I_O"], float(angles[i]), float(rates[i]))


def _swing_key(p, a) -> dict:
    """At the stage's key frame, the first impact, just before it (θ_I, θ̇_I⁻)."""
    return _swing_values_at(p, a["I_O"], a["theta_impact"], a["omega_impact"], xp=sp)


def _impact_key(p, a) -> dict:
    return _impact_values_at(p, a["I_O"], a["theta_impact"], a["omega_impact"], a["omega_after"], xp=sp)


def _swing_frames(solution, motion) -> dict:
    """The swing's symbols at every frame (the impacts' frames: just before)."""
    angles, rates = _states(solution, motion)
    values = _swing_values_at(solution.params, solution.answers["I_O"], angles, rates)
    return {k: np.broadcast_to(np.asarray(v, dtype=float), angles.shape).copy() for k, v in values.items()}


def _contact_arm(p, angle, xp=np):
    """∂r_C/∂θ · n, the contact's normal velocity per unit θ̇ (C turns about O: v_C = θ̇ E_z × r_C), at θ.
    (As a moment, (r_C × n)·E_z: the arm about O of the surface's normal through C.)"""
    rho = p["L"] + p["r"]
    return rho * xp.cos(angle) if p["surface"] == "floor" else -rho * xp.sin(angle)


def _impact_values_at(p, inertia: float, angle: float, before, after, xp=np) -> dict:
    """The impact's symbols for θ̇⁻ = ``before`` and θ̇⁺ = ``after`` (numbers or arrays): the surface's
    impulse is the change of the contact's normal velocity, v_n = θ̇ ∂r_C/∂θ·n, times the body's effective
    mass there, m_C = I_O / (∂r_C/∂θ·n)²; the pin's from the two linear impulse laws, (m_r + m_s) Δv_G less
    the surface's. (The solver has no formula for either: the angular impulse law about O then checks
    the contact's arm as the diagram's points and normal give it against the solver's kinematics.)"""
    per_rate = _contact_arm(p, angle, xp)
    impulse = inertia / per_rate**2 * (after - before) * per_rate
    arm = moment_coefficient(p) / p["g"]
    jump = after - before
    nx, ny = SURFACE_NORMAL[p["surface"]]
    return {m_s: p["m_s"], m_r: p["m_r"], L: p["L"], r: p["r"], g: p["g"], I_O: inertia, theta: angle,
            w_minus: before, w_plus: after, P_surface: impulse,
            Ohat_x: -arm * xp.sin(angle) * jump - impulse * nx,
            Ohat_y: arm * xp.cos(angle) * jump - impulse * ny}


def _impact_values(solution) -> dict:
    """At the first impact: θ_I, θ̇⁻ and θ̇⁺ are the solver's answers."""
    a = solution.answers
    return _impact_values_at(solution.params, a["I_O"], a["theta_impact"], a["omega_impact"], a["omega_after"])


def _impact_frames(solution, motion) -> dict:
    """The impact's symbols at each impact's frame (θ̇⁻ its speed before, θ̇⁺ = −e θ̇⁻ as the motion
    rebounds; the first impact's the answers), NaN in every other frame."""
    p, a = solution.params, solution.answers
    angles, rates = _states(solution, motion)
    at = np.zeros(len(angles), dtype=bool)
    for t_hit in motion["impact_times"]:
        at[_frame_at(motion, t_hit)] = True
    before = np.where(at, rates, np.nan)
    after = -p["e"] * before
    if len(motion["impact_times"]):
        after[_frame_at(motion, motion["impact_times"][0])] = a["omega_after"]
    values = _impact_values_at(p, a["I_O"], np.where(at, a["theta_impact"], np.nan), before, after)
    return {k: np.where(at, np.broadcast_to(np.asarray(v, dtype=float), at.shape), np.nan) for k, v in values.items()}


@functools.cache
def diagrams(surface: str) -> tuple[Diagram, Diagram]:
    """The swing's and the impact's diagrams for this surface."""
    points = _pendulum_points(surface)
    swing = Body("the pendulum", points=points, centre="G", about="O",
                 kinetic=(_ARM * (-sp.sin(theta) * thetaddot - sp.cos(theta) * thetadot**2),
                          _ARM * (sp.cos(theta) * thetaddot - sp.sin(theta) * thetadot**2), I_O * thetaddot),
                 kinetic_latex=(r"(m_r + m_s)\,\ddot{x}_G", r"(m_r + m_s)\,\ddot{y}_G", r"I_O\ddot{\theta}"),
                 outline=_outline())
    weights = (Load("m_r g", "the rod's weight", "gravity", "the pendulum", at="G_r", direction=(0, -1), size=m_r * g),
               Load("m_s g", "the sphere's weight", "gravity", "the pendulum", at="S", direction=(0, -1), size=m_s * g),
               Load("O", "the pin's reaction", "the pin", "the pendulum", at="O", components=(O_x, O_y)))
    jump = w_plus - w_minus
    hit = Body("the pendulum", points=points, centre="G", about="O",
               kinetic=(-_ARM * sp.sin(theta) * jump, _ARM * sp.cos(theta) * jump, I_O * jump),
               kinetic_latex=(r"(m_r + m_s)\,\Delta v_{Gx}", r"(m_r + m_s)\,\Delta v_{Gy}",
                              r"I_O\left(\dot\theta_I^+ - \dot\theta_I^-\right)"),
               outline=_outline())
    blows = (Load(r"\hat{P}", f"the {surface}'s impulse", f"the {surface}", "the pendulum", at="C", kind="impulse",
                  direction=SURFACE_NORMAL[surface], size=P_surface),
             Load(r"\hat{O}", "the pin's impulse", "the pin", "the pendulum", at="O", kind="impulse",
                  components=(Ohat_x, Ohat_y)))
    return (Diagram("swing", "During the swing", "force", (swing,), weights, _swing_values, frames=_swing_frames, key=_swing_key,
                    note="The rod and sphere turn together about O, one rigid body; its mass centre $G$ lies on the "
                         "rod, between the rod's centre $G_r$ and the sphere's $S$, where the weights act."),
            Diagram("impact", "At the impact", "impulse", (hit,), blows, _impact_values, frames=_impact_frames, key=_impact_key,
                    note=f"The {surface} is smooth: its impulse is along its normal, out of the {surface} into the "
                         "sphere at its contact point C. The weights are finite: their impulse over the instant "
                         "is negligible."))


def free_body_diagrams(params) -> tuple[Diagram, ...]:
    """The swing's (drawn halfway down the first fall) and the impact's (the first impact) diagrams for
    this surface."""
    return diagrams(params["surface"])


# The diagram the drawing exercise asks for (practice/diagram_judge.py): the impact, where the rebound is decided (the worked solution's diagram)
EXERCISE_DIAGRAM = "impact"

# The classic slips in drawing this diagram (practice/diagram_judge.py), as MISTAKES are the answers':
# each a load the physics does not put there, with a tutor's words that never show the diagram.
DIAGRAM_SLIPS = (
    DiagramSlip("weight in an impact", "a weight is a finite force: its impulse over the impact's instant is "
                "negligible against the contact's and the pin's.", kinds=("impulse",), direction=(0, -1),
                phase="impact"),
    DiagramSlip("centripetal force", "a centripetal force is not a force of its own: it is what the real forces' "
                "components toward O add up to.", at="G", direction=(-sp.cos(theta), -sp.sin(theta)), phase="swing"),
)



@functools.cache
@kept_pickled
def derivation(sphere: str, surface: str) -> Derivation:
    k = SPHERE_INERTIA[sphere]
    inertia = sp.Rational(1, 3) * m_r * L**2 + k * m_s * r**2 + m_s * (L + r) ** 2
    swing_diagram, impact_diagram = diagrams(surface)
    points = swing_diagram.body("the pendulum").points
    # Step 3's moment law about O, summed from the swing's diagram: Σ M_O = −Q cos θ = I_O θ̈. Q is read
    # off it, and the energy equation is its integral (θ̈ dθ = θ̇ dθ̇), so the diagram is the one source.
    moment_law = balance(swing_diagram, "the pendulum")[2]
    weight_moment = presentable(sp.simplify(-moment_law.lhs / sp.cos(theta)), (m_r * L / 2 + m_s * (L + r)) * g)
    drop = lambda upper, lower: Q * (sp.sin(upper) - sp.sin(lower))  # noqa: E731  V(upper) − V(lower)
    swept = sp.Dummy("alpha")
    work = sp.integrate(moment_law.lhs.subs(theta, swept), (swept, theta0, theta))  # ∫ Σ M_O dθ from θ₀
    presentable(work, drop(theta0, theta).subs(Q, weight_moment))  # (checks that the integral is the drop in V)
    energy = sp.Eq(sp.Rational(1, 2) * I_O * thetadot**2, drop(theta0, theta))

    contact = sp.Matrix(points["C"])  # the sphere's point nearest the surface, as the diagram places it
    normal = sp.Matrix(SURFACE_NORMAL[surface])
    if surface == "floor":
        touch = sp.Eq(contact[1], -d)
        impact_angle = sp.asin(sp.solve(touch.subs(sp.sin(theta), sp.Symbol("s")), sp.Symbol("s"))[0])
    else:
        touch = sp.Eq(theta, -sp.pi / 2)
        impact_angle = -sp.pi / 2
    v_contact = sp.diff(contact, theta) * thetadot
    v_n = sp.simplify(v_contact.dot(normal))

    roots = sp.solve(energy, thetadot)
    falling = root_with_sign([w.subs({theta0: sp.pi / 4, theta: 0}) for w in roots], -1)
    falling = roots[[w.subs({theta0: sp.pi / 4, theta: 0}) for w in roots].index(falling)]
    falling = presentable(falling, -sp.Pow(2 * drop(theta0, theta) / I_O, sp.S.Half, evaluate=False))
    s_f = sp.Symbol(r"\sin\theta_f")
    rebound = sp.Eq(sp.Rational(1, 2) * I_O * w_plus**2, drop(theta_f, theta_I))
    sin_rebound = sp.solve(rebound.subs(sp.sin(theta_f), s_f), s_f)[0]
    sin_rebound = sin_rebound.subs(w_plus, -e * w_minus).subs(w_minus, falling.subs(theta, theta_I))
    sin_rebound = presentable(sin_rebound, sp.sin(theta_I) + e**2 * (sp.sin(theta0) - sp.sin(theta_I)))
    # The surface's impulse, from Step 3's angular impulse law about O (the pin's impulse has no moment
    # about O) with the rebound θ̇⁺ = −e θ̇⁻.
    angular_impulse = balance(impact_diagram, "the pendulum")[2]
    at_impact = angular_impulse.subs({w_plus: -e * w_minus, theta: theta_I if surface == "floor" else impact_angle})
    impulse = sp.factor(sp.solve(at_impact, P_surface)[0])

    steps = [
        Step(r"Origin at the pivot O; θ the rod's angle from the horizontal, up + (counter-clockwise); basis "
             r"$\mathbf{E}_x$ horizontal, $\mathbf{E}_y$ up, $\mathbf{E}_z$ out of the page. The body turns about O: "
             r"the rod's centre $G_r$, the sphere's centre $S$ and the mass centre $G$ lie on the rod",
             r"\mathbf{r}_{G_r} = \tfrac{L}{2}\left(\cos\theta, \sin\theta\right),\quad "
             r"\mathbf{r}_S = (L + r)\left(\cos\theta, \sin\theta\right),\quad "
             r"\mathbf{r}_G = \rho_G\left(\cos\theta, \sin\theta\right),\quad "
             r"\rho_G = \frac{m_r L/2 + m_s (L + r)}{m_r + m_s}", part=1),
        Step("Moment of inertia about the pivot O (parallel-axis theorem for rod and "
             f"{'sphere' if sphere != 'disk' else 'ball, with the worked solution’s disk value'})",
             latex_eq(I_O, inertia), part=1),
        Step(f"The sphere's point C nearest the {surface} turns about O with the body, "
             r"$\mathbf{v}_C = \dot\theta\,\mathbf{E}_z \times \mathbf{r}_C$: its velocity along the "
             f"{surface}'s normal is proportional to θ̇",
             r"\mathbf{r}_C = \left(" + latex(contact[0]) + ", " + latex(contact[1]) + r"\right),\quad "
             + latex_eq(sp.Symbol("v_n"), v_n), part=1),
        *fbd_steps(swing_diagram), *fbd_steps(impact_diagram),
        *balance_steps(swing_diagram), *balance_steps(impact_diagram),
        Step("Moment of the weights about O per unit cos θ, from the moment law: the potential energy is V = Q sin θ",
             latex_eq(Q, weight_moment)),
        Step("Work–energy from rest at θ₀: the moment law $\\sum M_O = I_O\\ddot\\theta = -Q\\cos\\theta$, integrated once "
             r"($\ddot\theta\,d\theta = \dot\theta\,d\dot\theta$; gravity is the only force that works, the pin at O does none)",
             latex(energy)),
        Step("The sphere touches the " + ("floor: the lowest point of the sphere is a depth d below O"
                                           if surface == "floor" else
                                           "wall when the rod hangs straight down"),
             (latex(touch) + r"\quad\Rightarrow\quad " if surface == "floor" else "")
             + latex_eq(theta_I, impact_angle)),  # (the impact's angle, θ_I, as the steps after it name it)
        Step("Falling (θ decreasing), the root is negative",
             latex_eq(w_minus, falling.subs(theta, theta_I))),
        Step("Restitution reverses the normal velocity of the contact point, $v_n^+ = -e\\,v_n^-$; it is proportional to θ̇",
             latex_eq(w_plus, -e * w_minus)),
        Step(f"The {surface}'s impulse, from the angular impulse law about O (the pin's impulse has no moment about O)",
             latex_eq(P_surface, impulse)),
        Step(r"Energy after the bounce up to the highest angle $\theta_f$ ($\dot\theta = 0$ there)",
             latex(rebound)),
        Step("Hence, whatever the masses",
             latex_eq(sp.sin(theta_f) - sp.sin(theta_I), sin_rebound - sp.sin(theta_I))),
    ]
    chain = [
        Result("I_O", I_O, inertia, "inertia"),
        Result("Q", Q, weight_moment, "torque", "With your numbers: moment of the weights, Q"),
        Result("theta_impact", theta_I, impact_angle, "angle"),
        Result("omega_impact", w_minus, falling.subs(theta, theta_I), "angular_speed"),
        Result("omega_after", w_plus, -e * w_minus, "angular_speed"),
        Result("theta_rebound", theta_f, sp.asin(sin_rebound), "angle"),
        Result("energy_loss", loss, sp.Rational(1, 2) * I_O * (w_minus**2 - w_plus**2), "energy"),
    ]
    return Derivation(SYMBOLS, DIMENSIONS, steps, chain, {a.name: a.label for a in ANSWERS})


def validated(params) -> dict:
    """The parameters checked (a floor within the sphere's reach, deeper than its radius), as solve takes them."""
    p = validate_params(PARAMS, params)
    if p["surface"] == "floor":
        require(p["d"] > p["r"], f"The floor must lie deeper below the pivot than the sphere's radius "
                f"(d > r = {p['r']:g} m), got d = {p['d']:g} m: the sphere would start in the floor.")
        require(p["d"] < p["L"] + 2 * p["r"],
                f"The floor must be within the sphere's reach, d < L + 2r = {p['L'] + 2 * p['r']:g} m, "
                f"got d = {p['d']:g} m: the pendulum would swing past without touching it.")
    return p



# What a drag past the limit says and the release's refusal opens with: one regime, the same words.
NO_IMPACT = "released below the angle where the sphere touches the {surface}: no impact"


def _live_cases(sphere: str, surface: str) -> tuple[Case, ...]:
    """Released at or below the impact angle: the limit ``solve`` refuses; else the chain."""
    d_ = derivation(sphere, surface)
    return (Case("below_impact", NO_IMPACT.format(surface=surface),
                 d_, sp.Not(theta0 > theta_I), values=False),
            Case(surface, f"the sphere strikes the {surface} and rebounds", d_))


# Live while dragging (solvers/live.py): e and the release angle.
LIVE = Live(("e", "theta0"), _live_cases)

@within_model_range
def solve(**params) -> Solution:
    p = validated(params)
    d_ = derivation(p["sphere"], p["surface"])
    impact = impact_angle(p)
    if not p["theta0"] > impact:
        said = NO_IMPACT.format(surface=p["surface"])
        raise PhysicalLimitError(
            f"{said[0].upper()}{said[1:]} (θ₀ must be above θ_I = {plain_number(math.degrees(impact))}°).",
            theta_impact=impact)
    values = d_.evaluate(p)
    answers = {a.name: values[a.name] for a in ANSWERS}
    bounces = bounce_sequence(p, answers)
    steps = list(d_.steps) + d_.numeric_steps(values)
    checks = _checks(p, answers)
    notes = (f"Each bounce keeps a fraction e² = {plain_number(p['e'] ** 2, 3)} of the swing's energy above the "
             "impact height.",)
    I = answers["I_O"]
    ledger = (
        LedgerRow(r"angular momentum about O, $I_O\dot\theta$", I * answers["omega_impact"], I * answers["omega_after"],
                  "angular_momentum", f"the {p['surface']}'s impulse has a moment about O"),
        LedgerRow("kinetic energy", 0.5 * I * answers["omega_impact"] ** 2, 0.5 * I * answers["omega_after"] ** 2,
                  "energy", "elastic: e = 1" if p["e"] == 1 else "a fraction e² is kept" if p["e"] > 0 else
                  f"all lost: e = 0, the sphere stays against the {p['surface']}"),
    )
    return Solution("pendulum_rebound", p, answers, tuple(steps), checks, p["surface"], notes, ledger,
                    extras={"bounce_peaks": bounces})


def impact_angle(p) -> float:
    """θ_I, where the sphere touches the surface (the derivation's link; ``p`` validated)."""
    return derivation(p["sphere"], p["surface"]).evaluate(p, upto="theta_impact")["theta_impact"]


def moment_coefficient(p) -> float:
    """Q in θ̈ = −Q cos θ / I_O: the weight's moment arm sum, (m_r L/2 + m_s (L + r)) g."""
    return (p["m_r"] * p["L"] / 2 + p["m_s"] * (p["L"] + p["r"])) * p["g"]


def bounce_sequence(p, answers, count: int = 4) -> list[float]:
    """Peak angles after successive bounces: sin θ_n − sin θ_I = e^{2n} (sin θ₀ − sin θ_I)."""
    s_I, s_0 = math.sin(answers["theta_impact"]), math.sin(p["theta0"])
    return [math.asin(s_I + p["e"] ** (2 * n) * (s_0 - s_I)) for n in range(1, count + 1)]


def simulate(p, answers, bounces: int = 3):
    """θ(t) through ``bounces`` impacts, as drawn: the fall from rest integrated (I_O θ̈ = −Q cos θ), then
    after each impact the rise to the peak and the fall back.

    Returns (t, θ, θ̇, impacts, legs) with the legs in order. The fall is integrated from rest (the
    second method for the closed-form impact speed); each rise is drawn from the energy integral
    (swing.drawn_to_turn: its turn to 1e-8 of its time, where an integration's peak near a slow turn is
    some 1e-7 s off), or integrated tightly where that cannot draw it; each fall after a bounce is the
    rise mirrored in time (the swing is conservative). The legs are cached, so the checks and the
    animation share them; the checks' rise is integrated on its own (``first_rise``).
    """
    legs = _legs(_key(p, answers), bounces)
    impacts = [(leg.end[0], leg.end[2]) for leg in legs[0::2]]
    t = np.concatenate([leg.t for leg in legs])
    q = np.concatenate([leg.theta for leg in legs])
    w = np.concatenate([leg.omega for leg in legs])
    return t, q, w, impacts, list(legs)


def _key(p, answers) -> tuple:
    return tuple(sorted((k, v) for k, v in p.items())) + (("I_O", answers["I_O"]), ("theta_impact", answers["theta_impact"]))


@functools.lru_cache(maxsize=256)
def _legs(key: tuple, bounces: int):
    p = dict(key)
    acc = _acceleration(p)
    legs = [_fall(tuple((k, v) for k, v in key if k != "e"))]  # the fall before the first impact ignores e
    for bounce in range(bounces):
        t_hit, _, w_hit = legs[-1].end
        if p["e"] == 0:
            break
        speed = -p["e"] * w_hit  # the floor reverses and scales the angular velocity
        rise = _rise_drawn(p, acc, speed, t_hit) or _rise_integrated(p, speed, t_hit, None)
        peak = rise.end[0]
        back = type(rise)(2 * peak - rise.t[::-1], rise.theta[::-1].copy(), -rise.omega[::-1], True)
        legs += [rise, back]
    return tuple(legs)


def _rise_integrated(p, speed: float, t_hit: float, expected: float | None):
    """A rise from θ_I at θ̇ = ``speed`` to its peak, integrated tightly (RTOL, ATOL: a swing too small for
    the energy integral to draw is too small for DRAWING's atol too), in one chunk sized by ``expected``."""
    return integrate_leg(_acceleration(p), p["theta_impact"], speed, t_hit, _horizon(p), stop_at_rest=True,
                         expected=expected, tolerances=(RTOL, ATOL))


def first_rise(p, answers):
    """The first rise after the impact, integrated from its start (θ_I, −e θ̇⁻ of the integrated fall): the
    second method for the rebound angle θ_f. None at e = 0."""
    return _first_rise(_key(p, answers))


@functools.lru_cache(maxsize=256)
def _first_rise(key: tuple):
    p = dict(key)
    fall = _fall(tuple((k, v) for k, v in key if k != "e"))
    if p["e"] == 0:
        return None
    t_hit, _, w_hit = fall.end
    drawn = _rise_drawn(p, _acceleration(p), -p["e"] * w_hit, t_hit)
    return _rise_integrated(p, -p["e"] * w_hit, t_hit, drawn.t[-1] - t_hit if drawn is not None else None)


def _rise_drawn(p, acc, speed: float, t_hit: float):
    """A rise from the impact angle at θ̇ = ``speed``, drawn from energy conservation,
    θ̇² = speed² − 2 (Q/I_O)(sin θ − sin θ_I), up to its peak sin θ_p = sin θ_I + I_O speed²/(2Q);
    None if there is no peak to draw (at rest, or over the top)."""
    Q, I, theta_I = moment_coefficient(p), p["I_O"], p["theta_impact"]
    sin_peak = math.sin(theta_I) + I * speed**2 / (2 * Q)
    if speed == 0 or not -1 < sin_peak < 1:
        return None
    return drawn_to_turn(lambda q: speed**2 - 2 * Q / I * (np.sin(q) - math.sin(theta_I)), acc, theta_I,
                         math.asin(sin_peak), t_hit)


@functools.lru_cache(maxsize=256)
def _fall(key: tuple):
    """From release to the first impact (checks the impact speed)."""
    p = dict(key)
    Q, I, theta0 = moment_coefficient(p), p["I_O"], p["theta0"]
    expected = crossing_time(lambda q: 2 * Q / I * (math.sin(theta0) - np.sin(q)), theta0, p["theta_impact"])
    return integrate_leg(_acceleration(p), theta0, 0.0, 0.0, _horizon(p), stop_at_angle=p["theta_impact"],
                         direction=-1, expected=expected)


def _theta_ddot(Q, I, angle, xp=math):
    """The equation of motion, I θ̈ = −Q cos θ, for θ̈."""
    return -Q * xp.cos(angle) / I


def acceleration(p, a, angle, xp=math):
    """θ̈ at θ = ``angle``: integrated here (odeint, ``_acceleration``) and in the browser (``INTEGRATED``,
    generated)."""
    return _theta_ddot(moment_coefficient(p), a["I_O"], angle, xp)


def _acceleration(p):
    Q, I = moment_coefficient(p), p["I_O"]
    return lambda q: _theta_ddot(Q, I, q)


def horizon(p, a, xp=math) -> float:
    """The longest a leg may take: twenty times the swing's time scale, √(I_O/Q), and a second."""
    return xp.sqrt(a["I_O"] / moment_coefficient(p)) * 20 + 1.0


def _horizon(p) -> float:
    return horizon(p, p)


BOUNCES = 3  # the bounces the animation shows
SEEN = 1e-3  # the slowest rebound drawn, a fraction of the first impact's speed (its height a millionth of the fall's)


def stays(p, w_hit, w_first, xp=np):
    """Whether the animation ends at an impact at θ̇ = ``w_hit`` (the first was at ``w_first``): e = 0, or a
    rebound slower than SEEN of the first impact's speed, whose height (a millionth of the fall's) no
    screen shows, and whose turn no integration places to a microsecond where θ_I is the hanging
    equilibrium (−90° against the wall: a swing of any size turns a quarter period later, and one of
    1e-8 rad is a few units of rounding of θ there). With a margin of 1e-9 beyond an integration's error:
    at e = SEEN the first impact ends it whichever side of the closed form the integrated speed lies."""
    return p["e"] * xp.abs(w_hit) <= SEEN * xp.abs(w_first) * (1 + 1e-9)

# The fall to the surface, each bounce's rise to its peak and its fall back (``simulate``'s legs), in the
# browser (ui/live.py); the state (θ, θ̇); an impact it stays at (``stays``: e = 0) ends it. The bounce leaves from θ_I
# itself, as ``_legs`` does (where the fall's end was located, a rounding past it: at the hanging
# equilibrium, θ_I = −90° against the wall, past it gravity would pull the rod on, not back).
_FALL = Leg("impact", ends=lambda p, a, y, xp: y["theta"] - a["theta_impact"],
            then=lambda p, a, y, xp: {"theta": a["theta_impact"], "omega": -p["e"] * y["omega"]}, framed=True,
            last=lambda p, a, y, xp: stays(p, y["omega"], a["omega_impact"], xp))
_RISE = Leg("peak", ends=lambda p, a, y, xp: y["omega"])


def fastest(p, a, xp=np):
    """The swing's largest |θ̇|: at the lowest point of the first fall, θ = −90° where the fall passes it
    (to a wall beyond the bottom), else the impact (energy only leaves after it)."""
    low = xp.where(xp.less(a["theta_impact"], -math.pi / 2), -1.0, xp.sin(a["theta_impact"]))
    return xp.sqrt(2 * moment_coefficient(p) * xp.maximum(xp.sin(p["theta0"]) - low, 0.0) / a["I_O"])


INTEGRATED = Integrated(
    state=("theta", "omega"), start=lambda p, a, xp: {"theta": p["theta0"], "omega": 0.0},
    rates=lambda p, a, y, xp: {"theta": y["omega"], "omega": acceleration(p, a, y["theta"], xp)},
    legs=(_FALL, *(_RISE, _FALL) * BOUNCES), horizon=horizon, frames=60, curve=400, fastest=fastest,
    tolerances=(1e-12, 1e-12))  # (a release near upright turns slowly: its period is sensitive to the energy)


def _checks(p, a) -> tuple[Check, ...]:
    _, _, _, impacts, _ = simulate(p, a, bounces=BOUNCES)  # (the animation's legs: cached)
    rise = first_rise(p, a)
    checks = [Check("impact speed θ̇⁻ (energy vs. integrating θ̈)", a["omega_impact"], impacts[0][1],
                    relative_tolerance(a["omega_impact"], 1e-7),
                    "the fall conserves energy: the pivot does no work")]
    if rise is not None:
        checks.append(Check(r"rebound angle $\theta_f$ (energy vs. integrating $\ddot\theta$)", a["theta_rebound"],
                            rise.end[1], 1e-7,
                            "after the bounce energy is again conserved up to the peak"))
    # Not (1 − e²) ½ I θ̇⁻²: that is energy_loss's own definition rearranged. Here the kinetic energy
    # at impact comes from the integrated θ̇⁻, and what is left after it from the integrated peak
    # θ_f (the rise turns it all into Q (sin θ_f − sin θ_I)); with e = 0 nothing is left.
    T_before = 0.5 * a["I_O"] * impacts[0][1] ** 2
    T_after = moment_coefficient(p) * (math.sin(rise.end[1]) - math.sin(a["theta_impact"])) if rise is not None else 0.0
    checks.append(Check(r"energy lost: $\tfrac12 I_O (\dot\theta^-)^2 - Q (\sin\theta_f - \sin\theta_I)$, $\dot\theta^-$ and $\theta_f$ integrated",
                        a["energy_loss"], T_before - T_after,
                        relative_tolerance(T_before, 1e-6) + moment_coefficient(p) * 1e-7,
                        "the bounce is the only place energy goes; the swing conserves it"))
    return tuple(checks)


def _drawn_legs(solution: Solution, bounces: int = BOUNCES) -> list:
    """The legs the animation draws: ``simulate``'s, up to the impact the sphere stays at (``stays``)."""
    *_, legs = simulate(solution.params, solution.answers, bounces=bounces)
    seen = next((k + 1 for k in range(0, len(legs), 2) if stays(solution.params, legs[k].end[2], solution.answers["omega_impact"])),
                len(legs))
    return legs[:seen]


@per_solution
def motion(solution: Solution, frames: int | None = None, bounces: int = BOUNCES) -> dict:
    """θ(t) and θ̇(t) through several bounces, integrated, at ``frames`` even in time (by default as many as
    keep each frame's turn small: Integrated.frame_count) plus one at each impact (so the animation shows
    the sphere touching). Between the integrator's samples each leg is
    the quintic through θ, θ̇ and θ̈ (the equation of motion gives θ̈); the legs meet at the impacts,
    where θ̇ jumps. The browser integrates the same frames itself on the lesson page (``INTEGRATED``)."""
    legs = _drawn_legs(solution, bounces)
    impact_times = [leg.end[0] for leg in legs[0::2]]
    start, end = legs[0].t[0], legs[-1].end[0]
    count = frames or INTEGRATED.frame_count(solution.params, solution.answers, end - start)
    t = frame_instants(start, end, count, impact_times)
    theta, omega = _on_legs(legs, t, solution.params, solution.answers)
    return {"t": t, "theta": theta, "omega": omega, "impact_times": impact_times}


@per_solution
def curve(solution: Solution, points: int = INTEGRATED.curve, bounces: int = BOUNCES) -> tuple[np.ndarray, np.ndarray]:
    """θ(t) densely for its plot below the motion, ``points`` instants even in time and each impact (the
    cusps land on θ_I): (t, θ)."""
    legs = _drawn_legs(solution, bounces)
    t = frame_instants(legs[0].t[0], legs[-1].end[0], points, [leg.end[0] for leg in legs[0::2]])
    return t, _on_legs(legs, t, solution.params, solution.answers)[0]


def _on_legs(legs, times: np.ndarray, p, a) -> tuple[np.ndarray, np.ndarray]:
    """θ and θ̇ at ``times`` (sorted), each from the leg it falls in (an impact's time: the leg that
    ends there, at θ_I with the speed before): between its samples, the quintic through θ, θ̇ and θ̈."""
    theta, omega = np.empty_like(times), np.empty_like(times)
    start = 0
    for leg in legs:
        t_leg, keep = np.unique(leg.t, return_index=True)
        stop = int(np.searchsorted(times, t_leg[-1], side="right"))
        inside = slice(start, stop)
        if len(t_leg) > 1:
            theta[inside], omega[inside] = hermite_on_knots(t_leg, leg.theta[keep], leg.omega[keep], times[inside],
                                                            acceleration(p, a, leg.theta[keep], np))
        else:
            theta[inside], omega[inside] = leg.theta[0], leg.omega[0]
        start = stop
    theta[start:], omega[start:] = legs[-1].theta[-1], legs[-1].omega[-1]
    return theta, omega


def method(params) -> tuple[Step, ...]:
    """The symbolic steps for ``params`` without numbers, shown beside a refusal (a release below
    the impact angle): they say where the sphere touches."""
    p = validate_params(PARAMS, params)
    return derivation(p["sphere"], p["surface"]).steps


def derivation_of(solution: Solution) -> Derivation:
    """The derivation behind ``solution`` (its option and regime)."""
    return derivation(solution.params["sphere"], solution.params["surface"])


# How ?seed=N varies the parameters beyond the general rule (solvers.protocol.Variants).
VARIANTS = Variants(angles_deg={"theta0": (-20, 60)})

WARM: tuple[dict, ...] = ()  # every option combination is warmed already


# The typical slips practice mode names: wrong expressions in this module's symbols, each
# with the feedback a tutor would give (the hint never states the right value).
MISTAKES = (
    Mistake("I_O", "½ m r² is a disk's moment of inertia; a solid sphere has ⅖ m r² (the worked "
            "solution's slip).", lambda p: m_r * L**2 / 3 + m_s * r**2 / 2 + m_s * (L + r) ** 2,
            lambda p: p["sphere"] == "solid"),
    Mistake("I_O", "Missing parallel-axis terms: about O each body adds its mass times the square "
            "of its centre's distance from O.", lambda p: m_r * L**2 / 12 + SPHERE_INERTIA[p["sphere"]] * m_s * r**2),
    Mistake("I_O", "The rod turns about its end, not its middle: ¹⁄₁₂ m_r L² is its inertia about its centre.",
            lambda p: m_r * L**2 / 12 + SPHERE_INERTIA[p["sphere"]] * m_s * r**2
            + m_s * (L + r) ** 2),
    Mistake("theta_rebound", "e where e² belongs: energy scales with θ̇², so the swing keeps e² of it.",
            lambda p: sp.asin(sp.sin(theta_I) + e * (sp.sin(theta0) - sp.sin(theta_I))),
            lambda p: p["e"] not in (0, 1)),
    Mistake("theta_impact", "A sign: the floor is below the pivot, so sin θ_I is negative "
            "(the worked solution's slip).", lambda p: sp.asin((d - r) / (L + r)),
            lambda p: p["surface"] == "floor"),
    Mistake("omega_after", "A sign: the rod reverses its direction of rotation at the bounce.",
            lambda p: e * w_minus),
)
