"""drywall_lab.nlu.ensemble: BiLSTM-CRF taggers averaged into one CRF (a product of experts)."""
from __future__ import annotations

import itertools
import json

import numpy as np
import pytest
import torch

from drywall_lab.corpus.io import read_split
from drywall_lab.nlu import BiLstmCrfTagger, CrfEnsembleTagger, TaggerLoadError, crf_sequence_scores, load_tagger
from drywall_lab.nlu.cli import main as nlu_main

SENTENCES = [["Pick", "up", "panel", "500310"], ["put", "it", "on", "stud", "500113", "centre", "line"], [], ["go"]]


@pytest.fixture(scope="module")
def members() -> list[BiLstmCrfTagger]:
    before = torch.get_num_threads()
    torch.set_num_threads(min(2, before))
    rows = read_split("train")[:80]
    out = []
    for seed in (0, 1):
        tagger = BiLstmCrfTagger(embedding_dim=12, hidden_size=12, char_embedding_dim=6, char_filters=8, epochs=2,
                                 learning_rate=1e-2)
        tagger.fit(rows, progress=False, seed=seed)
        out.append(tagger)
    torch.set_num_threads(before)
    return out


@pytest.fixture(scope="module")
def ensemble(members) -> CrfEnsembleTagger:
    return CrfEnsembleTagger.combine(members)


def test_its_scores_are_the_members_mean(members, ensemble) -> None:
    words = [SENTENCES[1]]
    for tags in (["O"] * 7, ["O", "O", "O", "O", "ID_stud", "Vr_md", "Vr_md"]):
        index = torch.tensor([[members[0].labels.index(t) for t in tags]])
        scores = []
        for tagger in [*members, ensemble]:
            if tagger is ensemble:
                _, emissions, mask = next(ensemble._batches(words, 8))
                crf = ensemble._crf
            else:
                emissions, mask = tagger._emissions(words)
                crf = tagger.network.crf
            with torch.no_grad():
                scores.append(float(crf_sequence_scores(crf, emissions.detach(), mask, index)[0]))
        assert scores[2] == pytest.approx((scores[0] + scores[1]) / 2, abs=1e-5)


def test_one_member_is_that_member(members) -> None:
    alone = CrfEnsembleTagger.combine(members[:1])
    assert alone.predict(SENTENCES) == members[0].predict(SENTENCES)
    for a, b in zip(alone.predict_marginals(SENTENCES), members[0].predict_marginals(SENTENCES)):
        np.testing.assert_allclose(a, b, atol=1e-6)


def test_confidence_is_a_distribution_and_kbest_is_exact(ensemble) -> None:
    confidences = ensemble.predict_confidence(SENTENCES, k=4)
    assert [c.tags for c in confidences] == ensemble.predict(SENTENCES)
    assert confidences[2].tags == [] and confidences[2].kbest == [([], 0.0)]
    for words, c in zip(SENTENCES, confidences):
        assert c.marginals.shape == (len(words), len(ensemble.labels))
        if words:
            np.testing.assert_allclose(c.marginals.sum(axis=1), 1.0, atol=1e-6)
            assert c.kbest[0][0] == c.tags
            assert [p for _, p in c.kbest] == sorted((p for _, p in c.kbest), reverse=True)
    # a one-word instruction: the k best are the labels by probability, and their probabilities are the marginals
    one = confidences[3]
    best = np.argsort(-one.marginals[0])[:4]
    assert [tags[0] for tags, _ in one.kbest] == [ensemble.labels[i] for i in best]
    np.testing.assert_allclose(np.exp([p for _, p in one.kbest]), one.marginals[0][best], atol=1e-6)


def test_save_and_load(tmp_path, ensemble) -> None:
    directory = ensemble.save(tmp_path / "ensemble")
    meta = json.loads((directory / "tagger.json").read_text())
    assert meta["kind"] == "bilstm-crf-ensemble" and meta["members"] == ["member0", "member1"]
    loaded = load_tagger(directory)
    assert isinstance(loaded, CrfEnsembleTagger) and loaded.n_parameters() == ensemble.n_parameters()
    assert loaded.predict(SENTENCES) == ensemble.predict(SENTENCES)
    # a member gone or broken: a clear error, not a half-loaded ensemble
    (directory / "member1" / "weights.safetensors").write_bytes(b"not weights")
    with pytest.raises(TaggerLoadError, match="member1.*corrupt"):
        load_tagger(directory)
    meta["members"] = []
    (directory / "tagger.json").write_text(json.dumps(meta))
    with pytest.raises(TaggerLoadError, match="names no member"):
        load_tagger(directory)


def test_members_must_fit_together(members) -> None:
    other = BiLstmCrfTagger(labels=["O", "ID_wall"])
    with pytest.raises(ValueError, match="not trained"):
        CrfEnsembleTagger([members[0], other])
    with pytest.raises(ValueError, match="at least one"):
        CrfEnsembleTagger.combine([])


def test_fit_trains_its_members_with_successive_seeds() -> None:
    rows = read_split("train")[:30]
    ensemble = CrfEnsembleTagger(n_members=2, member_settings={"embedding_dim": 8, "hidden_size": 8, "epochs": 1})
    history = ensemble.fit(rows, progress=False, seed=5)
    assert [m.training_info["seed"] for m in ensemble.members] == [5, 6]
    assert list(history["member"]) == [0, 1]
    assert len(ensemble.predict([["put", "it", "down"]])[0]) == 3


def test_the_ensemble_command(tmp_path, members, capsys) -> None:
    paths = [members[i].save(tmp_path / f"m{i}") for i in range(2)]
    out = tmp_path / "both"
    assert nlu_main(["ensemble", *itertools.chain(*(("--member", str(p)) for p in paths)), "--out", str(out)]) == 0
    assert "ensemble of 2" in capsys.readouterr().out
    assert load_tagger(out).predict(SENTENCES) == CrfEnsembleTagger.combine(members).predict(SENTENCES)
    assert nlu_main(["ensemble", "--member", str(paths[0]), "--out", str(paths[0])]) == 2
    assert "one of the members" in capsys.readouterr().err
