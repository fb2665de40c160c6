"""The command line: python -m drywall_lab ..."""
from __future__ import annotations

import filecmp
import subprocess
import sys

from drywall_lab.__main__ import main
from drywall_lab.corpus import CORPUS_DIR, read_split, to_conll


def test_corpus_stats_agrees_with_the_paper(capsys):
    assert main(["corpus", "stats"]) == 0
    out = capsys.readouterr().out
    assert "Words per tag (Table 2)" in out
    assert "All figures within the project's bounds." in out


def test_corpus_generate_rewrites_the_committed_files(tmp_path, capsys):
    assert main(["corpus", "generate", "--out", str(tmp_path)]) == 0
    for split in ("train", "validation", "test", "novel"):
        assert filecmp.cmp(tmp_path / f"{split}.jsonl", CORPUS_DIR / f"{split}.jsonl", shallow=False), split


def test_corpus_conll_export(tmp_path, capsys):
    out = tmp_path / "test.conll"
    assert main(["corpus", "conll", "--split", "test", "--out", str(out)]) == 0
    assert out.read_text() == to_conll(read_split("test"))


def test_score_reports_agreement(tmp_path, capsys):
    rows = read_split("validation")[:5]
    gold = tmp_path / "gold.conll"
    to_conll(rows, gold)
    wrong = [dict(r, tags=["O"] * len(r["tags"])) for r in rows]
    answer = tmp_path / "answer.conll"
    to_conll(wrong, answer)
    assert main(["score", str(gold), str(gold)]) == 0
    assert "word accuracy 100.00%" in capsys.readouterr().out
    assert main(["score", str(gold), str(answer)]) == 0
    assert "instruction accuracy 0.00%" in capsys.readouterr().out


def test_score_with_a_missing_file_is_a_clear_error(tmp_path, capsys):
    assert main(["score", str(tmp_path / "nope.conll"), str(tmp_path / "nope.conll")]) == 2
    assert "error:" in capsys.readouterr().err


def test_module_runs_as_a_program():
    result = subprocess.run([sys.executable, "-m", "drywall_lab", "demo"], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert "The corpus against the paper's Table 2" in result.stdout
