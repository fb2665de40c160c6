"""Stand-alone checker for the first-sight set of 2026-12-07c.

Written from ../shared/spec/case-study.md (sections 1, 3, 4 and 5) and the
2026-12-07b checker as a template; standard library only, it does not import
drywall_lab.  Every episode is replayed from the fresh site (all nine panels
stacked, nothing installed, empty history) and the script asserts that
  - every expected command is feasible: the panel exists and is the top one of
    its stack, is not on the wall yet, stays inside the wall (x_right <=
    4.8768 + 0.01905) and shares no positive area with an installed panel
    (touching edges are allowed);
  - every expected refusal is for exactly the reason written in the gold:
      overlap / past_wall / not_on_top / unknown_id: the intended command
        (INTENDED) fails for that reason and for no other, and its words name it;
      off_end: the stud counted from the last stud (OFF_END) falls outside
        500100 ... 500112, while the panel asked for is there to be taken;
      ambiguous_size: the single number said (AMBIG) fits two sizes, both
        stacks have a panel, each reading could be carried out as it stands,
        and nothing else in the text (stack, size word, id) tells them apart;
  - the references that are not ids (REFS: sizes as given or turned, size
    words, "narrow"/"skinny"/"stretta"/"patla", absolute stacks, "same size" as
    the last panel, studs by position from either end, studs relative to the
    last stud, "same stud") agree with the gold, are backed by a cue word in
    the text (CUES), and the history-based ones only ever use an accepted
    command;
  - asides that name a row or a side not meant for this command (DISTRACTORS:
    "row 12 of the install sheet", "la fila in alto sull'altra parete") are in
    the text and are taken out before the placement-word checks;
  - ids spoken as words (SAID: "cinque zero zero uno zero tre", "five hundred
    one hundred six", "five oh oh one oh eight") are in the text and spell the
    id of the gold;
  - each command's panel and stud are said or derived, no other id is said as
    digits, and the placement words agree with the placement (English,
    Italian, Hinglish, article-dropping and spreadsheet phrasing; a
    vertical_left step names no centre line, row or lying flat);
  - the step after a refusal holds no back-reference word (BACK_REF_WORDS);
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    ids fl01..fl10, 5 or 6 steps an episode, one voice an episode, five
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

# Refused steps -------------------------------------------------------------
INTENDED = {   # what the worker meant, for refusals that depend on the site
    ("fl01", 3): ("500322", "500104", "horizontal_bottom"),  # 4x6 flat from 500104 runs into the 2x8s on 500103 and 500105
    ("fl03", 3): ("500301", "500106", "horizontal_top"),     # 500301 lies under 500311 and 500321
    ("fl07", 3): ("500312", "500113", "vertical_left"),      # there is no stud 500113
    ("fl08", 3): ("500322", "500110", "vertical_left"),      # 4x6 upright from 500110: ends at x = 5.263
}
INTENDED_REFS = {
    ("fl01", 3): {"size": (4, 6), "stack": "right"},
    ("fl08", 3): {"size": (4, 6), "stack": "right"},
}
OFF_END = {("fl09", 3): ("middle", 5)}    # "five studs to the right of that one", last stud 500108
AMBIG = {("fl05", 3): (8, "500100", "horizontal_top")}   # "length eight": 4 x 8 or 2 x 8

SAID = {   # ids said as words: (exact words in the text, id)
    ("fl01", 1): [("cinque zero zero uno zero tre", "500103")],
    ("fl02", 3): [("cinque zero zero uno zero nove", "500109")],
    ("fl05", 0): [("five hundred one hundred", "500100")],
    ("fl06", 1): [("five hundred one hundred six", "500106")],
    ("fl09", 2): [("five oh oh one oh eight", "500108")],
    ("fl10", 4): [("five oh oh one oh eight", "500108")],
}
DISTRACTORS = {   # asides naming a row or side that is not this command's
    ("fl02", 4): ["La fila in alto sull'altra parete"],
    ("fl07", 0): ["row 12"],
    ("fl10", 3): ["the top row on the east wall"],
}

REFS = {
    ("fl01", 0): {"dim": "full", "stack": "left"},
    ("fl01", 1): {"desc": "narrow", "size": (2, 8)},
    ("fl01", 2): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fl01", 4): {"size": (4, 6), "stack": "right"},
    ("fl01", 5): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fl02", 0): {"size": (4, 6), "stack": "right", "stud_abs": 2},
    ("fl02", 1): {"desc": "narrow", "stack": "middle", "stud_rel_prev": 0},
    ("fl02", 2): {"size": (4, 6), "stud_rel_prev": 3},
    ("fl02", 3): {"dim": "full"},
    ("fl02", 4): {"desc": "narrow", "stack": "middle", "stud_abs": 0},
    ("fl03", 0): {"dim": "full", "stack": "left"},
    ("fl03", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fl03", 2): {"size": (4, 6), "stack": "right", "stud_rel_prev": 6},
    ("fl03", 4): {"desc": "narrow", "stack": "middle", "size": (2, 8)},
    ("fl03", 5): {"size": (4, 6), "stack": "right", "stud_from_right": 4},
    ("fl04", 0): {"desc": "narrow", "stack": "middle", "size": (2, 8)},
    ("fl04", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fl04", 2): {"dim": "full", "stack": "left", "stud_abs": 6},
    ("fl04", 3): {"size": (4, 6), "stack": "right", "stud_rel_prev": 3},
    ("fl04", 4): {"desc": "narrow", "stack": "middle", "stud_abs": 0},
    ("fl05", 0): {"dim": "full", "stack": "left"},
    ("fl05", 1): {"desc": "narrow"},
    ("fl05", 2): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fl05", 4): {"size": (4, 8), "stack": "left"},
    ("fl05", 5): {"desc": "narrow", "stack": "middle"},
    ("fl06", 0): {"size": (4, 6), "stack": "right", "stud_from_right": 5},
    ("fl06", 1): {"desc": "narrow"},
    ("fl06", 2): {"same_size_as_prev": True, "stud_rel_prev": -6},
    ("fl06", 3): {"size": (6, 4), "stack": "right", "stud_abs": 0},
    ("fl06", 4): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fl07", 5): {"size": (2, 8), "stud_rel_prev": 5},
    ("fl08", 0): {"size": (4, 8), "stack": "left"},
    ("fl08", 1): {"same_size_as_prev": True, "stack": "left", "stud_rel_prev": 0},
    ("fl08", 2): {"size": (2, 8)},
    ("fl08", 4): {"size": (2, 8), "stack": "middle"},
    ("fl09", 0): {"dim": "full", "stack": "left"},
    ("fl09", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fl09", 2): {"desc": "narrow", "size": (2, 8), "stack": "middle"},
    ("fl09", 4): {"size": (2, 8), "stack": "middle"},
    ("fl09", 5): {"desc": "narrow", "stack": "middle", "stud_abs": 0},
    ("fl10", 0): {"size": (4, 6)},
    ("fl10", 1): {"size": (4, 6), "stud_rel_prev": 0},
    ("fl10", 2): {"dim": "full", "stack": "left", "stud_rel_prev": 5},
    ("fl10", 3): {"desc": "narrow", "stack": "middle", "stud_from_right": 3},
    ("fl10", 4): {"desc": "narrow", "same_size_as_prev": True},
}
PANEL_KEYS = ("size", "single", "dim", "desc", "stack", "same_size_as_prev")
STUD_KEYS = ("stud_abs", "stud_from_right", "stud_rel_prev")
HISTORY_KEYS = ("same_size_as_prev", "stud_rel_prev")

# Cue words that must back each reference in the text ------------------------
NUM = {2: ("2", "two", "due", "do"), 3: ("3", "three", "tre", "teen"),
       4: ("4", "four", "quattro", "char"), 5: ("5", "five", "cinque", "paanch"),
       6: ("6", "six", "sei", "chhe"), 8: ("8", "eight", "otto", "aath")}
CUES = {
    "dim": ("full", "standard"),
    "desc": ("narrow", "skinny", "strett", "patla"),
    "stack": {"left": ("left", "sinistra"),
              "middle": ("middle", "mezzo", "beech"),
              "right": ("right", "destra")},
    "same_size_as_prev": ("same size", "stessa misura", "same like before", "ditto",
                          "one more of those"),
    "stud_rel_same": ("same stud", "stesso montante", "stud=ditto"),
    "dir": {1: ("right", "destra", "+"), -1: ("left", "sinistra")},
    "stud_abs": {0: ("primo montante", "pehle stud", "first stud", "leftmost stud"),
                 2: ("terzo montante",), 6: ("saatva stud",)},
    "stud_from_right": {3: ("third stud from the right",),
                        4: ("chautha stud right se",),
                        5: ("fifth stud from right",)},
}

BACK_REF_WORDS = ("previous", "prev", "last", "same", "again", "that one", "of that",
                  "from that", "those", "just", "ditto", "another", "other", "before",
                  "too", "him", "her", "them", "one more", "more like", "like before",
                  # Italian
                  "stesso", "stessa", "prima", "ultimo", "ultima", "precedente",
                  "ancora", "altro", "altra", "un'altra", "anche", "di lei", "sopra di lei",
                  "di nuovo", "quella di", "come prima",
                  # Hinglish
                  "pichhle", "pichhla", "pichla", "uske", "iske", "usi", "wahi", "ek aur",
                  "phir se", "dobara", "wala hi")
TOP_PHRASES = ("top row", "row top", "row=top", "fila in alto")
BOTTOM_PHRASES = ("bottom row", "row bottom", "row=bottom", "fila in basso")
CENTRE_WORDS = ("centre", "center", "ctr", "linea centrale", "mezzeria", "middle of stud",
                "edge at middle")
FLAT_WORDS = ("flat", "horizontal", "lying", "laid", "lay ", " row", "sdraiat",
              "orizzontal", "fila", "lita ", "leta ")
UNITS = {"oh": 0, "o": 0, "zero": 0, "one": 1, "uno": 1, "two": 2, "due": 2, "three": 3,
         "tre": 3, "four": 4, "quattro": 4, "five": 5, "cinque": 5, "six": 6, "sei": 6,
         "seven": 7, "sette": 7, "eight": 8, "otto": 8, "nine": 9, "nove": 9}


def spell(words):
    """Digits of a spoken id.

    Digit by digit: 'cinque zero zero uno zero tre' -> '500103',
    'five oh oh one oh eight' -> '500108'.  In groups of hundreds:
    'five hundred one hundred six' -> '500' + '106' (a digit followed by
    'hundred' opens a new three-digit group)."""
    toks = [t for t in re.split(r"[\s\-]+", words.lower()) if t]
    if "hundred" not in toks:
        return "".join(t if t.isdigit() else str(UNITS[t]) for t in toks)
    groups, i = [], 0
    while i < len(toks):
        assert i + 1 < len(toks) and toks[i + 1] == "hundred", (words, "group")
        val = UNITS[toks[i]] * 100
        i += 2
        while i < len(toks) and not (i + 1 < len(toks) and toks[i + 1] == "hundred"):
            val += UNITS[toks[i]]
            i += 1
        groups.append(f"{val:03d}")
    return "".join(groups)


def stack_for_size(a, b):
    hits = [s for s, wl in SIZE_FT.items() if wl == (a, b)]
    return hits or [s for s, wl in SIZE_FT.items() if wl == (b, a)]


def stacks_for_single(n):
    return [s for s, (w, l) in SIZE_FT.items() if n in (w, l)]


def size_said(t, a, b):
    """'4x8', '4 by 8', 'four by eight', 'quattro per sei' in the (lower-case) text."""
    alt = lambda n: "(?:" + "|".join(map(re.escape, NUM[n])) + ")"
    return re.search(r"(?<!\w)" + alt(a) + r"\s*(?:x|by|per)\s*" + alt(b) + r"(?!\w)", t)


def strip_distractors(key, text):
    """The text with the asides that are not about this command taken out."""
    for phrase in DISTRACTORS.get(key, []):
        i = text.find(phrase)
        assert i >= 0, (key, "aside not in text", phrase)
        text = text[:i] + " " + text[i + len(phrase):]
    return text


def rect(pid, stud, placement):
    w, l = SIZES[STACK_OF[pid]]
    c = 0.4064 * STUDS[stud]
    left = c - 0.01905
    return {"vertical_left": (left, left + w, 0.0, l),
            "vertical_middle": (c, c + w, 0.0, l),
            "horizontal_top": (left, left + l, H - w, H),
            "horizontal_bottom": (left, left + l, 0.0, w)}[placement]


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
    x0, x1, z0, z1 = rect(pid, stud, placement)
    if x1 > WALL_END + EPS:
        out.append("past_wall")
    if any(min(x1, a1) - max(x0, a0) > EPS and min(z1, b1) - max(z0, b0) > EPS
           for (a0, a1, b0, b1), _ in wall):
        out.append("overlap")
    return out


def word_in(w, t):
    return re.search(r"(?<!\w)" + re.escape(w) + r"(?!\w)", t)


def check_refs(key, ref, pid, stud, last, t):
    """The references agree with the gold and each has its cue word in t (lower case)."""
    s = STACK_OF[pid]
    has = lambda words: any(w in t for w in words)
    if "size" in ref:
        assert stack_for_size(*ref["size"]) == [s], (key, ref)
        assert size_said(t, *ref["size"]), (key, "size not said", ref["size"])
    if "dim" in ref:
        assert ref["dim"] == "full" and s == "left", (key, ref)
        assert has(CUES["dim"]), (key, "size word not said")
    if "desc" in ref:   # "narrow", "skinny", "stretta", "patla": the one size 2 ft wide
        assert ref["desc"] == "narrow"
        assert [x for x, (w, _) in SIZE_FT.items() if w == 2] == [s], key
        assert has(CUES["desc"]), (key, "narrow not said")
    if "stack" in ref:
        assert ref["stack"] == s, (key, ref)
        assert has(CUES["stack"][s]), (key, "stack not said")
    if "same_size_as_prev" in ref:
        assert last is not None and SIZE_FT[STACK_OF[last[0]]] == SIZE_FT[s], key
        assert has(CUES["same_size_as_prev"]), (key, "same size not said")
    if "stud_rel_prev" in ref:
        n = ref["stud_rel_prev"]
        assert last is not None, key
        assert STUDS[stud] == STUDS[last[1]] + n, key
        if n == 0:
            assert has(CUES["stud_rel_same"]), (key, "same stud not said")
        else:
            assert has(CUES["dir"][1 if n > 0 else -1]), (key, "direction not said")
            assert any(word_in(w, t) for w in NUM[abs(n)]), (key, "count not said")
    if "stud_abs" in ref:
        assert STUDS[stud] == ref["stud_abs"], key
        assert has(CUES["stud_abs"][ref["stud_abs"]]), (key, "stud position not said")
    if "stud_from_right" in ref:
        assert STUDS[stud] == 13 - ref["stud_from_right"], key
        assert has(CUES["stud_from_right"][ref["stud_from_right"]]), (key, "from right not said")


def check_words(key, text, pid, stud, pl, ref):
    t = text.lower()
    said = {i for _, i in SAID.get(key, [])}
    assert pid in text or pid in said or any(k in ref for k in PANEL_KEYS), (key, "panel not said")
    assert stud in text or stud in said or any(k in ref for k in STUD_KEYS), (key, "stud not said")
    assert said <= {pid, stud}, (key, "id said as words is not the command's", said)
    for sid in STUDS:
        assert sid == stud or sid not in text, (key, "other stud id", sid)
    for p in STACK_OF:
        assert p == pid or p not in text, (key, "other panel id", p)
    for d in re.findall(r"\d{6}", text):
        assert d in (pid, stud), (key, "stray id", d)
    has = lambda words: any(w in t for w in words)
    if pl == "horizontal_top":
        assert has(TOP_PHRASES) and not has(BOTTOM_PHRASES) and not has(CENTRE_WORDS), key
    elif pl == "horizontal_bottom":
        assert has(BOTTOM_PHRASES) and not has(TOP_PHRASES) and not has(CENTRE_WORDS), key
    elif pl == "vertical_middle":
        assert has(CENTRE_WORDS), key
        assert not has(FLAT_WORDS + TOP_PHRASES + BOTTOM_PHRASES), key
    else:
        for w in CENTRE_WORDS + TOP_PHRASES + BOTTOM_PHRASES + FLAT_WORDS:
            assert w not in t, (key, w)


def back_refs(t):
    return [w for w in BACK_REF_WORDS
            if re.search(r"(?<![\w'])" + re.escape(w) + r"(?![\w'])", t)]


def main():
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl", encoding="utf-8") if l.strip()]
    gold = [json.loads(l) for l in open(HERE / "gold.jsonl", encoding="utf-8") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    assert [e["id"] for e in inst] == [f"fl{i:02d}" for i in range(1, 11)], "episode ids"
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
        assert len({g["style"] for g in rows}) == 1, ep
        eps_per_style[rows[0]["style"]] = eps_per_style.get(rows[0]["style"], 0) + 1
        state = {s: list(ids) for s, ids in FRESH.items()}   # fresh site every episode
        wall = []         # ((x0, x1, z0, z1), pid)
        last = None       # (pid, stud) of the last accepted command
        prev_refused = False
        for g in rows:
            key = (ep, g["step"])
            x = g["expect"]
            styles[g["style"]] = styles.get(g["style"], 0) + 1
            text = strip_distractors(key, g["text"])
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
                if why in ("overlap", "past_wall", "not_on_top", "already_installed",
                           "unknown_id"):
                    pid, stud, pl = INTENDED[key]
                    iref = INTENDED_REFS.get(key, {})
                    check_refs(key, iref, pid, stud, last, t)
                    check_words(key, text, pid, stud, pl, iref)
                    assert problems(state, wall, pid, stud, pl) == [why], \
                        (key, why, problems(state, wall, pid, stud, pl))
                    if why == "unknown_id":   # the panel itself could be taken
                        assert pid in STACK_OF and state[STACK_OF[pid]][-1:] == [pid], key
                        assert stud not in STUDS and stud in text, key
                elif why == "off_end":
                    s, n = OFF_END[key]
                    assert last is not None, key
                    assert not 0 <= STUDS[last[1]] + n <= 12, (key, last, n)
                    assert state[s], (key, "stack empty too")
                    assert any(w in t for w in CUES["stack"][s] + CUES["desc"]), key
                    assert any(w in t for w in CUES["dir"][1 if n > 0 else -1]), key
                    assert any(word_in(w, t) for w in NUM[abs(n)]), key
                    assert not re.findall(r"\d{6}", text), (key, "an id would anchor it")
                elif why == "ambiguous_size":
                    n, stud, pl = AMBIG[key]
                    stacks = stacks_for_single(n)
                    assert len(stacks) >= 2, key
                    assert any(word_in(w, t) for w in NUM[n]) and "length" in t, key
                    for s in stacks:   # each reading could be carried out as it stands
                        assert state[s], (key, s, "empty")
                        assert problems(state, wall, state[s][-1], stud, pl) == [], (key, s)
                    for cue in (CUES["dim"], CUES["desc"], *CUES["stack"].values()):
                        assert not any(w in t for w in cue), (key, "a cue decides it", cue)
                    assert re.findall(r"\d{6}", text) == [stud], key
                    check_words(key, text, state[stacks[0]][-1], stud, pl, {"single": n})
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
            p = problems(state, wall, pid, stud, pl)
            assert not p, (key, x, p)
            state[STACK_OF[pid]].pop()
            wall.append((rect(pid, stud, pl), pid))
            last = (pid, stud)
            placements[pl] = placements.get(pl, 0) + 1
            if any(k in ref for k in HISTORY_KEYS):
                history.append(key)
    for table in (INTENDED, INTENDED_REFS, OFF_END, AMBIG):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    assert set(DISTRACTORS) | set(SAID) <= set(texts), "table names a missing step"
    assert set(eps_per_style.values()) == {2} and len(eps_per_style) == 5, eps_per_style
    n = len(gold)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("refusals:", reasons)
    print("placements:", placements)
    print(f"history-dependent steps={len(history)}:", " ".join(f"{e}/{s}" for e, s in history))
    print(f"ids said as words={sum(map(len, SAID.values()))}, asides with a row or side={len(DISTRACTORS)}")
    print("OK")


if __name__ == "__main__":
    main()
