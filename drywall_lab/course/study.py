"""The project's full NLU study and its benchmarks' records, read for notebooks 02 (BiLSTM-CRF) and 03 (BERT).

The study (``results/paper``, written by ``python -m drywall_lab experiment paper``): :func:`read_study_table`,
:func:`accuracy_by_training_size` (Table 3 against training size), :func:`coref_comparison` (Table 5),
:func:`novel_comparison`, and sentences computed from them (:func:`data_efficiency_finding`,
:func:`novel_finding`, :func:`coref_finding`); the MiniLM learning rate's choice
(:func:`minilm_learning_rate_choice`) and the field benchmark (:func:`field_results`); the spread over seeds
(``seeds.csv``, written by ``python -m drywall_lab experiment seeds``): :func:`seed_spread`, :func:`seed_finding`.
"""
from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path
from typing import TYPE_CHECKING, Mapping, Sequence

import numpy as np
import pandas as pd

from drywall_lab.course.common import BENCHMARK_RESULTS, REPO_ROOT, STUDY_DIR

if TYPE_CHECKING:
    import matplotlib.pyplot as plt


def read_study_table(name: str, study_dir: Path | str = STUDY_DIR) -> pd.DataFrame:
    """One CSV of the study (``table3_validation``, ``table5_coref_validation``, ``novel``, ``m1_on_test``,
    ``training_history``, ``table4_errors_per_tag``, ``seeds``, ...); a ``FileNotFoundError`` saying how to write
    it."""
    path = Path(study_dir) / f"{name}.csv"
    if not path.is_file():
        study = "seeds" if name == "seeds" else "paper"
        raise FileNotFoundError(f"{path} does not exist: the study writes it with "
                                f"`python -m drywall_lab experiment {study} --out {study_dir}`")
    return pd.read_csv(path, index_col=0 if name.startswith("table4") else None)


def study_settings(study_dir: Path | str = STUDY_DIR) -> dict:
    """The settings the study ran with, as its ``README.md`` records them (train sizes, epochs, learning rate)."""
    path = Path(study_dir) / "README.md"
    if not path.is_file():
        raise FileNotFoundError(f"{path} does not exist: run "
                                f"`python -m drywall_lab experiment paper --out {study_dir}`")
    match = re.search(r"Settings: `(\{.*?\})`", path.read_text(encoding="utf-8"))
    if not match:
        raise ValueError(f"{path} does not record the study's settings (no 'Settings: `{{...}}`' line)")
    return json.loads(match.group(1))


def study_provenance(study_dir: Path | str = STUDY_DIR) -> str:
    """The line of the study's README saying where and how long it ran."""
    path = Path(study_dir) / "README.md"
    if not path.is_file():
        raise FileNotFoundError(f"{path} does not exist: run "
                                f"`python -m drywall_lab experiment paper --out {study_dir}`")
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("Machine"):
            return line.split(" Settings:")[0]
    return f"{path} does not say where the study ran"


#: How the notebooks name the study's two taggers.
TAGGER_NAMES = {"LSTM": "BiLSTM-CRF", "BERT": "MiniLM (BERT)"}
#: Their lines in the paper's Table 3 (the paper fine-tuned bert-base-uncased).
PAPER_TAGGER_NAMES = {"BiLSTM-CRF": "BiLSTM-CRF, paper", "MiniLM (BERT)": "bert-base, paper"}


def _model_parts(model: str) -> tuple[str, str, str]:
    """("LSTM", "M", "4") from "LSTM-M4"."""
    match = re.fullmatch(r"(LSTM|BERT)-([MC])(\d+)", model)
    if not match:
        raise ValueError(f"{model!r} is not a study model name like 'LSTM-M4' or 'BERT-C1'")
    return match.group(1), match.group(2), match.group(3)


