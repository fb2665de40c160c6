"""Stand-alone checker for the first-sight set of 2026-12-07d.

Written from ../shared/spec/case-study.md (sections 1, 3, 4 and 5) with the
2026-12-07c checker's layout as a template; standard library only, it does not
import drywall_lab.  Every episode is replayed from the fresh site (all nine
panels stacked, nothing installed, empty history) and the script asserts that
  - every expected command is feasible: the panel exists and is the top one of
    its stack, is not on the wall yet, stays inside the wall (x_right <=
    4.8768 + 0.01905) and shares no positive area with an installed panel
    (touching edges are allowed);
  - every expected refusal is for exactly the reason written in the gold:
      overlap / already_installed: the intended command (INTENDED) fails for
        that reason and for no other, and its words name it;
      empty_stack: the stack asked for (EMPTY) has no panel left, and the
        same-sized panel would otherwise fit at the stud and placement said;
      no_size_match: the size said (NO_MATCH) fits no stack, as given or
        turned, while the stud said exists;
      off_end: the stud counted from the last stud (OFF_END) falls outside
        500100 ... 500112, while the panel asked for is there to be taken;
      no_history: "same size as the last one" (NO_HISTORY) with no accepted
        command yet in the episode;
  - the references that are not ids (REFS: sizes, size words, nicknames
    "big'un"/"slim"/"stubby", "narrow"/"skinny"/"hẹp", absolute stacks, "same
    size" as the last panel, studs by position from either end, studs
    relative to the last stud, "same stud") agree with the gold, are backed by
    a cue word in the text (CUES), and the history-based ones only ever use an
    accepted command;
  - the sizes, areas and lengths written in the BIM rows (AREA_M2, MM) fit the
    panel named by its Tag / PanelMark;
  - asides that name a row, side, size or stud that is not this command's
    (DISTRACTORS) and words corrected away in the same step (CORRECTIONS: a
    stud or row that the worker takes back with "*", "no" or "nah") are in the
    text and are taken out before the checks of ids and placement words;
  - ids spoken as words (SAID: "năm không không một không sáu",
    "five oh oh one oh three", "Five-oh-oh-one-oh-nine") are in the text and
    spell the id of the gold;
  - each command's panel and stud are said or derived, no other id is said as
    digits, and the placement words agree with the placement (English,
    Vietnamese, BIM field and gaffer phrasing; a vertical_left step names no
    centre line, axis, row, course or lying flat);
  - the step after a refusal holds no back-reference word (BACK_REF_WORDS);
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    ids fm01..fm10, 5 or 6 steps an episode, one voice an episode, five
    voices of two episodes each.
usage: python3 check_gold.py
"""
import json
import pathlib
import re

HERE = pathlib.Path(__file__).resolve().parent
H = 2.4384
WALL_END = 4.8768 + 0.01905
EPS = 1e-9
FT = 0.3048
SIZES = {"left": (1.2192, 2.4384), "middle": (0.6096, 2.4384), "right": (1.2192, 1.8288)}
SIZE_FT = {"left": (4, 8), "middle": (2, 8), "right": (4, 6)}
FRESH = {"left": ["500300", "500310", "500320"],      # bottom -> top
         "middle": ["500301", "500311", "500321"],
         "right": ["500302", "500312", "500322"]}
STACK_OF = {pid: s for s, ids in FRESH.items() for pid in ids}
STUDS = {str(500100 + i): i for i in range(13)}
PLACEMENTS = ("vertical_left", "vertical_middle", "horizontal_top", "horizontal_bottom")
REASONS = ("overlap", "past_wall", "not_on_top", "already_installed", "empty_stack",
           "unknown_id", "no_history", "off_end", "no_size_match", "ambiguous_size",
           "unclear", "undetermined")
VOICES = ("vietnamese_switch", "bim_export", "chat_burst", "nickname_gaffer", "play_by_play")

