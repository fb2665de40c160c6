"""Notebook 07 (from the corpus to the field), exercise "instructions of your own": reference solution.

Reference solution: try the exercise first (``check_own_instructions(MY_INSTRUCTIONS, COMMAND, tagger)`` in the
notebook says what the robot did with each of your instructions). Any three different wordings that the pipeline
carries out as intended, none moving the robot wrongly, pass.
"""
from __future__ import annotations

#: The exercise's command: panel 500321 (the 2 x 8 on top of the middle stack) on stud 500104, upright with its
#: edge on the stud's centre line (as the notebook's exercise cell gives it to the check).
COMMAND = {"drywall_id": "500321", "stud_id": "500104", "placement": "vertical_middle"}

#: Three different wordings of ``COMMAND``: by size, by panel id, and a polite question in other words.
MY_INSTRUCTIONS = [
    "Put the 2 by 8 panel on stud 500104 on the centre line.",
    "panel 500321 to stud 500104, centre line",
    "Could you hang the two by eight on stud 500104 with its edge on the center line?",
]

#: Notebook 07 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
