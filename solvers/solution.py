"""The Solution record a solver returns: answers, the derivation's steps, the checks by a second
method, the ledger across an impact."""
from __future__ import annotations

import functools
import weakref
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, Callable, Mapping

import numpy as np


# The course's four steps (the worked solutions' method): every derivation step belongs to one.
PARTS = {
    1: "Step 1: origin, coordinates and basis; the kinematics",
    2: "Step 2: the free-body diagram",
    3: "Step 3: the balance laws, written from the diagram",
    4: "Step 4: the analysis",
}


@dataclass(frozen=True)
class Step:
    title: str
    latex: str
    numeric: bool = False  # the step puts in the numbers (hidden while a student practises)
    part: int = 4  # which of the course's four steps (PARTS) it belongs to; the numbers are the analysis


@dataclass(frozen=True)
class Check:
    """One line of the conservation ledger: a closed-form value and an independent second method.

    ``tolerance`` is absolute, so a quantity whose true value is zero is checked fairly.
    """

    name: str
    closed_form: float
    second_method: float
    tolerance: float
    explanation: str = ""

    def __post_init__(self):
        for name in ("closed_form", "second_method", "tolerance"):
            object.__setattr__(self, name, float(getattr(self, name)))

    @property
    def ok(self) -> bool:
        return bool(abs(self.closed_form - self.second_method) <= self.tolerance)


@dataclass(frozen=True)
class LedgerRow:
    """Before and after an impact: is the quantity conserved, and why (or why not)."""

    quantity: str
    before: float
    after: float
    dimension: str
    why: str

    @property
    def conserved(self) -> bool:
        return abs(self.after - self.before) <= 1e-9 * max(abs(self.before), abs(self.after), 1e-300)


@dataclass(frozen=True)
class Solution:
    problem: str
    params: Mapping[str, Any]
    answers: Mapping[str, float]
    steps: tuple[Step, ...]
    checks: tuple[Check, ...] = ()
    regime: str = ""
    notes: tuple[str, ...] = ()
    ledger: tuple[LedgerRow, ...] = ()
    extras: Mapping[str, Any] = field(default_factory=dict)
    symbolic_steps: int = -1  # how many leading steps are symbolic (the rest put in the numbers)

    def __post_init__(self):
        if self.symbolic_steps < 0:
            count = next((i for i, s in enumerate(self.steps) if s.numeric), len(self.steps))
            object.__setattr__(self, "symbolic_steps", count)
        object.__setattr__(self, "answers", MappingProxyType({k: float(v) for k, v in self.answers.items()}))
        object.__setattr__(self, "params", MappingProxyType(dict(self.params)))


def relative_tolerance(value: float, rel: float = 1e-9, floor: float = 1e-12) -> float:
    """An absolute tolerance scaled to ``value``, never zero."""
    return max(abs(value) * rel, floor)


def per_solution(fn: Callable) -> Callable:
    """``fn(solution, ...)`` computed once per Solution object and arguments, while the solution lives: a
    run asks for a motion up to three times (the stage's figure, a free-body diagram drawn at one of its
    frames, the Forces overlay), and each student's own values make a new solution every change, which a
    cache keyed by values would only fill. The result is shared, so its arrays are made read-only."""
    results: dict[tuple, tuple[weakref.ref, Any]] = {}

    @functools.wraps(fn)
    def once(solution, *args, **kwargs):
        key = (id(solution), args, tuple(sorted(kwargs.items())))
        hit = results.get(key)
        if hit is not None and hit[0]() is solution:
            return hit[1]
        value = fn(solution, *args, **kwargs)
        for array in (value.values() if isinstance(value, dict) else value if isinstance(value, tuple) else ()):
            if isinstance(array, np.ndarray):
                array.flags.writeable = False
        results[key] = (weakref.ref(solution, lambda _, key=key: results.pop(key, None)), value)
        return value
    return once
