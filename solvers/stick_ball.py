"""A ball slides into a free stick on a frictionless table (ME 230 review, problem 3).

Model: uniform stick (m_stick, length l, I = m_stick l²/12 about its midpoint) at rest on a
frictionless horizontal table; a ball, a point mass m_ball with no spin, slides at speed v
perpendicular to the stick and strikes it at a distance s from the midpoint. The impact is
instantaneous and the table exerts no horizontal impulse, so the linear momentum and the angular
momentum (about any fixed point) of ball plus stick are conserved. mode "stick": the ball attaches
and the pair moves as one rigid body. mode "bounce": Newton's restitution e acts on the normal
velocities at the contact and the ball separates. Motion after impact is free (no friction).
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
    Result,
    Solution,
    Step,
    latex,
    latex_eq,
    relative_tolerance,
    require,
    validate_params,
    per_solution,
)
from .diagram import Body, DiagramSlip, Circle, Diagram, Load, Rod, balance, balance_steps, fbd_steps
from .live import Case, Event, Live, first_crossing
from .protocol import About, Mistake, Variants

ABOUT = About(
    title="Ball slides into a free stick",
    group="Impacts",
    blurb="A ball hits a stick on ice and sticks (or bounces): momentum and angular momentum at work.",
    icon=":material/sports_cricket:",
    source="ME 230 final-exam review, problem 3",
    primary=("v", "s", "mode", "e"),  # always shown; the rest sit behind "More parameters"
)

PARAMS = (
    Number("m_ball", 1.0, "ball mass", "mass", r"m_b", low=0, ui_low=0.05, ui_high=10.0, step=0.05),
    Number("m_stick", 1.0, "stick mass", "mass", r"m_s", low=0, ui_low=0.05, ui_high=10.0, step=0.05),
    Number("l", 1.0, "stick length", "length", "l", low=0, ui_low=0.1, ui_high=5.0, step=0.05),
    Number("v", 1.0, "ball speed before impact", "speed", "v", low=0, ui_low=0.1, ui_high=10.0, step=0.1),
    Number("s", 0.5, "impact point from the stick's midpoint", "length", "s", low=0,
           ui_low=0.0, ui_high=2.5, step=0.01, ui_high_per=("l", 0.5), help="0 < s ≤ l/2; the default is the end, l/2."),
    Choice("mode", "stick", "what the ball does", ("stick", "bounce"),
           ("attaches to the stick (the worked solution)", "bounces off (restitution e)")),
    Number("e", 0.5, "coefficient of restitution (bounce only)", "dimensionless", "e", low=0, high=1,
           low_inclusive=True, high_inclusive=True, ui_low=0, ui_high=1, step=0.05),
)

ANSWERS_STICK = (
    Answer("d_cm", "combined CM from the stick's midpoint", r"d_{\mathrm{cm}}", "length"),
    Answer("v_cm", "speed of the combined CM", r"v_{\mathrm{cm}}", "speed"),
    Answer("omega", "angular velocity after", r"\omega", "angular_speed"),
    Answer("I_cm", "moment of inertia about the combined CM", r"I_{\mathrm{cm}}", "inertia"),
    Answer("T_before", "kinetic energy before", r"T_i", "energy"),
    Answer("T_after", "kinetic energy after", r"T_f", "energy"),
    Answer("energy_loss", "kinetic energy lost", r"\Delta T", "energy"),
    Answer("distance_per_rev", "distance the CM moves per revolution", r"x_{\mathrm{rev}}", "length"),
)
ANSWERS_BOUNCE = (
    Answer("v_ball", "ball velocity after (along its approach)", r"v_b'", "speed"),
    Answer("v_stick", "stick CM velocity after", r"v_s'", "speed"),
    Answer("omega", "stick angular velocity after", r"\omega", "angular_speed"),
    Answer("T_before", "kinetic energy before", r"T_i", "energy"),
    Answer("T_after", "kinetic energy after", r"T_f", "energy"),
    Answer("energy_loss", "kinetic energy lost", r"\Delta T", "energy"),
)
ANSWERS = ANSWERS_STICK  # the default mode's answers


def answers_for(mode: str) -> tuple[Answer, ...]:
    return ANSWERS_STICK if mode == "stick" else ANSWERS_BOUNCE


ERRATA = (
    r"A common slip: taking the angular momentum about the stick's midpoint but the moment of "
    r"inertia about the combined CM. Use one point for both (here the combined CM, with the "
    r"parallel-axis terms $m_s d_{\mathrm{cm}}^2$ and $m_b (s - d_{\mathrm{cm}})^2$).",
)

LIMIT_LABELS: dict[str, tuple[str, str]] = {}  # no physical limit to show

m_b, m_s, l, v, s, e = sp.symbols("m_b m_s l v s e", positive=True)
d_cm, v_cm, w, I_cm, T_i, T_f, loss, x_rev = sp.symbols(
    r"d_{\mathrm{cm}} v_{\mathrm{cm}} omega I_{\mathrm{cm}} T_i T_f \Delta{T} x_{\mathrm{rev}}", real=True)
v_b1, v_s1, J = sp.symbols(r"v_b' v_s' J", real=True)
SYMBOLS = {"m_ball": m_b, "m_stick": m_s, "l": l, "v": v, "s": s, "e": e}
DIMENSIONS = {p.name: p.dimension for p in PARAMS if isinstance(p, Number)}


# ---------------------------------------------------------------------------------------------
# Step 2: the ball and the stick isolated at the impact's instant, in the stage's top view (the stick
# along y with its midpoint M at the origin, the ball arriving along +x and striking at Q = (0, s)). The
# contact is smooth: the impulse J on the stick is along the ball's approach (+x), and the stick's on the
# ball is −J (an interaction pair). The table's support and gravity act out of the plane.

u_b, u_M, omega_z = sp.symbols(r"u_b u_M omega_z", real=True)  # after: ball's and midpoint's x-velocity, E_z spin
I_STICK = m_s * l**2 / 12
RHO = sp.Rational(6, 100) * l  # the ball's drawn radius (BALL_RADIUS): the model's ball is a point at its front


def _after(p, a) -> tuple[float, float, float]:
    """The ball's and the stick's midpoint's x-velocities after, and the stick's E_z spin (clockwise:
    negative), from the solver's answers."""
    if p["mode"] == "stick":  # one rigid body: a point at arm y from the midpoint moves at v_cm + ω (y − d_cm)
        return (a["v_cm"] + a["omega"] * (p["s"] - a["d_cm"]), a["v_cm"] - a["omega"] * a["d_cm"], -a["omega"])
    return a["v_ball"], a["v_stick"], -a["omega"]


