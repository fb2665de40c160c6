"""The project's hand-written field set (drywall_lab/field.py, data/field/): its size and make-up, its
hand-written tags, its expected outcomes through the IM (spec sections 3-5), and scoring a run on it."""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab.corpus import read_corpus, tokenize
from drywall_lab.corpus.tags import TAGS
from drywall_lab.errors import REFUSAL_REASONS
from drywall_lab.field import (ALL, FIELD_DIR, SOURCE_NAME, FieldSet, parse_instruction, assemble, check_gold, main,
                               read_field_set, score_run)

REPO = Path(__file__).resolve().parent.parent

#: The refusals of spec section 5 that the site and the words decide (the project's reason codes).
SECTION5_REASONS = ("undetermined", "unknown_id", "off_the_end", "ambiguous_size", "no_matching_size", "stack_empty",
                    "no_history", "already_installed", "not_on_top", "past_wall_end", "overlap")
#: The voices of ../shared/field, which the project's own set must not reuse.
SHARED_VOICES = {"foreman", "novice", "fragment", "speech", "corrective"}

#: Steps whose hand-written tags the IM cannot yet map to the reading the spec demands. The data is
#: not bent to the IM: each is a gap for the lead to review (issue 11). (episode, step): why.


@pytest.fixture(scope="module")
def field() -> FieldSet:
    return read_field_set()


@pytest.fixture(scope="module")
def mismatches(field) -> dict[tuple[str, int], dict]:
    return {(m["episode"], m["step"]): m for m in check_gold(field)}


# --- the set ------------------------------------------------------------------------------------
def test_size_episodes_and_voices(field):
    assert len(field.gold) >= 200
    assert 45 <= len(field.episodes) <= 55
    assert all(2 <= len(e["instructions"]) <= 8 for e in field.episodes)
    voices = pd.Series([g["style"] for g in field.gold]).value_counts()
    assert len(voices) >= 7
    assert not set(voices.index) & SHARED_VOICES
    assert voices.min() >= 20, voices  # every voice is measured on enough steps to be worth a row
    assert field.voices == sorted(voices.index)
    frame = field.frame()
    assert len(frame) == len(field.gold) and frame["refusal"].notna().sum() == frame["drywall_id"].isna().sum()


def test_every_refusal_reason_and_about_one_step_in_eight(field):
    assert set(SECTION5_REASONS) <= set(REFUSAL_REASONS)
    reasons = [g["expect"]["refusal"] for g in field.gold if "refusal" in g["expect"]]
    assert set(reasons) >= set(SECTION5_REASONS)
    assert 0.09 <= len(reasons) / len(field.gold) <= 0.16


def test_all_four_placements_and_every_stack_are_expected(field):
    commands = [g["expect"] for g in field.gold if "refusal" not in g["expect"]]
    assert {c["placement"] for c in commands} == {"vertical_left", "vertical_middle", "horizontal_top",
                                                  "horizontal_bottom"}
    assert {c["drywall_id"][-1] for c in commands} == {"0", "1", "2"}  # the left, middle and right stacks


def test_words_are_tokenize_and_tags_are_the_13(field):
    for g in field.gold:
        assert g["words"] == tokenize(g["text"]), g["text"]
        assert len(g["tags"]) == len(g["words"])
        assert set(g["tags"]) <= set(TAGS)
    tags = {t for g in field.gold for t in g["tags"]}
    assert tags == set(TAGS)  # every label is used somewhere


def test_the_json_lines_are_the_hand_typed_source(field):
    episodes, gold = assemble(FIELD_DIR / SOURCE_NAME)
    assert episodes == field.episodes
    assert gold == field.gold


def test_the_run_input_is_the_batch_contract(field):
    from drywall_lab.pipeline import read_episodes

    episodes = read_episodes(FIELD_DIR / "instructions.jsonl")
    assert [e["id"] for e in episodes] == [e["id"] for e in field.episodes]
    assert sum(len(e["instructions"]) for e in episodes) == len(field.gold)


