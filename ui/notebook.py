"""A Jupyter notebook (and the same code as a Python script) that rebuilds a page's derivation with
sympy for the page's numbers, step by step, and prints the answers.

Generated, never typed: the symbols are the solver's own (names and assumptions), each link of the
chain is the solver's own sympy expression (``Derivation.chain``) printed as sympy code, and the
numbers are the page's givens, angles written as the degrees the page shows. What the notebook does
with them is its own: exact substitution and sympy's arbitrary-precision evaluation, where the app
evaluates the same chain with lambdified floating-point code. It imports nothing of this project,
so a student can run it anywhere sympy is installed; a test executes it and compares its answers
with the solver's.
"""
from __future__ import annotations

import json
import keyword
import math

import sympy as sp
from sympy.printing.str import StrPrinter

from solvers import units
from solvers.core import Choice, Solution
from solvers.catalog import Problem
from viz import diagram as fbd

# The notebook's cell that draws the free-body diagrams (viz.diagram.as_data) with matplotlib; a
# label's LaTeX is matplotlib's mathtext.
DRAW_DIAGRAMS = """def draw_free_body_diagrams(diagrams):
    # (a function: its names stay its own, clear of the givens' symbols)
    try:
        import matplotlib.pyplot as plt
        from matplotlib.patches import Circle, FancyArrowPatch, Polygon
    except ImportError:
        plt = None
    for d in diagrams:
        print(d["text"])
        if plt is None:
            continue
        fig, ax = plt.subplots(figsize=(4.5, 4.5 * (d["box"][3] - d["box"][1]) / (d["box"][2] - d["box"][0])))
        for poly in d["polygons"]:
            ax.add_patch(Polygon(poly, closed=True, facecolor="#e8eaed", edgecolor="#3c4043", lw=1.5))
        for x, y, radius in d["circles"]:
            ax.add_patch(Circle((x, y), radius, facecolor="#e8eaed", edgecolor="#3c4043", lw=1.5))
        for x0, y0, x1, y1 in d["rods"]:
            ax.plot([x0, x1], [y0, y1], color="#3c4043", lw=6, solid_capstyle="round")
        for x, y, (tex, lx, ly) in d["points"]:
            ax.plot([x], [y], "o", color="#3c4043", ms=3)
            ax.text(lx, ly, tex, ha="center", va="center", fontsize=10)
        for tail, head, kind, label in d["arrows"]:
            color = "#3c4043" if kind == "basis" else "#b3261e"
            ax.add_patch(FancyArrowPatch(tail, head, arrowstyle="-|>", mutation_scale=14, color=color,
                                         lw=1 if kind == "basis" else 2, fill=kind != "impulse"))
            if label:
                ax.text(label[1], label[2], "$" + label[0] + "$", color=color, ha="center", va="center", fontsize=11)
        for *path, label in d["curls"]:
            xs, ys = zip(*path)
            ax.plot(xs[:-1], ys[:-1], color="#b3261e", lw=2)
            ax.add_patch(FancyArrowPatch(path[-3], path[-1], arrowstyle="-|>", mutation_scale=14, color="#b3261e"))
            ax.text(label[1], label[2], "$" + label[0] + "$", color="#b3261e", ha="center", va="center", fontsize=11)
        ax.set_xlim(d["box"][0], d["box"][2])
        ax.set_ylim(d["box"][1], d["box"][3])
        ax.set_aspect("equal")
        ax.axis("off")
        ax.set_title(d["title"])
        plt.show()


draw_free_body_diagrams({data})"""

NBFORMAT = 4
NBFORMAT_MINOR = 5
ANSWER_LINE = "answer"  # each answer printed as "answer <name> = <value> <unit>"


