"""Display equations that fit a phone: a long step's LaTeX broken over aligned lines.

A derivation step is one LaTeX string (solvers' ``Step.latex``), often a chain such as
``T = <formula> = <numbers> = <value>`` or a list of results ``a = …,\\quad b = …``. On a 360 px
phone a display equation holds about 17 em of KaTeX, and a wider one pushed its "= value" off the
screen. ``broken`` rewrites a too-wide step as ``\\begin{aligned}`` rows: one clause per row, a
relation chain one relation per row (aligned on the relation), and a side that is still too wide
split before its top-level + and − signs. The symbols are untouched, only rows are added, so what
a student reads is the same algebra.

Widths are estimated from the LaTeX (em per glyph, fractions as wide as their wider part, scripts
at 70 %): a cheap, deterministic stand-in for KaTeX's layout. The browser tests measure the real
boxes at 360 and 390 px.
"""
from __future__ import annotations

import functools
import re

# The width a display row may take, in em of KaTeX's display font, as this module estimates it: a
# 360 px phone's content box (328 px) holds 18.8 em at the phone font size of the derivation
# (ui/stylesheet.py PHONE_CSS); the estimate runs up to 15 % short of KaTeX's real layout.
PHONE_WIDTH_EM = 16.0
PHONE_BOX_EM = 18.8  # (that content box: what a row, as estimated, must never exceed)
# The width a row may take where the column is wide (a laptop, a projector): a step the phone breaks
# is sent broken at this width too (most: whole, as written), and the page takes that where its column
# holds it (ui/plotly_component/text.js), so a laptop draws it on the rows its width needs, at full size.
WIDE_WIDTH_EM = 36.0
# Smaller sizes KaTeX offers in math mode, for a row that no relation or sign can split (a wide
# fraction): the largest that fits is used.
_SIZES = ((0.9, r"\small"), (0.8, r"\footnotesize"), (0.7, r"\scriptsize"))

# Text mode (``\text{at }G``) is one token, its spaces kept: they are part of what it says ("at G", not "atG").
_TEXT = re.compile(r"\\(?:text|textrm|textit|textbf|mbox)\{[^{}]*\}")
_TOKEN = re.compile(_TEXT.pattern + r"|\\\\|\\[a-zA-Z]+|\\.|[{}^_&]|\S")
_SPACES = {r"\;": 0.28, r"\,": 0.17, r"\:": 0.22, r"\!": -0.17, r"\quad": 1.0, r"\qquad": 2.0, "~": 0.33}
_RELATIONS = {"=", r"\le", r"\ge", "<", ">", r"\approx", r"\ne", r"\equiv"}
_ARROWS = {r"\Rightarrow", r"\implies", r"\Longrightarrow", r"\iff"}
# Tokens that open and close a group: a row cannot end inside one.
_DEPTH = {"{": 1, "}": -1, r"\left": 1, r"\right": -1, r"\begin": 1, r"\end": -1}
_BIG = {r"\frac": 1.0, r"\dfrac": 1.0, r"\tfrac": 0.75}
# Upright letters (a word subscript, N_{\mathrm{front}}; a unit): the command itself takes no room.
_FONTS = {r"\mathrm"}
_FUNCTIONS = {r"\sin", r"\cos", r"\tan", r"\asin", r"\acos", r"\atan", r"\sqrt", r"\log", r"\ln", r"\exp"}


def tokens(latex: str) -> list[str]:
    return _TOKEN.findall(latex)


def joined(toks: list[str]) -> str:
    """Tokens back to LaTeX: a space only where a command name would run into a letter."""
    return "".join(t + " " if re.fullmatch(r"\\[a-zA-Z]+", t) else t for t in toks).strip()


def _group(toks: list[str], i: int) -> tuple[list[str], int]:
    """The argument starting at toks[i]: a braced group (without its braces) or one token."""
    if i >= len(toks):
        return [], i
    if toks[i] != "{":
        return [toks[i]], i + 1
    depth, j = 0, i
    while j < len(toks):
        depth += {"{": 1, "}": -1}.get(toks[j], 0)
        if depth == 0:
            return toks[i + 1: j], j + 1
        j += 1
    return toks[i + 1:], j