def test_no_field_sentence_is_in_the_generated_corpus(field):
    generated = {tuple(r["words"]) for rows in read_corpus().values() for r in rows}
    assert not [g["text"] for g in field.gold if tuple(g["words"]) in generated]


def test_readme_counts_are_the_sets(field):
    text = (FIELD_DIR / "README.md").read_text(encoding="utf-8")
    refusals = sum("refusal" in g["expect"] for g in field.gold)
    assert f"{len(field.gold)} instructions in {len(field.episodes)} episodes" in text
    assert f"({len(field.gold) - refusals} commands, {refusals} refusals" in text


def _occurs(words: list[str], tags: list[str], field: FieldSet) -> bool:
    n = len(words)
    return any(g["words"][i:i + n] == words and g["tags"][i:i + n] == tags
               for g in field.gold for i in range(len(g["words"]) - n + 1))


def test_guideline_examples_are_in_the_set(field):
    """Every tagged example of annotation_guidelines/field_set.md occurs, with its tags, in the field set."""
    text = (REPO / "annotation_guidelines" / "field_set.md").read_text(encoding="utf-8")
    tagged = re.compile(r"/(%s)(?![A-Za-z_])" % "|".join(t for t in TAGS if t != "O"))
    examples = [span for span in re.findall(r"`([^`]+)`", text) if tagged.search(span)]
    assert len(examples) >= 15
    for span in examples:
        for part in filter(str.strip, span.split("...")):
            _, words, tags = parse_instruction(part, "field_set.md")
            assert _occurs(words, tags, field), span


# --- the gold through the IM --------------------------------------------------------------------
def test_hand_written_tags_give_every_expected_outcome(mismatches):
    """Every step except the listed IM gaps: the IM with the hand-written tags gives the expected outcome."""
    assert not mismatches, "\n".join(f"{k}: {m['text']!r} expected {m['expect']}, got {m['got']} ({m['message']})"
                                      for k, m in mismatches.items())


def test_check_gold_reports_a_wrong_expectation(field):
    """check_gold is not vacuous: a changed expectation is caught, and the rest of its episode is not disturbed."""
    gold = [dict(g) for g in field.gold]
    i = next(i for i, g in enumerate(gold) if g["episode"] == "ep01" and g["step"] == 2)
    gold[i]["expect"] = {**gold[i]["expect"], "placement": "vertical_left"}
    j = next(j for j, g in enumerate(gold) if g["episode"] == "ep02" and g["step"] == 0)
    gold[j]["expect"] = {"refusal": "unknown_id"}
    found = {(m["episode"], m["step"]): m for m in check_gold(FieldSet(field.episodes, gold))}
    assert set(found) == {("ep01", 2), ("ep02", 0)}
    assert found[("ep01", 2)]["got"]["placement"] == "vertical_middle"
    assert found[("ep02", 0)]["got"] == {"refusal": "no_history"}


def test_check_gold_reports_a_gold_the_site_cannot_carry_out(field):
    """A gold that installs one panel twice is reported step by step, not a crash."""
    gold = [dict(g) for g in field.gold if g["episode"] == "ep02"]
    gold[0]["expect"] = dict(gold[1]["expect"])  # 500320 on 500104 expected at steps 0 and 1
    found = {(m["episode"], m["step"]): m["got"] for m in check_gold(FieldSet(field.episodes, gold))}
    assert found == {("ep02", 0): {"refusal": "no_history"},
                     ("ep02", 1): {"refusal": "overlap"}}  # 500310 over the 500320 the gold put there


def test_read_field_set_names_a_bad_line(tmp_path, field):
    (tmp_path / "instructions.jsonl").write_text((FIELD_DIR / "instructions.jsonl").read_text())
    lines = (FIELD_DIR / "gold.jsonl").read_text().splitlines()
    bad = json.loads(lines[3])
    bad["tags"] = bad["tags"][:-1]
    lines[3] = json.dumps(bad)
    (tmp_path / "gold.jsonl").write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"gold.jsonl, line 4: .* words but .* tags"):
        read_field_set(tmp_path)
    with pytest.raises(FileNotFoundError, match="no instructions.jsonl"):
        read_field_set(tmp_path / "nowhere")


