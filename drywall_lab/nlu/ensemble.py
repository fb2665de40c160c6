"""Several BiLSTM-CRF taggers read as one: a product of experts over their CRFs.

One training run is one draw (``benchmarks/field_seeds.py``): two runs of the same recipe, differing only in
their seed, tag the same hand-written instruction differently, each wrong in its own places. An ensemble of
such runs errs less than any one of them where their errors do not coincide (Dietterich 2000, "Ensemble methods
in machine learning"; Lakshminarayanan et al. 2017 for the better calibrated confidence it gives).

``CrfEnsembleTagger`` combines the members of a CRF ensemble the way a CRF combines its own features: the
ensemble's score of a tag sequence is the **mean of the members' scores** (emissions, start, end and transition
scores, each averaged over the members), so that its distribution over tag sequences is the members'
normalised geometric mean, ``P(y | x) ∝ Π_m P_m(y | x)^(1/M)`` (a product of experts, Hinton 2002). That is again
a linear-chain CRF, so everything the BiLSTM-CRF gives comes out of it unchanged: Viterbi tags, forward-backward
marginals and the exact k best sequences (``bilstm_crf.crf_confidence``), which the decision layer reads as it
reads one tagger's (issue 12).

Each member is a saved BiLSTM-CRF in its own sub-directory (``member0/``, ``member1/``, ...) of the ensemble's
directory, whose ``tagger.json`` names them; ``load_tagger`` loads it as any tagger. ``combine`` builds one from
trained taggers (``python -m drywall_lab ensemble --member DIR --member DIR ... --out DIR``); ``fit`` trains the
members itself, seeds ``seed``, ``seed + 1``, ...
"""
from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd
import torch
from torchcrf import CRF

from drywall_lab.corpus.tags import TAGS
from drywall_lab.nlu.base import (
    DEFAULT_SEED,
    KBest,
    Sentences,
    TagConfidence,
    Tagger,
    TaggerLoadError,
    check_k,
    check_sentences,
    load_tagger,
    resolve_device,
)
from drywall_lab.nlu.bilstm_crf import BiLstmCrfTagger, crf_confidence

MEMBER_DIR = "member{}"


def members_history(members: Sequence[BiLstmCrfTagger]) -> pd.DataFrame:
    """An ensemble's training history: its members' epochs one after the other, a ``member`` column saying whose."""
    return pd.concat([m.history.assign(member=i) for i, m in enumerate(members)], ignore_index=True)


