"""pendulum_rebound against an independent integration of the swing and the e² identity."""
import importlib
import math
import re

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings, strategies as st
from scipy.integrate import solve_ivp

from solvers import pendulum_rebound
from tests.derivations import declared_symbols, no_title_states_an_answer, number
from solvers.diagram import balance, balance_steps, fbd_steps, residuals
from tests.strategies import pos
from tests.drawing import DRAWN, EXAMPLES, circle, drawn, figures, static
from tests.pages.test_pages import run_page
from viz.pendulum_rebound import deg

# The solver contract, typed from PROBLEMS.md independently of the solver module (tests/physics/test_contract.py
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

# Cases of the shared tests in test_what_students_see.py beyond the defaults.
IN_VIEW = ({"e": 0.0},)  # no rebound: still in view
EDGE_LINKS = ({"e": "0"},)  # links whose numbers could read −0
LIMIT_LINKS = (({"theta0": "-40"}, 1),)  # released below the impact angle: the pendulum against its floor


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


@EXAMPLES
@given(VALID, st.floats(0.0, 1.0), st.sampled_from(["si", "us"]))
def test_beside_the_refusal_the_sphere_rests_on_the_surface_at_the_impact_angle(p, below, system):
    """viz.at_limit, beside the refusal of θ₀ ≤ θ_I: the sphere drawn touching the floor (its lowest point
    at −d), at sin θ_I = (r − d)/(L + r) from the geometry alone, the rod from the pivot to the sphere, θ₀
    dashed where it was asked for."""
    from viz.pendulum_rebound import at_limit
    assume(p["surface"] == "floor")  # (the wall is struck hanging straight down, below every release angle)
    theta_I = math.asin((p["r"] - p["d"]) / (p["L"] + p["r"]))
    p = {**p, "theta0": theta_I - 0.99 * below * (theta_I + math.pi / 2)}  # at or below θ_I, above −90°
    with pytest.raises(pendulum_rebound.PhysicalLimitError) as refused:
        pendulum_rebound.solve(**p)
    assert refused.value.theta_impact == pytest.approx(theta_I, abs=1e-9)
    (figure,) = at_limit(p, system)
    k = 1 / 0.3048 if system == "us" else 1.0
    xs, ys = static(figure, "sphere")
    cx, cy, radius = circle(xs, ys)
    assert radius == pytest.approx(p["r"] * k, abs=DRAWN)
    assert (cx, cy) == pytest.approx(((p["L"] + p["r"]) * k * math.cos(theta_I), (p["L"] + p["r"]) * k * math.sin(theta_I)), abs=2 * DRAWN)
    sag = radius * (1 - math.cos(math.pi / (len(xs) - 1)))  # a polygon's vertex may miss the lowest point by this
    assert -p["d"] * k - 2 * DRAWN <= ys.min() <= -p["d"] * k + sag + 2 * DRAWN
    rod_x, rod_y = static(figure, "rod")
    assert (rod_x[0], rod_y[0]) == (0, 0) and math.hypot(rod_x[-1], rod_y[-1]) == pytest.approx(p["L"] * k, abs=DRAWN)
    ray_x, ray_y = static(figure, "release angle θ₀ asked for")
    assert math.atan2(ray_y[-1], ray_x[-1]) == pytest.approx(p["theta0"], abs=1e-3)
    assert f"{pendulum_rebound.plain_number(math.degrees(theta_I))}°" in figure.description


def test_the_ode_of_the_solver_runs_several_bounces():
    s = pendulum_rebound.solve()
    t, q, w, impacts, legs = pendulum_rebound.simulate(s.params, s.answers, bounces=3)
    assert len(impacts) == 4
    # The first rise is integrated (the check on θ_f); later rises are drawn from the energy integral
    # (tests/physics/test_swing.py holds that drawing to an integration). Both reach the closed-form peaks.
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


# ----------------------------------------------------------------------------------------------
# What a student sees: the drawing agrees with the physics, the captions with the motion


