"""Choosing the decision layer's thresholds, and its risk against coverage (issue 12; ``drywall_lab.decision``).

The thresholds are chosen on the **generated** field corpus only: its validation split (the families the
tagger was trained on) and its novel split (held-back families), never on the hand-written field sets,
which stay a measuring stick. For every setting of the grid the script decides each instruction of both
splits (in its own episode context) and counts right outcomes, wrong actions (the robot acted, not as
intended) and over-refusals (a refusal or a question where a command was expected). The rule:

    cost = WRONG_ACTION_COST x wrong-action rate + over-refusal rate, averaged over the two splits;
    the setting of least cost wins; ties go to the more careful setting (higher ``act``, then ``recover``).

A wrong action moves a 25 kg sheet to the wrong place; a question costs the worker a few seconds, so a
wrong action counts as ``WRONG_ACTION_COST`` questions. The script also writes the risk-coverage curve
of the chosen setting (the ``act`` threshold moved, everything else fixed) and the best-path baseline,
to its results file (default ``benchmarks/results/decision.md``), with the machine, the date and the
command. ``drywall_lab.decision.DEFAULT_SETTINGS`` must equal the recorded choice (a test checks it).

    python benchmarks/decision.py [--tagger DIR] [--out FILE] [--quick]
"""
from __future__ import annotations

import argparse
import itertools
import sys
import time
from dataclasses import asdict, replace
from pathlib import Path

import pandas as pd

from drywall_lab.decision import (BEST_PATH, DEFAULT_SETTINGS, DecisionSettings, decide, decision_scores,
                                  risk_coverage)
from drywall_lab.im import ActionHistory, interpret
from drywall_lab.machine import describe_machine
from drywall_lab.pipeline import load_tagger_option
from drywall_lab.splits import split_rows

ROOT = Path(__file__).resolve().parent.parent
RESULTS = Path(__file__).resolve().parent / "results" / "decision.md"
SPLITS = ("field-validation", "field-novel")
WRONG_ACTION_COST = 10
GRID = {
    "act": (0.0, 0.3, 0.5, 0.7, 0.8, 0.9, 0.95),
    "recover": (0.2, 0.4, 0.6, 1.0),
    "doubt": (0.05, 0.1, 0.2, 0.35, 1.0),
    "margin": (1.5, 3.0, 5.0),
}
QUICK_GRID = {"act": (0.0, 0.7), "recover": (0.4, 1.0), "doubt": (0.2, 1.0), "margin": (3.0,)}


class Readings:
    """The tagger's readings of one split, tagged once, and a cache of the IM's interpretations."""

    def __init__(self, rows: list[dict], tagger, k: int) -> None:
        self.rows = rows
        self.labels = tagger.labels
        self.confidences = tagger.predict_confidence([r["words"] for r in rows], k=k)
        self.histories = [ActionHistory.from_commands(r["context"]["history"]) for r in rows]
        self._cache: dict[tuple[int, tuple[str, ...]], object] = {}

    def decide(self, settings: DecisionSettings) -> list:
        out = []
        for i, (row, conf, history) in enumerate(zip(self.rows, self.confidences, self.histories)):
            def cached(words, tags, hist, i=i):
                key = (i, tuple(tags))
                if key not in self._cache:
                    self._cache[key] = interpret(words, tags, hist)
                return self._cache[key]
            out.append(decide(row["words"], conf.kbest, conf.marginals, self.labels, history, settings, cached))
        return out


def cost(scores: dict[str, float]) -> float:
    return WRONG_ACTION_COST * scores["wrong_action_rate"] + scores["over_refusal_rate"]


def choose(readings: dict[str, Readings], grid: dict[str, tuple]) -> tuple[DecisionSettings, pd.DataFrame]:
    """Every setting of the grid scored on every split; the setting of least mean cost (ties: more careful)."""
    rows = []
    for act, recover, doubt, margin in itertools.product(grid["act"], grid["recover"], grid["doubt"], grid["margin"]):
        settings = replace(DEFAULT_SETTINGS, act=act, recover=recover, doubt=doubt, margin=margin)
        record = {"act": act, "recover": recover, "doubt": doubt, "margin": margin}
        costs = []
        for split, r in readings.items():
            scores = decision_scores(r.rows, r.decide(settings))
            record.update({f"{split}:{k}": v for k, v in scores.items()})
            costs.append(cost(scores))
        record["cost"] = sum(costs) / len(costs)
        rows.append(record)
    table = pd.DataFrame(rows)
    best = table.sort_values(["cost", "act", "recover", "doubt", "margin"], ascending=[True, False, True, True, False],
                             kind="stable").iloc[0]
    chosen = replace(DEFAULT_SETTINGS, act=float(best["act"]), recover=float(best["recover"]),
                     doubt=float(best["doubt"]), margin=float(best["margin"]))
    return chosen, table


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tagger", default=None, help="a saved tagger's directory (default: the shipped one)")
    parser.add_argument("--out", type=Path, default=None, help=f"results file (default {RESULTS.relative_to(ROOT)})")
    parser.add_argument("--quick", action="store_true", help="200 instructions a split and a small grid (needs --out)")
    args = parser.parse_args(argv)
    if args.quick and args.out is None:
        parser.error("--quick writes a check, not the recorded choice: give --out")
    out = args.out or RESULTS
    machine = describe_machine()
    tagger = load_tagger_option(args.tagger)
    grid = QUICK_GRID if args.quick else GRID
    started = time.perf_counter()
    readings = {s: Readings(split_rows(s)[:200] if args.quick else split_rows(s), tagger, DEFAULT_SETTINGS.k)
                for s in SPLITS}
    chosen, table = choose(readings, grid)
    lines = ["# Decision layer: thresholds and risk against coverage (`benchmarks/decision.py`)", "",
             f"**Command:** `python benchmarks/decision.py{''.join(' ' + a for a in (argv if argv is not None else sys.argv[1:]))}`",
             "", f"**Tagger:** {args.tagger or 'the shipped default tagger'}", "", *machine.markdown_lines(), "",
             f"Splits: {', '.join(f'{s} ({len(r.rows)} instructions)' for s, r in readings.items())}; "
             f"{len(table)} settings; rule: least mean of {WRONG_ACTION_COST} x wrong-action rate + over-refusal "
             "rate, ties to the more careful setting.", "",
             "## Choice", "", "```", f"chosen={asdict(chosen)}", "```", ""]
    compare = []
    for name, settings in (("best path (the paper)", BEST_PATH), ("chosen", chosen)):
        for split, r in readings.items():
            compare.append({"setting": name, "split": split, **decision_scores(r.rows, r.decide(settings))})
    compare_table = pd.DataFrame(compare)
    lines += ["## Best path against the chosen setting", "", "```",
              compare_table.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", ""]
    lines += ["## Risk against coverage (chosen setting, `act` moved)", ""]
    for split, r in readings.items():
        curve = risk_coverage(r.rows, r.decide(replace(chosen, act=0.0)))
        picks = curve.iloc[sorted({int(i) for i in pd.Series(range(len(curve))).quantile([0, .5, .8, .9, .95, .98, 1]).round()})]
        lines += [f"{split}:", "", "```", picks.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", ""]
    best_rows = table.sort_values("cost").head(10)
    lines += ["## The ten settings of least cost", "", "```",
              best_rows.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", "",
              f"{time.perf_counter() - started:.0f} s in all.", ""]
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines), encoding="utf-8")
    print(compare_table.to_string(index=False, float_format=lambda x: f"{x:.4f}"))
    print(f"chosen={asdict(chosen)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
