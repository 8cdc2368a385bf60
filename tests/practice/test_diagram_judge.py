"""The free-body diagram judge (practice/diagram_judge.py) against each problem's own declaration:
every problem's diagram, drawn as declared (and a reaction of unknown direction as one load or as its
two components), is judged right at hypothesis-drawn parameters; every single change to a right
drawing (a load taken away, turned, moved, of the wrong kind, one added, and each declared slip) is
found and named, and the finding points at the load changed. The messages never show the diagram."""
from __future__ import annotations

import math
import re

import pytest
from hypothesis import HealthCheck, assume, given, settings, strategies as st

from practice.diagram_judge import (TOLERANCE_DEG, DrawnLoad, Unreadable, drawn_as_declared, exercise_diagram,
                                    judge, judge_problem, read_drawing)
from solvers import registry
from tests.strategies import valid

IDS = registry.PROBLEM_IDS
VALID = {pid: valid(pid) for pid in IDS}
SETTINGS = dict(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _case(pid, params):
    """Every diagram of the problem at ``params``: (solver, diagram, values); [] past a limit."""
    solver = registry.solver(pid)
    try:
        solution = solver.solve(**params)
    except ValueError:
        return []
    if not solution.answers:
        return []
    return [(solver, d, d.values(solution)) for d in solver.free_body_diagrams(solution.params)]


def _replaced(drawing, k, **change):
    d = drawing[k]
    new = DrawnLoad(**{**d.__dict__, **change})
    return drawing[:k] + (new,) + drawing[k + 1:]


def _fixed(diagram, values):
    """Indices (in drawn_as_declared's single-load form) of the loads whose direction the physics fixes."""
    return [i for i, load in enumerate(diagram.loads) if load.kind != "couple" and load.direction is not None]


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_each_problem_s_own_diagram_is_judged_right(pid, data):
    for solver, diagram, values in _case(pid, data.draw(VALID[pid])):
        for components in (False, True):
            verdict = judge(diagram, values, drawn_as_declared(diagram, values, components), solver.DIAGRAM_SLIPS)
            assert verdict.right and verdict.findings == (), (pid, diagram.phase, components, verdict)


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_a_load_taken_away_is_missing(pid, data):
    for solver, diagram, values in _case(pid, data.draw(VALID[pid])):
        right = drawn_as_declared(diagram, values)
        k = data.draw(st.integers(0, len(right) - 1))
        verdict = judge(diagram, values, right[:k] + right[k + 1:], solver.DIAGRAM_SLIPS)
        if len(right) == 1:
            assert not verdict.readable  # nothing left: not a drawing, costs no attempt
            continue
        assert not verdict.right and verdict.keys == ("missing",), verdict
        assert verdict.findings[0].drawn is None
        body = diagram.loads[k].on
        assert body in verdict.findings[0].message


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_a_load_turned_is_found_the_wrong_way(pid, data):
    for solver, diagram, values in _case(pid, data.draw(VALID[pid])):
        fixed = _fixed(diagram, values)
        if not fixed:
            continue
        right = drawn_as_declared(diagram, values)
        k = data.draw(st.sampled_from(fixed))
        turn = data.draw(st.floats(TOLERANCE_DEG + 1, 360 - TOLERANCE_DEG - 1))
        verdict = judge(diagram, values, _replaced(right, k, angle=right[k].angle + turn), solver.DIAGRAM_SLIPS)
        assert not verdict.right
        slips = {s.key for s in solver.DIAGRAM_SLIPS}  # (turned onto a classic slip: named as that slip)
        assert verdict.keys in ((key,) for key in ("wrong way", "other body's load of the pair")) or (
            verdict.keys[0] in slips and verdict.keys[1:] == ("missing",)), verdict  # (the load meant is then missing)
        assert verdict.findings[0].drawn == k
        if diagram.loads[k].pair and verdict.keys[0] not in slips:  # the other body's load: only the one reversed
            assert (verdict.keys == ("other body's load of the pair",)) == (abs(turn - 180) < TOLERANCE_DEG)


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_a_load_turned_within_the_tolerance_is_still_right(pid, data):
    for solver, diagram, values in _case(pid, data.draw(VALID[pid])):
        right = drawn_as_declared(diagram, values)
        k = data.draw(st.integers(0, len(right) - 1))
        turn = data.draw(st.floats(-TOLERANCE_DEG + 0.5, TOLERANCE_DEG - 0.5))
        assert judge(diagram, values, _replaced(right, k, angle=right[k].angle + turn), solver.DIAGRAM_SLIPS).right


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_a_load_moved_to_another_point_is_found_there(pid, data):
    for solver, diagram, values in _case(pid, data.draw(VALID[pid])):
        right = drawn_as_declared(diagram, values)
        movable = [i for i, d in enumerate(right) if d.kind != "couple"]
        k = data.draw(st.sampled_from(movable))
        body = diagram.body(right[k].body)
        others = [p for p in body.points if not p.startswith("_") and p != right[k].at]
        to = data.draw(st.sampled_from(others))
        verdict = judge(diagram, values, _replaced(right, k, at=to), solver.DIAGRAM_SLIPS)
        assert not verdict.right
        if any(l.on == body.name and l.at == to and l.direction is None for l in diagram.loads):
            # moved onto a reaction of unknown direction, it may be read as that reaction's other component:
            # then the load it was is the one missing
            assert verdict.findings, verdict
            continue
        about = [f for f in verdict.findings if f.drawn == k]
        assert about, verdict
        assert about[0].key in ("wrong point", "weight off the mass centre", "extra") or about[0].key in {
            s.key for s in solver.DIAGRAM_SLIPS}, verdict


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_a_load_of_the_wrong_kind_is_named(pid, data):
    for solver, diagram, values in _case(pid, data.draw(VALID[pid])):
        right = drawn_as_declared(diagram, values)
        k = data.draw(st.sampled_from([i for i, d in enumerate(right) if d.kind != "couple"]))
        other = {"force": "impulse", "impulse": "force"}[right[k].kind]
        verdict = judge(diagram, values, _replaced(right, k, kind=other), solver.DIAGRAM_SLIPS)
        assert verdict.keys == ("wrong kind",) and verdict.findings[0].drawn == k, verdict


@pytest.mark.parametrize("pid", IDS)
@settings(**SETTINGS)
@given(data=st.data())
def test_a_load_added_is_one_too_many(pid, data):
    for solver, diagram, values in _case(pid, data.draw(VALID[pid])):
        right = drawn_as_declared(diagram, values)
        body = data.draw(st.sampled_from(diagram.bodies))
        at = data.draw(st.sampled_from([p for p in body.points if not p.startswith("_")]))
        kind = "impulse" if diagram.law == "impulse" else "force"
        # (a second load where a reaction of unknown direction acts may be its other component: allowed)
        assume(not any(l.on == body.name and l.at == at and l.direction is None for l in diagram.loads))
        added = DrawnLoad(kind, body.name, at, data.draw(st.floats(0, 359.9)), "X")
        verdict = judge(diagram, values, right + (added,), solver.DIAGRAM_SLIPS)
        assert not verdict.right
        assert any(f.drawn is not None for f in verdict.findings), verdict
        keys = {"extra", "finite force in an impact", "wrong way", "other body's load of the pair"} | {
            s.key for s in solver.DIAGRAM_SLIPS}
        assert set(verdict.keys) <= keys, verdict


def _slip_cases():
    for pid in IDS:
        solver = registry.solver(pid)
        for n, slip in enumerate(solver.DIAGRAM_SLIPS):
            yield pytest.param(pid, n, id=f"{pid}-{slip.key}-{n}")


def _slip_params(pid, slip):
    """Parameters under which the slip's diagram is the one drawn (a drive, a surface)."""
    if pid == "driven_cart" and slip.phase:
        return {"drive": slip.phase}
    return {}


@pytest.mark.parametrize("pid,n", list(_slip_cases()))
def test_each_declared_slip_is_named(pid, n):
    solver = registry.solver(pid)
    slip = solver.DIAGRAM_SLIPS[n]
    cases = [c for c in _case(pid, _slip_params(pid, slip)) if not slip.phase or c[1].phase == slip.phase]
    assert cases, f"{pid}: no diagram for the slip {slip.key!r}"
    for _, diagram, values in cases:
        right = drawn_as_declared(diagram, values)
        body = diagram.body(slip.on) if slip.on else diagram.bodies[0]
        at = slip.at or body.centre
        if slip.direction is None:
            angle = 45.0
        else:
            x, y = (float(c.subs(values)) if hasattr(c, "subs") else float(c) for c in slip.direction)
            angle = math.degrees(math.atan2(y, x))
        added = DrawnLoad(slip.kinds[0], body.name, at, angle, "F")
        verdict = judge(diagram, values, right + (added,), solver.DIAGRAM_SLIPS)
        assert verdict.keys == (slip.key,) and verdict.findings[0].drawn == len(right), verdict
        assert slip.message in verdict.findings[0].message


def test_the_findings_quote_the_student_s_name_and_never_the_diagram_s_symbols():
    solver = registry.solver("sliding_ladder")
    diagram = exercise_diagram(solver, solver.solve())
    values = diagram.values(solver.solve())
    right = drawn_as_declared(diagram, values)
    wrong = (DrawnLoad("force", "the ladder", "B", 90.0, "Floor push"),
             DrawnLoad("force", "the ladder", "A", 180.0, "wall"),  # pulling toward the wall
             DrawnLoad("force", "the ladder", "B", 0.0, "f"))  # friction on the smooth floor
    verdict = judge(diagram, values, wrong, solver.DIAGRAM_SLIPS)
    assert verdict.keys == ("wrong way", "friction on a smooth surface", "missing")
    assert "“wall”" in verdict.findings[0].message and "“f”" in verdict.findings[1].message
    for f in verdict.findings:
        assert not re.search(r"\bN_[AB]\b|m g", f.message), f.message
    assert right  # the right drawing names N_A, N_B, m g: the messages above did not


def test_the_weights_of_a_body_s_parts_may_be_drawn_as_one_at_its_mass_centre():
    solver = registry.solver("rod_disk_spring")
    solution = solver.solve()
    diagram = exercise_diagram(solver, solution)
    values = diagram.values(solution)
    parts = [d for d in drawn_as_declared(diagram, values) if d.at not in ("G_1", "G_2")]
    one = DrawnLoad("force", "the rod and disk", "G", 270.0, "W")
    assert judge(diagram, values, parts + [one], solver.DIAGRAM_SLIPS).right
    # at the contact point instead: the weight away from its mass centre
    verdict = judge(diagram, values, parts + [DrawnLoad("force", "the rod and disk", "A", 270.0, "W")],
                    solver.DIAGRAM_SLIPS)
    assert "weight off the mass centre" in verdict.keys


@pytest.mark.parametrize("raw,why", [
    ("not a list", "list"),
    ([{"kind": "push", "body": "the ladder", "at": "G", "angle": 0}], "kind"),
    ([{"kind": "force", "body": "the wall", "at": "G", "angle": 0}], "body"),
    ([{"kind": "force", "body": "the ladder", "at": "Z", "angle": 0}], "named point"),
    ([{"kind": "force", "body": "the ladder", "at": "", "angle": 0}], "not placed"),
    ([{"kind": "force", "body": "the ladder", "at": "G", "angle": float("nan")}], "degrees"),
    ([{"kind": "force", "body": "the ladder", "at": "G", "angle": "1e999"}], "degrees"),
    ([{"kind": "force", "body": "the ladder", "at": "G", "angle": True}], "degrees"),
    ([{"kind": "force", "body": "the ladder", "at": "G", "angle": 0, "name": ["x"]}], "text"),
    ([{"kind": "force", "body": "the ladder", "at": "G", "angle": 0}] * 25, "at most"),
    ([7], "not a load"),
])
def test_an_unreadable_drawing_is_explained_and_not_judged(raw, why):
    verdict = judge_problem("sliding_ladder", {}, raw)
    assert not verdict.readable and not verdict.right and why in verdict.message
    solver = registry.solver("sliding_ladder")
    with pytest.raises(Unreadable):
        read_drawing(raw, exercise_diagram(solver, solver.solve()))


def test_an_empty_drawing_is_not_an_attempt():
    verdict = judge_problem("disk_wall", {}, [])
    assert not verdict.readable and "Nothing is drawn" in verdict.message


def test_a_hostile_name_is_kept_as_plain_text_and_cut():
    solver = registry.solver("sliding_ladder")
    diagram = exercise_diagram(solver, solver.solve())
    name = "<script>alert(1)</script>\x00" + "x" * 100
    drawn = read_drawing([{"kind": "force", "body": "the ladder", "at": "G", "angle": 270, "name": name}], diagram)
    assert drawn[0].name.startswith("<script>") and len(drawn[0].name) == 40 and "\x00" not in drawn[0].name


def test_the_python_api_reads_the_page_s_drawing():
    raw = [{"kind": "force", "body": "the ladder", "at": "G", "angle": -90, "name": "W"},
           {"kind": "force", "body": "the ladder", "at": "B", "angle": 90, "name": "N_B"},
           {"kind": "force", "body": "the ladder", "at": "A", "angle": 0, "name": "N_A"}]
    assert judge_problem("sliding_ladder", {"theta0": 1.0}, raw).right
    verdict = judge_problem("sliding_ladder", {}, raw[:2])
    assert verdict.keys == ("missing",) and "touches the ladder" in verdict.findings[0].message


def test_loads_left_out_that_would_read_alike_are_said_once_with_how_many():
    """The cart's two normal pushes left out: one line, "in two more ways", not the same line twice."""
    solver = registry.solver("driven_cart")
    solution = solver.solve()
    diagram = exercise_diagram(solver, solution)
    values = diagram.values(solution)
    drawn = [d for d in drawn_as_declared(diagram, values) if not d.called.startswith("“2N")]
    verdict = judge(diagram, values, drawn)
    assert verdict.keys == ("missing",), verdict
    assert "touches the cart in two more ways" in verdict.findings[0].message
    one_less = [d for d in drawn_as_declared(diagram, values) if not d.called.startswith("“2N_{\\mathrm{rear")]
    said = judge(diagram, values, one_less).findings[0].message
    assert "Something else touches the cart:" in said and "more ways" not in said


def test_a_pin_s_reaction_is_right_in_any_direction_or_as_two_perpendicular_components():
    solver = registry.solver("pendulum_rebound")
    solution = solver.solve()
    diagram = exercise_diagram(solver, solution)
    values = diagram.values(solution)
    floor = DrawnLoad("impulse", "the pendulum", "C", 90.0, "P")
    for angle in (0.0, 37.0, 200.0):
        assert judge(diagram, values, (floor, DrawnLoad("impulse", "the pendulum", "O", angle, "O"))).right
    pair = (DrawnLoad("impulse", "the pendulum", "O", 30.0, "O1"), DrawnLoad("impulse", "the pendulum", "O", 120.0, "O2"))
    assert judge(diagram, values, (floor, *pair)).right
    skew = (DrawnLoad("impulse", "the pendulum", "O", 30.0, "O1"), DrawnLoad("impulse", "the pendulum", "O", 80.0, "O2"))
    assert not judge(diagram, values, (floor, *skew)).right


@pytest.mark.parametrize("pid", IDS)
def test_the_blank_the_page_is_sent_shows_no_load(pid):
    """What the drawing exercise sends the browser (viz.diagram.blank) names every point and no load: no
    load's symbol, name or what exerts it, no arrow but the basis's, and the same for any parameters."""
    from viz.diagram import blank
    solver = registry.solver(pid)
    solution = solver.solve()
    diagram = exercise_diagram(solver, solution)
    sent = blank(diagram, diagram.values(solution))
    text = str(sent)
    bodies = {b.name for b in diagram.bodies}
    for load in diagram.loads:
        for word in (load.name, load.by):
            assert word in bodies or word not in text, (pid, word)
    named = {(b.name, n) for b in diagram.bodies for n in b.points if not n.startswith("_")}
    # the only words drawn: each named point's letter and the basis's two
    assert sent["svg"].count("<text") == len(named) + 2
    assert sent["svg"].count("<polygon") == 2 + sum(1 for b in diagram.bodies for s in b.outline
                                                   if type(s).__name__ == "Outline")  # the basis's two heads
    assert {(p["body"], p["name"]) for p in sent["points"]} == named


def test_a_drawing_of_many_perpendicular_loads_at_a_pin_is_judged_not_searched_forever():
    """24 loads at the pin, alternately along the basis's two vectors: many ways to pair them as components.
    The judge weighs a bounded number of pairings (MAX_PAIRS, and no more pairs than open reactions)."""
    raw = [{"kind": "impulse", "body": "the pendulum", "at": "O", "angle": (i % 2) * 90, "name": f"O{i}"}
           for i in range(24)]
    verdict = judge_problem("pendulum_rebound", {}, raw)
    assert not verdict.right and len(verdict.findings) == 22  # two are the pin's components; one, up, is the floor's at O