def study_model(tagger: str, n_train: int, train_sizes: Mapping[str, int]) -> str:
    """The study's model of ``tagger`` ("LSTM" or "BERT") trained on ``n_train`` instructions, e.g. "LSTM-M4" for
    316 (``train_sizes`` as :func:`study_settings` gives them); a ``ValueError`` when the study has no such size."""
    if tagger not in TAGGER_NAMES:
        raise ValueError(f"{tagger!r} is not one of the study's taggers {sorted(TAGGER_NAMES)}")
    for key, n in train_sizes.items():
        if int(n) == n_train:
            return f"{tagger}-M{key}"
    raise ValueError(f"the study trained on {sorted(int(n) for n in train_sizes.values())} instructions, "
                     f"not on {n_train}")


#: Table 3's columns (plus ``acc_task``), as ``drywall_lab.course.table_3`` gives them.
TABLE3_COLUMNS = ["N_w", "Acc_word", "N_l", "Acc_inst", "acc_task"]


def study_rows(name: str, tagger: str, study_dir: Path | str = STUDY_DIR) -> pd.DataFrame:
    """One tagger's rows ("LSTM" or "BERT") of one of the study's per-model CSVs (``table3_validation``,
    ``m1_on_test``, ``novel``), indexed by model, with Table 3's columns (plus ``acc_task``): to set next to a
    demonstration run's ``table_3``."""
    table = read_study_table(name, study_dir)
    return table[table["model"].str.startswith(f"{tagger}-")].set_index("model")[TABLE3_COLUMNS]


def accuracy_by_training_size(table3: pd.DataFrame, train_sizes: Mapping[str, int]) -> pd.DataFrame:
    """Validation Acc_inst of both taggers against the number of training instructions (Table 3 of the study),
    with the paper's figures alongside; one row per training size, largest first."""
    records = []
    for _, r in table3.iterrows():
        kind, _, key = _model_parts(r["model"])
        records.append({"training instructions": int(train_sizes[key]), "tagger": TAGGER_NAMES[kind],
                        "Acc_inst": r["Acc_inst"], "paper": r.get("paper_Acc_inst", np.nan), "N_l": r["N_l"]})
    long = pd.DataFrame(records)
    wide = long.pivot(index="training instructions", columns="tagger", values="Acc_inst")
    paper = long.pivot(index="training instructions", columns="tagger", values="paper")
    paper = paper.rename(columns=PAPER_TAGGER_NAMES)
    wrong = long.pivot(index="training instructions", columns="tagger", values="N_l").add_prefix("N_l ")
    return pd.concat([wide, paper, wrong], axis=1).sort_index(ascending=False)


def plot_accuracy_by_training_size(frame: pd.DataFrame, ax: "plt.Axes | None" = None,
                                   title: str = "validation Acc_inst against training size (Table 3)") -> "plt.Axes":
    """Both taggers' validation Acc_inst against training size: the study solid, the paper dashed."""
    import matplotlib.pyplot as plt

    ax = ax or plt.subplots(figsize=(6, 3.6))[1]
    for i, name in enumerate(TAGGER_NAMES.values()):
        if name in frame:
            ax.plot(frame.index, frame[name], marker="o", color=f"C{i}", label=f"{name}, this study")
        if PAPER_TAGGER_NAMES[name] in frame:
            ax.plot(frame.index, frame[PAPER_TAGGER_NAMES[name]], marker="s", ls="--", color=f"C{i}", alpha=0.6,
                    label=PAPER_TAGGER_NAMES[name])
    ax.set_xticks(list(frame.index))
    ax.set_xlabel("training instructions")
    ax.set_ylabel("Acc_inst")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def _pct(value: float) -> str:
    return f"{value:.2%}"