class CrfEnsembleTagger(Tagger):
    """BiLSTM-CRF taggers (``members``, all with the same labels) whose CRF scores are averaged (module docstring).

    ``members``: trained ``BiLstmCrfTagger`` objects, or none, to be trained by ``fit`` from ``member_settings``
    (``BiLstmCrfTagger`` keyword arguments) ``n_members`` times.
    """

    kind = "bilstm-crf-ensemble"

    def __init__(
        self,
        members: Sequence[BiLstmCrfTagger] = (),
        *,
        labels: Sequence[str] = TAGS,
        tag_field: str = "tags",
        n_members: int = 3,
        member_settings: Mapping[str, Any] | None = None,
    ) -> None:
        members = list(members)
        if members:
            labels, tag_field = members[0].labels, members[0].tag_field
        super().__init__(labels=labels, tag_field=tag_field)
        for i, member in enumerate(members):
            if not isinstance(member, BiLstmCrfTagger):
                raise TypeError(f"member {i} is a {type(member).__name__}; an ensemble combines BiLSTM-CRF taggers")
            if not member.is_trained:
                raise ValueError(f"member {i} is not trained: train it (or load it) before combining it")
            if member.labels != self.labels or member.tag_field != self.tag_field:
                raise ValueError(f"member {i} tags {member.tag_field!r} with other labels than member 0: "
                                 "the members of an ensemble must share their labels")
        if n_members < 1:
            raise ValueError(f"an ensemble needs at least one member, got n_members={n_members}")
        self.members: list[BiLstmCrfTagger] = members
        self.n_members = len(members) or int(n_members)
        self.member_settings = dict(member_settings or {})
        self._crf: CRF | None = None
        if members:
            self._combine()

    @classmethod
    def combine(cls, members: Sequence[BiLstmCrfTagger]) -> "CrfEnsembleTagger":
        """The ensemble of trained taggers (at least one)."""
        if not members:
            raise ValueError("combine needs at least one trained BiLSTM-CRF tagger")
        ensemble = cls(members)
        ensemble.history = members_history(members)
        ensemble.training_info = {"members": [dict(m.training_info) for m in members]}
        return ensemble

    # -- the averaged CRF -----------------------------------------------------------------------
    def _combine(self) -> None:
        """The CRF whose start, end and transition scores are the members' means."""
        crf = CRF(len(self.labels), batch_first=True)
        with torch.no_grad():
            for name in ("start_transitions", "end_transitions", "transitions"):
                mean = torch.stack([getattr(m.network.crf, name).detach().cpu() for m in self.members]).mean(dim=0)
                getattr(crf, name).copy_(mean)
        self._crf = crf.to(self.device)

    def _batches(self, sentences: Sentences, batch_size: int):
        """(indices, mean emissions, mask) for batches of the non-empty word lists."""
        todo = [i for i, words in enumerate(sentences) if words]
        step = max(1, batch_size)
        for member in self.members:
            member.network.eval()
        for start in range(0, len(todo), step):
            index = todo[start : start + step]
            batch = [sentences[i] for i in index]
            parts = [member._emissions(batch) for member in self.members]
            emissions = torch.stack([e.to(self.device) for e, _ in parts]).mean(dim=0)
            yield index, emissions, parts[0][1].to(self.device)

    # -- the Tagger interface ---------------------------------------------------------------------
    def settings(self) -> dict[str, Any]:
        return {"n_members": self.n_members, "member_settings": self.member_settings}

    @property
    def is_trained(self) -> bool:
        return self._crf is not None

    @property
    def crf(self) -> CRF:
        """The averaged CRF: its start, end and transition scores are the members' means."""
        self._check_trained("crf")
        return self._crf

    def n_parameters(self) -> int:
        self._check_trained("n_parameters")
        return sum(m.n_parameters() for m in self.members)

    def _move(self, device: str) -> None:
        for member in self.members:
            member.to(device)
        if self._crf is not None:
            self._crf.to(device)

    def fit(
        self,
        train_rows: Sequence[Mapping],
        validation_rows: Sequence[Mapping] | None = None,
        *,
        epochs: int | None = None,
        progress: bool = True,
        seed: int = DEFAULT_SEED,
        device: str | None = None,
    ) -> pd.DataFrame:
        """Train ``n_members`` BiLSTM-CRFs from ``member_settings`` with seeds ``seed``, ``seed + 1``, ...; the
        history is the members' epochs one after the other (``member`` column)."""
        if device is not None:
            self._device = resolve_device(device)
        members = []
        for i in range(self.n_members):
            member = BiLstmCrfTagger(labels=self.labels, tag_field=self.tag_field, **self.member_settings)
            member.fit(train_rows, validation_rows, epochs=epochs, progress=progress, seed=seed + i, device=self._device)
            members.append(member)
        self.members = members
        self._combine()
        self.history = members_history(members)
        self.training_info = {"members": [dict(m.training_info) for m in members], "seed": seed}
        return self.history

    def predict(self, sentences: Sentences, batch_size: int = 64) -> list[list[str]]:
        """The Viterbi tags of the averaged CRF."""
        sentences = check_sentences(sentences)
        self._check_trained("predict")
        out: list[list[str]] = [[] for _ in sentences]
        with torch.inference_mode():
            for index, emissions, mask in self._batches(sentences, batch_size):
                for i, path in zip(index, self._crf.decode(emissions, mask=mask)):
                    out[i] = [self.labels[t] for t in path]
        return out

    def predict_marginals(self, sentences: Sentences, batch_size: int = 64) -> list[np.ndarray]:
        return [c.marginals for c in self.predict_confidence(sentences, k=1, batch_size=batch_size)]

    def predict_kbest(self, sentences: Sentences, k: int, batch_size: int = 64) -> list[KBest]:
        return [c.kbest for c in self.predict_confidence(sentences, k=k, batch_size=batch_size)]

    def predict_confidence(self, sentences: Sentences, k: int = 5, batch_size: int = 64) -> list[TagConfidence]:
        """Viterbi tags, forward-backward marginals and the k best sequences of the averaged CRF."""
        k = check_k(k)
        sentences = check_sentences(sentences)
        self._check_trained("predict_confidence")
        out = [TagConfidence([], np.zeros((0, len(self.labels))), [([], 0.0)]) for _ in sentences]
        with torch.inference_mode():
            for index, emissions, mask in self._batches(sentences, batch_size):
                marginals, kbest = crf_confidence(self._crf, emissions, mask, k)
                for row, i in enumerate(index):
                    out[i] = TagConfidence(
                        [self.labels[t] for t in kbest[row][0][0]],
                        marginals[row, : len(sentences[i])],
                        [([self.labels[t] for t in path], log_p) for path, log_p in kbest[row]],
                    )
        return out

    # -- saving and loading ----------------------------------------------------------------------
    def _save_weights(self, directory: Path) -> dict[str, Any]:
        names = []
        for i, member in enumerate(self.members):
            names.append(MEMBER_DIR.format(i))
            member.save(directory / names[-1])
        return {"members": names}

    @classmethod
    def _load_weights(cls, directory: Path, meta: Mapping[str, Any]) -> "CrfEnsembleTagger":
        names = meta.get("members")
        if not isinstance(names, list) or not names or not all(isinstance(n, str) and "/" not in n for n in names):
            raise TaggerLoadError(f"{directory}: tagger.json names no member directories (a 'members' list)")
        members = []
        for name in names:
            member = load_tagger(directory / name)
            if not isinstance(member, BiLstmCrfTagger):
                raise TaggerLoadError(f"{directory}: member {name} is a {member.kind} tagger, not a BiLSTM-CRF")
            if member.labels != list(meta["labels"]):
                raise TaggerLoadError(f"{directory}: member {name} has other labels than the ensemble's tagger.json")
            members.append(member)
        ensemble = cls(members, member_settings=meta["settings"].get("member_settings"))
        ensemble.history = members_history(members)
        return ensemble
