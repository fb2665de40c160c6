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
from typing import Iterable, Sequence

from drywall_lab.corpus.phrases import NUMBER_WORDS, ORDINAL_WORDS
from drywall_lab.errors import Refusal

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
MIDDLE_WORDS = frozenset({"middle", "center", "centre", "central", "halfway", "mid"})
CENTRE_WORDS = frozenset({"center", "centre"})
#: Words that say the centre-line placement (``Vr_md``): every ``Vr_md`` phrase of the guidelines has one.
CENTRE_LINE_WORDS = MIDDLE_WORDS | {"centred", "centered", "centreline", "centerline", "c-l", "half", "split",
                                    "splitting"}
#: Words that say a panel lies, but that stay ``O`` (annotation guidelines 4.7: "sideways", "lay it down",
#: "horizontal(ly)" before a row word): a reading with no placement tag puts the panel upright, and these say not.
LYING_WORDS = frozenset({"horizontal", "horizontally", "sideways", "landscape", "lying", "lies", "lay", "lays",
                         "laid"})
#: Words that say a panel stands ("upright", "stood up on its end"), also ``O``: the default placement.
UPRIGHT_WORDS = frozenset({"upright", "vertical", "vertically", "standing", "stood", "stand", "stands", "plumb",
                           "portrait"})
#: Words that take back or deny what was said ("not lying down", "lying down, no wait, upright", "let me say that
#: again"): a placement word near them may be the abandoned one (guidelines 4.7, corrections).
TAKE_BACK_WORDS = frozenset({"not", "no", "don't", "dont", "never", "wait", "sorry", "actually", "scratch", "meant",
                             "mean", "correction", "disregard", "ignore", "strike", "rather", "instead", "oops", "bad",
                             "hang", "hold", "wrong", "said", "say"})
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
#: Generic words that may stand between a count and its direction ("two studs to the right", "one panel over").
COUNTED_NOUNS = frozenset({"stud", "studs", "panel", "panels", "stack", "stacks", "sheet", "sheets", "board",
                           "boards", "place", "places", "over", "spot", "spots"})
#: Tags that carry no information for the rules (spec section 2; ``Trg``/``Dst`` are read as ``O``).
UNTAGGED = frozenset({"O", "Trg", "Dst"})
#: Words of a step from another stud or stack ("one over to the right", "just to the left", "two places"):
#: without a tagged anchor there is nothing to count from.
RELATIVE_WORDS = frozenset({"over", "place", "places", "next", "just", "beside", "same", "where"})
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


def is_punctuation(word: str) -> bool:
    """A word with neither a letter nor a digit (``•``, ``—``, ``->``): punctuation, never tagged."""
    return not any(c.isalnum() for c in word)


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


#: The words a size phrase ends with ("2 ft wide", "an 8 foot", "a six-footer").
_SIZE_ENDS = frozenset({"wide", "long", "tall", "high", "across", "ft", "foot", "feet", "footer"})


def is_noun_one(words: Sequence[str], i: int) -> bool:
    """Whether ``words[i]`` is "one" (or "1", as a text message writes it) standing for the panel right after a
    size ("a 2 ft wide 1", "the 4x8 one"): the noun, never a size of 1 ft.

    >>> is_noun_one(["a", "2", "ft", "wide", "1"], 4), is_noun_one(["the", "4x8", "one"], 2), is_noun_one(["1", "by", "2"], 0)
    (True, True, False)
    """
    if i <= 0 or normalise(words[i]) not in ("one", "1"):
        return False
    before = normalise(words[i - 1])
    return before in _SIZE_ENDS or before.endswith("-footer") or len(numbers_in(words[i - 1])) >= 2


def says_a_size(words: Sequence[str]) -> bool:
    """Whether the words say a panel size "A by B", in one word or three ("4x8", "four-by-eight", "2 by 8"), whatever
    their tags: a size the tagger missed is still a panel the worker named.

    >>> says_a_size("lay one of the four by eight sheets".split()), says_a_size(["the", "4x8"]), says_a_size(["4", "studs"])
    (True, True, False)
    """
    norm = [normalise(w) for w in words]
    if any(len(numbers_in(w)) >= 2 and not w.isdigit() for w in norm):
        return True
    return any(norm[i + 1] in ("by", "x") and len(numbers_in(norm[i])) == 1 and len(numbers_in(norm[i + 2])) == 1
               for i in range(len(norm) - 2))


