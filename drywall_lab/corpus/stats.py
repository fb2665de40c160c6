"""Corpus statistics side by side with the paper's Table 2 and its sentence-count groups."""
from __future__ import annotations

from collections import Counter
from typing import Iterable, Mapping

import pandas as pd

from drywall_lab.corpus.tags import (
    PAPER_N_INSTRUCTIONS,
    PAPER_N_SENTENCES,
    PAPER_N_WORDS,
    PAPER_TAG_COUNTS,
    PAPER_TEST_SENTENCE_GROUPS,
    TAGS,
)

#: The bounds the project holds its corpus to (issue "Foundation"): relative tolerance on
#: each tag's share for tags above 1 % in the paper, and absolute tolerances on the means.
SHARE_TOLERANCE = 0.20
WORDS_TOLERANCE = 3.0
SENTENCES_TOLERANCE = 0.2

Rows = Iterable[Mapping]


def _rows(corpus: Mapping[str, Rows] | Rows, splits: Iterable[str] = ("train", "validation", "test")) -> list[Mapping]:
    if isinstance(corpus, Mapping):
        return [r for s in splits if s in corpus for r in corpus[s]]
    return list(corpus)


def tag_table(corpus: Mapping[str, Rows] | Rows, splits: Iterable[str] = ("train", "validation", "test")) -> pd.DataFrame:
    """Words per tag and share of words, ours against the paper's Table 2."""
    rows = _rows(corpus, splits)
    counts = Counter(t for r in rows for t in r["tags"])
    n_words = sum(counts.values())
    table = pd.DataFrame(
        {
            "words": [counts.get(t, 0) for t in TAGS],
            "share_%": [100 * counts.get(t, 0) / n_words for t in TAGS],
            "paper_words": [PAPER_TAG_COUNTS[t] for t in TAGS],
            "paper_share_%": [100 * PAPER_TAG_COUNTS[t] / PAPER_N_WORDS for t in TAGS],
        },
        index=pd.Index(TAGS, name="tag"),
    )
    table["ratio"] = table["share_%"] / table["paper_share_%"]
    table["checked"] = table["paper_share_%"] > 1.0
    table["within_20%"] = (table["ratio"] - 1).abs() <= SHARE_TOLERANCE
    return table.round(3)


def summary_table(corpus: Mapping[str, Rows], splits: Iterable[str] = ("train", "validation", "test")) -> pd.DataFrame:
    """Instructions, words, sentences and their means, ours against the paper's."""
    rows = _rows(corpus, splits)
    n = len(rows)
    n_words = sum(len(r["words"]) for r in rows)
    n_sent = sum(r["n_sentences"] for r in rows)
    return pd.DataFrame(
        {
            "ours": [n, n_words, n_sent, n_words / n, n_sent / n],
            "paper": [PAPER_N_INSTRUCTIONS, PAPER_N_WORDS, PAPER_N_SENTENCES,
                      PAPER_N_WORDS / PAPER_N_INSTRUCTIONS, PAPER_N_SENTENCES / PAPER_N_INSTRUCTIONS],
        },
        index=["instructions", "words", "sentences", "words per instruction", "sentences per instruction"],
    ).round(3)


def sentence_groups(rows: Rows) -> pd.DataFrame:
    """Instructions per sentence count in one split, against the paper's test split (46/74/27/11)."""
    counts = Counter(r["n_sentences"] for r in rows)
    return pd.DataFrame(
        {"ours": [counts.get(k, 0) for k in PAPER_TEST_SENTENCE_GROUPS],
         "paper_test": list(PAPER_TEST_SENTENCE_GROUPS.values())},
        index=pd.Index(list(PAPER_TEST_SENTENCE_GROUPS), name="sentences"),
    )


def check_against_paper(corpus: Mapping[str, Rows]) -> list[str]:
    """What falls outside the project's bounds; an empty list when the corpus agrees with the paper."""
    problems = []
    summary = summary_table(corpus)
    words = summary.loc["words per instruction"]
    if abs(words["ours"] - words["paper"]) > WORDS_TOLERANCE:
        problems.append(f"words per instruction {words['ours']:.2f}, paper {words['paper']:.2f}")
    sent = summary.loc["sentences per instruction"]
    if abs(sent["ours"] - sent["paper"]) > SENTENCES_TOLERANCE:
        problems.append(f"sentences per instruction {sent['ours']:.3f}, paper {sent['paper']:.3f}")
    tags = tag_table(corpus)
    for tag, row in tags[tags["checked"] & ~tags["within_20%"]].iterrows():
        problems.append(f"{tag}: {row['share_%']:.2f}% of words, paper {row['paper_share_%']:.2f}%")
    return problems


def print_comparison(corpus: Mapping[str, Rows]) -> None:
    """Print the corpus statistics side by side with the paper's figures."""
    with pd.option_context("display.width", 120):
        print("Corpus (train + validation + test) against the paper's 1,584 instructions")
        print(summary_table(corpus).to_string())
        print("\nWords per tag (Table 2)")
        print(tag_table(corpus).to_string())
        if "test" in corpus:
            print("\nTest split by number of sentences")
            print(sentence_groups(corpus["test"]).to_string())
        problems = check_against_paper(corpus)
        print("\n" + ("All figures within the project's bounds." if not problems else "Outside bounds:\n  " + "\n  ".join(problems)))


def find_examples(rows: Rows, word: str, tag: str | None = None, n: int = 1) -> list[Mapping]:
    """The first ``n`` instructions where ``word`` (any case) carries ``tag`` (any tag if None)."""
    found = []
    for row in rows:
        if any(w.lower() == word.lower() and (tag is None or t == tag) for w, t in zip(row["words"], row["tags"])):
            found.append(row)
            if len(found) == n:
                break
    return found


def tags_of_word(rows: Rows, word: str) -> pd.Series:
    """How often each tag is given to ``word`` (any case): the confusions the paper reports."""
    counts = Counter(t for r in rows for w, t in zip(r["words"], r["tags"]) if w.lower() == word.lower())
    return pd.Series(counts, name=word, dtype=int).sort_values(ascending=False)
