"""stick_ball against the seed's numbers and the conservation laws about an arbitrary fixed point."""
import math

import pytest
from hypothesis import given, settings, strategies as st

from solvers import stick_ball
from tests.strategies import pos

# The solver contract, typed from PROBLEMS.md independently of the solver module (tests/test_contract.py
# checks every registered problem against its CONTRACT): parameter defaults (SI, radians), answer names,
# and values the solver must refuse in plain words.
CONTRACT = {
    "defaults": dict(m_ball=1.0, m_stick=1.0, l=1.0, v=1.0, s=0.5, mode="stick", e=0.5),
    "answers": {"I_cm", "T_after", "T_before", "d_cm", "distance_per_rev", "energy_loss", "omega", "v_cm"},
    "out_of_range": (("s", 0.6), ("s", 0.0), ("e", 2.0)),
    "too_large": ({"l": 1e300}, {"v": 1e300}, {"m_ball": 1e300}),
}


@st.composite
def valid_params(draw):
    l = draw(pos(0.05, 5))
    return {"m_ball": draw(pos(0.01, 20)), "m_stick": draw(pos(0.01, 20)), "l": l,
            "v": draw(pos(0.01, 20)), "s": draw(pos(0.01, 0.5)) * l,
            "mode": draw(st.sampled_from(["stick", "bounce"])), "e": draw(pos(0, 1))}


VALID = valid_params()  # random valid parameters (SI, radians) for property tests


def mistake_params(params: dict) -> dict:
    """Where every listed slip of practice mode applies and differs from the answer: the ball hits
    short of the stick's end."""
    return {"s": 0.4 * params.get("l", 1.0)}


def test_seed_numbers_equal_masses_end_hit():
    m, l, v = 1.0, 1.0, 1.0
    a = stick_ball.solve().answers
    assert a["d_cm"] == pytest.approx(l / 4)
    assert a["v_cm"] == pytest.approx(v / 2)
    assert a["omega"] == pytest.approx(6 * v / (5 * l))
    assert a["I_cm"] == pytest.approx(5 / 24 * m * l**2)
    assert a["T_before"] == pytest.approx(0.5 * m * v**2)
    assert a["T_after"] == pytest.approx(0.4 * m * v**2)
    assert a["distance_per_rev"] == pytest.approx(5 * math.pi * l / 6)


def test_default_s_is_the_end_of_whatever_stick():
    a = stick_ball.solve(l=2.0).answers
    assert a["d_cm"] == pytest.approx(0.5)  # l/4 with l = 2


def velocities_after(p, a):
    """(stick midpoint velocity, ball velocity, stick ω) after the impact."""
    if p["mode"] == "stick":
        return (a["v_cm"] - a["omega"] * a["d_cm"], a["v_cm"] + a["omega"] * (p["s"] - a["d_cm"]), a["omega"])
    return a["v_stick"], a["v_ball"], a["omega"]


@settings(max_examples=100, deadline=None)
@given(VALID, st.floats(-3, 3))
def test_momentum_and_angular_momentum_about_any_fixed_point(p, y0):
    a = stick_ball.solve(**p).answers
    mb, ms, l, v, s = p["m_ball"], p["m_stick"], p["l"], p["v"], p["s"]
    v_mid, v_ball, w = velocities_after(p, a)
    scale = mb * v
    assert ms * v_mid + mb * v_ball == pytest.approx(mb * v, abs=1e-9 * scale)
    # about the fixed point at arm y0 along the stick line: H = Σ m v_x (y − y0) + I ω
    H0 = mb * v * (s - y0)
    H1 = ms * v_mid * (0 - y0) + mb * v_ball * (s - y0) + ms * l**2 / 12 * w
    assert H1 == pytest.approx(H0, abs=1e-9 * scale * (abs(y0) + l))
    T1 = 0.5 * ms * v_mid**2 + 0.5 * ms * l**2 / 12 * w**2 + 0.5 * mb * v_ball**2
    assert a["T_after"] == pytest.approx(T1, rel=1e-9)
    assert a["energy_loss"] == pytest.approx(a["T_before"] - T1, abs=1e-9 * a["T_before"])
    assert a["energy_loss"] >= -1e-12 * a["T_before"]


@settings(max_examples=50, deadline=None)
@given(VALID)
def test_bounce_limits(p):
    plastic = stick_ball.solve(**{**p, "mode": "bounce", "e": 0.0}).answers
    stuck = stick_ball.solve(**{**p, "mode": "stick"}).answers
    # e → 0 ends with the ball moving with the stick's contact point: the same as attaching
    assert plastic["energy_loss"] == pytest.approx(stuck["energy_loss"], rel=1e-9)
    elastic = stick_ball.solve(**{**p, "mode": "bounce", "e": 1.0}).answers
    assert elastic["energy_loss"] == pytest.approx(0.0, abs=1e-9 * elastic["T_before"])
    # restitution: separation speed at the contact is e times the approach speed
    e = p["e"]
    b = stick_ball.solve(**{**p, "mode": "bounce"}).answers
    assert b["v_stick"] + b["omega"] * p["s"] - b["v_ball"] == pytest.approx(e * p["v"], abs=1e-9 * p["v"])
