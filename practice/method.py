"""The method as an exercise shows it: the worked steps with every equation that shows a result (an
unknown, an answer or an intermediate value, by symbol or by closed form in the givens) taken out, and
the free-body diagram left to the student. Shared by the Practice view (ui/practice.py), the printed
exercises (ui/documents.py) and the tests' leak check, so they cannot disagree about what shows a result."""
from __future__ import annotations

import re

from solvers.core import Derivation, latex


def flat_latex(tex: str) -> str:
    """LaTeX with its braces, spaces and \\left/\\right sizing taken out, so that P_{t} and P_t, or
    sympy's and a step's spacing of the same formula, compare alike. The page's method filter and
    the tests' leak check share it, so they cannot disagree about what counts as showing a result."""
    return re.sub(r"\\(?:left|right)(?![A-Za-z])|[{}\s]", "", tex)


def result_forms(derivation: Derivation) -> list[str]:
    """Every way a step can show a result (flattened): its symbol, and its closed form in the givens
    (a step may state N_front's expression without naming N_front). A closed form without givens
    (a bare number) is left to the value check: it would match any step with that number."""
    forms = []
    for link in derivation.chain:
        forms.append(flat_latex(latex(link.symbol)))
        closed = derivation.expression_of(link.name)
        if closed.free_symbols:
            forms.append(flat_latex(latex(closed)))
    return forms


DRAW_IT = ("Draw the free-body diagram: isolate the body, and put on it every force, impulse and couple, each "
           "at the point where it acts (the diagram comes with the solution).")


def exercise_steps(steps, derivation: Derivation) -> list[tuple[int, str, str]]:
    """The method as an exercise shows it, (part, title, equation or ""): every step's title, and the
    equation only of the steps that show no result (no unknown, answer or intermediate value, by
    symbol or by closed form); the free-body diagram (Step 2) is the student's to draw, so its steps
    are one instruction and the balance laws written from it (Step 3) keep their titles alone."""
    forms = result_forms(derivation)
    out = []
    for step in steps:
        if step.part == 2:
            if not out or out[-1][0] != 2:
                out.append((2, DRAW_IT, ""))
            continue
        flat = flat_latex(step.latex)
        shows = step.part == 3 or any(form in flat for form in forms)
        out.append((step.part, step.title, "" if shows else step.latex))
    return out
