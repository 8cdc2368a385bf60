"""disk_wall against the seed's closed form and against Routh's method: the impact integrated
step by step in the normal impulse, with Coulomb friction deciding stick or slip at each step."""
import math

import pytest
from hypothesis import given, settings, strategies as st

from solvers import disk_wall
from tests.strategies import pos
from tests.drawing import DRAWN, EXAMPLES, circle, drawn, figures, static

# The solver contract, typed from PROBLEMS.md independently of the solver module (tests/physics/test_contract.py
# checks every registered problem against its CONTRACT): parameter defaults (SI, radians), answer names,
# and values the solver must refuse in plain words.
CONTRACT = {
    "defaults": dict(m=1.0, R=0.1, V=2.0, theta=math.radians(30), omega=5.0, e=1.0, mu=math.inf),
    "answers": {"energy_loss", "impulse_n", "impulse_t", "omega1", "speed1", "v1x", "v1y"},
    "out_of_range": (("m", -1.0), ("theta", math.pi / 2), ("e", 1.5), ("mu", -0.1), ("V", 0.0), ("R", 0.0)),
    "too_large": ({"V": 1e200}, {"omega": 1e200}),
}


# random valid parameters (SI, radians) for property tests
VALID = st.fixed_dictionaries({
    "m": pos(0.01, 100), "R": pos(0.005, 5), "V": pos(0.01, 50),
    "theta": pos(0, math.radians(89.5)), "omega": pos(-200, 200), "e": pos(0, 1),
    "mu": st.one_of(st.just(math.inf), pos(0, 5)),
})

# Cases of the shared tests in test_what_students_see.py beyond the defaults.
IN_VIEW = ({"e": 0.0},)  # no rebound: still in view
EDGE_LINKS = ({"e": "0"}, {"mu": "0"})  # links whose numbers could read −0
CHECK_CASES = ({"mu": 0.2, "e": 0.5},)  # sliding: every shown check can fail here too


def mistake_params(params: dict) -> dict:
    """Where every listed slip of practice mode applies and differs from the answer: the restitution
    slip needs e ≠ 1."""
    return {"e": 0.5}


def routh(m, R, V, theta, omega, e, mu, steps=20000):
    """Integrate the impact in the normal impulse p from 0 to (1 + e) m V cos θ (a uniform disk's
    normal and tangential directions are uncoupled, so Poisson's and Newton's e agree)."""
    I = 0.5 * m * R**2
    vx, vy, w = V * math.sin(theta), V * math.cos(theta), omega
    total = (1 + e) * m * V * math.cos(theta)
    dp = total / steps
    Pt = 0.0
    for _ in range(steps):
        slip = vx - R * w
        # tangential impulse that would stop the slip in this step, and friction's cap
        stop = -slip / (1 / m + R**2 / I)
        dPt = stop if abs(stop) <= mu * dp else -math.copysign(mu * dp, slip)
        vx += dPt / m
        w -= R * dPt / I
        vy -= dp / m
        Pt += dPt
    return vx, vy, w, Pt, -total


def test_seed_closed_form_no_slip():
    V, th, R, w = 2.0, math.radians(30), 0.1, 5.0
    a = disk_wall.solve().answers
    assert a["v1x"] == pytest.approx(2 / 3 * V * math.sin(th) + R * w / 3, rel=1e-12)
    assert a["omega1"] == pytest.approx(a["v1x"] / R, rel=1e-12)
    assert a["v1y"] == pytest.approx(-V * math.cos(th), rel=1e-12)  # reverses (the seed's slip)
    assert a["speed1"] == pytest.approx(math.hypot(a["v1x"], a["v1y"]), rel=1e-12)
    assert a["impulse_n"] == pytest.approx(-2 * 1.0 * V * math.cos(th), rel=1e-12)


@settings(max_examples=60, deadline=None)
@given(VALID)
def test_agrees_with_routh_integration(p):
    mu = p["mu"] if math.isfinite(p["mu"]) else 1e9
    vx, vy, w, Pt, Pn = routh(**{**p, "mu": mu}, steps=4000)
    a = disk_wall.solve(**p).answers
    scale = p["V"] + p["R"] * abs(p["omega"])
    assert a["v1x"] == pytest.approx(vx, abs=2e-3 * scale)
    assert a["v1y"] == pytest.approx(vy, abs=1e-9 * scale)
    assert a["omega1"] * p["R"] == pytest.approx(w * p["R"], abs=2e-3 * scale)
    assert a["impulse_n"] == pytest.approx(Pn, rel=1e-9)