@EXAMPLES
@given(VALID)
def test_the_sphere_never_enters_the_floor_or_the_wall(p):
    _, (figure,) = figures("pendulum_rebound", **p)
    surface_x, surface_y = static(figure, p["surface"])
    touched = False
    for xs, ys in drawn(figure, "sphere"):
        cx, cy, radius = circle(xs, ys)
        gap = cy - surface_y[0] if p["surface"] == "floor" else cx - surface_x[0]
        assert gap >= radius - DRAWN * (1 + p["L"])
        touched |= gap <= radius + DRAWN * (1 + p["L"])
    assert touched, "a frame shows the sphere touching at the impact"


def test_the_theta_curve_reaches_the_impact_line_at_each_bounce():
    """The cusps of θ(t) used to sit a degree or two above the dashed θ_I line (resampled frames)."""
    solution, (figure,) = figures("pendulum_rebound", e=0.6)
    curve = next(t for t in figure.spec["data"] if t["name"] == "θ(t)")
    impact = math.degrees(solution.answers["theta_impact"])
    assert min(curve["y"]) == pytest.approx(impact, abs=1e-3)


def test_the_pendulum_caption_at_e_0_lists_no_rebounds_and_points_below():
    _, (figure,) = figures("pendulum_rebound", e=0.0)
    assert "does not rebound" in figure.description and "rebounding to" not in figure.description
    assert "Below: θ against time" in figure.description and "Right:" not in figure.description


@EXAMPLES
@given(VALID)
def test_the_pendulum_caption_never_repeats_a_rebound_angle(p):
    """Nor lists, as a rebound, the impact angle as it is written (to 0.1°)."""
    assume(0 < p["e"] < 1)
    solution, (figure,) = figures("pendulum_rebound", **p)
    match = re.search(r"rebounding to ([^a-z]*?)(?: on successive| then|\.)", figure.description)
    if match:
        angles = [a.strip() for a in match.group(1).rstrip(", ").split(",")]
        assert len(angles) == len(set(angles)), figure.description
        assert deg(solution.answers["theta_impact"]) not in angles, figure.description


def test_the_caption_lists_no_rebound_that_shows_as_the_impact_angle():
    """At θ₀ = −35° (floor, e = 0.6) the second peak is 0.08° above θ_I = −35.65°: written to 0.1°, both −35.6°."""
    _, (figure,) = figures("pendulum_rebound", theta0=math.radians(-35))
    assert "rebounding to −35.4°, then barely lifting off" in figure.description, figure.description


def test_whole_degree_sliders_show_whole_degrees():
    at = run_page("pendulum_rebound")
    theta0 = next(s for s in at.slider if s.key.endswith("__theta0"))
    assert theta0.proto.format == "%.0f"
    e = next(s for s in at.slider if s.key.endswith("__e"))
    assert e.proto.format == "%.2f"


def test_a_link_value_finer_than_the_control_is_rounded_to_what_it_shows():
    at = run_page("pendulum_rebound", {"theta0": "30.4"})
    assert next(s for s in at.slider if s.key.endswith("__theta0")).value == 30.0


def test_the_pendulum_s_energy_loss_check_rests_on_the_integrated_motion(monkeypatch):
    """It used to show ½ I (θ̇⁻² − θ̇⁺²) against (1 − e²) ½ I θ̇⁻² with θ̇⁺ = −e θ̇⁻: the same
    number rearranged. Its second side must now move when the integration does."""
    solver = importlib.import_module("solvers.pendulum_rebound")
    solution = solver.solve()
    p, answers = dict(solution.params), dict(solution.answers)
    honest = solver.simulate

    def integration_off(*args, **kwargs):  # θ̇ just before impact 0.1 % off
        t, q, w, impacts, legs = honest(*args, **kwargs)
        return t, q, w, [(impacts[0][0], impacts[0][1] * 1.001), *impacts[1:]], legs

    monkeypatch.setattr(solver, "simulate", integration_off)
    energy = next(c for c in solver._checks(p, answers) if c.name.startswith("energy lost"))
    assert not energy.ok
    assert energy.closed_form == pytest.approx(answers["energy_loss"])


