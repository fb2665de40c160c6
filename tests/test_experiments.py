"""The paper's NLU study (drywall_lab/nlu/experiments.py), on tiny settings: every table and figure is written."""
from __future__ import annotations

import pandas as pd

from drywall_lab.nlu.experiments import PAPER_TABLE3, ExperimentSettings, run_paper_experiment


def test_tiny_study_writes_every_table(tmp_path):
    settings = ExperimentSettings(train_sizes={"1": 24, "2": 16, "3": 12, "4": 8}, lstm_epochs=1, bert_epochs=1)
    tables = run_paper_experiment(tmp_path, settings, log=lambda _: None)
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