def _contact_impulse(p) -> float:
    """J from the effective mass at the contact (never from the velocities after): the normal relative
    speed v is stopped and reversed e-fold, J = (1 + e) v / (1/m_b + 1/m_s + s²/I_s), with e = 0 when the
    ball attaches."""
    e_ = p["e"] if p["mode"] == "bounce" else 0.0
    inverse = 1 / p["m_ball"] + 1 / p["m_stick"] + p["s"] ** 2 / (p["m_stick"] * p["l"] ** 2 / 12)
    return (1 + e_) * p["v"] / inverse


def _impact_values(solution) -> dict:
    return _impact_values_of(solution.params, solution.answers)


def _key_values(p, a) -> dict:
    """At the stage's key frame, the impact: the loads need the parameters only."""
    return {l: p["l"], s: p["s"], J: _contact_impulse(p)}


def _impact_values_of(p, a) -> dict:
    ball, mid, spin = _after(p, a)
    return {m_b: p["m_ball"], m_s: p["m_stick"], l: p["l"], v: p["v"], s: p["s"], J: _contact_impulse(p),
            u_b: ball, u_M: mid, omega_z: spin}


def _impact_frames(solution, motion) -> dict:
    """The impact's symbols at its frame (the bodies there as the diagram has them), NaN elsewhere."""
    at = np.arange(len(motion["t"])) == motion["impact_index"]
    return {sym: np.where(at, value, np.nan) for sym, value in _impact_values(solution).items()}


