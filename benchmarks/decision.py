"""Choosing the decision layer's thresholds, and its risk against coverage (issue 12; ``drywall_lab.decision``).

The thresholds are chosen on the **generated** field corpus only: its validation split (the families the
tagger was trained on) and its novel split (held-back families), never on the hand-written field sets,
which stay a measuring stick. For every setting of the grid the script plays both splits' episodes as
``run`` plays them (each step against the commands the pipeline itself acted on before it) with every tagger given and counts right outcomes, wrong actions (the
robot acted, not as intended) and over-refusals (a refusal or a question where a command was expected).
The rule:

    cost = WRONG_ACTION_COST x wrong-action rate + over-refusal rate, averaged over the two splits and the
    taggers; the setting of least cost wins; ties go to the more careful setting (higher ``act``, then
    ``recover``).

One training run is one draw (``benchmarks/field_seeds.py``): thresholds chosen for one model fit its
particular mistakes. Given the same recipe trained with several seeds (``--tagger`` once per model), the
script chooses for the recipe, by the mean cost over the models, and records what each model alone would
have chosen, so that the choice can be seen to be stable (or not).

A wrong action moves a 25 kg sheet to the wrong place; a question costs the worker a few seconds, so a
wrong action counts as ``WRONG_ACTION_COST`` questions. The script also writes the risk-coverage curve
of the chosen setting (the ``act`` threshold moved, everything else fixed) and the best-path baseline,
to its results file (default ``benchmarks/results/decision.md``), with the machine, the date and the
command. ``drywall_lab.decision.DEFAULT_SETTINGS`` must equal the recorded choice (a test checks it).

    python benchmarks/decision.py [--tagger DIR ...] [--jobs N] [--out FILE] [--quick]

The choice can be made for the shipped recipe, an ensemble of two seed models (``make default-tagger``), over the
three ensembles of two of the seed models 0-2: ``python benchmarks/field_seeds.py`` (the seed models in
``build/field_seeds``), then, for each pair ``A B`` of 0 1, 0 2 and 1 2, ``python -m drywall_lab ensemble --member
build/field_seeds/seedA --member build/field_seeds/seedB --out build/ensembles/seedA+seedB``, then
``python benchmarks/decision.py --jobs 2 --tagger build/ensembles/seed0+seed1 --tagger build/ensembles/seed0+seed2
--tagger build/ensembles/seed1+seed2`` (about 3 x 10 min on 2 CPU cores). The recorded choice (its command is in the
results file) was made for the shipped ensemble alone, ``--tagger drywall_lab/models/default_tagger`` (10 min).
"""
from __future__ import annotations

import argparse
import itertools
import multiprocessing
import sys
import time
from dataclasses import asdict, replace
from pathlib import Path

import pandas as pd

from drywall_lab.decision import (BEST_PATH, DEFAULT_SETTINGS, DecisionSettings, decision_scores, play_episode,
                                  risk_coverage)
from drywall_lab.im import ActionHistory, interpret
from drywall_lab.machine import describe_machine
from drywall_lab.pipeline import load_tagger_option
from drywall_lab.splits import split_rows

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results" / "decision.md"
SPLITS = ("field-validation", "field-novel")
WRONG_ACTION_COST = 10
GRID = {
    "act": (0.0, 0.3, 0.5, 0.7, 0.8, 0.9, 0.95),
    "recover": (0.05, 0.1, 0.2, 0.4, 1.0),
    "margin": (1.0, 1.5, 2.0, 3.0, 5.0),
    "pending": (True, False),
    "half": ("off", "said"),
    "through": (False, True),
}
#: The columns and order of the sort that ranks the settings: least cost, then the more careful (higher act,
#: lower recover, wider margin, asking about a back-reference after a step not understood, counting
#: half-understood refusals, keeping them open after an action).
SETTINGS = ["act", "recover", "margin", "pending", "half", "through"]
ORDER = [True, False, True, False, False, False, False]
QUICK_GRID = {"act": (0.0, 0.7), "recover": (0.4, 1.0), "margin": (3.0,), "pending": (True, False),
              "half": ("off", "said"), "through": (False, True)}


def grid_settings(grid: dict[str, tuple]) -> list[dict]:
    """The grid's settings, one dict each; ``half`` and ``through`` only refine ``pending`` (step 5), so they
    vary only where it is on. ``half="all"`` is not in the grid: it asks after refusals of instructions that
    said nothing of the missing part ("any sheet"), and with gold tags that changes intended outcomes."""
    out = []
    for values in itertools.product(*(grid[name] for name in SETTINGS)):
        record = dict(zip(SETTINGS, values))
        if not record["pending"] and (record["half"] != "off" or record["through"]):
            continue
        out.append(record)
    return out


