"""LTI 1.3 against a real platform implementation: ``lti1p3platform``'s platform (tests/lti_platform.py),
on loopback, signs the launches; the tool's routes (lti/routes.py) answer them, on SQLite and
PostgreSQL (the ``database`` fixture). Login → launch → hand-off, roles, deep linking, the refusals."""
from __future__ import annotations

import datetime as dt
import json
import logging
import re
from urllib.parse import unquote

import pytest
import requests
from starlette.responses import PlainTextResponse
from starlette.testclient import TestClient

from assignments import db, migrate, records, signing
from lti import launch as lti, passback, platforms, store
from lti.routes import LtiRoutes
from tests.lti_platform import (DEPLOYMENT, INSTRUCTOR, ISSUER, LEARNER, LEARNER_WITH_INSTITUTION_ROLE, LmsEmulator,
                                query_of)

SECRET = "lti-test-secret-0123456789abcdef"
TOOL = "http://tool.test"


@pytest.fixture(scope="module")
def lms(tmp_path_factory):
    key_dir = tmp_path_factory.mktemp("toolkey")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(platforms.KEY_ENV, "")
        mp.setenv(db.DATA_ENV, str(key_dir))
        jwks = {"keys": [platforms.tool_jwk()]}
    with LmsEmulator(TOOL, tool_jwks=jwks) as emulator:
        emulator.key_dir = key_dir
        yield emulator


@pytest.fixture
def tool(lms, database, tmp_path, monkeypatch):
    """The tool's routes on this test's database, registered with the emulator."""
    monkeypatch.setenv(signing.SECRET_ENV, SECRET)
    monkeypatch.delenv(platforms.KEY_ENV, raising=False)
    monkeypatch.setenv(db.DATA_ENV, str(lms.key_dir))
    file = tmp_path / "platforms.json"
    file.write_text(json.dumps([lms.registration_entry()]))
    monkeypatch.setenv(platforms.PLATFORMS_ENV, str(file))
    monkeypatch.setenv(platforms.URL_ENV, TOOL)
    monkeypatch.setattr(db, "engine", lambda: database)
    client = TestClient(LtiRoutes(PlainTextResponse("streamlit")), base_url=TOOL, follow_redirects=False)
    client.database = database
    lms.scores.clear()
    lms.fail_next.clear()
    return client


DUE = dt.datetime(2031, 1, 1, tzinfo=dt.timezone.utc)
# What does not depend on the database runs once; what stores (nonces, links, students, scores) on both.
SQLITE_ONLY = pytest.mark.parametrize("database", ["sqlite"], indirect=True)


def assignment(database, title="Week 9") -> int:
    settings = records.Settings.of(title, "pendulum_rebound", ("theta_rebound", "I_O"), 5e-3, DUE, 3)
    return records.create(settings, (), database).id


def custom_for(aid: int, context: str = "course-1") -> dict:
    """The custom parameter a deep link of this course gives its resource link."""
    platform = platforms.find(ISSUER)
    placed = lti.Launch(platform, {lti.CLAIM + "deployment_id": DEPLOYMENT, lti.CLAIM + "context": {"id": context}})
    return {"dl_assignment": store.placement(placed, aid)}


def form_of(tool, lms, user, roles, claims=None, expires_in=300, query_change=None, **setup) -> dict:
    """The LMS's login, the tool's redirect, the platform's signed answer: the form it posts."""
    start = lms.login_url(user, roles, **setup)
    assert start.startswith(TOOL + "/lti/login?")
    answer = tool.get(start)
    assert answer.status_code == 302, answer.text
    redirect = answer.headers["location"]
    assert redirect.startswith(lms.url + "/authorize?")
    query = query_of(redirect)
    assert query["redirect_uri"] == TOOL + "/lti/launch" and query["response_mode"] == "form_post"
    form = lms.authorize({**query, **(query_change or {})}, claims, expires_in)
    return {"id_token": form["id_token"], "state": form["state"]}


def handed(tool, response) -> dict:
    assert response.status_code == 303, response.text
    token = unquote(re.search(r"[?&]lti=([^&]+)", response.headers["location"]).group(1))
    payload = lti.redeem(token, store.spender(tool.database))
    assert payload is not None
    return {**payload, "path": response.headers["location"].split("?")[0]}


