"""The common mistakes of each problem, as wrong expressions in the solver's own symbols, each with
the feedback a tutor would give. One definition serves typed numbers (evaluated at the student's
parameters) and typed expressions (compared as expressions)."""
from __future__ import annotations

import sympy as sp

from solvers import disk_wall as dw
from solvers import driven_cart as dc
from solvers import eulers_disk as ed
from solvers import pendulum_rebound as pr
from solvers import rod_disk_spring as rd
from solvers import stick_ball as sb
from solvers.protocol import Mistake

S, C = sp.sin, sp.cos

MISTAKES: dict[str, tuple[Mistake, ...]] = {
    "disk_wall": (
        Mistake("v1y", "A sign: the normal component of the velocity reverses at the wall "
                "(the worked solution's slip).", lambda p: dw.e * dw.V * C(dw.theta)),
        Mistake("v1y", "The restitution coefficient is missing from the normal component.",
                lambda p: -dw.V * C(dw.theta), lambda p: p["e"] != 1),
        Mistake("v1x", "That is the velocity of a ring (I = m R²); a uniform disk has I_G = ½ m R².",
                lambda p: (dw.V * S(dw.theta) + dw.R * dw.omega) / 2, lambda p: p["mu"] == float("inf")),
        Mistake("v1x", "The spin term's sign: with ω counter-clockwise, B moves at v_x − Rω.",
                lambda p: sp.Rational(2, 3) * dw.V * S(dw.theta) - dw.R * dw.omega / 3,
                lambda p: p["mu"] == float("inf")),
        Mistake("v1x", "That is a smooth wall (μ = 0): here friction acts at B.",
                lambda p: dw.V * S(dw.theta), lambda p: p["mu"] > 0),
        Mistake("omega1", "That is the spin of a ring (I = m R²); a uniform disk has I_G = ½ m R².",
                lambda p: (dw.V * S(dw.theta) + dw.R * dw.omega) / (2 * dw.R), lambda p: p["mu"] == float("inf")),
        Mistake("omega1", "The spin term's sign: with ω counter-clockwise, B moves at v_x − Rω.",
                lambda p: (sp.Rational(2, 3) * dw.V * S(dw.theta) - dw.R * dw.omega / 3) / dw.R,
                lambda p: p["mu"] == float("inf")),
    ),
    "pendulum_rebound": (
        Mistake("I_O", "½ m r² is a disk's moment of inertia; a solid sphere has ⅖ m r² (the worked "
                "solution's slip).", lambda p: pr.m_r * pr.L**2 / 3 + pr.m_s * pr.r**2 / 2 + pr.m_s * (pr.L + pr.r) ** 2,
                lambda p: p["sphere"] == "solid"),
        Mistake("I_O", "Missing parallel-axis terms: about O each body adds its mass times the square "
                "of its centre's distance from O.", lambda p: pr.m_r * pr.L**2 / 12 + pr.SPHERE_INERTIA[p["sphere"]] * pr.m_s * pr.r**2),
        Mistake("I_O", "The rod turns about its end, not its middle: ¹⁄₁₂ m_r L² is its inertia about its centre.",
                lambda p: pr.m_r * pr.L**2 / 12 + pr.SPHERE_INERTIA[p["sphere"]] * pr.m_s * pr.r**2
                + pr.m_s * (pr.L + pr.r) ** 2),
        Mistake("theta_rebound", "e where e² belongs: energy scales with θ̇², so the swing keeps e² of it.",
                lambda p: sp.asin(sp.sin(pr.theta_I) + pr.e * (sp.sin(pr.theta0) - sp.sin(pr.theta_I))),
                lambda p: p["e"] not in (0, 1)),
        Mistake("theta_impact", "A sign: the floor is below the pivot, so sin θ_I is negative "
                "(the worked solution's slip).", lambda p: sp.asin((pr.d - pr.r) / (pr.L + pr.r)),
                lambda p: p["surface"] == "floor"),
        Mistake("omega_after", "A sign: the rod reverses its direction of rotation at the bounce.",
                lambda p: pr.e * pr.w_minus),
    ),
    "driven_cart": (
        Mistake("N_front", "Swapped axles: accelerating moves load to the rear, so the front wheels carry "
                "less (the worked solution's naming slip).", lambda p: dc.derivation(p["drive"]).expression_of("N_rear"),
                lambda p: p["mu"] > 0),
        Mistake("N_rear", "Swapped axles: accelerating moves load to the rear, so the rear wheels carry more.",
                lambda p: dc.derivation(p["drive"]).expression_of("N_front"), lambda p: p["mu"] > 0),
        Mistake("accel", "Only the driven wheels push: μg would need all four wheels driving.",
                lambda p: dc.mu * dc.g, lambda p: p["drive"] != "all"),
        Mistake("accel", "Without the load transfer (N = mg/4 each) you get μg/2; the moment balance "
                "shifts load between the axles.", lambda p: dc.mu * dc.g / 2, lambda p: p["drive"] != "all"),
    ),
    "eulers_disk": (
        Mistake("omega_p", "ω lies along a diameter, so the inertia is ¼ m r², not the axial ½ m r².",
                lambda p: sp.sqrt(2 * ed.g / (ed.r * S(ed.theta)))),
        Mistake("omega_s", "The spin is not the precession rate: rolling with G at rest ties them "
                "through the tilt θ.", lambda p: ed.w_p),
        Mistake("energy", "The kinetic energy is missing: the disk also turns, with kinetic energy ½ ω·H_G.",
                lambda p: ed.m * ed.g * ed.r * S(ed.theta)),
    ),
    "stick_ball": (
        Mistake("v_cm", "After the impact the momentum is shared by the ball and the stick.",
                lambda p: sb.v, lambda p: p["mode"] == "stick"),
        Mistake("I_cm", "Missing parallel-axis terms: about the combined CM the stick and the ball each add "
                "their mass times the square of their distance from it.", lambda p: sb.m_s * sb.l**2 / 12, lambda p: p["mode"] == "stick"),
        Mistake("omega", "Angular momentum about one point but inertia about another: take both about "
                "the combined CM (arm s − d_cm).",
                lambda p: sb.m_b * sb.v * sb.s / sb.derivation("stick").expression_of("I_cm"),
                lambda p: p["mode"] == "stick"),
        Mistake("omega", "Missing parallel-axis terms: the stick's own ¹⁄₁₂ m l² is not its inertia "
                "about the combined CM.",
                lambda p: sb.derivation("stick").in_parameters(sb.m_b * sb.v * (sb.s - sb.d_cm) / (sb.m_s * sb.l**2 / 12)),
                lambda p: p["mode"] == "stick"),
    ),
    "rod_disk_spring": (
        Mistake("I_O", "I_G where I_O belongs: about the pivot each body adds its mass times the square of "
                "its centre's distance from O.",
                lambda p: rd.m1 * rd.L**2 / 12 + rd.m2 * rd.R**2 / 2),
        Mistake("I_O", "The welded disk also turns about its own centre: its spin inertia belongs in I_O.",
                lambda p: rd.m1 * rd.L**2 / 3 + rd.m2 * (rd.L + rd.R) ** 2, lambda p: p["disk"] == "welded"),
        Mistake("U_spring", "A sign: the spring resists the fall, so its work is negative.",
                lambda p: rd.k * (rd.theta2**2 - rd.theta1**2) / 2),
        Mistake("omega2", "A pinned disk does not turn with the rod; this one is welded, so its own spin "
                "inertia belongs in I_O.", lambda p: sp.sqrt(2 * rd.T2 / (rd.m1 * rd.L**2 / 3 + rd.m2 * (rd.L + rd.R) ** 2)),
                lambda p: p["disk"] == "welded"),
        Mistake("omega2", "I_G where I_O belongs: about the pivot each body adds its mass times the square of "
                "its centre's distance from O.", lambda p: sp.sqrt(2 * rd.T2 / (rd.m1 * rd.L**2 / 12 + rd.m2 * rd.R**2 / 2))),
        Mistake("omega2", "A sign: the spring resists the fall, so its work is negative.",
                lambda p: sp.sqrt(2 * (rd.U_g - rd.U_s) / rd.I_O)),
    ),
}


def mistakes_for(problem: str, answer: str, params: dict) -> list[Mistake]:
    return [m for m in MISTAKES.get(problem, ()) if m.answer == answer and m.applies(params)]
