"""Assignments as instructors and students meet them (AppTest, a SQLite file per test): the
instructor creates an assignment from a roster and reads the gradebook; a student's signed link
opens their variant, fixed, and records each checked answer ("recorded" only once committed); a
changed link is refused; with the database down, practice still works and says it is unrecorded."""
from __future__ import annotations

import csv
import html
import io
import urllib.parse
import datetime as dt
import math
from pathlib import Path

import pytest
from streamlit.testing.v1 import AppTest

from assignments import db, records
from assignments.identity import StudentIdentity, link_query, parameters
from solvers import pendulum_rebound
from solvers import units
from tests.conftest import COURSE_SECRET, INSTRUCTOR_KEY, reset_database_caches

ROOT = Path(__file__).resolve().parents[2]
KEY, SECRET = INSTRUCTOR_KEY, COURSE_SECRET
INSTRUCTOR_PAGE = str(ROOT / "app_pages" / "gradebook.py")


def instructor(*, key: bool = True) -> AppTest:
    at = AppTest.from_file(INSTRUCTOR_PAGE, default_timeout=60).run()
    if key:
        at.text_input(key="assign__instructor_key").input(KEY).run()
    return at


def create(at: AppTest, roster: str = "label\ns01\ns02\n", before: bool = False, title: str = "Week 9: the bounce",
           problems=("pendulum_rebound",), press: bool = True, **settings) -> AppTest:
    """Fill in the new assignment (the problems first, as an instructor would) and press Create
    (unless not ``press``)."""
    at.multiselect(key=new_key(at, "problems")).set_value(list(problems)).run()
    at.text_input(key=new_key(at, "title")).input(title)
    at.text_area(key=new_key(at, "roster")).input(roster)
    if before:
        at.checkbox(key=new_key(at, "before")).check()
    at.run()
    for key, value in settings.items():  # one at a time: a choice may bring the next input
        widget(at, "assign__new", f"_{key}").set_value(value).run()
    if at.button(key=new_key(at, "create")).disabled or not press:  # flagged: the test reads why
        return at
    return at.button(key=new_key(at, "create")).click().run()


def banner_of(page: AppTest) -> str:
    """A student's assignment banner and the rules in the expander under it (ui.assignments.assignment_heading)."""
    from ui.assignments import RULES

    rules = next(e for e in page.expander if e.label == RULES)
    return page.info[0].value + "\n\n" + "\n\n".join(m.value for m in rules.markdown)


def new_key(at: AppTest, name: str) -> str:
    """The key of the new assignment form's input ``name`` (the form's keys are renewed once one is created)."""
    return widget(at, "assign__new", f"_{name}").key


def widget(at: AppTest, prefix: str, suffix: str):
    """The instructor page's widget whose key starts and ends so (the middle is the form's version)."""
    return next(w for w in at.main if (k := getattr(w, "key", None) or "").startswith(prefix) and k.endswith(suffix))


def gradebook_table(at: AppTest):
    return next(t.value for t in at.table if "student" in t.value.columns)


