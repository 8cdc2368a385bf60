"""eulers_disk against an independent kinematic model: the disk's orientation as Euler angles
(scipy Rotation), angular velocity and angular momentum by finite differences in the fixed frame."""
import importlib
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings, strategies as st
from scipy.spatial.transform import Rotation

from solvers import eulers_disk
from solvers.core import latex
from solvers.diagram import balance, residuals, resultant
from tests.strategies import pos
from tests.drawing import DRAWN, EXAMPLES, figures
from tests.pages.test_pages import assert_clean, run_page

# The solver contract, typed from PROBLEMS.md independently of the solver module (tests/physics/test_contract.py
# checks every registered problem against its CONTRACT): parameter defaults (SI, radians), answer names,
# and values the solver must refuse in plain words.
CONTRACT = {
    "defaults": dict(m=0.4, r=0.0375, theta=math.radians(10), g=9.81),
    "answers": {"contact_speed", "energy", "omega_p", "omega_s", "omega_total", "period"},
    "out_of_range": (("theta", 0.0), ("theta", math.pi / 2), ("r", -0.1)),
    "too_large": (dict(m=1e300, r=1e300, theta=1e300, g=1e300),),
}


# random valid parameters (SI, radians) for property tests
VALID = st.fixed_dictionaries({
    "m": pos(0.01, 10), "r": pos(0.005, 1), "theta": pos(math.radians(0.5), math.radians(89.5)),
    "g": pos(1, 25),
})


def orientation(t, theta, precession, spin):
    """Body frame: z along the disk's normal. R = Rz(φ) Rx(θ) Rz(ψ), φ = precession·t, ψ = spin·t."""
    return (Rotation.from_euler("z", precession * t) * Rotation.from_euler("x", theta)
            * Rotation.from_euler("z", spin * t)).as_matrix()


def angular_velocity(t, *args, h=1e-6):
    Rdot = (orientation(t + h, *args) - orientation(t - h, *args)) / (2 * h)
    W = Rdot @ orientation(t, *args).T
    return np.array([W[2, 1], W[0, 2], W[1, 0]])


def lowest_rim_point(t, r, *args):
    """Where the tilted rim touches the table: the body-frame rim point with the lowest height."""
    R = orientation(t, *args)
    a = np.linspace(0, 2 * np.pi, 1, endpoint=False)
    # lowest point of a circle in the body x-y plane: along −(projection of E_z onto the plane)
    ez_body = R.T @ np.array([0, 0, 1.0])
    d = -ez_body[:2] / np.linalg.norm(ez_body[:2])
    del a
    return R @ np.array([r * d[0], r * d[1], 0.0])


def test_seed_formula_and_teaching_identities():
    a = eulers_disk.solve().answers
    g, r, th, m = 9.81, 0.0375, math.radians(10), 0.4
    assert a["omega_p"] == pytest.approx(math.sqrt(4 * g / (r * math.sin(th))), rel=1e-12)
    assert a["omega_s"] == pytest.approx(a["omega_p"] * math.cos(th), rel=1e-12)
    assert a["omega_total"] == pytest.approx(a["omega_p"] * math.sin(th), rel=1e-12)
    assert a["energy"] == pytest.approx(1.5 * m * g * r * math.sin(th), rel=1e-12)
    assert a["period"] == pytest.approx(2 * math.pi / a["omega_p"], rel=1e-12)
    assert a["contact_speed"] == pytest.approx(a["omega_p"] * r * math.cos(th), rel=1e-12)


