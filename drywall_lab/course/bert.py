"""Notebook 03 (BERT): word tags to sub-word token labels (the from-scratch exercise) and the paper's Fig. 8(b)
redrawn, the sub-word vote and its exercise, and a fine-tuned encoder's view of its tokens."""
from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy as np
import pandas as pd

from drywall_lab.corpus.tags import TAGS
from drywall_lab.course.common import solution_file
from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from drywall_lab.nlu.base import Tagger
    from drywall_lab.nlu.bert import BertTagger

#: Notebook 03's worked example (section 1), tagged by the annotation guidelines: ``full-size`` is the panel's
#: size (``dim``), ``500107`` the destination stud's id (``ID_stud``); the corpus tags ``horizontally`` ``O``.
WORKED_WORDS: tuple[str, ...] = ("Put", "the", "full-size", "sheetrock", "on", "stud", "500107", "horizontally")
WORKED_TAGS: tuple[str, ...] = ("O", "O", "dim", "O", "O", "O", "ID_stud", "O")
#: The label of a token the loss ignores (PyTorch's ``CrossEntropyLoss`` ``ignore_index``): the special tokens.
IGNORED_LABEL = -100


# --- word tags to token labels (the from-scratch exercise) ------------------------------------------------------
@lru_cache(maxsize=1)
def _alignment_tagger() -> "BertTagger":
    """An untrained ``BertTagger`` holding only the default encoder's tokenizer: what its own encoding (the
    training path, section "BERT") needs to turn word tags into token labels. Loads no model."""
    from transformers import AutoTokenizer

    from drywall_lab.nlu.bert import BertTagger, default_encoder_path

    tagger = BertTagger()
    tagger.tokenizer = AutoTokenizer.from_pretrained(default_encoder_path(), local_files_only=True)
    return tagger


def library_alignment(words: Sequence[str], tags: Sequence[str]) -> tuple[list[str], list[int | None], list[int]]:
    """One tagged instruction as ``BertTagger`` trains on it: its sub-word tokens, their word ids (``None`` for
    ``[CLS]``/``[SEP]``) and their label ids (a word's tag's index in the tagger's labels, given to every
    sub-word of the word; ``IGNORED_LABEL`` for the special tokens). The library's own encoding, not a copy."""
    tagger = _alignment_tagger()
    encoded = tagger._encode(list(words), [tagger.labels.index(t) for t in tags])
    tokens = tagger.tokenizer.convert_ids_to_tokens(encoded["features"]["input_ids"])
    return list(tokens), list(encoded["word_ids"]), list(encoded["features"]["labels"])


def alignment_table(words: Sequence[str], tags: Sequence[str]) -> pd.DataFrame:
    """``library_alignment`` as a table, a row per token: the token, its word id, its word and the word's tag,
    and the label id the token is trained on (the paper's Fig. 4: one label per token)."""
    tokens, word_ids, labels = library_alignment(words, tags)
    return pd.DataFrame({"token": tokens, "word id": word_ids,
                         "word": [None if w is None else words[w] for w in word_ids],
                         "word tag": [None if w is None else tags[w] for w in word_ids],
                         "label id": labels}, dtype=object)


def alignment_cases(n_validation: int = 30, n_novel: int = 10) -> list[tuple[str, list[str], list[str]]]:
    """Cases for ``align_labels``: (what it tests, words, word tags); the worked example first, then the edge
    cases, then real instructions of the corpus (the first of the validation and the novel split)."""
    from drywall_lab import corpus

    cases: list[tuple[str, list[str], list[str]]] = [
        ("the worked example", list(WORKED_WORDS), list(WORKED_TAGS)),
        ("a word split in three pieces (500107: 500 ##10 ##7)", ["500107"], ["ID_stud"]),
        ("no words at all: only the special tokens [CLS] and [SEP]", [], []),
        ("a word the tokenizer turns into no token (a zero-width space): its word id never appears",
         ["stud", "\u200b", "500107"], ["O", "O", "St_loc2"]),
    ]
    rows = corpus.read_corpus()
    for split, n in (("validation", n_validation), ("novel", n_novel)):
        cases += [(f"{split} instruction {r['id']}", list(r["words"]), list(r["tags"])) for r in rows[split][:n]]
    return cases


