"""Notebook 01 (annotation): the corpus's tag shares (Table 2), the tagging exercise by the guidelines, entities
and entity-level scores (the from-scratch exercise) and the annotator's confusion matrix as a heatmap."""
from __future__ import annotations

import re
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

import pandas as pd

from drywall_lab.corpus.tags import TAGS
from drywall_lab.course.common import REPO_ROOT, solution_file
from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted

#: The annotation guidelines and their practice set (notebook 01).
GUIDELINES = REPO_ROOT / "annotation_guidelines" / "README.md"
PRACTICE_DIR = REPO_ROOT / "annotation_guidelines" / "practice"


def tag_share_table(table: pd.DataFrame) -> pd.DataFrame:
    """``corpus.tag_table`` (the paper's Table 2) for reading: what the project's bound says about each tag.

    The bound (within 20 %, relative, of the paper's share) is applied only to tags above 1 % of the paper's
    words; for the rarer ones a few words either way move the ratio a lot, so they are shown, not judged.
    """
    out = table[["words", "share_%", "paper_words", "paper_share_%", "ratio"]].copy()
    out["bound"] = ["within 20 % of the paper's share" if held else "none (under 1 % of the paper's words)"
                    for held in table["checked"]]
    out["verdict"] = ["-" if not held else ("within" if inside else "OUTSIDE")
                      for held, inside in zip(table["checked"], table["within_20%"])]
    return out


#: The practice instruction of notebook 01's tagging exercise (``annotation_guidelines/practice``).
TAGGING_EXERCISE = "P12"
PLACEMENT_TAGS = ("Vr_md", "Hr_top", "Hr_btm")
ANCHOR_TAGS = ("Dw_loc2", "St_loc2")


def guideline_headings(path: Path | str = GUIDELINES) -> list[str]:
    """The guidelines' section headings (``##`` and ``###``), without the hashes."""
    return [line.lstrip("#").strip() for line in Path(path).read_text(encoding="utf-8").splitlines()
            if re.match(r"#{2,3} ", line)]


def _heading(headings: Sequence[str], pattern: str) -> str:
    """The first heading matching ``pattern``; a ``ValueError`` when the guidelines have none."""
    for heading in headings:
        if re.search(pattern, heading):
            return heading
    raise ValueError(f"the annotation guidelines have no section matching {pattern!r}")


def guideline_sections(word: str, gold: str, given: str, headings: Sequence[str] | None = None) -> list[str]:
    """The guideline sections to read for ``word``, tagged ``given`` where the guidelines say ``gold``.

    The hard-case sections of section 4 that name the word ("middle", "previous", ...) or the mix-up (width
    and length, the default placement said in words, an anchor), section 2's general rule when the word
    should be ``O``, and always the gold tag's own section of section 3.
    """
    headings = guideline_headings() if headings is None else headings
    found = [h for h in headings if re.match(r"4\.\d+ ", h) and word.lower() in re.findall(r'"([^"]+)"', h)]
    if {gold, given} == {"width", "length"}:
        found.append(_heading(headings, r"^4\.\d+ Width and length"))
    if gold == "O" and given in PLACEMENT_TAGS:
        found.append(_heading(headings, r"^4\.\d+ The default placement"))
    if {gold, given} & set(ANCHOR_TAGS):
        found.append(_heading(headings, r"^4\.\d+ .*anchor"))
    if gold == "O":
        found.append(_heading(headings, r"^2\. The general rule"))
    found.append(f"3, the tag {_heading(headings, rf'^{re.escape(gold)}$')}")
    return [f"section {h}" for h in dict.fromkeys(found)]


def practice_instruction(instruction_id: str = TAGGING_EXERCISE) -> dict:
    """One instruction of the practice set with its answer-key tags (``practice_key.conll``)."""
    from drywall_lab.corpus import from_conll

    rows = {r["id"]: r for r in from_conll(PRACTICE_DIR / "practice_key.conll")}
    if instruction_id not in rows:
        raise ValueError(f"no practice instruction {instruction_id!r}; they are {', '.join(rows)}")
    return rows[instruction_id]


