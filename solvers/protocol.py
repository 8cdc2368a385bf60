"""The types a problem module declares besides its physics (see docs/adding-a-problem.md).

Plain data, no Streamlit and nothing from ui/ or viz/: the home page, the practice mode and the
variants read these from each problem's module, so a problem is one place.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Mapping

import sympy as sp


def always(params: dict) -> bool:
    """The default of ``Mistake.applies``: the slip gives a distinct value for every parameter set."""
    return True


@dataclass(frozen=True)
class About:
    """What the home page and the navigation show of a problem."""

    title: str
    group: str  # "Impacts", "Work–energy", "Newton–Euler", ...; groups appear in registry order
    blurb: str  # one line
    icon: str  # ":material/...:"
    source: str  # where the problem comes from
    us_units: bool = False  # the textbook's data are in US customary units
    # The parameters the lesson turns on, always shown; the rest (masses, lengths, g) sit behind
    # "More parameters", which opens by itself when a link changes one of them. Most important
    # first: the first number is the control the benchmarks move. Empty: every parameter shown.
    primary: tuple[str, ...] = ()


@dataclass(frozen=True)
class Mistake:
    """A typical slip, as a wrong expression in the solver's own symbols, with the feedback a tutor
    would give. One definition serves typed numbers (evaluated at the student's parameters) and
    typed expressions (compared as expressions)."""

    answer: str
    feedback: str
    wrong: Callable[[dict], sp.Expr]  # the solution's params -> the wrong expression
    applies: Callable[[dict], bool] = always  # the solution's params -> whether the slip is distinct here


@dataclass(frozen=True)
class Variants:
    """How ``?seed=N`` varies the parameters. Everything not named here follows the general rule:
    a number is drawn from its default × 0.6 … 1.4 (three significant figures), a coefficient of
    restitution from 0.3 … 0.9, an angle from its control's range; options and μ = ∞ keep their
    defaults."""

    angles_deg: Mapping[str, tuple[float, float] | None] = field(default_factory=dict)  # None: the textbook's value
    fixed: tuple[str, ...] = ("g",)  # parameters never varied
    derived: Mapping[str, Callable[[dict], float]] = field(default_factory=dict)  # set from the drawn ones


@dataclass(frozen=True)
class RegimeQuestion:
    """A question of which motion happens, put to a lecture hall before it is shown ("does the disk stick
    or slide at the wall?"): a problem declares its own in ``ROOM_QUESTIONS`` (optional; every problem's
    answers can be asked besides). ``regime(params)`` is what the model says happens at the parameters
    (every one, in SI), one of the ``choices``' words."""

    key: str  # short, unique among the problem's: the question's name in the records ("stick_or_slide")
    prompt: str
    choices: tuple[tuple[str, str], ...]  # (word, as the room reads it), in the order shown
    regime: Callable[[dict], str]
