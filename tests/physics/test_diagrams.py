"""The free-body diagrams (solvers/diagram.py, each problem's ``free_body_diagrams``) and the
course's four steps, for every registered problem: the picture and the equations are one source,
the balance laws hold at the solver's own numbers, and the drawing is legible (no label on another,
none outside the picture). Each problem's own file tests its directions by its physics."""
from __future__ import annotations

import html
import math
import re
from dataclasses import replace

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings, strategies as st

from solvers import registry
from solvers.diagram import balance, balance_steps, fbd_steps, residuals
from solvers.solution import PARTS
from tests.strategies import valid
from viz import diagram as fbd
from viz.common import DIGITS

IDS = registry.PROBLEM_IDS
VALID = {pid: valid(pid) for pid in IDS}
SETTINGS = dict(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _solutions(pid, params):
    solver = registry.solver(pid)
    try:
        return [solver.solve(**params)]
    except ValueError:
        return []


def test_every_problem_declares_its_diagrams():
    for pid in IDS:
        solution = registry.solver(pid).solve()
        diagrams = registry.solver(pid).free_body_diagrams(solution.params)
        assert diagrams, pid
        for d in diagrams:
            assert d.law in ("force", "impulse"), (pid, d.phase)
            names = {b.name for b in d.bodies}
            for load in d.loads:
                assert load.kind in ("force", "impulse", "couple"), (pid, load)
                assert load.on in names, (pid, load.symbol, load.on)
                if load.kind != "couple":
                    assert load.at in d.body(load.on).points, (pid, load.symbol, load.at)
                    assert (load.direction is None) == bool(load.components) or load.direction is not None, load
                assert load.name and load.by and load.symbol, (pid, load)
                if load.pair:  # an interaction pair: drawn on both bodies, opposite
                    partner = next(l for l in d.loads if l.name == load.pair)
                    assert partner.on != load.on and partner.pair == load.name, (pid, load.name)
                    values = d.values(solution)
                    for a, b in zip(load.vector, partner.vector):
                        assert math.isclose(float(sp.sympify(a).subs(values)), -float(sp.sympify(b).subs(values)),
                                            rel_tol=1e-12, abs_tol=1e-12), (pid, load.name)
            for body in d.bodies:
                assert body.centre in body.points and body.about in body.points, (pid, body.name)


def _parts(solution):
    return [s.part for s in solution.steps]


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_the_derivation_is_in_the_courses_four_steps_and_written_from_the_diagram(pid, data):
    """Every step in one of the four, in order, all four there; Step 2 is the declared diagrams'
    and Step 3 holds their balance laws, so the diagram and the equations cannot disagree."""
    for solution in _solutions(pid, data.draw(VALID[pid])):
        parts = _parts(solution)
        assert parts == sorted(parts) and set(parts) == set(PARTS), (pid, parts)
        diagrams = registry.solver(pid).free_body_diagrams(solution.params)
        steps = list(solution.steps)
        expected_fbd = [s for d in diagrams for s in fbd_steps(d)]
        assert [s for s in steps if s.part == 2] == expected_fbd, pid
        part3 = [s for s in steps if s.part == 3]
        for d in diagrams:
            for s in balance_steps(d):
                assert s in part3, (pid, d.phase, s.title)


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_the_balance_laws_hold_at_the_solvers_numbers(pid, data):
    """ΣF = m a_G and ΣM = Ḣ (or their impulse forms), summed from the declared loads, hold at the
    numbers the solver's own physics gives for the instant drawn."""
    for solution in _solutions(pid, data.draw(VALID[pid])):
        for d in registry.solver(pid).free_body_diagrams(solution.params):
            values = d.values(solution)
            rows = residuals(d, solution)
            for n, body in enumerate(d.bodies):
                laws = balance(d, body.name)
                # each law to the size of the largest term in the body's laws (a sum of large terms that
                # cancel, or a law whose terms all vanish: a cart with μ = 0)
                terms = [t for eq in laws for side in (eq.lhs, eq.rhs) for t in sp.Add.make_args(sp.expand(side))]
                scale = max(abs(float(t.subs(values))) for t in terms)
                for eq, (law, left, right) in zip(laws, rows[3 * n: 3 * n + 3]):
                    assert abs(left - right) <= 1e-7 * scale + 1e-300, (pid, d.phase, law, left, right, scale)


def test_a_load_left_out_of_the_diagram_breaks_the_balance():
    """Positive control: the balance check fails when a declared load is dropped."""
    from dataclasses import replace

    for pid in IDS:
        solution = registry.solver(pid).solve()
        for d in registry.solver(pid).free_body_diagrams(solution.params):
            values = d.values(solution)
            for load in d.loads:
                if load.kind == "couple":
                    size = abs(float(sp.sympify(load.size).subs(values)))
                else:
                    size = max(abs(float(sp.sympify(c).subs(values))) for c in load.vector)
                if size < 1e-6:
                    continue  # (a reaction that vanishes here, Euler's friction: nothing to miss)
                less = replace(d, loads=tuple(l for l in d.loads if l is not load))
                assert any(not math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-9) for _, a, b in residuals(less, solution)), \
                    (pid, d.phase, load.symbol)


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_the_drawing_is_legible(pid, data):
    """No label on another, every label and shape inside the picture's box, each label nearer what it
    names than anything else of its kind (a point's letter by its dot, a load's symbol by its arrow), each
    load drawn and said in words (the text alternative names each load and its point)."""
    solver = registry.solver(pid)
    for solution in _solutions(pid, data.draw(VALID[pid])):
        for d, drawing in zip(solver.free_body_diagrams(solution.params), fbd.drawings(solver, solution)):
            boxes = [label.box for label in drawing.labels]
            for i, a in enumerate(boxes):
                assert a.inside(drawing.box), (pid, d.phase, drawing.labels[i].tex)
                for j in range(i):
                    assert not a.overlaps(boxes[j]), (pid, d.phase, drawing.labels[i].tex, drawing.labels[j].tex)
            for x, y, label in drawing.points:
                if any(0 < math.hypot(x - u, y - v) < fbd.POINT_FONT for u, v, _ in drawing.points):
                    continue  # two dots closer than a letter's height: no place tells their letters apart
                others = [fbd._from_box(label.box, (u, v)) for u, v, other in drawing.points if other is not label]
                assert fbd._from_box(label.box, (x, y)) < min(others, default=math.inf), (pid, d.phase, label.tex)
            loads = [a for a in drawing.arrows if a.kind != "basis"]
            for arrow in loads:
                at = (arrow.label.x, arrow.label.y)
                others = [fbd._from_segment(at, b.tail, b.head) for b in loads if b is not arrow]
                assert fbd._from_segment(at, arrow.tail, arrow.head) < min(others, default=math.inf), (pid, d.phase, arrow.label.tex)
            drawn = {a.load for a in drawing.arrows} | {c.load for c in drawing.curls}
            for load in d.loads:
                assert load.symbol in drawn, (pid, d.phase, load.symbol)
                assert load.name in drawing.text, (pid, load.name)
            svg = fbd.svg(drawing)
            assert svg.startswith("<svg") and "role='img'" in svg and "aria-label=" in svg


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_a_diagram_laid_out_before_for_its_shape_is_the_one_laid_out_anew(pid, data):
    """``layout`` keeps each shape's drawing (a new stiffness draws the spring's diagram it drew before): what
    it returns is what laying it out at these values gives, for every state, the words with their values."""
    from solvers.diagram import numbers

    solver = registry.solver(pid)
    params = data.draw(VALID[pid])
    # each number moved alone, after the drawn state: where the drawing does not read it, the second is a
    # drawing kept from the first, and must be what laying it out anew gives
    states = [params] + [{**params, name: value * factor} for name, value in params.items()
                         if isinstance(value, float) and value for factor in (0.3, 1.3, 3.0)]
    for state in states:
        for solution in _solutions(pid, state):
            for d in solver.free_body_diagrams(solution.params):
                values = d.values(solution)
                kept = fbd.layout(d, values)
                at = numbers(d, {k: float(v) for k, v in values.items()})
                anew = fbd._laid_out(d, at, False)
                assert fbd.svg(replace(anew, text=kept.text)) == fbd.svg(kept), (pid, d.phase, state)
                assert kept.text == fbd.text_alternative(d, at)


