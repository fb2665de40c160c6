"""Scoring an annotator against the gold tags.

The paper checked its annotation guidelines by having two more people tag the
test split and comparing their tags with the first author's: in round one they
reached 96.05% and 89.24% accuracy, and after feedback 98.15% and 98.56% in round
two. The paper does not say what it counted; here, as in most tagging work, it
is read as word accuracy: the share of words given the gold tag.

``score_annotator`` computes that number and the ones that help explain it: how
many instructions came out entirely right, Cohen's kappa (agreement corrected for
chance, which matters when most words are ``O``), the confusion matrix, per-tag
recall and precision, and the list of every disagreement.

>>> gold = [["O", "ID_wall", "O", "ID_stud"], ["O", "St_loc1", "O"]]
>>> annotated = [["O", "ID_wall", "O", "ID_stud"], ["O", "O", "O"]]
>>> report = score_annotator(gold, annotated)
>>> round(report.word_accuracy, 4), report.instruction_accuracy
(0.8571, 0.5)
>>> report.disagreements
[(1, 1, 'St_loc1', 'O')]
"""
from __future__ import annotations

import warnings
from collections import Counter
from dataclasses import dataclass
from typing import Sequence

import numpy as np
import pandas as pd
from sklearn.exceptions import UndefinedMetricWarning
from sklearn.metrics import cohen_kappa_score, confusion_matrix

from drywall_lab.corpus.tags import TAGS

#: The paper's word accuracies of its two annotators, by round.
PAPER_ANNOTATOR_ACCURACY: dict[str, tuple[float, float]] = {
    "round 1": (0.9605, 0.8924),
    "round 2": (0.9815, 0.9856),
}

#: One disagreement: (instruction index, word index, gold tag, annotated tag).
Disagreement = tuple[int, int, str, str]


@dataclass
class AgreementReport:
    """How well one annotator's tags agree with the gold tags."""

    n_instructions: int
    n_words: int
    word_accuracy: float  #: share of words tagged as in gold
    instruction_accuracy: float  #: share of instructions with every word right
    cohen_kappa: float  #: chance-corrected agreement over all words; NaN when undefined
    confusion: pd.DataFrame  #: word counts, gold tags as rows, annotated tags as columns
    per_tag: pd.DataFrame  #: per tag: gold, annotated, correct, recall, precision
    disagreements: list[Disagreement]

    def summary(self) -> str:
        """A few lines in the spirit of the paper's sentence on its annotators."""
        lines = [
            f"{self.n_instructions} instructions, {self.n_words} words",
            f"word accuracy {self.word_accuracy:.2%}, "
            f"instruction accuracy {self.instruction_accuracy:.2%}, "
            f"Cohen's kappa {self.cohen_kappa:.4f}",
        ]
        if self.disagreements:
            pairs = Counter((gold, annotated) for _, _, gold, annotated in self.disagreements)
            common = ", ".join(f"{g} -> {a} ({n})" for (g, a), n in pairs.most_common(3))
            lines.append(f"{len(self.disagreements)} words disagree; most often (gold -> annotated): {common}")
        else:
            lines.append("no disagreements")
        return "\n".join(lines)


def score_annotator(
    gold: Sequence[Sequence[str]],
    annotated: Sequence[Sequence[str]],
    labels: Sequence[str] = TAGS,
) -> AgreementReport:
    """Compare ``annotated`` with ``gold``: one tag list per instruction, in the same order.

    Raises ``ValueError`` naming the instruction when the two disagree on the number
    of instructions or of words, or when a tag is not one of ``labels``.
    """
    labels = list(labels)
    if not labels or len(set(labels)) != len(labels):
        raise ValueError(f"labels must be a non-empty list without repeats, got {labels!r}")
    _check_shapes(gold, annotated)
    _check_tags(gold, "gold", labels)
    _check_tags(annotated, "annotated", labels)

    gold_words = [tag for tags in gold for tag in tags]
    annotated_words = [tag for tags in annotated for tag in tags]
    if not gold_words:
        raise ValueError("there are no words to score")

    disagreements = [
        (i, j, g, a)
        for i, (gold_tags, annotated_tags) in enumerate(zip(gold, annotated))
        for j, (g, a) in enumerate(zip(gold_tags, annotated_tags))
        if g != a
    ]
    wrong_instructions = {i for i, _, _, _ in disagreements}

    matrix = confusion_matrix(gold_words, annotated_words, labels=labels)
    confusion = pd.DataFrame(
        matrix,
        index=pd.Index(labels, name="gold"),
        columns=pd.Index(labels, name="annotated"),
    )
    return AgreementReport(
        n_instructions=len(gold),
        n_words=len(gold_words),
        word_accuracy=1 - len(disagreements) / len(gold_words),
        instruction_accuracy=1 - len(wrong_instructions) / len(gold),
        cohen_kappa=_kappa(gold_words, annotated_words, labels),
        confusion=confusion,
        per_tag=_per_tag(confusion),
        disagreements=disagreements,
    )


def _check_shapes(gold: Sequence[Sequence[str]], annotated: Sequence[Sequence[str]]) -> None:
    if len(gold) != len(annotated):
        raise ValueError(
            f"gold has {len(gold)} instructions but the annotation has {len(annotated)}; "
            f"instruction {min(len(gold), len(annotated))} is the first without a partner"
        )
    for i, (gold_tags, annotated_tags) in enumerate(zip(gold, annotated)):
        if isinstance(gold_tags, str) or isinstance(annotated_tags, str):
            raise TypeError(f"instruction {i}: expected a list of tags, got a single string")
        if len(gold_tags) != len(annotated_tags):
            raise ValueError(
                f"instruction {i}: gold has {len(gold_tags)} words but the annotation has {len(annotated_tags)}"
            )


def _check_tags(instructions: Sequence[Sequence[str]], side: str, labels: list[str]) -> None:
    known = set(labels)
    for i, tags in enumerate(instructions):
        for j, tag in enumerate(tags):
            if tag not in known:
                raise ValueError(f"instruction {i}, word {j}: unknown {side} tag {tag!r}")


def _kappa(gold_words: list[str], annotated_words: list[str], labels: list[str]) -> float:
    """Cohen's kappa; NaN when chance agreement is already 1 (both use one and the same tag)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UndefinedMetricWarning)
        return float(cohen_kappa_score(gold_words, annotated_words, labels=labels))


def _per_tag(confusion: pd.DataFrame) -> pd.DataFrame:
    """Counts, recall and precision per tag, read off the confusion matrix."""
    gold = confusion.sum(axis=1)
    annotated = confusion.sum(axis=0)
    correct = pd.Series(np.diag(confusion.to_numpy()), index=confusion.index)
    table = pd.DataFrame({"gold": gold, "annotated": annotated, "correct": correct})
    table["recall"] = table["correct"] / table["gold"].replace(0, np.nan)
    table["precision"] = table["correct"] / table["annotated"].replace(0, np.nan)
    table.index.name = "tag"
    return table
