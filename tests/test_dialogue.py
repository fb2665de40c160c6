"""The dialogue (drywall_lab/dialogue.py): scripted conversations, the chat command, the wall in text."""
from __future__ import annotations

import io
import math

import numpy as np

from drywall_lab.corpus.markup import parse
from drywall_lab.corpus.tags import TAGS
from drywall_lab.dialogue import Dialogue, chat_widget, run_chat, wall_text
from drywall_lab.nlu.base import TagConfidence
from drywall_lab.site import default_site


class ScriptedTagger:
    """Readings fixed in advance for each instruction: {text: [(markup, probability), ...]}."""

    labels = TAGS

    def __init__(self, readings: dict[str, list[tuple[str, float]]]) -> None:
        self.readings = readings

    def predict_confidence(self, sentences, k=5, batch_size=64):
        out = []
        for words in sentences:
            options = self.readings[" ".join(words)]
            kbest = []
            for markup, p in options:
                tags = [t.tag for t in parse(markup) if t.is_word]
                assert len(tags) == len(words)
                kbest.append((tags, math.log(p)))
            marginals = np.zeros((len(words), len(TAGS)))
            for i, tag in enumerate(kbest[0][0]):
                marginals[i, TAGS.index(tag)] = 1.0
            out.append(TagConfidence(kbest[0][0], marginals, kbest[:k]))
        return out

    def predict_kbest(self, sentences, k, batch_size=64):
        return [c.kbest for c in self.predict_confidence(sentences, k, batch_size)]


CENTRE = "put the 2 by 8 on stud 500104 centre line"
READINGS = {
    CENTRE: [("put the 2/width by 8/length on stud 500104/ID_stud centre/Vr_md line/Vr_md", 0.6),
             ("put the 2/width by 8/length on stud 500104/ID_stud centre line", 0.25)],
    "the full sheet on stud 500100": [("the full/dim sheet on stud 500100/ID_stud", 0.97)],
    "panel 500300 on stud 500108": [("panel 500300/ID_wall on stud 500108/ID_stud", 0.99)],
    "same again on stud 500106": [("same/dim again/dim on stud 500106/ID_stud", 0.99)],
}


def test_an_either_or_question_answered_the_first_carries_out_the_first_command():
    d = Dialogue(ScriptedTagger(READINGS))
    reply = d.say(CENTRE)
    assert reply.question and reply.command is None and len(d.history) == 0
    assert reply.text.startswith("Did you mean panel 500321 on stud 500104 upright with its edge on the stud's centre")
    assert [c.placement.value for c in reply.options] == ["vertical_middle", "vertical_left"]
    reply = d.say("the first")
    assert reply.command.as_contract() == {"drywall_id": "500321", "stud_id": "500104", "placement": "vertical_middle"}
    assert len(d.history) == 1 and d.pending is None


def test_a_bare_yes_to_an_either_or_question_is_no_answer_and_the_robot_asks_which():
    d = Dialogue(ScriptedTagger(READINGS))
    d.say(CENTRE)
    reply = d.say("yes")
    assert reply.question and reply.command is None and len(d.history) == 0 and reply.text.startswith("Which one")
    assert d.say("the centre line").command.placement.value == "vertical_middle"  # an answer by what it says
    d = Dialogue(ScriptedTagger(READINGS))
    d.say(CENTRE)
    assert d.say("neither").command is None and d.pending is None and len(d.history) == 0


def test_the_second_option_and_no():
    d = Dialogue(ScriptedTagger(READINGS))
    d.say(CENTRE)
    assert d.say("the second").command.placement.value == "vertical_left"
    d = Dialogue(ScriptedTagger(READINGS))
    d.say(CENTRE)
    reply = d.say("no")
    assert reply.command is None and "will not" in reply.text and len(d.history) == 0 and d.pending is None


def test_same_again_after_a_no_means_the_last_panel_carried_out():
    """A question answered "no" leaves nothing behind: "same again" is the size of the last panel installed (the
    4 x 8 from the left stack), not of the 2 x 8 the robot asked about and did not place."""
    d = Dialogue(ScriptedTagger(READINGS))
    assert d.say("the full sheet on stud 500100").command.drywall_id == "500320"
    assert d.say(CENTRE).question
    assert d.say("no").command is None and d.pending is None and len(d.history) == 1
    reply = d.say("same again on stud 500106")
    assert reply.command.as_contract() == {"drywall_id": "500310", "stud_id": "500106", "placement": "vertical_left"}
    assert [c.drywall_id for c in d.history.commands] == ["500320", "500310"]


def test_a_corrected_instruction_replaces_the_question():
    d = Dialogue(ScriptedTagger(READINGS))
    d.say(CENTRE)
    reply = d.say("the full sheet on stud 500100")
    assert reply.command.drywall_id == "500320" and len(d.history) == 1


def test_a_refusal_leaves_the_wall_as_it_was():
    d = Dialogue(ScriptedTagger(READINGS))
    reply = d.say("panel 500300 on stud 500108")
    assert reply.command is None and not reply.question and "500300" in reply.text and len(d.history) == 0
    assert d.say("   ").text.startswith("I did not hear an instruction")


def test_the_chat_command_with_the_default_tagger(monkeypatch, capsys):
    from drywall_lab.__main__ import main

    lines = iter(["Pick up the full-size drywall and put it on stud 500100.", "quit"])
    monkeypatch.setattr("builtins.input", lambda prompt="": next(lines))
    assert main(["chat"]) == 0
    out = capsys.readouterr().out
    assert "robot> Placing 500320 on stud 500100" in out and "1 panel(s) installed." in out
    assert out.count("left stack (4 x 8)") == 2  # the wall before and after the placement


