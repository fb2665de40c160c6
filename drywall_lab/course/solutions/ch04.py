"""Notebook 04 (information mapping), exercises "rule S3 of Fig. 12 yourself" and "rule T2 of Fig. 10 from
scratch": reference solutions.

Reference solutions: try the exercise first (``check_relative_stud(relative_stud)`` in the notebook compares your
answer with the project's rules on every anchor, both directions and counts past the wall's end;
``check_stacks_of_size(stacks_of_size)`` compares yours with rule T2 on three sites and every size said).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Mapping

if TYPE_CHECKING:
    from drywall_lab.site import Site


def relative_stud(site: "Site", anchor_id: str, direction: str, count: int) -> str | None:
    """The id of the stud ``count`` places to the ``direction`` (``"left"``: lower ids, ``"right"``: higher) of
    the anchor stud, the anchor itself for ``count`` 0, ``None`` past either end of the wall."""
    ids = site.stud_ids
    index = ids.index(anchor_id) + (count if direction == "right" else -count)
    return ids[index] if 0 <= index < len(ids) else None  # the lower bound: a negative index counts from the end



def stacks_of_size(sizes: Mapping[str, tuple[float, float]], width: float | None,
                   length: float | None) -> list[str]:
    """The stacks whose panels have the size said (rule T2 of Fig. 10): ``sizes`` maps each stack to its panels'
    (width, length) in feet; a ``None`` width or length matches any; when no stack has the size as said, the
    stacks that have it turned (width and length swapped)."""
    def matching(w: float | None, l: float | None) -> list[str]:
        return [stack for stack, (sw, sl) in sizes.items() if (w is None or sw == w) and (l is None or sl == l)]

    return matching(width, length) or matching(length, width)


#: Notebook 04 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
