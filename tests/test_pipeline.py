"""Instructions to commands, episode by episode (drywall_lab/pipeline.py): the batch contract of
spec section 6 and the paper's three layouts (Figs. 15-18)."""
from __future__ import annotations

import json

import pytest

from drywall_lab.corpus import tokenize
from drywall_lab.pipeline import (
    map_gold_episode,
    paper_layouts,
    parse_episode,
    read_episodes,
    run_episode,
    run_episodes,
)

SPACING, HALF, FT = 0.4064, 0.01905, 0.3048


class GoldTagger:
    """Tags instructions it knows with their hand-checked tags (the layouts' ``tagged`` field)."""

    def __init__(self, layouts):
        self.known = {tuple(w): t for layout in layouts for w, t in zip(layout["words"], layout["tags"])}

    def predict(self, sentences):
        return [list(self.known.get(tuple(s), ["O"] * len(s))) for s in sentences]


@pytest.fixture(scope="module")
def layouts():
    return paper_layouts()


def test_layout_text_and_markup_agree(layouts):
    assert [layout["id"] for layout in layouts] == ["layout1", "layout2", "layout3"]
    for layout in layouts:
        assert len(layout["instructions"]) == len(layout["tagged"]) == len(layout["expected"])
        assert [tokenize(text) for text in layout["instructions"]] == layout["words"]


def test_layouts_give_their_expected_commands(layouts):
    for layout in layouts:
        results, history = map_gold_episode(layout)
        got = [r.command.as_contract() if r.command else {"refusal": r.refusal.reason} for r in results]
        assert got == layout["expected"], layout["id"]
        assert len(history) == sum("refusal" not in e for e in layout["expected"])


def test_layout1_history_table_is_the_papers(layouts):
    """Fig. 16: panel 500320 on stud 500100 at the stud's left line, then three more, all vertical."""
    _, history = map_gold_episode(layouts[0])
    rows = history.frame.to_dict("records")
    assert [r["drywall_id"] for r in rows] == ["500320", "500322", "500310", "500321"]
    assert [r["stud_id"] for r in rows] == ["500100", "500103", "500107", "500110"]
    assert {r["ver_hor"] for r in rows} == {"vertical"}
    assert [r["left_cent"] for r in rows] == ["left", "center", "center", "center"]
    assert rows[0]["installed_x_left"] == pytest.approx(-HALF)
    assert rows[0]["installed_x_right"] == pytest.approx(-HALF + 4 * FT)
    assert rows[2]["installed_x_left"] == pytest.approx(7 * SPACING)  # "second to the left of 500109"
    assert rows[3]["installed_x_right"] == pytest.approx(10 * SPACING + 2 * FT)


def test_layout2_is_two_rows_of_horizontal_panels(layouts):
    _, history = map_gold_episode(layouts[1])
    rows = history.frame.to_dict("records")
    assert [r["top_btm"] for r in rows] == ["bottom", "bottom", "top", "top"]
    assert rows[1]["installed_x_left"] == pytest.approx(rows[0]["installed_x_right"])  # butted, not overlapping
    assert max(r["installed_x_right"] for r in rows) <= 12 * SPACING + HALF


def test_refused_step_changes_nothing(layouts):
    layout = layouts[2]
    results, history = map_gold_episode(layout)
    refused = [i for i, e in enumerate(layout["expected"]) if "refusal" in e]
    assert refused == [2]
    assert "500301 is under 500311" in results[2].refusal.message
    # the step after the refusal counts from the last *accepted* command's stud (500102 -> 500105)
    assert results[3].command.stud_id == "500105"