def test_a_new_stiffness_draws_the_springs_diagram_it_drew_before_with_its_own_words():
    solver = registry.solver("rod_disk_spring")
    first, second = solver.solve(k=20.0), solver.solve(k=35.0)
    (d1,), (d2,) = solver.free_body_diagrams(first.params), solver.free_body_diagrams(second.params)
    a, b = fbd.layout(d1, d1.values(first)), fbd.layout(d2, d2.values(second))
    assert a.arrows is b.arrows and a.points is b.points  # laid out once
    assert fbd.svg(a).split("aria-label")[0] == fbd.svg(b).split("aria-label")[0]


def test_an_unknown_reaction_is_drawn_as_its_two_components_and_an_impulse_with_an_open_head():
    from solvers import disk_wall

    solution = disk_wall.solve()
    drawing = fbd.drawings(disk_wall, solution)[0]
    loads = [a for a in drawing.arrows if a.kind != "basis"]
    assert sorted(a.label.tex for a in loads) == sorted(sp.latex(c) for c in disk_wall.IMPACT.loads[0].components)
    assert all(a.kind == "impulse" for a in loads)
    assert "fill='#ffffff' stroke='#b3261e'" in fbd.svg(drawing)  # the open head


def test_labels_are_written_as_subscripts():
    assert fbd.runs("N_A") == (("N", ""), ("A", "sub"))
    assert fbd.runs(r"m_{s} g") == (("m", ""), ("s", "sub"), ("g", ""))
    assert fbd.runs(r"\mu N_{f}") == (("μN", ""), ("f", "sub"))
    assert fbd.runs(r"2 \mu N_{\mathrm{front}}") == (("2μN", ""), ("front", "sub upright"))  # as the derivation sets it
    assert fbd.plain_label(r"O_{x}") == "O_x"
    from solvers import driven_cart
    drawn = fbd.svg(fbd.drawings(driven_cart, driven_cart.solve())[0])
    assert "<tspan baseline-shift='sub' font-size='70%' font-style='normal'>front</tspan>" in drawn


