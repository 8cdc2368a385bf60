"""rod_disk_spring against the seed's numbers and an independent integration of the motion."""
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings, strategies as st
from scipy.integrate import solve_ivp

from solvers import rod_disk_spring
from tests.derivations import declared_symbols, no_title_states_an_answer, number
from solvers.diagram import balance, balance_steps, fbd_steps, residuals
from tests.strategies import pos
from tests.drawing import DRAWN, EXAMPLES, circle, drawn, figures, static

# The solver contract, typed from PROBLEMS.md independently of the solver module (tests/physics/test_contract.py
# checks every registered problem against its CONTRACT): parameter defaults (SI, radians), answer names,
# and values the solver must refuse in plain words.
CONTRACT = {
    "defaults": dict(m1=6.0, m2=9.0, k=20.0, L=0.45, R=0.075, theta1=0.0, theta2=math.pi / 2, g=9.81, disk="welded"),
    "answers": {"I_O", "T2", "U_gravity", "U_spring", "omega2"},
    "out_of_range": (("theta2", 0.0), ("theta2", 2 * math.pi), ("k", -1.0)),
    "too_large": (dict(m1=1e300, m2=1e300, k=1e300, L=1e300, R=1e300, g=1e300),),
}


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


@st.composite
def valid_params(draw):
    """Parameters for which the assembly does reach θ2 (checked here from the energy, independently)."""
    p = {"m1": draw(pos(0.1, 30)), "m2": draw(pos(0.1, 30)), "L": draw(pos(0.05, 2)),
         "R": draw(pos(0.01, 0.5)), "g": draw(pos(1, 25)),
         "disk": draw(st.sampled_from(["welded", "pinned"]))}
    Q = (p["m1"] * p["L"] / 2 + p["m2"] * (p["L"] + p["R"])) * p["g"]
    p["k"] = draw(pos(0, 0.9)) * Q  # softer than gravity at the top, so an upright release falls
    p["theta1"] = draw(st.one_of(st.just(0.0), pos(0, 1.0)))
    p["theta2"] = p["theta1"] + draw(pos(0.05, 3.0))
    return p


VALID = valid_params().filter(reaches)  # random valid parameters (SI, radians) that reach θ2

# Cases of the shared tests in test_what_students_see.py beyond the defaults.
IN_VIEW = ({"k": 0.0},)  # no spring: over the top, still in view
EDGE_LINKS = ({"k": "0"},)  # links whose numbers could read −0
CHECK_CASES = ({"theta1": 0.4, "theta2": 2.0},)  # released off upright: every shown check can fail here too
LIMIT_LINKS = (({"k": "100"}, 1), ({"k": "51"}, 1))  # held upright, or stopped short of θ₂: the method and the picture


def test_seed_numbers():
    a = rod_disk_spring.solve().answers
    assert a["omega2"] == pytest.approx(4.90, abs=0.005)
    assert a["I_O"] / 2 == pytest.approx(1.455, abs=0.0005)  # T = 1.455 θ̇²
    assert a["U_gravity"] == pytest.approx(13.24 + 46.35, abs=0.01)
    assert a["U_spring"] == pytest.approx(-20 * math.pi**2 / 8, rel=1e-12)  # −24.67 J
    assert a["T2"] == pytest.approx(34.92, abs=0.01)


def integrate(p, I):
    Q = (p["m1"] * p["L"] / 2 + p["m2"] * (p["L"] + p["R"])) * p["g"]
    at = lambda t, y: y[0] - p["theta2"]  # noqa: E731
    at.terminal, at.direction = True, 1
    w0 = 1e-7 if p["theta1"] < 1e-3 else 0.0  # near upright (an equilibrium): a stated nudge
    sol = solve_ivp(lambda t, y: [y[1], (Q * math.sin(y[0]) - p["k"] * y[0]) / I], (0, 1e4),
                    [p["theta1"], w0], events=at, rtol=1e-11, atol=1e-13, method="LSODA")
    return sol.y_events[0][0][1]


