"""Reading tagged words as people say them: numbers, ordinals, directions, anchors.

The rules in ``target.py`` and ``stud.py`` never look at raw strings; they ask these
small pure functions what a word means. A word reaches them as typed or as a
speech recogniser wrote it: any case, edge punctuation, digits or number words
("4", "four", "zero"), ordinals ("second", "2nd"), sizes in one word ("4x8",
"four-by-eight", "8'"), "centre" or "center".

A count is read as said: "zero", "0" and "same" are 0 places (spec section 3), never
the default of one. ``line_position`` reads an absolute position on a row of studs or
stacks (rules S2 and T4) and refuses, as ``undetermined``, every count or ordinal it
cannot place with certainty instead of dropping it.
"""
from __future__ import annotations

import re
from functools import lru_cache
from typing import Iterable, Sequence, TypeVar

from drywall_lab.corpus.phrases import NUMBER_WORDS, ORDINAL_WORDS
from drywall_lab.errors import Refusal
from drywall_lab.site import size_words as size_words_table

_T = TypeVar("_T")

#: Number words a worker may say, beyond the phrase banks' (which stop at twelve): a count past the
#: wall's end must be read, so that it is refused as ``off_the_end`` instead of dropped.
_NUMBER_WORDS: dict[str, int] = {word: n for n, word in NUMBER_WORDS.items()} | {
    "eleven": 11, "thirteen": 13, "fourteen": 14, "fifteen": 15, "sixteen": 16, "seventeen": 17,
    "eighteen": 18, "nineteen": 19, "twenty": 20,
}
_ORDINAL_WORDS: dict[str, int] = {word: n for n, word in ORDINAL_WORDS.items()} | {
    "eighth": 8, "ninth": 9, "tenth": 10, "eleventh": 11, "twelfth": 12, "thirteenth": 13, "fourteenth": 14,
    "fifteenth": 15, "sixteenth": 16, "seventeenth": 17, "eighteenth": 18, "nineteenth": 19, "twentieth": 20,
}
_ORDINAL_DIGITS = re.compile(r"^(\d+)(?:st|nd|rd|th)$")
_PIECES = re.compile(r"\d+|[a-z]+")
_EDGE = re.compile(r"^[^\w]+|[^\w]+$")
_POSSESSIVE_ID = re.compile(r"^(\d{4,})['’]s$")

LEFT_WORDS = frozenset({"left", "leftmost", "left-most", "lefthand", "left-hand"})
RIGHT_WORDS = frozenset({"right", "rightmost", "right-most", "righthand", "right-hand"})
#: A step along the wall said as an order: the studs (and stacks) are numbered from the left, so "past", "after",
#: "beyond", "further along" go right and "before", "back from", "short of" go left ("two past 500104").
ORDER_WORDS: dict[str, str] = {"past": "right", "after": "right", "beyond": "right", "along": "right",
                               "before": "left", "back": "left", "short": "left"}
MIDDLE_WORDS = frozenset({"middle", "center", "centre", "central", "halfway", "mid"})
#: Row words that say the top and the bottom row (``Hr_top``, ``Hr_btm``): every row phrase of the guidelines has one
#: ("up top", "across the top", "the upper course", "at the ceiling"; "down low", "floor level"); a row noun after
#: them ("row", "course", "half") carries the tag too but says neither row on its own.
TOP_ROW_WORDS = frozenset({"top", "upper", "high", "ceiling"})
BOTTOM_ROW_WORDS = frozenset({"bottom", "lower", "low", "floor"})
#: Words that point back at the last accepted command ("previous", "the one you just hung").
BACK_REFERENCE_WORDS = frozenset({
    "same", "previous", "previously", "last", "just", "before", "earlier", "again", "time",
    "installed", "hung", "used", "placed", "match", "matching", "matches", "like", "another", "those", "ditto",
})
#: Words that point back at the last piece only as the anchor of a relative position, where no word of
#: ``BACK_REFERENCE_WORDS`` is said ("three right of that/St_loc2 one", "of where/St_loc2 you put it", "the pile that/Dw_loc2
#: one came/Dw_loc2 from"; guidelines 4.7): an anchor is always a piece already handled, and these name no other.
ANCHOR_POINTING_WORDS = frozenset({"that", "it", "where", "came", "went"})
#: Back-reference words that say the *size* is the same ("same size as the previous one", "like the last one",
#: "matching", "ditto"). The others point back without saying so ("another", "again", "one of those", "last"): the
#: guidelines tag them ``dim`` only when nothing else names the panel ("another 2x8" is the 2x8).
SAME_SIZE_WORDS = frozenset({"same", "like", "match", "matching", "matches", "previous", "previously", "ditto"})
#: Size words that name the standard 4 x 8 panel (spec section 3, target rule 3).
STANDARD_SIZE_WORDS = frozenset({"full-size", "full-sized", "fullsize", "full", "standard", "regular", "normal",
                                 "whole", "standard-size"})
