"""Tests of drywall_lab.course: the fast-mode switch, the table helpers, the study readers and the exercise checks
of notebooks 01-04 (each check against the reference answer and against wrong ones)."""
from __future__ import annotations

import json
from collections import Counter

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab import course
from drywall_lab.corpus import TAGS, read_corpus, tag_table
from drywall_lab.course import bert as course_bert
from drywall_lab.course import fast_mode
from drywall_lab.errors import REFUSAL_REASONS
from drywall_lab.nlu import vote_word_tags
from drywall_lab.nlu.experiments import MINILM_LEARNING_RATE
from drywall_lab.pipeline import paper_layouts


# --- fast mode ---------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("value", ["1", "true", "TRUE", "True", "yes", "Yes", "on", "ON", " 1 "])
def test_fast_mode_on(monkeypatch, value):
    monkeypatch.setenv("DRYWALL_FAST", value)
    assert fast_mode() is True


@pytest.mark.parametrize("value", ["0", "false", "FALSE", "", "no", "off", "  "])
def test_fast_mode_off(monkeypatch, value):
    monkeypatch.setenv("DRYWALL_FAST", value)
    assert fast_mode() is False


def test_fast_mode_unset_is_full_mode(monkeypatch):
    monkeypatch.delenv("DRYWALL_FAST", raising=False)
    assert fast_mode() is False


@pytest.mark.parametrize("value", ["2", "fast", "y es"])
def test_fast_mode_rejects_unknown_values(monkeypatch, value):
    monkeypatch.setenv("DRYWALL_FAST", value)
    with pytest.raises(ValueError, match="DRYWALL_FAST"):
        fast_mode()


# --- tables ------------------------------------------------------------------------------------------------------
def test_percent_table_reads_as_text_and_leaves_the_numbers():
    frame = pd.DataFrame({"model": ["a", "b"], "N_w": [0, 3], "Acc_inst": [1.0, 0.9177215], "acc_task": [0.5, np.nan]})
    shown = course.percent_table(frame)
    assert list(shown["Acc_inst"]) == ["100.00%", "91.77%"]
    assert list(shown["acc_task"]) == ["50.00%", ""]
    assert "91.77%" in shown.to_string() and "Styler" not in repr(shown)
    assert frame["Acc_inst"].iloc[1] == pytest.approx(0.9177215)  # the original is untouched
    assert list(course.percent_table(frame, ["Acc_inst"], digits=1)["Acc_inst"]) == ["100.0%", "91.8%"]


class _FixedTagger:
    """A stand-in tagger that answers with given tag lists."""

    def __init__(self, answers):
        self.answers = answers

    def predict(self, sentences):
        return [list(a) for a in self.answers[: len(sentences)]]

    def gold_tags(self, rows):
        return [r["tags"] for r in rows]


def test_table_3_row_scores_and_maps_through_the_rules():
    rows = read_corpus()["validation"][:20]
    perfect = course.table_3_row("gold", _FixedTagger([r["tags"] for r in rows]), rows)
    assert perfect == {"model": "gold", "N_w": 0, "Acc_word": 1.0, "N_l": 0, "Acc_inst": 1.0, "acc_task": 1.0}
    all_o = course.table_3_row("all O", _FixedTagger([["O"] * len(r["words"]) for r in rows]), rows)
    assert all_o["N_w"] == sum(t != "O" for r in rows for t in r["tags"])
    assert all_o["Acc_inst"] == 0.0 and all_o["acc_task"] < 0.2
    table = course.table_3({"gold": _FixedTagger([r["tags"] for r in rows])}, rows)
    assert table.index.tolist() == ["gold"] and table.loc["gold", "acc_task"] == 1.0
    with pytest.raises(ValueError, match="no instructions"):
        course.table_3_row("empty", _FixedTagger([]), [])


