"""Which control a benchmark moves on a problem's page: the lesson's first control, the first of
the problem's ABOUT.primary parameters that is a number (so a new problem is benchmarked with no
code here)."""
from __future__ import annotations

from solvers import registry, units
from solvers.core import Number
from ui.params import is_slider


def lesson_control(pid: str) -> tuple[str, float, str, float]:
    """(widget key, start value as the control shows it, "slider" or "number", step per change):
    a box moves up by half its step, a slider down by one step (it starts at the textbook's value,
    often at the top of what the lesson explores)."""
    solver = registry.solver(pid)
    specs = {p.name: p for p in solver.PARAMS}
    p = next(specs[name] for name in solver.ABOUT.primary if isinstance(specs.get(name), Number))
    start = units.to_display(p.default, p.dimension)
    step = p.step or 0.01
    if is_slider(p):
        return f"{pid}__si__{p.name}", start, "slider", -step
    return f"{pid}__si__{p.name}", start, "number", step / 2
