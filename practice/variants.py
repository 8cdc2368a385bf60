"""Per-student variants: ``?seed=N`` gives reproducible parameters in sensible ranges.

The seed is hashed with SHA-256 (never Python's salted ``hash()``) into numpy's PCG64 generator,
so a link gives the same numbers in every session, process and machine. Numbers are drawn around
the textbook's defaults (×0.6 … ×1.4, angles within the control's range), rounded to three
significant figures, and redrawn until the solver accepts the combination. Options, gravity and
μ = ∞ keep their defaults, so each variant stays the worked problem with other numbers. What a
problem varies differently (an angle's range, a parameter never varied, one set from the others) its
solver module declares as ``VARIANTS`` (``solvers.protocol.Variants``).

An assignment's variants come from a stream of their own (``ASSIGNMENT``): the number in a
student's assignment link, opened as a public ``?seed=N`` link, gives other numbers.
"""
from __future__ import annotations

import csv
import hashlib
import io
import math
from types import ModuleType

import numpy as np

from solvers.core import Choice, Number
from solvers.protocol import Variants

MAX_SEED = 10**9
PUBLIC, ASSIGNMENT = "dynamics-lab", "dynamics-lab/assignment"  # the parameter streams


def _generator(stream: str, problem: str, seed: int, attempt: int) -> np.random.Generator:
    digest = hashlib.sha256(f"{stream}|{problem}|{seed}|{attempt}".encode()).digest()
    return np.random.Generator(np.random.PCG64(int.from_bytes(digest[:16], "big")))


def _three_figures(x: float) -> float:
    return float(f"{x:.3g}")


def _draw(rules: Variants, p: Number, rng: np.random.Generator) -> float:
    if p.dimension == "angle":  # degrees: a control's range is in its display unit
        lo, hi = rules.angles_deg.get(p.name) or (p.ui_low or 0.0, p.ui_high or 89.0)
        return math.radians(round(float(rng.uniform(lo, hi))))
    if p.low == 0 and p.high == 1:  # a coefficient of restitution
        return round(float(rng.uniform(0.3, 0.9)), 2)
    if p.default == 0:
        return _three_figures(float(rng.uniform(p.ui_low or 0.0, p.ui_high or 1.0)))
    return _three_figures(p.default * float(rng.uniform(0.6, 1.4)))


def variant(solver: ModuleType, problem: str, seed: int, stream: str = PUBLIC) -> dict:
    """The parameters (SI, radians) of variant ``seed`` in ``stream`` (PUBLIC: ``?seed=N``, or
    ASSIGNMENT); raises ValueError for a bad seed."""
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed <= MAX_SEED:
        raise ValueError(f"A variant number is a whole number from 0 to {MAX_SEED}.")
    rules = solver.VARIANTS
    kept = {name for name, degrees in rules.angles_deg.items() if degrees is None}  # the textbook's value
    for attempt in range(200):
        rng = _generator(stream, problem, seed, attempt)
        params = {}
        for p in solver.PARAMS:
            if isinstance(p, Choice) or p.name in rules.fixed or p.name in kept or p.name in rules.derived:
                continue
            if p.allow_inf and math.isinf(p.default):
                continue
            params[p.name] = _draw(rules, p, rng)
        for name, rule in rules.derived.items():
            params[name] = rule(params)
        try:
            solver.solve(**params)
        except ValueError:
            continue
        return params
    raise RuntimeError(f"no valid variant found for {problem} seed {seed}")  # pragma: no cover


def variants_csv(solver: ModuleType, problem: str, first: int, last: int) -> str:
    """A table of variants first..last (at most 500): seed, parameters, answers (SI, radians)."""
    if not (0 <= first <= last <= MAX_SEED) or last - first >= 500:
        raise ValueError("Ask for at most 500 variants, numbered from 0 to 10⁹, first ≤ last.")
    out = io.StringIO()
    writer = None
    for seed in range(first, last + 1):
        params = variant(solver, problem, seed)
        solution = solver.solve(**params)
        row = {"seed": seed} | {f"param:{k}": v for k, v in solution.params.items()} | {
            f"answer:{k}": v for k, v in solution.answers.items()}
        if writer is None:
            writer = csv.DictWriter(out, fieldnames=list(row))
            writer.writeheader()
        writer.writerow(row)
    return out.getvalue()
