"""How well a tagger did: the paper's Table 3 and Table 4 figures.

All functions are pure and take tag lists, one list per instruction, gold first:

- ``count_word_errors`` is the paper's :math:`N_w`, the number of wrongly tagged words;
- ``count_instruction_errors`` is :math:`N_l`, the number of instructions with at least
  one wrong word;
- ``acc_word`` = (words - N_w) / words and ``acc_inst`` = (instructions - N_l) /
  instructions, as defined under Table 3 (the paper: ``Acc_word = (3895 - N_w) / 3895``
  and ``Acc_inst = (158 - N_l) / 158`` on its validation split);
- ``tag_error_table`` is Table 4 for one model: per gold tag the number of words, how
  many were tagged wrongly and the error rate; ``confusion_pairs`` says what they were
  tagged instead (the paper's Fig. 14: ``most left`` Dw_loc1 -> St_loc1, ...).

>>> gold = [["O", "ID_wall", "O", "ID_stud"], ["O", "Vr_md", "Vr_md"]]
>>> predicted = [["O", "ID_wall", "O", "ID_stud"], ["O", "Dw_loc1", "Vr_md"]]
>>> count_word_errors(gold, predicted), count_instruction_errors(gold, predicted)
(1, 1)
>>> round(acc_word(gold, predicted), 4), acc_inst(gold, predicted)
(0.8571, 0.5)
"""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np
import pandas as pd
from sklearn.metrics import accuracy_score, confusion_matrix

from drywall_lab.corpus.tags import TAGS

TagLists = Sequence[Sequence[str]]


@dataclass(frozen=True)
class TaggingScores:
    """The paper's Table 3 row for one model on one split."""

    n_instructions: int
    n_words: int
    n_word_errors: int  #: N_w
    n_instruction_errors: int  #: N_l
    acc_word: float
    acc_inst: float


def _check_same_shape(gold: TagLists, predicted: TagLists) -> None:
    """Raise ValueError naming the first instruction where the two do not line up."""
    if len(gold) != len(predicted):
        raise ValueError(f"gold has {len(gold)} instructions but the prediction has {len(predicted)}")
    for i, (g, p) in enumerate(zip(gold, predicted)):
        if isinstance(g, str) or isinstance(p, str):
            raise TypeError(f"instruction {i}: expected a list of tags, got a single string")
        if len(g) != len(p):
            raise ValueError(f"instruction {i}: gold has {len(g)} words but the prediction has {len(p)}")


def _flatten(gold: TagLists, predicted: TagLists) -> tuple[list[str], list[str]]:
    _check_same_shape(gold, predicted)
    gold_words = [t for tags in gold for t in tags]
    predicted_words = [t for tags in predicted for t in tags]
    if not gold_words:
        raise ValueError("there are no words to score")
    return gold_words, predicted_words


def count_word_errors(gold: TagLists, predicted: TagLists) -> int:
    """N_w: the number of words whose predicted tag differs from gold (Table 3, note a)."""
    _check_same_shape(gold, predicted)
    return sum(g != p for g_tags, p_tags in zip(gold, predicted) for g, p in zip(g_tags, p_tags))


def count_instruction_errors(gold: TagLists, predicted: TagLists) -> int:
    """N_l: the number of instructions with at least one wrongly tagged word (Table 3, note c)."""
    _check_same_shape(gold, predicted)
    return sum(list(g) != list(p) for g, p in zip(gold, predicted))


def acc_word(gold: TagLists, predicted: TagLists) -> float:
    """Word-level accuracy: the share of all words tagged as in gold (Table 3, note b)."""
    gold_words, predicted_words = _flatten(gold, predicted)
    return float(accuracy_score(gold_words, predicted_words))


def acc_inst(gold: TagLists, predicted: TagLists) -> float:
    """Instruction-level accuracy: the share of instructions with every word right (Table 3, note d)."""
    _flatten(gold, predicted)  # same checks as acc_word, and no instructions is an error
    return 1.0 - count_instruction_errors(gold, predicted) / len(gold)