def test_run_chat_ends_at_the_end_of_input():
    def read(prompt):
        raise EOFError
    out = io.StringIO()
    assert run_chat(Dialogue(ScriptedTagger(READINGS)), read, out) == 0
    assert out.getvalue().endswith("0 panel(s) installed.\n")


def test_wall_text_draws_panels_and_stacks():
    state = default_site().fresh().install("500320", "500100", "vertical_left").install("500321", "500104", "horizontal_top")
    text = wall_text(state)
    lines = text.splitlines()
    assert lines[0].count("M") == 24 and lines[7].count("L") == 12  # 8 ft across the top; 4 ft wide at the floor
    assert "00  01  02" in text and "left stack (4 x 8): 500300, 500310 (top last)" in text


def test_chat_widget_runs_a_scripted_exchange():
    ui = chat_widget(Dialogue(ScriptedTagger(READINGS)))
    box = ui.children[0].children[0]
    box.value = CENTRE  # Enter in the text box sends it
    assert ui.dialogue.pending is not None and box.value == ""
    box.value = "the second"
    assert len(ui.dialogue.history) == 1 and ui.dialogue.pending is None
    assert ui.dialogue.history.commands[0].placement.value == "vertical_left"


# --- the dialogue contract (the spec's dialogue.md) -------------------------------------------------------------
def _serve(requests: list, tagger=None) -> list[dict]:
    import json

    from drywall_lab.dialogue import serve

    lines = "".join((r if isinstance(r, str) else json.dumps(r)) + "\n" for r in requests)
    out = io.StringIO()
    assert serve(Dialogue(tagger or ScriptedTagger(READINGS)), io.StringIO(lines), out) == 0
    return [json.loads(line) for line in out.getvalue().splitlines()]


def test_the_contract_asks_with_options_and_carries_out_the_one_chosen():
    replies = _serve([{"new": "ep1"}, {"say": CENTRE}, {"choose": 1}, {"say": CENTRE}, {"new": "ep2"}, {"say": CENTRE},
                      {"choose": None}, {"choose": 0}])
    assert [r["kind"] for r in replies] == ["ready", "question", "command", "refusal", "ready", "question", "nothing",
                                            "error"]
    assert replies[1]["options"] == [
        {"drywall_id": "500321", "stud_id": "500104", "placement": "vertical_middle"},
        {"drywall_id": "500321", "stud_id": "500104", "placement": "vertical_left"}]
    assert replies[2]["command"] == replies[1]["options"][1]
    # the next 2 x 8 (500311) on the same stud overlaps the one carried out: no option that does not fit
    assert replies[3]["reason"] == "overlap" and replies[5]["options"] == replies[1]["options"]
    assert all(isinstance(r["text"], str) and r["text"] for r in replies)


def test_new_starts_a_fresh_site_and_a_refusal_has_its_reason():
    replies = _serve([{"new": 1}, {"say": "the full sheet on stud 500100"}, {"new": "2"},
                      {"say": "panel 500300 on stud 500108"}, {"say": "the full sheet on stud 500100"}])
    assert replies[1]["command"]["drywall_id"] == "500320"
    assert replies[3] == {"kind": "refusal", "reason": "not_on_top", "text": replies[3]["text"]}
    assert replies[4]["command"]["drywall_id"] == "500320"  # the fresh site has it on top again


def test_a_malformed_request_gets_an_error_and_the_process_goes_on():
    from drywall_lab.dialogue import MAX_REQUEST_CHARS

    junk = ['{"say": "put the', "\x00\x81 garbage", "[1, 2]", "42", '{"say": 5}', '{"choose": true}',
            '{"choose": 7}', '{"new": "a", "say": "b"}', '{"shout": "x"}', '{"say": "' + "x" * (MAX_REQUEST_CHARS * 3) + '"}',
            "", {"new": "after"}, {"say": "the full sheet on stud 500100"}]
    replies = _serve(junk)
    assert [r["kind"] for r in replies] == ["error"] * 10 + ["ready", "command"]  # the empty line gets no reply
    assert "longer than" in replies[9]["text"]


def test_an_instruction_too_long_is_refused_before_tagging():
    """``run``, ``chat`` and ``dialogue`` refuse an instruction over ``MAX_INSTRUCTION_WORDS`` words without tagging
    it: the tagger here fails the test if it is given one."""
    from drywall_lab.pipeline import MAX_INSTRUCTION_WORDS, run_episode

    class ShortOnly(ScriptedTagger):
        def predict_confidence(self, sentences, k=5, batch_size=64):
            assert all(len(s) <= MAX_INSTRUCTION_WORDS for s in sentences), "a long instruction was tagged"
            return super().predict_confidence(sentences, k, batch_size)

        def predict_kbest(self, sentences, k, batch_size=64):
            assert all(len(s) <= MAX_INSTRUCTION_WORDS for s in sentences), "a long instruction was tagged"
            return super().predict_kbest(sentences, k, batch_size)

    readings = {**READINGS, "": [("", 1.0)]}
    long_text = "put the full sheet on stud 500100 " * 30_000
    replies = _serve([{"new": 1}, {"say": long_text[:19_000]}, {"say": "the full sheet on stud 500100"}], ShortOnly(readings))
    assert replies[1]["kind"] == "refusal" and "at most 200 words" in replies[1]["text"]
    assert replies[2]["kind"] == "command"
    results = run_episode({"id": "e", "instructions": [long_text, "the full sheet on stud 500100"]}, ShortOnly(readings))
    assert results[0].refusal is not None and "at most 200 words" in results[0].refusal.message
    assert results[1].command.drywall_id == "500320"
    d = Dialogue(ShortOnly(readings))
    assert "at most 200 words" in d.say(long_text).text and len(d.history) == 0