#: Words that say a size is meant but not which: "standard size", "same size as before" get their size from the
#: other word; a lone "size" or "sized" names no panel.
SIZE_WORDS = frozenset({"size", "sized", "sizes"})
#: Words that make "first"/"last" mean the end of the wall, not the last action ("the very last stud").
END_WORDS = frozenset({"very", "far", "most", "furthest", "farthest", "end"})
#: Tags that carry no information for the rules (spec section 2; ``Trg``/``Dst`` are read as ``O``).
UNTAGGED = frozenset({"O", "Trg", "Dst"})
#: Words of a step from another stud or stack ("one over to the right", "just to the left", "two places"):
#: without a tagged anchor there is nothing to count from.
RELATIVE_WORDS = frozenset({"over", "place", "places", "next", "just", "beside", "same", "where"})
#: Words that say a step goes on from where the work is ("two studs further right", "three more to the left", "one
#: over to the right"): with no anchor tagged, the step counts from the previous stud (annotation guidelines,
#: St_loc1).
GOING_ON_WORDS = frozenset({"further", "farther", "more", "over"})
#: Words of a stud position that mean "0 places from the anchor": "the same stud as last time", "where the
#: last one went" (annotation guidelines 3, St_loc1, and 4.7).
SAME_WORDS = frozenset({"same", "where"})
#: Short written forms (phone messages, notes) read as the word they stand for.
SPELLINGS: dict[str, str] = {
    "frm": "from", "fr": "from", "b4": "before", "prev": "previous", "lft": "left", "rt": "right", "rgt": "right",
    "ctr": "centre", "cntr": "center", "mid": "middle", "nxt": "next", "thru": "through",
}
#: Single digits as they are read out one by one ("five oh oh one oh three"): a spoken id.
_DIGIT_WORDS: dict[str, str] = {"zero": "0", "oh": "0", "o": "0", "one": "1", "two": "2", "three": "3",
                                "four": "4", "five": "5", "six": "6", "seven": "7", "eight": "8", "nine": "9"}


@lru_cache(maxsize=8192)
def normalise(word: str) -> str:
    """Lower case, edge punctuation dropped, short forms spelt out: ``"Centre,"`` -> ``"centre"``, ``"frm"`` -> ``"from"``."""
    w = _EDGE.sub("", word.strip().lower())
    return SPELLINGS.get(w, w)


def numbers_in(word: str) -> list[int]:
    """The numbers a word says, in order: ``"4x8"`` -> [4, 8], ``"four-by-eight"`` -> [4, 8], ``"8'"`` -> [8].

    Ordinals are not numbers here (see ``ordinal_of``), nor is a number after ``#``: ``"card #4"``, ``"item #2"``
    are labels, never a size or a count (an id keeps its ``#``: ``ids_in``).
    """
    if word.strip().startswith("#"):
        return []
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


def _counts(words: Sequence[str]) -> list[tuple[int, bool]]:
    """(count, is an ordinal) for every count said, in order; "one" (or "1", as a phone message writes it) after an
    ordinal or after a word that points back is the generic noun."""
    out: list[tuple[int, bool]] = []
    before_noun = False
    for word in words:
        w = normalise(word)
        n = ordinal_of(word)
        if n is not None:
            out.append((n, True))
        elif not (before_noun and w in ("one", "1")):
            out.extend((number, False) for number in numbers_in(word))
        before_noun = n is not None or _points_back(w)
    return out


