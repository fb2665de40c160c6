"""Scoring an annotator against gold (drywall_lab.annotation)."""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab.annotation import PAPER_ANNOTATOR_ACCURACY, AgreementReport, score_annotator
from drywall_lab.corpus import from_conll
from drywall_lab.corpus.tags import TAGS

REPO = Path(__file__).resolve().parent.parent

GOLD = [
    ["O", "O", "ID_wall", "O", "ID_stud"],
    ["O", "St_loc1", "St_loc1", "O", "Vr_md"],
]
#: Two mistakes, both in instruction 1: St_loc1 -> O at word 2, Vr_md -> O at word 4.
ANNOTATED = [
    ["O", "O", "ID_wall", "O", "ID_stud"],
    ["O", "St_loc1", "O", "O", "O"],
]


@pytest.fixture
def report() -> AgreementReport:
    return score_annotator(GOLD, ANNOTATED)


def test_perfect_agreement() -> None:
    r = score_annotator(GOLD, GOLD)
    assert (r.n_instructions, r.n_words) == (2, 10)
    assert r.word_accuracy == r.instruction_accuracy == r.cohen_kappa == 1.0
    assert r.disagreements == []
    assert (r.confusion.to_numpy() == np.diag(r.per_tag["gold"])).all()
    used = r.per_tag[r.per_tag["gold"] > 0]
    assert (used["recall"] == 1.0).all() and (used["precision"] == 1.0).all()
    assert "no disagreements" in r.summary()


def test_hand_computed_case(report: AgreementReport) -> None:
    assert (report.n_instructions, report.n_words) == (2, 10)
    assert report.word_accuracy == pytest.approx(0.8)
    assert report.instruction_accuracy == pytest.approx(0.5)
    assert report.disagreements == [(1, 2, "St_loc1", "O"), (1, 4, "Vr_md", "O")]


def test_kappa_from_the_counts(report: AgreementReport) -> None:
    # gold counts:      O 5, ID_wall 1, ID_stud 1, St_loc1 2, Vr_md 1
    # annotated counts: O 7, ID_wall 1, ID_stud 1, St_loc1 1, Vr_md 0
    p_o = 8 / 10
    p_e = (5 * 7 + 1 * 1 + 1 * 1 + 2 * 1 + 1 * 0) / 10**2
    assert report.cohen_kappa == pytest.approx((p_o - p_e) / (1 - p_e))
    # the same from the confusion matrix
    m = report.confusion.to_numpy()
    n = m.sum()
    p_e_matrix = (m.sum(axis=1) @ m.sum(axis=0)) / n**2
    assert report.cohen_kappa == pytest.approx((np.trace(m) / n - p_e_matrix) / (1 - p_e_matrix))


def test_confusion_matrix(report: AgreementReport) -> None:
    c = report.confusion
    assert list(c.index) == list(c.columns) == list(TAGS)
    assert (c.index.name, c.columns.name) == ("gold", "annotated")
    assert c.loc["St_loc1", "O"] == 1
    assert c.loc["Vr_md", "O"] == 1
    assert c.loc["O", "St_loc1"] == 0  # rows are gold, not the other way round
    assert c.loc["O", "O"] == 5
    assert c.loc["St_loc1", "St_loc1"] == 1
    off_diagonal = c.to_numpy().sum() - np.trace(c.to_numpy())
    assert off_diagonal == 2
    assert c.to_numpy().sum() == 10


def test_per_tag(report: AgreementReport) -> None:
    t = report.per_tag
    assert list(t.index) == list(TAGS)
    assert list(t.columns) == ["gold", "annotated", "correct", "recall", "precision"]
    assert t.loc["O"].tolist() == pytest.approx([5, 7, 5, 1.0, 5 / 7])
    assert t.loc["St_loc1"].tolist() == pytest.approx([2, 1, 1, 0.5, 1.0])
    assert t.loc["Vr_md", "recall"] == 0.0
    assert math.isnan(t.loc["Vr_md", "precision"])  # never annotated: no precision
    assert t.loc["Hr_top", ["gold", "annotated", "correct"]].tolist() == [0, 0, 0]
    assert math.isnan(t.loc["Hr_top", "recall"]) and math.isnan(t.loc["Hr_top", "precision"])


def test_summary(report: AgreementReport) -> None:
    text = report.summary()
    assert "word accuracy 80.00%" in text
    assert "instruction accuracy 50.00%" in text
    assert f"Cohen's kappa {report.cohen_kappa:.4f}" in text
    assert "St_loc1 -> O (1)" in text
    assert len(text.splitlines()) == 3


def test_custom_labels() -> None:
    r = score_annotator([["A", "B"]], [["A", "A"]], labels=["A", "B"])
    assert list(r.confusion.index) == ["A", "B"]
    assert r.confusion.loc["B", "A"] == 1


def test_single_tag_kappa_is_nan() -> None:
    r = score_annotator([["O", "O"]], [["O", "O"]])
    assert r.word_accuracy == 1.0
    assert math.isnan(r.cohen_kappa)


#: Every document that quotes the paper's annotator figures ("96.05 % and 89.24 % ... 98.15 % and 98.56 %").
QUOTING_THE_PAPER = ("drywall_lab/annotation.py", "annotation_guidelines/README.md",
                     "annotation_guidelines/practice/README.md", "notebooks/01_annotation.ipynb")


def percentages(text: str) -> list[str]:
    """Every two-decimal percentage in a text, in order: '96.05 %' and '96.05%' both give '96.05'."""
    return re.findall(r"(\d{1,3}\.\d{2}) ?%", text)