class SympyCode(StrPrinter):
    """sympy expressions as sympy code in the notebook's names: ``sp.sin(theta)``,
    ``sp.Rational(1, 3)``, each symbol as its Python name."""

    def __init__(self, names: dict[sp.Symbol, str]):
        super().__init__()
        self.names = names

    def _print_Symbol(self, expr):
        return self.names[expr]

    def _print_Function(self, expr):
        return f"sp.{expr.func.__name__}({', '.join(self._print(a) for a in expr.args)})"

    def _print_Rational(self, expr):
        return f"sp.Rational({expr.p}, {expr.q})"

    def _print_Pow(self, expr, rational=False):
        if expr.exp is sp.S.Half:
            return f"sp.sqrt({self._print(expr.base)})"
        if expr.exp == -sp.S.Half:
            return f"1/sp.sqrt({self._print(expr.base)})"
        return super()._print_Pow(expr, rational)

    def _print_Pi(self, expr):
        return "sp.pi"

    def _print_Infinity(self, expr):
        return "sp.oo"

    def _print_Exp1(self, expr):
        return "sp.E"


def _symbol_line(name: str, symbol: sp.Symbol, comment: str = "") -> str:
    assumptions = "".join(f", {k}={v}" for k, v in sorted(symbol._assumptions_orig.items()))
    return f"{name} = sp.Symbol({symbol.name!r}{assumptions})" + (f"  # {comment}" if comment else "")


def _exact(value: float) -> str:
    """A given as exact sympy: its shortest decimal as a Rational (6.0 -> 6, 0.075 -> 3/40)."""
    if math.isinf(value):
        return "sp.oo" if value > 0 else "-sp.oo"
    if float(value).is_integer() and abs(value) < 1e15:
        return f"sp.Integer({int(value)})"
    return f"sp.Rational({repr(float(value))!r})"


def _angle(value: float) -> str:
    """An angle as the page shows it, in degrees, turned into radians by sympy (sp.rad(30) is pi/6);
    an angle that is no such number of degrees (to 6 figures) as its radians."""
    degrees = float(f"{math.degrees(value):.6g}")
    if math.isclose(math.radians(degrees), value, rel_tol=1e-13, abs_tol=1e-15):
        return f"sp.rad({_exact(degrees)})"
    return _exact(value)


def _unit(dimension: str) -> str:
    """SI, and an angle in radians (sympy's trigonometric functions take radians)."""
    return "rad" if dimension == "angle" else units.unit(dimension, "si")


