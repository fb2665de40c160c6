"""Helpers for the course notebooks 01-04 (issue 13): fast mode, tables, the study's results, exercise checks.

- :func:`fast_mode`: the one reading of ``DRYWALL_FAST`` every notebook uses (README, "Fast mode").
- Tables that read well both as HTML and as text: :func:`percent_table`, :func:`table_3` (the paper's
  Table 3 row for a tagger, plus ``acc_task``), :func:`scores_on_sets`, :func:`tag_share_table` (Table 2).
- The project's full NLU study (``results/paper``, written by ``python -m drywall_lab experiment paper``):
  :func:`read_study_table`, :func:`accuracy_by_training_size` (Table 3 against training size),
  :func:`coref_comparison` (Table 5), :func:`novel_comparison`, and sentences computed from them
  (:func:`data_efficiency_finding`, :func:`novel_finding`, :func:`coref_finding`); the MiniLM learning
  rate's choice (:func:`minilm_learning_rate_choice`) and the field benchmark (:func:`field_results`).
- Exercises in the way of a manipulation course (a skeleton the student completes, a check that says what
  is right or wrong): :func:`check_tagging` (notebook 01, the annotation guidelines),
  :func:`check_most_forbidden` (02, the CRF's transition scores), :func:`check_vote` (03, the sub-word vote),
  :func:`check_relative_stud` (04, rule S3 of Fig. 12). Each returns an :class:`ExerciseCheck`.
- Notebook 04's layouts step by step: :func:`map_layout`, :func:`show_layout`; every refusal reason with an
  example: :func:`refusal_examples`.
"""
from __future__ import annotations

import importlib.util
import json
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy as np
import pandas as pd

from drywall_lab.corpus.tags import TAGS

if TYPE_CHECKING:
    import matplotlib.pyplot as plt

    from drywall_lab.im import ActionHistory, Interpretation
    from drywall_lab.nlu.base import Tagger
    from drywall_lab.site import Site, SiteState

#: The repository root: the study's results, the benchmarks and the annotation guidelines live there.
REPO_ROOT = Path(__file__).resolve().parent.parent
#: Where ``python -m drywall_lab experiment paper`` writes the study (``--out results/paper``).
STUDY_DIR = REPO_ROOT / "results" / "paper"
#: The benchmarks' recorded results.
BENCHMARK_RESULTS = REPO_ROOT / "benchmarks" / "results"
#: The annotation guidelines and their practice set (notebook 01).
GUIDELINES = REPO_ROOT / "annotation_guidelines" / "README.md"
PRACTICE_DIR = REPO_ROOT / "annotation_guidelines" / "practice"

# --- fast mode -----------------------------------------------------------------------------------------------
#: Values of ``DRYWALL_FAST`` (compared without case or surrounding spaces) that switch fast mode on / off.
FAST_ON = ("1", "true", "yes", "on")
FAST_OFF = ("", "0", "false", "no", "off")


def fast_mode() -> bool:
    """True when the environment variable ``DRYWALL_FAST`` asks for the course's fast mode.

    ``1``, ``true``, ``yes`` or ``on`` (any case) switch it on; unset, empty, ``0``, ``false``, ``no`` or
    ``off`` leave the notebooks in full mode. Any other value is a ``ValueError`` naming the accepted ones,
    so a typo never silently picks a mode.
    """
    value = os.environ.get("DRYWALL_FAST", "").strip().lower()
    if value in FAST_ON:
        return True
    if value in FAST_OFF:
        return False
    raise ValueError(
        f"DRYWALL_FAST={os.environ['DRYWALL_FAST']!r} is not understood: use one of "
        f"{', '.join(FAST_ON)} for fast mode or {', '.join(v for v in FAST_OFF if v)} (or leave it unset) "
        "for full mode"
    )


# --- tables --------------------------------------------------------------------------------------------------
#: The share columns of a Table 3 row, shown as percentages.
SHARE_COLUMNS = ("Acc_word", "Acc_inst", "acc_task")


def percent_table(frame: pd.DataFrame, columns: Sequence[str] = SHARE_COLUMNS, digits: int = 2) -> pd.DataFrame:
    """A copy of ``frame`` with the share ``columns`` (those it has) written as percentages, e.g. ``"99.37%"``.

    Unlike a pandas ``Styler``, the result reads the same as HTML and as text (``print``, a terminal, nbval).
    """
    out = frame.copy()
    for column in columns:
        if column in out:
            out[column] = [f"{v:.{digits}%}" if pd.notna(v) else "" for v in out[column]]
    return out