def data_efficiency_finding(table3: pd.DataFrame, train_sizes: Mapping[str, int], n_validation: int) -> str:
    """Whether the paper's data-efficiency finding holds in the study, in words computed from Table 3.

    The paper: with its fewest training instructions (316, the M4 models), BERT got many more validation
    instructions entirely right than the BiLSTM-CRF. The sentence compares the instructions each gets wrong
    (N_l) at the smallest size in the study and in the paper.
    """
    frame = accuracy_by_training_size(table3, train_sizes)
    n = frame.index.min()
    lstm, bert = TAGGER_NAMES["LSTM"], TAGGER_NAMES["BERT"]
    row = frame.loc[n]
    ours = int(row[f"N_l {lstm}"] - row[f"N_l {bert}"])  # > 0: BERT gets more instructions right
    text = (f"With {n} training instructions the BiLSTM-CRF gets {_pct(row[lstm])} of the {n_validation} validation "
            f"instructions entirely right and MiniLM {_pct(row[bert])}")
    paper_gap = None
    paper_lstm, paper_bert = (row.get(PAPER_TAGGER_NAMES[name]) for name in (lstm, bert))
    if pd.notna(paper_lstm) and pd.notna(paper_bert):
        paper_gap = round((paper_bert - paper_lstm) * n_validation)
        text += f" (the paper, with bert-base: {_pct(paper_lstm)} and {_pct(paper_bert)})"
    text += ". "
    if abs(ours) <= 2:
        text += (f"Here the two are within {abs(ours)} instruction{'s' if abs(ours) != 1 else ''} of each other: "
                 "on this corpus the BiLSTM-CRF learns as much from little data as the pre-trained encoder")
    elif ours > 0:
        text += f"MiniLM gets {ours} more instructions right: pre-training pays off with little data here too"
    else:
        text += (f"The BiLSTM-CRF gets {-ours} more instructions right: on this corpus the paper's finding "
                 "(pre-training pays off most with little data) does not hold")
    if paper_gap is not None:
        text += f", where in the paper BERT was ahead by about {paper_gap} of {n_validation} instructions."
    else:
        text += "."
    return text


def novel_comparison(table3: pd.DataFrame, novel: pd.DataFrame) -> pd.DataFrame:
    """Every model's Acc_inst and acc_task on the validation split against the novel split (withheld phrasings)."""
    validation = table3.set_index("model")[["Acc_inst", "acc_task"]].add_prefix("validation ")
    withheld = novel.set_index("model")[["Acc_word", "Acc_inst", "acc_task"]].add_prefix("novel ")
    return validation.join(withheld, how="inner")


def novel_finding(table3: pd.DataFrame, novel: pd.DataFrame, models: Sequence[str] = ("LSTM-M1", "BERT-M1")) -> str:
    """How far the models trained on all 1,268 instructions fall on the novel split, in words from the CSVs."""
    frame = novel_comparison(table3, novel)
    parts = []
    for model in models:
        if model in frame.index:
            r = frame.loc[model]
            parts.append(f"{model} gets {_pct(r['validation Acc_inst'])} of the validation instructions entirely "
                         f"right and {_pct(r['novel Acc_inst'])} of the novel ones (acc_task "
                         f"{_pct(r['validation acc_task'])} -> {_pct(r['novel acc_task'])})")
    if not parts:
        return "The study has none of the models " + ", ".join(models) + "."
    best = frame.loc[[m for m in models if m in frame.index], "novel Acc_inst"].idxmax()
    return "; ".join(parts) + f". On the novel split {best} is ahead on Acc_inst."


#: The Acc_inst columns of ``seeds.csv`` that :func:`seed_spread` summarises, by split.
SEED_SPLITS = {"validation": "validation_acc_inst", "novel": "novel_acc_inst"}
#: The statistics over the seeds, in :func:`seed_spread`'s column names ("validation mean", "novel sd", ...).
SEED_STATISTICS = {"mean": "mean", "sd": "std", "min": "min", "max": "max"}


