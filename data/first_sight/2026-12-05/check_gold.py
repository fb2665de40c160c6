"""Stand-alone checker for the first-sight set of 2026-12-05.

Replays each episode's expected commands on the fresh site with the geometry
of spec sections 1, 4 and 5 (written from /work/shared/spec/case-study.md
only; it does not import drywall_lab).  Asserts that
  - every expected command is feasible (panel on top of its stack, inside the
    wall, no positive-area overlap with an installed panel);
  - every expected refusal is for exactly the stated reason: for overlap /
    past_wall / not_on_top the intended command (INTENDED below) is infeasible
    for that reason and no other; empty_stack, unknown_id, no_history and
    ambiguous_size are checked against the replayed state / the site (for
    ambiguous_size: the single number matches two sizes and the command is
    feasible with either panel, so the site does not tell them apart);
    undetermined steps name a panel but no stud (written in UNDETERMINED);
  - the references that are not ids (sizes, a single width, stacks, ordinal
    studs, same size as previous, stack relative to the previous panel, stud
    relative to the previous stud), written in REFS, agree with the gold;
  - every expected command's panel id and stud id either appear in the text
    or are derived in REFS; the placement words agree with the placement
    (top / bottom / centre; a vertical_left step says no centre line except
    "not the centre line");
  - instructions.jsonl and gold.jsonl hold the same texts in the same order,
    every episode has 4 to 6 steps.
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
           "no_history", "ambiguous_size", "undetermined")

# Intended command of each refused step whose refusal depends on geometry / stack order.
INTENDED = {
    ("fc01", 4): ("500310", "500109", "vertical_middle"),  # over the two 4x6 flats
    ("fc02", 2): ("500310", "500105", "vertical_left"),    # 500320 is on top
    ("fc03", 4): ("500310", "500110", "vertical_left"),    # 4x8 runs past the last stud
}
INTENDED_REFS = {
    ("fc01", 4): {"size": (4, 8)},
    ("fc03", 4): {"size": (4, 8)},
}
INTENDED_STACK = {("fc05", 3): "middle"}          # empty_stack
UNKNOWN = {("fc07", 2): "500115"}                 # unknown_id
NO_HISTORY = {("fc06", 0)}                        # "same size as last time" at step 0
# ambiguous_size: (field, number, stud, placement): the number matches >= 2 sizes
AMBIG = {("fc04", 1): ("length", 8, "500104", "vertical_left")}
# undetermined: the panel the step names (its stack) and no stud at all
UNDETERMINED = {("fc09", 3): {"size": (4, 6)}}    # "not on the same stud as last time"

REFS = {
    ("fc01", 0): {"stack": "left"},
    ("fc01", 1): {"size": (2, 8)},
    ("fc01", 2): {"size": (4, 6)},
    ("fc01", 3): {"size": (4, 6), "stud_rel_prev": 0},
    ("fc01", 5): {"size": (2, 8)},
    ("fc02", 0): {"size": (2, 8), "stud_abs": 1},
    ("fc02", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fc02", 3): {"stack": "left"},
    ("fc02", 4): {"size": (4, 6)},
    ("fc03", 0): {"size": (4, 8), "stud_abs": 0},
    ("fc03", 1): {"width": 2},
    ("fc03", 2): {"size": (4, 6)},
    ("fc03", 3): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fc03", 5): {"width": 2},
    ("fc04", 0): {"size": (2, 8), "stud_abs": 12 - 2},
    ("fc04", 2): {"size": (4, 8)},
    ("fc04", 3): {"stack_rel_prev": 1},
    ("fc04", 4): {"size": (4, 6), "stud_abs": 0},
    ("fc05", 0): {"stack": "middle"},
    ("fc05", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fc05", 2): {"stack": "middle"},
    ("fc05", 4): {"size": (4, 6)},
    ("fc06", 1): {"size": (4, 8), "stud_abs": 0},
    ("fc06", 2): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fc06", 3): {"stack_rel_prev": 1},
    ("fc06", 4): {"size": (4, 6)},
    ("fc07", 0): {"size": (8, 4)},
    ("fc07", 1): {"size": (8, 2)},
    ("fc07", 3): {"size": (6, 4)},
    ("fc07", 4): {"size": (6, 4), "stud_rel_prev": 0},
    ("fc08", 0): {"size": (6, 4), "stud_abs": 12 - 3},
    ("fc08", 1): {"size": (8, 2), "stud_rel_prev": -6},
    ("fc08", 2): {"size": (8, 2)},
    ("fc08", 3): {"size": (8, 4), "stud_abs": 0},
    ("fc08", 4): {"size": (6, 4)},
    ("fc09", 0): {"size": (2, 8)},
    ("fc09", 1): {"size": (4, 6)},
    ("fc09", 2): {"size": (4, 8)},
    ("fc09", 4): {"size": (4, 6), "stud_abs": 0},
    ("fc10", 0): {"stack": "left", "stud_abs": 0},
    ("fc10", 1): {"stack": "middle", "stud_rel_prev": 3},
    ("fc10", 2): {"size": (4, 8)},
    ("fc10", 3): {"size": (4, 6)},
}
PANEL_KEYS = ("size", "width", "stack", "same_size_as_prev", "stack_rel_prev")
STUD_KEYS = ("stud_abs", "stud_rel_prev")


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
    if pl == "horizontal_top":
        assert "top" in t, key
    elif pl == "horizontal_bottom":
        assert "bottom" in t, key
    elif pl == "vertical_middle":
        assert "centre" in t, key
    else:
        assert "centre" not in t or "not the centre" in t, key
        for w in ("along the top", "along the bottom", "top row", "bottom row", "landscape"):
            assert w not in t, (key, w)


def main():
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl") if l.strip()]
    gold = [json.loads(l) for l in open(HERE / "gold.jsonl") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    n_ref = 0
    styles = {}
    reasons = {}
    for e in inst:
        ep = e["id"]
        rows = by_ep[ep]
        assert 4 <= len(rows) <= 6, (ep, len(rows))
        assert [g["step"] for g in rows] == list(range(len(rows))), ep
        assert [g["text"] for g in rows] == e["instructions"], ep
        assert len({g["style"] for g in rows}) == 1, ep
        state = {s: list(ids) for s, ids in FRESH.items()}   # every episode: fresh site
        wall = []          # ((x0, x1, z0, z1), pid)
        last = None        # (pid, stud) of the last accepted command
        for g in rows:
            key = (ep, g["step"])
            x = g["expect"]
            styles[g["style"]] = styles.get(g["style"], 0) + 1
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
                elif why == "ambiguous_size":
                    field, n, stud, pl = AMBIG[key]
                    i = 0 if field == "width" else 1
                    hits = [s for s, wl in SIZE_FT.items() if wl[i] == n]
                    assert len(hits) >= 2, key
                    assert stud in g["text"], key
                    for s in hits:   # the site does not tell them apart
                        assert state[s], key
                        assert not problems(state, wall, state[s][-1], stud, pl), (key, s)
                elif why == "undetermined":
                    ref = UNDETERMINED[key]
                    assert len(stack_for_size(*ref["size"])) == 1, key
                    assert not any(sid in g["text"] for sid in STUDS), key
                continue       # a refused step leaves the state as it was
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
    # every refused key named above must belong to a refusal step
    refused = {(g["episode"], g["step"]) for g in gold if "refusal" in g["expect"]}
    for table in (INTENDED, INTENDED_STACK, UNKNOWN, NO_HISTORY, AMBIG, UNDETERMINED):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    n = len(gold)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("refusals:", reasons)
    print("OK")


if __name__ == "__main__":
    main()
