"""What an exercise check says, for every notebook's exercises (the course's, robot control's, the field's).

:class:`ExerciseCheck` is the result of a check: passed or not, and a message a line saying what is right, or
what is not and why. An exercise the student has not attempted yet (the notebook's stub left as it is) is
neither: :meth:`ExerciseCheck.not_attempted` says what to fill in, is printed as ``NOT ATTEMPTED YET: ...`` and
has ``attempted`` false, so that a notebook cell may ``assert check.passed or not check.attempted`` and run
through untouched. :func:`is_unattempted` recognises a stub: ``...`` (Ellipsis), a list of nothing but ``...``,
a function that raises ``NotImplementedError``, and ``None`` where an exercise says so.
:func:`call_student` runs a student's function and reports an error instead of raising it.
This module imports nothing of the project, so that library modules (``drywall_lab.field``,
``drywall_lab.rc.exercises``) and ``drywall_lab.course`` may all use it.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

#: What a stub's body raises: ``raise NotImplementedError("your code here")``.
STUB_ERROR = NotImplementedError


@dataclass
class ExerciseCheck:
    """What a check found: ``passed``, and one message a line saying what is right, or what is not and why.

    ``attempted`` is false only for an exercise still at its stub (:meth:`not_attempted`): not passed, and not
    failed either, so a notebook runs through with the exercise left for the student.
    """

    passed: bool
    messages: list[str] = field(default_factory=list)
    attempted: bool = True

    @classmethod
    def not_attempted(cls, what: str, solution: str | None = None, **extra: Any) -> "ExerciseCheck":
        """The check of an exercise still at its stub: "fill in ``what``", and where its reference solution is.

        ``extra`` goes to a subclass's own fields (``SimulationCheck``'s ``result``, ``run``).
        """
        messages = [f"fill in {what}, then run the cell again"]
        if solution:
            messages.append(f"stuck? the reference solution is in {solution}; try the exercise first")
        return cls(False, messages, attempted=False, **extra)

    @property
    def status(self) -> str:
        """``PASSED``, ``NOT YET`` (attempted, not right yet) or ``NOT ATTEMPTED YET`` (the stub)."""
        if not self.attempted:
            return "NOT ATTEMPTED YET"
        return "PASSED" if self.passed else "NOT YET"

    def __str__(self) -> str:
        return "\n".join([self.status + ":"] + [f"- {m}" for m in self.messages])


def is_unattempted(answer: Any, *probe: Any, none: bool = False) -> bool:
    """Whether a student's ``answer`` is still the exercise's stub.

    A stub is ``...`` (Ellipsis); a list or tuple of nothing but ``...`` (``[...]``, the skeleton of a list to
    fill); ``None`` when ``none`` is true (where an exercise documents it); or a function that raises
    ``NotImplementedError`` when called on ``probe`` (the check's first case), which is also how a function whose
    body is still ``...`` counts when ``none`` is true (it returns ``None``). Any other error of the student's
    function is not a stub but a mistake, for the check to report.
    """
    if answer is Ellipsis or (none and answer is None):
        return True
    if isinstance(answer, (list, tuple)):
        return bool(answer) and all(a is Ellipsis for a in answer)
    if callable(answer) and probe:
        try:
            result = answer(*probe)
        except STUB_ERROR:
            return True
        except Exception:  # noqa: BLE001 - a mistake, not a stub: the check reports it
            return False
        return none and result is None
    return False


def call_student(function: Callable, *args: Any) -> tuple[Any, str | None]:
    """The student's function called on ``args``: (its result, None), or (None, what it raised)."""
    try:
        return function(*args), None
    except Exception as e:  # noqa: BLE001 - any error in a student's code is reported, not raised
        return None, f"{type(e).__name__}: {e}"