@settings(max_examples=40, deadline=None)
@given(VALID)
def test_speed_agrees_with_integration(p):
    assume(reaches(p))
    a = rod_disk_spring.solve(**p).answers
    I = p["m1"] * p["L"] ** 2 / 3 + p["m2"] * (p["L"] + p["R"]) ** 2 + (
        p["m2"] * p["R"] ** 2 / 2 if p["disk"] == "welded" else 0.0)
    assert a["I_O"] == pytest.approx(I, rel=1e-12)
    assert a["omega2"] == pytest.approx(integrate(p, I), rel=1e-5)
    assert a["T2"] == pytest.approx(0.5 * I * a["omega2"] ** 2, rel=1e-9)


def test_pinned_disk_turns_faster_than_welded():
    assert rod_disk_spring.solve(disk="pinned").answers["omega2"] > rod_disk_spring.solve().answers["omega2"]


def test_spring_that_stops_the_rod_reports_the_largest_angle():
    with pytest.raises(ValueError) as err:
        rod_disk_spring.solve(k=40.0, theta2=math.radians(300))
    theta_max = err.value.theta_max
    # at θ_max the kinetic energy is zero: gravity's work equals the spring's stored energy
    Q = (6 * 0.45 / 2 + 9 * 0.525) * 9.81
    assert Q * (1 - math.cos(theta_max)) == pytest.approx(40.0 / 2 * theta_max**2, rel=1e-9)
    assert f"{math.degrees(theta_max):.4g}" in str(err.value)
    # asking for an angle just below it works
    assert rod_disk_spring.solve(k=40.0, theta2=theta_max * 0.999).answers["omega2"] > 0


def test_stiff_spring_holds_it_upright():
    """Upright both moments vanish: the refusal names what decides, k against Q (59.6 N·m here: (6·0.45/2 +
    9·0.525)·9.81), not a moment that "already beats" another at θ = 0."""
    with pytest.raises(ValueError) as err:
        rod_disk_spring.solve(k=100.0)
    assert err.value.theta_max == 0.0
    said = str(err.value)
    assert "upright is stable" in said and "k = 100 N·m/rad ≥ Q = 59.6" in said and "already beats" not in said, said


@pytest.mark.parametrize("theta1", [0.0, 5e-4])
def test_the_linearised_escape_from_upright_matches_integrating_all_the_way(theta1):
    """A nudged release leaves upright on its linearised motion for ESCAPE rad; integrating the
    full equation from the nudge itself (hundreds of steps more) lands on the same θ̇ at θ₂."""
    from solvers.swing import integrate_leg
    s = rod_disk_spring.solve(theta1=theta1)
    p = dict(s.params)
    acc = rod_disk_spring.equation_of_motion(p, s.answers["I_O"])
    whole = integrate_leg(acc, theta1, rod_disk_spring.NUDGE, 0.0, 100.0, stop_at_angle=p["theta2"], direction=1)
    leg, _ = rod_disk_spring._legs(tuple(sorted(p.items())) + (("I_O", s.answers["I_O"]),))
    assert leg.t[0] == 0.0 and leg.theta[0] == theta1
    assert leg.end[2] == pytest.approx(whole.end[2], rel=1e-9)
    assert leg.end[0] == pytest.approx(whole.end[0], rel=1e-6)


def test_the_stop_is_a_physical_limit_the_page_can_show():
    from solvers.core import PhysicalLimitError
    with pytest.raises(PhysicalLimitError) as err:
        rod_disk_spring.solve(theta2=6.0)
    assert 0 < err.value.theta_max < 6.0
    assert "largest angle" in str(err.value)


