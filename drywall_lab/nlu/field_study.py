"""From the corpus to the field: the ablation of issue 11 (``python -m drywall_lab experiment field``).

Six taggers, each trained once with seed 0: the BiLSTM-CRF without and with character features
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
the settings); the shipped default tagger's settings are ``DEFAULT_FIELD_TAGGER``.
"""
from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from drywall_lab.machine import describe_machine, format_load, load_average
from drywall_lab.nlu.base import Tagger

#: The shipped default tagger: a BiLSTM-CRF with character features, trained on the field corpus
#: (``make default-tagger`` trains it with these settings).
DEFAULT_FIELD_TAGGER = {"corpus": "field", "char_features": True, "batch_size": 32, "epochs": 8}
SHARED_FIELD = Path(__file__).resolve().parents[2].parent / "shared" / "field"
EVALUATION = ("test", "novel", "field-test", "field-novel")


@dataclass
class FieldStudySettings:
    """What to train: ``fast()`` is a quick check (small data, one or two epochs), ``full()`` the study."""

    lstm_epochs: dict[str, int] = field(default_factory=lambda: {"paper": 20, "field": 8})
    bert_epochs: dict[str, int] = field(default_factory=lambda: {"paper": 10, "field": 2})
    train_sizes: dict[str, int | None] = field(default_factory=lambda: {"paper": None, "field": None})
    evaluation_size: int | None = None
    seed: int = 0

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
        batch = {"batch_size": DEFAULT_FIELD_TAGGER["batch_size"]} if corpus == "field" else {}
        out.append((f"LSTM {corpus}", corpus, "bilstm-crf",
                    BiLstmCrfTagger(epochs=settings.lstm_epochs[corpus], **batch)))
        out.append((f"LSTM+char {corpus}", corpus, "bilstm-crf",
                    BiLstmCrfTagger(epochs=settings.lstm_epochs[corpus], **CHAR_FEATURES, **batch)))
        out.append((f"MiniLM {corpus}", corpus, "bert",
                    BertTagger(epochs=settings.bert_epochs[corpus], learning_rate=MINILM_LEARNING_RATE,
                               warmup_ratio=MINILM_WARMUP_RATIO)))
    return out


def score_tagger(tagger: Tagger, settings: FieldStudySettings) -> dict:
    """Every figure of one row of the ablation table (module docstring)."""
    from drywall_lab.decision import BEST_PATH, DEFAULT_SETTINGS, decide_rows, decision_scores
    from drywall_lab.field import read_field_set, score_run
    from drywall_lab.im import task_accuracy
    from drywall_lab.nlu.metrics import score_tagging
    from drywall_lab.pipeline import run_episodes
    from drywall_lab.splits import split_rows

    row: dict = {}
    for split in EVALUATION:
        rows = split_rows(split)[: settings.evaluation_size]
        predicted = tagger.predict([r["words"] for r in rows])
        decided = decision_scores(rows, decide_rows(rows, tagger, DEFAULT_SETTINGS))
        row.update({f"{split} acc_inst": score_tagging(tagger.gold_tags(rows), predicted).acc_inst,
                    f"{split} acc_task": task_accuracy(rows, predicted),
                    f"{split} decided": decided["accuracy"], f"{split} wrong": decided["wrong_action_rate"]})
    sets = {"data/field": (None, True)}
    if (SHARED_FIELD / "instructions.jsonl").is_file():
        sets["shared/field"] = (SHARED_FIELD, False)
    for name, (directory, tagged) in sets.items():
        field_set = read_field_set(directory, tagged=tagged) if directory else read_field_set()
        for mode, decision in (("best", BEST_PATH), ("decided", DEFAULT_SETTINGS)):
            scores = score_run(run_episodes(field_set.episodes, tagger, settings=decision), field_set).loc["ALL"]
            row[f"{name} {mode}"] = scores["accuracy"]
            row[f"{name} {mode} wrong"] = scores["wrong_action_rate"]
    return row


def run_field_study(out_dir: Path | str, settings: FieldStudySettings | None = None) -> pd.DataFrame:
    """Train and score the six taggers; write ``ablation.csv`` and ``README.md`` to ``out_dir``."""
    from drywall_lab.splits import CORPORA, split_rows, training_rows

    settings = settings or FieldStudySettings.full()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    machine = describe_machine()
    started = time.perf_counter()
    rows = []
    for name, corpus, kind, tagger in study_taggers(settings):
        validation_split = CORPORA[corpus][1]
        train = training_rows(corpus)[: settings.train_sizes[corpus]]
        validation = split_rows(validation_split)[: settings.evaluation_size]
        tagger.fit(train, validation, seed=settings.seed, progress=False)
        row = {"model": name, "kind": kind, "corpus": corpus, "n_train": len(train),
               "epochs": tagger.training_info.get("epochs"), "train_seconds": tagger.training_info.get("wall_seconds")}
        row.update(score_tagger(tagger, settings))
        rows.append(row)
        pd.DataFrame(rows).to_csv(out / "ablation.csv", index=False)  # written as it goes: a long run keeps its rows
        print(json.dumps({k: (round(v, 4) if isinstance(v, float) else v) for k, v in row.items()}), flush=True)
    table = pd.DataFrame(rows)
    wall = time.perf_counter() - started
    lines = ["# From the corpus to the field: the ablation (`python -m drywall_lab experiment field`)", "",
             *machine.markdown_lines(), f"- load at the end: {format_load(load_average())}",
             f"- wall time: {wall / 60:.1f} min", f"- settings: `{settings}`", "",
             "Each figure is a share of the instructions (steps). `acc_inst`: every tag right; `acc_task`: the "
             "best reading's command or refusal is the intended one; `decided`: right through the decision layer "
             "(a question counts as a refusal); `wrong`: the robot acted, not as intended. The field sets are "
             "played episode by episode as `run` plays them, with the single best reading (`best`) and with the "
             "decision layer (`decided`).", "", "```",
             table.drop(columns=["kind"]).set_index("model").T.to_string(float_format=lambda x: f"{x:.3f}"), "```", ""]
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
    return table, f"{path.relative_to(study_dir.parent.parent)}: {len(table)} models{(', ' + wall.strip('- ')) if wall else ''}."
