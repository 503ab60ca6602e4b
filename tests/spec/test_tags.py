"""A problem's ``tags:`` (the topics a catalogue files it under) are read as written, and a
tag that is not a lowercase hyphenated word, a tag listed twice or tags that are not a list are
refused with one located message."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.errors import SpecError
from mechgrade.spec import load_problem_text

BASE = (Path(__file__).resolve().parents[1] / "data" / "spec" / "base.yaml").read_text()


def _with_tags(text: str) -> str:
    return BASE.replace("inertial:", f"tags: {text}\ninertial:")


def test_tags_are_read_in_the_order_written():
    assert load_problem_text(_with_tags("[work-energy, 3d-rigid-body]"), "base.yaml").tags == \
        ("work-energy", "3d-rigid-body")


def test_a_problem_without_tags_has_none():
    assert load_problem_text(BASE, "base.yaml").tags == ()


def test_tags_change_no_solution_key():
    # a catalogue's topics are not physics: the problem compares (and caches) as before
    assert load_problem_text(_with_tags("[pendulum]"), "base.yaml") == \
        load_problem_text(BASE, "base.yaml")


@pytest.mark.parametrize("tags, message", [
    ("[Work Energy]", "base.yaml:4:8: tags[0]: expected a tag of lowercase letters and digits, "
                      "words joined by single hyphens (work-energy), found 'Work Energy'"),
    ("[springs, springs]", "base.yaml:4:7: tags: expected a list of tags with each tag once, "
                           "such as [work-energy, springs], found a list of 2"),
    ("springs", "base.yaml:4:7: tags: expected a list of tags with each tag once, such as "
                "[work-energy, springs], found 'springs'"),
    ("[a--b]", "base.yaml:4:8: tags[0]: expected a tag of lowercase letters and digits, words "
               "joined by single hyphens (work-energy), found 'a--b'"),
])
def test_a_bad_tag_list_is_refused_with_where_and_what(tags, message):
    with pytest.raises(SpecError) as caught:
        load_problem_text(_with_tags(tags), "base.yaml")
    assert str(caught.value) == message
