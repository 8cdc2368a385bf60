"""Handouts for a class (AppTest): behind the instructor key; for a range of variants or an
assignment's roster, each student's sheet has their own givens, room to work and no answer, and the
answer key has each variant's answers and derivation; the same as one LaTeX file (balanced, only
defined macros, compiled where pdflatex is) and as Markdown. Students are named only by the roster's
labels."""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

from streamlit.testing.v1 import AppTest

from assignments import records
from assignments.identity import parameters
from practice.variants import variant
from solvers import units
from tests.records.test_assignment_pages import KEY, create, instructor
from tests.pages.test_pages import assert_clean, downloads_shown
from tests.practice.test_practice import leaks, setup
from tests.pages.test_takehome import DEFINED, PDFLATEX, macros, unbalanced
from ui import documents
from solvers.catalog import BY_ID

ROOT = Path(__file__).resolve().parents[2]
PAGE = str(ROOT / "app_pages" / "handouts.py")


def handouts(query: dict | None = None) -> AppTest:
    at = AppTest.from_file(PAGE, default_timeout=60)
    at.query_params.update(query or {})
    return at.run()


def sheets_text(at: AppTest) -> str:
    return "\n".join(m.value for m in at.markdown)


def test_the_handouts_are_closed_without_the_key(monkeypatch):
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", KEY)
    at = handouts()
    assert_clean(at)
    assert not at.get("download_button") and "Variant" not in sheets_text(at)
    at.text_input(key="handouts__instructor_key").input("not-the-key").run()
    assert at.error and "Variant" not in sheets_text(at)


def range_of_variants(monkeypatch, pid: str, first: int, last: int) -> AppTest:
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", KEY)
    at = handouts({"instructor": KEY})
    assert "instructor" not in at.query_params  # the key leaves the address bar
    at.selectbox(key="handouts__problem").select(pid).run()
    at.number_input(key="handouts__first").set_value(first).run()
    at.number_input(key="handouts__last").set_value(last).run()
    assert_clean(at)
    return at


def test_statements_for_a_range_of_variants_have_each_students_givens_and_no_answer(monkeypatch):
    pid, seeds = "rod_disk_spring", (5, 6, 7)
    at = range_of_variants(monkeypatch, pid, seeds[0], seeds[-1])
    text = sheets_text(at)
    assert text.count("## Your work") == len(seeds) and "Derivation" not in text
    assert sum(h.proto.body == '<div class="dl-sheet-break"></div>' for h in at.get("html")) == len(seeds) - 1  # a sheet each
    assert sum(h.proto.body == '<div class="dl-work"></div>' for h in at.get("html")) == len(seeds)  # room to work
    files = downloads_shown(at)
    for seed in seeds:
        params = variant(BY_ID[pid].solver, pid, seed)
        sheet = text.split(f"*Variant {seed}*")[1].split("*Variant")[0]
        assert units.format_quantity(params["m1"], "mass", sig=6) in sheet and f"/{pid}?seed={seed}" in sheet
        _, solution, judge, answers = setup(pid, **params)
        for shown in (sheet, *files.values()):
            assert leaks(shown, solution, answers.values(), judge) == [], seed


def test_the_answer_key_has_each_variants_answers_and_derivation(monkeypatch, tmp_path):
    pid, seeds = "driven_cart", (11, 12)
    at = range_of_variants(monkeypatch, pid, seeds[0], seeds[-1])
    at.radio(key="handouts__what").set_value("Answer key").run()
    assert_clean(at)
    text, files = sheets_text(at), downloads_shown(at)
    assert text.count("## Derivation, step by step") == len(seeds) and "Your work" not in text
    tex = files[f"{pid}-variants-11-12-key.tex"]
    for seed in seeds:
        _, solution, judge, answers = setup(pid, **variant(BY_ID[pid].solver, pid, seed))
        sheet = text.split(f"*Variant {seed}*")[1].split("*Variant")[0]
        for a in answers.values():
            assert units.format_quantity(solution.answers[a.name], a.dimension) in sheet, (seed, a.name)
        assert leaks(sheet, solution, answers.values(), judge)  # the leak check finds them: it is the key
        assert f"Variant {seed}" in tex
    assert tex.count(r"\newpage") == len(seeds) - 1 and not unbalanced(tex) and macros(tex) <= DEFINED
    if PDFLATEX:
        (tmp_path / "key.tex").write_text(tex)
        run = subprocess.run([PDFLATEX, "-interaction=nonstopmode", "-halt-on-error", "key.tex"], cwd=tmp_path,
                             capture_output=True, text=True, timeout=60)
        assert run.returncode == 0, run.stdout[-1500:]


