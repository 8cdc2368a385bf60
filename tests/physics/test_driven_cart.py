"""driven_cart against the seed's formula and an independent numpy solve of the six equations."""
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings, strategies as st

from solvers import driven_cart
from solvers.diagram import Circle, balance, balance_steps, fbd_steps, residuals
from tests.strategies import pos
from tests.drawing import DRAWN, EXAMPLES, circle, drawn, figures

# The solver contract, typed from PROBLEMS.md independently of the solver module (tests/physics/test_contract.py
# checks every registered problem against its CONTRACT): parameter defaults (SI, radians), answer names,
# and values the solver must refuse in plain words.
CONTRACT = {
    "defaults": dict(m=1200.0, a=0.5, b=1.3, c=0.75, mu=0.8, g=9.81, drive="front"),
    "answers": {"F_drive", "N_front", "N_rear", "accel"},
    "out_of_range": (("mu", -0.5), ("a", 0.0)),
}


@st.composite
def valid_params(draw):
    a, b = draw(pos(0.05, 3)), draw(pos(0.1, 3))
    drive = draw(st.sampled_from(["front", "rear", "all"]))
    mu_max = 5 if drive == "front" else 0.999 * b / a
    return {"m": draw(pos(10, 1e4)), "a": a, "b": b, "c": draw(pos(0.1, 2)),
            "mu": draw(pos(0, mu_max)), "g": draw(pos(1, 25)), "drive": drive}


VALID = valid_params()  # random valid parameters (SI, radians) for property tests

# Cases of the shared tests in test_what_students_see.py beyond the defaults.
IN_VIEW = ({}, {"drive": "rear", "mu": 2.59}, {"drive": "all", "mu": 2.5})  # near a wheelie too: still in view
EDGE_LINKS = ({"mu": "0"}, {"m": "10000"})  # links whose numbers could read −0 or need a power of ten
CHECK_CASES = ({"drive": "rear"},)  # beyond the defaults: every shown check can fail here too
LIMIT_LINKS = (({"drive": "rear", "mu": "3"}, 1),)  # the wheelie: the method and the ẍ–μ plot stay


def six_equations(m, a, b, c, mu, g, drive):
    """Unknowns N1..N4 (vertical), L1..L4 (lateral), xdd; wheels 1 rear-left (−b, +c), 2 front-left
    (+b, +c), 3 front-right (+b, −c), 4 rear-right (−b, −c), contact at height −a below the CM."""
    xs, zs = [-b, b, b, -b], [c, c, -c, -c]
    driven = {"front": [1, 2], "rear": [0, 3], "all": [0, 1, 2, 3]}[drive]
    t = [mu if i in driven else 0.0 for i in range(4)]
    A, rhs = [], []
    A.append([t[0], t[1], t[2], t[3], 0, 0, 0, 0, -m]); rhs.append(0)          # Σ F_x = m ẍ
    A.append([1, 1, 1, 1, 0, 0, 0, 0, 0]); rhs.append(m * g)                      # Σ F_y = 0
    A.append([0, 0, 0, 0, 1, 1, 1, 1, 0]); rhs.append(0)                          # Σ F_z = 0
    # M = r × F with r = (x, −a, z), F = (t N, N, L)
    A.append([-zs[i] for i in range(4)] + [-a] * 4 + [0]); rhs.append(0)         # M_x
    A.append([zs[i] * t[i] for i in range(4)] + [-xs[i] for i in range(4)] + [0]); rhs.append(0)  # M_y
    A.append([xs[i] + a * t[i] for i in range(4)] + [0] * 4 + [0]); rhs.append(0)  # M_z
    # the seed's assumptions
    for row in ([1, 0, 0, -1], [0, 1, -1, 0]):
        A.append(row + [0] * 5); rhs.append(0)
    for i in range(4):
        A.append([0] * 4 + [1 if j == i else 0 for j in range(4)] + [0]); rhs.append(0)
    x, *_ = np.linalg.lstsq(np.array(A, float), np.array(rhs, float), rcond=None)
    residual = np.array(A, float) @ x - np.array(rhs, float)
    return x, float(np.abs(residual).max())


def test_seed_front_drive_result():
    a = driven_cart.solve().answers
    m, aa, b, mu, g = 1200, 0.5, 1.3, 0.8, 9.81
    assert a["accel"] == pytest.approx(mu * b * g / (mu * aa + 2 * b), rel=1e-12)
    assert a["N_front"] == pytest.approx(b / (mu * aa + 2 * b) * m * g / 2, rel=1e-12)
    assert a["N_rear"] == pytest.approx((mu * aa + b) / (mu * aa + 2 * b) * m * g / 2, rel=1e-12)
    assert a["N_front"] < a["N_rear"]  # load moves to the rear: driven fronts are the unloaded ones
    assert a["F_drive"] == pytest.approx(m * a["accel"], rel=1e-12)


