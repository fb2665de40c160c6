"""Notebook 02's from-scratch piece: the CRF on a three-word toy (path score, partition function by enumeration
and by the forward algorithm, log-likelihood, Viterbi) and its grader ``check_viterbi``; the transitions heatmap
and the architecture diagram (the paper's Figs. 3 and 8(a))."""
from __future__ import annotations

import itertools
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import nbformat  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from drywall_lab.course import bilstm_crf as ch02  # noqa: E402
from drywall_lab.course.common import solution_file  # noqa: E402
from drywall_lab.course.solutions import ch02 as solutions  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOK = ROOT / "notebooks" / "02_bilstm_crf.ipynb"
MARKER = "# from scratch: your code here"


@pytest.fixture(scope="module")
def toy():
    crf = ch02.toy_crf()
    return crf, (ch02.TOY_EMISSIONS, *ch02.crf_scores(crf))


# --- the library's CRF arithmetic on the toy ---------------------------------------------------------------------
def test_path_score_adds_start_emissions_transitions_and_end(toy):
    _, (em, tr, start, end) = toy
    assert ch02.path_score(em, tr, start, end, [0, 1, 0]) == pytest.approx(
        start[0] + em[0, 0] + tr[0, 1] + em[1, 1] + tr[1, 0] + em[2, 0] + end[0])
    assert ch02.path_score(em[:1], tr, start, end, [2]) == pytest.approx(start[2] + em[0, 2] + end[2])


def test_the_partition_function_by_enumeration_and_forward_agree_with_torchcrf(toy):
    crf, scores = toy
    assert len(ch02.path_scores(*scores)) == 27
    log_z = ch02.brute_force_log_partition(*scores)
    assert ch02.forward_log_partition(*scores) == pytest.approx(log_z, abs=1e-10)
    table = ch02.forward_table(*scores, tags=ch02.TOY_TAGS, words=ch02.TOY_WORDS)
    assert table.shape == (3, 3) and list(table.columns) == list(ch02.TOY_TAGS)
    em, _, start, _ = scores
    np.testing.assert_allclose(table.iloc[0], start + em[0])
    for path in ([0, 1, 0], [2, 2, 2], [1, 0, 2]):  # torchcrf's crf(emissions, tags) = score - log Z
        assert ch02.torchcrf_log_likelihood(crf, em, path) == pytest.approx(
            ch02.path_score(*scores, path) - log_z, abs=1e-4)


def test_the_toy_shows_transitions_overruling_a_word(toy):
    """The notebook's point: the best path is the gold O St_loc1 O, each word's best emission alone is not."""
    crf, scores = toy
    best, _ = ch02.brute_force_best_path(*scores)
    assert best == ch02.torchcrf_decode(crf, ch02.TOY_EMISSIONS) == [0, 1, 0]
    assert list(np.argmax(ch02.TOY_EMISSIONS, axis=1)) != best


# --- the grader ---------------------------------------------------------------------------------------------------
def test_the_reference_solution_passes_every_case():
    check = ch02.check_viterbi(solutions.viterbi)
    assert check.passed and check.attempted, str(check)
    assert len(check.messages) == len(ch02._viterbi_cases()) >= 8
    assert "the notebook's toy" in check.messages[0] and "27 paths" in check.messages[0]


def test_the_reference_solution_agrees_with_brute_force_on_more_random_cases():
    rng = np.random.default_rng(5)
    for n_words, n_tags in itertools.product(range(1, 6), range(2, 5)):
        scores = (rng.normal(size=(n_words, n_tags)), rng.normal(size=(n_tags, n_tags)), rng.normal(size=n_tags),
                  rng.normal(size=n_tags))
        path, score = solutions.viterbi(*scores)
        want_path, want_score = ch02.brute_force_best_path(*scores)
        assert path == want_path and score == pytest.approx(want_score)


def _raise_stub(emissions, transitions, start, end):
    raise NotImplementedError("your code here")


def _dots_stub(emissions, transitions, start, end):
    ...


@pytest.mark.parametrize("stub", [_raise_stub, _dots_stub])
def test_the_stub_is_not_attempted(stub):
    check = ch02.check_viterbi(stub)
    text = str(check)
    assert not check.passed and not check.attempted
    assert text.startswith("NOT ATTEMPTED YET:\n- fill in "), text
    assert solution_file(2) in text and "viterbi(" in text


