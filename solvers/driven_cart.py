"""A four-wheeled cart accelerated by its driven wheels (O'Reilly 9.3).

Model: rigid cart of mass m translating along E_x (no pitch, all four wheels on the ground), CM at
height a, axles at x = ±b from the CM (front at +b), wheels at z = ±c. Wheels are massless; each
driven wheel pushes forward with traction at the friction limit, F_i = μ N_i, and the free wheels
carry no traction. Wheel numbering follows the worked solution: 1 (rear, +c), 2 (front, +c), 3 (front, −c),
4 (rear, −c). Nine unknowns (four normal forces, four lateral forces, ẍ) meet six equations, so,
as in the worked solution, the lateral forces are taken as zero and the load as symmetric left to right.
Rear- and all-wheel drive unload the front axle and lift it once μa ≥ b; the model then no
longer applies (a wheelie) and ``solve`` refuses.
"""
from __future__ import annotations

import functools

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
    Number,
    PhysicalLimitError,
    Result,
    Solution,
    Step,
    latex,
    latex_eq,
    relative_tolerance,
    validate_params,
    per_solution,
)
from .diagram import Body, DiagramSlip, Circle, Diagram, Load, Outline, balance, balance_steps, fbd_steps
from .live import Case, Live
from .sweeps import swept
from .protocol import About, Mistake, RegimeQuestion, Variants

ABOUT = About(
    title="Cart with driven wheels",
    group="Newton–Euler",
    blurb="Front, rear or all-wheel drive: how hard can it accelerate before the front lifts?",
    icon=":material/directions_car:",
    source="O'Reilly 9.3",
    primary=("mu", "drive", "a", "b"),  # always shown; the rest sit behind "More parameters"
)

PARAMS = (
    Number("m", 1200.0, "mass", "mass", "m", low=0, ui_low=100.0, ui_high=5000.0, step=50.0),
    Number("a", 0.5, "height of the CM", "length", "a", low=0, ui_low=0.05, ui_high=3.0, step=0.05),
    Number("b", 1.3, "half wheelbase", "length", "b", low=0, ui_low=0.1, ui_high=3.0, step=0.05),
    Number("c", 0.75, "half track", "length", "c", low=0, ui_low=0.1, ui_high=2.0, step=0.05,
           help="Drops out of the planar answer."),
    Number("mu", 0.8, "friction coefficient at the driven wheels", "dimensionless", r"\mu", low=0,
           low_inclusive=True, ui_low=0.0, ui_high=3.0, step=0.05),
    Number("g", 9.81, "gravity", "acceleration", "g", low=0, ui_low=0.5, ui_high=30.0, step=0.01),
    Choice("drive", "front", "driven wheels", ("front", "rear", "all"),
           ("front-wheel drive (the worked solution)", "rear-wheel drive", "all-wheel drive")),
)

ANSWERS = (
    Answer("accel", "acceleration of the CM", r"\ddot{x}_C", "acceleration"),
    Answer("N_front", "normal force on one front wheel", r"N_{\mathrm{front}}", "force"),
    Answer("N_rear", "normal force on one rear wheel", r"N_{\mathrm{rear}}", "force"),
    Answer("F_drive", "total traction force", r"F_{\mathrm{drive}}", "force"),
)

ERRATA = (
    r"In the worked solution, the driven wheels 2 and 3 (at $+b$) are the front, yet the line "
    r"“$N_1 = N_4 = N_\mathrm{front}$, $N_2 = N_3 = N_\mathrm{rear}$” swaps the names; its equations (7)–(10) "
    r"and boxed results are right. Accelerating moves load to the **rear** axle, so driven front "
    r"wheels are the *unloaded* ones.",
    r"The worked solution's moment sum drops the traction's yaw term $c\mu(N_2 - N_3)$; it cancels by the "
    r"left–right symmetry, so the answers stand.",
)

m, a, b, c, mu, g = sp.symbols("m a b c mu g", positive=True)
xdd = sp.Symbol(r"\ddot{x}_C", real=True)
N = sp.symbols("N_1 N_2 N_3 N_4", real=True)
Nz = sp.symbols("N_{1z} N_{2z} N_{3z} N_{4z}", real=True)
N_front, N_rear, F_drive = sp.symbols(r"N_{\mathrm{front}} N_{\mathrm{rear}} F_{\mathrm{drive}}", real=True)  # (words: upright)
SYMBOLS = {"m": m, "a": a, "b": b, "c": c, "mu": mu, "g": g}
DIMENSIONS = {p.name: p.dimension for p in PARAMS if isinstance(p, Number)}

