"""The course's exercises as the student meets them (issue 31): each notebook's exercise cell is a stub, its check
says "NOT ATTEMPTED YET" for it and lets the notebook run on, the reference solution kept apart in
``drywall_lab.course.solutions`` passes, and a wrong answer fails with a message that says why.

The checks' many wrong answers are tried in ``tests/test_course.py`` (01-04), ``tests/test_rc.py`` (05, 06) and
``tests/test_field.py`` (07); here one wrong answer a check, next to the solution and the stub.
"""
from __future__ import annotations

import ast
import contextlib
import importlib
import inspect
import io
import re
from pathlib import Path

import nbformat
import pytest

from drywall_lab import course
from drywall_lab.exercise import ExerciseCheck, is_unattempted
from drywall_lab.rc import exercises as rc_exercises
from drywall_lab.rc.exercises import SimulationCheck

ROOT = Path(__file__).resolve().parent.parent
#: Every notebook's chapter number and file, and the names its solution module gives the solution objects.
NOTEBOOKS = {
    1: ("01_annotation.ipynb", ("MY_ANSWER",)),
    2: ("02_bilstm_crf.ipynb", ("most_forbidden",)),
    3: ("03_bert.ipynb", ("my_vote",)),
    4: ("04_information_mapping.ipynb", ("relative_stud",)),
    5: ("05_robot_control.ipynb", ("softer", "KP_SCALE")),
    6: ("06_end_to_end.ipynb", ("MY_INSTRUCTIONS",)),
    7: ("07_corpus_to_field.ipynb", ("MY_INSTRUCTIONS",)),
}
STUB_MARKER = "# your code here"
STUB_ASSERT = "assert check.passed or not check.attempted"


def solution(chapter: int):
    return importlib.import_module(f"drywall_lab.course.solutions.ch{chapter:02d}")


def _raise_stub(*args):
    raise NotImplementedError("your code here")


def _dots_stub(*args):
    ...


def _not_attempted(check: ExerciseCheck, chapter: int) -> None:
    """What every check says of a stub: not passed, not attempted, "NOT ATTEMPTED YET: fill in ...", and where the
    chapter's reference solution is."""
    text = str(check)
    assert not check.passed and not check.attempted and check.status == "NOT ATTEMPTED YET", text
    assert text.startswith("NOT ATTEMPTED YET:\n- fill in "), text
    assert course.solution_file(chapter) in text, text


@pytest.fixture(scope="module")
def tagger():
    from drywall_lab.nlu import default_tagger

    return default_tagger()


# --- the result and the stub, generically ----------------------------------------------------------------------------
def test_exercise_check_not_attempted_is_neither_passed_nor_failed():
    check = ExerciseCheck.not_attempted("my_answer", "somewhere.py")
    assert (check.passed, check.attempted) == (False, False)
    assert str(check) == ("NOT ATTEMPTED YET:\n- fill in my_answer, then run the cell again\n"
                          "- stuck? the reference solution is in somewhere.py; try the exercise first")
    assert check.passed or not check.attempted  # what a notebook's exercise cell asserts
    # existing callers: a check built as before is an attempt, printed as before
    assert ExerciseCheck(True, ["right"]).attempted and str(ExerciseCheck(True, ["right"])) == "PASSED:\n- right"
    assert str(ExerciseCheck(False, ["wrong"])) == "NOT YET:\n- wrong"
    simulated = SimulationCheck.not_attempted("softer")
    assert isinstance(simulated, SimulationCheck) and simulated.result is None and simulated.run is None
    assert simulated.messages == ["fill in softer, then run the cell again"]


def test_is_unattempted_knows_the_stubs_and_nothing_else():
    assert is_unattempted(...) and is_unattempted([...]) and is_unattempted((..., ...))
    assert is_unattempted(None, none=True) and not is_unattempted(None)
    assert is_unattempted(_raise_stub, 1, 2)
    assert is_unattempted(_dots_stub, 1, none=True) and not is_unattempted(_dots_stub, 1)  # None where documented
    assert not is_unattempted(lambda x: 1 / x, 0)  # another error is a mistake, for the check to report
    assert not is_unattempted(lambda x: x, 1, none=True)
    assert not is_unattempted(_raise_stub)  # a function is only judged on the check's first case
    for answer in ("...", "", [], ["an instruction", ...], 0, 0.1, False):
        assert not is_unattempted(answer, none=True), answer


