"""Shared machinery of the solvers, under one name: ``from solvers.core import X`` works for every
piece a problem module uses. Nothing here knows any physics; each problem module declares its
parameters, derives its equations once per process with sympy, and hands the result chain to
:class:`Derivation`.

The pieces live in their own modules:

- ``errors``: ParameterError, PhysicalLimitError, OutOfModelRangeError, ``require``,
  ``within_model_range``
- ``specs``: the parameter and answer specs (Number, Choice, Answer) and ``validate_params``
- ``solution``: the Solution record (Step, Check, LedgerRow, Solution), ``per_solution``
- ``derivation``: the derivation chain (Result, Derivation, ``latex``, ``latex_eq``, ``presentable``,
  ``root_with_sign``)
- ``formatting`` and ``units``: numbers as plain text and LaTeX, and quantities with their units
"""
from __future__ import annotations

from .derivation import Derivation, Result, as_written, latex, latex_eq, presentable, root_with_sign
from .errors import (ARITHMETIC_FAILURES, OutOfModelRangeError, ParameterError, PhysicalLimitError, require,
                     within_model_range)
from .formatting import latex_number, plain_fixed, plain_number
from .solution import Check, LedgerRow, Solution, Step, per_solution, relative_tolerance
from .specs import Answer, Choice, Number, Param, validate_params
from .units import latex_quantity

__all__ = [
    "ARITHMETIC_FAILURES", "Answer", "Check", "Choice", "Derivation", "LedgerRow", "Number",
    "OutOfModelRangeError", "Param", "ParameterError", "PhysicalLimitError", "Result", "Solution", "Step",
    "as_written", "latex", "latex_eq", "latex_number", "latex_quantity", "per_solution", "plain_fixed", "plain_number", "presentable", "relative_tolerance",
    "require", "root_with_sign", "validate_params", "within_model_range",
]