@pytest.mark.parametrize("path", QUOTING_THE_PAPER)
def test_documents_quote_the_papers_annotator_figures(path: str) -> None:
    """The constant and every text that quotes the paper give the same four figures, round 1 then round 2."""
    expected = [f"{100 * v:.2f}" for rnd in ("round 1", "round 2") for v in PAPER_ANNOTATOR_ACCURACY[rnd]]
    found = percentages((REPO / path).read_text(encoding="utf-8"))
    runs = [found[i : i + len(expected)] for i in range(len(found))]
    assert expected in runs, f"{path} quotes {found}, not the paper's {expected} in that order"


def test_practice_student_sits_between_the_papers_rounds() -> None:
    """What the practice README says of the student's answer is what scoring it gives, against the paper's rounds."""
    practice = REPO / "annotation_guidelines" / "practice"
    gold, answer = (from_conll(practice / name) for name in ("practice_key.conll", "student_answer.conll"))
    r = score_annotator([row["tags"] for row in gold], [row["tags"] for row in answer])
    readme = " ".join((practice / "README.md").read_text(encoding="utf-8").split())
    assert f"{100 * r.word_accuracy:.2f} % word accuracy" in readme
    assert f"Cohen's kappa {r.cohen_kappa:.3f}" in readme
    assert f"over {r.n_words} words" in readme
    assert max(PAPER_ANNOTATOR_ACCURACY["round 1"]) < r.word_accuracy < min(PAPER_ANNOTATOR_ACCURACY["round 2"])
    assert "above both of the paper's first-round annotators" in readme and "below both of them after feedback" in readme


# --- bad input ---------------------------------------------------------------------------


def test_different_number_of_instructions() -> None:
    with pytest.raises(ValueError, match="instruction 2"):
        score_annotator(GOLD + [["O"]], ANNOTATED)


def test_different_number_of_words_names_the_instruction() -> None:
    with pytest.raises(ValueError, match=r"instruction 1\b.*5 words.*4"):
        score_annotator(GOLD, [ANNOTATED[0], ANNOTATED[1][:4]])


def test_unknown_tag_names_the_place() -> None:
    with pytest.raises(ValueError, match=r"instruction 1, word 3: unknown annotated tag 'B-dim'"):
        score_annotator(GOLD, [ANNOTATED[0], ["O", "St_loc1", "O", "B-dim", "O"]])
    with pytest.raises(ValueError, match=r"instruction 0, word 0: unknown gold tag 'Trg'"):
        score_annotator([["Trg"]], [["O"]])


def test_a_string_is_not_an_instruction() -> None:
    with pytest.raises(TypeError, match="instruction 0"):
        score_annotator(["O"], ["O"])


def test_nothing_to_score() -> None:
    with pytest.raises(ValueError, match="no words"):
        score_annotator([], [])


# --- properties ---------------------------------------------------------------------------

tag = st.sampled_from(TAGS)


@st.composite
def paired_taggings(draw: st.DrawFn, equal_length: bool = False) -> tuple[list[list[str]], list[list[str]]]:
    """A gold tagging and an annotation of the same shape."""
    n = draw(st.integers(1, 6))
    if equal_length:
        lengths = [draw(st.integers(1, 8))] * n
    else:
        lengths = draw(st.lists(st.integers(1, 8), min_size=n, max_size=n))
    gold = [draw(st.lists(tag, min_size=k, max_size=k)) for k in lengths]
    # copy gold, changing some words, so that agreement is neither always perfect nor always poor
    annotated = [[draw(tag) if draw(st.booleans()) else g for g in tags] for tags in gold]
    return gold, annotated


@settings(max_examples=200, deadline=None)
@given(paired_taggings())
def test_properties(pair: tuple[list[list[str]], list[list[str]]]) -> None:
    gold, annotated = pair
    r = score_annotator(gold, annotated)
    assert 0.0 <= r.word_accuracy <= 1.0
    assert 0.0 <= r.instruction_accuracy <= 1.0
    assert r.confusion.to_numpy().sum() == r.n_words == sum(map(len, gold))
    assert np.trace(r.confusion.to_numpy()) == r.per_tag["correct"].sum()
    assert r.word_accuracy == pytest.approx(r.per_tag["correct"].sum() / r.n_words)
    assert (r.per_tag["gold"] == r.confusion.sum(axis=1)).all()
    assert (r.per_tag["annotated"] == r.confusion.sum(axis=0)).all()
    assert len(r.disagreements) == r.n_words - r.per_tag["correct"].sum()
    # every imperfect instruction holds at least one wrong word
    assert (1 - r.instruction_accuracy) * r.n_instructions <= len(r.disagreements) + 1e-9
    assert (r.word_accuracy == 1.0) == (r.instruction_accuracy == 1.0)
    assert math.isnan(r.cohen_kappa) or -1.0 - 1e-9 <= r.cohen_kappa <= 1.0 + 1e-9
    for i, j, g, a in r.disagreements:
        assert gold[i][j] == g != a == annotated[i][j]


@settings(max_examples=200, deadline=None)
@given(paired_taggings(equal_length=True))
def test_equal_lengths_instruction_accuracy_at_most_word_accuracy(
    pair: tuple[list[list[str]], list[list[str]]],
) -> None:
    r = score_annotator(*pair)
    assert r.instruction_accuracy <= r.word_accuracy + 1e-12