def test_scores_on_sets_scores_each_named_set():
    from drywall_lab.splits import split_rows

    sets = ["validation", "field-set"]
    by_words = {tuple(r["words"]): r["tags"] for name in sets for r in split_rows(name)}

    class GoldTagger(_FixedTagger):
        """Answers every instruction of the two sets with its gold tags."""

        def predict(self, sentences):
            return [list(by_words[tuple(s)]) for s in sentences]

    table = course.scores_on_sets(GoldTagger([]), sets, limit=30)
    assert table.index.tolist() == sets
    assert (table["instructions"] == 30).all() and (table["Acc_inst"] == 1.0).all() and (table["acc_task"] == 1.0).all()
    assert course.scores_on_sets(GoldTagger([]), ["field-set"]).loc["field-set", "instructions"] == len(
        split_rows("field-set"))
    with pytest.raises(ValueError, match="limit"):
        course.scores_on_sets(GoldTagger([]), sets, limit=0)
    with pytest.raises(ValueError, match="unknown split"):
        course.scores_on_sets(GoldTagger([]), ["nonsense"])


def test_tag_share_table_says_which_tags_are_held_to_the_bound():
    table = tag_table(read_corpus())
    shown = course.tag_share_table(table)
    assert "checked" not in shown
    rare = table.index[~table["checked"]]
    assert (shown.loc[rare, "verdict"] == "-").all()
    assert shown.loc[rare, "bound"].str.startswith("none").all()
    held = table.index[table["checked"]]
    assert set(shown.loc[held, "verdict"]) <= {"within", "OUTSIDE"}
    off = table.copy()
    off.loc["O", "within_20%"] = False
    assert course.tag_share_table(off).loc["O", "verdict"] == "OUTSIDE"


# --- the study ---------------------------------------------------------------------------------------------------
SIZES = {"1": 1268, "4": 316}


def _table3(lstm_wrong: int, bert_wrong: int, n: int = 158) -> pd.DataFrame:
    rows = []
    for kind, wrong4 in (("LSTM", lstm_wrong), ("BERT", bert_wrong)):
        for key, wrong in (("1", 0), ("4", wrong4)):
            rows.append({"model": f"{kind}-M{key}", "N_w": wrong, "Acc_word": 1.0, "N_l": wrong,
                         "Acc_inst": 1 - wrong / n, "acc_task": 1 - wrong / (2 * n),
                         "paper_Acc_inst": {"LSTM-M4": 0.4873, "BERT-M4": 0.7911}.get(f"{kind}-M{key}", 0.9937)})
    return pd.DataFrame(rows)


def test_accuracy_by_training_size_reads_table_3():
    frame = course.accuracy_by_training_size(_table3(12, 13), SIZES)
    assert frame.index.tolist() == [1268, 316]
    assert frame.loc[316, "BiLSTM-CRF"] == pytest.approx(1 - 12 / 158)
    assert frame.loc[316, "bert-base, paper"] == pytest.approx(0.7911)
    assert frame.loc[316, "N_l MiniLM (BERT)"] == 13


@pytest.mark.parametrize("lstm_wrong, bert_wrong, says", [
    (12, 13, "within 1 instruction of each other"),
    (40, 10, "MiniLM gets 30 more instructions right"),
    (5, 20, "The BiLSTM-CRF gets 15 more instructions right"),
])
def test_data_efficiency_finding_follows_the_figures(lstm_wrong, bert_wrong, says):
    text = course.data_efficiency_finding(_table3(lstm_wrong, bert_wrong), SIZES, 158)
    assert says in text
    assert f"{1 - lstm_wrong / 158:.2%}" in text and "48.73%" in text
    assert "ahead by about 48 of 158" in text


def test_novel_and_coref_findings_are_computed():
    table3 = _table3(12, 13)
    novel = table3.assign(Acc_inst=[0.5, 0.4, 0.3, 0.2], acc_task=[0.7, 0.6, 0.8, 0.5])
    text = course.novel_finding(table3, novel)
    assert "LSTM-M1 gets 100.00% of the validation instructions entirely right and 50.00% of the novel ones" in text
    assert "LSTM-M1 is ahead" in text
    table5 = table3[table3.model.str.startswith("BERT")].assign(
        model=["BERT-C1", "BERT-C4"], Acc_inst=[1.0, 1 - 16 / 158], paper_Acc_inst=[0.9873, 0.7215])
    text = course.coref_finding(table3, table5, SIZES, 158)
    assert "lower at 1 and higher at 0 of the 2 training sizes" in text
    assert "3 instructions fewer right (the paper: 11 fewer)" in text


