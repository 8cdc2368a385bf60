"""The problem's sketch (viz/sketch.py, each problem's ``sketch(params)``), which heads Practice, an
assignment's problem and a handout's statement: at hypothesis-drawn parameters it names only the givens
(with the statement table's symbols), the named points and the basis; it says no number and no answer;
it draws the start, not a later instant; and every label lies inside its picture, none on another."""
from __future__ import annotations

import math
import re

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from solvers import registry
from tests.strategies import valid
from viz.catalog import drawings
from viz.diagram import svg

IDS = registry.PROBLEM_IDS
VALID = {pid: valid(pid) for pid in IDS}


def _sketch(pid, params):
    solver = registry.solver(pid)
    try:
        solution = solver.solve(**params)
    except ValueError:
        return None, None
    return solution, drawings(pid).sketch(solution.params)


@pytest.mark.parametrize("pid", IDS)
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_the_sketch_names_the_givens_and_nothing_the_solution_would(pid, data):
    solution, sketch = _sketch(pid, data.draw(VALID[pid]))
    if sketch is None:
        return
    solver = registry.solver(pid)
    givens = {p.symbol for p in solver.PARAMS if hasattr(p, "symbol")}
    points = {name for d in solver.free_body_diagrams(solution.params) for b in d.bodies for name in b.points}
    texts = [label.tex for label in sketch.labels]
    marked = [t for t in texts if t not in points]
    basis = {t for t in marked if t.startswith(r"\mathbf")}
    assert set(marked) - basis <= givens, (pid, set(marked) - givens)
    assert set(marked) - basis, pid  # it marks some given
    answers = {a.symbol for a in solver.ANSWERS} | {a.symbol for a in getattr(solver, "answers_for", lambda r: ())(
        solution.regime)}
    assert not set(texts) & answers, pid
    assert not any(re.search(r"\d", t.replace("_0", "").replace("_1", "").replace("_2", "")) for t in texts), texts
    words = sketch.text
    assert not re.search(r"\d", re.sub(r"[θ][_₀-₉0-9]+|_[0-9]", "", words)), words  # no number in its words
    picture = svg(sketch)
    assert "NaN" not in picture and "inf" not in picture.lower()
    box = sketch.box
    labels = sketch.labels
    for i, label in enumerate(labels):
        b = label.box
        assert box.x0 <= b.x0 and b.x1 <= box.x1 and box.y0 <= b.y0 and b.y1 <= box.y1, (pid, label.tex)
        for other in labels[:i]:
            assert not b.overlaps(other.box), (pid, label.tex, other.tex)


def test_the_pendulum_s_sketch_is_at_its_release_not_its_impact():
    """Its rod at θ₀ (a given), not at the impact's angle (an answer)."""
    solution, sketch = _sketch("pendulum_rebound", {"theta0": math.radians(40)})
    (x0, y0, x1, y1), = sketch.rods
    assert math.degrees(math.atan2(y1 - y0, x1 - x0)) == pytest.approx(40, abs=0.01)
    assert math.degrees(solution.answers["theta_impact"]) < 0


def test_the_ladder_s_sketch_is_at_its_release():
    _, sketch = _sketch("sliding_ladder", {"theta0": math.radians(55)})
    (bx, by, ax, ay), = sketch.rods
    assert math.degrees(math.atan2(ay - by, bx - ax)) == pytest.approx(55, abs=0.01)
