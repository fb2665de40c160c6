"""Which stud the panel goes on: the paper's Fig. 12, as spec section 3 fixes it.

Three rules, tried in order:

1. ``ID_stud``: that stud.
2. ``St_loc1`` alone: a stud named by where it is on the wall: leftmost/first,
   rightmost/last, middle/centre, "n-th from the left/right", or a bare ordinal
   ("the third stud", counted from the left).
3. ``St_loc1`` + ``St_loc2``: ``St_loc1`` is a direction with an optional count
   (default 1; "same" is 0), ``St_loc2`` the anchor: a stud id, the leftmost or
   rightmost stud, or the previous stud (the stud of the last accepted command).
   "second to the left of 500109" is 500107.
"""
from __future__ import annotations

from drywall_lab.errors import Refusal
from drywall_lab.im import words as W
from drywall_lab.im.context import MappingContext
from drywall_lab.im.trace import Decision, Rule, TaggedInstruction, Trace, first_decision
from drywall_lab.site import Stud


def _stud_at(ctx: MappingContext, index: int, said: str) -> Stud:
    studs = ctx.site.studs
    if not 0 <= index < len(studs):
        raise Refusal(
            "off_the_end",
            f"There is no stud {said}: the wall has {len(studs)} studs, {studs[0].stud_id} to {studs[-1].stud_id}.",
        )
    return studs[index]


def _ordinal(words: list[str]) -> int | None:
    return next((n for n in map(W.ordinal_of, words) if n is not None), None)


# --- rule 1 ---------------------------------------------------------------------------
def stud_by_id(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 1 (Fig. 12): a word tagged ``ID_stud`` names the stud."""
    said = ti.words_with("ID_stud")
    if not said:
        return None
    ids = W.ids_in(said)
    if not ids:
        raise Refusal("undetermined", f"{W.quote(said)} is tagged as a stud id but is not a number: which stud?")
    if len(ids) > 1:
        raise Refusal("undetermined", f"Two studs are named, {' and '.join(ids)}: which one should I use?")
    stud = ctx.site.stud(ids[0])  # unknown_id for an id not on this wall
    return Decision(stud.stud_id, f"stud {stud.stud_id} (x = {stud.x_center:.4f} m)")


# --- rule 2 ---------------------------------------------------------------------------
def stud_by_position(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 2 (Fig. 12): ``St_loc1`` alone names a stud by where it is on the wall."""
    if not ti.has("St_loc1") or ti.has("St_loc2"):
        return None
    said = ti.words_with("St_loc1")
    quoted = W.quote(ti.phrase("St_loc1"))
    n = len(ctx.site.studs)
    sides = W.sides_in(said)
    nth = _ordinal(said)
    if len(sides) > 1:
        raise Refusal("undetermined", f"{quoted} names both the left and the right: which stud?")
    side = next(iter(sides), None)
    if nth is not None and side is not None and W.says_from(said):
        stud = _stud_at(ctx, nth - 1 if side == "left" else n - nth, quoted)
        how = f"{nth} counted from the {side}"
    elif W.says_middle(said):
        stud, how = ctx.site.studs[n // 2], "the middle stud"
    elif side is not None:
        stud = ctx.site.studs[0 if side == "left" else n - 1]
        how = f"the {side}most stud"
    elif nth is not None:
        stud, how = _stud_at(ctx, nth - 1, quoted), f"{nth} counted from the left"
    elif W.says_last(said):
        stud, how = ctx.site.studs[-1], "the last stud"
    else:
        return None
    return Decision(stud.stud_id, f"{quoted}: {how} -> stud {stud.stud_id}")


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
    sides = W.sides_in(said)
    if len(sides) == 1:
        side = next(iter(sides))
        return ctx.site.studs[0 if side == "left" else -1], f"the {side}most stud"
    if _ordinal(said) == 1:
        return ctx.site.studs[0], "the first (leftmost) stud"
    if W.says_last(said) and W.says_end(said):  # "the very last stud", not "the stud you used last"
        return ctx.site.studs[-1], "the last (rightmost) stud"
    if W.back_reference_words(said):
        last = ctx.require_last(quoted)
        stud = ctx.site.stud(last["stud_id"])
        return stud, f"the previous stud {stud.stud_id}"
    raise Refusal("undetermined", f"{quoted} does not say which stud the position is counted from.")


def stud_by_relative_position(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 3 (Fig. 12): the stud ``count`` places left or right of an anchor stud ("same" is 0 places)."""
    if not (ti.has("St_loc1") and ti.has("St_loc2")):
        return None
    direction_words = ti.words_with("St_loc1")
    quoted = W.quote(direction_words)
    if W.says_same(direction_words):
        anchor, anchor_text = _anchor(ti, ctx)
        return Decision(anchor.stud_id, f"{quoted} as {anchor_text} -> stud {anchor.stud_id}")
    direction = W.direction_of(direction_words, quoted, "stud")
    count = W.count_in(direction_words) or 1
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
    trace = trace if trace is not None else Trace()
    if ti.has("St_loc2"):
        message = (f"{W.quote(ti.words_with('St_loc2'))} says which stud to count from, but not how far or in "
                   "which direction: which stud should it go on?")
    else:
        message = ("The instruction does not say which stud the panel goes on: give the stud's id "
                   "(\"stud 500107\") or where it is (\"the leftmost stud\", \"two to the right of 500103\").")
    return first_decision("destination", STUD_RULES, ti, ctx, trace, message).value
