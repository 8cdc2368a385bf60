"""Hypothesis strategies: random *valid* parameters for each problem (SI, radians)."""
from __future__ import annotations

import math

from hypothesis import strategies as st


def pos(lo, hi):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


disk_wall = st.fixed_dictionaries({
    "m": pos(0.01, 100), "R": pos(0.005, 5), "V": pos(0.01, 50),
    "theta": pos(0, math.radians(89.5)), "omega": pos(-200, 200), "e": pos(0, 1),
    "mu": st.one_of(st.just(math.inf), pos(0, 5)),
})


@st.composite
def pendulum_rebound(draw):
    L = draw(pos(0.05, 3))
    r = draw(pos(0.01, 1))
    surface = draw(st.sampled_from(["floor", "wall"]))
    d = draw(pos(r * 1.01, (L + 2 * r) * 0.99))
    sin_I = (r - d) / (L + r) if surface == "floor" else -1.0
    theta_I = math.asin(sin_I)
    theta0 = draw(pos(theta_I + 0.02, math.radians(89)))
    return {"m_s": draw(pos(0.05, 50)), "m_r": draw(pos(0.05, 50)), "L": L, "r": r, "d": d,
            "e": draw(pos(0, 1)), "theta0": theta0, "g": draw(pos(1, 25)),
            "sphere": draw(st.sampled_from(["solid", "hollow", "disk"])), "surface": surface}


@st.composite
def driven_cart(draw):
    a, b = draw(pos(0.05, 3)), draw(pos(0.1, 3))
    drive = draw(st.sampled_from(["front", "rear", "all"]))
    mu_max = 5 if drive == "front" else 0.999 * b / a
    return {"m": draw(pos(10, 1e4)), "a": a, "b": b, "c": draw(pos(0.1, 2)),
            "mu": draw(pos(0, mu_max)), "g": draw(pos(1, 25)), "drive": drive}


eulers_disk = st.fixed_dictionaries({
    "m": pos(0.01, 10), "r": pos(0.005, 1), "theta": pos(math.radians(0.5), math.radians(89.5)),
    "g": pos(1, 25),
})


@st.composite
def stick_ball(draw):
    l = draw(pos(0.05, 5))
    return {"m_ball": draw(pos(0.01, 20)), "m_stick": draw(pos(0.01, 20)), "l": l,
            "v": draw(pos(0.01, 20)), "s": draw(pos(0.01, 0.5)) * l,
            "mode": draw(st.sampled_from(["stick", "bounce"])), "e": draw(pos(0, 1))}


@st.composite
def rod_disk_spring(draw):
    """Parameters for which the assembly does reach θ2 (checked here from the energy, independently)."""
    p = {"m1": draw(pos(0.1, 30)), "m2": draw(pos(0.1, 30)), "L": draw(pos(0.05, 2)),
         "R": draw(pos(0.01, 0.5)), "g": draw(pos(1, 25)),
         "disk": draw(st.sampled_from(["welded", "pinned"]))}
    Q = (p["m1"] * p["L"] / 2 + p["m2"] * (p["L"] + p["R"])) * p["g"]
    p["k"] = draw(pos(0, 0.9)) * Q  # softer than gravity at the top, so an upright release falls
    p["theta1"] = draw(st.one_of(st.just(0.0), pos(0, 1.0)))
    p["theta2"] = p["theta1"] + draw(pos(0.05, 3.0))
    return p


def reaches(p) -> bool:
    """Does the released assembly get to θ2? (kinetic energy stays positive on the way)"""
    Q = (p["m1"] * p["L"] / 2 + p["m2"] * (p["L"] + p["R"])) * p["g"]
    th1 = p["theta1"]
    if Q * math.sin(th1) - p["k"] * th1 <= 0 and th1 > 0:
        return False
    n = 2000
    for i in range(1, n + 1):
        q = th1 + (p["theta2"] - th1) * i / n
        if Q * (math.cos(th1) - math.cos(q)) - p["k"] / 2 * (q * q - th1 * th1) <= 0:
            return False
    return True


ALL = {
    "disk_wall": disk_wall, "pendulum_rebound": pendulum_rebound(), "driven_cart": driven_cart(),
    "eulers_disk": eulers_disk, "stick_ball": stick_ball(), "rod_disk_spring": rod_disk_spring(),
}