def test_assemble_refuses_a_tag_on_punctuation_and_a_missing_outcome(tmp_path):
    source = tmp_path / "set.txt"
    source.write_text("== a1 radio\n> Panel 500320/ID_wall, stud 500100/ID_stud ,/ID_stud over\n= 500320 500100 vertical_left\n")
    with pytest.raises(ValueError, match="line 2: ',' is tagged ID_stud but is only punctuation"):
        assemble(source)
    source.write_text("== a1 radio\n> Panel 500320/ID_wall, stud 500100/ID_stud\n")
    with pytest.raises(ValueError, match="no '=' line"):
        assemble(source)
    source.write_text("== a1 radio\n> Panel 500320/ID_wall \\n stud 500100/ID_stud\n= refuse nonsense\n")
    with pytest.raises(ValueError, match="unknown refusal reason 'nonsense'"):
        assemble(source)


def test_assemble_keeps_line_breaks_and_punctuation(tmp_path):
    source = tmp_path / "set.txt"
    source.write_text("== a1 checklist\n> - panel: 4'x8'/width \\n - stud: 500100/ID_stud. \\n - fix: centre/Vr_md\n"
                      "= 500320 500100 vertical_middle\n")
    episodes, gold = assemble(source)
    assert episodes == [{"id": "a1", "instructions": ["- panel: 4'x8'\n- stud: 500100.\n- fix: centre"]}]
    assert gold[0]["words"] == ["-", "panel", "4'x8", "-", "stud", "500100", "-", "fix", "centre"]
    assert gold[0]["tags"] == ["O", "O", "width", "O", "O", "ID_stud", "O", "O", "Vr_md"]
    assert gold[0]["style"] == "checklist"


# --- scoring a run ------------------------------------------------------------------------------
def _command(panel: str, stud: str, placement: str = "vertical_left") -> dict:
    return {"drywall_id": panel, "stud_id": stud, "placement": placement}


#: Two voices, six steps: texting expects 3 commands and a refusal; radio a command and a refusal.
GOLD = [
    {"episode": "t", "step": 0, "style": "texting", "expect": _command("500320", "500100")},
    {"episode": "t", "step": 1, "style": "texting", "expect": _command("500310", "500103")},
    {"episode": "t", "step": 2, "style": "texting", "expect": {"refusal": "overlap"}},
    {"episode": "t", "step": 3, "style": "texting", "expect": _command("500321", "500106", "vertical_middle")},
    {"episode": "r", "step": 0, "style": "radio", "expect": {"refusal": "not_on_top"}},
    {"episode": "r", "step": 1, "style": "radio", "expect": _command("500322", "500100")},
]


def _record(episode: str, step: int, command: dict | None = None, refusal: str | None = None) -> dict:
    return {"episode": episode, "step": step, "words": [], "tags": [], "command": command, "refusal": refusal}


RECORDS = [
    _record("t", 0, _command("500320", "500100")),                      # right
    _record("t", 1, _command("500310", "500104")),                      # wrong action: another stud
    _record("t", 2, refusal="Panel 500320 would overlap ..."),          # right: a refusal was expected
    _record("t", 3, refusal="Which stud?"),                             # over-refusal
    _record("r", 0, _command("500300", "500100")),                      # wrong action: should have refused
    _record("r", 1, _command("500322", "500100", "vertical_middle")),   # wrong action: another placement
]


