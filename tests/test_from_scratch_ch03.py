"""Notebook 03's from-scratch piece: word tags to sub-word token labels (``align_labels``, checked by
``check_align_labels`` against ``BertTagger``'s own alignment), and the paper's Fig. 8(b) redrawn."""
from __future__ import annotations

from pathlib import Path

import matplotlib
import nbformat
import pytest

from drywall_lab.course.bert import (IGNORED_LABEL, WORKED_TAGS, WORKED_WORDS, alignment_table, check_align_labels,
                                     library_alignment, plot_bert_tagger)
from drywall_lab.course.common import solution_file
from drywall_lab.course.solutions import ch03

matplotlib.use("Agg")

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "03_bert.ipynb"
MARKER = "# from scratch: your code here"


def _raise_stub(word_ids, word_labels):
    raise NotImplementedError("your code here")


def _dots_stub(word_ids, word_labels):
    ...


def test_the_library_alignment_labels_every_sub_word_and_ignores_the_specials():
    tokens, word_ids, labels = library_alignment(["500107", "on"], ["ID_stud", "O"])
    assert tokens == ["[CLS]", "500", "##10", "##7", "on", "[SEP]"]
    assert word_ids == [None, 0, 0, 0, 1, None]
    assert labels[0] == labels[-1] == IGNORED_LABEL and len(set(labels[1:4])) == 1 and labels[1] != labels[4]
    table = alignment_table(WORKED_WORDS, WORKED_TAGS)
    assert list(table.columns) == ["token", "word id", "word", "word tag", "label id"]
    assert list(table.loc[table["word"] == "500107", "word tag"]) == ["ID_stud"] * 3


def test_the_solution_passes():
    check = check_align_labels(ch03.align_labels)
    assert check.passed and check.attempted, str(check)
    assert "agree with BertTagger's own alignment" in str(check)


@pytest.mark.parametrize("stub", [_raise_stub, _dots_stub])
def test_the_stub_is_not_attempted(stub):
    check = check_align_labels(stub)
    text = str(check)
    assert not check.passed and not check.attempted, text
    assert text.startswith("NOT ATTEMPTED YET:\n- fill in "), text
    assert solution_file(3) in text


def _first_only(word_ids, word_labels):
    return [-100 if w is None or (k and word_ids[k - 1] == w) else word_labels[w] for k, w in enumerate(word_ids)]


def _specials_labelled(word_ids, word_labels):
    return [0 if w is None else word_labels[w] for w in word_ids]


def _shifted(word_ids, word_labels):
    return [-100 if w is None else word_labels[w + 1] if w + 1 < len(word_labels) else word_labels[w]
            for w in word_ids]


def _one_per_word(word_ids, word_labels):
    return list(word_labels)


@pytest.mark.parametrize("wrong, expected", [
    (_first_only, "you labelled only the first sub-word of each word"),
    (_specials_labelled, "token 0 '[CLS]' is a special token (word id None): it gets -100"),
    (_shifted, "the label of a neighbouring word: shifted by one"),
    (_one_per_word, "(one per word: the model needs one per token)"),
])
def test_wrong_answers_fail_with_what_is_wrong(wrong, expected):
    check = check_align_labels(wrong)
    assert not check.passed and check.attempted
    assert expected in str(check), str(check)


def test_a_slip_seen_only_in_an_edge_case_is_caught():
    # right on every word of one token, wrong only where a word has several: the worked example catches it
    def last_piece_only(word_ids, word_labels):
        return [-100 if w is None or (k + 1 < len(word_ids) and word_ids[k + 1] == w) else word_labels[w]
                for k, w in enumerate(word_ids)]

    check = check_align_labels(last_piece_only)
    assert not check.passed and "the worked example" in str(check)
    assert "token 3 'full' belongs to word 2 'full-size'" in str(check)


def test_fig_8b_is_drawn_on_the_worked_example_s_word_pieces():
    figure = plot_bert_tagger(WORKED_WORDS, WORKED_TAGS)
    texts = [t.get_text() for t in figure.axes[0].texts]
    for piece in ("[CLS]", "500", "##10", "##7", "sheet", "##rock", "[SEP]"):
        assert piece in texts, piece
    assert texts.count("ID_stud") == 3 and texts.count("dim") == 3 and texts.count("(ignored)") == 2
    assert texts.count("linear") == len(library_alignment(WORKED_WORDS, WORKED_TAGS)[0])
    assert any(t.startswith("transformer encoder: 6 layers of 384 units") for t in texts)
    matplotlib.pyplot.close(figure)


def test_the_notebook_holds_the_stub_and_names_the_solution_file():
    cells = nbformat.read(NOTEBOOK, as_version=4).cells
    found = [i for i, c in enumerate(cells) if c.cell_type == "code" and MARKER in c.source]
    assert len(found) == 1
    source = cells[found[0]].source
    assert 'raise NotImplementedError("your code here")' in source
    assert "word_labels[word] for word in word_ids" not in source and "-100 if" not in source
    assert source.rstrip().endswith("check = check_align_labels(align_labels)\nprint(check)\n"
                                    "assert check.passed or not check.attempted")
    above = next(c for c in reversed(cells[:found[0]]) if c.cell_type == "markdown")
    assert f"`{solution_file(3)}`" in above.source and "try the exercise first" in above.source
    assert any(c.cell_type == "code" and "plot_bert_tagger(" in c.source for c in cells)