def counts_in(words: Sequence[str]) -> list[int]:
    """Every count said, in order: ordinals and numbers ("second", "two", "2nd", "zero", "0").

    "one" right after an ordinal is the generic noun ("the 2nd one to the left"), not a count; so is "one" or "1"
    right after a word that points back ("the last 1", "that one").

    >>> counts_in(["2nd", "one"]), counts_in(["last", "1"]), counts_in(["two", "studs"])
    ([2], [], [2])
    """
    return [n for n, _ in _counts(words)]


def one_count(words: Sequence[str], quoted: str, what: str) -> int | None:
    """The count of a relative position, None if none is said; ``undetermined`` when it gives two.

    "one to the right", "second to the left", "two places to the right", "zero to the left" give 1, 2, 2, 0;
    "second three to the right" is refused.
    """
    counts = counts_in(words)
    if len(counts) > 1:
        raise Refusal("undetermined", f"{quoted} gives two counts, {counts[0]} and {counts[1]}: which {what}?")
    return counts[0] if counts else None


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


def relative_step(words: Sequence[str], quoted: str, what: str) -> tuple[str | None, int]:
    """(direction, count) of a relative position's direction words ``words`` (``quoted``): "two to the left" is
    ("left", 2), the count 1 when none is said; "the same" is (None, 0), the anchor itself. A count beside "same",
    two counts, or no single direction are ``undetermined`` (``one_count``, ``direction_of``)."""
    count = one_count(words, quoted, what)
    if says_same(words):
        if count not in (None, 0):
            raise Refusal("undetermined", f"{quoted} says both the same {what} and {places(count)} away: which {what}?")
        return None, 0
    return direction_of(words, quoted, what), 1 if count is None else count


def one_id(said: Sequence[str], what: str, verb: str) -> str:
    """The one id in ``said``, words tagged as naming a ``what`` ("stud", "panel") by its id; ``undetermined`` when
    they hold none, or several (the question ends "which one should I ``verb``?")."""
    ids = ids_in(said)
    if not ids:
        raise Refusal("undetermined", f"Which {what}: you said {quote(said)}, and I did not hear a {what} number in it.")
    if len(ids) > 1:
        raise Refusal("undetermined", f"Two {what}s are named, {' and '.join(ids)}: which one should I {verb}?")
    return ids[0]


def direction_of(words: Sequence[str], quoted: str, what: str) -> str:
    """The one direction ("left" or "right") of a relative position, said as a side or as an order along the wall
    (``ORDER_WORDS``: "two past 500104" is two to the right); ``undetermined`` if none or both."""
    sides = sides_in(words) | {ORDER_WORDS[w] for w in map(normalise, words) if w in ORDER_WORDS}
    if len(sides) != 1:
        problem = "names both left and right" if sides else "does not say left or right"
        raise Refusal("undetermined", f"{quoted} {problem}: which {what}?")
    return next(iter(sides))


def says_middle(words: Iterable[str]) -> bool:
    return any(normalise(w) in MIDDLE_WORDS for w in words)


#: The nouns of a stack (field corpus ``STACK_NOUNS``, "stack", "pile", ...): "the top of the left stack" is a place in it.
STACK_WORDS = frozenset({"stack", "stacks", "pile", "piles", "pallet", "bunch", "lot"})


#: The panel's nouns, and the words that say its stack's uppermost sheet ("the top sheet", "the topmost 2x8").
PANEL_WORDS = frozenset({"sheet", "panel", "board", "drywall", "piece", "one", "rock", "sheetrock", "plasterboard",
                         "wallboard", "gwb"})
UPPERMOST_WORDS = frozenset({"top", "topmost", "uppermost"})


#: Words before "the top" that make it a row ("across the top", "at the top"), and after "top" ("top row").
_ROW_LEADS = frozenset({"across", "along", "at", "up", "in", "into", "to", "onto", "on", "near", "by"})
_ROW_NEXT = frozenset({"row", "course", "position", "half", "part", "level", "plate", "tier", "run", "edge", "line"})