def table_3_row(name: str, tagger: "Tagger", rows: Sequence[Mapping]) -> dict:
    """The paper's Table 3 row for ``tagger`` on ``rows`` (N_w, Acc_word, N_l, Acc_inst), plus ``acc_task``:
    the share of instructions whose predicted tags lead the IM rules to the intended command or refusal."""
    from drywall_lab.im import task_accuracy
    from drywall_lab.nlu.metrics import score_tagging

    if not rows:
        raise ValueError(f"no instructions to score {name!r} on")
    predicted = tagger.predict([r["words"] for r in rows])
    s = score_tagging(tagger.gold_tags(rows), predicted)
    return {"model": name, "N_w": s.n_word_errors, "Acc_word": s.acc_word, "N_l": s.n_instruction_errors,
            "Acc_inst": s.acc_inst, "acc_task": task_accuracy(rows, predicted)}


def table_3(taggers: Mapping[str, "Tagger"], rows: Sequence[Mapping]) -> pd.DataFrame:
    """Table 3 (plus ``acc_task``) for several taggers on the same instructions, one row per tagger."""
    return pd.DataFrame([table_3_row(name, tagger, rows) for name, tagger in taggers.items()]).set_index("model")


def describe_tagger(tagger: "Tagger") -> str:
    """One sentence saying what a trained tagger is and what it was trained on, from its own record
    (``training_info``, saved with it): the notebooks never assume which tagger is shipped. An ensemble
    (``CrfEnsembleTagger``) is described by its members."""
    members = getattr(tagger, "members", None)
    if not members:
        return _describe_one(tagger, tagger.n_parameters()) + "."
    seeds = ", ".join(str(m.training_info.get("seed", "?")) for m in members)
    one = _describe_one(members[0], None, wall_time=False).removeprefix("a ")
    return (f"an ensemble of {len(members)} taggers whose CRF scores are averaged ({tagger.n_parameters():,} parameters "
            f"in all; seeds {seeds}), each {one}.")


def _describe_one(tagger: "Tagger", n_parameters: int | None, wall_time: bool = True) -> str:
    info = tagger.training_info
    kind = {"bilstm-crf": "a BiLSTM-CRF", "bert": "a fine-tuned BERT-family encoder"}.get(tagger.kind, tagger.kind)
    features = " reading characters as well as words" if getattr(tagger, "uses_characters", False) else ""
    text = f"{kind}{features}" + (f" with {n_parameters:,} parameters" if n_parameters is not None else "")
    if "n_train_instructions" in info and "epochs" in info:
        text += f", trained on {info['n_train_instructions']:,} instructions for {info['epochs']} epochs"
        if "n_validation_instructions" in info:
            text += f" (validated on {info['n_validation_instructions']:,})"
        if wall_time and info.get("wall_seconds") is not None:
            text += f" in {info['wall_seconds']:.0f} s"
    return text


def training_curves(tagger: "Tagger", name: str) -> dict[str, pd.DataFrame]:
    """A trained tagger's per-epoch history for ``plot_training_curves``, named ``name`` and the number of
    instructions it was trained on; an ensemble gives one curve per member (its seed in the name)."""
    members = getattr(tagger, "members", None) or [tagger]
    curves = {}
    for member in members:
        info = member.training_info
        label = f"{name} ({info.get('n_train_instructions', '?')} instructions"
        label += f", seed {info['seed']})" if len(members) > 1 and "seed" in info else ")"
        curves[label] = member.history
    return curves


def scores_on_sets(tagger: "Tagger", sets: Sequence[str], limit: int | None = None) -> pd.DataFrame:
    """Table 3 (plus ``acc_task``) of one tagger on named sets (``drywall_lab.splits``), one row per set; on the
    first ``limit`` instructions of each set when given (the notebooks' fast mode)."""
    from drywall_lab.splits import split_rows

    if limit is not None and limit < 1:
        raise ValueError(f"limit must be at least 1, got {limit}")
    records = []
    for name in sets:
        rows = split_rows(name)[:limit]
        records.append({"instructions": len(rows)} | table_3_row(name, tagger, rows))
    frame = pd.DataFrame(records)
    return frame.rename(columns={"model": "set"}).set_index("set")


def tag_share_table(table: pd.DataFrame) -> pd.DataFrame:
    """``corpus.tag_table`` (the paper's Table 2) for reading: what the project's bound says about each tag.

    The bound (within 20 %, relative, of the paper's share) is applied only to tags above 1 % of the paper's
    words; for the rarer ones a few words either way move the ratio a lot, so they are shown, not judged.
    """
    out = table[["words", "share_%", "paper_words", "paper_share_%", "ratio"]].copy()
    out["bound"] = ["within 20 % of the paper's share" if held else "none (under 1 % of the paper's words)"
                    for held in table["checked"]]
    out["verdict"] = ["-" if not held else ("within" if inside else "OUTSIDE")
                      for held, inside in zip(table["checked"], table["within_20%"])]
    return out


