"""The command line: python -m drywall_lab ..."""
from __future__ import annotations

import filecmp
import json
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


def test_run_with_the_default_tagger_follows_the_contract(tmp_path):
    """Spec section 6, from outside: a subprocess, JSON lines in and out, the default tagger."""
    episodes = tmp_path / "episodes.jsonl"
    episodes.write_text(
        json.dumps({"id": "e1", "instructions": [
            "Pick up the full-size drywall and put it on stud 500100.",
            "Take panel 500300 and put it on stud 500104.",
            "Grab the panel that is two feet wide and put it on the stud three to the right of the previous stud.",
            "",
        ]}) + "\n" + json.dumps({"id": 2, "instructions": ["Put the 4 by 6 panel on stud 500112."]}) + "\n"
    )
    out = subprocess.run([sys.executable, "-m", "drywall_lab", "run", str(episodes)], capture_output=True, text=True,
                         check=True).stdout
    records = [json.loads(line) for line in out.splitlines()]
    assert [(r["episode"], r["step"]) for r in records] == [("e1", 0), ("e1", 1), ("e1", 2), ("e1", 3), (2, 0)]
    for r in records:
        assert list(r) == ["episode", "step", "words", "tags", "command", "refusal"]
        assert len(r["words"]) == len(r["tags"])
    assert records[0]["command"] == {"drywall_id": "500320", "stud_id": "500100", "placement": "vertical_left"}
    assert records[0]["tags"][records[0]["words"].index("500100")] == "ID_stud"
    assert records[1]["command"] is None and "500300 is under 500310" in records[1]["refusal"]
    # "previous" is the last accepted command (stud 500100), not the refused one
    assert records[2]["command"] == {"drywall_id": "500321", "stud_id": "500103", "placement": "vertical_left"}
    assert records[3]["words"] == [] and records[3]["command"] is None and "empty" in records[3]["refusal"]
    assert records[4]["command"] is None and "past the wall's last stud" in records[4]["refusal"]


def test_run_with_a_corrupt_tagger_directory(tmp_path, capsys):
    episodes = tmp_path / "episodes.jsonl"
    episodes.write_text('{"id": "a", "instructions": ["put it on stud 500100"]}\n')
    broken = tmp_path / "tagger"
    broken.mkdir()
    (broken / "tagger.json").write_text("{not json")
    assert main(["run", str(episodes), "--tagger", str(broken)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and "tagger.json" in err


def test_evaluate_reports_task_accuracy_through_the_rules(capsys):
    """acc_task puts the tagger's tags through the IM rules: with tags that are all O, only the
    instructions meant to be refused as undetermined come out right."""
    from drywall_lab.im import task_accuracy

    assert main(["evaluate", "--split", "validation"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    figures = dict(item.split("=") for item in last.split())
    assert set(figures) == {"acc_word", "acc_inst", "n_instructions", "acc_task"}
    # an instruction with every tag right gets its intended outcome (gold tags give 100%), so acc_task >= acc_inst
    assert float(figures["acc_task"]) >= float(figures["acc_inst"])
    rows = read_split("validation")
    undetermined = sum(r["expected"]["refusal"] == "undetermined" for r in rows) / len(rows)
    assert task_accuracy(rows, [["O"] * len(r["words"]) for r in rows]) == undetermined
