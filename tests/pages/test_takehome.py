"""Take it home: the derivation as a standalone .tex (compiled with pdflatex where TeX is installed,
and in any case balanced, ASCII, every macro defined), as Markdown with $$ math, and as a notebook
and a script that re-derive it with sympy and print the solver's answers. The notebook runs in a
real Jupyter kernel (nbclient); the script form runs in-process over random variants."""
from __future__ import annotations

import contextlib
import io
import itertools
import json
import os
import re
import shutil
import subprocess
import time

import pytest
from hypothesis import given, settings, strategies as hst

from practice.variants import MAX_SEED, variant
from solvers.core import Choice
from tests.pages.test_pages import assert_clean, downloads_shown, run_page
from ui import documents, notebook
from solvers.catalog import BY_ID, PROBLEMS

IDS = [p.id for p in PROBLEMS]
PDFLATEX = shutil.which("pdflatex")


def cases(pid: str) -> list[dict]:
    """Every option combination the solver accepts, a variant, and (the disk) the sliding regime."""
    solver = BY_ID[pid].solver
    choices = [p for p in solver.PARAMS if isinstance(p, Choice)]
    out = [dict(zip([c.name for c in choices], combo)) for combo in itertools.product(*[c.options for c in choices])]
    out.append(variant(solver, pid, 31))
    if pid == "disk_wall":
        out.append({"mu": 0.02})
    return out


def solved(pid: str, params: dict):
    problem = BY_ID[pid]
    solution = problem.solver.solve(**params)
    return problem, solution, problem.answers_of(solution)


LINK = "http://127.0.0.1:8501/{}?e=0.6&theta0=30&units=us&q=a_b%20c#x"


def tex_of(pid: str, params: dict, exercise: bool = False) -> str:
    problem, solution, answers = solved(pid, params)
    return documents.latex(documents.document(problem, solution, answers, link=LINK.format(pid), exercise=exercise))


# -- LaTeX ------------------------------------------------------------------------------------------

# What LaTeX's kernel, the article class, amsmath and amssymb define, of what the documents use.
# A macro outside this list fails the test by name; where pdflatex is installed (CI) each problem's
# file is also compiled, which is the proof.
DEFINED = set(r"""
documentclass usepackage setlength textwidth oddsidemargin evensidemargin textheight topmargin parindent
parskip pagestyle begin end section subsection noindent textit textbf texttt emph par item allowbreak newpage vspace fill
ensuremath textbackslash textless textgreater textbar ldots
alpha beta gamma delta Delta theta tau mu pi sigma psi omega phi lambda rho Sigma ell infty int le ge approx
cdot times circ to surd sqrt frac tfrac dfrac left right lvert rvert quad qquad Rightarrow iff limits
sin cos tan operatorname mathbf mathrm boldsymbol hat dot ddot vec text small footnotesize scriptsize
subsubsection setcounter sum
draw fill node
""".split())  # the last line: TikZ's, in a free-body diagram's tikzpicture
ENVIRONMENTS = {"document", "tabular", "itemize", "enumerate", "equation*", "aligned", "matrix", "center", "tikzpicture"}


def macros(tex: str) -> set[str]:
    """Every control word used (a row break \\\\ and escaped characters are not macros)."""
    return set(re.findall(r"\\([A-Za-z]+)", re.sub(r"\\[\\{}$&#%_^~ ,;:!]", " ", tex)))


def unbalanced(tex: str) -> list[str]:
    """What is not closed or closed out of order: environments, braces, inline math."""
    found, stack = [], []
    for m in re.finditer(r"\\(begin|end)\{([^}]*)\}", tex):
        kind, name = m.groups()
        if kind == "begin":
            stack.append(name)
        elif not stack or stack.pop() != name:
            found.append(f"\\end{{{name}}} out of order")
    found += [f"\\begin{{{name}}} never ended" for name in stack]
    plain = re.sub(r"\\[\\{}$&#%_]", "", tex)
    depth = 0
    for c in plain:
        depth += {"{": 1, "}": -1}.get(c, 0)
        if depth < 0:
            found.append("a } before its {")
            depth = 0
    if depth:
        found.append(f"{depth} {{ never closed")
    found += [f"odd $ on line {n}" for n, line in enumerate(plain.splitlines(), 1) if line.count("$") % 2]
    return found


def test_the_checks_find_what_they_must():
    """Positive controls for the static checks used where pdflatex is missing."""
    assert unbalanced(r"\begin{itemize}\item x") == [r"\begin{itemize} never ended"]
    assert unbalanced(r"\begin{a}\begin{b}\end{a}\end{b}")
    assert unbalanced("{x") and unbalanced("x}") and unbalanced("$x")
    assert not unbalanced(r"\{ $a_{1}$ \\ \} \% \$")
    assert macros(r"\frac{a}{b} \\ \foo \{ \% x\,y") == {"frac", "foo"}