def seed_spread(seeds: pd.DataFrame | None = None, study_dir: Path | str = STUDY_DIR) -> pd.DataFrame:
    """How much a model's Acc_inst moves with the random seed alone: one row a model (in the file's order), the
    number of seeds, its training instructions, and the mean, standard deviation (over the seeds, n - 1), min and
    max of its validation and novel Acc_inst. ``seeds`` is ``seeds.csv`` (one row a model and seed), read from
    ``study_dir`` when not given."""
    from drywall_lab.nlu.experiments import seed_summary

    if seeds is None:
        seeds = read_study_table("seeds", study_dir)
    needed = {"model", "seed", "train_instructions", *SEED_SPLITS.values()}
    if missing := needed - set(seeds.columns):
        raise ValueError(f"the seed table lacks the columns {sorted(missing)}")
    if seeds.empty:
        raise ValueError("the seed table has no rows")
    if seeds.duplicated(["model", "seed"]).any():
        raise ValueError("the seed table has a model and seed twice")
    groups = seeds.groupby("model", sort=False)
    if (groups["train_instructions"].nunique() > 1).any():
        raise ValueError("a model of the seed table was trained on different numbers of instructions")
    summary = seed_summary(seeds)
    frame = pd.DataFrame({"seeds": summary[("seeds", "")],
                          "training instructions": groups["train_instructions"].first()})
    for split, column in SEED_SPLITS.items():
        for name, statistic in SEED_STATISTICS.items():
            frame[f"{split} {name}"] = summary[(column, statistic)]
    return frame


def seed_share_columns(spread: pd.DataFrame) -> list[str]:
    """The columns of :func:`seed_spread`'s table that are shares (for ``percent_table``)."""
    return [c for c in spread if c.split(" ")[0] in SEED_SPLITS]


def _spread_text(row: pd.Series, split: str) -> str:
    """"92.41% ± 1.10% (91.14% to 93.67%)", or the one value where there is a single seed."""
    if row["seeds"] < 2:
        return f"{_pct(row[f'{split} mean'])} (one seed: no spread)"
    return (f"{_pct(row[f'{split} mean'])} ± {_pct(row[f'{split} sd'])} "
            f"({_pct(row[f'{split} min'])} to {_pct(row[f'{split} max'])})")


def _spread_comparison(first: str, second: str, a: pd.Series, b: pd.Series, split: str) -> str:
    """Which of two models is ahead on a split's mean, and whether their seeds' ranges separate them."""
    mean_a, mean_b = a[f"{split} mean"], b[f"{split} mean"]
    if mean_a == mean_b:
        return f"on the {split} split the two means are equal"
    ahead, behind, top, bottom = (first, second, a, b) if mean_a > mean_b else (second, first, b, a)
    text = f"on the {split} split {ahead} is ahead by {abs(mean_a - mean_b) * 100:.2f} points on the mean"
    if top[f"{split} min"] > bottom[f"{split} max"]:
        return text + f", and every seed of {ahead} is above every seed of {behind}"
    return text + (f", but the seeds' ranges overlap (the best seed of {behind} is at least as good as the worst "
                   f"of {ahead}): the difference is within what the seed alone moves")


def seed_finding(spread: pd.DataFrame, models: Sequence[str] = ("LSTM-M4", "BERT-M4")) -> str:
    """The paper's data-efficiency comparison (M4: BiLSTM-CRF against BERT with the fewest training instructions)
    over the seeds, in words computed from :func:`seed_spread`'s table: mean ± standard deviation (min to max) of
    each on the validation and novel splits, and whether the seeds' ranges separate them."""
    first, second = models
    absent = [m for m in models if m not in spread.index]
    if absent:
        return "The seed table has no row for " + " or ".join(absent) + "."
    a, b = spread.loc[first], spread.loc[second]
    n_a, n_b = int(a["seeds"]), int(b["seeds"])
    seeds = f"{n_a} seeds" if n_a == n_b else f"{n_a} and {n_b} seeds"
    sizes = (f"{int(a['training instructions'])} training instructions each"
             if a["training instructions"] == b["training instructions"]
             else f"{int(a['training instructions'])} and {int(b['training instructions'])} training instructions")
    parts = [f"Over {seeds} ({sizes}), mean ± standard deviation (min to max) of Acc_inst: "
             f"{first} {_spread_text(a, 'validation')} on the validation split and {_spread_text(a, 'novel')} on "
             f"the novel one; {second} {_spread_text(b, 'validation')} and {_spread_text(b, 'novel')}."]
    comparisons = [_spread_comparison(first, second, a, b, split) for split in SEED_SPLITS]
    parts.append(comparisons[0][0].upper() + comparisons[0][1:] + "; " + comparisons[1] + ".")
    return " ".join(parts)