def test_the_committed_study_reads(tmp_path):
    """The notebooks' readers work on results/paper as the study writes it."""
    settings_ = course.study_settings()
    table3 = course.read_study_table("table3_validation")
    frame = course.accuracy_by_training_size(table3, settings_["train_sizes"])
    assert len(frame) == len(settings_["train_sizes"])
    assert "Machine" in course.study_provenance()
    with pytest.raises(FileNotFoundError, match="experiment paper"):
        course.read_study_table("table3_validation", tmp_path)
    (tmp_path / "README.md").write_text("no settings here")
    with pytest.raises(ValueError, match="settings"):
        course.study_settings(tmp_path)


def _grid(best_lr: float) -> str:
    points = [{"train_size": n, "learning_rate": lr, "val_acc_inst_by_epoch": [0.9 + 0.05 * (lr == best_lr)] * 3}
              for n in (316, 1268) for lr in (1e-4, best_lr)]
    return "# results\n```\n" + "\n".join(json.dumps(p) for p in points) + "\n```\n"


def test_minilm_choice_says_whether_grid_code_and_study_agree(tmp_path):
    study = tmp_path / "study"
    study.mkdir()
    (study / "README.md").write_text(f'Settings: `{{"bert_learning_rate": {MINILM_LEARNING_RATE}}}`.')
    results = tmp_path / "bert_settings.md"
    results.write_text(_grid(MINILM_LEARNING_RATE))
    table, text = course.minilm_learning_rate_choice(results, study)
    assert f"picks {MINILM_LEARNING_RATE:g}" in text and ": the same." in text
    assert f"ran MiniLM at {MINILM_LEARNING_RATE:g}, this choice" in text
    assert table.loc[MINILM_LEARNING_RATE, "mean_over_sizes"] == pytest.approx(0.95)
    other = 5e-5
    results.write_text(_grid(other))
    (study / "README.md").write_text(f'Settings: `{{"bert_learning_rate": {other}}}`.')
    _, text = course.minilm_learning_rate_choice(results, study)
    assert "NOT the library's" in text and "predate the current choice" in text
    _, text = course.minilm_learning_rate_choice(tmp_path / "missing.md", study)
    assert "is missing" in text


def test_field_results_not_run_and_run(tmp_path):
    table, text = course.field_results(tmp_path / "field.md")
    assert table is None and "not been run yet" in text
    (tmp_path / "field.md").write_text("# Field\n\n**Tagger:** the shipped default\n\n## Summary\n\n```\n"
                                       "data_field_accuracy=0.4600\ndata_field_wrong_action_rate=0.1200\n"
                                       "data_field_over_refusal_rate=0.3000\n```\n")
    table, text = course.field_results(tmp_path / "field.md")
    assert table.loc["data_field", "accuracy"] == pytest.approx(0.46)
    assert table.loc["data_field", "wrong_action_rate"] == pytest.approx(0.12)
    assert "the shipped default" in text


# --- notebook 01: tagging by the guidelines ------------------------------------------------------------------------
def _markup(row: dict) -> str:
    return " ".join(w if t == "O" else f"{w}/{t}" for w, t in zip(row["words"], row["tags"]))


def test_check_tagging_passes_the_key_and_names_each_wrong_word():
    row = course.practice_instruction()
    answer = _markup(row)
    assert course.check_tagging(answer).passed
    assert course.check_tagging(row["tags"]).passed
    wrong = answer.replace("middle/Vr_md", "middle/Dw_loc1").replace("500102/St_loc2", "500102/ID_stud")
    check = course.check_tagging(wrong)
    assert not check.passed
    text = str(check)
    assert text.startswith("NOT YET")
    assert "'middle': you tagged Dw_loc1, the guidelines say Vr_md" in text and 'section 4.1 "middle"' in text
    assert "'500102': you tagged ID_stud, the guidelines say St_loc2" in text and "anchor" in text
    assert f"{len(row['words']) - 2} of {len(row['words'])} words right" in text


def test_check_tagging_explains_bad_answers():
    row = course.practice_instruction()
    answer = _markup(row)
    assert "not a tag" in str(course.check_tagging(answer.replace("/Vr_md", "/Vr_mid", 1)))
    assert "keep the instruction's words" in str(course.check_tagging("Goo " + answer.split(" ", 1)[1]))
    assert "words, the instruction" in str(course.check_tagging(answer + " extra"))
    assert "one tag per word" in str(course.check_tagging(["O"]))
    assert "not a tag" in str(course.check_tagging(["Q"] * len(row["words"])))
    with pytest.raises(ValueError, match="no practice instruction"):
        course.check_tagging(answer, "P99")


