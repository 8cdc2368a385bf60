"""Units a student may write after a number, by dimension: every accepted spelling with its size in
SI units. Spellings are case-sensitive, as in print: MJ is a megajoule and mJ a millijoule, mN a
millinewton and Nm a newton metre. A spelling may mean different things in different dimensions
(g: a gram for a mass, standard gravity for an acceleration; lb: a pound of mass or of force), so
a unit is looked up together with the dimension of the answer it goes with.

Written as data below ``solvers/`` so that it can grow into the one units module of the project
(labels, LaTeX and display factors, now in ``ui/units.py``)."""
from __future__ import annotations

import math
import re

LB = 0.45359237  # kg
FT = 0.3048  # m
INCH = 0.0254  # m
LBF = LB * 9.80665  # N
SLUG = LBF / FT  # kg
G0 = 9.80665  # m/s², standard gravity
DEG = math.pi / 180

# dimension -> {spelling (normalised: no spaces, no multiplication signs, powers as ^2): SI per unit}
SPELLINGS: dict[str, dict[str, float]] = {
    "angle": {"rad": 1.0, "deg": DEG, "°": DEG, "degree": DEG, "degrees": DEG},
    "angular_speed": {"rad/s": 1.0, "rad/sec": 1.0, "1/s": 1.0, "/s": 1.0, "deg/s": DEG, "°/s": DEG, "rpm": math.pi / 30,
                      "rev/min": math.pi / 30, "rev/s": 2 * math.pi},
    "speed": {"m/s": 1.0, "cm/s": 0.01, "mm/s": 1e-3, "km/s": 1e3, "km/h": 1 / 3.6, "ft/s": FT, "ft/sec": FT,
              "in/s": INCH, "mph": 1609.344 / 3600},
    "acceleration": {"m/s^2": 1.0, "cm/s^2": 0.01, "mm/s^2": 1e-3, "ft/s^2": FT, "in/s^2": INCH, "g": G0},
    "force": {"N": 1.0, "kN": 1e3, "mN": 1e-3, "MN": 1e6, "lbf": LBF, "lb": LBF, "kip": 1000 * LBF},
    "impulse": {"Ns": 1.0, "kNs": 1e3, "mNs": 1e-3, "kgm/s": 1.0, "lbfs": LBF, "lbs": LBF,
                "slugft/s": SLUG * FT},
    "angular_momentum": {"kgm^2/s": 1.0, "Nms": 1.0, "Js": 1.0, "ftlbfs": FT * LBF,
                         "lbffts": FT * LBF, "slugft^2/s": SLUG * FT**2},
    "energy": {"J": 1.0, "kJ": 1e3, "mJ": 1e-3, "MJ": 1e6, "Nm": 1.0, "kNm": 1e3, "ftlbf": FT * LBF,
               "ftlb": FT * LBF, "lbft": FT * LBF, "lbfft": FT * LBF},
    "torque": {"Nm": 1.0, "kNm": 1e3, "mNm": 1e-3, "J": 1.0, "ftlbf": FT * LBF, "ftlb": FT * LBF,
               "lbft": FT * LBF, "lbfft": FT * LBF},
    "stiffness": {"Nm/rad": 1.0, "Nm": 1.0, "ftlbf/rad": FT * LBF, "ftlb/rad": FT * LBF, "lbft/rad": FT * LBF},
    "inertia": {"kgm^2": 1.0, "gcm^2": 1e-7, "slugft^2": SLUG * FT**2, "lbft^2": LB * FT**2,
                "lbin^2": LB * INCH**2},
    "length": {"m": 1.0, "cm": 0.01, "mm": 1e-3, "km": 1e3, "ft": FT, "in": INCH},
    "mass": {"kg": 1.0, "g": 1e-3, "mg": 1e-6, "lb": LB, "slug": SLUG},
    "time": {"s": 1.0, "ms": 1e-3, "sec": 1.0, "min": 60.0},
    "dimensionless": {},
}


def normalise(text: str) -> str:
    """The spelling a unit is looked up by: spaces, ·, ⋅, * and - between factors dropped, ² and
    **2 as ^2, a trailing full stop dropped. Case is kept."""
    t = re.sub(r"[\s·⋅*\-]", "", text.replace("**", "^"))
    return t.replace("²", "^2").replace("³", "^3").rstrip(".")


def si_per_unit(text: str, dimension: str) -> float | None:
    """SI units per one ``text`` for an answer of ``dimension`` (None if not a unit of it)."""
    return SPELLINGS.get(dimension, {}).get(normalise(text))


def dimensions_of(text: str) -> list[str]:
    """Every dimension in which ``text`` is a unit (to say what a misplaced unit measures)."""
    key = normalise(text)
    return [d for d, table in SPELLINGS.items() if key in table]


def close_spellings(text: str) -> list[str]:
    """Accepted spellings equal to ``text`` but for case (kn for kN), across all dimensions."""
    key = normalise(text).lower()
    return sorted({s for table in SPELLINGS.values() for s in table if s.lower() == key and s != normalise(text)})