IMPACT = Diagram(
    "impact", "At the impact", "impulse",
    bodies=(Body("the ball", points={"B": (-RHO, s), "Q": (0, s)}, centre="B", about="B",
                 kinetic=(m_b * (u_b - v), 0, 0), kinetic_latex=(r"m_b\left(u_b - v\right)", "0", "0"),
                 outline=(Circle("B", RHO),)),
            Body("the stick", points={"M": (0, 0), "Q": (0, s), "_top": (0, l / 2), "_bottom": (0, -l / 2)},
                 centre="M", about="M", kinetic=(m_s * u_M, 0, I_STICK * omega_z),
                 kinetic_latex=(r"m_s u_M", "0", r"I_M\,\omega_z"), outline=(Rod(("_top", "_bottom")),))),
    loads=(Load("J", "the stick's impulse on the ball", "the stick", "the ball", at="Q", kind="impulse",
                direction=(-1, 0), size=J, pair="the ball's impulse on the stick"),
           Load("J", "the ball's impulse on the stick", "the ball", "the stick", at="Q", kind="impulse",
                direction=(1, 0), size=J, pair="the stick's impulse on the ball")),
    values=_impact_values, frames=_impact_frames, key=_key_values,
    note=("The contact is smooth, so the impulse is perpendicular to the stick, along the ball's approach, whether "
          "the ball attaches or bounces; the table's support and gravity act out of the plane (finite, they give "
          "no impulse over the instant). The ball is a point (drawn with a size); $u_b$, $u_M$: the ball's and the "
          "stick's midpoint's velocities after, $\\omega_z$ the stick's spin (clockwise: negative)."))


def free_body_diagrams(params) -> tuple[Diagram, ...]:
    """The impact's instant (the same diagram whether the ball attaches or bounces)."""
    return (IMPACT,)


# The classic slips in drawing this diagram (practice/diagram_judge.py), as MISTAKES are the answers':
# each a load the physics does not put there, with a tutor's words that never show the diagram.
DIAGRAM_SLIPS = (
    DiagramSlip("force of motion", "no force or impulse carries the ball along its velocity: before the impact it "
                "keeps moving by its own momentum.", on="the ball", at="B", direction=(1, 0)),
    DiagramSlip("weight in the table's plane", "the ball and the stick slide on a horizontal table: the weights and "
                "the table's support act out of this plane and balance.", direction=(0, -1)),
)



def _sides(eq: sp.Eq) -> tuple[sp.Expr, sp.Expr]:
    return eq.lhs, eq.rhs


def _moment_law_about(body: str, point: tuple) -> tuple[sp.Expr, sp.Expr]:
    """``body``'s moment law moved from its centre (where the diagram writes it) to the fixed ``point``, as
    (impulses' moment, change of angular momentum): ΣM_P = ΣM_G + r_G/P × ΣP̂ and ΔH_P = ΔH_G + r_G/P × m Δv_G,
    so each side adds r_G/P × its own side of the two linear laws (the balance laws' generated sides, nothing
    written anew)."""
    b = IMPACT.body(body)
    assert b.about == b.centre  # the moment law about the mass centre, so ΔH moves with m Δv_G
    (fx, kx), (fy, ky), (fm, km) = (_sides(eq) for eq in balance(IMPACT, body))
    dx, dy = (c - q for c, q in zip(b.points[b.centre], point))
    return fm + dx * fy - dy * fx, km + dx * ky - dy * kx