def test_practice_withholds_the_diagram():
    """The exercise's method says to draw the diagram and shows neither it nor the balance laws."""
    from practice.method import DRAW_IT, exercise_steps

    for pid in IDS:
        solver = registry.solver(pid)
        solution = solver.solve()
        shown = exercise_steps(solution.steps[: solution.symbolic_steps], solver.derivation_of(solution))
        assert [t for part, t, _ in shown if part == 2] == [DRAW_IT], pid
        assert all(tex == "" for part, _, tex in shown if part == 3), pid
        diagrams = solver.free_body_diagrams(solution.params)
        hidden = [s.title for d in diagrams for s in fbd_steps(d)] + [s.latex for d in diagrams for s in balance_steps(d)]
        text = " ".join(t + tex for _, t, tex in shown)
        assert not any(h in text for h in hidden), pid


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_the_stages_forces_are_the_diagrams_at_each_frame(pid, data):
    """The Forces overlay draws each declared load at its point, along its vector, in the frames of
    its phase and no other; at the instant the diagram is drawn for, the same numbers as the diagram."""
    import numpy as np

    solver = registry.solver(pid)
    for solution in _solutions(pid, data.draw(VALID[pid])):
        diagrams = [d for d in solver.free_body_diagrams(solution.params) if d.frames is not None]
        if not diagrams:
            continue
        motion = solver.motion(solution)
        frames = len(motion["t"])
        traces, _ = fbd.overlay(solver, solution, motion, width=1.0)
        arrows = {tuple(t.style["meta"]): t for t in traces if t.style.get("mode") == "lines"}
        assert arrows, pid
        for d in diagrams:
            per_frame = d.frames(solution, motion)
            assert all(np.shape(v) in ((), (frames,)) for v in per_frame.values()), (pid, d.phase)  # (a constant: one value)
            per_frame = {k: np.broadcast_to(np.asarray(v, dtype=float), (frames,)) for k, v in per_frame.items()}
            at = d.values(solution)
            # the frame the diagram is drawn for, where it is one: every symbol agrees there
            hits = [i for i in range(frames) if all(
                math.isclose(float(per_frame[s][i]), float(v), rel_tol=1e-6, abs_tol=1e-9)
                for s, v in at.items() if s in per_frame and np.isfinite(per_frame[s][i]))
                and all(np.isfinite(per_frame[s][i]) for s in at if s in per_frame)]
            for load in d.loads:
                if load.kind == "couple":
                    continue
                trace = arrows[(load.on, load.symbol)]
                xs, ys = trace.per_frame["x"], trace.per_frame["y"]
                for i in hits[:1]:
                    at_frame = {s: per_frame[s][i] for s in per_frame}
                    vx, vy = (float(sp.sympify(c).subs(at_frame)) for c in load.vector)
                    largest = max(math.hypot(*(float(sp.sympify(c).subs(at_frame)) for c in other.vector))
                                  for other in d.loads if other.kind == load.kind)
                    if math.hypot(vx, vy) < 1e-3 * largest:
                        continue  # (a thousandth of the largest: below what the figure draws)
                    shaft = (xs[i][1] - xs[i][0], ys[i][1] - ys[i][0])
                    # drawn along the load's vector
                    assert shaft[0] * vx + shaft[1] * vy > 0, (pid, d.phase, load.symbol)
                    # (to the figure's rounding, viz.common.DIGITS decimals at each end)
                    slack = 2 * 10.0 ** -DIGITS / math.hypot(*shaft) + 1e-3
                    assert abs(shaft[0] * vy - shaft[1] * vx) <= slack * math.hypot(*shaft) * math.hypot(vx, vy)