def student(query: dict) -> AppTest:
    at = AppTest.from_file(str(ROOT / "app_pages" / "pendulum_rebound.py"), default_timeout=60)
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
    assert any("opens at your due time" in m.value for m in page.markdown)
    answer(page, "theta_rebound", "1")
    assert any("Recorded: attempt 1 of 3" in i.value for i in page.info)
    answer(page, "theta_rebound", rebound_in_degrees(ann))
    assert any("attempt 2 of 3" in i.value and "it counts" in i.value for i in page.success)
    table = page.table[-1].value
    assert list(table["attempt"]) == [1, 2] and list(table["counts"]) == ["no", "yes"]

    # Bob changes his link's variant to Ann's: refused, nothing recorded.
    tampered = student(link_query(bob) | {"seed": str(ann.seed)})
    assert "changed since your instructor issued it" in tampered.error[0].value
    assert not any(b.label == "Check" for b in tampered.button)

    # The gradebook, on screen and as CSV.
    book = instructor()
    shown = gradebook_table(book)
    assert list(shown["student"]) == ["s01", "s02"] and list(shown["score"]) == ["1 / 6", "0 / 6"]
    assert records.attempt_count(aid) == 2
    rows = list(csv.DictReader(io.StringIO(records.gradebook_csv(records.gradebook(aid)))))
    assert rows[0]["theta_rebound:right_at_attempt"] == "2" and rows[1]["theta_rebound:attempts_used"] == "0"


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
    the page of whoever opens the link. Such text is unreadable, so never recorded; what is recorded
    (a readable answer, here with Markdown's emphasis marks) is shown with every mark escaped."""
    create(instructor())
    ann = records.roster(records.assignments()[0][0])[0]
    page = answer(student(link_query(ann)), "theta_rebound",
                  "![x](https://attacker.example/p.png) [**click**](https://evil.example)")
    assert not page.exception and not page.table and records.attempt_count(ann.assignment_id) == 0
    page = answer(page, "theta_rebound", "1*2*3")
    typed = page.table[-1].value["you typed"].iloc[-1]
    assert typed == r"1\*2\*3"


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


# -- issue 26: typos cost nothing, late work is visible, every slip is undoable

def one_assignment(**settings):
    """An assignment created on the instructor's page; its id, settings and roster."""
    create(instructor(), **settings)
    aid, s = records.assignments()[0]
    return aid, s, records.roster(aid)


def page_text(at: AppTest) -> str:
    return "\n".join(e.value for kind in (at.markdown, at.info, at.warning, at.error, at.success)
                     for e in kind if isinstance(e.value, str)).replace("\\", "")  # Markdown's escapes


def test_a_typo_costs_no_attempt_and_the_icon_matches_the_verdict(course):
    """``hello``, ``w`` for ω and an unclosed bracket were each "Recorded: attempt n of 3" under a
    check-mark: they are explained, never recorded, and the right answer after them is attempt 1."""
    aid, _, (ann, _) = one_assignment()
    page = student(link_query(ann))
    for typo in ("hello", "w", "(1 + 2", "3 kg"):
        page = answer(page, "theta_rebound", typo)
        assert not page.exception
        assert any("not counted as an attempt" in w.value for w in page.warning), typo
        assert not any("Recorded" in e.value for kind in (page.info, page.success, page.warning) for e in kind)
    assert records.attempt_count(aid) == 0
    page = answer(page, "theta_rebound", "1")
    recorded = next(i for i in page.info if "Recorded: attempt 1 of 3" in i.value)
    assert recorded.icon == ":material/cancel:" and page.error[0].icon == ":material/cancel:"
    page = answer(page, "theta_rebound", "1")  # the same answer again: not a second attempt
    assert any("not counted again" in i.value for i in page.info) and records.attempt_count(aid) == 1
    # the same value typed another way (its unit, an expression of it) is the same answer too
    for same in ("1 °", "1deg", "2/2", " 1.000 "):
        page = answer(page, "theta_rebound", same)
        assert any("not counted again" in i.value for i in page.info), same
    assert records.attempt_count(aid) == 1
    page = answer(page, "theta_rebound", rebound_in_degrees(ann))
    right = next(s for s in page.success if "Recorded: attempt 2 of 3" in s.value)
    assert "it counts" in right.value and right.icon == ":material/task_alt:"
    assert "Highest angle after the bounce done (right)" in banner_of(page).replace("\\", "")


def test_the_banner_tells_one_story(course):
    """Graded, what counts, attempts left, the due time, when the solution opens; and no "Practice,
    not a proctored assessment … hidden until you ask" under it."""
    _, s, (ann, _) = one_assignment()
    page = student(link_query(ann))
    banner = banner_of(page)
    for said in ("Graded assignment: Week 9: the bounce", "What counts", "costs no attempt", "Attempts left",
                 f"Due {records.when_text(s.due, 'UTC')}", "The solution** opens at your due time",
                 "earns no points"):
        assert said in banner, said
    assert "not a proctored assessment" not in page_text(page)
    assert "until you ask for it" not in page_text(page)


def test_right_but_late_reads_as_right_but_late_everywhere(course):
    aid, s, (ann, bob) = one_assignment()
    records.edit(aid, records.replace(s, due=records.now() - dt.timedelta(hours=2)))
    page = answer(student(link_query(ann)), "theta_rebound", rebound_in_degrees(ann))
    said = next(w.value for w in page.warning if "Recorded" in w.value)
    assert "Right, but it earns no points" in said and "right but late" in said
    assert "has passed" in page.info[0].value or "has passed" in page.warning[0].value
    mine = "\n".join(m.value for m in page.markdown).replace("\\", "")
    assert "right but 2 h late (attempt 1): no credit" in mine  # was "not yet right; 2 of 3 attempts left"
    book = instructor()
    row = gradebook_table(book).iloc[0]
    assert row["Highest angle after the bounce"].startswith("right but") and row["score"] == "0 / 6"
    assert "got it right after the due time (no late credit)" in page_text(book)  # was "0 of 1 got it right"
    # how the score was made names the late answer (was "nothing yet = 0 of 6": as if never tried)
    assert row["how"] == "no points = 0 of 6 (Highest angle after the bounce right but 2 h late: no credit)"
    # the banner says it is done (was "0 of 3" left after a wrong answer following the right one)
    banner = banner_of(page).replace("\\", "")
    assert "Highest angle after the bounce done (right but 2 h late: no credit)" in banner


@pytest.mark.parametrize("late", [False, True])
def test_an_attempt_after_a_right_one_changes_nothing_and_says_so(course, late):
    """A right answer settles it (on time or late): nothing after it can earn more. A wrong answer
    after it was told "Not right; 0 attempts left" and the banner "0 of 3", as if the student had
    failed it."""
    aid, s, (ann, _) = one_assignment()
    if late:
        records.edit(aid, records.replace(s, due=records.now() - dt.timedelta(hours=2)))
    page = answer(student(link_query(ann)), "theta_rebound", rebound_in_degrees(ann))
    for wrong in ("1", "2"):
        page = answer(page, "theta_rebound", wrong)
        said = [i for i in page.info if "Recorded" in i.value]
        assert len(said) == 1 and "your attempt 1 at “Highest angle after the bounce” was already right, and it " \
            "stands: this one changes nothing" in said[0].value and "attempts left" not in said[0].value
    assert records.attempt_count(aid) == 3  # every attempt is still recorded
    banner = banner_of(page).replace("\\", "")
    assert ("Highest angle after the bounce done (right but 2 h late: no credit)" if late else
            "Highest angle after the bounce done (right)") in banner
    book = records.gradebook(aid)
    assert book.cell("s01", ("pendulum_rebound", "theta_rebound")).status(book.settings).startswith(
        "right but 2 h late (attempt 1)" if late else "right at attempt 1")


def test_an_answer_past_the_graded_attempts_is_not_called_attempt_4_of_3(course):
    """Right at the last graded attempt, then more answers: they were "attempt 4 of 3", "attempt 5 of 3"
    (and a wrong answer past the limit "attempt 4 at …, over your limit of 3"): no count past the limit."""
    aid, s, (ann, bob) = one_assignment()
    page = student(link_query(ann))
    for typed in ("1", "2", rebound_in_degrees(ann), "3", rebound_in_degrees(ann) + " deg"):
        page = answer(page, "theta_rebound", typed)
    said = " ".join(m.value for m in [*page.info, *page.success, *page.warning] if "Recorded" in m.value)
    assert "of 3" not in said and "answer 5 at “Highest angle after the bounce”, past your 3 graded attempts" in said, said
    assert records.attempt_count(aid) == 5  # every answer is still recorded
    fresh = student(link_query(bob))
    for typed in ("1", "2", "3", "4"):
        fresh = answer(fresh, "theta_rebound", typed)
    said = " ".join(m.value for m in fresh.warning if "Recorded" in m.value)
    assert "answer 4 at “Highest angle after the bounce”, past your 3 graded attempts" in said and "of 3" not in said, said


@pytest.mark.parametrize("length", [201, 10_000])
def test_an_answer_too_long_is_read_and_refused_in_words(course, length):
    """The box had max_chars=200: Streamlit dropped a longer paste without a word, and "Check" then said
    "Type an answer first." The judge now gets it and says the limit; no attempt is spent."""
    aid, _, (ann, _) = one_assignment()
    page = answer(student(link_query(ann)), "theta_rebound", "1+" * (length // 2) + "1"[: length % 2])
    said = " ".join(w.value for w in page.warning).replace("\\", "")  # Markdown's escapes
    assert f"too long ({length} characters; at most 200)" in said and "not counted as an attempt" in said
    assert "Type an answer first" not in said and records.attempt_count(aid) == 0


def test_late_credit_is_set_on_the_page_and_explained(course):
    aid, s, (ann, _) = one_assignment(late_policy="per_day", late_per_day=25.0)
    assert s.late_policy == "per_day" and s.late_value == 0.25
    records.edit(aid, records.replace(s, due=records.now() - dt.timedelta(hours=30)))
    page = answer(student(link_query(ann)), "theta_rebound", rebound_in_degrees(ann))
    assert any("earns 50 % of its points (late credit)" in w.value for w in page.warning)
    row = gradebook_table(instructor()).iloc[0]
    assert row["score"] == "0.5 / 6" and row["how"] == "Highest angle after the bounce 1 × 50 % (late) = 0.5 of 6"


def test_create_twice_or_after_a_reload_makes_one_assignment(course):
    at = create(instructor())
    # created: the form emptied (Create not pressable twice), the new assignment chosen and said so
    assert "Assignment 1 created for 2 students" in at.success[0].value
    assert at.text_input(key=new_key(at, "title")).value == "" and at.button(key=new_key(at, "create")).disabled
    assert at.selectbox(key="assign__chosen").value == 1
    again = create(instructor(), press=False)  # a reload: a new session, the same form
    assert any("exists already" in i.value for i in again.info)
    again.button(key=new_key(again, "create")).click().run()
    assert "Assignment 1 was already created" in again.success[0].value and "nothing was added" in again.success[0].value
    assert len(records.assignments()) == 1


@pytest.mark.parametrize("change, flagged", [
    ({"roster": "s01\ns02\ns01\n"}, "Repeated label: s01 (lines 1 and 3)"),
    ({"roster": "s01\n" + "x" * 140_000 + "\n"}, "too long"),
    ({"roster": 's01\n"' + "x" * 140_000}, "too long"),
    ({"roster": "s01\nJane Doe\n"}, "Line 2"),
    ({"due_day": dt.date(2020, 1, 1)}, "is already past"),
    ({"roster": ""}, "Paste or upload a roster"),
])
def test_bad_input_is_flagged_before_creating(course, change, flagged):
    at = create(instructor(), **change)
    assert not at.exception
    assert any(flagged in e.value.replace("\\", "") for e in at.error), [e.value for e in at.error]
    assert at.button(key=new_key(at, "create")).disabled and records.assignments() == []


def test_a_title_naming_another_problem_is_flagged(course):
    """"Week 13: ladder" became a disk assignment (the picker sat outside the form)."""
    at = create(instructor(), title="Week 13: ladder", problems=("disk_wall",))
    assert any("“ladder”" in w.value and "Ladder sliding" in w.value for w in at.warning)
    assert at.button(key=new_key(at, "create")).disabled and records.assignments() == []
    at.checkbox(key=new_key(at, "confirm")).check().run()
    at.button(key=new_key(at, "create")).click().run()
    assert records.assignments()[0][1].problems == ("disk_wall",)


def test_the_instructor_edits_closes_reopens_extends_and_undoes(course):
    aid, s, (ann, bob) = one_assignment()
    book = instructor()
    widget(book, f"assign__edit{aid}_", "_attempts").set_value(5)
    widget(book, f"assign__edit{aid}_", "_hints").uncheck()
    book.button[[b.label for b in book.button].index("Save the changes")].click().run()
    assert any("attempts per answer 3 → 5" in m.value for m in book.success)
    assert records.assignment(aid).attempts_allowed == 5 and not records.assignment(aid).hints

    # a tighter tolerance: said to apply from now on (a verdict already given stands; nothing said so)
    widget(book, f"assign__edit{aid}_", "_tolerance").set_value(0.01)
    book.button[[b.label for b in book.button].index("Save the changes")].click().run()
    assert any("tolerance" in m.value and "from now on" in m.value and "keep the verdict" in m.value
               for m in book.success), [m.value for m in book.success]

    due = records.assignment(aid).due
    widget(book, f"assign__edit{aid}_", "_zone").set_value("Asia/Tokyo")  # a new zone alone
    book.button[[b.label for b in book.button].index("Save the changes")].click().run()
    assert records.assignment(aid).timezone == "Asia/Tokyo" and records.assignment(aid).due == due

    book.button(key=f"assign__status_closed_{aid}").click().run()
    assert records.assignment(aid).status == "closed"
    page = answer(student(link_query(ann)), "theta_rebound", "1")
    assert any("closed" in w.value for w in page.warning) and records.attempt_count(aid) == 0
    book.button(key=f"assign__status_open_{aid}").click().run()
    assert records.assignment(aid).status == "open"
    assert widget(instructor(), f"assign__edit{aid}_", "_attempts").value == 5

    # Bob: a day's extension and one extra attempt, from the page
    records.edit(aid, records.replace(records.assignment(aid), due=records.now() - dt.timedelta(hours=1)))
    book = instructor()
    book.selectbox(key=f"assign__grant{aid}_who").select("s02").run()
    widget(book, f"assign__grant{aid}_", "_extend_s02").check()
    widget(book, f"assign__grant{aid}_", "_s02_due_day").set_value(dt.date.today() + dt.timedelta(days=2))
    widget(book, f"assign__grant{aid}_", "_extra_s02").set_value(1)
    book.button[[b.label for b in book.button].index("Save for this student")].click().run()
    assert not book.exception
    standing = records.standing(bob)
    assert standing.allowed == 6 and standing.due > records.now()
    page = answer(student(link_query(bob)), "theta_rebound", rebound_in_degrees(bob))
    assert any("it counts" in m.value for m in page.success) and "(your extension)" in page.info[0].value

    history = records.history(aid)
    assert [e.action for e in history][:4] == ["student", "edited", "reopened", "closed"]
    book = instructor()
    shown = next(t.value for t in book.table if "change" in t.value.columns)
    assert len(shown) == len(history) and "s02" in shown["what"].iloc[0]
    first_edit = history[-2]  # attempts 3 → 5, hints off
    widget(book, f"assign__undo_pick{aid}_", "").select(first_edit.id).run()
    widget(book, f"assign__undo{aid}_", "").click().run()
    assert not book.exception and any("Undone" in m.value for m in book.success)
    back = records.assignment(aid)
    assert back.attempts_allowed == 3 and back.hints and records.standing(bob).allowed == 4
    assert widget(book, f"assign__edit{aid}_", "_attempts").value == 3  # the form shows what is stored
    closed = next(e for e in history if e.action == "closed")  # reopened since: refused, in words
    widget(book, f"assign__undo_pick{aid}_", "").select(closed.id).run()
    widget(book, f"assign__undo{aid}_", "").click().run()
    assert any("changed since" in e.value for e in book.error) and records.assignment(aid).status == "open"


def test_after_a_change_the_undo_offers_the_newest_and_the_extension_follows_the_due_time(course):
    """An instructor picked an older change in "Undo a change", then edited the due time on the same page:
    Undo took back the older one (a student's extension), not the edit just made. And the extension's
    suggested date stayed the old due time's."""
    aid, s, _ = one_assignment()
    book = instructor()
    book.selectbox(key=f"assign__grant{aid}_who").select("s02").run()
    widget(book, f"assign__grant{aid}_", "_extend_s02").check()
    book.button[[b.label for b in book.button].index("Save for this student")].click().run()
    granted = records.history(aid)[0]
    assert granted.action == "student"
    widget(book, f"assign__undo_pick{aid}_", "").select(granted.id).run()
    book.selectbox(key=f"assign__grant{aid}_who").select("s01").run()  # its form shown before the edit
    new_due = s.due + dt.timedelta(days=3)
    widget(book, f"assign__edit{aid}_", "_due_day").set_value(new_due.date())
    book.button[[b.label for b in book.button].index("Save the changes")].click().run()
    edited = records.history(aid)[0]
    assert edited.action == "edited" and widget(book, f"assign__undo_pick{aid}_", "").value == edited.id
    assert widget(book, f"assign__grant{aid}_", "_s01_due_day").value == (new_due + dt.timedelta(days=2)).date()


def test_opening_the_solution_in_an_assignment_asks_first(course):
    """One tap on "Show the solution" (under Check, on a phone) cost every later answer its points, unasked."""
    aid, _, (ann, _) = one_assignment(before=True)
    page = student(link_query(ann))
    page.button(key="pendulum_rebound__reveal").click().run()
    assert any("Opening the solution is recorded" in w.value for w in page.warning)
    assert not records.solution_shown(ann)
    page.button(key="pendulum_rebound__reveal_keep").click().run()
    assert not any("Opening the solution" in w.value for w in page.warning) and not records.solution_shown(ann)
    page.button(key="pendulum_rebound__reveal").click().run()
    page.button(key="pendulum_rebound__reveal_sure").click().run()
    assert records.solution_shown(ann) and not page.exception
    page = answer(page, "theta_rebound", rebound_in_degrees(ann))
    said = next(w.value for w in page.warning if "Recorded" in w.value)
    assert "you had opened the solution" in said and "right but after the solution" in said and "late" not in said


def test_adding_students_checks_the_labels_first_and_counts_in_words(course):
    aid, s, _ = one_assignment()
    book = instructor()
    book.text_area(key=f"assign__more{aid}_roster").input("s03\nJane Doe\n").run()
    assert any("Line 2" in e.value for e in book.error)  # said before pressing, as in the new assignment's form
    assert book.button(key=f"assign__more{aid}_add").disabled
    book.text_area(key=f"assign__more{aid}_roster").input("s02\ns03\n").run()
    assert not book.button(key=f"assign__more{aid}_add").disabled and not book.warning
    book.button(key=f"assign__more{aid}_add").click().run()
    assert "Added 1 student; 1 student was on the roster already" in book.success[0].value
    assert [st_.label for st_ in records.roster(aid)] == ["s01", "s02", "s03"]
    records.edit(aid, records.replace(s, due=records.now() - dt.timedelta(hours=1)))
    book = instructor()
    book.text_area(key=f"assign__more{aid}_roster").input("s04\n").run()
    assert any("students added now start late" in w.value for w in book.warning)


def test_the_instructor_adds_a_problem_and_changes_what_counts(course):
    """The edit had the points of the answers chosen at creation only: no problem could be added, no
    answer counted or dropped, short of a new assignment and new links for everyone."""
    aid, s, (ann, _) = one_assignment()
    book = instructor()
    widget(book, f"assign__parts{aid}_", "_problems").set_value(["pendulum_rebound", "disk_wall"]).run()
    widget(book, f"assign__parts{aid}_", "_answers_disk_wall").set_value(["v1x", "omega1"]).run()
    widget(book, f"assign__parts{aid}_", "_weight_disk_wall_omega1").set_value(2.0)
    widget(book, f"assign__parts{aid}_", "_answers_pendulum_rebound").set_value(["theta_rebound"]).run()
    widget(book, f"assign__parts{aid}_", "_save").click().run()
    assert not book.exception
    saved = records.assignment(aid)
    assert saved.problems == ("pendulum_rebound", "disk_wall") and saved.part("pendulum_rebound").answers == ("theta_rebound",)
    assert saved.part("disk_wall").weights == (1.0, 2.0) and saved.out_of == 1 + 3
    assert "Spinning disk hits a rough wall added" in book.success[0].value
    # Ann's link, as sent, now lists both problems; the new one takes her answers
    page = student(link_query(ann))
    assert "This assignment has 2 problems" in page_text(page)
    # with the first problem taken out, the link sent before points to the assignment's problems
    records.edit(aid, records.replace(saved, parts=(saved.part("disk_wall"),)))
    refused = student(link_query(ann))
    assert "not part of this assignment" in refused.error[0].value
    problems = next(h.proto.body for h in refused.get("html") if "<ol>" in h.proto.body)  # opened in this tab
    assert '<a href="disk_wall?assignment=' in problems and 'target="_self"' in problems, problems


def test_the_links_say_that_opening_one_answers_as_its_student(course):
    """An instructor who clicked a student's link in the table answered as that student (recorded, and the
    solution there costs the student its points): the page says so, and shows the links as text to copy."""
    aid, s, _ = one_assignment()
    book = instructor()
    assert any("answers as that student" in w.value for w in book.info)
    links = next(h.proto.body for h in book.get("html") if 'class="dl-links"' in h.proto.body)
    assert links.count("<code>http") == 2 and "<a " not in links, links  # text to copy (each with its Copy button)
    assert links.count('<button type="button" data-dl-copy=') == 2


def test_a_warned_edit_is_dropped_once_its_inputs_change(course):
    """The problems' section stands outside a form: pressing Save, reading the warning, correcting a
    weight and pressing "Save it anyway" saved the edit as it was before the correction."""
    aid, s, (ann, _) = one_assignment()
    answer(student(link_query(ann)), "theta_rebound", rebound_in_degrees(ann))
    book = instructor()
    counted = list(s.part("pendulum_rebound").answers)
    widget(book, f"assign__parts{aid}_", "_answers_pendulum_rebound").set_value(
        [a for a in counted if a != "theta_rebound"]).run()
    widget(book, f"assign__parts{aid}_", "_save").click().run()
    assert any("Nothing is saved yet" in w.value for w in book.warning)
    widget(book, f"assign__parts{aid}_", "_answers_pendulum_rebound").set_value(counted).run()  # corrected
    assert not any("Nothing is saved yet" in w.value for w in book.warning)
    assert not [b for b in book.button if b.label == "Save it anyway"] and records.assignment(aid) == s


def test_a_unit_left_out_is_explained_whatever_the_feedback(course):
    """With hints and slip names off, an answer in deg/s where rad/s is read said "Not right. Check each
    step" and "not counted": the student was told to redo right work."""
    aid, _, (ann, _) = one_assignment(hints=False, slip_names=False)
    params = parameters(ann, pendulum_rebound, "pendulum_rebound")
    after = pendulum_rebound.solve(**params).answers["omega_after"]
    page = answer(student(link_query(ann)), "omega_after", f"{math.degrees(after):.6g}")
    said = " ".join(w.value for w in page.warning)
    assert "deg/s" in said and "not counted as an attempt" in said and "Check each step" not in said
    assert records.attempt_count(aid) == 0


def slip_value(params: dict) -> str:
    """The rebound angle (degrees) that the e-for-e² slip gives at these givens."""
    from practice.judge import Judge

    slip = next(m for m in pendulum_rebound.MISTAKES if m.answer == "theta_rebound")
    solution = pendulum_rebound.solve(**params)
    judge = Judge(solution, pendulum_rebound.derivation_of(solution), pendulum_rebound.ANSWERS)
    return f"{math.degrees(judge._value_of(slip.wrong(dict(solution.params)))):.5f}"


def test_feedback_policy_per_assignment_and_practice_keeps_its_hints(course):
    from tests.records.test_records import E_FOR_E2

    aid, s, (ann, _) = one_assignment()
    typed = slip_value(parameters(ann, pendulum_rebound, "pendulum_rebound"))
    page = answer(student(link_query(ann)), "theta_rebound", typed)
    assert E_FOR_E2 in page.error[0].value  # hints on: as in Practice
    records.edit(aid, records.replace(s, hints=False))
    page = answer(student(link_query(ann)), "theta_rebound", typed[:-1])
    said = page.error[0].value.replace("\\", "")
    assert E_FOR_E2.split(":")[1].strip()[:20] not in said and "e where e² belongs" in said  # named, no hint
    records.edit(aid, records.replace(records.assignment(aid), slip_names=False))
    page = answer(student(link_query(ann)), "theta_rebound", typed[:-2])
    assert page.error[0].value.startswith("Not right. Check each step")
    mine = next(t.value for t in page.table if "slip" in t.value.columns)  # nor does the list of attempts name it
    assert len(mine) == 3 and set(mine["slip"]) == {""}
    practice = AppTest.from_file(str(ROOT / "app_pages" / "pendulum_rebound.py"), default_timeout=60)
    practice.query_params.update({"practice": "1"})
    practice = answer(practice.run(), "theta_rebound", slip_value(pendulum_rebound.solve().params))
    assert E_FOR_E2 in practice.error[0].value  # Practice keeps today's feedback


def test_the_answer_after_the_last_attempt(course):
    aid, s, (ann, _) = one_assignment()
    records.edit(aid, records.replace(s, attempts_allowed=1, answer_after_last=True))
    page = answer(student(link_query(ann)), "theta_rebound", "1")
    expected = units.format_quantity(pendulum_rebound.solve(**parameters(ann, pendulum_rebound, "pendulum_rebound"))
                                     .answers["theta_rebound"], "angle")
    assert any("used every attempt" in i.value and expected in i.value for i in page.info)


def test_a_problem_set_is_one_assignment_with_one_score(course):
    from solvers import disk_wall

    aid, s, (ann, _) = one_assignment(problems=("pendulum_rebound", "disk_wall"), title="Week 9: two impacts")
    assert s.problems == ("pendulum_rebound", "disk_wall") and s.out_of == 6 + 7
    page = student(link_query(ann))
    assert "This assignment has 2 problems" in page_text(page)
    # the other problem's link: the same signed query, opened in the same tab or LMS frame (a Markdown
    # link opened a new tab)
    (links,) = [m for m in page.markdown if "This assignment has 2 problems" in m.value]
    query = html.escape(urllib.parse.urlencode(link_query(ann)))
    assert links.allow_html and f'<a href="disk_wall?{query}" target="_self">' in links.value
    other = AppTest.from_file(str(ROOT / "app_pages" / "disk_wall.py"), default_timeout=60)
    other.query_params.update(link_query(ann))
    other.run()
    assert not other.exception and "Graded assignment" in other.info[0].value
    value = disk_wall.solve(**parameters(ann, disk_wall, "disk_wall")).answers["v1x"]
    names = [a.name for a in disk_wall.ANSWERS]
    other.selectbox(key="disk_wall__attempt_answer").select_index(names.index("v1x"))
    other.text_input(key="disk_wall__attempt").input(f"{units.to_display(value, 'speed'):.6g}")
    other.button(key="disk_wall__check").click().run()
    assert any("it counts" in m.value for m in other.success)
    answer(page, "theta_rebound", rebound_in_degrees(ann))
    book = instructor()
    row = gradebook_table(book).iloc[0]
    assert row["score"] == "2 / 13"
    # the table heads each answer with its problem's number, the titles said once above it
    assert row["P1: Highest angle after the bounce"] == "right at attempt 1"
    assert row["how"].startswith("P1: Highest angle after the bounce 1 + P2: Velocity after, along the wall 1 =")
    assert any("**P1**: Rod" in m.value and "**P2**: Spinning disk" in m.value for m in book.markdown), \
        [m.value[:60] for m in book.markdown]


def test_a_title_too_long_is_kept_and_refused_in_words(course):
    """The title box had max_chars=120: Streamlit dropped a longer paste without a word (the box stayed
    empty). It is kept as typed, the check above Create says the limit, and nothing is created."""
    at = create(instructor(), title="Week 9: " + "the bouncing pendulum, " * 6)
    assert at.text_input(key=new_key(at, "title")).value.startswith("Week 9: the bouncing pendulum")
    assert "The title needs 1 to 120 characters (it has 146)." in page_text(at)
    assert records.assignments() == []


def test_an_edit_that_takes_points_already_earned_asks_first_and_says_whose(course):
    """Moving the due time before an answer already recorded right turned it "right but late: no credit"
    under a message saying "late answers from now on": the page now says, before saving, whose score drops
    and by how much, and saves only when asked again; taking back a student's extension likewise."""
    aid, s, (ann, bob) = one_assignment()
    page = answer(student(link_query(ann)), "theta_rebound", rebound_in_degrees(ann))
    assert any("it counts" in m.value for m in page.success)
    earned = records.gradebook(aid).score("s01")
    assert earned > 0

    def move_due_to_yesterday(book):
        widget(book, f"assign__edit{aid}_", "_due_day").set_value(dt.date.today() - dt.timedelta(days=1))
        book.button[[b.label for b in book.button].index("Save the changes")].click().run()
        return book

    book = move_due_to_yesterday(instructor())
    said = " ".join(w.value for w in book.warning)
    assert "Nothing is saved yet" in said and f"s01 {records._number(earned)} of 6 → 0 of 6" in said, said
    assert "s02" not in said and records.assignment(aid).due == s.due  # bob had nothing to lose
    book.button[[b.label for b in book.button].index("Do not save it")].click().run()
    assert records.assignment(aid).due == s.due and not book.warning

    book = move_due_to_yesterday(book)
    book.button[[b.label for b in book.button].index("Save it anyway")].click().run()
    assert not book.exception and records.assignment(aid).due < records.now()
    assert any("those already recorded included" in m.value for m in book.success)
    assert records.gradebook(aid).score("s01") == 0

    # Bob answers right within his extension; taking the extension back asks first too
    records.grant(aid, "s02", extended_due=records.now() + dt.timedelta(days=2))
    page = answer(student(link_query(bob)), "theta_rebound", rebound_in_degrees(bob))
    assert any("it counts" in m.value for m in page.success)
    book = instructor()
    book.selectbox(key=f"assign__grant{aid}_who").select("s02").run()
    widget(book, f"assign__grant{aid}_", "_extend_s02").uncheck()
    book.button[[b.label for b in book.button].index("Save for this student")].click().run()
    assert "s02" in " ".join(w.value for w in book.warning) and records.standing(bob).grant.extended_due is not None
    book.button[[b.label for b in book.button].index("Save it anyway")].click().run()
    assert records.standing(bob).grant.extended_due is None and records.gradebook(aid).score("s02") == 0

    # an undo that lowers a score says so after
    records.grant(aid, "s02", extended_due=records.now() + dt.timedelta(days=2))
    book = instructor()
    widget(book, f"assign__undo_pick{aid}_", "").select(records.history(aid)[0].id).run()
    widget(book, f"assign__undo{aid}_", "").click().run()
    assert any("It lowered the share of the points earned by 1 student: s02" in m.value for m in book.success)


def test_an_edit_that_lowers_no_one_s_share_saves_at_once(course):
    """Points doubled on every answer, more attempts, a later due time: saved without a question."""
    aid, s, (ann, _) = one_assignment()
    answer(student(link_query(ann)), "theta_rebound", rebound_in_degrees(ann))
    doubled = records.replace(s, parts=tuple(records.replace(part, weights=tuple(2 * part.weight(n) for n in part.answers))
                                             for part in s.parts))
    assert records.points_taken(aid, settings=doubled) == []
    assert records.points_taken(aid, settings=records.replace(s, due=s.due + dt.timedelta(days=3))) == []
    taken = records.points_taken(aid, settings=records.replace(s, due=records.now() - dt.timedelta(days=1)))
    assert [t.label for t in taken] == ["s01"] and taken[0].after == 0 < taken[0].before


def test_the_points_boxes_come_in_reading_order(course):
    """Four columns of "Points:" boxes put the first, fifth… answers in one column: the page's order (and the
    Tab key's) went down each column. Rows of four keep the answers' own order, on creation and in the edit."""
    from solvers import disk_wall

    names = [f"Points: {a.heading}" for a in disk_wall.ANSWERS]
    at = instructor()
    at.multiselect(key=new_key(at, "problems")).set_value(["disk_wall"]).run()
    shown = [w.label for w in at.number_input if w.label.startswith("Points:")]
    assert len(names) > 4 and shown == names
    aid, _, _ = one_assignment(problems=("disk_wall",), title="Week 9: the wall")
    book = instructor()
    edited = [w.label for w in book.number_input if w.label.startswith("Points:") and w.key.startswith(f"assign__parts{aid}_")]
    assert len(edited) == len(disk_wall.ANSWERS) and edited == shown


def test_the_students_links_are_made_from_the_apps_address_at_either_of_the_pages_addresses():
    """The instructor's page is at /assignments and, for older links, /gradebook: a student's link is the
    app's address and the problem, whichever the instructor opened."""
    from ui.assignments import app_base

    for path in ("assignments", "gradebook", "assignments/", "gradebook?lti=x"):
        assert app_base(f"https://dl.example.edu/dynamics/{path}") == "https://dl.example.edu/dynamics", path
    assert app_base("http://localhost:8501/assignments") == "http://localhost:8501"


def test_named_slips_shows_its_real_state_and_why_while_hints_are_on(course):
    """Issue 54: "Named slips" was greyed out while Hints was on, showing whatever it was left at (unticked,
    though hints name every slip) and not saying why. While Hints is on it is ticked, cannot be changed, and
    says why; with Hints off it is the instructor's again, as they left it."""
    at = instructor()
    hints = widget(at, "assign__new", "_hints")
    assert hints.value  # (on by default)
    names = widget(at, "assign__new", "_slip_names_shown")
    assert names.value and names.disabled and "Hints on already name the slip" in (names.help or "")
    assert any("Hints on already name the slip" in c.value for c in at.caption)
    hints.uncheck().run()
    names = widget(at, "assign__new", "_slip_names")
    assert names.value and not names.disabled
    names.uncheck().run()
    widget(at, "assign__new", "_hints").check().run()
    shown = widget(at, "assign__new", "_slip_names_shown")
    assert shown.value and shown.disabled  # the real state: the hint names the slip
    widget(at, "assign__new", "_hints").uncheck().run()
    assert not widget(at, "assign__new", "_slip_names").value  # as the instructor left it
    assert not at.exception and not at.warning
