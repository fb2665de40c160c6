"""The tag set (the paper's Fig. 7, Table 2 and Table 5; spec section 2).

Thirteen word-level labels with no BIO prefixes: ``O`` and twelve that
characterise the target panel, the destination stud or the placement. The
co-reference variant adds ``Trg`` and ``Dst`` for generic words ("the panel",
"it", "stud") that point at the target or the destination.
"""
from __future__ import annotations

TAGS: tuple[str, ...] = (
    "O",
    "ID_wall",
    "dim",
    "length",
    "width",
    "Dw_loc1",
    "Dw_loc2",
    "ID_stud",
    "St_loc1",
    "St_loc2",
    "Vr_md",
    "Hr_top",
    "Hr_btm",
)
COREF_TAGS: tuple[str, ...] = TAGS + ("Trg", "Dst")

TARGET_TAGS = ("ID_wall", "dim", "length", "width", "Dw_loc1", "Dw_loc2")
DESTINATION_TAGS = ("ID_stud", "St_loc1", "St_loc2")
PLACEMENT_TAGS = ("Vr_md", "Hr_top", "Hr_btm")

#: One line per tag, in the project's words (the guidelines say more).
TAG_MEANINGS: dict[str, str] = {
    "O": "a word that does not characterise the target, destination or placement",
    "ID_wall": "the id of the target panel (500300 ... 500322)",
    "dim": "a size word for the target ('full-size', 'standard') or a back-reference to the last panel's size ('same as the previous one')",
    "length": "the number giving the target's length (the second number in 'A by B')",
    "width": "the number giving the target's width (the first number in 'A by B')",
    "Dw_loc1": "where the target's stack is ('leftmost', 'in the middle'), or the direction of a relative position ('second to the right')",
    "Dw_loc2": "the anchor of a relative panel position: a panel id or the previously installed panel",
    "ID_stud": "the id of the destination stud (500100 ... 500112)",
    "St_loc1": "where the stud is ('leftmost', 'third from the left'), or the direction of a relative position ('second to the left')",
    "St_loc2": "the anchor of a relative stud position: a stud id, the leftmost/rightmost stud or the previous stud",
    "Vr_md": "vertical placement with the left edge on the stud's centre line ('middle line', 'center line')",
    "Hr_top": "horizontal placement in the top row ('top row', 'upper part')",
    "Hr_btm": "horizontal placement in the bottom row ('bottom row', 'lower part')",
    "Trg": "(co-reference variant) a generic word for the target: 'panel', 'drywall', 'it'",
    "Dst": "(co-reference variant) a generic word for the destination: 'stud'",
}

#: Colours for tagged examples in notebooks (one per tag; O stays plain).
TAG_COLOURS: dict[str, str] = {
    "O": "#ffffff",
    "ID_wall": "#f4a582",
    "dim": "#fddbc7",
    "length": "#d6604d",
    "width": "#e08214",
    "Dw_loc1": "#fee090",
    "Dw_loc2": "#fdb863",
    "ID_stud": "#92c5de",
    "St_loc1": "#4393c3",
    "St_loc2": "#abd9e9",
    "Vr_md": "#a6dba0",
    "Hr_top": "#5aae61",
    "Hr_btm": "#c2a5cf",
    "Trg": "#e7d4e8",
    "Dst": "#d1e5f0",
}

#: The paper's Table 2: words per tag over its 1,584 instructions (39,841 words).
PAPER_TAG_COUNTS: dict[str, int] = {
    "Dw_loc1": 702,
    "Dw_loc2": 368,
    "Hr_btm": 184,
    "Hr_top": 210,
    "ID_stud": 550,
    "ID_wall": 514,
    "O": 31080,
    "St_loc1": 2652,
    "St_loc2": 964,
    "Vr_md": 1666,
    "dim": 259,
    "length": 346,
    "width": 346,
}
PAPER_N_INSTRUCTIONS = 1584
PAPER_N_SENTENCES = 3072
PAPER_N_WORDS = 39841
PAPER_SPLIT_SIZES = {"train": 1268, "validation": 158, "test": 158}
#: Test split by number of sentences (the paper's latency paragraph).
PAPER_TEST_SENTENCE_GROUPS = {1: 46, 2: 74, 3: 27, 4: 11}
#: Ground-truth words per tag in the paper's validation split (Table 4).
PAPER_VALIDATION_TAG_COUNTS: dict[str, int] = {
    "Dw_loc1": 83, "Dw_loc2": 37, "Hr_btm": 16, "Hr_top": 26, "ID_stud": 56, "ID_wall": 45,
    "O": 3021, "St_loc1": 259, "St_loc2": 94, "Vr_md": 171, "dim": 19, "length": 34, "width": 34,
}
