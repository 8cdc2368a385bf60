"""pendulum_rebound against an independent integration of the swing and the e² identity."""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.integrate import solve_ivp

from solvers import pendulum_rebound
from tests.strategies import pos

# The solver contract, typed from PROBLEMS.md independently of the solver module (tests/test_contract.py
# checks every registered problem against its CONTRACT): parameter defaults (SI, radians), answer names,
# and values the solver must refuse in plain words.
CONTRACT = {
    "defaults": dict(m_s=4.536, m_r=1.814, L=0.6096, r=0.09144, d=0.5, e=0.6, theta0=0.0, g=9.81, sphere="solid", surface="floor"),
    "answers": {"I_O", "energy_loss", "omega_after", "omega_impact", "theta_impact", "theta_rebound"},
    "out_of_range": (("d", 0.05), ("d", 2.0), ("e", -0.1), ("theta0", math.pi / 2), ("theta0", -0.7)),
    "too_large": ({"L": 1e300},),
}


@st.composite
def valid_params(draw):
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


VALID = valid_params()  # random valid parameters (SI, radians) for property tests

SPHERE_K = {"solid": 2 / 5, "hollow": 2 / 3, "disk": 1 / 2}


def inertia(p):
    return p["m_r"] * p["L"] ** 2 / 3 + SPHERE_K[p["sphere"]] * p["m_s"] * p["r"] ** 2 + p["m_s"] * (p["L"] + p["r"]) ** 2


def fall(p, theta_I):
    """θ̇ when the sphere reaches θ_I, integrating Σ M_O = I_O θ̈ (the seed's equation)."""
    moment = (p["L"] * p["m_r"] * p["g"] / 2 + (p["L"] + p["r"]) * p["m_s"] * p["g"])
    I = inertia(p)
    hit = lambda t, y: y[0] - theta_I  # noqa: E731
    hit.terminal, hit.direction = True, -1
    sol = solve_ivp(lambda t, y: [y[1], -math.cos(y[0]) * moment / I], (0, 100), [p["theta0"], 0.0],
                    events=hit, rtol=1e-11, atol=1e-12, method="LSODA")
    return sol.y_events[0][0][1]


def test_solid_sphere_inertia_and_impact_angle():
    a = pendulum_rebound.solve().answers
    p = dict(m_s=4.536, m_r=1.814, L=0.6096, r=0.09144, sphere="solid")
    assert a["I_O"] == pytest.approx(inertia(p), rel=1e-12)
    assert a["theta_impact"] == pytest.approx(math.asin((0.09144 - 0.5) / (0.6096 + 0.09144)), rel=1e-12)
    assert a["theta_impact"] < 0  # the floor is below the pivot (the seed had the sign wrong)
    assert a["omega_impact"] < 0 < a["omega_after"]


def test_the_seeds_disk_inertia_is_an_option():
    solid = pendulum_rebound.solve().answers["I_O"]
    disk = pendulum_rebound.solve(sphere="disk").answers["I_O"]
    assert disk - solid == pytest.approx((1 / 2 - 2 / 5) * 4.536 * 0.09144**2, rel=1e-12)


@settings(max_examples=50, deadline=None)
@given(VALID)
def test_impact_speed_agrees_with_integration_and_rebound_obeys_e_squared(p):
    a = pendulum_rebound.solve(**p).answers
    assert a["omega_impact"] == pytest.approx(fall(p, a["theta_impact"]), rel=1e-6)
    assert a["omega_after"] == pytest.approx(-p["e"] * a["omega_impact"], rel=1e-12, abs=1e-300)
    sI, s0, sf = math.sin(a["theta_impact"]), math.sin(p["theta0"]), math.sin(a["theta_rebound"])
    assert sf - sI == pytest.approx(p["e"] ** 2 * (s0 - sI), rel=1e-9, abs=1e-12)
    T = 0.5 * a["I_O"] * a["omega_impact"] ** 2
    assert a["energy_loss"] == pytest.approx((1 - p["e"] ** 2) * T, rel=1e-9, abs=1e-12)
    assert 0 <= a["energy_loss"] <= T * (1 + 1e-12)


def test_limits_of_restitution():
    elastic = pendulum_rebound.solve(e=1.0).answers
    assert elastic["theta_rebound"] == pytest.approx(0.0, abs=1e-9)  # back to θ0 = 0
    assert elastic["energy_loss"] == pytest.approx(0.0, abs=1e-12)
    plastic = pendulum_rebound.solve(e=0.0).answers
    assert plastic["theta_rebound"] == pytest.approx(plastic["theta_impact"])


def test_wall_is_struck_hanging_straight_down():
    a = pendulum_rebound.solve(surface="wall", d=100.0).answers  # d ignored for the wall
    assert a["theta_impact"] == pytest.approx(-math.pi / 2)


def test_release_below_the_floor_is_refused_with_the_impact_angle():
    with pytest.raises(ValueError) as err:
        pendulum_rebound.solve(theta0=math.radians(-50))
    assert err.value.theta_impact == pytest.approx(math.asin((0.09144 - 0.5) / (0.6096 + 0.09144)))


def test_the_ode_of_the_solver_runs_several_bounces():
    s = pendulum_rebound.solve()
    t, q, w, impacts, legs = pendulum_rebound.simulate(s.params, s.answers, bounces=3)
    assert len(impacts) == 4
    # The first rise is integrated (the check on θ_f); later rises are drawn from the energy integral
    # (tests/test_swing.py holds that drawing to an integration). Both reach the closed-form peaks.
    peaks = [leg.end[1] for leg in legs[1::2]]
    assert peaks == pytest.approx(s.extras["bounce_peaks"][:3], abs=1e-7)
    assert [w for _, w in impacts[1:]] == pytest.approx([impacts[0][1] * s.params["e"] ** n for n in (1, 2, 3)],
                                                         rel=1e-7)
    assert np.all(np.diff(t) >= 0), "the legs follow one another in time"


@pytest.mark.parametrize("d", [2.0, 1.25])
def test_a_rebound_too_small_to_multiply_still_turns_back(d):
    """Found by hypothesis: with e = 5e-324 the rebound rate is subnormal (θ̇⁻ × θ̇⁺ underflows to 0)
    or zero, and the integrator missed the turn, swinging on through the floor. It must stop at once."""
    s = pendulum_rebound.solve(m_s=1.0, m_r=1.0, L=1.0, r=1.0, d=d, e=5e-324, theta0=0.0, g=1.0,
                               sphere="solid", surface="floor")
    assert all(c.ok for c in s.checks), s.checks
    assert s.answers["theta_rebound"] == pytest.approx(s.answers["theta_impact"], abs=1e-9)


def test_the_drawn_motion_bounces_with_decaying_peaks():
    s = pendulum_rebound.solve()
    m = pendulum_rebound.motion(s)
    assert len(m["impact_times"]) == 4
    assert min(m["theta"]) >= s.answers["theta_impact"] - 1e-6  # never through the floor
    assert math.isclose(m["theta"][0], s.params["theta0"])
