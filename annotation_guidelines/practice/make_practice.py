"""Rebuild the practice set from data/corpus/validation.jsonl.

    python annotation_guidelines/practice/make_practice.py

writes practice.txt, practice_key.conll and student_answer.conll next to this file and prints the
student's score. Each of the 20 items says what kind of instruction it wants (the hard cases of the
guidelines) and, for some, the first-round mistake the student makes on it; the first validation
instruction that fits is taken, so the set can be rebuilt whenever the corpus is regenerated. Patterns
use the guidelines' markup, matched on lowercased words: ``word/TAG`` (a bare word is ``O``), ``a|b`` for
alternatives, ``*`` any word, ``#`` a 6-digit id, ``N`` a number (digits or a number word).
"""
from __future__ import annotations

import json
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

from drywall_lab.annotation import score_annotator
from drywall_lab.corpus import TAGS, from_conll, read_split, to_conll, tokenize
from drywall_lab.corpus.phrases import NUMBER_WORDS as PHRASE_NUMBER_WORDS

HERE = Path(__file__).resolve().parent
NUMBER_WORDS = {word: n for n, word in PHRASE_NUMBER_WORDS.items()}  # "four" -> 4


def _token_ok(word: str, tag: str, pattern: str) -> bool:
    text, _, want = pattern.partition("/")
    if tag != (want or "O"):
        return False
    if text == "*":
        return True
    if text == "#":
        return bool(re.fullmatch(r"\d{6}", word))
    if text == "N":
        return word.isdigit() or word in NUMBER_WORDS
    return word in text.split("|")


def find(row: dict, pattern: str) -> list[int]:
    """Start indices where ``pattern`` matches the row's words and tags."""
    parts = pattern.split()
    words = [w.lower() for w in row["words"]]
    return [i for i in range(len(words) - len(parts) + 1)
            if all(_token_ok(words[i + j], row["tags"][i + j], p) for j, p in enumerate(parts))]


def number(word: str) -> int:
    return int(word) if word.isdigit() else NUMBER_WORDS[word.lower()]


def speech_style(row: dict) -> bool:
    """Lowercase, no punctuation: the speech-recogniser style."""
    return row["text"] == row["text"].lower() and not re.search(r"[.,?!]", row["text"])


@dataclass
class Item:
    """One practice instruction: what it must contain, and the student's mistakes on it."""

    about: str
    patterns: list[str]
    style: str | None = None  # "typed" | "speech" | None
    sentences: tuple[int, ...] = (1, 2, 3, 4)
    refused: bool | None = False  # None: either
    test: callable = None  # an extra condition on the row
    # (pattern, word offset in the pattern, the student's tag)
    mistakes: list[tuple[str, int, str]] = field(default_factory=list)

    def fits(self, row: dict, relax: int = 0) -> bool:
        """Relax 1 drops the style, 2 the sentence count too, 3 the extra patterns too."""
        if relax < 1 and self.style is not None and speech_style(row) != (self.style == "speech"):
            return False
        if relax < 2 and row["n_sentences"] not in self.sentences:
            return False
        if self.refused is not None and (row["expected"]["refusal"] is not None) != self.refused:
            return False
        if self.test is not None and not self.test(row):
            return False
        patterns = [m[0] for m in self.mistakes] + (self.patterns if relax < 3 else [])
        return all(find(row, p) for p in patterns)


def _turned(row: dict) -> bool:
    return any(number(row["words"][i]) > number(row["words"][i + 2]) for i in find(row, "N/width by N/length"))


def _default_placement(row: dict) -> bool:
    return not any(t in ("Vr_md", "Hr_top", "Hr_btm") for t in row["tags"])


def _number_words(row: dict) -> bool:
    return any(w.lower() in NUMBER_WORDS and t in ("width", "length") for w, t in zip(row["words"], row["tags"]))


