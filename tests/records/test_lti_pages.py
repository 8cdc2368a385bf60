"""What an LMS launch hands the pages (AppTest, SQLite): a learner's hand-off opens their variant of the
assignment, records under their LMS label and queues their score; the hand-off works once; the
course's instructor sees that course's assignments only, with no key to type, and the grades sent."""
from __future__ import annotations

import datetime as dt

from assignments import db, migrate, records
from lti import launch as lti
from assignments.identity import parameters
from solvers import pendulum_rebound
from tests.records.test_assignment_pages import INSTRUCTOR_PAGE, ROOT, answer, student

from streamlit.testing.v1 import AppTest

DUE = dt.datetime(2031, 1, 1, tzinfo=dt.timezone.utc)
EVERY_ANSWER = tuple(a.name for a in pendulum_rebound.ANSWERS)  # as the shared ``answer`` helper picks them
ISSUER = "https://lms.test"


def placed(title: str, context: str, resource: str) -> int:
    aid = records.create(records.Settings.of(title, "pendulum_rebound", EVERY_ANSWER, 5e-3, DUE, 3)).id
    with db.session() as s, s.begin():
        s.add(db.LtiLink(assignment_id=aid, issuer=ISSUER, deployment_id="d1", context_id=context,
                         resource_link_id=resource, lineitem=""))
    return aid


def lms_student(aid: int, sub: str):
    label = lti.label_of(ISSUER, sub)
    records.enrol(aid, [label])
    with db.session() as s, s.begin():
        s.add(db.LtiMember(assignment_id=aid, label=label, issuer=ISSUER, sub=sub, name=""))
    return label, lti.handoff({"role": "student", "a": aid, "l": label, "s": records.student_seed(aid, label)})


def test_a_learner_launch_opens_their_variant_records_and_works_once(course):
    migrate.upgrade()
    aid = placed("Week 9 from the LMS", "course-1", "rl-1")
    label, token = lms_student(aid, "learner-7")
    page = student({"lti": token})
    assert not page.exception and "Week 9 from the LMS" in page.info[0].value and label.replace("-", "\\-") in page.info[0].value
    assert "lti" not in page.query_params  # the hand-off is taken out of the address at once
    answer(page, "theta_rebound", "1")
    assert any("Recorded: attempt 1 of 3" in i.value for i in page.info)
    with db.session() as s:
        assert s.query(db.LtiScore).filter_by(assignment_id=aid, label=label).count() == 1  # queued for the LMS
    elsewhere = AppTest.from_file(str(ROOT / "app_pages" / "disk_wall.py"), default_timeout=60)
    elsewhere.session_state["lti__arrival"] = page.session_state["lti__arrival"]  # the same session, another page
    elsewhere.run()
    assert not elsewhere.exception and not elsewhere.error  # practice there, as anyone
    assert not any("Graded assignment" in i.value for i in elsewhere.info)
    again = student({"lti": token})  # the same address opened again (a reload, a copied link)
    assert "expired or was already used" in again.error[0].value
    assert not any(b.label == "Check" for b in again.button)


def test_the_lms_instructor_sees_their_course_only_without_a_key(course):
    migrate.upgrade()
    mine = placed("Ours", "course-1", "rl-1")
    placed("Another course's", "course-2", "rl-2")
    records.create(records.Settings.of("Signed links only", "pendulum_rebound", ("theta_rebound",), 5e-3, DUE, 3))
    label, _ = lms_student(mine, "learner-1")
    token = lti.handoff({"role": "instructor", "iss": ISSUER, "ctx": "course-1", "title": "Dynamics 101", "a": mine})
    at = AppTest.from_file(INSTRUCTOR_PAGE, default_timeout=60)
    at.query_params["lti"] = token
    at.run()
    assert not at.exception and not any(w.key == "assign__instructor_key" for w in at.text_input)  # no key asked
    assert "Dynamics 101" in at.info[0].value
    choices = at.selectbox(key="assign__chosen").options
    assert len(choices) == 1 and "Ours" in choices[0]
    assert not any(e.label == "New assignment" for e in at.expander)
    assert any("Grades sent to the LMS" in m.value for m in at.markdown)
    key_holder = AppTest.from_file(INSTRUCTOR_PAGE, default_timeout=60).run()
    assert key_holder.text_input(key="assign__instructor_key")  # without a launch: the key, as before


