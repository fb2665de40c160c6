"""Stand-alone checker for the first-sight set of 2026-12-06c.

Replays each episode's expected commands on the fresh site with the geometry
of spec sections 1, 4 and 5 (written from ../shared/spec/case-study.md only;
it does not import drywall_lab; standard library only).  Asserts that
  - every expected command is feasible (panel on top of its stack, not yet
    installed, inside the wall, no positive-area overlap with an installed
    panel; touching edges are fine);
  - every expected refusal is for exactly the stated reason: for overlap /
    past_wall the intended command (INTENDED below) is infeasible for that
    reason and no other; already_installed: the intended panel is on the wall
    in the replayed state and its intended place is otherwise free;
    no_history: nothing was accepted yet in the episode; no_size_match: the
    size said matches no stack, as given or turned; ambiguous_size: the single
    number said matches two sizes;
  - the references that are not ids (sizes as given or turned, a single
    number, "full"/"standard", "narrow"/"skinny", absolute stacks, a stack
    relative to the previous panel's stack or to a panel id, same size as the
    previous panel, absolute studs by position, a stud relative to the
    previous stud), written in REFS, agree with the gold;
  - ids said as words ("five oh oh one oh oh", "cinq zéro zéro un zéro six",
    "five double oh one double oh") or spaced digits ("500 104") are in the
    text and spell the gold's id (SAID);
  - every expected command's panel id and stud id are said or derived, no
    other id is said as digits (but an anchor panel, ANCHOR), and the
    placement words agree with the placement (English, Quebec French or
    console keywords; a vertical_left step says nothing of a centre line, a
    row or lying flat);
  - the step right after a refusal uses no back-reference word (English or
    French), so no one has to wonder whether the refused instruction counts;
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    every episode has 5 or 6 steps, one voice an episode, ids fh01..fh10.
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
FRESH = {"left": ["500300", "500310", "500320"],
         "middle": ["500301", "500311", "500321"],
         "right": ["500302", "500312", "500322"]}  # bottom -> top
STACK_OF = {pid: s for s, ids in FRESH.items() for pid in ids}
STUDS = {str(500100 + i): i for i in range(13)}
PLACEMENTS = ("vertical_left", "vertical_middle", "horizontal_top", "horizontal_bottom")
REASONS = ("overlap", "past_wall", "not_on_top", "already_installed", "empty_stack",
           "unknown_id", "no_history", "off_end", "no_size_match", "ambiguous_size",
           "unclear", "undetermined")

# Intended command of each refused step whose refusal depends on geometry / the wall.
INTENDED = {
    ("fh01", 5): ("500301", "500112", "vertical_middle"),  # last 2x8 on the last stud, c/l
    ("fh03", 3): ("500320", "500108", "vertical_left"),    # 500320 already in the bottom row
    ("fh05", 2): ("500322", "500103", "horizontal_bottom"),  # 4x6 flat from 500103 into the 2x8
}
INTENDED_REFS = {
    ("fh01", 5): {"size": (2, 8), "stud_from_right": 1},
    ("fh05", 2): {"size": (4, 6), "stud_rel_prev": 0},
}
NO_HISTORY = {("fh02", 0)}                        # "the same size as the last one you put up", fresh site
NO_SIZE = {("fh04", 2): (4, 12)}                  # "quatre par douze"
AMBIGUOUS = {("fh07", 2): 4}                      # "a four-foot one": 4x8 or 4x6
ANCHOR = {("fh08", 4): {"500310"}}                # "the stack just right of panel 500310"

SAID = {   # ids said as words or spaced digits: (exact words in the text, id)
    ("fh01", 0): [("five oh oh one oh oh", "500100")],
    ("fh01", 3): [("five oh oh one oh seven", "500107")],
    ("fh02", 3): [("five-oh-oh-one-oh-nine", "500109")],
    ("fh03", 2): [("cinq zéro zéro un zéro six", "500106")],
    ("fh05", 1): [("five oh oh one oh three", "500103")],
    ("fh06", 2): [("five zero zero one zero zero", "500100")],
    ("fh07", 0): [("five double oh one double oh", "500100")],
    ("fh07", 3): [("500 106", "500106")],
    ("fh08", 0): [("five-oh-oh-one-oh-two", "500102")],
    ("fh08", 1): [("500 104", "500104")],
}

REFS = {
    ("fh01", 0): {"dim": "full"},
    ("fh01", 1): {"single": 2, "desc": "narrow", "stack": "middle"},
    ("fh01", 2): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fh01", 3): {"size": (4, 6)},
    ("fh01", 4): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fh02", 1): {"size": (4, 8), "stack": "left", "stud_abs": 3},
    ("fh02", 2): {"dim": "full", "stud_rel_prev": 3},
    ("fh02", 3): {"stack": "right"},
    ("fh02", 4): {"dim": "full", "stud_abs": 0},
    ("fh03", 0): {"dim": "full", "stud_abs": 0},
    ("fh03", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fh03", 2): {"size": (2, 8)},
    ("fh03", 4): {"size": (2, 8), "stack": "middle"},
    ("fh03", 5): {"size": (2, 8), "stud_rel_prev": 2},
    ("fh04", 0): {"stack": "middle", "stud_abs": 6},
    ("fh04", 1): {"size": (4, 8), "stud_rel_prev": 2},
    ("fh04", 3): {"dim": "full", "stack": "left", "stud_abs": 0},
    ("fh04", 4): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fh05", 0): {"size": (4, 8)},
    ("fh05", 1): {"desc": "narrow", "stack": "middle"},
    ("fh05", 3): {"size": (4, 6), "stack": "right"},
    ("fh05", 4): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fh05", 5): {"size": (2, 8), "stud_from_right": 3},
    ("fh06", 0): {"stack": "right", "stud_abs": 0},
    ("fh06", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fh06", 2): {"desc": "narrow"},
    ("fh06", 3): {"stack": "left"},
    ("fh06", 4): {"stack_rel_prev": 2, "stud_abs": 9},
    ("fh07", 0): {"dim": "full", "stack": "left"},
    ("fh07", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fh07", 3): {"single": 6, "stack": "right"},
    ("fh07", 4): {"desc": "narrow", "stud_rel_prev": 0},
    ("fh07", 5): {"single": 6, "stud_rel_prev": 3},
    ("fh08", 0): {"stack": "middle"},
    ("fh08", 1): {"stack_rel_prev": 1},
    ("fh08", 2): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fh08", 3): {"dim": "full", "stud_from_right": 4},
    ("fh08", 4): {"stack_rel_id": ("500310", 1), "stud_abs": 0},
    ("fh09", 1): {"size": (6, 4), "stud_rel_prev": 2},
    ("fh09", 2): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fh09", 3): {"dim": "full"},
    ("fh09", 4): {"stack": "middle", "stud_from_right": 3},
    ("fh10", 0): {"stack": "right"},
    ("fh10", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fh10", 2): {"size": (2, 8), "stud_abs": 0},
    ("fh10", 3): {"size": (4, 8), "stud_abs": 6},
    ("fh10", 4): {"same_size_as_prev": True, "stud_rel_prev": 3},
}
PANEL_KEYS = ("size", "single", "dim", "desc", "stack", "same_size_as_prev", "stack_rel_prev",
              "stack_rel_id")
STUD_KEYS = ("stud_abs", "stud_from_right", "stud_rel_prev")
HISTORY_KEYS = ("same_size_as_prev", "stack_rel_prev", "stud_rel_prev")
BACK_REF_WORDS = ("previous", "last", "same", "again", "that one", "that'n", "just", "ditto",
                  "prev", "another", "other", "before", "too",
                  "même", "encore", "dernier", "dernière", "précédent", "celle-là",
                  "celui-là", "pareil", "autre")
TOP_PHRASES = ("top row", "row=top", "en haut")
BOTTOM_PHRASES = ("bottom row", "row=bottom", "en bas")
CENTRE_WORDS = ("centre", "center", "middle line", "ligne du centre")
FLAT_WORDS = ("flat", "horizontal", "lying", "lay ", "à plat", "couch", " row", "row=")
DIGIT_WORDS = {"oh": "0", "o": "0", "zero": "0", "zéro": "0", "one": "1", "un": "1",
               "two": "2", "deux": "2", "three": "3", "trois": "3", "four": "4",
               "quatre": "4", "five": "5", "cinq": "5", "six": "6", "seven": "7",
               "sept": "7", "eight": "8", "huit": "8", "nine": "9", "neuf": "9"}


def spell(words):
    """Digits spelled by a spoken or spaced id: 'five double oh one oh oh' -> '500100'."""
    out, double = "", False
    for tok in re.split(r"[\s\-]+", words.lower()):
        if tok == "double":
            double = True
            continue
        d = tok if tok.isdigit() else DIGIT_WORDS[tok]
        out += d * (2 if double else 1)
        double = False
    return out


def stack_for_size(a, b):
    hits = [s for s, (w, l) in SIZE_FT.items() if (w, l) == (a, b)]
    if not hits:
        hits = [s for s, (w, l) in SIZE_FT.items() if (w, l) == (b, a)]
    return hits


def stacks_for_single(n):
    return [s for s, (w, l) in SIZE_FT.items() if n in (w, l)]


def rect(pid, stud, placement):
    w, l = SIZES[STACK_OF[pid]]
    c = 0.4064 * STUDS[stud]
    left = c - 0.01905
    if placement == "vertical_left":
        return left, left + w, 0.0, l
    if placement == "vertical_middle":
        return c, c + w, 0.0, l
    if placement == "horizontal_top":
        return left, left + l, H - w, H
    if placement == "horizontal_bottom":
        return left, left + l, 0.0, w
    raise ValueError(placement)


def problems(state, wall, pid, stud, placement):
    """Reasons the command is infeasible (empty list = feasible)."""
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
    for (a0, a1, b0, b1), _ in wall:
        if min(x1, a1) - max(x0, a0) > EPS and min(z1, b1) - max(z0, b0) > EPS:
            out.append("overlap")
            break
    return out


def check_refs(key, ref, pid, stud, last):
    s = STACK_OF[pid]
    if "size" in ref:
        assert stack_for_size(*ref["size"]) == [s], (key, ref)
    if "single" in ref:
        assert stacks_for_single(ref["single"]) == [s], (key, ref)
    if "dim" in ref:
        assert ref["dim"] == "full" and s == "left", (key, ref)
    if "desc" in ref:      # "narrow" / "skinny": the only size 2 ft wide
        assert ref["desc"] == "narrow" and [t for t, (w, _) in SIZE_FT.items() if w == 2] == [s], key
    if "stack" in ref:
        assert ref["stack"] == s, (key, ref)
    if "same_size_as_prev" in ref:
        assert last is not None and SIZE_FT[STACK_OF[last[0]]] == SIZE_FT[s], key
    if "stack_rel_prev" in ref:
        assert last is not None, key
        i = STACK_ORDER.index(STACK_OF[last[0]]) + ref["stack_rel_prev"]
        assert 0 <= i < 3 and STACK_ORDER[i] == s, key
    if "stack_rel_id" in ref:
        anchor, n = ref["stack_rel_id"]
        i = STACK_ORDER.index(STACK_OF[anchor]) + n
        assert 0 <= i < 3 and STACK_ORDER[i] == s, key
    if "stud_rel_prev" in ref:
        assert last is not None, key
        assert STUDS[stud] == STUDS[last[1]] + ref["stud_rel_prev"], key
    if "stud_abs" in ref:
        assert STUDS[stud] == ref["stud_abs"], key
    if "stud_from_right" in ref:
        assert STUDS[stud] == 13 - ref["stud_from_right"], key


def check_words(key, text, pid, stud, pl, ref):
    t = text.lower()
    said = {i for _, i in SAID.get(key, [])}
    assert pid in text or pid in said or any(k in ref for k in PANEL_KEYS), (key, "panel not said")
    assert stud in text or stud in said or any(k in ref for k in STUD_KEYS), (key, "stud not said")
    assert not (stud in said and any(k in ref for k in STUD_KEYS)), (key, "stud said and derived")
    allowed = ANCHOR.get(key, set())
    for sid in STUDS:
        assert sid == stud or sid not in text, (key, "other stud id", sid)
    for p in STACK_OF:
        assert p == pid or p in allowed or p not in text, (key, "other panel id", p)
    has = lambda words: any(w in t for w in words)
    if pl == "horizontal_top":
        assert has(TOP_PHRASES) and not has(BOTTOM_PHRASES), key
        assert not has(CENTRE_WORDS), key
    elif pl == "horizontal_bottom":
        assert has(BOTTOM_PHRASES) and not has(TOP_PHRASES), key
        assert not has(CENTRE_WORDS), key
    elif pl == "vertical_middle":
        assert has(CENTRE_WORDS), key
        assert not has(FLAT_WORDS) and not has(TOP_PHRASES) and not has(BOTTOM_PHRASES), key
    else:
        assert not has(CENTRE_WORDS), key
        for w in TOP_PHRASES + BOTTOM_PHRASES + FLAT_WORDS:
            assert w not in t, (key, w)


def main():
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl", encoding="utf-8") if l.strip()]
    gold = [json.loads(l) for l in open(HERE / "gold.jsonl", encoding="utf-8") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    assert [e["id"] for e in inst] == [f"fh{i:02d}" for i in range(1, 11)], "episode ids"
    texts = {(g["episode"], g["step"]): g["text"] for g in gold}
    for key, pairs in SAID.items():
        for words, i in pairs:
            assert words in texts[key], (key, words)
            assert spell(words) == i, (key, words, spell(words))
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
        state = {s: list(ids) for s, ids in FRESH.items()}   # every episode: fresh site
        wall = []          # ((x0, x1, z0, z1), pid)
        last = None        # (pid, stud) of the last accepted command
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
                if why in ("overlap", "past_wall", "already_installed"):
                    pid, stud, pl = INTENDED[key]
                    check_refs(key, INTENDED_REFS.get(key, {}), pid, stud, last)
                    p = problems(state, wall, pid, stud, pl)
                    assert p == [why], (key, why, p)
                elif why == "no_history":
                    assert key in NO_HISTORY and last is None and not wall, key
                elif why == "no_size_match":
                    assert stack_for_size(*NO_SIZE[key]) == [], key
                elif why == "ambiguous_size":
                    assert len(stacks_for_single(AMBIGUOUS[key])) >= 2, key
                else:
                    raise AssertionError((key, "no check for", why))
                prev_refused = True
                continue       # a refused step leaves the state as it was
            prev_refused = False
            assert set(x) == {"drywall_id", "stud_id", "placement"}, key
            pid, stud, pl = x["drywall_id"], x["stud_id"], x["placement"]
            assert isinstance(pid, str) and isinstance(stud, str), key
            assert pl in PLACEMENTS, key
            assert key in REFS or key in SAID or (pid in g["text"] and stud in g["text"]), (key, "no REFS")
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
    refused = {(g["episode"], g["step"]) for g in gold if "refusal" in g["expect"]}
    for table in (INTENDED, INTENDED_REFS, NO_HISTORY, NO_SIZE, AMBIGUOUS):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    assert not set(SAID) & refused, "SAID names a refused step"
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
