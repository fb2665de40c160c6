"""What every chapter's helpers share (notebooks 01-07): the repository's root, fast mode, the exercise checks'
result and percentages in tables.

``fast_mode`` and ``ExerciseCheck`` live in library modules (``drywall_lab.fast``, ``drywall_lab.exercise``) that
import nothing of the course, so that library modules may use them; they are re-exported here for the notebooks.
"""
from __future__ import annotations

from pathlib import Path
from typing import Sequence

import pandas as pd

from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted
from drywall_lab.fast import FAST_OFF, FAST_ON, fast_mode

__all__ = ["BENCHMARK_RESULTS", "ExerciseCheck", "FAST_OFF", "FAST_ON", "REPO_ROOT", "SHARE_COLUMNS", "STUDY_DIR",
           "call_student", "fast_mode", "is_unattempted", "percent_table", "solution_file"]

#: The repository root: the study's results, the benchmarks and the annotation guidelines live there.
REPO_ROOT = Path(__file__).resolve().parent.parent.parent
#: Where ``python -m drywall_lab experiment paper`` writes the study (``--out results/paper``).
STUDY_DIR = REPO_ROOT / "results" / "paper"
#: The benchmarks' recorded results.
BENCHMARK_RESULTS = REPO_ROOT / "benchmarks" / "results"



def solution_file(chapter: int) -> str:
    """Where notebook ``chapter``'s reference solution and answer keys are, as the checks name it:
    ``drywall_lab/course/solutions/ch01.py`` for notebook 01."""
    return f"drywall_lab/course/solutions/ch{chapter:02d}.py"


#: The share columns of a Table 3 row, shown as percentages.
SHARE_COLUMNS = ("Acc_word", "Acc_inst", "acc_task")


def percent_table(frame: pd.DataFrame, columns: Sequence[str] = SHARE_COLUMNS, digits: int = 2) -> pd.DataFrame:
    """A copy of ``frame`` with the share ``columns`` (those it has) written as percentages, e.g. ``"99.37%"``.

    Unlike a pandas ``Styler``, the result reads the same as HTML and as text (``print``, a terminal, nbval).
    """
    out = frame.copy()
    for column in columns:
        if column in out:
            out[column] = [f"{v:.{digits}%}" if pd.notna(v) else "" for v in out[column]]
    return out
