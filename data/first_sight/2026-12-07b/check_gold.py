"""Stand-alone checker for the first-sight set of 2026-12-07b.

Written from ../shared/spec/case-study.md (sections 1, 3, 4 and 5) and the
2026-12-07 checker as a template; standard library only, it does not import
drywall_lab.  Every episode is replayed from the fresh site (all nine panels
stacked, nothing installed, empty history) and the script asserts that
  - every expected command is feasible: the panel exists and is the top one of
    its stack, is not on the wall yet, stays inside the wall (x_right <=
    4.8768 + 0.01905) and shares no positive area with an installed panel
    (touching edges are allowed);
  - every expected refusal is for exactly the reason written in the gold:
      past_wall / overlap / already_installed: the intended command (INTENDED)
        fails for that reason and for no other, and its words name it;
      empty_stack: the stack asked for (EMPTY) has no panel left at that step;
      no_size_match: the size said (NO_MATCH) fits no stack, as given or turned;
      no_history: the step leans on the last panel (a back-reference word)
        while nothing has been accepted yet in the episode;
  - the references that are not ids (REFS: sizes as given or turned, a single
    length, size words, "narrow"/"skinny"/"slim"/"wąska", absolute stacks,
    "same size" as the last panel, studs by position from either end, studs
    relative to the last stud) agree with the gold, are backed by a cue word
    in the text (CUES), and the history-based ones only ever use an accepted
    command;
  - self-corrections (RETRACTED: "stud 500107, uh, no, 500106", "the four by
    six— no, the four by eight") are in the text, are followed closely by a
    correction marker, and are taken out before the word checks: what is left
    names only the gold's panel and stud;
  - ids spoken as words (SAID: "pięć zero zero jeden zero trzy",
    "five-oh-oh-one-oh-six") are in the text and spell the id of the gold (or
    of the intended command);
  - each command's panel and stud are said or derived, no other id is said as
    digits, and the placement words agree with the placement (English,
    Polish, patois and texting phrasing; a vertical_left step names no centre
    line, row or lying flat);
  - the step after a refusal holds no back-reference word (BACK_REF_WORDS);
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    ids fk01..fk10, 5 or 6 steps an episode, one voice an episode, five
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
STACK_ORDER = ["left", "middle", "right"]
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
    ("fk01", 3): ("500310", "500110", "vertical_left"),      # 4x8 upright from 500110: ends at x = 5.264
    ("fk07", 3): ("500321", "500108", "vertical_left"),      # 500321 went up in step 1
    ("fk09", 3): ("500322", "500100", "horizontal_bottom"),  # 4x6 flat from 500100 runs into 500320 on 500103
}
INTENDED_REFS = {
    ("fk01", 3): {"size": (4, 8), "dim": "full", "stack": "left"},
    ("fk09", 3): {"size": (4, 6)},
}
EMPTY = {("fk03", 4): "middle"}          # the fourth slim board asked of the middle stack
NO_MATCH = {("fk06", 3): (3, 8)}         # "a 3x8": no such size, as given or turned
NO_HISTORY = {("fk05", 0)}               # "1 more like the last one" on a fresh site

SAID = {   # ids said as words: (exact words in the text, id)
    ("fk01", 1): [("pięć zero zero jeden zero trzy", "500103")],
    ("fk01", 3): [("pięć zero zero jeden jeden zero", "500110")],
    ("fk02", 2): [("pięć zero zero jeden zero zero", "500100")],
    ("fk03", 1): [("five-oh-oh-one-oh-six", "500106")],
    ("fk08", 4): [("five-oh-oh-one-oh-five", "500105")],
}
RETRACTED = {   # words the speaker takes back at once (self-corrections)
    ("fk09", 0): ["from the middle"],
    ("fk09", 1): ["500107"],
    ("fk09", 2): ["to the left"],
    ("fk09", 3): ["from stud 500104"],
    ("fk09", 4): ["on stud 500101"],
    ("fk09", 5): ["stand it up plain"],
    ("fk10", 0): ["the four by six"],
    ("fk10", 2): ["stud 500105"],
    ("fk10", 3): ["in the bottom row"],
    ("fk10", 4): ["the third stud from the right"],
}
CORRECTION_MARKERS = ("no", "sorry", "wait", "i mean", "er", "uh", "actually", "the fourth")

REFS = {
    ("fk01", 0): {"dim": "full", "stack": "left"},
    ("fk01", 1): {"size": (2, 8), "desc": "narrow"},
    ("fk01", 2): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fk01", 4): {"size": (4, 6), "stack": "right"},
    ("fk01", 5): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fk02", 0): {"size": (4, 8), "stud_from_right": 4},
    ("fk02", 1): {"desc": "narrow", "stack": "middle", "stud_rel_prev": -2},
    ("fk02", 2): {"stack": "right"},
    ("fk02", 3): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fk02", 4): {"desc": "narrow", "size": (2, 8), "stud_abs": 5},
    ("fk03", 0): {"dim": "full", "stack": "left"},
    ("fk03", 1): {"desc": "narrow", "stack": "middle"},
    ("fk03", 2): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fk03", 3): {"desc": "narrow", "stack": "middle"},
    ("fk03", 5): {"dim": "full", "stack": "left", "stud_abs": 0},
    ("fk04", 0): {"size": (4, 6), "stack": "right"},
    ("fk04", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fk04", 2): {"dim": "full", "stud_abs": 5},
    ("fk04", 3): {"desc": "narrow", "stack": "middle", "stud_rel_prev": 3},
    ("fk04", 4): {"desc": "narrow", "stack": "middle", "stud_from_right": 3},
    ("fk05", 1): {"size": (4, 8), "stack": "left"},
    ("fk05", 2): {"desc": "narrow", "size": (2, 8)},
    ("fk05", 3): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fk05", 4): {"size": (4, 6), "stack": "right"},
    ("fk05", 5): {"desc": "narrow", "stack": "middle"},
    ("fk06", 0): {"dim": "full", "stud_abs": 6},
    ("fk06", 1): {"size": (4, 6), "stud_abs": 0},
    ("fk06", 2): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fk06", 4): {"desc": "narrow", "size": (2, 8), "stack": "middle"},
    ("fk07", 0): {"dim": "full", "size": (4, 8), "stack": "left"},
    ("fk07", 1): {"desc": "narrow", "size": (2, 8), "stack": "middle"},
    ("fk07", 2): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fk07", 4): {"size": (4, 6), "stack": "right"},
    ("fk07", 5): {"size": (4, 6), "stud_rel_prev": 0},
    ("fk08", 0): {"desc": "narrow", "size": (2, 8), "stack": "middle", "stud_abs": 0},
    ("fk08", 1): {"dim": "full", "stud_abs": 2},
    ("fk08", 2): {"size": (6, 4), "stud_rel_prev": 3},
    ("fk08", 3): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fk08", 4): {"size": (2, 8)},
    ("fk09", 0): {"dim": "full", "stack": "left"},
    ("fk09", 1): {"desc": "narrow", "stack": "middle"},
    ("fk09", 2): {"same_size_as_prev": True, "stud_rel_prev": 4},
    ("fk09", 4): {"size": (4, 6), "stack": "right"},
    ("fk09", 5): {"desc": "narrow", "stack": "middle"},
    ("fk10", 0): {"size": (4, 8), "dim": "full"},
    ("fk10", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fk10", 2): {"single": 6, "stack": "right"},
    ("fk10", 3): {"desc": "narrow", "stack": "middle", "stud_rel_prev": 0},
    ("fk10", 4): {"size": (4, 6), "stud_from_right": 4},
}
PANEL_KEYS = ("size", "single", "dim", "desc", "stack", "same_size_as_prev")
STUD_KEYS = ("stud_abs", "stud_from_right", "stud_rel_prev")
HISTORY_KEYS = ("same_size_as_prev", "stud_rel_prev")

# Cue words that must back each reference in the text ------------------------
NUM = {2: ("2", "two", "dwa"), 3: ("3", "three", "tree", "trzy"), 4: ("4", "four", "cztery"),
       6: ("6", "six", "sześć"), 8: ("8", "eight", "osiem")}
CUES = {
    "dim": ("full", "standard", "std", "pełn"),
    "desc": ("narrow", "skinny", "slim", "wąsk"),
    "stack": {"left": ("left", "lef'", "lewego"),
              "middle": ("middle", "mid pile", "środkowej kupki"),
              "right": ("right", "prawego")},
    "same_size_as_prev": ("same size", "same sz", "taki sam", "taką samą"),
    "stud_rel_same": ("same stud", "ten sam stud", "tym samym studzie"),
    "dir": {1: ("right", "prawo", "➡️"), -1: ("left", "lewo")},
    "single": {6: ("six-foot",)},
    "stud_abs": {0: ("leftmost stud", "1st stud", "firs' stud"), 2: ("third stud",),
                 5: ("sixth stud", "szósty stud"), 6: ("middle stud",)},
    "stud_from_right": {3: ("tird stud from di right",),
                        4: ("fourth from the right", "czwarty stud od prawej")},
}

BACK_REF_WORDS = ("previous", "prev", "last", "las'", "same", "again", "that one", "dat one",
                  "just", "jus'", "ditto", "another", "anodda", "other", "before", "too",
                  "him", "them", "one more", "more like", "yday",
                  "poprzedniego", "poprzedni", "poprzednia", "taki sam", "taką samą",
                  "ten sam", "tym samym", "jeszcze", "znowu", "nią", "niej", "ostatni",
                  "ostatnia", "też")
TOP_PHRASES = ("top row", "górnym rzędzie")
BOTTOM_PHRASES = ("bottom row", "btm row", "dolnym rzędzie")
CENTRE_WORDS = ("centre", "center", "ctr", "linii środkowej", "linię środkową")
FLAT_WORDS = ("flat", "horizontal", "lying", "laid", "lay ", " row", "poziomo", "leżąc",
              "rzędzie", "on its side")
DIGIT_WORDS = {"oh": "0", "o": "0", "zero": "0", "one": "1", "jeden": "1", "two": "2",
               "dwa": "2", "three": "3", "tree": "3", "trzy": "3", "four": "4",
               "cztery": "4", "five": "5", "pięć": "5", "six": "6", "sześć": "6",
               "seven": "7", "siedem": "7", "eight": "8", "osiem": "8", "nine": "9",
               "dziewięć": "9"}


def spell(words):
    """Digits of a spoken id: 'pięć zero zero jeden zero trzy' -> '500103'."""
    return "".join(t if t.isdigit() else DIGIT_WORDS[t]
                   for t in re.split(r"[\s\-]+", words.lower()) if t)


def stack_for_size(a, b):
    hits = [s for s, wl in SIZE_FT.items() if wl == (a, b)]
    return hits or [s for s, wl in SIZE_FT.items() if wl == (b, a)]


def stacks_for_single(n):
    return [s for s, (w, l) in SIZE_FT.items() if n in (w, l)]


def size_said(t, a, b):
    """'4x8', '4 by 8', 'four by eight', 'cztery na osiem' in the (lower-case) text."""
    alt = lambda n: "(?:" + "|".join(map(re.escape, NUM[n])) + ")"
    return re.search(r"(?<!\w)" + alt(a) + r"\s*(?:x|by|na)\s*" + alt(b) + r"(?!\w)", t)


def strip_retracted(key, text):
    """The text with the self-corrected words taken out (each checked first)."""
    for phrase in RETRACTED.get(key, []):
        i = text.find(phrase)
        assert i >= 0, (key, "retracted words not in text", phrase)
        after = text[i + len(phrase): i + len(phrase) + 22].lower()
        assert any(re.search(r"(?<!\w)" + re.escape(m) + r"(?!\w)", after)
                   for m in CORRECTION_MARKERS), (key, "no correction after", phrase)
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


def check_refs(key, ref, pid, stud, last, t):
    """The references agree with the gold and each has its cue word in t (lower case)."""
    s = STACK_OF[pid]
    has = lambda words: any(w in t for w in words)
    if "size" in ref:
        assert stack_for_size(*ref["size"]) == [s], (key, ref)
        assert size_said(t, *ref["size"]), (key, "size not said", ref["size"])
    if "single" in ref:
        assert stacks_for_single(ref["single"]) == [s], (key, ref)
        assert has(CUES["single"][ref["single"]]), (key, "single not said")
    if "dim" in ref:
        assert ref["dim"] == "full" and s == "left", (key, ref)
        assert has(CUES["dim"]), (key, "size word not said")
    if "desc" in ref:   # "narrow", "skinny", "slim", "wąska": the one size 2 ft wide
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
            assert any(re.search(r"(?<!\w)" + re.escape(w) + r"(?!\w)", t)
                       for w in NUM[abs(n)]), (key, "count not said")
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
    assert [e["id"] for e in inst] == [f"fk{i:02d}" for i in range(1, 11)], "episode ids"
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
            text = strip_retracted(key, g["text"])
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
                if why in ("overlap", "past_wall", "not_on_top", "already_installed"):
                    pid, stud, pl = INTENDED[key]
                    iref = INTENDED_REFS.get(key, {})
                    check_refs(key, iref, pid, stud, last, t)
                    check_words(key, text, pid, stud, pl, iref)
                    assert problems(state, wall, pid, stud, pl) == [why], \
                        (key, why, problems(state, wall, pid, stud, pl))
                elif why == "empty_stack":
                    s = EMPTY[key]
                    assert state[s] == [], (key, state[s])
                    assert any(w in t for w in CUES["stack"][s]), key
                elif why == "no_size_match":
                    a, b = NO_MATCH[key]
                    assert stack_for_size(a, b) == [] and size_said(t, a, b), key
                elif why == "no_history":
                    assert key in NO_HISTORY and last is None and back_refs(t), key
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
    for table in (INTENDED, INTENDED_REFS, EMPTY, NO_MATCH, NO_HISTORY):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    assert set(RETRACTED) | set(SAID) <= set(texts), "table names a missing step"
    assert set(eps_per_style.values()) == {2} and len(eps_per_style) == 5, eps_per_style
    n = len(gold)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("refusals:", reasons)
    print("placements:", placements)
    print(f"history-dependent steps={len(history)}:", " ".join(f"{e}/{s}" for e, s in history))
    print(f"self-corrected steps={len(RETRACTED)}, ids said as words={sum(map(len, SAID.values()))}")
    print("OK")


if __name__ == "__main__":
    main()
