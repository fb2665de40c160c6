"""Notebook 06 (end to end), exercises "a wall of your own" and, from scratch, "where a panel covers the wall":
reference solutions.

Reference solutions: try the exercise first (``check_layout(my_instructions, tagger)`` in the notebook says which
panel each of your instructions puts where, or why it was refused, and what the tagger read; ``check_panel_rect
(panel_rect)`` compares your rectangle with the site's own on every panel, stud and placement). Many other
wordings build the wall too: sizes, stack positions and studs counted from others instead of ids.
"""
from __future__ import annotations

from drywall_lab.site import WALL_HEIGHT, Panel, Placement, Rect, Stud

#: One instruction per panel of ``drywall_lab.rc.exercises.EXERCISE_WALL``, in an order the stacks allow.
MY_INSTRUCTIONS = [
    "Pick up the full-size drywall and put it on stud 500100 in the bottom row.",
    "Take the 4 by 6 panel. Put it on the first stud in the top row.",
    "Pick up the standard panel and put it on stud 500106.",
    "Grab the drywall from the middle stack and hang it on stud 500109 on the center line.",
]


def panel_rect(panel: Panel, stud: Stud, placement: Placement) -> Rect:
    """From scratch: where ``panel`` covers the wall when put on ``stud`` (the paper's Fig. 6).

    The left edge is on the stud's centre line for vertical_middle, on its left line otherwise; a vertical panel
    stands on its short side (w across, l up), a horizontal one lies on its long side (l across, w up), in the
    top row (hanging from the wall's height) or the bottom row (on the floor).
    """
    x_left = stud.x_center if placement == Placement.VERTICAL_MIDDLE else stud.x_left_line
    if placement in (Placement.VERTICAL_LEFT, Placement.VERTICAL_MIDDLE):
        return Rect(x_left, x_left + panel.w, 0.0, panel.l)
    if placement == Placement.HORIZONTAL_TOP:
        return Rect(x_left, x_left + panel.l, WALL_HEIGHT - panel.w, WALL_HEIGHT)
    return Rect(x_left, x_left + panel.l, 0.0, panel.w)


#: Notebook 06 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