# --- notebook 01 -------------------------------------------------------------------------------------------------
def test_01_solution_passes_stub_is_not_attempted_wrong_fails():
    assert course.check_tagging(solution(1).MY_ANSWER).passed
    for stub in (..., None):
        _not_attempted(course.check_tagging(stub), 1)
    wrong = course.check_tagging(solution(1).MY_ANSWER.replace("right/St_loc1", "right/Dw_loc1"))
    assert not wrong.passed and wrong.attempted
    assert "'right': you tagged Dw_loc1, the guidelines say St_loc1" in str(wrong)


# --- notebook 02 -------------------------------------------------------------------------------------------------
def test_02_solution_passes_stub_is_not_attempted_wrong_fails(tagger):
    check = course.check_most_forbidden(solution(2).most_forbidden, tagger)
    assert check.passed and "the trained tagger's transitions, k = 5: right" in str(check)
    for stub in (_raise_stub, _dots_stub, ...):
        _not_attempted(course.check_most_forbidden(stub), 2)
    wrong = course.check_most_forbidden(lambda t, k: list(t.stack().nlargest(k).index))
    assert not wrong.passed and wrong.attempted and "forbidden means lowest" in str(wrong)


# --- notebook 03 -------------------------------------------------------------------------------------------------
def test_03_solution_passes_stub_is_not_attempted_wrong_fails():
    assert course.check_vote(solution(3).my_vote).passed
    for stub in (_raise_stub, _dots_stub, ...):
        _not_attempted(course.check_vote(stub), 3)

    def first_token(tags, word_ids, n_words):
        return [next((t for t, w in zip(tags, word_ids) if w == i), "O") for i in range(n_words)]

    wrong = course.check_vote(first_token)
    assert not wrong.passed and wrong.attempted and "more than half, not ID_wall" in str(wrong)


# --- notebook 04 -------------------------------------------------------------------------------------------------
def test_04_solution_passes_stub_is_not_attempted_wrong_fails():
    assert course.check_relative_stud(solution(4).relative_stud).passed
    for stub in (_raise_stub, ...):
        _not_attempted(course.check_relative_stud(stub), 4)
    nothing = course.check_relative_stud(_dots_stub)  # None is a real answer here (past the wall's end)
    assert not nothing.passed and nothing.attempted and "only a step past either end gives None" in str(nothing)


# --- notebook 05 -------------------------------------------------------------------------------------------------
def test_05_solution_passes():
    check = rc_exercises.check_servo_gains(solution(5).softer, solution(5).KP_SCALE)
    assert check.passed and check.result.success, str(check)


def test_05_stub_is_not_attempted_and_wrong_gains_fail_without_simulating(monkeypatch):
    monkeypatch.setattr(rc_exercises, "RobotCell", None)  # nothing may be simulated here
    softer = solution(5).softer
    for stub_softer, stub_scale in ((_raise_stub, ...), (_dots_stub, ...), (_raise_stub, 0.1), (softer, ...),
                                    (softer, None)):
        check = rc_exercises.check_servo_gains(stub_softer, stub_scale)
        _not_attempted(check, 5)
        assert check.result is None
    assert "softer() is right" in str(rc_exercises.check_servo_gains(softer, ...))
    assert "KP_SCALE" in str(rc_exercises.check_servo_gains(_raise_stub, ...))
    kv_like_kp = rc_exercises.check_servo_gains(lambda g, s: type(g)(g.kp * s, g.kv * s, g.force), ...)
    assert not kv_like_kp.passed and kv_like_kp.attempted and "square root" in str(kv_like_kp)


