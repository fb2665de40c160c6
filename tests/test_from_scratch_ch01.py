"""Notebook 01's from-scratch piece: the entities of a tag sequence (``entity_spans``, checked by
``check_entity_spans`` against seqeval's entities), entity-level scores, and the annotator's confusion heatmap."""
from __future__ import annotations

from pathlib import Path

import matplotlib
import nbformat
import pandas as pd
import pytest
from seqeval.metrics import f1_score, precision_score, recall_score

from drywall_lab.corpus import from_conll
from drywall_lab.course.annotation import (PRACTICE_DIR, check_entity_spans, entity_matches, entity_scores,
                                           plot_confusion, reference_entity_spans)
from drywall_lab.course.common import solution_file
from drywall_lab.course.solutions import ch01

matplotlib.use("Agg")

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "01_annotation.ipynb"
MARKER = "# from scratch: your code here"


def _raise_stub(tags):
    raise NotImplementedError("your code here")


def _dots_stub(tags):
    ...


def test_reference_spans_are_maximal_runs_of_one_tag_end_exclusive():
    tags = ["St_loc1", "St_loc1", "St_loc2", "O", "O", "dim", "O", "dim", "dim"]
    assert reference_entity_spans(tags) == {("St_loc1", 0, 2), ("St_loc2", 2, 3), ("dim", 5, 6), ("dim", 7, 9)}
    assert reference_entity_spans([]) == set() and reference_entity_spans(["O", "O"]) == set()


def test_entity_scores_are_seqeval_s_micro_scores_on_the_practice_set():
    key = [r["tags"] for r in from_conll(PRACTICE_DIR / "practice_key.conll")]
    answer = [r["tags"] for r in from_conll(PRACTICE_DIR / "student_answer.conll")]
    scores = entity_scores(key, answer)
    io = [[[t if t == "O" else f"I-{t}" for t in tags] for tags in side] for side in (key, answer)]
    assert scores.loc["ALL", "precision"] == pytest.approx(precision_score(*io))
    assert scores.loc["ALL", "recall"] == pytest.approx(recall_score(*io))
    assert scores.loc["ALL", "f1"] == pytest.approx(f1_score(*io))
    assert scores.loc["ALL", "correct"] < scores.loc["ALL", "gold"]  # the student's answer is not perfect
    perfect = entity_scores(key, key)
    assert (perfect["precision"] == 1).all() and (perfect["recall"] == 1).all()


def test_entity_matches_shows_a_run_cut_in_two():
    words = ["in", "the", "upper", "horizontal", "row"]
    table = entity_matches(words, ["O", "O", "Hr_top", "Hr_top", "Hr_top"], ["O", "O", "Hr_top", "O", "Hr_top"])
    assert list(table["words"]) == ["upper", "upper horizontal row", "row"]
    assert list(table["in gold"]) == [False, True, False] and list(table["predicted"]) == [True, False, True]


def test_the_solution_passes():
    check = check_entity_spans(ch01.entity_spans)
    assert check.passed and check.attempted, str(check)
    assert "agree with seqeval's entities" in str(check)


@pytest.mark.parametrize("stub", [_raise_stub, _dots_stub])
def test_the_stub_is_not_attempted(stub):
    check = check_entity_spans(stub)
    text = str(check)
    assert not check.passed and not check.attempted, text
    assert text.startswith("NOT ATTEMPTED YET:\n- fill in "), text
    assert solution_file(1) in text


def _inclusive_ends(tags):
    return {(t, s, e - 1) for t, s, e in ch01.entity_spans(tags)}


def _runs_over_tag_changes(tags):
    spans, start = set(), None
    for i, tag in enumerate(list(tags) + ["O"]):
        if tag == "O" and start is not None:
            spans.add((tags[start], start, i))
            start = None
        elif tag != "O" and start is None:
            start = i
    return spans


def _o_as_entity(tags):
    spans, start = set(), 0
    for i in range(1, len(tags) + 1):
        if i == len(tags) or tags[i] != tags[start]:
            spans.add((tags[start], start, i))
            start = i
    return spans


def _one_per_word(tags):
    return {(t, i, i + 1) for i, t in enumerate(tags) if t != "O"}


@pytest.mark.parametrize("wrong, expected", [
    (_inclusive_ends, "your ends are inclusive"),
    (_runs_over_tag_changes, "runs on over a change of tag at word 3 (St_loc1 then St_loc2)"),
    (_o_as_entity, "('O', 0, 7) is not an entity"),
    (_one_per_word, "a run of words with the same tag is one entity"),
    (lambda tags: len(tags), "return a set of (tag, start, end) tuples"),
])
def test_wrong_answers_fail_with_what_is_wrong(wrong, expected):
    check = check_entity_spans(wrong)
    assert not check.passed and check.attempted
    assert expected in str(check), str(check)


def test_a_list_of_lists_is_accepted():
    assert check_entity_spans(lambda tags: [list(span) for span in ch01.entity_spans(tags)]).passed


def test_the_confusion_heatmap_writes_each_count():
    confusion = pd.DataFrame([[9, 1], [2, 4]], index=["length", "width"], columns=["length", "width"])
    ax = plot_confusion(confusion)
    assert sorted(t.get_text() for t in ax.texts) == ["1", "2", "4", "9"]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["length", "width"]
    matplotlib.pyplot.close(ax.figure)


def test_the_notebook_holds_the_stub_names_the_solution_file_and_has_the_glossary():
    cells = nbformat.read(NOTEBOOK, as_version=4).cells
    found = [i for i, c in enumerate(cells) if c.cell_type == "code" and MARKER in c.source]
    assert len(found) == 1
    source = cells[found[0]].source
    assert 'raise NotImplementedError("your code here")' in source and "spans.add" not in source
    assert source.rstrip().endswith("check = check_entity_spans(entity_spans)\nprint(check)\n"
                                    "assert check.passed or not check.attempted")
    above = next(c for c in reversed(cells[:found[0]]) if c.cell_type == "markdown")
    assert f"`{solution_file(1)}`" in above.source and "try the exercise first" in above.source
    after = "\n".join(c.source for c in cells[found[0] + 1:] if c.cell_type == "code")
    assert "entity_spans(" not in after.replace("reference_entity_spans(", "")  # nothing after uses the student's
    glossary = next(c.source for c in cells if c.cell_type == "markdown" and c.source.startswith("## Glossary"))
    for metric in ("Acc_word", "Acc_inst", "acc_task", "precision", "recall", "F1", "decided", "wrong action",
                   "extra turns"):
        assert metric in glossary, metric
    assert any(c.cell_type == "code" and "plot_confusion(" in c.source for c in cells)
