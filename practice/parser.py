"""A safe parser for answers typed by students: text -> sympy expression, with no eval anywhere.

    parse_expression("2/3*V*sin(theta) + R*omega/3", symbols) -> sympy.Expr

A tokenizer and a recursive-descent grammar build sympy objects directly from a whitelist:
numbers, the given symbols (by name, by Greek name, or as the Greek letter itself), the constant
pi, ° after a number or bracket (degrees), and the functions sin cos tan asin acos atan sqrt exp log abs. Powers are written ^ or **,
a number or a closing bracket times what follows may omit the * (2V, 2(a+b), (a)(b)), and the
Unicode minus, × and · are understood. The problem's own symbols come first: where a problem has a
restitution coefficient, e is that coefficient; Euler's number is exp(1).

Written as by hand, a run of givens and functions is their product, each function taking the given
after it (Rω is R·ω, 2Vsinθ is 2·V·sin θ, Vsin(θ) is V·sin θ), and an exponent belongs to the last
letter (Rω^2 is R·ω²); sinθ^2 is refused as ambiguous. Two numbers side by side are refused, not
multiplied: 1.0.8 is a typo, 3 4 two numbers, 1,5 a decimal comma.

Everything is bounded so that no input can take long: its length, its number of tokens, its
nesting depth, the size of every number, and every exponent (which must be a constant of
modest size, checked before sympy can evaluate anything). Any refusal is a ValueError whose
message points at the problem.
"""
from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass
from typing import Iterable

import sympy as sp

MAX_LENGTH = 200
MAX_TOKENS = 120
MAX_DEPTH = 25
MAX_NUMBER_TEXT = 24
MAX_EXPONENT = 12
MAX_MAGNITUDE = 1e100
MAX_EXP_ARGUMENT = 230  # exp(230) ≈ 1e100

GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "zeta": "ζ", "eta": "η",
    "theta": "θ", "iota": "ι", "kappa": "κ", "lambda": "λ", "mu": "μ", "nu": "ν", "xi": "ξ",
    "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ", "phi": "φ", "chi": "χ", "psi": "ψ", "omega": "ω",
    "Delta": "Δ", "Omega": "Ω", "Theta": "Θ", "Phi": "Φ",
}
FUNCTIONS = {
    "sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "asin": sp.asin, "acos": sp.acos, "atan": sp.atan,
    "sqrt": sp.sqrt, "exp": sp.exp, "log": sp.log, "ln": sp.log, "abs": sp.Abs,
    "arcsin": sp.asin, "arccos": sp.acos, "arctan": sp.atan,
}
_GREEK_LETTERS = "".join(GREEK.values())
_TOKEN = re.compile(
    r"\s*(?:"
    r"(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
    rf"|(?P<name>[A-Za-z{_GREEK_LETTERS}][A-Za-z0-9_{_GREEK_LETTERS}]*)"
    r"|(?P<op>\*\*|[-+*/^(),−×·°])"
    r")"
)


class UnknownName(ValueError):
    """A name that is not a function, pi or one of the allowed symbols; ``name`` says which, so a
    caller can explain it in its own terms (an unknown of the problem, a near miss of a given)."""

    def __init__(self, message: str, name: str):
        super().__init__(message)
        self.name = name


@dataclass(frozen=True)
class Token:
    kind: str  # number, name, op, end
    text: str
    position: int


def _where(text: str, position: int) -> str:
    return f"at position {position + 1}"


def tokenize(text: str) -> list[Token]:
    if not isinstance(text, str):
        raise ValueError("The answer must be text.")
    if len(text) > MAX_LENGTH:
        raise ValueError(f"The answer is too long ({len(text)} characters; at most {MAX_LENGTH}).")
    tokens: list[Token] = []
    position = 0
    while position < len(text):
        if text[position:].strip() == "":
            break
        match = _TOKEN.match(text, position)
        if not match or match.end() == position:
            bad = text[position:].lstrip()[:1]
            where = len(text) - len(text[position:].lstrip())
            if bad == "." and tokens and tokens[-1].kind == "number" and where == position:
                raise ValueError(_two_points(text, tokens[-1].position, position + 1))
            shown = f"'{bad}'" if bad.isprintable() else repr(bad)  # (a backslash as typed, not as Python's '\\')
            raise ValueError(f"The character {shown} (U+{ord(bad):04X}) {_where(text, where)} is not "
                             "allowed: use numbers, the problem's symbols, + − * / ^ ( ) and "
                             "sin cos tan asin acos atan sqrt exp log abs.")
        kind = match.lastgroup
        start = match.start(kind)
        value = match.group(kind)
        tokens.append(Token(kind, value, start))
        if len(tokens) > MAX_TOKENS:
            raise ValueError(f"The answer has too many parts (more than {MAX_TOKENS}).")
        position = match.end()
    tokens.append(Token("end", "", len(text)))
    _no_numbers_side_by_side(text, tokens)
    return tokens