def _viterbi_with(transform):
    """The reference solution given altered inputs: how the usual slips behave."""
    def wrong(emissions, transitions, start, end):
        return solutions.viterbi(*transform(emissions, transitions, start, end))
    return wrong


def _greedy(emissions, transitions, start, end):
    path = [int(j) for j in np.argmax(emissions, axis=1)]
    return path, ch02.path_score(emissions, transitions, start, end, path)


def _back_pointers_one_off(emissions, transitions, start, end):
    """Viterbi whose back-pointers are kept in a table with a row per word, read at the row of word t - 1."""
    n_words, n_tags = emissions.shape
    best, back = start + emissions[0], np.zeros((n_words, n_tags), dtype=int)
    for t in range(1, n_words):
        candidates = best[:, None] + transitions
        back[t], best = np.argmax(candidates, axis=0), np.max(candidates, axis=0) + emissions[t]
    best = best + end
    path = [int(np.argmax(best))]
    for t in range(n_words - 1, 0, -1):
        path.insert(0, int(back[t - 1, path[0]]))
    return path, float(np.max(best))


def _back_pointers_from_the_wrong_end(emissions, transitions, start, end):
    """Viterbi that follows each back-pointer from the last word's tag instead of the tag just found."""
    best, history = start + emissions[0], []
    for word in emissions[1:]:
        candidates = best[:, None] + transitions
        history.append(np.argmax(candidates, axis=0))
        best = np.max(candidates, axis=0) + word
    best = best + end
    path = [int(np.argmax(best))]
    for pointers in reversed(history):
        path.append(int(pointers[path[0]]))
    return path[::-1], float(np.max(best))


def _backwards(emissions, transitions, start, end):
    path, score = solutions.viterbi(emissions, transitions, start, end)
    return path[::-1], score


WRONG = [
    (_viterbi_with(lambda e, tr, s, en: (e, tr, 0 * s, 0 * en)), "left out both the start and the end scores"),
    (_viterbi_with(lambda e, tr, s, en: (e, tr, 0 * s, en)), "left out the start scores"),
    (_viterbi_with(lambda e, tr, s, en: (e, tr, s, 0 * en)), "left out the end scores"),
    (_viterbi_with(lambda e, tr, s, en: (e, tr.T, s, en)), "your transitions are transposed"),
    (_greedy, "each word's highest emission score on its own (greedy)"),
    (_back_pointers_one_off, "your back-pointers are read one word off"),
    (_back_pointers_from_the_wrong_end, "the back-pointers do not lead back along the best path"),
    (_backwards, "your path is backwards"),
    (lambda e, tr, s, en: (solutions.viterbi(e, tr, s, en)[0][:-1], 0.0), "tags for"),
    (lambda e, tr, s, en: (solutions.viterbi(e, tr, s, en)[0], 0.0), "the path is right, but its score"),
    (lambda e, tr, s, en: solutions.viterbi(e, tr, s, en)[0], "return (path, score)"),
    (lambda e, tr, s, en: 1 / 0, "raised ZeroDivisionError"),
]


@pytest.mark.parametrize("answer, says", WRONG)
def test_wrong_answers_fail_with_what_is_wrong(answer, says):
    check = ch02.check_viterbi(answer)
    assert check.attempted and not check.passed, str(check)
    assert says in check.messages[-1], str(check)


def test_the_grader_does_not_hand_the_students_function_its_own_arrays():
    seen = []

    def mutating(emissions, transitions, start, end):
        seen.append(start)
        start[:] = 0
        emissions[:] = 0
        return solutions.viterbi(emissions, transitions, start, end)

    assert not ch02.check_viterbi(mutating).passed
    assert not np.allclose(ch02.TOY_EMISSIONS, 0)  # the toy survives a student's function writing to its input