# --- on the page (AppTest) -----------------------------------------------------------------------

def _page(pid: str, query: dict | None = None):
    from tests.pages.test_pages import run_page

    return run_page(pid, query)


@pytest.mark.parametrize("pid", IDS)
def test_the_page_draws_step_two_and_heads_the_four_steps(pid):
    """The derivation's element gets the four headings and, under Step 2, each diagram's SVG (its text
    alternative the SVG's aria-label, naming every load) and caption; the stage's Forces switch (off) is there where the stage can show the forces."""
    from tests.pages.test_pages import derivation_shown, shown
    from ui.figure import NAME

    at = _page(pid)
    d = derivation_shown(at)
    assert [title for _, title in d["parts"]] == list(PARTS.values())
    solver = registry.solver(pid)
    declared = solver.free_body_diagrams(solver.solve().params)
    assert len(d["diagrams"]) == len(declared)
    for (svg, caption), diagram in zip(d["diagrams"], declared):
        assert svg.startswith("<svg") and caption.startswith("Free-body diagram") and ":" not in caption
        text = html.unescape(re.search(r"aria-label='([^']*)'", svg).group(1))  # the text alternative
        assert text.startswith(caption + ":")
        for load in diagram.loads:
            assert load.name in text
    stage = shown(at, NAME)[0]
    assert stage.get("forces") is (False if any(x.frames is not None for x in declared) else None), pid


@pytest.mark.parametrize("pid", [p for p in IDS if p != "eulers_disk"])
def test_the_forces_switch_lays_the_loads_on_the_stage_and_keeps_its_link(pid):
    """?forces=1 switches it on and the stage figure carries the overlay's arrows; off, none; the link
    says so as it changes."""
    import orjson

    from tests.pages.test_pages import shown
    from ui.figure import NAME

    def stage_names(at):
        spec = shown(at, NAME)[0]["spec"]
        spec = orjson.loads(spec) if isinstance(spec, (str, bytes)) else spec
        return [t.get("name", "") for t in spec["data"]]

    on = _page(pid, {"forces": "1"})
    assert shown(on, NAME)[0]["forces"] is True
    assert fbd.OVERLAY_NAME in stage_names(on)
    on.session_state[f"{pid}__forces"] = False  # (what the switch's press sets: its callback, ui/page._set_forces)
    on.run()
    assert shown(on, NAME)[0]["forces"] is False
    assert fbd.OVERLAY_NAME not in stage_names(on)
    assert "forces" not in on.query_params
    off = _page(pid)
    assert fbd.OVERLAY_NAME not in stage_names(off)


