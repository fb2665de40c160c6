"""Every named set of instructions the taggers are trained and evaluated on, in one place.

- the paper corpus (``data/corpus``, the paper's study): ``train``, ``validation``, ``test``, ``novel``;
- the field corpus (``data/field_corpus``, site language, issue 11): ``field-train``, ``field-validation``,
  ``field-test``, ``field-novel`` (held-back families);
- the hand-written field set (``data/field``, evaluation only): ``field-set``.

Every set's rows have ``words``, ``tags``, ``context.history`` and ``expected``, so ``acc_task`` (the IM
rules' outcome against the intended one) is computed the same way on all of them.
"""
from __future__ import annotations

PAPER_SPLITS = ("train", "validation", "test", "novel")
FIELD_CORPUS_SPLITS = ("field-train", "field-validation", "field-test", "field-novel")
FIELD_SET = "field-set"
ALL_SPLITS = PAPER_SPLITS + FIELD_CORPUS_SPLITS + (FIELD_SET,)
#: What ``evaluate`` accepts: every set but the training splits.
EVALUATION_SPLITS = ("validation", "test", "novel", "field-validation", "field-test", "field-novel", FIELD_SET)
#: The training corpora: (training splits, validation split). The field corpus trains on its own training
#: split and the paper corpus's, the latter twice: beside 20,000 field instructions in fifteen registers, the
#: paper's 1,268 formal phrasings keep enough weight that its test split stays at the paper's level (issue 11).
CORPORA = {"paper": (("train",), "validation"), "field": (("field-train", "train", "train"), "field-validation")}


def split_rows(name: str) -> list[dict]:
    """The rows of a named set (see the module docstring); a ``ValueError`` naming the sets for an unknown one."""
    if name in PAPER_SPLITS:
        from drywall_lab.corpus import read_split

        return read_split(name)
    if name in FIELD_CORPUS_SPLITS:
        from drywall_lab.corpus.field_generator import field_split

        return field_split(name.removeprefix("field-"))
    if name == FIELD_SET:
        from drywall_lab.field import field_set_rows

        return field_set_rows()
    raise ValueError(f"unknown split {name!r}; the sets are {', '.join(ALL_SPLITS)}")


def training_rows(corpus: str) -> list[dict]:
    """The training instructions of a corpus (``CORPORA``): every one of its training splits, in order."""
    if corpus not in CORPORA:
        raise ValueError(f"unknown corpus {corpus!r}; the corpora are {', '.join(CORPORA)}")
    return [row for split in CORPORA[corpus][0] for row in split_rows(split)]