# --- the study (results/paper) ---------------------------------------------------------------------------------
def read_study_table(name: str, study_dir: Path | str = STUDY_DIR) -> pd.DataFrame:
    """One CSV of the study (``table3_validation``, ``table5_coref_validation``, ``novel``, ``m1_on_test``,
    ``training_history``, ``table4_errors_per_tag``, ...); a ``FileNotFoundError`` saying how to write it."""
    path = Path(study_dir) / f"{name}.csv"
    if not path.is_file():
        raise FileNotFoundError(f"{path} does not exist: the study writes it with "
                                f"`python -m drywall_lab experiment paper --out {study_dir}`")
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
                   + (f"; tagger: {tagger.group(1)}." if tagger else "."))


# --- exercises -------------------------------------------------------------------------------------------------
@dataclass
class ExerciseCheck:
    """What a check found: ``passed``, and one message a line saying what is right, or what is not and why."""

    passed: bool
    messages: list[str] = field(default_factory=list)

    def __str__(self) -> str:
        return "\n".join([("PASSED" if self.passed else "NOT YET") + ":"] + [f"- {m}" for m in self.messages])


def _call(function: Callable, *args: Any) -> tuple[Any, str | None]:
    """The student's function called on ``args``: (its result, None), or (None, what it raised)."""
    try:
        return function(*args), None
    except Exception as e:  # noqa: BLE001 - any error in a student's code is reported, not raised
        return None, f"{type(e).__name__}: {e}"


# --- notebook 01: tagging by the guidelines --------------------------------------------------------------------
#: The practice instruction of notebook 01's tagging exercise (``annotation_guidelines/practice``).
TAGGING_EXERCISE = "P12"
PLACEMENT_TAGS = ("Vr_md", "Hr_top", "Hr_btm")
ANCHOR_TAGS = ("Dw_loc2", "St_loc2")


def guideline_headings(path: Path | str = GUIDELINES) -> list[str]:
    """The guidelines' section headings (``##`` and ``###``), without the hashes."""
    return [line.lstrip("#").strip() for line in Path(path).read_text(encoding="utf-8").splitlines()
            if re.match(r"#{2,3} ", line)]


def _heading(headings: Sequence[str], pattern: str) -> str:
    """The first heading matching ``pattern``; a ``ValueError`` when the guidelines have none."""
    for heading in headings:
        if re.search(pattern, heading):
            return heading
    raise ValueError(f"the annotation guidelines have no section matching {pattern!r}")


def guideline_sections(word: str, gold: str, given: str, headings: Sequence[str] | None = None) -> list[str]:
    """The guideline sections to read for ``word``, tagged ``given`` where the guidelines say ``gold``.

    The hard-case sections of section 4 that name the word ("middle", "previous", ...) or the mix-up (width
    and length, the default placement said in words, an anchor), section 2's general rule when the word
    should be ``O``, and always the gold tag's own section of section 3.
    """
    headings = guideline_headings() if headings is None else headings
    found = [h for h in headings if re.match(r"4\.\d+ ", h) and word.lower() in re.findall(r'"([^"]+)"', h)]
    if {gold, given} == {"width", "length"}:
        found.append(_heading(headings, r"^4\.\d+ Width and length"))
    if gold == "O" and given in PLACEMENT_TAGS:
        found.append(_heading(headings, r"^4\.\d+ The default placement"))
    if {gold, given} & set(ANCHOR_TAGS):
        found.append(_heading(headings, r"^4\.\d+ .*anchor"))
    if gold == "O":
        found.append(_heading(headings, r"^2\. The general rule"))
    found.append(f"3, the tag {_heading(headings, rf'^{re.escape(gold)}$')}")
    return [f"section {h}" for h in dict.fromkeys(found)]


def practice_instruction(instruction_id: str = TAGGING_EXERCISE) -> dict:
    """One instruction of the practice set with its answer-key tags (``practice_key.conll``)."""
    from drywall_lab.corpus import from_conll

    rows = {r["id"]: r for r in from_conll(PRACTICE_DIR / "practice_key.conll")}
    if instruction_id not in rows:
        raise ValueError(f"no practice instruction {instruction_id!r}; they are {', '.join(rows)}")
    return rows[instruction_id]


def parse_tagged(answer: str) -> tuple[list[str], list[str]]:
    """Words and tags from the guidelines' notation, ``word/TAG`` for a tagged word and a bare word for ``O``.

    Punctuation at a word's edges is dropped as ``corpus.tokenize`` drops it (``500103/St_loc2.`` is the word
    ``500103`` tagged ``St_loc2``). An unknown tag is a ``ValueError`` naming it and listing the tags.
    """
    from drywall_lab.corpus import tokenize

    words, tags = [], []
    for piece in answer.split():
        word, slash, tag = piece.rpartition("/")
        if not slash:
            word, tag = piece, "O"
        tag = tag.strip(".,?!;:\"'()")
        if tag not in TAGS:
            raise ValueError(f"{piece!r}: {tag!r} is not a tag; the tags are {', '.join(TAGS)}")
        for w in tokenize(word):
            words.append(w)
            tags.append(tag)
    return words, tags


