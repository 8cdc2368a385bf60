"""For instructors, under a problem page: the per-student variants (``?seed=N`` links, every course's,
behind the instructor key) and their CSV of parameters and answers; an LMS instructor, without the key,
is told their own course's assignments on the problem instead (their answer keys are on Handouts)."""
from __future__ import annotations

import streamlit as st

from assignments import records
from practice.variants import MAX_SEED, variants_csv
from solvers.catalog import Problem
from ui.results import plain
from ui.session import course_assignments, instructor_key_entry, is_instructor, lms_course


def _course_keys(problem: Problem) -> None:
    """An LMS instructor's session (no key given): its course's assignments on this problem, whose
    answer keys the Handouts page gives it; the ``?seed=N`` variants below are every course's, so
    they stay behind the key."""
    course = lms_course()
    if course is None:
        return
    try:
        placed = course_assignments(course)
        mine = [s.title for aid, s in records.assignments() if aid in placed and problem.id in s.problems]
    except records.RecordingUnavailable as error:
        st.error(str(error))
        return
    said = ", ".join(f"“{plain(t)}”" for t in mine) if mine else "none on this problem yet"
    st.markdown(f"From your course site. Your course's assignments here: {said}. Each student's givens and "
                "answers are on the **Handouts** page (in the menu, For instructors; choose **Answer key**), "
                "with no key to type. The numbered variants of `?seed=N` links below are shared by every "
                "course: they need the instructor key.")


def variants_export(problem: Problem) -> None:
    with st.expander("For instructors: per-student variants"):
        if not is_instructor():
            _course_keys(problem)
        if not instructor_key_entry(f"{problem.id}__instructor_key"):
            return
        st.markdown(f"Hand out `?seed=N` links (N from 0 to {MAX_SEED:,}); each gives its own numbers, the "
                    "same in every session, and opens in Practice. Export the parameters and answers (SI units, "
                    "radians) to check students' work. Put no names or student ids in links: they end up in "
                    "access logs.")
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