def _names_the_uppermost(norm: Sequence[str], i: int) -> bool:
    """Whether ``norm[i]`` is a top word that names the uppermost sheet of a stack: before a panel's noun or size,
    after a stack's noun ("pile top sheet", not "the mid bunch top") or after a determiner not led by a row's
    preposition ("the top 2x8", not "across the top sheetrock")."""
    w, before, after = norm[i], norm[i - 1], norm[i + 1]
    if w not in UPPERMOST_WORDS or after in _ROW_NEXT:
        return False
    size = len(numbers_in(after)) >= 2 and ("x" in after or "by" in after)
    if before in STACK_WORDS:
        return after in PANEL_WORDS or size  # not "the mid bunch, top": a row
    led = not _ROW_LEADS.isdisjoint(norm[max(0, i - 4):i - 1])  # "across (okay) the top sheet of rock"
    return before in ("the", "a", "that", "this") and not led and (after in PANEL_WORDS or size)


def stack_place(words: Sequence[str]) -> list[int]:
    """Where a row word names a place in a stack, not a row on the wall ("whatever is on top of the left stack", "the one
    at the bottom of the stack is cracked"): the positions of the row word, ``of`` and the words up to the stack's noun,
    which say which panel is meant or why, never the placement (guidelines 4.7).

    The uppermost sheet named as such is a place in its stack too: a top word right before the panel's noun or
    size, or right after a stack's noun ("the top 2x8", "the top sheet", "right pile top sheet"): the sheet on
    top is the one the robot takes, never the top row (which is "the top row", "up top", "across the top").

    >>> stack_place("the one at the bottom of the stack is cracked".split()), stack_place("the bottom of the wall".split())
    ([4, 5, 6, 7], [])
    >>> stack_place("left pile top sheet to 500107".split()), stack_place("the top 2x8 in the top row".split())
    ([2], [1])
    """
    norm = [normalise(w) for w in words]
    out = [i for i in range(1, len(norm) - 1) if norm[i] in UPPERMOST_WORDS and _names_the_uppermost(norm, i)]
    if STACK_WORDS.isdisjoint(norm):
        return out
    for i, w in enumerate(norm[:-2]):
        if w not in TOP_ROW_WORDS | BOTTOM_ROW_WORDS or norm[i + 1] != "of":
            continue
        for j in range(i + 2, min(i + 6, len(norm))):
            if norm[j] in STACK_WORDS:
                out.extend(range(i, j + 1))
                break
    return out


#: How many words after "of" an anchor said but not tagged is quoted from.
ANCHOR_REACH = 4
#: Words that may stand between a side and its "of" ("the right side of", "left, ok, of"): none names a thing.
ANCHOR_GAP_WORDS = frozenset({"side", "hand", "ok", "okay", "so", "like", "yeah", "well", "basically", "alright",
                              "uh", "um", "er", "hmm"})


def unread_anchor(words: Sequence[str], tags: Sequence[str], tag: str) -> list[str]:
    """The untagged words after a position that ends in a side and "of" ("the pile to the right of the door"): an
    anchor was said, but no word of it was read as one (no ``Dw_loc2`` / ``St_loc2`` at all). [] where none was said,
    or one was read."""
    idx = [i for i, t in enumerate(tags) if t == tag]
    if not idx or {"Dw_loc1": "Dw_loc2", "St_loc1": "St_loc2"}.get(tag) in tags \
            or normalise(words[idx[-1]]) not in LEFT_WORDS | RIGHT_WORDS:
        return []
    k = idx[-1] + 1
    while k < len(words) and tags[k] == "O" and normalise(words[k]) in ANCHOR_GAP_WORDS:
        k += 1  # "to the right side of", "to the left, ok, of"
    if k >= len(words) or normalise(words[k]) != "of":
        return []
    said = []
    for j in range(k + 1, min(len(words), k + 1 + ANCHOR_REACH)):
        if tags[j] != "O":
            break
        said.append(words[j])
    return said


def says_from(words: Iterable[str]) -> bool:
    """ "from the left", "counting from the right": a position counted from one end."""
    return any(normalise(w) in ("from", "counting") for w in words)


def says_end(words: Iterable[str]) -> bool:
    """ "very", "far", "most", "end": the words that make "first"/"last" an end of the wall."""
    return any(normalise(w) in END_WORDS for w in words)


