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

**Speed** (issue 29). A second member doubled the network's cost, and on a CPU a single short instruction is
mostly per-call costs around a small amount of arithmetic. At prediction the members therefore run as one
computation wherever they read their input alike (the same vocabulary, characters, id handling and widths, as
members trained on the same data do; ``_FusedMembers``): a batch's words and characters are turned into ids once
and looked up once in the members' embedding tables concatenated, the LSTMs read one packed batch (each member its
own columns), and the Viterbi path, the marginals and the k best use the averaged CRF's scores made into NumPy arrays
once, at load (the Viterbi path is a NumPy transcription of ``torchcrf``'s decode: the same float32 additions in
the same order). Each member's own convolution, LSTM and linear layer still does its own arithmetic, so the
emissions are the member-by-member computation's bit for bit at the same thread setting; that computation is kept
(``_batches``, ``_reference_emissions``, ``_reference_predict``, ``_reference_confidence``) and
``tests/test_ensemble_speed.py`` compares the two. A batch of at most ``SINGLE_THREAD_WORDS`` words (one instruction)
runs on one intra-op thread, torch's setting restored after: on a 2-core machine that is also running other work,
two threads' synchronisation on matrices this small costs more than it saves. The members' LSTMs, nearly all the
remaining time, run side by side instead, each on one thread (the first on the calling thread, the others on a
small pool's; torch releases the interpreter inside ``torch.lstm``): one instruction's tags in about 1.8 ms where
one after the other took 2.5 ms, the same arithmetic on each thread, so the same emissions bit for bit.
``torch.vmap`` over the members has no batching rule for ``aten::lstm`` (torch 2.13), and on a CPU one
block-diagonal LSTM of the members' summed width (four times the arithmetic) and one ``bmm`` recurrence over all
members and directions (a Python loop over the words) were both slower than two ``torch.lstm`` calls.
"""
from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from functools import lru_cache
from pathlib import Path
from typing import Any, Callable, Iterator, Mapping, Sequence

import numpy as np
import pandas as pd
import torch
import torch.nn.functional as F
from torch.nn.utils.rnn import PackedSequence, pack_padded_sequence, pad_packed_sequence
from torchcrf import CRF

from drywall_lab.corpus.tags import TAGS
from drywall_lab.nlu.base import (KBest, Sentences, TagConfidence, Tagger, TaggerLoadError, check_k, load_tagger,
                                   resolve_device)
from drywall_lab.nlu.bilstm_crf import (CHAR_KERNEL_SIZE, BiLstmCrfTagger, _forward_backward, _kbest, _log_partition,
                                         crf_confidences, fill_confidence, no_confidences, viterbi_tags)

MEMBER_DIR = "member{}"
#: A batch of at most this many words (all sentences together) runs on one intra-op thread (module docstring,
#: "Speed"); 0 turns that off. Larger batches keep torch's thread setting.
SINGLE_THREAD_WORDS = 64
#: Members after the first that read such a short batch each on a thread of its own, side by side with the first
#: (``_side_by_side``); an ensemble of more members reads them one after the other.
MAX_SIDE_BY_SIDE = 3


def members_history(members: Sequence[BiLstmCrfTagger]) -> pd.DataFrame:
    """An ensemble's training history: its members' epochs one after the other, a ``member`` column saying whose."""
    return pd.concat([m.history.assign(member=i) for i, m in enumerate(members)], ignore_index=True)


@contextmanager
def _intra_op_threads(n_words: int) -> Iterator[None]:
    """Run a batch of at most ``SINGLE_THREAD_WORDS`` words on one intra-op thread; torch's setting is restored after
    (module docstring, "Speed")."""
    before = torch.get_num_threads()
    if before <= 1 or n_words > SINGLE_THREAD_WORDS:
        yield
        return
    torch.set_num_threads(1)
    try:
        yield
    finally:
        torch.set_num_threads(before)


def _read_alike(members: Sequence[BiLstmCrfTagger]) -> bool:
    """Whether the members turn words into the same ids and vectors of the same widths (so ``_FusedMembers`` can run
    them as one): the same vocabulary, characters, id handling, embedding and character widths."""
    def reading(m: BiLstmCrfTagger) -> tuple:
        return (m.vocabulary, m.characters, m.id_prefix_digits, m.embedding_dim, m.char_embedding_dim, m.char_filters)

    return all(reading(m) == reading(members[0]) for m in members[1:])


def _viterbi(e: np.ndarray, lengths: np.ndarray, start: np.ndarray, end: np.ndarray,
             trans: np.ndarray) -> list[list[int]]:
    """``torchcrf.CRF.decode`` in NumPy: the same float32 additions in the same order, ties to the first index.

    ``e``: float32 emissions (batch, time, tags); ``lengths``: words per row (at least 1); the CRF's scores in float32.
    """
    batch, time, _ = e.shape
    shortest = int(lengths.min())
    score = start + e[:, 0]
    history = []
    for t in range(1, time):
        candidates = score[:, :, None] + trans
        candidates += e[:, t, None, :]
        history.append(candidates.argmax(axis=1))
        best = candidates.max(axis=1)
        score = best if t < shortest else np.where((t < lengths)[:, None], best, score)
    score = score + end
    paths = []
    for b in range(batch):
        tag = int(score[b].argmax())
        path = [tag]
        for t in range(int(lengths[b]) - 1, 0, -1):
            tag = int(history[t - 1][b, tag])
            path.append(tag)
        paths.append(path[::-1])
    return paths


@lru_cache(maxsize=1)
def _member_pool() -> ThreadPoolExecutor:
    """The threads that read the members after the first, side by side with it (``_side_by_side``)."""
    return ThreadPoolExecutor(max_workers=MAX_SIDE_BY_SIDE, thread_name_prefix="ensemble-member")


def _on_one_thread(read: Callable[[int], torch.Tensor], m: int) -> torch.Tensor:
    torch.set_num_threads(1)
    with torch.inference_mode():
        return read(m)


def _side_by_side(read: Callable[[int], torch.Tensor], n: int) -> list[torch.Tensor]:
    """``read(m)`` for the members ``m`` < ``n``, the first on the calling thread and the others each on a thread of
    ``_member_pool`` at the same time, every one on one intra-op thread (module docstring, "Speed")."""
    others = [_member_pool().submit(_on_one_thread, read, m) for m in range(1, n)]
    return [read(0)] + [future.result() for future in others]


class _FusedMembers:
    """The members' networks (in evaluation mode) run as one computation, for members that read their input alike.

    The words and characters of a batch are looked up once, in the members' embedding tables concatenated into
    one (one table for words, one for characters); the members' LSTMs read one packed batch, each its own columns
    of it. Each member's character convolution, LSTM and linear layer still does its own arithmetic on its own
    numbers, so the mean emissions are those of the members run one by one, bit for bit (a grouped convolution or
    one matrix over all members' LSTM outputs would be a few microseconds faster, but sums in another order).
    Built from the members' weights as they are: ``CrfEnsembleTagger`` rebuilds it when it combines or moves them.
    """

    def __init__(self, members: Sequence[BiLstmCrfTagger], device: str) -> None:
        self.first = members[0]
        self.networks = [m.network for m in members]
        self.n = len(members)
        self.width = self.first.embedding_dim + self.first.char_filters  # what each LSTM reads per word
        self.char_dim = self.first.char_embedding_dim
        with torch.no_grad():
            self.word_table = torch.cat([n.embedding.weight for n in self.networks], dim=1).to(device)
            self.char_table = (torch.cat([n.char_cnn.embedding.weight for n in self.networks], dim=1).to(device)
                               if self.first.uses_characters else None)
        self.device = device

    def inputs(self, sentences: Sequence[Sequence[str]]) -> tuple[torch.Tensor, list[int], torch.Tensor | None]:
        """(word ids (batch, time), lengths, character ids (batch * time, chars) or None) of non-empty word lists,
        as the members' ``_batch`` and ``_char_batch`` make them."""
        first = self.first
        lengths = [len(s) for s in sentences]
        time = max(lengths)
        words = torch.tensor([first.word_ids(s) + [0] * (time - len(s)) for s in sentences], dtype=torch.long)
        chars = None
        if first.uses_characters:
            char_lists = [first.char_ids(s) for s in sentences]
            width = max(len(c) for ids in char_lists for c in ids) or 1
            rows = []
            for ids in char_lists:
                rows.extend(c + [0] * (width - len(c)) for c in ids)
                rows.extend([[0] * width] * (time - len(ids)))
            chars = torch.tensor(rows, dtype=torch.long)
        if self.device != "cpu":
            words = words.to(self.device)
            chars = chars.to(self.device) if chars is not None else None
        return words, lengths, chars

    def emissions(self, words: torch.Tensor, lengths: list[int], chars: torch.Tensor | None,
                  concurrent: bool = False) -> torch.Tensor:
        """The members' mean emissions (batch, time, tags): ``BiLstmCrfNetwork.emissions`` of each in evaluation
        mode, stacked and averaged; ``concurrent``: the members' LSTMs side by side (``_side_by_side``)."""
        nets = self.networks
        for net in nets:
            if net.training:
                net.eval()
        batch, time = words.shape
        n = self.n
        x = F.embedding(words, self.word_table).view(batch, time, n, -1)
        if chars is not None:
            present = chars != 0
            embedded = F.embedding(chars, self.char_table)  # (words, chars, member * char_dim)
            d = self.char_dim
            h = torch.cat([F.conv1d(embedded[:, :, m * d : (m + 1) * d].transpose(1, 2), net.char_cnn.conv.weight,
                                    net.char_cnn.conv.bias, padding=CHAR_KERNEL_SIZE // 2)
                           for m, net in enumerate(nets)], dim=1)
            pooled = h.masked_fill(~present[:, None, :], float("-inf")).max(dim=2).values
            pooled = torch.where(present.any(dim=1, keepdim=True), pooled, torch.zeros_like(pooled))
            x = torch.cat([x, pooled.view(batch, time, n, -1)], dim=3)  # (batch, time, member, width)
        if min(lengths) == time:  # nothing to pack
            inputs = [x[:, :, m].contiguous() for m in range(n)]

            def read(m: int) -> torch.Tensor:
                return nets[m].lstm(inputs[m])[0]
        else:
            packed = pack_padded_sequence(x.reshape(batch, time, n * self.width), torch.tensor(lengths),
                                          batch_first=True, enforce_sorted=False)
            data = packed.data.view(-1, n, self.width)

            def read(m: int) -> torch.Tensor:
                out = nets[m].lstm(PackedSequence(data[:, m].contiguous(), *packed[1:]))[0]
                return pad_packed_sequence(out, batch_first=True, total_length=time)[0]
        outs = _side_by_side(read, n) if concurrent else [read(m) for m in range(n)]
        return torch.stack([net.tag_scores(out) for out, net in zip(outs, nets)]).mean(dim=0)


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
        self._fused: _FusedMembers | None = None
        self._scores64: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        self._scores32: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
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
        """The CRF whose start, end and transition scores are the members' means (and the fast path's parts)."""
        crf = CRF(len(self.labels), batch_first=True)
        with torch.no_grad():
            for name in ("start_transitions", "end_transitions", "transitions"):
                mean = torch.stack([getattr(m.network.crf, name).detach().cpu() for m in self.members]).mean(dim=0)
                getattr(crf, name).copy_(mean)
        self._crf = crf.to(self.device)
        self._prepare(self.device)

    def _prepare(self, device: str) -> None:
        """What prediction reuses from call to call: the averaged CRF's scores as NumPy arrays (float32 for the
        Viterbi path, float64 for the marginals and k best, as ``crf_confidence`` makes them) and the fused members."""
        scores = [getattr(self._crf, name).detach().cpu() for name in ("start_transitions", "end_transitions",
                                                                        "transitions")]
        self._scores32 = tuple(x.numpy().copy() for x in scores)
        self._scores64 = tuple(x.double().numpy() for x in scores)
        self._fused = _FusedMembers(self.members, device) if _read_alike(self.members) else None

    # -- the members one by one: the straightforward computation (the fast path's reference) ----------------------
    def _batches(self, sentences: Sentences, batch_size: int):
        """(indices, mean emissions, mask) for batches of the non-empty word lists, each member run on its own."""
        todo = [i for i, words in enumerate(sentences) if words]
        step = max(1, batch_size)
        for member in self.members:
            member.network.eval()
        for start in range(0, len(todo), step):
            index = todo[start : start + step]
            yield index, *self._reference_emissions([sentences[i] for i in index])

    def _reference_emissions(self, batch: Sequence[Sequence[str]]) -> tuple[torch.Tensor, torch.Tensor]:
        """(mean emissions, mask) of non-empty word lists: every member's own ``_emissions``, stacked and averaged."""
        parts = [member._emissions(batch) for member in self.members]
        emissions = torch.stack([e.to(self.device) for e, _ in parts]).mean(dim=0)
        return emissions, parts[0][1].to(self.device)

    def _reference_predict(self, sentences: Sentences, batch_size: int = 64) -> list[list[str]]:
        """``predict`` member by member, decoded by ``torchcrf``."""
        sentences = self._checked(sentences, "predict")
        return viterbi_tags(self._crf, self._batches(sentences, batch_size), self.labels, len(sentences))

    def _reference_confidence(self, sentences: Sentences, k: int = 5, batch_size: int = 64) -> list[TagConfidence]:
        """``predict_confidence`` member by member, through ``crf_confidence``."""
        k = check_k(k)
        sentences = self._checked(sentences, "predict_confidence")
        return crf_confidences(self._crf, self._batches(sentences, batch_size), sentences, self.labels, k)

    # -- the members as one (the fast path) ----------------------------------------------------------------------
    def _fast_batches(self, sentences: Sentences, batch_size: int):
        """(indices, mean emissions as float32 NumPy (batch, time, tags), lengths) for batches of the non-empty word
        lists, from the fused members; each batch is computed inside ``_intra_op_threads``."""
        todo = [i for i, words in enumerate(sentences) if words]
        step = max(1, batch_size)
        for start in range(0, len(todo), step):
            index = todo[start : start + step]
            batch = [sentences[i] for i in index]
            cores = torch.get_num_threads()
            n_words = sum(map(len, batch))
            with _intra_op_threads(n_words), torch.inference_mode():
                words, lengths, chars = self._fused.inputs(batch)
                concurrent = (self._fused.device == "cpu" and cores > 1 and n_words <= SINGLE_THREAD_WORDS
                              and self.n_members - 1 <= MAX_SIDE_BY_SIDE)
                emissions = self._fused.emissions(words, lengths, chars, concurrent).cpu().numpy()
            yield index, emissions, np.array(lengths)

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
            self._prepare(device)

    def _fit(self, train_rows: Sequence[Mapping], validation_rows: Sequence[Mapping] | None, *, epochs: int | None,
             progress: bool, seed: int, device: str | None) -> pd.DataFrame:
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
        if self._fused is None:
            return self._reference_predict(sentences, batch_size)
        sentences = self._checked(sentences, "predict")
        out: list[list[str]] = [[] for _ in sentences]
        for index, emissions, lengths in self._fast_batches(sentences, batch_size):
            for i, path in zip(index, _viterbi(emissions, lengths, *self._scores32)):
                out[i] = [self.labels[t] for t in path]
        return out

    def predict_marginals(self, sentences: Sentences, batch_size: int = 64) -> list[np.ndarray]:
        return [c.marginals for c in self.predict_confidence(sentences, k=1, batch_size=batch_size)]

    def _float64_batches(self, sentences: Sentences, batch_size: int):
        """``_fast_batches`` as the CRF's NumPy recursions take them: (indices, float64 emissions, boolean mask)."""
        for index, emissions, lengths in self._fast_batches(sentences, batch_size):
            yield index, emissions.astype(np.float64), np.arange(emissions.shape[1])[None, :] < lengths[:, None]

    def predict_kbest(self, sentences: Sentences, k: int, batch_size: int = 64) -> list[KBest]:
        """The k best sequences of the averaged CRF with their log-probabilities, from the forward half alone
        (log Z; no marginals): the readings the decision weighs, a third cheaper than ``predict_confidence``."""
        if self._fused is None:
            return [c.kbest for c in self._reference_confidence(sentences, k, batch_size)]
        k = check_k(k)
        sentences = self._checked(sentences, "predict_kbest")
        out: list[KBest] = [[([], 0.0)] for _ in sentences]
        for index, e, mask in self._float64_batches(sentences, batch_size):
            with torch.inference_mode():
                kbest = _kbest(e, mask, *self._scores64, k, _log_partition(e, mask, *self._scores64))
            for row, i in enumerate(index):
                out[i] = [([self.labels[t] for t in path], log_p) for path, log_p in kbest[row]]
        return out

    def predict_confidence(self, sentences: Sentences, k: int = 5, batch_size: int = 64) -> list[TagConfidence]:
        """Viterbi tags, forward-backward marginals and the k best sequences of the averaged CRF."""
        if self._fused is None:
            return self._reference_confidence(sentences, k, batch_size)
        k = check_k(k)
        sentences = self._checked(sentences, "predict_confidence")
        out = no_confidences(len(sentences), self.labels)
        for index, e, mask in self._float64_batches(sentences, batch_size):
            with torch.inference_mode():  # the k best's many small torch.topk calls skip autograd's bookkeeping
                marginals, log_z = _forward_backward(e, mask, *self._scores64)
                kbest = _kbest(e, mask, *self._scores64, k, log_z)
            fill_confidence(out, index, sentences, self.labels, marginals, kbest)
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
