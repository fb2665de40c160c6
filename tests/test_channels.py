"""Noise channels of the field corpus (drywall_lab/corpus/channels.py): held back whole and in pairs."""
from __future__ import annotations

import random
import re

import pytest

from drywall_lab.corpus import channels as C
from drywall_lab.corpus import field_generator as FG
from drywall_lab.corpus.markup import Token
from drywall_lab.corpus.phrases import Chooser


@pytest.fixture(scope="module")
def splits():
    return {split: FG.field_split(split) for split in FG.COMMITTED_SPLITS}


@pytest.mark.parametrize("split", ["validation", "test"])
def test_the_training_splits_never_meet_a_held_back_channel_or_pair(splits, split):
    for row in splits[split]:
        chosen = set(row["channels"])
        assert not chosen & (set(C.HELD_BACK) | set(C.HELD_BACK_OVERLAYS)), row["id"]
        assert not any(set(pair) <= chosen for pair in C.HELD_BACK_PAIRS), row["id"]


def test_every_novel_instruction_goes_through_a_held_back_channel_or_pair(splits):
    held = C.held_back_combinations()
    for row in splits["novel"]:
        assert any(set(h) <= set(row["channels"]) for h in held), row["id"]
    used = {name for row in splits["validation"] for name in row["channels"]}
    assert used == set(C.CHANNELS) - set(C.HELD_BACK) - set(C.HELD_BACK_OVERLAYS) | {C.SIZE_PROPERTIES, C.UNDECIDED}
    for name, rate in C.HELD_BACK_OVERLAYS.items():
        drawn = {row["id"] for row in splits["novel"] if C.overlay_drawn(row["id"], name)[1]}
        assert (rate - 0.05) * len(splits["novel"]) < len(drawn) < (rate + 0.05) * len(splits["novel"]), name
        overlaid = {row["id"] for row in splits["novel"] if name in row["channels"]}
        assert overlaid <= drawn and overlaid, name  # named where it changed the row, and it does change some


def test_an_overlay_leaves_the_rest_of_the_novel_split_as_it_was():
    """An overlay channel draws from its own random stream: the rows it skips are the rows without it."""
    rows = FG.generate_field_split("novel", n=60)
    overlays = dict(C.HELD_BACK_OVERLAYS)
    C.HELD_BACK_OVERLAYS.clear()
    try:
        plain = FG.generate_field_split("novel", n=60)
    finally:
        C.HELD_BACK_OVERLAYS.update(overlays)
    assert len(rows) == len(plain)
    for row, without in zip(rows, plain):
        assert bool(set(overlays) & set(row["channels"])) == (row != without)


def test_a_channel_keeps_every_tag_on_a_word_that_says_it():
    ch = Chooser(random.Random(3))
    sentence = [Token("put", "O", "O"), Token("the", "O", "O"), Token("2x8", "width", "width"), Token("on", "O", "O"),
                Token("500104", "ID_stud", "ID_stud"), Token("centre", "Vr_md", "Vr_md"), Token("line", "Vr_md", "Vr_md")]
    for name, channel in C.CHANNELS.items():
        for _ in range(20):
            out = channel(ch, [list(sentence)])
            tags = {t.tag for s in out for t in s if t.is_word}
            stud = "St_loc1" if name == "restated_studs" else "ID_stud"  # the stud said by its position, twice
            assert {"width", stud, "Vr_md"} <= tags, name


def test_restated_studs_name_one_stud_twice_by_position_and_the_im_reads_it():
    """``restated_studs``: "on stud 500100" becomes "on the first stud, the leftmost one" (two position phrases,
    both ``St_loc1``), and the IM reads each phrase on its own: the same stud as the id, for every stud."""
    from drywall_lab.im import ActionHistory, interpret

    rng = Chooser(random.Random(4))
    for stud in range(500100, 500111):
        sentence = _sentence(f"put the 2x8/width on stud {stud}/ID_stud please")
        for _ in range(12):
            out = C.restated_studs(rng, [list(sentence)])
            words = [t.word for s in out for t in s if t.is_word]
            tags = [t.tag for s in out for t in s if t.is_word]
            assert "ID_stud" not in tags and tags.count("St_loc1") >= 2
            assert interpret(words, tags, history=ActionHistory()).outcome()["stud_id"] == str(stud), words


