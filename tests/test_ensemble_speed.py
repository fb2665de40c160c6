"""The ensemble's fast path (issue 29): its members run as one computation, with the member-by-member outputs.

``CrfEnsembleTagger.predict`` / ``predict_confidence`` (and so ``predict_marginals`` / ``predict_kbest``) run the
fused members (``_FusedMembers``), a NumPy Viterbi and the CRF's cached scores; ``_reference_predict`` /
``_reference_confidence`` are the straightforward computation (every member's own ``_emissions``, stacked and
averaged, ``torchcrf``'s decode and ``crf_confidence``). Tags and k-best sequences must be the same, marginals and
log-probabilities within 1e-5.
"""
from __future__ import annotations

import numpy as np
import pytest
import torch

from drywall_lab.corpus import read_split
from drywall_lab.corpus.tags import TAGS
from drywall_lab.nlu import DEFAULT_TAGGER_DIR, BiLstmCrfTagger, CrfEnsembleTagger, load_tagger
from drywall_lab.nlu import ensemble as ensemble_module

TOLERANCE = 1e-5
#: Length-1 instructions, unknown words and characters, an empty word, a word longer than MAX_WORD_CHARS, an empty
#: instruction among the others.
ODD = [
    ["go"], ["500113"], ["Sheetrock"], [""], [],
    ["put", "the", "4'x8'", "sheetrock", "on", "stud", "#500107", "ñandú", ""],
    ["extraordinarilylongwordthatgoespastthelimit", "stud"],
    ["PUT", "PANEL", "500398", "ON", "STUD", "500113", "IN", "THE", "TOP", "ROW"],
]


def assert_same_outputs(tagger: CrfEnsembleTagger, sentences: list[list[str]], k: int = 5,
                        batch_size: int = 64) -> None:
    assert tagger.predict(sentences, batch_size) == tagger._reference_predict(sentences, batch_size)
    fast = tagger.predict_confidence(sentences, k=k, batch_size=batch_size)
    reference = tagger._reference_confidence(sentences, k=k, batch_size=batch_size)
    assert len(fast) == len(reference) == len(sentences)
    for words, f, r in zip(sentences, fast, reference):
        assert f.tags == r.tags and len(f.tags) == len(words)
        assert [tags for tags, _ in f.kbest] == [tags for tags, _ in r.kbest]
        np.testing.assert_allclose([p for _, p in f.kbest], [p for _, p in r.kbest], rtol=0, atol=TOLERANCE)
        assert f.marginals.shape == r.marginals.shape == (len(words), len(tagger.labels))
        np.testing.assert_allclose(f.marginals, r.marginals, rtol=0, atol=TOLERANCE)
    for f, r in zip(tagger.predict_marginals(sentences, batch_size), reference):
        np.testing.assert_allclose(f, r.marginals, rtol=0, atol=TOLERANCE)
    for f, r in zip(tagger.predict_kbest(sentences, k, batch_size), reference):  # log Z from the forward half alone
        assert [tags for tags, _ in f] == [tags for tags, _ in r.kbest]
        np.testing.assert_allclose([p for _, p in f], [p for _, p in r.kbest], rtol=0, atol=TOLERANCE)


def assert_same_emissions(tagger: CrfEnsembleTagger, batch: list[list[str]]) -> None:
    with torch.inference_mode():
        fused = tagger._fused.emissions(*tagger._fused.inputs(batch))
        reference, mask = tagger._reference_emissions(batch)
    assert fused.shape == reference.shape == (len(batch), max(map(len, batch)), len(tagger.labels))
    torch.testing.assert_close(fused, reference, rtol=0, atol=TOLERANCE)


@pytest.fixture(scope="module")
def shipped() -> CrfEnsembleTagger:
    return load_tagger(DEFAULT_TAGGER_DIR)


@pytest.fixture(scope="module")
def test_sentences() -> list[list[str]]:
    return [r["words"] for r in read_split("test")[:12]]


def test_the_shipped_tagger_runs_its_members_as_one(shipped) -> None:
    assert isinstance(shipped, CrfEnsembleTagger) and len(shipped.members) == 2
    assert shipped._fused is not None


@pytest.mark.parametrize("batch_size", [1, 3, 64])
def test_the_shipped_tagger_gives_the_member_by_member_outputs(shipped, test_sentences, batch_size) -> None:
    # batch 1: every instruction alone (as `run` tags them); 3 and 64: mixed lengths, padded and packed
    assert_same_outputs(shipped, test_sentences + ODD, batch_size=batch_size)


@pytest.mark.parametrize("k", [1, 8])
def test_k_best_of_any_k(shipped, test_sentences, k) -> None:
    assert_same_outputs(shipped, test_sentences[:4] + ODD[:3], k=k, batch_size=4)


def test_the_fused_emissions_are_the_members_mean(shipped, test_sentences) -> None:
    for words in test_sentences[:4] + [s for s in ODD if s]:
        assert_same_emissions(shipped, [words])
    assert_same_emissions(shipped, test_sentences[:6] + [s for s in ODD if s])  # mixed lengths in one batch