@settings(max_examples=40, deadline=None)
@given(VALID)
def test_rolling_and_balance_of_angular_momentum_in_a_fixed_frame(p):
    a = eulers_disk.solve(**p).answers
    m, r, th, g = p["m"], p["r"], p["theta"], p["g"]
    # the contact point precesses at −ω_p (seed's sense); the spin relative to that frame is ω_s
    args = (th, -a["omega_p"], a["omega_s"])
    t = 0.3 / a["omega_p"]
    w = angular_velocity(t, *args)
    assert np.linalg.norm(w) == pytest.approx(a["omega_total"], rel=1e-6)
    r_AG = lowest_rim_point(t, r, *args)
    assert r_AG[2] == pytest.approx(-r * math.sin(th), rel=1e-9)  # G at height r sin θ
    # the material point at the contact is at rest (rolling without slip, G fixed)
    assert np.linalg.norm(np.cross(w, r_AG)) <= 1e-5 * a["omega_total"] * r
    I_body = np.diag([m * r**2 / 4, m * r**2 / 4, m * r**2 / 2])

    def H(time):
        R = orientation(time, *args)
        return R @ I_body @ R.T @ angular_velocity(time, *args)

    h = 1e-4 / a["omega_p"]
    dHdt = (H(t + h) - H(t - h)) / (2 * h)
    torque = np.cross(r_AG, np.array([0, 0, m * g]))
    assert np.linalg.norm(dHdt - torque) <= 1e-4 * m * g * r
    # energy: the translational part is zero, G is at rest
    T = 0.5 * w @ (orientation(t, *args) @ I_body @ orientation(t, *args).T) @ w
    assert a["energy"] == pytest.approx(m * g * r * math.sin(th) + T, rel=1e-6)


@settings(max_examples=25, deadline=None)
@given(VALID, pos(math.radians(0.5), math.radians(89.5)))
def test_the_curves_against_tilt_are_the_solver_s_answers_whatever_tilt_the_disk_has(p, other_tilt):
    """The companion figure's curves are kept by every parameter but θ (issue 28: moving θ redraws
    only the point): for two disks that differ in θ alone they are the same, read-only, and each
    point on them is what solving that disk at that tilt gives."""
    tilts = np.radians(np.linspace(1, 80, 9))
    curves = eulers_disk.versus_tilt(p, tilts)
    again = eulers_disk.versus_tilt({**p, "theta": other_tilt}, tilts)
    for name, values in curves.items():
        assert again[name] is values and not values.flags.writeable
        for tilt, value in zip(tilts, values):
            assert value == pytest.approx(eulers_disk.solve(**{**p, "theta": float(tilt)}).answers[name], rel=1e-9)


def test_finite_time_singularity_trend():
    small, large = eulers_disk.solve(theta=math.radians(1)), eulers_disk.solve(theta=math.radians(30))
    assert small.answers["omega_p"] > large.answers["omega_p"]
    assert small.answers["omega_total"] < large.answers["omega_total"]
    assert small.answers["energy"] < large.answers["energy"]


def test_kanes_equations_keep_the_steady_state_and_its_rate():
    from solvers import eulers_disk_dynamics as dynamics

    for tilt in (5, 10, 30, 60):
        s = eulers_disk.solve(theta=math.radians(tilt))
        steady = dynamics.integrate_steady(dict(s.params), s.answers["omega_p"], periods=2)
        assert steady["tilt_drift"] < 1e-9
        assert all(abs(abs(w) - s.answers["omega_p"]) < 1e-7 * s.answers["omega_p"] for w in steady["precession"])
        assert abs(steady["yaw_turned"]) == pytest.approx(2 * 2 * math.pi, rel=1e-8)  # two precessions


def test_dissipation_drains_energy_and_the_contact_whirls_faster():
    from solvers import eulers_disk_dynamics as dynamics

    params = dict(eulers_disk.solve(theta=math.radians(8)).params)
    run = dynamics.decay(params, damping=4e-5, t_max=4.0)
    energy = run["energy"]
    assert all(b <= a * (1 + 1e-7) for a, b in zip(energy, energy[1:])), "energy never increases"
    assert energy[-1] < 0.95 * energy[0]
    assert run["tilt"][-1] < run["tilt"][0]
    assert run["precession"][-1] > run["precession"][0]
    undamped = dynamics.decay(params, damping=0.0, t_max=1.0)
    assert undamped["energy"][-1] == pytest.approx(undamped["energy"][0], rel=1e-6)  # conserved without it


