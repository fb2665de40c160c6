"""Two things offered with "or": the worker has not decided, and the robot asks (annotation guidelines 4.8).

"on 500105 or 500106, I forget which", "the four by six or the two by eight", "on the centre line or the left
line": a part of the command (the panel, the stud or the placement) said twice, joined by "or". Unlike a change of
mind (``correction``: "500105, no, 500106"), neither is taken back, so either may be meant. The guidelines tag both;
the default placement (the stud's left line) has no tag and is read from its words ("the left line", "the left
edge"). ``offered_alternatives`` finds the offer; the IM (``mapper.interpret``) reads each alternative on its own
(the other's words as ``O``) and, where they give different outcomes, refuses as ``unclear`` with both commands as
the options of its question (``Interpretation.alternatives``). An "or" that starts a correction ("or rather", "or
no") or is followed by no part ("or so", "or whatever") offers nothing.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

from drywall_lab.corpus.tags import DESTINATION_TAGS, PLACEMENT_TAGS, TARGET_TAGS
from drywall_lab.im import words as W

OR_WORDS = frozenset({"or"})
#: Words right after "or" that make it no offer: a correction starts ("or rather", "or no, 500106") or nothing is
#: named ("or whatever", "or else"). An "or so" names nothing where no part follows; where one does, it is an offer.
NOT_OFFERED_AFTER = frozenset({"rather", "no", "wait", "actually", "sorry", "i", "whatever", "something",
                               "anything", "else", "not", "otherwise", "better", "make", "scratch"})
#: At most this many words between "or" and the words of a part on either side ("500105 , or , let's see , maybe
#: 500106").
REACH = 5
#: The parts a command has, and the tags that say each.
PARTS: dict[str, tuple[str, ...]] = {"panel": TARGET_TAGS, "stud": DESTINATION_TAGS, "placement": PLACEMENT_TAGS}
#: Tags that say the same kind of thing: a group of alternatives spans one role ("four by six": width and length).
ROLES: tuple[frozenset[str], ...] = (frozenset({"ID_wall"}), frozenset({"dim", "width", "length"}),
                                     frozenset({"Dw_loc1"}), frozenset({"Dw_loc2"}), frozenset({"ID_stud"}),
                                     frozenset({"St_loc1"}), frozenset({"St_loc2"}), frozenset(PLACEMENT_TAGS))
#: The nouns after "left" that name the default placement ("the left line", "its left edge").
LEFT_EDGE_NOUNS = frozenset({"line", "edge", "side"})


@dataclass(frozen=True)
class Offer:
    """A part said twice with "or": the word positions of each alternative (``()``: the default placement, said
    in untagged words at ``default_words``)."""

    part: str
    first: tuple[int, ...]
    second: tuple[int, ...]
    default_words: tuple[int, ...] = ()

    def readings(self, tags: Sequence[str]) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The tags of each alternative read on its own: the other alternative's words as ``O``."""
        def without(drop: tuple[int, ...]) -> tuple[str, ...]:
            return tuple("O" if i in drop else t for i, t in enumerate(tags))
        return without(self.second), without(self.first)


def _part_of(tag: str) -> str | None:
    return next((part for part, tags in PARTS.items() if tag in tags), None)


def _role_of(tag: str) -> frozenset[str]:
    return next(role for role in ROLES if tag in role)


def _group(tags: Sequence[str], i: int, step: int) -> tuple[int, ...]:
    """The words of the role of ``tags[i]`` from ``i`` on, away from the "or" (``step``: -1 back, 1 on), across a
    single untagged word ("four by six")."""
    role = _role_of(tags[i])
    out = [i]
    j = i + step
    while 0 <= j < len(tags):
        if tags[j] in role:
            out.append(j)
        elif not (tags[j] == "O" and 0 <= j + step < len(tags) and tags[j + step] in role):
            break
        j += step
    return tuple(sorted(out))


def _tagged_near(tags: Sequence[str], k: int, step: int) -> int | None:
    """The first tagged word within ``REACH`` words of ``k`` in direction ``step`` (None if the first is further)."""
    for j in range(k + step, k + step * (REACH + 1), step):
        if not 0 <= j < len(tags):
            return None
        if tags[j] != "O":
            return j
    return None


def _default_near(norm: Sequence[str], tags: Sequence[str], k: int, step: int) -> tuple[int, ...]:
    """The untagged words naming the default placement within ``REACH`` words of ``k`` ("the left line"; "left"
    alone right beside the "or"), or ()."""
    for j in range(k + step, k + step * (REACH + 1), step):
        if not 0 <= j < len(norm) or tags[j] != "O":
            return ()
        if norm[j] in W.LEFT_WORDS:
            noun = next((n for n in range(j + 1, j + 4) if n < len(norm) and norm[n] in LEFT_EDGE_NOUNS
                         and tags[n] == "O"), None)  # "the left line", "the left, let's see, edge"
            if noun is not None:
                return (j, noun)
            return (j,) if abs(j - k) == 1 else ()
    return ()


def offered_alternatives(words: Sequence[str], tags: Sequence[str]) -> Offer | None:
    """The first part said twice with "or" (module docstring), or None (always, for tags that follow the guidelines
    and an instruction that offers nothing)."""
    norm = [W.normalise(w) for w in words]
    if OR_WORDS.isdisjoint(norm):
        return None
    for k, word in enumerate(norm):
        if word not in OR_WORDS or (k + 1 < len(norm) and norm[k + 1] in NOT_OFFERED_AFTER):
            continue
        before, after = _tagged_near(tags, k, -1), _tagged_near(tags, k, 1)
        part_before = _part_of(tags[before]) if before is not None else None
        part_after = _part_of(tags[after]) if after is not None else None
        if part_before is not None and part_before == part_after:
            return Offer(part_before, _group(tags, before, -1), _group(tags, after, 1))
        if part_before == "placement":
            default = _default_near(norm, tags, k, 1)
            if default:
                return Offer("placement", _group(tags, before, -1), (), default)
        if part_after == "placement":
            default = _default_near(norm, tags, k, -1)
            if default:
                return Offer("placement", (), _group(tags, after, 1), default)
    return None
