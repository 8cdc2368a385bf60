"""Which control a benchmark moves on a problem's page: the lesson's first control, the first of
the problem's ABOUT.primary parameters that is a number (so a new problem is benchmarked with no
code here)."""
from __future__ import annotations

from solvers import registry, units
from solvers.core import Number
from ui.params import slider_range


def lesson_control(pid: str) -> tuple[str, float, str, float]:
    """(widget key, start value as the control shows it, "slider", step per change): every number
    of the lesson is a slider (ui.params), moved down by one step (it starts at the textbook's value,
    often at the top of what the lesson explores)."""
    p = first_number(pid)
    return f"{pid}__si__{p.name}", units.to_display(p.default, p.dimension), "slider", -slider_range(p, "si")[2]


def first_number(pid: str) -> Number:
    solver = registry.solver(pid)
    specs = {p.name: p for p in solver.PARAMS}
    return next(specs[name] for name in solver.ABOUT.primary if isinstance(specs.get(name), Number))


def changes_of(pid: str, count: int) -> list[float]:
    """Up to ``count`` distinct values for the lesson control, as a student's moves give them: a
    slider along its own grid (the only values a drag gives),
    first away from the start in the step's direction, then, past the slider's end, on the other
    side of the start. Never the start itself, never out of the slider's range: a slider with fewer
    positions than ``count`` gives all it has."""
    key, start, kind, step = lesson_control(pid)
    lo, hi, _ = slider_range(first_number(pid), "si")  # as ui.params draws it
    inside = lambda v: lo - 1e-9 <= v <= hi + 1e-9  # noqa: E731
    ahead = [v for v in (round(start + step * i, 6) for i in range(1, count + 1)) if inside(v)]
    behind = [v for v in (round(start - step * i, 6) for i in range(1, count + 1)) if inside(v)]
    return (ahead + behind)[:count]