HANDOUTS = str(ROOT / "app_pages" / "handouts.py")


def handouts_as(arrival: dict | None) -> AppTest:
    at = AppTest.from_file(HANDOUTS, default_timeout=60)
    if arrival is not None:
        at.query_params["lti"] = lti.handoff(arrival)
    return at.run()


def test_an_lms_instructor_gets_their_course_answer_keys_and_no_other(course):
    """The answer keys of the course's own assignments open without the key; another course's, the
    signed-link assignments and the numbered variants (every course's) do not; a learner gets none."""
    migrate.upgrade()
    ours, theirs = placed("Ours", "course-1", "rl-1"), placed("Theirs", "course-2", "rl-2")
    records.create(records.Settings.of("Signed links only", "pendulum_rebound", ("theta_rebound",), 5e-3, DUE, 3))
    mine, _ = lms_student(ours, "learner-1")
    other, _ = lms_student(theirs, "learner-2")
    teacher = {"role": "instructor", "iss": ISSUER, "ctx": "course-1", "title": "Dynamics 101", "a": ours}
    at = handouts_as(teacher)
    assert not at.exception and not at.text_input  # no key asked
    assert not at.radio(key="handouts__what").value.startswith("Answer")
    assert [r.key for r in at.radio] == ["handouts__what"]  # no range of variants: only the course's rosters
    (choice,) = at.selectbox(key="handouts__assignment").options
    assert "Ours" in choice
    at.radio(key="handouts__what").set_value("Answer key").run()
    sheets = "\n".join(m.value for m in at.markdown)
    assert not at.exception and f"Student {mine}" in sheets and other not in sheets
    solution = pendulum_rebound.solve(**parameters(records.roster(ours)[0], pendulum_rebound, "pendulum_rebound"))
    assert f"= {solution.answers['energy_loss']:.2f}" in sheets  # their energy lost, in J (as the sheet rounds)

    elsewhere = handouts_as({**teacher, "ctx": "course-2", "a": theirs})  # another course's instructor
    (choice,) = elsewhere.selectbox(key="handouts__assignment").options
    assert "Theirs" in choice and "Ours" not in choice

    for arrival in ({"role": "student", "a": ours, "l": mine, "s": records.student_seed(ours, mine)}, None):
        closed = handouts_as(arrival)  # a learner from the LMS, or nobody: the key box, nothing else
        assert not closed.exception and closed.text_input(key="handouts__instructor_key")
        assert not closed.selectbox and not closed.radio


def test_an_lms_instructor_on_a_problem_page_is_told_their_course_keys_not_given_the_variants(course):
    migrate.upgrade()
    placed("Ours", "course-1", "rl-1")
    placed("Theirs", "course-2", "rl-2")
    at = AppTest.from_file(str(ROOT / "app_pages" / "pendulum_rebound.py"), default_timeout=60)
    at.query_params["practice"] = "1"  # the export is in Practice
    at.query_params["lti"] = lti.handoff({"role": "instructor", "iss": ISSUER, "ctx": "course-1", "a": 0})
    at.run()
    said = "\n".join(m.value for m in at.markdown)
    assert not at.exception and "Your course's assignments here: “Ours”" in said and "Theirs" not in said
    assert at.text_input(key="pendulum_rebound__instructor_key")  # the seed variants: still the key
    assert not any(b.label == "Prepare the CSV" for b in at.button)


def test_the_course_keys_say_so_when_the_database_is_away(course, monkeypatch):
    from sqlalchemy.exc import OperationalError

    from lti import store

    migrate.upgrade()
    token = lti.handoff({"role": "instructor", "iss": ISSUER, "ctx": "course-1", "a": 0})

    def away(*args, **kwargs):
        raise OperationalError("SELECT", {}, Exception("connection refused"))

    at = AppTest.from_file(HANDOUTS, default_timeout=60)
    at.query_params["lti"] = token
    monkeypatch.setattr(store, "contexts_assignments", away)  # the hand-off is redeemed; then the database goes
    at.run()
    assert not at.exception and "cannot be reached" in at.error[0].value and not at.selectbox
