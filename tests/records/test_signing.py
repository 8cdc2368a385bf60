"""Signed assignment links: a link round-trips to the identity it was issued for, and a change of
any single character (assignment, variant, label or signature) is refused with a clear message."""
from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as hst

from assignments import signing
from assignments.identity import LINK_KEYS, LinkRefused, StudentIdentity, from_link, link_query
from practice.variants import MAX_SEED

SECRET = "course-secret-for-the-tests-0018"
labels = hst.from_regex(signing.LABEL, fullmatch=True)
identities = hst.builds(StudentIdentity, hst.integers(1, 10**9 - 1), labels, hst.integers(0, MAX_SEED))
# What a single changed character may become: anything a URL can carry, the same characters included.
replacements = hst.characters(codec="utf-8", exclude_characters="\x00")


@pytest.fixture(autouse=True)
def course_secret(monkeypatch):
    monkeypatch.setenv(signing.SECRET_ENV, SECRET)


@given(identity=identities)
def test_a_link_round_trips_to_its_identity(identity):
    query = link_query(identity)
    assert set(query) == set(LINK_KEYS) and from_link(query) == identity


@settings(max_examples=300)
@given(identity=identities, key=hst.sampled_from(LINK_KEYS), position=hst.integers(0, 63), new=replacements)
def test_any_single_character_change_is_refused(identity, key, position, new):
    query = link_query(identity)
    value = query[key]
    position %= len(value)
    if value[position] == new:
        new = "1" if new != "1" else "2"
    changed = query | {key: value[:position] + new + value[position + 1:]}
    with pytest.raises(LinkRefused, match="changed since your instructor issued it|incomplete"):
        from_link(changed)


@given(identity=identities)
def test_another_courses_secret_refuses_the_link(identity):
    query = link_query(identity)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(signing.SECRET_ENV, SECRET + "-other")
        with pytest.raises(LinkRefused):
            from_link(query)


def test_a_missing_part_or_secret_says_what_is_wrong(monkeypatch):
    query = link_query(StudentIdentity(3, "s017", 417))
    with pytest.raises(LinkRefused, match="incomplete.*sig"):
        from_link({k: v for k, v in query.items() if k != "sig"})
    monkeypatch.setenv(signing.SECRET_ENV, "short")  # too short: treated as not set
    with pytest.raises(LinkRefused, match="course secret"):
        from_link(query)


@pytest.mark.parametrize("label", ["Jane Doe", "jane@uni.edu", "", "-x", "=cmd", "a" * 41, "s\x1f1"])
def test_labels_are_opaque_codes(label):
    with pytest.raises(ValueError, match="no names or e-mail"):
        signing.sign(1, 1, label)


@pytest.mark.parametrize("key, spelling", [("assignment", "0{}"), ("seed", "0{}"), ("assignment", "arabic-indic"),
                                           ("seed", "arabic-indic"), ("assignment", "+{}"), ("seed", " {}")])
def test_a_number_has_one_spelling(key, spelling):
    """Only the canonical ASCII spelling is accepted: "01" or "٣" (int() reads both as the same
    number, so the signature would verify) are refused in plain words."""
    query = link_query(StudentIdentity(3, "s017", 417))
    value = query[key]
    other = ("".join(chr(0x660 + int(d)) for d in value) if spelling == "arabic-indic" else spelling.format(value))
    assert int(other) == int(value)  # the same number to Python
    with pytest.raises(LinkRefused, match="changed since your instructor issued it"):
        from_link(query | {key: other})


# -- sealed short-lived tokens (an LTI login's state, a launch's hand-off)

PAYLOADS = hst.dictionaries(hst.text("abcdefghij", min_size=1, max_size=5),
                            hst.one_of(hst.integers(-10**6, 10**6), hst.text(max_size=30)), max_size=4)


@settings(max_examples=60, deadline=None)
@given(PAYLOADS, hst.data())
def test_a_sealed_token_opens_unchanged_and_only_unchanged(payload, data):
    token = signing.seal("lti-handoff", payload, 60)
    opened = signing.unseal("lti-handoff", token)
    assert {k: v for k, v in opened.items() if k != "exp"} == {k: v for k, v in payload.items() if k != "exp"}
    assert signing.unseal("lti-state", token) is None  # sealed for another purpose
    at = data.draw(hst.integers(0, len(token) - 1))
    swapped = "A" if token[at] != "A" else "B"
    assert signing.unseal("lti-handoff", token[:at] + swapped + token[at + 1:]) is None


def test_a_sealed_token_expires_and_needs_the_course_secret(monkeypatch):
    assert signing.unseal("lti-handoff", signing.seal("lti-handoff", {"a": 1}, -1)) is None
    token = signing.seal("lti-handoff", {"a": 1}, 60)
    monkeypatch.setenv(signing.SECRET_ENV, "another-course-secret-000000")
    assert signing.unseal("lti-handoff", token) is None
    assert signing.unseal("lti-handoff", None) is None and signing.unseal("lti-handoff", "x" * 9000) is None