@settings(max_examples=6, deadline=None)
@given(tilt=st.floats(3, 60), damping=st.floats(2e-4, 2e-3))
def test_the_run_down_stops_the_first_time_the_tilt_reaches_one_degree(tilt, damping):
    """The tilt nods as it falls (it crosses 1° several times within one nod): the run-down ends at
    the first crossing, as one finely sampled integration at tighter tolerances finds it."""
    from scipy.integrate import odeint

    from solvers import eulers_disk_dynamics as dynamics

    s = eulers_disk.solve(theta=math.radians(tilt))
    params = dict(s.params)
    run = dynamics.decay(params, damping=damping, t_max=30.0)
    assert run["reached"]
    t = np.arange(0.0, run["time_to_stop"] + 0.05, 2e-4)
    y = odeint(dynamics._rate(params, damping), dynamics.steady_state(params, s.answers["omega_p"]), t,
               rtol=1e-11, atol=1e-13, mxstep=10**6)
    first = t[np.argmax(math.pi / 2 - y[:, 1] <= math.radians(1))]
    assert first - 2e-4 <= run["time_to_stop"] <= first + 1e-9
    assert math.degrees(run["tilt"][-1]) == pytest.approx(1.0, abs=1e-6)


@settings(max_examples=8, deadline=2000)
@given(tilt=st.floats(0.05, 1.0), radius=st.floats(0.005, 0.5))
def test_a_run_down_that_starts_at_or_below_one_degree_is_its_start_alone(tilt, radius):
    """Below 1° the event that ends a run-down never fires: the slider's lowest tilt (0.5°) with its
    smallest radius integrated 120 s of a 950 rad/s whirl for minutes, and every run-down asked for
    after it waited. The start is all there is, at once: the steady state's ω_p = √(4g / (r sin θ))."""
    from viz import eulers_disk as viz

    s = eulers_disk.solve(theta=math.radians(tilt), r=radius)
    figure = viz.on_request(s)
    tilt_trace, rate_trace = figure.spec["data"]
    assert list(tilt_trace["x"]) == [0.0] and tilt_trace["y"][0] == pytest.approx(tilt, abs=1e-4)  # (rounded for JSON)
    assert rate_trace["y"][0] == pytest.approx(math.sqrt(4 * 9.81 / (radius * math.sin(math.radians(tilt)))), rel=1e-4)
    assert tilt_trace["mode"] == rate_trace["mode"] == "markers"  # one point: a line would draw nothing
    assert "nothing is left to run down" in figure.description


@pytest.mark.parametrize("tilt, radius, direction", [(10.0, 0.005, "grown"), (60.0, 0.1, "fallen")])
def test_the_run_down_caption_says_what_its_plot_shows(tilt, radius, direction):
    """The caption's ω_p 'from … to …' are the plotted ends, and whether it grew or fell is read from
    them: at a steep tilt the precession slows as the disk settles (it said 'grown from 21.3 to 16')."""
    from solvers.core import plain_number
    from viz import eulers_disk as viz

    figure = viz.on_request(eulers_disk.solve(theta=math.radians(tilt), r=radius))
    tilt_trace, rate_trace = figure.spec["data"]
    first, last = rate_trace["y"][0], rate_trace["y"][-1]
    assert (last > first) == (direction == "grown")
    said = f"ωₚ {direction} from {plain_number(first, 3)} to {plain_number(last, 3)} rad/s"
    assert said in figure.description, figure.description
    if "reaches 1°" in figure.description:
        assert tilt_trace["y"][-1] == pytest.approx(1.0, abs=1e-3)
        assert f"after {plain_number(tilt_trace['x'][-1], 3)} s" in figure.description


def test_a_run_down_computed_for_one_student_leaves_the_others_at_their_pace():
    """The integration runs in the worker process (viz.on_request): a script thread beside it keeps
    its pace (in a thread of the server's own process, a 2 ms run took 370 ms beside it)."""
    import random
    import threading
    import time

    from solvers import eulers_disk_dynamics as dynamics
    from viz import on_request

    params = dict(eulers_disk.solve(theta=math.radians(random.uniform(8, 12))).params)  # not kept anywhere
    on_request.in_worker(dynamics.decay, params, 2e-3, 0.5)  # the worker started and warm

    def pace() -> float:
        started = time.perf_counter()
        sum(math.sin(i) * math.cos(i) for i in range(200_000))  # another session's run, in Python
        return time.perf_counter() - started

    alone = min(pace() for _ in range(3))
    running = threading.Thread(target=on_request.in_worker, args=(dynamics.decay, params, 5e-6, 60.0))
    running.start()
    time.sleep(0.2)
    beside = [pace() for _ in range(3)]
    measured_while_it_ran = running.is_alive()
    running.join()
    assert measured_while_it_ran
    assert max(beside) < 5 * alone, (alone, beside)


