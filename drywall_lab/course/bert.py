"""Notebook 03 (BERT): the sub-word vote, its exercise, and a fine-tuned encoder's view of its tokens."""
from __future__ import annotations

from typing import TYPE_CHECKING, Callable, Mapping, Sequence

import numpy as np
import pandas as pd

from drywall_lab.corpus.tags import TAGS
from drywall_lab.course.common import solution_file
from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted

if TYPE_CHECKING:
    from drywall_lab.nlu.base import Tagger


def vote_cases(n_random: int = 200, seed: int = 3) -> list[tuple[str, list[str], list[int | None], int]]:
    """Cases for the vote: (what it tests, token tags, word ids, number of words); the hand-made ones first."""
    cases: list[tuple[str, list[str], list[int | None], int]] = [
        ("one token per word", ["O", "O", "ID_stud", "O"], [None, 0, 1, None], 2),
        ("a majority of three tokens", ["O", "ID_stud", "ID_wall", "ID_stud", "O"], [None, 0, 0, 0, None], 1),
        ("a majority that is not the first token", ["ID_wall", "ID_stud", "ID_stud"], [0, 0, 0], 1),
        ("a tie of two tokens (the first decides)", ["Dw_loc1", "Vr_md"], [0, 0], 1),
        ("the same tie the other way round", ["Vr_md", "Dw_loc1"], [0, 0], 1),
        ("three tokens tagged three ways (no majority: the first decides)", ["width", "length", "dim"], [0, 0, 0], 1),
        ("a two-two tie of four tokens", ["St_loc1", "St_loc2", "St_loc2", "St_loc1"], [0, 0, 0, 0], 1),
        ("the most frequent tag without more than half (the first decides)",
         ["O", "Dw_loc1", "Dw_loc1", "St_loc1", "Vr_md"], [0, 0, 0, 0, 0], 1),
        ("exactly half is not more than half", ["Vr_md", "Hr_top", "Hr_top", "Dw_loc1"], [0, 0, 0, 0], 1),
        ("a word with no token gets O", ["width"], [0], 2),
        ("special tokens ([CLS], [SEP], padding) vote for no word", ["Hr_btm", "dim", "Hr_btm", "Hr_btm"],
         [None, 0, None, None], 1),
        ("words in order, each with its own tokens", ["O", "width", "O", "length", "length", "O"],
         [None, 0, 1, 2, 2, None], 3),
    ]
    rng = np.random.default_rng(seed)
    for i in range(n_random):
        n_words = int(rng.integers(1, 6))
        counts = rng.integers(0 if i % 5 == 0 else 1, 5, size=n_words)
        word_ids: list[int | None] = [None] + [w for w in range(n_words) for _ in range(counts[w])] + [None]
        palette = list(rng.choice(TAGS, size=3, replace=False))
        tags = [str(rng.choice(palette)) for _ in word_ids]
        cases.append((f"random case {i + 1}", tags, word_ids, n_words))
    return cases


def _vote_reason(tags: list[str]) -> str:
    """Which part of the rule decides a word with these token tags."""
    if not tags:
        return "it has no token, so it is O"
    best, count = max(((t, tags.count(t)) for t in dict.fromkeys(tags)), key=lambda p: p[1])
    if count * 2 > len(tags):
        return f"{count} of its {len(tags)} tokens say {best}: more than half"
    return f"no tag has more than half of its {len(tags)} tokens, so its first token decides: {tags[0]}"


def check_vote(vote: Callable[[list[str], list[int | None], int], Sequence[str]]) -> ExerciseCheck:
    """Notebook 03's exercise: ``vote(token_tags, word_ids, n_words)`` against ``drywall_lab.nlu.vote_word_tags``
    (the paper's "more than half of the tokens" rule, the first token without a strict majority) on hand-made
    cases (ties, three-way splits, words without tokens, special tokens) and random ones; the first
    disagreement is explained word by word. The notebook's stub (a function that raises ``NotImplementedError``,
    or whose body is still ``...``) is "not attempted yet"."""
    from drywall_lab.nlu.bert import vote_word_tags

    cases = vote_cases()
    _, first_tags, first_ids, first_n = cases[0]
    if is_unattempted(vote, list(first_tags), list(first_ids), first_n, none=True):
        return ExerciseCheck.not_attempted("my_vote(token_tags, word_ids, n_words): one tag per word, voted from "
                                           "its tokens' tags", solution_file(3))
    for what, tags, word_ids, n_words in cases:
        want = vote_word_tags(tags, word_ids, n_words)
        got, error = call_student(vote, list(tags), list(word_ids), n_words)
        if error:
            return ExerciseCheck(False, [f"{what}: your function raised {error} on token tags {tags}, "
                                         f"word ids {word_ids}, n_words {n_words}"])
        got = list(got) if isinstance(got, (list, tuple)) else got
        if got == want:
            continue
        messages = [f"{what}: token tags {tags}, word ids {word_ids}, n_words {n_words}",
                    f"the vote gives {want}, your function {got}"]
        if not isinstance(got, list) or len(got) != n_words:
            messages.append(f"return one tag per word: a list of {n_words}")
        else:
            for w, (g, v) in enumerate(zip(got, want)):
                if g != v:
                    own = [t for t, i in zip(tags, word_ids) if i == w]
                    messages.append(f"word {w} (its tokens say {own}): {_vote_reason(own)}, not {g}")
                    break
        return ExerciseCheck(False, messages)
    return ExerciseCheck(True, [f"all {len(cases)} cases agree with vote_word_tags, ties and words without "
                                "tokens included"])


def token_predictions(tagger: "Tagger", words: Sequence[str]) -> pd.DataFrame:
    """A trained ``BertTagger``'s view of one instruction: each sub-word token, the word it belongs to and the
    tag the model gives it, through the tagger's own prediction path (``predict`` votes these into word tags)."""
    return _token_tables(tagger, [list(words)])[0]


def _token_tables(tagger: "Tagger", sentences: Sequence[Sequence[str]]) -> list[pd.DataFrame]:
    """``token_predictions`` for many instructions, in batches (``BertTagger.predict_tokens``)."""
    return [pd.DataFrame(rows, columns=["token", "word id", "token tag"], dtype=object)
            for rows in tagger.predict_tokens(sentences)]


def vote_statistics(tagger: "Tagger", rows: Sequence[Mapping]) -> dict[str, int]:
    """How often the vote has work to do on ``rows``: words of several tokens, those whose tokens disagree, and
    those with no strict majority (decided by the first token)."""
    counts = {"words of several tokens": 0, "tokens disagree": 0, "no strict majority": 0}
    for table in _token_tables(tagger, [row["words"] for row in rows]):
        for _, tags in table.dropna(subset=["word id"]).groupby("word id")["token tag"]:
            tags = list(tags)
            if len(tags) > 1:
                counts["words of several tokens"] += 1
                if len(set(tags)) > 1:
                    counts["tokens disagree"] += 1
                    counts["no strict majority"] += max(map(tags.count, tags)) * 2 <= len(tags)
    return counts

