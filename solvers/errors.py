"""The errors a solver raises, each a ValueError with a plain-words message: a parameter out of
its range, a combination the model cannot describe (a physical limit, carried as attributes for the
page to show), magnitudes the arithmetic cannot carry."""
from __future__ import annotations

import functools
from typing import Any, Callable


class ParameterError(ValueError):
    """A parameter is unknown, of the wrong type, not finite, or out of its allowed range."""


class PhysicalLimitError(ValueError):
    """The parameters are valid one by one, but the model cannot describe their combination.

    The limit the page should show is carried as attributes (e.g. ``mu_lift``, ``theta_max``),
    listed in ``limits`` as ``{name: value}`` (SI, radians).
    """

    def __init__(self, message: str, **limits: float):
        super().__init__(message)
        self.limits = dict(limits)
        for name, value in limits.items():
            setattr(self, name, value)


def require(condition: bool, message: str) -> None:
    """Raise a ParameterError with ``message`` unless ``condition`` holds (cross-parameter rules)."""
    if not condition:
        raise ParameterError(message)


class OutOfModelRangeError(ParameterError):
    """Each value is allowed, but together they overflow floating point (a length of 1e300 m
    squared, a mass ratio of 1e-300): no physics limit, just past what the numbers can carry."""


ARITHMETIC_FAILURES = (OverflowError, ZeroDivisionError, FloatingPointError)


def within_model_range(compute: Callable[..., Any]) -> Callable[..., Any]:
    """Wrap a solver's ``solve`` (or anything computed from its parameters) so that floating-point
    overflow or a division by an underflowed zero becomes a plain refusal, never a traceback."""
    @functools.wraps(compute)
    def guarded(*args, **kwargs):
        try:
            return compute(*args, **kwargs)
        except ARITHMETIC_FAILURES as error:
            raise OutOfModelRangeError(
                "These values are too large (or too small) for the model: the arithmetic "
                f"overflows ({type(error).__name__}). Use magnitudes closer to a real "
                "laboratory set-up, e.g. within a factor of a million of the defaults.") from None
    return guarded