def width(toks: list[str]) -> float:
    """Estimated width in em of a token list as KaTeX lays it out in display mode."""
    return _width(tuple(toks))


@functools.lru_cache(maxsize=65536)
def _width(toks: tuple[str, ...]) -> float:
    # Kept per token run: breaking a side measures the same groups and growing prefixes again and
    # again (tens of thousands of calls per derivation without it).
    total, i = 0.0, 0
    while i < len(toks):
        t = toks[i]
        if t in _BIG:
            num, i = _group(toks, i + 1)
            den, i = _group(toks, i)
            total += _BIG[t] * max(width(num), width(den)) + 0.3
        elif t == r"\sqrt":
            arg, i = _group(toks, i + 1)
            total += width(arg) + 1.0
        elif t in ("^", "_"):
            arg, i = _group(toks, i + 1)
            total += 0.7 * width(arg)
        elif t == r"\begin":
            _, i = _group(toks, i + 1)
            body, depth, j = [], 1, i
            while j < len(toks) and depth:
                depth += {r"\begin": 1, r"\end": -1}.get(toks[j], 0)
                body.append(toks[j])
                j += 1
            body, i = body[:-1], j + 3  # skip \end{name}
            rows = _split(body, {r"\\"})
            total += max((sum(width(c) + 1.0 for c in _split(row, {"&"})) for row in rows), default=0.0)
        elif t in (r"\left", r"\right"):  # the delimiter that follows is counted as a glyph
            total += 0.1
            i += 1
        else:
            total += _glyph(t)
            i += 1
    return total


def _glyph(t: str) -> float:
    if _TEXT.fullmatch(t):  # its letters and its spaces
        text = t[t.index("{") + 1:-1]
        return 0.55 * len(text.replace(" ", "")) + 0.25 * text.count(" ")
    if t in _SPACES:
        return _SPACES[t]
    if t in _RELATIONS or t in ("+", "-", r"\times", r"\pm", r"\mp"):
        return 1.3 if t in _RELATIONS else 1.2
    if t in _ARROWS:
        return 1.8
    if t in ("{", "}", "&", r"\\"):
        return 0.0
    if t in (",", ".", ";", ":", "!", "|"):
        return 0.3
    if t in ("(", ")", "[", "]"):
        return 0.4
    if t == r"\cdot":  # a binary operator: the dot and a medium space either side
        return 0.75
    if t in _FUNCTIONS:
        return 0.5 * (len(t) - 1) + 0.2
    if t in _FONTS:  # a font for the group that follows, which is measured as its glyphs
        return 0.0
    if t.startswith("\\"):
        return 0.7 if len(t) > 2 else 0.3
    return 0.55


def _split(toks: list[str], at: set[str]) -> list[list[str]]:
    """Split at top-level occurrences of the tokens in ``at`` (outside braces, \\left…\\right and
    environments); the separators are dropped."""
    parts, current, depth = [], [], 0
    for t in toks:
        if depth == 0 and t in at:
            parts.append(current)
            current = []
            continue
        depth += {"{": 1, "}": -1, r"\left": 1, r"\right": -1, r"\begin": 1, r"\end": -1}.get(t, 0)
        current.append(t)
    parts.append(current)
    return parts


def _cut_before(toks: list[str], at: set[str]) -> list[list[str]]:
    """Split at top-level tokens in ``at``, keeping each separator at the start of its piece. A sign
    at the very start, or right after another operator, is unary and not a cut."""
    parts, current, depth = [], [], 0
    for t in toks:
        # A relation always cuts; a sign only as a binary operator (not unary, not a script).
        binary = t in _RELATIONS or (current and current[-1] not in _RELATIONS | {"+", "-", r"\cdot", "(", "{", "^", "_"})
        if depth == 0 and t in at and current and binary:
            parts.append(current)
            current = []
        depth += _DEPTH.get(t, 0)
        current.append(t)
    parts.append(current)
    return [p for p in parts if p]