# --- notebook 06 -------------------------------------------------------------------------------------------------
def test_06_solution_builds_the_wall(tagger):
    check = rc_exercises.check_layout(solution(6).MY_INSTRUCTIONS, tagger)
    assert check.passed and check.run.all_placed, str(check)


def test_06_stub_is_not_attempted_and_wrong_fails_without_running_the_robot(tagger, monkeypatch):
    monkeypatch.setattr(rc_exercises, "simulate_episode", None)
    for stub in ([...], ..., None):
        _not_attempted(rc_exercises.check_layout(stub, None), 6)  # no tagger needed for a stub
    half = rc_exercises.check_layout(solution(6).MY_INSTRUCTIONS[:2], tagger)
    assert not half.passed and half.attempted and "still missing" in str(half)
    placeholder = rc_exercises.check_layout(solution(6).MY_INSTRUCTIONS[:3] + [...], tagger)
    assert not placeholder.passed and "replace every ... with an instruction" in str(placeholder)


# --- notebook 07 -------------------------------------------------------------------------------------------------
def test_07_solution_passes_stub_is_not_attempted_wrong_fails(tagger, monkeypatch):
    from drywall_lab import field

    ch07 = solution(7)
    assert field.check_own_instructions(ch07.MY_INSTRUCTIONS, ch07.COMMAND, tagger).passed
    for stub in ([...], ..., None):
        _not_attempted(field.check_own_instructions(stub, ch07.COMMAND), 7)  # the default tagger is not loaded
    wrong = field.check_own_instructions(ch07.MY_INSTRUCTIONS[:2] + ["panel 500321 to stud 500105, centre line"],
                                         ch07.COMMAND, tagger)
    assert not wrong.passed and wrong.attempted and "MOVED THE ROBOT WRONGLY" in str(wrong)
    unfinished = field.check_own_instructions(ch07.MY_INSTRUCTIONS[:2] + [...], ch07.COMMAND, tagger)
    assert not unfinished.passed and "at least 3 different instructions; there are 2" in str(unfinished)


# --- the committed notebooks -------------------------------------------------------------------------------------
def _cells(chapter: int):
    return nbformat.read(ROOT / "notebooks" / NOTEBOOKS[chapter][0], as_version=4).cells


def _exercise_cell(chapter: int) -> tuple[int, str]:
    """(index, source) of the notebook's one exercise cell: the code cell with the stub marker."""
    found = [(i, c.source) for i, c in enumerate(_cells(chapter)) if c.cell_type == "code" and STUB_MARKER in c.source]
    assert len(found) == 1, f"notebook {chapter:02d}: {len(found)} code cells with {STUB_MARKER!r}"
    return found[0]


def _solution_fragments(chapter: int) -> list[str]:
    """What of the reference solution must not be in the exercise cell: each code line of a solution function's
    body (docstring and comments left out, short lines such as ``return out`` too), each tagged word of a tagged
    answer, each instruction of a list, the value of a number."""
    module = solution(chapter)
    fragments = []
    for name in NOTEBOOKS[chapter][1]:
        value = getattr(module, name)
        if callable(value):
            function = ast.parse(inspect.getsource(value)).body[0]
            body = function.body[1:] if ast.get_docstring(function) else function.body
            for statement in body:
                for line in ast.unparse(statement).splitlines():
                    if len(line.strip()) >= 12:
                        fragments.append(line.strip())
        elif isinstance(value, str):
            fragments += [w for w in value.split() if "/" in w] or [value]
        elif isinstance(value, list):
            fragments += value
        else:
            fragments.append(f"= {value!r}")
    assert fragments
    return fragments


