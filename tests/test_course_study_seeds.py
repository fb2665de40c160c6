"""Tests of the spread over seeds (``drywall_lab.course.study.seed_spread`` and ``seed_finding``), read by
notebooks 02 and 03 from ``results/paper/seeds.csv``."""
from __future__ import annotations

import pandas as pd
import pytest

from drywall_lab.course.common import percent_table
from drywall_lab.course.study import seed_finding, seed_share_columns, seed_sizes_finding, seed_spread

COLUMNS = ["model", "seed", "train_instructions", "validation_acc_inst", "novel_acc_inst", "novel_acc_task",
           "train_seconds"]


def _seeds(rows: list[tuple]) -> pd.DataFrame:
    return pd.DataFrame(rows, columns=COLUMNS)


@pytest.fixture
def seeds() -> pd.DataFrame:
    """Three seeds of LSTM-M1, LSTM-M4 and BERT-M4: BERT-M4 above LSTM-M4 on every validation seed, the two
    overlapping on the novel split."""
    return _seeds([
        ("LSTM-M1", 0, 1268, 1.00, 0.50, 0.80, 95.0), ("LSTM-M1", 1, 1268, 0.99, 0.52, 0.81, 96.0),
        ("LSTM-M1", 2, 1268, 1.00, 0.48, 0.79, 94.0),
        ("LSTM-M4", 0, 316, 0.90, 0.30, 0.70, 50.0), ("LSTM-M4", 1, 316, 0.92, 0.40, 0.72, 51.0),
        ("LSTM-M4", 2, 316, 0.94, 0.35, 0.71, 52.0),
        ("BERT-M4", 0, 316, 0.96, 0.33, 0.75, 130.0), ("BERT-M4", 1, 316, 0.98, 0.37, 0.74, 131.0),
        ("BERT-M4", 2, 316, 0.97, 0.38, 0.76, 129.0),
    ])


def test_one_row_a_model_in_the_files_order_with_its_statistics(seeds):
    spread = seed_spread(seeds)
    assert list(spread.index) == ["LSTM-M1", "LSTM-M4", "BERT-M4"]
    assert list(spread["seeds"]) == [3, 3, 3]
    assert list(spread["training instructions"]) == [1268, 316, 316]
    row = spread.loc["LSTM-M4"]
    assert row["validation mean"] == pytest.approx(0.92)
    assert row["validation sd"] == pytest.approx(0.02)  # over the seeds, n - 1: sqrt((0.02² + 0 + 0.02²) / 2)
    assert (row["validation min"], row["validation max"]) == pytest.approx((0.90, 0.94))
    assert row["novel mean"] == pytest.approx(0.35)
    assert row["novel sd"] == pytest.approx(0.05)
    assert (row["novel min"], row["novel max"]) == pytest.approx((0.30, 0.40))
    assert seed_share_columns(spread) == [f"{split} {s}" for split in ("validation", "novel")
                                          for s in ("mean", "sd", "min", "max")]
    shown = percent_table(spread, seed_share_columns(spread))
    assert shown.loc["LSTM-M4", "validation mean"] == "92.00%" and shown.loc["LSTM-M4", "seeds"] == 3


def test_the_finding_states_the_m4_comparison_from_the_table(seeds):
    text = seed_finding(seed_spread(seeds))
    assert text.startswith("Over 3 seeds (316 training instructions each), mean ± standard deviation")
    assert "LSTM-M4 92.00% ± 2.00% (90.00% to 94.00%) on the validation split" in text
    assert "BERT-M4 97.00% ± 1.00% (96.00% to 98.00%)" in text
    assert ("On the validation split BERT-M4 is ahead by 5.00 points on the mean, and every seed of BERT-M4 is "
            "above every seed of LSTM-M4") in text
    assert "on the novel split BERT-M4 is ahead by 1.00 points on the mean, but the seeds' ranges overlap" in text