_CLAUSE_GLUE = re.compile(r"(,?\s*(?:\\quad|\\qquad|\\;)\s*(?:\\Rightarrow|\\implies|\\iff)\s*(?:\\quad|\\;)?"
                          r"|,\s*\\quad|\\qquad|,\s*\\;|\\\\)")


def _clauses(latex: str) -> list[tuple[str, str]]:
    """The top-level clauses of a step and the connective before each ("", "\\Rightarrow" or "\\iff")."""
    pieces = _CLAUSE_GLUE.split(latex)
    out, connective = [], ""
    for n, piece in enumerate(pieces):
        if n % 2:
            connective = (r"\iff" if "iff" in piece else
                          r"\Rightarrow" if ("Rightarrow" in piece or "implies" in piece) else "")
            continue
        if piece.strip():
            out.append((connective, piece.strip()))
    # A separator inside braces (a matrix row, a fraction) is not a clause boundary: only keep the
    # split when every clause is balanced.
    if any(_unbalanced(c) for _, c in out):
        return [("", latex)]
    return out


def _unbalanced(latex: str) -> bool:
    toks = tokens(latex)
    return (toks.count("{") != toks.count("}") or toks.count(r"\left") != toks.count(r"\right")
            or toks.count(r"\begin") != toks.count(r"\end"))


def _rows_of_clause(connective: str, clause: str, limit: float) -> list[str]:
    """A clause as aligned rows: the first relation carries the alignment mark."""
    prefix = (connective + r"\; ") if connective else ""
    toks = tokens(clause)
    if width(toks) + (2.0 if connective else 0.0) <= limit:
        return [prefix + _aligned_at_first_relation(toks)]
    sides = _cut_before(toks, _RELATIONS)
    if sides[0][0] in _RELATIONS:
        return [row for side in sides for row in _rows_of_side(side, limit)]
    head = [prefix + joined(t) for t in _packed(sides[0], limit)]
    rows = [row for side in sides[1:] for row in _rows_of_side(side, limit)]
    # The left-hand side keeps its first relation on its row unless it is itself long; a long one
    # goes in the second column too, so that the first column stays narrow.
    if rows and len(head) == 1 and width(sides[0]) <= 0.4 * limit:
        return [head[0] + " " + rows[0], *rows[1:]]
    return [*("&" + h for h in head), *rows]


def _packed(side: list[str], limit: float, at: set[str] = frozenset({"+", "-"})) -> list[list[str]]:
    """Terms of one side packed into rows of at most ``limit`` em, cut before top-level signs;
    rows after the first are indented."""
    lead = [side[0]] if side[0] in _RELATIONS else []
    rows, current = [], lead
    terms = _cut_before(side[len(lead):], {"+", "-"} & set(at))
    if r"\cdot" in at:  # a product too wide by itself is cut before its dots, the sums first
        terms = [piece for term in terms for piece in
                 (_cut_before(term, {r"\cdot"}) if width(term) > limit - 1.0 else [term])]
    for term in terms:
        if current and current != lead and width(current + term) > limit - 1.0:
            rows.append(current)
            # A row that opens with a sign or a dot: ``{}`` before it keeps TeX's binary spacing
            # (the idiom for a broken line), and it is read as an operator, never as a sign.
            current = [r"\quad"] + (["{}"] if term[0] in ("+", "-", r"\cdot") else []) + term
        else:
            current = current + term
    rows.append(current)
    return rows


def _rows_of_side(side: list[str], limit: float) -> list[str]:
    """One relation and its right-hand side (``= a + b``) as rows starting at the alignment mark,
    split before top-level + and − when too wide; a side that has none is opened up (``_opened``)
    and also split before its products' dots."""
    if width(side) <= limit:
        return ["&" + joined(side)]
    rows = _packed(side, limit)
    for _ in range(3):  # open one level of brackets at a time, while that makes the rows narrower
        widest = max(width(row) for row in rows)
        if widest <= limit:
            break
        side = _opened(side)
        tried = _packed(side, limit, at={"+", "-", r"\cdot"})
        if max(width(row) for row in tried) >= widest:
            break
        rows = tried
    return ["&" + joined(row) for row in rows]


