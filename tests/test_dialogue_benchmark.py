"""The scripted worker of benchmarks/dialogue.py (the rules of ../shared/field/score_dialogue.py), on scripted
readings: a chosen option, a question answered with none, a plain restatement, a missed step, a wrong action."""
from __future__ import annotations

from test_dialogue import CENTRE, READINGS, ScriptedTagger

from drywall_lab.dialogue import Dialogue

MIDDLE = {"drywall_id": "500321", "stud_id": "500104", "placement": "vertical_middle"}
LEFT = {"drywall_id": "500321", "stud_id": "500104", "placement": "vertical_left"}


def _dialogue(extra: dict | None = None) -> Dialogue:
    readings = {**READINGS, **(extra or {})}
    return Dialogue(ScriptedTagger(readings))


def test_the_worker_chooses_the_intended_option_with_one_extra_turn(benchmark_script):
    script = benchmark_script("dialogue")
    d = _dialogue()
    d.respond({"new": "e"})
    assert script.play_step(d, CENTRE, LEFT) == {"outcome": "right", "extra": 1, "first": False, "asked": 1,
                                                 "held": 1}
    assert [c.placement.value for c in d.history.commands] == ["vertical_left"]


def test_a_refusal_is_restated_plainly_once_and_then_missed(benchmark_script):
    script = benchmark_script("dialogue")
    plain = script.plainly(MIDDLE)
    assert plain == "Put panel 500321 on stud 500104, vertically, with its edge on the centre line of the stud."
    said = "Put panel 500321 on stud 500104 vertically with its edge on the centre line of the stud"  # the front end's
    d = _dialogue({said: [("Put panel 500321/ID_wall on stud 500104/ID_stud vertically with its edge on the "
                           "centre/Vr_md line/Vr_md of the stud", 0.99)]})
    d.respond({"new": "e"})
    # "panel 500300" is not on top: refused; the restatement is carried out
    assert script.play_step(d, "panel 500300 on stud 500108", MIDDLE) == {"outcome": "right", "extra": 1,
                                                                         "first": False, "asked": 0, "held": 0}
    d.respond({"new": "e"})
    assert script.play_step(d, "panel 500300 on stud 500108", {"refusal": "not_on_top"}) == {
        "outcome": "right", "extra": 0, "first": True, "asked": 0, "held": 0}
    assert script.play_step(d, "the full sheet on stud 500100", MIDDLE)["outcome"] == "wrong"


def test_scores_by_voice(benchmark_script):
    import pandas as pd

    script = benchmark_script("dialogue")
    frame = pd.DataFrame([{"voice": "a", "outcome": "right", "extra": 1, "first": False, "asked": 1, "held": 1},
                          {"voice": "a", "outcome": "missed", "extra": 2, "first": False, "asked": 1, "held": 0},
                          {"voice": "a", "outcome": "right", "extra": 0, "first": True, "asked": 0, "held": 0},
                          {"voice": "a", "outcome": "wrong", "extra": 0, "first": False, "asked": 0, "held": 0}])
    s = script.scores(frame)
    assert (s["success"], s["wrong"], s["missed"], s["first_reply"], s["extra_turns"]) == (0.5, 0.25, 0.25, 0.25, 0.75)
    assert (s["questions"], s["options_hold"]) == (2, 0.5)
