"""A second opinion on confident mistakes: does a differently built tagger catch the shipped tagger's wrong actions?

On hand-written language the shipped BiLSTM-CRF is sometimes confidently wrong, and its own probabilities do
not catch it (issue 12). ``drywall_lab.decision.second_opinion`` lets a second tagger veto an action: when the
decision layer would act and the second tagger's best reading, through the same IM rules and history, gives
another command (rule ``command``) or any other outcome (rule ``any``), the robot asks instead. This script
measures the rule with a given second tagger (``--check DIR``, a saved tagger), in two parts:

1. **the choice**, on the generated field corpus's validation and novel splits only (their episodes played in
   order, as ``benchmarks/decision.py`` plays them), with ``benchmarks/decision.py``'s cost: ``WRONG_ACTION_COST`` x wrong-action rate +
   over-refusal rate, averaged over the two splits; ``none`` (no check) wins ties;
2. **the measurement** of every rule on the hand-written field sets (``data/field`` and, where it exists,
   ``../shared/field`` with its own ``score.py``), played episode by episode as ``run`` plays them.

It writes its results file (default ``benchmarks/results/second_opinion.md``) with the machine, the date, the
command and both taggers. The check tagger used for the recorded results is the ablation's "MiniLM field"
(MiniLM fine-tuned on the field corpus, seed 1; 36 min on the 2-core CPU beside another job; its 91 MB of weights
are not in the repository), which ``experiment field`` keeps in ``build/field_study/minilm-field``:

    python -m drywall_lab experiment field --out results/field --models "MiniLM field"
    python benchmarks/second_opinion.py --check build/field_study/minilm-field [--tagger DIR] [--out FILE] [--quick]

(``python -m drywall_lab train bert --corpus field --epochs 2 --learning-rate 3e-4 --warmup-ratio 0.1 --seed 1
--out DIR`` trains the same kind of check on its own.)
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from decision import SPLITS, WRONG_ACTION_COST, Readings, cost  # noqa: E402 (benchmarks/decision.py: the same rule)
from field import describe_tagger, field_sets, run_set, shared_score  # noqa: E402 (benchmarks/field.py)
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

from drywall_lab.decision import DEFAULT_SETTINGS, decision_scores  # noqa: E402
from drywall_lab.machine import describe_machine  # noqa: E402
from drywall_lab.nlu import load_tagger  # noqa: E402
from drywall_lab.pipeline import load_tagger_option  # noqa: E402
from drywall_lab.splits import split_rows  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results" / "second_opinion.md"
#: rule name -> second_opinion's any_difference (None: no check)
RULES = {"none": None, "command": False, "any": True}


def split_decisions(rows: list[dict], tagger, check) -> dict[str, list]:
    """Each rule's decisions on corpus rows, the split's episodes played in order as ``run`` plays them
    (``benchmarks/decision.py``'s ``Readings``: each step against the commands the pipeline acted on before it)."""
    readings = Readings(rows, tagger, DEFAULT_SETTINGS.k)
    check_tags = check.predict([list(r["words"]) for r in rows])
    return {rule: readings.decide(DEFAULT_SETTINGS, None if any_difference is None else check_tags, bool(any_difference))
            for rule, any_difference in RULES.items()}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", required=True, help="the second tagger's saved directory")
    parser.add_argument("--tagger", default=None, help="the first tagger (default: the shipped one)")
    add_results_options(parser, RESULTS, "100 instructions a split")
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    machine = describe_machine()
    started = time.perf_counter()
    tagger, check = load_tagger_option(args.tagger), load_tagger(args.check)
    command = command_line("second_opinion.py", (argv if argv is not None else sys.argv[1:]))
    lines = ["# A second opinion on confident mistakes (`benchmarks/second_opinion.py`)", "",
             f"**Command:** `{command}`", "", f"**Tagger:** {describe_tagger(args.tagger, tagger)}", "",
             f"**Check:** {describe_tagger(args.check, check)}", "", *machine.markdown_lines(), ""]

    choice = []
    for split in SPLITS:
        rows = split_rows(split)[:100] if args.quick else split_rows(split)
        for rule, decisions in split_decisions(rows, tagger, check).items():
            scores = decision_scores(rows, decisions)
            choice.append({"rule": rule, "split": split, "n": len(rows), **scores, "cost": cost(scores)})
    choice_table = pd.DataFrame(choice)
    mean_cost = choice_table.groupby("rule", sort=False)["cost"].mean()
    chosen = mean_cost.idxmin()  # the first of equal costs: "none" comes first
    lines += [f"## The choice, on the generated splits ({', '.join(SPLITS)})", "",
              f"Cost: {WRONG_ACTION_COST} x wrong-action rate + over-refusal rate, mean over the splits.", "", "```",
              choice_table.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", "",
              "```", *(f"mean cost {rule}: {c:.4f}" for rule, c in mean_cost.items()), f"chosen={chosen}", "```", ""]
    print(choice_table.to_string(index=False, float_format=lambda x: f"{x:.4f}"))
    print(f"chosen={chosen}")

    measured, summary = [], []
    for name, directory in field_sets().items():
        for rule, any_difference in RULES.items():
            records, scores, _ = run_set(directory, tagger, None if any_difference is None else check,
                                         bool(any_difference))
            row = scores.loc["ALL"]
            measured.append({"set": name, "rule": rule, "steps": int(row["n"]), "accuracy": row["accuracy"],
                             "wrong_action_rate": row["wrong_action_rate"], "over_refusal_rate": row["over_refusal_rate"]})
            if name == "shared_field":
                report = shared_score(records).rstrip().splitlines()
                lines += [f"`score.py` on shared_field, rule {rule}: " + " ".join(report[-2:]), ""]
            if rule == chosen or rule == "none":
                summary.append(f"{name}_{rule}_accuracy={row['accuracy']:.4f} "
                               f"{name}_{rule}_wrong_action_rate={row['wrong_action_rate']:.4f}")
    measured_table = pd.DataFrame(measured)
    lines += ["## Measured on the hand-written field sets (never used for the choice)", "", "```",
              measured_table.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", "",
              "## Summary", "", "```", f"chosen={chosen}", *summary, "```", "",
              f"{time.perf_counter() - started:.0f} s in all.", ""]
    write_results_file(out, lines)
    print(measured_table.to_string(index=False, float_format=lambda x: f"{x:.4f}"))
    print("\n".join(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