# --- the figures --------------------------------------------------------------------------------------------------
def test_plot_transitions_draws_a_labelled_diverging_heatmap():
    labels = ["O", "ID_stud", "St_loc1"]
    table = pd.DataFrame([[0.5, -2.0, 0.1], [1.0, 0.0, -0.3], [0.2, 0.4, -1.0]], index=labels, columns=labels)
    fig = ch02.plot_transitions(table)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "tag after" and ax.get_ylabel() == "tag before"
    assert [t.get_text() for t in ax.get_xticklabels()] == labels == [t.get_text() for t in ax.get_yticklabels()]
    image = ax.get_images()[0]
    assert image.get_cmap().name == "RdBu" and image.norm.vmin == -image.norm.vmax == -2.0  # centred on 0
    np.testing.assert_allclose(image.get_array(), table.to_numpy())
    assert "-2.00" in {t.get_text() for t in ax.texts}
    plt.close(fig)


def _texts(fig) -> str:
    return "\n".join(t.get_text() for ax in fig.axes for t in ax.texts + [ax.title])


def test_draw_bilstm_crf_has_every_layer_for_every_word():
    words, tags = ["Pick", "up", "the", "panel"], ["O", "O", "O", "Dw_loc1"]
    fig = ch02.draw_bilstm_crf(words, tags, {"embedding_dim": 50, "hidden_size": 150, "char_filters": 0})
    text = _texts(fig)
    for layer in ("word embedding (50)", "forward LSTM", "backward LSTM", "concatenation", "(300)",
                  "linear: emission scores", "CRF layer", "transitions[tag before, tag after]"):
        assert layer in text, layer
    assert "character CNN" not in text
    for word in words:
        assert f'"{word}"' in text
    assert text.count("forward LSTM") == text.count("backward LSTM") == len(words)
    assert "Dw_loc1" in text
    plt.close(fig)


def test_draw_bilstm_crf_shows_character_features_where_the_tagger_uses_them():
    fig = ch02.draw_bilstm_crf(["to", "stud"], None, {"char_filters": 30})
    assert _texts(fig).count("character CNN (30)") == 2 and "with character features" in _texts(fig)
    plt.close(fig)


# --- the committed notebook -----------------------------------------------------------------------------------------
def _cells():
    return nbformat.read(NOTEBOOK, as_version=4).cells


def test_the_notebook_holds_the_stub_not_the_solution():
    cells = _cells()
    found = [i for i, c in enumerate(cells) if c.cell_type == "code" and MARKER in c.source]
    assert len(found) == 1
    source = cells[found[0]].source
    assert 'raise NotImplementedError("your code here")' in source
    assert "\n# your code here" not in source and "    # your code here" not in source
    assert "np.argmax(candidates" not in source and "back_pointers" not in source
    assert source.rstrip().endswith("check = check_viterbi(viterbi)\nprint(check)\n"
                                    "assert check.passed or not check.attempted")
    above = next(c for c in reversed(cells[:found[0]]) if c.cell_type == "markdown")
    assert f"`{solution_file(2)}`" in above.source and "try the exercise first" in above.source


def test_the_notebook_stub_cell_runs_and_says_not_attempted(capsys):
    source = next(c.source for c in _cells() if c.cell_type == "code" and MARKER in c.source)
    namespace = {"check_viterbi": ch02.check_viterbi}
    exec(compile(source, "notebook 02's from-scratch cell", "exec"), namespace)  # noqa: S102
    assert not namespace["check"].attempted
    assert capsys.readouterr().out.startswith("NOT ATTEMPTED YET:\n- fill in viterbi(")


def test_the_notebook_draws_the_figures():
    code = "\n".join(c.source for c in _cells() if c.cell_type == "code")
    assert "plot_transitions(transitions)" in code and "draw_bilstm_crf(" in code
    assert "transitions.round(2)" not in code  # the heatmap replaced the table


def test_tagged_window_picks_the_words_with_most_tags():
    words = ["It", "is", "the", "one", "on", "the", "left", "stud", "500111", "please"]
    tags = ["O", "O", "O", "O", "O", "O", "St_loc1", "O", "ID_stud", "O"]
    assert ch02.tagged_window(words, tags, 4) == (["the", "left", "stud", "500111"],
                                                  ["O", "St_loc1", "O", "ID_stud"])
    assert ch02.tagged_window(words[:3], tags[:3], 4) == (words[:3], tags[:3])  # shorter than the window
    assert ch02.tagged_window(["a", "b"], ["O", "O"], 1) == (["a"], ["O"])  # no tags: the first window
