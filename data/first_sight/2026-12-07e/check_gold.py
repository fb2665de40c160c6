"""Stand-alone checker for the first-sight set of 2026-12-07e.

Written from ../shared/spec/case-study.md (sections 1, 3, 4 and 5) with the
2026-12-07d checker's layout as a template; standard library only, it does not
import drywall_lab.  Every episode is replayed from the fresh site (all nine
panels stacked, nothing installed, empty history) and the script asserts that
  - every expected command is feasible: the panel exists and is the top one of
    its stack, is not on the wall yet, stays inside the wall (x_right <=
    4.8768 + 0.01905) and shares no positive area with an installed panel
    (touching edges are allowed);
  - every expected refusal is for exactly the reason written in the gold:
      overlap / not_on_top / past_wall / already_installed: the intended
        command (INTENDED) fails for that reason and for no other (an
        installed panel is not tested against itself), and its words name it;
      unknown_id: the id said (UNKNOWN) is no panel or stud of the site, and
        the other ids said exist;
      ambiguous_size: the one number said (AMBIGUOUS) is the length of two
        sizes, nothing else in the text names a stack, and both readings would
        be carried out as they stand;
      off_end: the stack counted from the last panel's stack (OFF_END) falls
        outside left ... right;
      undetermined: the panel is named but no stud is (UNDETERMINED): no id,
        no stud position, no stud relative to the last one;
      unclear: the words leave two or more commands (UNCLEAR), each of which
        would be carried out as it stands, and each has its cue in the text;
  - the references that are not ids (REFS: sizes said width first or turned,
    one length said as "six-footer", size words, "narrow" / "skinny" / "узкий",
    absolute stacks, "same size" / "same kind" as the last panel, studs by
    position, studs relative to the last stud, "same stud") agree with the
    gold, are backed by a cue word in the text (CUES), and the history-based
    ones only ever use an accepted command;
  - asides that name a row, size or stud that is not this command's
    (DISTRACTORS: quoted e-mail lines, furniture sizes, a window between two
    studs) and words taken back in the same step (CORRECTIONS: a stud, a
    panel or a placement that the other worker overrules) are in the text and
    are taken out before the checks of ids, sizes and placement words;
  - ids written with a space (SAID: "500 103") are in the text and give the
    id of the gold;
  - each command's panel and stud are said or derived, no other id is said as
    digits, no other size is left in the text, and the placement words agree
    with the placement (English, Russian, client phrasing "along the top",
    "lined up with the middle of the stud"; a vertical_left step names no
    centre line, row or lying flat);
  - the step after a refusal holds no back-reference word (BACK_REF_WORDS);
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    ids fn01..fn10, 5 or 6 steps an episode, one voice an episode, five
    voices of two episodes each, and no two refusals share a reason.
usage: python3 check_gold.py
"""
import json
import pathlib
import re

HERE = pathlib.Path(__file__).resolve().parent
H = 2.4384
WALL_END = 4.8768 + 0.01905
EPS = 1e-9
SIZES = {"left": (1.2192, 2.4384), "middle": (0.6096, 2.4384), "right": (1.2192, 1.8288)}
SIZE_FT = {"left": (4, 8), "middle": (2, 8), "right": (4, 6)}
STACK_ORDER = ("left", "middle", "right")
FRESH = {"left": ["500300", "500310", "500320"],      # bottom -> top
         "middle": ["500301", "500311", "500321"],
         "right": ["500302", "500312", "500322"]}
STACK_OF = {pid: s for s, ids in FRESH.items() for pid in ids}
STUDS = {str(500100 + i): i for i in range(13)}
PLACEMENTS = ("vertical_left", "vertical_middle", "horizontal_top", "horizontal_bottom")
REASONS = ("overlap", "past_wall", "not_on_top", "already_installed", "empty_stack",
           "unknown_id", "no_history", "off_end", "no_size_match", "ambiguous_size",
           "unclear", "undetermined")
VOICES = ("russian_switch", "email_reply", "length_first", "client_walkthrough", "crew_crosstalk")

