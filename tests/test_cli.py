"""The command line: python -m drywall_lab ..."""
from __future__ import annotations

import filecmp
import json
import random
import re
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from drywall_lab.__main__ import main
from drywall_lab.corpus import CORPUS_DIR, SPLIT_SIZES, TAGS, read_split, to_conll, tokenize
from drywall_lab.corpus.io import MARKS_AFTER, MARKS_BEFORE, UNSPACED


def test_corpus_stats_agrees_with_the_paper(capsys):
    assert main(["corpus", "stats"]) == 0
    out = capsys.readouterr().out
    assert "Words per tag (Table 2)" in out
    assert "All figures within the project's bounds." in out


def test_corpus_generate_rewrites_the_committed_files(regenerated_corpus):
    """``corpus generate`` (run once for the session, tests/conftest.py): the committed files, the count of
    each split, and no file left open."""
    assert regenerated_corpus.exit_code == 0
    assert regenerated_corpus.resource_warnings == []
    for split in ("train", "validation", "test", "novel"):
        fresh = regenerated_corpus.out_dir / f"{split}.jsonl"
        assert filecmp.cmp(fresh, CORPUS_DIR / f"{split}.jsonl", shallow=False), split
        assert re.search(rf"^{split} +{SPLIT_SIZES[split]} instructions -> {re.escape(str(fresh))}$",
                         regenerated_corpus.stdout, re.MULTILINE), regenerated_corpus.stdout


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


