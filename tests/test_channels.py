"""Noise channels of the field corpus (drywall_lab/corpus/channels.py): held back whole and in pairs."""
from __future__ import annotations

import random

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
        assert not chosen & set(C.HELD_BACK), row["id"]
        assert not any(set(pair) <= chosen for pair in C.HELD_BACK_PAIRS), row["id"]


def test_every_novel_instruction_goes_through_a_held_back_channel_or_pair(splits):
    held = C.held_back_combinations()
    for row in splits["novel"]:
        assert any(set(h) <= set(row["channels"]) for h in held), row["id"]
    used = {name for row in splits["validation"] for name in row["channels"]}
    assert used == set(C.CHANNELS) - set(C.HELD_BACK)


def test_a_channel_keeps_every_tag_on_a_word_that_says_it():
    ch = Chooser(random.Random(3))
    sentence = [Token("put", "O", "O"), Token("the", "O", "O"), Token("2x8", "width", "width"), Token("on", "O", "O"),
                Token("500104", "ID_stud", "ID_stud"), Token("centre", "Vr_md", "Vr_md"), Token("line", "Vr_md", "Vr_md")]
    for name, channel in C.CHANNELS.items():
        for _ in range(20):
            out = channel(ch, [list(sentence)])
            tags = {t.tag for s in out for t in s if t.is_word}
            assert {"width", "ID_stud", "Vr_md"} <= tags, name


def test_spoken_ids_say_the_same_id():
    from drywall_lab.nlu.normalise import normalise_text

    rng = random.Random(0)
    for ident in ["500100", "500112", "500321", "500310"]:
        for _ in range(30):
            assert normalise_text(" ".join(C.say_id(rng, ident))) == ident


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