def test_too_many_variants_are_refused_in_plain_words(monkeypatch):
    at = range_of_variants(monkeypatch, "disk_wall", 1, 500)
    assert at.error and "from 1 to 60 variants" in at.error[0].value and not at.get("download_button")


def test_handouts_from_an_assignments_roster_carry_its_labels_and_givens(course):
    create(instructor(), roster="label\ns_01\ns02\n")
    aid, settings = records.assignments()[0]
    at = handouts({"instructor": KEY})
    at.radio(key="handouts__source").set_value("An assignment's roster").run()
    assert_clean(at)
    text = sheets_text(at)
    students = records.roster(aid)  # in the roster's order
    assert [m.group(1) for m in re.finditer(r"^\*Student (\S+)\*$", text, re.M)] == [
        who.label.replace("_", "\\_") for who in students]
    for who in students:
        params = parameters(who, BY_ID[settings.problem].solver, settings.problem)
        sheet = text.split(f"Student {who.label.replace('_', chr(92) + '_')}*")[1].split("*Student")[0]
        assert units.format_quantity(params["e"], "dimensionless", sig=6) in sheet
        assert units.format_quantity(params["theta0"], "angle", sig=6) in sheet
        assert "?seed=" not in sheet and "sig=" not in sheet  # no link: each student's own is theirs
    statements = downloads_shown(at)[f"{settings.problem}-assignment-{aid}-statements.tex"]
    assert r"Student s\_01" in statements and not unbalanced(statements)
    # Only the roster's labels name a student: the page has no other name to give.
    assert set(re.findall(r"Student (\S+)", text)) == {r"s\_01*", "s02*"}
    assert documents.ascii_only(statements)


def test_a_handouts_link_sets_the_problem_the_variants_and_the_key(monkeypatch):
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", KEY)
    at = handouts({"instructor": KEY, "problem": "stick_ball", "first": "3", "last": "4", "what": "key"})
    assert_clean(at)
    text = sheets_text(at)
    assert "*Variant 3*" in text and "*Variant 4*" in text and "*Variant 5*" not in text
    assert text.count("## Answers") == 2
    ignored = handouts({"instructor": KEY, "problem": "nope", "first": "-1", "what": "<x>"})
    assert_clean(ignored)
    assert "*Variant 1*" in sheets_text(ignored) and "## Your work" in sheets_text(ignored)  # the defaults


def link_of(at: AppTest) -> dict:
    """The page's address's query, one value a name."""
    return {k: (v[-1] if isinstance(v, list) else v) for k, v in at.query_params.items()}


def test_every_choice_on_the_handouts_page_is_in_its_link(monkeypatch):
    """Issue 54: the address kept what=statements after choosing Answer key. Each choice is written into
    the link as it is made, and that link opens the same choices (a range of variants, and a roster)."""
    at = range_of_variants(monkeypatch, "stick_ball", 3, 4)
    assert link_of(at) == {"problem": "stick_ball", "first": "3", "last": "4", "what": "statements"}
    at.radio(key="handouts__what").set_value("Answer key").run()
    assert link_of(at) == {"problem": "stick_ball", "first": "3", "last": "4", "what": "key"}
    again = handouts({"instructor": KEY, **link_of(at)})
    assert_clean(again)
    assert again.radio(key="handouts__what").value == "Answer key"
    assert (again.selectbox(key="handouts__problem").value, again.number_input(key="handouts__first").value,
            again.number_input(key="handouts__last").value) == ("stick_ball", 3, 4)


def test_a_rosters_handout_is_in_its_link_too(course):
    create(instructor(), roster="label\ns01\ns02\n")
    create(instructor(), roster="label\ns03\n", title="The second")
    (first, _), (second, _) = sorted(records.assignments(), key=lambda a: a[0])
    at = handouts({"instructor": KEY})
    at.radio(key="handouts__source").set_value("An assignment's roster").run()
    at.selectbox(key="handouts__assignment").set_value(second).run()
    at.radio(key="handouts__what").set_value("Answer key").run()
    assert_clean(at)
    assert link_of(at) == {"whose": "roster", "assignment": str(second), "what": "key"}
    again = handouts({"instructor": KEY, **link_of(at)})
    assert_clean(again)
    assert again.radio(key="handouts__source").value == "An assignment's roster"
    assert again.selectbox(key="handouts__assignment").value == second
    assert again.radio(key="handouts__what").value == "Answer key" and "Student s03" in sheets_text(again)
    gone = handouts({"instructor": KEY, "whose": "roster", "assignment": "999", "what": "key"})  # no such assignment
    assert_clean(gone)
    assert gone.selectbox(key="handouts__assignment").value in (first, second)