def check_tagging(answer: str | Sequence[str], instruction_id: str = TAGGING_EXERCISE) -> ExerciseCheck:
    """Notebook 01's exercise: a practice instruction tagged by the guidelines, against the answer key.

    ``answer`` is the instruction in the guidelines' notation (``word/TAG``, a bare word is ``O``) or one tag
    per word. Every wrong word is named with the tag the key gives and the guideline sections to read.
    """
    key = practice_instruction(instruction_id)
    words, gold = key["words"], key["tags"]
    if isinstance(answer, str):
        try:
            given_words, given = parse_tagged(answer)
        except ValueError as e:
            return ExerciseCheck(False, [str(e)])
        for i, (got, want) in enumerate(zip(given_words, words)):
            if got != want:
                return ExerciseCheck(False, [f"word {i + 1} of your answer is {got!r} where the instruction has "
                                             f"{want!r}: keep the instruction's words and add /TAG to them"])
        if len(given_words) != len(words):
            return ExerciseCheck(False, [f"your answer has {len(given_words)} words, the instruction {len(words)}"])
    else:
        given = list(answer)
        if len(given) != len(words):
            return ExerciseCheck(False, [f"{len(given)} tags for {len(words)} words: give one tag per word"])
        unknown = [t for t in given if t not in TAGS]
        if unknown:
            return ExerciseCheck(False, [f"{unknown[0]!r} is not a tag; the tags are {', '.join(TAGS)}"])
    headings = guideline_headings()
    wrong = [(i, w, g, a) for i, (w, g, a) in enumerate(zip(words, gold, given)) if g != a]
    if not wrong:
        return ExerciseCheck(True, [f"all {len(words)} words of {instruction_id} tagged as the answer key tags them"])
    messages = [f"{len(words) - len(wrong)} of {len(words)} words right; {len(wrong)} to look at again:"]
    for i, w, g, a in wrong:
        messages.append(f"word {i + 1} {w!r}: you tagged {a}, the guidelines say {g} "
                        f"(see {'; '.join(guideline_sections(w, g, a, headings))})")
    return ExerciseCheck(False, messages)


# --- notebook 02: the CRF's transition scores ------------------------------------------------------------------
def crf_transitions(tagger: "Tagger") -> pd.DataFrame:
    """A trained BiLSTM-CRF's transition scores as a table: row = the tag before, column = the tag after.

    The CRF adds ``transitions[a, b]`` to a tag sequence's score wherever tag ``b`` follows tag ``a``; the most
    negative entries are the transitions it has learned to (almost) forbid. For an ensemble of BiLSTM-CRFs
    (``CrfEnsembleTagger``), the members' mean, which is what it decodes with.
    """
    from drywall_lab.nlu.ensemble import CrfEnsembleTagger

    if isinstance(tagger, CrfEnsembleTagger):
        crf = tagger.crf
    else:
        crf = getattr(getattr(tagger, "network", None), "crf", None)
    if crf is None:
        raise ValueError("crf_transitions needs a trained BiLstmCrfTagger (or an ensemble of them)")
    scores = crf.transitions.detach().cpu().numpy().astype(float)
    labels = list(tagger.labels)
    return pd.DataFrame(scores, index=pd.Index(labels, name="from (tag before)"),
                        columns=pd.Index(labels, name="to (tag after)"))


def reference_most_forbidden(transitions: pd.DataFrame, k: int) -> list[tuple[str, str]]:
    """The reference answer: the ``k`` (before, after) tag pairs with the lowest transition scores, lowest first."""
    stacked = transitions.stack()
    return [(str(a), str(b)) for a, b in stacked.nsmallest(k, keep="first").index]


def _exercise_matrices(tagger: "Tagger | None") -> list[tuple[str, pd.DataFrame, int]]:
    """The tables the check tries: the trained tagger's, then small ones built to catch the usual slips."""
    cases = []
    if tagger is not None:
        cases.append(("the trained tagger's transitions", crf_transitions(tagger), 5))
    labels = ["O", "ID_stud", "St_loc1", "St_loc2"]
    asymmetric = pd.DataFrame([[0.5, 1.0, 0.2, -0.1], [0.3, -4.0, 2.5, -9.0], [0.0, -2.0, 1.5, 0.8],
                               [0.7, -6.0, -1.0, 1.2]], index=labels, columns=labels)
    cases.append(("a small table whose rows and columns are not interchangeable", asymmetric, 3))
    cases.append(("the same small table", asymmetric, 1))
    rng = np.random.default_rng(13)
    cases.append(("a random 13 x 13 table", pd.DataFrame(rng.normal(size=(13, 13)), index=list(TAGS),
                                                        columns=list(TAGS)), 4))
    return cases