def _first_sub_word_only(word_ids: Sequence[int | None], word_labels: Sequence[int]) -> list[int]:
    """The other common convention (a slip here): only a word's first sub-word labelled, the rest ignored."""
    return [IGNORED_LABEL if w is None or (k > 0 and word_ids[k - 1] == w) else word_labels[w]
            for k, w in enumerate(word_ids)]


def _alignment_slip(tokens: Sequence[str], word_ids: Sequence[int | None], word_labels: Sequence[int],
                    words: Sequence[str], got: list[Any], want: list[int]) -> str:
    """What is wrong with ``got`` where it first differs from ``want``, naming the known slips."""
    k = next(i for i, (g, w) in enumerate(zip(got, want)) if g != w)
    word = word_ids[k]
    token = f"token {k} {tokens[k]!r}"
    if word is None:
        return (f"{token} is a special token (word id None): it gets {IGNORED_LABEL}, which the loss ignores, "
                f"not {got[k]!r}")
    about = f"{token} belongs to word {word} {words[word]!r}, whose label id is {word_labels[word]}"
    if got == _first_sub_word_only(word_ids, word_labels):
        return (f"{about}, and you gave it {got[k]!r}: you labelled only the first sub-word of each word. "
                "BertTagger trains every sub-word token on its word's label (the paper's vote reads all of a "
                f"word's tokens when it predicts); {IGNORED_LABEL} is for the special tokens only")
    if got[k] == IGNORED_LABEL:
        return f"{about}, not {IGNORED_LABEL}: only the special tokens (word id None) are ignored"
    if isinstance(got[k], str):
        return f"{about}: return label ids (the numbers in word_labels), not tags such as {got[k]!r}"
    neighbours = [v for v in (word - 1, word + 1) if 0 <= v < len(word_labels) and word_labels[v] == got[k]]
    if neighbours or (0 <= k - 1 < len(word_labels) and word_labels[k - 1] == got[k]):
        return (f"{about}; yours gave {got[k]!r}, the label of a neighbouring word: shifted by one. The token's "
                "word is word_ids[k] itself (no +1 or -1 for [CLS]), and its position among the tokens is not "
                "its word's index")
    return f"{about}; yours gave {got[k]!r}"


def check_align_labels(align_labels: Callable[[list[int | None], list[int]], Sequence[int]]) -> ExerciseCheck:
    """Notebook 03's from-scratch exercise: ``align_labels(word_ids, word_labels)``, one label id per token, against
    the library's own alignment (``BertTagger``'s encoding for training, through ``library_alignment``) with the
    real tokenizer, on the worked example, edge cases (a word in three pieces, only special tokens, a word with no
    token) and corpus instructions. Known slips are named: labelling only the first sub-word, giving the special
    tokens a label, a shift by one word. The notebook's stub is "not attempted yet"."""
    cases = [(what, words, tags, *library_alignment(words, tags)) for what, words, tags in alignment_cases()]
    labels = _alignment_tagger().labels
    _, _, first_tags, _, first_ids, _ = cases[0]
    if is_unattempted(align_labels, list(first_ids), [labels.index(t) for t in first_tags], none=True):
        return ExerciseCheck.not_attempted("align_labels(word_ids, word_labels): one label id per token, from its "
                                           "word's label id", solution_file(3))
    for what, words, tags, tokens, word_ids, want in cases:
        word_labels = [labels.index(t) for t in tags]
        got, error = call_student(align_labels, list(word_ids), list(word_labels))
        shown = f"{what}: tokens {tokens}, word ids {word_ids}, word labels {word_labels}"
        if error:
            hint = [f"the special tokens' word id is None: give them {IGNORED_LABEL} before looking a word up"] \
                if "NoneType" in error else []
            return ExerciseCheck(False, [shown, f"your function raised {error}", *hint])
        got = got.tolist() if hasattr(got, "tolist") else got
        got = list(got) if isinstance(got, (list, tuple)) else got
        if got == want:
            continue
        messages = [shown, f"the library's alignment gives {want}, your function {got}"]
        if not isinstance(got, list) or len(got) != len(want):
            per_word = " (one per word: the model needs one per token)" if isinstance(got, list) and \
                len(got) == len(words) else ""
            messages.append(f"return a list of one label id per token: {len(want)} here, the special tokens "
                            f"included{per_word}")
        else:
            messages.append(_alignment_slip(tokens, word_ids, word_labels, words, got, want))
        return ExerciseCheck(False, messages)
    return ExerciseCheck(True, [f"all {len(cases)} cases agree with BertTagger's own alignment: every sub-word token "
                                f"of a word gets the word's label id, the special tokens {IGNORED_LABEL}"])


