"""Stand-alone checker for the second first-sight set of 2026-12-04 (2026-12-04b).

Replays each episode's expected commands on the fresh site with the geometry
of spec sections 1, 4 and 5 (written from /work/shared/spec/case-study.md
only; it does not import drywall_lab).  Asserts that
  - every expected command is feasible (panel on top of its stack, inside the
    wall, no positive-area overlap with an installed panel);
  - every expected refusal is for exactly the stated reason: for overlap /
    past_wall / not_on_top the intended command (INTENDED below) is infeasible
    for that reason and no other; empty_stack, unknown_id, no_size and off_end
    are checked against the replayed state / the site;
  - the references that are not ids (sizes, stacks, ordinal studs, same size
    as previous, stack relative to the previous panel or to a panel id, stud
    relative to the previous stud), written in REFS, agree with the gold;
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
           "no_size", "off_end")

# Intended command of each refused step whose refusal depends on geometry / stack order.
INTENDED = {
    ("fb03", 3): ("500302", "500109", "vertical_left"),    # 500322 is on top
    ("fb04", 4): ("500322", "500108", "vertical_left"),    # 4x6 over the bottom 2x8
    ("fb07", 4): ("500310", "500110", "vertical_middle"),  # runs past the last stud
}
# Derivation of those intended commands (checked like REFS, on the state at that step).
INTENDED_REFS = {
    ("fb04", 4): {"size": (4, 6)},
    ("fb07", 4): {"same_size_as_prev": True, "stud_rel_prev": 3},
}
INTENDED_STACK = {("fb02", 3): "middle"}        # empty_stack
UNKNOWN = {("fb06", 2): "500330"}               # unknown_id
NO_SIZE = {("fb09", 3): (3, 8)}                 # no_size
OFF_END = {("fb08", 3): 5}                      # off_end: stud of previous + n

REFS = {
    ("fb01", 0): {"size": (4, 8)}, ("fb01", 1): {"size": (2, 8)},
    ("fb01", 2): {"size": (4, 6)}, ("fb01", 3): {"size": (4, 6)},
    ("fb01", 4): {"size": (2, 8)},
    ("fb02", 0): {"stack": "middle"}, ("fb02", 1): {"stack": "middle"},
    ("fb02", 4): {"stack": "right"},
    ("fb03", 4): {"stack": "right"},
    ("fb04", 0): {"size": (4, 8), "stud_abs": 0},
    ("fb04", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fb04", 2): {"stack_rel_prev": 1},
    ("fb04", 3): {"size": (2, 8)},
    ("fb05", 0): {"size": (2, 8)},
    ("fb05", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fb05", 2): {"size": (4, 6)}, ("fb05", 3): {"size": (4, 8)},
    ("fb06", 0): {"stack": "right", "stud_abs": 2},
    ("fb06", 3): {"stack_rel_panel": ("500321", -1)},
    ("fb06", 4): {"size": (2, 8)},
    ("fb07", 0): {"stack": "right", "stud_abs": 0},
    ("fb07", 1): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fb07", 2): {"stack": "middle", "stud_abs": 5},
    ("fb07", 3): {"stack_rel_prev": -1, "stud_rel_prev": 2},
    ("fb07", 5): {"stack": "middle", "stud_abs": 12 - 2},
    ("fb08", 0): {"stack": "middle", "stud_abs": 6},
    ("fb08", 1): {"stack": "left", "stud_rel_prev": -4},
    ("fb08", 2): {"stack": "middle", "stud_abs": 6 + 2},
    ("fb08", 4): {"stack": "middle", "stud_abs": 12 - 2},
    ("fb09", 0): {"size": (4, 8)}, ("fb09", 1): {"size": (2, 8)},
    ("fb09", 2): {"size": (4, 6)}, ("fb09", 4): {"size": (4, 8)},
    ("fb10", 0): {"stack": "middle"},
    ("fb10", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fb10", 2): {"size": (4, 8)},
    ("fb10", 3): {"size": (4, 6), "stack": "right"},
    ("fb10", 4): {"size": (2, 8), "stud_abs": 0},
}


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
    if "stack" in ref:
        assert ref["stack"] == s, (key, ref)
    if "same_size_as_prev" in ref:
        assert last is not None and STACK_OF[last[0]] == s, key
    if "stack_rel_prev" in ref:
        assert last is not None, key
        i = STACK_ORDER.index(STACK_OF[last[0]]) + ref["stack_rel_prev"]
        assert 0 <= i < 3 and STACK_ORDER[i] == s, key
    if "stack_rel_panel" in ref:
        anchor, n = ref["stack_rel_panel"]
        i = STACK_ORDER.index(STACK_OF[anchor]) + n
        assert 0 <= i < 3 and STACK_ORDER[i] == s, key
    if "stud_rel_prev" in ref:
        assert last is not None, key
        assert STUDS[stud] == STUDS[last[1]] + ref["stud_rel_prev"], key
    if "stud_abs" in ref:
        assert STUDS[stud] == ref["stud_abs"], key


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
                    check_refs(key, INTENDED_REFS.get(key, {}), pid, stud, last)
                    p = problems(state, wall, pid, stud, pl)
                    assert p == [why], (key, why, p)
                elif why == "empty_stack":
                    assert not state[INTENDED_STACK[key]], key
                elif why == "unknown_id":
                    assert UNKNOWN[key] not in STUDS and UNKNOWN[key] not in STACK_OF, key
                elif why == "no_size":
                    assert stack_for_size(*NO_SIZE[key]) == [], key
                elif why == "off_end":
                    assert last is not None, key
                    assert not 0 <= STUDS[last[1]] + OFF_END[key] <= 12, key
                continue       # a refused step leaves the state as it was
            assert set(x) == {"drywall_id", "stud_id", "placement"}, key
            pid, stud, pl = x["drywall_id"], x["stud_id"], x["placement"]
            assert isinstance(pid, str) and isinstance(stud, str), key
            assert pl in PLACEMENTS, key
            check_refs(key, REFS.get(key, {}), pid, stud, last)
            p = problems(state, wall, pid, stud, pl)
            assert not p, (key, x, p)
            state[STACK_OF[pid]].pop()
            wall.append((rect(pid, stud, pl), pid))
            last = (pid, stud)
    # every refused/unknown key named above must belong to a refusal step
    refused = {(g["episode"], g["step"]) for g in gold if "refusal" in g["expect"]}
    for table in (INTENDED, INTENDED_STACK, UNKNOWN, NO_SIZE, OFF_END):
        assert set(table) <= refused, table
    assert not set(REFS) & refused, "REFS names a refused step"
    n = len(gold)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("refusals:", reasons)
    print("OK")


if __name__ == "__main__":
    main()
