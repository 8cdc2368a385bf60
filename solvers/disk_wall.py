"""A spinning uniform disk strikes a rough straight wall (ME 230 review, problem 1).

Model: rigid uniform disk, I_C = ½ m R², in the plane; the wall is fixed. Axes: x along the wall,
y the wall normal pointing from the disk into the wall, ω counter-clockwise (E_z out of the page).
The contact point is B = C + R E_y. The impact is instantaneous: gravity and any finite force are
negligible against the impulse P = P_t E_x + P_n E_y at B. Newton's restitution e acts on the
normal velocity of B; Coulomb friction μ bounds the tangential impulse, |P_t| ≤ μ |P_n|.
μ = ∞ (the worked solution's assumption) means B does not slip at the end of the impact. For a uniform
disk the tangential and normal directions are uncoupled at B, so with finite μ either the impact
ends in sticking or B slides in one direction throughout.
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
    Derivation,
    LedgerRow,
    Number,
    Result,
    Solution,
    Step,
    latex,
    latex_eq,
    relative_tolerance,
    validate_params,
    per_solution,
)
from .diagram import Body, DiagramSlip, Circle, Diagram, Load, balance, balance_steps, fbd_steps
from .live import Case, Live
from .protocol import About, Mistake, RegimeQuestion, Variants

ABOUT = About(
    title="Spinning disk hits a rough wall",
    group="Impacts",
    blurb="A spinning disk strikes a wall: does it stick or slide, and where does it go?",
    icon=":material/sports_hockey:",
    source="ME 230 final-exam review, problem 1",
    primary=("V", "omega", "theta", "e", "mu"),  # always shown; the rest sit behind "More parameters"
)

PARAMS = (
    Number("m", 1.0, "mass", "mass", "m", low=0, ui_low=0.1, ui_high=10.0, step=0.1),
    Number("R", 0.1, "radius", "length", "R", low=0, ui_low=0.01, ui_high=1.0, step=0.01),
    Number("V", 2.0, "speed before impact", "speed", "V", low=0, ui_low=0.1, ui_high=10.0, step=0.1,
           help="The disk must be moving toward the wall."),
    Number("theta", math.radians(30), "angle of approach from the wall normal", "angle", r"\theta",
           low=0, high=math.pi / 2, low_inclusive=True, ui_low=0, ui_high=89, step=1.0),
    Number("omega", 5.0, "angular velocity before impact (counter-clockwise +)", "angular_speed",
           r"\omega", ui_low=-50.0, ui_high=50.0, step=0.5),
    Number("e", 1.0, "coefficient of restitution", "dimensionless", "e", low=0, high=1,
           low_inclusive=True, high_inclusive=True, ui_low=0, ui_high=1, step=0.05),
    Number("mu", math.inf, "wall friction coefficient", "dimensionless", r"\mu",
           low=0, low_inclusive=True, allow_inf=True, ui_low=0, ui_high=2, step=0.05),
)

ANSWERS = (
    Answer("v1x", "velocity after, along the wall", r"v_{1x}", "speed"),
    Answer("v1y", "velocity after, wall normal", r"v_{1y}", "speed"),
    Answer("omega1", "angular velocity after", r"\omega_1", "angular_speed"),
    Answer("speed1", "speed after", r"v_1", "speed"),
    Answer("impulse_t", "tangential impulse on the disk", r"P_t", "impulse"),
    Answer("impulse_n", "normal impulse on the disk", r"P_n", "impulse"),
    Answer("energy_loss", "kinetic energy lost", r"\Delta T", "energy"),
)

ERRATA = (
    r"The worked solution writes $v_{1y} = +V\cos\theta$ (“magnitude conserved”). After an elastic impact "
    r"the normal component **reverses**: $v_{1y} = -eV\cos\theta$, pointing away from the wall.",
)

LIMIT_LABELS: dict[str, tuple[str, str]] = {}  # no physical limit to show

m, R, V, theta, omega, e, mu = sp.symbols(r"m R V theta omega e mu", positive=True)
omega = sp.Symbol(r"omega", real=True)
sigma = sp.Symbol(r"sigma", real=True)  # direction of slip of B before impact, ±1
v1x, v1y, omega1, P_t, P_n, speed1, T_minus, T_plus, loss = sp.symbols(
    r"v_{1x} v_{1y} omega_1 P_t P_n v_1 T^- T^+ \Delta{T}", real=True
)
SYMBOLS = {"m": m, "R": R, "V": V, "theta": theta, "omega": omega, "e": e, "mu": mu,
           "slip_direction": sigma}
DIMENSIONS = {p.name: p.dimension for p in PARAMS if isinstance(p, Number)} | {
    "slip_direction": "dimensionless"}


def _vec(*components) -> sp.Matrix:
    return sp.Matrix(components)


I_C = sp.Rational(1, 2) * m * R**2


def _impact_values(solution) -> dict:
    """Every symbol of the impact's diagram, from the solution (its answers are the solver's)."""
    return _impact_values_of(solution.params, solution.answers)


def _impact_values_of(p, a) -> dict:
    return {m: p["m"], R: p["R"], V: p["V"], theta: p["theta"], omega: p["omega"], P_t: a["impulse_t"],
            P_n: a["impulse_n"], v1x: a["v1x"], v1y: a["v1y"], omega1: a["omega1"]}


def _impact_frames(solution, motion) -> dict:
    """The impact's symbols at each frame of ``motion``: its values at the impact's frame (the centre
    at the origin there, as in the diagram), NaN in every other (the impulse acts at that instant only)."""
    at = np.arange(len(motion["t"])) == motion["impact_index"]
    return {sym: np.where(at, value, np.nan) for sym, value in _impact_values(solution).items()}


# Step 2: the disk at the impact. The wall's impulse at B is the only one: gravity and the table's
# support are finite (and act out of the plane), negligible against it over the impact's instant.
IMPACT = Diagram(
    "impact", "At the impact", "impulse",
    bodies=(Body("the disk", points={"C": (0, 0), "B": (0, R)}, centre="C", about="C",
                 kinetic=(m * (v1x - V * sp.sin(theta)), m * (v1y - V * sp.cos(theta)), I_C * (omega1 - omega)),
                 kinetic_latex=(r"m\left(v_{1x} - V\sin\theta\right)", r"m\left(v_{1y} - V\cos\theta\right)",
                                r"I_C\left(\omega_1 - \omega\right)"),
                 outline=(Circle("C", R),)),),
    loads=(Load("P", "the wall's impulse", "the wall", "the disk", at="B", kind="impulse",
                components=(P_t, P_n)),),
    values=_impact_values,
    frames=_impact_frames,
    key=_impact_values_of,  # the stage's key frame is the impact
    note="Gravity and the table's support are finite and act out of the plane: negligible against the impulse.",
)


def free_body_diagrams(params) -> tuple[Diagram, ...]:
    """The diagrams the derivation uses, for these parameters (one: the impact's instant)."""
    return (IMPACT,)


# The classic slips in drawing this diagram (practice/diagram_judge.py), as MISTAKES are the answers':
# each a load the physics does not put there, with a tutor's words that never show the diagram.
DIAGRAM_SLIPS = (
    DiagramSlip("force of motion", "no force or impulse carries the disk along its velocity: before the "
                "impact it keeps moving by its own momentum.", on="the disk", direction=(sp.sin(theta), sp.cos(theta))),
    DiagramSlip("weight in the table's plane", "the disk slides on a horizontal table: its weight and the table's "
                "support act out of this plane and balance each other (and over the impact's instant a finite "
                "force adds no impulse).", on="the disk", direction=(0, -1)),
)



@functools.cache
@kept_pickled
def derivation(regime: str) -> Derivation:
    """The symbolic derivation for ``regime`` = "stick" or "slip" (done once per process)."""
    v_before = _vec(V * sp.sin(theta), V * sp.cos(theta), 0)
    r_BC = _vec(0, R, 0)
    v_B_before = v_before + _vec(0, 0, omega).cross(r_BC)
    v_after = _vec(v1x, v1y, 0)
    v_B_after = v_after + _vec(0, 0, omega1).cross(r_BC)
    linear_x, linear_y, angular = balance(IMPACT, "the disk")  # written from the diagram (Step 3)
    linear = [linear_x, linear_y]
    restitution = sp.Eq(v1y, -e * v_before[1])
    if regime == "stick":
        tangential = sp.Eq(v_B_after[0], 0)
    else:
        tangential = sp.Eq(P_t, -sigma * mu * (1 + e) * m * V * sp.cos(theta))
    solved = sp.solve([*linear, angular, restitution, tangential], [v1x, v1y, omega1, P_t, P_n],
                      dict=True)[0]
    solved = {k: sp.factor_terms(sp.expand(v)) for k, v in solved.items()}

    T = lambda v, w: sp.Rational(1, 2) * m * (v[0] ** 2 + v[1] ** 2) + sp.Rational(1, 2) * I_C * w**2
    steps = [
        Step(r"Origin at the centre C at the instant of impact; $\mathbf{E}_x$ along the wall, $\mathbf{E}_y$ "
             r"the wall's normal into the wall, $\mathbf{E}_z$ out of the page (ω counter-clockwise +). "
             "Velocity of the centre before impact",
             latex(sp.Eq(sp.Symbol(r"\mathbf{v}_C^-"), v_before[:2, :], evaluate=False)), part=1),
        Step(r"Velocity of the contact point $B = C + R\,\mathbf{E}_y$: $\mathbf{v}_B = \mathbf{v}_C + \omega\mathbf{E}_z \times R\,\mathbf{E}_y$",
             latex(sp.Eq(sp.Symbol(r"\mathbf{v}_B^-"), v_B_before[:2, :], evaluate=False)), part=1),
        *fbd_steps(IMPACT),
        *balance_steps(IMPACT),
        Step("Newton's restitution on the normal velocity (the normal component reverses)",
             latex(restitution)),
    ]
    if regime == "stick":
        steps.append(Step(r"No slip at B at the end of the impact: $\mathbf{v}_B^+ \cdot \mathbf{E}_x = 0$",
                          latex(tangential)))
    else:
        steps.append(Step(
            r"B slides throughout: friction is at its limit $\mu\lvert P_n\rvert$ and opposes the slip "
            "(σ = sign of the slip velocity of B before impact)", latex(tangential)))
    steps.append(Step("Solve the five linear equations",
                      r" ,\quad ".join(latex_eq(k, solved[k]) for k in (v1x, omega1, P_t, P_n))))
    if regime == "stick":
        steps.append(Step(r"Friction must supply this: no slip is possible only while $\lvert P_t\rvert \le \mu\lvert P_n\rvert$",
                          r"\left|P_t\right| \le \mu \left|P_n\right|"))
    steps.append(Step("Angular momentum about the contact point B is conserved (the impulse has "
                      "no moment about B); the worked solution's route",
                      latex_eq(I_C * omega + m * R * v_before[0], I_C * omega1 + m * R * v1x)))

    chain = [
        Result("impulse_n", P_n, solved[P_n], "impulse"),
        Result("impulse_t", P_t, solved[P_t], "impulse"),
        Result("v1x", v1x, solved[v1x], "speed"),
        Result("v1y", v1y, solved[v1y], "speed"),
        Result("omega1", omega1, solved[omega1], "angular_speed"),
        Result("speed1", speed1, sp.sqrt(v1x**2 + v1y**2), "speed"),
        Result("T_before", T_minus, T(v_before, omega), "energy", "Kinetic energy before"),
        Result("T_after", T_plus, T(_vec(v1x, v1y), omega1), "energy", "Kinetic energy after"),
        Result("energy_loss", loss, T_minus - T_plus, "energy"),
    ]
    return Derivation(SYMBOLS, DIMENSIONS, steps, chain, {a.name: a.label for a in ANSWERS})



def _live_cases() -> tuple[Case, ...]:
    """Stick when the no-slip impulse is within the friction cone (as ``solve`` decides), else slip.
    (μ = ∞: ∞·|P_n| holds any |P_t|, P_n being never zero.)"""
    stick = derivation("stick")
    return (Case("stick", "B sticks: the contact stops slipping", stick,
                 sp.Abs(P_t) <= mu * sp.Abs(P_n) * (1 + sp.Float(1e-12)),
                 {"slip_direction": sp.Integer(0)}),
            Case("slip", "B slides throughout the impact: friction at its limit", derivation("slip"),
                 inputs={"slip_direction": sp.sign(V * sp.sin(theta) - R * omega)}))


# Live while dragging (solvers/live.py): the approach, the spin, e and μ.
LIVE = Live(("V", "omega", "theta", "e", "mu"), _live_cases)

@within_model_range
def solve(**params) -> Solution:
    p = validate_params(PARAMS, params)
    values = dict(p, slip_direction=0.0)
    stick = derivation("stick").evaluate(values)
    slip_before = p["V"] * math.sin(p["theta"]) - p["R"] * p["omega"]
    sticks = math.isinf(p["mu"]) or abs(stick["impulse_t"]) <= p["mu"] * abs(stick["impulse_n"]) * (
        1 + 1e-12)
    regime = "stick" if sticks else "slip"
    if sticks:
        result = stick
    else:
        values["slip_direction"] = math.copysign(1.0, slip_before)
        result = derivation("slip").evaluate(values)
    d = derivation(regime)
    steps = list(d.steps) + d.numeric_steps(result)
    answers = {a.name: result[a.name] for a in ANSWERS}
    return Solution("disk_wall", p, answers, tuple(steps), _checks(p, answers), regime,
                    _notes(p, answers, regime, slip_before), _ledger(p, result),
                    extras={"chain_inputs": {"slip_direction": values["slip_direction"]}})


def _ledger(p, v) -> tuple[LedgerRow, ...]:
    m_ = p["m"]
    vx0, vy0 = p["V"] * math.sin(p["theta"]), p["V"] * math.cos(p["theta"])
    return (
        LedgerRow("momentum along the wall, $m v_x$", m_ * vx0, m_ * v["v1x"], "impulse",
                  "changed by the friction impulse $P_t$" if v["impulse_t"] else "no friction impulse"),
        LedgerRow("momentum into the wall, $m v_y$", m_ * vy0, m_ * v["v1y"], "impulse",
                  "reversed by the wall's normal impulse" if p["e"] > 0 else
                  "stopped by the wall's normal impulse (e = 0: no rebound)"),
        LedgerRow(r"angular momentum about B, $I\omega + m R v_x$", _H_B(p, p["omega"], vx0),
                  _H_B(p, v["omega1"], v["v1x"]), "angular_momentum", "the whole impulse acts at B"),
        LedgerRow("kinetic energy", v["T_before"], v["T_after"], "energy", _energy_reason(p, v)),
    )


def _H_B(p, omega, vx) -> float:
    """Angular momentum about the contact point B: I_C ω + m R v_x (C is R below B)."""
    return 0.5 * p["m"] * p["R"] ** 2 * omega + p["m"] * p["R"] * vx


def _energy_reason(p, v) -> str:
    causes = []
    if p["e"] < 1:
        causes.append(f"restitution (e = {p['e']:g} < 1)")
    if abs(v["impulse_t"]) > 1e-12 * abs(v["impulse_n"]):
        causes.append("friction working against the slip at B")
    return ("lost to " + " and ".join(causes)) if causes else "elastic, and no friction work"


def _checks(p, a) -> tuple[Check, ...]:
    m_, R_, I_C = p["m"], p["R"], 0.5 * p["m"] * p["R"] ** 2
    vx0, vy0 = p["V"] * math.sin(p["theta"]), p["V"] * math.cos(p["theta"])
    H_B_before, H_B_after = _H_B(p, p["omega"], vx0), _H_B(p, a["omega1"], a["v1x"])
    # Kelvin's theorem: the work of an impulse is P · (v_B⁻ + v_B⁺)/2 at its point of action.
    vB_before = (vx0 - R_ * p["omega"], vy0)
    vB_after = (a["v1x"] - R_ * a["omega1"], a["v1y"])
    work = (a["impulse_t"] * (vB_before[0] + vB_after[0]) + a["impulse_n"] * (vB_before[1] + vB_after[1])) / 2
    return (
        Check("angular momentum about B", H_B_before, H_B_after,
              relative_tolerance(I_C * abs(p["omega"]) + m_ * R_ * p["V"], 1e-9),
              "conserved: the wall's impulse acts at B, so it has no moment about B"),
        Check("linear momentum along x", m_ * (a["v1x"] - vx0), a["impulse_t"],
              relative_tolerance(m_ * (p["V"] + R_ * abs(p["omega"])), 1e-9),
              "changes by exactly the friction impulse"),
        Check("energy lost = −work of the impulse (Kelvin)", a["energy_loss"], -work,
              relative_tolerance(0.5 * m_ * p["V"] ** 2 + 0.5 * I_C * p["omega"] ** 2, 1e-9),
              "never negative; zero only for e = 1 with no slip work"),
    )


def _notes(p, a, regime, slip_before) -> tuple[str, ...]:
    if regime == "stick":
        if math.isinf(p["mu"]):
            note = "Rough wall (μ = ∞): B stops slipping; the worked solution's assumption."
        else:
            note = (f"Sticks: no slip needs |P_t| = {plain_number(abs(a['impulse_t']))} N·s, within "
                    f"μ|P_n| = {plain_number(p['mu'] * abs(a['impulse_n']))} N·s.")
    else:
        note = (f"Slides: no slip would need more friction than μ|P_n| = "
                f"{plain_number(p['mu'] * abs(a['impulse_n']))} N·s, so B slides "
                f"{'forward (+x)' if slip_before > 0 else 'backward (−x)'} through the whole impact.")
    return (note,)


def frame_times(p, a, frames: int = 40, xp=np) -> list:
    """The motion's instants: ``frames`` of them, evenly spaced over the time the centre takes to move 3R
    before the impact (t = 0, exactly, the last of the first half) and 3R after it (at least a quarter
    of V: a disk that barely leaves still leaves the view slowly). ``xp``: numpy, or solvers.live's
    namespace for expressions (the browser's motion, generated from this)."""
    t_in = 3.0 * p["R"] / p["V"]
    t_out = 3.0 * p["R"] / xp.maximum(a["speed1"], 0.25 * p["V"])
    n_in, n_out = frames // 2, frames - frames // 2 - 1
    return [*(-t_in + t_in * i / n_in for i in range(n_in)), 0.0, *(t_out * j / n_out for j in range(1, n_out + 1))]


def state_at(p, a, t, xp=np) -> dict:
    """The centre's position and velocity and the disk's turn at time ``t`` (the impact at t = 0 with the
    centre at the origin, the wall at y = R): straight lines at the velocities before and after."""
    vx0, vy0 = p["V"] * xp.sin(p["theta"]), p["V"] * xp.cos(p["theta"])
    after = xp.less(0, t)

    def pick(later, before):
        return xp.where(after, later, before)
    return {"x": pick(a["v1x"] * t, vx0 * t), "y": pick(a["v1y"] * t, vy0 * t),
            "angle": pick(a["omega1"] * t, p["omega"] * t), "vx": pick(a["v1x"], vx0), "vy": pick(a["v1y"], vy0)}


@per_solution
def motion(solution: Solution, frames: int = 40) -> dict:
    """The motion through the impact, frame by frame (``frame_times``, ``state_at``)."""
    p, a = solution.params, solution.answers
    t = np.array(frame_times(p, a, frames))
    return {"t": t, **state_at(p, a, t), "impact_index": frames // 2, "wall_y": p["R"]}


def derivation_of(solution: Solution) -> Derivation:
    """The derivation behind ``solution`` (its option and regime)."""
    return derivation(solution.regime)


# How ?seed=N varies the parameters beyond the general rule (solvers.protocol.Variants).
VARIANTS = Variants(angles_deg={"theta": (10, 70)})

# Solved at server start besides every option combination: the sliding regime's derivation, which
# no option reaches (the default μ = ∞ never slides).
WARM = ({"mu": 0.01, "omega": -40.0},)


# The typical slips practice mode names: wrong expressions in this module's symbols, each
# with the feedback a tutor would give (the hint never states the right value).
MISTAKES = (
    Mistake("v1y", "A sign: the normal component of the velocity reverses at the wall "
            "(the worked solution's slip).", lambda p: e * V * sp.cos(theta)),
    Mistake("v1y", "The restitution coefficient is missing from the normal component.",
            lambda p: -V * sp.cos(theta), lambda p: p["e"] != 1),
    Mistake("v1x", "That is the velocity of a ring (I = m R²); a uniform disk has I_G = ½ m R².",
            lambda p: (V * sp.sin(theta) + R * omega) / 2, lambda p: p["mu"] == float("inf")),
    Mistake("v1x", "The spin term's sign: with ω counter-clockwise, B moves at v_x − Rω.",
            lambda p: sp.Rational(2, 3) * V * sp.sin(theta) - R * omega / 3,
            lambda p: p["mu"] == float("inf")),
    Mistake("v1x", "That is a smooth wall (μ = 0): here friction acts at B.",
            lambda p: V * sp.sin(theta), lambda p: p["mu"] > 0),
    Mistake("omega1", "That is the spin of a ring (I = m R²); a uniform disk has I_G = ½ m R².",
            lambda p: (V * sp.sin(theta) + R * omega) / (2 * R), lambda p: p["mu"] == float("inf")),
    Mistake("omega1", "The spin term's sign: with ω counter-clockwise, B moves at v_x − Rω.",
            lambda p: (sp.Rational(2, 3) * V * sp.sin(theta) - R * omega / 3) / R,
            lambda p: p["mu"] == float("inf")),
)

# What a lecture hall may be asked before the motion is shown (ui/room.py), besides the answers.
ROOM_QUESTIONS = (
    RegimeQuestion("stick_or_slip", "During the impact, does the disk's rim stick to the wall or slide along it?",
                   (("stick", "It sticks: B stops sliding"), ("slip", "It slides the whole time")),
                   lambda p: solve(**p).regime),
)
