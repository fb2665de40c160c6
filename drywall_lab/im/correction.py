"""The final intention counts: the tagged words a change of mind takes back (annotation guidelines 4.7).

The guidelines tag only what the worker finally meant: in "the second stud from the right, no, the fourth from the
right" the abandoned "second stud from the right" is ``O``. A tagger may still tag both (the words look alike), and
read as they are the rules see two counts and refuse, or act on the abandoned words. Before any rule, the IM reads
a tagged instruction as the guidelines mean it (``taken_back``):

- **A correction** (``CORRECTION_CUES``: "no", "wait", "actually", "sorry", "scratch that", "I mean", ...) followed,
  within ``WINDOW`` words, by tagged words of the same part (the panel, the stud or the placement) that were
  already said before it: the earlier words of that part are taken back. What the correction says again decides
  how much: a bare count ("two studs right of 500104, wait no, three") takes back the earlier count only; an anchor
  alone ("right of 500104, sorry, of 500105") the earlier anchor only; anything else (an id, a size, a stack, a
  position, a placement) the whole earlier part. An upright word right after a correction ("up top, no wait,
  standing up") takes back an earlier placement: the default is said in words.
- **A negation** (``NEGATIONS``: "not", "never mind", "forget", "without", ...) rules out the tagged phrase that
  starts right after it, within ``NEGATION_WINDOW`` words of "the", "on", ... ("the right pile, not the left", "not
  on the centre line"), when the same part is also said otherwise: an alternative to the negated one. A negation of
  untagged words ("not upright but ...", "not the default , ...") or of the only mention of a part ("why is it not on
  500100 yet?") rules nothing out; nor does a double negation ("don't forget the centre line").

The correction words must come right before what they say again: "wait, because the switch box sits low on the wall"
says why, and a tagged "low" six words on is not taken as a new placement. Gold tags never tag abandoned words,
so the rule changes nothing on them (tested on every split); the trace names what it took back.
"""
from __future__ import annotations

from typing import Sequence

from drywall_lab.corpus.tags import DESTINATION_TAGS, PLACEMENT_TAGS, TARGET_TAGS
from drywall_lab.im import words as W

#: Words that abandon what was just said, as normalised word sequences (guidelines 4.7, a change of mind). "hang on" is
#: also the verb ("hang on 500105"), so it is none here; "not that" is one ("the 4x8 , not that , the 2x8"), never a
#: negation.
CORRECTION_CUES: tuple[tuple[str, ...], ...] = (
    ("scratch", "that"), ("strike", "that"), ("disregard", "that"), ("ignore", "that"), ("i", "mean"), ("i", "meant"),
    ("not", "that"), ("hold", "on"), ("my", "bad"), ("my", "mistake"), ("no",), ("wait",), ("sorry",), ("actually",),
    ("correction",), ("oops",),
)
#: Words that rule out the phrase right after them (guidelines 4.7, a negated alternative).
NEGATIONS: tuple[tuple[str, ...], ...] = (
    ("never", "mind"), ("not",), ("don't",), ("dont",), ("forget",), ("skip",), ("without",),
)
#: A correction says its new words at once: at most this many words between the correction words and them
#: ("no , put it on 500105": three).
WINDOW = 4
#: A negation rules out the phrase that starts at most this many words after it ("not on the centre line").
NEGATION_WINDOW = 2

#: The words that may stand between a negation and the phrase it rules out ("not on the centre line").
_LEAD_WORDS = frozenset({"the", "a", "an", "on", "onto", "in", "at", "to", "from", "of", "with", "its", "stud", "panel"})

PARTS: dict[str, tuple[str, ...]] = {"panel": TARGET_TAGS, "stud": DESTINATION_TAGS, "placement": PLACEMENT_TAGS}
_DIRECTION = {"panel": "Dw_loc1", "stud": "St_loc1"}
_ANCHOR = {"panel": "Dw_loc2", "stud": "St_loc2"}
_COMPANION = {"Dw_loc1": "Dw_loc2", "Dw_loc2": "Dw_loc1", "St_loc1": "St_loc2", "St_loc2": "St_loc1"}
_PART_OF = {tag: part for part, part_tags in PARTS.items() for tag in part_tags}
_FIRST_WORDS = frozenset(cue[0] for cue in CORRECTION_CUES + NEGATIONS)


def is_negation(cue: str) -> bool:
    """Whether the words that took something back (a value of ``taken_back``) are a negation, not a correction."""
    return tuple(W.normalise(w) for w in cue.split()) in NEGATIONS


