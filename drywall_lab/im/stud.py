"""Which stud the panel goes on: the paper's Fig. 12, as spec section 3 fixes it.

Three rules, tried in order:

1. ``ID_stud``: that stud. Where position words name a stud too ("the far left stud, 500100"), they must
   name the same one: two different studs are ``undetermined`` (a question, never a guess).
2. ``St_loc1`` alone: a stud named by where it is on the wall: leftmost/first,
   rightmost/last, middle/centre, "n-th from the left/right", or a bare ordinal
   ("the third stud", counted from the left); "the same stud" (or "where the last one
   went") alone is the stud of the last accepted command. What the rule cannot place with
   certainty is refused as ``undetermined``, never read by dropping a word: an
   ordinal with a side but no "from" ("the third stud left": from the left end, or
   to the left of another stud?), a step with no anchor tagged ("three to the
   left", "just to the right"), a count with the middle or with "last"
   (``words.line_position``). A step said as going on from where the work is ("two studs
   further right", "one more to the left", "three over to the right") counts from the
   previous stud (``stud_going_on``). A stud named twice by its position, in two phrases
   ("the very first stud, the leftmost one"), is read phrase by phrase: both must name the
   same stud.
3. ``St_loc1`` + ``St_loc2``: ``St_loc1`` is a direction with an optional count
   (default 1; "zero", "0" and "same" are 0: the anchor itself), ``St_loc2`` the
   anchor: a stud id, the leftmost or rightmost stud, or the previous stud (the stud
   of the last accepted command), or a stud named by where it is on the wall as in rule 2
   ("three left of the centre stud", "one past the third stud"). "second to the left of 500109"
   is 500107. Two counts, or an anchor that names no stud, are ``undetermined``.
"""
from __future__ import annotations

from drywall_lab.errors import Refusal
from drywall_lab.im import words as W
from drywall_lab.im.context import MappingContext
from drywall_lab.im.trace import Decision, Rule, TaggedInstruction, Trace, first_decision
from drywall_lab.site import Stud


def _stud_at(ctx: MappingContext, index: int, said: str) -> Stud:
    studs = ctx.site.studs
    return W.on_the_row(studs, index, f"There is no stud {said}: the wall has {len(studs)} studs, "
                                      f"{studs[0].stud_id} to {studs[-1].stud_id}.")