def test_a_learner_arrives_as_a_student_of_the_assignment_with_their_own_variant(tool, lms):
    aid = assignment(tool.database)
    got = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "learner-7", LEARNER, custom=custom_for(aid),
                                                             name="Ada Lovelace")))
    label = lti.label_of(ISSUER, "learner-7")
    assert got["path"] == TOOL + "/pendulum_rebound"
    assert (got["role"], got["a"], got["l"], got["s"]) == ("student", aid, label, records.student_seed(aid, label))
    assert label in [s.label for s in records.roster(aid, tool.database)]
    other = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "learner-8", LEARNER, custom=custom_for(aid))))
    assert other["l"] != label
    with db.session(tool.database) as s:  # the sub kept for passback, no name unless the admin asks
        member = s.query(db.LtiMember).filter_by(label=label).one()
        assert (member.sub, member.name) == ("learner-7", "")
        assert s.query(db.LtiLink).filter_by(resource_link_id="rl-1").one().lineitem == lms.url + "/lineitems/rl-1"
    again = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "learner-7", LEARNER)))  # the link is known now
    assert (again["a"], again["l"], again["s"]) == (aid, label, got["s"])
    signed = records.enrol(aid, ["s01"], tool.database)  # a signed-link student of the same assignment
    assert {s.label for s in records.gradebook(aid, tool.database).students} == {"s01", label, other["l"]}
    assert {s.label for s in signed} == {"s01", label, other["l"]}  # both kinds in one gradebook


def test_an_instructor_arrives_as_the_instructor_of_that_course_only(tool, lms):
    aid = assignment(tool.database)
    got = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR, custom=custom_for(aid))))
    assert got["path"] == TOOL + "/assignments"
    assert (got["role"], got["iss"], got["ctx"], got["a"]) == ("instructor", ISSUER, "course-1", aid)
    assert store.contexts_assignments(ISSUER, "course-1", tool.database) == [aid]
    assert store.contexts_assignments(ISSUER, "course-2", tool.database) == []
    assert not records.roster(aid, tool.database)  # staff are not students


@SQLITE_ONLY
def test_an_institution_role_does_not_make_a_student_the_instructor(tool, lms):
    aid = assignment(tool.database)
    got = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "learner-9", LEARNER_WITH_INSTITUTION_ROLE,
                                                             custom=custom_for(aid))))
    assert got["role"] == "student" and got["path"].endswith("/pendulum_rebound")


@SQLITE_ONLY
def test_a_placement_from_another_course_or_assignment_opens_nothing(tool, lms):
    aid = assignment(tool.database)
    forged = custom_for(aid, context="course-2")  # sealed for another course
    answer = tool.post("/lti/launch", data=form_of(tool, lms, "learner-1", LEARNER, custom=forged, resource_link="rl-x"))
    assert answer.status_code == 400 and "has no Dynamics Lab assignment yet" in answer.text


BAD = {
    "expired": (lambda tool, lms: form_of(tool, lms, "l", LEARNER, expires_in=-120), "expired id_token"),
    "wrong audience": (lambda tool, lms: form_of(tool, lms, "l", LEARNER, claims={"aud": "another-tool"}),
                       "InvalidAudienceError"),
    "unknown deployment": (lambda tool, lms: form_of(tool, lms, "l", LEARNER,
                                                     claims={lti.CLAIM + "deployment_id": "deployment-9"}),
                           "unknown deployment"),
    "tampered token": (lambda tool, lms: _tampered(form_of(tool, lms, "l", LEARNER)), "InvalidSignatureError"),
    "altered state": (lambda tool, lms: {**form_of(tool, lms, "l", LEARNER), "state": "x.y"}, "state"),
    "foreign nonce": (lambda tool, lms: form_of(tool, lms, "l", LEARNER, query_change={"nonce": "chosen-by-attacker"}),
                      "nonce differs"),
}


def _tampered(form: dict) -> dict:
    import base64

    head, body, signature = form["id_token"].split(".")
    claims = json.loads(base64.urlsafe_b64decode(body + "=" * (-len(body) % 4)))
    claims[lti.CLAIM + "roles"] = INSTRUCTOR  # a learner's token edited to say instructor
    body = base64.urlsafe_b64encode(json.dumps(claims).encode()).decode().rstrip("=")
    return {**form, "id_token": f"{head}.{body}.{signature}"}