# Refused steps -------------------------------------------------------------
INTENDED = {   # what the worker meant, for refusals that depend on the site
    ("fm01", 3): ("500321", "500108", "vertical_left"),     # 2x8 upright on 500108 runs into the 4x6 on the centre line of 500106
    ("fm03", 3): ("500321", "500110", "vertical_middle"),   # duplicate BIM row: 500321 went up at step 1
}
INTENDED_REFS = {
    ("fm01", 3): {"size": (2, 8), "stack": "middle", "desc": "narrow"},
    ("fm03", 3): {"size": (2, 8)},
}
EMPTY = {("fm06", 3): ("middle", (2, 8), "500106", "vertical_middle")}   # third 2x8 went up at step 2
NO_MATCH = {("fm02", 2): ((4, 10), "500105", "vertical_left")}         # there is no 4 x 10 (nor 10 x 4)
OFF_END = {("fm07", 4): ("right", 4)}     # "four fingers, thumb right" of 500109 -> 500113
NO_HISTORY = {("fm09", 0): "500104"}      # "same size as the last one you hung yesterday" on a fresh site

SAID = {   # ids said as words: (exact words in the text, id)
    ("fm01", 2): [("năm không không một không sáu", "500106")],
    ("fm02", 3): [("năm không không một không năm", "500105")],
    ("fm07", 3): [("Five-oh-oh-one-oh-nine", "500109")],
    ("fm09", 2): [("five oh oh one oh three", "500103")],
}
DISTRACTORS = {   # asides naming a row, side, size or stud that is not this command's
    ("fm01", 2): ["Hàng trên bên tường kia"],          # top row on the other wall: tomorrow
    ("fm02", 3): ["Hàng dưới tường B"],                # bottom row of wall B: this afternoon
    ("fm04", 4): ["infill under the 2x8"],             # the 2x8 above it, not this panel
    ("fm09", 2): ["500100's covered"],                 # what he sees: the sheet already on 500100
    ("fm09", 5): ["cutting the 2x8 for the window"],   # Jono's job
}
CORRECTIONS = {   # words taken back in the same step, and the marker that takes them back
    ("fm05", 2): ("500104", "*500105"),
    ("fm08", 3): ("Top course", ", no. Bottom course"),
    ("fm10", 4): ("500111", "nah"),
}
AREA_M2 = {   # NetArea written in the BIM row, m2 (2 decimals)
    ("fm04", 0): 2.97, ("fm04", 1): 2.97, ("fm04", 2): 2.23, ("fm04", 3): 1.49, ("fm04", 4): 2.23,
}
MM = {("fm03", 1): (610, 2438)}   # Width_mm, Length_mm written in the BIM row