def counts_in(words: Sequence[str]) -> list[int]:
    """Every count said, in order: ordinals and numbers ("second", "two", "2nd", "zero", "0").

    "one" right after an ordinal is the generic noun ("the 2nd one to the left"), not a count; so is "one" or "1"
    right after a word that points back ("the last 1", "that one").

    >>> counts_in(["2nd", "one"]), counts_in(["last", "1"]), counts_in(["two", "studs"])
    ([2], [], [2])
    """
    return [n for n, _ in _counts(words)]


def untagged_count_before(words: Sequence[str], tags: Sequence[str], tag: str) -> int | None:
    """The index of a count left untagged right before the first ``tag`` word; None if there is none.

    "zero studs to/St_loc1 the/St_loc1 right/St_loc1": the position's own count ("zero") was not tagged,
    so reading the tagged words alone would drop it. Only a position with no count of its own and a
    direction ("left", "right") or a step word ("over", "places") can be missing one; generic nouns
    between are skipped; "one" is not a count here ("the one to the right"), nor is an id. A tagged position
    that starts with "one" right after an untagged ordinal ("3rd one/St_loc1 to/St_loc1 the left") has lost its
    count too: "one" is the ordinal's noun, as ``counts_in`` reads it when both are tagged.
    """
    first = next((i for i, t in enumerate(tags) if t == tag), None)
    if first is None:
        return None
    if (normalise(words[first]) == "one" and first > 0 and tags[first - 1] in UNTAGGED
            and ordinal_of(words[first - 1]) is not None):
        return first - 1  # "3rd one/St_loc1 to/St_loc1 the/St_loc1 left/St_loc1": 'one' is the ordinal's noun
    said = [w for w, t in zip(words, tags) if t == tag]
    if counts_in(said) or not (says_relative(said) or any(normalise(w) in ("left", "right") for w in said)):
        return None
    i = first - 1
    while i >= 0 and tags[i] in UNTAGGED and normalise(words[i]) in COUNTED_NOUNS:
        i -= 1
    if i < 0 or tags[i] not in UNTAGGED or normalise(words[i]) == "one" or ids_in([words[i]]):
        return None
    return i if ordinal_of(words[i]) is not None or len(numbers_in(words[i])) == 1 else None


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


def direction_of(words: Sequence[str], quoted: str, what: str) -> str:
    """The one direction ("left" or "right") of a relative position; ``undetermined`` if none or both."""
    sides = sides_in(words)
    if len(sides) != 1:
        problem = "names both left and right" if sides else "does not say left or right"
        raise Refusal("undetermined", f"{quoted} {problem}: which {what}?")
    return next(iter(sides))


def says_middle(words: Iterable[str]) -> bool:
    return any(normalise(w) in MIDDLE_WORDS for w in words)


def _with_pieces(words: Iterable[str]) -> set[str]:
    """The normalised words and the pieces of their hyphenated compounds: "bottom-row" gives "bottom-row", "bottom"
    and "row"."""
    out = set()
    for word in words:
        w = normalise(word)
        out.add(w)
        out.update(piece for piece in w.split("-") if piece)
    return out


def says_centre_line(words: Iterable[str]) -> bool:
    """ "centre", "c-l", "centre-line", "split the stud": a word that can carry ``Vr_md``; "the left line" alone cannot."""
    return not CENTRE_LINE_WORDS.isdisjoint(_with_pieces(words))


#: The row nouns that follow a row word in a row phrase ("top row", "bottom course", "bottom-row"; guidelines 4.7).
ROW_NOUNS = frozenset({"row", "course", "half", "part", "level", "plate", "tier", "run"})


def row_phrases(words: Sequence[str]) -> list[tuple[int, ...]]:
    """The row phrases of the words: a row word with a row noun right after it ("top row", "the bottom course") or in
    one hyphenated word ("bottom-row"), each as its positions. The guidelines tag such a phrase as the placement,
    always.

    >>> row_phrases("the next bottom-row sheet at 500106".split()), row_phrases("top row over it".split())
    ([(2,)], [(0, 1)])
    """
    norm = [normalise(w) for w in words]
    rows = TOP_ROW_WORDS | BOTTOM_ROW_WORDS
    out: list[tuple[int, ...]] = []
    for i, w in enumerate(norm):
        pieces = [p for p in w.split("-") if p]
        if len(pieces) > 1 and pieces[0] in rows and pieces[1] in ROW_NOUNS:
            out.append((i,))
        elif w in rows and i + 1 < len(norm) and norm[i + 1] in ROW_NOUNS:
            out.append((i, i + 1))
    return out


#: Counts before "left" that say what remains ("has one left", "only two left"), not a side.
_REMAINING_BEFORE = frozenset({"has", "have", "had", "got", "only", "just", "is", "are", "there's", "theres"})


