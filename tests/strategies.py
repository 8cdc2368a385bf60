"""Hypothesis strategies. Each problem's random *valid* parameters (SI, radians) are declared in its
own tests/physics/test_<pid>.py as ``VALID``; ``valid(pid)`` finds them for the tests every problem shares."""
from __future__ import annotations

import importlib

from hypothesis import strategies as st


def pos(lo, hi):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


def problem_tests(pid: str):
    """The problem's own test module, tests/physics/test_<pid>.py (its CONTRACT and VALID)."""
    return importlib.import_module(f"tests.physics.test_{pid}")


def valid(pid: str) -> st.SearchStrategy[dict]:
    return problem_tests(pid).VALID
