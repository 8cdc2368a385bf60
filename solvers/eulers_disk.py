"""Euler's disk in steady precession (ME 230 review; Moffatt, Nature 404, 2000).

Model: thin uniform disk (m, r; I about its axis ½ m r², about a diameter ¼ m r²) rolling without
slip on a fixed horizontal table, tilted at a constant angle θ from the table, its centre of mass
G at rest (the worked solution's assumption 4: the contact point's circle has radius r cos θ about the
vertical through G). Frame {e_x, e_y, e_z = E_z} precesses with the contact point at rate ω_p
about E_z (angular velocity −ω_p E_z, the worked solution's sense). The disk's normal is n = sin θ e_y +
cos θ e_z and the contact point A is at r (cos θ e_y − sin θ e_z) from G. With G at rest the table
force is the weight alone, N = mg, and friction is zero.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp

from . import eulers_disk_dynamics as dynamics  # the full equations (Kane's method)
from .kept import kept_pickled
from .core import (
    within_model_range,
    Answer,
    Check,
    Derivation,
    Number,
    Result,
    Solution,
    Step,
    as_written,
    latex,
    latex_eq,
    presentable,
    relative_tolerance,
    root_with_sign,
    validate_params,
    per_solution,
)
from .diagram import Body, DiagramSlip, Diagram, Load, Rod, balance, balance_steps, fbd_steps
from .live import Case, Live
from .sweeps import swept
from .protocol import About, Mistake, Variants

ABOUT = About(
    title="Euler's disk",
    group="Newton–Euler",
    blurb="A coin-like disk whirls ever faster as it settles: steady precession and its singularity.",
    icon=":material/album:",
    source="ME 230 final-exam review; Moffatt, Nature 404 (2000)",
    primary=("theta", "r"),  # always shown; the rest sit behind "More parameters"
)

PARAMS = (
    Number("m", 0.4, "mass", "mass", "m", low=0, ui_low=0.05, ui_high=5.0, step=0.05),
    Number("r", 0.0375, "radius", "length", "r", low=0, ui_low=0.005, ui_high=0.5, step=0.0025),
    Number("theta", math.radians(10), "tilt from the table", "angle", r"\theta", low=0,
           high=math.pi / 2, ui_low=0.5, ui_high=89.5, step=0.5),
    Number("g", 9.81, "gravity", "acceleration", "g", low=0, ui_low=0.5, ui_high=30.0, step=0.01),
)

ANSWERS = (
    Answer("omega_p", "precession rate of the contact point", r"\omega_p", "angular_speed"),
    Answer("omega_s", "spin rate relative to the precessing frame", r"\omega_s", "angular_speed"),
    Answer("omega_total", "magnitude of the disk's angular velocity", r"\lvert\boldsymbol\omega\rvert",
           "angular_speed"),
    Answer("energy", "total energy (zero with the disk flat)", r"E", "energy"),
    # (not v_A: the disk's material point at A is at rest, v_A = 0 in Step 1; this is the point of contact's path)
    Answer("contact_speed", "speed of the contact point around its circle", r"v_{\mathrm{contact}}", "speed"),
    Answer("period", "time for one precession", r"\tau", "time"),
)

ERRATA = (
    r"The worked solution's equation references (3)–(7) in the last steps mean its equations (13)–(17).",
    r"As $\theta \to 0$ the contact point whirls faster ($\omega_p \to \infty$) while the disk "
    r"itself turns slower ($|\boldsymbol\omega| = \omega_p\sin\theta \to 0$) and the energy "
    r"$\tfrac32 mgr\sin\theta$ runs out: Moffatt's finite-time singularity.",
)

LIMIT_LABELS: dict[str, tuple[str, str]] = {}  # no physical limit to show

m, r, theta, g = sp.symbols(r"m r theta g", positive=True)
w_p, w_s, w_tot, E, v_contact, tau = sp.symbols(r"omega_p omega_s |\boldsymbol{\omega}| E v_{\mathrm{contact}} tau",
                                               real=True)
psidot, N_ = sp.symbols(r"\dot{\psi} N", real=True)
SYMBOLS = {"m": m, "r": r, "theta": theta, "g": g}
DIMENSIONS = {p.name: p.dimension for p in PARAMS}


def _vec_latex(v: sp.Matrix) -> str:
    basis = (r"\mathbf{e}_x", r"\mathbf{e}_y", r"\mathbf{e}_z")
    comps = [sp.factor(sp.expand_trig(sp.simplify(c))) for c in v]
    out = ""
    for c, e in ((as_written(c), e) for c, e in zip(comps, basis) if c != 0):  # its sign before it: − ω_p sin²θ e_z
        negative = c.could_extract_minus_sign()
        size = -c if negative else c
        body = rf"\left({latex(size)}\right)" if isinstance(size, sp.Add) else latex(size)
        out += ("- " if negative else "+ " if out else "") + body + r"\," + e + " "
    return out.strip() or "0"


F_ = sp.Symbol("F", real=True)  # the table's friction on the disk at A, along e_y


@functools.cache
def _kinematics() -> dict:
    """The precessing frame's vectors and the angular momentum, derived once."""
    n = sp.Matrix([0, sp.sin(theta), sp.cos(theta)])
    r_AG = r * sp.Matrix([0, sp.cos(theta), -sp.sin(theta)])
    Ez = sp.Matrix([0, 0, 1])
    precession = -w_p * Ez
    omega = psidot * n + precession
    rolling = omega.cross(r_AG)  # v_A = v_G + ω × r_A/G with v_G = 0
    spin = sp.solve(rolling[0], psidot)[0]
    I_axis, I_diam = m * r**2 / 2, m * r**2 / 4
    H = I_axis * omega.dot(n) * n + I_diam * (omega - omega.dot(n) * n)
    H_rolled = sp.simplify(H.subs(psidot, spin))
    dHdt = precession.cross(H_rolled)  # components fixed in the precessing frame
    return {"n": n, "r_AG": r_AG, "Ez": Ez, "precession": precession, "omega": omega, "rolling": rolling,
            "spin": spin, "H_rolled": H_rolled, "dHdt": dHdt}


