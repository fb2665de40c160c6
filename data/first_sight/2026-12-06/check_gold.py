"""Stand-alone checker for the first-sight set of 2026-12-06.

Replays each episode's expected commands on the fresh site with the geometry
of spec sections 1, 4 and 5 (written from ../shared/spec/case-study.md only;
it does not import drywall_lab).  Asserts that
  - every expected command is feasible (panel on top of its stack, inside the
    wall, no positive-area overlap with an installed panel; touching edges are
    fine);
  - every expected refusal is for exactly the stated reason: for overlap /
    past_wall / not_on_top the intended command (INTENDED below) is infeasible
    for that reason and no other; empty_stack, unknown_id, no_history,
    off_end (a stud counted from the previous stud runs past the last stud)
    and no_size_match (the size said matches no stack, as given or turned)
    are checked against the replayed state / the site; for unclear, the
    readings the words allow (UNCLEAR) are at least two different commands,
    each feasible as it stands, so the site does not tell them apart;
  - the references that are not ids (sizes, a single width, stacks, same size
    as previous, stack relative to the previous panel's stack, stud relative
    to the previous stud), written in REFS, agree with the gold;
  - every expected command's panel id and stud id either appear in the text
    or are derived in REFS, no other id is said (except an id the speaker
    corrects away from, CORRECTED), and the placement words agree with the
    placement (a top row / bottom row / centre line phrase, in English or in
    the Scots spelling "alang"; a vertical_left step says nothing of a centre
    line, a row or lying flat);
  - the step right after a refusal uses no back-reference word ("previous",
    "last", "same", "again", "that one", "just", and the Spanish "mismo",
    "misma", "anterior", "igual", "otra vez"), so no one has to wonder
    whether the refused instruction counts;
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    every episode has 4 to 6 steps, one voice an episode, ids fe01..fe10.
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
           "no_history", "off_end", "no_size_match", "unclear")

# Intended command of each refused step whose refusal depends on geometry / stack order.
INTENDED = {
    ("fe01", 4): ("500311", "500107", "vertical_left"),      # upright 2x8 into the flat 4x6s and 500321
    ("fe03", 4): ("500302", "500110", "vertical_left"),      # upright 4x6 runs past the last stud
    ("fe07", 4): ("500301", "500102", "vertical_left"),      # 500311 lies on it
}
INTENDED_REFS = {
    ("fe03", 4): {"size": (4, 6)},
}
INTENDED_STACK = {("fe10", 3): "middle"}          # empty_stack: a fourth two-foot panel
UNKNOWN = {("fe05", 4): "500330"}                 # unknown_id
NO_HISTORY = {("fe08", 0)}                        # "del mismo tamano que la anterior" at step 0
# off_end: the stud counted from the previous stud (this many to the right) is past 500112
OFF_END = {("fe04", 3): 3}                        # "Same again, three studs further alang tae the right"
# no_size_match: the size said matches no stack, as given or turned
NO_SIZE = {("fe06", 3): (3, 8)}                   # "3 by 8 board"
# unclear: the readings the words allow; each is feasible, so the site does not tell them apart
UNCLEAR = {("fe09", 2): [("500322", "500107", "vertical_left"),
                         ("500322", "500107", "vertical_middle")]}   # "centre line or the left line"
# ids said in a self-correction ("from stud 500106, oh, sorry, I mean from stud 500107")
CORRECTED = {("fe10", 5): {"500106"}}

REFS = {
    ("fe01", 0): {"size": (4, 8)},
    ("fe01", 1): {"size": (4, 6)},
    ("fe01", 2): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fe01", 3): {"width": 2},
    ("fe01", 5): {"stack": "middle"},
    ("fe02", 0): {"size": (2, 8)},
    ("fe02", 1): {"size": (4, 8), "stud_rel_prev": 0},
    ("fe02", 2): {"size": (4, 6)},
    ("fe02", 3): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fe02", 4): {"size": (2, 8)},
    ("fe03", 0): {"size": (4, 8)},
    ("fe03", 1): {"width": 2},
    ("fe03", 2): {"size": (4, 6)},
    ("fe03", 3): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fe03", 5): {"width": 2},
    ("fe04", 0): {"stack": "middle"},
    ("fe04", 1): {"size": (4, 8)},
    ("fe04", 2): {"stack_rel_prev": 1},
    ("fe04", 4): {"size": (4, 6)},
    ("fe04", 5): {"size": (4, 6), "stud_rel_prev": 0},
    ("fe05", 0): {"size": (4, 8)},
    ("fe05", 1): {"size": (2, 8)},
    ("fe05", 2): {"size": (4, 6)},
    ("fe05", 3): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fe05", 5): {"size": (2, 8)},
    ("fe06", 0): {"size": (4, 8)},
    ("fe06", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fe06", 2): {"size": (2, 8)},
    ("fe06", 4): {"size": (2, 8)},
    ("fe06", 5): {"same_size_as_prev": True, "stud_rel_prev": -2},
    ("fe07", 0): {"size": (4, 8)},
    ("fe07", 1): {"size": (2, 8)},
    ("fe07", 3): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fe07", 5): {"stack": "middle"},
    ("fe08", 1): {"size": (4, 6)},
    ("fe08", 2): {"size": (2, 8)},
    ("fe08", 3): {"stack": "left"},
    ("fe08", 4): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fe09", 0): {"size": (4, 8)},
    ("fe09", 1): {"width": 2},
    ("fe09", 3): {"size": (4, 6)},
    ("fe09", 4): {"width": 2, "stud_rel_prev": -1},
    ("fe10", 0): {"size": (2, 8)},
    ("fe10", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fe10", 2): {"width": 2},
    ("fe10", 4): {"size": (4, 8)},
    ("fe10", 5): {"size": (4, 6)},
}
PANEL_KEYS = ("size", "width", "stack", "same_size_as_prev", "stack_rel_prev")
STUD_KEYS = ("stud_abs", "stud_rel_prev")
HISTORY_KEYS = ("same_size_as_prev", "stack_rel_prev", "stud_rel_prev")
BACK_REF_WORDS = ("previous", "last", "same", "again", "that one", "just",
                  "mismo", "misma", "anterior", "igual", "otra vez")
TOP_PHRASES = ("top row", "along the top", "alang the top", "top course")
BOTTOM_PHRASES = ("bottom row", "along the bottom", "alang the bottom", "bottom course")
CENTRE_WORDS = ("centre", "center", "centro")
FLAT_WORDS = ("flat", "horizontal", "lying", "lyin'", "acostad")


def stack_for_size(a, b):
    hits = [s for s, (w, l) in SIZE_FT.items() if (w, l) == (a, b)]
    if not hits:
        hits = [s for s, (w, l) in SIZE_FT.items() if (w, l) == (b, a)]
    return hits


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
    if "width" in ref:
        assert [t for t, (w, _) in SIZE_FT.items() if w == ref["width"]] == [s], (key, ref)
    if "stack" in ref:
        assert ref["stack"] == s, (key, ref)
    if "same_size_as_prev" in ref:
        assert last is not None and STACK_OF[last[0]] == s, key
    if "stack_rel_prev" in ref:
        assert last is not None, key
        i = STACK_ORDER.index(STACK_OF[last[0]]) + ref["stack_rel_prev"]
        assert 0 <= i < 3 and STACK_ORDER[i] == s, key
    if "stud_rel_prev" in ref:
        assert last is not None, key
        assert STUDS[stud] == STUDS[last[1]] + ref["stud_rel_prev"], key
    if "stud_abs" in ref:
        assert STUDS[stud] == ref["stud_abs"], key


def check_words(key, text, pid, stud, pl, ref):
    t = text.lower()
    assert pid in text or any(k in ref for k in PANEL_KEYS), (key, "panel not said")
    assert stud in text or any(k in ref for k in STUD_KEYS), (key, "stud not said")
    # no other stud / panel id in the text than the ones meant (or corrected away from)
    allowed = CORRECTED.get(key, set())
    for sid in STUDS:
        assert sid == stud or sid in allowed or sid not in text, (key, "other stud id", sid)
    for p in STACK_OF:
        assert p == pid or p in allowed or p not in text, (key, "other panel id", p)
    has = lambda words: any(w in t for w in words)
    if pl == "horizontal_top":
        assert has(TOP_PHRASES) and not has(BOTTOM_PHRASES) and "bottom" not in t, key
    elif pl == "horizontal_bottom":
        assert has(BOTTOM_PHRASES) and not has(TOP_PHRASES), key
    elif pl == "vertical_middle":
        assert has(CENTRE_WORDS), key
        assert not has(FLAT_WORDS) and not has(TOP_PHRASES) and not has(BOTTOM_PHRASES), key
    else:
        assert not has(CENTRE_WORDS), key
        for w in TOP_PHRASES + BOTTOM_PHRASES + FLAT_WORDS:
            assert w not in t, (key, w)


def main():
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl") if l.strip()]
    gold = [json.loads(l) for l in open(HERE / "gold.jsonl") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    assert [e["id"] for e in inst] == [f"fe{i:02d}" for i in range(1, 11)], "episode ids"
    n_ref = 0
    styles, reasons, placements = {}, {}, {}
    history = []
    for e in inst:
        ep = e["id"]
        rows = by_ep[ep]
        assert set(e) == {"id", "instructions"}, ep
        assert 4 <= len(rows) <= 6, (ep, len(rows))
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
                    assert stud in g["text"], key
                    check_refs(key, INTENDED_REFS.get(key, {}), pid, stud, last)
                    p = problems(state, wall, pid, stud, pl)
                    assert p == [why], (key, why, p)
                elif why == "empty_stack":
                    assert not state[INTENDED_STACK[key]], key
                elif why == "unknown_id":
                    u = UNKNOWN[key]
                    assert u in g["text"], key
                    assert u not in STUDS and u not in STACK_OF, key
                elif why == "no_history":
                    assert key in NO_HISTORY and last is None, key
                elif why == "off_end":
                    n = OFF_END[key]
                    assert last is not None, key
                    assert not 0 <= STUDS[last[1]] + n <= 12, key
                elif why == "no_size_match":
                    a, b = NO_SIZE[key]
                    assert f"{a} by {b}" in g["text"], key
                    assert stack_for_size(a, b) == [], key
                elif why == "unclear":
                    cmds = UNCLEAR[key]
                    assert len(set(cmds)) >= 2, key
                    for pid, stud, pl in cmds:
                        assert stud in g["text"], key
                        assert not problems(state, wall, pid, stud, pl), (key, pid, stud, pl)
                prev_refused = True
                continue       # a refused step leaves the state as it was
            prev_refused = False
            assert set(x) == {"drywall_id", "stud_id", "placement"}, key
            pid, stud, pl = x["drywall_id"], x["stud_id"], x["placement"]
            assert isinstance(pid, str) and isinstance(stud, str), key
            assert pl in PLACEMENTS, key
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
    # every refused key named above must belong to a refusal step
    refused = {(g["episode"], g["step"]) for g in gold if "refusal" in g["expect"]}
    for table in (INTENDED, INTENDED_STACK, UNKNOWN, NO_HISTORY, OFF_END, NO_SIZE, UNCLEAR):
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
