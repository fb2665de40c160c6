"""How the panel goes on the stud (the paper's IM section on placement; spec section 3).

``Vr_md`` -> vertical, left edge on the stud's centre line; ``Hr_top`` -> horizontal,
top row; ``Hr_btm`` -> horizontal, bottom row; none of the three -> vertical, left
edge on the stud's left line (the paper's default). Two different placements in one
instruction are refused: the robot will not guess.
"""
from __future__ import annotations

from drywall_lab.errors import Refusal
from drywall_lab.im import words as W
from drywall_lab.im.trace import TaggedInstruction, Trace
from drywall_lab.site import Placement

PLACEMENT_BY_TAG: dict[str, Placement] = {
    "Vr_md": Placement.VERTICAL_MIDDLE,
    "Hr_top": Placement.HORIZONTAL_TOP,
    "Hr_btm": Placement.HORIZONTAL_BOTTOM,
}
PLACEMENT_TAGS = tuple(PLACEMENT_BY_TAG)


def resolve_placement(ti: TaggedInstruction, trace: Trace | None = None) -> Placement:
    """The placement the placement tags say; the default when there are none."""
    trace = trace if trace is not None else Trace()
    said = [tag for tag in PLACEMENT_TAGS if ti.has(tag)]
    if len(said) > 1:
        phrases = " and ".join(W.quote(ti.words_with(tag)) for tag in said)
        message = f"{phrases} ask for two different placements: which one?"
        trace.add("placement", "P1 placement tags", True, ti, PLACEMENT_TAGS, f"refused (undetermined): {message}")
        raise Refusal("undetermined", message)
    if said:
        placement = PLACEMENT_BY_TAG[said[0]]
        trace.add("placement", "P1 placement tags", True, ti, PLACEMENT_TAGS, placement.value)
        return placement
    trace.add("placement", "P1 placement tags", False, ti, PLACEMENT_TAGS, "does not apply")
    trace.add("placement", "P2 default", True, conclusion="no placement tag: vertical, left edge on the stud's left line")
    return Placement.VERTICAL_LEFT