# --- rule 1 ---------------------------------------------------------------------------
def stud_by_id(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 1 (Fig. 12): a word tagged ``ID_stud`` names the stud."""
    said = ti.words_with("ID_stud")
    if not said:
        return None
    stud = ctx.site.stud(W.one_id(said, "stud", "use"))  # unknown_id for an id not on this wall
    also = _position_said_too(ti, ctx)
    if also is not None and also.value != stud.stud_id:
        raise Refusal("undetermined", f"Stud {stud.stud_id} and {W.quote(ti.words_with('St_loc1'))} (stud "
                                      f"{also.value}) are two different studs: which one should I use?")
    agrees = f", as {W.quote(ti.words_with('St_loc1'))} says too" if also is not None else ""
    return Decision(stud.stud_id, f"stud {stud.stud_id} (x = {stud.x_center:.4f} m){agrees}")


def _position_said_too(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """The stud that position words beside an id name ("the far left stud, 500100"; rules 2-3), or None: no
    position words, a lone side word ("right" of "right now" is a time word), or words that name no stud."""
    said = ti.words_with("St_loc1")
    if not said or (len(said) == 1 and W.sides_in(said)):
        return None
    try:
        return stud_by_relative_position(ti, ctx) if ti.has("St_loc2") else stud_by_position(ti, ctx)
    except Refusal:
        return None


# --- rule 2 ---------------------------------------------------------------------------
def stud_by_position(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 2 (Fig. 12): ``St_loc1`` alone names a stud by where it is on the wall."""
    if not ti.has("St_loc1") or ti.has("St_loc2"):
        return None
    said = ti.words_with("St_loc1")
    if W.says_same(said) and not (W.counts_in(said) or W.sides_in(said) or W.says_middle(said)):
        quoted = W.quote(ti.phrase("St_loc1"))  # "the same stud", "where the last one went": the previous stud
        stud = ctx.site.stud(ctx.require_last(quoted)["stud_id"])
        return Decision(stud.stud_id, f"{quoted}: the stud of the last accepted command -> stud {stud.stud_id}")
    going_on = stud_going_on(ti, ctx)
    if going_on is not None:
        return going_on
    try:
        position = W.line_position(said, W.quote(ti.span("St_loc1")), len(ctx.site.studs), "stud")
    except Refusal as refusal:
        position = _said_twice(ti, len(ctx.site.studs), refusal)
    if position is None:
        return None
    index, how = position
    quoted = W.quote(ti.phrase("St_loc1"))
    anchor = W.unread_anchor(ti.words, ti.tags, "St_loc1")
    if anchor:
        raise Refusal("undetermined", f"You said {quoted} of {W.quote(anchor)}: which stud do you count from?")
    stud = _stud_at(ctx, index, quoted)
    return Decision(stud.stud_id, f"{quoted}: {how} -> stud {stud.stud_id}")


def stud_going_on(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 2, a step that goes on from where the work is ("two studs further right", "three more to the left", "one
    over to the right"; ``words.goes_on``): counted from the previous stud (the stud of the last accepted command),
    as if "of the previous stud" were said. None for any other position; a step counted from something the site
    does not have ("two over to the right of the door") is left to the rule below, which asks."""
    step = W.goes_on(ti.span("St_loc1"))
    if step is None or W.unread_anchor(ti.words, ti.tags, "St_loc1"):
        return None
    direction, count = step
    quoted = W.quote(ti.span("St_loc1"))
    last = ctx.site.stud(ctx.require_last(quoted)["stud_id"])
    where = f"{quoted}: {W.places(count)} to the {direction} of the previous stud {last.stud_id}"
    stud = _stud_at(ctx, last.index + (count if direction == "right" else -count), where)
    return Decision(stud.stud_id, f"{where} -> stud {stud.stud_id}")


#: Words that may stand inside one position ("third stud from the left") without starting another.
_STUD_NOUNS = frozenset({"stud", "studs", "post", "posts"})
#: Words around a bare side ("on the left"): a phrase of only these and a side is no position on its own.
_SIDE_ONLY = frozenset({"on", "the", "to", "at", "left", "right"})


def position_groups(ti: TaggedInstruction) -> list[list[str]]:
    """The ``St_loc1`` words in separate phrases: a new phrase starts where any word but a stud noun comes
    between two of them ("the first stud, the leftmost one" -> ["first"], ["leftmost"])."""
    idx = ti.indices("St_loc1")
    groups: list[list[int]] = [idx[:1]]
    for a, b in zip(idx, idx[1:]):
        if all(w.lower() in _STUD_NOUNS for w in ti.words[a + 1:b]):
            groups[-1].append(b)
        else:
            groups.append([b])
    return [[ti.words[i] for i in g] for g in groups if g]


def _said_twice(ti: TaggedInstruction, studs: int, refusal: Refusal) -> tuple[int, str]:
    """One stud named twice by its position ("the very first stud, the leftmost one"): each phrase read on its
    own must name the same stud; otherwise the refusal the words read together gave stands."""
    groups = position_groups(ti)
    if len(groups) < 2:
        raise refusal
    read = []
    for group in groups:
        if {w.lower() for w in group} <= _SIDE_ONLY:  # "the first stud on the left": the ordinal-and-side question
            raise refusal
        try:
            position = W.line_position(group, W.quote(group), studs, "stud")
        except Refusal:
            raise refusal from None
        if position is None:
            raise refusal
        read.append(position)
    if len({index for index, _ in read}) != 1:
        raise refusal
    return read[0][0], " and ".join(how for _, how in read) + " (said twice, the same stud)"


# --- rule 3 ---------------------------------------------------------------------------
def _anchor(ti: TaggedInstruction, ctx: MappingContext) -> tuple[Stud, str]:
    """The stud a relative position is counted from, read from the ``St_loc2`` words."""
    said = ti.words_with("St_loc2")
    quoted = W.quote(said)
    ids = W.ids_in(said)
    if len(ids) > 1:
        raise Refusal("undetermined", f"Two anchor studs are named, {' and '.join(ids)}: which one?")
    if ids:
        stud = ctx.site.stud(ids[0])
        return stud, f"stud {stud.stud_id}"
    if W.points_back(said) and not (W.says_last(said) and W.says_end(said)):  # not "the very last stud"
        if W.counts_in(said) or W.sides_in(said) or W.says_middle(said):
            raise Refusal("undetermined", f"{quoted} mixes the previous stud with a position: which stud should "
                                          "the position be counted from?")
        last = ctx.require_last(quoted)
        stud = ctx.site.stud(last["stud_id"])
        return stud, f"the previous stud {stud.stud_id}"
    position = W.line_position(said, quoted, len(ctx.site.studs), "stud")  # "the middle stud", "the third stud"
    if position is None:
        raise Refusal("undetermined", f"Which stud: you said {quoted}, but not which stud to count from.")
    index, how = position
    stud = _stud_at(ctx, index, quoted)
    return stud, f"{quoted} ({how}, stud {stud.stud_id})"


def stud_by_relative_position(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 3 (Fig. 12): the stud ``count`` places left or right of an anchor stud ("zero", "0", "same": 0 places)."""
    if not (ti.has("St_loc1") and ti.has("St_loc2")):
        return None
    direction_words = ti.words_with("St_loc1")
    quoted = W.quote(direction_words)
    direction, count = W.relative_step(direction_words, quoted, "stud")
    if direction is None:  # "the same stud as 500104": the anchor itself
        anchor, anchor_text = _anchor(ti, ctx)
        return Decision(anchor.stud_id, f"{quoted} as {anchor_text} -> stud {anchor.stud_id}")
    anchor, anchor_text = _anchor(ti, ctx)
    where = f"{W.places(count)} to the {direction} of {anchor_text}"
    stud = _stud_at(ctx, anchor.index + (count if direction == "right" else -count), where)
    return Decision(stud.stud_id, f"{where} -> stud {stud.stud_id}")


STUD_RULES: tuple[Rule, ...] = (
    ("S1 stud id", ("ID_stud",), stud_by_id),
    ("S2 stud position", ("St_loc1",), stud_by_position),
    ("S3 relative stud position", ("St_loc1", "St_loc2"), stud_by_relative_position),
)


def resolve_stud(ti: TaggedInstruction, ctx: MappingContext, trace: Trace | None = None) -> str:
    """The id of the destination stud, trying rules 1-3 in order; a ``Refusal`` otherwise."""
    if ti.has("St_loc2"):
        message = (f"{W.quote(ti.words_with('St_loc2'))} says which stud to count from, but not how far or in "
                   "which direction: which stud should it go on?")
    else:
        message = ("The instruction does not say which stud the panel goes on: give the stud's id "
                   "(\"stud 500107\") or where it is (\"the leftmost stud\", \"two to the right of 500103\").")
    return first_decision("destination", STUD_RULES, ti, ctx, trace, message).value