@pytest.mark.parametrize("pid", IDS)
def test_the_latex_is_ascii_balanced_and_uses_only_defined_macros(pid):
    for params in cases(pid):
        for exercise in (False, True):
            tex = tex_of(pid, params, exercise)
            assert documents.ascii_only(tex), (params, sorted({c for c in tex if ord(c) > 127}))
            assert not unbalanced(tex), (params, unbalanced(tex))
            assert macros(tex) <= DEFINED, (params, macros(tex) - DEFINED)
            assert set(re.findall(r"\\begin\{([^}]*)\}", tex)) <= ENVIRONMENTS


@pytest.mark.parametrize("pid", IDS)
def test_every_text_a_problem_shows_can_be_written_in_latex(pid):
    """Titles, notes, checks, slips, labels and options: every character has its LaTeX."""
    solver = BY_ID[pid].solver
    texts = [BY_ID[pid].title, BY_ID[pid].blurb, BY_ID[pid].source, *solver.ERRATA]
    for p in solver.PARAMS:
        texts += [p.label] + ([p.label_of(o) for o in p.options] if isinstance(p, Choice) else [])
    for params in cases(pid):
        problem, solution, answers = solved(pid, params)
        doc = documents.document(problem, solution, answers)
        texts += [t for t, _ in doc.steps] + list(doc.notes) + list(doc.checks) + [a[1] for a in doc.answers]
        texts += [v for _, _, v in doc.givens] + [a[2] for a in doc.answers]
    missing = set().union(*(documents.unmapped(t) for t in texts))
    assert not missing, documents.character_names(missing)


def test_unicode_text_becomes_latex():
    assert documents.tex_text("θ̇⁻² at 30°, ½ m·r², v₁ – “x” & 5 %") == (
        r"\ensuremath{\dot{\theta}^{-2}} at 30\ensuremath{^{\circ}}, \ensuremath{\tfrac12} m\ensuremath{\cdot}"
        r"r\ensuremath{^{2}}, v\ensuremath{_{1}} -- ``x'' \& 5 \%")
    assert documents.tex_markdown("a **bold** $x^2$ and *it*") == r"a \textbf{bold} $x^2$ and \emph{it}"


@pytest.mark.skipif(not PDFLATEX and not os.environ.get("CI"), reason="no pdflatex: apt-get install texlive-latex-base")
@pytest.mark.parametrize("pid", IDS)
def test_the_latex_compiles_with_pdflatex(pid, tmp_path):
    assert PDFLATEX, "CI installs texlive-latex-base (.ci/run)"
    files = {"derivation.tex": tex_of(pid, {})}
    if pid == IDS[0]:  # an exercise too, once
        files["exercise.tex"] = tex_of(pid, {}, exercise=True)
    for name, text in files.items():
        (tmp_path / name).write_text(text)
        run = subprocess.run([PDFLATEX, "-interaction=nonstopmode", "-halt-on-error", name], cwd=tmp_path,
                             capture_output=True, text=True, timeout=60)
        assert run.returncode == 0, run.stdout[-1500:]
        assert (tmp_path / name.replace(".tex", ".pdf")).stat().st_size > 1000


# -- Markdown ---------------------------------------------------------------------------------------

@pytest.mark.parametrize("pid", IDS)
def test_the_markdown_has_every_step_as_display_math(pid):
    problem, solution, answers = solved(pid, {})
    text = documents.markdown(documents.document(problem, solution, answers, link=LINK.format(pid)))
    assert text.startswith(f"# {problem.title}") and LINK.format(pid) in text
    blocks = re.findall(r"^\$\$\n(.*?)\n\$\$$", text, re.S | re.M)
    assert blocks == [step.latex for step in solution.steps]
    for label, _, value in documents.givens(problem, solution):
        assert f"| {label} |" in text and value in text
    assert text.count("$$") % 2 == 0 and all(f"**{value}**" in text for _, _, value in
                                             documents.document(problem, solution, answers).answers)


# -- the notebook -----------------------------------------------------------------------------------

def printed_answers(output: str) -> dict[str, float]:
    return {m.group(1): float(m.group(2)) for m in re.finditer(rf"^{notebook.ANSWER_LINE} (\w+) = (\S+)", output, re.M)}


def run_script(code: str) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "<take-home script>", "exec"), {"__name__": "__main__"})  # noqa: S102 (our own file)
    return out.getvalue()


