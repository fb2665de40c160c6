"""Stand-alone checker for the first-sight set of 2026-12-08c.

Written from ../shared/spec/case-study.md (sections 1, 3, 4 and 5) with the
2026-12-08a checker as a template; standard library only, it does not import
drywall_lab.  Every episode is replayed from the fresh site (all nine panels
stacked, nothing installed, empty history) and the script asserts that
  - every expected command is feasible: the panel exists and is the top one of
    its stack, is not on the wall yet, stays inside the wall (x_right <=
    4.8768 + 0.01905) and shares no positive area with an installed panel
    (touching edges are allowed);
  - every expected refusal is for exactly the reason written in the gold:
      overlap / not_on_top / past_wall / already_installed / empty_stack: the
        intended command (INTENDED) fails for that reason and for no other
        (an installed panel is not tested against itself; for empty_stack the
        stack named, by size or size word, has no panel left and the place
        would be free), and its words name it;
      off_end: a stud counted from the last stud lies outside 500100 ...
        500112 (OFF_END), and the count, direction and anchor are said;
      unknown_id: the id said (UNKNOWN) is no panel or stud of the site, and
        any other id said exists;
      no_history: a stud counted from the last placement ("two studs to the
        right of the prior placement", NO_HISTORY) is asked for while the
        history is empty; the panel is named by its size and no id is said;
      no_size_match: the size said (NO_MATCH: "nine by four") is no stack's
        size either way round, and nothing else in the text names a stack;
      ambiguous_size: the one width or length said (AMBIGUOUS: "four-foot
        sheet") is that of two sizes, nothing else in the text names a stack,
        and both readings would be carried out as they stand;
      undetermined: the panel is named but no stud is (UNDETERMINED): no id,
        no stud position, no stud relative to the last one or to an anchor;
      unclear: the words leave two or more commands (UNCLEAR: "on the left
        line or on the center line"), each of which would be carried out as it
        stands, each stud is in the text and each panel is said (id, size or
        size word);
  - the references that are not ids (REFS: sizes said, in either order
    ("eight by four" is the 4 x 8 turned), size words "full" / "full-size",
    "narrow" / "skinny", absolute studs ("the first stud", "the middle stud"),
    studs counted from the last stud ("same stud", "o'r un stud", "three studs
    right of that one", "two studs to the right of the one you just did",
    "five studs to the right of the prior placement", "dau stud i'r dde o
    hwnna") and the stack to the right of the previously installed panel's
    stack) agree with the gold, are backed by a cue word in the text (CUES),
    and the history-based ones only ever use an accepted command;
  - asides (ASIDES: a size that is not this command's: the 60 by 80 quilt, the
    4x2 timber going back to the van) are in the text and are taken out before
    the checks of ids, sizes, size words and placement words;
  - each command's panel and stud are said or derived, no other id is said as
    digits, no other size, size word, narrow word or stack is left in the
    text, and the placement words agree with the placement (English and
    Welsh; a vertical_left step names no centre line, row or lying flat);
  - the step after a refusal holds no back-reference word (BACK_REF_WORDS,
    English and Welsh);
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    ids fu01..fu10, 4 to 7 steps an episode, 50 to 60 steps in all, one voice
    an episode, five voices of two episodes each, about one refusal in five.
usage: python3 check_gold.py [GOLD.jsonl]   (default: gold.jsonl beside this file)
"""
import json
import pathlib
import re
import sys

HERE = pathlib.Path(__file__).resolve().parent
H = 2.4384
WALL_END = 4.8768 + 0.01905
EPS = 1e-9
SIZES = {"left": (1.2192, 2.4384), "middle": (0.6096, 2.4384), "right": (1.2192, 1.8288)}
SIZE_FT = {"left": (4, 8), "middle": (2, 8), "right": (4, 6)}
FRESH = {"left": ["500300", "500310", "500320"],      # bottom -> top
         "middle": ["500301", "500311", "500321"],
         "right": ["500302", "500312", "500322"]}