#: Wheel contact points relative to the CM: (x, y, z). 1 rear left, 2 front left, 3 front right, 4 rear right.
WHEELS = ((-b, -a, c), (b, -a, c), (b, -a, -c), (-b, -a, -c))
DRIVEN = {"front": (1, 2), "rear": (0, 3), "all": (0, 1, 2, 3)}


def balance_equations(drive: str) -> list[sp.Eq]:
    """The six Newton–Euler equations: ΣF = m ẍ E_x and ΣM_C = 0 (the cart does not rotate)."""
    force_total = sp.zeros(3, 1)
    moment_total = sp.zeros(3, 1)
    for i, position in enumerate(WHEELS):
        traction = mu * N[i] if i in DRIVEN[drive] else 0
        force = sp.Matrix([traction, N[i], Nz[i]])
        force_total += force
        moment_total += sp.Matrix(position).cross(force)
    force_total += sp.Matrix([0, -m * g, 0])
    return [sp.Eq(force_total[0], m * xdd), sp.Eq(force_total[1], 0), sp.Eq(force_total[2], 0),
            *(sp.Eq(sp.expand(moment_total[i]), 0) for i in range(3))]


SYMMETRY = {N[0]: N_rear, N[3]: N_rear, N[1]: N_front, N[2]: N_front,
            Nz[0]: 0, Nz[1]: 0, Nz[2]: 0, Nz[3]: 0}


# Step 2: the cart from the side (front to the right), in the stage's coordinates (viz.driven_cart and
# ``motion``): the origin O on the ground below the centre of mass C at the start, x forward, y up; C at
# (x_C, a). Each axle's two wheels drawn as one, carrying 2N (the loads symmetric left to right, the
# lateral forces zero: the worked solution's assumption); the driven axles push forward with traction at
# the friction limit, 2μN; the free wheels (massless) carry none, and none is drawn.
x_C = sp.Symbol("x_C", real=True)
_WHEEL = sp.Min(sp.Rational(3, 10) * b, sp.Rational(3, 5) * a)  # as the stage draws them (viz.driven_cart)
_TOP = sp.Max(2 * a, sp.Rational(11, 5) * _WHEEL)
_BOTTOM = sp.Rational(9, 10) * _WHEEL
#: C the centre of mass, F and R the front (wheels 2, 3) and rear (1, 4) contact points; "_" points only
#: shape the outline (the body's corners, the wheels' hubs).
_CART_POINTS = {"C": (x_C, a), "F": (x_C + b, 0), "R": (x_C - b, 0),
                "_front_hub": (x_C + b, _WHEEL), "_rear_hub": (x_C - b, _WHEEL),
                "_1": (x_C - b - _WHEEL, _BOTTOM), "_2": (x_C + b + _WHEEL, _BOTTOM),
                "_3": (x_C + b + _WHEEL, _TOP), "_4": (x_C - b - _WHEEL, _TOP)}
AXLES = (("front", "F", N_front), ("rear", "R", N_rear))


def cart_shape(a_: float, b_: float) -> tuple[dict[str, tuple[float, float]], float]:
    """The cart's named points and corners (``_CART_POINTS``) in metres at rest (x_C = 0), and its wheels'
    radius, for a CM height ``a_`` and half wheelbase ``b_``: the problem's sketch draws them."""
    at = {a: a_, b: b_, x_C: 0.0}
    return ({name: (float(sp.sympify(x).subs(at)), float(sp.sympify(y).subs(at))) for name, (x, y) in _CART_POINTS.items()},
            float(_WHEEL.subs(at)))
DRIVEN_AXLES = {"front": ("front",), "rear": ("rear",), "all": ("front", "rear")}


def _cart_values(solution) -> dict:
    """Every symbol at the start, x_C = 0 (the instant drawn: the forces are the same at every instant,
    the acceleration being constant). The numbers come from the second method, the worked solution's six
    wheel-by-wheel equations solved numerically (``_wheel_by_wheel``), not from the side view's balance
    laws that the derivation solves."""
    p = solution.params
    wheels = _wheel_by_wheel(p)
    return {m: p["m"], a: p["a"], b: p["b"], mu: p["mu"], g: p["g"], x_C: 0.0, xdd: wheels[8],
            N_front: wheels[1], N_rear: wheels[0]}