@SQLITE_ONLY
def test_a_bad_launch_gets_a_plain_refusal_and_is_logged(tool, lms, caplog):
    aid = assignment(tool.database)
    for case, (make, why) in BAD.items():
        form = make(tool, lms)
        caplog.clear()
        with caplog.at_level(logging.WARNING, "dynamics_lab.lti"):
            answer = tool.post("/lti/launch", data=form)
        assert answer.status_code == 400 and "Not accepted" in answer.text, case
        assert "Traceback" not in answer.text and form["id_token"] not in caplog.text, case
        assert any(why in r.getMessage() for r in caplog.records), (case, caplog.text)
    assert not records.roster(aid, tool.database)


def test_a_replayed_launch_is_refused(tool, lms, caplog):
    aid = assignment(tool.database)
    form = form_of(tool, lms, "learner-1", LEARNER, custom=custom_for(aid))
    assert tool.post("/lti/launch", data=form).status_code == 303
    with caplog.at_level(logging.WARNING, "dynamics_lab.lti"):
        again = tool.post("/lti/launch", data=form)
    assert again.status_code == 400 and "already used" in again.text
    assert "replayed nonce" in caplog.text


@SQLITE_ONLY
def test_a_login_from_an_unregistered_platform_is_refused(tool, lms):
    answer = tool.get("/lti/login", params={"iss": "https://evil.test", "login_hint": "x",
                                            "target_link_uri": TOOL + "/lti/launch"})
    assert answer.status_code == 400 and "not registered" in answer.text
    elsewhere = tool.get("/lti/login", params={"iss": ISSUER, "login_hint": "x", "client_id": "dl-client-1",
                                               "target_link_uri": "https://evil.test/lti/launch"})
    assert elsewhere.status_code == 400 and "Not accepted" in elsewhere.text
    unknown = tool.get("/lti/login", params={"iss": ISSUER, "login_hint": "x", "lti_deployment_id": "deployment-9"})
    assert unknown.status_code == 400 and "deployment of Dynamics Lab is not registered" in unknown.text


@SQLITE_ONLY
def test_the_hand_off_is_spent_once_and_cannot_be_edited(tool, lms):
    spend = store.spender(tool.database)
    token = lti.handoff({"role": "student", "a": 1, "l": "lti-x", "s": 3})
    packed, mac = token.split(".")
    edited = lti.handoff({"role": "instructor"}).split(".")[0] + "." + mac
    assert lti.redeem(edited, spend) is None
    assert lti.redeem(token, spend)["role"] == "student"
    assert lti.redeem(token, spend) is None  # a reload of the same URL, or a copied link


@SQLITE_ONLY
def test_the_routes_follow_a_path_prefix(tool, lms):
    from streamlit import config

    config.set_option("server.baseUrlPath", "dynamics-lab")
    try:
        prefixed = TestClient(LtiRoutes(PlainTextResponse("streamlit")), base_url=TOOL)
    finally:
        config.set_option("server.baseUrlPath", "")
    assert prefixed.get("/dynamics-lab/lti/jwks").json()["keys"]
    assert prefixed.get("/lti/jwks").text == "streamlit"  # outside the prefix: Streamlit's


@SQLITE_ONLY
def test_jwks_and_canvas_configuration(tool, lms):
    keys = tool.get("/lti/jwks").json()["keys"]
    assert keys[0]["kty"] == "RSA" and keys[0]["alg"] == "RS256" and "d" not in keys[0]
    config = tool.get("/lti/config.json").json()
    assert config["oidc_initiation_url"] == TOOL + "/lti/login"
    assert config["target_link_uri"] == TOOL + "/lti/launch" and config["public_jwk_url"] == TOOL + "/lti/jwks"


def test_deep_linking_places_an_assignment_with_a_line_item_in_the_lms(tool, lms):
    picker = tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR, deep_link=True))
    assert picker.status_code == 200 and "Add a Dynamics Lab assignment" in picker.text
    sealed = re.search(r"name='dl' value='([^']+)'", picker.text).group(1)
    step = tool.post("/lti/deep_link", data={"dl": sealed, "problem": "pendulum_rebound"})
    assert "Answers that count" in step.text and "theta_rebound" in step.text
    assert f"value='{records.DIAGRAM}'>" in step.text  # the free-body diagram offered, not chosen by default
    done = tool.post("/lti/deep_link", data={"dl": sealed, "problem": "pendulum_rebound", "step": "create",
                                             "title": "Week 10: rebound", "answer": ["theta_rebound", records.DIAGRAM],
                                             "tolerance": "0.01", "attempts": "2", "due": "2031-02-01T12:00"})
    assert done.status_code == 200, done.text
    action = re.search(r"<form method='post' action='([^']+)'>", done.text).group(1)
    token = re.search(r"name='JWT' value='([^']+)'", done.text).group(1)
    assert action == lms.url + "/deep_link_return"
    assert requests.post(action, data={"JWT": token}, timeout=10).status_code == 200  # the platform checks it
    (item,) = lms.deep_links[-1]
    assert item["type"] == "ltiResourceLink" and item["lineItem"]["scoreMaximum"] == 2
    aid = int(item["custom"]["dl_assignment"].split(".")[0])
    made = records.assignment(aid, tool.database)
    assert (made.title, made.tolerance, made.attempts_allowed) == ("Week 10: rebound", 0.01, 2)
    assert [p.answers for p in made.parts] == [("theta_rebound", records.DIAGRAM)]
    got = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "learner-3", LEARNER, resource_link="rl-new",
                                                             custom=item["custom"])))
    assert (got["role"], got["a"]) == ("student", aid)


