"""The one units module (solvers/units.py): what a page shows reads back as the same quantity, in
either unit system, and units are read case-sensitively."""
from __future__ import annotations

import math
import re

import pytest
from hypothesis import given, settings, strategies as st

from solvers import registry, units
from solvers.core import Number

DIMENSIONS = sorted(units.DIMENSIONS)
SUPERSCRIPTS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻", "0123456789-")


def read_back(shown: str, dimension: str) -> float:
    """A quantity as format_quantity writes it, read the way a student's typed answer is: the number
    (no-break-space groups, a true minus, × 10ⁿ) and then the unit by its spelling."""
    match = re.fullmatch(r"(−?\d+(?:\u202f\d{3})*(?:\.\d+)?)(?:\u202f×\u202f10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+))? ?(.*)", shown)
    assert match, shown
    number = float(match.group(1).replace("\u202f", "").replace("−", "-"))
    if match.group(2):
        number *= 10.0 ** int(match.group(2).translate(SUPERSCRIPTS))
    label = match.group(3)
    return number * (units.si_per_unit(label, dimension) if label else 1.0)


@given(dimension=st.sampled_from(DIMENSIONS), system=st.sampled_from(["si", "us"]),
       x=st.floats(1e-6, 1e9) | st.floats(-1e9, -1e-6))
def test_what_a_page_shows_reads_back_as_the_same_quantity(dimension, system, x):
    assert units.to_si(units.to_display(x, dimension, system), dimension, system) == pytest.approx(x, rel=1e-12)
    assert read_back(units.format_quantity(x, dimension, system, sig=6), dimension) == pytest.approx(x, rel=1e-5)


@given(dimension=st.sampled_from([d for d in DIMENSIONS if units.SPELLINGS[d]]), data=st.data(),
       value=st.floats(1e-3, 1e6))
def test_every_spelling_reads_its_own_size_and_its_other_case_never_the_same(dimension, data, value):
    spelling, size = data.draw(st.sampled_from(sorted(units.SPELLINGS[dimension].items())))
    assert value * units.si_per_unit(f" {spelling} ", dimension) == value * size
    swapped = units.si_per_unit(spelling.swapcase(), dimension)
    assert spelling.swapcase() == spelling or swapped is None or swapped != size


def test_case_is_meaning():
    assert units.si_per_unit("MJ", "energy") == 1e6 and units.si_per_unit("mJ", "energy") == 1e-3
    assert units.si_per_unit("mN", "force") == 1e-3 and units.si_per_unit("Nm", "torque") == 1.0
    assert units.si_per_unit("KN", "force") is None and units.close_spellings("KN") == ["kN"]
    assert units.si_per_unit("g", "mass") == 1e-3 and units.si_per_unit("g", "acceleration") == units.G0


def test_each_dimension_shows_a_label_and_latex_and_us_units_come_in_pairs():
    for name, dim in units.DIMENSIONS.items():
        assert (dim.us_label is None) == (dim.us_factor is None), name
        assert bool(dim.label) == bool(dim.latex) == (name != "dimensionless"), name
        assert all(units.normalise(s) == s for s in dim.spellings), name


def test_every_dimension_a_problem_uses_is_in_the_table():
    for solver in registry.solvers():
        used = {p.dimension for p in solver.PARAMS if isinstance(p, Number)} | {a.dimension for a in solver.ANSWERS}
        assert used <= set(units.DIMENSIONS), (solver.__name__, used - set(units.DIMENSIONS))


def test_a_controls_range_is_in_its_display_unit():
    theta = Number("theta", math.radians(30), "an angle", "angle", r"\theta", ui_low=0, ui_high=89)
    assert theta.ui_unit == "°" and Number("L", 1.0, "a length", "length", "L").ui_unit == "m"


@settings(max_examples=300, deadline=None)
@given(dimension=st.sampled_from([d for d, dim in units.DIMENSIONS.items() if dim.us_label]),
       digits=st.integers(1, 999), exponent=st.integers(-3, 3))
def test_a_value_round_in_the_shown_unit_reads_back_round_after_four_figures_in_si(dimension, digits, exponent):
    """A textbook's 10 lb or 0.3 ft, kept in SI to four figures (4.536 kg, 0.09144 m), shows as
    10 lb and 0.3 ft again, not 10.0002 lb: conversion noise below the SI value's own rounding is
    not shown."""
    us = digits * 10.0**exponent
    si = float(f"{units.to_si(us, dimension, 'us'):.4g}")
    assert units.shown_value(si, dimension, "us") == pytest.approx(us, rel=1e-12)
    assert units.shown_value(si, dimension, "si") == si  # nothing to convert: as it is


BASE = {"kg": (1, 0, 0), "m": (0, 1, 0), "s": (0, 0, 1), "N": (1, 1, -2), "J": (1, 2, -2), "rad": (0, 0, 0),
        "°": (0, 0, 0)}


def test_each_dimension_s_powers_of_mass_length_and_time_are_its_si_label_s():
    """``Dimension.mlt`` (what the judge checks an expression's units against) read off the SI label the pages
    print, each factor of it in base units: kg·m²/s is (1, 2, −1), N·m/rad is N times m, J is kg·m²/s²."""
    for name, dimension in units.DIMENSIONS.items():
        powers = [0, 0, 0]
        numerator, *denominators = dimension.label.split("/")
        for sign, part in [(1, numerator)] + [(-1, d) for d in denominators]:
            for factor in filter(None, part.split("·")):
                power = {"²": 2, "³": 3}.get(factor[-1], 1)
                base = BASE[factor.rstrip("²³")] if factor != "1" else (0, 0, 0)
                powers = [p + sign * power * b for p, b in zip(powers, base)]
        assert tuple(powers) == units.mlt(name), name