def test_in_feet_the_figure_is_the_metric_one_scaled():
    """?units=us draws the pendulum in feet: every moving trace of the motion in every frame, and the
    axes' ranges, are the metric figure's times 1 ft/0.3048 m (the velocity arrow was scaled by it twice,
    3.3 times too long, and the view fitted to it was twice too wide)."""
    import json

    from solvers import pendulum_rebound as solver
    from viz import pendulum_rebound as viz
    from viz.common import expanded

    solution = solver.solve()
    si, us = (expanded(json.loads(viz.figures(solution, system)[0].json())) for system in ("si", "us"))
    ft = 1 / 0.3048
    for axis in ("xaxis", "yaxis"):
        assert np.allclose(us["layout"][axis]["range"], np.asarray(si["layout"][axis]["range"]) * ft, rtol=1e-3)
    compared = 0
    for frame_si, frame_us in zip(si["frames"], us["frames"], strict=True):
        for t, a, b in zip(frame_si["traces"], frame_si["data"], frame_us["data"], strict=True):
            if si["data"][t].get("xaxis", "x") != "x":
                continue  # θ(t) below: degrees and seconds in both
            for k in ("x", "y"):
                x, y = (np.array([np.nan if v is None else v for v in d[k]], dtype=float) for d in (a, b))
                assert np.allclose(y, x * ft, rtol=1e-3, atol=2e-4, equal_nan=True), (si["data"][t]["name"], k)
                compared += 1
    assert compared > 100


# ----------------------------------------------------------------------------------------------
# The free-body diagrams (Step 2), the balance laws written from them (Step 3), and the stage's frames


def _vector(load, values) -> tuple[float, float]:
    return tuple(number(c, values) for c in load.vector)


def _balance_holds(d, solution, rel=1e-9) -> None:
    """Each body's three balance laws at the numbers the diagram is drawn for, each to ``rel`` of the
    largest term in the body's laws (a law whose terms cancel: the x law at θ = −90°)."""
    values = d.values(solution)
    rows = residuals(d, solution)
    for n, body in enumerate(d.bodies):
        laws = balance(d, body.name)
        terms = [t for eq in laws for side in (eq.lhs, eq.rhs) for t in sp.Add.make_args(sp.expand(side))]
        scale = max(abs(number(t, values)) for t in terms)
        for law, left, right in rows[3 * n: 3 * n + 3]:
            assert abs(left - right) <= rel * scale, (d.phase, law, left, right, scale)


def _agreeing_frames(per_frame, values) -> list[int]:
    """The frames at which every symbol of ``per_frame`` has its number in ``values`` (to rounding)."""
    scale = max(abs(float(v)) for v in values.values())
    same = np.ones(len(next(iter(per_frame.values()))), dtype=bool)
    for s, v in values.items():
        same &= np.isclose(per_frame[s], float(v), rtol=1e-9, atol=1e-12 * scale)
    return [int(i) for i in np.nonzero(same)[0]]


OPTIONS = [(sphere, surface) for sphere in SPHERE_K for surface in ("floor", "wall")]


@pytest.mark.parametrize("sphere, surface", OPTIONS)
@settings(max_examples=8, deadline=None)
@given(VALID)
def test_each_diagram_s_balance_laws_hold_at_the_solvers_numbers(sphere, surface, p):
    """ΣF = m a_G, ΣM_O = I_O θ̈ (the swing) and their impulse forms (the impact), summed from the declared
    loads, hold at the numbers the solver's own physics gives for the instant drawn: θ̈ from its equation
    of motion, θ̇⁻ and θ̇⁺ its answers."""
    p = {**p, "sphere": sphere, "surface": surface}
    if surface == "floor" and not p["theta0"] > math.asin((p["r"] - p["d"]) / (p["L"] + p["r"])) + 0.01:
        p["theta0"] = math.radians(60)  # (drawn for the wall, below the floor's impact angle)
    solution = pendulum_rebound.solve(**p)
    diagrams = pendulum_rebound.free_body_diagrams(solution.params)
    assert [(d.phase, d.law) for d in diagrams] == [("swing", "force"), ("impact", "impulse")]
    for d in diagrams:
        values = d.values(solution)
        assert declared_symbols(d) <= set(values), (d.phase, declared_symbols(d) - set(values))
        _balance_holds(d, solution)
    swing = diagrams[0].values(solution)
    assert swing[pendulum_rebound.I_O] == solution.answers["I_O"]  # the inertia the derivation uses
    impact = diagrams[1].values(solution)
    assert (impact[pendulum_rebound.w_minus], impact[pendulum_rebound.w_plus]) == (
        solution.answers["omega_impact"], solution.answers["omega_after"])


