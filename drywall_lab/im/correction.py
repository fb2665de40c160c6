"""The final intention counts: the tagged words a change of mind takes back (annotation guidelines 4.7).

The guidelines tag only what the worker finally meant: in "the second stud from the right, no, the fourth from the
right" the abandoned "second stud from the right" is ``O``. A tagger may still tag both (the words look alike), and
read as they are the rules see two counts and refuse, or act on the abandoned words. Before any rule, the IM reads
a tagged instruction as the guidelines mean it (``taken_back``): a correction (``CORRECTION_CUES``: "no", "wait",
"actually", "sorry", "scratch that", "I mean", ...) followed, within ``WINDOW`` words, by tagged words of the same
part (the panel, the stud or the placement) that were already said before it: the earlier words of that part are
taken back. What the correction says again decides how much: a bare count ("two studs right of 500104, wait no,
three") takes back the earlier count only; an anchor alone ("right of 500104, sorry, of 500105") the earlier anchor
only; anything else (an id, a size, a stack, a position, a placement) the whole earlier part. A negation ("the right
pile, not the left") takes nothing back: the words after it are read as tagged.

The correction words must come right before what they say again: "wait, because the switch box sits low on the wall"
says why, and a tagged "low" six words on is not taken as a new placement. Gold tags never tag abandoned words,
so the rule changes nothing on them (tested on every split); the trace names what it took back.
"""
from __future__ import annotations

import functools

from typing import Sequence

from drywall_lab.corpus.tags import DESTINATION_TAGS, PLACEMENT_TAGS, TARGET_TAGS
from drywall_lab.im import words as W

#: Words that abandon what was just said, as normalised word sequences (guidelines 4.7, a change of mind). "hang on" is
#: also the verb ("hang on 500105"), so it is none here; "not that" is one ("the 4x8 , not that , the 2x8"), never a
#: negation.
CORRECTION_CUES: tuple[tuple[str, ...], ...] = (
    ("scratch", "that"), ("strike", "that"), ("disregard", "that"), ("ignore", "that"), ("i", "mean"), ("i", "meant"),
    ("not", "that"), ("hold", "on"), ("my", "bad"), ("my", "mistake"), ("no",), ("wait",), ("sorry",), ("actually",),
    ("correction",), ("oops",), ("second", "thought"),
)
#: A correction says its new words at once: at most this many words between the correction words and them
#: ("no , put it on 500105": four, the comma counted).
WINDOW = 4

PARTS: dict[str, tuple[str, ...]] = {"panel": TARGET_TAGS, "stud": DESTINATION_TAGS, "placement": PLACEMENT_TAGS}
_DIRECTION = {"panel": "Dw_loc1", "stud": "St_loc1"}
_ANCHOR = {"panel": "Dw_loc2", "stud": "St_loc2"}
_FIRST_WORDS = frozenset(cue[0] for cue in CORRECTION_CUES)


@functools.lru_cache(maxsize=1024)
def _spans(norm: tuple[str, ...], cues: tuple[tuple[str, ...], ...]) -> tuple[tuple[int, int], ...]:
    """(start, end) of every cue in the normalised words, left to right, the longest cue first at each word (kept for
    the next reading of the same words: the decision reads up to k tag sequences of one instruction)."""
    first = {cue[0] for cue in cues}
    out, i = [], 0
    while i < len(norm):
        cue = None if norm[i] not in first else next((c for c in cues if norm[i:i + len(c)] == c), None)
        if cue is None:
            i += 1
            continue
        out.append((i, i + len(cue)))
        i += len(cue)
    return tuple(out)


def _is_count(word: str) -> bool:
    return bool(W.numbers_in(word)) or W.ordinal_of(word) is not None


def _replaced(part: str, before: list[int], after: list[int], words: Sequence[str], tags: Sequence[str]) -> list[int]:
    """The earlier words of ``part`` that the words said again (``after``) replace."""
    said_again = {tags[i] for i in after}
    if part in _DIRECTION:
        direction, anchor = _DIRECTION[part], _ANCHOR[part]
        if said_again == {direction} and all(_is_count(words[i]) for i in after):
            return [i for i in before if tags[i] == direction and _is_count(words[i])]  # "wait no , three"
        if said_again == {anchor}:
            return [i for i in before if tags[i] == anchor]  # "right of 500104 , sorry , of 500105"
    return before


def taken_back(words: Sequence[str], tags: Sequence[str]) -> dict[int, str]:
    """The positions of the tagged words that a later correction takes back, each with the words that took it back;
    empty when there are none (always, for tags that follow the guidelines)."""
    norm = tuple(W.normalise(w) for w in words)
    if _FIRST_WORDS.isdisjoint(norm):
        return {}
    dropped: dict[int, str] = {}
    for start, end in _spans(norm, tuple(CORRECTION_CUES)):
        cue = " ".join(words[start:end])
        for part, part_tags in PARTS.items():
            before = [i for i in range(start) if tags[i] in part_tags and i not in dropped]
            if not before:
                continue
            after = [i for i in range(end, len(words)) if tags[i] in part_tags and i not in dropped]
            if not after or after[0] - end > WINDOW:
                continue
            dropped.update((i, cue) for i in _replaced(part, before, after, words, tags))
    return dict(sorted(dropped.items()))