def test_code_switch_says_english_in_spanish_and_the_front_end_reads_it_back():
    """``code_switch``: runs of one tag said in another language, and the front end gives back the very words and
    tags."""
    from drywall_lab.nlu.normalise import normalise

    rng = Chooser(random.Random(5))
    sentence = _sentence("take the next sheet from the pile on/Dw_loc1 the/Dw_loc1 left/Dw_loc1 and put it on the "
                         "top/Hr_top row/Hr_top two/St_loc1 studs/St_loc1 to/St_loc1 the/St_loc1 right/St_loc1 of "
                         "the previous/St_loc2 one/St_loc2")
    switched = 0
    for _ in range(30):
        out = C.code_switch(rng, [list(sentence)])
        said = [t for s in out for t in s if t.is_word]
        read = normalise(" ".join(t.word for t in said))
        switched += [t.word for t in said] != [t.word for t in sentence]
        assert list(read.words) == [t.word.lower() for t in sentence]
        assert read.tags_of_words([t.tag for t in said]) == [t.tag for t in sentence]
    assert switched >= 25


def test_an_opener_names_nothing():
    rng = Chooser(random.Random(6))
    sentence = _sentence("put the 2x8/width on stud 500104/ID_stud")
    for _ in range(30):
        out = C.openers(rng, [list(sentence)])
        said = [t for t in out[0] if t.is_word]
        assert said[-len(sentence):] == sentence and {t.tag for t in said[:-len(sentence)]} == {"O"}


def test_spoken_ids_say_the_same_id():
    from drywall_lab.nlu.normalise import normalise_text

    rng = random.Random(0)
    said = set()
    for ident in ["500100", "500112", "500321", "500310", "500106"]:
        for _ in range(30):
            words = C.say_id(rng, ident)
            said.add(" ".join(words))
            assert normalise_text(" ".join(words)) == ident
    assert "five hundred one hundred six" in said  # two numbers of hundreds
    assert not any(w.count("hundred") == 2 for w in map(" ".join, (C.say_id(rng, "500106", grouped=False)
                                                                     for _ in range(30))))


def test_evaluate_reports_the_decision_layer_by_channel(splits):
    """``nlu.cli.scores_by_channel``: one line a channel met (and ``none``), its rows counted; gold tags are right on
    every one."""
    from drywall_lab.corpus.tags import TAGS
    from drywall_lab.decision import decide_tags
    from drywall_lab.im import ActionHistory
    from drywall_lab.nlu.cli import scores_by_channel

    rows = splits["novel"][:40]
    decisions = [decide_tags(r["words"], r["tags"], TAGS, ActionHistory.from_commands(r["context"]["history"]))
                 for r in rows]
    table = scores_by_channel(rows, decisions).set_index("channel")
    met = {name for r in rows for name in r["channels"]}
    assert set(table.index) - {"none"} == met
    for name in met:
        assert table.loc[name, "n"] == sum(name in r["channels"] for r in rows)
    assert (table["acc_decided"] == 1.0).all() and (table["wrong_action_rate"] == 0.0).all()


def _sentence(tagged: str) -> list[Token]:
    return [Token(*(w.split("/") + ["O"])[:2], (w.split("/") + ["O"])[1]) for w in tagged.split()]


def _words(out) -> str:
    return " ".join(t.word for s in out for t in s if t.is_word)


def test_relative_talk_says_a_step_as_an_order_along_the_wall_and_the_im_reads_it():
    """``relative_talk``: "two to the right of 500104" becomes "two past 500104" (or after, beyond, ...), and the IM
    reads the order words as the direction (``im.words.ORDER_WORDS``): the same stud as before the rewrite."""
    from drywall_lab.im import ActionHistory, interpret

    sentence = _sentence("put the 2x8/width on the stud two/St_loc1 to/St_loc1 the/St_loc1 right/St_loc1 of "
                         "500104/St_loc2 please")
    rng = Chooser(random.Random(1))
    said = set()
    for _ in range(60):
        out = C.relative_talk(rng, [list(sentence)])
        words = [t.word for s in out for t in s if t.is_word]
        tags = [t.tag for s in out for t in s if t.is_word]
        said.add(_words(out))
        assert interpret(words, tags, history=ActionHistory()).outcome()["stud_id"] == "500106", words
    assert any("right" not in s for s in said) and any("right" in s for s in said)  # sometimes left as it was