def check_most_forbidden(most_forbidden: Callable[[pd.DataFrame, int], Sequence[tuple[str, str]]],
                         tagger: "Tagger | None" = None) -> ExerciseCheck:
    """Notebook 02's exercise: ``most_forbidden(transitions, k)`` must return the ``k`` (before, after) tag
    pairs with the lowest scores, lowest first, on the trained tagger's table and on tables built to catch
    swapped rows and columns, the highest scores instead of the lowest, and the wrong order."""
    messages = []
    for name, table, k in _exercise_matrices(tagger):
        want = reference_most_forbidden(table, k)
        got, error = _call(most_forbidden, table.copy(), k)
        if error:
            return ExerciseCheck(False, messages + [f"on {name} (k = {k}) your function raised {error}"])
        try:
            returned, got = got, [tuple(str(t) for t in pair) for pair in got]
            assert not isinstance(returned, str) and all(len(pair) == 2 for pair in got)
        except (TypeError, AssertionError):
            return ExerciseCheck(False, messages + [f"on {name} (k = {k}) your function returned {returned!r}: "
                                                    "return a list of (tag before, tag after) pairs"])
        if got == want:
            messages.append(f"{name}, k = {k}: right")
            continue
        problem = f"on {name} (k = {k}) you returned {got}, the lowest scores are {want}"
        if len(got) != k:
            hint = f"return exactly k = {k} pairs"
        elif got == [(b, a) for a, b in want]:
            hint = "your pairs are (after, before): a row of the table is the tag before, a column the tag after"
        elif set(got) == set(reference_most_forbidden(-table, k)) or got == reference_most_forbidden(-table, k):
            hint = "those are the highest scores, the transitions the CRF favours most: forbidden means lowest"
        elif set(got) == set(want):
            hint = "the right pairs in the wrong order: the lowest score first"
        else:
            first = next(i for i, (g, w) in enumerate(zip(got, want)) if g != w)
            g, w = got[first], want[first]
            score = table.loc[g[0], g[1]] if g[0] in table.index and g[1] in table.columns else float("nan")
            hint = (f"pair {first + 1}: {g} scores {score:.3f}, but {w} scores {table.loc[w[0], w[1]]:.3f}")
        return ExerciseCheck(False, messages + [f"{problem}: {hint}"])
    return ExerciseCheck(True, messages)


# --- notebook 03: the sub-word vote ----------------------------------------------------------------------------
def vote_cases(n_random: int = 200, seed: int = 3) -> list[tuple[str, list[str], list[int | None], int]]:
    """Cases for the vote: (what it tests, token tags, word ids, number of words); the hand-made ones first."""
    cases: list[tuple[str, list[str], list[int | None], int]] = [
        ("one token per word", ["O", "O", "ID_stud", "O"], [None, 0, 1, None], 2),
        ("a majority of three tokens", ["O", "ID_stud", "ID_wall", "ID_stud", "O"], [None, 0, 0, 0, None], 1),
        ("a majority that is not the first token", ["ID_wall", "ID_stud", "ID_stud"], [0, 0, 0], 1),
        ("a tie of two tokens (the first decides)", ["Dw_loc1", "Vr_md"], [0, 0], 1),
        ("the same tie the other way round", ["Vr_md", "Dw_loc1"], [0, 0], 1),
        ("three tokens tagged three ways (no majority: the first decides)", ["width", "length", "dim"], [0, 0, 0], 1),
        ("a two-two tie of four tokens", ["St_loc1", "St_loc2", "St_loc2", "St_loc1"], [0, 0, 0, 0], 1),
        ("the most frequent tag without more than half (the first decides)",
         ["O", "Dw_loc1", "Dw_loc1", "St_loc1", "Vr_md"], [0, 0, 0, 0, 0], 1),
        ("exactly half is not more than half", ["Vr_md", "Hr_top", "Hr_top", "Dw_loc1"], [0, 0, 0, 0], 1),
        ("a word with no token gets O", ["width"], [0], 2),
        ("special tokens ([CLS], [SEP], padding) vote for no word", ["Hr_btm", "dim", "Hr_btm", "Hr_btm"],
         [None, 0, None, None], 1),
        ("words in order, each with its own tokens", ["O", "width", "O", "length", "length", "O"],
         [None, 0, 1, 2, 2, None], 3),
    ]
    rng = np.random.default_rng(seed)
    for i in range(n_random):
        n_words = int(rng.integers(1, 6))
        counts = rng.integers(0 if i % 5 == 0 else 1, 5, size=n_words)
        word_ids: list[int | None] = [None] + [w for w in range(n_words) for _ in range(counts[w])] + [None]
        palette = list(rng.choice(TAGS, size=3, replace=False))
        tags = [str(rng.choice(palette)) for _ in word_ids]
        cases.append((f"random case {i + 1}", tags, word_ids, n_words))
    return cases


