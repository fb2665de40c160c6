"""How much of a field figure is the training run? The shipped recipe trained with several seeds, each played on the
hand-written field sets.

The shipped tagger's members are training runs of one recipe (``make default-tagger``, ``DEFAULT_ENSEMBLE_SEEDS``). On 170 or 226 hand-written steps one
instruction is half a point, and two runs of the same recipe on the same corpus can disagree on dozens of them.
This script trains the shipped recipe (``drywall_lab.nlu.field_study.DEFAULT_FIELD_TAGGER``: BiLSTM-CRF with
character features on the field corpus, one torch thread, CPU) with each seed of ``--seeds``, plays ``data/field``
and, where it exists, ``../shared/field`` through the `run` contract with the decision layer (as
``benchmarks/field.py`` does), and writes each seed's accuracy, wrong-action rate and over-refusal rate, with
their mean, smallest and largest, to its results file (default ``benchmarks/results/field_seeds.md``); with the
same seeds' figures on generated splits (``GENERATED``), where the field sets play no part.

A seed's model is trained into ``--models``/seed<N> (default ``build/field_seeds``) unless a trained tagger is
already there; training is bit for bit on the CPU with one thread, so a model found there is the one the command
would train, as long as the field corpus and the recipe are the same: each model's ``recipe.fingerprint`` records
the generator and the recipe (``DEFAULT_FIELD_TAGGER``) it was trained from, and a model from another
generator or recipe (or without the record) stops the script, which asks for it to be deleted and trained again. Up to ``--jobs`` seeds train at once (about 9 min each on the 2-core CPU with two at once).

    python benchmarks/field_seeds.py [--seeds 0 1 2] [--models DIR] [--jobs 2] [--out FILE] [--quick]

``--swa-epochs N`` trains the recipe with another weight averaging (0: none), into its own ``--models`` and
``--out``: what the averaging buys, seed for seed (``benchmarks/results/field_seeds_no_averaging.md``)::

    python benchmarks/field_seeds.py --swa-epochs 0 --models build/field_seeds_no_averaging \
        --out benchmarks/results/field_seeds_no_averaging.md
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from field import field_sets, run_set  # noqa: E402 (benchmarks/field.py: the same play and scores)
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

from drywall_lab.corpus.field_generator import generator_fingerprint  # noqa: E402
from drywall_lab.machine import describe_machine  # noqa: E402
from drywall_lab.nlu import DEFAULT_TAGGER_DIR, load_tagger  # noqa: E402
from drywall_lab.nlu.field_study import DEFAULT_FIELD_TAGGER, split_scores  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results" / "field_seeds.md"
MODELS = ROOT / "build" / "field_seeds"
FIGURES = ("accuracy", "wrong_action_rate", "over_refusal_rate")
#: Generated splits scored too, so that two recipes are also compared where the field sets played no part: the paper
#: corpus's test split (the issue's Acc_inst target) and the field corpus's novel split (held-back families).
GENERATED = ("test", "field-novel")
QUICK = {"train_size": 300, "epochs": 1, "generated": 40, "field_sets": ("data_field",)}


def recipe_with(swa_epochs: int | None) -> dict:
    """The shipped recipe (``DEFAULT_FIELD_TAGGER``), with another weight averaging when ``swa_epochs`` is given."""
    return {**DEFAULT_FIELD_TAGGER, **({} if swa_epochs is None else {"swa_epochs": swa_epochs})}


def train_command(seed: int, out: Path, quick: bool, recipe: dict = DEFAULT_FIELD_TAGGER) -> list[str]:
    """The `train` command of the shipped recipe (the Makefile's `default-tagger`; or ``recipe``) for one seed."""
    command = [sys.executable, "-m", "drywall_lab", "train", "bilstm-crf", "--corpus", recipe["corpus"],
               "--batch-size", str(recipe["batch_size"]), "--epochs", str(QUICK["epochs"] if quick else recipe["epochs"]),
               "--device", "cpu", "--seed", str(seed), "--out", str(out)]
    if recipe["char_features"]:
        command.append("--char-features")
    if recipe["swa_epochs"]:
        command += ["--swa-epochs", str(recipe["swa_epochs"])]
    if quick:
        command += ["--train-size", str(QUICK["train_size"])]
    return command


STAMP = "recipe.fingerprint"


def recipe_fingerprint(quick: bool, recipe: dict = DEFAULT_FIELD_TAGGER) -> str:
    """What a seed model depends on besides its seed: the field corpus generator and the recipe's settings."""
    settings = {key: value for key, value in recipe.items() if key != "seed"}
    return hashlib.sha256(json.dumps([generator_fingerprint(), settings, quick], sort_keys=True).encode()).hexdigest()


def train_missing(seeds: list[int], models: Path, jobs: int, quick: bool,
                  recipe: dict = DEFAULT_FIELD_TAGGER) -> dict[int, str]:
    """Train every seed whose directory holds no tagger yet, ``jobs`` at a time; how each model was had.

    A model found is used only if its ``recipe.fingerprint`` is the generator's and the recipe's now
    (``recipe_fingerprint``); otherwise ``SystemExit`` says which directory to delete."""
    current = recipe_fingerprint(quick, recipe)
    how, queue, running = {}, [], []
    for seed in seeds:
        out = models / f"seed{seed}"
        if (out / "tagger.json").is_file():
            stamp = out / STAMP
            if not stamp.is_file() or stamp.read_text(encoding="utf-8").strip() != current:
                raise SystemExit(f"{out} was trained from another field corpus or recipe than now (its {STAMP} "
                                 f"is {'missing' if not stamp.is_file() else 'different'}): delete it to train it again")
            how[seed] = f"found in {out}"
        else:
            queue.append((seed, out))
    env = dict(os.environ, OMP_NUM_THREADS="1")
    while queue or running:
        while queue and len(running) < max(1, jobs):
            seed, out = queue.pop(0)
            out.parent.mkdir(parents=True, exist_ok=True)
            log = open(out.parent / f"seed{seed}.log", "w", encoding="utf-8")
            running.append((seed, out, log, time.perf_counter(),
                            subprocess.Popen(train_command(seed, out, quick, recipe), cwd=ROOT, env=env, stdout=log,
                                             stderr=subprocess.STDOUT)))
            print(f"training seed {seed} into {out}", flush=True)
        for item in list(running):
            seed, out, log, started, process = item
            if process.poll() is None:
                continue
            log.close()
            running.remove(item)
            if process.returncode != 0:
                raise RuntimeError(f"training seed {seed} failed (exit {process.returncode}); see {log.name}")
            (out / STAMP).write_text(current + "\n", encoding="utf-8")
            how[seed] = f"trained here in {time.perf_counter() - started:.0f} s"
        time.sleep(1)
    return how


def weights_digest(directory: Path) -> str:
    return hashlib.sha256((directory / "weights.safetensors").read_bytes()).hexdigest()


def shipped_digests() -> set[str]:
    """The weights of the shipped tagger's models: each member's, for an ensemble (``CrfEnsembleTagger``)."""
    members = json.loads((DEFAULT_TAGGER_DIR / "tagger.json").read_text(encoding="utf-8")).get("members") or ["."]
    return {weights_digest(DEFAULT_TAGGER_DIR / member) for member in members}


def generated_scores(tagger, limit: int | None = None) -> dict[str, float]:
    """Per generated split (``GENERATED``): the ablation's figures of a split (``field_study.split_scores``)."""
    return {key: value for split in GENERATED for key, value in split_scores(tagger, split, limit).items()}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2], help="the seeds to train (default 0 1 2)")
    parser.add_argument("--models", type=Path, default=MODELS, help=f"where the models go (default {MODELS.relative_to(ROOT)})")
    parser.add_argument("--jobs", type=int, default=2, help="seeds trained at once (default 2)")
    parser.add_argument("--swa-epochs", type=int, default=None, metavar="N",
                        help=f"the recipe with weights averaged over the last N epochs instead of "
                             f"{DEFAULT_FIELD_TAGGER['swa_epochs']} (0: none); give its own --models and --out")
    add_results_options(parser, RESULTS, "300 instructions and one epoch a seed, data/field only")
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    recipe = recipe_with(args.swa_epochs)
    if recipe != DEFAULT_FIELD_TAGGER and (args.out is None or args.models == MODELS):
        parser.error("--swa-epochs trains another recipe than the shipped one: give it its own --models and --out")
    machine = describe_machine()
    started = time.perf_counter()
    how = train_missing(sorted(set(args.seeds)), args.models, args.jobs, args.quick, recipe)
    shipped = shipped_digests()
    rows = []
    for seed in sorted(how):
        directory = args.models / f"seed{seed}"
        tagger = load_tagger(directory)
        row = {"seed": seed, "n_train": tagger.training_info.get("n_train_instructions"),
               "epochs": tagger.training_info.get("epochs"), "shipped": weights_digest(directory) in shipped}
        for name, field_dir in field_sets().items():
            if args.quick and name not in QUICK["field_sets"]:
                continue  # a quick check plays the project's own set only
            scores = run_set(field_dir, tagger)[1].loc["ALL"]
            row.update({f"{name} {figure}": float(scores[figure]) for figure in FIGURES})
        row.update(generated_scores(tagger, QUICK["generated"] if args.quick else None))
        rows.append(row)
        print(json.dumps(row), flush=True)
    table = pd.DataFrame(rows).set_index("seed")
    figures = [c for c in table.columns if c.split(" ")[-1] in FIGURES]
    generated = [c for c in table.columns if c.split(" ")[0] in GENERATED]
    spread = table[figures].agg(["mean", "min", "max"])
    generated_spread = table[generated].agg(["mean", "min", "max"])
    command = command_line("field_seeds.py", (argv if argv is not None else sys.argv[1:]))
    summary = [f"{column.replace(' ', '_')}_{stat}={spread.loc[stat, column]:.4f}"
               for column in figures if not column.endswith("over_refusal_rate") for stat in ("mean", "min", "max")]
    what = "The shipped recipe" if recipe == DEFAULT_FIELD_TAGGER else f"The shipped recipe with swa_epochs={recipe['swa_epochs']}"
    lines = [f"# {what}, seed by seed, on the field sets (`benchmarks/field_seeds.py`)", "",
             f"**Command:** `{command}`", "", *machine.markdown_lines(),
             f"- wall time: {(time.perf_counter() - started) / 60:.1f} min", "",
             "The models: " + "; ".join(f"seed {seed}: {text}" for seed, text in sorted(how.items())) + ". `shipped`: "
             "the model's weights are those of the shipped tagger or of one of its members, byte for byte. Each figure is a share of the steps, played "
             "episode by episode as `run` plays them, with the decision layer's default settings.", "",
             "```", table[["n_train", "epochs", "shipped"]].T.to_string(), "",
             pd.concat([table[figures].T.add_prefix("seed "), spread.T], axis=1).to_string(float_format=lambda x: f"{x:.4f}"),
             "```", "",
             "On generated splits, where the field sets play no part (`acc_task`: the best reading through the IM rules; "
             "`decided`, `wrong`: through the decision layer, "
             "each instruction in its intended context, as `evaluate` scores it):", "", "```",
             pd.concat([table[generated].T.add_prefix("seed "), generated_spread.T], axis=1)
             .to_string(float_format=lambda x: f"{x:.4f}"),
             "```", "", "## Summary", "", "```", *summary, "```", ""]
    write_results_file(out, lines)
    print("\n".join(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
