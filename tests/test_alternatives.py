"""Two things offered with "or" (drywall_lab/im/alternatives.py): the robot asks which, with both as options."""
from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab.corpus.tags import TAGS
from drywall_lab.decision import decide_tags
from drywall_lab.im import interpret
from drywall_lab.im.alternatives import offered_alternatives


def _read(tagged: str) -> tuple[list[str], list[str]]:
    words, tags = [], []
    for item in tagged.split():
        word, _, tag = item.partition("/")
        words.append(word)
        tags.append(tag or "O")
    return words, tags


@pytest.mark.parametrize("tagged, part", [
    ("put 500310/ID_wall or 500320/ID_wall on stud 500104/ID_stud", "panel"),
    ("the four/width by six/length or a two/width by eight/length on 500104/ID_stud", "panel"),
    ("the 4x6/width on stud 500104/ID_stud or maybe 500106/ID_stud , not sure which", "stud"),
    ("the 4x6/width on 500104/ID_stud , on the centre/Vr_md line/Vr_md or the top/Hr_top row/Hr_top", "placement"),
    ("the 4x6/width on 500104/ID_stud , centre/Vr_md line/Vr_md or the left line", "placement"),
    ("the 4x6/width on 500104/ID_stud , the left edge or the bottom/Hr_btm row/Hr_btm", "placement"),
])
def test_an_offer_is_a_question_with_both_commands_as_options(tagged, part):
    words, tags = _read(tagged)
    offer = offered_alternatives(words, tags)
    assert offer is not None and offer.part == part
    result = interpret(words, tags)
    assert result.refusal is not None and result.refusal.reason == "unclear"
    assert len(result.alternatives) == 2 and result.alternatives[0].outcome() != result.alternatives[1].outcome()
    assert any(step.rule == "R0 alternatives" for step in result.trace.steps)
    decision = decide_tags(words, tags, list(TAGS))
    assert decision.action == "ask" and decision.refusal.reason == "unclear"
    commands = [alt for alt in result.alternatives if alt.command is not None]
    assert len(decision.options) == len(commands) and decision.options  # each command offered, none made up


@pytest.mark.parametrize("tagged", [
    "put the 4x6/width on 500104 or rather 500105/ID_stud",  # a correction, tagged as the guidelines tag it
    "the 4x6/width on 500104/ID_stud or so",
    "the 4x6/width or whatever is on top , on 500104/ID_stud",
    "the 4x6/width on 500104/ID_stud or 500104/ID_stud",  # both say the same: read as one
])
def test_an_or_that_offers_nothing_is_read_as_usual(tagged):
    words, tags = _read(tagged)
    result = interpret(words, tags)
    assert result.command is not None and not result.alternatives


def test_or_rather_starts_a_correction_not_an_offer():
    words, tags = _read("put the 4x6/width on 500104/ID_stud or rather 500105/ID_stud")
    assert offered_alternatives(words, tags) is None


def test_an_offered_panel_that_is_buried_leaves_one_option_to_confirm():
    words, tags = _read("put 500300/ID_wall or 500320/ID_wall on stud 500104/ID_stud")
    result = interpret(words, tags)
    assert result.refusal.reason == "unclear" and "500300" in result.refusal.message
    decision = decide_tags(words, tags, list(TAGS))
    assert decision.action == "ask" and decision.options == [("command", "500320", "500104", "vertical_left")]


_TAGGED = st.sampled_from(["O", "ID_stud", "ID_wall", "width", "length", "Vr_md", "Hr_top", "St_loc1", "St_loc2"])
_WORDS = st.sampled_from(["or", "the", "left", "line", "500104", "500105", "four", "by", "rather", "so", "edge", ","])


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(_WORDS, _TAGGED), min_size=1, max_size=14))
def test_an_offer_always_names_words_of_one_part(pairs):
    words = [w for w, _ in pairs]
    tags = [t for _, t in pairs]
    offer = offered_alternatives(words, tags)
    if offer is None:
        return
    assert "or" in [w.lower() for w in words]
    first, second = offer.readings(tags)
    assert len(first) == len(second) == len(tags)
    said = [tags[i] for i in offer.first + offer.second]
    assert said and all(t != "O" for t in said)
