"""The one units module: for each dimension, the unit pages show in SI and in US customary units
(label and factor), the SI unit in LaTeX as the derivation's numbers carry it, and every spelling a
student may type after a number with its size in SI units.

The solvers work in SI and radians. Pages show degrees for angles and, where the textbook did, US
customary units: shown = SI value × factor. ``Number.ui_low``/``ui_high``/``step`` are in the SI
display unit (``unit(dimension)``: degrees for angles, SI otherwise).

Spellings are case-sensitive, as in print: MJ is a megajoule and mJ a millijoule, mN a millinewton
and Nm a newton metre. A spelling may mean different things in different dimensions (g: a gram for
a mass, standard gravity for an acceleration; lb: a pound of mass or of force), so a unit is looked
up together with the dimension of the answer it goes with.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping

from .formatting import latex_number, plain_number

LB = 0.45359237  # kg
FT = 0.3048  # m
INCH = 0.0254  # m
G0 = 9.80665  # m/s², standard gravity
LBF = LB * G0  # N
SLUG = LBF / FT  # kg
DEG = math.pi / 180
FT_LBF = FT * LBF  # J (or N·m)


@dataclass(frozen=True)
class Dimension:
    label: str  # the unit pages show in SI ("°" for angles: pages show degrees)
    factor: float  # shown = SI value × factor
    latex: str  # the SI unit in LaTeX, as the derivation's substituted numbers carry it (rad for angles)
    # What a student may type after a number -> SI units per one of it (normalised: no spaces, no
    # multiplication signs, powers as ^2).
    spellings: Mapping[str, float]
    us_label: str | None = None  # the US customary unit pages show; None: as in SI
    us_factor: float | None = None
    mlt: tuple[int, int, int] = (0, 0, 0)  # the powers of mass, length and time in it (an angle: none)


DIMENSIONS: Mapping[str, Dimension] = MappingProxyType({
    "mass": Dimension("kg", 1.0, r"\mathrm{kg}", {"kg": 1.0, "g": 1e-3, "mg": 1e-6, "lb": LB, "slug": SLUG},
                      "lb", 1 / LB, mlt=(1, 0, 0)),
    "length": Dimension("m", 1.0, r"\mathrm{m}", {"m": 1.0, "cm": 0.01, "mm": 1e-3, "km": 1e3, "ft": FT, "in": INCH},
                        "ft", 1 / FT, mlt=(0, 1, 0)),
    "angle": Dimension("°", 180 / math.pi, r"\mathrm{rad}",
                       {"rad": 1.0, "deg": DEG, "°": DEG, "degree": DEG, "degrees": DEG}),
    "speed": Dimension("m/s", 1.0, r"\mathrm{m/s}",
                       {"m/s": 1.0, "cm/s": 0.01, "mm/s": 1e-3, "km/s": 1e3, "km/h": 1 / 3.6, "ft/s": FT,
                        "ft/sec": FT, "in/s": INCH, "mph": 1609.344 / 3600},
                       "ft/s", 1 / FT, mlt=(0, 1, -1)),
    "angular_speed": Dimension("rad/s", 1.0, r"\mathrm{rad/s}",
                               {"rad/s": 1.0, "rad/sec": 1.0, "1/s": 1.0, "/s": 1.0, "deg/s": DEG, "°/s": DEG,
                                "rpm": math.pi / 30, "rev/min": math.pi / 30, "rev/s": 2 * math.pi}, mlt=(0, 0, -1)),
    "acceleration": Dimension("m/s²", 1.0, r"\mathrm{m/s^2}",
                              {"m/s^2": 1.0, "cm/s^2": 0.01, "mm/s^2": 1e-3, "ft/s^2": FT, "in/s^2": INCH, "g": G0},
                              "ft/s²", 1 / FT, mlt=(0, 1, -2)),
    "force": Dimension("N", 1.0, r"\mathrm{N}",
                       {"N": 1.0, "kN": 1e3, "mN": 1e-3, "MN": 1e6, "kgm/s^2": 1.0, "lbf": LBF, "lb": LBF, "kip": 1000 * LBF},
                       "lbf", 1 / LBF, mlt=(1, 1, -2)),
    "impulse": Dimension("N·s", 1.0, r"\mathrm{N\,s}",
                         {"Ns": 1.0, "kNs": 1e3, "mNs": 1e-3, "kgm/s": 1.0, "lbfs": LBF, "lbs": LBF,
                          "slugft/s": SLUG * FT},
                         "lbf·s", 1 / LBF, mlt=(1, 1, -1)),
    "angular_momentum": Dimension("kg·m²/s", 1.0, r"\mathrm{kg\,m^2/s}",
                                  {"kgm^2/s": 1.0, "Nms": 1.0, "Js": 1.0, "ftlbfs": FT_LBF, "lbffts": FT_LBF,
                                   "slugft^2/s": SLUG * FT**2},
                                  "ft·lbf·s", 1 / FT_LBF, mlt=(1, 2, -1)),
    "energy": Dimension("J", 1.0, r"\mathrm{J}",
                        {"J": 1.0, "kJ": 1e3, "mJ": 1e-3, "MJ": 1e6, "Nm": 1.0, "kNm": 1e3, "kgm^2/s^2": 1.0, "ftlbf": FT_LBF,
                         "ftlb": FT_LBF, "lbft": FT_LBF, "lbfft": FT_LBF},
                        "ft·lbf", 1 / FT_LBF, mlt=(1, 2, -2)),
    "inertia": Dimension("kg·m²", 1.0, r"\mathrm{kg\,m^2}",
                         {"kgm^2": 1.0, "gcm^2": 1e-7, "slugft^2": SLUG * FT**2, "lbft^2": LB * FT**2,
                          "lbin^2": LB * INCH**2},
                         "slug·ft²", 1 / (SLUG * FT**2), mlt=(1, 2, 0)),
    "stiffness": Dimension("N·m/rad", 1.0, r"\mathrm{N\,m/rad}",
                           {"Nm/rad": 1.0, "Nm": 1.0, "ftlbf/rad": FT_LBF, "ftlb/rad": FT_LBF, "lbft/rad": FT_LBF},
                           "ft·lbf/rad", 1 / FT_LBF, mlt=(1, 2, -2)),
    "torque": Dimension("N·m", 1.0, r"\mathrm{N\,m}",
                        {"Nm": 1.0, "kNm": 1e3, "mNm": 1e-3, "J": 1.0, "kgm^2/s^2": 1.0, "ftlbf": FT_LBF, "ftlb": FT_LBF,
                         "lbft": FT_LBF, "lbfft": FT_LBF},
                        "ft·lbf", 1 / FT_LBF, mlt=(1, 2, -2)),
    "time": Dimension("s", 1.0, r"\mathrm{s}", {"s": 1.0, "ms": 1e-3, "sec": 1.0, "min": 60.0}, mlt=(0, 0, 1)),
    "dimensionless": Dimension("", 1.0, "", {}),
})

# Views of the table by unit system and by dimension (for code that walks them).
SYSTEMS = MappingProxyType({
    "si": MappingProxyType({name: (d.label, d.factor) for name, d in DIMENSIONS.items()}),
    "us": MappingProxyType({name: (d.us_label, d.us_factor) if d.us_label is not None else (d.label, d.factor)
                            for name, d in DIMENSIONS.items()}),
})
SPELLINGS = MappingProxyType({name: d.spellings for name, d in DIMENSIONS.items()})


# --------------------------------------------------------------------------------------------
# Showing a quantity


def unit(dimension: str, system: str = "si") -> str:
    """The unit a page shows for ``dimension`` in ``system`` ("si" or "us")."""
    return SYSTEMS[system][dimension][0]


def mlt(dimension: str) -> tuple[int, int, int]:
    """The powers of mass, length and time in ``dimension`` (an angle and a ratio: none)."""
    return DIMENSIONS[dimension].mlt


def si_units_of(powers) -> str:
    """Powers of mass, length and time written in SI base units, as the pages write units: kg·m²/s², 1/s, m^(1/2)."""
    def power(symbol, n):
        n = abs(n)
        return symbol + ({1: "", 2: "²", 3: "³", 4: "⁴"}.get(n) if n in (1, 2, 3, 4) else f"^({n})" if "/" in str(n) else f"^{n}")
    up = [power(u, n) for u, n in zip(("kg", "m", "s"), powers) if n > 0]
    down = [power(u, n) for u, n in zip(("kg", "m", "s"), powers) if n < 0]
    below = "·".join(down) if len(down) < 2 else "(" + "·".join(down) + ")"  # 1/(m·s), not 1/m·s
    return ("·".join(up) or "1") + ("/" + below if down else "") if up or down else "1"


def to_display(x: float, dimension: str, system: str = "si") -> float:
    return x * SYSTEMS[system][dimension][1]


def to_si(x: float, dimension: str, system: str = "si") -> float:
    return x / SYSTEMS[system][dimension][1]


# The solvers keep a textbook's values to four figures in SI (4.536 kg for 10 lb, 1.814 kg for
# 4 lb): converted back, they differ from the round value by up to half a unit in the fourth figure.
CONVERSION_NOISE = 5e-4  # relative


def shown_value(x: float, dimension: str, system: str = "si") -> float:
    """``x`` (SI) as a control shows it in ``system``: where a conversion happens, the shortest
    decimal within ``CONVERSION_NOISE`` of the converted value (10 lb, not 10.0002 lb; 32.2 ft/s²,
    not 32.185), so a unit switch shows the quantity a person would type; unconverted, as it is."""
    factor = SYSTEMS[system][dimension][1]
    shown = x * factor
    if factor == 1.0 or not math.isfinite(shown) or shown == 0:
        return shown
    for figures in range(1, 7):
        rounded = float(f"{shown:.{figures}g}")
        if abs(rounded - shown) <= CONVERSION_NOISE * abs(shown):
            return rounded
    return shown


format_value = plain_number  # one formatting of numbers for every page


def format_quantity(x: float, dimension: str, system: str = "si", sig: int = 4) -> str:
    """``x`` (SI) as a page shows it: in the system's unit, ``sig`` figures, degrees glued (30°)."""
    return with_unit(format_value(to_display(x, dimension, system), sig), dimension, system)


