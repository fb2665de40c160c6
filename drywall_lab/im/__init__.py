"""Information mapping (the paper's IM module, Figs. 9-12; spec sections 3-5).

Tagged words plus the building component tables and the action history become a
robot command, or a refusal a worker understands, with a trace of every rule.

- ``words``: reading numbers, ordinals, directions and anchors as people say them;
- ``correction``: the final intention counts: tagged words that a change of mind takes back ("the second from
  the right, no, the fourth") are read as ``O`` before any rule;
- ``target``: which panel (Figs. 10 and 11); ``stud``: which stud (Fig. 12);
  ``placement``: how it goes on;
- ``command``: ``RobotCommand``; ``history``: ``ActionHistory``;
- ``mapper``: ``interpret``, ``InformationMapper`` and the corpus's task accuracy.
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
