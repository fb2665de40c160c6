"""What an exercise check says, for every notebook's exercises (the course's, robot control's, the field's).

:class:`ExerciseCheck` is the result of a check: passed or not, and a message a line saying what is right, or
what is not and why. :func:`call_student` runs a student's function and reports an error instead of raising it.
This module imports nothing of the project, so that library modules (``drywall_lab.field``,
``drywall_lab.rc.exercises``) and ``drywall_lab.course`` may all use it.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable


@dataclass
class ExerciseCheck:
    """What a check found: ``passed``, and one message a line saying what is right, or what is not and why."""

    passed: bool
    messages: list[str] = field(default_factory=list)

    def __str__(self) -> str:
        return "\n".join([("PASSED" if self.passed else "NOT YET") + ":"] + [f"- {m}" for m in self.messages])


def call_student(function: Callable, *args: Any) -> tuple[Any, str | None]:
    """The student's function called on ``args``: (its result, None), or (None, what it raised)."""
    try:
        return function(*args), None
    except Exception as e:  # noqa: BLE001 - any error in a student's code is reported, not raised
        return None, f"{type(e).__name__}: {e}"
