"""The paper's NLU study (drywall_lab/nlu/experiments.py), on tiny settings: every table and figure is written."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
from dataclasses import asdict
from pathlib import Path
from types import ModuleType

import pandas as pd
import pytest
from conftest import load_benchmark
from hypothesis import given, settings
from hypothesis import strategies as st

from drywall_lab.nlu.experiments import (
    MINILM_EPOCHS,
    MINILM_LEARNING_RATE,
    MINILM_WARMUP_RATIO,
    PAPER_TABLE3,
    SEED_COLUMNS,
    ExperimentSettings,
    merge_seed_rows,
    run_paper_experiment,
    run_seed_study,
    seed_summary,
    study_rerun_lines,
)


def test_tiny_study_writes_every_table(tmp_path):
    tiny = ExperimentSettings(train_sizes={"1": 24, "2": 16, "3": 12, "4": 8}, lstm_epochs=1, bert_epochs=1)
    tables = run_paper_experiment(tmp_path, tiny, log=lambda _: None)
    t3 = pd.read_csv(tmp_path / "table3_validation.csv")
    assert list(t3.model) == [f"LSTM-M{i}" for i in range(1, 5)] + [f"BERT-M{i}" for i in range(1, 5)]
    assert t3.paper_Acc_inst.tolist() == [PAPER_TABLE3[m][3] / 100 for m in t3.model]
    assert ((t3.Acc_word >= 0) & (t3.Acc_word <= 1) & (t3.N_l <= 158)).all()
    assert (t3.N_l == ((1 - t3.Acc_inst) * 158).round().astype(int)).all()
    assert list(pd.read_csv(tmp_path / "table5_coref_validation.csv").model) == [f"BERT-C{i}" for i in range(1, 5)]
    t4 = pd.read_csv(tmp_path / "table4_errors_per_tag.csv", index_col="tag")
    assert t4.loc["ALL"].tolist() == t3.N_w.tolist()
    novel = pd.read_csv(tmp_path / "novel.csv")
    assert len(novel) == 12
    t4n = pd.read_csv(tmp_path / "table4_errors_per_tag_novel.csv", index_col="tag")
    assert t4n.loc["ALL"].tolist() == novel.N_w[:8].tolist()
    assert pd.read_csv(tmp_path / "seconds_by_sentences.csv").instructions.sum() == 158
    assert tables["best_on_test"].model.iloc[0] in set(t3.model)
    m1 = pd.read_csv(tmp_path / "m1_on_test.csv")
    assert list(m1.model) == ["LSTM-M1", "BERT-M1"] and (m1.train_seconds > 0).all()
    assert (t3.train_seconds > 0).all()
    wrong = pd.read_csv(tmp_path / "m1_test_errors.csv")
    for m in ("LSTM-M1", "BERT-M1"):  # one row per wrong test instruction
        assert (wrong.model == m).sum() == m1.set_index("model").loc[m, "N_l"]
    readme = (tmp_path / "README.md").read_text()
    for m in ("LSTM-M1", "BERT-M1"):  # the verdict follows the figure
        acc = m1.set_index("model").loc[m, "Acc_inst"]
        assert f"{m} test Acc_inst >= 99.4% (paper 99.37%): {acc:.2%} vs 99.40%: {'met' if acc >= 0.994 else 'missed'}" in readme
    assert (tmp_path / "fig13_training_accuracy.png").stat().st_size > 10_000
    history = pd.read_csv(tmp_path / "training_history.csv")  # Fig. 13's data, one row per model and epoch
    assert history.groupby("model").epoch.max().to_dict() == {m: 1 for m in list(t3.model) + [f"BERT-C{i}" for i in range(1, 5)]}
    assert "Table 3" in (tmp_path / "README.md").read_text()
    assert "Machine at the start: " in readme and "logical cores" in readme and "load average at the end" in readme


# --- the study's MiniLM learning rate: chosen on validation by benchmarks/bert_settings.py --------------
REPO = Path(__file__).resolve().parent.parent
README = REPO / "README.md"
#: Where the benchmarks' and studies' findings are told, quoting their results files.
RESULTS_PAGE = REPO / "benchmarks" / "README.md"


def load_script(name: str) -> ModuleType:
    """A script of ``benchmarks/`` imported as a module (it is not a package)."""
    return load_benchmark(name)


def grid_lines(text: str) -> list[dict]:
    """The grid points a bert_settings results file records, one JSON line each."""
    return [json.loads(line) for line in text.splitlines() if line.startswith('{"train_size"')]


def point(size: int, lr: float, curve: list[float]) -> dict:
    return {"train_size": size, "learning_rate": lr, "val_acc_inst_by_epoch": curve}


def test_seed_study_trains_each_model_once_a_seed_and_summarises_the_spread(tmp_path):
    tiny = ExperimentSettings(train_sizes={"1": 24, "2": 16, "3": 12, "4": 48}, lstm_epochs=2, bert_epochs=1)
    rows = run_seed_study(tmp_path, tiny, seeds=(0, 1), models=("LSTM-M4",), log=lambda _: None)
    table = pd.read_csv(tmp_path / "seeds.csv")
    assert list(table.columns) == ["model", "seed", "train_instructions", "validation_acc_inst", "novel_acc_inst",
                                   "novel_acc_task", "train_seconds"]
    assert table.model.tolist() == ["LSTM-M4"] * 2 and table.seed.tolist() == [0, 1]
    assert (table.train_instructions == 48).all() and rows.equals(table)
    summary = seed_summary(table)
    assert summary.loc["LSTM-M4", ("seeds", "")] == 2
    assert summary.loc["LSTM-M4", ("novel_acc_inst", "mean")] == pytest.approx(table.novel_acc_inst.mean(), abs=1e-4)
    assert summary.loc["LSTM-M4", ("validation_acc_inst", "max")] == pytest.approx(table.validation_acc_inst.max(), abs=1e-4)
    assert "python -m drywall_lab experiment seeds" in (tmp_path / "seeds.md").read_text()


def test_a_run_of_some_models_keeps_the_other_models_rows_in_the_studys_order(tmp_path):
    path = tmp_path / "seeds.csv"
    row = dict(zip(SEED_COLUMNS, ["LSTM-M4", 0, 316, 0.9, 0.3, 0.7, 50.0]))
    assert merge_seed_rows(path, pd.DataFrame([row])).to_dict("records") == [row]  # no file yet: the new rows
    old = pd.DataFrame([{**row, "model": m, "seed": k} for m in ("BERT-M4", "LSTM-M1", "BERT-M2") for k in (0, 1)])
    old.to_csv(path, index=False)
    new = pd.DataFrame([{**row, "model": "BERT-M2", "seed": k, "validation_acc_inst": 0.5} for k in (0, 1, 2)])
    merged = merge_seed_rows(path, new)
    assert merged.model.tolist() == ["LSTM-M1"] * 2 + ["BERT-M2"] * 3 + ["BERT-M4"] * 2  # SEED_MODELS order
    assert (merged[merged.model == "BERT-M2"].validation_acc_inst == 0.5).all()  # the old BERT-M2 rows replaced
    with pytest.raises(ValueError, match="no such model in the study: BERT-M9"):
        run_seed_study(tmp_path, models=("BERT-M9",), log=lambda _: None)


def test_seed_zero_is_set_next_to_the_study_run(tmp_path):
    table = pd.DataFrame({"model": ["LSTM-M4", "LSTM-M4"], "seed": [0, 1], "validation_acc_inst": [0.93, 0.5],
                          "novel_acc_inst": [0.35, 0.1]})
    assert study_rerun_lines(table, tmp_path, 158, 200) == []  # no study files: nothing to compare
    pd.DataFrame({"model": ["LSTM-M4"], "Acc_inst": [0.93]}).to_csv(tmp_path / "table3_validation.csv", index=False)
    pd.DataFrame({"model": ["LSTM-M4"], "Acc_inst": [0.38]}).to_csv(tmp_path / "novel.csv", index=False)
    lines = study_rerun_lines(table, tmp_path, 158, 200)
    row = next(line for line in lines if line.startswith("- LSTM-M4"))
    assert "validation 93.00% (study 93.00%, +0)" in row
    assert "novel 35.00% (study 38.00%, -6)" in row  # 3 points of 200 instructions


def test_seed_summary_of_known_figures():
    table = pd.DataFrame({"model": ["A", "A", "A", "B"], "seed": [0, 1, 2, 0],
                          "validation_acc_inst": [0.9, 0.8, 1.0, 0.5], "novel_acc_inst": [0.5, 0.5, 0.5, 0.25]})
    summary = seed_summary(table)
    assert summary.loc["A", ("validation_acc_inst", "mean")] == pytest.approx(0.9)
    assert summary.loc["A", ("validation_acc_inst", "std")] == pytest.approx(0.1)
    assert summary.loc["A", ("novel_acc_inst", "std")] == 0 and summary.loc["B", ("seeds", "")] == 1
    assert list(summary.index) == ["A", "B"]


def test_the_study_uses_the_recorded_choice():
    """MINILM_LEARNING_RATE is what the rule picks on the grid recorded in benchmarks/results/bert_settings.md."""
    choose = load_script("bert_settings").choose_learning_rate
    grid = grid_lines((REPO / "benchmarks" / "results" / "bert_settings.md").read_text(encoding="utf-8"))
    assert len(grid) >= 2
    chosen, _ = choose(grid)
    assert chosen == MINILM_LEARNING_RATE
    settings = ExperimentSettings.paper()
    assert (settings.bert_learning_rate, settings.bert_epochs, settings.bert_warmup_ratio) == (
        MINILM_LEARNING_RATE, MINILM_EPOCHS, MINILM_WARMUP_RATIO)
    assert ExperimentSettings().bert_learning_rate == MINILM_LEARNING_RATE


def test_rule_reads_the_last_epochs_and_averages_over_sizes():
    choose = load_script("bert_settings").choose_learning_rate
    grid = [point(316, 1e-4, [0.9, 0.9, 0.5, 0.5, 0.5]), point(316, 3e-4, [0.1, 0.1, 0.6, 0.6, 0.6]),
            point(1268, 1e-4, [1.0, 1.0, 1.0]), point(1268, 3e-4, [0.0, 0.97, 0.97, 0.97])]
    chosen, table = choose(grid)  # 1e-4: (0.5 + 1.0) / 2 = 0.75; 3e-4: (0.6 + 0.97) / 2 = 0.785
    assert chosen == 3e-4
    assert table.loc[1e-4, "mean_over_sizes"] == pytest.approx(0.75)
    assert table.loc[3e-4, 316] == pytest.approx(0.6)
    assert choose(grid, last_epochs=5)[0] == 1e-4  # the whole curve: 1e-4 leads early


@settings(max_examples=30, deadline=None)
@given(curves=st.lists(st.lists(st.integers(0, 158).map(lambda k: k / 158), min_size=3, max_size=6),
                       min_size=6, max_size=6), order=st.randoms(use_true_random=False))
def test_rule_ignores_the_order_of_the_grid_and_breaks_ties_to_the_smaller_rate(curves, order):
    choose = load_script("bert_settings").choose_learning_rate
    cells = [(size, lr) for size in (316, 1268) for lr in (1e-4, 2e-4, 3e-4)]
    grid = [point(size, lr, curve) for (size, lr), curve in zip(cells, curves)]
    chosen, table = choose(grid)
    shuffled = list(grid)
    order.shuffle(shuffled)
    assert choose(shuffled)[0] == chosen
    best = table["mean_over_sizes"].max()
    tie = load_script("bert_settings").TIE  # means equal but for rounding (summed in another order) are a tie
    assert best - table.loc[chosen, "mean_over_sizes"] <= tie
    assert all(table.loc[lr, "mean_over_sizes"] < best - tie for lr in table.index if lr < chosen)
    # a smaller rate with the chosen one's curves ties with it, and wins the tie
    twin = [dict(p, learning_rate=5e-5) for p in grid if p["learning_rate"] == chosen]
    assert choose(grid + twin)[0] == 5e-5


def test_rule_refuses_an_incomplete_or_repeated_grid():
    choose = load_script("bert_settings").choose_learning_rate
    with pytest.raises(ValueError, match="no grid points"):
        choose([])
    with pytest.raises(ValueError, match=r"incomplete: no point for 0.0003 at 1268"):
        choose([point(316, 1e-4, [1.0]), point(316, 3e-4, [1.0]), point(1268, 1e-4, [1.0])])
    with pytest.raises(ValueError, match="twice"):
        choose([point(316, 1e-4, [1.0]), point(316, 1e-4, [0.5])])


def test_bert_settings_quick_reads_no_test_split_and_writes_its_results(tmp_path, monkeypatch, capsys):
    script = load_script("bert_settings")
    read = script.read_split
    asked = []

    def only_train_and_validation(split):
        asked.append(split)
        if split not in ("train", "validation"):
            raise AssertionError(f"bert_settings.py read the {split} split")
        return read(split)

    monkeypatch.setattr(script, "read_split", only_train_and_validation)
    out = tmp_path / "bert_settings.md"
    assert script.main(["--quick", "--out", str(out)]) == 0
    assert sorted(asked) == ["train", "validation"]
    text = out.read_text(encoding="utf-8")
    assert f"Written by `python benchmarks/bert_settings.py --quick --out {out}`" in text
    assert "- cpu: " in text and "- logical cores: " in text and re.search(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d UTC", text)
    assert f"Rule: {script.RULE}." in text
    grid = grid_lines(text)
    assert [(p["train_size"], p["learning_rate"]) for p in grid] == [(4, 1e-4), (4, 3e-4)]
    assert all("test" not in key for p in grid for key in p)
    assert f"Chosen learning rate: **{script.choose_learning_rate(grid)[0]:g}**" in text
    assert "chosen learning rate:" in capsys.readouterr().out


# --- the README quotes the files the committed commands wrote ----------------------------------------
def readme_text(page: Path = README) -> str:
    return " ".join(page.read_text(encoding="utf-8").split())


def test_results_page_quotes_the_study():
    """The results page's study table and training times are results/paper's figures."""
    paper = REPO / "results" / "paper"
    t3 = pd.read_csv(paper / "table3_validation.csv").set_index("model")
    m1 = pd.read_csv(paper / "m1_on_test.csv").set_index("model")
    novel = pd.read_csv(paper / "novel.csv").set_index("model")
    readme = readme_text(RESULTS_PAGE)
    pct = "{:.2%}".format
    assert f"| LSTM-M1 / BERT-M1, test Acc_inst | {pct(m1.Acc_inst['LSTM-M1'])} / {pct(m1.Acc_inst['BERT-M1'])} |" in readme
    assert (f"| LSTM-M1 / BERT-M1, validation Acc_inst | {pct(t3.Acc_inst['LSTM-M1'])} / "
            f"{pct(t3.Acc_inst['BERT-M1'])} |") in readme
    assert (f"| LSTM-M4 / BERT-M4 (316 instructions), validation Acc_inst | {pct(t3.Acc_inst['LSTM-M4'])} / "
            f"{pct(t3.Acc_inst['BERT-M4'])} |") in readme
    assert ("| LSTM-M1 / BERT-M1, novel Acc_inst (acc_task) | "
            + " / ".join(f"{novel.Acc_inst[m]:.1%} ({novel.acc_task[m]:.1%})" for m in ("LSTM-M1", "BERT-M1"))) in readme
    assert (f"BiLSTM-CRF {m1.train_seconds['LSTM-M1']:.0f} s (20 epochs), "
            f"MiniLM {m1.train_seconds['BERT-M1']:.0f} s (10 epochs)") in readme
    minutes = float(re.search(r"wall time ([\d.]+) min", (paper / "README.md").read_text(encoding="utf-8")).group(1))
    assert f"{minutes:.0f} min on the 2-core CPU" in readme


def test_results_page_quotes_the_field_ablation():
    """The README's 'What each step bought' figures are results/field/ablation.csv's."""
    ablation = pd.read_csv(REPO / "results" / "field" / "ablation.csv").set_index("model")
    readme = readme_text(RESULTS_PAGE)
    pct = "{:.1%}".format

    def pair(model: str, field_set: str, reading: str) -> str:
        row = ablation.loc[model]
        wrong = "best wrong" if reading == "best" else "decided wrong"
        return f"{pct(row[f'{field_set} {reading}'])} / {pct(row[f'{field_set} {wrong}'])}"

    start = ablation.loc["LSTM paper"]
    assert (f"data/field {pct(start['data/field best'])} right, {pct(start['data/field best wrong'])} wrong; "
            f"shared/field {pct(start['shared/field best'])} right, {pct(start['shared/field best wrong'])} wrong") in readme
    assert (f"{pair('LSTM+char field', 'data/field', 'best')} and {pair('LSTM+char field', 'shared/field', 'best')} "
            f"with the best reading, {pair('LSTM+char field', 'data/field', 'decided')} and "
            f"{pair('LSTM+char field', 'shared/field', 'decided')} through the decision layer") in readme
    assert (f"{pair('MiniLM field', 'data/field', 'decided')} and {pair('MiniLM field', 'shared/field', 'decided')} "
            "through the decision layer") in readme
    assert (f"({pct(start['data/field best'])} to {pct(start['data/field decided'])} on data/field)") in readme
    minutes = float(re.search(r"training time of every model: ([\d.]+) min",
                              (REPO / "results" / "field" / "README.md").read_text()).group(1))
    assert minutes == pytest.approx(ablation["train_seconds"].sum() / 60, abs=0.06)
    assert f"{minutes:.0f} min of training on the 2-core CPU" in readme


def test_the_committed_study_ran_with_the_papers_settings():
    text = (REPO / "results" / "paper" / "README.md").read_text(encoding="utf-8")
    recorded = json.loads(re.search(r"Settings: `(\{.*?\})`", text).group(1))
    assert recorded == json.loads(json.dumps(asdict(ExperimentSettings.paper())))


def scores_file() -> dict[str, dict[str, str]]:
    """drywall_lab/models/default_tagger/scores.txt: split -> {figure: value} as `make tagger-scores` writes it."""
    from drywall_lab.nlu import DEFAULT_TAGGER_DIR

    lines = (DEFAULT_TAGGER_DIR / "scores.txt").read_text(encoding="utf-8").splitlines()
    return {split: dict(pair.split("=", 1) for pair in rest.split()) for split, rest in (line.split(" ", 1) for line in lines)}


DEFAULT_TAGGER_ROWS = {"validation": "validation", "test": "test", "novel": "novel (withheld phrasings)",
                       "field-validation": "field-validation", "field-test": "field-test",
                       "field-novel": "field-novel (held-back families)",
                       "field-set": "field-set (hand-written, each step in its intended context)"}


def test_readme_quotes_the_default_tagger_scores():
    from drywall_lab.splits import EVALUATION_SPLITS

    scores = scores_file()
    assert set(scores) == set(EVALUATION_SPLITS) == set(DEFAULT_TAGGER_ROWS)
    readme = readme_text()
    for split, label in DEFAULT_TAGGER_ROWS.items():
        s = scores[split]
        row = (f"| {label} | {s['acc_word']} | {s['acc_inst']} | {s['acc_task']} | {s['acc_decided']} | "
               f"{s['wrong_action_rate']} |")
        assert row in readme, split


# --- the Makefile recipe that writes scores.txt ------------------------------------------------------
FAKE_PYTHON = """#!/bin/sh
# stands in for `python -m drywall_lab evaluate --tagger DIR --split SPLIT` (arguments $5 and $7)
[ -f "$5/tagger.json" ] || { echo "error: $5 is not a saved tagger" >&2; exit 2; }
echo "the tagger on the $7 split"
echo "acc_word=0.5000 acc_inst=0.2500 n_instructions=4"
echo "acc_word=0.9$7 acc_inst=0.8 n_instructions=4 acc_task=0.7"
"""


@pytest.fixture
def fake_bin(tmp_path) -> Path:
    """A bin directory whose `python` prints an evaluate-like report; the recipe's shell logic is what is tested."""
    if shutil.which("make") is None:
        pytest.skip("make is not installed")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "python").write_text(FAKE_PYTHON)
    (bin_dir / "python").chmod(0o755)
    (bin_dir / ".installed").touch()
    return bin_dir


