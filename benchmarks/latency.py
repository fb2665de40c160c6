"""Prediction time per instruction of the NLU taggers (the paper's prediction-time paragraph).

The paper (BERT-M1, bert-base-uncased, a free Google Colab GPU): about 0.025 s per instruction on
average; by number of sentences 0.0224 / 0.0176 / 0.0324 / 0.0606 s for 1 / 2 / 3 / 4 sentences.
This script times, on the test split (158 instructions) and on the CPU:

(a) ``lstm``: the shipped default BiLSTM-CRF (``default_tagger()``);
(b) ``minilm``: a ``BertTagger`` with the default offline MiniLM encoder (6 layers, 384 units).
    Loaded from ``--bert DIR`` when given; otherwise fine-tuned here briefly (1 epoch on 100
    instructions): prediction time does not depend on the values of the weights, only on the
    architecture and the input, so a briefly trained model is timed as fast as a fully trained one;
(c) ``bert_base``: an encoder of the paper's size (``transformers.BertConfig()`` defaults: 12 layers,
    768 hidden units, 12 heads, 110 M parameters) with *random* weights (offline, there is no
    pre-trained bert-base here), put into a ``BertTagger`` in place of the fine-tuned model and
    used with the same uncased WordPiece tokenizer, so it goes through exactly the same
    ``predict`` path: tokenisation, forward pass, argmax, sub-word vote.

Every figure is the wall time of ``tagger.predict(...)`` (``time.perf_counter``), after warm-up:

- *single*: each test instruction alone, ``predict([words])``, repeated ``--repeats`` times
  (once for bert_base); p50 and p95 over all calls, and the mean per sentence-count group;
- *batched*: the whole test split in batches of ``--batch-size``, ``predict(batch)``, repeated
  ``--repeats`` times; each batch's time divided by its size gives a per-instruction time; p50
  and p95 over those.

Run from the repository root: ``python benchmarks/latency.py [--bert DIR]``; the last line reads
``lstm_p50_ms=... minilm_p50_ms=... bert_base_p50_ms=...`` (single-instruction p50).
"""
from __future__ import annotations

import argparse
import os
import platform
import time
from pathlib import Path

import numpy as np
import pandas as pd
import torch

from drywall_lab.corpus import read_split
from drywall_lab.nlu import BertTagger, default_encoder_path, default_tagger, load_tagger
from drywall_lab.nlu.bert import _quiet_transformers

#: Targets of the project's issue: single-instruction p50 on a 2-core CPU.
TARGETS_MS = {"lstm": 2.0, "minilm": 10.0}
PAPER_GROUP_SECONDS = {1: 0.0224, 2: 0.0176, 3: 0.0324, 4: 0.0606}


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def minilm_tagger(directory: str | None, train_rows: list[dict]) -> tuple[BertTagger, str, float | None]:
    """The MiniLM tagger: loaded, or fine-tuned briefly here (returns the training wall seconds)."""
    if directory:
        tagger = load_tagger(directory)
        return tagger, f"loaded from {directory}", tagger.training_info.get("wall_seconds")
    tagger = BertTagger(learning_rate=1e-4)
    tagger.fit(train_rows, epochs=1, progress=False, seed=0)
    info = tagger.training_info
    return tagger, f"fine-tuned here: 1 epoch on {info['n_train_instructions']} instructions", info["wall_seconds"]


def random_bert_base_tagger(labels: list[str]) -> BertTagger:
    """A BertTagger around a randomly initialised bert-base-sized token classifier (BertConfig defaults)."""
    from transformers import AutoTokenizer, BertConfig, BertForTokenClassification

    config = BertConfig(num_labels=len(labels), id2label=dict(enumerate(labels)),
                        label2id={t: i for i, t in enumerate(labels)})
    tagger = BertTagger(labels=labels)
    with _quiet_transformers():
        tagger.tokenizer = AutoTokenizer.from_pretrained(str(default_encoder_path()), local_files_only=True)
    tagger.model = BertForTokenClassification(config).eval()
    return tagger


def time_single(tagger, sentences: list[list[str]], repeats: int, warmup: int = 10) -> np.ndarray:
    """Seconds per ``predict([words])`` call, shape (repeats, len(sentences))."""
    for words in sentences[:warmup]:
        tagger.predict([words])
    out = np.empty((repeats, len(sentences)))
    for r in range(repeats):
        for i, words in enumerate(sentences):
            t0 = time.perf_counter()
            tagger.predict([words])
            out[r, i] = time.perf_counter() - t0
    return out


