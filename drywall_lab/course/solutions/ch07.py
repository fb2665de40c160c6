"""Notebook 07 (from the corpus to the field), exercises "instructions of your own" and "the least expected cost
from scratch": reference solutions.

Reference solutions: try the exercise first (``check_own_instructions(MY_INSTRUCTIONS, COMMAND, tagger)`` in the
notebook says what the robot did with each of your instructions; any three different wordings that the pipeline
carries out as intended, none moving the robot wrongly, pass. ``check_expected_cost(least_expected_cost, example)``
compares your decision with the library's on the worked example and on many random cases).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Mapping

if TYPE_CHECKING:
    from drywall_lab.decision import DecisionCosts

#: The exercise's command: panel 500321 (the 2 x 8 on top of the middle stack) on stud 500104, upright with its
#: edge on the stud's centre line (as the notebook's exercise cell gives it to the check).
COMMAND = {"drywall_id": "500321", "stud_id": "500104", "placement": "vertical_middle"}

#: Three different wordings of ``COMMAND``: by size, by panel id, and a polite question in other words.
MY_INSTRUCTIONS = [
    "Put the 2 by 8 panel on stud 500104 on the centre line.",
    "panel 500321 to stud 500104, centre line",
    "Could you hang the two by eight on stud 500104 with its edge on the center line?",
]


def least_expected_cost(probabilities: Mapping[str, float], costs: "DecisionCosts",
                        option_floor: float) -> tuple[str, Any, float]:
    """The action of least expected cost (step 3 of ``drywall_lab.decision``): ``("act", command, cost)``,
    ``("ask", options, cost)`` or ``("refuse", None, cost)``; ``probabilities`` holds each command's probability,
    what is left of 1 is no command. On a tie, the more careful action: refuse, then ask, then act."""
    commands = sorted(probabilities, key=lambda c: -probabilities[c])
    p_commands = sum(probabilities.values())
    refuse = costs.refuse * p_commands
    if not commands:
        return "refuse", None, refuse
    best = commands[0]
    options = [c for c in commands if probabilities[c] >= option_floor][:3] or [best]
    act = costs.wrong * (1.0 - probabilities[best])
    ask = costs.ask + costs.refuse * (p_commands - sum(probabilities[c] for c in options))
    if refuse <= ask and refuse <= act:
        return "refuse", None, refuse
    if ask <= act:
        return "ask", options, ask
    return "act", best, act


#: Notebook 07 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