@settings(max_examples=100, deadline=None)
@given(VALID)
def test_momentum_bookkeeping_and_energy_never_increases(p):
    a = disk_wall.solve(**p).answers
    m, R = p["m"], p["R"]
    I = 0.5 * m * R**2
    vx0, vy0 = p["V"] * math.sin(p["theta"]), p["V"] * math.cos(p["theta"])
    assert m * (a["v1x"] - vx0) == pytest.approx(a["impulse_t"], abs=1e-9 * m * (p["V"] + R * abs(p["omega"])))
    assert m * (a["v1y"] - vy0) == pytest.approx(a["impulse_n"], abs=1e-9 * m * p["V"])
    # about the contact point: H_B = I ω + m R v_x is unchanged
    H0 = I * p["omega"] + m * R * vx0
    H1 = I * a["omega1"] + m * R * a["v1x"]
    assert H1 == pytest.approx(H0, abs=1e-9 * (abs(I * p["omega"]) + m * R * p["V"]))
    T0 = 0.5 * m * p["V"] ** 2 + 0.5 * I * p["omega"] ** 2
    T1 = 0.5 * m * a["speed1"] ** 2 + 0.5 * I * a["omega1"] ** 2
    assert a["energy_loss"] == pytest.approx(T0 - T1, abs=1e-9 * T0)
    assert a["energy_loss"] >= -1e-9 * T0
    if math.isfinite(p["mu"]):
        assert abs(a["impulse_t"]) <= p["mu"] * abs(a["impulse_n"]) * (1 + 1e-9) + 1e-15


def test_limits():
    # μ = 0: a smooth wall leaves the tangential motion and the spin alone
    a = disk_wall.solve(mu=0.0, e=0.5).answers
    assert a["v1x"] == pytest.approx(2.0 * math.sin(math.radians(30)))
    assert a["omega1"] == pytest.approx(5.0)
    assert a["v1y"] == pytest.approx(-0.5 * 2.0 * math.cos(math.radians(30)))
    # μ large: the finite-μ answer becomes the no-slip one
    assert dict(disk_wall.solve(mu=1e6).answers) == pytest.approx(dict(disk_wall.solve().answers))
    # e = 0: the disk leaves along the wall
    assert disk_wall.solve(e=0.0).answers["v1y"] == 0.0
    # a smooth elastic impact conserves energy
    assert disk_wall.solve(mu=0.0, e=1.0).answers["energy_loss"] == pytest.approx(0.0, abs=1e-12)


def test_slip_regime_is_reported_and_limited():
    s = disk_wall.solve(mu=0.02, omega=-30.0)
    assert s.regime == "slip"
    assert abs(s.answers["impulse_t"]) == pytest.approx(0.02 * abs(s.answers["impulse_n"]))
    assert disk_wall.solve().regime == "stick"


# ----------------------------------------------------------------------------------------------
# What a student sees: the drawing agrees with the physics, the captions with the motion


@EXAMPLES
@given(VALID)
def test_the_disk_never_enters_the_wall(p):
    _, (figure,) = figures("disk_wall", **p)
    _, wall_y = static(figure, "wall")
    for xs, ys in drawn(figure, "disk"):
        cx, cy, radius = circle(xs, ys)
        assert wall_y[0] - cy >= radius - DRAWN * (1 + p["R"])


@pytest.mark.parametrize("e", [0.0, 0.3, 1.0])
def test_the_disk_leaves_the_wall_only_when_the_caption_says_so(e):
    solution, (figure,) = figures("disk_wall", e=e)
    ys = [circle(*frame)[1] for frame in drawn(figure, "disk")]
    after = ys[figure.spec["animation"]["times"].tolist().index(0.0):]
    if e == 0:
        assert "does not rebound" in figure.description and "leaves" not in figure.description
        assert max(after) - min(after) < DRAWN
    else:
        assert "leaves at" in figure.description
        assert after[-1] < after[0] - 0.5 * solution.params["R"]