def says_same(words: Iterable[str]) -> bool:
    """ "same", "where" (the last one went): 0 places from the anchor."""
    return any(normalise(w) in SAME_WORDS for w in words)


def goes_on(words: Sequence[str]) -> tuple[str, int] | None:
    """(direction, count) of a step said as going on from where the work is ("two studs further right" -> ("right",
    2), "one over to the left" -> ("left", 1), "more to the right" -> ("right", 1)): a going-on word
    (``GOING_ON_WORDS``) with one side and at most one count that is no ordinal, and nothing else of a position (no
    "from", middle, end, "same" or id). None otherwise."""
    said = [normalise(w) for w in words]
    if not any(w in GOING_ON_WORDS for w in said) or len(sides_in(said)) != 1:
        return None
    counts = _counts(words)
    if len(counts) > 1 or any(is_ordinal for _, is_ordinal in counts) or says_from(said) or says_middle(said) \
            or says_end(said) or says_same(said) or says_last(said) or ids_in(words):
        return None
    return next(iter(sides_in(said))), counts[0][0] if counts else 1


def says_relative(words: Iterable[str]) -> bool:
    """ "over", "places", "just", "next", "same": words of a step from another stud or stack."""
    return any(normalise(w) in RELATIVE_WORDS for w in words)


def says_last(words: Iterable[str]) -> bool:
    return any(normalise(w) in ("last", "final") for w in words)


def back_reference_words(words: Iterable[str]) -> list[str]:
    return [w for w in words if normalise(w) in BACK_REFERENCE_WORDS]


def says_same_size(words: Iterable[str]) -> bool:
    """Whether back-reference words say the size is the same as before (``SAME_SIZE_WORDS``: "same size as the last
    one", "like the previous one"), not only that the worker points back ("another", "one of those", "again")."""
    return any(normalise(w) in SAME_SIZE_WORDS for w in words)


def points_back(anchor_words: Iterable[str]) -> bool:
    """Whether an anchor's words point back at the last accepted command: a back-reference word ("previous", "the
    one you just used") or, in an anchor only, a pointing word ("that one", "where you put it", ``ANCHOR_POINTING_WORDS``)."""
    return any(_points_back(normalise(w)) for w in anchor_words)


def _points_back(normalised: str) -> bool:
    return normalised in BACK_REFERENCE_WORDS or normalised in ANCHOR_POINTING_WORDS


def standard_size_words(words: Iterable[str]) -> list[str]:
    """The words that name the standard size ("full-size", "standard"); a lone "size" is not one."""
    return [w for w in words if normalise(w) in STANDARD_SIZE_WORDS]


def property_size_words(words: Iterable[str]) -> list[str]:
    """The words that say a size by a property ("narrow", "skinny", "short"; ``site.size_words``)."""
    return [w for w in words if normalise(w) in size_words_table()]


def size_words(words: Iterable[str]) -> list[str]:
    """The generic size words ("size", "sized"): a size is meant, but they do not say which."""
    return [w for w in words if normalise(w) in SIZE_WORDS]


def ids_in(words: Iterable[str]) -> list[str]:
    """The ids said, in order, without repeats: whole numbers of four or more digits.

    An id is one word ("500107", "#500107", the possessive "500107's") or read out digit by digit over several
    words ("five oh oh one oh seven", "5 0 0 1 0 7"): a run of single digits makes one id.
    """
    out: list[str] = []
    run = ""

    def finish() -> None:
        nonlocal run
        if len(run) >= 4 and run not in out:
            out.append(run)
        run = ""

    for word in words:
        w = _POSSESSIVE_ID.sub(r"\1", normalise(word).lstrip("#"))
        digit = w if (len(w) == 1 and w.isdigit()) else _DIGIT_WORDS.get(w)
        if digit is not None:
            run += digit
            continue
        finish()
        if len(w) >= 4 and w.isdigit() and w not in out:
            out.append(w)
    finish()
    return out


def on_the_row(row: Sequence[_T], index: int, off_the_end: str) -> _T:
    """``row[index]`` (a stud of the wall, a stack) for an index on the row, never counted round from the other end;
    past either end the ``off_the_end`` refusal with the message ``off_the_end``."""
    if not 0 <= index < len(row):
        raise Refusal("off_the_end", off_the_end)
    return row[index]