@SQLITE_ONLY
def test_only_staff_may_deep_link_and_a_bad_choice_is_said(tool, lms):
    answer = tool.post("/lti/launch", data=form_of(tool, lms, "learner-1", LEARNER, deep_link=True))
    assert answer.status_code == 400 and "Only the course" in answer.text
    picker = tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR, deep_link=True))
    sealed = re.search(r"name='dl' value='([^']+)'", picker.text).group(1)
    bad = tool.post("/lti/deep_link", data={"dl": sealed, "problem": "pendulum_rebound", "step": "create",
                                            "title": "W", "answer": ["theta_rebound"], "tolerance": "lots",
                                            "attempts": "2", "due": "2031-02-01T12:00"})
    assert bad.status_code == 200 and "must be a number" in bad.text
    assert tool.post("/lti/deep_link", data={"dl": sealed[:-2] + "xx", "problem": "x"}).status_code == 400


# -- grade passback (AGS) to the emulator's score endpoint

def learner(tool, lms, user="learner-7", aid=None):
    aid = aid or assignment(tool.database)
    got = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, user, LEARNER, custom=custom_for(aid))))
    return store.from_handoff(got)


def scores_for(lms, user):
    return [s for s in lms.scores if s["userId"] == user]


def due_now(database):
    with db.session(database) as s, s.begin():
        for row in s.query(db.LtiScore):
            row.next_try = records.now()


def test_a_recorded_attempt_sends_the_score_that_counts_to_the_lms(tool, lms):
    student = learner(tool, lms, "pb-1")
    records.record_attempt(student, "theta_rebound", "1", True, "right", bound=tool.database)
    assert passback.queue(student, tool.database)
    assert passback.run_due(tool.database) == 1
    (score,) = scores_for(lms, "pb-1")
    assert (score["scoreGiven"], score["scoreMaximum"]) == (1, 2)
    assert (score["activityProgress"], score["gradingProgress"]) == ("Submitted", "FullyGraded")
    assert score["lineitem"] == "rl-1"
    records.record_attempt(student, "I_O", "2", True, "right", bound=tool.database)
    passback.queue(student, tool.database)
    passback.run_due(tool.database)
    assert [(s["scoreGiven"], s["activityProgress"]) for s in scores_for(lms, "pb-1")] == [(1, "Submitted"),
                                                                                           (2, "Completed")]
    passback.queue(student, tool.database)  # the same score again: nothing new is sent (idempotent)
    passback.run_due(tool.database)
    assert len(scores_for(lms, "pb-1")) == 2
    assert passback.summary(student.assignment_id, tool.database) == passback.Passback(1, 0, [])


def test_a_busy_lms_is_tried_again_with_backoff_and_the_page_never_waits(tool, lms):
    student = learner(tool, lms, "pb-2")
    records.record_attempt(student, "theta_rebound", "1", True, "right", bound=tool.database)
    lms.fail_next[:] = [429, 503]
    passback.queue(student, tool.database)
    passback.run_due(tool.database)
    with db.session(tool.database) as s:
        row = s.query(db.LtiScore).one()
        assert (row.status, row.tries) == ("waiting", 1) and "429" in row.error
        assert row.next_try > records.now()  # not before its backoff
    assert passback.run_due(tool.database) == 0
    due_now(tool.database)
    passback.run_due(tool.database)
    with db.session(tool.database) as s:
        row = s.query(db.LtiScore).one()
        assert (row.status, row.tries) == ("waiting", 2) and "503" in row.error
    due_now(tool.database)
    passback.run_due(tool.database)
    assert [s["scoreGiven"] for s in scores_for(lms, "pb-2")] == [1]
    assert passback.summary(student.assignment_id, tool.database).sent == 1