REFS = {
    ("fm01", 0): {"dim": "full", "stack": "left"},
    ("fm01", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fm01", 2): {"size": (4, 6), "stack": "right"},
    ("fm01", 4): {"size": (2, 8), "stack": "middle", "stud_abs": 6},
    ("fm01", 5): {"size": (4, 6), "stack": "right", "stud_rel_prev": 3},
    ("fm02", 0): {"desc": "narrow", "stack": "middle", "stud_abs": 0},
    ("fm02", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fm02", 3): {"size": (4, 8), "stack": "left"},
    ("fm02", 4): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fm03", 0): {"size": (4, 8)},
    ("fm03", 1): {"size": (2, 8)},
    ("fm03", 2): {"size": (4, 6)},
    ("fm03", 4): {"size": (4, 6)},
    ("fm03", 5): {"size": (2, 8)},
    ("fm04", 1): {"stud_rel_prev": 0},
    ("fm04", 3): {"size": (2, 8)},
    ("fm05", 0): {"size": (4, 6), "stack": "right"},
    ("fm05", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fm05", 2): {"dim": "full", "stack": "left"},
    ("fm05", 3): {"desc": "narrow", "size": (2, 8), "stack": "middle", "stud_rel_prev": 3},
    ("fm05", 4): {"size": (2, 8), "same_size_as_prev": True},
    ("fm06", 0): {"desc": "narrow", "stack": "middle", "stud_abs": 0},
    ("fm06", 1): {"desc": "narrow", "same_size_as_prev": True, "stud_rel_prev": 2},
    ("fm06", 2): {"size": (2, 8), "stack": "middle"},
    ("fm06", 4): {"dim": "full", "stack": "left"},
    ("fm06", 5): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fm07", 0): {"nick": "big'un", "stack": "left"},
    ("fm07", 1): {"nick": "slim", "stack": "middle", "stud_rel_prev": 3},
    ("fm07", 2): {"nick": "slim", "same_size_as_prev": True, "stud_rel_prev": 2},
    ("fm07", 3): {"nick": "stubby", "stack": "right"},
    ("fm07", 5): {"nick": "slim", "stack": "middle", "stud_abs": 0},
    ("fm08", 0): {"nick": "stubby", "stack": "right", "stud_abs": 6},
    ("fm08", 1): {"nick": "slim", "stack": "middle", "stud_rel_prev": 0},
    ("fm08", 2): {"nick": "stubby", "stack": "right", "stud_rel_prev": 3},
    ("fm08", 3): {"nick": "big'un", "stack": "left", "stud_abs": 0},
    ("fm08", 4): {"nick": "big'un", "same_size_as_prev": True, "stud_rel_prev": 0},
    ("fm09", 1): {"dim": "full", "stack": "left"},
    ("fm09", 2): {"desc": "narrow", "stack": "middle"},
    ("fm09", 3): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fm09", 4): {"size": (4, 6), "stack": "right", "stud_from_right": 6},
    ("fm09", 5): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fm10", 0): {"size": (2, 8), "stack": "middle"},
    ("fm10", 1): {"size": (4, 6), "stack": "right"},
    ("fm10", 2): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fm10", 3): {"dim": "full", "stack": "left", "stud_abs": 0},
    ("fm10", 4): {"desc": "narrow", "stack": "middle"},
}
PANEL_KEYS = ("size", "dim", "desc", "nick", "stack", "same_size_as_prev")
STUD_KEYS = ("stud_abs", "stud_from_right", "stud_rel_prev")
HISTORY_KEYS = ("same_size_as_prev", "stud_rel_prev")

# Cue words that must back each reference in the text ------------------------
NUM = {2: ("2", "two", "hai"), 3: ("3", "three", "ba"), 4: ("4", "four", "bốn"),
       6: ("6", "six", "sáu"), 8: ("8", "eight", "tám"), 10: ("10", "ten", "mười")}
NICK = {"big'un": "left", "slim": "middle", "stubby": "right"}
CUES = {
    "dim": ("full",),
    "desc": ("narrow", "skinny", "hẹp"),
    "stack": {"left": ("left", "chồng bên trái"),
              "middle": ("middle", "chồng giữa"),
              "right": ("right", "chồng bên phải")},
    "same_size_as_prev": ("same size", "cùng cỡ", "another", "same again", "one more"),
    "stud_rel_same": ("same stud", "cùng stud", "same host stud"),
    "dir": {1: ("right", "qua phải", "thumb right"), -1: ("left", "qua trái")},
    "stud_abs": {0: ("first stud", "stud đầu tiên"),
                 6: ("stud thứ bảy từ bên trái", "middle stud")},
    "stud_from_right": {6: ("sixth stud counting from the right",)},
}

BACK_REF_WORDS = ("previous", "prev", "last", "same", "again", "that one", "of that",
                  "from that", "from there", "those", "just", "another", "other", "before",
                  "too", "her", "it again", "one more", "as well", "above", "under it",
                  "on top of it", "yesterday",
                  # Vietnamese
                  "cùng", "trước", "lúc nãy", "vừa rồi", "nữa", "đó", "giống", "lại", "thêm",
                  "tấm kia")
TOP_PHRASES = ("top row", "hàng trên", "upper", "top course")
BOTTOM_PHRASES = ("bottom row", "hàng dưới", "lower", "bottom course")
CENTRE_WORDS = ("centre", "center", "tim", "axis", "stud_axis", "studaxis")
FLAT_WORDS = ("flat", "horizontal", "lay", "nằm", "row", "course", "hàng")
UNITS = {"oh": 0, "zero": 0, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5,
         "six": 6, "seven": 7, "eight": 8, "nine": 9,
         "không": 0, "một": 1, "hai": 2, "ba": 3, "bốn": 4, "năm": 5, "sáu": 6,
         "bảy": 7, "tám": 8, "chín": 9}


def spell(words):
    """Digits of an id said digit by digit: 'năm không không một không sáu' -> '500106',
    'Five-oh-oh-one-oh-nine' -> '500109'."""
    toks = [t for t in re.split(r"[\s\-]+", words.lower()) if t]
    return "".join(t if t.isdigit() else str(UNITS[t]) for t in toks)


def word_in(w, t):
    return re.search(r"(?<![\w'])" + re.escape(w) + r"(?![\w'])", t)


def has(words, t):
    return any(word_in(w, t) for w in words)


def stack_for_size(a, b):
    hits = [s for s, wl in SIZE_FT.items() if wl == (a, b)]
    return hits or [s for s, wl in SIZE_FT.items() if wl == (b, a)]


def size_said(t, a, b):
    """'4x8', '4 x 6', 'four by eight' in the (lower-case) text."""
    alt = lambda n: "(?:" + "|".join(map(re.escape, NUM[n])) + ")"
    return re.search(r"(?<![\w/])" + alt(a) + r"\s*(?:x|by)\s*" + alt(b) + r"(?!\w)", t)


def sizes_said(t):
    return {(int(a), int(b)) for a, b in re.findall(r"(?<![\w/])(\d+)\s*x\s*(\d+)(?!\w)", t)}


def take_out(key, text):
    """The text with asides and corrected-away words taken out."""
    for phrase in DISTRACTORS.get(key, []):
        i = text.find(phrase)
        assert i >= 0, (key, "aside not in text", phrase)
        text = text[:i] + " " + text[i + len(phrase):]
    if key in CORRECTIONS:
        old, marker = CORRECTIONS[key]
        i, j = text.find(old), text.find(marker)
        assert 0 <= i < j, (key, "correction not in text, or not after the words it takes back")
        text = text[:i] + " " + text[i + len(old):]
    return text


def rect(pid, stud, placement, size=None):
    w, l = size or SIZES[STACK_OF[pid]]
    c = 0.4064 * STUDS[stud]
    left = c - 0.01905
    return {"vertical_left": (left, left + w, 0.0, l),
            "vertical_middle": (c, c + w, 0.0, l),
            "horizontal_top": (left, left + l, H - w, H),
            "horizontal_bottom": (left, left + l, 0.0, w)}[placement]


def geometry(wall, r):
    x0, x1, z0, z1 = r
    out = []
    if x1 > WALL_END + EPS:
        out.append("past_wall")
    if any(min(x1, a1) - max(x0, a0) > EPS and min(z1, b1) - max(z0, b0) > EPS
           for (a0, a1, b0, b1), _ in wall):
        out.append("overlap")
    return out


def problems(state, wall, pid, stud, placement):
    """Why the command cannot be carried out (empty list: it can)."""
    if pid not in STACK_OF or stud not in STUDS:
        return ["unknown_id"]
    out = []
    s = STACK_OF[pid]
    if any(p == pid for _, p in wall):
        out.append("already_installed")
    elif not state[s] or state[s][-1] != pid:
        out.append("not_on_top")
    return out + geometry(wall, rect(pid, stud, placement))


def check_refs(key, ref, pid, stud, last, t):
    """The references agree with the gold and each has its cue word in t (lower case)."""
    s = STACK_OF[pid]
    if "size" in ref:
        assert stack_for_size(*ref["size"]) == [s], (key, ref)
        assert size_said(t, *ref["size"]), (key, "size not said", ref["size"])
    for a, b in sizes_said(t):   # every size left in the text is this panel's
        assert stack_for_size(a, b) == [s], (key, "another size in the text", (a, b))
    if "dim" in ref:
        assert ref["dim"] == "full" and s == "left", (key, ref)
        assert has(CUES["dim"], t), (key, "size word not said")
    if "desc" in ref:   # "narrow", "skinny", "hẹp": the one size 2 ft wide
        assert ref["desc"] == "narrow"
        assert [x for x, (w, _) in SIZE_FT.items() if w == 2] == [s], key
        assert has(CUES["desc"], t), (key, "narrow not said")
    if "nick" in ref:
        assert NICK[ref["nick"]] == s, (key, ref)
        assert word_in(ref["nick"], t), (key, "nickname not said")
    if "stack" in ref:
        assert ref["stack"] == s, (key, ref)
        assert has(CUES["stack"][s], t), (key, "stack not said")
    if "same_size_as_prev" in ref:
        assert last is not None and SIZE_FT[STACK_OF[last[0]]] == SIZE_FT[s], key
        assert has(CUES["same_size_as_prev"], t), (key, "same size not said")
    if "stud_rel_prev" in ref:
        n = ref["stud_rel_prev"]
        assert last is not None, key
        assert STUDS[stud] == STUDS[last[1]] + n, key
        if n == 0:
            assert has(CUES["stud_rel_same"], t), (key, "same stud not said")
        else:
            assert has(CUES["dir"][1 if n > 0 else -1], t), (key, "direction not said")
            assert has(NUM[abs(n)], t), (key, "count not said")
    if "stud_abs" in ref:
        assert STUDS[stud] == ref["stud_abs"], key
        assert has(CUES["stud_abs"][ref["stud_abs"]], t), (key, "stud position not said")
    if "stud_from_right" in ref:
        n = ref["stud_from_right"]
        assert STUDS[stud] == 13 - n, key
        assert has(CUES["stud_from_right"][n], t), (key, "from right not said")


def check_words(key, text, pid, stud, pl, ref):
    """Ids and placement words of a command (text: asides and corrections taken out)."""
    t = text.lower()
    said = {i for _, i in SAID.get(key, [])}
    assert pid in text or pid in said or any(k in ref for k in PANEL_KEYS), (key, "panel not said")
    assert stud in text or stud in said or any(k in ref for k in STUD_KEYS), (key, "stud not said")
    assert said <= {pid, stud}, (key, "id said as words is not the command's", said)
    for d in re.findall(r"\d{6}", text):
        assert d in (pid, stud), (key, "stray id", d)
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


def check_bim(key, pid):
    w, l = SIZE_FT[STACK_OF[pid]]
    if key in AREA_M2:
        assert abs(w * l * FT * FT - AREA_M2[key]) < 0.005, (key, "area", w * l * FT * FT)
    if key in MM:
        assert MM[key] == (round(w * FT * 1000), round(l * FT * 1000)), (key, "mm")


def back_refs(t):
    return [w for w in BACK_REF_WORDS if word_in(w, t)]


def main():
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl", encoding="utf-8") if l.strip()]
    gold = [json.loads(l) for l in open(HERE / "gold.jsonl", encoding="utf-8") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    assert [e["id"] for e in inst] == [f"fm{i:02d}" for i in range(1, 11)], "episode ids"
    texts = {(g["episode"], g["step"]): g["text"] for g in gold}
    for key, pairs in SAID.items():
        for words, i in pairs:
            assert words in texts[key], (key, words)
            assert spell(words) == i, (key, words, spell(words))
    refused = {(g["episode"], g["step"]) for g in gold if "refusal" in g["expect"]}
    n_ref = 0
    styles, reasons, placements, eps_per_style = {}, {}, {}, {}
    history = []
    for e in inst:
        ep = e["id"]
        rows = by_ep[ep]
        assert set(e) == {"id", "instructions"}, ep
        assert 5 <= len(rows) <= 6, (ep, len(rows))
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
            t = text.lower()
            if prev_refused:
                assert not back_refs(g["text"].lower()), \
                    (key, "back-reference right after a refusal", back_refs(g["text"].lower()))
            if "refusal" in x:
                assert set(x) == {"refusal"}, key
                n_ref += 1
                why = x["refusal"]
                assert why in REASONS, (key, why)
                reasons[why] = reasons.get(why, 0) + 1
                if why in ("overlap", "already_installed"):
                    pid, stud, pl = INTENDED[key]
                    iref = INTENDED_REFS.get(key, {})
                    check_refs(key, iref, pid, stud, last, t)
                    check_words(key, text, pid, stud, pl, iref)
                    assert problems(state, wall, pid, stud, pl) == [why], \
                        (key, why, problems(state, wall, pid, stud, pl))
                elif why == "empty_stack":
                    s, size, stud, pl = EMPTY[key]
                    assert not state[s], (key, "stack not empty", state[s])
                    assert stack_for_size(*size) == [s] and size_said(t, *size), key
                    assert has(CUES["stack"][s], t), key
                    assert stud in text and re.findall(r"\d{6}", text) == [stud], key
                    assert not geometry(wall, rect(None, stud, pl, SIZES[s])), (key, "would not fit either")
                    assert has(CENTRE_WORDS, t) == (pl == "vertical_middle"), key
                elif why == "no_size_match":
                    size, stud, pl = NO_MATCH[key]
                    assert not stack_for_size(*size), (key, size)
                    assert size_said(t, *size), (key, "size not said")
                    assert stud in STUDS and re.findall(r"\d{6}", text) == [stud], key
                    for cue in (CUES["dim"], CUES["desc"], *CUES["stack"].values(), tuple(NICK)):
                        assert not has(cue, t), (key, "a cue names a stack", cue)
                elif why == "off_end":
                    s, n = OFF_END[key]
                    assert last is not None, key
                    assert not 0 <= STUDS[last[1]] + n <= 12, (key, last, n)
                    assert state[s], (key, "stack empty too")
                    assert has(CUES["stack"][s] + CUES["desc"] + tuple(k for k, v in NICK.items() if v == s), t), key
                    assert has(CUES["dir"][1 if n > 0 else -1], t), key
                    assert has(NUM[abs(n)], t), key
                    assert not re.findall(r"\d{6}", text), (key, "an id would anchor it")
                elif why == "no_history":
                    stud = NO_HISTORY[key]
                    assert last is None, (key, "there is a last command", last)
                    assert "same size as the last one" in t, key
                    assert stud in STUDS and re.findall(r"\d{6}", text) == [stud], key
                    for cue in (CUES["dim"], CUES["desc"], tuple(NICK)):
                        assert not has(cue, t), (key, "a cue names the panel", cue)
                    assert not sizes_said(t), key
                else:
                    raise AssertionError((key, "no check for", why))
                prev_refused = True
                continue      # a refused step leaves site and history as they were
            prev_refused = False
            assert set(x) == {"drywall_id", "stud_id", "placement"}, key
            pid, stud, pl = x["drywall_id"], x["stud_id"], x["placement"]
            assert isinstance(pid, str) and isinstance(stud, str) and pl in PLACEMENTS, key
            assert key in REFS or key in SAID or (pid in text and stud in text), (key, "no REFS")
            ref = REFS.get(key, {})
            check_refs(key, ref, pid, stud, last, t)
            check_words(key, text, pid, stud, pl, ref)
            check_bim(key, pid)
            p = problems(state, wall, pid, stud, pl)
            assert not p, (key, x, p)
            state[STACK_OF[pid]].pop()
            wall.append((rect(pid, stud, pl), pid))
            last = (pid, stud)
            placements[pl] = placements.get(pl, 0) + 1
            if any(k in ref for k in HISTORY_KEYS):
                history.append(key)
    for table in (INTENDED, INTENDED_REFS, EMPTY, NO_MATCH, OFF_END, NO_HISTORY):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    assert set(DISTRACTORS) | set(SAID) | set(CORRECTIONS) <= set(texts), "table names a missing step"
    assert set(eps_per_style.values()) == {2} and len(eps_per_style) == 5, eps_per_style
    assert len(set(reasons)) == n_ref, ("two refusals share a reason", reasons)
    n = len(gold)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("refusals:", reasons)
    print("placements:", placements)
    print(f"history-dependent steps={len(history)}:", " ".join(f"{e}/{s}" for e, s in history))
    print(f"ids said as words={sum(map(len, SAID.values()))}, asides={len(DISTRACTORS)}, "
          f"corrections={len(CORRECTIONS)}")
    print("OK")


if __name__ == "__main__":
    main()