# Refused steps -------------------------------------------------------------
INTENDED = {   # what the worker meant, for refusals that depend on the site
    ("fn01", 4): ("500312", "500108", "vertical_middle"),   # 4x6 on the centre line of 500108 runs into the 4x6 on 500106
    ("fn02", 2): ("500301", "500102", "vertical_middle"),   # 500301 is the bottom of the middle stack
    ("fn03", 3): ("500320", "500100", "vertical_left"),     # e-mail resent: 500320 went up at step 0
    ("fn06", 2): ("500322", "500108", "horizontal_bottom"), # a flat 4x6 from 500108 ends at x = 5.061
}
INTENDED_REFS = {
    ("fn01", 4): {"size": (4, 6)},
    ("fn06", 2): {"size": (6, 4)},
}
UNKNOWN = {("fn04", 3): ("500330", "500100")}       # (unknown id said, the other id said)
AMBIGUOUS = {("fn05", 3): (8, "500109", "vertical_middle")}   # "eight-footer": 4x8 and 2x8
OFF_END = {("fn07", 3): 1}        # the pile right of the right pile
UNDETERMINED = {("fn08", 2): "right"}   # panel from the right-hand pile, no stud at all
UNCLEAR = {("fn09", 3): [("500322", "500106", "vertical_middle"),
                         ("500322", "500106", "vertical_left")]}   # centre line or left line, not settled

SAID = {   # ids written with a space: (exact words in the text, id)
    ("fn07", 1): [("500 103", "500103")],
}
DISTRACTORS = {   # asides naming a row, size or stud that is not this command's
    ("fn01", 5): ["Саша, 4x8 на потолок после обеда."],        # Sasha: the 4x8 on the ceiling after lunch
    ("fn02", 4): ["На последний стад не влезет"],               # it won't fit on the last stud
    ("fn03", 1): ["I was thinking stud 500104."],               # quoted question
    ("fn03", 5): ["> Can we do the 2x8 on 500111? That's where the drawing has it."],
    ("fn04", 1): ["> Dana, is the 2x8 in the top row here?"],   # quoted question, names the top row
    ("fn04", 4): ["not 500330"],                                # the typo taken back
    ("fn07", 1): ["it's about six feet wide"],                  # the bookshelf
    ("fn07", 4): ["my grandmother's mirror goes up there, it's 30 by 40."],
    ("fn08", 0): ["fairy lights along the top one day"],        # a top row that is not this one
    ("fn08", 3): ["the window's going between 500106 and 500108"],
    ("fn08", 4): ["the Wi-Fi box sits at 48 inches"],
}
CORRECTIONS = {   # words taken back in the same step, and the words that take them back
    ("fn09", 1): ("500104", "nah, 500103"),
    ("fn10", 1): ("same again", "nah, use a full sheet"),
    ("fn10", 2): ("500105", "that'll hit the top sheet, go 500106"),
    ("fn10", 4): ("left line", "make it the centre line"),
}