@functools.cache
@kept_pickled
def derivation(mode: str) -> Derivation:
    I_stick = m_s * l**2 / 12
    origin = Step(r"Top view. Origin at the stick's midpoint M at the instant of impact; $\mathbf{E}_x$ along the "
                  r"ball's approach, $\mathbf{E}_y$ along the stick, $\mathbf{E}_z$ out of the table "
                  r"(counter-clockwise +). The ball strikes at Q, a distance s from M; before, it moves at "
                  r"$v\,\mathbf{E}_x$ and the stick is at rest. After: the ball at $u_b\,\mathbf{E}_x$, the stick's "
                  r"midpoint at $u_M\,\mathbf{E}_x$, the stick turning at $\omega_z\,\mathbf{E}_z$",
                  r"\mathbf{r}_Q = s\,\mathbf{E}_y,\quad \mathbf{v}_{\mathrm{ball}}^- = v\,\mathbf{E}_x", part=1)
    # Step 3 (generated from the diagram), then the two bodies' laws added: the pair J, −J cancels
    (ball_x, _, _), (stick_x, _, _) = balance(IMPACT, "the ball"), balance(IMPACT, "the stick")
    impulses = sp.expand(ball_x.lhs + stick_x.lhs)
    assert impulses == 0  # the interaction pair cancels
    momentum_sum = sp.Eq(impulses, ball_x.rhs + stick_x.rhs, evaluate=False)
    diagrams = [*fbd_steps(IMPACT), *balance_steps(IMPACT)]
    T_before = m_b * v**2 / 2
    if mode == "stick":
        cm = sp.Eq(d_cm, (m_s * 0 + m_b * s) / (m_s + m_b))
        # attached: one rigid body turning clockwise at ω about the combined centre C = d_cm E_y, moving at v_cm E_x;
        # a point at arm y along the stick moves at (v_cm + ω (y − d_cm)) E_x
        attached = {u_b: v_cm + w * (s - d_cm), u_M: v_cm - w * d_cm, omega_z: -w}
        inertia = sp.Eq(I_cm, I_stick + m_s * d_cm**2 + m_b * (s - d_cm) ** 2)
        # linear momentum: the two x laws added, with the attached velocities; the ω term is the combined CM's
        # definition (m_b (s − d_cm) = m_s d_cm), zero
        linear = sp.expand(momentum_sum.rhs.subs(attached))
        assert sp.simplify(linear.coeff(w).subs(d_cm, cm.rhs)) == 0
        momentum = sp.Eq(-linear.coeff(w, 0).coeff(v_cm, 0), linear.coeff(v_cm) * v_cm)
        # angular momentum about the fixed point where C is at the impact: each body's moment law moved there
        C = (sp.Integer(0), d_cm)
        (ball_m, ball_k), (stick_m, stick_k) = _moment_law_about("the ball", C), _moment_law_about("the stick", C)
        moments = sp.expand(ball_m + stick_m)
        assert moments == 0  # the pair acts at one point, Q: its moments cancel about any point
        turning = sp.expand((ball_k + stick_k).subs(attached))
        assert sp.simplify(turning.coeff(v_cm).subs(d_cm, cm.rhs)) == 0  # C is the combined CM
        assert sp.simplify(turning.coeff(w) + inertia.rhs) == 0  # the ω term is −I_cm ω
        before = sp.factor(turning.coeff(w, 0).coeff(v_cm, 0))  # 0 = this − I_cm ω
        assert sp.simplify(before - m_b * v * (s - d_cm)) == 0  # only the ball carries it before, arm s − d_cm
        angular = sp.Eq(before, I_cm * w)
        solved_v = sp.solve(momentum, v_cm)[0]
        solved_w = sp.solve(angular, w)[0]
        T_after = (m_b + m_s) * v_cm**2 / 2 + I_cm * w**2 / 2
        steps = [
            origin,
            Step("Centre of mass C of stick + ball, measured from the stick's midpoint", latex(cm), part=1),
            Step(r"The ball attaches: after, the two move as one rigid body, C at $v_{\mathrm{cm}}\,\mathbf{E}_x$, turning "
                 r"clockwise at ω ($\omega_z = -\omega$); a point at arm y along the stick moves at "
                 r"$v_{\mathrm{cm}} + \omega\,(y - d_{\mathrm{cm}})$",
                 r",\quad ".join(latex_eq(k_, attached[k_]) for k_ in (u_b, u_M, omega_z)), part=1),
            *diagrams,
            Step("The two bodies' x laws added: the pair (−J on the ball, J on the stick) cancels, so the "
                 "system's linear momentum is conserved; with the attached velocities (the ω terms cancel: "
                 r"$m_b(s - d_{\mathrm{cm}}) = m_s d_{\mathrm{cm}}$, C being the combined centre)",
                 latex(momentum_sum) + r"\;\Rightarrow\;" + latex(momentum) + r"\;\Rightarrow\;"
                 + latex_eq(v_cm, solved_v)),
            Step("Moment of inertia about the combined CM (parallel-axis theorem for the stick, "
                 "point mass for the ball)", latex(inertia)),
            Step("Each body's moment law moved to C (its moment law about its own centre plus "
                 r"$\mathbf{r}_{G/C}\times$ its linear laws) and added: the pair acts at Q, so its moments cancel and "
                 "the angular momentum about C is conserved; before impact only the ball carries it "
                 r"(arm $s - d_{\mathrm{cm}}$)",
                 latex(sp.Eq(moments, ball_k + stick_k, evaluate=False)) + r"\;\Rightarrow\;" + latex(angular)
                 + r"\;\Rightarrow\;" + latex_eq(w, solved_w)),
            Step("Kinetic energy before and after (the impact is perfectly plastic, e = 0)",
                 latex_eq(T_i, T_before) + r",\quad " + latex_eq(T_f, T_after)),
            Step("Distance the CM travels while the body turns once", latex_eq(x_rev, v_cm * 2 * sp.pi / w)),
        ]
        chain = [
            Result("d_cm", d_cm, cm.rhs, "length"),
            Result("v_cm", v_cm, solved_v, "speed"),
            Result("I_cm", I_cm, inertia.rhs, "inertia"),
            Result("omega", w, solved_w, "angular_speed"),
            Result("T_before", T_i, T_before, "energy"),
            Result("T_after", T_f, T_after, "energy"),
            Result("energy_loss", loss, T_i - T_f, "energy"),
            Result("distance_per_rev", x_rev, v_cm * 2 * sp.pi / w, "length"),
        ]
    else:
        # the two bodies' balance laws (Step 3), with the velocities after named as the derivation names them
        after = {u_b: v_b1, u_M: v_s1, omega_z: -w}
        ball = balance(IMPACT, "the ball")[0].subs(after)
        stick_lin, _, stick_ang = (eq.subs(after) for eq in balance(IMPACT, "the stick"))
        restitution = sp.Eq(v_s1 + w * s - v_b1, e * v)
        solved = sp.solve([ball, stick_lin, stick_ang, restitution], [v_b1, v_s1, w, J], dict=True)[0]
        solved = {k: sp.factor(val) for k, val in solved.items()}
        T_after = m_b * v_b1**2 / 2 + m_s * v_s1**2 / 2 + I_stick * w**2 / 2
        steps = [
            origin,
            Step(r"The ball bounces off: after, it moves at $v_b'\,\mathbf{E}_x$ (a point: no spin), the stick's "
                 r"midpoint at $v_s'\,\mathbf{E}_x$, the stick turning clockwise at ω; its point Q then moves at "
                 r"$v_s' + \omega s$",
                 r",\quad ".join(latex_eq(k_, after[k_]) for k_ in (u_b, u_M, omega_z)), part=1),
            *diagrams,
            Step("The two bodies' x laws added: the pair (−J on the ball, J on the stick) cancels, so the "
                 "system's linear momentum is conserved", latex(momentum_sum)),
            Step(r"The balance laws with these velocities ($u_b = v_b'$, $u_M = v_s'$, $\omega_z = -\omega$)",
                 latex(ball) + r",\quad " + latex(stick_lin) + r",\quad " + latex(stick_ang)),
            Step("Newton's restitution on the normal velocities at the contact point", latex(restitution)),
            Step("Solve the four linear equations",
                 r",\quad ".join(latex_eq(k, solved[k]) for k in (J, v_b1, v_s1, w))),
            Step("Kinetic energy before and after", latex_eq(T_i, T_before) + r",\quad " + latex_eq(T_f, T_after)),
        ]
        chain = [
            Result("v_ball", v_b1, solved[v_b1], "speed"),
            Result("v_stick", v_s1, solved[v_s1], "speed"),
            Result("omega", w, solved[w], "angular_speed"),
            Result("T_before", T_i, T_before, "energy"),
            Result("T_after", T_f, T_after, "energy"),
            Result("energy_loss", loss, T_i - T_f, "energy"),
        ]
    return Derivation(SYMBOLS, DIMENSIONS, steps, chain, {a.name: a.label for a in ANSWERS_STICK + ANSWERS_BOUNCE})