def _cart_key(p, answers) -> dict:
    """At the stage's key frame, the start: the side view's own answers (a drag's live values)."""
    return {m: p["m"], a: p["a"], b: p["b"], mu: p["mu"], g: p["g"], x_C: 0, xdd: answers["accel"],
            N_front: answers["N_front"], N_rear: answers["N_rear"]}


def _cart_frames(solution, motion) -> dict:
    """The same at every frame of ``motion``, the cart at the motion's x (x_C = 0 at the first frame)."""
    values = _cart_values(solution)
    frames = len(motion["t"])
    return {sym: (np.asarray(motion["x"], dtype=float) if sym is x_C else np.full(frames, value))
            for sym, value in values.items()}


@functools.cache
def side_view(drive: str) -> Diagram:
    """The cart's free-body diagram for this drive: the weight at C, each axle's normal force 2N at its
    contact point, the driven axles' traction 2μN there, forward."""
    loads = [Load("m g", "the weight", "gravity", "the cart", at="C", direction=(0, -1), size=m * g)]
    for axle, point, load in AXLES:
        loads.append(Load(rf"2N_{{\mathrm{{{axle}}}}}", f"the ground's normal force on the {axle} wheels",
                          "the ground", "the cart", at=point, direction=(0, 1), size=2 * load))
    for axle, point, load in AXLES:
        if axle in DRIVEN_AXLES[drive]:
            loads.append(Load(rf"2\mu N_{{\mathrm{{{axle}}}}}", f"the ground's traction on the driven {axle} wheels",
                              "the ground", "the cart", at=point, direction=(1, 0), size=2 * mu * load))
    cart = Body("the cart", points=_CART_POINTS, centre="C", about="C", kinetic=(m * xdd, 0, 0),
                kinetic_latex=(r"m\ddot{x}_C", "0", "0"),
                outline=(Outline(("_1", "_2", "_3", "_4")), Circle("_front_hub", _WHEEL), Circle("_rear_hub", _WHEEL)))
    free = [axle for axle, _, _ in AXLES if axle not in DRIVEN_AXLES[drive]]
    wheels = (f"the {free[0]} wheels are free: massless, they carry no traction; " if free else "")
    return Diagram(drive, "Accelerating", "force", bodies=(cart,), loads=tuple(loads), values=_cart_values,
                   frames=_cart_frames, key=_cart_key, note=("Seen from the side: each axle's two wheels as one (the loads "
                   f"symmetric left to right, no lateral forces); {wheels}the cart translates, so the moments "
                   "about C balance."))


def free_body_diagrams(params) -> tuple[Diagram, ...]:
    """The side view for this drive (one diagram: the forces are the same throughout)."""
    return (side_view(params["drive"]),)


# The classic slips in drawing this diagram (practice/diagram_judge.py), as MISTAKES are the answers':
# each a load the physics does not put there, with a tutor's words that never show the diagram.
DIAGRAM_SLIPS = (
    DiagramSlip("traction at a free wheel", "those wheels are not driven: a free-rolling wheel of negligible mass "
                "takes no friction from the ground.", at="R", direction=(1, 0), either_way=True, phase="front"),
    DiagramSlip("traction at a free wheel", "those wheels are not driven: a free-rolling wheel of negligible mass "
                "takes no friction from the ground.", at="F", direction=(1, 0), either_way=True, phase="rear"),
    DiagramSlip("m a drawn as a force", "m a is what the forces produce, the balance laws' other side; it is not a "
                "force on the cart.", at="C", direction=(1, 0), either_way=True),
)



def _same_equations(these, those) -> bool:
    """Whether two lists of equations are the same up to each one's sign (sides swapped)."""
    left = [sp.expand(e.lhs - e.rhs) for e in these]
    right = [sp.expand(e.lhs - e.rhs) for e in those]
    return len(left) == len(right) and all(any(sp.expand(x - y) == 0 or sp.expand(x + y) == 0 for y in right)
                                           for x in left)