def _spans(norm: Sequence[str], cues: Sequence[tuple[str, ...]]) -> list[tuple[int, int]]:
    """(start, end) of every cue in the normalised words, left to right, the longest cue first at each word."""
    out, i = [], 0
    while i < len(norm):
        cue = next((c for c in cues if tuple(norm[i:i + len(c)]) == c), None)
        if cue is None:
            i += 1
            continue
        out.append((i, i + len(cue)))
        i += len(cue)
    return out


def _gap(words: Sequence[str], start: int, end: int) -> int:
    """How many words (punctuation not counted) stand between positions ``start`` and ``end``."""
    return sum(1 for w in words[start:end] if not W.is_punctuation(w))


def _phrase(first: int, words: Sequence[str], tags: Sequence[str], part_tags: Sequence[str]) -> list[int]:
    """The tagged words of one phrase of a part from ``first`` on: it ends at punctuation, at three untagged words in a
    row, or where a tag it has had comes back after another ("not the 4 by 6 the 4 by 8"); "one over to the right of
    the stud 500107" is one phrase."""
    out: list[int] = []
    seen: set[str] = set()
    untagged = 0
    for i in range(first, len(words)):
        if tags[i] in part_tags:
            if tags[i] in seen and tags[i] != tags[out[-1]]:
                break
            out.append(i)
            seen.add(tags[i])
            untagged = 0
        elif W.is_punctuation(words[i]) or untagged == 2:
            break
        else:
            untagged += 1
    return out


def _next_words(norm: Sequence[str], words: Sequence[str], start: int) -> list[str]:
    """The normalised words from ``start`` on, as far as ``WINDOW`` words after it (punctuation not counted)."""
    out: list[str] = []
    for i in range(start, len(words)):
        if _gap(words, start, i) > WINDOW:
            break
        out.append(norm[i])
    return out


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
    """The positions of the tagged words that a later correction or a negation takes back, each with the words
    that took it back; empty when there are none (always, for tags that follow the guidelines)."""
    norm = [W.normalise(w) for w in words]
    if _FIRST_WORDS.isdisjoint(norm):
        return {}
    dropped: dict[int, str] = {}
    corrections = _spans(norm, CORRECTION_CUES)
    in_correction = {i for start, end in corrections for i in range(start, end)}
    negations = [span for span in _spans(norm, NEGATIONS) if span[0] not in in_correction]
    for n, (start, end) in enumerate(negations):
        if any(other[0] == end or other[1] == start for other in negations[:n] + negations[n + 1:]):
            continue  # "don't forget the centre line": a double negation rules nothing out
        first = end
        while first < len(words) and tags[first] not in _PART_OF and norm[first] in _LEAD_WORDS:
            first += 1
        if first == len(words) or tags[first] not in _PART_OF or _gap(words, end, first) > NEGATION_WINDOW:
            continue  # "not upright but ...", "not , centre line": the negation is about untagged words
        part_tags = PARTS[_PART_OF[tags[first]]]
        phrase = _phrase(first, words, tags, part_tags)
        said = {tags[i] for i in phrase}
        # the anchor of a negated direction (or the direction of a negated anchor) is the same position, no alternative
        same_position = {_COMPANION[t] for t in said if t in _COMPANION} - said
        if any(tags[i] in part_tags and tags[i] not in same_position for i in range(len(words))
               if i not in phrase and i not in dropped):
            # an alternative is said besides the negated one ("the right pile , not the left"); alone, a negated
            # phrase may be no alternative at all ("why is it not on 500100 yet?")
            dropped.update((i, " ".join(words[start:end])) for i in phrase)
    for start, end in corrections:
        cue = " ".join(words[start:end])
        for part, part_tags in PARTS.items():
            before = [i for i in range(start) if tags[i] in part_tags and i not in dropped]
            if not before:
                continue
            after = [i for i in range(end, len(words)) if tags[i] in part_tags and i not in dropped]
            if after and _gap(words, end, after[0]) <= WINDOW:
                replaced = _replaced(part, before, after, words, tags)
            elif part == "placement" and not W.UPRIGHT_WORDS.isdisjoint(_next_words(norm, words, end)):
                replaced = before  # "up top , no wait , standing up": the default, said in words
            else:
                continue
            dropped.update((i, cue) for i in replaced)
    return dict(sorted(dropped.items()))