def places(count: int) -> str:
    """ "one place", "three places"."""
    word = NUMBER_WORDS.get(count, str(count))
    return f"{word} place" if count == 1 else f"{word} places"


def quote(words: Sequence[str]) -> str:
    """Words as a worker would read them back: ``'the length is 8'``."""
    return "'" + " ".join(words) + "'"


def line_position(said: Sequence[str], quoted: str, length: int, what: str) -> tuple[int, str] | None:
    """Where an absolute position puts a stud or stack on a row of ``length`` (0 = the left end), and how.

    The readings the spec and the annotation guidelines decide (rules S2 and T4 of spec section 3):
    "n-th from the left/right" (or "counting from") is counted from that end; the middle is
    ``length // 2``; left/leftmost/far left and right/rightmost/far right are the ends; "last" is the
    right end; a bare ordinal counts from the left. ``None`` when the words name no position. The index
    may lie off the row: the caller refuses it as ``off_the_end``.

    Everything else is refused as ``undetermined``, never read by dropping a word: both sides; a step
    from another stud or stack with no anchor tagged ("two to the right", "just to the left", "same");
    an id among the position words; an ordinal with a side but no "from" ("third ... left": from the
    left end, or to the left of another stud?); an ordinal with "from" but no side, with the middle or
    with "last" ("second last"); the middle with a side or with "last"; "last" with "left"; two counts.
    """
    sides = sides_in(said)
    if len(sides) > 1:
        raise Refusal("undetermined", f"{quoted} names both the left and the right: which {what}?")
    side = next(iter(sides), None)
    counts = _counts(said)
    ordinals = list(dict.fromkeys(n for n, is_ordinal in counts if is_ordinal))
    numbers = [n for n, is_ordinal in counts if not is_ordinal]
    middle, last, from_ = says_middle(said), says_last(said), says_from(said)
    if ids_in(said):
        raise Refusal("undetermined", f"{quoted} mixes an id with a position: which {what}?")
    if len(ordinals) > 1 or (ordinals and numbers):
        second = ordinals[1] if len(ordinals) > 1 else numbers[0]
        raise Refusal("undetermined", f"{quoted} gives two counts, {ordinals[0]} and {second}: which {what}?")
    nth = ordinals[0] if ordinals else None
    if numbers and side is not None and from_:
        raise Refusal("undetermined", f"{quoted} does not say whether it is the {_ordinal_text(numbers[0])} {what} "
                                      f"from the {side} end or {places(numbers[0])} from it: which {what}?")
    if numbers or says_relative(said):
        raise Refusal("undetermined", f"{quoted} counts from another {what} but does not say which one: which {what}?")
    if nth is not None:
        if middle:
            raise Refusal("undetermined", f"{quoted} gives a count and the middle: which {what}?")
        if last and side is None:
            raise Refusal("undetermined", f"{quoted} does not say whether to count from the left end or back from "
                                          f"the right end: which {what}?")
        if last:
            raise Refusal("undetermined", f"{quoted} gives a count and 'last': which {what}?")
        if side is not None and from_:
            return (nth - 1 if side == "left" else length - nth), f"{_ordinal_text(nth)} counted from the {side}"
        if side is not None:
            raise Refusal("undetermined", f"{quoted} does not say whether to count from the {side} end or to the "
                                          f"{side} of another {what}: which {what}?")
        if from_:
            raise Refusal("undetermined", f"{quoted} does not say which end to count from: which {what}?")
        return nth - 1, f"{_ordinal_text(nth)} counted from the left"
    if middle and (side is not None or last):
        other = f"the {side}" if side is not None else "'last'"
        raise Refusal("undetermined", f"{quoted} names both the middle and {other}: which {what}?")
    if middle:
        return length // 2, "the middle"
    if last and side == "left":
        raise Refusal("undetermined", f"{quoted} names both 'last' and the left: which {what}?")
    if side is not None:
        return (0 if side == "left" else length - 1), f"the {side} end"
    if last:
        return length - 1, "the last (right end)"
    return None


def _ordinal_text(n: int) -> str:
    """ "1st", "2nd", "3rd", "11th"."""
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"
