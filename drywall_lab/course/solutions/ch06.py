"""Notebook 06 (end to end), exercise "a wall of your own": reference solution.

Reference solution: try the exercise first (``check_layout(my_instructions, tagger)`` in the notebook says which
panel each of your instructions puts where, or why it was refused, and what the tagger read). Many other
wordings build the wall too: sizes, stack positions and studs counted from others instead of ids.
"""
from __future__ import annotations

#: One instruction per panel of ``drywall_lab.rc.exercises.EXERCISE_WALL``, in an order the stacks allow.
MY_INSTRUCTIONS = [
    "Pick up the full-size drywall and put it on stud 500100 in the bottom row.",
    "Take the 4 by 6 panel. Put it on the first stud in the top row.",
    "Pick up the standard panel and put it on stud 500106.",
    "Grab the drywall from the middle stack and hang it on stud 500109 on the center line.",
]

#: Notebook 06 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