def parse_tagged(answer: str) -> tuple[list[str], list[str]]:
    """Words and tags from the guidelines' notation, ``word/TAG`` for a tagged word and a bare word for ``O``.

    Punctuation at a word's edges is dropped as ``corpus.tokenize`` drops it (``500103/St_loc2.`` is the word
    ``500103`` tagged ``St_loc2``). An unknown tag is a ``ValueError`` naming it and listing the tags.
    """
    from drywall_lab.corpus import tokenize

    words, tags = [], []
    for piece in answer.split():
        word, slash, tag = piece.rpartition("/")
        if not slash:
            word, tag = piece, "O"
        tag = tag.strip(".,?!;:\"'()")
        if tag not in TAGS:
            raise ValueError(f"{piece!r}: {tag!r} is not a tag; the tags are {', '.join(TAGS)}")
        for w in tokenize(word):
            words.append(w)
            tags.append(tag)
    return words, tags


def check_tagging(answer: str | Sequence[str], instruction_id: str = TAGGING_EXERCISE) -> ExerciseCheck:
    """Notebook 01's exercise: a practice instruction tagged by the guidelines, against the answer key.

    ``answer`` is the instruction in the guidelines' notation (``word/TAG``, a bare word is ``O``) or one tag
    per word. Every wrong word is named with the tag the key gives and the guideline sections to read.
    The notebook's stub, ``...`` (or ``None``), is "not attempted yet" (``ExerciseCheck.not_attempted``).
    """
    key = practice_instruction(instruction_id)
    if is_unattempted(answer, none=True):
        return ExerciseCheck.not_attempted(f"my_answer: the instruction {instruction_id} with /TAG after every word "
                                           "that carries information (a bare word is O)", solution_file(1))
    words, gold = key["words"], key["tags"]
    if isinstance(answer, str):
        try:
            given_words, given = parse_tagged(answer)
        except ValueError as e:
            return ExerciseCheck(False, [str(e)])
        for i, (got, want) in enumerate(zip(given_words, words)):
            if got != want:
                return ExerciseCheck(False, [f"word {i + 1} of your answer is {got!r} where the instruction has "
                                             f"{want!r}: keep the instruction's words and add /TAG to them"])
        if len(given_words) != len(words):
            return ExerciseCheck(False, [f"your answer has {len(given_words)} words, the instruction {len(words)}"])
    else:
        given = list(answer)
        if len(given) != len(words):
            return ExerciseCheck(False, [f"{len(given)} tags for {len(words)} words: give one tag per word"])
        unknown = [t for t in given if t not in TAGS]
        if unknown:
            return ExerciseCheck(False, [f"{unknown[0]!r} is not a tag; the tags are {', '.join(TAGS)}"])
    headings = guideline_headings()
    wrong = [(i, w, g, a) for i, (w, g, a) in enumerate(zip(words, gold, given)) if g != a]
    if not wrong:
        return ExerciseCheck(True, [f"all {len(words)} words of {instruction_id} tagged as the answer key tags them"])
    messages = [f"{len(words) - len(wrong)} of {len(words)} words right; {len(wrong)} to look at again:"]
    for i, w, g, a in wrong:
        messages.append(f"word {i + 1} {w!r}: you tagged {a}, the guidelines say {g} "
                        f"(see {'; '.join(guideline_sections(w, g, a, headings))})")
    return ExerciseCheck(False, messages)



# --- entities and entity-level scores (the from-scratch exercise) ----------------------------------------------
#: The tag of words outside every entity.
OUTSIDE = "O"
#: The practice instruction of notebook 01's entity section: the student's answer cuts one entity in two.
ENTITY_EXAMPLE = "P16"
#: One entity: (tag, start, end), the words ``words[start:end]`` (end exclusive).
Span = tuple[str, int, int]


def reference_entity_spans(tags: Sequence[str]) -> set[Span]:
    """The entities of one tag sequence as ``(tag, start, end)`` word spans, end exclusive (``words[start:end]``).

    The tags have no B-/I- prefixes (the paper's Fig. 7), so an entity is a maximal run of words with one and the
    same tag other than ``O``: an ``O`` or a change of tag ends it. Computed by seqeval's ``get_entities`` with
    the tags read as an IO scheme (``I-`` before each), which ends a run exactly there; seqeval's ends are
    inclusive, hence the ``+ 1``.

    >>> sorted(reference_entity_spans(["O", "St_loc1", "St_loc1", "St_loc2", "O", "Vr_md"]))
    [('St_loc1', 1, 3), ('St_loc2', 3, 4), ('Vr_md', 5, 6)]
    """
    from seqeval.metrics.sequence_labeling import get_entities

    return {(tag, start, end + 1) for tag, start, end in
            get_entities([tag if tag == OUTSIDE else f"I-{tag}" for tag in tags])}