def test_run_output_follows_the_contract(layouts):
    records = list(run_episodes(layouts, GoldTagger(layouts)))
    assert len(records) == sum(len(layout["instructions"]) for layout in layouts)
    for record in records:
        assert set(record) == {"episode", "step", "words", "tags", "command", "refusal"}
        assert (record["command"] is None) != (record["refusal"] is None)
        if record["command"] is not None:
            assert set(record["command"]) == {"drywall_id", "stud_id", "placement"}
        else:
            assert isinstance(record["refusal"], str) and record["refusal"]
        json.dumps(record)
    steps = {}
    for record in records:
        steps.setdefault(record["episode"], []).append(record["step"])
    assert all(s == list(range(len(s))) for s in steps.values())
    first = records[0]
    assert first["episode"] == "layout1" and first["step"] == 0
    assert first["command"] == {"drywall_id": "500320", "stud_id": "500100", "placement": "vertical_left"}


def test_each_episode_starts_from_the_fresh_site(layouts):
    tagger = GoldTagger(layouts)
    once = list(run_episodes([layouts[0]], tagger))
    twice = list(run_episodes([layouts[0], {**layouts[0], "id": "again"}], tagger))
    assert [r["command"] for r in twice[len(once):]] == [r["command"] for r in once]


def test_empty_and_garbled_instructions_are_refused(layouts):
    results = run_episode({"id": "e", "instructions": ["", "   ", "%%% ### !!!", "asdf qwer"]}, GoldTagger(layouts))
    assert all(r.refusal is not None and r.refusal.reason == "undetermined" for r in results)


@pytest.mark.parametrize("line, message", [
    ("not json", "line 2: not a JSON object"),
    ("[1, 2]", "line 2: an episode must be a JSON object"),
    ('{"instructions": []}', "line 2: the episode has no 'id'"),
    ('{"id": "a"}', "line 2: the episode has no 'instructions'"),
    ('{"id": "a", "instructions": "put it there"}', "must be a list of strings"),
    ('{"id": "a", "instructions": ["ok", 3]}', "must be a list of strings"),
    ('{"id": null, "instructions": []}', "id must be a string or a number"),
])
def test_read_episodes_names_the_bad_line(tmp_path, line, message):
    path = tmp_path / "episodes.jsonl"
    path.write_text('{"id": "fine", "instructions": ["x"]}\n' + line + "\n")
    with pytest.raises(ValueError) as info:
        read_episodes(path)
    assert message in str(info.value)


def test_read_episodes_keeps_numbers_and_skips_blank_lines(tmp_path):
    path = tmp_path / "episodes.jsonl"
    path.write_text('\n{"id": 7, "instructions": ["a"], "note": "kept"}\n\n')
    assert read_episodes(path) == [{"id": 7, "instructions": ["a"], "note": "kept"}]
    with pytest.raises(FileNotFoundError):
        read_episodes(tmp_path / "missing.jsonl")
    assert parse_episode({"id": "x", "instructions": []}) == {"id": "x", "instructions": []}


# --- reading episodes files: one reader (corpus.io.read_jsonl), every error names its line -------------------
def test_read_episodes_accepts_a_byte_order_mark(tmp_path):
    """Editors on Windows save UTF-8 with a byte-order mark; line 1 is still an episode."""
    path = tmp_path / "episodes.jsonl"
    path.write_bytes(b"\xef\xbb\xbf" + b'{"id": "a", "instructions": ["put it on stud 500100"]}\r\n'
                     + b'{"id": "b", "instructions": []}\r\n')
    assert read_episodes(path) == [{"id": "a", "instructions": ["put it on stud 500100"]},
                                   {"id": "b", "instructions": []}]