STACK_ORDER = ("left", "middle", "right")
STACK_OF = {pid: s for s, ids in FRESH.items() for pid in ids}
STUDS = {str(500100 + i): i for i in range(13)}
PLACEMENTS = ("vertical_left", "vertical_middle", "horizontal_top", "horizontal_bottom")
REASONS = ("overlap", "past_wall", "not_on_top", "already_installed", "empty_stack",
           "unknown_id", "no_history", "off_end", "no_size_match", "ambiguous_size",
           "unclear", "undetermined")
VOICES = ("retired_seamstress", "hockey_coach", "dog_trainer", "welsh_switch", "retired_trooper")
EPISODES = [f"fu{i:02d}" for i in range(1, 11)]
STEPS_PER_EPISODE = (4, 7)
STEPS_IN_ALL = (50, 60)

# Refused steps -------------------------------------------------------------
INTENDED = {   # what the worker meant, for refusals that depend on the site
    ("fu01", 4): ("500321", "500110", "vertical_left"),       # 500321 stands on 500103's centre line since step 1;
                                                              # the place (x 4.045 ... 4.655) is free
    ("fu04", 2): ("500320", "500110", "vertical_middle"),     # x 4.064 ... 5.283 > 4.896
    ("fu05", 3): (None, "500109", "vertical_left"),           # a fourth full sheet: left stack empty
    ("fu07", 5): ("500311", "500110", "vertical_left"),       # x 4.045 ... 4.655 runs into the 4x6 on 500108
                                                              # (x 3.232 ... 4.451)
    ("fu08", 2): ("500300", "500105", "vertical_left"),       # 500300 lies under 500310 and 500320
}
INTENDED_REFS = {
    ("fu04", 2): {"dim": "full"},
    ("fu05", 3): {"dim": "full"},
    ("fu07", 5): {"size": (8, 2)},
}
OFF_END = {   # a count from the last stud ("rel"), with the panel said
    ("fu04", 5): {"rel": 3, "panel": {"size": (2, 8)}},     # 500110 + 3 = 500113
}
UNKNOWN = {("fu09", 3): ("500332", {"500105"})}   # (unknown id said, the other ids said)
NO_HISTORY = {("fu10", 0): {"phrase": "prior placement", "rel": 2, "panel": {"size": (4, 6)}}}
NO_MATCH = {("fu07", 2): (9, 4)}                  # a UK "nine by four" (2.7 m board): none here
AMBIGUOUS = {("fu03", 2): ("w", 4, "four-foot sheet", "500105", "vertical_left")}   # 4x8 and 4x6
UNDETERMINED = {("fu06", 2): "right"}             # "up over Biscuit's crate"
UNCLEAR = {("fu02", 3): [("500320", "500106", "vertical_left"),
                         ("500320", "500106", "vertical_middle")]}   # "left line or center line"

ASIDES = {   # asides: a size that is not this command's
    ("fu02", 2): ["My quilting frame goes against this wall, and the quilt on it is 60 by 80."],
    ("fu08", 4): ["Gwynfor, dos â'r 4x2 'na allan i'r fan."],     # timber back to the van
}