def make_tagger_scores(bin_dir: Path, tagger_dir: Path) -> subprocess.CompletedProcess:
    return subprocess.run(["make", "--no-print-directory", "-o", f"{bin_dir}/.installed", "tagger-scores",
                           f"BIN={bin_dir}", f"TAGGER_DIR={tagger_dir}"], cwd=REPO, capture_output=True, text=True,
                          timeout=60)


def test_tagger_scores_recipe_writes_evaluates_last_line_per_split(fake_bin, tmp_path):
    from drywall_lab.splits import EVALUATION_SPLITS

    tagger = tmp_path / "tagger"
    tagger.mkdir()
    (tagger / "tagger.json").write_text("{}")
    result = make_tagger_scores(fake_bin, tagger)
    assert result.returncode == 0, result.stderr
    assert (tagger / "scores.txt").read_text().splitlines() == [
        f"{split} acc_word=0.9{split} acc_inst=0.8 n_instructions=4 acc_task=0.7" for split in EVALUATION_SPLITS]
    assert sorted(p.name for p in tagger.iterdir()) == ["scores.txt", "tagger.json"]


def test_tagger_scores_recipe_keeps_the_old_scores_when_evaluate_fails(fake_bin, tmp_path):
    tagger = tmp_path / "not-a-tagger"
    tagger.mkdir()
    (tagger / "scores.txt").write_text("validation acc_word=1.0000\n")
    result = make_tagger_scores(fake_bin, tagger)
    assert result.returncode != 0
    assert "not a saved tagger" in result.stderr
    assert (tagger / "scores.txt").read_text() == "validation acc_word=1.0000\n"
    assert sorted(p.name for p in tagger.iterdir()) == ["scores.txt"]  # no temporary file left
