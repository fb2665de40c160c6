"""How the study's BERT settings were chosen: MiniLM fine-tuned at several learning rates.

The paper fine-tuned bert-base-uncased (12 layers, 110 M parameters) at 3e-5 for 5 epochs. The
project's offline default encoder is MiniLM-L6-H384 (6 layers, 22 M parameters), which that recipe
leaves under-trained (test Acc_inst 0.74 after 5 epochs at 3e-5; see notebook 03). This script
fine-tunes a ``BertTagger`` (the default MiniLM, batch 16, dropout 0.1, seed 0, linear decay after a
warm-up) for each grid point and prints, per point, the validation Acc_inst after every epoch and,
for the full training split, the test Acc_inst. ``python -m drywall_lab experiment paper`` uses the
chosen point (``ExperimentSettings``).

Run from the repository root: ``python benchmarks/bert_settings.py [--sizes 316 1268]
[--learning-rates 1e-4 2e-4 3e-4] [--epochs 10] [--warmup-ratio 0.1]``; one JSON line per grid point.
Each point at 1,268 instructions takes about 5 min on 2 CPU cores. Results with the machine:
``benchmarks/results/bert_settings.md``.
"""
from __future__ import annotations

import argparse
import json
import time

from drywall_lab.corpus import read_split
from drywall_lab.nlu.bert import BertTagger
from drywall_lab.nlu.metrics import score_tagging


def run_point(train: list[dict], validation: list[dict], test: list[dict], *, size: int, learning_rate: float,
              epochs: int, warmup_ratio: float) -> dict:
    """Fine-tune once and return the validation curve (and test Acc_inst for the full split)."""
    tagger = BertTagger(learning_rate=learning_rate, epochs=epochs, warmup_ratio=warmup_ratio)
    started = time.perf_counter()
    history = tagger.fit(train[:size], validation, progress=False, seed=0)
    result = {"train_size": size, "learning_rate": learning_rate, "epochs": epochs, "warmup_ratio": warmup_ratio,
              "seconds": round(time.perf_counter() - started),
              "val_acc_inst_by_epoch": [round(float(v), 3) for v in history["val_acc_inst"]]}
    if size == len(train):
        predicted = tagger.predict([r["words"] for r in test])
        result["test_acc_inst"] = round(score_tagging(tagger.gold_tags(test), predicted).acc_inst, 4)
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[316, 1268])
    parser.add_argument("--learning-rates", type=float, nargs="+", default=[1e-4, 2e-4, 3e-4])
    parser.add_argument("--epochs", type=int, default=10)
    parser.add_argument("--warmup-ratio", type=float, default=0.1)
    args = parser.parse_args()
    train, validation, test = (read_split(s) for s in ("train", "validation", "test"))
    for size in args.sizes:
        for lr in args.learning_rates:
            print(json.dumps(run_point(train, validation, test, size=size, learning_rate=lr, epochs=args.epochs,
                                       warmup_ratio=args.warmup_ratio)), flush=True)


if __name__ == "__main__":
    main()
