"""The six problems as the app lists them: title, method group, one line, and display options."""
from __future__ import annotations

import importlib
from dataclasses import dataclass
from types import ModuleType


@dataclass(frozen=True)
class Problem:
    id: str
    title: str
    group: str
    blurb: str
    icon: str
    source: str
    us_units: bool = False  # the textbook's data are in US customary units
    # The parameters the lesson turns on, always shown; the rest (masses, lengths, g) sit behind
    # "More parameters", which opens by itself when a link changes one of them.
    primary: tuple[str, ...] = ()

    @property
    def solver(self) -> ModuleType:
        return importlib.import_module(f"solvers.{self.id}")

    @property
    def page_path(self) -> str:
        return f"pages/{self.id}.py"


PROBLEMS = (
    Problem("disk_wall", "Spinning disk hits a rough wall", "Impacts",
            "A spinning disk strikes a wall: does it stick or slide, and where does it go?",
            ":material/sports_hockey:", "ME 230 final-exam review, problem 1",
            primary=("V", "omega", "theta", "e", "mu")),
    Problem("stick_ball", "Ball slides into a free stick", "Impacts",
            "A ball hits a stick on ice and sticks (or bounces): momentum and angular momentum at work.",
            ":material/sports_cricket:", "ME 230 final-exam review, problem 3",
            primary=("v", "s", "mode", "e")),
    Problem("pendulum_rebound", "Rod-and-sphere pendulum bounces off the floor", "Work–energy",
            "Release, swing, bounce: each bounce keeps a fraction e² of the swing.",
            ":material/height:", "Hibbeler 19-56", us_units=True,
            primary=("theta0", "e")),
    Problem("rod_disk_spring", "Rod and disk on a torsional spring", "Work–energy",
            "Gravity pulls, the spring resists: how fast is it turning at θ₂?",
            ":material/rotate_right:", "Hibbeler 18-9",
            primary=("k", "theta2", "disk")),
    Problem("driven_cart", "Cart with driven wheels", "Newton–Euler",
            "Front, rear or all-wheel drive: how hard can it accelerate before the front lifts?",
            ":material/directions_car:", "O'Reilly 9.3",
            primary=("mu", "drive", "a", "b")),
    Problem("eulers_disk", "Euler's disk", "Newton–Euler",
            "A coin-like disk whirls ever faster as it settles: steady precession and its singularity.",
            ":material/album:", "ME 230 final-exam review; Moffatt, Nature 404 (2000)",
            primary=("theta", "r")),
)

BY_ID = {p.id: p for p in PROBLEMS}
GROUPS = ("Impacts", "Work–energy", "Newton–Euler")