def first_stop(p) -> float:
    """The first angle past θ₁ where the kinetic energy Q (cos θ₁ − cos θ) − k (θ² − θ₁²)/2 is spent (a
    fine grid for the bracket, then Brent's method): the turning point from the energy alone."""
    from scipy.optimize import brentq
    Q = (p["m1"] * p["L"] / 2 + p["m2"] * (p["L"] + p["R"])) * p["g"]
    energy = lambda q: Q * (math.cos(p["theta1"]) - math.cos(q)) - p["k"] / 2 * (q * q - p["theta1"] ** 2)  # noqa: E731
    grid = np.linspace(p["theta1"], p["theta2"], 20001)[1:]
    spent = int(np.argmax(np.array([energy(q) for q in grid]) <= 0))
    return brentq(energy, grid[spent - 1] if spent else p["theta1"] + 1e-12, grid[spent], xtol=1e-14)


# Parameters where the spring stops the rod short of θ₂ after it has fallen some way.
STOPPED = valid_params().filter(lambda p: not reaches(p) and (p["theta1"] == 0 or
          (p["m1"] * p["L"] / 2 + p["m2"] * (p["L"] + p["R"])) * p["g"] * math.sin(p["theta1"]) > p["k"] * p["theta1"]))


@EXAMPLES
@given(STOPPED)
def test_beside_the_refusal_the_swing_turns_where_the_energy_is_spent_short_of_theta2(p):
    """viz.at_limit draws the swing the refusal speaks of: integrated, the rod turns at the angle where the
    energy balance says the kinetic energy is spent (θ_max, found here by root-finding), never past it
    nor past θ₂, dashed where it was asked for; its caption names the refusal's θ_max."""
    from viz.rod_disk_spring import at_limit
    with pytest.raises(rod_disk_spring.SpringStopsRodError) as refused:
        rod_disk_spring.solve(**p)
    theta_max = first_stop(p)
    assert refused.value.theta_max == pytest.approx(theta_max, abs=1e-6)
    (figure,) = at_limit(p)
    angles = np.array([math.atan2(xs[-1], ys[-1]) for xs, ys in drawn(figure, "rod")])
    angles = np.where(angles < -1e-9, angles + 2 * math.pi, angles)  # θ from the upward vertical, 0 to 2π
    reach = p["L"] + 2 * p["R"]
    assert angles.max() <= theta_max + DRAWN / p["L"] + 1e-9 and angles.max() < p["theta2"]
    assert angles.max() == pytest.approx(theta_max, abs=1e-6 + DRAWN / p["L"]), (angles.max(), theta_max)
    assert angles[figure.key_frame] == angles.max()  # the key instant: the turn
    mark_x, mark_y = static(figure, "θ₂")
    assert math.atan2(mark_x[-1], mark_y[-1]) % (2 * math.pi) == pytest.approx(p["theta2"], abs=DRAWN / reach + 1e-6)
    assert f"{math.degrees(refused.value.theta_max):.4g}°" in figure.description


@pytest.mark.parametrize("theta1, k", [(0.0, 100.0), (0.3, 60.0)])
def test_where_the_rod_does_not_fall_the_assembly_is_drawn_at_its_release(theta1, k):
    """Held upright by a stiff spring, or released where the spring already wins (k θ₁ ≥ Q sin θ₁): no
    swing toward θ₂ to show, so a still picture of the assembly at θ₁, the disk on the rod's end, the
    spring round the pivot clear of it, θ₂ dashed."""
    from viz.rod_disk_spring import at_limit
    p = {**CONTRACT["defaults"], "k": k, "theta1": theta1, "theta2": 2.0}
    Q = (p["m1"] * p["L"] / 2 + p["m2"] * (p["L"] + p["R"])) * p["g"]
    assert (Q <= k) if theta1 == 0 else (k * theta1 >= Q * math.sin(theta1))  # the case, from the moments alone
    with pytest.raises(rod_disk_spring.SpringStopsRodError):
        rod_disk_spring.solve(**p)
    (figure,) = at_limit(p)
    assert "animation" not in figure.spec
    rod_x, rod_y = static(figure, "rod")
    assert math.atan2(rod_x[-1], rod_y[-1]) == pytest.approx(theta1, abs=DRAWN / p["L"])
    cx, cy, radius = circle(*static(figure, "disk"))
    assert radius == pytest.approx(p["R"], abs=DRAWN)
    assert math.hypot(cx, cy) == pytest.approx(p["L"] + p["R"], abs=2 * DRAWN)
    sx, sy = static(figure, "torsional spring")
    assert np.hypot(sx - cx, sy - cy).min() >= radius - DRAWN
    mark_x, mark_y = static(figure, "θ₂")
    assert math.atan2(mark_x[-1], mark_y[-1]) == pytest.approx(2.0, abs=1e-3)


