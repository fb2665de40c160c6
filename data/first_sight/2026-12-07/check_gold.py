"""Stand-alone checker for the first-sight set of 2026-12-07.

Written from ../shared/spec/case-study.md (sections 1, 3, 4 and 5) and the
2026-12-06c checker as a template; standard library only, it does not import
drywall_lab.  Every episode is replayed from the fresh site (all nine panels
stacked, nothing installed, empty history) and the script asserts that
  - every expected command is feasible: the panel exists and is the top one of
    its stack, is not on the wall yet, stays inside the wall (x_right <=
    4.8768 + 0.01905) and shares no positive area with an installed panel
    (touching edges are allowed);
  - every expected refusal is for exactly the reason written in the gold:
      past_wall / overlap / not_on_top: the intended command (INTENDED) fails
        for that reason and for no other;
      unknown_id: the id said (UNKNOWN) spells an id that is neither a panel
        nor a stud, while the other id said is a real one;
      off_end: the relative reference (OFF_END) counts past the end of the
        stacks (or studs) from its anchor;
      ambiguous_size: the single number said (AMBIGUOUS) is a side of two sizes;
  - the references that are not ids (REFS: sizes as given or turned, size
    words, "narrow"/"skinny", absolute stacks, a stack relative to the last
    panel's stack, "same size" as the last panel, studs by position from
    either end, studs relative to the last stud or to a stud id) agree with
    the gold, and the history-based ones only ever use an accepted command;
  - ids spoken as words (SAID: "five-oh-oh-one-oh-three",
    "five-zero-zero-one-zero-niner", "cinco zero zero um zero cinco") are in
    the text and spell the id of the gold (or of the intended command);
  - each command's panel and stud are said or derived, no other id is said as
    digits (an anchor stud excepted, ANCHOR), and the placement words agree
    with the placement (English, Brazilian Portuguese, pidgin and radio
    phrasing; a vertical_left step names no centre line, row or lying flat);
  - the step after a refusal holds no back-reference word (BACK_REF_WORDS);
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    ids fj01..fj10, 5 or 6 steps an episode, one voice an episode, five
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
    ("fj01", 4): ("500312", "500108", "horizontal_top"),     # 4x6 flat from 500108: ends at x = 5.06
    ("fj05", 3): ("500322", "500100", "horizontal_bottom"),  # 4x6 flat from 500100 runs into 500320
    ("fj09", 1): ("500300", "500103", "vertical_left"),      # 500300 lies under 500310
}
INTENDED_REFS = {
    ("fj01", 4): {"size": (4, 6)},
    ("fj05", 3): {"size": (4, 6), "stack": "right"},
}
UNKNOWN = {("fj03", 4): ("five-zero-zero-tree-one-tree", "five-zero-zero-one-zero-zero")}
OFF_END = {("fj06", 1): ("stack_rel_prev", -1)}   # the stack left of the left stack
AMBIGUOUS = {("fj07", 2): 4}                      # "four-foot board": 4x8 or 4x6

SAID = {   # ids said as words: (exact words in the text, id)
    ("fj01", 1): [("five-oh-oh-one-oh-three", "500103")],
    ("fj01", 4): [("five-oh-oh-one-oh-eight", "500108")],
    ("fj02", 3): [("five-oh-oh-one-oh-oh", "500100")],
    ("fj03", 0): [("five-zero-zero-one-zero-fife", "500105")],
    ("fj03", 2): [("five-zero-zero-one-zero-seven", "500107")],
    ("fj03", 5): [("five-zero-zero-tree-zero-one", "500301"),
                  ("five-zero-zero-one-zero-zero", "500100")],
    ("fj04", 0): [("five-zero-zero-one-zero-zero", "500100")],
    ("fj04", 4): [("five-zero-zero-one-zero-niner", "500109")],
    ("fj05", 1): [("cinco zero zero um zero cinco", "500105")],
    ("fj07", 1): [("five zero zero one zero zero", "500100")],
}
ANCHOR = {("fj08", 4): {"500102"}}   # "three stud to di right of stud 500102"

REFS = {
    ("fj01", 0): {"dim": "full"},
    ("fj01", 1): {"desc": "narrow", "stack": "middle"},
    ("fj01", 2): {"desc": "narrow", "stud_rel_prev": 2},
    ("fj01", 3): {"size": (4, 6), "stud_abs": 7},
    ("fj01", 5): {"size": (4, 6), "stud_abs": 7},
    ("fj02", 0): {"stack": "left", "stud_abs": 6},
    ("fj02", 1): {"stack": "right"},
    ("fj02", 2): {"same_size_as_prev": True, "stud_rel_prev": 3, "stud_abs": 3},
    ("fj02", 3): {"desc": "narrow"},
    ("fj02", 4): {"desc": "narrow", "stud_abs": 10},
    ("fj03", 0): {"stack": "middle"},
    ("fj03", 1): {"same_size_as_prev": True, "stud_rel_prev": -2},
    ("fj03", 2): {"size": (4, 6)},
    ("fj03", 3): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fj04", 0): {"size": (4, 8)},
    ("fj04", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fj04", 2): {"stack": "right", "stud_rel_prev": 3},
    ("fj04", 3): {"size": (2, 8), "stud_rel_prev": 0},
    ("fj04", 4): {"size": (4, 6)},
    ("fj05", 0): {"size": (4, 8)},
    ("fj05", 1): {"size": (2, 8), "desc": "narrow"},
    ("fj05", 2): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fj05", 4): {"size": (4, 6)},
    ("fj06", 0): {"dim": "full", "stud_from_right": 4},
    ("fj06", 2): {"size": (2, 8)},
    ("fj06", 3): {"size": (4, 6), "stud_rel_prev": 3},
    ("fj06", 4): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fj07", 0): {"dim": "full", "stack": "left"},
    ("fj07", 1): {"desc": "narrow", "stack": "middle"},
    ("fj07", 3): {"size": (4, 6)},
    ("fj07", 4): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fj07", 5): {"desc": "narrow", "stud_abs": 2},
    ("fj08", 0): {"stack": "middle", "stud_abs": 0},
    ("fj08", 1): {"stack_rel_prev": 1, "stud_rel_prev": 2},
    ("fj08", 2): {"desc": "narrow", "stack": "middle", "stud_rel_prev": 0},
    ("fj08", 3): {"size": (4, 8)},
    ("fj08", 4): {"size": (4, 6), "stud_rel_id": ("500102", 3)},
    ("fj09", 0): {"dim": "full"},
    ("fj09", 2): {"stack": "middle"},
    ("fj09", 3): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fj09", 4): {"size": (4, 6), "stud_abs": 7},
    ("fj09", 5): {"desc": "narrow", "stud_rel_prev": 3},
    ("fj10", 0): {"size": (6, 4), "stud_abs": 0},
    ("fj10", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fj10", 2): {"dim": "full"},
    ("fj10", 3): {"desc": "narrow", "stack": "middle", "stud_rel_prev": 3},
    ("fj10", 4): {"desc": "narrow", "stud_from_right": 3},
}
PANEL_KEYS = ("size", "single", "dim", "desc", "stack", "same_size_as_prev", "stack_rel_prev")
STUD_KEYS = ("stud_abs", "stud_from_right", "stud_rel_prev", "stud_rel_id")
HISTORY_KEYS = ("same_size_as_prev", "stack_rel_prev", "stud_rel_prev")
BACK_REF_WORDS = ("previous", "last", "same", "again", "that one", "dat one", "just", "ditto",
                  "prev", "another", "other", "before", "too", "yer man", "him", "them",
                  "mesmo", "mesma", "outra", "outro", "anterior", "última", "último",
                  "de novo", "essa", "esse", "dessa", "desse", "daquela", "dela", "dele",
                  "também")
TOP_PHRASES = ("top row", "fileira de cima")
BOTTOM_PHRASES = ("bottom row", "fileira de baixo")
CENTRE_WORDS = ("centre", "center", "centro", "middle line")
FLAT_WORDS = ("flat", "horizontal", "lying", "lay ", "lie am", "deitad", "deita ", " row",
              "fileira", "on its side")
DIGIT_WORDS = {"oh": "0", "o": "0", "zero": "0", "one": "1", "um": "1", "two": "2",
               "dois": "2", "three": "3", "tree": "3", "três": "3", "four": "4",
               "quatro": "4", "five": "5", "fife": "5", "cinco": "5", "six": "6",
               "seis": "6", "seven": "7", "sete": "7", "eight": "8", "oito": "8",
               "nine": "9", "niner": "9", "nove": "9"}


def spell(words):
    """Digits of a spoken id: 'five-zero-zero-one-zero-niner' -> '500109'."""
    return "".join(t if t.isdigit() else DIGIT_WORDS[t]
                   for t in re.split(r"[\s\-]+", words.lower()) if t)


def stack_for_size(a, b):
    hits = [s for s, wl in SIZE_FT.items() if wl == (a, b)]
    return hits or [s for s, wl in SIZE_FT.items() if wl == (b, a)]


def stacks_for_single(n):
    return [s for s, (w, l) in SIZE_FT.items() if n in (w, l)]


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


def check_refs(key, ref, pid, stud, last):
    s = STACK_OF[pid]
    if "size" in ref:
        assert stack_for_size(*ref["size"]) == [s], (key, ref)
    if "single" in ref:
        assert stacks_for_single(ref["single"]) == [s], (key, ref)
    if "dim" in ref:
        assert ref["dim"] == "full" and s == "left", (key, ref)
    if "desc" in ref:   # "narrow", "skinny", "estreita": the one size 2 ft wide
        assert ref["desc"] == "narrow"
        assert [t for t, (w, _) in SIZE_FT.items() if w == 2] == [s], key
    if "stack" in ref:
        assert ref["stack"] == s, (key, ref)
    if "same_size_as_prev" in ref:
        assert last is not None and SIZE_FT[STACK_OF[last[0]]] == SIZE_FT[s], key
    if "stack_rel_prev" in ref:
        assert last is not None, key
        i = STACK_ORDER.index(STACK_OF[last[0]]) + ref["stack_rel_prev"]
        assert 0 <= i < 3 and STACK_ORDER[i] == s, key
    if "stud_rel_prev" in ref:
        assert last is not None, key
        assert STUDS[stud] == STUDS[last[1]] + ref["stud_rel_prev"], key
    if "stud_rel_id" in ref:
        anchor, n = ref["stud_rel_id"]
        assert STUDS[stud] == STUDS[anchor] + n, key
    if "stud_abs" in ref:
        assert STUDS[stud] == ref["stud_abs"], key
    if "stud_from_right" in ref:
        assert STUDS[stud] == 13 - ref["stud_from_right"], key


def check_words(key, text, pid, stud, pl, ref):
    t = text.lower()
    said = {i for _, i in SAID.get(key, [])}
    assert pid in text or pid in said or any(k in ref for k in PANEL_KEYS), (key, "panel not said")
    assert stud in text or stud in said or any(k in ref for k in STUD_KEYS), (key, "stud not said")
    allowed = ANCHOR.get(key, set())
    for sid in STUDS:
        assert sid == stud or sid in allowed or sid not in text, (key, "other stud id", sid)
    for p in STACK_OF:
        assert p == pid or p not in text, (key, "other panel id", p)
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


def main():
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl", encoding="utf-8") if l.strip()]
    gold = [json.loads(l) for l in open(HERE / "gold.jsonl", encoding="utf-8") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    assert [e["id"] for e in inst] == [f"fj{i:02d}" for i in range(1, 11)], "episode ids"
    texts = {(g["episode"], g["step"]): g["text"] for g in gold}
    for key, pairs in SAID.items():
        for words, i in pairs:
            assert words in texts[key], (key, words)
            assert spell(words) == i, (key, words, spell(words))
    refused = {(g["episode"], g["step"]) for g in gold if "refusal" in g["expect"]}
    for key, (bad, good) in UNKNOWN.items():
        assert bad in texts[key] and good in texts[key], key
        assert spell(bad) not in STACK_OF and spell(bad) not in STUDS, key
        assert spell(good) in STACK_OF or spell(good) in STUDS, key
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
            if prev_refused:
                t = g["text"].lower()
                for w in BACK_REF_WORDS:
                    assert not re.search(r"(?<![\w'])" + re.escape(w) + r"(?![\w'])", t), \
                        (key, "back-reference right after a refusal", w)
            if "refusal" in x:
                assert set(x) == {"refusal"}, key
                n_ref += 1
                why = x["refusal"]
                assert why in REASONS, (key, why)
                reasons[why] = reasons.get(why, 0) + 1
                if why in ("overlap", "past_wall", "not_on_top", "already_installed"):
                    pid, stud, pl = INTENDED[key]
                    check_refs(key, INTENDED_REFS.get(key, {}), pid, stud, last)
                    for _, i in SAID.get(key, []):
                        assert i in (pid, stud), (key, i)
                    assert problems(state, wall, pid, stud, pl) == [why], \
                        (key, why, problems(state, wall, pid, stud, pl))
                elif why == "unknown_id":
                    assert key in UNKNOWN, key
                elif why == "off_end":
                    kind, n = OFF_END[key]
                    assert kind == "stack_rel_prev" and last is not None, key
                    i = STACK_ORDER.index(STACK_OF[last[0]]) + n
                    assert not 0 <= i < 3, key
                elif why == "ambiguous_size":
                    assert len(stacks_for_single(AMBIGUOUS[key])) >= 2, key
                else:
                    raise AssertionError((key, "no check for", why))
                prev_refused = True
                continue      # a refused step leaves site and history as they were
            prev_refused = False
            assert set(x) == {"drywall_id", "stud_id", "placement"}, key
            pid, stud, pl = x["drywall_id"], x["stud_id"], x["placement"]
            assert isinstance(pid, str) and isinstance(stud, str) and pl in PLACEMENTS, key
            assert key in REFS or key in SAID or (pid in g["text"] and stud in g["text"]), \
                (key, "no REFS")
            ref = REFS.get(key, {})
            check_refs(key, ref, pid, stud, last)
            check_words(key, g["text"], pid, stud, pl, ref)
            p = problems(state, wall, pid, stud, pl)
            assert not p, (key, x, p)
            state[STACK_OF[pid]].pop()
            wall.append((rect(pid, stud, pl), pid))
            last = (pid, stud)
            placements[pl] = placements.get(pl, 0) + 1
            if any(k in ref for k in HISTORY_KEYS):
                history.append(key)
    for table in (INTENDED, INTENDED_REFS, UNKNOWN, OFF_END, AMBIGUOUS):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    assert set(eps_per_style.values()) == {2} and len(eps_per_style) == 5, eps_per_style
    n = len(gold)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("refusals:", reasons)
    print("placements:", placements)
    print(f"history-dependent steps={len(history)}:", " ".join(f"{e}/{s}" for e, s in history))
    print("OK")


if __name__ == "__main__":
    main()