def _live_cases(mode: str) -> tuple[Case, ...]:
    """Off the stick (refused, as ``solve`` does), else the mode's chain."""
    return (Case("off_stick", "the impact point is off the stick (s > l/2)", when=s > l / 2 * (1 + sp.Float(1e-12)),
                 values=False),
            Case(mode, "the ball attaches" if mode == "stick" else "the ball bounces off", derivation(mode)))


# Live while dragging (solvers/live.py): the ball's speed, where it hits, and e.
LIVE = Live(("v", "s", "e"), _live_cases)

@within_model_range
def solve(**params) -> Solution:
    if "s" not in params:
        length = params.get("l", 1.0)
        # The default impact point is the stick's end, l/2 of whatever l is given (if valid).
        if isinstance(length, (int, float)) and not isinstance(length, bool) and math.isfinite(length):
            params = {**params, "s": length / 2}
    p = validate_params(PARAMS, params)
    require(p["s"] <= p["l"] / 2 * (1 + 1e-12),
            f"The impact point must be on the stick: s ≤ l/2 = {p['l'] / 2:g} m, got s = {p['s']:g} m.")
    d_ = derivation(p["mode"])
    values = d_.evaluate(p)
    answers = {a.name: values[a.name] for a in answers_for(p["mode"])}
    steps = list(d_.steps) + d_.numeric_steps(values)
    lost = answers["energy_loss"] / answers["T_before"]
    notes = (f"Energy: {plain_number(100 * lost, 3)} % of the kinetic energy is lost in the impact"
             + (" (perfectly plastic: the ball attaches)." if p["mode"] == "stick" else "."),)
    return Solution("stick_ball", p, answers, tuple(steps), _checks(p, answers), p["mode"], notes,
                    _ledger(p, answers))