def test_stack_talk_adds_only_o_words_and_keeps_the_outcome():
    """``stack_talk``: "from the top of the middle pile", "the top 2x8": row words that say which sheet, all ``O``."""
    sentence = _sentence("grab the 2x8/width sheet from the middle/Dw_loc1 pile and put it on 500104/ID_stud")
    rng = Chooser(random.Random(2))
    seen = set()
    for _ in range(40):
        out = C.stack_talk(rng, [list(sentence)])
        added = [t for s in out for t in s if t.is_word and t.word in ("top", "topmost", "uppermost")]
        assert all(t.tag == "O" for t in added)
        assert [t.tag for s in out for t in s if t.is_word and t.tag != "O"] == ["width", "Dw_loc1", "ID_stud"]
        seen.add(_words(out))
    assert any("top of the middle pile" in s for s in seen) and any("the top 2x8" in s or "topmost 2x8" in s
                                                                      or "uppermost 2x8" in s for s in seen)


def test_asides_are_composed_and_all_o():
    rng = random.Random(4)
    remarks = {" ".join(C.aside_words(rng)) for _ in range(300)}
    assert len(remarks) > 150  # composed, not a short list
    # errands: other people's sheets of a size, or a row elsewhere, said around the instruction
    sized = [r for r in remarks if re.search(r"\b(4x8|2x8|4x6|4 by 8|2 by 8|4x12|4 by 10)s?\b", r)
             and any(who in r for who in C.ERRAND_SLOTS["who"])]
    rows = [r for r in remarks if re.search(r"\b(top|bottom|upper|lower) (row|course)\b", r)
            and any(where in r for where in C.ERRAND_SLOTS["where"])]
    assert len(sized) > 5 and len(rows) > 2
    assert not any("sixs" in r for r in remarks)
    # an errand's row is always said with another place: "we do the top row" alone would be a command
    for frame in C.ERRAND_FRAMES:
        assert "{row}" not in frame or "{where}" in frame, frame
    ch = Chooser(random.Random(5))
    sentence = _sentence("put the 2x8/width on 500104/ID_stud")
    for _ in range(30):
        out = C.asides(ch, [list(sentence), list(sentence)])
        assert [t.tag for s in out for t in s if t.is_word and t.tag != "O"] == ["width", "ID_stud"] * 2


@pytest.mark.parametrize("tagged", [
    "grab the 2x8/width sheet and put it on 500104/ID_stud centre/Vr_md line/Vr_md",
    "one from the middle/Dw_loc1 pile on 500104/ID_stud",
    "hang the panel 500310/ID_wall on stud 500104/ID_stud",
    "put a full-size/dim board on 500106/ID_stud",
])
def test_site_references_name_the_panel_first_and_keep_the_outcome(tagged):
    """``site_references``: the panel or its stack named first and pointed back at ("the middle pile has the ones we
    want, one from that pile ..."), or a size said as what is left of it; the tagged words move with their tags, the
    added words are ``O``, and the IM reads the same command as before the rewrite."""
    from drywall_lab.im import ActionHistory, interpret

    sentence = _sentence(tagged)
    before = interpret([t.word for t in sentence], [t.tag for t in sentence], history=ActionHistory()).outcome()
    ch = Chooser(random.Random(6))
    said = set()
    for _ in range(40):
        out = C.site_references(ch, [list(sentence)])
        words = [t.word for s in out for t in s if t.is_word]
        tags = [t.tag for s in out for t in s if t.is_word]
        assert sorted(t for t in tags if t != "O") == sorted(t.tag for t in sentence if t.tag != "O"), words
        assert interpret(words, tags, history=ActionHistory()).outcome() == before, words
        said.add(_words(out))
    assert len(said) > 3 and all(s != _words([sentence]) for s in said)  # always rewritten, in several ways