# ----------------------------------------------------------------------------------------------
# What a student sees: the drawing agrees with the physics, the captions with the motion


@EXAMPLES
@given(VALID)
def test_the_disk_never_covers_the_spring(p):
    assume(p["k"] > 0)  # valid("rod_disk_spring") reaches θ2 already
    _, (figure,) = figures("rod_disk_spring", **p)
    for (xs, ys), (sx, sy) in zip(drawn(figure, "disk"), drawn(figure, "torsional spring")):
        cx, cy, radius = circle(xs, ys)
        assert np.hypot(sx - cx, sy - cy).min() >= radius - DRAWN


def test_the_spring_animation_starts_where_the_motion_is_visible_and_says_it_was_nudged():
    solution, (figure,) = figures("rod_disk_spring")
    anim = figure.spec["animation"]
    theta = np.array([math.atan2(x[1], y[1]) for x, y in drawn(figure, "rod")])  # rod tip angle from up
    assert math.degrees(abs(theta[0])) < 2  # no long wait at upright before the fall
    assert "nudge" in figure.description and "animation starts there" in figure.description
    turn = np.degrees(np.abs(np.diff(np.unwrap(theta))))
    assert turn.max() <= 10.5  # dense through the fast part
    assert anim["times"][0] > 1.0  # the creep it skipped (the nudge is 1e-6 rad/s)
    moved = np.abs(np.degrees(theta)) > 3
    assert moved.mean() > 0.8  # most frames show motion, not an upright rod


def test_with_no_spring_the_caption_says_it_goes_over_the_top():
    _, (figure,) = figures("rod_disk_spring", k=0.0)
    assert not any(t["name"] == "torsional spring" for t in figure.spec["data"])  # and none is drawn
    assert "keeps turning" in figure.description and "comes to rest at about 360" not in figure.description
    _, (pendulum,) = figures("rod_disk_spring", k=0.0, theta1=0.3)
    assert "returns" in pendulum.description  # released off upright, it swings back like a pendulum


# ----------------------------------------------------------------------------------------------
# The free-body diagram (Step 2), the balance laws written from it (Step 3), and the stage's frames


@pytest.mark.parametrize("disk", ["welded", "pinned"])
@settings(max_examples=10, deadline=None)
@given(VALID)
def test_the_balance_laws_hold_at_the_solvers_numbers(disk, p):
    """ΣF = m a_G and ΣM_O = −I_O θ̈ (θ grows clockwise), summed from the declared loads, hold passing θ₂
    at the solver's numbers: |θ̇₂| its answer, θ̈ from its equation of motion, I_O the derivation's (no
    spin of a pinned disk: it does not turn)."""
    p = {**p, "disk": disk}  # (whether it reaches θ₂ does not depend on the disk's spin)
    solution = rod_disk_spring.solve(**p)
    (d,) = rod_disk_spring.free_body_diagrams(solution.params)
    values = d.values(solution)
    assert declared_symbols(d) <= set(values), declared_symbols(d) - set(values)
    assert values[rod_disk_spring.theta] == p["theta2"] and values[rod_disk_spring.thetadot] == solution.answers["omega2"]
    I = p["m1"] * p["L"] ** 2 / 3 + p["m2"] * (p["L"] + p["R"]) ** 2 + (p["m2"] * p["R"] ** 2 / 2 if disk == "welded" else 0)
    assert values[rod_disk_spring.I_O] == pytest.approx(I, rel=1e-12)
    laws = balance(d, "the rod and disk")
    terms = [t for eq in laws for side in (eq.lhs, eq.rhs) for t in sp.Add.make_args(sp.expand(side))]
    scale = max(abs(number(t, values)) for t in terms)
    for law, left, right in residuals(d, solution):
        assert abs(left - right) <= 1e-9 * scale, (law, left, right, scale)


