"""Stand-alone checker for the first-sight set of 2026-12-06b.

Replays each episode's expected commands on the fresh site with the geometry
of spec sections 1, 4 and 5 (written from ../shared/spec/case-study.md only;
it does not import drywall_lab; standard library only).  Asserts that
  - every expected command is feasible (panel on top of its stack, not yet
    installed, inside the wall, no positive-area overlap with an installed
    panel; touching edges are fine);
  - every expected refusal is for exactly the stated reason: for overlap /
    past_wall / not_on_top the intended command (INTENDED below) is infeasible
    for that reason and no other; empty_stack is checked against the replayed
    stacks; off_end (a stud counted from the previous stud runs past the last
    stud) against the replayed previous stud; ambiguous_size (a single number
    that matches two sizes) against the site;
  - the references that are not ids (sizes, a single number, "full sheet",
    absolute stacks, stack relative to the previous panel's stack, same size
    as the previous panel, absolute studs by position, stud relative to the
    previous stud), written in REFS, agree with the gold;
  - every expected command's panel id and stud id either appear in the text or
    are derived in REFS, no other id is said (but the id a speaker corrects
    away from, CORRECTED), and the placement words agree with the placement
    (top row / bottom row / centre line, in English, German or shorthand; a
    vertical_left step says nothing of a centre line, a row or lying flat);
  - the step right after a refusal uses no back-reference word, so no one has
    to wonder whether the refused instruction counts;
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    every episode has 4 to 7 steps, one voice an episode, ids fg01..fg10.
usage: python3 check_gold.py
"""
import json
import pathlib

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
REASONS = ("overlap", "past_wall", "not_on_top", "empty_stack", "unknown_id",
           "no_history", "off_end", "no_size_match", "ambiguous_size", "unclear",
           "undetermined")

# Intended command of each refused step whose refusal depends on geometry / stack order.
INTENDED = {
    ("fg01", 2): ("500311", "500104", "vertical_middle"),  # 2x8 on 500104 c/l into the 2x8 on 500103 c/l
    ("fg02", 2): ("500320", "500112", "vertical_left"),    # upright 4x8 on the last stud
    ("fg05", 1): ("500300", "500100", "vertical_left"),    # 500300 is under 500310
}
INTENDED_REFS = {
    ("fg01", 2): {"same_size_as_prev": True, "stud_rel_prev": 1},
    ("fg02", 2): {"dim": "full", "stud_from_right": 1},
}
INTENDED_STACK = {("fg07", 3): "middle"}          # empty_stack: a fourth two by eight
OFF_END = {("fg09", 5): 3}                        # "ditto, 3 studs R of prev" from 500110
AMBIGUOUS = {("fg04", 2): 8}                      # "the eight-footer": 4x8 or 2x8
CORRECTED = {("fg08", 4): {"500101"}, ("fg10", 3): {"500106"}}