def _momenta(p, a) -> tuple[float, float, float, float]:
    """Linear momentum, and angular momentum about the stick's midpoint (a fixed point in the table
    frame, where the stick starts), before and after, from the separate bodies' velocities."""
    mb, ms, v_, s_ = p["m_ball"], p["m_stick"], p["v"], p["s"]
    if p["mode"] == "stick":
        # Rigid-body kinematics: a point at arm y from the midpoint moves at v_cm + ω (y − d_cm).
        v_mid = a["v_cm"] + a["omega"] * (0 - a["d_cm"])
        v_ballpt = a["v_cm"] + a["omega"] * (s_ - a["d_cm"])
    else:
        v_mid, v_ballpt = a["v_stick"], a["v_ball"]
    I_stick = ms * p["l"] ** 2 / 12
    # the ball passes at arm s from the midpoint (sign: +E_z)
    return mb * v_, ms * v_mid + mb * v_ballpt, mb * v_ * s_, I_stick * a["omega"] + mb * v_ballpt * s_


def _ledger(p, a) -> tuple[LedgerRow, ...]:
    p_before, p_after, H_before, H_after = _momenta(p, a)
    return (
        LedgerRow("linear momentum", p_before, p_after, "impulse",
                  "the frictionless table gives no horizontal impulse"),
        LedgerRow("angular momentum about the stick's midpoint", H_before, H_after, "angular_momentum",
                  "no external moment about any fixed point"),
        LedgerRow("kinetic energy", a["T_before"], a["T_after"], "energy",
                  "lost: the ball attaches (perfectly plastic)" if p["mode"] == "stick" else
                  ("elastic: e = 1" if a["energy_loss"] <= 1e-12 * a["T_before"] else
                   f"lost: restitution e = {p['e']:g} < 1")),
    )