def test_a_spring_couple_turned_round_or_a_weight_pointing_up_breaks_the_balance():
    """Positive control: the moment law catches a couple with the twist, and the force laws a weight up."""
    from dataclasses import replace

    solution = rod_disk_spring.solve(theta1=0.4, theta2=2.0)
    (d,) = rod_disk_spring.free_body_diagrams(solution.params)
    for load in d.loads:
        if load.kind == "couple":
            wrong = replace(load, size=-load.size)
        elif load.direction is not None:
            wrong = replace(load, direction=tuple(-c for c in load.direction))
        else:
            continue
        broken = replace(d, loads=tuple(wrong if l is load else l for l in d.loads))
        assert any(not math.isclose(a, b, rel_tol=1e-6) for _, a, b in residuals(broken, solution)), load.symbol


@settings(max_examples=40, deadline=None)
@given(VALID)
def test_the_loads_point_as_the_physics_says(p):
    """Gravity down (−y on the stage) at the rod's and the disk's centres; the spring's couple opposes its
    twist (untwisted at θ = 0): its component along θ's own sense of rotation, which the declared points
    give (the sign of r × ∂r/∂θ), has the sign opposite to θ. The points where the stage puts them: θ
    from the upward vertical toward +x."""
    solution = rod_disk_spring.solve(**p)
    (d,) = rod_disk_spring.free_body_diagrams(solution.params)
    v = d.values(solution)
    body = d.body("the rod and disk")
    weights = [l for l in d.loads if l.by == "gravity"]
    assert sorted(l.at for l in weights) == ["G_1", "G_2"]
    for load in weights:
        x, y = (number(c, v) for c in load.vector)
        assert x == 0 and y < 0, load.symbol
    angle = float(v[rod_disk_spring.theta])
    for name, rho in (("G_1", p["L"] / 2), ("G_2", p["L"] + p["R"]), ("A", p["L"])):
        x, y = (number(c, v) for c in body.points[name])
        assert (x, y) == pytest.approx((rho * math.sin(angle), rho * math.cos(angle)), rel=1e-12, abs=1e-12)
    tip = [sp.sympify(c) for c in body.points["A"]]
    turning = number(tip[0] * sp.diff(tip[1], rod_disk_spring.theta) - tip[1] * sp.diff(tip[0], rod_disk_spring.theta), v)
    assert turning < 0  # θ grows clockwise, as the stage turns the rod
    (couple,) = [l for l in d.loads if l.kind == "couple"]
    assert couple.by == "the torsional spring" and couple.at == "O"
    along_theta = math.copysign(1.0, turning) * number(couple.size, v)
    assert along_theta * angle <= 0  # against the twist
    assert abs(along_theta) == pytest.approx(p["k"] * abs(angle), rel=1e-12, abs=1e-300)