def test_a_load_turned_round_breaks_the_balance():
    """Positive control: the surface's impulse into the surface, or a weight pointing up, and the laws fail."""
    from dataclasses import replace

    for surface in ("floor", "wall"):
        solution = pendulum_rebound.solve(surface=surface)
        for d in pendulum_rebound.free_body_diagrams(solution.params):
            for load in d.loads:
                if load.direction is None:
                    continue
                flipped = replace(load, direction=tuple(-c for c in load.direction))
                wrong = replace(d, loads=tuple(flipped if l is load else l for l in d.loads))
                assert any(not math.isclose(a, b, rel_tol=1e-6) for _, a, b in residuals(wrong, solution)), load.symbol


@settings(max_examples=40, deadline=None)
@given(VALID)
def test_the_loads_point_as_the_physics_says(p):
    """Gravity down (−y on the stage) at the rod's and the sphere's centres; at the impact no weight, and
    the smooth surface's impulse acts at the sphere's point on the surface, along the surface's normal
    out of it, into the sphere, through the sphere's centre. The surface from the problem's geometry
    (PROBLEMS.md): the floor is y = −d, the wall (touching the hanging sphere, on the side it swings
    toward) x = −r."""
    solution = pendulum_rebound.solve(**p)
    swing, impact = pendulum_rebound.free_body_diagrams(solution.params)
    v = swing.values(solution)
    weights = [l for l in swing.loads if l.by == "gravity"]
    assert sorted(l.at for l in weights) == ["G_r", "S"]
    for load in weights:
        x, y = _vector(load, v)
        assert x == 0 and y < 0, load.symbol
    assert -sum(_vector(l, v)[1] for l in weights) == pytest.approx((p["m_r"] + p["m_s"]) * p["g"], rel=1e-12)
    pendulum = swing.body("the pendulum")
    for name, rho in (("G_r", p["L"] / 2), ("S", p["L"] + p["r"])):  # on the rod, at θ from the horizontal
        x, y = (number(c, v) for c in pendulum.points[name])
        angle = float(v[pendulum_rebound.theta])
        assert (x, y) == pytest.approx((rho * math.cos(angle), rho * math.sin(angle)), rel=1e-12, abs=1e-12)

    w = impact.values(solution)
    assert not [l for l in impact.loads if l.by == "gravity"] and "negligible" in impact.note
    (push,) = [l for l in impact.loads if l.by == f"the {p['surface']}"]
    assert push.kind == "impulse" and push.at == "C"
    points = impact.body(push.on).points
    cx, cy = (number(c, w) for c in points["C"])
    sx, sy = (number(c, w) for c in points["S"])
    reach = p["L"] + 2 * p["r"]
    if p["surface"] == "floor":
        outward, gap = (0.0, 1.0), cy + p["d"]
    else:
        outward, gap = (1.0, 0.0), cx + p["r"]
    assert abs(gap) <= 1e-9 * reach  # the contact point lies on the surface
    assert math.hypot(cx - sx, cy - sy) == pytest.approx(p["r"], rel=1e-9)  # and on the sphere
    x, y = _vector(push, w)
    assert x * outward[0] + y * outward[1] >= 0  # pushes out of the surface, never pulls
    assert abs(x * outward[1] - y * outward[0]) <= 1e-12 * math.hypot(x, y)  # along the normal: smooth
    assert abs((sx - cx) * y - (sy - cy) * x) <= 1e-9 * p["r"] * math.hypot(x, y)  # through the centre
    assert x * outward[0] + y * outward[1] > 0  # (θ̇⁻ ≠ 0 at the impact: it does push, for any e)