def _checks(p, a) -> tuple[Check, ...]:
    """Second method: momentum and angular momentum about the stick's midpoint, computed from the
    separate bodies after impact; and the energy lost from the effective mass at the contact, a
    formula that never uses the velocities after."""
    p_before, p_after, H_before, H_after = _momenta(p, a)
    e_ = 0.0 if p["mode"] == "stick" else p["e"]  # attaching: no relative normal velocity after
    I_stick = p["m_stick"] * p["l"] ** 2 / 12
    # The mass a push along the approach line at the contact meets: 1/m* = 1/m_b + 1/m_s + s²/I.
    m_star = 1 / (1 / p["m_ball"] + 1 / p["m_stick"] + p["s"] ** 2 / I_stick)
    return (
        Check("linear momentum", p_before, p_after, relative_tolerance(p_before, 1e-9),
              "the table exerts no horizontal impulse"),
        Check("angular momentum about the stick's midpoint", H_before, H_after,
              relative_tolerance(H_before, 1e-9), "no external moment either"),
        Check(r"energy lost: $T_i - T_f$ vs $\tfrac12 (1 - e^2)\, m^* v^2$", a["energy_loss"], 0.5 * (1 - e_**2) * m_star * p["v"] ** 2,
              relative_tolerance(a["T_before"], 1e-9),
              r"$m^*$ is the effective mass at the contact, $1/m^* = 1/m_b + 1/m_s + s^2/I$; "
              + ("attaching is e = 0" if p["mode"] == "stick" else "restitution keeps e² of the approach's share")),
    )


BALL_RADIUS = 0.06  # the ball's drawn radius, as a fraction of l (the model's ball is a point)