def test_a_short_batch_runs_on_one_thread_and_the_setting_is_restored(shipped, test_sentences, monkeypatch) -> None:
    seen = []
    hook = shipped.members[0].network.lstm.register_forward_pre_hook(lambda *_: seen.append(torch.get_num_threads()))
    before = torch.get_num_threads()
    try:
        torch.set_num_threads(2)
        shipped.predict([test_sentences[0]])
        shipped.predict_confidence([test_sentences[0]])
        assert torch.get_num_threads() == 2
        many = [w for words in test_sentences for w in words]
        assert len(many) > ensemble_module.SINGLE_THREAD_WORDS
        shipped.predict([many])
        assert torch.get_num_threads() == 2
        monkeypatch.setattr(ensemble_module, "SINGLE_THREAD_WORDS", 0)
        shipped.predict([test_sentences[0]])
    finally:
        hook.remove()
        torch.set_num_threads(before)
    assert seen == [1, 1, 2, 2]


def random_member(vocabulary: list[str], *, characters: str | None = "abcdeinoprstu0135", seed: int = 0,
                  **settings) -> BiLstmCrfTagger:
    """An untrained BiLSTM-CRF with random weights (its CRF's too): for comparing two computations, any weights do."""
    if characters is not None:
        settings = {"char_embedding_dim": 5, "char_filters": 4, **settings}
    member = BiLstmCrfTagger(labels=TAGS, **{"embedding_dim": 6, "hidden_size": 7, **settings})
    torch.manual_seed(seed)
    member._build(["<pad>", "<unk>", "<id>", "<num>", "<ordinal>", *vocabulary],
                  ["<pad>", "<unk>", *characters] if characters is not None else ())
    with torch.no_grad():
        for p in member.network.parameters():
            p.normal_(0, 1.0)
    member.network.eval()
    return member


VOCABULARY = ["put", "the", "panel", "on", "stud", "<id:5001>", "<id:5003>", "top", "row", "go"]
SMALL = [["put", "the", "panel", "500310", "on", "stud", "500113"], ["go"], ["top", "row", "sheetrock"], [],
         ["Stud"], ["the", "", "panel", "4x8"]]


@pytest.mark.parametrize("settings", [
    [{"seed": 1}, {"seed": 2}],
    # three members whose LSTMs differ
    [{"seed": 1}, {"seed": 2, "hidden_size": 5, "num_layers": 1}, {"seed": 3, "num_layers": 3}],
    [{"seed": 1, "characters": None}, {"seed": 2, "characters": None}],  # no character features
    [{"seed": 4}],  # one member
])
@pytest.mark.parametrize("batch_size", [1, 64])
def test_other_ensembles_give_the_member_by_member_outputs(settings, batch_size) -> None:
    tagger = CrfEnsembleTagger([random_member(VOCABULARY, **s) for s in settings])
    assert tagger._fused is not None
    assert_same_outputs(tagger, SMALL, k=6, batch_size=batch_size)
    assert_same_emissions(tagger, [s for s in SMALL if s])


def test_members_that_read_differently_run_one_by_one() -> None:
    tagger = CrfEnsembleTagger([random_member(VOCABULARY, seed=1), random_member(VOCABULARY[:-1], seed=2)])
    assert tagger._fused is None
    confidence = tagger.predict_confidence(SMALL, k=3)
    assert tagger.predict(SMALL) == tagger._reference_predict(SMALL) == [c.tags for c in confidence]


def test_a_member_left_in_training_mode_is_read_in_evaluation_mode() -> None:
    tagger = CrfEnsembleTagger([random_member(VOCABULARY, seed=1, dropout=0.5), random_member(VOCABULARY, seed=2)])
    tagger.members[0].network.train()
    assert_same_outputs(tagger, SMALL)
    assert not tagger.members[0].network.training


def test_moving_and_saving_keep_the_fast_path(tmp_path) -> None:
    tagger = CrfEnsembleTagger.combine([random_member(VOCABULARY, seed=1), random_member(VOCABULARY, seed=2)])
    tagger.to("cpu")
    assert tagger._fused is not None
    assert_same_outputs(tagger, SMALL)
    loaded = load_tagger(tagger.save(tmp_path / "ensemble"))
    assert loaded._fused is not None
    assert loaded.predict(SMALL) == tagger.predict(SMALL)
    for a, b in zip(loaded.predict_marginals(SMALL), tagger.predict_marginals(SMALL)):
        np.testing.assert_allclose(a, b, rtol=0, atol=TOLERANCE)


def test_the_members_read_side_by_side_give_the_same_emissions(shipped, test_sentences) -> None:
    """A short batch's members' LSTMs run side by side, each on one thread (``_side_by_side``): the same
    arithmetic as one after the other, so the same emissions bit for bit, packed or not."""
    for batch in ([test_sentences[0]], test_sentences[:3], [["go"], test_sentences[1]]):
        with torch.inference_mode():
            inputs = shipped._fused.inputs(batch)
            before = torch.get_num_threads()
            torch.set_num_threads(1)
            try:
                apart = shipped._fused.emissions(*inputs, concurrent=False)
                together = shipped._fused.emissions(*inputs, concurrent=True)
            finally:
                torch.set_num_threads(before)
        assert torch.equal(apart, together)