def _opened(side: list[str]) -> list[str]:
    r"""The same expression with its outer brackets made splittable: a big fraction with a short
    denominator ``\frac{A}{B}`` written ``\frac{1}{B}\,A`` (``\frac{1}{B} \cdot A`` where A opens with a
    number), and ``\left( … \right)`` written with
    ``\Bigl( … \Bigr)``, which need not close on the same row."""
    out, i, depth, opened = [], 0, 0, 0
    while i < len(side):
        t = side[i]
        if depth or (opened and t == r"\left"):  # nested inside an opened bracket: kept whole
            depth += _DEPTH.get(t, 0)
            out.append(t)
            i += 1
            continue
        if t in (r"\frac", r"\dfrac"):
            num, j = _group(side, i + 1)
            den, k = _group(side, j)
            if not opened and width(num) > 8 and width(den) < 3:
                # (a number after ½ is multiplied, not a mixed number: ½ · 1 · (…), not ½ 1 · (…))
                # (a digit, or its stand-in: ``broken`` breaks a step's shape, its digits as U+E000…)
                times = r"\cdot" if num and (_PRIVATE.match(num[0]) or num[0][:1] in "0123456789.") else r"\,"
                out += [r"\frac", "{", "1", "}", "{", *den, "}", times, *num]
                i = k
                continue
        if t in (r"\left", r"\right") and i + 1 < len(side) and side[i + 1] in "()[]":
            out.append(r"\Bigl" if t == r"\left" else r"\Bigr")
            opened += 1 if t == r"\left" else -1
            i += 1
            continue
        if t == "{" and not opened and _only_brackets(_group(side, i)[0]):
            out.append(t)  # a brace around brackets only (a function's argument): opened below
            i += 1
            continue
        depth += _DEPTH.get(t, 0)
        out.append(t)
        i += 1
    # Braces that only wrapped a bracketed group (``\operatorname{asin}{\left( … \right)}``) go too.
    return [t for n, t in enumerate(out) if not _wraps_brackets(out, n)]


def _only_brackets(group: list[str]) -> bool:
    r"""Whether a group is one ``\left( … \right)`` and nothing else."""
    if len(group) < 4 or group[0] != r"\left" or group[-2] != r"\right":
        return False
    depth = 0
    for n, t in enumerate(group):
        depth += _DEPTH.get(t, 0)
        if depth == 0 and n < len(group) - 2:
            return False
    return True


def _wraps_brackets(toks: list[str], n: int) -> bool:
    if toks[n] == "{":
        return n + 1 < len(toks) and toks[n + 1] == r"\Bigl"
    if toks[n] == "}":
        return n >= 2 and toks[n - 2] == r"\Bigr"
    return False


def _aligned_at_first_relation(toks: list[str]) -> str:
    for n, t in enumerate(toks):
        if t in _RELATIONS and n > 0 and _depth_zero(toks[:n]):
            return joined(toks[:n]) + " &" + joined(toks[n:])
    return "&" + joined(toks)


def _depth_zero(toks: list[str]) -> bool:
    depth = 0
    for t in toks:
        depth += {"{": 1, "}": -1, r"\left": 1, r"\right": -1, r"\begin": 1, r"\end": -1}.get(t, 0)
    return depth == 0


_DIGIT = re.compile(r"[0-9]")
_PLACEHOLDER = 0xE000  # Unicode's private use area: one stand-in per digit of a step
_PRIVATE = re.compile("[\ue000-\uf8ff]")