@EXAMPLES
@given(VALID)
def test_the_stage_s_frames_carry_the_diagram_at_each_frame(p):
    """``frames`` gives every symbol an array of the motion's length, one per frame of the stage's figure
    (the overlay's frames are the animation's); the motion has a frame at θ₂, where the diagram is drawn,
    with the same numbers as ``values``; and the figure draws the disk where the diagram puts G_2."""
    solution, (figure,) = figures("rod_disk_spring", **p)
    m = rod_disk_spring.motion(solution)
    n = len(m["t"])
    assert len(figure.spec["animation"]["times"]) == n
    (d,) = rod_disk_spring.free_body_diagrams(solution.params)
    per_frame = d.frames(solution, m)
    assert set(per_frame) >= declared_symbols(d)
    assert all(np.shape(v) == (n,) and np.isfinite(v).all() for v in per_frame.values())
    values = d.values(solution)
    scale = max(abs(float(v)) for v in values.values())
    same = np.ones(n, dtype=bool)
    for s, v in values.items():
        same &= np.isclose(per_frame[s], float(v), rtol=1e-9, atol=1e-12 * scale)
    agree = list(np.nonzero(same)[0])
    assert agree and agree[0] == figure.key_frame  # the key instant: passing θ₂ on the fall
    i = agree[0]
    xs, ys = drawn(figure, "disk")[i]
    at = {s: per_frame[s][i] for s in per_frame}
    centre = [number(c, at) for c in d.body("the rod and disk").points["G_2"]]
    assert circle(xs, ys)[:2] == pytest.approx(centre, abs=2 * DRAWN)
    for j in (0, n // 2, n - 1):  # and at any frame
        xs, ys = drawn(figure, "disk")[j]
        at = {s: per_frame[s][j] for s in per_frame}
        assert circle(xs, ys)[:2] == pytest.approx([number(c, at) for c in d.body("the rod and disk").points["G_2"]],
                                                   abs=2 * DRAWN)


def test_the_derivation_is_in_the_four_steps_with_the_diagram_in_steps_two_and_three():
    """Origin, coordinates and basis, the kinematics and I_O first (part 1), then Step 2 and Step 3 from the
    diagram, then the works and the work–energy equation, the moment law integrated; the spring's work
    is its couple's from the diagram. No title states a result."""
    for disk in ("welded", "pinned"):
        solution = rod_disk_spring.solve(disk=disk)
        steps = solution.steps
        parts = [s.part for s in steps]
        assert parts == sorted(parts) and set(parts) == {1, 2, 3, 4}
        assert steps[0].title.startswith("Origin at the pin O") and "basis" in steps[0].title
        (d,) = rod_disk_spring.free_body_diagrams(solution.params)
        assert [s for s in steps if s.part == 2] == list(fbd_steps(d))
        assert [s for s in steps if s.part == 3] == list(balance_steps(d))
        assert any("moment law" in s.title and "integrated" in s.title for s in steps if s.part == 4)
        assert ("pinned" in disk) == ("does not change" in d.note)
        no_title_states_an_answer(solution)



def test_theta2_passed_just_before_the_spring_stops_it_is_found_on_the_first_swing():
    """The rod and disk pass θ₂ = 135.9° only 0.13° before the spring stops them, within one of the
    integration's grid steps, both samples short of it: the fall's end (its key frame, the check's θ̇₂) is
    that first passage, at the time solve_ivp (DOP853, its own event search) finds, not a later swing's."""
    p = {"m1": 2.874951628287427, "m2": 10.16703829397586, "L": 1.699504256378757, "R": 0.4356766195602051,
         "g": 18.99104393376579, "disk": "pinned", "k": 279.60003565268397, "theta1": 0.10062537109580985,
         "theta2": 2.3712327735774354}
    s = rod_disk_spring.solve(**p)
    Q, I = rod_disk_spring.weight_moment(s.params), s.answers["I_O"]
    reached = lambda t, y: y[0] - p["theta2"]  # noqa: E731
    reached.terminal = True
    sol = solve_ivp(lambda t, y: [y[1], (Q * math.sin(y[0]) - p["k"] * y[0]) / I], (0, 20), [p["theta1"], 0.0],
                    method="DOP853", events=reached, rtol=1e-12, atol=1e-14, max_step=0.005)
    fall = rod_disk_spring.simulate(s.params, s.answers)
    m = rod_disk_spring.motion(s)
    at_theta2 = float(m["t"][np.argmin(np.abs(m["theta"] - p["theta2"]))])
    assert at_theta2 == pytest.approx(sol.t_events[0][0], abs=1e-6)
    assert np.all(np.diff(fall.theta) > 0)  # one fall to the turn, no swing back in it
