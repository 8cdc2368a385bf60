"""“Try it yourself”: answers and final steps hidden, a box for an answer (a number or an
expression), feedback on the common slips, then the solution on request. Also the instructor's
export of per-student variants. Nothing a student types is evaluated or rendered as Markdown."""
from __future__ import annotations

import re

import streamlit as st

from practice.judge import Judge
from practice.variants import MAX_SEED, variants_csv
from solvers.core import Solution
from ui import units
from ui.catalog import Problem
from ui.results import plain

def seed_from_url() -> tuple[int | None, str | None]:
    raw = st.query_params.get("seed")
    if raw is None:
        return None, None
    if re.fullmatch(r"\d{1,10}", raw) and int(raw) <= MAX_SEED:
        return int(raw), None
    return None, f"The link's variant number “{plain(raw[:20])}” is not a whole number from 0 to {MAX_SEED}; " \
                 "showing the textbook's numbers."


def practice_panel(problem: Problem, solution: Solution, answers, system: str) -> bool:
    """Draw the answer box; return True once the student asked to see the solution."""
    signature = repr(sorted(solution.params.items()))
    revealed_key = f"{problem.id}__revealed"
    if st.session_state.get(revealed_key) != signature:
        st.session_state.pop(revealed_key, None)
    st.info("Practice, not a proctored assessment: work the problem with these numbers, then check "
            "your answers. The solution stays hidden until you ask for it.", icon=":material/school:")
    judge = Judge(solution, problem.solver.derivation_of(solution))
    names = ", ".join(sorted(judge.typeable_symbols()))
    with st.form(key=f"{problem.id}__practice"):
        answer = st.selectbox("Answer to check", answers, format_func=lambda a: a.label.capitalize(),
                              key=f"{problem.id}__attempt_answer")
        text = st.text_input("Your answer", max_chars=200, key=f"{problem.id}__attempt",
                             help=f"A number, with a unit or read in the unit the page shows (degrees for "
                                  f"angles), or an expression in the problem's symbols: {names}. "
                                  "Write powers as ^ or **, e.g. 2/3*V*sin(theta) + R*omega/3.")
        submitted = st.form_submit_button("Check", type="primary")
    if submitted:
        verdict = judge.check(answer, text or "", system)
        if verdict.understood:
            st.caption("Read as:")
            st.latex(verdict.understood)
        (st.success if verdict.correct else st.error)(plain(verdict.message))
    if st.button("Reveal the solution", key=f"{problem.id}__reveal"):
        st.session_state[revealed_key] = signature
    return st.session_state.get(revealed_key) == signature


def instructor_export(problem: Problem) -> None:
    with st.expander("For instructors: per-student variants"):
        st.markdown(f"Hand out `?seed=N` links (N from 0 to {MAX_SEED:,}); each gives its own numbers, the "
                    "same in every session. Export the parameters and answers (SI units, radians) to check "
                    "students' work. Put no names or student ids in links: they end up in access logs.")
        c1, c2 = st.columns(2)
        first = c1.number_input("First seed", 0, MAX_SEED, 1, key=f"{problem.id}__seed_first")
        last = c2.number_input("Last seed", 0, MAX_SEED, 30, key=f"{problem.id}__seed_last")
        if st.button("Prepare the CSV", key=f"{problem.id}__prepare"):
            try:
                st.session_state[f"{problem.id}__csv"] = variants_csv(problem.solver, problem.id, int(first), int(last))
            except ValueError as error:
                st.error(plain(str(error)))
        data = st.session_state.get(f"{problem.id}__csv")
        if data:
            st.download_button("Download variants (CSV)", data, file_name=f"{problem.id}-variants.csv",
                               mime="text/csv", key=f"{problem.id}__download")