def what_is_left(words: Sequence[str]) -> list[int]:
    """Where "left" says what remains ("the middle pile has one left", "only two left in it"), not the left side: the
    position of "left" right after a count that follows "has", "only", ... and before no "of", "from", ... ("is one
    left of 500104 free?" is a direction; guidelines 4.7: ``O``).

    >>> what_is_left("since the middle pile has one left , use it".split()), what_is_left("the one left of it".split())
    ([6], [])
    """
    norm = [normalise(w) for w in words]
    return [i for i in range(2, len(norm)) if norm[i] == "left" and (numbers_in(words[i - 1]) or norm[i - 1] in
            ("none", "nothing", "few", "some")) and norm[i - 2] in _REMAINING_BEFORE
            and (i + 1 == len(norm) or norm[i + 1] not in _DIRECTION_AFTER)]


#: Words after "left" that make it a direction ("is one left of 500104 free?"), never what remains.
_DIRECTION_AFTER = frozenset({"of", "from", "to", "off", "side", "hand", "end"})


#: A lying word says how *this* panel goes only near the instruction's own words: at most this many words from a
#: tagged word ("the 4 by 6 lying down at 500100"), not in a story before it.
LYING_REACH = 4


def lying_words(words: Sequence[str], tags: Sequence[str] | None = None) -> list[int]:
    """Where the words say the panel lies ("lying down", "sideways", "horizontally"), unless a word takes something
    back or denies it ("not sideways", "no wait"; the lying word may be the abandoned one) or a word says it stands
    ("we did the last wall sideways; this one upright"): then none is given. With ``tags``, a lying word more than
    ``LYING_REACH`` words from every tagged word says nothing of this panel: it is a story or a reason ("on the last
    job we did every wall sideways anyway the 2x8 from the left ...").

    >>> lying_words("the 4 by 6 lying down at 500100".split()), lying_words("not sideways , upright".split())
    ([4], [])
    """
    said = [normalise(w) for w in words]
    if any(w in TAKE_BACK_WORDS or w in UPRIGHT_WORDS for w in said):
        return []
    return _near_tagged([i for i, w in enumerate(said) if w in LYING_WORDS], tags)


def _near_tagged(positions: list[int], tags: Sequence[str] | None) -> list[int]:
    """The positions within ``LYING_REACH`` words of a tagged word (all of them without ``tags``)."""
    if tags is None or not positions:
        return positions
    tagged = [j for j, t in enumerate(tags) if t not in UNTAGGED]
    return [i for i in positions if any(abs(i - j) <= LYING_REACH for j in tagged)]


#: Words before a noun: "the upright", "each upright" name a stud (trade talk), not how the panel stands.
_DETERMINERS = frozenset({"the", "a", "an", "that", "this", "each", "every", "next", "first", "last", "same", "one"})


def upright_words(words: Sequence[str], tags: Sequence[str] | None = None) -> list[int]:
    """Where the words say the panel stands ("standing up", "upright", ``UPRIGHT_WORDS``), as ``lying_words`` reads
    lying words: none when a word takes something back or says it lies; with ``tags``, only those within
    ``LYING_REACH`` words of a tagged word. After "the", "each", ... it is a noun: "at the upright" is the stud.

    >>> upright_words("the 4x6 stands on 500102".split()), upright_words("lying down , not upright".split())
    ([2], [])
    """
    said = [normalise(w) for w in words]
    if any(w in TAKE_BACK_WORDS or w in LYING_WORDS for w in said):
        return []
    return _near_tagged([i for i, w in enumerate(said)
                         if w in UPRIGHT_WORDS and not (i and said[i - 1] in _DETERMINERS)], tags)


#: The stud spacings of framing (inches on centre): "16 in on centre", "sixteen-inch centres", "24 o.c.".
SPACING_INCHES = frozenset({12, 16, 24})
_SPACING_UNITS = frozenset({"in", "inch", "inches"})
_SPACING_CENTRES = frozenset({"centres", "centers", "o.c", "oc"})
_SPACING_NUMBERS = [[n] for n in sorted(SPACING_INCHES)]