def underflows(text: str, value: float) -> bool:
    """Whether a number typed as ``text`` (1e-400) is not zero but read as ``value`` 0: no double holds it."""
    return value == 0 and re.search(r"[1-9]", text.lower().split("e")[0]) is not None


def _two_points(text: str, start: int, end: int) -> str:
    """A run of digits with a second decimal point (1.0.8, 3..2), and where that point is."""
    run = text[start:end]
    second = start + run.index(".", run.index(".") + 1) if run.count(".") > 1 else start + len(run) - 1
    return (f"{run!r} {_where(text, start)} is not a number: a number has one decimal point "
            f"(the second is {_where(text, second)}).")


def _no_numbers_side_by_side(text: str, tokens: list[Token]) -> None:
    """Refuse a number followed by another number (1.0.8, 3 4) or by a comma and a number (1,5):
    read as a product they would give a confident wrong value."""
    for before, after in zip(tokens, tokens[1:]):
        if before.kind != "number":
            continue
        if after.kind == "number":
            end = after.position + len(after.text)
            run = text[before.position:end]
            if after.position == before.position + len(before.text) and "." in before.text + after.text:
                raise ValueError(_two_points(text, before.position, end))
            raise ValueError(f"Two numbers side by side {_where(text, before.position)} ({run!r}): put an "
                             "operator (+ − * /) between them.")
        if after.kind == "op" and after.text == "," and re.match(r"\s*\d", text[after.position + 1:]):
            raise ValueError(f"A decimal comma {_where(text, after.position)}: write decimals with a point "
                             "(1.5, not 1,5).")


def _symbol_table(allowed_symbols: Iterable[sp.Symbol]) -> dict[str, sp.Symbol]:
    """Names a student may type for each symbol: its own name, with Greek names also as letters
    (theta_0 and θ_0 and θ0), and without underscores or braces (v_{1x}, v_1x, v1x); a word set upright
    is typed as the word (d_cm for d_{\\mathrm{cm}})."""
    table: dict[str, sp.Symbol] = {}
    for symbol in allowed_symbols:
        name = symbol.name
        plain = re.sub(r"\\mathrm\{([^{}]*)\}", r"\1", name)  # (the type is not in the name a student types)
        plain = re.sub(r"[{}\\]", "", plain)  # v_{1x} -> v_1x, \Delta T -> DeltaT
        plain = plain.replace(" ", "")
        spellings = {name, plain, plain.replace("_", "")}
        for spelling in list(spellings):
            for word, letter in GREEK.items():
                if spelling.startswith(word):
                    rest = spelling[len(word):]
                    spellings |= {letter + rest, letter + rest.replace("_", "")}
        for spelling in spellings:
            if re.fullmatch(rf"[A-Za-z{_GREEK_LETTERS}][A-Za-z0-9_{_GREEK_LETTERS}]*", spelling):
                table.setdefault(spelling, symbol)
    return table


def _magnitude_ok(value: sp.Expr) -> bool:
    if value.is_Integer or value.is_Rational:
        p, q = sp.fraction(value)
        return (abs(int(p)).bit_length() <= 333) and (abs(int(q)).bit_length() <= 333)
    if value.is_Float:
        return abs(float(value)) <= MAX_MAGNITUDE
    return True


