"""Parameter and answer specs: data, shared by validation here and by the controls in ui/."""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np

from . import units
from .errors import ParameterError


# How far from the textbook's value a magnitude may go: a laboratory's range (a gram to a tonne
# for a kilogram), and a bound on the work a link can ask of the time integrations.
MODEL_FACTOR = 1e3


@dataclass(frozen=True)
class Number:
    """A real-valued parameter, SI units, radians for angles.

    ``low``/``high`` bound the physically valid range (``None`` = unbounded) and the flags say
    whether each bound is allowed; they are in SI units and radians, as the value. ``ui_low``/
    ``ui_high``/``step`` give a control's range, in ``ui_unit``: the dimension's display unit in SI
    (degrees for angles, the SI unit otherwise); a lesson's slider spans them.
    """

    name: str
    default: float
    label: str
    dimension: str  # key into solvers.units.DIMENSIONS: mass, length, angle, speed, ...
    symbol: str  # LaTeX
    low: float | None = None
    high: float | None = None
    low_inclusive: bool = False
    high_inclusive: bool = False
    allow_inf: bool = False
    ui_low: float | None = None
    ui_high: float | None = None
    step: float | None = None
    help: str = ""
    # The control's top, at most this fraction of another parameter's value (s ≤ l/2: ("l", 0.5)), so
    # a slider spans only values that other parameter allows.
    ui_high_per: tuple[str, float] | None = None

    @property
    def ui_unit(self) -> str:
        """The unit ``ui_low``, ``ui_high`` and ``step`` are in ("°" for angles)."""
        return units.unit(self.dimension, "si")

    def range_text(self) -> str:
        """The allowed range in words, in the API's units (angles also in degrees)."""
        def show(v: float) -> str:
            if self.dimension == "angle":
                return f"{v:g} rad ({math.degrees(v):g}°)"
            return f"{v:g}"

        parts = []
        if self.low is not None:
            parts.append(("at least " if self.low_inclusive else "greater than ") + show(self.low))
        if self.high is not None:
            parts.append(("at most " if self.high_inclusive else "less than ") + show(self.high))
        text = " and ".join(parts) if parts else "any finite number"
        if self.allow_inf:
            text += ", or inf"
        return text

    def validate(self, value: Any) -> float:
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
            raise ParameterError(
                f"{self.name} ({self.label}) must be a number, not {type(value).__name__} "
                f"{value!r}; allowed: {self.range_text()}."
            )
        x = float(value)
        if math.isnan(x):
            raise ParameterError(f"{self.name} ({self.label}) is NaN; allowed: {self.range_text()}.")
        if math.isinf(x) and not (self.allow_inf and x > 0):
            raise ParameterError(
                f"{self.name} ({self.label}) must be finite; allowed: {self.range_text()}."
            )
        too_low = self.low is not None and (x < self.low or (x == self.low and not self.low_inclusive))
        too_high = self.high is not None and (
            x > self.high or (x == self.high and not self.high_inclusive)
        ) and not (math.isinf(x) and self.allow_inf)
        if too_low or too_high:
            shown = f"{x:g} rad ({math.degrees(x):g}°)" if self.dimension == "angle" else f"{x:g}"
            raise ParameterError(
                f"{self.name} ({self.label}) = {shown} is out of range: it must be {self.range_text()}."
            )
        bounds = self.model_bounds()
        if bounds and not (math.isinf(x) and self.allow_inf) and x != 0 and not bounds[0] <= abs(x) <= bounds[1]:
            raise ParameterError(
                f"{self.name} ({self.label}) = {x:g} is out of range for this model: it is meant for "
                f"magnitudes from {bounds[0]:g} to {bounds[1]:g} (a thousandth to a thousand times the "
                f"textbook's {self.default:g}); far beyond that the numbers say nothing about a real "
                "set-up and the time integrations cannot follow the motion in reasonable time."
            )
        return x

    def model_bounds(self) -> tuple[float, float] | None:
        """The magnitudes the model is meant for: within ``MODEL_FACTOR`` of the textbook's value
        (a strictly positive parameter also from below). None for angles (their ranges bound
        them) and for a parameter whose default is 0 or infinite."""
        d = abs(self.default)
        if self.dimension == "angle" or d == 0 or math.isinf(d):
            return None
        positive = self.low == 0 and not self.low_inclusive
        return (d / MODEL_FACTOR if positive else 0.0, d * MODEL_FACTOR)


@dataclass(frozen=True)
class Choice:
    """A parameter that takes one of a few exact lowercase strings."""

    name: str
    default: str
    label: str
    options: tuple[str, ...]
    option_labels: tuple[str, ...] = ()
    help: str = ""

    def validate(self, value: Any) -> str:
        if not isinstance(value, str) or value not in self.options:
            allowed = ", ".join(repr(o) for o in self.options)
            raise ParameterError(
                f"{self.name} ({self.label}) must be one of {allowed}, not {value!r}."
            )
        return value

    def label_of(self, option: str) -> str:
        labels = self.option_labels or self.options
        return dict(zip(self.options, labels))[option]


Param = Number | Choice


@dataclass(frozen=True)
class Answer:
    """How an answer is named, written and measured (for pages and the numeric steps)."""

    name: str
    label: str
    symbol: str  # LaTeX
    dimension: str

    @property
    def heading(self) -> str:
        """The label as a heading or a list item: its first letter capitalised, the rest as written (cm,
        v_cm, I_O, G)."""
        return self.label[:1].upper() + self.label[1:]


def validate_params(spec: Sequence[Param], given: Mapping[str, Any]) -> dict[str, Any]:
    """Check names, types and ranges; return every parameter with defaults filled in."""
    known = {p.name for p in spec}
    unknown = [k for k in given if k not in known]
    if unknown:
        raise ParameterError(
            f"unknown parameter{'s' if len(unknown) > 1 else ''} "
            f"{', '.join(repr(k) for k in unknown)}; this problem takes: "
            f"{', '.join(p.name for p in spec)}."
        )
    return {p.name: p.validate(given.get(p.name, p.default)) for p in spec}
