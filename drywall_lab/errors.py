"""The one exception a worker sees when an instruction cannot be carried out.

The case study's refusals (spec section 5) each have a short reason code, so that
scripts and tests can tell them apart, and a message written for the worker who
gave the instruction. Nothing in the action history or the site changes when a
``Refusal`` is raised.
"""
from __future__ import annotations

#: Every reason code a refusal can carry, with what it means.
REFUSAL_REASONS: dict[str, str] = {
    "undetermined": "the target, the destination or a placement cannot be read from the tags",
    "unknown_id": "a panel or stud id that is not on this site",
    "off_the_end": "a relative position runs past the first or last stack or stud",
    "ambiguous_size": "a size that fits more than one kind of panel",
    "no_matching_size": "a size that fits no panel on this site",
    "stack_empty": "the stack that holds the wanted panel is empty",
    "no_history": "'previous' or 'last' is used before anything has been installed",
    "already_installed": "the panel is already on the wall",
    "not_on_top": "the panel is under other panels in its stack",
    "past_wall_end": "the panel would reach past the last stud",
    "overlap": "the panel would overlap a panel already on the wall",
    "unclear": "the words allow more than one command, or the tagger is not sure of a word the command depends on: "
               "the message asks one question (drywall_lab.decision)",
}


class Refusal(Exception):
    """An instruction the robot will not carry out, with a ``reason`` code and a message.

    >>> r = Refusal("not_on_top", "Panel 500300 is under 500310 and 500320 in the left stack.")
    >>> r.reason, str(r)
    ('not_on_top', 'Panel 500300 is under 500310 and 500320 in the left stack.')
    """

    def __init__(self, reason: str, message: str) -> None:
        if reason not in REFUSAL_REASONS:
            raise ValueError(f"unknown refusal reason {reason!r}; expected one of {sorted(REFUSAL_REASONS)}")
        super().__init__(message)
        self.reason = reason
        self.message = message

    def __repr__(self) -> str:
        return f"Refusal({self.reason!r}, {self.message!r})"