class Readings:
    """The tagger's readings of one split, tagged once, and a cache of the IM's interpretations.

    ``decide`` plays the split's episodes as ``run`` plays them: each step is decided against the history of the
    commands the pipeline itself acted on before it in its episode (starting from the episode's own first
    context), so that a refusal or a wrong action early in an episode costs what it costs in the field, where
    "the same stud again" then points at another command. Rows are scored against their intended outcome."""

    def __init__(self, rows: list[dict], tagger, k: int) -> None:
        self.rows = rows
        self.labels = tagger.labels
        self.confidences = tagger.predict_confidence([r["words"] for r in rows], k=k)
        episodes: dict[str, list[int]] = {}
        for i, row in enumerate(rows):
            episodes.setdefault(row["context"]["episode"], []).append(i)
        self.episodes = [sorted(steps, key=lambda i: rows[i]["context"]["step"]) for steps in episodes.values()]
        self._cache: dict[tuple, object] = {}

    def interpret(self, words, tags, history):
        """The IM's ``interpret``, cached on the words, the tags and the commands in the history."""
        key = (tuple(words), tuple(tags), tuple((c.drywall_id, c.stud_id, c.placement.value) for c in history.commands))
        if key not in self._cache:
            self._cache[key] = interpret(words, tags, history)
        return self._cache[key]

    def decide(self, settings: DecisionSettings, checks: list | None = None, any_difference: bool = False) -> list:
        """One decision a row, the episodes played in order; ``checks``: a second tagger's tags, one a row, for
        ``play_episode``'s second opinion (``benchmarks/second_opinion.py``)."""
        out: list = [None] * len(self.rows)
        for steps in self.episodes:
            history = ActionHistory.from_commands(self.rows[steps[0]]["context"]["history"])
            decisions = play_episode([self.rows[i]["words"] for i in steps], [self.confidences[i] for i in steps],
                                     self.labels, history, settings, self.interpret,
                                     None if checks is None else [checks[i] for i in steps], any_difference)
            for i, decision in zip(steps, decisions):
                out[i] = decision
        return out


def cost(scores: dict[str, float]) -> float:
    return WRONG_ACTION_COST * scores["wrong_action_rate"] + scores["over_refusal_rate"]


def _key(settings: DecisionSettings) -> tuple:
    return tuple(getattr(settings, name) for name in SETTINGS)


def _least_cost(table: pd.DataFrame, column: str) -> pd.Series:
    """The row of least ``column``; ties go to the more careful setting (``ORDER``)."""
    return table.sort_values([column, *SETTINGS], ascending=ORDER, kind="stable").iloc[0]


def _settings_of(row: pd.Series) -> DecisionSettings:
    return replace(DEFAULT_SETTINGS, **{name: type(getattr(DEFAULT_SETTINGS, name))(row[name]) for name in SETTINGS})


def _score_setting(readings: dict[str, dict[str, Readings]], record: dict) -> dict:
    """One row of ``choose``'s table: ``record``'s setting scored on every split with every tagger."""
    record = dict(record)
    settings = replace(DEFAULT_SETTINGS, **record)
    per_split: dict[str, list[dict]] = {}
    costs = []
    for name, splits in readings.items():
        own = []
        for split, r in splits.items():
            scores = decision_scores(r.rows, r.decide(settings))
            per_split.setdefault(split, []).append(scores)
            own.append(cost(scores))
        record[f"cost:{name}"] = sum(own) / len(own)
        costs.extend(own)
    for split, scores in per_split.items():
        for k in scores[0]:
            record[f"{split}:{k}"] = sum(s[k] for s in scores) / len(scores)
    record["cost"] = sum(costs) / len(costs)
    return record


