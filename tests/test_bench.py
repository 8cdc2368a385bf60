"""The benchmarks' own helpers (bench/): what they send must be what a class could send."""
from __future__ import annotations

import pytest

from bench.controls import changes_of, lesson_control
from bench.lecture_load import source_address
from solvers import registry, units
from ui.params import is_slider


@pytest.mark.parametrize("pid", registry.PROBLEM_IDS)
def test_a_benchmarks_changes_are_distinct_values_the_control_can_take(pid):
    key, start, kind, step = lesson_control(pid)
    p = next(p for p in registry.solver(pid).PARAMS if key.endswith(f"__{p.name}"))
    values = changes_of(pid, 30)
    assert len(set(values)) == len(values) and start not in values
    if is_slider(p):
        lo = p.ui_low if p.ui_low is not None else p.low
        hi = p.ui_high if p.ui_high is not None else p.high
        assert all(lo - 1e-9 <= v <= hi + 1e-9 for v in values)
        assert all(abs((v - start) / step - round((v - start) / step)) < 1e-6 for v in values)  # on its grid
        assert len(values) == min(30, round((hi - lo) / abs(step)))  # every position but the start, at most
    else:
        assert len(values) == 30
    for v in values:  # each solves: a refusal would be timed as a change
        registry.solver(pid).solve(**{p.name: units.to_si(v, p.dimension)})


def test_a_lectures_sessions_come_from_their_own_loopback_addresses():
    addresses = [source_address(n) for n in range(200)]
    assert len(set(addresses)) == 200
    assert all(a.startswith("127.0.0.") and a != "127.0.0.1" and 2 <= int(a.rsplit(".", 1)[1]) <= 254
               for a in addresses)