def time_batched(tagger, sentences: list[list[str]], batch_size: int, repeats: int) -> np.ndarray:
    """Seconds per instruction of each batch (batch time / batch size), over ``repeats`` passes."""
    tagger.predict(sentences[:batch_size], batch_size=batch_size)  # warm-up
    out = []
    for _ in range(repeats):
        for start in range(0, len(sentences), batch_size):
            batch = sentences[start : start + batch_size]
            t0 = time.perf_counter()
            tagger.predict(batch, batch_size=batch_size)
            out.append((time.perf_counter() - t0) / len(batch))
    return np.array(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bert", metavar="DIR", help="a saved MiniLM BertTagger to time (default: fine-tune one briefly)")
    parser.add_argument("--repeats", type=int, default=3, help="passes over the test split (bert_base: 1)")
    parser.add_argument("--batch-size", type=int, default=32)
    parser.add_argument("--train-size", type=int, default=100, help="instructions for the brief MiniLM fine-tuning")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args(argv)

    torch.set_num_threads(args.threads)
    test = read_split("test")
    sentences = [r["words"] for r in test]
    groups = np.array([r["n_sentences"] for r in test])
    started = time.perf_counter()
    print(f"machine: {cpu_model()}, {os.cpu_count()} logical cores, torch {torch.__version__} "
          f"with {torch.get_num_threads()} threads; test split: {len(test)} instructions, "
          f"{sum(map(len, sentences))} words; instructions by sentence count "
          f"{ {int(g): int((groups == g).sum()) for g in sorted(set(groups))} }; "
          f"load average at start {os.getloadavg()[0]:.2f} (other jobs on the machine slow every figure)")

    lstm = default_tagger()
    minilm, minilm_source, minilm_train_s = minilm_tagger(args.bert, read_split("train")[: args.train_size])
    bert_base = random_bert_base_tagger(list(minilm.labels))
    models = {
        "lstm": (lstm, "shipped default BiLSTM-CRF", args.repeats),
        "minilm": (minilm, f"BertTagger, MiniLM encoder ({minilm_source})", args.repeats),
        "bert_base": (bert_base, "BertTagger, bert-base-sized encoder, random weights", 1),
    }

    rows, group_rows = [], []
    for name, (tagger, what, repeats) in models.items():
        single = time_single(tagger, sentences, repeats)
        batched = time_batched(tagger, sentences, args.batch_size, args.repeats)
        rows.append({
            "model": name, "parameters": tagger.n_parameters(),
            "single_p50_ms": 1e3 * np.percentile(single, 50), "single_p95_ms": 1e3 * np.percentile(single, 95),
            "single_mean_ms": 1e3 * single.mean(),
            "batched_p50_ms": 1e3 * np.percentile(batched, 50), "batched_p95_ms": 1e3 * np.percentile(batched, 95),
            "calls": f"{single.size} single, {batched.size} batches", "what": what,
        })
        per_instruction = single.mean(axis=0)
        for g in sorted(set(groups)):
            group_rows.append({"model": name, "sentences": int(g), "instructions": int((groups == g).sum()),
                               "mean_ms": 1e3 * per_instruction[groups == g].mean(),
                               "paper_gpu_ms (bert-base)": 1e3 * PAPER_GROUP_SECONDS.get(int(g), float("nan"))})
        print(f"  timed {name} ({time.perf_counter() - started:.0f} s so far)", flush=True)

    table = pd.DataFrame(rows).set_index("model")
    pd.set_option("display.width", 200)
    pd.set_option("display.max_colwidth", 80)
    print("\nPer-instruction prediction time on the test split (ms; single = one instruction per predict call,"
          f" batched = batches of {args.batch_size}):")
    print(table.drop(columns=["what"]).round(2).to_string())
    for name, row in table.iterrows():
        print(f"  {name}: {row['what']}")
    print("\nMean single-instruction time by number of sentences (ms):")
    print(pd.DataFrame(group_rows).pivot(index="sentences", columns="model", values="mean_ms").round(2)
          .assign(**{"paper, bert-base on a GPU": [1e3 * PAPER_GROUP_SECONDS.get(g, float("nan")) for g in sorted(set(groups))],
                     "instructions": [int((groups == g).sum()) for g in sorted(set(groups))]}).to_string())

    print("\nTraining wall time:")
    info = lstm.training_info
    print(f"  lstm (LSTM-M1, shipped): {info['wall_seconds']:.1f} s for {info['epochs']} epochs on "
          f"{info['n_train_instructions']} instructions (training_info['wall_seconds'] of the default tagger)")
    if minilm_train_s is not None and not args.bert:
        per = minilm_train_s / args.train_size
        print(f"  minilm: {minilm_train_s:.1f} s for 1 epoch on {args.train_size} instructions = {per:.3f} s per "
              f"instruction-epoch; the paper's BERT-M1 (5 epochs on 1,268) would take about {per * 5 * 1268 / 60:.0f} min "
              "at that rate (an extrapolation, not a measurement)")
    elif minilm_train_s is not None:
        print(f"  minilm ({args.bert}): {minilm_train_s:.1f} s (training_info['wall_seconds'])")

    print()
    for name, target in TARGETS_MS.items():
        p50 = table.loc[name, "single_p50_ms"]
        print(f"target {name} single p50 < {target:g} ms: {'met' if p50 < target else 'MISSED'} ({p50:.2f} ms)")
    print(f"total benchmark time: {time.perf_counter() - started:.0f} s; load average at the end {os.getloadavg()[0]:.2f}")
    print(" ".join(f"{name}_p50_ms={table.loc[name, 'single_p50_ms']:.2f}" for name in models))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