def frame_times(p, a, frames: int = 45, xp=np) -> list:
    """The motion's instants: a fifth of ``frames`` (at least 8) over the ball's last 0.6 l before the impact
    (t = 0, exactly), the rest evenly after it, for one turn of the stick (at most the time the ball takes
    over 12 l), or until the stick reaches the bounced ball again (``a["second_contact"]``, infinite if
    never: ``SECOND_CONTACT``). ``xp``: numpy, or solvers.live's namespace for expressions (the browser's
    motion, generated from this)."""
    t_in = 0.6 * p["l"] / p["v"]
    t_out = xp.minimum(_turn_or_passing(p, a, xp), a["second_contact"])
    n_in = max(frames // 5, 8)
    n_out = frames - n_in - 1
    return [*(-t_in + t_in * i / n_in for i in range(n_in)), 0.0, *(t_out * j / n_out for j in range(1, n_out + 1))]


def state_at(p, a, t, xp=np) -> dict:
    """Where the stick's ends and midpoint, the ball's centre and the combined centre of mass are at time
    ``t`` (top view: the stick along y at x = 0 and the ball approaching along +x with its surface at
    y = s; the impact at t = 0, after which the stick turns clockwise: the ball's angular momentum is −z).
    The ball is drawn as a disk of radius ``BALL_RADIUS`` l whose front touches the stick at the impact."""
    l_, v_, s_ = p["l"], p["v"], p["s"]
    rho = BALL_RADIUS * l_
    tp = xp.maximum(t, 0.0)
    phi = -a["omega"] * tp
    before = xp.less(t, 0)
    normal = (xp.cos(phi), xp.sin(phi))  # the stick's normal, +x at the impact
    if p["mode"] == "stick":
        d_ = a["d_cm"]
        centre_x, centre_y = a["v_cm"] * tp, d_

        def body(arm):  # a point at arm y (from the midpoint) along the stick
            return centre_x - (arm - d_) * xp.sin(phi), centre_y + (arm - d_) * xp.cos(phi)
        on_stick = body(s_)
        ball = (xp.where(before, v_ * t, on_stick[0]) - rho * normal[0], xp.where(before, s_, on_stick[1] - rho * normal[1]))
        cm = (centre_x, centre_y)
    else:
        def body(arm):
            return _stick_point(a, arm, tp, xp)
        ball = (xp.where(before, v_ * t, a["v_ball"] * tp) - rho, s_)
        total = p["m_ball"] + p["m_stick"]
        # the combined CM of the model (the ball a point at its contact side), for the straight path
        cm = ((p["m_ball"] * (ball[0] + rho) + p["m_stick"] * body(0.0)[0]) / total,
              (p["m_ball"] * ball[1] + p["m_stick"] * body(0.0)[1]) / total)
    return {"top": body(l_ / 2), "bottom": body(-l_ / 2), "mid": body(0.0), "ball": ball, "cm": cm}


def _turn_or_passing(p, a, xp=np):
    """How long the motion after the impact runs at most: one turn of the stick, or the ball's 12 l."""
    return xp.minimum(2 * math.pi / a["omega"], 12 * p["l"] / p["v"])


# After a bounce, the stick swinging round into the ball again: a second impact, which this model does not
# treat, so the motion ends there. Closer than 1e-9 l is the bounce's own contact, or rounding.
SECOND_CONTACT = Event("second_contact", lambda p, a, t, xp: gap(p, a, BALL_RADIUS * p["l"], t, xp) + 1e-9 * p["l"],
                       _turn_or_passing, 4000, lambda p: p["mode"] == "bounce")
MOTION_EVENTS = (SECOND_CONTACT,)


@per_solution
def motion(solution: Solution, frames: int = 45) -> dict:
    """The motion frame by frame (``frame_times``, ``state_at``); when the ball bounces, the two move
    freely until the stick swings round into it again: a second impact, which this model does not
    treat, so the motion ends there (``SECOND_CONTACT``: the time, else None)."""
    p, a = solution.params, solution.answers
    second = first_crossing(SECOND_CONTACT, p, a)
    t = np.array(frame_times(p, a | {"second_contact": second}, frames))
    s = state_at(p, a, t)
    n = len(t)
    s = {k: tuple(np.broadcast_to(np.asarray(c, dtype=float), (n,)).copy() for c in xy) for k, xy in s.items()}
    return {"t": t, "impact_index": max(frames // 5, 8), **s, "ball_radius": BALL_RADIUS * p["l"],
            "second_contact": None if math.isinf(second) else second}


def _stick_point(a, arm, t, xp=np):
    """Where the point at ``arm`` along the bounced stick is at time t ≥ 0."""
    phi = -a["omega"] * t
    return a["v_stick"] * t - arm * xp.sin(phi), arm * xp.cos(phi)


def gap(p, a, rho: float, t, xp=np) -> np.ndarray:
    """Distance from the bounced ball's surface to the stick (a segment) at times t ≥ 0: negative
    means they overlap."""
    if xp is np:
        t = np.atleast_1d(np.asarray(t, dtype=float))
    (x0, y0), (x1, y1) = _stick_point(a, -p["l"] / 2, t, xp), _stick_point(a, p["l"] / 2, t, xp)
    bx, by = a["v_ball"] * t - rho, p["s"]
    dx, dy = x1 - x0, y1 - y0
    along = xp.minimum(xp.maximum(((bx - x0) * dx + (by - y0) * dy) / (dx**2 + dy**2), 0.0), 1.0)
    return xp.hypot(bx - x0 - along * dx, by - y0 - along * dy) - rho


def derivation_of(solution: Solution) -> Derivation:
    """The derivation behind ``solution`` (its option and regime)."""
    return derivation(solution.params["mode"])


# How ?seed=N varies the parameters beyond the general rule (solvers.protocol.Variants).
# s is stated (a page fills a missing s with the textbook's 0.5 m): the end of this variant's stick
VARIANTS = Variants(derived={"s": lambda p: p["l"] / 2})

WARM: tuple[dict, ...] = ()  # every option combination is warmed already


# The typical slips practice mode names: wrong expressions in this module's symbols, each
# with the feedback a tutor would give (the hint never states the right value).
MISTAKES = (
    Mistake("v_cm", "After the impact the momentum is shared by the ball and the stick.",
            lambda p: v, lambda p: p["mode"] == "stick"),
    Mistake("I_cm", "Missing parallel-axis terms: about the combined CM the stick and the ball each add "
            "their mass times the square of their distance from it.", lambda p: m_s * l**2 / 12, lambda p: p["mode"] == "stick"),
    Mistake("omega", "Angular momentum about one point but inertia about another: take both about "
            "the combined CM (arm s − d_cm).",
            lambda p: m_b * v * s / derivation("stick").expression_of("I_cm"),
            lambda p: p["mode"] == "stick"),
    Mistake("omega", "Missing parallel-axis terms: the stick's own ¹⁄₁₂ m l² is not its inertia "
            "about the combined CM.",
            lambda p: derivation("stick").in_parameters(m_b * v * (s - d_cm) / (m_s * l**2 / 12)),
            lambda p: p["mode"] == "stick"),
)