def score_tagging(gold: TagLists, predicted: TagLists) -> TaggingScores:
    """Everything of Table 3 at once: counts, N_w, N_l, Acc_word and Acc_inst."""
    gold_words, _ = _flatten(gold, predicted)
    n_w = count_word_errors(gold, predicted)
    n_l = count_instruction_errors(gold, predicted)
    return TaggingScores(
        n_instructions=len(gold),
        n_words=len(gold_words),
        n_word_errors=n_w,
        n_instruction_errors=n_l,
        acc_word=1.0 - n_w / len(gold_words),
        acc_inst=1.0 - n_l / len(gold),
    )


def tag_error_table(gold: TagLists, predicted: TagLists, labels: Sequence[str] = TAGS) -> pd.DataFrame:
    """The paper's Table 4 for one model: per gold tag, words, errors and error rate.

    Rows follow ``labels`` (tags that are in the data but not in ``labels`` are added at
    the end); columns ``words`` (gold words with that tag), ``errors`` (of those, how many
    got another tag) and ``error_rate`` (errors / words; NaN for a tag with no words).
    A last row ``ALL`` sums the words and errors.
    """
    gold_words, predicted_words = _flatten(gold, predicted)
    names = list(dict.fromkeys([*labels, *sorted(set(gold_words) | set(predicted_words))]))
    matrix = confusion_matrix(gold_words, predicted_words, labels=names)
    words = matrix.sum(axis=1)
    errors = words - np.diag(matrix)
    table = pd.DataFrame({"words": words, "errors": errors}, index=pd.Index(names, name="tag"))
    table.loc["ALL"] = [int(words.sum()), int(errors.sum())]
    table = table.astype(int)
    table["error_rate"] = table["errors"] / table["words"].replace(0, np.nan)
    return table


def confusion_pairs(gold: TagLists, predicted: TagLists) -> pd.DataFrame:
    """Every (gold tag, predicted tag) mix-up with its count, most frequent first.

    Columns ``gold``, ``predicted``, ``count``; empty when every word is right.
    """
    gold_words, predicted_words = _flatten(gold, predicted)
    pairs = Counter((g, p) for g, p in zip(gold_words, predicted_words) if g != p)
    rows = [{"gold": g, "predicted": p, "count": n} for (g, p), n in pairs.most_common()]
    return pd.DataFrame(rows, columns=["gold", "predicted", "count"])


def instruction_errors(gold: TagLists, predicted: TagLists) -> list[tuple[int, int, str, str]]:
    """Every wrongly tagged word as (instruction index, word index, gold tag, predicted tag)."""
    _check_same_shape(gold, predicted)
    return [
        (i, j, g, p)
        for i, (g_tags, p_tags) in enumerate(zip(gold, predicted))
        for j, (g, p) in enumerate(zip(g_tags, p_tags))
        if g != p
    ]


def error_examples(rows: Sequence[Mapping], predicted: TagLists, tag_field: str = "tags") -> pd.DataFrame:
    """The instructions a tagger got wrong, one row each, most wrong words first (the paper's Fig. 14).

    Columns ``index`` (position in ``rows``), ``id``, ``n_errors`` and ``mistakes``, e.g.
    ``"middle: Dw_loc1 -> Vr_md"`` (word: gold -> predicted, ``;``-separated); empty when
    every instruction is right. Ties keep the order of ``rows``.
    """
    gold = [list(row[tag_field]) for row in rows]
    by_instruction: dict[int, list[str]] = {}
    for i, j, g, p in instruction_errors(gold, predicted):
        by_instruction.setdefault(i, []).append(f"{rows[i]['words'][j]}: {g} -> {p}")
    records = [
        {"index": i, "id": rows[i].get("id", str(i)), "n_errors": len(m), "mistakes": "; ".join(m)}
        for i, m in by_instruction.items()
    ]
    table = pd.DataFrame(records, columns=["index", "id", "n_errors", "mistakes"])
    return table.sort_values("n_errors", ascending=False, kind="stable").reset_index(drop=True)