def test_a_refused_score_is_shown_and_sent_again_later(tool, lms):
    student = learner(tool, lms, "pb-3")
    records.record_attempt(student, "theta_rebound", "1", True, "right", bound=tool.database)
    lms.fail_next[:] = [400]
    passback.queue(student, tool.database)
    passback.run_due(tool.database)
    shown = passback.summary(student.assignment_id, tool.database)
    assert shown.sent == 0 and shown.failed[0][0] == student.label and "400" in shown.failed[0][1]
    assert passback.run_due(tool.database) == 0  # an hour later, or now from the gradebook:
    assert passback.send_again(student.assignment_id, tool.database) == 1
    passback.run_due(tool.database)
    assert [s["scoreGiven"] for s in scores_for(lms, "pb-3")] == [1]


def test_the_best_score_wins_and_staff_are_never_sent(tool, lms):
    student = learner(tool, lms, "pb-4")
    records.record_attempt(student, "theta_rebound", "1", True, "right", bound=tool.database)
    with db.session(tool.database) as s, s.begin():  # the LMS already has more (a rule changed since)
        s.add(db.LtiScore(assignment_id=student.assignment_id, label=student.label, status="sent", sent=2.0,
                          sent_progress="Completed", tries=0, next_try=records.now(), error=""))
    passback.queue(student, tool.database)
    passback.run_due(tool.database)
    assert scores_for(lms, "pb-4") == []
    teacher = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR)))
    assert teacher["role"] == "instructor"
    staff = records.StudentIdentity(student.assignment_id, lti.label_of(ISSUER, "teacher-1"), 1, "lti")
    assert not passback.queue(staff, tool.database)


def test_migration_0003_adds_the_lti_tables_in_place(database, monkeypatch):
    """A course's database at 0002 (an assignment, a student, an attempt) gains the LTI tables, its
    gradebook untouched, and comes back to 0002 without them."""
    from alembic import command
    from sqlalchemy import inspect

    monkeypatch.setenv(signing.SECRET_ENV, SECRET)
    aid = assignment(database)
    signed = records.enrol(aid, ["s01"], database)[0]
    records.record_attempt(signed, "theta_rebound", "1", True, "right", bound=database)
    cfg = migrate.config()
    with database.begin() as connection:
        cfg.attributes["connection"] = connection
        command.downgrade(cfg, "0002")
    assert not {"lti_used", "lti_link", "lti_member", "lti_score"} & set(inspect(database).get_table_names())
    migrate.upgrade(database)
    assert {"lti_used", "lti_link", "lti_member", "lti_score"} <= set(inspect(database).get_table_names())
    assert records.gradebook(aid, database).score("s01") == 1


# -- the course roster (NRPS) for its instructor

def test_the_instructor_sees_who_has_not_started_from_the_lms_roster(tool, lms):
    from lti import roster

    student = learner(tool, lms, "ros-1")
    records.record_attempt(student, "theta_rebound", "1", True, "right", bound=tool.database)
    lms.members[:] = [
        {"user_id": "ros-1", "name": "Ann", "roles": LEARNER, "status": "Active"},
        {"user_id": "ros-2", "name": "Bea", "roles": LEARNER, "status": "Active"},
        {"user_id": "teacher-1", "name": "Prof", "roles": INSTRUCTOR, "status": "Active"},
        {"user_id": "ros-3", "name": "Cem", "roles": LEARNER, "status": "Active"},
        {"user_id": "ros-4", "name": "Dee", "roles": LEARNER, "status": "Inactive"},
    ]
    got = handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR)))
    assert got["nrps"] == lms.url + "/memberships/course-1"
    seen = roster.standing(got["iss"], got["aud"], got["nrps"], student.assignment_id, tool.database)  # 3 pages
    assert [(m.name, m.attempts) for m in seen] == [("Bea", 0), ("Cem", 0), ("Ann", 1)]
    assert seen[-1].label == student.label
    passback._tokens.clear()  # a token the LMS does not know: refused, and said
    with pytest.raises(roster.RosterUnavailable, match="401"):
        roster.standing(got["iss"], got["aud"], lms.url + "/memberships/course-1", 1, tool.database,
                        post=lambda *a, **k: _token_of("not-a-token"))