def assert_same_answers(printed: dict[str, float], solution) -> None:
    assert set(printed) == set(solution.answers), (printed, dict(solution.answers))
    for name, value in solution.answers.items():
        assert printed[name] == pytest.approx(value, rel=1e-9, abs=1e-12), name


@pytest.mark.parametrize("pid", IDS)
def test_the_script_prints_the_solvers_answers_in_every_option(pid):
    for params in cases(pid):
        problem, solution, _ = solved(pid, params)
        assert_same_answers(printed_answers(run_script(notebook.script(problem, solution))), solution)


@pytest.mark.parametrize("pid", IDS)
@settings(max_examples=3, deadline=None)
@given(seed=hst.integers(0, MAX_SEED))
def test_the_script_prints_the_solvers_answers_for_any_variant(pid, seed):
    problem = BY_ID[pid]
    solution = problem.solver.solve(**variant(problem.solver, pid, seed))
    assert_same_answers(printed_answers(run_script(notebook.script(problem, solution))), solution)


def test_a_slip_in_the_notebook_is_caught():
    """Positive control: the comparison fails when a given or a step of the notebook is off."""
    problem, solution, _ = solved("rod_disk_spring", {})
    code = notebook.script(problem, solution)
    slipped_step = re.sub(r"^(U_spring_expr = )(.*)$", r"\1(\2)*sp.Rational(1001, 1000)", code, flags=re.M)
    slipped_given = code.replace("k: sp.Integer(20)", "k: sp.Integer(21)")
    for slipped in (slipped_step, slipped_given):
        assert slipped != code
        with pytest.raises(AssertionError):
            assert_same_answers(printed_answers(run_script(slipped)), solution)


def test_the_notebook_imports_nothing_of_the_app():
    problem, solution, _ = solved("sliding_ladder", {})
    imports = re.findall(r"^\s*(?:import|from)\s+(\w+)", notebook.script(problem, solution), re.M)
    assert set(imports) == {"sympy", "matplotlib"}  # matplotlib only for the diagram, and optional (below)


def test_the_notebooks_diagram_cell_says_the_diagram_without_matplotlib():
    """Without matplotlib the diagram's cell prints the diagram in words and the notebook runs on."""
    problem, solution, _ = solved("sliding_ladder", {})
    source = notebook.script(problem, solution).replace("import matplotlib.pyplot as plt", "raise ImportError")
    printed = run_script(source)
    assert "Free-body diagram, against the wall: the ladder" in printed
    assert printed_answers(printed)


@pytest.fixture(scope="module")
def kernel_ready():
    pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    from jupyter_client.kernelspec import NoSuchKernel, KernelSpecManager

    try:
        KernelSpecManager().get_kernel_spec("python3")
    except NoSuchKernel:
        pytest.skip("no python3 Jupyter kernel")


def test_each_problems_notebook_runs_in_jupyter_and_prints_the_solvers_answers(kernel_ready, tmp_path):
    """One notebook per problem (a variant's numbers), executed cell by cell in a real kernel from
    an empty folder: nothing of this project on its path."""
    import nbformat
    from nbclient import NotebookClient

    for n, pid in enumerate(IDS):
        problem = BY_ID[pid]
        solution = problem.solver.solve(**variant(problem.solver, pid, 100 + n))
        nb = nbformat.reads(notebook.notebook(problem, solution, LINK.format(pid)), as_version=4)
        nbformat.validate(nb)
        NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
        output = "".join(o.get("text", "") for cell in nb.cells if cell.cell_type == "code"
                         for o in cell.outputs if o.output_type == "stream")
        assert_same_answers(printed_answers(output), solution)
        equations = [o for cell in nb.cells if cell.cell_type == "code" for o in cell.outputs
                     if o.output_type == "execute_result" and "text/latex" in o.get("data", {})]
        assert len(equations) == len(problem.solver.derivation_of(solution).chain), pid  # each link shown


# -- on the page ------------------------------------------------------------------------------------

@pytest.mark.parametrize("pid", IDS)
def test_the_study_page_offers_the_derivation_and_a_notebook_for_its_numbers(pid):
    at = run_page(pid)
    assert_clean(at)
    files = downloads_shown(at)
    assert set(files) == {f"{pid}-derivation.tex", f"{pid}-derivation.md", f"{pid}.ipynb", f"{pid}.py"}
    solution = BY_ID[pid].solver.solve()
    assert_same_answers(printed_answers(run_script(files[f"{pid}.py"])), solution)
    assert json.loads(files[f"{pid}.ipynb"])["nbformat"] == 4
    assert all(step.latex in files[f"{pid}-derivation.md"] for step in solution.steps)


