"""What every chapter's helpers share (notebooks 01-07): the repository's root, fast mode, the exercise checks'
result, percentages in tables and figures shown small enough to commit.

``fast_mode`` and ``ExerciseCheck`` live in library modules (``drywall_lab.fast``, ``drywall_lab.exercise``) that
import nothing of the course, so that library modules may use them; they are re-exported here for the notebooks.
"""
from __future__ import annotations

import io
from pathlib import Path
from typing import TYPE_CHECKING, Sequence

import pandas as pd

from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted
from drywall_lab.fast import FAST_OFF, FAST_ON, fast_mode

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["BENCHMARK_RESULTS", "ExerciseCheck", "FAST_OFF", "FAST_ON", "REPO_ROOT", "SHARE_COLUMNS", "STUDY_DIR",
           "call_student", "compact_figures", "compact_png", "fast_mode", "is_unattempted", "percent_table", "solution_file"]

#: The repository root: the study's results, the benchmarks and the annotation guidelines live there.
REPO_ROOT = Path(__file__).resolve().parent.parent.parent
#: Where ``python -m drywall_lab experiment paper`` writes the study (``--out results/paper``).
STUDY_DIR = REPO_ROOT / "results" / "paper"
#: The benchmarks' recorded results.
BENCHMARK_RESULTS = REPO_ROOT / "benchmarks" / "results"


#: Colours of the palette a notebook's figures are shown with (:func:`compact_figures`).
FIGURE_COLOURS = 256


def compact_png(fig: Figure, colours: int = FIGURE_COLOURS) -> bytes:
    """``fig`` as the notebook's inline backend draws it (its own resolution, tight bounding box), as a PNG of at most
    ``colours`` colours: an adaptive palette without dithering, which keeps a plot's flat colours and lines exact
    enough to read and takes about a third of the bytes of full colour."""
    from PIL import Image

    drawn = io.BytesIO()
    fig.savefig(drawn, format="png", dpi=fig.dpi, bbox_inches="tight", facecolor=fig.get_facecolor(),
                edgecolor=fig.get_edgecolor())
    image = Image.open(drawn).convert("RGB").quantize(colors=colours, method=Image.Quantize.MEDIANCUT,
                                                      dither=Image.Dither.NONE)
    out = io.BytesIO()
    image.save(out, format="PNG", optimize=True)
    return out.getvalue()


def compact_figures(colours: int = FIGURE_COLOURS) -> bool:
    """Show this notebook's matplotlib figures with :func:`compact_png`, so that a committed notebook with its outputs
    stays small (the course keeps each under 1 MB). Call it once, after ``%matplotlib inline``; it returns whether it
    took effect (``False`` outside IPython, where there is nothing to show)."""
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    shell = get_ipython()
    if shell is None:
        return False
    from matplotlib.figure import Figure

    shell.display_formatter.formatters["image/png"].for_type(Figure, lambda fig: compact_png(fig, colours))
    return True


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