def test_site_references_leave_a_bare_number_or_a_spread_target_alone():
    """A size said as a bare number ("width of two") is no thing to point back at; a target whose words are spread
    over the sentence is left as it is."""
    ch = Chooser(random.Random(7))
    for tagged in ["get the board width of two/width on 500104/ID_stud",
                   "the 4/width sheet by the door 8/length long on 500104/ID_stud"]:
        sentence = _sentence(tagged)
        assert C.site_references(ch, [list(sentence)]) == [sentence]


def test_metric_sizes_say_the_sides_in_metric_and_the_front_end_reads_them_back():
    """``metric_sizes`` (held back whole): the sides in millimetres, centimetres or metres, their tags kept; the front
    end (``normalise.metric_sizes``) reads them as the feet they stand for, so the IM reads the same panel."""
    from drywall_lab.im import ActionHistory, interpret
    from drywall_lab.nlu.normalise import normalise

    ch = Chooser(random.Random(8))
    said = set()
    for tagged in ["put the 2x8/width on 500104/ID_stud", "a 4/width by 6/length board on 500104/ID_stud",
                   "the 2/width foot wide one on 500104/ID_stud", "the four-by-eight/width on 500104/ID_stud"]:
        sentence = _sentence(tagged)
        before = interpret([t.word for t in sentence], [t.tag for t in sentence], history=ActionHistory()).outcome()
        for _ in range(15):
            out = C.metric_sizes(ch, [list(sentence)])
            text = _words(out)
            said.add(text)
            read = normalise(text)
            tags = read.tags_of_words([t.tag for s in out for t in s if t.is_word])
            assert interpret(list(read.words), tags, history=ActionHistory()).outcome() == before, (text, read.words)
    assert {"600x2400", "1.2", "120"} <= {w.removesuffix("mm").removesuffix("cm") for s in said for w in s.split()}


def _phrase(text: str) -> list[Token]:
    """ "two/St_loc1 studs" -> tokens (a word without a tag is O)."""
    return [Token(w.split("/")[0], w.split("/")[1], w.split("/")[1]) if "/" in w else Token(w, "O", "O")
            for w in text.split()]


@pytest.mark.parametrize("said, written", [
    ("two/St_loc1 studs over/St_loc1 to/St_loc1 the/St_loc1 right/St_loc1 of the previous/St_loc2 stud", "prev+2"),
    ("one/St_loc1 to/St_loc1 the/St_loc1 left/St_loc1 of 500104/St_loc2", "500104-1"),
    ("three/St_loc1 studs further/St_loc1 right/St_loc1 of the leftmost/St_loc2 stud",
     "three studs further right of the leftmost stud"),  # an anchor a sum does not name
    ("2nd/St_loc1 from/St_loc1 the/St_loc1 right/St_loc1", "2nd from the right"),  # no anchor
])
def test_a_stud_counted_from_the_previous_one_or_an_id_is_written_as_a_sum(said, written):
    out = C._written_sums(_phrase(said))
    assert " ".join(t.word for t in out) == written
    if "+" in written or "-" in written:
        assert [t.tag for t in out] == ["St_loc1"]


def test_a_value_that_says_which_goes_after_its_label_and_the_front_end_reads_it_back():
    from drywall_lab.nlu.normalise import normalise

    out = C._labels_first(_phrase("the same/dim size/dim in the top/Hr_top row/Hr_top on the far/Dw_loc1 left/Dw_loc1 pile"), "=")
    assert [t.word for t in out] == ["the", "size=same", "in", "the", "row=top", "on", "the", "far", "left", "pile"]
    assert normalise(" ".join(t.word for t in out)).words[:6] == ("the", "same", "size", "in", "the", "top")