def seed_sizes_finding(spread: pd.DataFrame, split: str = "validation") -> str:
    """The BiLSTM-CRF against BERT at each training size the seed table has both of (M1 ... M4), over the seeds: which
    is ahead on the mean of ``split``'s Acc_inst, and whether the seeds' ranges separate them; one sentence a size."""
    lines = []
    for size in ("M1", "M2", "M3", "M4"):
        first, second = f"LSTM-{size}", f"BERT-{size}"
        if first not in spread.index or second not in spread.index:
            continue
        a, b = spread.loc[first], spread.loc[second]
        comparison = _spread_comparison(first, second, a, b, split)
        lines.append(f"{size} ({int(a['training instructions'])} training instructions): {first} "
                     f"{_spread_text(a, split)}, {second} {_spread_text(b, split)}; {comparison}.")
    return "\n".join(lines) if lines else "The seed table has no size with both models."


def coref_comparison(table3: pd.DataFrame, table5: pd.DataFrame, train_sizes: Mapping[str, int]) -> pd.DataFrame:
    """Table 5 against Table 3: BERT with the 15 co-reference labels (C) and with the 13 labels (M), validation
    Acc_inst and acc_task by training size, the paper's Acc_inst alongside."""
    records = []
    for table, variant in ((table3, "M"), (table5, "C")):
        for _, r in table.iterrows():
            kind, v, key = _model_parts(r["model"])
            if kind == "BERT" and v == variant:
                records.append({"training instructions": int(train_sizes[key]), "variant": variant,
                                "Acc_inst": r["Acc_inst"], "acc_task": r["acc_task"],
                                "paper Acc_inst": r.get("paper_Acc_inst", np.nan)})
    long = pd.DataFrame(records)
    wide = long.pivot(index="training instructions", columns="variant",
                      values=["Acc_inst", "acc_task", "paper Acc_inst"])
    wide.columns = [f"{value} BERT-{variant}" for value, variant in wide.columns]
    return wide.sort_index(ascending=False)


def coref_finding(table3: pd.DataFrame, table5: pd.DataFrame, train_sizes: Mapping[str, int],
                  n_validation: int) -> str:
    """What the co-reference labels change, in words computed from Tables 3 and 5 of the study."""
    frame = coref_comparison(table3, table5, train_sizes)
    behind = [n for n in frame.index if frame.loc[n, "Acc_inst BERT-C"] < frame.loc[n, "Acc_inst BERT-M"]]
    ahead = [n for n in frame.index if frame.loc[n, "Acc_inst BERT-C"] > frame.loc[n, "Acc_inst BERT-M"]]
    n = frame.index.min()
    diff = round((frame.loc[n, "Acc_inst BERT-M"] - frame.loc[n, "Acc_inst BERT-C"]) * n_validation)
    text = (f"With the two extra labels BERT's validation Acc_inst is lower at {len(behind)} and higher at "
            f"{len(ahead)} of the {len(frame)} training sizes; with {n} instructions the co-reference model gets "
            f"{abs(diff)} instruction{'s' if abs(diff) != 1 else ''} {'fewer' if diff >= 0 else 'more'} right")
    if frame[["paper Acc_inst BERT-M", "paper Acc_inst BERT-C"]].notna().all().all():
        paper_diff = round((frame.loc[n, "paper Acc_inst BERT-M"] - frame.loc[n, "paper Acc_inst BERT-C"])
                           * n_validation)
        text += f" (the paper: {abs(paper_diff)} {'fewer' if paper_diff >= 0 else 'more'})"
    return text + "."