@functools.lru_cache(maxsize=2048)  # the symbolic steps: the same text on every run
def broken(latex: str, limit: float = PHONE_WIDTH_EM) -> str:
    """The step's LaTeX, unchanged when it fits ``limit`` em, else as aligned rows that do.

    Breaking is the largest part of a page's run (about 10 ms a derivation), and on a new value
    only the digits of the numeric steps change, while every digit is one glyph of one width to
    this module. So a step is broken once per *shape*: each digit replaced by its own stand-in
    (the first digit by U+E000, the second by U+E001, …), the shape's rows kept, and the digits
    put back where their stand-ins went (``tests/pages/test_equations.py`` holds this to breaking the
    step itself)."""
    digits = _DIGIT.findall(latex)
    if not digits or len(digits) > 6000 or _PRIVATE.search(latex):
        return _broken(latex, limit)
    counter = iter(range(_PLACEHOLDER, _PLACEHOLDER + len(digits)))
    shape = _DIGIT.sub(lambda _: chr(next(counter)), latex)
    return _broken(shape, limit).translate({_PLACEHOLDER + n: d for n, d in enumerate(digits)})


@functools.lru_cache(maxsize=4096)
def _broken(latex: str, limit: float) -> str:
    if width(tokens(latex)) <= limit:
        return latex
    shown = _aligned(latex, limit)
    # A row in the second column starts after the first column's widest cell (another clause's left-hand
    # side): where that takes a phone's block past what even an exact estimate would fit, its rows are
    # broken again: the widest rows that fit, an em narrower at a time (down to half the limit), else the
    # narrowest. (A wide column's rows are measured where they are shown: ui/plotly_component/text.js takes
    # them only where they fit, else the phone's.)
    fits = limit * PHONE_BOX_EM / PHONE_WIDTH_EM
    if limit > PHONE_WIDTH_EM or laid_out_width(shown) <= fits:
        return shown
    narrowest = shown
    for n in range(1, int(limit / 2) + 1):
        tried = _aligned(latex, limit - n)
        if laid_out_width(tried) <= fits:
            return tried
        narrowest = min(narrowest, tried, key=laid_out_width)
    return narrowest


def _aligned(latex: str, limit: float) -> str:
    """The step's clauses as aligned rows, each at most ``limit`` em (set smaller where it cannot be split)."""
    rows = [row for connective, clause in _clauses(latex) for row in _rows_of_clause(connective, clause, limit)]
    return r"\begin{aligned}" + r" \\ ".join(_scaled(row, limit) for row in rows) + r"\end{aligned}"


def laid_out_width(latex: str) -> float:
    """Estimated width in em of a step as shown: an aligned block as wide as its widest cell in each
    column together (a row that starts in the second column starts after the first column's widest cell),
    a cell set smaller (``_scaled``) at its size."""
    return sum(_columns(latex))


def _columns(latex: str) -> list[float]:
    """The estimated width of each column of an aligned block (its widest cell); a step not in rows, one column."""
    if not latex.startswith(r"\begin{aligned}"):
        return [width(tokens(latex))]
    inner = latex.removeprefix(r"\begin{aligned}").removesuffix(r"\end{aligned}")
    columns: dict[int, float] = {}
    for row in _split(tokens(inner), {r"\\"}):
        for n, cell in enumerate(_split(row, {"&"})):
            factor = next((f for f, name in _SIZES if cell[:1] == [name]), 1.0)
            columns[n] = max(columns.get(n, 0.0), factor * width(cell[1:] if factor < 1 else cell))
    return list(columns.values())


def wide_too(latex: str) -> list[str]:
    """``broken(latex)`` for a phone, and where a wide column would set it otherwise, ``broken`` at
    ``WIDE_WIDTH_EM`` too (a laptop's step on the rows its width needs: the phone's four rows are one there)."""
    narrow = broken(latex)
    wide = broken(latex, WIDE_WIDTH_EM)
    return [narrow] if wide == narrow else [narrow, wide]


def _scaled(row: str, limit: float) -> str:
    """A row that still does not fit, set in the largest smaller size that does (each cell of an
    aligned row starts at the normal size, so the command goes at the start of every cell)."""
    w = width(tokens(row))
    if w <= limit:
        return row
    size = next((name for factor, name in _SIZES if w * factor <= limit), _SIZES[-1][1])
    cells = _split(tokens(row), {"&"})
    return "&".join(size + " " + joined(cell) for cell in cells)
