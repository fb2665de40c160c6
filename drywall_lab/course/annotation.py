"""Notebook 01 (annotation): the corpus's tag shares (Table 2) and the tagging exercise by the guidelines."""
from __future__ import annotations

import re
from pathlib import Path
from typing import Sequence

import pandas as pd

from drywall_lab.corpus.tags import TAGS
from drywall_lab.course.common import REPO_ROOT, solution_file
from drywall_lab.exercise import ExerciseCheck, is_unattempted

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