def cells(problem: Problem, solution: Solution, link: str = "") -> list[tuple[str, str]]:
    """The notebook's cells, (kind, source) with kind "markdown" or "code"."""
    solver = problem.solver
    derivation = solver.derivation_of(solution)
    symbols = derivation.symbols  # parameters, chain inputs and results, by name
    for name in symbols:
        if not name.isidentifier() or keyword.iskeyword(name) or name in ("sp", "values", "N"):
            raise ValueError(f"{problem.id}: {name!r} cannot name a Python variable")
    names = {sym: name for name, sym in symbols.items()}
    code = SympyCode(names)
    specs = {p.name: p for p in solver.PARAMS}
    inputs = dict(solution.extras.get("chain_inputs", {}))
    results = {link_.name for link_ in derivation.chain}
    out: list[tuple[str, str]] = []
    md = lambda text: out.append(("markdown", text))  # noqa: E731
    py = lambda text: out.append(("code", text))  # noqa: E731

    md(f"# {problem.title}\n\n{problem.blurb} Source: {problem.source}.\n\n"
       "This notebook rebuilds the page's derivation with sympy, step by step, for the page's numbers, "
       "and prints the answers. It needs only sympy (`pip install sympy`)."
       + (f"\n\nThe page, with these numbers: <{link}>" if link else ""))
    py("import sympy as sp")

    chosen = [f"- {spec.label}: {spec.label_of(solution.params[name])}" for name, spec in specs.items()
              if isinstance(spec, Choice)]
    md("## The givens\n\nSI units; an angle as the degrees the page shows, turned into radians by `sp.rad`."
       + ("\n\nOptions (they choose which derivation applies):\n" + "\n".join(chosen) if chosen else ""))
    lines = []
    for name, sym in symbols.items():
        if name in results:
            continue
        spec = specs.get(name)
        lines.append(_symbol_line(name, sym, spec.label if spec else "an input the app computes by quadrature"))
    lines.append("")
    lines.append("values = {")
    for name in symbols:
        if name in results:
            continue
        spec = specs.get(name)
        value = solution.params[name] if spec else inputs[name]
        if spec is not None and spec.dimension == "angle" and math.isfinite(value):
            shown, comment = _angle(value), units.format_quantity(value, "angle", sig=6)
        else:
            shown, comment = _exact(value), f"{units.format_value(value, 6)} {_unit(spec.dimension) if spec else ''}"
        lines.append(f"    {name}: {shown},  # {comment}".rstrip())
    lines.append("}")
    py("\n".join(lines))

    symbolic = solution.steps[: solution.symbolic_steps]
    md("## The derivation, as the page shows it\n\n" + "\n\n".join(
        f"**{i}.** {step.title}\n\n$$\n{step.latex}\n$$" for i, step in enumerate(symbolic, start=1)))
    drawn = [fbd.as_data(d) for d in fbd.drawings(solver, solution)]
    if drawn:
        md("## The free-body diagram\n\nStep 2 of the method, drawn with matplotlib from the same shapes the page "
           "draws (the problem's declared forces, laid out for these numbers). Without matplotlib the cell "
           "says the diagram in words.")
        py(DRAW_DIAGRAMS.format(data=json.dumps(drawn, ensure_ascii=False)))
    md("## The chain of results, in sympy\n\nEach result as the derivation gives it, in the givens and the "
       "results before it.")
    answers = problem.answers_of(solution)
    labels = {a.name: a.label for a in answers}
    for link_ in derivation.chain:
        label = labels.get(link_.name) or link_.title or link_.name
        py(f"# {label} ({_unit(link_.dimension) or 'no unit'})\n"
           f"{_symbol_line(link_.name, link_.symbol)}\n"
           f"{link_.name}_expr = {code.doprint(link_.expr)}\n"
           f"sp.Eq({link_.name}, {link_.name}_expr)")

    md("## With the page's numbers, step by step\n\nEach result with the numbers substituted exactly, "
       "then evaluated to 15 figures.")
    evaluate = []
    for link_ in derivation.chain:
        evaluate.append(f"values[{link_.name}] = {link_.name}_expr.subs(values)\n"
                        f"print({link_.name!r}, '=', sp.N(values[{link_.name}], 15), {_unit(link_.dimension)!r})")
    py("\n".join(evaluate))

    md("## The answers\n\nSI units, angles in radians (and degrees).")
    show = ["for name, symbol, unit in ["]
    show += [f"    ({a.name!r}, {a.name}, {_unit(a.dimension)!r})," for a in answers]
    show += ["]:",
             "    value = sp.N(values[symbol], 15)",
             "    degrees = f'({sp.N(value * 180 / sp.pi, 6)} degrees)' if unit == 'rad' else ''",
             f"    print('{ANSWER_LINE}', name, '=', value, unit, degrees)"]
    py("\n".join(show))
    return out


def notebook(problem: Problem, solution: Solution, link: str = "") -> str:
    """The notebook as .ipynb JSON (nbformat 4.5; ``nbformat.validate`` accepts it)."""
    nb_cells = []
    for n, (kind, source) in enumerate(cells(problem, solution, link)):
        cell = {"cell_type": kind, "id": f"cell-{n}", "metadata": {}, "source": source.splitlines(keepends=True)}
        if kind == "code":
            cell |= {"execution_count": None, "outputs": []}
        nb_cells.append(cell)
    return json.dumps({"cells": nb_cells, "metadata": {
        "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
        "language_info": {"name": "python"}}, "nbformat": NBFORMAT, "nbformat_minor": NBFORMAT_MINOR},
        indent=1, ensure_ascii=False) + "\n"


def script(problem: Problem, solution: Solution, link: str = "") -> str:
    """The same cells as a Python script: Markdown as comments, every result printed."""
    out = []
    for kind, source in cells(problem, solution, link):
        if kind == "markdown":
            out.append("\n".join(f"# {line}".rstrip() for line in source.splitlines()))
        else:
            lines = source.splitlines()
            if lines and lines[-1].startswith("sp.Eq("):  # a notebook shows its last value; a script prints it
                lines[-1] = f"print({lines[-1]})"
            out.append("\n".join(lines))
    return "\n\n".join(out) + "\n"
