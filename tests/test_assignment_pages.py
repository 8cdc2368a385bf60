"""Assignments as instructors and students meet them (AppTest, a SQLite file per test): the
instructor creates an assignment from a roster and reads the gradebook; a student's signed link
opens their variant, fixed, and records each checked answer ("recorded" only once committed); a
changed link is refused; with the database down, practice still works and says it is unrecorded."""
from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import pytest
from streamlit.testing.v1 import AppTest

from assignments import db, records, signing
from assignments.identity import StudentIdentity, link_query, parameters
from solvers import pendulum_rebound
from solvers import units

ROOT = Path(__file__).resolve().parent.parent
KEY, SECRET = "instructor-key-0018", "course-secret-for-the-tests-0018"
INSTRUCTOR_PAGE = str(ROOT / "pages" / "gradebook.py")


def reset_database_caches():
    from ui.assignments import _schema_ready

    db.engine.cache_clear()
    _schema_ready.clear()


@pytest.fixture
def course(monkeypatch, tmp_path):
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", KEY)
    monkeypatch.setenv(signing.SECRET_ENV, SECRET)
    monkeypatch.setenv(db.URL_ENV, f"sqlite:///{tmp_path / 'course.sqlite'}")
    reset_database_caches()
    yield
    reset_database_caches()


def instructor(*, key: bool = True) -> AppTest:
    at = AppTest.from_file(INSTRUCTOR_PAGE, default_timeout=60).run()
    if key:
        at.text_input(key="assign__instructor_key").input(KEY).run()
    return at


def create(at: AppTest, roster: str = "label\ns01\ns02\n", before: bool = False) -> AppTest:
    at.selectbox(key="assign__problem").select("pendulum_rebound").run()
    at.text_input(key="assign__title").input("Week 9: the bounce")
    at.text_area(key="assign__roster").input(roster)
    if before:
        at.checkbox(key="assign__before").check()
    return next(b for b in at.button if b.label.startswith("Create the assignment")).click().run()


def student(query: dict) -> AppTest:
    at = AppTest.from_file(str(ROOT / "pages" / "pendulum_rebound.py"), default_timeout=60)
    at.query_params.update(query)
    return at.run()


def answer(at: AppTest, name: str, text: str) -> AppTest:
    names = [a.name for a in pendulum_rebound.ANSWERS]
    at.selectbox(key="pendulum_rebound__attempt_answer").select_index(names.index(name))
    at.text_input(key="pendulum_rebound__attempt").input(text)
    return at.button(key="pendulum_rebound__check").click().run()


def rebound_in_degrees(who: StudentIdentity) -> str:
    params = parameters(who, pendulum_rebound, "pendulum_rebound")
    return f"{math.degrees(pendulum_rebound.solve(**params).answers['theta_rebound']):.4f}"


def test_the_page_is_closed_without_the_key(course):
    at = instructor(key=False)
    assert not any(b.label.startswith("Create") for b in at.button)
    at.text_input(key="assign__instructor_key").input("not-the-key").run()
    assert at.error and not any(b.label.startswith("Create") for b in at.button)


