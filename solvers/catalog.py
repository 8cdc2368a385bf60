"""The problems as the app lists them, in registry order: each problem's id with what its solver
module's ABOUT declares (title, method group, one line, display options)."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from types import ModuleType

from solvers import registry
from solvers.protocol import About


@dataclass(frozen=True)
class Problem(About):
    id: str = field(kw_only=True)

    @property
    def solver(self) -> ModuleType:
        return registry.solver(self.id)

    @property
    def page_path(self) -> str:
        return f"app_pages/{self.id}.py"

    def answers_of(self, solution) -> tuple:
        """The answers a solution shows: its regime's (``answers_for``), where the problem has them."""
        picker = getattr(self.solver, "answers_for", None)
        return picker(solution.regime) if picker else self.solver.ANSWERS


PROBLEMS = tuple(Problem(**dataclasses.asdict(registry.solver(pid).ABOUT), id=pid) for pid in registry.PROBLEM_IDS)
BY_ID = {p.id: p for p in PROBLEMS}
GROUPS = tuple(dict.fromkeys(p.group for p in PROBLEMS))  # in the order of each group's first problem