class _token_of:
    def __init__(self, token):
        self.status_code, self.headers, self.text = 200, {}, ""
        self.token = token

    def json(self):
        return {"access_token": self.token, "expires_in": 3600}


# -- the settings and the frame

def test_only_registered_platforms_may_frame_the_app_or_receive_its_forms(tmp_path, monkeypatch):
    from edge import headers

    monkeypatch.delenv(platforms.PLATFORMS_ENV, raising=False)
    monkeypatch.setenv(headers.FRAME_ENV, "https://moodle.example.edu")
    assert headers.frame_ancestors() == "https://moodle.example.edu" and headers.form_targets() == "'self'"
    file = tmp_path / "platforms.json"
    entry = {"issuer": "https://canvas.instructure.com", "client_id": "1", "auth_login_url": "https://sso.test/a",
             "auth_token_url": "https://sso.test/t", "key_set_url": "https://sso.test/k", "deployment_ids": ["1:x"],
             "frame_origins": ["https://canvas.example.edu"]}
    file.write_text(json.dumps([entry, {**entry, "issuer": "https://lms.other.edu", "frame_origins": None}]))
    monkeypatch.setenv(platforms.PLATFORMS_ENV, str(file))
    policy = headers.content_security_policy()
    assert ("frame-ancestors https://moodle.example.edu https://canvas.example.edu https://lms.other.edu"
            in policy)
    assert "form-action 'self' https://canvas.example.edu https://lms.other.edu" in policy
    monkeypatch.delenv(headers.FRAME_ENV)
    assert headers.frame_ancestors() == "'self' https://canvas.example.edu https://lms.other.edu"


@pytest.mark.parametrize("entries, said", [
    ("not json", "is not valid JSON"),
    ([], "must hold a list of platforms"),
    ([{"issuer": "https://a.test"}], "lacks client_id"),
    ([{"issuer": "https://a.test", "client_id": "1", "auth_login_url": "ftp://x", "auth_token_url": "https://a.test/t",
       "key_set_url": "https://a.test/k", "deployment_ids": ["d"]}], "auth_login_url 'ftp://x' is not an http(s) URL"),
])
def test_a_platform_file_that_cannot_work_stops_the_start_in_plain_words(tmp_path, monkeypatch, entries, said):
    import serve

    file = tmp_path / "platforms.json"
    file.write_text(entries if isinstance(entries, str) else json.dumps(entries))
    monkeypatch.setenv(platforms.PLATFORMS_ENV, str(file))
    monkeypatch.setenv(signing.SECRET_ENV, SECRET)
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", "instructor-key-0030")
    monkeypatch.setenv(platforms.URL_ENV, TOOL)
    problems = serve.settings_problems()
    assert len(problems) == 1 and said in problems[0], problems


def test_lti_needs_the_public_address_and_the_course_secret(tmp_path, monkeypatch, lms):
    import serve

    file = tmp_path / "platforms.json"
    file.write_text(json.dumps([lms.registration_entry()]))
    monkeypatch.setenv(platforms.PLATFORMS_ENV, str(file))
    monkeypatch.setenv(db.DATA_ENV, str(lms.key_dir))
    monkeypatch.delenv(signing.SECRET_ENV, raising=False)
    monkeypatch.delenv(platforms.URL_ENV, raising=False)
    problems = " ".join(serve.settings_problems())
    assert "DL_PUBLIC_URL is not the app's public address" in problems and "DL_COURSE_SECRET is not" in problems
    monkeypatch.setenv(platforms.URL_ENV, TOOL)
    monkeypatch.setenv(signing.SECRET_ENV, SECRET)
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", "instructor-key-0030")
    assert serve.settings_problems() == []


@SQLITE_ONLY
def test_names_are_kept_only_when_the_admin_turns_it_on(tool, lms, monkeypatch):
    aid = assignment(tool.database)
    monkeypatch.setenv(platforms.NAMES_ENV, "1")
    handed(tool, tool.post("/lti/launch", data=form_of(tool, lms, "named-1", LEARNER, custom=custom_for(aid),
                                                       name="Ada Lovelace")))
    with db.session(tool.database) as s:
        assert s.query(db.LtiMember).filter_by(sub="named-1").one().name == "Ada Lovelace"


