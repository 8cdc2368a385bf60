"""What a student sees around the answers (issue 17): the drawn bodies never overlap and stay in
view, captions agree with the motion they describe, no number reads −0, a link carries what the
controls show, and every check shown compares two computations that could disagree.

The geometry is read from the figures as drawn (the rounded coordinates the browser gets), not
from the solvers' arrays, so a drawing that strays from the physics is caught too.
"""
from __future__ import annotations

import importlib
import math
import re

import numpy as np
import pytest
from hypothesis import assume, given, settings

from solvers.core import Choice, Number, plain_fixed, plain_number
from tests import strategies
from tests.test_pages import IDS, assert_clean, run_page
from ui.catalog import BY_ID
from ui.params import as_shown, display_format

DRAWN = 2e-4  # coordinates are rounded to 4 decimals: a drawn gap may read this much short
EXAMPLES = settings(max_examples=25, deadline=None)


def figures(pid, **params):
    solution = importlib.import_module(f"solvers.{pid}").solve(**params)
    return solution, importlib.import_module(f"viz.{pid}").figures(solution)


def drawn(figure, name):
    """Per frame, the (x, y) points of the moving trace called ``name`` (NaN gaps dropped)."""
    spec = figure.spec
    anim = spec["animation"]
    index = next(i for i, j in enumerate(anim["traces"]) if spec["data"][j]["name"] == name)
    coords = anim["coords"][index]
    frames = []
    for xs, ys in zip(coords["x"], coords["y"]):
        xs, ys = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)
        keep = ~(np.isnan(xs) | np.isnan(ys))
        frames.append((xs[keep], ys[keep]))
    return frames


def static(figure, name):
    trace = next(t for t in figure.spec["data"] if t["name"] == name)
    return np.asarray(trace["x"], dtype=float), np.asarray(trace["y"], dtype=float)


def circle(xs, ys):
    """Centre and radius of a drawn circle (a closed polygon: the last point repeats the first)."""
    cx, cy = xs[:-1].mean(), ys[:-1].mean()
    return cx, cy, float(np.hypot(xs - cx, ys - cy).mean())


def distance_to_segment(px, py, ax, ay, bx, by) -> float:
    dx, dy = bx - ax, by - ay
    along = min(max(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0), 1.0)
    return math.hypot(px - ax - along * dx, py - ay - along * dy)


# ----------------------------------------------------------------------------------------------
# No two bodies overlap in any frame


@EXAMPLES
@given(strategies.valid("stick_ball"))
def test_the_stick_never_passes_through_the_ball(p):
    _, (figure,) = figures("stick_ball", **p)
    for (bx, by), (sx, sy) in zip(drawn(figure, "ball"), drawn(figure, "stick")):
        cx, cy, radius = circle(bx, by)
        assert distance_to_segment(cx, cy, sx[0], sy[0], sx[1], sy[1]) >= radius - DRAWN * (1 + p["l"])


def test_the_trial_s_bounce_stops_at_the_second_contact_and_says_so():
    """/stick_ball?mode=bounce&s=0.25: the stick's other half used to sweep through the ball."""
    _, (figure,) = figures("stick_ball", mode="bounce", s=0.25)
    assert "second impact" in figure.description and "stops there" in figure.description
    times = figure.spec["animation"]["times"]
    assert 1.4 < times[-1] < 1.55  # it ends at the contact, about 1.47 s after the impact
    (bx, by), (sx, sy) = drawn(figure, "ball")[-1], drawn(figure, "stick")[-1]
    cx, cy, radius = circle(bx, by)
    assert distance_to_segment(cx, cy, sx[0], sy[0], sx[1], sy[1]) == pytest.approx(radius, abs=5 * DRAWN)


@EXAMPLES
@given(strategies.valid("pendulum_rebound"))
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