# Each slot is a list of alternatives, best first; the first that some validation instruction fits is
# used (see ``choose``), so the set survives a regenerated corpus.
ITEMS: list[list[Item]] = [
    [Item("anchor id of a stud position (student: ID_stud)", ["#/ID_wall", "middle|center|centre/Vr_md line/Vr_md"],
          style="speech", sentences=(1,), mistakes=[("of #/St_loc2", 1, "ID_stud")]),
     Item("anchor id of a stud position (student: ID_stud)", ["#/ID_wall"], mistakes=[("of|from #/St_loc2", 1, "ID_stud")])],
    [Item("turned size 'A by B' (student: swapped)", ["center|centre|middle/Vr_md line/Vr_md"], style="typed", sentences=(1,),
          test=_turned, mistakes=[("N/width by N/length", 0, "length"), ("N/width by N/length", 2, "width")]),
     Item("turned size 'A by B' (student: swapped)", [], test=_turned,
          mistakes=[("N/width by N/length", 0, "length"), ("N/width by N/length", 2, "width")])],
    [Item("'the one in the middle' = stack; 'vertically' (student: Vr_md)", ["one in the middle/Dw_loc1"], style="speech",
          test=_default_placement, mistakes=[("vertically", 0, "Vr_md")]),
     Item("a stack position; 'vertically' (student: Vr_md)", ["*/Dw_loc1"], test=_default_placement,
          mistakes=[("vertically", 0, "Vr_md")]),
     Item("'vertically' with the default placement (student: Vr_md)", [], test=_default_placement,
          mistakes=[("vertically", 0, "Vr_md")])],
    [Item("'the middle stud' (student tags 'stud')", ["in the middle/Vr_md of the stud", "*/Dw_loc1"], style="typed",
          mistakes=[("middle|center|centre/St_loc1 stud", 1, "St_loc1")]),
     Item("the stud in the middle (student tags 'stud')", [], mistakes=[("middle|center|centre/St_loc1 stud", 1, "St_loc1")]),
     Item("'the third stud from the left' (student tags 'stud')", [],
          mistakes=[("*/St_loc1 stud from/St_loc1 the/St_loc1", 1, "St_loc1")])],
    [Item("'center line' and 'center stud' in one instruction", ["center|centre|middle/Vr_md line/Vr_md",
          "the stud is the center|centre|middle/St_loc1 stud", "N/length feet long"], style="typed"),
     Item("'middle' twice: the stud and the placement", ["middle|center|centre/St_loc1", "middle|center|centre/Vr_md"]),
     Item("'middle' twice: the stack and the placement", ["middle|center|centre/Dw_loc1", "middle|center|centre/Vr_md"]),
     Item("'in the middle' after a stud already named = placement", ["*/St_loc1 stud in the middle/Vr_md"]),
     Item("'in the middle' after a stud already named = placement", ["#/ID_stud in the middle/Vr_md"])],
    [Item("'the length is 8 and the width is 4' (student: swapped)", [], style="typed", sentences=(3, 4),
          mistakes=[("length is N/length", 2, "width"), ("width is N/width", 2, "length")]),
     Item("length named first (student: swapped)", [],
          mistakes=[("length of|is N/length", 2, "width"), ("width of|is N/width", 2, "length")]),
     Item("length named first (student: swapped)", [],
          mistakes=[("N/length feet long", 0, "width"), ("N/width feet wide", 0, "length")])],
    [Item("default placement in words (student: 'left' = St_loc1)", ["*/Dw_loc2"], style="typed",
          mistakes=[("line its edge up with the left side of the stud", 6, "St_loc1")]),
     Item("default placement in words (student: 'left' = St_loc1)", [],
          mistakes=[("left side of the stud", 0, "St_loc1")])],
    [Item("speech style, number words, 'install it vertically'", ["install it vertically", "#/ID_stud"], style="speech",
          test=_number_words),
     Item("speech style, number words", [], style="speech", test=_number_words)],
    [Item("'the middle board' = stack; top part", ["middle|center|centre/Dw_loc1", "*/Hr_top"], style="speech"),
     Item("a stack position; top row", ["*/Dw_loc1", "*/Hr_top"]),
     Item("top row", ["*/Hr_top"])],
    [Item("previous panel and previous stud as anchors; bottom row", ["previous|previously/Dw_loc2", "*/Hr_btm",
          "last/St_loc2"], style="speech"),
     Item("the previous panel as an anchor", ["previous|previously|last|just/Dw_loc2"])],
    [Item("'same size as the previous one' = dim; 'the last stud you used' = St_loc2",
          ["same/dim", "previous|previously/dim", "last/St_loc2 stud"], style="typed"),
     Item("a back-reference for the size, and the previous stud as an anchor", ["same/dim", "*/St_loc2"],
          test=lambda r: any(w.lower() in ("previous", "previously", "last", "just") and t == "St_loc2"
                             for w, t in zip(r["words"], r["tags"])))],
    [Item("'the same drywall as the previously installed one'", ["previously/dim installed/dim", "*/Vr_md", "#/St_loc2"],
          style="speech"),
     Item("a back-reference for the size", ["same/dim", "*/Vr_md"]),
     Item("a size word", ["*/dim"])],
    [Item("'on the middle line' (student: the middle stack)", ["*/St_loc1 to/St_loc1 the/St_loc1 left|right/St_loc1"],
          style="typed", test=_number_words, mistakes=[("on the middle/Vr_md line/Vr_md", 2, "Dw_loc1"),
                                                        ("on the middle/Vr_md line/Vr_md", 3, "O")]),
     Item("'on the middle line' (student: the middle stack)", [], mistakes=[("on the middle/Vr_md line/Vr_md", 2, "Dw_loc1"),
                                                                          ("on the middle/Vr_md line/Vr_md", 3, "O")])],
    [Item("refused: a position off the end of the wall", ["rightmost|leftmost/St_loc2", "*/Dw_loc2"], refused=True,
          test=lambda r: r["expected"]["refusal"] == "off_the_end"),
     Item("refused: a relative position", ["*/St_loc2"], refused=True),
     Item("refused", [], refused=True)],
    [Item("size with named roles; lower horizontal row", ["lower/Hr_btm horizontal/Hr_btm row/Hr_btm", "N/length feet long"],
          style="typed", sentences=(3,)),
     Item("size; bottom row", ["*/Hr_btm", "N/length"]),
     Item("bottom row", ["*/Hr_btm"])],
    [Item("'upper horizontal row' (student: 'horizontal' O)", ["it is the one", "*/Dw_loc2"], style="speech",
          mistakes=[("upper/Hr_top horizontal/Hr_top row/Hr_top", 1, "O")]),
     Item("'upper horizontal row' (student: 'horizontal' O)", [],
          mistakes=[("upper/Hr_top horizontal/Hr_top row/Hr_top", 1, "O")])],
    [Item("'the previous stud' (student: dim)", ["*/Dw_loc2"], style="speech", sentences=(4,),
          mistakes=[("previous/St_loc2 stud", 0, "dim")]),
     Item("'the previous stud' (student: dim)", [], mistakes=[("previous/St_loc2", 0, "dim")]),
     Item("'the stud you used last' (student: dim)", [], mistakes=[("last/St_loc2", 0, "dim")])],
    [Item("refused: unknown stud id; 'full' = dim", ["*/dim", "#/ID_stud"], refused=True,
          test=lambda r: r["expected"]["refusal"] == "unknown_id"),
     Item("refused, a different reason", [], refused=True)],
    [Item("count span of a panel position; 'horizontally at the bottom'", ["N/Dw_loc1 to/Dw_loc1 the/Dw_loc1 left|right/Dw_loc1",
          "horizontally at the bottom/Hr_btm"], style="typed"),
     Item("count span of a panel position", ["N/Dw_loc1 to/Dw_loc1 the/Dw_loc1 left|right/Dw_loc1"]),
     Item("relative panel position", ["*/Dw_loc1 of", "*/Dw_loc2"])],
    [Item("'two to the left' (student tags only 'two' and 'left')", ["#/ID_wall", "far/St_loc2 right|left/St_loc2 end/St_loc2"],
          style="typed", mistakes=[("N/St_loc1 to/St_loc1 the/St_loc1 left|right/St_loc1", 1, "O"),
                                   ("N/St_loc1 to/St_loc1 the/St_loc1 left|right/St_loc1", 2, "O")]),
     Item("'two to the left' (student tags only 'two' and 'left')", [],
          mistakes=[("*/St_loc1 to/St_loc1 the/St_loc1 left|right/St_loc1", 1, "O"),
                    ("*/St_loc1 to/St_loc1 the/St_loc1 left|right/St_loc1", 2, "O")])],
]