# --- the paper's Fig. 8(b) ----------------------------------------------------------------------------------------
@lru_cache(maxsize=1)
def encoder_size() -> tuple[int, int]:
    """(transformer layers, hidden units) of the default encoder, read from its configuration."""
    from transformers import AutoConfig

    from drywall_lab.nlu.bert import default_encoder_path

    config = AutoConfig.from_pretrained(default_encoder_path(), local_files_only=True)
    return int(config.num_hidden_layers), int(config.hidden_size)


def plot_bert_tagger(words: Sequence[str] = WORKED_WORDS, tags: Sequence[str] = WORKED_TAGS,
                     ax: Any = None) -> "Figure":
    """The paper's Fig. 8(b), the BERT tagger, drawn on one instruction's real word pieces: tokens (``[CLS]`` ...
    ``[SEP]``) -> embeddings E (token + position) -> the transformer layers -> one contextual vector T per token
    -> the same linear layer on every token -> a tag per token (the word's tag on each of its sub-words; the
    special tokens' outputs are ignored). The encoder's size is the default encoder's (``encoder_size``)."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import FancyBboxPatch

    tokens, word_ids, _ = library_alignment(words, tags)
    layers, hidden = encoder_size()
    n = len(tokens)
    if ax is None:
        _, ax = plt.subplots(figsize=(max(8.0, 0.95 * n), 5.2))
    rows = {"token": 0.0, "E": 1.2, "T": 3.6, "linear": 4.7, "tag": 5.8}

    def box(x: float, y: float, text: str, colour: str, width: float = 0.8, size: float = 8.5) -> None:
        ax.add_patch(FancyBboxPatch((x - width / 2, y - 0.3), width, 0.6, boxstyle="round,pad=0.02",
                                    facecolor=colour, edgecolor="0.3"))
        ax.text(x, y, text, ha="center", va="center", fontsize=size)

    for i, (token, word) in enumerate(zip(tokens, word_ids)):
        special = word is None
        box(i, rows["token"], token, "0.92" if special else "#fde9c9", size=8.5 if len(token) <= 8 else 6.5)
        box(i, rows["E"], f"E$_{{{i}}}$", "#dbe9f6")
        box(i, rows["T"], f"T$_{{{i}}}$", "#dbe9f6")
        box(i, rows["linear"], "linear", "#e3f1df", size=7.5)
        ax.text(i, rows["tag"], "(ignored)" if special else tags[word], ha="center", va="center", fontsize=8,
                rotation=35, color="0.5" if special else "black", fontweight="normal" if special else "bold")
        for low, high in (("token", "E"), ("T", "linear"), ("linear", "tag")):
            ax.annotate("", (i, rows[high] - 0.32), (i, rows[low] + 0.32), arrowprops={"arrowstyle": "->", "lw": 0.8})
        ax.annotate("", (i, 2.05), (i, rows["E"] + 0.32), arrowprops={"arrowstyle": "->", "lw": 0.8})
        ax.annotate("", (i, rows["T"] - 0.32), (i, 2.75), arrowprops={"arrowstyle": "->", "lw": 0.8})
    ax.add_patch(FancyBboxPatch((-0.45, 2.05), n - 0.1, 0.7, boxstyle="round,pad=0.02", facecolor="#c9dcef",
                                edgecolor="0.3"))
    ax.text((n - 1) / 2, 2.4, f"transformer encoder: {layers} layers of {hidden} units, every token attends to "
            "every other", ha="center", va="center", fontsize=10)
    for name, y in (("tokens", rows["token"]), ("embeddings", rows["E"]), ("contextual\nvectors", rows["T"]),
                    ("token\nclassifier", rows["linear"]), ("tags", rows["tag"])):
        ax.text(-0.75, y, name, ha="right", va="center", fontsize=9, color="0.25")
    ax.set_xlim(-2.2, n - 0.4)
    ax.set_ylim(-0.6, 6.5)
    ax.axis("off")
    ax.set_title("The BERT tagger (the paper's Fig. 8(b)), on one instruction's word pieces", fontsize=11)
    return ax.figure


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