@EXAMPLES
@given(strategies.valid("disk_wall"))
def test_the_disk_never_enters_the_wall(p):
    _, (figure,) = figures("disk_wall", **p)
    _, wall_y = static(figure, "wall")
    for xs, ys in drawn(figure, "disk"):
        cx, cy, radius = circle(xs, ys)
        assert wall_y[0] - cy >= radius - DRAWN * (1 + p["R"])


@EXAMPLES
@given(strategies.valid("rod_disk_spring"))
def test_the_disk_never_covers_the_spring(p):
    assume(p["k"] > 0)  # valid("rod_disk_spring") reaches θ2 already
    _, (figure,) = figures("rod_disk_spring", **p)
    for (xs, ys), (sx, sy) in zip(drawn(figure, "disk"), drawn(figure, "torsional spring")):
        cx, cy, radius = circle(xs, ys)
        assert np.hypot(sx - cx, sy - cy).min() >= radius - DRAWN


@EXAMPLES
@given(strategies.valid("driven_cart"))
def test_the_cart_stands_on_the_ground(p):
    _, figs = figures("driven_cart", **p)
    for xs, ys in drawn(figs[0], "wheels"):
        for wheel in (slice(0, len(xs) // 2), slice(len(xs) // 2, None)):  # rear, front
            _, cy, radius = circle(xs[wheel], ys[wheel])
            assert cy - radius == pytest.approx(0.0, abs=DRAWN)  # on the ground, not in it
    for xs, ys in drawn(figs[0], "cart body"):
        assert ys.min() > 0


@EXAMPLES
@given(strategies.valid("eulers_disk"))
def test_euler_s_disk_stays_on_the_table(p):
    _, figs = figures("eulers_disk", **p)
    rim = figs[0].spec["animation"]["coords"][0]["z"]
    assert min(min(row) for row in rim) >= -DRAWN * (1 + p["r"])


# ----------------------------------------------------------------------------------------------
# In view: nothing moving is cut off at the edge of the view


CUT_CASES = [("driven_cart", {"drive": "rear", "mu": 2.59}), ("driven_cart", {"drive": "all", "mu": 2.5}),
             ("driven_cart", {}), ("stick_ball", {"mode": "bounce", "s": 0.25}), ("disk_wall", {"e": 0.0}),
             ("pendulum_rebound", {"e": 0.0}), ("rod_disk_spring", {"k": 0.0})]


@pytest.mark.parametrize("pid,params", CUT_CASES)
def test_every_moving_shape_stays_inside_the_view(pid, params):
    _, figs = figures(pid, **params)
    figure = figs[0]
    layout = figure.spec["layout"]
    (x_lo, x_hi), (y_lo, y_hi) = layout["xaxis"]["range"], layout["yaxis"]["range"]
    anim = figure.spec["animation"]
    for j, coords in zip(anim["traces"], anim["coords"]):
        if figure.spec["data"][j].get("xaxis", "x") != "x" or "x" not in coords:
            continue  # another subplot (the energy bars, θ(t))
        for xs, ys in zip(coords["x"], coords["y"]):
            xs, ys = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)
            if np.isnan(xs).all():
                continue  # nothing drawn in this frame (the impulse outside its instant)
            assert np.nanmin(xs) >= x_lo and np.nanmax(xs) <= x_hi, figure.spec["data"][j]["name"]
            assert np.nanmin(ys) >= y_lo and np.nanmax(ys) <= y_hi, figure.spec["data"][j]["name"]


def test_a_cart_near_a_wheelie_keeps_a_readable_scale():
    """Rear drive at μ = 2.59 used to zoom out to 30 m, the cart tiny."""
    _, figs = figures("driven_cart", drive="rear", mu=2.59)
    x_lo, x_hi = figs[0].spec["layout"]["xaxis"]["range"]
    assert x_hi - x_lo < 8 * 2 * 1.3  # within eight wheelbases


# ----------------------------------------------------------------------------------------------
# Captions agree with the motion


@EXAMPLES
@given(strategies.valid("stick_ball"))
def test_the_bounce_caption_agrees_with_the_ball_s_direction(p):
    p = {**p, "mode": "bounce"}
    solution, (figure,) = figures("stick_ball", **p)
    anim = figure.spec["animation"]
    impact = int(np.argmin(np.abs(np.asarray(anim["times"]))))
    start = circle(*drawn(figure, "ball")[impact])[0]
    moved = np.array([circle(xs, ys)[0] - start for xs, ys in drawn(figure, "ball")[impact + 1:]])
    text = figure.description
    assume(len(moved) and np.abs(moved).max() > 10 * DRAWN)  # it moves far enough to tell
    if "bounces back" in text:
        assert moved.max() <= DRAWN
    elif "carries on forward" in text:
        assert moved.min() >= -DRAWN
    else:
        assert "stops dead" in text
    (bx, by), (sx, sy) = drawn(figure, "ball")[-1], drawn(figure, "stick")[-1]
    cx, cy, radius = circle(bx, by)
    touching_at_the_end = distance_to_segment(cx, cy, sx[0], sy[0], sx[1], sy[1]) - radius < 5 * DRAWN * (1 + p["l"])
    if "second impact" in text:
        assert touching_at_the_end  # the motion ends where the caption says: at the second contact


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


def test_the_pendulum_caption_at_e_0_lists_no_rebounds_and_points_below():
    _, (figure,) = figures("pendulum_rebound", e=0.0)
    assert "does not rebound" in figure.description and "rebounding to" not in figure.description
    assert "Below: θ against time" in figure.description and "Right:" not in figure.description


@EXAMPLES
@given(strategies.valid("pendulum_rebound"))
def test_the_pendulum_caption_never_repeats_a_rebound_angle(p):
    assume(0 < p["e"] < 1)
    _, (figure,) = figures("pendulum_rebound", **p)
    match = re.search(r"rebounding to ([^a-z]*?)(?: on successive| then|\.)", figure.description)
    if match:
        angles = [a.strip() for a in match.group(1).rstrip(", ").split(",")]
        assert len(angles) == len(set(angles)), figure.description


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
# Numbers: never −0, powers typeset, the URL carries what the control shows

# A minus after a digit, or after TeX's ``{}`` that opens a broken row, is a subtraction, not a sign;
# one before ``0^{2}`` negates the square of a substituted zero (−θ̇⁺² at e = 0), not a number −0.
MINUS_ZERO = re.compile(r"(?<![\d.}])[−-]0(?:\.0*)?(?![\d.^])")
EDGES = [("disk_wall", {"e": "0"}), ("disk_wall", {"mu": "0"}), ("rod_disk_spring", {"k": "0"}),
         ("pendulum_rebound", {"e": "0"}), ("stick_ball", {"mode": "bounce", "e": "1"}),
         ("driven_cart", {"mu": "0"}), ("driven_cart", {"m": "10000"})]


def test_the_formatter_never_writes_minus_zero_and_groups_or_typesets_large_numbers():
    assert plain_number(-0.0) == "0" and plain_number(-0.00001, 1) == "−1 × 10⁻⁵"
    assert plain_number(-0.00004, 4) != "−0"
    assert plain_number(30490.3) == "30\u2009490" and plain_number(3.049e7) == "3.049 × 10⁷"
    assert plain_fixed(-0.04, 1) == "0.0" and plain_fixed(-35.62, 1) == "−35.6"


@pytest.mark.parametrize("pid,query", EDGES)
def test_no_shown_number_is_minus_zero(pid, query):
    at = run_page(pid, query)
    assert_clean(at)
    texts = [m.value for m in at.markdown] + [c.value for c in at.caption]
    solver = BY_ID[pid].solver
    params = {}
    for spec in solver.PARAMS:
        if spec.name in query:
            params[spec.name] = query[spec.name] if isinstance(spec, Choice) else float(query[spec.name])
    _, figs = figures(pid, **params)
    texts += [f.description for f in figs] + [f.title for f in figs]
    for text in texts:
        # Inside LaTeX a minus is '-' too; both must not stand before a bare zero.
        assert not MINUS_ZERO.search(text.replace("$", " ")), (pid, query, MINUS_ZERO.search(text), text[:300])
        assert "× 10^" not in text and not re.search(r"\de[+-]\d", text)  # no 3.049e+04 either


@pytest.mark.parametrize("pid", IDS)
def test_url_values_carry_what_the_controls_show(pid):
    at = run_page(pid, {"units": "us"} if pid == "pendulum_rebound" else {})
    system = "us" if pid == "pendulum_rebound" else "si"
    changed = 0
    for widget in [*at.number_input, *at.slider]:
        name = widget.key.split("__")[-1]
        spec = next((p for p in BY_ID[pid].solver.PARAMS if p.name == name), None)
        if not isinstance(spec, Number) or widget.value is None or math.isinf(widget.value):
            continue
        value = widget.value * 1.0137913 if widget.value else 0.0137913
        lo, hi = getattr(widget, "min", None), getattr(widget, "max", None)
        if lo is not None and not lo <= value <= hi:
            value = widget.value * 0.9862087
        widget.set_value(value).run()
        assert_clean(at)
        if name in at.query_params:
            changed += 1
            assert at.query_params[name] == f"{as_shown(spec, value):g}"
            # ... which is at most six figures, or the slider's own decimals
            assert float(at.query_params[name]) == pytest.approx(value, rel=1e-5, abs=0.5 * 10 ** -(
                int(display_format(spec)[2:-1]) if display_format(spec).endswith("f") else 99))
    assert changed
    assert system


def test_whole_degree_sliders_show_whole_degrees():
    at = run_page("pendulum_rebound")
    theta0 = next(s for s in at.slider if s.key.endswith("__theta0"))
    assert theta0.proto.format == "%.0f"
    e = next(s for s in at.slider if s.key.endswith("__e"))
    assert e.proto.format == "%.2f"


def test_a_link_value_finer_than_the_control_is_rounded_to_what_it_shows():
    at = run_page("pendulum_rebound", {"theta0": "30.4"})
    assert next(s for s in at.slider if s.key.endswith("__theta0")).value == 30.0


# ----------------------------------------------------------------------------------------------
# Words: "the worked solution", never "the seed"; the run-down switch kept in the URL


@pytest.mark.parametrize("pid", IDS)
def test_on_screen_the_course_s_solution_is_the_worked_solution(pid):
    solver = BY_ID[pid].solver
    words = list(solver.ERRATA)
    for spec in solver.PARAMS:
        words += [spec.label, spec.help] + (list(spec.option_labels) if isinstance(spec, Choice) else [])
        if isinstance(spec, Choice):
            for option in spec.options:
                solution = solver.solve(**{spec.name: option})
                words += [s.title for s in solution.steps] + list(solution.notes)
                words += [c.name + c.explanation for c in solution.checks]
    at = run_page(pid)
    words += [m.value for m in at.markdown] + [r.label for r in at.radio]
    for text in words:
        assert "seed" not in text.lower(), text


def test_the_run_down_switch_is_kept_in_the_url():
    at = run_page("eulers_disk")
    at.toggle(key="eulers_disk__on_request").set_value(True).run()
    assert_clean(at)
    assert at.query_params.get("rundown") == "1"
    again = run_page("eulers_disk", dict(at.query_params))
    assert again.toggle(key="eulers_disk__on_request").value is True


def test_log_and_run_down_axes_label_their_ticks_in_full():
    solution, figs = figures("eulers_disk")
    log_axis = figs[1].spec["layout"]["yaxis"]
    assert log_axis["type"] == "log"
    assert [float(t) for t in log_axis["ticktext"]] == log_axis["tickvals"]
    assert all(str(v)[0] in "125" for v in log_axis["tickvals"])
    decay = importlib.import_module("viz.eulers_disk").on_request(solution)
    assert not any("overlaying" in v for v in decay.spec["layout"].values() if isinstance(v, dict))


# ----------------------------------------------------------------------------------------------
# Every shown check compares two computations that can disagree

CHECK_CASES = [("disk_wall", {}), ("disk_wall", {"mu": 0.2, "e": 0.5}), ("stick_ball", {}),
               ("stick_ball", {"mode": "bounce", "s": 0.25}), ("pendulum_rebound", {}),
               ("driven_cart", {"drive": "rear"}), ("eulers_disk", {}), ("rod_disk_spring", {}),
               ("rod_disk_spring", {"theta1": 0.4, "theta2": 2.0})]


@pytest.mark.parametrize("pid,params", CHECK_CASES)
def test_every_check_fails_when_an_earlier_step_is_wrong(pid, params):
    """A check that cannot fail (a value against its own definition, or against a max that
    contains it) is caught. One given misread, or one step of the derivation's chain, at a time is
    put 0.1 % wrong and every later step is recomputed from it, as a slip would propagate (the
    checks' second methods still get the true givens); each check must flag some such slip other
    than in the very value it shows. A check of T₂ against
    U_g + U_s, with T₂ defined as that sum, never does: a wrong U_g carries into T₂."""
    solver = importlib.import_module(f"solvers.{pid}")
    solution = solver.solve(**params)
    p, answers = dict(solution.params), dict(solution.answers)
    chain = solver.derivation_of(solution)
    inputs = {**p, **solution.extras.get("chain_inputs", {})}
    values = chain.evaluate(inputs)
    assert all(c.ok for c in solver._checks(p, answers))
    caught: dict[int, set[str]] = {i: set() for i in range(len(solution.checks))}
    def nudged(x):
        return x * 1.001 + 1e-3 * (x == 0)
    numeric = [name for name, x in p.items() if isinstance(x, float) and math.isfinite(x)]
    slips = [(name, chain.evaluate({**inputs, name: nudged(p[name])})) for name in numeric]  # a misread given
    slips += [(link.name, chain.evaluate(inputs, overrides={link.name: nudged(values[link.name])}))
              for link in chain.chain]
    for slipped_name, slipped in slips:
        wrong = {name: slipped.get(name, value) for name, value in answers.items()}
        for i, check in enumerate(solver._checks(p, wrong)):
            if not check.ok:
                caught[i].add(slipped_name)
    for i, check in enumerate(solution.checks):
        shown = {name for name, value in answers.items() if value == check.closed_form}
        assert caught[i] - shown, f"{check.name!r} is failed by no slip but one in the value it shows"
        assert check.closed_form is not check.second_method  # and none compares a number with itself


def test_the_stick_s_energy_check_is_a_second_computation():
    """It used to show T_before against max(T_before, T_after): "0.5 vs 0.5" whatever happened."""
    solution = importlib.import_module("solvers.stick_ball").solve()
    energy = next(c for c in solution.checks if "energy" in c.name)
    assert energy.closed_form != pytest.approx(solution.answers["T_before"])
    # the worked solution's numbers: equal masses hit at the end lose 1/5 of ½ m v²
    assert energy.second_method == pytest.approx(0.1, rel=1e-12)


@pytest.mark.parametrize("pid,query,figures_shown", [
    ("driven_cart", {"drive": "rear", "mu": "3"}, 1),  # the wheelie: the ẍ–μ plot shows where it starts
    ("rod_disk_spring", {"k": "100"}, 0),
])
def test_a_physical_limit_keeps_the_method_and_what_shows_why(pid, query, figures_shown):
    """At μ ≥ 2.6 (rear drive) only the error used to remain: the derivation and the plot went."""
    at = run_page(pid, query)
    assert_clean(at)
    assert at.error and at.metric
    method = next(m.value for m in at.markdown if "### Derivation, step by step" in m.value)
    assert "without numbers" in method and "$$" in method
    assert len(at.get("component_instance")) == figures_shown


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
