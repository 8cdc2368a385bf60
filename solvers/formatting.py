"""Numbers as students read them: plain text for answers and captions, LaTeX for the derivation's
substituted steps. No units here (solvers/units.py adds them) and no physics."""
from __future__ import annotations

import math

_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
GROUPED_BELOW = 1e6  # up to here a number is written out in full, in groups of three digits


def plain_number(x: float, sig: int = 4) -> str:
    """Plain-text number with ``sig`` significant figures and a true minus sign: digits grouped by
    narrow no-break spaces from ten thousand (30 490), a typeset power of ten from a million
    (3.049 × 10⁷, its spaces no-break too) and below 10⁻⁴, and a value that rounds to zero written 0,
    never −0. No line breaks inside it."""
    if math.isinf(x):
        return "∞" if x > 0 else "−∞"
    rounded = float(f"{x:.{sig}g}")
    if rounded == 0:
        return "0"
    size = abs(rounded)
    if size >= GROUPED_BELOW or size < 1e-4:
        mantissa, exponent = f"{rounded:.{sig - 1}e}".split("e")
        mantissa = mantissa.rstrip("0").rstrip(".") if "." in mantissa else mantissa
        text = f"{mantissa}\u202f×\u202f10{str(int(exponent)).translate(_SUPERSCRIPT)}"
    elif size >= 1e4:
        text = f"{rounded:,.{max(0, sig - len(str(int(size))))}f}"
        text = (text.rstrip("0").rstrip(".") if "." in text else text).replace(",", "\u202f")
    else:
        text = f"{rounded:.{sig}g}"
    return text.replace("-", "−")


def plain_fixed(x: float, decimals: int = 1) -> str:
    """``x`` with a fixed number of decimals and a true minus sign; −0.0 is written 0.0."""
    text = f"{x:.{decimals}f}"
    return text.lstrip("-") if float(text) == 0 else text.replace("-", "−")


def latex_number(x: float, sig: int = 4, keep_zeros: bool = True) -> str:
    """A number as compact LaTeX with ``sig`` significant figures (scientific when far from 1).

    ``keep_zeros`` shows trailing zeros (a computed 41.00); without it a given 0.5 stays 0.5.
    """
    if math.isinf(x):
        return r"\infty" if x > 0 else r"-\infty"
    if x == 0:
        return "0"
    mantissa_text, exponent_text = f"{x:.{sig - 1}e}".split("e")
    exponent = int(exponent_text)
    if -3 <= exponent < 5:
        text = f"{x:#.{sig}g}" if keep_zeros else f"{x:.{sig}g}"
        if "e" not in text:
            return text.rstrip(".")
    text = mantissa_text if keep_zeros else mantissa_text.rstrip("0").rstrip(".")
    return rf"{text} \times 10^{{{exponent}}}"