@pytest.mark.parametrize("seed", range(40))
def test_a_value_taken_back_leaves_the_meant_value_tagged_and_the_front_end_drops_the_other(seed):
    from drywall_lab.nlu.normalise import normalise

    sentence = _phrase("put the 2x8/width on stud 500104/ID_stud in the top/Hr_top row/Hr_top , second/St_loc1 "
                       "from/St_loc1 the/St_loc1 left/St_loc1")
    out = C.value_repairs(Chooser(random.Random(seed)), [sentence])[0]
    tagged = [(t.word, t.tag) for t in out if t.is_word and t.tag != "O"]
    assert sorted(tagged) == sorted((t.word, t.tag) for t in sentence if t.is_word and t.tag != "O")  # the meant values
    # as tagged (a value taken back late is said again after the rest of its clause)
    assert len([t for t in out if t.is_word]) > len([t for t in sentence if t.is_word])  # something was taken back
    text = " ".join(t.word for t in out).replace(" ,", ",").replace(" .", ".")
    assert normalise(text).words == normalise(" ".join(t.word for t in sentence if t.is_word)).words, text


def test_a_value_taken_back_late_is_put_back_by_the_front_end(monkeypatch):
    """Taken back after a reason, or with the rest of its clause said before the cue ("the top row from the first
    stud, no. bottom row"): the front end reads the instruction as it was meant, typed with its punctuation or
    without; a late form that a register losing its punctuation would spoil is said in place instead."""
    from drywall_lab.nlu.normalise import normalise

    monkeypatch.setattr(C, "LATE_SHARE", 1.0)
    sentence = _phrase("hang the 4x6/width in the bottom/Hr_btm row/Hr_btm from the first/St_loc1 stud on the "
                       "left/Dw_loc1 pile/Dw_loc1")
    late = 0
    for seed in range(40):
        out = C.value_repairs(Chooser(random.Random(seed)), [sentence])[0]
        text = " ".join(t.word for t in out).replace(" ,", ",").replace(" .", ".")
        late += any(c in text for c in (". ", "nah", "nope", "wait"))  # a late cue, not one said in place
        assert sorted((t.word, t.tag) for t in out if t.is_word and t.tag != "O") == \
            sorted((t.word, t.tag) for t in sentence if t.is_word and t.tag != "O")
        read = normalise(text)
        assert read.words == normalise(" ".join(t.word for t in sentence if t.is_word)).words, text
        assert any(c.kind == "repair" for c in read.changes)
    assert late >= 10


def _read_outcome(out):
    """The IM's outcome (after a command on stud 500104) of a channel's output read through the front end, with the
    corpus's tags of the words read."""
    from drywall_lab.corpus.generator import join_tokens
    from drywall_lab.im import ActionHistory, interpret
    from drywall_lab.nlu.normalise import normalise

    text, words, tags, _ = join_tokens(out, True, lambda w, first: w, lambda w: w.strip(";,\t\n"))
    read = normalise(text)
    history = ActionHistory.from_commands([{"drywall_id": "500321", "stud_id": "500104", "placement": "vertical_left"}])
    return text, interpret(list(read.words), read.tags_of_words(tags), history=history).outcome()


@pytest.mark.parametrize("seed", range(20))
@pytest.mark.parametrize("link", ["of", "from"])
def test_continued_steps_leave_the_anchor_unsaid_and_the_im_counts_from_the_previous_stud(seed, link):
    sentence = _phrase(f"put the full/dim sheet two/St_loc1 studs to/St_loc1 the/St_loc1 right/St_loc1 {link} the "
                       "previous/St_loc2 stud please")
    out = C.continued_steps(Chooser(random.Random(seed)), [sentence])
    text, outcome = _read_outcome(out)
    assert "previous" not in text and {"further", "more", "over"} & set(text.split()), text
    assert outcome["stud_id"] == "500106", text


@pytest.mark.parametrize("seed", range(20))
@pytest.mark.parametrize("anchor, stud", [("the previous/St_loc2 stud", "500106"), ("500106/St_loc2", "500108"),
                                          ("the seventh/St_loc2 stud", "500108")])
def test_an_anchor_said_first_is_read_back_as_the_same_command(seed, anchor, stud):
    sentence = _phrase(f"put the full/dim sheet two/St_loc1 studs to/St_loc1 the/St_loc1 right/St_loc1 of {anchor} "
                       "please")
    out = C.anchor_first(Chooser(random.Random(seed)), [sentence])
    text, outcome = _read_outcome(out)
    assert text.index(anchor.split("/")[0].split()[-1]) < text.index("two"), text  # the anchor comes first
    assert outcome["stud_id"] == stud, text