def test_one_issuer_with_several_registrations_is_told_apart(tmp_path, monkeypatch):
    """Instructure-hosted Canvas: one issuer for every school; each registration its client id and deployments."""
    entry = {"issuer": "https://canvas.instructure.com", "auth_login_url": "https://sso.test/a",
             "auth_token_url": "https://sso.test/t", "key_set_url": "https://sso.test/k"}
    file = tmp_path / "platforms.json"
    file.write_text(json.dumps([{**entry, "client_id": "1", "deployment_ids": ["1:a"]},
                                {**entry, "client_id": "2", "deployment_ids": ["2:b", "2:c"]}]))
    monkeypatch.setenv(platforms.PLATFORMS_ENV, str(file))
    assert platforms.find("https://canvas.instructure.com") is None  # ambiguous: never a guess
    assert platforms.find("https://canvas.instructure.com", "2").client_id == "2"
    assert platforms.serving("https://canvas.instructure.com", "2:c").client_id == "2"
    assert platforms.serving("https://canvas.instructure.com", "3:z") is None


# -- read as a hostile student would (or a launch naming addresses that are not the LMS's)

@SQLITE_ONLY
@pytest.mark.parametrize("return_url", ["javascript:alert(document.domain)", "https://attacker.test/collect",
                                        "data:text/html,<script>alert(1)</script>"])
def test_a_deep_link_answer_goes_only_to_the_lms_own_address(tool, lms, return_url):
    answer = tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR, deep_link=True,
                                                   return_url=return_url))
    assert answer.status_code == 400 and "Not accepted" in answer.text and return_url not in answer.text


@SQLITE_ONLY
def test_a_staff_launch_without_a_course_is_refused(tool, lms):
    for deep_link in (False, True):
        answer = tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR, deep_link=deep_link,
                                                       claims={lti.CLAIM + "context": {"title": "no id"}}))
        assert answer.status_code == 400 and "from a course" in answer.text


@SQLITE_ONLY
def test_scores_and_the_roster_go_only_to_the_lms_own_address(tool, lms):
    """A launch's line item or roster URL elsewhere (an internal address: server-side request
    forgery, a bearer token handed to a stranger) is not posted to; the instructor sees why."""
    from lti import roster

    aid = assignment(tool.database)
    got = handed(tool, tool.post("/lti/launch", data=form_of(
        tool, lms, "ssrf-1", LEARNER, custom=custom_for(aid), resource_link="rl-ssrf",
        lineitem="http://169.254.169.254/latest/lineitems/1")))
    student = store.from_handoff(got)
    records.record_attempt(student, "theta_rebound", "1", True, "right", bound=tool.database)
    posted = []
    assert passback.queue(student, tool.database)
    assert passback.run_due(tool.database, post=lambda *a, **k: posted.append(a) or _token_of("t")) == 1
    assert posted == []  # not even an access token was asked for
    (failed,) = passback.summary(aid, tool.database).failed
    assert "not on the LMS's registered addresses" in failed[1]
    with pytest.raises(roster.RosterUnavailable, match="not the LMS's registered address"):
        roster.standing(ISSUER, lms.registration_entry()["client_id"], "http://127.0.0.1:1/memberships/x", aid,
                        tool.database, post=lambda *a, **k: posted.append(a) or _token_of("t"))
    assert posted == []


@SQLITE_ONLY
def test_an_oversize_post_is_refused_before_it_is_read_whole(tool):
    answer = tool.post("/lti/launch", data={"id_token": "x" * 300_000, "state": "s"})
    assert answer.status_code == 413 and "larger" in answer.text


@SQLITE_ONLY
def test_deep_linking_cannot_adopt_an_assignment_of_signed_links(tool, lms):
    """Another class's assignment (signed links, a roster) cannot be taken over by an LMS instructor
    who gives its exact title, problem and due time: its gradebook would be theirs."""
    settings = records.Settings.of("Week 11", "pendulum_rebound", ("theta_rebound",), 0.01, DUE, 2)
    theirs = records.create(settings, ["s01"], tool.database).id
    picker = tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR, deep_link=True))
    sealed = re.search(r"name='dl' value='([^']+)'", picker.text).group(1)
    done = tool.post("/lti/deep_link", data={"dl": sealed, "problem": "pendulum_rebound", "step": "create",
                                             "title": "Week 11", "answer": ["theta_rebound"], "tolerance": "0.01",
                                             "attempts": "2", "due": DUE.strftime("%Y-%m-%dT%H:%M")})
    assert done.status_code == 200 and "exists in another course" in done.text and "JWT" not in done.text
    assert store.contexts_of(theirs, tool.database) == set()