REFS = {
    ("fu01", 0): {"dim": "full"},
    ("fu01", 1): {"size": (2, 8), "desc": "narrow"},
    ("fu01", 2): {"size": (4, 6)},
    ("fu01", 3): {"size": (4, 6)},
    ("fu01", 5): {"size": (2, 8), "desc": "narrow"},
    ("fu02", 0): {"size": (4, 6)},
    ("fu02", 1): {"size": (2, 8), "desc": "narrow"},
    ("fu02", 2): {"size": (4, 6)},
    ("fu02", 4): {"dim": "full"},
    ("fu03", 0): {"dim": "full"},
    ("fu03", 1): {"size": (2, 8)},
    ("fu03", 3): {"size": (4, 6)},
    ("fu03", 4): {"size": (2, 8), "stud_rel_prev": 0},
    ("fu03", 5): {"size": (4, 6)},
    ("fu04", 0): {"size": (4, 6)},
    ("fu04", 1): {"size": (4, 6), "stud_rel_prev": 0},
    ("fu04", 3): {"dim": "full"},
    ("fu04", 4): {"size": (2, 8), "stud_rel_prev": 3},
    ("fu04", 6): {"size": (2, 8)},
    ("fu05", 0): {"dim": "full", "stud_abs": 0},
    ("fu05", 1): {"dim": "full"},
    ("fu05", 2): {"dim": "full"},
    ("fu05", 4): {"size": (4, 6)},
    ("fu06", 0): {"size": (2, 8), "desc": "narrow", "stud_abs": 6},
    ("fu06", 1): {"size": (4, 6)},
    ("fu06", 3): {"size": (4, 6)},
    ("fu06", 4): {"size": (2, 8)},
    ("fu06", 5): {"size": (2, 8), "desc": "narrow", "stud_rel_prev": 2},
    ("fu07", 0): {"size": (8, 4)},
    ("fu07", 1): {"size": (8, 2)},
    ("fu07", 3): {"size": (8, 4)},
    ("fu07", 4): {"size": (6, 4)},
    ("fu08", 0): {"size": (6, 4)},
    ("fu08", 1): {"size": (6, 4), "stud_rel_prev": 0},
    ("fu08", 3): {"dim": "full"},
    ("fu08", 4): {"size": (8, 2)},
    ("fu08", 5): {"size": (8, 2), "stud_rel_prev": 2},
    ("fu09", 0): {"dim": "full"},
    ("fu09", 1): {"size": (2, 8)},
    ("fu09", 2): {"size": (4, 6)},
    ("fu09", 4): {"size": (4, 6)},
    ("fu09", 5): {"size": (2, 8), "stud_rel_prev": 5},
    ("fu10", 1): {"size": (4, 6)},
    ("fu10", 2): {"size": (2, 8), "stud_rel_prev": 0},
    ("fu10", 3): {"size": (4, 6), "stud_rel_prev": 3},
    ("fu10", 4): {"dim": "full"},
    ("fu10", 5): {"stack_rel": 1},
}
PANEL_KEYS = ("size", "dim", "desc", "stack", "stack_rel", "same_size_as_prev")
STUD_KEYS = ("stud_abs", "stud_rel_prev", "stud_rel")
HISTORY_KEYS = ("same_size_as_prev", "stud_rel_prev", "stack_rel")

# Cue words that must back each reference in the text ------------------------
NUM = {2: ("2", "two", "dau", "dwy"), 3: ("3", "three", "tri", "tair"), 4: ("4", "four", "pedwar"),
       5: ("5", "five", "pump")}
CUES = {
    "dim": ("full", "regular", "standard", "full-size"),
    "desc": ("narrow", "skinny"),
    "stack": {"left": ("left stack", "left pile"),
              "middle": ("middle stack", "middle pile"),
              "right": ("right stack", "right pile")},
    "stack_rel": {1: ("stack to the right of where the previously installed panel came from",),
                  -1: ("stack to the left of where the previously installed panel came from",)},
    "same_size_as_prev": ("same size",),
    "stud_rel_same": ("same stud", "o'r un stud", "'run stud"),
    "dir": {1: ("right of that one", "to the right of the one you just did",
                "to the right of the prior placement", "i'r dde o hwnna"),
            -1: ("left of that one", "to the left of the one you just did",
                 "to the left of the prior placement", "i'r chwith o hwnna")},
    "anchor": ("that one", "the one you just did", "prior placement", "hwnna"),   # the last stud
    "stud_abs": {0: ("first stud",),
                 6: ("middle stud",)},
    "rel_dir": {1: ("to the right of",), -1: ("to the left of",)},   # from a named anchor
    "rel_end": {"rightmost": ("rightmost stud",), "leftmost": ("leftmost stud",)},
}

BACK_REF_WORDS = ("previous", "previously", "prior", "last", "same", "again", "that one", "of that",
                  "from that", "from there", "another", "other", "before", "too", "one more",
                  "as well", "above", "under it", "on top of it", "on top of that", "it again",
                  "just", "instead", "remaining", "next to it", "like it", "over it", "you just did",
                  # Welsh
                  "yr un", "o'r un", "'run", "eto", "arall", "dwytha", "diwetha", "diwethaf", "cynt",
                  "blaenorol", "hwnna", "honna", "hwnnw", "uwchben", "hefyd", "wrth ymyl", "fath",
                  "'fath", "un fath")