def _vote_reason(tags: list[str]) -> str:
    """Which part of the rule decides a word with these token tags."""
    if not tags:
        return "it has no token, so it is O"
    best, count = max(((t, tags.count(t)) for t in dict.fromkeys(tags)), key=lambda p: p[1])
    if count * 2 > len(tags):
        return f"{count} of its {len(tags)} tokens say {best}: more than half"
    return f"no tag has more than half of its {len(tags)} tokens, so its first token decides: {tags[0]}"


def check_vote(vote: Callable[[list[str], list[int | None], int], Sequence[str]]) -> ExerciseCheck:
    """Notebook 03's exercise: ``vote(token_tags, word_ids, n_words)`` against ``drywall_lab.nlu.vote_word_tags``
    (the paper's "more than half of the tokens" rule, the first token without a strict majority) on hand-made
    cases (ties, three-way splits, words without tokens, special tokens) and random ones; the first
    disagreement is explained word by word."""
    from drywall_lab.nlu.bert import vote_word_tags

    cases = vote_cases()
    for what, tags, word_ids, n_words in cases:
        want = vote_word_tags(tags, word_ids, n_words)
        got, error = _call(vote, list(tags), list(word_ids), n_words)
        if error:
            return ExerciseCheck(False, [f"{what}: your function raised {error} on token tags {tags}, "
                                         f"word ids {word_ids}, n_words {n_words}"])
        got = list(got) if isinstance(got, (list, tuple)) else got
        if got == want:
            continue
        messages = [f"{what}: token tags {tags}, word ids {word_ids}, n_words {n_words}",
                    f"the vote gives {want}, your function {got}"]
        if not isinstance(got, list) or len(got) != n_words:
            messages.append(f"return one tag per word: a list of {n_words}")
        else:
            for w, (g, v) in enumerate(zip(got, want)):
                if g != v:
                    own = [t for t, i in zip(tags, word_ids) if i == w]
                    messages.append(f"word {w} (its tokens say {own}): {_vote_reason(own)}, not {g}")
                    break
        return ExerciseCheck(False, messages)
    return ExerciseCheck(True, [f"all {len(cases)} cases agree with vote_word_tags, ties and words without "
                                "tokens included"])


def token_predictions(tagger: "Tagger", words: Sequence[str]) -> pd.DataFrame:
    """A trained ``BertTagger``'s view of one instruction: each sub-word token, the word it belongs to and the
    tag the model gives it, through the tagger's own prediction path (``predict`` votes these into word tags)."""
    return _token_tables(tagger, [list(words)])[0]


def _token_tables(tagger: "Tagger", sentences: Sequence[Sequence[str]]) -> list[pd.DataFrame]:
    """``token_predictions`` for many instructions, in batches (``BertTagger.predict_tokens``)."""
    return [pd.DataFrame(rows, columns=["token", "word id", "token tag"], dtype=object)
            for rows in tagger.predict_tokens(sentences)]


def vote_statistics(tagger: "Tagger", rows: Sequence[Mapping]) -> dict[str, int]:
    """How often the vote has work to do on ``rows``: words of several tokens, those whose tokens disagree, and
    those with no strict majority (decided by the first token)."""
    counts = {"words of several tokens": 0, "tokens disagree": 0, "no strict majority": 0}
    for table in _token_tables(tagger, [row["words"] for row in rows]):
        for _, tags in table.dropna(subset=["word id"]).groupby("word id")["token tag"]:
            tags = list(tags)
            if len(tags) > 1:
                counts["words of several tokens"] += 1
                if len(set(tags)) > 1:
                    counts["tokens disagree"] += 1
                    counts["no strict majority"] += max(map(tags.count, tags)) * 2 <= len(tags)
    return counts


# --- notebook 04: rule S3 and the layouts ----------------------------------------------------------------------
#: How the S3 exercise's cases say a count.
COUNT_WORDS = {0: "zero", 1: "one", 2: "two", 3: "3", 4: "four", 5: "5th", 12: "12", 13: "thirteen"}


def words_and_tags(markup: str) -> tuple[list[str], list[str]]:
    """Words and tags from the project's markup: ``"the full-size/dim drywall on stud 500107/ID_stud"``."""
    from drywall_lab.corpus.markup import parse

    tokens = [t for t in parse(markup) if t.is_word]
    return [t.word for t in tokens], [t.tag for t in tokens]