def test_the_worker_counts_the_requests_a_new_one_waits_behind():
    """The run-down's spinner says how many figures other students asked for first (three asked at
    once waited 4, 14 and 16 s behind the same words): viz.on_request counts them while they last."""
    import threading
    import time

    from viz import on_request

    on_request.in_worker(time.sleep, 0.0)  # the worker started
    before = on_request.waiting()
    asked = [threading.Thread(target=on_request.in_worker, args=(time.sleep, 0.6)) for _ in range(2)]
    for thread in asked:
        thread.start()
    time.sleep(0.3)
    assert on_request.waiting() == before + 2  # one in the worker, one queued behind it
    for thread in asked:
        thread.join()
    assert on_request.waiting() == before


def test_the_animation_reports_its_slow_motion():
    from viz import eulers_disk as viz
    solution = eulers_disk.solve()
    fig = viz.figures(solution)[0]
    period = solution.answers["period"]
    assert fig.extra["slow_motion"] == pytest.approx(4.0 / period)
    assert f"{4.0 / period:.0f}×" in fig.title


# ----------------------------------------------------------------------------------------------
# What a student sees: the drawing agrees with the physics, the captions with the motion


@EXAMPLES
@given(VALID)
def test_euler_s_disk_stays_on_the_table(p):
    _, figs = figures("eulers_disk", **p)
    rim = figs[0].spec["animation"]["coords"][0]["z"]
    assert min(min(row) for row in rim) >= -DRAWN * (1 + p["r"])


@EXAMPLES
@given(VALID)
def test_the_whole_disk_stands_inside_the_scene_s_box_drawn_to_one_scale(p):
    """WebGL clips a 3-D scene to its axes' ranges: every frame's rim, radius and contact point lie
    inside them (a tilt of 68° put the rim's top, 2r sin θ above the table, above a box r high), and
    the box's aspect ratio is its ranges' (one scale on x, y and z)."""
    import json
    from viz.common import unpacked
    _, figs = figures("eulers_disk", **p)
    spec = json.loads(figs[0].json())
    scene, anim = spec["layout"]["scene"], spec["animation"]
    ranges = {k: scene[f"{k}axis"]["range"] for k in "xyz"}
    for coords in anim["coords"]:
        frames = unpacked(coords, len(anim["times"]))
        for k in "xyz":
            values = np.asarray(frames[k], dtype=float)
            assert np.nanmin(values) >= ranges[k][0] - 1e-9 * abs(ranges[k][0]) - DRAWN
            assert np.nanmax(values) <= ranges[k][1] * (1 + 1e-3) + DRAWN  # (the range rounded as drawn)
    extent = {k: ranges[k][1] - ranges[k][0] for k in "xyz"}
    for k in "yz":
        assert scene["aspectratio"][k] / scene["aspectratio"]["x"] == pytest.approx(extent[k] / extent["x"], rel=2e-3)


@EXAMPLES
@given(VALID)
def test_the_scene_s_axis_titles_stand_inside_its_ranges(p):
    """plotly.js removes a 3-D annotation whose point lies outside its axes' ranges, and the ranges it draws
    carry a round-off (210 mm drawn as 209.99999999999997): each axis title, anchored at the box's edge,
    stands inside every range by far more than a round-off (at r = 0.2 and 0.375 m two of the three were
    gone), on the edge it names."""
    _, figs = figures("eulers_disk", **p)
    scene = figs[0].spec["layout"]["scene"]
    titles = {a["text"]: a for a in scene["annotations"]}
    assert set(titles) == {"x (mm)", "y (mm)", "z (mm)"}
    for title in titles.values():
        for k in "xyz":
            low, high = scene[f"{k}axis"]["range"]
            assert low + 1e-6 * (high - low) < title[k] < high - 1e-6 * (high - low), (title, k, low, high)
    low, high = scene["yaxis"]["range"]
    assert titles["x (mm)"]["y"] == pytest.approx(low, rel=1e-3) and titles["y (mm)"]["x"] == pytest.approx(high, rel=1e-3)