@pytest.mark.parametrize("seed", range(30))
def test_chat_messages_are_read_back_as_the_same_command(seed):
    sentence = _phrase("grab the full/dim sheet from the left/Dw_loc1 pile and stand it on 500108/ID_stud with its "
                       "edge on the centre/Vr_md line/Vr_md")
    out = C.chat_messages(Chooser(random.Random(seed)), [sentence])
    text, outcome = _read_outcome(out)
    assert "\n" in text and ":" in text
    assert outcome == {"drywall_id": "500320", "stud_id": "500108", "placement": "vertical_middle", "refusal": None}, text


@pytest.mark.parametrize("seed", range(20))
def test_a_pasted_table_is_read_back_as_the_same_command(seed):
    sentence = _phrase("grab the full/dim sheet from the left/Dw_loc1 pile and put it two/St_loc1 studs to/St_loc1 "
                       "the/St_loc1 right/St_loc1 of the previous/St_loc2 stud on the centre/Vr_md line/Vr_md")
    out = C.pasted_tables(Chooser(random.Random(seed)), [sentence])
    text, outcome = _read_outcome(out)
    assert "\n" in text
    assert outcome == {"drywall_id": "500320", "stud_id": "500106", "placement": "vertical_middle", "refusal": None}, text


def test_a_table_is_not_made_of_fields_whose_words_interleave():
    sentence = _phrase("put it on 500104/ID_stud , the full/dim one , stud 500104/ID_stud again")
    assert C.pasted_tables(Chooser(random.Random(0)), [sentence]) == [sentence]


@pytest.mark.parametrize("seed", range(30))
def test_an_email_reply_is_read_back_as_the_same_command(seed):
    sentence = _phrase("grab the full/dim sheet from the left/Dw_loc1 pile and stand it on 500108/ID_stud with its "
                       "edge on the centre/Vr_md line/Vr_md")
    out = C.email_replies(Chooser(random.Random(seed)), [sentence])
    text, outcome = _read_outcome(out)
    assert text.startswith("Subject:") and "\n\n" in text
    assert outcome == {"drywall_id": "500320", "stud_id": "500108", "placement": "vertical_middle", "refusal": None}, text


@pytest.mark.parametrize("seed", range(40))
def test_crew_crosstalk_is_read_back_as_the_same_command(seed):
    sentence = _phrase("grab the full/dim sheet from the left/Dw_loc1 pile and lay it on 500106/ID_stud in the "
                       "top/Hr_top row/Hr_top")
    out = C.crew_crosstalk(Chooser(random.Random(seed)), [sentence])
    text, outcome = _read_outcome(out)
    assert text.count(":") >= 2, text
    assert outcome == {"drywall_id": "500320", "stud_id": "500106", "placement": "horizontal_top", "refusal": None}, text


def test_hyphenated_writes_compounds_the_front_end_reads_as_the_words_again():
    """``hyphenated``: pairs of words of one tag after a head word joined by a hyphen ("left-line", "bottom-row"); the
    front end reads the same words as before the rewrite."""
    from drywall_lab.nlu.normalise import normalise

    sentence = _sentence("stand the 2x8/width up on 500104/ID_stud on the left line , far/St_loc1 right/St_loc1 "
                         "in the bottom/Hr_btm row/Hr_btm")
    before = normalise(_words([sentence])).words
    seen = set()
    for seed in range(30):
        out = C.hyphenated(Chooser(random.Random(seed)), [list(sentence)])
        words = _words(out)
        seen.update(w for w in words.split() if "-" in w)
        assert normalise(words).words == before
        assert [t.tag for s in out for t in s if t.is_word and "-" in t.word and t.tag != "O"] in (
            [], ["St_loc1"], ["Hr_btm"], ["St_loc1", "Hr_btm"])
    assert {"left-line", "far-right", "bottom-row"} <= seen