def stud_spacing(words: Sequence[str]) -> list[int]:
    """Where the words give the stud spacing ("the studs are 16 in on centre", spec section 1; "sixteen-inch centres",
    "24 o.c."): the positions of the spacing phrase, which says how the wall is framed and never the centre-line
    placement (guidelines 4.7). Only the framing spacings (``SPACING_INCHES``) count, never a panel size or an id:
    "the 4 by 8 on centre" is a placement.

    >>> stud_spacing("walls are sixteen on centre , 500104".split()), stud_spacing("the 4 by 8 on centre".split())
    ([2, 3, 4], [])
    """
    norm = [normalise(w) for w in words]
    if CENTRE_WORDS.isdisjoint(norm) and _SPACING_CENTRES.isdisjoint(norm):
        return []  # no centre said at all: the usual case, decided without reading a number
    out: list[int] = []
    for i, w in enumerate(norm):
        if numbers_in(words[i]) not in _SPACING_NUMBERS and w not in ("twenty-four", "twentyfour"):
            continue
        j = i + 1
        while j < len(norm) and norm[j] in _SPACING_UNITS:
            j += 1
        if j < len(norm) and norm[j] in _SPACING_CENTRES:
            out.extend(range(i, j + 1))
        elif j + 1 < len(norm) and norm[j] == "on" and norm[j + 1] in CENTRE_WORDS | _SPACING_CENTRES:
            out.extend(range(i, j + 2))
    return out


#: The nouns of a stack (field corpus ``STACK_NOUNS``, "stack", "pile", ...): "the top of the left stack" is a place in it.
STACK_WORDS = frozenset({"stack", "stacks", "pile", "piles", "pallet", "bunch", "lot"})


def stack_place(words: Sequence[str]) -> list[int]:
    """Where a row word names a place in a stack, not a row on the wall ("whatever is on top of the left stack", "the one
    at the bottom of the stack is cracked"): the positions of the row word, ``of`` and the words up to the stack's noun,
    which say which panel is meant or why, never the placement (guidelines 4.7).

    >>> stack_place("the one at the bottom of the stack is cracked".split()), stack_place("the bottom of the wall".split())
    ([4, 5, 6, 7], [])
    """
    norm = [normalise(w) for w in words]
    if STACK_WORDS.isdisjoint(norm):
        return []
    out: list[int] = []
    for i, w in enumerate(norm[:-2]):
        if w not in TOP_ROW_WORDS | BOTTOM_ROW_WORDS or norm[i + 1] != "of":
            continue
        for j in range(i + 2, min(i + 6, len(norm))):
            if norm[j] in STACK_WORDS:
                out.extend(range(i, j + 1))
                break
    return out


def says_placement(tag: str, words: Iterable[str]) -> bool:
    """Whether words tagged with the placement tag ``tag`` can say that placement: a centre word for ``Vr_md``
    ("the left line" cannot), a top or bottom row word for ``Hr_top`` or ``Hr_btm`` ("row" alone, "lol" cannot).

    >>> says_placement("Hr_btm", ["bottom", "row"]), says_placement("Hr_btm", ["lol"]), says_placement("Vr_md", ["line"])
    (True, False, False)
    >>> says_placement("Hr_btm", ["bottom-row"]), says_placement("Vr_md", ["centre-line"]), says_placement("Hr_top", ["top-row"])
    (True, True, True)
    """
    if tag == "Vr_md":
        return says_centre_line(words)
    said = TOP_ROW_WORDS if tag == "Hr_top" else BOTTOM_ROW_WORDS
    return not said.isdisjoint(_with_pieces(words))  # "bottom-row", "top-course" too


def says_from(words: Iterable[str]) -> bool:
    """ "from the left", "counting from the right": a position counted from one end."""
    return any(normalise(w) in ("from", "counting") for w in words)


def says_end(words: Iterable[str]) -> bool:
    """ "very", "far", "most", "end": the words that make "first"/"last" an end of the wall."""
    return any(normalise(w) in END_WORDS for w in words)


def says_same(words: Iterable[str]) -> bool:
    """ "same", "where" (the last one went): 0 places from the anchor."""
    return any(normalise(w) in SAME_WORDS for w in words)


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


#: Back-reference words that say "one more of the same", never a piece to count *away* from: "the same stud again" is
#: the last stud, but "right of ... again" has no anchor ("left pile , top row again" with "again" tagged ``Dw_loc2``).
REPEAT_WORDS = frozenset({"again", "another", "ditto"})


def only_repeats(anchor_words: Iterable[str]) -> bool:
    """Whether an anchor's words that point back are all ``REPEAT_WORDS`` ("again"): they anchor "the same" only."""
    pointing = [normalise(w) for w in anchor_words if _points_back(normalise(w))]
    return bool(pointing) and all(w in REPEAT_WORDS for w in pointing)


def _points_back(normalised: str) -> bool:
    return normalised in BACK_REFERENCE_WORDS or normalised in ANCHOR_POINTING_WORDS


def standard_size_words(words: Iterable[str]) -> list[str]:
    """The words that name the standard size ("full-size", "standard"); a lone "size" is not one."""
    return [w for w in words if normalise(w) in STANDARD_SIZE_WORDS]


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