@pytest.mark.parametrize("word, gold, given, section", [
    ("middle", "St_loc1", "Vr_md", '4.1 "middle"'),
    ("previous", "dim", "St_loc2", '4.2 "previous"'),
    ("8", "width", "length", "4.3 Width and length"),
    ("vertically", "O", "Vr_md", "4.4 The default placement"),
    ("500103", "St_loc2", "ID_stud", "4.5 Destination, anchor"),
    ("stud", "O", "St_loc1", "2. The general rule"),
])
def test_guideline_sections_point_at_the_hard_cases(word, gold, given, section):
    sections = course.guideline_sections(word, gold, given)
    assert any(s.startswith(f"section {section}") for s in sections), sections
    assert sections[-1] == f"section 3, the tag {gold}"


def test_guideline_sections_say_when_the_guidelines_lack_a_section():
    with pytest.raises(ValueError, match="no section"):
        course.guideline_sections("8", "width", "length", headings=["3. The tags", "width", "length"])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["stud", "500107", "left", "the", "full-size"]), st.sampled_from(TAGS)),
                min_size=1, max_size=8))
def test_parse_tagged_reads_back_what_it_is_given(pairs):
    text = " ".join(w if t == "O" else f"{w}/{t}" for w, t in pairs) + "."
    assert course.parse_tagged(text) == ([w for w, _ in pairs], [t for _, t in pairs])


# --- notebook 02: the CRF's transitions ----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def shipped():
    from drywall_lab.nlu import default_tagger

    return default_tagger()


def test_crf_transitions_is_the_crf_table(shipped):
    member = shipped.members[0]
    table = course.crf_transitions(member)
    assert table.shape == (13, 13) and list(table.index) == list(member.labels) == list(table.columns)
    crf = member.network.crf.transitions.detach().numpy()
    assert table.loc["Hr_btm", "Hr_top"] == pytest.approx(crf[TAGS.index("Hr_btm"), TAGS.index("Hr_top")])
    with pytest.raises(ValueError, match="BiLstmCrfTagger"):
        course.crf_transitions(object())


def test_describe_tagger_reads_the_taggers_record(shipped):
    member = shipped.members[0]
    text = course.describe_tagger(member)
    info = member.training_info
    assert text.startswith("a BiLSTM-CRF") and f"{member.n_parameters():,} parameters" in text
    assert f"trained on {info['n_train_instructions']:,} instructions for {info['epochs']} epochs" in text
    assert ("reading characters" in text) == member.uses_characters
    # the shipped ensemble: described by its members, with their seeds
    text = course.describe_tagger(shipped)
    seeds = ", ".join(str(m.training_info["seed"]) for m in shipped.members)
    assert text.startswith(f"an ensemble of {len(shipped.members)} taggers") and f"seeds {seeds})" in text
    assert f"({shipped.n_parameters():,} parameters in all;" in text and "each BiLSTM-CRF reading characters" in text
    info = shipped.members[0].training_info
    assert text.endswith(f"trained on {info['n_train_instructions']:,} instructions for {info['epochs']} epochs "
                         f"(validated on {info['n_validation_instructions']:,}).")


def test_training_curves_one_per_member(shipped):
    curves = course.training_curves(shipped, "shipped")
    assert len(curves) == len(shipped.members)
    for (name, history), member in zip(curves.items(), shipped.members):
        assert f"seed {member.training_info['seed']}" in name and history is member.history
    single = course.training_curves(shipped.members[0], "one")
    assert list(single) == [f"one ({shipped.members[0].training_info['n_train_instructions']} instructions)"]


def test_crf_transitions_of_an_ensemble_are_its_members_mean(shipped):
    table = course.crf_transitions(shipped)
    mean = np.mean([course.crf_transitions(m).to_numpy() for m in shipped.members], axis=0)
    np.testing.assert_allclose(table.to_numpy(), mean, atol=1e-6)


def test_check_most_forbidden_passes_the_reference(shipped):
    check = course.check_most_forbidden(course.reference_most_forbidden, shipped)
    assert check.passed and "trained tagger" in str(check)