@pytest.mark.parametrize("chapter", sorted(NOTEBOOKS))
def test_the_committed_exercise_cell_is_a_stub_without_the_solution(chapter):
    index, source = _exercise_cell(chapter)
    assert STUB_ASSERT in source and "assert check.passed\n" not in source + "\n"
    assert "..." in source or "raise NotImplementedError" in source
    normalised = "\n".join(line.strip() for line in source.splitlines()).replace('"', "'")
    for fragment in _solution_fragments(chapter):
        assert fragment.replace('"', "'") not in normalised, \
            f"notebook {chapter:02d}'s exercise cell holds the solution: {fragment!r}"
    cell = _cells(chapter)[index]  # committed as executed in full mode: the stub's check says it is not attempted
    printed = "".join(o.get("text", "") for o in cell.outputs if o.get("output_type") == "stream")
    assert all(o.get("output_type") == "stream" for o in cell.outputs)
    assert not cell.outputs or "NOT ATTEMPTED YET:\n- fill in " in printed, printed


@pytest.mark.parametrize("chapter", sorted(NOTEBOOKS))
def test_the_markdown_above_the_exercise_says_where_the_solution_is(chapter):
    index, _ = _exercise_cell(chapter)
    above = next(c for c in reversed(_cells(chapter)[:index]) if c.cell_type == "markdown")
    assert f"`{course.solution_file(chapter)}`" in above.source and "try the exercise first" in above.source


#: What each exercise cell needs from the cells before it, for its stub: the checks, and for 02, 06 and 07 a
#: tagger (none: a stub is answered before any tagger is used).
def _namespace(chapter: int) -> dict:
    from drywall_lab.field import check_own_instructions
    from drywall_lab.rc import ServoGains

    return {"check_tagging": course.check_tagging, "check_most_forbidden": course.check_most_forbidden,
            "check_vote": course.check_vote, "check_relative_stud": course.check_relative_stud,
            "check_servo_gains": rc_exercises.check_servo_gains, "SOFTEST_ASKED": rc_exercises.SOFTEST_ASKED,
            "ServoGains": ServoGains, "check_layout": rc_exercises.check_layout,
            "check_own_instructions": check_own_instructions, "tagger": None}


@pytest.mark.parametrize("chapter", sorted(NOTEBOOKS))
def test_the_committed_stub_runs_and_says_not_attempted(chapter, monkeypatch):
    monkeypatch.setattr(rc_exercises, "RobotCell", None)  # a stub is never simulated
    monkeypatch.setattr(rc_exercises, "simulate_episode", None)
    _, source = _exercise_cell(chapter)
    namespace = _namespace(chapter)
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(compile(source, f"notebook {chapter:02d}'s exercise cell", "exec"), namespace)  # noqa: S102
    _not_attempted(namespace["check"], chapter)
    assert "NOT ATTEMPTED YET:\n- fill in" in printed.getvalue()
    if chapter == 2:  # the cells after it use most_forbidden: the library's stands in for the stub
        assert namespace["most_forbidden"] is course.reference_most_forbidden


def _questions(chapter: int) -> list[int]:
    """The numbers of the questions in the notebook's closing "**Questions.**" cell (none: no such cell)."""
    cells = [c.source for c in _cells(chapter) if c.cell_type == "markdown" and "**Questions.**" in c.source]
    if not cells:
        return []
    return [int(n) for n in re.findall(r"^(\d+)\. ", cells[-1].split("**Questions.**", 1)[1], flags=re.M)]


@pytest.mark.parametrize("chapter", sorted(NOTEBOOKS))
def test_each_question_has_an_answer_key(chapter):
    answers = solution(chapter).ANSWERS
    assert sorted(answers) == _questions(chapter)
    assert all(isinstance(a, str) and len(a.split()) >= 30 for a in answers.values())
    assert solution(chapter).__doc__ and "try the exercise first" in solution(chapter).__doc__


def test_notebooks_02_and_03_end_with_four_questions():
    assert _questions(2) == _questions(3) == [1, 2, 3, 4]


def test_the_course_does_not_import_the_solutions():
    """``from drywall_lab.course import ...`` in a notebook does not bring the solutions in."""
    import subprocess
    import sys

    code = ("import sys, drywall_lab.course; "
            "print(any(m.startswith('drywall_lab.course.solutions') for m in sys.modules))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert done.stdout.strip() == "False", done.stderr[-2000:]