REFS = {
    ("fn01", 0): {"dim": "full", "stack": "left"},
    ("fn01", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fn01", 2): {"desc": "narrow", "stack": "middle"},
    ("fn01", 3): {"size": (4, 6), "stack": "right", "stud_rel_prev": 0},
    ("fn02", 0): {"size": (4, 8), "stack": "left", "stud_abs": 6},
    ("fn02", 1): {"desc": "narrow", "stack": "middle", "stud_abs": 0},
    ("fn02", 3): {"size": (2, 8), "stack": "middle"},
    ("fn02", 4): {"size": (4, 8), "stack": "left"},
    ("fn03", 1): {"size": (2, 8)},
    ("fn03", 2): {"size": (4, 6), "stack": "right"},
    ("fn03", 4): {"size": (4, 6), "stack": "right"},
    ("fn03", 5): {"size": (2, 8), "stack": "middle"},
    ("fn04", 0): {"dim": "full", "stack": "left"},
    ("fn04", 1): {"size": (2, 8), "stack": "middle"},
    ("fn04", 2): {"size": (4, 6), "stack": "right", "stud_rel_prev": 0},
    ("fn05", 0): {"size": (8, 4)},
    ("fn05", 1): {"footer": 6},
    ("fn05", 2): {"size": (8, 2), "stud_rel_prev": 0},
    ("fn05", 4): {"size": (8, 4)},
    ("fn05", 5): {"size": (6, 4), "stud_rel_prev": -3},
    ("fn06", 0): {"size": (8, 2), "stud_abs": 6},
    ("fn06", 1): {"size": (8, 4)},
    ("fn06", 3): {"size": (6, 4)},
    ("fn06", 4): {"footer": 6, "same_size_as_prev": True, "stud_abs": 0},
    ("fn07", 0): {"size": (4, 8)},
    ("fn07", 1): {"same_size_as_prev": True},
    ("fn07", 2): {"stack": "right"},
    ("fn07", 4): {"desc": "narrow", "stack": "middle"},
    ("fn07", 5): {"stack": "right"},
    ("fn08", 0): {"desc": "narrow", "stack": "middle"},
    ("fn08", 1): {"size": (4, 8), "stud_rel_prev": 0},
    ("fn08", 3): {"stack": "right"},
    ("fn08", 4): {"same_size_as_prev": True},
    ("fn09", 0): {"dim": "full", "stack": "left"},
    ("fn09", 1): {"dim": "full"},
    ("fn09", 2): {"desc": "narrow", "stack": "middle"},
    ("fn09", 4): {"size": (4, 6), "stack": "right"},
    ("fn09", 5): {"size": (4, 6), "stud_rel_prev": 3},
    ("fn10", 0): {"size": (4, 6), "stack": "right", "stud_abs": 0},
    ("fn10", 1): {"dim": "full", "stud_rel_prev": 0},
    ("fn10", 2): {"desc": "narrow", "stack": "middle"},
    ("fn10", 3): {"desc": "narrow", "same_size_as_prev": True, "stud_rel_prev": 2},
    ("fn10", 4): {"desc": "narrow", "stack": "middle"},
}
PANEL_KEYS = ("size", "dim", "desc", "stack", "same_size_as_prev", "footer")
STUD_KEYS = ("stud_abs", "stud_rel_prev")
HISTORY_KEYS = ("same_size_as_prev", "stud_rel_prev")

# Cue words that must back each reference in the text ------------------------
NUM = {2: ("2", "two", "два", "два"), 3: ("3", "three", "три"), 4: ("4", "four"),
       6: ("6", "six"), 8: ("8", "eight")}
CUES = {
    "dim": ("full",),
    "desc": ("narrow", "skinny", "узкий"),
    "stack": {"left": ("left stack", "левой стопки"),
              "middle": ("middle stack", "middle pile", "off the middle", "from the middle", "со средней"),
              "right": ("right stack", "pile on the right", "right-hand pile", "правой стопки")},
    "same_size_as_prev": ("same size", "same kind", "такой же", "another"),
    "stud_rel_same": ("same stud", "того же стада", "same stud 500103"),
    "dir": {1: ("right of that one", "вправо"), -1: ("left of that one", "влево")},
    "stud_abs": {0: ("first stud", "первый стад слева"),
                 6: ("middle stud", "средний стад")},
}
# one length said alone ("six-footer"); "eight-footer" is the length of two sizes
FOOTER = {6: "six-footer", 8: "eight-footer"}

BACK_REF_WORDS = ("previous", "last", "same", "again", "that one", "of that", "from that",
                  "from there", "another", "other", "before", "too", "one more", "as well",
                  "above", "under it", "on top of it", "it again", "just",
                  # Russian
                  "такой же", "тот же", "того же", "ещё", "еще", "тоже", "под него", "над ним",
                  "прошлый", "предыдущий", "последний", "снова", "опять")
TOP_PHRASES = ("top row", "верхний ряд", "along the top")
BOTTOM_PHRASES = ("bottom row", "нижний ряд", "along the bottom")
CENTRE_WORDS = ("centre", "center", "по центру", "middle of the stud")
FLAT_WORDS = ("flat", "lay", "laid", "lying", "sideways", "row", "лёжа", "лежа", "ряд")
WORDNUM = {"two": 2, "four": 4, "six": 6, "eight": 8}


def word_in(w, t):
    return re.search(r"(?<![\w'])" + re.escape(w) + r"(?![\w'])", t)


def has(words, t):
    return any(word_in(w, t) for w in words)


def stack_for_size(a, b):
    hits = [s for s, wl in SIZE_FT.items() if wl == (a, b)]
    return hits or [s for s, wl in SIZE_FT.items() if wl == (b, a)]


def stacks_for_length(n):
    return [s for s, (_, l) in SIZE_FT.items() if l == n]


def sizes_said(t):
    """Every 'A x B' / 'A by B' / 'A-by-B' in the (lower-case) text, digits or words."""
    n = r"(\d+|two|four|six|eight)"
    out = set()
    for a, b in re.findall(r"(?<![\w/])" + n + r"\s*(?:x|-by-|\s+by\s+)\s*" + n + r"(?!\w)", t):
        out.add((int(WORDNUM.get(a, a)), int(WORDNUM.get(b, b))))
    return out


def take_out(key, text):
    """The text with asides and corrected-away words taken out."""
    for phrase in DISTRACTORS.get(key, []):
        i = text.find(phrase)
        assert i >= 0, (key, "aside not in text", phrase)
        text = text[:i] + " " + text[i + len(phrase):]
    if key in CORRECTIONS:
        old, marker = CORRECTIONS[key]
        i, j = text.find(old), text.find(marker)
        assert 0 <= i < j, (key, "correction not in text, or not before the words that take it back")
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


def check_refs(key, ref, pid, stud, last, t):
    """The references agree with the gold and each has its cue word in t (lower case)."""
    s = STACK_OF[pid]
    if "size" in ref:
        assert stack_for_size(*ref["size"]) == [s], (key, ref)
        assert ref["size"] in sizes_said(t), (key, "size not said", ref["size"])
    for a, b in sizes_said(t):   # every size left in the text is this panel's
        assert stack_for_size(a, b) == [s], (key, "another size in the text", (a, b))
    if "footer" in ref:
        assert stacks_for_length(ref["footer"]) == [s], (key, ref)
        assert word_in(FOOTER[ref["footer"]], t), (key, "footer not said")
    for n, w in FOOTER.items():
        if word_in(w, t):
            assert ref.get("footer") == n, (key, "a length said that is not a reference", w)
    if "dim" in ref:
        assert ref["dim"] == "full" and s == "left", (key, ref)
        assert has(CUES["dim"], t), (key, "size word not said")
    if "desc" in ref:   # "narrow", "skinny", "узкий": the one size 2 ft wide
        assert ref["desc"] == "narrow"
        assert [x for x, (w, _) in SIZE_FT.items() if w == 2] == [s], key
        assert has(CUES["desc"], t), (key, "narrow not said")
    if "stack" in ref:
        assert ref["stack"] == s, (key, ref)
        assert has(CUES["stack"][s], t), (key, "stack not said")
    for other, cues in CUES["stack"].items():   # no other stack named
        if other != s:
            assert not has(cues, t), (key, "another stack named", other)
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


def ids_in(text):
    return re.findall(r"\d{6}", text)


def check_words(key, text, pid, stud, pl, ref):
    """Ids and placement words of a command (text: asides and corrections taken out)."""
    t = text.lower()
    said = {i for _, i in SAID.get(key, [])}
    assert pid in text or pid in said or any(k in ref for k in PANEL_KEYS), (key, "panel not said")
    assert stud in text or stud in said or any(k in ref for k in STUD_KEYS), (key, "stud not said")
    assert said <= {pid, stud}, (key, "id said with a space is not the command's", said)
    for d in ids_in(text):
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


def back_refs(t):
    return [w for w in BACK_REF_WORDS if word_in(w, t)]


def stud_cues(t):
    cues = CUES["stud_rel_same"] + CUES["dir"][1] + CUES["dir"][-1] + \
        sum(CUES["stud_abs"].values(), ()) + ("last stud", "последний стад", "stud marked")
    return [w for w in cues if word_in(w, t)]


def check_refusal(key, why, state, wall, last, text):
    t = text.lower()
    if why in ("overlap", "not_on_top", "past_wall", "already_installed"):
        pid, stud, pl = INTENDED[key]
        iref = INTENDED_REFS.get(key, {})
        check_refs(key, iref, pid, stud, last, t)
        check_words(key, text, pid, stud, pl, iref)
        got = problems(state, wall, pid, stud, pl)
        assert got == [why], (key, why, got)
    elif why == "unknown_id":
        bad, other = UNKNOWN[key]
        assert bad not in STACK_OF and bad not in STUDS and bad in text, key
        assert set(ids_in(text)) == {bad, other} and (other in STACK_OF or other in STUDS), key
    elif why == "ambiguous_size":
        n, stud, pl = AMBIGUOUS[key]
        hits = stacks_for_length(n)
        assert len(hits) >= 2 and word_in(FOOTER[n], t), (key, hits)
        assert not sizes_said(t), key
        for cue in (CUES["dim"], CUES["desc"], *CUES["stack"].values()):
            assert not has(cue, t), (key, "a cue names a stack", cue)
        assert ids_in(text) == [stud], key
        for s in hits:   # each reading would be carried out as it stands
            assert state[s], (key, s)
            assert not problems(state, wall, state[s][-1], stud, pl), (key, "a reading fails anyway", s)
        assert has(CENTRE_WORDS, t) == (pl == "vertical_middle"), key
    elif why == "off_end":
        n = OFF_END[key]
        assert last is not None, key
        i = STACK_ORDER.index(STACK_OF[last[0]]) + n
        assert not 0 <= i < len(STACK_ORDER), (key, last, n)
        assert has(("pile to the right of that one",) if n > 0 else ("pile to the left of that one",), t), key
        assert not ids_in(text), (key, "an id would name the panel")
    elif why == "undetermined":
        s = UNDETERMINED[key]
        assert has(CUES["stack"][s], t), key
        assert not ids_in(text) and not stud_cues(t), (key, "a stud is named", stud_cues(t))
    elif why == "unclear":
        options = UNCLEAR[key]
        assert len(set(options)) >= 2, key
        for pid, stud, pl in options:
            assert not problems(state, wall, pid, stud, pl), (key, "an option fails anyway", pid, stud, pl)
            assert stud in text, key
        pls = {pl for _, _, pl in options}
        if "vertical_middle" in pls:
            assert has(CENTRE_WORDS, t), key
        if "vertical_left" in pls:
            assert word_in("left line", t), key
    else:
        raise AssertionError((key, "no check for", why))


def main():
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl", encoding="utf-8") if l.strip()]
    gold = [json.loads(l) for l in open(HERE / "gold.jsonl", encoding="utf-8") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    assert [e["id"] for e in inst] == [f"fn{i:02d}" for i in range(1, 11)], "episode ids"
    texts = {(g["episode"], g["step"]): g["text"] for g in gold}
    for key, pairs in SAID.items():
        for words, i in pairs:
            assert words in texts[key], (key, words)
            assert words.replace(" ", "") == i, (key, words)
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
                check_refusal(key, why, state, wall, last, text)
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
            p = problems(state, wall, pid, stud, pl)
            assert not p, (key, x, p)
            state[STACK_OF[pid]].pop()
            wall.append((rect(pid, stud, pl), pid))
            last = (pid, stud)
            placements[pl] = placements.get(pl, 0) + 1
            if any(k in ref for k in HISTORY_KEYS):
                history.append(key)
    for table in (INTENDED, INTENDED_REFS, UNKNOWN, AMBIGUOUS, OFF_END, UNDETERMINED, UNCLEAR):
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
    print(f"ids with a space={sum(map(len, SAID.values()))}, asides={len(DISTRACTORS)}, "
          f"corrections={len(CORRECTIONS)}")
    print("OK")


if __name__ == "__main__":
    main()
