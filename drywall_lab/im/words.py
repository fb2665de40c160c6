"""Reading tagged words as people say them: numbers, ordinals, directions, anchors.

The rules in ``target.py`` and ``stud.py`` never look at raw strings; they ask these
small pure functions what a word means. A word reaches them as typed or as a
speech recogniser wrote it: any case, edge punctuation, digits or number words
("4", "four"), ordinals ("second", "2nd"), sizes in one word ("4x8",
"four-by-eight", "8'"), "centre" or "center".
"""
from __future__ import annotations

import re
from typing import Iterable, Sequence

from drywall_lab.corpus.phrases import NUMBER_WORDS, ORDINAL_WORDS
from drywall_lab.errors import Refusal

#: Number words a worker may say, beyond the phrase banks' (which stop at twelve).
_NUMBER_WORDS: dict[str, int] = {word: n for n, word in NUMBER_WORDS.items()} | {"eleven": 11}
_ORDINAL_WORDS: dict[str, int] = {word: n for n, word in ORDINAL_WORDS.items()} | {
    "eighth": 8, "ninth": 9, "tenth": 10, "eleventh": 11, "twelfth": 12, "thirteenth": 13,
}
_ORDINAL_DIGITS = re.compile(r"^(\d+)(?:st|nd|rd|th)$")
_PIECES = re.compile(r"\d+|[a-z]+")
_EDGE = re.compile(r"^[^\w]+|[^\w]+$")

LEFT_WORDS = frozenset({"left", "leftmost", "left-most", "lefthand", "left-hand"})
RIGHT_WORDS = frozenset({"right", "rightmost", "right-most", "righthand", "right-hand"})
MIDDLE_WORDS = frozenset({"middle", "center", "centre", "central", "halfway", "mid"})
#: Words that point back at the last accepted command ("previous", "the one you just hung").
BACK_REFERENCE_WORDS = frozenset({
    "same", "previous", "previously", "last", "just", "before", "earlier", "again", "time",
    "installed", "hung", "used", "placed", "match", "matching", "matches", "like",
})
#: Size words that name the standard 4 x 8 panel (spec section 3, target rule 3).
STANDARD_SIZE_WORDS = frozenset({"full-size", "full-sized", "fullsize", "full", "standard", "regular", "size", "normal", "sized"})
#: Words that make "first"/"last" mean the end of the wall, not the last action ("the very last stud").
END_WORDS = frozenset({"very", "far", "most", "furthest", "farthest", "end"})


def normalise(word: str) -> str:
    """Lower case, edge punctuation dropped: ``"Centre,"`` -> ``"centre"``."""
    return _EDGE.sub("", word.strip().lower())


def numbers_in(word: str) -> list[int]:
    """The numbers a word says, in order: ``"4x8"`` -> [4, 8], ``"four-by-eight"`` -> [4, 8], ``"8'"`` -> [8].

    Ordinals are not numbers here (see ``ordinal_of``).
    """
    w = normalise(word)
    if ordinal_of(w) is not None:
        return []
    if w in _NUMBER_WORDS:
        return [_NUMBER_WORDS[w]]
    out = []
    for piece in _PIECES.findall(w):
        if piece.isdigit():
            out.append(int(piece))
        elif piece in _NUMBER_WORDS:
            out.append(_NUMBER_WORDS[piece])
    return out


def ordinal_of(word: str) -> int | None:
    """``"second"`` and ``"2nd"`` -> 2; ``None`` for a word that is not an ordinal."""
    w = normalise(word)
    if w in _ORDINAL_WORDS:
        return _ORDINAL_WORDS[w]
    m = _ORDINAL_DIGITS.match(w)
    return int(m.group(1)) if m else None


def count_in(words: Iterable[str]) -> int | None:
    """The count of a relative position: an ordinal or a number ("second", "two", "2nd"); None if none is said.

    "one to the right", "second to the left", "two places to the right" give 1, 2, 2.
    """
    for word in words:
        n = ordinal_of(word)
        if n is None:
            numbers = numbers_in(word)
            n = numbers[0] if numbers else None
        if n is not None:
            return n
    return None


def sides_in(words: Iterable[str]) -> set[str]:
    """The sides named: a subset of {"left", "right"}."""
    sides = set()
    for word in words:
        w = normalise(word)
        if w in LEFT_WORDS:
            sides.add("left")
        elif w in RIGHT_WORDS:
            sides.add("right")
    return sides


def direction_of(words: Sequence[str], quoted: str, what: str) -> str:
    """The one direction ("left" or "right") of a relative position; ``undetermined`` if none or both."""
    sides = sides_in(words)
    if len(sides) != 1:
        problem = "names both left and right" if sides else "does not say left or right"
        raise Refusal("undetermined", f"{quoted} {problem}: which {what}?")
    return next(iter(sides))


def says_middle(words: Iterable[str]) -> bool:
    return any(normalise(w) in MIDDLE_WORDS for w in words)


def says_from(words: Iterable[str]) -> bool:
    """ "from the left", "counting from the right": a position counted from one end."""
    return any(normalise(w) in ("from", "counting") for w in words)


def says_end(words: Iterable[str]) -> bool:
    """ "very", "far", "most", "end": the words that make "first"/"last" an end of the wall."""
    return any(normalise(w) in END_WORDS for w in words)


def says_same(words: Iterable[str]) -> bool:
    return any(normalise(w) == "same" for w in words)


def says_last(words: Iterable[str]) -> bool:
    return any(normalise(w) in ("last", "final") for w in words)


def back_reference_words(words: Iterable[str]) -> list[str]:
    return [w for w in words if normalise(w) in BACK_REFERENCE_WORDS]


def standard_size_words(words: Iterable[str]) -> list[str]:
    return [w for w in words if normalise(w) in STANDARD_SIZE_WORDS]


def ids_in(words: Iterable[str]) -> list[str]:
    """The ids said, in order, without repeats: words that are whole numbers of four or more digits."""
    out: list[str] = []
    for word in words:
        w = normalise(word).lstrip("#")
        if len(w) >= 4 and w.isdigit() and w not in out:
            out.append(w)
    return out


def places(count: int) -> str:
    """ "one place", "three places"."""
    word = NUMBER_WORDS.get(count, str(count))
    return f"{word} place" if count == 1 else f"{word} places"


def quote(words: Sequence[str]) -> str:
    """Words as a worker would read them back: ``'the length is 8'``."""
    return "'" + " ".join(words) + "'"
