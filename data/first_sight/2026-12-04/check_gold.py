"""Stand-alone checker for the first-sight set (2026-12-04).

Replays each episode's expected commands on the fresh site with the geometry
of spec section 4/5 (written from /work/shared/spec/case-study.md only; it
does not import drywall_lab).  Asserts that
  - every expected command is feasible (panel on top of its stack, inside the
    wall, no positive-area overlap with an installed panel);
  - every expected refusal for overlap / past_wall / not_on_top / empty_stack
    is indeed infeasible for the intended command (INTENDED below), and for
    exactly that reason; unknown_id / no_size / previous_empty are checked too;
  - back-references (same size as previous, relative stack, relative stud)
    written in REFS agree with the gold;
  - instructions.jsonl and gold.jsonl hold the same texts in the same order.
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

# Intended command of each refused step whose refusal depends on site state.
INTENDED = {
    ("fs01", 2): ("500312", "500106", "vertical_left"),    # not on top
    ("fs04", 3): ("500300", "500110", "vertical_left"),    # past the wall
    ("fs05", 2): ("500311", "500104", "vertical_left"),    # overlap
    ("fs06", 3): (None, "500110", "vertical_middle"),      # middle stack empty
}
INTENDED_STACK = {("fs06", 3): "middle"}
UNKNOWN = {("fs02", 3): "500113"}
NO_SIZE = {("fs11", 0): (3, 8)}

# Derivation checks for steps whose target or stud is a back-reference
# or a size / position word (not an id).
REFS = {
    ("fs01", 0): {"size": (4, 8)}, ("fs01", 1): {"size": (2, 8)},
    ("fs01", 3): {"size": (4, 6)},
    ("fs02", 0): {"stack": "left"}, ("fs02", 1): {"size": (4, 6)},
    ("fs02", 2): {"size": (2, 8)},
    ("fs03", 0): {"stack": "middle", "stud_abs": 0},
    ("fs03", 1): {"size": (2, 8)}, ("fs03", 2): {"size": (4, 6)},
    ("fs03", 3): {"size": (4, 8)},
    ("fs04", 0): {"stack": "left", "stud_abs": 0},
    ("fs04", 1): {"same_size_as_prev": True, "stud_rel_prev": 3},
    ("fs04", 2): {"stack_rel_prev": 1},
    ("fs05", 0): {"stack": "left", "stud_abs": 0}, ("fs05", 1): {"size": (2, 8)},
    ("fs05", 3): {"size": (2, 8), "stud_rel_prev": 2},
    ("fs05", 4): {"size": (4, 6), "stud_abs": 7},
    ("fs06", 0): {"size": (2, 8)},
    ("fs06", 1): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fs06", 2): {"size": (2, 8)}, ("fs06", 4): {"size": (8, 4)},
    ("fs07", 0): {"size": (4, 8)}, ("fs07", 1): {"stack_rel_prev": 1},
    ("fs07", 2): {"size": (2, 8)}, ("fs07", 3): {"size": (4, 6)},
    ("fs08", 0): {"stack": "right"}, ("fs08", 1): {"size": (4, 8), "stud_abs": 5},
    ("fs08", 2): {"size": (4, 6), "stud_abs": 0},
    ("fs08", 3): {"size": (4, 6), "stud_abs": 0},
    ("fs09", 0): {"size": (2, 8), "stud_abs": 10},
    ("fs09", 1): {"same_size_as_prev": True, "stud_rel_prev": -2},
    ("fs09", 2): {"stack": "left", "stud_abs": 0},
    ("fs09", 3): {"same_size_as_prev": True, "stud_rel_prev": 0},
    ("fs09", 4): {"stack_rel_prev": 1},
    ("fs10", 0): {"size": (4, 6)}, ("fs10", 1): {"size": (2, 8)},
    ("fs10", 2): {"same_size_as_prev": True, "stud_rel_prev": 2},
    ("fs10", 3): {"stack": "left"},
    ("fs11", 1): {"size": (4, 8)}, ("fs11", 2): {"size": (4, 6)},
    ("fs11", 3): {"size": (4, 6)},
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
    out = []
    if pid not in STACK_OF or stud not in STUDS:
        return ["unknown_id"]
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


def main():
    inst = [json.loads(l) for l in open(HERE / "instructions.jsonl") if l.strip()]
    gold = [json.loads(l) for l in open(HERE / "gold.jsonl") if l.strip()]
    by_ep = {}
    for g in gold:
        by_ep.setdefault(g["episode"], []).append(g)
    assert [e["id"] for e in inst] == list(by_ep), "episode order differs"
    n_ref = 0
    styles = {}
    for e in inst:
        ep = e["id"]
        rows = by_ep[ep]
        assert [g["step"] for g in rows] == list(range(len(rows))), ep
        assert [g["text"] for g in rows] == e["instructions"], ep
        state = {s: list(ids) for s, ids in FRESH.items()}
        wall = []          # ((x0, x1, z0, z1), pid)
        last = None        # (pid, stud) of the last accepted command
        for g in rows:
            key = (ep, g["step"])
            x = g["expect"]
            styles[g["style"]] = styles.get(g["style"], 0) + 1
            if "refusal" in x:
                n_ref += 1
                why = x["refusal"]
                if why in ("overlap", "past_wall", "not_on_top"):
                    pid, stud, pl = INTENDED[key]
                    p = problems(state, wall, pid, stud, pl)
                    assert p == [why], (key, why, p)
                elif why == "empty_stack":
                    assert not state[INTENDED_STACK[key]], key
                elif why == "unknown_id":
                    assert UNKNOWN[key] not in STUDS and UNKNOWN[key] not in STACK_OF, key
                elif why == "no_size":
                    assert stack_for_size(*NO_SIZE[key]) == [], key
                elif why == "previous_empty":
                    assert last is None, key
                else:
                    raise AssertionError((key, "unchecked refusal reason", why))
                continue
            assert set(x) == {"drywall_id", "stud_id", "placement"}, key
            pid, stud, pl = x["drywall_id"], x["stud_id"], x["placement"]
            assert isinstance(pid, str) and isinstance(stud, str), key
            assert pl in PLACEMENTS, key
            ref = REFS.get(key, {})
            s = STACK_OF[pid]
            if "size" in ref:
                assert stack_for_size(*ref["size"]) == [s], (key, ref)
            if "stack" in ref:
                assert ref["stack"] == s, (key, ref)
            if "same_size_as_prev" in ref:
                assert last is not None and STACK_OF[last[0]] == s, key
            if "stack_rel_prev" in ref:
                i = STACK_ORDER.index(STACK_OF[last[0]]) + ref["stack_rel_prev"]
                assert STACK_ORDER[i] == s, key
            if "stud_rel_prev" in ref:
                assert STUDS[stud] == STUDS[last[1]] + ref["stud_rel_prev"], key
            if "stud_abs" in ref:
                assert STUDS[stud] == ref["stud_abs"], key
            p = problems(state, wall, pid, stud, pl)
            assert not p, (key, x, p)
            state[s].pop()
            wall.append((rect(pid, stud, pl), pid))
            last = (pid, stud)
    n = len(gold)
    print(f"episodes={len(inst)} steps={n} refusals={n_ref} commands={n - n_ref}")
    print("styles:", styles)
    print("OK")


if __name__ == "__main__":
    main()