def choose(rows: list[dict]) -> list[tuple[Item, dict]]:
    """For each slot, the first instruction that fits: every alternative strictly first, then relaxed."""
    used: set[str] = set()
    chosen = []
    for k, alternatives in enumerate(ITEMS, 1):
        pick = next(((item, r) for relax in range(4) for item in alternatives for r in rows
                     if r["id"] not in used and item.fits(r, relax)), None)
        if pick is None:
            raise SystemExit(f"slot {k} ({alternatives[0].about}): no validation instruction fits")
        used.add(pick[1]["id"])
        chosen.append(pick)
    return chosen


def student_answer(item: Item, row: dict) -> dict:
    tags, coref = list(row["tags"]), list(row["coref_tags"])
    for pattern, offset, wrong in item.mistakes:
        i = find(row, pattern)[0] + offset
        old = tags[i]
        assert old != wrong, (row["id"], pattern)
        tags[i] = wrong
        # the co-reference column follows the student's 13-label choice
        coref[i] = wrong if wrong != "O" else ("O" if coref[i] == old else coref[i])
    return {"words": row["words"], "tags": tags, "coref_tags": coref}


def main() -> int:
    rows = read_split("validation")
    key, answer, lines = [], [], []
    for k, (item, row) in enumerate(choose(rows), 1):
        pid = f"P{k:02d}"
        assert tokenize(row["text"]) == row["words"], row["id"]
        key.append({**row, "id": pid})
        answer.append({"id": pid, "text": row["text"], **student_answer(item, row)})
        lines.append(f"{pid}\t{row['text']}\n")
        print(f"{pid}  {row['id']}  {item.about}")

    (HERE / "practice.txt").write_text("".join(lines), encoding="utf-8")
    to_conll(key, HERE / "practice_key.conll")
    blocks = []
    for a in answer:
        block = [f"# id = {a['id']}", f"# text = {json.dumps(a['text'], ensure_ascii=False)}"]
        block += [f"{w}\t{t}\t{c}" for w, t, c in zip(a["words"], a["tags"], a["coref_tags"])]
        blocks.append("\n".join(block))
    (HERE / "student_answer.conll").write_text("\n\n".join(blocks) + "\n", encoding="utf-8")

    # read back and check what the set promises
    key_back = from_conll(HERE / "practice_key.conll")
    answer_back = from_conll(HERE / "student_answer.conll")
    assert [r["id"] for r in key_back] == [r["id"] for r in answer_back] == [f"P{k:02d}" for k in range(1, 21)]
    assert all(kb == k for kb, k in zip(key_back, key)), "practice_key.conll does not read back as written"
    assert set(TAGS) <= {t for r in key for t in r["tags"]}, "not every tag occurs in the practice set"
    assert {r["n_sentences"] for r in key} == {1, 2, 3, 4}
    assert any(speech_style(r) for r in key) and not all(speech_style(r) for r in key)
    assert any(r["expected"]["refusal"] for r in key)
    report = score_annotator([r["tags"] for r in key_back], [r["tags"] for r in answer_back])
    print(report.summary())
    assert 0.90 < report.word_accuracy < 0.98 and report.cohen_kappa > 0.8, "the student's score is out of range"
    return 0


if __name__ == "__main__":
    sys.exit(main())
