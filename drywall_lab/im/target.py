"""Which panel to pick: the paper's Figs. 10 and 11, as spec section 3 fixes them.

Five rules, tried in order; the first that applies decides:

1. ``ID_wall``: that panel.
2. ``width`` / ``length`` numbers (feet): the stack whose size matches; "A by B" is
   width A, length B; tried turned when nothing matches as said; a single number
   that fits two sizes is ambiguous.
3. ``dim``: a size word ("full-size", "standard", "regular size") is the standard 4 x 8; a
   property ("the narrow one", "the short one"; ``data/site/size_words.csv``) is the size with
   the least or the most of a width or a length, ambiguous when two sizes share it ("the wide
   one"); a back-reference ("same as the previous one") is the size of the last installed
   panel. A lone "size" or "sized" names no size: the rule does not apply; nor does a word that only
   points back ("another", "one of those") when other words name the panel ("another 2x8").
4. ``Dw_loc1`` alone: a stack named by its position (left/middle/right, first/second/third,
   "first from the right"). What the rule cannot place with certainty is refused as
   ``undetermined``, never read by dropping a word: an ordinal with a side but no "from"
   ("the second panel from the right" with "from" untagged), a step with no anchor tagged
   ("two to the right"), a count with the middle or with "last" (``words.line_position``).
5. ``Dw_loc1`` + ``Dw_loc2``: a stack counted from an anchor (a panel id, or the
   previous panel's stack) in a direction; "zero", "0" and "same" are 0 places (the
   anchor's own stack); two counts are ``undetermined``.

Rules 2 to 5 name a stack; the panel is the one on top of it now. Each rule is a
small pure function of the tagged words and the context that returns a
``Decision`` (or ``None`` when it does not apply) or raises a ``Refusal``.
"""
from __future__ import annotations

from drywall_lab.errors import Refusal
from drywall_lab.im import words as W
from drywall_lab.im.context import MappingContext
from drywall_lab.im.trace import Decision, Rule, TaggedInstruction, Trace, first_decision
from drywall_lab.site import STACK_NAMES, size_words

SIZE_TAGS = ("width", "length")


def _size_text(size: tuple[float, float]) -> str:
    return f"{size[0]:g} x {size[1]:g}"


def _sizes_list(ctx: MappingContext, stacks: list[str]) -> str:
    names = [_size_text(ctx.site.stack_size(s)) for s in stacks]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def top_of(ctx: MappingContext, stack: str, why: str) -> Decision:
    """The panel on top of ``stack`` now; ``stack_empty`` when nothing is left in it."""
    top = ctx.state.top(stack)
    size = _size_text(ctx.site.stack_size(stack))
    if top is None:
        raise Refusal("stack_empty", f"The {stack} stack ({size} panels) is empty: all its panels are used. {why}")
    return Decision(top, f"{why} -> {stack} stack ({size}); its top panel is {top}")


def _stacks_of_size(ctx: MappingContext, width: float | None, length: float | None) -> list[str]:
    return [s for s, (w, l) in ctx.site.sizes.items()
            if (width is None or w == width) and (length is None or l == length)]