def entity_matches(words: Sequence[str], gold: Sequence[str], predicted: Sequence[str] | None = None) -> pd.DataFrame:
    """The entities of one instruction, a row each in word order: tag, start, end (exclusive) and the words; with
    ``predicted``, the entities of either side and whether each is in the gold tags and in the predicted ones
    (an entity counts as found only with the same tag, start and end)."""
    gold_spans = reference_entity_spans(gold)
    predicted_spans = reference_entity_spans(predicted) if predicted is not None else set()
    rows = [{"tag": t, "start": s, "end": e, "words": " ".join(words[s:e]),
             **({} if predicted is None else {"in gold": (t, s, e) in gold_spans,
                                               "predicted": (t, s, e) in predicted_spans})}
            for t, s, e in sorted(gold_spans | predicted_spans, key=lambda span: (span[1], span[2], span[0]))]
    return pd.DataFrame(rows, columns=["tag", "start", "end", "words"] + ([] if predicted is None else
                                                                         ["in gold", "predicted"]))


def entity_scores(gold: Sequence[Sequence[str]], predicted: Sequence[Sequence[str]]) -> pd.DataFrame:
    """Entity-level precision, recall and F1, per tag and over all entities (row ``ALL``, the micro average that
    seqeval reports by default): ``gold`` and ``predicted`` entities (``reference_entity_spans``), ``correct``
    (the same tag, start and end in both), precision = correct / predicted, recall = correct / gold, F1 their
    harmonic mean (NaN where a count is 0). Rows: the tags with an entity on either side, in ``TAGS`` order."""
    if len(gold) != len(predicted) or any(len(g) != len(p) for g, p in zip(gold, predicted)):
        raise ValueError("gold and predicted must have the same instructions and words")
    counts: dict[str, list[int]] = {}
    for g, p in zip(gold, predicted):
        g_spans, p_spans = reference_entity_spans(g), reference_entity_spans(p)
        for spans, column in ((g_spans, 0), (p_spans, 1), (g_spans & p_spans, 2)):
            for tag, _, _ in spans:
                counts.setdefault(tag, [0, 0, 0])[column] += 1
    order = [t for t in TAGS if t in counts] + sorted(set(counts) - set(TAGS))
    table = pd.DataFrame([counts[t] for t in order], index=pd.Index(order, name="tag"),
                         columns=["gold", "predicted", "correct"], dtype=int)
    table.loc["ALL"] = table.sum() if len(table) else [0, 0, 0]
    table["precision"] = table["correct"] / table["predicted"].replace(0, float("nan"))
    table["recall"] = table["correct"] / table["gold"].replace(0, float("nan"))
    table["f1"] = 2 * table["precision"] * table["recall"] / (table["precision"] + table["recall"])
    return table


def entity_cases() -> list[tuple[str, list[str]]]:
    """Cases for ``entity_spans``: (what it tests, tags); the notebook's worked example first, then edge cases,
    then the practice set's key and a student's answer, and the gold tags of the corpus's validation split."""
    from drywall_lab.corpus import from_conll, read_split

    cases: list[tuple[str, list[str]]] = [
        (f"the worked example, {ENTITY_EXAMPLE}'s key", list(practice_instruction(ENTITY_EXAMPLE)["tags"])),
        ("no entity: every word O", ["O", "O", "O"]),
        ("an instruction of no words", []),
        ("one word, one entity", ["ID_wall"]),
        ("a run at the very start and one at the very end", ["St_loc1", "St_loc1", "O", "St_loc2"]),
        ("two runs of different tags with no O between (a change of tag ends a run)",
         ["O", "St_loc1", "St_loc1", "St_loc2", "St_loc2", "O"]),
        ("two runs of one tag with O between are two entities", ["dim", "O", "O", "dim", "dim"]),
        ("one-word entities side by side", ["O", "width", "length", "O"]),
    ]
    for name in ("practice_key", "student_answer"):
        cases += [(f"{r['id']} of {name}.conll", list(r["tags"])) for r in from_conll(PRACTICE_DIR / f"{name}.conll")]
    cases += [(f"validation instruction {r['id']}", list(r["tags"])) for r in read_split("validation")]
    return cases


def _spans_text(spans: set[Span] | list[Span]) -> str:
    return ", ".join(str(s) for s in sorted(spans, key=lambda s: (s[1], s[2], s[0]))) or "none"