# -- no answer before "Show the solution" -----------------------------------------------------------

def test_an_assignment_link_offers_only_the_exercise_until_the_solution_is_shown(course):
    """A student's assignment link (the solution open before the due time here): before "Show the
    solution" its downloads are the statement and the method with no answer in them; after, the
    derivation and the notebook, which the same leak check finds the answers in."""
    from assignments import records
    from assignments.identity import link_query, parameters
    from tests.records.test_assignment_pages import create, instructor, student
    from tests.practice.test_practice import leaks, setup

    create(instructor(), before=True)
    ann = records.roster(records.assignments()[0][0])[0]
    page = student(link_query(ann))
    assert_clean(page)
    files = downloads_shown(page)
    assert set(files) == {"pendulum_rebound-exercise.tex", "pendulum_rebound-exercise.md"}
    _, solution, judge, answers = setup("pendulum_rebound", **parameters(ann, BY_ID["pendulum_rebound"].solver,
                                                                         "pendulum_rebound"))
    assert all(value in files["pendulum_rebound-exercise.md"] for _, _, value in
               documents.givens(BY_ID["pendulum_rebound"], solution))  # the student's own givens
    for name, text in files.items():
        assert leaks(text, solution, answers.values(), judge) == [], name
    page.button(key="pendulum_rebound__reveal").click().run()
    page.button(key="pendulum_rebound__reveal_sure").click().run()  # (an assignment asks first)
    files = downloads_shown(page)
    assert "pendulum_rebound.ipynb" in files
    for name, text in files.items():
        assert leaks(text, solution, answers.values(), judge), name


# -- the lesson page's download links (serve.py's route) --------------------------------------------

def test_a_download_link_makes_the_files_of_the_page_state_it_names():
    """The route's file for a changed state is the file the page's own functions make for that state,
    and each bad link gets a plain refusal, never a traceback."""
    from ui import takehome

    problem = BY_ID["disk_wall"]
    solution = problem.solver.solve(e=0.5)
    expected = {name: make() for _, name, _, make in
                takehome.files(problem, solution, problem.answers_of(solution), "si", "http://h/disk_wall?e=0.5")}
    for name, text in expected.items():
        status, kind, body = takehome.made("disk_wall", name, "e=0.5", "http://h/disk_wall")
        assert status == 200 and body.decode() == text, name
    assert takehome.made("disk_wall", "disk_wall.py", "e=0.5", "")[2] != takehome.made("disk_wall", "disk_wall.py", "", "")[2]
    for problem_id, name, query in [("disk_wall", "x.py", ""), ("nope", "nope.py", ""), ("disk_wall", "disk_wall.py", "e=NaN"),
                                    ("disk_wall", "disk_wall.py", "e=<script>"), ("disk_wall", "disk_wall.py", "e=-5"),
                                    ("disk_wall", "disk_wall.py", "e=" + "1" * 5000)]:
        status, kind, body = takehome.made(problem_id, name, query, "")
        assert status in (400, 404) and kind.startswith("text/plain") and b"Traceback" not in body, (query, body)


def test_the_download_route_serves_files_passes_the_rest_on_and_bounds_a_flood():
    from starlette.responses import PlainTextResponse
    from starlette.testclient import TestClient

    from ui.takehome import DOWNLOAD_BURST, DOWNLOAD_RATE, DownloadServer

    client = TestClient(DownloadServer(PlainTextResponse("streamlit")))
    started = time.monotonic()  # this client's bucket is filled at its first download, just below
    answer = client.get("/download/pendulum_rebound/pendulum_rebound-derivation.md?units=us&L=3.5"
                        "&x=)](https://evil.example/login)&assignment=1&seed=7&student=s001&sig=abc")
    assert answer.status_code == 200 and 'filename="pendulum_rebound-derivation.md"' in answer.headers["content-disposition"]
    # the file cites the page it came from, with the numbers it was made from and nothing else of the link
    # (a name the problem does not know made a Markdown link showing this address and going elsewhere)
    assert "(http://testserver/pendulum_rebound?L=3.5&units=us)" in answer.text
    assert "evil" not in answer.text and "sig=" not in answer.text
    assert client.get("/stick_ball").text == "streamlit"
    codes = [client.get("/download/stick_ball/stick_ball.py").status_code for _ in range(DOWNLOAD_BURST + 10)]
    refilled = DOWNLOAD_RATE * (time.monotonic() - started)  # tokens that came back meanwhile
    # the burst, less the derivation downloaded above, plus what came back meanwhile
    assert 429 in codes and DOWNLOAD_BURST - 1 <= codes.count(200) <= DOWNLOAD_BURST - 1 + refilled