TOP_PHRASES = ("top row", "rhes ucha", "rhes uchaf")
BOTTOM_PHRASES = ("bottom row", "rhes isa", "rhes isaf")
CENTRE_WORDS = ("centre", "center", "canol", "ganol", "llinell ganol")
FLAT_WORDS = ("flat", "lay", "laid", "lying", "horizontal", "row",
              "fflat", "gorwedd", "llorwedd", "rhes")
WORDNUM = {"two": 2, "three": 3, "four": 4, "six": 6, "eight": 8, "nine": 9, "ten": 10,
           "twelve": 12}
SIDE_WORDS = {"w": {"four feet wide": 4, "two feet wide": 2, "four-foot sheet": 4,
                    "two-foot sheet": 2},
              "l": {"eight feet long": 8, "six feet long": 6, "eight-footer": 8,
                    "six-footer": 6}}
# a word boundary: no Latin letter, digit or apostrophe either side
NB = r"0-9A-Za-z_'\u00C0-\u024F"
# after a size: a plural "s" ("2 by 8s", "two-by-eights"), then no letter or digit
NB_SIZE = r"0-9A-Za-z_\u00C0-\u024F"


def word_in(w, t):
    return re.search(r"(?<![" + NB + r"])" + re.escape(w) + r"(?![" + NB + r"])", t)


def has(words, t):
    return any(word_in(w, t) for w in words)


def stack_for_size(a, b):
    hits = [s for s, wl in SIZE_FT.items() if wl == (a, b)]
    return hits or [s for s, wl in SIZE_FT.items() if wl == (b, a)]


def stacks_for(side, n):
    """The stacks whose width ("w") or length ("l") is n feet."""
    return [s for s, (w, l) in SIZE_FT.items() if (w if side == "w" else l) == n]


def sizes_said(t):
    """Every 'A x B' / 'A by B' / 'A-by-B' (plural 'A by Bs' too) in the (lower-case) text."""
    n = r"(\d+|two|three|four|six|eight|nine|ten|twelve)"
    out = set()
    for a, b in re.findall(r"(?<![" + NB + r"/])" + n + r"\s*(?:x|×|-by-|\s+by\s+)\s*" + n
                           + r"s?(?![" + NB_SIZE + r"])", t):
        out.add((int(WORDNUM.get(a, a)), int(WORDNUM.get(b, b))))
    return out


def take_out(key, text):
    """The text with asides taken out."""
    for phrase in ASIDES.get(key, []):
        i = text.find(phrase)
        assert i >= 0, (key, "aside not in text", phrase)
        text = text[:i] + " " + text[i + len(phrase):]
    return text


def rect(pid, stud, placement, size=None):
    w, l = size or SIZES[STACK_OF[pid]]
    c = 0.4064 * STUDS[stud]
    left = c - 0.01905
    return {"vertical_left": (left, left + w, 0.0, l),
            "vertical_middle": (c, c + w, 0.0, l),
            "horizontal_top": (left, left + l, H - w, H),
            "horizontal_bottom": (left, left + l, 0.0, w)}[placement]


def geometry(wall, r, skip=None):
    x0, x1, z0, z1 = r
    out = []
    if x1 > WALL_END + EPS:
        out.append("past_wall")
    if any(min(x1, a1) - max(x0, a0) > EPS and min(z1, b1) - max(z0, b0) > EPS
           for (a0, a1, b0, b1), p in wall if p != skip):
        out.append("overlap")
    return out


def problems(state, wall, pid, stud, placement):
    """Why the command cannot be carried out (empty list: it can)."""
    if pid not in STACK_OF or stud not in STUDS:
        return ["unknown_id"]
    out = []
    s = STACK_OF[pid]
    if any(p == pid for _, p in wall):
        out.append("already_installed")      # not tested against its own place on the wall
    elif not state[s] or state[s][-1] != pid:
        out.append("not_on_top")
    return out + geometry(wall, rect(pid, stud, placement), skip=pid)


def check_rel(key, n, last, t):
    """A stud counted n from the last stud: the cue words are in t."""
    assert last is not None, key
    if n == 0:
        assert has(CUES["stud_rel_same"], t), (key, "same stud not said")
    else:
        assert has(CUES["dir"][1 if n > 0 else -1], t), (key, "direction not said")
        assert has(NUM[abs(n)], t), (key, "count not said")
        assert has(CUES["anchor"], t), (key, "the last stud is not named as the anchor")