@settings(max_examples=80, deadline=None)
@given(VALID)
def test_agrees_with_a_linear_solve_of_all_six_equations(p):
    x, residual = six_equations(**p)
    weight = p["m"] * p["g"]
    assert residual < 1e-8 * weight  # consistent: the assumptions close the system exactly
    a = driven_cart.solve(**p).answers
    assert a["accel"] == pytest.approx(x[8], rel=1e-9, abs=1e-9 * p["g"])
    assert a["N_rear"] == pytest.approx(x[0], rel=1e-9)
    assert a["N_front"] == pytest.approx(x[1], rel=1e-9)
    assert a["F_drive"] == pytest.approx(p["m"] * x[8], rel=1e-9, abs=1e-9 * weight)
    assert a["N_front"] > 0 and a["N_rear"] > 0


@pytest.mark.parametrize("drive", ["rear", "all"])
def test_wheelie_is_refused_at_and_beyond_mu_a_equals_b(drive):
    for mu in (2.6, 3.0, 5.2, 6.0, 100.0):  # b/a = 2.6; past μa = 2b the rear formula flips sign
        with pytest.raises(ValueError) as err:
            driven_cart.solve(drive=drive, mu=mu)
        assert err.value.mu_lift == pytest.approx(2.6)
        assert "wheelie" in str(err.value)
    assert driven_cart.solve(drive=drive, mu=2.59).answers["N_front"] > 0


def test_front_drive_never_lifts():
    a = driven_cart.solve(mu=50.0).answers
    assert a["N_front"] > 0 and a["accel"] < 9.81 * 1.3 / 0.5


def test_all_wheel_drive_gives_mu_g():
    assert driven_cart.solve(drive="all").answers["accel"] == pytest.approx(0.8 * 9.81)


def test_the_wheelie_is_a_physical_limit_the_page_can_show():
    from solvers.core import PhysicalLimitError
    with pytest.raises(PhysicalLimitError) as err:
        driven_cart.solve(drive="rear", mu=2.6)  # μa = b exactly: lifts
    assert err.value.mu_lift == pytest.approx(1.3 / 0.5)


@settings(max_examples=25, deadline=None)
@given(VALID, st.floats(0.05, 3.0))
def test_the_curves_against_mu_are_the_solver_s_answers_whatever_mu_the_cart_has(p, other_mu):
    """The companion figure's curves are kept by every parameter but μ (issue 28: moving μ redraws
    only the point): for two carts that differ in μ alone they are the same, read-only, and each
    point on them is what solving that cart at that μ gives (NaN past its wheelie)."""
    mus = np.linspace(0.0, 3.0, 13)
    curves = driven_cart.acceleration_versus_mu(p, mus)
    again = driven_cart.acceleration_versus_mu({**p, "mu": other_mu}, mus)
    for drive, values in curves.items():
        assert again[drive] is values and not values.flags.writeable
        for mu, accel in zip(mus, values):
            try:
                expected = driven_cart.solve(**{**p, "mu": float(mu), "drive": drive}).answers["accel"]
            except ValueError:  # the front wheels lift: no acceleration to draw
                assert math.isnan(accel)
                continue
            assert accel == pytest.approx(expected, rel=1e-9, abs=1e-12)


# ----------------------------------------------------------------------------------------------
# What a student sees: the drawing agrees with the physics, the captions with the motion


