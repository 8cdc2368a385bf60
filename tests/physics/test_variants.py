"""The general rule of ?seed=N variants and each problem's own VARIANTS, on a made-up problem (so
no rule can hide in a problem's name)."""
from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from practice.variants import variant
from solvers.core import Choice, Number
from solvers.protocol import Variants

PARAMS = (
    Number("c", 2.0, "a length", "length", "c", low=0, ui_low=0.1, ui_high=5.0),
    Number("g", 9.81, "gravity", "acceleration", "g", low=0),
    Number("theta", math.radians(30), "an angle", "angle", r"\theta", low=0, high=math.pi / 2, ui_low=0, ui_high=89),
    Number("e", 0.5, "restitution", "dimensionless", "e", low=0, high=1, low_inclusive=True, high_inclusive=True),
    Number("mu", math.inf, "friction", "dimensionless", r"\mu", low=0, allow_inf=True),
    Choice("kind", "a", "a kind", ("a", "b")),
)


def made_up(rules: Variants, solve=lambda **p: None) -> SimpleNamespace:
    return SimpleNamespace(PARAMS=PARAMS, VARIANTS=rules, solve=solve)


@pytest.mark.parametrize("seed", range(8))
def test_the_general_rule(seed):
    params = variant(made_up(Variants()), "made_up", seed)
    assert set(params) == {"c", "theta", "e"}  # g, μ = ∞ and options keep their defaults
    assert 0.6 * 2.0 <= params["c"] <= 1.4 * 2.0 and float(f"{params['c']:.3g}") == params["c"]
    assert 0.3 <= params["e"] <= 0.9
    degrees = math.degrees(params["theta"])
    assert 0 <= degrees <= 89 and degrees == pytest.approx(round(degrees))


def test_a_parameter_named_c_is_varied_unless_its_problem_fixes_it():
    drawn = {variant(made_up(Variants()), "made_up", seed)["c"] for seed in range(6)}
    assert len(drawn) > 1
    assert "c" not in variant(made_up(Variants(fixed=("g", "c"))), "made_up", 3)


def test_angle_ranges_kept_angles_and_derived_parameters():
    ranged = [variant(made_up(Variants(angles_deg={"theta": (10, 20)})), "made_up", s)["theta"] for s in range(10)]
    assert all(math.radians(10) <= t <= math.radians(20) for t in ranged)
    assert "theta" not in variant(made_up(Variants(angles_deg={"theta": None})), "made_up", 1)
    params = variant(made_up(Variants(derived={"e": lambda p: p["c"] / 10})), "made_up", 2)
    assert params["e"] == params["c"] / 10


def test_a_variant_the_solver_refuses_is_drawn_again():
    def solve(**p):
        if p["c"] > 2.0:
            raise ValueError("too long")
    assert all(variant(made_up(Variants(), solve), "made_up", s)["c"] <= 2.0 for s in range(10))