def test_module_runs_as_a_program(tmp_path):
    """``python -m drywall_lab``: the help lists every command, and the exit status reaches the shell."""
    result = subprocess.run([sys.executable, "-m", "drywall_lab", "--help"], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 0, result.stderr
    for command in ("corpus", "score", "train", "evaluate", "experiment", "interpret", "run", "demo"):
        assert re.search(rf"^ +{command} +\w", result.stdout, re.MULTILINE), command
    bad = tmp_path / "bad.jsonl"
    bad.write_bytes(b'{"id": "a", "instructions": ["x"]}\n{"id": "b", "instructions": ["\xff"]}\n')
    result = subprocess.run([sys.executable, "-m", "drywall_lab", "run", str(bad)], capture_output=True, text=True,
                            timeout=120)
    assert (result.returncode, result.stdout) == (2, "")
    assert result.stderr == f"error: {bad}, line 2: not valid UTF-8 text (byte 0xff at position 31 of the line: " \
                            "invalid start byte)\n"


def test_demo_prints_each_part_of_the_course(capsys):
    """``demo``: the site, tagged instructions, Table 2, a student's agreement, the tagger's scores on the
    test split and the paper's layouts, each step with the outcome the layout expects (Figs. 15-18)."""
    from drywall_lab.pipeline import paper_layouts

    assert main(["demo"]) == 0
    out = capsys.readouterr().out
    sections = re.split(r"^== (.+) ==$", out, flags=re.MULTILINE)[1:]
    parts = dict(zip(sections[::2], sections[1::2]))
    assert list(parts) == [
        "The site (spec section 1)", "Three training instructions with their tags",
        "The corpus against the paper's Table 2", "A student's practice annotation scored against the key",
        next(k for k in parts if k.startswith("The default tagger (bilstm-crf")),
        "The paper's layouts (Figs. 15-18): instruction -> tags -> command",
    ]
    site = parts["The site (spec section 1)"]
    assert len(re.findall(r"^ *5001\d\d ", site, re.MULTILINE)) == 13  # the studs
    assert len(re.findall(r"^ *5003\d\d ", site, re.MULTILINE)) == 9  # the panels
    train = read_split("train")[:3]
    for row in train:
        assert row["text"] in parts["Three training instructions with their tags"]
    assert "Words per tag (Table 2)" in parts["The corpus against the paper's Table 2"]
    assert "word accuracy" in parts["A student's practice annotation scored against the key"]
    tagger_part = next(v for k, v in parts.items() if k.startswith("The default tagger"))
    figures = dict(item.split("=") for item in tagger_part.split())
    assert set(figures) == {"acc_word", "acc_inst", "acc_task", "n_instructions"}
    assert int(figures["n_instructions"]) == SPLIT_SIZES["test"]
    assert all(0 <= float(figures[k]) <= 1 for k in ("acc_word", "acc_inst", "acc_task"))
    outcomes = re.findall(r"^     -> (?:panel (\d+) on stud (\d+)|refused \((\w+)\))", out, re.MULTILINE)
    expected = [e for layout in paper_layouts() for e in layout["expected"]]
    assert [(e.get("drywall_id", ""), e.get("stud_id", ""), e.get("refusal", "")) for e in expected] == outcomes


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
    assert set(figures) == {"acc_word", "acc_inst", "n_instructions", "acc_task", "acc_decided", "wrong_action_rate",
                            "over_refusal_rate", "coverage"}
    # an instruction with every tag right gets its intended outcome (gold tags give 100%), so acc_task >= acc_inst
    assert float(figures["acc_task"]) >= float(figures["acc_inst"])
    # the decision layer's three outcomes share out the instructions
    shares = [float(figures[k]) for k in ("acc_decided", "wrong_action_rate", "over_refusal_rate")]
    assert sum(shares) == pytest.approx(1.0, abs=2e-4)
    assert main(["evaluate", "--tagger", "gold", "--split", "field-set"]) == 0
    assert capsys.readouterr().out.strip().splitlines()[-1].endswith("acc_task=1.0000")
    rows = read_split("validation")
    undetermined = sum(r["expected"]["refusal"] == "undetermined" for r in rows) / len(rows)
    assert task_accuracy(rows, [["O"] * len(r["words"]) for r in rows]) == undetermined


# --- interpret --history / --record: never a silent empty wall, nothing recorded lost -----------------------------
FIRST = "the 2/width by 8/length panel on stud 500100/ID_stud"
SECOND = "panel 500320/ID_wall on stud 500104/ID_stud"


def test_record_without_history_is_an_error(capsys):
    assert main(["interpret", "--tagged", FIRST, "--record"]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == "error: --record needs --history FILE: the action history CSV to record the command in\n"


def test_a_missing_history_file_is_an_error_unless_recording(tmp_path, capsys):
    """A mistyped --history path must not silently start from an empty wall; with --record it starts one."""
    history = tmp_path / "wall.csv"
    assert main(["interpret", "--tagged", FIRST, "--history", str(history)]) == 2
    assert capsys.readouterr().err == (f"error: no action history at {history} "
                                       "(to start a new wall in that file, add --record)\n")
    assert not history.exists()
    assert main(["interpret", "--tagged", FIRST, "--history", str(history), "--record"]) == 0
    assert f"recorded: {history} now has 1 row(s)" in capsys.readouterr().out
    assert main(["interpret", "--tagged", SECOND, "--history", str(history)]) == 0  # read, not recorded
    assert "history: 1 accepted command(s) before this one" in capsys.readouterr().out
    assert len(history.read_text().splitlines()) == 2


def test_recording_a_refusal_in_a_new_file_starts_an_empty_wall(tmp_path, capsys):
    history = tmp_path / "new" / "wall.csv"
    assert main(["interpret", "--tagged", "panel 500300/ID_wall on stud 500100/ID_stud", "--history", str(history),
                 "--record"]) == 1
    assert "refused (not_on_top)" in capsys.readouterr().out
    assert history.read_text().splitlines() == ["stud_id,installed_x_left,installed_x_right,left_cent,ver_hor,"
                                                "top_btm,drywall_id,w,l"]
    assert main(["interpret", "--tagged", FIRST, "--history", str(history), "--record"]) == 0
    assert len(history.read_text().splitlines()) == 2


def test_a_folder_as_history_is_a_clear_error(tmp_path, capsys):
    for extra in ([], ["--record"]):
        assert main(["interpret", "--tagged", FIRST, "--history", str(tmp_path), *extra]) == 2
        assert capsys.readouterr().err == f"error: --history {tmp_path} is a folder, not an action history CSV file\n"


def test_a_history_that_cannot_be_used_is_a_clear_error(tmp_path, capsys):
    """Any OSError ends in a message naming the path, never a traceback."""
    blocker = tmp_path / "site"
    blocker.write_text("not a folder")
    history = blocker / "walls" / "wall.csv"
    assert main(["interpret", "--tagged", FIRST, "--history", str(history), "--record"]) == 2
    assert capsys.readouterr().err == f"error: --history {history} cannot be created: {blocker} is a file, not a folder\n"
    assert blocker.read_text() == "not a folder"
    too_long = tmp_path / ("w" * 300 + ".csv")
    for extra in ([], ["--record"]):
        assert main(["interpret", "--tagged", FIRST, "--history", str(too_long), *extra]) == 2
        assert capsys.readouterr().err == f"error: {too_long}: File name too long\n"


def test_a_failed_write_leaves_the_recorded_history_as_it_was(tmp_path, capsys, monkeypatch):
    """The history is written whole or not at all (a temporary file, then os.replace)."""
    from drywall_lab.im import ActionHistory

    history = tmp_path / "wall.csv"
    assert main(["interpret", "--tagged", FIRST, "--history", str(history), "--record"]) == 0
    recorded = history.read_bytes()

    def full_disk(self, path):
        with open(path, "w") as f:
            f.write("stud_id,ins")  # a partial write, then the disk is full
        raise OSError(28, "No space left on device", str(path))

    monkeypatch.setattr(ActionHistory, "to_csv", full_disk)
    assert main(["interpret", "--tagged", SECOND, "--history", str(history), "--record"]) == 2
    assert "No space left on device" in capsys.readouterr().err
    assert history.read_bytes() == recorded
    assert sorted(p.name for p in tmp_path.iterdir()) == ["wall.csv"]  # no temporary file left behind


def test_unreadable_paths_in_other_commands_are_clear_errors(tmp_path, capsys):
    folder = tmp_path / "folder"
    folder.mkdir()
    assert main(["score", str(folder), str(folder)]) == 2
    assert capsys.readouterr().err == f"error: {folder}: Is a directory\n"
    assert main(["corpus", "conll", "--split", "test", "--out", str(folder)]) == 2
    assert capsys.readouterr().err == f"error: {folder}: Is a directory\n"
    assert main(["run", str(folder)]) == 2
    assert capsys.readouterr().err == f"error: {folder} is a folder, not an episodes file\n"


# --- run: bad bytes name their line; any text gives one valid record an instruction (spec section 6) ------------
def test_run_accepts_a_byte_order_mark(tmp_path, capsys):
    episodes = tmp_path / "episodes.jsonl"
    episodes.write_bytes(b'\xef\xbb\xbf{"id": "a", "instructions": ["Put panel 500320 on stud 500100."]}\n')
    assert main(["run", str(episodes)]) == 0
    [record] = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert record["command"] == {"drywall_id": "500320", "stud_id": "500100", "placement": "vertical_left"}


@pytest.mark.parametrize("line, message", [
    (b'{"id": "b", "instructions": ["caf\xe9"]}', "line 3: not valid UTF-8 text (byte 0xe9 at position 34"),
    (b'{"id": "b", "instructions": ["x"]', "line 3: not a JSON object (Expecting ',' delimiter at position 34)"),
    (b'{"id": "b", "instructions": ["\\udc80"]}', "line 3: instruction 1 is not Unicode text"),
])
def test_run_names_the_line_it_cannot_read(tmp_path, capsys, line, message):
    episodes = tmp_path / "episodes.jsonl"
    episodes.write_bytes(b'{"id": "a", "instructions": ["x"]}\n\n' + line + b"\n")
    assert main(["run", str(episodes)]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.startswith(f"error: {episodes}, line 3: ") and message in captured.err


def check_run_records(records: list[dict], episodes: list[dict]) -> None:
    """Spec section 6: one record an instruction, in order, each well formed; a command only without a refusal."""
    expected_keys = [(e["id"], step) for e in episodes for step in range(len(e["instructions"]))]
    assert [(r["episode"], r["step"]) for r in records] == expected_keys
    texts = [text for e in episodes for text in e["instructions"]]
    for record, text in zip(records, texts):
        assert list(record) == ["episode", "step", "words", "tags", "command", "refusal"]
        # the worker's own words: the text's words (``tokenize``), a script written without spaces cut into words and
        # its marks ("，") taken off (``normalise.split_unspaced``); every character of a word kept as typed
        words = tokenize(text)
        if UNSPACED.search(text) or any(mark in text for mark in MARKS_AFTER + MARKS_BEFORE):
            assert re.sub(r"[\W_]", "", "".join(record["words"])) == re.sub(r"[\W_]", "", "".join(words))
        else:
            assert record["words"] == words
        assert isinstance(record["tags"], list) and len(record["tags"]) == len(record["words"])
        assert set(record["tags"]) <= set(TAGS)
        if record["command"] is None:
            assert isinstance(record["refusal"], str) and record["refusal"].strip()
        else:
            assert record["refusal"] is None
            assert list(record["command"]) == ["drywall_id", "stud_id", "placement"]
            assert all(isinstance(v, str) for v in record["command"].values())


def run_in_process(episodes: list[dict], path, capsys) -> list[dict]:
    path.write_text("".join(json.dumps(e, ensure_ascii=False) + "\n" for e in episodes), encoding="utf-8")
    capsys.readouterr()
    code = main(["run", str(path)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert captured.err == ""
    return [json.loads(line) for line in captured.out.split("\n")[:-1]]  # JSON lines: split at "\n" only


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(instructions=st.lists(st.text(max_size=5000), max_size=3))
@example(instructions=[""]).via("the empty instruction")
@example(instructions=["\x00", "\u2028", "\r", "\x85\x1c\x1d\x1e\x1f\x0b\x0c"]).via("characters that split lines")
@example(instructions=["\ufeff put panel 500320 on stud 500100", "\u202e001005 duts no 023005 lenap"])
@example(instructions=["Put panel 500320 on stud 500100."] * 2).via("the second is refused: already installed")
def test_run_gives_one_valid_record_for_any_instruction_text(tmp_path_factory, capsys, instructions):
    episodes = [{"id": "any", "instructions": instructions}, {"id": 7, "instructions": instructions[:1]}]
    path = tmp_path_factory.mktemp("run") / "episodes.jsonl"
    check_run_records(run_in_process(episodes, path, capsys), episodes)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.one_of(
    st.binary(max_size=2000),
    st.lists(st.one_of(st.binary(max_size=60), st.sampled_from([
        b'{"id": "a", "instructions": ["put it on stud 500100"]}', b"\xef\xbb\xbf", b"\xff", b"\xed\xa0\x80",
        b"\\ud800", b'"', b"{", b"}", b"[", b"\r", b" ", b"\x00"])), max_size=12).map(b"\n".join),
))
@example(data=b"").via("an empty file")
@example(data=b"\xef\xbb\xbf").via("only a byte-order mark")
@example(data=b'{"id": "a", "instructions": ["\\ud800"]}').via("a lone surrogate escape")
@example(data=b'\xef\xbb\xbf{"id": "a", "instructions": []}\n{"id": "b", "instructions": ["\xff"]}')
def test_run_on_any_bytes_exits_cleanly_and_names_the_line(tmp_path_factory, capsys, data):
    path = tmp_path_factory.mktemp("bytes") / "episodes.jsonl"
    path.write_bytes(data)
    capsys.readouterr()
    code = main(["run", str(path)])
    captured = capsys.readouterr()
    assert code in (0, 2)
    if code == 2:
        assert captured.out == ""
        line = re.fullmatch(rf"error: {re.escape(str(path))}, line (\d+): [^\n]+\n", captured.err)
        assert line, captured.err
        assert 1 <= int(line.group(1)) <= data.count(b"\n") + 1
    else:
        assert captured.err == ""
        for record in captured.out.split("\n")[:-1]:
            json.loads(record)


def test_run_on_150_random_unicode_instructions(tmp_path, capsys):
    """The outside check of issue 10: 150 random Unicode instructions in one episode, no command that comes
    with a refusal, 150 valid records."""
    rng = random.Random(10)
    planes = [(0x20, 0x7E), (0x00, 0x1F), (0xA0, 0x24F), (0x370, 0x3FF), (0x400, 0x4FF), (0x2000, 0x206F),
              (0x3040, 0x30FF), (0x4E00, 0x9FFF), (0xFE00, 0xFFFD), (0x1F300, 0x1FAFF), (0xE0000, 0xE007F)]
    words = ["put", "panel", "stud", "500100", "500320", "left", "third", "from", "the", "4", "by", "8"]

    def instruction() -> str:
        pieces = []
        for _ in range(rng.randint(0, 40)):
            if rng.random() < 0.3:
                pieces.append(rng.choice(words))
            else:
                low, high = rng.choice(planes)
                pieces.append("".join(chr(rng.randint(low, high)) for _ in range(rng.randint(1, 8))))
        return rng.choice([" ", "  ", "\t", "\u3000"]).join(pieces)

    episodes = [{"id": "random", "instructions": [instruction() for _ in range(150)]}]
    records = run_in_process(episodes, tmp_path / "episodes.jsonl", capsys)
    assert len(records) == 150
    check_run_records(records, episodes)


def test_run_writes_json_escapes_where_the_output_is_not_utf8(tmp_path, monkeypatch, capsys):
    import io

    episodes = tmp_path / "episodes.jsonl"
    episodes.write_text(json.dumps({"id": "é", "instructions": ["Put panel 500320 on stud 500100 ✓ café"]}) + "\n")
    ascii_out = io.TextIOWrapper(io.BytesIO(), encoding="ascii")
    monkeypatch.setattr(sys, "stdout", ascii_out)
    assert main(["run", str(episodes)]) == 0
    ascii_out.flush()
    [record] = [json.loads(line) for line in ascii_out.buffer.getvalue().decode("ascii").splitlines()]
    assert record["episode"] == "é" and record["words"][-2:] == ["✓", "café"]


def test_run_into_a_closed_pipe_is_a_message_not_a_traceback(tmp_path, monkeypatch, capsys):
    import io

    class ClosedPipe(io.StringIO):
        encoding = "utf-8"

        def write(self, text):
            raise BrokenPipeError(32, "Broken pipe")

    episodes = tmp_path / "episodes.jsonl"
    episodes.write_text('{"id": "a", "instructions": ["put it on stud 500100"]}\n')
    monkeypatch.setattr(sys, "stdout", ClosedPipe())
    assert main(["run", str(episodes)]) == 2
    assert capsys.readouterr().err == "error: the output was closed before everything was written\n"


def test_interpret_text_that_is_not_utf8_is_a_clear_error(capsys):
    """Bytes that are not UTF-8 on the command line reach argv as lone surrogates (PEP 383)."""
    assert main(["interpret", "--tagged", "put it on stud 500100/ID_stud \udcff"]) == 2
    captured = capsys.readouterr()
    assert (captured.out, captured.err) == ("", "error: the instruction is not valid UTF-8 text (at character 31)\n")