def _steady_values(solution) -> dict:
    """The steady state drawn, from the solver's answers: ω_p, and the table's force from the motion the
    answers give G. Rolling (A's material point at rest) with the answers' ω = ω_s n − ω_p E_z moves G at
    v_G = ω × r_G/A = r (ω_s − ω_p cos θ) e_x (its other components cancel identically); steady, that is fixed
    in the precessing frame, so a_G = −ω_p E_z × v_G = −ω_p r (ω_s − ω_p cos θ) e_y. The table supplies m a_G
    less the weight: F = m a_G·e_y, N = m g + m a_G·E_z (with ω_s = ω_p cos θ, G at rest: F = 0, N = m g).
    Never from the diagram's own balance laws."""
    p, a = solution.params, solution.answers
    v_G = p["r"] * (a["omega_s"] - a["omega_p"] * math.cos(p["theta"]))  # along e_x
    a_G = (-a["omega_p"] * v_G, 0.0)  # (e_y, E_z)
    return {m: p["m"], r: p["r"], theta: p["theta"], g: p["g"], w_p: a["omega_p"],
            F_: p["m"] * a_G[0] + 0.0, N_: p["m"] * p["g"] + p["m"] * a_G[1]}  # (+ 0.0: a zero is never −0)


@functools.cache
def steady() -> Diagram:
    """The disk edge-on in the vertical plane through its axis and the contact point A, at any instant of the
    steady precession (the picture is the same in the precessing frame): drawn x = e_y, horizontal from G
    toward A; drawn y = E_z, up; origin at G, as the derivation's. The weight at G, the table's force at A as
    its components (friction F along e_y, normal N along E_z). Moments are along e_x = e_y × E_z, out of the
    drawing (counter-clockwise +), and the kinetic side is the e_x component of dH_G/dt, the gyroscopic
    term the derivation computes in its kinematics."""
    k = _kinematics()
    r_AG = k["r_AG"]
    A = (r_AG[1], r_AG[2])  # (e_y, E_z) components of r_A/G
    turning = sp.factor(sp.expand_trig(sp.simplify(k["dHdt"][0])))
    disk = Body("the disk", points={"G": (sp.Integer(0), sp.Integer(0)), "A": A, "_rim": (-A[0], -A[1])},
                centre="G", about="G", kinetic=(sp.Integer(0), sp.Integer(0), turning),
                kinetic_latex=(r"m\,\mathbf{a}_G\cdot\mathbf{e}_y = 0", r"m\,\mathbf{a}_G\cdot\mathbf{E}_z = 0",
                               r"\dot{\mathbf{H}}_G\cdot\mathbf{e}_x = " + latex(turning)),
                outline=(Rod(("A", "_rim")),))
    loads = (Load("m g", "the weight", "gravity", "the disk", at="G", direction=(0, -1), size=m * g),
             Load("A", "the table's force", "the table", "the disk", at="A", components=(F_, N_)))
    return Diagram("steady", "In steady precession", "force", (disk,), loads, _steady_values,
                   basis=(r"\mathbf{e}_y", r"\mathbf{E}_z"),
                   note=(r"Drawn edge-on in the vertical plane through the disk's axis and A ($\mathbf{e}_y$ toward A, "
                         r"$\mathbf{E}_z$ up, origin at G; moments along $\mathbf{e}_x$, out of the page): G is at rest, "
                         r"so the forces balance, and their moment about G turns $\mathbf{H}_G$ with the precession."))