class _Parser:
    def __init__(self, text: str, symbols: dict[str, sp.Symbol]):
        self.text = text
        self.tokens = tokenize(text)
        self.i = 0
        self.symbols = symbols
        self.depth = 0

    # -- helpers
    @property
    def token(self) -> Token:
        return self.tokens[self.i]

    def advance(self) -> Token:
        token = self.tokens[self.i]
        self.i += 1
        return token

    def expect(self, op: str) -> None:
        if self.token.kind != "op" or self.token.text != op:
            found = self.token.text or "the end"
            if op == ")" and found == "the end":
                raise ValueError("A bracket is not closed: a '(' has no matching ')'.")
            raise ValueError(f"Expected {op!r} {_where(self.text, self.token.position)}, found {found!r}.")
        self.advance()

    def enter(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise ValueError(f"The answer is nested too deeply (more than {MAX_DEPTH} levels).")

    def leave(self) -> None:
        self.depth -= 1

    def is_op(self, *ops: str) -> bool:
        return self.token.kind == "op" and self.token.text in ops

    # -- grammar
    def parse(self) -> sp.Expr:
        if self.token.kind == "end":
            raise ValueError("The answer is empty.")
        expr = self.sum()
        if self.is_op(")"):
            raise ValueError(f"The ')' {_where(self.text, self.token.position)} has no matching '('.")
        if self.token.kind != "end":
            raise ValueError(f"Unexpected {self.token.text!r} {_where(self.text, self.token.position)}.")
        return expr

    def sum(self) -> sp.Expr:
        self.enter()
        expr = self.product()
        while self.is_op("+", "-", "−"):
            op = self.advance().text
            right = self.product()
            expr = expr + right if op == "+" else expr - right
            self.check(expr)
        self.leave()
        return expr

    def starts_primary(self) -> bool:
        return self.token.kind in ("number", "name") or self.is_op("(")

    def product(self) -> sp.Expr:
        expr = self.unary()
        while True:
            if self.is_op("*", "×", "·"):
                self.advance()
                expr = expr * self.unary()
            elif self.is_op("/"):
                self.advance()
                divisor = self.unary()
                if divisor == 0:
                    raise ValueError("The answer divides by zero.")
                expr = expr / divisor
            elif self.starts_primary():  # implicit multiplication: 2V, 2(a+b), R omega
                expr = expr * self.power()
            else:
                return expr
            self.check(expr)

    def unary(self) -> sp.Expr:
        if self.is_op("-", "−", "+"):
            op = self.advance().text
            self.enter()
            operand = self.unary()
            self.leave()
            return operand if op == "+" else -operand
        return self.power()

    def power(self) -> sp.Expr:
        lead, bare = sp.Integer(1), None
        if self.token.kind == "name":  # Rω, 2Vsinθ: the exponent and ° belong to the last factor
            lead, base, bare = self.name_run()
        else:
            base = self.primary()
        while self.is_op("°"):  # 30° is 30·π/180: angles in the answer's trig read as degrees
            self.advance()
            base = base * sp.pi / 180
        if self.is_op("^", "**"):
            if bare is not None:
                function, argument = bare
                raise ValueError(f"{function}{argument}^… {_where(self.text, self.token.position)} is ambiguous: "
                                 f"write {function}({argument})^2 or {function}({argument}^2).")
            position = self.advance().position
            self.enter()
            exponent = self.unary()  # right-associative: a^b^c = a^(b^c); a^-1 allowed
            self.leave()
            base = self.checked_power(base, exponent, position)
        result = lead * base
        self.check(result)
        return result

    def checked_power(self, base: sp.Expr, exponent: sp.Expr, position: int) -> sp.Expr:
        if exponent.free_symbols:
            raise ValueError(f"Exponents must be numbers {_where(self.text, position)} (a symbol in an "
                             "exponent is not expected in these problems).")
        value = complex(sp.N(exponent, 15))
        if abs(value.imag) > 0 or abs(value.real) > MAX_EXPONENT:
            raise ValueError(f"The exponent {_where(self.text, position)} is too large: an exponent here is "
                             f"a real number between −{MAX_EXPONENT} and {MAX_EXPONENT}.")
        if base.is_number and not base.free_symbols:
            size = abs(complex(sp.N(base, 15)))
            if size > 0 and abs(math.log10(size) * value.real) > 100:
                raise ValueError(f"The power {_where(self.text, position)} makes a number too large.")
        result = sp.Pow(base, exponent)
        self.check(result)
        return result

    def primary(self) -> sp.Expr:
        token = self.token
        if token.kind == "number":
            self.advance()
            return self.number(token)
        if self.is_op("("):
            self.advance()
            self.enter()
            expr = self.sum()
            self.leave()
            self.expect(")")
            return expr
        found = token.text or "the end of the answer"
        raise ValueError(f"Expected a number, a symbol or '(' {_where(self.text, token.position)}, "
                         f"found {found!r}.")

    def number(self, token: Token) -> sp.Expr:
        if len(token.text) > MAX_NUMBER_TEXT:
            raise ValueError(f"The number {_where(self.text, token.position)} has too many digits.")
        if re.fullmatch(r"\d+", token.text):
            value = sp.Integer(int(token.text))
        else:
            as_float = float(token.text)
            if not math.isfinite(as_float) or abs(as_float) > MAX_MAGNITUDE:
                raise ValueError(f"The number {_where(self.text, token.position)} is too large.")
            if underflows(token.text, as_float):
                raise ValueError(f"The number {_where(self.text, token.position)} is too small to tell from zero.")
            value = sp.Rational(token.text) if "e" not in token.text.lower() else sp.Float(token.text, 15)
        self.check(value)
        return value

    def name_run(self) -> tuple[sp.Expr, sp.Expr, tuple[str, str] | None]:
        """A name token as the student meant it: (the product of all factors but the last, the
        last factor, and (function, argument) if that last factor is a function written without
        brackets). Each factor is a given, pi, or a function applied to the given after it or to
        the bracket after the name."""
        token = self.advance()
        text = token.text
        pieces = self.pieces(text, bracket_follows=self.is_op("("))
        if pieces is None:
            if text in FUNCTIONS:
                raise ValueError(f"{text} needs brackets: {text}(…) {_where(self.text, token.position)}.")
            hint = " (Euler's number is written exp(1))" if text == "e" else ""
            known = ", ".join(sorted({s.name for s in self.symbols.values()}))
            raise UnknownName(f"Unknown name {text!r} {_where(self.text, token.position)}{hint}. "
                              f"This problem's symbols: {known}.", text)
        factors: list[sp.Expr] = []
        bare = None
        i = 0
        while i < len(pieces):
            spelling, value = pieces[i]
            if value is not None:
                factors.append(value)
                bare = None
                i += 1
                continue
            if i + 1 < len(pieces):  # sinθ: the function takes the given after it
                argument_spelling, argument = pieces[i + 1]
                factors.append(self.call(spelling, argument, token))
                bare = (spelling, argument_spelling)
                i += 2
                continue
            self.advance()  # the bracket after the name holds the argument
            self.enter()
            argument = self.sum()
            self.leave()
            self.expect(")")
            factors.append(self.call(spelling, argument, token))
            bare = None
            i += 1
        return sp.Mul(*factors[:-1]), factors[-1], bare

    def call(self, function_name: str, argument: sp.Expr, token: Token) -> sp.Expr:
        function = FUNCTIONS[function_name]
        if function is sp.exp and argument.is_number and abs(complex(sp.N(argument, 15))) > MAX_EXP_ARGUMENT:
            raise ValueError(f"exp of a number that large {_where(self.text, token.position)} is out of range.")
        result = function(argument)
        self.check(result)
        return result

    def pieces(self, text: str, bracket_follows: bool) -> list[tuple[str, sp.Expr | None]] | None:
        """``text`` as a run of the problem's symbols, pi and functions (value None), in the fewest
        pieces: every function followed by a given (its argument) or, last, by the bracket after
        the name. None if it is no such run."""
        vocabulary: dict[str, sp.Expr | None] = {**{f: None for f in FUNCTIONS}, "pi": sp.pi, "π": sp.pi,
                                                 **self.symbols}  # the problem's own names come first
        longest = max(map(len, vocabulary))

        @functools.cache
        def best(start: int, needs_argument: bool) -> tuple | None:
            if start == len(text):
                return () if not needs_argument or bracket_follows else None
            found = None
            for end in range(min(len(text), start + longest), start, -1):
                piece = text[start:end]
                if piece not in vocabulary:
                    continue
                is_function = vocabulary[piece] is None
                if needs_argument and is_function:
                    continue
                rest = best(end, is_function)
                if rest is not None and (found is None or len(rest) + 1 < len(found)):
                    found = ((piece, vocabulary[piece]), *rest)
            return found

        found = best(0, False)
        return list(found) if found else None

    def check(self, expr: sp.Expr) -> None:
        for atom in expr.atoms(sp.Number):
            if not _magnitude_ok(atom):
                raise ValueError("A number in the answer is too large.")
        if sp.zoo in expr.atoms() or sp.nan in expr.atoms():
            raise ValueError("The answer is undefined (it divides by zero).")


def parse_expression(text: str, allowed_symbols: Iterable[sp.Symbol]) -> sp.Expr:
    """Parse ``text`` into a sympy expression over ``allowed_symbols`` (the very Symbol objects
    given), or raise ValueError saying what is wrong and where."""
    symbols = list(allowed_symbols)
    for s in symbols:
        if not isinstance(s, sp.Symbol):
            raise TypeError("allowed_symbols must be sympy Symbols")
    return _Parser(text, _symbol_table(symbols)).parse()