def relative_stud_cases(site: "Site | None" = None) -> list[tuple[str, str, int, str]]:
    """(anchor id, direction, count, the instruction's words) for every stud of the site as anchor, both
    directions and counts from 0 to past the wall's end."""
    from drywall_lab.site import default_site

    site = site or default_site()
    cases = []
    for anchor in site.stud_ids:
        for direction in ("left", "right"):
            for count, said in COUNT_WORDS.items():
                cases.append((anchor, direction, count,
                              f"put the full-size/dim panel on the stud {said}/St_loc1 to/St_loc1 the/St_loc1 "
                              f"{direction}/St_loc1 of 500000/St_loc2".replace("500000", anchor)))
    return cases


def rule_s3(markup: str, site: "Site | None" = None) -> tuple[str | None, str]:
    """What the library's rules (``resolve_stud``, Fig. 12) make of one instruction: (stud id or None, why)."""
    from drywall_lab.errors import Refusal
    from drywall_lab.im import MappingContext, TaggedInstruction, resolve_stud
    from drywall_lab.site import default_site

    site = site or default_site()
    words, tags = words_and_tags(markup)
    try:
        return resolve_stud(TaggedInstruction(words, tags), MappingContext(site, site.fresh())), ""
    except Refusal as refusal:
        return None, f"{refusal.reason}: {refusal}"


def check_relative_stud(relative_stud: Callable[["Site", str, str, int], str | None],
                        site: "Site | None" = None) -> ExerciseCheck:
    """Notebook 04's exercise: ``relative_stud(site, anchor_id, direction, count)`` (rule S3 of Fig. 12: the stud
    ``count`` places to the ``direction`` of the anchor, ``None`` past the wall's end) against the library's
    rules on every anchor, both directions and counts from 0 to past the end; the first disagreement and
    how many there are."""
    from drywall_lab.site import default_site

    site = site or default_site()
    cases = relative_stud_cases(site)
    disagreements = []
    for anchor, direction, count, markup in cases:
        want, why = rule_s3(markup, site)
        got, error = _call(relative_stud, site, anchor, direction, count)
        if error or got != want:
            disagreements.append((anchor, direction, count, markup, want, why, got, error))
    if not disagreements:
        return ExerciseCheck(True, [f"all {len(cases)} cases agree with rule S3 ({len(site.stud_ids)} anchors, left "
                                    f"and right, counts {min(COUNT_WORDS)} to {max(COUNT_WORDS)})"])
    messages = [f"{len(disagreements)} of {len(cases)} cases disagree with rule S3; the first of each kind:"]
    seen = set()
    for anchor, direction, count, markup, want, why, got, error in disagreements:
        kind, hint = _s3_mistake(site, anchor, direction, count, want, got, error)
        if kind in seen:
            continue
        seen.add(kind)
        said = " ".join(words_and_tags(markup)[0])
        result = f"raised {error}" if error else repr(got)
        rules = repr(want) if want else f"no stud ({why})"
        messages.append(f"'{said}': the rules give {rules}, your function {result}"
                        + (f"; {hint}" if hint else ""))
    return ExerciseCheck(False, messages)


def _s3_mistake(site: "Site", anchor: str, direction: str, count: int, want: str | None, got: Any,
                error: str | None) -> tuple[str, str]:
    """(the kind of a wrong S3 answer, a hint saying what to change)."""
    ids = site.stud_ids
    if error:
        return "error", "it should return a stud id or None, never raise"
    if got is not None and not isinstance(got, str):
        return "type", f"return the stud's id as a string, like {ids[0]!r}, or None"
    if got is not None and got not in ids:
        return "unknown", f"{got!r} is not a stud of this site; the studs are {ids[0]} to {ids[-1]}"
    if want is None:
        step = ids.index(anchor) + (count if direction == "right" else -count)
        wrapped = 0 <= step % len(ids) < len(ids) and got == ids[step % len(ids)] and step < 0
        return "past the end", ("past the end of the wall there is no stud: return None"
                                + (" (a negative list index counts from the other end in Python)" if wrapped else ""))
    if got is None:
        return "none", "that stud is on the wall: only a step past either end gives None"
    step = site.stud(got).index - site.stud(want).index
    if count == 0:
        return "zero", "zero places away is the anchor itself"
    if site.stud(got).index - site.stud(anchor).index == -(site.stud(want).index - site.stud(anchor).index):
        return "direction", "that is the other direction: right is towards higher ids, left towards lower"
    return "distance", (f"your stud is {abs(step)} stud{'s' if abs(step) != 1 else ''} to the "
                        f"{'right' if step > 0 else 'left'} of the one the rules give")


