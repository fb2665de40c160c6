"""The generated novel split drawn again: is its figure a property of the pipeline or of one draw? (issues 29, 30)

The decision's weights are fitted on half of the committed field-novel split's episodes
(``benchmarks/decision.py``), and its figures are reported on that split. This script draws the novel split again
from other seeds (``field_generator.generate_field_split("novel", seed=...)``: the same held-back phrasing families,
channels, pairs and overlays, other sentences), decides every row in its intended context with the shipped tagger
and decision (as ``evaluate`` scores ``acc_decided``), and reports each draw and its spread, by channel too.

    python benchmarks/novel_redraws.py [--draws N] [--quick --out FILE]

It writes ``benchmarks/results/novel_redraws.md``; its last lines are ``redraws_accuracy_mean=...``,
``redraws_wrong_action_rate_mean=...`` and ``redraws_wrong_action_rate_max=...``.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

from drywall_lab.corpus.field_generator import FIELD_SEED, generate_field_split  # noqa: E402
from drywall_lab.decision import decide_rows, decision_scores  # noqa: E402
from drywall_lab.machine import describe_machine  # noqa: E402
from drywall_lab.nlu.cli import scores_by_channel  # noqa: E402
from drywall_lab.nlu.default import default_tagger  # noqa: E402
from drywall_lab.splits import split_rows  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results" / "novel_redraws.md"
QUICK_ROWS = 40


def draw_seeds(draws: int) -> list[int]:
    """The seeds of the redraws: the committed split's seed + 1, + 2, ..."""
    return [FIELD_SEED + k for k in range(1, draws + 1)]


def scored(rows: list[dict], tagger) -> tuple[dict[str, float], pd.DataFrame]:
    decisions = decide_rows(rows, tagger)
    return decision_scores(rows, decisions), scores_by_channel(rows, decisions)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--draws", type=int, default=3, help="how many redraws (default 3)")
    add_results_options(parser, RESULTS, quick=f"{QUICK_ROWS} rows a draw, one draw")
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    started = time.perf_counter()
    tagger = default_tagger()
    n = QUICK_ROWS if args.quick else None
    draws = {"committed": split_rows("field-novel")[:n]}
    for seed in draw_seeds(1 if args.quick else args.draws):
        draws[f"seed {seed}"] = generate_field_split("novel", n=n, seed=seed)
    lines = ["# The novel split drawn again (`benchmarks/novel_redraws.py`)", "",
             f"**Command:** `{command_line('novel_redraws.py', argv if argv is not None else sys.argv[1:])}`", "",
             "**Tagger:** the shipped default tagger (drywall_lab/models/default_tagger), the shipped decision", "",
             *describe_machine().markdown_lines(), "",
             "Each row decided in its intended context (as `evaluate` scores `acc_decided`). The committed draw is the "
             "one the decision's weights were fitted on (half of its episodes, `decision.md`); the others are new.", ""]
    table, channels = [], {}
    for name, rows in draws.items():
        scores, by_channel = scored(rows, tagger)
        table.append({"draw": name, "n": len(rows), "accuracy": scores["accuracy"],
                      "wrong_action_rate": scores["wrong_action_rate"],
                      "over_refusal_rate": scores["over_refusal_rate"], "wrong_actions": round(
                          scores["wrong_action_rate"] * len(rows))})
        channels[name] = by_channel.set_index("channel")["wrong_action_rate"]
        print(table[-1], flush=True)
    frame = pd.DataFrame(table)
    lines += ["```", frame.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", "",
              "Wrong-action rate by channel, each draw:", "", "```",
              pd.DataFrame(channels).to_string(float_format=lambda x: f"{x:.4f}"), "```", ""]
    new = frame[frame.draw != "committed"]
    summary = [f"redraws_accuracy_mean={statistics.mean(new.accuracy):.4f}",
               f"redraws_wrong_action_rate_mean={statistics.mean(new.wrong_action_rate):.4f}",
               f"redraws_wrong_action_rate_max={max(new.wrong_action_rate):.4f}"]
    lines += [f"Wall time: {time.perf_counter() - started:.0f} s.", "", "## Summary", "", "```", *summary, "```", ""]
    write_results_file(out, lines)
    print("\n".join(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