def _forked_map(function, items: list, jobs: int) -> list:
    """``[function(x) for x in items]`` in ``jobs`` forked processes, each on a contiguous share of ``items`` (a fork
    shares the parent's readings and caches without copying them through a pipe; only the results come back)."""
    context = multiprocessing.get_context("fork")
    bounds = [len(items) * j // jobs for j in range(jobs + 1)]
    workers = []
    for start, stop in zip(bounds, bounds[1:]):
        receive, send = context.Pipe(duplex=False)
        process = context.Process(target=lambda part=items[start:stop], pipe=send: pipe.send([function(x) for x in part]))
        process.start()
        send.close()
        workers.append((process, receive))
    out = []
    for process, receive in workers:
        try:
            out += receive.recv()
        except EOFError:
            process.join()
            raise RuntimeError(f"a worker process failed (exit code {process.exitcode})") from None
        process.join()
    return out


def choose(readings: dict[str, dict[str, Readings]], grid: dict[str, tuple],
           jobs: int = 1) -> tuple[DecisionSettings, pd.DataFrame]:
    """Every setting of the grid scored on every split with every tagger (``readings[tagger][split]``); the setting
    of least mean cost over them all wins (ties: the more careful). The table has one row a setting: the mean
    rates over the taggers for each split, each tagger's own cost (``cost:<tagger>``) and the mean ``cost``.
    ``jobs`` > 1 scores the settings in that many forked processes (the same table, in the grid's order)."""
    records = grid_settings(grid)
    if jobs > 1:
        rows = _forked_map(lambda record: _score_setting(readings, record), records, jobs)
    else:
        rows = [_score_setting(readings, record) for record in records]
    table = pd.DataFrame(rows)
    return _settings_of(_least_cost(table, "cost")), table


def each_alone(table: pd.DataFrame, names: list[str], chosen: DecisionSettings) -> pd.DataFrame:
    """What each tagger alone would have chosen, its cost there, and its cost at the joint choice."""
    joint = table[(table[SETTINGS] == pd.Series(dict(zip(SETTINGS, _key(chosen))))).all(axis=1)].iloc[0]
    out = []
    for name in names:
        best = _least_cost(table, f"cost:{name}")
        out.append({"tagger": name, "own choice": str(_key(_settings_of(best))), "own cost": best[f"cost:{name}"],
                    "cost at the joint choice": joint[f"cost:{name}"]})
    return pd.DataFrame(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tagger", action="append", default=None,
                        help="a saved tagger's directory; give it once per model to choose for a recipe across "
                             "seeds (default: the shipped tagger alone)")
    parser.add_argument("--jobs", type=int, default=1, help="settings scored in this many processes at once (default 1)")
    add_results_options(parser, RESULTS, "200 instructions a split and a small grid")
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    options = args.tagger or [None]
    names = [option or "the shipped tagger" for option in options]
    if len(set(names)) != len(names):
        parser.error("each --tagger must name a different model")
    machine = describe_machine()
    grid = QUICK_GRID if args.quick else GRID
    started = time.perf_counter()
    readings: dict[str, dict[str, Readings]] = {}
    for name, option in zip(names, options):
        tagger = load_tagger_option(option)
        readings[name] = {s: Readings(split_rows(s)[:200] if args.quick else split_rows(s), tagger, DEFAULT_SETTINGS.k)
                          for s in SPLITS}
    chosen, table = choose(readings, grid, args.jobs)
    first = readings[names[0]]
    lines = ["# Decision layer: thresholds and risk against coverage (`benchmarks/decision.py`)", "",
             f"**Command:** `{command_line('decision.py', (argv if argv is not None else sys.argv[1:]))}`",
             "", f"**Taggers:** {', '.join(names)}", "", *machine.markdown_lines(), "",
             f"Splits: {', '.join(f'{s} ({len(r.rows)} instructions)' for s, r in first.items())}; "
             f"{len(table)} settings; rule: least mean of {WRONG_ACTION_COST} x wrong-action rate + over-refusal "
             f"rate over the splits and the {len(names)} tagger(s), ties to the more careful setting.", "",
             "## Choice", "", "```", f"chosen={asdict(chosen)}", "```", ""]
    if len(names) > 1:
        alone = each_alone(table, names, chosen)
        lines += ["## Each tagger alone", "",
                  f"The setting ({', '.join(SETTINGS)}) of least cost for each tagger on its own, and its cost "
                  "at the joint choice:", "", "```", alone.to_string(index=False, float_format=lambda x: f"{x:.4f}"),
                  "```", ""]
    compare = []
    for label, settings in (("best path (the paper)", BEST_PATH), ("chosen", chosen)):
        for name, splits in readings.items():
            for split, r in splits.items():
                compare.append({"setting": label, "tagger": name, "split": split,
                                **decision_scores(r.rows, r.decide(settings))})
    compare_table = pd.DataFrame(compare)
    if len(names) == 1:
        compare_table = compare_table.drop(columns=["tagger"])
    lines += ["## Best path against the chosen setting", "", "```",
              compare_table.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", ""]
    lines += [f"## Risk against coverage (chosen setting, `act` moved; {names[0]})", ""]
    for split, r in first.items():
        curve = risk_coverage(r.rows, r.decide(replace(chosen, act=0.0)))
        picks = curve.iloc[sorted({int(i) for i in pd.Series(range(len(curve))).quantile([0, .5, .8, .9, .95, .98, 1]).round()})]
        lines += [f"{split}:", "", "```", picks.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", ""]
    best_rows = table.sort_values(["cost", *SETTINGS], ascending=ORDER, kind="stable").head(10)
    lines += ["## The ten settings of least cost", "",
              "Rates: the mean over the taggers; `cost:<tagger>`: each tagger's own cost.", "", "```",
              best_rows.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", "",
              f"{time.perf_counter() - started:.0f} s in all.", ""]
    write_results_file(out, lines)
    print(compare_table.to_string(index=False, float_format=lambda x: f"{x:.4f}"))
    print(f"chosen={asdict(chosen)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