def with_unit(value: str, dimension: str, system: str = "si") -> str:
    """A number already written in the system's unit (``value``), with that unit: degrees glued (30°)."""
    label = unit(dimension, system)
    if not label:
        return value
    return f"{value}{label}" if label == "°" else f"{value} {label}"


def latex_quantity(x: float, dimension: str, sig: int = 4) -> str:
    """``x`` (SI) in LaTeX with its SI unit, as a derivation's substituted step ends (an angle also
    in degrees)."""
    dim = DIMENSIONS.get(dimension)
    text = latex_number(x, sig) + (rf"\;{dim.latex}" if dim and dim.latex else "")
    if dimension == "angle" and math.isfinite(x):
        text += rf"\;\left({latex_number(math.degrees(x), sig)}^{{\circ}}\right)"
    return text


# --------------------------------------------------------------------------------------------
# Reading a unit a student typed


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


# The simple units every spelling is made of (kg, m, s, N, ft, lbf…), and the hertz, which no answer here is
# in: a unit made of them but of another kind (kg·m for an inertia) is the wrong kind, not a typo.
SIMPLE_UNITS = frozenset({s for table in SPELLINGS.values() for s in table if re.fullmatch(r"[A-Za-z°]+", s)}
                         | {"Hz", "kHz"})


