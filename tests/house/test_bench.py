"""The benchmarks' own helpers (bench/): what they send must be what a class could send."""
from __future__ import annotations

import pytest

from bench.controls import changes_of, lesson_control
from bench.lecture_load import source_address
from solvers import registry, units


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_a_benchmarks_changes_are_distinct_values_the_control_can_take(pid):
    """Each change is a value the page's own slider (as the page draws it) can be dragged to."""
    from tests.pages.test_pages import run_page

    key, start, kind, step = lesson_control(pid)
    p = next(p for p in registry.solver(pid).PARAMS if key.endswith(f"__{p.name}"))
    slider = next(e for e in run_page(pid).main if getattr(e, "key", None) == key).proto
    assert kind == "slider" and abs(step) == pytest.approx(slider.step)
    values = changes_of(pid, 30)
    assert len(set(values)) == len(values) and start not in values
    assert all(slider.min - 1e-9 <= v <= slider.max + 1e-9 for v in values)
    assert all(abs((v - slider.min) / slider.step - round((v - slider.min) / slider.step)) < 1e-6 for v in values)  # on its grid
    assert len(values) == min(30, round((slider.max - slider.min) / slider.step))  # every position but the start, at most
    for v in values:  # each solves: a refusal would be timed as a change
        registry.solver(pid).solve(**{p.name: units.to_si(v, p.dimension)})


def test_a_lectures_sessions_come_from_their_own_loopback_addresses():
    addresses = [source_address(n) for n in range(200)]
    assert len(set(addresses)) == 200
    assert all(a.startswith("127.0.0.") and a != "127.0.0.1" and 2 <= int(a.rsplit(".", 1)[1]) <= 254
               for a in addresses)
