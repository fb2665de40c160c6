"""Information mapping (the paper's IM module, Figs. 9-12; the case study's rules).

Tagged words plus the building component tables and the action history become a
robot command, or a refusal a worker understands, with a trace of every rule.

- ``words``: reading numbers, ordinals, directions and anchors as people say them;
- ``correction``: the final intention counts: tagged words that a change of mind takes back ("the second from
  the right, no, the fourth") are read as ``O`` before any rule;
- ``target``: which panel (Figs. 10 and 11); ``stud``: which stud (Fig. 12);
  ``placement``: how it goes on;
- ``command``: ``RobotCommand``; ``history``: ``ActionHistory``;
- ``mapper``: ``interpret``, ``InformationMapper`` and the corpus's task accuracy.

The rules in full
-----------------
The rules apply in order, the first that applies deciding: the target from an ``ID_wall`` id, then
``width``/``length`` numbers (tried turned when nothing matches as said; one number fitting two sizes is
refused as ambiguous), then a ``dim`` size word or back-reference, then ``Dw_loc1`` alone (a stack position),
then ``Dw_loc1`` + ``Dw_loc2`` (counted from an anchor panel's stack); the stud from ``ID_stud`` (where
position words name a stud too, "the far left stud, 500100", they must name the same one: two different studs
are refused as ``undetermined``, with a question naming both), then ``St_loc1`` alone, then ``St_loc1`` +
``St_loc2``; the placement from ``Vr_md``/``Hr_top``/``Hr_btm``, the default otherwise. Then two checks on the
site: the panel can be picked (on top of its stack, not installed) and it fits (inside the wall, no overlap).
Each refusal has one of the reason codes of ``drywall_lab.errors.REFUSAL_REASONS`` and a message for the
worker ("Panel 500300 is under 500310 and 500320 in the left stack; only the top panel, 500320, can be
picked.").

No word is silently dropped: an ordinal with a side but no "from" ("the third stud left"), a relative position
without an anchor, a lone "size" and an anchor that names no stud are refused as ``undetermined`` with a
question; an anchor named by its place on the wall is read as rule 2 reads it ("three left of the centre
stud"), and a step may be said as an order along the wall, the studs being numbered from the left ("two past
500104", "the stud before the last one"; ``words.ORDER_WORDS``); "zero", "0" and "same" are 0 places (for
stacks too: "the same stack as the previous one").

Field language is read as the annotation guidelines' section 4.7 says: "same stud" or "where the last one
went" alone is the previous stud, an id read out digit by digit is one id, so is a possessive one ("500104's
centre line"), "another of those" and "ditto" point back, so does a pointing word as the anchor of a relative
position ("two right of that/St_loc2 one", "of where/St_loc2 you put it", "the pile that/Dw_loc2 one
came/Dw_loc2 from"), short written forms (``frm``, ``b4``, ``lft``, ``ctr``) are spelt out, a word that only
points back ("another", "one of those", "again") is no size when other words name the panel ("another 2x8" is
the 2x8; "same size as the last one" always is one), and a row word naming a place in a stack ("off the top
of the middle pile", "the top sheet", "the top 2x8") is no row (read as ``O``, trace step ``R0 place in a
stack``).

**Only the final intention counts** (``drywall_lab/im/correction.py``, guidelines 4.7): when a tagger has
tagged the abandoned words of a change of mind too ("the second/St_loc1 stud from/St_loc1 the/St_loc1
right/St_loc1 No the fourth/St_loc1 from/St_loc1 the/St_loc1 right/St_loc1"), the words of the same part said
before the correction words (``no``, ``wait``, ``actually``, ``sorry``, ``scratch that``, ``I mean``, ...) are
read as ``O``, provided the correction says them again within four words (a bare count replaces only the
count: "two studs right of 500104, wait no, three"). The trace's first step (``R0 final intention``) names
what was taken back. With gold tags every instruction of every split, the field corpus and the hand-written
field set included, gives its intended command or refusal (tested); notebook 04 shows the traces, the tricky
cases, every refusal and the paper's layouts step by step.
"""
from drywall_lab.errors import REFUSAL_REASONS, Refusal
from drywall_lab.im.command import HISTORY_FIELDS, RobotCommand
from drywall_lab.im.context import MappingContext
from drywall_lab.im.history import ActionHistory
from drywall_lab.im.mapper import (InformationMapper, Interpretation, interpret, interpret_row, task_accuracy,
                                   task_correct)
from drywall_lab.im.placement import resolve_placement
from drywall_lab.im.stud import STUD_RULES, resolve_stud
from drywall_lab.im.target import TARGET_RULES, resolve_target
from drywall_lab.im.trace import TaggedInstruction, Trace, TraceStep

__all__ = [
    "ActionHistory", "HISTORY_FIELDS", "InformationMapper", "Interpretation", "MappingContext", "REFUSAL_REASONS",
    "Refusal", "RobotCommand", "STUD_RULES", "TARGET_RULES", "TaggedInstruction", "Trace", "TraceStep", "interpret",
    "interpret_row", "resolve_placement", "resolve_stud", "resolve_target", "task_accuracy", "task_correct",
]