def free_body_diagrams(params) -> tuple[Diagram, ...]:
    """The steady precession's diagram (the same for every parameter set; the stage is 3-D: no frames)."""
    return (steady(),)


# The classic slips in drawing this diagram (practice/diagram_judge.py), as MISTAKES are the answers':
# each a load the physics does not put there, with a tutor's words that never show the diagram.
DIAGRAM_SLIPS = (
    DiagramSlip("centripetal force", "G is at rest in steady precession: nothing needs to turn it; and a "
                "centripetal force is never a force of its own, it is what the real forces add up to.",
                at="G", direction=(1, 0), either_way=True),
)



@functools.cache
@kept_pickled
def derivation() -> Derivation:
    k = _kinematics()
    omega, rolling, spin = k["omega"], k["rolling"], k["spin"]
    H_rolled, dHdt = k["H_rolled"], k["dHdt"]
    omega_rolled = sp.simplify(omega.subs(psidot, spin))
    # Step 3's laws from the diagram: the force laws give F = 0 and N = mg (a_G = 0), the moment law about G
    # (along e_x) then gives ω_p
    balance_x, balance_y, balance_m = balance(steady(), "the disk")
    forces = sp.solve([balance_x, balance_y], [F_, N_], dict=True)[0]
    moment_eq = sp.Eq(sp.simplify(balance_m.lhs.subs(forces)), balance_m.rhs)
    w_p_solved = root_with_sign(sp.solve(moment_eq, w_p), +1)
    w_p_shown = presentable(w_p_solved, sp.Pow(4 * g / (r * sp.sin(theta)), sp.S.Half, evaluate=False))
    magnitude = presentable(sp.sqrt(sp.simplify(omega_rolled.dot(omega_rolled))), w_p * sp.sin(theta))
    kinetic = sp.simplify(omega_rolled.dot(H_rolled) / 2)
    energy = m * g * r * sp.sin(theta) + kinetic
    energy_closed = presentable(energy.subs(w_p, w_p_shown), sp.Rational(3, 2) * m * g * r * sp.sin(theta))

    steps = [
        Step(r"Origin at the centre G, at rest; the frame $\{\mathbf{e}_x, \mathbf{e}_y, \mathbf{e}_z = \mathbf{E}_z\}$ "
             r"precesses with the contact point A ($\mathbf{e}_y$ horizontal toward A, $\mathbf{E}_z$ up). Angular "
             r"velocity: spin $\dot\psi$ about the normal $\mathbf{n}$ plus the precession $-\omega_p\mathbf{E}_z$",
             rf"\boldsymbol\omega = \dot\psi\,\mathbf{{n}} - \omega_p \mathbf{{E}}_z = {_vec_latex(omega)}", part=1),
        Step("Rolling without slip with G at rest: the disk's own point at A has zero velocity (the point of "
             "contact itself runs round its circle)",
             rf"\mathbf{{v}}_A = \boldsymbol\omega \times \mathbf{{r}}_{{A/G}} = {_vec_latex(rolling)} = 0"
             rf"\;\Rightarrow\; {latex_eq(psidot, spin)} = \omega_s", part=1),
        Step("So ω points along the diameter through A (the instantaneous axis passes through A and G)",
             rf"\boldsymbol\omega = {_vec_latex(omega_rolled)},\quad {latex_eq(w_tot, magnitude)}", part=1),
        Step("Angular momentum about G: ½ m r² along n, ¼ m r² across it",
             rf"\mathbf{{H}}_G = {_vec_latex(H_rolled)}", part=1),
        Step(r"$\theta$, $\omega_s$, $\omega_p$ constant: $\mathbf{H}_G$ is fixed in the precessing frame, so "
             r"$d\mathbf{H}_G/dt = -\omega_p\mathbf{E}_z \times \mathbf{H}_G$, along $\mathbf{e}_x$; G is at rest, "
             r"$\mathbf{a}_G = 0$", rf"\dot{{\mathbf{{H}}}}_G = {_vec_latex(dHdt)},\quad \mathbf{{a}}_G = 0", part=1),
        *fbd_steps(steady()),
        *balance_steps(steady()),
        Step("The force laws: no friction, and the table carries the weight",
             latex_eq(F_, forces[F_]) + r",\quad " + latex_eq(N_, forces[N_])),
        Step(r"The moment law about G, $\mathbf{e}_x$ component, with $F = 0$ and $N = mg$", latex(moment_eq)
             + rf"\;\Rightarrow\; {latex_eq(w_p, w_p_shown)}"),
        Step(r"Energy: potential $m g r\sin\theta$ plus kinetic $\tfrac12\boldsymbol\omega\cdot\mathbf{H}_G$ (G at rest)",
             latex_eq(E, energy) + " = " + latex(energy_closed)),
    ]
    chain = [
        Result("omega_p", w_p, w_p_shown, "angular_speed"),
        Result("omega_s", w_s, spin.subs(w_p, w_p), "angular_speed"),
        Result("omega_total", w_tot, magnitude, "angular_speed"),
        Result("energy", E, energy_closed, "energy"),
        Result("contact_speed", v_contact, w_p * r * sp.cos(theta), "speed"),
        Result("period", tau, 2 * sp.pi / w_p, "time"),
    ]
    return Derivation(SYMBOLS, DIMENSIONS, steps, chain, {a.name: a.label for a in ANSWERS})