def test_the_finding_follows_the_numbers_when_the_order_turns(seeds):
    turned = seeds.copy()
    bert = turned["model"] == "BERT-M4"
    turned.loc[bert, "validation_acc_inst"] -= 0.10  # BERT-M4 now 0.86-0.88, below every LSTM-M4 seed
    text = seed_finding(seed_spread(turned))
    assert "On the validation split LSTM-M4 is ahead by 5.00 points" in text
    assert "every seed of LSTM-M4 is above every seed of BERT-M4" in text


def test_one_seed_has_no_spread_and_a_missing_model_is_said():
    spread = seed_spread(_seeds([("LSTM-M4", 0, 316, 0.9, 0.3, 0.7, 50.0), ("BERT-M4", 0, 316, 0.95, 0.3, 0.7, 130.0)]))
    assert spread.loc["LSTM-M4", "seeds"] == 1 and pd.isna(spread.loc["LSTM-M4", "validation sd"])
    text = seed_finding(spread)
    assert "LSTM-M4 90.00% (one seed: no spread)" in text and "the two means are equal" in text
    assert seed_finding(spread, ("LSTM-M3", "BERT-M4")) == "The seed table has no row for LSTM-M3."


def test_bad_tables_are_refused(seeds, tmp_path):
    with pytest.raises(ValueError, match="lacks the columns"):
        seed_spread(seeds.drop(columns="novel_acc_inst"))
    with pytest.raises(ValueError, match="no rows"):
        seed_spread(seeds.iloc[:0])
    with pytest.raises(ValueError, match="a model and seed twice"):
        seed_spread(pd.concat([seeds, seeds.iloc[:1]]))
    changed = seeds.copy()
    changed.loc[0, "train_instructions"] = 948
    with pytest.raises(ValueError, match="different numbers of instructions"):
        seed_spread(changed)
    with pytest.raises(FileNotFoundError, match="experiment seeds"):
        seed_spread(study_dir=tmp_path)


def test_reads_seeds_csv_from_the_study_folder(seeds, tmp_path):
    seeds.to_csv(tmp_path / "seeds.csv", index=False)
    pd.testing.assert_frame_equal(seed_spread(study_dir=tmp_path), seed_spread(seeds))


def test_the_study_model_of_a_size_and_its_rows():
    """What notebooks 02 and 03 set next to their demonstration run: the study's model of the same size, and one
    tagger's rows of the committed study."""
    from drywall_lab.course.study import TABLE3_COLUMNS, study_model, study_rows, study_settings

    sizes = {"1": 1268, "2": 948, "3": 632, "4": 316}
    assert study_model("LSTM", 316, sizes) == "LSTM-M4" and study_model("BERT", 1268, sizes) == "BERT-M1"
    with pytest.raises(ValueError, match="not on 300"):
        study_model("LSTM", 300, sizes)
    with pytest.raises(ValueError, match="not one of the study's taggers"):
        study_model("CRF", 316, sizes)
    assert study_model("LSTM", 316, study_settings()["train_sizes"]) == "LSTM-M4"
    lstm = study_rows("table3_validation", "LSTM")
    assert list(lstm.index) == ["LSTM-M1", "LSTM-M2", "LSTM-M3", "LSTM-M4"] and list(lstm.columns) == TABLE3_COLUMNS
    assert list(study_rows("m1_on_test", "BERT").index) == ["BERT-M1"]


def test_each_size_with_both_models_is_compared_over_the_seeds(seeds):
    text = seed_sizes_finding(seed_spread(seeds))
    assert text.splitlines() == [text]  # only M4 has both models in the fixture: one sentence
    assert text.startswith("M4 (316 training instructions): LSTM-M4 92.00% ± 2.00% (90.00% to 94.00%), BERT-M4 97.00%")
    assert "BERT-M4 is ahead by 5.00 points on the mean, and every seed of BERT-M4 is above every seed of LSTM-M4" in text
    novel = seed_sizes_finding(seed_spread(seeds), "novel")
    assert "the seeds' ranges overlap" in novel
    assert seed_sizes_finding(seed_spread(seeds[seeds.model != "BERT-M4"])) == \
        "The seed table has no size with both models."