def made_of_units(text: str) -> bool:
    """Whether ``text`` is a product or quotient of simple units, each maybe to a power (kg·m, N/s, 1/s^2)."""
    pieces = re.split(r"[\s·⋅*/]+", re.sub(r"(\^|\*\*)-?\d+|[²³]", "", text.strip().rstrip(".")))
    return bool(pieces) and all(p in SIMPLE_UNITS or p == "1" for p in pieces) and any(p != "1" for p in pieces)


def written(text: str) -> str:
    """A unit as typed, written as the pages write units: the factors the student separated joined by ·,
    powers 2 and 3 as ² and ³, no spaces around / ("kg*m^2", "kg m**2": kg·m²; "ft / s": ft/s; "N-m": N·m).
    Letters typed together stay together (kgm^2: kgm²): which units they are is not this function's guess."""
    t = re.sub(r"\s*([/^])\s*", r"\1", text.strip().rstrip(".").replace("**", "^"))
    t = re.sub(r"(?<=[A-Za-z°²³\d])\s*-\s*(?=[A-Za-z°])|\s*[*·⋅]\s*|\s+", "·", t)
    return re.sub(r"\^([23])(?!\d)", lambda power: "²" if power[1] == "2" else "³", t)


def close_spellings(text: str) -> list[str]:
    """Accepted spellings equal to ``text`` but for case (kn for kN), across all dimensions."""
    key = normalise(text).lower()
    return sorted({s for table in SPELLINGS.values() for s in table if s.lower() == key and s != normalise(text)})
