"""Notebook 04 (information mapping), exercise "rule S3 of Fig. 12 yourself": reference solution.

Reference solution: try the exercise first (``check_relative_stud(relative_stud)`` in the notebook compares your
answer with the project's rules on every anchor, both directions and counts past the wall's end).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from drywall_lab.site import Site


def relative_stud(site: "Site", anchor_id: str, direction: str, count: int) -> str | None:
    """The id of the stud ``count`` places to the ``direction`` (``"left"``: lower ids, ``"right"``: higher) of
    the anchor stud, the anchor itself for ``count`` 0, ``None`` past either end of the wall."""
    ids = site.stud_ids
    index = ids.index(anchor_id) + (count if direction == "right" else -count)
    return ids[index] if 0 <= index < len(ids) else None  # the lower bound: a negative index counts from the end


#: Notebook 04 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