def anchor_ids(ref):
    """Stud ids said as the anchor of a relative stud (allowed beside the command's ids)."""
    if "stud_rel" in ref and ref["stud_rel"][1] in STUDS:
        return {ref["stud_rel"][1]}
    return set()


def check_refs(key, ref, s, stud, last, t):
    """The references agree with the gold (stack s, stud) and each has its cue word in t (lower case)."""
    if "size" in ref:
        assert stack_for_size(*ref["size"]) == [s], (key, ref)
        assert ref["size"] in sizes_said(t), (key, "size not said", ref["size"])
    for a, b in sizes_said(t):   # every size left in the text is this panel's
        assert stack_for_size(a, b) == [s], (key, "another size in the text", (a, b))
    if "dim" in ref:
        assert ref["dim"] == "full" and s == "left", (key, ref)
        assert has(CUES["dim"], t), (key, "size word not said")
    else:
        assert not has(CUES["dim"], t), (key, "a size word is left in the text")
    if "desc" in ref:   # "narrow", "smala": the one size 2 ft wide
        assert ref["desc"] == "narrow"
        assert stacks_for("w", 2) == [s], key
        assert has(CUES["desc"], t), (key, "narrow not said")
    else:
        assert not has(CUES["desc"], t), (key, "a narrow word is left in the text")
    if "stack" in ref:
        assert ref["stack"] == s, (key, ref)
        assert has(CUES["stack"][s], t), (key, "stack not said")
    for other, cues in CUES["stack"].items():   # no other stack named
        if other != s:
            assert not has(cues, t), (key, "another stack named", other)
    if "stack_rel" in ref:   # the last panel's original stack moved by n (spec target rule 5)
        n = ref["stack_rel"]
        assert last is not None, key
        i = STACK_ORDER.index(STACK_OF[last[0]]) + n
        assert 0 <= i < 3 and STACK_ORDER[i] == s, (key, "relative stack", i)
        assert has(CUES["stack_rel"][1 if n > 0 else -1], t), (key, "relative stack not said")
    if "same_size_as_prev" in ref:
        assert last is not None and SIZE_FT[STACK_OF[last[0]]] == SIZE_FT[s], key
        assert has(CUES["same_size_as_prev"], t), (key, "same size not said")
    if "stud_rel_prev" in ref:
        assert last is not None, key
        assert STUDS[stud] == STUDS[last[1]] + ref["stud_rel_prev"], key
        check_rel(key, ref["stud_rel_prev"], last, t)
    if "stud_abs" in ref:
        assert STUDS[stud] == ref["stud_abs"], key
        assert has(CUES["stud_abs"][ref["stud_abs"]], t), (key, "stud position not said")
    if "stud_rel" in ref:    # counted from a named anchor: a stud id or an end stud
        n, anchor = ref["stud_rel"]
        base = STUDS[anchor] if anchor in STUDS else {"leftmost": 0, "rightmost": 12}[anchor]
        assert STUDS[stud] == base + n, (key, "relative stud", base + n)
        assert has(CUES["rel_dir"][1 if n > 0 else -1], t), (key, "direction not said")
        assert has(NUM[abs(n)], t), (key, "count not said")
        assert anchor in t if anchor in STUDS else has(CUES["rel_end"][anchor], t), \
            (key, "anchor not said")


def ids_in(text):
    return re.findall(r"\d{6}", text)