def _live_cases() -> tuple[Case, ...]:
    return (Case("steady", "steady precession", derivation()),)


# Live while dragging (solvers/live.py): the tilt and the radius.
LIVE = Live(("theta", "r"), _live_cases)

@within_model_range
def solve(**params) -> Solution:
    p = validate_params(PARAMS, params)
    d_ = derivation()
    values = d_.evaluate(p)
    answers = {a.name: values[a.name] for a in ANSWERS}
    steps = list(d_.steps) + d_.numeric_steps(values)
    turn = 2 * math.pi * (1 - math.cos(p["theta"]))
    notes = (f"Per precession the contact point goes once round, but the disk itself turns only "
             f"2π(1 − cos θ) = {math.degrees(turn):.3g}° relative to the table.",)
    return Solution("eulers_disk", p, answers, tuple(steps), _checks(p, answers), "steady", notes,
                    extras={"turn_per_precession": turn})


def body_state(p, answers, phase: float = 0.0):
    """ω, the normal n and r_A/G in the fixed frame (numpy), for a precession phase φ."""
    th, wp = p["theta"], answers["omega_p"]
    c, s = math.cos(phase), math.sin(phase)
    e_y = np.array([-s, c, 0.0])  # e_x = (c, s, 0): the precessing frame turned by φ
    e_z = np.array([0.0, 0.0, 1.0])
    n = math.sin(th) * e_y + math.cos(th) * e_z
    r_AG = p["r"] * (math.cos(th) * e_y - math.sin(th) * e_z)
    omega = answers["omega_s"] * n - wp * e_z
    return omega, n, r_AG