REFS = {
    ("fg01", 0): {"dim": "full"},
    ("fg01", 1): {"single": 2},
    ("fg01", 3): {"size": (4, 6)},
    ("fg01", 4): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fg01", 5): {"stack": "middle", "stud_from_right": 3},
    ("fg02", 0): {"stack": "right", "stud_abs": 6},
    ("fg02", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fg02", 3): {"dim": "full"},
    ("fg02", 4): {"stack_rel_prev": 1, "stud_abs": 0},
    ("fg03", 0): {"size": (4, 8)},
    ("fg03", 1): {"size": (4, 6)},
    ("fg03", 2): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fg03", 3): {"single": 2, "stud_from_right": 3},
    ("fg03", 4): {"same_size_as_prev": True, "stud_rel_prev": -2},
    ("fg04", 0): {"size": (2, 8), "stud_abs": 0},
    ("fg04", 1): {"dim": "full"},
    ("fg04", 3): {"single": 6},
    ("fg04", 4): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fg04", 5): {"stack": "middle", "stud_rel_prev": -2},
    ("fg05", 0): {"stack": "left", "size": (4, 8)},
    ("fg05", 2): {"stack": "left"},
    ("fg05", 3): {"size": (4, 6)},
    ("fg05", 4): {"single": 2, "stud_rel_prev": 0},
    ("fg06", 0): {"stack": "right", "size": (4, 6), "stud_abs": 0},
    ("fg06", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fg06", 2): {"stack_rel_prev": -1},
    ("fg06", 3): {"dim": "full", "stud_abs": 6},
    ("fg06", 4): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fg07", 0): {"size": (2, 8)},
    ("fg07", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fg07", 2): {"size": (2, 8)},
    ("fg07", 4): {"dim": "full", "size": (4, 8)},
    ("fg07", 5): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fg08", 0): {"stack": "right", "size": (4, 6), "stud_abs": 0},
    ("fg08", 1): {"stack_rel_prev": -1},
    ("fg08", 2): {"dim": "full", "size": (4, 8)},
    ("fg08", 3): {"stack": "middle", "stud_rel_prev": 3},
    ("fg08", 4): {"size": (4, 6)},
    ("fg09", 0): {"size": (4, 6)},
    ("fg09", 1): {"size": (2, 8)},
    ("fg09", 2): {"stack": "right", "stud_rel_prev": 3},
    ("fg09", 3): {"size": (4, 8)},
    ("fg09", 4): {"size": (2, 8)},
    ("fg10", 0): {"stack": "middle"},
    ("fg10", 1): {"stack_rel_prev": 1, "stud_rel_prev": 2},
    ("fg10", 2): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fg10", 3): {"size": (4, 8)},
    ("fg10", 4): {"size": (2, 8), "stud_from_right": 3},
}
PANEL_KEYS = ("size", "single", "dim", "stack", "same_size_as_prev", "stack_rel_prev")
STUD_KEYS = ("stud_abs", "stud_from_right", "stud_rel_prev")
HISTORY_KEYS = ("same_size_as_prev", "stack_rel_prev", "stud_rel_prev")
BACK_REF_WORDS = ("previous", "last", "same", "again", "that one", "just", "ditto", "prev",
                  "another", "gleich", "nochmal", "selbe", "vorherig", "letzt", "wieder")
TOP_PHRASES = ("top row", "along the top")
BOTTOM_PHRASES = ("bottom row", "along the bottom", "btm row")
CENTRE_WORDS = ("centre", "center", "mittellinie", "c/l")
FLAT_WORDS = ("flat", "horizontal", "lying", "lyin'", "liegend", " row")  # " row": not "narrow"


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
    if not state[s] or state[s][-1] != pid:
        out.append("not_on_top")     # also covers an installed panel (no longer in its stack)
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
    if "stud_abs" in ref:
        assert STUDS[stud] == ref["stud_abs"], key
    if "stud_from_right" in ref:
        assert STUDS[stud] == 13 - ref["stud_from_right"], key


def check_words(key, text, pid, stud, pl, ref):
    t = text.lower()
    assert pid in text or any(k in ref for k in PANEL_KEYS), (key, "panel not said")
    assert stud in text or any(k in ref for k in STUD_KEYS), (key, "stud not said")
    allowed = CORRECTED.get(key, set())
    for sid in STUDS:
        assert sid == stud or sid in allowed or sid not in text, (key, "other stud id", sid)
    for p in STACK_OF:
        assert p == pid or p in allowed or p not in text, (key, "other panel id", p)
    has = lambda words: any(w in t for w in words)
    if pl == "horizontal_top":
        assert has(TOP_PHRASES) and "bottom" not in t and "btm" not in t, key
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
    assert [e["id"] for e in inst] == [f"fg{i:02d}" for i in range(1, 11)], "episode ids"
    n_ref = 0
    styles, reasons, placements = {}, {}, {}
    history = []
    for e in inst:
        ep = e["id"]
        rows = by_ep[ep]
        assert set(e) == {"id", "instructions"}, ep
        assert 4 <= len(rows) <= 7, (ep, len(rows))
        assert [g["step"] for g in rows] == list(range(len(rows))), ep
        assert [g["text"] for g in rows] == e["instructions"], ep
        assert all(set(g) == {"episode", "step", "text", "style", "expect"} for g in rows), ep
        assert len({g["style"] for g in rows}) == 1, ep
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
                    assert w not in t, (key, "back-reference right after a refusal", w)
            if "refusal" in x:
                assert set(x) == {"refusal"}, key
                n_ref += 1
                why = x["refusal"]
                assert why in REASONS, (key, why)
                reasons[why] = reasons.get(why, 0) + 1
                if why in ("overlap", "past_wall", "not_on_top"):
                    pid, stud, pl = INTENDED[key]
                    check_refs(key, INTENDED_REFS.get(key, {}), pid, stud, last)
                    p = problems(state, wall, pid, stud, pl)
                    assert p == [why], (key, why, p)
                elif why == "empty_stack":
                    assert not state[INTENDED_STACK[key]], key
                elif why == "off_end":
                    n = OFF_END[key]
                    assert last is not None, key
                    assert not 0 <= STUDS[last[1]] + n <= 12, key
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
            assert key in REFS or (pid in g["text"] and stud in g["text"]), (key, "no REFS")
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
    for table in (INTENDED, INTENDED_REFS, INTENDED_STACK, OFF_END, AMBIGUOUS):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    assert set(CORRECTED) <= set(REFS) | {(g["episode"], g["step"]) for g in gold}, CORRECTED
    n = len(gold)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("refusals:", reasons)
    print("placements:", placements)
    print(f"history-dependent steps={len(history)}:", " ".join(f"{e}/{s}" for e, s in history))
    print("OK")


if __name__ == "__main__":
    main()