def check_words(key, text, pid, stud, pl, ref):
    """Ids and placement words of a command (text: asides taken out)."""
    t = text.lower()
    assert pid is None or pid in text or any(k in ref for k in PANEL_KEYS), (key, "panel not said")
    assert stud is None or stud in text or any(k in ref for k in STUD_KEYS), (key, "stud not said")
    for d in ids_in(text):
        assert d in (pid, stud) or d in anchor_ids(ref), (key, "stray id", d)
    if pl == "horizontal_top":
        assert has(TOP_PHRASES, t) and not has(BOTTOM_PHRASES + CENTRE_WORDS, t), key
    elif pl == "horizontal_bottom":
        assert has(BOTTOM_PHRASES, t) and not has(TOP_PHRASES + CENTRE_WORDS, t), key
    elif pl == "vertical_middle":
        assert has(CENTRE_WORDS, t), (key, "no centre word")
        assert not has(FLAT_WORDS + TOP_PHRASES + BOTTOM_PHRASES, t), key
    else:
        for w in CENTRE_WORDS + TOP_PHRASES + BOTTOM_PHRASES + FLAT_WORDS:
            assert not word_in(w, t), (key, w)


def back_refs(t):
    return [w for w in BACK_REF_WORDS if word_in(w, t)]


def stud_cues(t):
    cues = CUES["stud_rel_same"] + CUES["dir"][1] + CUES["dir"][-1] + CUES["anchor"] + \
        CUES["rel_dir"][1] + CUES["rel_dir"][-1] + sum(CUES["rel_end"].values(), ()) + \
        sum(CUES["stud_abs"].values(), ()) + ("last stud", "leftmost", "rightmost", "first stud",
                                             "middle stud", "end stud", "stud")
    return [w for w in cues if word_in(w, t)]


def names_a_stack(t):
    return has(CUES["dim"] + CUES["desc"] + sum(CUES["stack"].values(), ()), t) or bool(sizes_said(t))


TABLE_OF = {"overlap": INTENDED, "not_on_top": INTENDED, "past_wall": INTENDED,
            "already_installed": INTENDED, "empty_stack": INTENDED, "off_end": OFF_END,
            "unknown_id": UNKNOWN, "no_history": NO_HISTORY, "no_size_match": NO_MATCH,
            "ambiguous_size": AMBIGUOUS, "undetermined": UNDETERMINED, "unclear": UNCLEAR}


def panel_stack(ref):
    """The stack a panel description (size, size word, narrow word, stack) gives, or None."""
    hits = set()
    if "size" in ref:
        hits |= set(stack_for_size(*ref["size"]))
    if "dim" in ref:
        hits.add("left")
    if "desc" in ref:
        hits |= set(stacks_for("w", 2))
    if "stack" in ref:
        hits.add(ref["stack"])
    return hits.pop() if len(hits) == 1 else None