# --- directions by the physics, each problem's own ------------------------------------------------

def _load_vector(d, symbol: str, values, on: str | None = None) -> tuple[float, float]:
    load = next(l for l in d.loads if l.symbol == symbol and (on is None or l.on == on))
    return tuple(float(sp.sympify(c).subs(values)) for c in load.vector)


def _couple(d, symbol: str, values) -> float:
    return float(sp.sympify(next(l for l in d.loads if l.symbol == symbol).size).subs(values))


def _gravity_down(d, values) -> None:
    for load in d.loads:
        if load.by == "gravity":
            x, y = _load_vector(d, load.symbol, values, load.on)
            assert x == 0 and y < 0, (d.phase, load.symbol)


TOL = 1e-9


def _disk_wall(solution, d, v):
    p = solution.params
    x, y = _load_vector(d, "P", v)
    assert y <= 0  # the wall pushes the disk back, out of the wall (E_y points into it)
    slip = p["V"] * math.sin(p["theta"]) - p["R"] * p["omega"]  # B's slip velocity before, along E_x
    assert x * slip <= TOL * abs(y)  # friction opposes the slip it resists


def _sliding_ladder(solution, d, v):
    _gravity_down(d, v)
    assert _load_vector(d, "N_B", v)[1] >= -TOL * solution.params["m"] * solution.params["g"]  # the floor pushes up
    if d.phase == "both_contacts":
        assert _load_vector(d, "N_A", v)[0] >= 0  # the wall pushes away from itself, never pulls


def _driven_cart(solution, d, v):
    _gravity_down(d, v)
    weight = solution.params["m"] * solution.params["g"]
    for load in d.loads:
        x, y = _load_vector(d, load.symbol, v)
        if "normal" in load.name:
            assert x == 0 and y >= -TOL * weight  # the ground pushes up
        elif "traction" in load.name:
            assert y == 0 and x >= 0  # forward: the driven wheels push the cart ahead


def _pendulum_rebound(solution, d, v):
    if d.phase == "swing":
        _gravity_down(d, v)
        return
    x, y = _load_vector(d, r"\hat{P}", v)
    normal = (0, 1) if solution.params["surface"] == "floor" else (1, 0)  # out of the surface, into the sphere
    assert x * normal[0] + y * normal[1] >= 0 and x * normal[1] - y * normal[0] == 0


def _rod_disk_spring(solution, d, v):
    _gravity_down(d, v)
    twist = float(v[next(s for s in v if s.name == "theta")])  # clockwise +
    assert _couple(d, r"k\theta", v) * twist >= 0  # E_z +: anticlockwise, against the clockwise twist


def _stick_ball(solution, d, v):
    on_stick = _load_vector(d, "J", v, "the stick")
    on_ball = _load_vector(d, "J", v, "the ball")
    assert on_stick[0] > 0 and on_stick[1] == 0  # along the ball's approach: it pushes the stick forward
    assert on_ball == (-on_stick[0], -on_stick[1])


def _eulers_disk(solution, d, v):
    _gravity_down(d, v)
    friction, normal = _load_vector(d, "A", v)
    assert normal > 0 and abs(friction) <= 1e-12 * normal


DIRECTIONS = {"disk_wall": _disk_wall, "sliding_ladder": _sliding_ladder, "driven_cart": _driven_cart,
              "pendulum_rebound": _pendulum_rebound, "rod_disk_spring": _rod_disk_spring,
              "stick_ball": _stick_ball, "eulers_disk": _eulers_disk}


def test_every_problem_has_its_directions_tested():
    assert set(DIRECTIONS) == set(IDS)


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_directions_are_right_by_the_physics(pid, data):
    """A contact pushes out of its surface into the body and never pulls, friction opposes the slip,
    gravity points down, a spring's couple opposes its twist, an interaction pair is opposite: at the
    numbers the diagram is drawn for."""
    solver = registry.solver(pid)
    for solution in _solutions(pid, data.draw(VALID[pid])):
        for d in solver.free_body_diagrams(solution.params):
            DIRECTIONS[pid](solution, d, d.values(solution))
