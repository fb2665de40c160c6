"""From the corpus to the field: the ablation of issue 11 (``python -m drywall_lab experiment field``).

Six taggers, each trained once with one seed (``STUDY_SEED``): the BiLSTM-CRF without and with character features
and the MiniLM tagger, each trained on the paper corpus (1,268 instructions) and on the field
corpus (20,000). Each is scored on

- the paper corpus's test and novel splits and the field corpus's test and novel splits: Acc_inst and
  acc_task (its tags through the IM rules) and, through the decision layer, the share decided right and
  the wrong-action rate;
- the hand-written field sets, end to end as the ``run`` contract plays them (episode by episode, the
  history made by the pipeline's own decisions): ``data/field`` and, where it exists beside the checkout,
  ``../shared/field`` (a measuring stick: scored, never read for anything else). Accuracy and wrong-action
  rate with the single best reading (the paper's pipeline) and with the decision layer.

Everything is written to ``out_dir`` (``ablation.csv``, ``README.md`` with the machine, the wall time and
the settings); the shipped default tagger's members are trained with ``DEFAULT_FIELD_TAGGER``. Each model's row is also kept
in ``rows/<model>.json`` with a fingerprint of what it depends on (the corpus generator, the training corpora,
the study's and the decision layer's settings, the field sets), so that the six models can be trained in
separate runs, even at the same time (``--models``), and the table is put together from the rows whose
fingerprint is current; a row left from an older corpus or setting is never shown. The trained models are kept
too (``--keep-models``, by default ``build/field_study``) with a fingerprint of what their training depends on,
so that a change that only touches scoring (the decision layer's thresholds, a field set) re-scores the rows
without training them again.
"""
from __future__ import annotations

import hashlib
import json
import re
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import pandas as pd

from drywall_lab.machine import describe_machine, format_load, load_average
from drywall_lab.nlu.base import Tagger

#: The recipe of the shipped default tagger's members: a BiLSTM-CRF with character features, trained on the field
#: corpus, its weights averaged over the last 3 epochs (``make default-tagger`` trains each member with these settings,
#: ``benchmarks/field_seeds.py`` one model for each seed it is given).
DEFAULT_FIELD_TAGGER = {"corpus": "field", "char_features": True, "batch_size": 32, "epochs": 8, "swa_epochs": 3}
#: The shipped default tagger is the ensemble (``CrfEnsembleTagger``: their CRF scores averaged) of the recipe's seed
#: models with these seeds: of the ensembles of two or more of the three seed models, the one that
#: keeps the paper's test split at the issue's Acc_inst (99.4% or more) with the least decision cost on the generated
#: field validation and novel splits and the paper's novel split (``benchmarks/results/ensemble.md``, ``chosen=``;
#: tested), never chosen on the hand-written sets.
DEFAULT_ENSEMBLE_SEEDS = (0, 1)
#: The ablation trains each of its models once, with this seed (a member of the shipped ensemble).
STUDY_SEED = 1
SHARED_FIELD = Path(__file__).resolve().parents[2].parent / "shared" / "field"
EVALUATION = ("test", "novel", "field-test", "field-novel")


@dataclass
class FieldStudySettings:
    """What to train: ``fast()`` is a quick check (small data, one or two epochs), ``full()`` the study.

    ``evaluation_size``: the rows of each generated split and the episodes of each hand-written set scored (their
    first ones; None: all of them)."""

    lstm_epochs: dict[str, int] = field(default_factory=lambda: {"paper": 20, "field": 8})
    bert_epochs: dict[str, int] = field(default_factory=lambda: {"paper": 10, "field": 2})
    train_sizes: dict[str, int | None] = field(default_factory=lambda: {"paper": None, "field": None})
    evaluation_size: int | None = None
    seed: int = STUDY_SEED

    @classmethod
    def full(cls) -> "FieldStudySettings":
        return cls()

    @classmethod
    def fast(cls) -> "FieldStudySettings":
        return cls(lstm_epochs={"paper": 2, "field": 1}, bert_epochs={"paper": 1, "field": 1},
                   train_sizes={"paper": 200, "field": 400}, evaluation_size=60)