def minilm_learning_rate_choice(results: Path | str = BENCHMARK_RESULTS / "bert_settings.md",
                                study_dir: Path | str = STUDY_DIR) -> tuple[pd.DataFrame | None, str]:
    """How the study's MiniLM learning rate was chosen, from the recorded grid of ``benchmarks/bert_settings.py``.

    Returns the table the script's rule reads (mean validation Acc_inst over the last epochs, per learning
    rate and training size; ``None`` when the results file is missing) and sentences saying what the rule
    picks, whether it is ``MINILM_LEARNING_RATE`` (what the study uses) and what the committed study ran with.
    """
    from drywall_lab.nlu.experiments import MINILM_LEARNING_RATE

    results = Path(results)
    script = REPO_ROOT / "benchmarks" / "bert_settings.py"
    lines = [f"The library's choice, drywall_lab.nlu.experiments.MINILM_LEARNING_RATE = {MINILM_LEARNING_RATE:g}."]
    table = None
    if not results.is_file() or not script.is_file():
        lines.append(f"The grid it was chosen on is not here ({results} or {script} is missing).")
    else:
        spec = importlib.util.spec_from_file_location("bert_settings_script", script)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        grid = [json.loads(line) for line in results.read_text(encoding="utf-8").splitlines()
                if line.startswith('{"train_size"')]
        if not grid:
            lines.append(f"{results} records no grid points.")
        else:
            chosen, table = module.choose_learning_rate(grid)
            lines.append(f"The rule ({module.RULE}) picks {chosen:g} on the grid recorded in "
                         f"{results.relative_to(REPO_ROOT) if results.is_relative_to(REPO_ROOT) else results}"
                         + (": the same." if chosen == MINILM_LEARNING_RATE
                            else f": NOT the library's {MINILM_LEARNING_RATE:g}; the recorded grid and the code "
                                 "disagree."))
    try:
        ran_at = study_settings(study_dir).get("bert_learning_rate")
    except (FileNotFoundError, ValueError) as e:
        lines.append(f"The study's settings could not be read: {e}")
    else:
        if ran_at is None:
            lines.append("The study's settings do not record a MiniLM learning rate.")
        elif ran_at == MINILM_LEARNING_RATE:
            lines.append(f"The committed study (results/paper) ran MiniLM at {ran_at:g}, this choice.")
        else:
            lines.append(f"The committed study (results/paper) ran MiniLM at {ran_at:g}, "
                         f"not at {MINILM_LEARNING_RATE:g}: "
                         "its BERT rows predate the current choice until `python -m drywall_lab experiment paper` "
                         "is run again.")
    return table, "\n".join(lines)


def field_results(path: Path | str = BENCHMARK_RESULTS / "field.md") -> tuple[pd.DataFrame | None, str]:
    """The field benchmark's summary (``benchmarks/field.py``: the whole pipeline on hand-written field sets), as
    a table of its ``<set>_<figure>=value`` lines, and a sentence; ``None`` and a "not run yet" sentence when
    the results file does not exist."""
    path = Path(path)
    if not path.is_file():
        return None, (f"The field benchmark has not been run yet ({path.name} does not exist): "
                      "`python benchmarks/field.py` writes it.")
    text = path.read_text(encoding="utf-8")
    summary = text.split("## Summary", 1)[1] if "## Summary" in text else text
    records = []
    for match in re.finditer(r"^(\w+?)_(accuracy|wrong_action_rate|over_refusal_rate)=([\d.]+)$", summary, re.M):
        records.append({"set": match.group(1), "figure": match.group(2), "value": float(match.group(3))})
    if not records:
        return None, f"{path} has no summary lines (<set>_accuracy=...)."
    table = pd.DataFrame(records).pivot(index="set", columns="figure", values="value")
    tagger = re.search(r"\*\*Tagger:\*\* (.+)", text)
    return table, (f"Recorded in {path.name} (the whole pipeline, the decision layer included)"
                   + (f"; tagger: {tagger.group(1).rstrip('.')}." if tagger else "."))