# --- rule 1 ---------------------------------------------------------------------------
def target_by_id(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 1 (Fig. 11): a word tagged ``ID_wall`` names the panel."""
    said = ti.words_with("ID_wall")
    if not said:
        return None
    panel = ctx.site.panel(W.one_id(said, "panel", "pick"))  # unknown_id for an id not on this site
    return Decision(panel.drywall_id, f"panel {panel.drywall_id} ({panel.stack} stack, {_size_text(panel.size_ft)})")


# --- rule 2 ---------------------------------------------------------------------------
def _said_size(ti: TaggedInstruction) -> tuple[float | None, float | None] | None:
    """(width, length) as said; a one-word size ("4x8") or two numbers under one tag are "A by B"."""
    widths: list[int] = []
    lengths: list[int] = []
    for word, tag in zip(ti.words, ti.tags):
        if tag not in SIZE_TAGS:
            continue
        numbers = W.numbers_in(word)
        if len(numbers) >= 2:
            return float(numbers[0]), float(numbers[1])
        (widths if tag == "width" else lengths).extend(numbers)
    widths = list(dict.fromkeys(widths))
    lengths = list(dict.fromkeys(lengths))
    if len(widths) + len(lengths) == 0:
        return None
    if not lengths and len(widths) == 2:
        return float(widths[0]), float(widths[1])
    if not widths and len(lengths) == 2:
        return float(lengths[0]), float(lengths[1])
    if len(widths) > 1 or len(lengths) > 1:
        raise Refusal("ambiguous_size", f"{W.quote(ti.phrase(*SIZE_TAGS))} gives more than one size: which panel?")
    return (float(widths[0]) if widths else None), (float(lengths[0]) if lengths else None)


def target_by_size(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 2 (Fig. 10): width and length numbers in feet pick the stack of that size."""
    if not ti.has(*SIZE_TAGS):
        return None
    size = _said_size(ti)
    if size is None:
        return None  # tagged words without a number ("wide"): leave it to the next rules
    width, length = size
    said = W.quote(ti.phrase(*SIZE_TAGS))
    for turned in (False, True):
        w, l = (length, width) if turned else (width, length)
        hits = _stacks_of_size(ctx, w, l)
        if len(hits) > 1:
            which = "both" if len(hits) == 2 else "all of"
            sizes = " and the ".join(_size_text(ctx.site.stack_size(s)) for s in hits)
            raise Refusal("ambiguous_size", f"{said} fits {which} the {sizes} panels: which one?")
        if hits:
            note = " (turned: width and length swapped)" if turned else ""
            return top_of(ctx, hits[0], f"size {said}{note}")
    raise Refusal(
        "no_matching_size",
        f"No panel on this site matches {said}; the panels are {_sizes_list(ctx, list(STACK_NAMES))} feet.",
    )


# --- rule 3 ---------------------------------------------------------------------------
def target_by_dim(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 3 (Fig. 10): "full-size"/"standard" is the 4 x 8; "same as last time" is the last panel's size.

    A lone "size" or "sized" says a size is meant but not which: the rule does not apply. Nor does a word that
    points back without saying the size is the same ("another", "one of those", "again"; ``words.says_same_size``)
    when other words name the panel ("another 2x8", "one of those from the right pile"): the guidelines tag it
    ``dim`` only when nothing else does.
    """
    said = ti.words_with("dim")
    if not said:
        return None
    quoted = W.quote(ti.phrase("dim"))
    loose = W.back_reference_words(said) and not W.says_same_size(said)
    named = W.standard_size_words(said) or W.property_size_words(said)
    if loose and (named or _named_otherwise(ti)):
        if named:  # "another full sheet", "one more narrow one": one more of the size the word names
            return _by_size_word(said, ctx, quoted)
        return None  # "another 2x8", "one of those from the right pile": the other words name the panel
    if W.back_reference_words(said):
        last = ctx.require_last(quoted)
        size = ctx.site.panel(last["drywall_id"]).size_ft
        stack = _stacks_of_size(ctx, *size)[0]
        return top_of(ctx, stack, f"{quoted}: the size of the last installed panel {last['drywall_id']} ({_size_text(size)})")
    if named:
        return _by_size_word(said, ctx, quoted)
    return None


def _by_size_word(said: list[str], ctx: MappingContext, quoted: str) -> Decision:
    """The stack the size words among ``said`` name: the standard size ("full-size"), or the size with the least or
    the most of a measure ("the narrow one": the least width; ``site.size_words``). A property two sizes share ("the
    wide one": 4 x 8 and 4 x 6) is ambiguous, like a single number that fits two sizes (rule 2); so are two words
    that name different stacks."""
    table = size_words()
    why: dict[str, str] = {}  # stack -> what named it, the first word that did
    if W.standard_size_words(said):
        why[_standard_stack(ctx)] = "the standard size"
    for word in W.property_size_words(said):
        measure, extreme = table[W.normalise(word)]
        stacks = ctx.site.stacks_with_extreme(measure, extreme)
        if len(stacks) > 1:
            raise Refusal("ambiguous_size", f"{quoted} fits more than one size ({_sizes_list(ctx, stacks)}): "
                                            "which one? Say it in feet (\"the 4 by 8\").")
        why.setdefault(stacks[0], f"the size with the {extreme} {measure}")
    if len(why) > 1:
        named = _sizes_list(ctx, sorted(why, key=STACK_NAMES.index))
        raise Refusal("ambiguous_size", f"{quoted} names more than one size ({named}): which panel?")
    (stack, reason), = why.items()
    return top_of(ctx, stack, f"{quoted}: {reason}")


def _standard_stack(ctx: MappingContext) -> str:
    return [p.stack for p in ctx.site.panels if p.size_name == "standard"][0]


def _named_otherwise(ti: TaggedInstruction) -> bool:
    """Whether words other than ``dim`` name the panel: an id, a size with a number, a stack position."""
    return (ti.has("ID_wall", "Dw_loc1")
            or any(W.numbers_in(w) for w in ti.words_with(*SIZE_TAGS)))


# --- rule 4 ---------------------------------------------------------------------------
def _stack_at(ctx: MappingContext, index: int, said: str) -> str:
    return W.on_the_row(STACK_NAMES, index, f"There is no stack {said}: there are only {len(STACK_NAMES)} stacks "
                                            f"({', '.join(STACK_NAMES)}).")


def target_by_position(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 4 (Fig. 11): ``Dw_loc1`` alone names a stack by where it is."""
    if not ti.has("Dw_loc1") or ti.has("Dw_loc2"):
        return None
    position = W.line_position(ti.words_with("Dw_loc1"), W.quote(ti.span("Dw_loc1")), len(STACK_NAMES), "stack")
    if position is None:
        return None
    index, how = position
    quoted = W.quote(ti.phrase("Dw_loc1"))
    anchor = W.unread_anchor(ti.words, ti.tags, "Dw_loc1")
    if anchor:
        raise Refusal("undetermined", f"You said {quoted} of {W.quote(anchor)}: which stack do you count from?")
    stack = _stack_at(ctx, index, quoted)
    return top_of(ctx, stack, f"{quoted}: {how}, the {stack} stack")


# --- rule 5 ---------------------------------------------------------------------------
def target_by_relative_position(ti: TaggedInstruction, ctx: MappingContext) -> Decision | None:
    """Rule 5 (Fig. 11): the stack ``count`` places left or right of an anchor panel's stack."""
    if not (ti.has("Dw_loc1") and ti.has("Dw_loc2")):
        return None
    direction_words = ti.words_with("Dw_loc1")
    anchor_words = ti.words_with("Dw_loc2")
    quoted = W.quote(direction_words)
    direction, count = W.relative_step(direction_words, quoted, "stack")
    direction = direction or "right"  # "the same stack as 500301": zero places, either way
    ids = W.ids_in(anchor_words)
    if len(ids) > 1:
        raise Refusal("undetermined", f"Two anchor panels are named, {' and '.join(ids)}: which one?")
    if ids:
        anchor = ctx.site.panel(ids[0])
        anchor_text = f"panel {anchor.drywall_id}"
    elif W.points_back(anchor_words):
        last = ctx.require_last(W.quote(anchor_words))
        anchor = ctx.site.panel(last["drywall_id"])
        anchor_text = f"the previous panel {anchor.drywall_id}"
    else:
        raise Refusal("undetermined", f"Which panel: you said {W.quote(anchor_words)}, but not which stack to count from.")
    index = STACK_NAMES.index(anchor.stack) + (count if direction == "right" else -count)
    where = (f"{W.places(count)} to the {direction} of the {anchor.stack} stack ({anchor_text})" if count
             else f"the same stack as {anchor_text}, the {anchor.stack} stack")
    stack = _stack_at(ctx, index, where)
    return top_of(ctx, stack, f"{where}: the {stack} stack")


#: The target rules in the order they are tried (spec section 3).
TARGET_RULES: tuple[Rule, ...] = (
    ("T1 panel id", ("ID_wall",), target_by_id),
    ("T2 width and length", SIZE_TAGS, target_by_size),
    ("T3 size word or same as before", ("dim",), target_by_dim),
    ("T4 stack position", ("Dw_loc1",), target_by_position),
    ("T5 relative stack position", ("Dw_loc1", "Dw_loc2"), target_by_relative_position),
)


def resolve_target(ti: TaggedInstruction, ctx: MappingContext, trace: Trace | None = None) -> str:
    """The id of the panel the instruction means, trying rules 1-5 in order; a ``Refusal`` otherwise."""
    if ti.has("Dw_loc2"):
        message = (f"{W.quote(ti.words_with('Dw_loc2'))} says which panel to count from, but not in which "
                   "direction: which panel should I pick?")
    elif W.size_words(ti.words_with("dim")):
        message = (f"{W.quote(ti.phrase('dim'))} does not say which size: give the size (\"the 4 by 8\", "
                   "\"the full-size panel\"), the panel's id, or where its stack is.")
    else:
        message = ("The instruction does not say which panel to pick: give its id, its size "
                   "(\"the 4 by 8\"), or where its stack is (\"the panel on the left\").")
    return first_decision("target", TARGET_RULES, ti, ctx, trace, message).value