def _entity_slip(tags: Sequence[str], got: set, want: set[Span]) -> str:
    """What is wrong with ``got``, naming the known slips."""
    outside = sorted(s for s in got if s and s[0] == OUTSIDE)
    if outside:
        return f"{outside[0]} is not an entity: O marks the words outside every entity"
    if got == {(t, s, e - 1) for t, s, e in want}:
        return ("your ends are inclusive (the index of the last word); here end is exclusive, one past the last word, "
                "so that words[start:end] are the entity's words")
    for span in sorted(got - want, key=str):
        if len(span) == 3 and isinstance(span[1], int) and isinstance(span[2], int) and 0 <= span[1] < span[2]:
            inside = list(tags[span[1]:span[2]])
            changes = [k for k in range(span[1] + 1, min(span[2], len(tags))) if tags[k] != tags[k - 1]]
            if changes and OUTSIDE not in inside:
                k = changes[0]
                return (f"your {span} runs on over a change of tag at word {k} ({tags[k - 1]} then {tags[k]}): "
                        "a change of tag ends an entity even with no O between")
            if OUTSIDE in inside:
                return f"your {span} takes in a word tagged O (word {span[1] + inside.index(OUTSIDE)}): O ends a run"
    if got == {(tags[i], i, i + 1) for i in range(len(tags)) if tags[i] != OUTSIDE} and got != want:
        return "you made every tagged word an entity of its own: a run of words with the same tag is one entity"
    return f"missing: {_spans_text(want - got)}; not entities: {_spans_text(got - want)}"


def check_entity_spans(entity_spans: Callable[[list[str]], Iterable[Span]]) -> ExerciseCheck:
    """Notebook 01's from-scratch exercise: ``entity_spans(tags)``, the set of ``(tag, start, end)`` entities (end
    exclusive), against ``reference_entity_spans`` (seqeval's ``get_entities``) on the worked example, edge cases
    (no entity, no words, runs at both ends, a change of tag with no O between, one-word entities side by side),
    the practice set and the validation split's gold tags. Known slips are named: inclusive ends, a run over a
    change of tag, O as an entity, one entity per word. The notebook's stub is "not attempted yet"."""
    cases = entity_cases()
    if is_unattempted(entity_spans, list(cases[0][1]), none=True):
        return ExerciseCheck.not_attempted("entity_spans(tags): the set of (tag, start, end) entities, end exclusive",
                                           solution_file(1))
    for what, tags in cases:
        want = reference_entity_spans(tags)
        result, error = call_student(entity_spans, list(tags))
        shown = f"{what}: tags {tags}"
        if error:
            return ExerciseCheck(False, [shown, f"your function raised {error}"])
        try:
            got = {tuple(span) for span in result}
        except TypeError:
            return ExerciseCheck(False, [shown, f"return a set of (tag, start, end) tuples, not {result!r}"])
        if got == want:
            continue
        return ExerciseCheck(False, [shown, f"the entities are {_spans_text(want)}", f"yours are {_spans_text(got)}",
                                     _entity_slip(tags, got, want)])
    return ExerciseCheck(True, [f"all {len(cases)} cases agree with seqeval's entities: maximal runs of one tag, "
                                "end exclusive"])


# --- the annotator's confusion matrix as a heatmap -----------------------------------------------------------------
def plot_confusion(confusion: pd.DataFrame, ax: Any = None,
                   title: str = "Key (rows) against the student's answer (columns)") -> Any:
    """A confusion matrix (word counts, gold tags as rows, given tags as columns) as a heatmap: each square
    coloured by its share of the row (where the key's words of that tag went), its count written in it."""
    import matplotlib.pyplot as plt
    import numpy as np

    counts = confusion.to_numpy()
    shares = counts / np.maximum(counts.sum(axis=1, keepdims=True), 1)
    if ax is None:
        _, ax = plt.subplots(figsize=(1.0 + 0.75 * counts.shape[1], 0.8 + 0.6 * counts.shape[0]))
    image = ax.imshow(shares, cmap="Blues", vmin=0, vmax=1)
    for (i, j), n in np.ndenumerate(counts):
        if n:
            ax.text(j, i, str(n), ha="center", va="center", fontsize=9,
                    color="white" if shares[i, j] > 0.6 else "black")
    ax.set_xticks(range(counts.shape[1]), [str(c) for c in confusion.columns], rotation=45, ha="right")
    ax.set_yticks(range(counts.shape[0]), [str(r) for r in confusion.index])
    ax.set_xlabel("answer")
    ax.set_ylabel("key")
    ax.set_title(title, fontsize=10)
    ax.figure.colorbar(image, ax=ax, fraction=0.046, pad=0.04, label="share of the key's row")
    return ax