def test_score_run_by_voice_and_all():
    table = score_run(RECORDS, GOLD)
    assert list(table.index) == ["radio", "texting", ALL]
    texting, radio, total = table.loc["texting"], table.loc["radio"], table.loc[ALL]
    assert texting["n"] == 4 and radio["n"] == 2 and total["n"] == 6
    assert texting["accuracy"] == pytest.approx(2 / 4)
    assert texting["wrong_action_rate"] == pytest.approx(1 / 4)
    assert texting["over_refusal_rate"] == pytest.approx(1 / 4)
    assert texting["refusal_precision"] == pytest.approx(1 / 2)  # two refusals given, one expected
    assert texting["refusal_recall"] == pytest.approx(1.0)
    assert radio["accuracy"] == 0 and radio["wrong_action_rate"] == 1 and radio["over_refusal_rate"] == 0
    assert math.isnan(radio["refusal_precision"])  # no refusal given
    assert radio["refusal_recall"] == 0
    assert total["accuracy"] == pytest.approx(2 / 6)
    assert total["wrong_action_rate"] == pytest.approx(3 / 6)
    assert total["over_refusal_rate"] == pytest.approx(1 / 6)
    assert total["refusal_precision"] == pytest.approx(1 / 2)
    assert total["refusal_recall"] == pytest.approx(1 / 2)


def test_score_run_of_the_gold_itself_is_perfect(field):
    records = [_record(g["episode"], g["step"], None if "refusal" in g["expect"] else g["expect"],
                       g["expect"].get("refusal")) for g in field.gold]
    table = score_run(records, field)
    assert table.loc[ALL, "n"] == len(field.gold)
    assert (table["accuracy"] == 1).all() and (table["wrong_action_rate"] == 0).all()
    assert (table["refusal_recall"].fillna(1) == 1).all()


def test_score_run_refuses_a_run_that_does_not_match_the_gold():
    with pytest.raises(ValueError, match="no record for 1 gold step"):
        score_run(RECORDS[:-1], GOLD)
    with pytest.raises(ValueError, match="no such step"):
        score_run(RECORDS + [_record("t", 9, refusal="?")], GOLD)
    with pytest.raises(ValueError, match="appears twice"):
        score_run(RECORDS + RECORDS[:1], GOLD)
    with pytest.raises(ValueError, match="exactly one of 'command' and 'refusal'"):
        score_run([_record("t", 0)] + RECORDS[1:], GOLD)


OUTCOMES = st.sampled_from(["command_right", "command_other", "refusal"])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["a", "b", "c"]), st.booleans(), OUTCOMES), min_size=1, max_size=40))
def test_score_run_rates_partition_the_steps(steps):
    """Every step is right, a wrong action or an over-refusal; ALL counts every voice's steps."""
    gold, records = [], []
    for k, (voice, refusal_expected, said) in enumerate(steps):
        expect = {"refusal": "overlap"} if refusal_expected else _command("500320", "500100")
        gold.append({"episode": "e", "step": k, "style": voice, "expect": expect})
        command = {"command_right": _command("500320", "500100"), "command_other": _command("500320", "500101")}
        records.append(_record("e", k, command.get(said), "no" if said == "refusal" else None))
    table = score_run(records, gold)
    sums = table["accuracy"] + table["wrong_action_rate"] + table["over_refusal_rate"]
    assert (sums.round(12) == 1).all()
    assert table.loc[ALL, "n"] == table.drop(index=ALL)["n"].sum() == len(steps)
    assert table.loc[ALL, "right"] == sum((r and s == "refusal") or (not r and s == "command_right")
                                          for _, r, s in steps)


def test_command_line_check_and_score(tmp_path, field, capsys):
    assert main(["check"]) == 0
    assert f"{len(field.gold)} steps, 0 mismatch(es)" in capsys.readouterr().out
    run = tmp_path / "run.jsonl"
    run.write_text("".join(json.dumps(_record(g["episode"], g["step"], refusal="no")) + "\n" for g in field.gold))
    assert main(["score", str(run)]) == 0
    out = capsys.readouterr().out
    assert "ALL" in out and "over_refusal_rate" in out
    assert main(["score", str(tmp_path / "missing.jsonl")]) == 2


