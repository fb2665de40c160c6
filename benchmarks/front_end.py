"""Each step of the front end switched off: what it moves on generated and hand-written instructions (issue 29).

The front end (``drywall_lab.nlu.normalise``: ``STEPS``) reads ids, shorthand, fillers, false starts, metric sides,
plural sizes and Spanish mixed into an instruction into the words the tagger knows. A step earns its keep when
switching it off moves a generated outcome, as a rule of the IM or the decision does (``rule_ablation.py``).
For each step, this script re-reads every instruction's own text without it and plays what changed with the shipped
tagger and decision:

- the generated splits (``field-validation``, ``field-novel``): each row in its intended context, as ``evaluate``
  decides it; only the rows whose words the step changes are decided again;
- the hand-written sets (``data/field``, ``../shared/field``, ``data/first_sight/*``): episode by episode, as
  ``run`` plays them, where the step changes any of their words.

    python benchmarks/front_end.py [--quick --out FILE]

It writes ``benchmarks/results/front_end.md``: per step and set, the rows it changes and the right answers and
wrong actions with the step on and off.
"""
from __future__ import annotations

import argparse
import sys
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Callable, Iterator, Sequence

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

from drywall_lab.decision import decide_rows, decision_scores  # noqa: E402
from drywall_lab.field import read_field_set, score_run  # noqa: E402
from drywall_lab.machine import describe_machine  # noqa: E402
from drywall_lab.nlu import normalise as N  # noqa: E402
from drywall_lab.nlu.default import default_tagger  # noqa: E402
from drywall_lab.pipeline import run_episodes  # noqa: E402
from drywall_lab.splits import split_rows  # noqa: E402

from field import field_sets  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results" / "front_end.md"
GENERATED_SPLITS = ("field-validation", "field-novel")
QUICK_ROWS = 60


def without(step: Callable | None) -> tuple[Callable, ...]:
    """The front end's steps less ``step`` (None: all of them)."""
    return tuple(s for s in N.STEPS if s is not step)


@contextmanager
def front_end_of(steps: tuple[Callable, ...]) -> Iterator[None]:
    """The front end reads with ``steps`` inside the block (the module's ``STEPS`` put back afterwards)."""
    shipped = N.STEPS
    N.STEPS = steps
    try:
        yield
    finally:
        N.STEPS = shipped


def read_with(steps: tuple[Callable, ...], text: str) -> list[str]:
    """``text`` through ``steps``."""
    with front_end_of(steps):
        return list(N.normalise(text).words)


def generated_effect(rows: Sequence[dict], step: Callable, tagger, base: list) -> dict:
    """The rows whose words ``step`` changes, decided again without it: counts of right and wrong, on and off."""
    steps = without(step)
    changed = [(k, dict(row, words=read_with(steps, row["text"]))) for k, row in enumerate(rows)]
    changed = [(k, row) for k, row in changed if row["words"] != rows[k]["words"]]
    if not changed:
        return {"rows": 0, "right_on": 0, "right_off": 0, "wrong_on": 0, "wrong_off": 0}
    on = decision_scores([rows[k] for k, _ in changed], [base[k] for k, _ in changed])
    off = decision_scores([row for _, row in changed], decide_rows([row for _, row in changed], tagger))  # its words
    n = len(changed)
    return {"rows": n, "right_on": round(on["accuracy"] * n), "right_off": round(off["accuracy"] * n),
            "wrong_on": round(on["wrong_action_rate"] * n), "wrong_off": round(off["wrong_action_rate"] * n)}


def hand_written_effect(directory: Path, step: Callable, tagger, base: dict) -> dict:
    """A hand-written set played as ``run`` plays it, without ``step``, where the step changes any of its words."""
    field_set = read_field_set(directory, tagged=False)
    texts = [text for episode in field_set.episodes for text in episode["instructions"]]
    steps = without(step)
    rows = sum(read_with(steps, t) != list(N.normalise(t).words) for t in texts)
    if not rows:
        return {"rows": 0, "right_on": base["right"], "right_off": base["right"], "wrong_on": base["wrong"],
                "wrong_off": base["wrong"]}
    with front_end_of(steps):
        off = played(directory, tagger)
    return {"rows": rows, "right_on": base["right"], "right_off": off["right"], "wrong_on": base["wrong"],
            "wrong_off": off["wrong"]}


def played(directory: Path, tagger) -> dict:
    """Right answers and wrong actions of one hand-written set as ``run`` plays it."""
    field_set = read_field_set(directory, tagged=False)
    scores = score_run(list(run_episodes(field_set.episodes, tagger)), field_set).loc["ALL"]
    n = int(scores["n"])
    return {"right": round(scores["accuracy"] * n), "wrong": round(scores["wrong_action_rate"] * n), "n": n}


def cell(effect: dict) -> str:
    if not effect["rows"]:
        return "·"
    right = effect["right_off"] - effect["right_on"]
    wrong = effect["wrong_off"] - effect["wrong_on"]
    return f"{effect['rows']} rows: {right:+d} right, {wrong:+d} wrong"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_results_options(parser, RESULTS, quick=f"the first {QUICK_ROWS} rows of each generated split, no hand-written set")
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    started = time.perf_counter()
    tagger = default_tagger()
    generated = {split: split_rows(split)[:QUICK_ROWS if args.quick else None] for split in GENERATED_SPLITS}
    decided = {split: decide_rows(rows, tagger) for split, rows in generated.items()}
    hand = {} if args.quick else field_sets()
    base = {name: played(directory, tagger) for name, directory in hand.items()}
    columns = [*generated, *hand]
    lines = ["# The front end, step by step (`benchmarks/front_end.py`)", "",
             f"**Command:** `{command_line('front_end.py', argv if argv is not None else sys.argv[1:])}`", "",
             "**Tagger:** the shipped default tagger (drywall_lab/models/default_tagger)", "",
             *describe_machine().markdown_lines(), "",
             "Each step of `drywall_lab.nlu.normalise.STEPS` switched off in turn: the instructions whose words it "
             "changes, and the change in right answers and wrong actions against the front end as shipped "
             "(generated splits: each row in its intended context; hand-written sets: episode by episode as `run` "
             "plays them; `·`: the step changes none of its words).", "",
             "| step | " + " | ".join(columns) + " | verdict |", "|---" * (len(columns) + 2) + "|"]
    summary = []
    for step in N.STEPS:
        effects = {split: generated_effect(rows, step, tagger, decided[split]) for split, rows in generated.items()}
        effects |= {name: hand_written_effect(directory, step, tagger, base[name]) for name, directory in hand.items()}
        moved = [e for split, e in effects.items() if split in generated and
                 (e["right_on"], e["wrong_on"]) != (e["right_off"], e["wrong_off"])]
        verdict = "earns its keep" if moved else "moves no generated outcome"
        lines.append(f"| `{step.__name__}` | " + " | ".join(cell(effects[c]) for c in columns) + f" | {verdict} |")
        for split in generated:
            e = effects[split]
            summary.append(f"{step.__name__}_{split.replace('-', '_')}_rows={e['rows']} "
                           f"right_off_minus_on={e['right_off'] - e['right_on']} "
                           f"wrong_off_minus_on={e['wrong_off'] - e['wrong_on']}")
        print(lines[-1], flush=True)
    lines += ["", f"Wall time: {time.perf_counter() - started:.0f} s.", "", "## Summary", "", "```", *summary, "```", ""]
    write_results_file(out, lines)
    print("\n".join(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