@pytest.mark.parametrize("tilt", [5.0, 10.0, 40.0, 68.0, 89.5])
def test_the_caption_says_how_far_the_disk_turns_and_barely_only_where_it_does(tilt):
    """Rolling without slip, the rim rolls 2πr cos θ (the contact's circle) a precession, so the disk
    turns 2πr(1 − cos θ)/r relative to the table: 360°(1 − cos θ). "Barely turns" only below a quarter turn."""
    from viz import eulers_disk as viz
    caption = viz.figures(eulers_disk.solve(theta=math.radians(tilt)))[0].description
    turn = 360 * (1 - math.cos(math.radians(tilt)))
    assert f"turns {'only ' if turn < 90 else ''}{turn:.1f}°" in caption
    assert ("barely turns" in caption) == (turn < 90)


def test_a_turn_below_a_degree_is_said_in_two_figures():
    """At the control's lowest tilt, 0.5°, the disk turns 360°(1 − cos 0.5°) = 0.0137° a precession: said as
    0.014°, not "0.0°" (a student read that as not turning at all)."""
    from viz import eulers_disk as viz
    caption = viz.figures(eulers_disk.solve(theta=math.radians(0.5)))[0].description
    assert "turns only 0.014° relative to the table" in caption


def test_the_run_down_switch_is_kept_in_the_url():
    at = run_page("eulers_disk")
    at.toggle(key="eulers_disk__on_request").set_value(True).run()
    assert_clean(at)
    assert at.query_params.get("rundown") == "1"
    again = run_page("eulers_disk", dict(at.query_params))
    assert again.toggle(key="eulers_disk__on_request").value is True


def test_a_run_down_whose_worker_died_twice_is_said_not_a_traceback(monkeypatch):
    """in_worker replaces a killed worker once; killed again (out of memory twice), the page says so."""
    from concurrent.futures.process import BrokenProcessPool

    from viz import on_request

    def died(*_):
        raise BrokenProcessPool("killed")
    monkeypatch.setattr(on_request, "figure", died)
    at = run_page("eulers_disk", {"rundown": "1"})
    assert not at.exception
    assert any("could not be computed" in e.value and "off and on again" in e.value for e in at.error), at.error
    assert at.toggle(key="eulers_disk__on_request").value is True  # kept: switching it off and on retries


def test_log_and_run_down_axes_label_their_ticks_in_full():
    solution, figs = figures("eulers_disk")
    log_axis = figs[1].spec["layout"]["yaxis"]
    assert log_axis["type"] == "log"
    assert [float(t) for t in log_axis["ticktext"]] == log_axis["tickvals"]
    assert all(str(v)[0] in "125" for v in log_axis["tickvals"])
    decay = importlib.import_module("viz.eulers_disk").on_request(solution)
    assert not any("overlaying" in v for v in decay.spec["layout"].values() if isinstance(v, dict))


# ----------------------------------------------------------------------------------------------
# The free-body diagram: the disk edge-on in the vertical plane through its axis and A


def _steady(solution):
    (d,) = eulers_disk.free_body_diagrams(solution.params)
    assert d.phase == "steady" and d.law == "force" and d.frames is None  # a 3-D stage: no overlay
    return d


def _number(expr, values) -> float:
    return float(sp.sympify(expr).subs(values))


@settings(max_examples=25, deadline=None)
@given(VALID)
def test_the_edge_on_balance_laws_hold_at_the_solver_s_numbers(p):
    """ΣF = m a_G (zero: G at rest) and ΣM_G = dH_G/dt·e_x, summed from the declared loads, hold at the
    solver's ω_p and the table's force its answers give (from the motion of G, never the diagram's laws)."""
    s = eulers_disk.solve(**p)
    d = _steady(s)
    weight = p["m"] * p["g"]
    for law, left, right in residuals(d, s):
        scale = weight * (p["r"] if law.endswith("moment") else 1.0)
        assert abs(left - right) <= 1e-9 * scale, (law, left, right, scale)