@EXAMPLES
@given(VALID)
def test_the_cart_stands_on_the_ground(p):
    _, figs = figures("driven_cart", **p)
    for xs, ys in drawn(figs[0], "wheels"):
        for wheel in (slice(0, len(xs) // 2), slice(len(xs) // 2, None)):  # rear, front
            _, cy, radius = circle(xs[wheel], ys[wheel])
            assert cy - radius == pytest.approx(0.0, abs=DRAWN)  # on the ground, not in it
    for xs, ys in drawn(figs[0], "cart body"):
        assert ys.min() > 0


def test_a_cart_near_a_wheelie_keeps_a_readable_scale():
    """Rear drive at μ = 2.59 used to zoom out to 30 m, the cart tiny."""
    _, figs = figures("driven_cart", drive="rear", mu=2.59)
    x_lo, x_hi = figs[0].spec["layout"]["xaxis"]["range"]
    assert x_hi - x_lo < 8 * 2 * 1.3  # within eight wheelbases


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(["rear", "all"]), st.floats(0.2, 2.0), st.floats(1.05, 3.0))
def test_a_cart_past_the_lift_off_is_marked_across_the_plot_not_at_zero_acceleration(drive, a, past):
    """Beside the wheelie's refusal the ẍ–μ plot marks this cart's μ = past · b/a: a line across the plot at
    that μ, from ẍ = 0 to above the highest curve (a point at ẍ = 0 read as "it does not accelerate")."""
    from viz.driven_cart import at_limit
    p = {**{q.name: q.default for q in driven_cart.PARAMS}, "drive": drive, "a": a}
    p["mu"] = past * p["b"] / a
    with pytest.raises(ValueError):
        driven_cart.solve(**p)  # the model refuses: the front wheels lift
    (figure,) = at_limit(p)
    spec = figure.spec
    (mark,) = [t for t in spec["data"] if str(t.get("name", "")).startswith("this cart")]
    curves = [t for t in spec["data"] if t.get("name", "").endswith("drive")]
    highest = max(np.nanmax(np.asarray(t["y"], dtype=float)) for t in curves)
    assert mark.get("mode") == "lines" and np.allclose(np.asarray(mark["x"], dtype=float), p["mu"], rtol=1e-3)
    ys = np.asarray(mark["y"], dtype=float)
    assert ys.min() == 0 and ys.max() >= highest


# ----------------------------------------------------------------------------------------------
# The free-body diagram (Step 2) and the balance laws written from it (Step 3)


def _diagram(solution):
    (d,) = driven_cart.free_body_diagrams(solution.params)
    return d


def _vector(load, values):
    return tuple(float(sp.sympify(c).subs(values)) for c in load.vector)


@settings(max_examples=25, deadline=None)
@given(VALID)
def test_the_side_view_s_balance_laws_hold_at_the_wheel_by_wheel_numbers(p):
    """ΣF_x = m ẍ_C, ΣF_y = 0 and ΣM_C = 0, summed from the declared loads, hold at the numbers of the
    worked solution's six equations solved numerically (the diagram's values), for every drive."""
    s = driven_cart.solve(**p)
    d = _diagram(s)
    values = d.values(s)
    # every term is at most the weight (a force) or the weight times b + μa (a moment about C)
    scale = p["m"] * p["g"] * max(1.0, p["b"] + p["mu"] * p["a"])
    for law, left, right in residuals(d, s):
        assert abs(left - right) <= 1e-9 * scale, (law, left, right, scale)
    # and the values are the answers (per wheel: the diagram's axle carries two)
    assert float(values[driven_cart.N_front]) == pytest.approx(s.answers["N_front"], rel=1e-9)
    assert float(values[driven_cart.N_rear]) == pytest.approx(s.answers["N_rear"], rel=1e-9)
    assert float(values[driven_cart.xdd]) == pytest.approx(s.answers["accel"], rel=1e-9, abs=1e-12 * p["g"])


@settings(max_examples=40, deadline=None)
@given(VALID)
def test_the_diagram_s_forces_point_as_the_physics_says(p):
    """Gravity down at C; the ground pushes each axle up with two wheels' load, 2N; the traction pushes
    forward (along ẍ) at the driven axles only and adds up to F_drive; the free wheels carry none."""
    s = driven_cart.solve(**p)
    d = _diagram(s)
    values = d.values(s)
    points = d.body("the cart").points
    assert float(sp.sympify(points["F"][0] - points["C"][0]).subs(values)) == pytest.approx(p["b"])  # ahead
    assert float(sp.sympify(points["R"][0] - points["C"][0]).subs(values)) == pytest.approx(-p["b"])  # behind
    weight = p["m"] * p["g"]
    by_name = {load.name: load for load in d.loads}
    gx, gy = _vector(by_name["the weight"], values)
    assert by_name["the weight"].at == "C" and gx == 0 and gy == pytest.approx(-weight, rel=1e-12)
    driven = {"front": {"front"}, "rear": {"rear"}, "all": {"front", "rear"}}[p["drive"]]
    traction_total = 0.0
    for axle, point in (("front", "F"), ("rear", "R")):
        normal = by_name[f"the ground's normal force on the {axle} wheels"]
        assert normal.at == point and points[point][1] == 0  # at the contact, on the ground
        nx, ny = _vector(normal, values)
        assert nx == 0 and ny > 0  # out of the ground, into the cart
        assert ny == pytest.approx(2 * s.answers[f"N_{axle}"], rel=1e-9)  # the axle's two wheels
        traction = by_name.get(f"the ground's traction on the driven {axle} wheels")
        assert (traction is not None) == (axle in driven)  # no zero force drawn at the free wheels
        if traction is not None:
            tx, ty = _vector(traction, values)
            assert traction.at == point and ty == 0 and tx >= 0
            assert tx * s.answers["accel"] >= 0  # forward, the way the cart accelerates
            assert tx == pytest.approx(p["mu"] * ny, rel=1e-12, abs=1e-12 * weight)  # at the friction limit
            traction_total += tx
    assert traction_total == pytest.approx(s.answers["F_drive"], rel=1e-9, abs=1e-9 * weight)
    assert len(d.loads) == 3 + len(driven)


@settings(max_examples=15, deadline=None)
@given(VALID)
def test_the_diagram_is_drawn_where_the_stage_draws_the_cart_at_every_frame(p):
    """Diagram.frames: one value per frame of the motion, the forces constant, the cart at the motion's
    x; the first frame is the instant the diagram is drawn for. Its points in the stage's coordinates:
    C where the stage marks the centre of mass, the wheels' outlines on the stage's wheels."""
    s, figs = figures("driven_cart", **p)
    d = _diagram(s)
    motion = driven_cart.motion(s)
    frames = d.frames(s, motion)
    n = len(motion["t"])
    values = d.values(s)
    assert set(frames) == set(values)
    for sym, column in frames.items():
        column = np.asarray(column, dtype=float)
        assert column.shape == (n,) and np.all(np.isfinite(column)), sym
        assert column[0] == pytest.approx(float(values[sym]), rel=1e-12, abs=1e-12), sym
        if sym is driven_cart.x_C:
            assert np.array_equal(column, motion["x"])
        else:
            assert np.all(column == column[0]), sym  # the forces are the same at every instant
    body = d.body("the cart")
    symbols = sorted(frames, key=lambda sym: sym.name)
    columns = [np.asarray(frames[sym], dtype=float) for sym in symbols]
    at = lambda expr: np.broadcast_to(sp.lambdify(symbols, sp.sympify(expr), "numpy")(*columns), (n,))  # noqa: E731
    cx, cy = (at(c) for c in body.points["C"])
    for i, (xs, ys) in enumerate(drawn(figs[0], "centre of mass")):
        assert (cx[i], cy[i]) == (pytest.approx(xs[0], abs=DRAWN), pytest.approx(ys[0], abs=DRAWN))
    hubs = {shape.centre: (*(at(c) for c in body.points[shape.centre]), at(shape.radius))
            for shape in body.outline if isinstance(shape, Circle)}
    for i, (xs, ys) in enumerate(drawn(figs[0], "wheels")):
        for hub, half in (("_rear_hub", slice(0, len(xs) // 2)), ("_front_hub", slice(len(xs) // 2, None))):
            wx, wy, radius = circle(xs[half], ys[half])
            hx, hy, hr = (column[i] for column in hubs[hub])
            assert (hx, hy) == (pytest.approx(wx, abs=10 * DRAWN), pytest.approx(wy, abs=10 * DRAWN))
            assert hr == pytest.approx(radius, rel=0.01)


@pytest.mark.parametrize("drive", ["front", "rear", "all"])
def test_the_derivation_is_in_the_four_steps_and_solves_the_diagram_s_laws(drive):
    """Step 1 (origin, coordinates, basis, kinematics), Step 2 the declared diagram, Step 3 its balance
    laws, then the analysis, in that order; the answers solve Step 3's laws, and the worked solution's
    wheel-by-wheel route is shown reducing to them."""
    s = driven_cart.solve(drive=drive, mu=0.5)
    d = _diagram(s)
    parts = [step.part for step in s.steps]
    assert parts == sorted(parts) and set(parts) == {1, 2, 3, 4}
    assert s.steps[0].part == 1 and "Origin" in s.steps[0].title and r"\mathbf{E}_x" in s.steps[0].title
    assert [step for step in s.steps if step.part == 2] == list(fbd_steps(d))
    assert [step for step in s.steps if step.part == 3] == list(balance_steps(d))
    at = {driven_cart.m: s.params["m"], driven_cart.a: s.params["a"], driven_cart.b: s.params["b"],
          driven_cart.mu: s.params["mu"], driven_cart.g: s.params["g"], driven_cart.xdd: s.answers["accel"],
          driven_cart.N_front: s.answers["N_front"], driven_cart.N_rear: s.answers["N_rear"]}
    for law in balance(d, "the cart"):
        assert float((law.lhs - law.rhs).subs(at)) == pytest.approx(0, abs=1e-9 * s.params["m"] * s.params["g"])
    remains = next(step for step in s.steps if step.title.startswith("What remains"))
    assert "Step 3" in remains.title and remains.part == 4


@pytest.mark.parametrize("drive", ["rear", "all"])
def test_the_method_shown_past_the_wheelie_follows_the_four_steps_too(drive):
    """Beside the refusal, the method: the four parts in order, the diagram and its laws among them, and
    last the condition μa < b that the cart fails."""
    params = {"drive": drive, "mu": 3.0}
    with pytest.raises(driven_cart.FrontWheelsLiftError):
        driven_cart.solve(**params)
    steps = driven_cart.method(params)
    parts = [step.part for step in steps]
    assert parts == sorted(parts) and set(parts) == {1, 2, 3, 4}
    assert [step for step in steps if step.part == 2] == list(fbd_steps(driven_cart.side_view(drive)))
    assert r"\mu a < b" in steps[-1].latex and not any(step.numeric for step in steps)