def _checks(p, a) -> tuple[Check, ...]:
    """Second method: numpy vectors in the fixed frame at an arbitrary phase, with the inertia
    tensor built from the principal moments, and dH/dt by finite rotation of the frame."""
    omega, n, r_AG = body_state(p, a, phase=0.7)
    H = _H_at(p, a, 0.7)
    kinetic = 0.5 * omega @ H
    potential = p["m"] * p["g"] * p["r"] * math.sin(p["theta"])
    dt = 1e-6 / a["omega_p"]
    H_later = _H_at(p, a, 0.7 - a["omega_p"] * dt)
    H_earlier = _H_at(p, a, 0.7 + a["omega_p"] * dt)
    dHdt = (H_later - H_earlier) / (2 * dt)
    torque = np.cross(r_AG, np.array([0.0, 0.0, p["m"] * p["g"]]))
    scale = p["m"] * p["g"] * p["r"]
    steady = dynamics.integrate_steady(p, a["omega_p"], periods=1.0)
    return (
        Check(r"$\lvert\boldsymbol\omega\rvert$: $\omega_p\sin\theta$ vs $\lvert\omega_s\mathbf{n} - \omega_p\mathbf{E}_z\rvert$", a["omega_total"], float(np.linalg.norm(omega)),
              relative_tolerance(a["omega_total"], 1e-9),
              r"rolling without slip: $\boldsymbol\omega$ points along G→A, whose share of $\boldsymbol\omega$ is $\omega_p\sin\theta$ whatever $\omega_s$"),
        Check("energy: mgr sin θ + ½ ω·Iω", a["energy"], potential + kinetic,
              relative_tolerance(a["energy"], 1e-9), "the steady state conserves energy"),
        Check(r"$\mathbf{M}_G$ vs $d\mathbf{H}_G/dt$ (finite difference), along $\mathbf{M}_G$", float(np.linalg.norm(torque)),
              float(dHdt @ torque) / max(float(np.linalg.norm(torque)), 1e-300), 1e-5 * scale,
              "balance of angular momentum about G (the other components vanish in both)"),
        Check("tilt after one precession, Kane's equations integrated", p["theta"], p["theta"] + steady["tilt_drift"],
              1e-8, "the full rolling-disk equations keep the steady state steady"),
        Check("precession rate from Kane's equations", a["omega_p"], abs(steady["precession"][-1]),
              relative_tolerance(a["omega_p"], 1e-7), r"the same $\omega_p$ from the general equations of motion"),
    )


def _H_at(p, a, phase: float) -> np.ndarray:
    omega, n, _ = body_state(p, a, phase)
    I_axis, I_diam = p["m"] * p["r"] ** 2 / 2, p["m"] * p["r"] ** 2 / 4
    return (I_diam * np.eye(3) + (I_axis - I_diam) * np.outer(n, n)) @ omega