@pytest.mark.parametrize("answer, says", [
    (lambda t, k: [(b, a) for a, b in course.reference_most_forbidden(t, k)], "your pairs are (after, before)"),
    (lambda t, k: list(t.stack().nlargest(k).index), "forbidden means lowest"),
    (lambda t, k: course.reference_most_forbidden(t, k)[::-1], "wrong order"),
    (lambda t, k: course.reference_most_forbidden(t, k + 1), "exactly k"),
    (lambda t, k: list(t.stack().nsmallest(k + 1).index)[1:], "pair 1:"),
    (lambda t, k: 1 / 0, "raised ZeroDivisionError"),
    (lambda t, k: "O", "list of (tag before, tag after) pairs"),
])
def test_check_most_forbidden_fails_wrong_answers(answer, says):
    check = course.check_most_forbidden(answer)
    assert not check.passed and says in str(check), str(check)


# --- notebook 03: the sub-word vote --------------------------------------------------------------------------------
def _most_frequent(tags, word_ids, n_words):
    per_word = [[t for t, w in zip(tags, word_ids) if w == i] for i in range(n_words)]
    return [Counter(t).most_common(1)[0][0] if t else "O" for t in per_word]


def _first_token(tags, word_ids, n_words):
    per_word = [[t for t, w in zip(tags, word_ids) if w == i] for i in range(n_words)]
    return [t[0] if t else "O" for t in per_word]


def _half_is_enough(tags, word_ids, n_words):
    out = []
    for i in range(n_words):
        own = [t for t, w in zip(tags, word_ids) if w == i]
        best, count = Counter(own).most_common(1)[0] if own else ("O", 0)
        out.append(best if count * 2 >= len(own) else own[0])
    return out


def test_check_vote_passes_the_library_vote():
    check = course.check_vote(vote_word_tags)
    assert check.passed and "ties" in str(check)


@pytest.mark.parametrize("answer, says", [
    (_most_frequent, "no tag has more than half of its 5 tokens, so its first token decides: O, not Dw_loc1"),
    (_first_token, "2 of its 3 tokens say ID_stud: more than half, not ID_wall"),
    (_half_is_enough, "exactly half is not more than half"),
    (lambda t, w, n: [vote_word_tags(t, w, n)[0]], "return one tag per word"),
    (lambda t, w, n: vote_word_tags(t, w), "a word with no token gets O"),
])
def test_check_vote_fails_wrong_votes(answer, says):
    check = course.check_vote(answer)
    assert not check.passed and says in str(check), str(check)


def test_vote_cases_cover_ties_and_words_without_tokens():
    cases = course.vote_cases()
    assert any(n > len({w for w in ids if w is not None}) for _, _, ids, n in cases)  # a word with no token
    ties = [tags for _, tags, ids, _ in cases if len(ids) > 1 and len(set(ids)) == 1
            and max(Counter(tags).values()) * 2 <= len(tags)]
    assert len(ties) >= 3


@pytest.fixture(scope="module")
def tiny_bert():
    """MiniLM fine-tuned for one epoch on a few instructions, with a short token budget so that long
    instructions are cut into pieces."""
    import torch

    from drywall_lab.nlu import BertTagger

    torch.set_num_threads(min(2, torch.get_num_threads()))
    tagger = BertTagger(learning_rate=MINILM_LEARNING_RATE, max_length=16)
    tagger.fit(read_corpus()["train"][:16], epochs=1, progress=False, seed=0)
    return tagger


def test_token_predictions_vote_to_what_predict_says(tiny_bert):
    rows = read_corpus()["validation"][:6]
    predicted = tiny_bert.predict([r["words"] for r in rows])
    for row, tags in zip(rows, predicted):
        table = course.token_predictions(tiny_bert, row["words"])
        assert table["word id"].dropna().max() == len(row["words"]) - 1  # every piece, word ids offset
        voted = vote_word_tags(list(table["token tag"]), list(table["word id"]), len(row["words"]))
        assert voted == tags
    batched = course_bert._token_tables(tiny_bert, [r["words"] for r in rows])  # what vote_statistics reads
    for row, table in zip(rows, batched):
        single = course.token_predictions(tiny_bert, row["words"])
        assert table[["token", "word id"]].equals(single[["token", "word id"]])
    stats = course.vote_statistics(tiny_bert, rows)
    assert stats["words of several tokens"] > 0
    assert stats["words of several tokens"] >= stats["tokens disagree"] >= stats["no strict majority"]