@SQLITE_ONLY
def test_a_choice_without_a_problem_and_a_token_answer_that_is_no_token_are_said_not_crashed(tool, lms):
    picker = tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR, deep_link=True))
    sealed = re.search(r"name='dl' value='([^']+)'", picker.text).group(1)
    bare = tool.post("/lti/deep_link", data={"dl": sealed, "step": "create", "title": "W", "answer": ["x"],
                                             "tolerance": "0.01", "attempts": "2", "due": "2031-02-01T12:00"})
    assert bare.status_code == 200 and "is not a problem of this app" in bare.text  # said, and the list again
    student = learner(tool, lms, "tok-1")
    records.record_attempt(student, "theta_rebound", "1", True, "right", bound=tool.database)
    assert passback.queue(student, tool.database)

    class NotJson(_token_of):
        def json(self):
            raise ValueError("<html>login page</html>")

    passback._tokens.clear()
    assert passback.run_due(tool.database, post=lambda *a, **k: NotJson("")) == 1
    with db.session(tool.database) as s:  # waiting again, with the reason, not stuck "sending"
        row = s.query(db.LtiScore).one()
        assert row.status == "waiting" and "held no access token" in row.error


@SQLITE_ONLY
def test_a_hostile_title_is_text_in_the_deep_link_pages(tool, lms):
    picker = tool.post("/lti/launch", data=form_of(tool, lms, "teacher-1", INSTRUCTOR, deep_link=True))
    sealed = re.search(r"name='dl' value='([^']+)'", picker.text).group(1)
    title = "<script>alert(1)</script>' onmouseover='x"
    done = tool.post("/lti/deep_link", data={"dl": sealed, "problem": "pendulum_rebound", "step": "create",
                                             "title": title, "answer": ["theta_rebound"], "tolerance": "0.01",
                                             "attempts": "2", "due": "2031-03-01T12:00"})
    assert done.status_code == 200 and "<script>alert" not in done.text and "' onmouseover" not in done.text
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in done.text
    bad = tool.post("/lti/deep_link", data={"dl": sealed, "problem": "<b>x</b>", "step": "create", "title": title,
                                            "answer": ["theta_rebound"], "tolerance": "many", "attempts": "2",
                                            "due": "2031-03-01T12:00"})
    assert bad.status_code == 200 and "<b>x</b>" not in bad.text and "<script>alert" not in bad.text


def resigned(token: str, lms, changes: dict) -> str:
    """The platform's id_token with ``changes`` to its claims, signed again with the platform's own key (as a
    buggy LMS would send it: the emulator sets the deep-linking claims after any extra ones)."""
    import jwt as pyjwt

    header = pyjwt.get_unverified_header(token)
    claims = {**pyjwt.decode(token, options={"verify_signature": False}), **changes}
    return pyjwt.encode(claims, lms.private_key, algorithm="RS256", headers={"kid": header["kid"]})


@SQLITE_ONLY
@pytest.mark.parametrize("role, deep_link, claim, value", [
    (LEARNER, False, lti.CLAIM + "resource_link", "x"),
    (LEARNER, False, lti.CLAIM + "resource_link", ["x"]),
    (LEARNER, False, lti.CLAIM + "context", ["x"]),
    (INSTRUCTOR, False, lti.CLAIM + "context", "abc"),
    (INSTRUCTOR, True, lti.DL_CLAIM + "deep_linking_settings", "x"),
    (INSTRUCTOR, False, lti.NRPS_CLAIM, ["https://lms.example/roster"]),
    (LEARNER, False, lti.CLAIM + "roles", "Learner"),
])
def test_a_claim_of_the_wrong_type_from_a_registered_platform_is_refused_not_a_500(tool, lms, caplog, role, deep_link,
                                                                                    claim, value):
    """A token signed by the platform's own key with a resource_link, context or deep-linking settings of the
    wrong type (a buggy LMS) was a 500 with a traceback in the log: it is refused in words, and said why."""
    aid = assignment(tool.database)
    form = form_of(tool, lms, "someone-1", role, deep_link=deep_link, custom=custom_for(aid))
    form = {**form, "id_token": resigned(form["id_token"], lms, {claim: value})}
    with caplog.at_level(logging.WARNING, "dynamics_lab.lti"):
        answer = tool.post("/lti/launch", data=form)
    assert answer.status_code == 400 and "Not accepted" in answer.text and "Traceback" not in answer.text
    assert "wrong type" in caplog.text and claim in caplog.text