@pytest.mark.parametrize("line, message", [
    (b'{"id": "b", "instructions": ["caf\xff"]}', "line 3: not valid UTF-8 text (byte 0xff at position 34 of the line: invalid start byte)"),
    (b'{"id": "b", "instructions": ["\xe2\x82"]}', "line 3: not valid UTF-8 text (byte 0xe2 at position 31"),
    (b'{"id": "b", "instructions": ["\xed\xa0\x80"]}', "line 3: not valid UTF-8 text (byte 0xed"),  # a surrogate
    (b'{"id": "b", "instructions": ["\\ud800"]}', "line 3: instruction 1 is not Unicode text"),
    (b'{"id": "\\udfff", "instructions": []}', "line 3: the episode id is not Unicode text"),
    (b'{"id": 1' + b"0" * 5000 + b', "instructions": []}', "line 3: not a JSON object"),  # past int's digit limit
    (b"[" * 100_000 + b"]" * 100_000, "line 3: not a JSON object (nested too deeply)"),
    (b'{"id": "a", "instructions": []} {"id": "b", "instructions": []}', "line 3: not a JSON object (Extra data"),
    (b"\xef\xbb\xbf{}", "line 3: not a JSON object (a byte-order mark"),  # only the file's start may have one
])
def test_read_episodes_names_the_line_that_cannot_be_read(tmp_path, line, message):
    path = tmp_path / "episodes.jsonl"
    path.write_bytes(b'{"id": "fine", "instructions": ["x"]}\n\n' + line + b"\n")
    with pytest.raises(ValueError) as info:
        read_episodes(path)
    assert str(info.value).startswith(f"{path}, line 3: ")
    assert message in str(info.value)


def test_read_episodes_reads_lines_split_only_at_newlines(tmp_path):
    """U+2028, U+0085 and a lone carriage return are allowed inside JSON strings; they do not end a line."""
    texts = ["a\u2028b", "c\x85d", "e\x1cf", "g\x00h"]
    path = tmp_path / "episodes.jsonl"
    path.write_bytes(json.dumps({"id": "u", "instructions": texts}, ensure_ascii=False).encode() + b"\n")
    assert read_episodes(path) == [{"id": "u", "instructions": texts}]


# --- the default tagger on input nobody meant (spec section 6: a record, never a traceback) --------------------
def _words_nobody_says(n: int, seed: int = 0) -> str:
    import random

    rng = random.Random(seed)
    return " ".join("".join(rng.choice("bcdfghjklmnpqrstvwxz") for _ in range(rng.randint(1, 9))) for _ in range(n))


@pytest.mark.parametrize("text", [
    "", " \t ", ".,;:!?", "%%% ### !!! ... ---", "\x00", "\x00\x01\x07\x1b\x7f", "\u2028\r\x0b\x0c",
    "\u200b\u200d\ufeff", _words_nobody_says(10_000),
], ids=["empty", "blank", "punctuation", "symbols", "nul", "controls", "line-separators", "zero-width",
        "10000-words"])
def test_default_tagger_and_rules_refuse_what_says_nothing(text):
    from drywall_lab.nlu import default_tagger

    from drywall_lab.nlu.normalise import normalise

    from drywall_lab.pipeline import too_long

    [result] = run_episode({"id": "odd", "instructions": [text]}, default_tagger())
    # an instruction too long to be one is refused as said, before the front end and the tagger
    assert result.words == (tokenize(text) if too_long(text) else list(normalise(text).words))
    assert len(result.tags) == len(result.words)
    assert result.command is None and result.refusal.reason == "undetermined", result.refusal
    [record] = run_episodes([{"id": "odd", "instructions": [text]}], default_tagger())
    assert record["words"] == tokenize(text) and len(record["tags"]) == len(record["words"])


def test_run_reads_through_the_front_end_and_reports_the_workers_own_words():
    """The tagger and the IM read the normalised words; ``run`` reports the worker's words, each with the tag of
    the word it became, and the trace starts with what the front end changed (issue 29)."""
    from drywall_lab.nlu import default_tagger

    text = "um put the four by eight on stud five oh oh one oh four"
    episode = {"id": "spoken", "instructions": [text]}
    [result] = run_episode(episode, default_tagger())
    assert result.words[-1] == "500104" and "um" not in result.words
    assert [s.stage for s in result.trace][:2] == ["front end", "front end"]
    [record] = run_episodes([episode], default_tagger())
    assert record["words"] == tokenize(text)
    assert record["tags"][-6:] == ["ID_stud"] * 6 and record["tags"][0] == "O"
    assert record["command"] == {"drywall_id": "500320", "stud_id": "500104", "placement": "vertical_left"}