# --- for the course (notebook 07) ----------------------------------------------------------------------------
def test_failures_lists_the_wrong_steps_with_the_words_tagged_differently(field):
    from drywall_lab.field import failures

    records = [_record(g["episode"], g["step"], command=g["expect"]) if "refusal" not in g["expect"]
               else _record(g["episode"], g["step"], refusal="no") for g in field.gold]
    assert failures(records, field).empty
    first = next(i for i, g in enumerate(field.gold) if "refusal" not in g["expect"] and "ID_stud" in g["tags"])
    g = field.gold[first]
    wrong_tags = ["O" if t == "ID_stud" else t for t in g["tags"]]
    records[first] = {**_record(g["episode"], g["step"], refusal="which stud?"), "words": g["words"], "tags": wrong_tags}
    table = failures(records, field)
    assert list(table["mistake"]) == ["over_refusal"] and "ID_stud -> O" in table["tags_differ"].iloc[0]


def test_check_own_instructions_passes_right_ones_and_names_a_wrong_action():
    from drywall_lab.field import check_own_instructions

    expected = {"drywall_id": "500320", "stud_id": "500100", "placement": "vertical_left"}
    good = ["Pick up the full-size drywall and put it on stud 500100.", "panel 500320 on stud 500100",
            "Put the standard panel on stud 500100, please."]
    check = check_own_instructions(good, expected)
    assert check.passed, str(check)
    wrong = good[:2] + ["panel 500320 on stud 500101"]
    check = check_own_instructions(wrong, expected)
    assert not check.passed and "MOVED THE ROBOT WRONGLY" in str(check)
    check = check_own_instructions(good[:1] * 3, expected)
    assert not check.passed and "at least 3 different instructions" in str(check)


def test_read_ablation(tmp_path):
    from drywall_lab.nlu.field_study import read_ablation

    table, note = read_ablation(tmp_path / "results" / "field")
    assert table is None and "experiment field" in note
    study = tmp_path / "results" / "field"
    study.mkdir(parents=True)
    (study / "ablation.csv").write_text("model,kind,test acc_task\nLSTM paper,bilstm-crf,1.0\n")
    (study / "README.md").write_text("- wall time: 3.0 min\n")
    table, note = read_ablation(study)
    assert table.loc["LSTM paper", "test acc_task"] == 1.0 and "1 models" in note and "wall time: 3.0 min" in note
    assert "Out of date" not in note  # no kept rows: nothing to compare
    # a kept row from another corpus or other settings is named as out of date; a current one is not
    import json

    from drywall_lab.nlu.field_study import FieldStudySettings, study_fingerprint

    (study / "rows").mkdir()
    (study / "rows" / "lstm-paper.json").write_text(json.dumps({"fingerprint": "old", "row": {"model": "LSTM paper"}}))
    assert "Out of date: the rows of LSTM paper were made" in read_ablation(study)[1]
    current = study_fingerprint(FieldStudySettings.full())
    (study / "rows" / "lstm-paper.json").write_text(json.dumps({"fingerprint": current, "row": {"model": "LSTM paper"}}))
    assert "Out of date" not in read_ablation(study)[1]


def test_the_field_corpus_trains_on_both_training_splits():
    from drywall_lab.splits import training_rows

    with pytest.raises(ValueError, match="unknown corpus"):
        training_rows("web")
    paper = training_rows("paper")
    assert len(paper) == 1268 and {r["id"][:5] for r in paper} == {"train"}


