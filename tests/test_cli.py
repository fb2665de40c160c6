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


# --- interpret and run (information mapping, spec section 6) ------------------------------------------
def test_interpret_tagged_prints_trace_command_and_row(capsys):
    code = main(["interpret", "--tagged", "Pick up the full-size/dim drywall and put it on stud 500100/ID_stud."])
    out = capsys.readouterr().out
    assert code == 0
    assert "full-size/dim" in out and "500100/ID_stud" in out
    assert "T3 size word or same as before" in out
    assert "command: panel 500320 on stud 500100" in out
    assert "new action history row:" in out and "-0.01905" in out


def test_interpret_records_into_a_history_file(tmp_path, capsys):
    history = tmp_path / "wall.csv"
    assert main(["interpret", "--tagged", "the 2/width by 8/length panel on stud 500100/ID_stud",
                 "--history", str(history), "--record"]) == 0
    assert main(["interpret", "--tagged", "the same/dim size as the previous/dim one on the stud two/St_loc1 "
                 "to/St_loc1 the/St_loc1 right/St_loc1 of the previous/St_loc2 one", "--history", str(history),
                 "--record"]) == 0
    out = capsys.readouterr().out
    assert "panel 500311 on stud 500102" in out
    text = history.read_text()
    # a refusal leaves the file exactly as it was
    assert main(["interpret", "--tagged", "panel 500321/ID_wall on stud 500108/ID_stud", "--history", str(history),
                 "--record"]) == 1
    out = capsys.readouterr().out
    assert "refused (already_installed)" in out and "unchanged" in out
    assert history.read_text() == text
    assert len(text.strip().splitlines()) == 3  # header and two rows


def test_interpret_bad_history_file_is_a_clear_error(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("stud_id,drywall_id\n500100,500320\n")
    assert main(["interpret", "--tagged", "panel 500320/ID_wall on stud 500100/ID_stud", "--history", str(bad)]) == 2
    assert "error:" in capsys.readouterr().err


def test_run_with_a_missing_or_bad_file(tmp_path, capsys):
    assert main(["run", str(tmp_path / "missing.jsonl")]) == 2
    assert "no episodes file" in capsys.readouterr().err
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"id": "a", "instructions": ["x"]}\n{"id": "b"}\n')
    assert main(["run", str(bad)]) == 2
    assert "line 2" in capsys.readouterr().err