@functools.cache
@kept_pickled
def derivation(drive: str) -> Derivation:
    diagram = side_view(drive)
    laws = list(balance(diagram, "the cart"))  # written from the diagram (Step 3)
    solved = sp.solve(laws, [xdd, N_front, N_rear], dict=True)[0]
    solved = {k: sp.factor(v) for k, v in solved.items()}
    traction = sum((mu * N[i] for i in DRIVEN[drive]), sp.Integer(0)).subs(SYMMETRY)

    # The worked solution's route, wheel by wheel in three dimensions: with its assumptions it leaves
    # exactly the side view's three balance laws (checked here, once).
    equations = balance_equations(drive)
    reduced = [sp.simplify(eq.subs(SYMMETRY)) for eq in equations]
    independent = [eq for eq in reduced if eq is not sp.true]
    if not _same_equations(independent, laws):  # pragma: no cover - a derivation error
        raise AssertionError(f"the wheel-by-wheel equations do not reduce to the side view's: {independent}")

    names = ("x", "y", "z")
    steps = [
        Step(r"Origin O on the ground below the centre of mass C at the start, in the cart's mid-plane; "
             r"$\mathbf{E}_x$ forward, $\mathbf{E}_y$ up, $\mathbf{E}_z$ across to the left (seen from the side, "
             "the front to the right). All four wheels stay on the ground: C keeps its height a and the cart "
             "translates, without rotating",
             r"\mathbf{r}_C = x_C\,\mathbf{E}_x + a\,\mathbf{E}_y,\quad \ddot{\mathbf{r}}_C = \ddot{x}_C\,\mathbf{E}_x,"
             r"\quad \boldsymbol{\omega} = \mathbf{0}", part=1),
        Step(r"The wheels' contact points relative to C (1 rear-left, 2 front-left, 3 front-right, 4 rear-right); "
             "from the side, F is the front axle's (wheels 2, 3) and R the rear's (wheels 1, 4)",
             r",\;".join(rf"\mathbf{{r}}_{i + 1} = {latex(sp.Matrix(w).T)}" for i, w in enumerate(WHEELS))
             + r",\quad \mathbf{r}_{F/C} = b\,\mathbf{E}_x - a\,\mathbf{E}_y,\;"
               r"\mathbf{r}_{R/C} = -b\,\mathbf{E}_x - a\,\mathbf{E}_y", part=1),
        *fbd_steps(diagram),
        *balance_steps(diagram),
        Step(r"Solve Step 3's three balance laws for $\ddot{x}_C$, $N_\mathrm{front}$ and $N_\mathrm{rear}$",
             r",\quad ".join(latex_eq(k, solved[k]) for k in (xdd, N_front, N_rear))),
        Step(r"The worked solution's route, wheel by wheel in three dimensions, driven wheels pushing with "
             r"$F_i = \mu N_i$. Balance of linear momentum, $\sum\mathbf{F} = m\ddot{x}_C\mathbf{E}_x$ (three components)",
             r"\\ ".join(latex(eq) for eq in equations[:3])),
        Step(r"Balance of angular momentum about C, $\sum\mathbf{M}_C = \mathbf{0}$ (the cart translates)",
             r"\\ ".join(rf"{names[i]}:\; " + latex(eq) for i, eq in enumerate(equations[3:]))),
        Step("Nine unknowns, six equations: take the lateral forces as zero and the loads symmetric "
             "left to right (the worked solution's assumption)",
             r",\;".join([r"N_{iz} = 0", r"N_1 = N_4 = N_\mathrm{rear}", r"N_2 = N_3 = N_\mathrm{front}"])),
        Step("What remains is Step 3's three balance laws (the others hold identically)",
             r"\\ ".join(latex(eq) for eq in independent)),
    ]
    if drive != "front":
        # (both: with rear drive N_front's formula is positive again past μa = 2b, where N_rear's is negative)
        steps.append(Step(r"The front wheels stay down only while $N_\mathrm{front} > 0$, with the rear's $N_\mathrm{rear} > 0$",
                          r",\quad ".join(f"{latex(k)} = {latex(solved[k])} > 0" for k in (N_front, N_rear))
                          + r"\quad\iff\quad \mu a < b"))
    chain = [
        Result("N_front", N_front, solved[N_front], "force"),
        Result("N_rear", N_rear, solved[N_rear], "force"),
        Result("accel", xdd, solved[xdd], "acceleration"),
        Result("F_drive", F_drive, traction, "force"),
    ]
    return Derivation(SYMBOLS, DIMENSIONS, steps, chain, {a.name: a.label for a in ANSWERS})