def orientations(p, answers, t) -> np.ndarray:
    """The disk's attitude at each time t, shape (len(t), 3, 3): R = Rz(φ) Rx(θ) Rz(ψ), body z
    along the disk's normal, with the precession φ = −ω_p t and the spin ψ = ω_s t (the rolling
    condition ψ̇ = ω_p cos θ)."""
    def rz(a):
        c, s, zero, one = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([c, -s, zero], -1), np.stack([s, c, zero], -1),
                         np.stack([zero, zero, one], -1)], -2)
    t = np.asarray(t, dtype=float)
    c, s = math.cos(p["theta"]), math.sin(p["theta"])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    return rz(-answers["omega_p"] * t) @ rx @ rz(answers["omega_s"] * t)


FRAMES = 48  # one precession's frames, its first and last alike


def frame_times(p, a, frames: int = FRAMES, xp=np) -> list:
    """The motion's instants: ``frames`` of them evenly over one precession, from t = 0. ``xp``: numpy, or
    solvers.live's namespace for expressions (the browser's motion, generated from this)."""
    return [0.0, *(a["period"] * i / (frames - 1) for i in range(1, frames))]


@per_solution
def motion(solution: Solution, frames: int = FRAMES, rim_points: int = 36) -> dict:
    """One precession: the rim, a marked radius and the contact point, in the table frame, with G
    fixed at height r sin θ above the origin (``orientations``: the rotation matrices, the contact found
    as the rim's lowest point)."""
    p, a = solution.params, solution.answers
    r = p["r"]
    t = np.array(frame_times(p, a, frames))
    G = np.array([0.0, 0.0, r * math.sin(p["theta"])])
    angles = np.linspace(0.0, 2 * np.pi, rim_points)
    rim_body = r * np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)])
    R = orientations(p, a, t)
    rims = np.swapaxes(R @ rim_body, 1, 2) + G
    marks = np.stack([np.broadcast_to(G, (frames, 3)), G + r * R[:, :, 0]], axis=1)
    down = -R[:, 2, :]  # the table's downward vertical in body axes: Rᵀ (0, 0, −1)
    d = down[:, :2] / np.hypot(down[:, 0], down[:, 1])[:, None]  # toward the lowest point of the rim
    contacts = G + r * (R[:, :, 0] * d[:, :1] + R[:, :, 1] * d[:, 1:])
    return {"t": t, "rim": rims, "mark": marks, "contact": contacts, "G": G}


@swept("theta", SYMBOLS)
def versus_tilt(base: dict, tilts: np.ndarray) -> dict[str, np.ndarray]:
    """ω_p, |ω| and the energy against the tilt θ, the other parameters held; read-only arrays."""
    d_ = derivation()
    return {k: np.array(d_.vectorized(k)(theta=tilts, **base), dtype=float) for k in ("omega_p", "omega_total", "energy")}


def derivation_of(solution: Solution) -> Derivation:
    """The derivation behind ``solution`` (its option and regime)."""
    return derivation()


# How ?seed=N varies the parameters beyond the general rule (solvers.protocol.Variants).
VARIANTS = Variants(angles_deg={"theta": (5, 40)})

WARM: tuple[dict, ...] = ()  # every option combination is warmed already


# The typical slips practice mode names: wrong expressions in this module's symbols, each
# with the feedback a tutor would give (the hint never states the right value).
MISTAKES = (
    Mistake("omega_p", "ω lies along a diameter, so the inertia is ¼ m r², not the axial ½ m r².",
            lambda p: sp.sqrt(2 * g / (r * sp.sin(theta)))),
    Mistake("omega_s", "The spin is not the precession rate: rolling with G at rest ties them "
            "through the tilt θ.", lambda p: w_p),
    Mistake("energy", "The kinetic energy is missing: the disk also turns, with kinetic energy ½ ω·H_G.",
            lambda p: m * g * r * sp.sin(theta)),
)