# --- notebook 04: rule S3 and the layouts --------------------------------------------------------------------------
def _reference_relative_stud(site, anchor_id, direction, count):
    ids = site.stud_ids
    i = ids.index(anchor_id) + (count if direction == "right" else -count)
    return ids[i] if 0 <= i < len(ids) else None


def test_check_relative_stud_passes_the_reference():
    check = course.check_relative_stud(_reference_relative_stud)
    assert check.passed and "208 cases" in str(check)


@pytest.mark.parametrize("answer, says", [
    (lambda s, a, d, n: s.stud_ids[s.stud_ids.index(a) + (n if d == "right" else -n)]
     if s.stud_ids.index(a) + (n if d == "right" else -n) < 13 else None, "a negative list index"),
    (lambda s, a, d, n: _reference_relative_stud(s, a, "left" if d == "right" else "right", n), "the other direction"),
    (lambda s, a, d, n: _reference_relative_stud(s, a, d, max(n, 1)), "zero places away is the anchor itself"),
    (lambda s, a, d, n: _reference_relative_stud(s, a, d, n + 1), "1 stud to the right of the one the rules give"),
    (lambda s, a, d, n: str(int(a) + (n if d == "right" else -n)), "not a stud of this site"),
    (lambda s, a, d, n: int(a), "as a string"),
    (lambda s, a, d, n: None, "only a step past either end gives None"),
    (lambda s, a, d, n: {}["x"], "never raise"),
])
def test_check_relative_stud_fails_wrong_answers(answer, says):
    check = course.check_relative_stud(answer)
    assert not check.passed and "disagree with rule S3" in str(check)
    assert says in str(check), str(check)


def test_rule_s3_is_the_library_rule():
    assert course.rule_s3("the stud second/St_loc1 to/St_loc1 the/St_loc1 left/St_loc1 of 500109/St_loc2") == (
        "500107", "")
    stud, why = course.rule_s3("the stud two/St_loc1 to/St_loc1 the/St_loc1 left/St_loc1 of 500100/St_loc2")
    assert stud is None and why.startswith("off_the_end")


def test_map_layout_follows_every_paper_layout():
    for layout in paper_layouts():
        run = course.map_layout(layout)
        assert run.problems() == []
        assert len(run.states) == len(run.step_lines()) == len(layout["expected"])
        installed = [len(state.installed) for state in run.states]
        assert installed == list(np.cumsum([r.accepted for r in run.results]))
    layout = dict(paper_layouts()[0])
    layout["expected"] = [{"refusal": "overlap"}] + layout["expected"][1:]
    assert course.map_layout(layout).problems()[0].startswith("step 0: expected {'refusal': 'overlap'}")


def test_refusal_examples_show_every_reason():
    table = course.refusal_examples(read_corpus())
    assert set(table.reason) == set(REFUSAL_REASONS)
    assert table.message.str.len().min() > 20


def test_compact_png_is_a_palette_png_of_the_figure_and_smaller_than_full_colour():
    import io

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from PIL import Image

    fig, ax = plt.subplots(figsize=(4, 3))
    ax.imshow(np.random.default_rng(0).normal(size=(30, 30)), cmap="RdBu")  # a heatmap, many colours
    ax.set_title("transitions")
    full = io.BytesIO()
    fig.savefig(full, format="png", dpi=fig.dpi, bbox_inches="tight")
    small = course.compact_png(fig)
    plt.close(fig)
    image, original = Image.open(io.BytesIO(small)), Image.open(io.BytesIO(full.getvalue()))
    assert image.format == "PNG" and image.mode == "P" and image.size == original.size
    assert len(image.getcolors(maxcolors=256)) <= 256
    assert len(small) < 0.6 * len(full.getvalue())
    assert len(Image.open(io.BytesIO(course.compact_png(plt.figure(), colours=8))).getcolors(maxcolors=8)) <= 8


def test_compact_figures_outside_ipython_does_nothing():
    assert course.compact_figures() is False


def test_committed_notebooks_are_small():
    """The committed notebooks, full-mode outputs included: at most 1 MB each and 3 MB in all."""
    from pathlib import Path

    sizes = {p.name: p.stat().st_size for p in sorted((Path(__file__).parent.parent / "notebooks").glob("*.ipynb"))}
    assert len(sizes) == 7
    assert all(size <= 1_000_000 for size in sizes.values()), sizes
    assert sum(sizes.values()) <= 3_000_000, sizes