class FrontWheelsLiftError(PhysicalLimitError):
    """Rear or all-wheel drive with μa ≥ b: the front wheels leave the ground (a wheelie)."""


# What a PhysicalLimitError's attribute is, for the page that shows it: (label, dimension).
LIMIT_LABELS = {"mu_lift": ("μ at which the front wheels lift (μ = b/a)", "dimensionless")}



# What a drag past the limit says and the release's refusal opens with: one regime, the same words.
LIFT_OFF = "the front wheels lift off (μa ≥ b): a wheelie this model cannot describe"


def _live_cases(drive: str) -> tuple[Case, ...]:
    """Rear and all-wheel drive: the front wheels lift once μa ≥ b (``solve``'s limit); else the chain."""
    lift = () if drive == "front" else (
        Case("lift_off", LIFT_OFF,
             when=sp.Not(mu * a < b), values=False),)
    return (*lift, Case(drive, "all four wheels on the ground", derivation(drive)))


# Live while dragging (solvers/live.py): μ and where the CM sits.
LIVE = Live(("mu", "a", "b"), _live_cases)

@within_model_range
def solve(**params) -> Solution:
    p = validate_params(PARAMS, params)
    if p["drive"] != "front" and not p["mu"] * p["a"] < p["b"]:
        mu_lift = p["b"] / p["a"]
        raise FrontWheelsLiftError(
            f"{LIFT_OFF[0].upper()}{LIFT_OFF[1:]} (all four wheels on the ground). With {p['drive']}-wheel drive "
            f"they lift once μ ≥ b/a = {plain_number(mu_lift)}; here μ = {plain_number(p['mu'])}.",
            mu_lift=mu_lift)
    d_ = derivation(p["drive"])
    values = d_.evaluate(p)
    answers = {a_.name: values[a_.name] for a_ in ANSWERS}
    steps = list(d_.steps) + d_.numeric_steps(values)
    notes = ("Acceleration moves load to the rear axle: "
             rf"$N_\mathrm{{rear}} - N_\mathrm{{front}}$ = {plain_number(answers['N_rear'] - answers['N_front'])} N per wheel.",)
    return Solution("driven_cart", p, answers, tuple(steps), _checks(p, answers), p["drive"], notes)


def _wheel_by_wheel(p) -> np.ndarray:
    """[N_1..N_4, N_1z..N_4z, ẍ_C]: the six balance equations as a numeric linear system, with the
    symmetry assumptions as extra rows, solved by least squares (numpy), independent of sympy's solve."""
    matrix, rhs = _numeric_system(p["drive"])
    args = [p[k] for k in SYMBOLS]
    sol, *_ = np.linalg.lstsq(np.array(matrix(*args), dtype=float),
                              np.array(rhs(*args), dtype=float).ravel(), rcond=None)
    return sol


def _checks(p, ans) -> tuple[Check, ...]:
    """Second method: the six balance equations solved numerically (``_wheel_by_wheel``)."""
    sol = _wheel_by_wheel(p)
    weight = p["m"] * p["g"]
    return (
        Check(r"$\ddot{x}_C$ from the linear solve of all six equations", ans["accel"], sol[8],
              relative_tolerance(p["g"], 1e-9), "ΣF = m ẍ with the traction of the driven wheels"),
        Check(r"$N_\mathrm{front}$ (wheels 2, 3)", ans["N_front"], sol[1], relative_tolerance(weight, 1e-9),
              "moments about the CM balance: no pitching"),
        Check(r"$N_\mathrm{rear}$ (wheels 1, 4)", ans["N_rear"], sol[0], relative_tolerance(weight, 1e-9),
              "the four normal forces carry the weight"),
    )


@functools.cache
def _numeric_system(drive: str):
    """The six equations plus the symmetry rows as A x = rhs in the unknowns N_1..N_4,
    N_1z..N_4z, ẍ_C; returns (A, rhs) as functions of (m, a, b, c, mu, g)."""
    eqs = [eq.lhs - eq.rhs for eq in balance_equations(drive)]
    eqs += [N[0] - N[3], N[1] - N[2], Nz[0] - Nz[1], Nz[1] - Nz[2], Nz[2] - Nz[3], Nz[0]]
    A, rhs = sp.linear_eq_to_matrix(eqs, [*N, *Nz, xdd])
    args = list(SYMBOLS.values())
    return sp.lambdify(args, A, modules="numpy"), sp.lambdify(args, rhs, modules="numpy")


