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
