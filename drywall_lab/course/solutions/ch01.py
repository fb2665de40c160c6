"""Notebook 01 (annotation), exercises "tag an instruction by the guidelines" and "entities, from scratch":
reference solutions.

Reference solutions: try the exercise first (``check_tagging(my_answer)`` in the notebook says which words you
tagged differently from the answer key, and which guideline sections to read again; ``check_entity_spans`` names
the first instruction whose entities you find wrongly, and the slip it looks like).
"""
from __future__ import annotations

#: Practice instruction P12 in the guidelines' notation (``word/TAG``, a bare word is ``O``): "same" and
#: "previous" both say the size is the previous panel's (``dim``, section 4.2), "middle line" is the placement
#: (``Vr_md``, section 4.1), "right" the direction counted from the anchor stud (``St_loc1``) and 500102 that
#: anchor (``St_loc2``, section 4.5), not the destination.
MY_ANSWER = ("Go ahead and then place a drywall panel of the same/dim size as the previous/dim one on the "
             "middle/Vr_md line/Vr_md. The stud is laying right/St_loc1 from the stud 500102/St_loc2. Good job.")



def entity_spans(tags: list[str]) -> set[tuple[str, int, int]]:
    """The entities of a tag sequence: (tag, start, end) for each maximal run of one tag other than "O", end
    exclusive (the entity's words are ``words[start:end]``); an "O" or a change of tag ends a run."""
    spans = set()
    start = None
    for i, tag in enumerate(tags):
        if start is not None and tag != tags[start]:
            spans.add((tags[start], start, i))
            start = None
        if start is None and tag != "O":
            start = i
    if start is not None:
        spans.add((tags[start], start, len(tags)))
    return spans


#: Notebook 01 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