def frame_times(p, a, frames: int = 40, duration: float = 1.5, wheelbases: float = 3.0, xp=np) -> list:
    """The motion's instants, evenly spaced from the start: for ``duration`` or until the cart has gone
    ``wheelbases`` wheelbases, whichever is first (a hard-driven cart would leave the view). ``xp``:
    numpy, or solvers.live's namespace for expressions (the browser's motion, generated from this)."""
    reach = wheelbases * 2 * p["b"]
    end = xp.where(xp.less(0, a["accel"]), xp.minimum(duration, (2 * reach / xp.maximum(a["accel"], 1e-300)) ** 0.5),
                   duration)
    return [0.0, *(end * i / (frames - 1) for i in range(1, frames))]


def state_at(p, a, t, xp=np) -> dict:
    """From rest at constant acceleration: x(t) = ½ ẍ t², v = ẍ t."""
    return {"x": 0.5 * a["accel"] * t**2, "v": a["accel"] * t}


@per_solution
def motion(solution: Solution, frames: int = 40, duration: float = 1.5, wheelbases: float = 3.0) -> dict:
    """The motion frame by frame (``frame_times``, ``state_at``)."""
    p, a = solution.params, solution.answers
    t = np.array(frame_times(p, a, frames, duration, wheelbases))
    return {"t": t, **state_at(p, a, t)}


@swept("mu", SYMBOLS)
def acceleration_versus_mu(base: dict, mus: np.ndarray) -> dict[str, np.ndarray]:
    """ẍ against μ for each drive, NaN where the front wheels would lift (μa ≥ b); read-only arrays."""
    curves = {}
    for drive in DRIVEN:
        accel = np.array(derivation(drive).vectorized("accel")(mu=mus, **base), dtype=float)
        if drive != "front":
            accel[~(mus * base["a"] < base["b"])] = np.nan
        curves[drive] = accel
    return curves


def method(params) -> tuple[Step, ...]:
    """The symbolic steps for ``params`` without numbers: shown beside a refusal, where they say why
    (the last one: the front wheels stay down only while μa < b)."""
    return derivation(validate_params(PARAMS, params)["drive"]).steps


def derivation_of(solution: Solution) -> Derivation:
    """The derivation behind ``solution`` (its option and regime)."""
    return derivation(solution.params["drive"])


# How ?seed=N varies the parameters beyond the general rule (solvers.protocol.Variants).
VARIANTS = Variants(fixed=("g", "c"))  # the track c drops out of the answers

WARM: tuple[dict, ...] = ()  # every option combination is warmed already


# The typical slips practice mode names: wrong expressions in this module's symbols, each
# with the feedback a tutor would give (the hint never states the right value).
MISTAKES = (
    Mistake("N_front", "Swapped axles: accelerating moves load to the rear, so the front wheels carry "
            "less (the worked solution's naming slip).", lambda p: derivation(p["drive"]).expression_of("N_rear"),
            lambda p: p["mu"] > 0),
    Mistake("N_rear", "Swapped axles: accelerating moves load to the rear, so the rear wheels carry more.",
            lambda p: derivation(p["drive"]).expression_of("N_front"), lambda p: p["mu"] > 0),
    Mistake("accel", "Only the driven wheels push: μg would need all four wheels driving.",
            lambda p: mu * g, lambda p: p["drive"] != "all"),
    Mistake("accel", "Without the load transfer (N = mg/4 each) you get μg/2; the moment balance "
            "shifts load between the axles.", lambda p: mu * g / 2, lambda p: p["drive"] != "all"),
)


def _front_wheels(p: dict) -> str:
    try:
        solve(**p)
    except FrontWheelsLiftError:
        return "lift"
    return "stay"


# What a lecture hall may be asked before the motion is shown (ui/room.py), besides the answers.
ROOM_QUESTIONS = (
    RegimeQuestion("front_wheels", "At full traction, do the front wheels stay on the ground or lift off?",
                   (("stay", "They stay on the ground"), ("lift", "They lift off (a wheelie)")), _front_wheels),
)