@EXAMPLES
@given(VALID)
def test_the_stage_s_frames_carry_each_diagram_at_each_frame(p):
    """``frames`` gives every symbol an array of the motion's length: the swing at every frame, the impact
    at each impact's frame only (NaN elsewhere, θ̇⁺ = −e θ̇⁻ there); at the frame each diagram is drawn
    for, the same numbers as ``values``. And they are the stage's coordinates: the figure draws the
    sphere where the diagram puts S, and at the impact touching the surface at C."""
    solution, (figure,) = figures("pendulum_rebound", **p)
    m = pendulum_rebound.motion(solution)
    n = len(m["t"])
    assert len(figure.spec["animation"]["times"]) == n  # the overlay's frames are the figure's
    swing, impact = pendulum_rebound.free_body_diagrams(solution.params)
    hits = [int(np.argmin(np.abs(m["t"] - t))) for t in m["impact_times"]]
    first = hits[0]
    for d in (swing, impact):
        per_frame = d.frames(solution, m)
        assert set(per_frame) >= declared_symbols(d)
        assert all(np.shape(v) == (n,) for v in per_frame.values()), d.phase
        agree = _agreeing_frames(per_frame, d.values(solution))
        assert agree, d.phase  # the instant drawn is a frame of the stage
        if d is swing:
            assert all(np.isfinite(v).all() for v in per_frame.values())
            assert agree[0] <= first  # on the first fall
            i = agree[0]
        else:
            finite = np.isfinite(per_frame[pendulum_rebound.P_surface])
            assert list(np.nonzero(finite)[0]) == sorted(set(hits))
            assert first in agree and set(agree) <= set(hits)  # (e = 1: every impact's the same)
            before, after = per_frame[pendulum_rebound.w_minus], per_frame[pendulum_rebound.w_plus]
            assert np.allclose(after[hits[1:]], -p["e"] * before[hits[1:]], rtol=1e-12, atol=0)
            assert np.allclose(per_frame[pendulum_rebound.theta][hits], solution.answers["theta_impact"], rtol=0, atol=1e-6)
            i = first
        at = {s: per_frame[s][i] for s in per_frame}
        xs, ys = drawn(figure, "sphere")[i]
        centre = circle(xs, ys)[:2]
        sx, sy = (number(c, at) for c in d.body("the pendulum").points["S"])
        assert centre == pytest.approx((sx, sy), abs=2 * DRAWN), d.phase
    surface_x, surface_y = static(figure, p["surface"])
    cx, cy = (number(c, {s: v[first] for s, v in impact.frames(solution, m).items()})
              for c in impact.body("the pendulum").points["C"])
    if p["surface"] == "floor":
        assert cy == pytest.approx(surface_y[0], abs=2 * DRAWN)
    else:
        assert cx == pytest.approx(surface_x[0], abs=2 * DRAWN)


def test_the_derivation_is_in_the_four_steps_with_the_diagrams_in_steps_two_and_three():
    """Origin, coordinates and basis first (part 1), then each diagram's Step 2, then its balance laws,
    then the analysis; the work–energy step is the moment law integrated, the surface's impulse the
    angular impulse law solved; no title states a result."""
    for sphere, surface in OPTIONS:
        solution = pendulum_rebound.solve(sphere=sphere, surface=surface, theta0=0.3)
        steps = solution.steps
        parts = [s.part for s in steps]
        assert parts == sorted(parts) and set(parts) == {1, 2, 3, 4}
        assert steps[0].title.startswith("Origin at the pivot O") and "basis" in steps[0].title
        swing, impact = pendulum_rebound.free_body_diagrams(solution.params)
        assert [s for s in steps if s.part == 2] == [*fbd_steps(swing), *fbd_steps(impact)]
        assert [s for s in steps if s.part == 3] == [*balance_steps(swing), *balance_steps(impact)]
        assert any("moment law" in s.title and "integrated" in s.title for s in steps if s.part == 4)
        assert any("angular impulse law about O" in s.title for s in steps if s.part == 4)
        no_title_states_an_answer(solution)



@EXAMPLES
@given(VALID)
def test_the_frames_are_close_enough_to_follow_the_swing(p):
    """The rod turns at most Integrated.turn (8°) from one frame to the next, however long and fast the
    swing (a release near upright against a wall, e = 1, once jumped 67° a frame over its 11 s), unless
    the frames are at their most; and its fastest |θ̇| is ``fastest``'s, the closed form that counts them."""
    solution = pendulum_rebound.solve(**p)
    m = pendulum_rebound.motion(solution)
    spec = pendulum_rebound.INTEGRATED
    assert np.abs(m["omega"]).max() <= pendulum_rebound.fastest(solution.params, solution.answers) * (1 + 1e-7) + 1e-12
    if len(m["t"]) - len(m["impact_times"]) < spec.most - 1:
        assert np.abs(np.diff(m["theta"])).max() <= spec.turn * (1 + 1e-6)