def check_refusal(key, why, state, wall, last, text):
    t = text.lower()
    assert key in TABLE_OF.get(why, {}), (key, "refusal not worked out for this reason", why)
    if why in ("overlap", "not_on_top", "past_wall", "already_installed"):
        pid, stud, pl = INTENDED[key]
        assert pid is not None, (key, "no panel worked out for", why)
        iref = INTENDED_REFS.get(key, {})
        check_refs(key, iref, STACK_OF[pid], stud, last, t)
        check_words(key, text, pid, stud, pl, iref)
        if any(k in iref for k in PANEL_KEYS):   # described: the panel is the top of that stack
            assert pid not in text, key
            assert state[STACK_OF[pid]] and state[STACK_OF[pid]][-1] == pid, key
        got = problems(state, wall, pid, stud, pl)
        assert got == [why], (key, why, got)
    elif why == "empty_stack":
        _, stud, pl = INTENDED[key]
        iref = INTENDED_REFS.get(key, {})
        s = panel_stack(iref)
        assert s is not None, (key, "no stack worked out")
        check_refs(key, iref, s, stud, last, t)
        check_words(key, text, None, stud, pl, iref)
        assert not state[s], (key, "the stack is not empty", state[s])
        assert not geometry(wall, rect(FRESH[s][0], stud, pl)), (key, "the place is not free")
    elif why == "off_end":
        spec = OFF_END[key]
        assert last is not None, (key, "the history is empty: that would be no_history")
        if "rel" in spec:       # a stud counted from the last stud
            n = spec["rel"]
            check_rel(key, n, last, t)
            assert not 0 <= STUDS[last[1]] + n <= 12, (key, "the stud exists", STUDS[last[1]] + n)
            assert not ids_in(text), (key, "an id is said")
            s = panel_stack(spec["panel"])
            assert s is not None, (key, "no panel worked out")
            if "desc" in spec["panel"]:
                assert has(CUES["desc"], t), (key, "narrow not said")
            assert state[s], (key, "the stack of the panel named is empty")
        else:                   # a stack counted from the last panel's (original) stack
            n = spec["stack_rel"]
            i = STACK_ORDER.index(STACK_OF[last[0]]) + n
            assert not 0 <= i < 3, (key, "the stack exists", i)
            assert has(CUES["stack_rel"][1 if n > 0 else -1], t), (key, "relative stack not said")
            assert not sizes_said(t) and not ids_in(text).__contains__(last[0]), key
            assert not has(CUES["dim"] + CUES["desc"] + sum(CUES["stack"].values(), ()), t), \
                (key, "another panel description would decide")
            studs = [d for d in ids_in(text) if d in STUDS]
            assert len(studs) == 1 and set(ids_in(text)) == set(studs), (key, "one stud, no panel id")
    elif why == "unknown_id":
        bad, others = UNKNOWN[key]
        assert bad not in STACK_OF and bad not in STUDS and bad in text, key
        assert set(ids_in(text)) == {bad} | others, key
        assert all(o in STACK_OF or o in STUDS for o in others), key
        assert names_a_stack(t) or others, (key, "nothing else is said")
    elif why == "no_history":
        spec = NO_HISTORY[key]   # a stud counted from the last placement, with nothing placed yet
        assert last is None, (key, "the history is not empty")
        assert spec["phrase"] in text and back_refs(t), key
        n = spec["rel"]
        assert has(CUES["dir"][1 if n > 0 else -1], t), (key, "direction not said")
        assert has(NUM[abs(n)], t) and has(CUES["anchor"], t), (key, "count or anchor not said")
        assert not ids_in(text), (key, "an id is said")
        s = panel_stack(spec["panel"])
        assert s is not None and state[s], (key, "no panel, or its stack is empty")
        check_refs(key, spec["panel"], s, None, None, t)
    elif why == "no_size_match":
        a, b = NO_MATCH[key]
        assert sizes_said(t) == {(a, b)}, key
        assert not stack_for_size(a, b), (key, "the size matches a stack")
        assert not has(CUES["dim"] + CUES["desc"] + sum(CUES["stack"].values(), ()), t), key
    elif why == "ambiguous_size":
        side, n, phrase, stud, pl = AMBIGUOUS[key]
        hits = stacks_for(side, n)
        assert len(hits) >= 2 and phrase in t, (key, hits)
        assert SIDE_WORDS[side].get(phrase) == n, key
        assert not sizes_said(t), key
        assert not has(CUES["dim"] + CUES["desc"] + sum(CUES["stack"].values(), ()), t), key
        assert ids_in(text) == [stud], key
        for s in hits:   # each reading would be carried out as it stands
            assert state[s], (key, s)
            assert not problems(state, wall, state[s][-1], stud, pl), (key, "a reading fails anyway", s)
        assert has(CENTRE_WORDS, t) == (pl == "vertical_middle"), key
    elif why == "undetermined":
        s = UNDETERMINED[key]
        assert has(CUES["stack"][s], t) or [stack_for_size(*ab) for ab in sizes_said(t)] == [[s]], key
        assert state[s], (key, "the stack of the panel named is empty")
        assert not ids_in(text) and not stud_cues(t), (key, "a stud is named", stud_cues(t))
    elif why == "unclear":
        options = UNCLEAR[key]
        assert len(set(options)) >= 2, key
        for pid, stud, pl in options:
            assert not problems(state, wall, pid, stud, pl), (key, "an option fails anyway", pid, stud, pl)
            assert stud in text, key
            assert state[STACK_OF[pid]][-1] == pid, key
            assert pid in text or SIZE_FT[STACK_OF[pid]] in sizes_said(t) or \
                (STACK_OF[pid] == "left" and has(CUES["dim"], t)), (key, "option not said", pid)
        assert set(ids_in(text)) <= {x for o in options for x in o[:2]}, key
        assert len({o[0] for o in options}) == len(options) or \
            len({o[1] for o in options}) == len(options) or \
            len({o[2] for o in options}) == len(options), key
    else:
        raise AssertionError((key, "no check for", why))