def test_the_ablation_is_put_together_from_current_rows(tmp_path):
    """``experiment field --models``: a run trains only the models named, keeps each row with a fingerprint, and
    the table holds every current row (in study order); a row from another corpus or setting is left out."""
    import json

    from drywall_lab.nlu.field_study import FieldStudySettings, read_ablation, run_field_study

    tiny = FieldStudySettings(lstm_epochs={"paper": 1, "field": 1}, bert_epochs={"paper": 1, "field": 1},
                              train_sizes={"paper": 40, "field": 40}, evaluation_size=8)
    with pytest.raises(ValueError, match="unknown model.*LSTM paper"):
        run_field_study(tmp_path, tiny, ["LSTM web"])
    table = run_field_study(tmp_path, tiny, ["LSTM paper"])
    assert list(table["model"]) == ["LSTM paper"] and table.loc[0, "n_train"] == 40
    assert 0 <= table.loc[0, "data/field decided wrong"] <= 1
    readme = (tmp_path / "README.md").read_text(encoding="utf-8")
    assert "Not run yet with the current corpus and settings: LSTM+char paper, MiniLM paper" in readme
    row_file = tmp_path / "rows" / "lstm-paper.json"
    kept = json.loads(row_file.read_text(encoding="utf-8"))
    assert kept["row"]["model"] == "LSTM paper"
    # another run with another model keeps the first row; the table follows the study's order
    (tmp_path / "rows" / "lstm-char-paper.json").write_text(json.dumps({**kept, "row": {**kept["row"], "model": "LSTM+char paper"}}))
    table = run_field_study(tmp_path, tiny, [])
    assert list(table["model"]) == ["LSTM paper", "LSTM+char paper"]
    assert read_ablation(tmp_path)[0].index.tolist() == ["LSTM paper", "LSTM+char paper"]
    # a row whose fingerprint is not current (another corpus, other settings) is not shown
    row_file.write_text(json.dumps({**kept, "fingerprint": "old"}))
    table = run_field_study(tmp_path, tiny, [])
    assert list(table["model"]) == ["LSTM+char paper"]
    assert "Not run yet with the current corpus and settings: LSTM paper, MiniLM paper" in (tmp_path / "README.md").read_text()


def test_the_ablation_scores_a_kept_model_without_training_it_again(tmp_path, capsys, monkeypatch):
    """``experiment field --keep-models``: a model trained once is kept with its training fingerprint; a later run
    (here: after the decision layer's settings changed, so the row itself is stale) scores the kept model instead
    of training it, and a model kept under another fingerprint is trained again."""
    import json

    from drywall_lab import decision
    from drywall_lab.nlu import field_study as FS

    tiny = FS.FieldStudySettings(lstm_epochs={"paper": 1, "field": 1}, bert_epochs={"paper": 1, "field": 1},
                                 train_sizes={"paper": 40, "field": 40}, evaluation_size=8)
    models = tmp_path / "models"
    first = FS.run_field_study(tmp_path / "out", tiny, ["LSTM paper"], keep_models=models)
    assert "LSTM paper: trained" in capsys.readouterr().out
    kept = models / "lstm-paper"
    assert (kept / FS.MODEL_STAMP).read_text().strip() == FS.training_fingerprint(tiny)
    weights = {p.name: p.read_bytes() for p in kept.iterdir() if p.is_file()}

    row_before = json.loads((tmp_path / "out" / "rows" / "lstm-paper.json").read_text())
    import dataclasses

    monkeypatch.setattr(decision, "DEFAULT_SETTINGS", dataclasses.replace(decision.DEFAULT_SETTINGS, option_floor=0.123))
    assert FS.study_fingerprint(tiny) != row_before["fingerprint"]  # the row is stale, the model is not
    again = FS.run_field_study(tmp_path / "out", tiny, ["LSTM paper"], keep_models=models)
    assert f"LSTM paper: the model kept in {kept}" in capsys.readouterr().out
    assert {p.name: p.read_bytes() for p in kept.iterdir() if p.is_file()} == weights
    assert again.loc[0, "train_seconds"] == first.loc[0, "train_seconds"]
    assert again.loc[0, "test acc_inst"] == first.loc[0, "test acc_inst"]

    (kept / FS.MODEL_STAMP).write_text("another corpus\n")
    FS.run_field_study(tmp_path / "out", tiny, ["LSTM paper"], keep_models=models)
    assert "LSTM paper: trained" in capsys.readouterr().out
    assert (kept / FS.MODEL_STAMP).read_text().strip() == FS.training_fingerprint(tiny)
