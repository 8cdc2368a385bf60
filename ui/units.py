"""Display units. The solvers work in SI and radians; pages show degrees and, where the
textbook did, US customary units. Each dimension maps to (label, factor): display = SI × factor."""
from __future__ import annotations

import math

from solvers.core import plain_number as format_value  # noqa: F401  (one formatting for every page)

SI = {
    "mass": ("kg", 1.0),
    "length": ("m", 1.0),
    "angle": ("°", 180 / math.pi),
    "speed": ("m/s", 1.0),
    "angular_speed": ("rad/s", 1.0),
    "acceleration": ("m/s²", 1.0),
    "force": ("N", 1.0),
    "impulse": ("N·s", 1.0),
    "angular_momentum": ("kg·m²/s", 1.0),
    "energy": ("J", 1.0),
    "inertia": ("kg·m²", 1.0),
    "stiffness": ("N·m/rad", 1.0),
    "torque": ("N·m", 1.0),
    "time": ("s", 1.0),
    "dimensionless": ("", 1.0),
}
_LB, _FT, _LBF = 0.45359237, 0.3048, 4.4482216152605
US = SI | {
    "mass": ("lb", 1 / _LB),
    "length": ("ft", 1 / _FT),
    "speed": ("ft/s", 1 / _FT),
    "acceleration": ("ft/s²", 1 / _FT),
    "force": ("lbf", 1 / _LBF),
    "impulse": ("lbf·s", 1 / _LBF),
    "angular_momentum": ("ft·lbf·s", 1 / (_FT * _LBF)),
    "energy": ("ft·lbf", 1 / (_FT * _LBF)),
    "inertia": ("slug·ft²", 1 / (_LBF / _FT * _FT**2)),
    "stiffness": ("ft·lbf/rad", 1 / (_FT * _LBF)),
    "torque": ("ft·lbf", 1 / (_FT * _LBF)),
}
SYSTEMS = {"si": SI, "us": US}



def unit(dimension: str, system: str = "si") -> str:
    return SYSTEMS[system][dimension][0]


def to_display(x: float, dimension: str, system: str = "si") -> float:
    return x * SYSTEMS[system][dimension][1]


def to_si(x: float, dimension: str, system: str = "si") -> float:
    return x / SYSTEMS[system][dimension][1]


def format_quantity(x: float, dimension: str, system: str = "si", sig: int = 4) -> str:
    label = unit(dimension, system)
    value = format_value(to_display(x, dimension, system), sig)
    if not label:
        return value
    return f"{value}{label}" if label == "°" else f"{value} {label}"
