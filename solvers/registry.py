"""The problems, in the order the home page lists them within a group: the one list of their ids.

Everything else (app, pages, practice, server warm-up, tests, benchmarks) iterates over
``PROBLEM_IDS``. A problem's viz module is found by convention, ``viz.<pid>``: solvers/ never
imports viz/.
"""
from __future__ import annotations

import importlib
from types import ModuleType

PROBLEM_IDS: tuple[str, ...] = (
    "disk_wall",
    "stick_ball",
    "pendulum_rebound",
    "rod_disk_spring",
    "driven_cart",
    "eulers_disk",
    "sliding_ladder",
)


def solver(pid: str) -> ModuleType:
    """The problem's solver module, ``solvers.<pid>``; KeyError for an id not registered."""
    if pid not in PROBLEM_IDS:
        raise KeyError(f"{pid!r} is not a registered problem; registered: {', '.join(PROBLEM_IDS)}")
    return importlib.import_module(f"solvers.{pid}")


def solvers() -> tuple[ModuleType, ...]:
    """Every registered problem's solver module, in registry order."""
    return tuple(solver(pid) for pid in PROBLEM_IDS)