@dataclass
class GoldLayoutRun:
    """One of the paper's layouts mapped by the IM rules from its hand-checked tags, step by step."""

    layout: Mapping
    results: list["Interpretation"]
    history: "ActionHistory"
    states: list["SiteState"]  #: the site after each step (a refused step leaves it as it was)

    def outcomes(self) -> list[dict]:
        """Each step as the layout's ``expected`` writes it: the command, or ``{"refusal": reason}``."""
        return [r.command.as_contract() if r.accepted else {"refusal": r.refusal.reason} for r in self.results]

    def problems(self) -> list[str]:
        """Every step whose outcome is not the layout's expected one (none: the rules agree with the layout)."""
        found = [f"step {k}: expected {want}, got {got}"
                 for k, (got, want) in enumerate(zip(self.outcomes(), self.layout["expected"])) if got != want]
        if len(self.results) != len(self.layout["expected"]):
            found.append(f"{len(self.results)} steps, the layout expects {len(self.layout['expected'])}")
        return found

    def step_lines(self) -> list[str]:
        """One line per step: the command, or the refusal and its message."""
        return [str(r.command) if r.accepted else f"refused ({r.refusal.reason}): {r.refusal.message}"
                for r in self.results]

    def titles(self) -> list[str]:
        return [f"after step {k}" + ("" if r.accepted else " (refused: nothing changes)")
                for k, r in enumerate(self.results)]

    def figure(self) -> "plt.Figure":
        """The wall after each step (the paper's Figs. 16-18)."""
        from drywall_lab.plots import draw_wall_steps

        return draw_wall_steps(self.states, self.titles())


def map_layout(layout: Mapping, site: "Site | None" = None) -> GoldLayoutRun:
    """A layout's hand-tagged instructions through the IM rules in order, on a fresh site: no tagger."""
    from drywall_lab.im import InformationMapper

    mapper = InformationMapper(site)
    results, states = [], []
    for words, tags in zip(layout["words"], layout["tags"]):
        results.append(mapper.apply(words, tags))
        states.append(mapper.history.state)
    return GoldLayoutRun(layout, results, mapper.history, states)


def show_layout(layout: Mapping, site: "Site | None" = None) -> GoldLayoutRun:
    """Map a layout (``map_layout``) and show it: each step's tagged words and outcome, then the wall step by step."""
    from IPython.display import HTML, display

    from drywall_lab.display import tagged_html

    run = map_layout(layout, site)
    for step, (words, tags, line) in enumerate(zip(layout["words"], layout["tags"], run.step_lines())):
        display(HTML(f"<b>step {step}</b>" + tagged_html(words, tags)))
        print(f"step {step}: {line}")
    run.figure()
    return run


def unclear_example() -> tuple[str, str]:
    """The decision layer's question (reason ``unclear``, ``drywall_lab.decision``) for one instruction that an
    unsure tagger reads two ways: "middle" as the placement (``Vr_md``) or as nothing (``O``); (text, message)."""
    from drywall_lab.corpus.tags import TAGS as LABELS
    from drywall_lab.decision import decide

    words, centre = words_and_tags("put the full-size/dim panel on stud 500104/ID_stud in the middle/Vr_md")
    default = ["O" if t == "Vr_md" else t for t in centre]
    decision = decide(words, [(centre, np.log(0.55)), (default, np.log(0.45))],
                      np.zeros((len(words), len(LABELS))), LABELS)
    return " ".join(words) + " (read two ways: 'middle' as Vr_md, p = 0.55, or O, p = 0.45)", decision.refusal.message


def refusal_examples(rows_by_split: Mapping[str, Sequence[Mapping]]) -> pd.DataFrame:
    """Spec section 5's refusal reasons, each with the first corpus instruction refused for it and the message
    the worker hears; ``stack_empty`` (which the corpus's episodes never reach) on a history built for it, and
    ``unclear`` (the decision layer's question, never a gold-tag outcome) from ``unclear_example``."""
    from drywall_lab.errors import REFUSAL_REASONS
    from drywall_lab.im import ActionHistory, interpret, interpret_row

    examples: dict[str, tuple[str, str]] = {}
    for rows in rows_by_split.values():
        for r in rows:
            reason = r["expected"]["refusal"]
            if reason and reason not in examples:
                examples[reason] = (r["text"], interpret_row(r).refusal.message)
    if "stack_empty" not in examples:
        emptied = ActionHistory.from_commands([{"drywall_id": d, "stud_id": s, "placement": "vertical_left"}
                                               for d, s in [("500321", "500100"), ("500311", "500102"),
                                                            ("500301", "500104")]])
        words, tags = words_and_tags("Take the 2/width by 8/length panel and put it on stud 500108/ID_stud")
        examples["stack_empty"] = (" ".join(words), interpret(words, tags, emptied).refusal.message)
    if "unclear" not in examples:
        examples["unclear"] = unclear_example()
    return pd.DataFrame([{"reason": k, "meaning": REFUSAL_REASONS[k], "instruction": examples[k][0],
                          "message": examples[k][1]} for k in REFUSAL_REASONS if k in examples])