def test_an_assignment_end_to_end(course):
    at = create(instructor())
    assert not at.exception and "created for 2 students" in at.success[0].value
    aid, settings = records.assignments()[0]
    assert settings.problem == "pendulum_rebound" and settings.attempts_allowed == 3
    ann, bob = records.roster(aid)

    # Ann: a slip, then the right number. Each attempt is recorded, and says so.
    page = student(link_query(ann))
    assert not page.exception and "Week 9: the bounce" in page.info[0].value
    assert "Fixed by your assignment link" in page.sidebar.markdown[-1].value
    assert not any(b.label == "Show the solution" for b in page.button)  # not before the due time
    assert any("opens at the due time" in m.value for m in page.markdown)
    answer(page, "theta_rebound", "1")
    assert any("Recorded: attempt 1 of 3" in i.value for i in page.info)
    answer(page, "theta_rebound", rebound_in_degrees(ann))
    assert any("attempt 2 of 3" in i.value and "it counts" in i.value for i in page.info)
    table = page.table[-1].value
    assert list(table["#"]) == [1, 2] and list(table["counts"]) == ["no", "yes"]

    # Bob changes his link's variant to Ann's: refused, nothing recorded.
    tampered = student(link_query(bob) | {"seed": str(ann.seed)})
    assert "changed since your instructor issued it" in tampered.error[0].value
    assert not any(b.label == "Check" for b in tampered.button)

    # The gradebook, on screen and as CSV.
    book = instructor()
    shown = book.table[-1].value
    assert list(shown["student"]) == ["s01", "s02"] and list(shown["score"]) == ["1 / 6", "0 / 6"]
    assert records.attempt_count(aid) == 2
    rows = list(csv.DictReader(io.StringIO(records.gradebook_csv(records.gradebook(aid)))))
    assert rows[0]["theta_rebound:first_right_attempt"] == "2" and rows[1]["theta_rebound:attempts"] == "0"


def test_a_link_cannot_change_the_numbers_it_was_issued_with(course):
    create(instructor())
    aid, _ = records.assignments()[0]
    ann = records.roster(aid)[0]
    page = student(link_query(ann) | {"e": "1", "theta0": "80"})  # an easier variant, asked for in the link
    params = parameters(ann, pendulum_rebound, "pendulum_rebound")
    statement = next(m.value for m in page.markdown if m.value.startswith("### The problem"))
    assert units.format_quantity(params["e"], "dimensionless") in statement
    assert "e" not in page.query_params and page.query_params["sig"] == link_query(ann)["sig"]


def test_with_the_database_down_practice_works_unrecorded(course, monkeypatch):
    create(instructor())
    aid, _ = records.assignments()[0]
    ann = records.roster(aid)[0]
    monkeypatch.setenv(db.URL_ENV, "sqlite:////dev/null/down/course.sqlite")
    reset_database_caches()
    page = student(link_query(ann))
    assert not page.exception and "cannot be reached" in page.warning[0].value
    answer(page, "theta_rebound", rebound_in_degrees(ann))
    assert page.success and page.success[0].value.startswith("Right")  # judged all the same
    assert not any("Recorded" in i.value for i in page.info)
    assert "cannot be reached" in instructor().error[0].value


def test_what_a_student_typed_is_shown_as_plain_text(course):
    """st.table renders its cells as Markdown: a typed image or link would load or be clickable on
    the page of whoever opens the link. The cell holds every punctuation mark escaped (typed here)."""
    create(instructor())
    ann = records.roster(records.assignments()[0][0])[0]
    page = answer(student(link_query(ann)), "theta_rebound",
                  "![x](https://attacker.example/p.png) [**click**](https://evil.example)")
    assert not page.exception
    typed = page.table[-1].value["you typed"].iloc[-1]
    assert typed == (r"\!\[x\]\(https\:\/\/attacker\.example\/p\.png\) "
                     r"\[\*\*click\*\*\]\(https\:\/\/evil\.example\)")


def givens(page: AppTest) -> list[str]:
    statement = next(m.value for m in page.markdown if m.value.startswith("### The problem"))
    return [row for row in statement.splitlines() if row.startswith("| ") and "---" not in row]


def test_a_plain_variant_link_is_not_the_assignment(course):
    """The number in a student's link opened as ``?seed=N`` (no signature, "Show the solution" offered,
    nothing recorded) gives other givens: the solution before the due time stays closed."""
    create(instructor())
    aid, _ = records.assignments()[0]
    ann = records.roster(aid)[0]
    signed = student(link_query(ann))
    plain_link = student({"seed": str(ann.seed)})
    assert not plain_link.exception and any(b.label == "Show the solution" for b in plain_link.button)
    assert len(givens(signed)) == len(givens(plain_link)) > 3
    assert givens(signed) != givens(plain_link)
    assert str(ann.seed) not in "".join(m.value for m in signed.sidebar.markdown)  # no number to reuse