def study_taggers(settings: FieldStudySettings) -> list[tuple[str, str, str, Tagger]]:
    """(name, corpus, kind, untrained tagger) for the six models of the ablation."""
    from drywall_lab.nlu.bert import BertTagger
    from drywall_lab.nlu.bilstm_crf import CHAR_FEATURES, BiLstmCrfTagger
    from drywall_lab.nlu.experiments import MINILM_LEARNING_RATE, MINILM_WARMUP_RATIO

    out = []
    for corpus in ("paper", "field"):
        # On the field corpus, the shipped recipe's training (batch size, weight averaging); on the paper's, the paper's.
        batch = ({"batch_size": DEFAULT_FIELD_TAGGER["batch_size"], "swa_epochs": DEFAULT_FIELD_TAGGER["swa_epochs"]}
                 if corpus == "field" else {})
        out.append((f"LSTM {corpus}", corpus, "bilstm-crf",
                    BiLstmCrfTagger(epochs=settings.lstm_epochs[corpus], **batch)))
        out.append((f"LSTM+char {corpus}", corpus, "bilstm-crf",
                    BiLstmCrfTagger(epochs=settings.lstm_epochs[corpus], **CHAR_FEATURES, **batch)))
        out.append((f"MiniLM {corpus}", corpus, "bert",
                    BertTagger(epochs=settings.bert_epochs[corpus], learning_rate=MINILM_LEARNING_RATE,
                               warmup_ratio=MINILM_WARMUP_RATIO)))
    return out


def split_scores(tagger: Tagger, split: str, limit: int | None = None) -> dict[str, float]:
    """One generated split (its first ``limit`` rows): Acc_inst, acc_task (the best reading through the IM rules)
    and, through the decision layer (each instruction in its intended context, as ``evaluate`` scores it), the share
    decided right and the wrong-action rate, keyed ``"<split> <figure>"``."""
    from drywall_lab.decision import DEFAULT_SETTINGS, decide_rows, decision_scores
    from drywall_lab.im import task_accuracy
    from drywall_lab.nlu.metrics import score_tagging
    from drywall_lab.splits import split_rows

    rows = split_rows(split)[:limit]
    predicted = tagger.predict([r["words"] for r in rows])
    decided = decision_scores(rows, decide_rows(rows, tagger, DEFAULT_SETTINGS))
    return {f"{split} acc_inst": score_tagging(tagger.gold_tags(rows), predicted).acc_inst,
            f"{split} acc_task": task_accuracy(rows, predicted),
            f"{split} decided": decided["accuracy"], f"{split} wrong": decided["wrong_action_rate"]}


def score_tagger(tagger: Tagger, settings: FieldStudySettings) -> dict:
    """Every figure of one row of the ablation table (module docstring)."""
    from drywall_lab.decision import BEST_PATH, DEFAULT_SETTINGS
    from drywall_lab.field import read_field_set, score_run
    from drywall_lab.pipeline import run_episodes

    row: dict = {}
    for split in EVALUATION:
        row.update(split_scores(tagger, split, settings.evaluation_size))
    sets = {"data/field": (None, True)}
    if (SHARED_FIELD / "instructions.jsonl").is_file():
        sets["shared/field"] = (SHARED_FIELD, False)
    for name, (directory, tagged) in sets.items():
        field_set = read_field_set(directory, tagged=tagged) if directory else read_field_set()
        episodes = field_set.episodes[:settings.evaluation_size]
        kept = {str(e["id"]) for e in episodes}
        gold = [g for g in field_set.gold if str(g["episode"]) in kept]
        for mode, decision in (("best", BEST_PATH), ("decided", DEFAULT_SETTINGS)):
            scores = score_run(run_episodes(episodes, tagger, settings=decision), gold).loc["ALL"]
            row[f"{name} {mode}"] = scores["accuracy"]
            row[f"{name} {mode} wrong"] = scores["wrong_action_rate"]
    return row


def training_fingerprint(settings: FieldStudySettings) -> str:
    """A hash of what a model of the ablation depends on besides the code of the taggers: the field corpus
    generator, the training corpora, the study's settings and the shipped recipe."""
    from drywall_lab.corpus.field_generator import generator_fingerprint
    from drywall_lab.splits import CORPORA

    return hashlib.sha256(json.dumps([generator_fingerprint(), CORPORA, repr(settings), DEFAULT_FIELD_TAGGER],
                                     sort_keys=True, default=str).encode()).hexdigest()