@settings(max_examples=25, deadline=None)
@given(VALID)
def test_the_table_carries_the_weight_without_friction_and_its_moment_turns_h_g(p):
    """Gravity down at G; the table's force at A up, N = m g ≥ 0, friction zero (G at rest); A below G by
    r sin θ on the table, r cos θ toward A; and the moment law along e_x is the fixed frame's: the moment of
    the drawn forces about G and the diagram's kinetic side both equal dH_G/dt·e_x found by finite
    differences of an independent Euler-angle model (scipy), e_x = e_y × E_z with e_y horizontal toward A."""
    s = eulers_disk.solve(**p)
    a = s.answers
    d = _steady(s)
    values = d.values(s)
    m, r, th, g = p["m"], p["r"], p["theta"], p["g"]
    weight, table = (next(l for l in d.loads if l.by == by) for by in ("gravity", "the table"))
    assert weight.at == "G" and tuple(_number(c, values) for c in weight.vector) == (0.0, pytest.approx(-m * g, rel=1e-12))
    assert table.at == "A" and table.direction is None  # its direction is the physics' to find: two components
    friction, normal = (_number(c, values) for c in table.components)
    assert normal >= 0 and normal == pytest.approx(m * g, rel=1e-12)  # up (E_z), carrying the weight
    assert abs(friction) <= 1e-12 * m * g
    disk = d.body("the disk")
    G, A = ((_number(x, values), _number(y, values)) for x, y in (disk.points["G"], disk.points["A"]))
    assert A[0] - G[0] == pytest.approx(r * math.cos(th), rel=1e-12)
    assert A[1] - G[1] == pytest.approx(-r * math.sin(th), rel=1e-12)
    # the fixed frame's moment law, along e_x
    args = (th, -a["omega_p"], a["omega_s"])
    t = 0.3 / a["omega_p"]
    r_AG = lowest_rim_point(t, r, *args)
    e_y = np.array([r_AG[0], r_AG[1], 0.0]) / math.hypot(r_AG[0], r_AG[1])
    e_x = np.cross(e_y, [0.0, 0.0, 1.0])
    assert r_AG @ e_y == pytest.approx(A[0] - G[0], rel=1e-9) and r_AG[2] == pytest.approx(A[1] - G[1], rel=1e-9)
    I_body = np.diag([m * r**2 / 4, m * r**2 / 4, m * r**2 / 2])

    def H(time):
        R = orientation(time, *args)
        return R @ I_body @ R.T @ angular_velocity(time, *args)

    h = 1e-4 / a["omega_p"]
    turning = (H(t + h) - H(t - h)) / (2 * h) @ e_x
    assert turning > 0  # m g r cos θ: the table's push tips H_G forward as it precesses
    moment = _number(resultant(d, "the disk")[2], values)
    assert moment == pytest.approx(m * g * r * math.cos(th), rel=1e-12)
    assert moment == pytest.approx(turning, rel=1e-4)
    assert _number(disk.kinetic[2], values) == pytest.approx(turning, rel=1e-4)
    assert disk.kinetic[:2] == (0, 0)  # a_G = 0


def test_the_derivation_is_in_the_four_steps_and_gets_omega_p_from_the_diagram_s_moment_law():
    """Kinematics first (ω, rolling, H_G and its rate), then the diagram, its laws, the analysis; the ω_p
    step's equation is the diagram's moment law with F = 0 and N = m g put in."""
    s = eulers_disk.solve()
    parts = [step.part for step in s.steps]
    assert parts == sorted(parts) and set(parts) == {1, 2, 3, 4}
    assert "Origin" in s.steps[0].title
    assert any(r"\dot{\mathbf{H}}_G" in step.latex for step in s.steps if step.part == 1)
    d = _steady(s)
    law = balance(d, "the disk")[2]
    with_forces = sp.Eq(law.lhs.subs({eulers_disk.F_: 0, eulers_disk.N_: eulers_disk.m * eulers_disk.g}), law.rhs)
    omega_p_step = next(step for step in s.steps if "moment law" in step.title and step.part == 4)
    assert omega_p_step.latex.startswith(latex(sp.Eq(sp.simplify(with_forces.lhs), with_forces.rhs)))