def main(gold_path=None):
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl", encoding="utf-8") if l.strip()]
    gold = [json.loads(l) for l in open(gold_path or HERE / "gold.jsonl", encoding="utf-8") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    assert [e["id"] for e in inst] == EPISODES, "episode ids"
    texts = {(g["episode"], g["step"]): g["text"] for g in gold}
    refused = {(g["episode"], g["step"]) for g in gold if "refusal" in g["expect"]}
    n_ref = 0
    styles, reasons, placements, eps_per_style = {}, {}, {}, {}
    history = []
    for e in inst:
        ep = e["id"]
        rows = by_ep[ep]
        assert set(e) == {"id", "instructions"}, ep
        assert STEPS_PER_EPISODE[0] <= len(rows) <= STEPS_PER_EPISODE[1], (ep, len(rows))
        assert [g["step"] for g in rows] == list(range(len(rows))), ep
        assert [g["text"] for g in rows] == e["instructions"], ep
        assert all(set(g) == {"episode", "step", "text", "style", "expect"} for g in rows), ep
        assert len({g["style"] for g in rows}) == 1 and rows[0]["style"] in VOICES, ep
        eps_per_style[rows[0]["style"]] = eps_per_style.get(rows[0]["style"], 0) + 1
        state = {s: list(ids) for s, ids in FRESH.items()}   # fresh site every episode
        wall = []         # ((x0, x1, z0, z1), pid)
        last = None       # (pid, stud) of the last accepted command
        prev_refused = False
        for g in rows:
            key = (ep, g["step"])
            x = g["expect"]
            styles[g["style"]] = styles.get(g["style"], 0) + 1
            text = take_out(key, g["text"])
            if prev_refused:
                assert not back_refs(g["text"].lower()), \
                    (key, "back-reference right after a refusal", back_refs(g["text"].lower()))
            if "refusal" in x:
                assert set(x) == {"refusal"}, key
                n_ref += 1
                why = x["refusal"]
                assert why in REASONS, (key, why)
                reasons[why] = reasons.get(why, 0) + 1
                check_refusal(key, why, state, wall, last, text)
                prev_refused = True
                continue      # a refused step leaves site and history as they were
            prev_refused = False
            assert set(x) == {"drywall_id", "stud_id", "placement"}, key
            pid, stud, pl = x["drywall_id"], x["stud_id"], x["placement"]
            assert isinstance(pid, str) and isinstance(stud, str) and pl in PLACEMENTS, key
            assert pid in STACK_OF and stud in STUDS, (key, "unknown id in the gold")
            assert key in REFS or (pid in text and stud in text), (key, "no REFS")
            ref = REFS.get(key, {})
            if any(k in ref for k in PANEL_KEYS):
                assert pid not in text, (key, "panel both named and described")
            if any(k in ref for k in STUD_KEYS):
                assert stud not in text, (key, "stud both named and derived")
            check_refs(key, ref, STACK_OF[pid], stud, last, text.lower())
            check_words(key, text, pid, stud, pl, ref)
            p = problems(state, wall, pid, stud, pl)
            assert not p, (key, x, p)
            state[STACK_OF[pid]].pop()
            wall.append((rect(pid, stud, pl), pid))
            last = (pid, stud)
            placements[pl] = placements.get(pl, 0) + 1
            if any(k in ref for k in HISTORY_KEYS):
                history.append(key)
    for table in (INTENDED, INTENDED_REFS, OFF_END, UNKNOWN, NO_HISTORY, NO_MATCH, AMBIGUOUS,
                  UNDETERMINED, UNCLEAR):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    assert set(ASIDES) <= set(texts), "table names a missing step"
    assert set(eps_per_style.values()) == {2} and len(eps_per_style) == 5, eps_per_style
    n = len(gold)
    assert STEPS_IN_ALL[0] <= n <= STEPS_IN_ALL[1], n
    assert 0.15 <= n_ref / n <= 0.25, (n_ref, n)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("refusals:", reasons)
    print("placements:", placements)
    print(f"history-dependent steps={len(history)}:", " ".join(f"{e}/{s}" for e, s in history))
    print(f"asides={len(ASIDES)}")
    print("OK")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