def study_fingerprint(settings: FieldStudySettings) -> str:
    """A hash of what a row of the ablation depends on besides the code of the taggers and the IM: what its model
    depends on (``training_fingerprint``), the decision layer's defaults and the field sets."""
    from drywall_lab.decision import DEFAULT_SETTINGS
    from drywall_lab.field import FIELD_DIR

    digest = hashlib.sha256(json.dumps([training_fingerprint(settings), asdict(DEFAULT_SETTINGS)],
                                       sort_keys=True, default=str).encode())
    for directory in (FIELD_DIR, SHARED_FIELD):
        for name in ("instructions.jsonl", "gold.jsonl"):
            if (directory / name).is_file():
                digest.update(name.encode() + b"\0" + (directory / name).read_bytes())
    return digest.hexdigest()


def _slug(name: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")


def _row_path(out: Path, name: str) -> Path:
    return out / "rows" / (_slug(name) + ".json")


MODEL_STAMP = "study.fingerprint"  #: in a kept model's directory: the training fingerprint it was trained under


def trained_model(tagger: Tagger, train: list[dict], validation: list[dict], seed: int, kept: Path | None,
                  fingerprint: str) -> tuple[Tagger, bool]:
    """The tagger trained on ``train``, or the model kept in ``kept`` when it was trained under ``fingerprint``
    (``training_fingerprint``); a model trained here is kept there. Returns the tagger and whether it was loaded."""
    from drywall_lab.nlu.base import load_tagger

    stamp = kept / MODEL_STAMP if kept is not None else None
    if stamp is not None and stamp.is_file() and stamp.read_text(encoding="utf-8").strip() == fingerprint:
        return load_tagger(kept), True
    tagger.fit(train, validation, seed=seed, progress=False)
    if kept is not None:
        if stamp.is_file():
            stamp.unlink()  # never a stamp beside weights it does not describe, even if saving fails half way
        tagger.save(kept)
        stamp.write_text(fingerprint + "\n", encoding="utf-8")
    return tagger, False


def run_field_study(out_dir: Path | str, settings: FieldStudySettings | None = None,
                    models: list[str] | None = None, keep_models: Path | str | None = None) -> pd.DataFrame:
    """Train and score the taggers named in ``models`` (default: all six, ``study_taggers``), keep each row in
    ``rows/``, and write ``ablation.csv`` and ``README.md`` to ``out_dir`` from every row whose fingerprint is
    current (the models not run yet are named in the README). With ``keep_models``, each trained model is kept in
    a folder of it, and a model kept there under the current ``training_fingerprint`` is scored without training
    it again. Returns the table."""
    from drywall_lab.splits import CORPORA, split_rows, training_rows

    settings = settings or FieldStudySettings.full()
    study = study_taggers(settings)
    names = [name for name, *_ in study]
    unknown = sorted(set(models or []) - set(names))
    if unknown:
        raise ValueError(f"unknown model(s) {', '.join(unknown)}; the study's models are: {', '.join(names)}")
    out = Path(out_dir)
    (out / "rows").mkdir(parents=True, exist_ok=True)
    fingerprint, trained_under = study_fingerprint(settings), training_fingerprint(settings)
    machine = describe_machine()
    started = time.perf_counter()
    for name, corpus, kind, tagger in study:
        if models is not None and name not in models:
            continue
        validation_split = CORPORA[corpus][1]
        train = training_rows(corpus)[: settings.train_sizes[corpus]]
        validation = split_rows(validation_split)[: settings.evaluation_size]
        kept = Path(keep_models) / _slug(name) if keep_models is not None else None
        tagger, loaded = trained_model(tagger, train, validation, settings.seed, kept, trained_under)
        print(f"{name}: {'the model kept in ' + str(kept) if loaded else 'trained'}", flush=True)
        row = {"model": name, "kind": kind, "corpus": corpus, "n_train": len(train),
               "epochs": tagger.training_info.get("epochs"), "train_seconds": tagger.training_info.get("wall_seconds")}
        row.update(score_tagger(tagger, settings))
        _row_path(out, name).write_text(json.dumps({"fingerprint": fingerprint, "machine": machine.markdown_lines(),
                                                    "row": row}, indent=1) + "\n", encoding="utf-8")
        print(json.dumps({k: (round(v, 4) if isinstance(v, float) else v) for k, v in row.items()}), flush=True)
    wall = time.perf_counter() - started
    return write_ablation(out, names, settings, fingerprint, wall)


def write_ablation(out: Path, names: list[str], settings: FieldStudySettings, fingerprint: str,
                   wall: float) -> pd.DataFrame:
    """``ablation.csv`` and ``README.md`` from the current rows in ``out/rows``, in the order of ``names``."""
    rows, missing, machines = [], [], []
    for name in names:
        path = _row_path(out, name)
        kept = json.loads(path.read_text(encoding="utf-8")) if path.is_file() else None
        if kept is None or kept.get("fingerprint") != fingerprint:
            missing.append(name)
            continue
        rows.append(kept["row"])
        machines.append(tuple(line for line in kept["machine"] if not line.startswith(("- load", "- date"))))
    table = pd.DataFrame(rows)
    table.to_csv(out / "ablation.csv", index=False)
    machine = describe_machine()
    lines = ["# From the corpus to the field: the ablation (`python -m drywall_lab experiment field`)", "",
             *machine.markdown_lines(), f"- load at the end: {format_load(load_average())}",
             f"- wall time: {wall / 60:.1f} min (this run); training time of every model: "
             f"{table['train_seconds'].sum() / 60 if len(table) else 0:.1f} min",
             f"- settings: `{settings}`", ""]
    if len(set(machines)) > 1:
        lines += ["The rows were not all measured on the same machine: see `rows/*.json`.", ""]
    if missing:
        lines += [f"Not run yet with the current corpus and settings: {', '.join(missing)} "
                  f"(`python -m drywall_lab experiment field --models ...`).", ""]
    lines += ["Each figure is a share of the instructions (steps). `acc_inst`: every tag right; `acc_task`: the "
              "best reading's command or refusal is the intended one; `decided`: right through the decision layer "
              "(a question counts as a refusal); `wrong`: the robot acted, not as intended. The field sets are "
              "played episode by episode as `run` plays them, with the single best reading (`best`) and with the "
              "decision layer (`decided`).", ""]
    if len(table):
        lines += ["```", table.drop(columns=["kind"]).set_index("model").T.to_string(float_format=lambda x: f"{x:.3f}"),
                  "```", ""]
    (out / "README.md").write_text("\n".join(lines), encoding="utf-8")
    return table


def read_ablation(study_dir: Path | str | None = None) -> tuple[pd.DataFrame | None, str]:
    """The ablation table as ``experiment field`` wrote it (one row a model), and a sentence saying where it
    comes from; ``None`` and a "not run yet" sentence when the study has not been run."""
    study_dir = Path(study_dir) if study_dir is not None else Path(__file__).resolve().parents[2] / "results" / "field"
    path = study_dir / "ablation.csv"
    if not path.is_file():
        return None, f"The ablation has not been run yet ({path} is missing): `python -m drywall_lab experiment field`."
    table = pd.read_csv(path).set_index("model")
    readme = study_dir / "README.md"
    wall = next((line for line in readme.read_text(encoding="utf-8").splitlines() if "wall time" in line), "") \
        if readme.is_file() else ""
    note = f"{path.relative_to(study_dir.parent.parent)}: {len(table)} models{(', ' + wall.strip('- ')) if wall else ''}."
    stale = stale_rows(study_dir)
    if stale:
        note += (f" Out of date: the rows of {', '.join(stale)} were made with another field corpus or other settings "
                 "than the current ones (`python -m drywall_lab experiment field` runs them again).")
    return table, note


def stale_rows(study_dir: Path, settings: FieldStudySettings | None = None) -> list[str]:
    """The models whose kept row (``rows/*.json``) has another fingerprint than ``study_fingerprint(settings)``
    (the full study by default): the table shows them, but they no longer describe the current corpus or settings."""
    current = study_fingerprint(settings or FieldStudySettings.full())
    stale = []
    for path in sorted((Path(study_dir) / "rows").glob("*.json")):
        kept = json.loads(path.read_text(encoding="utf-8"))
        if kept.get("fingerprint") != current:
            stale.append(kept.get("row", {}).get("model", path.stem))
    return stale
