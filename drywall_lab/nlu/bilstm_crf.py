"""The BiLSTM-CRF tagger (the paper's section "BiLSTM-CRF", Fig. 3 and Fig. 8(a)).

Words are looked up in an embedding table, read left to right and right to left by a
two-layer bidirectional LSTM, turned into one score per tag and word by a linear layer,
and a CRF layer (``torchcrf.CRF``) picks the best tag sequence with the transition scores
it learned between neighbouring tags. The loss is minus the CRF's log-likelihood.

**Vocabulary.** Words are lower-cased. Numbers are replaced by shape tokens so that an
id never seen in training is still read as an id: a 5- to 7-digit number (the paper's
BIM ids, section "Data Generation") becomes ``<id:DDDD>``, keeping its first four digits
(``500113`` -> ``<id:5001>``, the class of the stud ids; ``500330`` -> ``<id:5003>``, the
panels), and an id with an unseen prefix falls back to ``<id>``. Other words the
training data never showed back off to ``<num>`` (other numbers), ``<ordinal>``
(``7th``) or ``<unk>``. Those fallback tokens are learned by *word dropout*: during
training each word is replaced by its fallback token with probability
``max(word_dropout, unk_alpha / (unk_alpha + count))`` (count = how often the training
data has it; Kiperwasser & Goldberg 2016), so rare words and a share of all words
teach the network what to do with a word it does not know, from context alone.

**Characters** (off by default, so the paper's network is unchanged; ``CHAR_FEATURES``
turns them on). With ``char_embedding_dim`` and ``char_filters`` above 0 each word also
gets a vector from its characters, the character CNN of Ma & Hovy (2016, section 2.1 and
Table 1: character embedding 30, 30 filters of width 3, max-pooling over the word):
the word as typed, lower-cased, is looked up character by character (characters the
training data never showed become ``<unk>``; at most ``MAX_WORD_CHARS`` per word),
convolved and max-pooled, and the result is concatenated to the word embedding. So a
word the vocabulary lacks ("sheetrock", "4'x8'", "eight-footer") is not only ``<unk>``:
it still carries its form. A word replaced by its fallback token by word dropout keeps
its characters, which is what teaches the network to read them.

**Weight averaging** (off by default; ``swa_epochs``). Over the last ``swa_epochs`` epochs the network's weights
are averaged after every optimizer step (stochastic weight averaging, Izmailov et al. 2018, "Averaging Weights
Leads to Wider Optima and Better Generalization"; ``torch.optim.swa_utils.AveragedModel``, equal weights), and the
average is the trained network. Training is unchanged, and so is the model's size; only the weights kept differ.
The averaged network generalises better off the generator's language: the shipped recipe with 3 averaged epochs of
8, over three seeds, is right on more hand-written field steps with fewer wrong actions than without
(``benchmarks/results/field_seeds.md``; README, "One training run is one draw").

**Confidence** (issue 12). ``predict_marginals`` runs the forward-backward algorithm over
the CRF's emission, start, end and transition scores (``crf_marginals``);
``predict_kbest`` is an exact k-best (list) Viterbi (``crf_kbest``), each sequence's
log-probability being its score minus log Z. Both run in float64 NumPy, the forward-backward
with a scale factor per word (exact to rounding; a log-space fallback for extreme scores).
"""
from __future__ import annotations

import json
import re
import time
from collections import Counter
from pathlib import Path
from typing import Any, Iterable, Mapping, Sequence

import numpy as np
import pandas as pd
import torch
from torch import nn
from torch.nn.utils.rnn import pack_padded_sequence, pad_packed_sequence
from torch.optim.swa_utils import AveragedModel
from torchcrf import CRF
from tqdm.auto import tqdm

from drywall_lab.corpus.tags import TAGS
from drywall_lab.nlu.base import (KBest, Sentences, TagConfidence, Tagger, TaggerLoadError, check_k,
                                   check_sentences)
from drywall_lab.nlu.metrics import acc_inst, acc_word

WEIGHTS_FILE = "weights.safetensors"
VOCABULARY_FILE = "vocabulary.json"
CHAR_VOCABULARY_FILE = "characters.json"
PAD, UNK, ID, NUM, ORDINAL = "<pad>", "<unk>", "<id>", "<num>", "<ordinal>"
#: Tokens every vocabulary starts with (``<pad>`` is id 0).
SPECIAL_TOKENS = (PAD, UNK, ID, NUM, ORDINAL)
#: The character vocabulary starts with these (``<pad>`` is id 0, ``<unk>`` id 1); then single characters.
CHAR_SPECIAL_TOKENS = (PAD, UNK)
#: Characters read per word (a longer word is read from its first ``MAX_WORD_CHARS``).
MAX_WORD_CHARS = 24
#: The width of the character CNN's filters (Ma & Hovy 2016, Table 1).
CHAR_KERNEL_SIZE = 3
#: The character settings of Ma & Hovy (2016, Table 1), as ``train --char-features`` uses them.
CHAR_FEATURES = {"char_embedding_dim": 30, "char_filters": 30}

_ID = re.compile(r"\d{5,7}")
_NUMBER = re.compile(r"\d+(?:[.,]\d+)?")
_ORDINAL = re.compile(r"\d+(?:st|nd|rd|th)")


def word_key(word: str, id_prefix_digits: int = 4) -> str:
    """The vocabulary key of a word: lower-cased, an id replaced by its shape token.

    >>> word_key("Stud"), word_key("500113"), word_key("500113", id_prefix_digits=0), word_key("4x8")
    ('stud', '<id:5001>', '<id>', '4x8')
    """
    word = word.lower()
    if _ID.fullmatch(word):
        return f"<id:{word[:id_prefix_digits]}>" if id_prefix_digits > 0 else ID
    return word


def fallback_token(key: str) -> str:
    """The token an unknown (or dropped-out) vocabulary key backs off to.

    >>> [fallback_token(k) for k in ("<id:5001>", "12", "7th", "sheetrock", "<unk>")]
    ['<id>', '<num>', '<ordinal>', '<unk>', '<unk>']
    """
    if key.startswith("<id"):
        return ID
    if _NUMBER.fullmatch(key):
        return NUM
    if _ORDINAL.fullmatch(key):
        return ORDINAL
    return UNK


def word_characters(word: str) -> str:
    """The characters the character CNN reads of a word: the word as typed, lower-cased, cut at ``MAX_WORD_CHARS``.

    >>> word_characters("Sheetrock"), word_characters("4'X8'")
    ('sheetrock', "4'x8'")
    """
    return word.lower()[:MAX_WORD_CHARS]


def character_vocabulary(words: Iterable[str]) -> list[str]:
    """``<pad>``, ``<unk>``, then every character of ``words`` (as ``word_characters`` reads them), sorted.

    >>> character_vocabulary(["Stud", "4x8"])
    ['<pad>', '<unk>', '4', '8', 'd', 's', 't', 'u', 'x']
    """
    return [*CHAR_SPECIAL_TOKENS, *sorted({c for w in words for c in word_characters(w)})]


class CharCnn(nn.Module):
    """Ma & Hovy's (2016) character CNN: char embedding -> dropout -> convolution (width 3) -> max over the word.

    Input: character ids (words, chars), 0 = padding; output (words, ``n_filters``). A word
    with no characters (an empty string, or a padding position) gives zeros. Padding
    characters embed to zeros, so a word's vector does not depend on how long the other
    words of its batch are.
    """

    def __init__(self, n_chars: int, char_embedding_dim: int, n_filters: int, dropout: float) -> None:
        super().__init__()
        self.embedding = nn.Embedding(n_chars, char_embedding_dim, padding_idx=0)
        self.dropout = nn.Dropout(dropout)
        self.conv = nn.Conv1d(char_embedding_dim, n_filters, CHAR_KERNEL_SIZE, padding=CHAR_KERNEL_SIZE // 2)

    def forward(self, char_ids: torch.Tensor) -> torch.Tensor:
        present = char_ids != 0  # (words, chars)
        x = self.dropout(self.embedding(char_ids)).transpose(1, 2)  # (words, dim, chars)
        h = self.conv(x).masked_fill(~present[:, None, :], float("-inf"))
        pooled = h.max(dim=2).values
        return torch.where(present.any(dim=1, keepdim=True), pooled, torch.zeros_like(pooled))


class BiLstmCrfNetwork(nn.Module):
    """[Embedding ; char CNN] -> dropout -> BiLSTM (stacked) -> dropout -> linear tag scores -> CRF.

    Without characters (``n_chars == 0``) this is the paper's network, parameter for parameter.
    """

    def __init__(
        self, vocabulary_size: int, n_tags: int, embedding_dim: int, hidden_size: int, num_layers: int, dropout: float,
        n_chars: int = 0, char_embedding_dim: int = 0, char_filters: int = 0,
    ) -> None:
        super().__init__()
        self.embedding = nn.Embedding(vocabulary_size, embedding_dim, padding_idx=0)
        self.dropout = nn.Dropout(dropout)
        self.lstm = nn.LSTM(
            embedding_dim + char_filters,
            hidden_size,
            num_layers=num_layers,
            bidirectional=True,
            batch_first=True,
            dropout=dropout if num_layers > 1 else 0.0,
        )
        self.tag_scores = nn.Linear(2 * hidden_size, n_tags)
        self.crf = CRF(n_tags, batch_first=True)
        # Created last, so that without characters the other layers draw the same random numbers as before.
        self.char_cnn = CharCnn(n_chars, char_embedding_dim, char_filters, dropout) if char_filters > 0 else None

    def word_vectors(self, word_ids: torch.Tensor, char_ids: torch.Tensor | None = None) -> torch.Tensor:
        """What the BiLSTM reads for each word, before dropout: (batch, time, embedding [+ char filters])."""
        x = self.embedding(word_ids)
        if self.char_cnn is None:
            return x
        if char_ids is None:
            raise ValueError("this network reads characters: pass char_ids")
        batch, time = word_ids.shape
        chars = self.char_cnn(char_ids.reshape(batch * time, -1)).reshape(batch, time, -1)
        return torch.cat([x, chars], dim=-1)

    def emissions(
        self, word_ids: torch.Tensor, lengths: torch.Tensor, char_ids: torch.Tensor | None = None
    ) -> torch.Tensor:
        """Per-word tag scores, shape (batch, time, tags); padding positions are ignored by the LSTM."""
        x = self.dropout(self.word_vectors(word_ids, char_ids))
        packed = pack_padded_sequence(x, lengths.cpu(), batch_first=True, enforce_sorted=False)
        out, _ = self.lstm(packed)
        out, _ = pad_packed_sequence(out, batch_first=True, total_length=word_ids.size(1))
        return self.tag_scores(self.dropout(out))


# -- the CRF's probabilities (forward-backward, k-best Viterbi) -------------------------------------
def _crf_parts(crf: CRF, emissions: torch.Tensor, mask: torch.Tensor):
    """float64 copies of the scores (batch-first emissions) and a boolean mask whose first column is true."""
    if emissions.dim() != 3 or emissions.shape[:2] != mask.shape or emissions.size(2) != crf.num_tags:
        raise ValueError(f"emissions must be (batch, time, {crf.num_tags}) and mask (batch, time)")
    mask = mask.bool()
    if emissions.size(1) == 0 or not bool(mask[:, 0].all()):
        raise ValueError("every sequence needs at least one word (the mask's first column must be true)")
    if bool((mask[:, 1:] & ~mask[:, :-1]).any()):
        raise ValueError("the mask must be true on a prefix of each row (padding at the end only)")
    return (
        emissions.double(), mask, crf.start_transitions.double(), crf.end_transitions.double(),
        crf.transitions.double(),
    )


def _numpy_parts(crf: CRF, emissions: torch.Tensor, mask: torch.Tensor):
    """``_crf_parts`` as float64 NumPy arrays: these loops run one small step per word, where NumPy's
    per-call cost is a fraction of torch's (the decision layer's latency, issue 12)."""
    e, mask, start, end, trans = _crf_parts(crf, emissions, mask)
    return tuple(x.detach().cpu().numpy() for x in (e, mask, start, end, trans))


def _scaled_forward(e: np.ndarray, mask: np.ndarray, start: np.ndarray, end: np.ndarray, trans: np.ndarray):
    """The forward half of ``_forward_backward``: (alpha, each word's forward vector scaled to sum 1; log Z;
    the exponentiated emissions, transitions and end scores that the backward half reuses). A step whose every
    row goes on skips the mask's bookkeeping (one instruction at a time, the decision's case)."""
    batch, time, n_tags = e.shape
    shift = e.max(axis=2)
    emit = np.exp(e - shift[:, :, None])
    t_max = trans.max()
    step = np.exp(trans - t_max)
    every = mask.all(axis=0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        alpha = np.empty_like(e)
        a = np.exp(start - start.max()) * emit[:, 0]
        scale = a.sum(axis=1)
        log_z = np.log(scale) + start.max() + shift[:, 0]
        alpha[:, 0] = a = a / scale[:, None]
        for t in range(1, time):
            nxt = (a @ step) * emit[:, t]
            scale = nxt.sum(axis=1)
            if every[t]:
                a = nxt / scale[:, None]
                log_z = log_z + (np.log(scale) + t_max + shift[:, t])
            else:
                on = mask[:, t]
                a = np.where(on[:, None], nxt / scale[:, None], a)
                log_z = log_z + np.where(on, np.log(scale) + t_max + shift[:, t], 0.0)
            alpha[:, t] = a
        final = np.exp(end - end.max())
        log_z = log_z + np.log((a * final).sum(axis=1)) + end.max()
    return alpha, log_z, (emit, step, final)


def _log_partition(e: np.ndarray, mask: np.ndarray, start: np.ndarray, end: np.ndarray,
                   trans: np.ndarray) -> np.ndarray:
    """log Z alone, from the forward half (what the k best's log-probabilities need: no marginals)."""
    log_z = _scaled_forward(e, mask, start, end, trans)[1]
    if not np.isfinite(log_z).all():
        return _forward_backward_log(e, mask, start, end, trans)[1]
    return log_z


def _forward_backward(e: np.ndarray, mask: np.ndarray, start: np.ndarray, end: np.ndarray,
                      trans: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(marginals, log Z): forward-backward with a scale factor at every word (Rabiner's scaling).

    Scores are exponentiated after subtracting their maximum (per word for the emissions), the
    forward vector is renormalised to sum 1 at each word and the logs of the factors are summed:
    log Z is exact to rounding, and no quantity under- or overflows unless one step's scores
    span more than about 700 nats, in which case the log-space recursion is used instead.
    """
    batch, time, n_tags = e.shape
    alpha, log_z, (emit, step, final) = _scaled_forward(e, mask, start, end, trans)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        beta = np.empty_like(e)
        beta[:, time - 1] = b = np.broadcast_to(final, (batch, n_tags))
        for t in range(time - 2, -1, -1):
            nxt = (emit[:, t + 1] * b) @ step.T
            b = np.where(mask[:, t + 1, None], nxt / nxt.sum(axis=1, keepdims=True), final)
            beta[:, t] = b
        joint = alpha * beta
        marginals = joint / joint.sum(axis=2, keepdims=True) * mask[:, :, None]
    if not (np.isfinite(log_z).all() and np.isfinite(marginals).all()):
        return _forward_backward_log(e, mask, start, end, trans)
    return marginals, log_z


def _logsumexp(x: np.ndarray, axis: int) -> np.ndarray:
    top = x.max(axis=axis, keepdims=True)
    top = np.where(np.isfinite(top), top, 0.0)
    return np.squeeze(top, axis=axis) + np.log(np.exp(x - top).sum(axis=axis))


def _forward_backward_log(e, mask, start, end, trans) -> tuple[np.ndarray, np.ndarray]:
    """The same in log space: slower, for scores too extreme for the scaled recursion."""
    batch, time, _ = e.shape
    alpha = np.empty_like(e)
    alpha[:, 0] = start + e[:, 0]
    for t in range(1, time):
        step = _logsumexp(alpha[:, t - 1, :, None] + trans[None] + e[:, t, None, :], axis=1)
        alpha[:, t] = np.where(mask[:, t, None], step, alpha[:, t - 1])
    beta = np.empty_like(e)
    beta[:, time - 1] = end
    for t in range(time - 2, -1, -1):
        step = _logsumexp(trans[None] + (e[:, t + 1] + beta[:, t + 1])[:, None, :], axis=2)
        beta[:, t] = np.where(mask[:, t + 1, None], step, end)
    lengths = mask.sum(axis=1)
    log_z = _logsumexp(alpha[np.arange(batch), lengths - 1] + end, axis=1)
    return np.exp(alpha + beta - log_z[:, None, None]) * mask[:, :, None], log_z


def crf_log_partition(crf: CRF, emissions: torch.Tensor, mask: torch.Tensor) -> torch.Tensor:
    """log Z for each sequence (batch-first emissions), float64: the log-sum-exp of all tag sequences' scores."""
    return torch.from_numpy(_log_partition(*_numpy_parts(crf, emissions, mask)))


def crf_marginals(crf: CRF, emissions: torch.Tensor, mask: torch.Tensor) -> torch.Tensor:
    """P(tag of word t = j | words), float64 (batch, time, tags), by forward-backward.

    ``alpha_t(j) * beta_t(j) / Z``, where alpha sums the scores of all prefixes ending in j
    at t (start, emissions, transitions) and beta those of all suffixes after it
    (transitions, emissions, end), computed with scaling (``_forward_backward``). Padding
    positions (mask false) are zeros.
    """
    return torch.from_numpy(_forward_backward(*_numpy_parts(crf, emissions, mask))[0])


def crf_sequence_scores(crf: CRF, emissions: torch.Tensor, mask: torch.Tensor, tags: torch.Tensor) -> torch.Tensor:
    """The CRF's score of given tag sequences (batch-first, padded), float64: start + emissions + transitions + end."""
    e, mask, start, end, trans = _crf_parts(crf, emissions, mask)
    batch = torch.arange(e.size(0))
    score = start[tags[:, 0]] + e[batch, 0, tags[:, 0]]
    for t in range(1, e.size(1)):
        score = score + torch.where(mask[:, t], trans[tags[:, t - 1], tags[:, t]] + e[batch, t, tags[:, t]], 0.0)
    last = tags[batch, mask.sum(dim=1) - 1]
    return score + end[last]


def _kbest(e: np.ndarray, mask: np.ndarray, start: np.ndarray, end: np.ndarray, trans: np.ndarray, k: int,
           log_z: np.ndarray) -> list[list[tuple[list[int], float]]]:
    """``crf_kbest`` on NumPy parts, with log Z already known."""
    batch, time, n_tags = e.shape
    # scores[b, j, r]: the r-th best prefix score ending in tag j (-inf where fewer prefixes exist)
    scores = np.full((batch, n_tags, k), -np.inf)
    scores[:, :, 0] = start + e[:, 0]
    pointers = []  # per step t >= 1: (batch, tags, k) index into the previous step's tags * k + rank
    keep = np.broadcast_to(np.arange(n_tags * k).reshape(1, n_tags, k), (batch, n_tags, k))
    into = np.repeat(trans, k, axis=0)[None]  # row j * k + r: from tag j
    every = mask.all(axis=0)
    for t in range(1, time):
        candidates = scores.reshape(batch, n_tags * k, 1) + into + e[:, t, None, :]
        best, index = (x.numpy() for x in torch.from_numpy(candidates).topk(k, dim=1))  # (batch, k, tags)
        if every[t]:  # every row goes on: no padding to keep
            scores = best.transpose(0, 2, 1)
            pointers.append(index.transpose(0, 2, 1))
        else:
            on = mask[:, t, None, None]
            scores = np.where(on, best.transpose(0, 2, 1), scores)
            pointers.append(np.where(on, index.transpose(0, 2, 1), keep))
    final = (scores + end[None, :, None]).reshape(batch, n_tags * k)
    top, where = (x.numpy() for x in torch.from_numpy(final).topk(k, dim=1))
    lengths = mask.sum(axis=1)
    out = []
    for b in range(batch):
        found = []
        for score, flat in zip(top[b].tolist(), where[b].tolist()):
            if score == float("-inf"):
                break
            path = [flat // k]
            for t in range(int(lengths[b]) - 1, 0, -1):
                flat = int(pointers[t - 1][b, flat // k, flat % k])
                path.append(flat // k)
            found.append((path[::-1], score - float(log_z[b])))
        out.append(found)
    return out


def crf_kbest(crf: CRF, emissions: torch.Tensor, mask: torch.Tensor, k: int) -> list[list[tuple[list[int], float]]]:
    """The k highest-scoring tag sequences of each sequence with their log-probabilities (score - log Z).

    List Viterbi: at each word, for each tag, the k best prefixes ending in that tag are
    kept (a prefix outside them cannot start one of the k best paths, so this is exact).
    Per sequence: at most k (fewer when fewer tag sequences exist), best first; ties keep
    ``torch.topk``'s order. The first is the Viterbi path that ``crf.decode`` gives.
    """
    k = check_k(k)
    parts = _numpy_parts(crf, emissions, mask)
    return _kbest(*parts, k, _log_partition(*parts))


def fill_confidence(out: list[TagConfidence], index: Sequence[int], sentences: Sequence[Sequence[str]],
                    labels: Sequence[str], marginals: np.ndarray, kbest: list[list[tuple[list[int], float]]]) -> None:
    """Put each batch row's ``TagConfidence`` (best tags, marginals cut to its words, k best) at ``out[index[row]]``."""
    for row, i in enumerate(index):
        out[i] = TagConfidence([labels[t] for t in kbest[row][0][0]], marginals[row, : len(sentences[i])],
                               [([labels[t] for t in path], log_p) for path, log_p in kbest[row]])


def crf_confidence(crf: CRF, emissions: torch.Tensor, mask: torch.Tensor,
                   k: int) -> tuple[np.ndarray, list[list[tuple[list[int], float]]]]:
    """(marginals, k best) from one forward-backward: what ``predict_confidence`` needs."""
    k = check_k(k)
    parts = _numpy_parts(crf, emissions, mask)
    marginals, log_z = _forward_backward(*parts)
    return marginals, _kbest(*parts, k, log_z)


#: Batches of word lists as ``BiLstmCrfTagger._batches`` makes them: (indices, emissions, mask).
CrfBatches = Iterable[tuple[Sequence[int], torch.Tensor, torch.Tensor]]


def no_confidences(n: int, labels: Sequence[str]) -> list[TagConfidence]:
    """What ``predict_confidence`` gives each of ``n`` empty word lists; ``fill_confidence`` replaces the others."""
    return [TagConfidence([], np.zeros((0, len(labels))), [([], 0.0)]) for _ in range(n)]


def viterbi_tags(crf: CRF, batches: CrfBatches, labels: Sequence[str], n: int) -> list[list[str]]:
    """The Viterbi tags (``crf.decode``) of ``n`` word lists whose non-empty ones ``batches`` holds; ``[]`` for the
    empty ones."""
    out: list[list[str]] = [[] for _ in range(n)]
    with torch.inference_mode():
        for index, emissions, mask in batches:
            for i, path in zip(index, crf.decode(emissions, mask=mask)):
                out[i] = [labels[t] for t in path]
    return out


def crf_confidences(crf: CRF, batches: CrfBatches, sentences: Sequence[Sequence[str]], labels: Sequence[str],
                    k: int) -> list[TagConfidence]:
    """``predict_confidence`` of ``sentences`` whose non-empty ones ``batches`` holds (``crf_confidence``)."""
    out = no_confidences(len(sentences), labels)
    with torch.inference_mode():
        for index, emissions, mask in batches:
            marginals, kbest = crf_confidence(crf, emissions, mask, k)
            fill_confidence(out, index, sentences, labels, marginals, kbest)
    return out


class BiLstmCrfTagger(Tagger):
    """BiLSTM-CRF with the paper's settings (section "Data Generation and NLU", parameters).

    Paper: 2 layers, word embedding 50, "the number of hidden layer LSTM neurons is 300",
    batch 16, dropout 0.1, Adam with learning rate 0.001, 20 epochs, "about 250,000
    parameters" in total. Those figures do not all fit together, so one has to give:

    - read here (the default): 300 = the width of each BiLSTM layer's output, 150 units
      forward + 150 backward, in 2 stacked layers. On the project's training split (177
      vocabulary entries) that is 8,850 (embedding) + 784,800 (LSTM) + 3,913 (linear) +
      195 (CRF) = **797,758 parameters**, about three times the paper's total;
    - ``hidden_size=75`` (300 neurons = 2 layers x 2 directions x 75) gives the paper's
      total, 223,408 parameters, but on this corpus its validation Acc_inst swings
      between 97.5% and 100% from epoch to epoch and seed to seed, where 150 units end at
      100% on every seed tried (0-3); 300 units per direction would be 3.0 million.

    ``hidden_size`` is therefore the number of units per direction and layer, as in
    ``torch.nn.LSTM``. ``word_dropout``, ``unk_alpha`` and ``id_prefix_digits`` control
    how unseen words and ids are handled (see the module docstring). ``char_embedding_dim``
    and ``char_filters`` (both 0, off, by default: the paper's network; ``CHAR_FEATURES``
    for Ma & Hovy's 30 and 30) add the character CNN. ``labels`` and ``tag_field`` select
    the 13-tag task or the co-reference variant (Table 5). ``swa_epochs`` (0, off, by default) averages the
    weights over the last epochs (module docstring).
    """

    kind = "bilstm-crf"

    def __init__(
        self,
        *,
        labels: Sequence[str] = TAGS,
        tag_field: str = "tags",
        embedding_dim: int = 50,
        hidden_size: int = 150,
        num_layers: int = 2,
        dropout: float = 0.1,
        learning_rate: float = 1e-3,
        batch_size: int = 16,
        epochs: int = 20,
        word_dropout: float = 0.05,
        unk_alpha: float = 0.25,
        id_prefix_digits: int = 4,
        char_embedding_dim: int = 0,
        char_filters: int = 0,
        swa_epochs: int = 0,
    ) -> None:
        super().__init__(labels=labels, tag_field=tag_field)
        if min(embedding_dim, hidden_size, num_layers, batch_size, epochs) < 1:
            raise ValueError("embedding_dim, hidden_size, num_layers, batch_size and epochs must be positive")
        if not 0 <= dropout < 1:
            raise ValueError(f"dropout must be in [0, 1), got {dropout}")
        if not 0 <= word_dropout < 1:
            raise ValueError(f"word_dropout must be in [0, 1), got {word_dropout}")
        if not (unk_alpha >= 0 and 0 <= id_prefix_digits <= 7):
            raise ValueError("unk_alpha must be >= 0 and id_prefix_digits in 0..7")
        if learning_rate <= 0:
            raise ValueError(f"learning_rate must be positive, got {learning_rate}")
        if swa_epochs < 0:
            raise ValueError(f"swa_epochs must be at least 0 (0: no weight averaging), got {swa_epochs}")
        if char_embedding_dim < 0 or char_filters < 0 or (char_embedding_dim == 0) != (char_filters == 0):
            raise ValueError(
                "char_embedding_dim and char_filters must both be 0 (no character features) or both positive, "
                f"got {char_embedding_dim} and {char_filters}"
            )
        self.embedding_dim = embedding_dim
        self.hidden_size = hidden_size
        self.num_layers = num_layers
        self.dropout = dropout
        self.learning_rate = learning_rate
        self.batch_size = batch_size
        self.epochs = epochs
        self.word_dropout = word_dropout
        self.unk_alpha = unk_alpha
        self.id_prefix_digits = id_prefix_digits
        self.char_embedding_dim = char_embedding_dim
        self.char_filters = char_filters
        self.swa_epochs = swa_epochs
        self.vocabulary: list[str] = []
        self._index: dict[str, int] = {}
        self.characters: list[str] = []
        self._char_index: dict[str, int] = {}
        self.network: BiLstmCrfNetwork | None = None

    # -- settings and state ---------------------------------------------------------------
    def settings(self) -> dict[str, Any]:
        return {
            "embedding_dim": self.embedding_dim,
            "hidden_size": self.hidden_size,
            "num_layers": self.num_layers,
            "dropout": self.dropout,
            "learning_rate": self.learning_rate,
            "batch_size": self.batch_size,
            "epochs": self.epochs,
            "word_dropout": self.word_dropout,
            "unk_alpha": self.unk_alpha,
            "id_prefix_digits": self.id_prefix_digits,
            "char_embedding_dim": self.char_embedding_dim,
            "char_filters": self.char_filters,
            "swa_epochs": self.swa_epochs,
        }

    @property
    def uses_characters(self) -> bool:
        """Whether words are also read character by character (``char_filters > 0``)."""
        return self.char_filters > 0

    @property
    def is_trained(self) -> bool:
        return self.network is not None

    def n_parameters(self) -> int:
        self._check_trained("n_parameters")
        return sum(p.numel() for p in self.network.parameters() if p.requires_grad)

    def _build(self, vocabulary: Sequence[str], characters: Sequence[str] = ()) -> None:
        self.vocabulary = list(vocabulary)
        self._index = {w: i for i, w in enumerate(self.vocabulary)}
        self.characters = list(characters) if self.uses_characters else []
        self._char_index = {c: i for i, c in enumerate(self.characters)}
        self.network = BiLstmCrfNetwork(
            len(self.vocabulary), len(self.labels), self.embedding_dim, self.hidden_size, self.num_layers, self.dropout,
            n_chars=len(self.characters), char_embedding_dim=self.char_embedding_dim, char_filters=self.char_filters,
        )
        self.network.to(self.device)

    def _move(self, device: str) -> None:
        if self.network is not None:
            self.network.to(device)

    # -- words to ids -----------------------------------------------------------------------
    def word_ids(self, words: Sequence[str]) -> list[int]:
        """Vocabulary ids of the words: known keys as they are, others by their fallback token."""
        keys = (word_key(w, self.id_prefix_digits) for w in words)
        return [self._index.get(k, self._index[fallback_token(k)]) for k in keys]

    def char_ids(self, words: Sequence[str]) -> list[list[int]]:
        """Character-vocabulary ids of each word's characters (``word_characters``); unknown characters -> ``<unk>``."""
        unknown = self._char_index[UNK]
        return [[self._char_index.get(c, unknown) for c in word_characters(w)] for w in words]

    def _batch(self, id_lists: Sequence[Sequence[int]]) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        lengths = torch.tensor([len(ids) for ids in id_lists])
        padded = torch.zeros(len(id_lists), int(lengths.max()), dtype=torch.long)
        for i, ids in enumerate(id_lists):
            padded[i, : len(ids)] = torch.as_tensor(ids, dtype=torch.long)
        mask = torch.arange(padded.size(1))[None, :] < lengths[:, None]
        return padded.to(self.device), lengths, mask.to(self.device)

    def _char_batch(self, char_lists: Sequence[Sequence[Sequence[int]]], time: int) -> torch.Tensor | None:
        """(batch, time, chars) character ids, zero-padded; None without character features."""
        if not self.uses_characters:
            return None
        width = max((len(c) for words in char_lists for c in words), default=0) or 1
        padded = torch.zeros(len(char_lists), time, width, dtype=torch.long)
        for i, words in enumerate(char_lists):
            for j, chars in enumerate(words):
                if chars:
                    padded[i, j, : len(chars)] = torch.as_tensor(chars, dtype=torch.long)
        return padded.to(self.device)

    def _emissions(self, sentences: Sequence[Sequence[str]]) -> tuple[torch.Tensor, torch.Tensor]:
        """(emissions, mask) of non-empty word lists, in evaluation mode."""
        words, lengths, mask = self._batch([self.word_ids(s) for s in sentences])
        chars = self._char_batch([self.char_ids(s) for s in sentences], words.size(1)) if self.uses_characters else None
        return self.network.emissions(words, lengths, chars), mask

    def input_vectors(self, words: Sequence[str]) -> np.ndarray:
        """What the BiLSTM reads for each word (no dropout): (n_words, embedding_dim + char_filters).

        Without character features an unknown word is exactly its fallback token's vector
        (``<unk>``); with them, its characters make it its own.
        """
        self._check_trained("input_vectors")
        words = check_sentences([words])[0]
        if not words:
            return np.zeros((0, self.embedding_dim + self.char_filters), dtype=np.float32)
        ids, _, _ = self._batch([self.word_ids(words)])
        chars = self._char_batch([self.char_ids(words)], ids.size(1)) if self.uses_characters else None
        self.network.eval()
        with torch.inference_mode():
            return self.network.word_vectors(ids, chars)[0].cpu().numpy()

    # -- training -------------------------------------------------------------------------------
    def _fit(self, train_rows: Sequence[Mapping], validation_rows: Sequence[Mapping] | None, *, epochs: int | None,
             progress: bool, seed: int, device: str | None) -> pd.DataFrame:
        """Build the vocabulary (and the character vocabulary) from ``train_rows`` and train from scratch with Adam.

        Per epoch ``history`` records the mean training loss (minus the CRF
        log-likelihood per instruction), the training word accuracy as the paper's
        Fig. 13(a) plots it (over the epoch's batches, dropout on, as Keras reports it),
        validation Acc_word / Acc_inst when ``validation_rows`` are given, and seconds.
        ``device``: ``"auto"``, ``"cpu"`` or ``"cuda"`` (``None``: the tagger's, cpu unless ``to`` said so).
        With ``swa_epochs``, the weights are averaged over the last ``min(swa_epochs, epochs)`` epochs and the
        last row's validation figures are the averaged network's, the one kept.
        """
        train_rows, gold, validation_rows, validation_gold, epochs = self._fit_input(
            train_rows, validation_rows, epochs, self.epochs, device=device, seed=seed
        )
        rng = np.random.default_rng(seed)
        key_lists = [[word_key(w, self.id_prefix_digits) for w in r["words"]] for r in train_rows]
        counts = Counter(k for keys in key_lists for k in keys)
        characters = character_vocabulary(w for r in train_rows for w in r["words"]) if self.uses_characters else ()
        self._build([*SPECIAL_TOKENS, *sorted(k for k in counts if k not in SPECIAL_TOKENS)], characters)
        tag_index = {t: i for i, t in enumerate(self.labels)}
        tag_lists = [[tag_index[t] for t in tags] for tags in gold]
        key_ids = [np.array([self._index[k] for k in keys]) for keys in key_lists]
        fallback_ids = [np.array([self._index[fallback_token(k)] for k in keys]) for keys in key_lists]
        # A word dropped out to its fallback token keeps its characters.
        char_lists = [self.char_ids(r["words"]) for r in train_rows] if self.uses_characters else None
        drop_p = [
            np.array([max(self.word_dropout, self.unk_alpha / (self.unk_alpha + counts[k])) for k in keys])
            for keys in key_lists
        ]
        optimizer = torch.optim.Adam(self.network.parameters(), lr=self.learning_rate)
        n_batches = -(-len(train_rows) // self.batch_size)
        records = []
        bar = tqdm(total=epochs * n_batches, desc=f"{self.kind} training", unit="batch", disable=not progress)
        started = time.perf_counter()
        averaged = None
        for epoch in range(1, epochs + 1):
            t0 = time.perf_counter()
            if self.swa_epochs and epoch == max(1, epochs - self.swa_epochs + 1):
                averaged = AveragedModel(self.network)
            self.network.train()
            order = rng.permutation(len(train_rows))
            total_loss, correct, seen = 0.0, 0, 0
            for b in range(n_batches):
                index = order[b * self.batch_size : (b + 1) * self.batch_size]
                ids = [
                    np.where(rng.random(len(key_ids[i])) < drop_p[i], fallback_ids[i], key_ids[i]) for i in index
                ]
                words, lengths, mask = self._batch(ids)
                chars = self._char_batch([char_lists[i] for i in index], words.size(1)) if char_lists else None
                tags, _, _ = self._batch([tag_lists[i] for i in index])
                emissions = self.network.emissions(words, lengths, chars)
                loss = -self.network.crf(emissions, tags, mask=mask, reduction="mean")
                optimizer.zero_grad()
                loss.backward()
                optimizer.step()
                if averaged is not None:
                    averaged.update_parameters(self.network)
                with torch.no_grad():
                    for path, i in zip(self.network.crf.decode(emissions.detach(), mask=mask), index):
                        correct += sum(p == t for p, t in zip(path, tag_lists[i]))
                        seen += len(path)
                total_loss += loss.item() * len(index)
                bar.update()
                bar.set_postfix(epoch=epoch, loss=f"{loss.item():.3f}")
            records.append(self._epoch_record(
                epoch, loss_sum=total_loss, n_items=len(train_rows), correct=correct, seen=seen,
                validation_rows=validation_rows, validation_gold=validation_gold, bar=bar, started=t0,
            ))
        bar.close()
        if averaged is not None:
            self.network.load_state_dict(averaged.module.state_dict())
            if validation_gold is not None:
                self.network.eval()
                predicted = self.predict([r["words"] for r in validation_rows])
                records[-1]["val_acc_word"] = acc_word(validation_gold, predicted)
                records[-1]["val_acc_inst"] = acc_inst(validation_gold, predicted)
        self.network.eval()
        return self._finish_fit(records, n_train=len(train_rows), n_validation=len(validation_rows), epochs=epochs,
                                seed=seed, started=started)

    # -- prediction ---------------------------------------------------------------------------
    def _batches(self, sentences: Sentences, batch_size: int) -> Iterable[tuple[list[int], torch.Tensor, torch.Tensor]]:
        """(indices, emissions, mask) for batches of the non-empty word lists, in evaluation mode."""
        self.network.eval()
        todo = [i for i, words in enumerate(sentences) if words]
        step = max(1, batch_size)
        for start in range(0, len(todo), step):
            index = todo[start : start + step]
            emissions, mask = self._emissions([sentences[i] for i in index])
            yield index, emissions, mask

    def predict(self, sentences: Sentences, batch_size: int = 64) -> list[list[str]]:
        """Tag each word list (Viterbi decoding of the CRF); words as typed, any case."""
        sentences = self._checked(sentences, "predict")
        return viterbi_tags(self.network.crf, self._batches(sentences, batch_size), self.labels, len(sentences))

    def predict_marginals(self, sentences: Sentences, batch_size: int = 64) -> list[np.ndarray]:
        """Per word list, P(word i has label j) as an (n_words, n_labels) array: CRF forward-backward (``crf_marginals``)."""
        sentences = self._checked(sentences, "predict_marginals")
        out = [np.zeros((0, len(self.labels))) for _ in sentences]
        with torch.inference_mode():
            for index, emissions, mask in self._batches(sentences, batch_size):
                marginals = crf_marginals(self.network.crf, emissions, mask).cpu().numpy()
                for row, i in enumerate(index):
                    out[i] = marginals[row, : len(sentences[i])]
        return out

    def predict_kbest(self, sentences: Sentences, k: int, batch_size: int = 64) -> list[KBest]:
        """Per word list, the k most probable tag sequences and their log-probabilities (``crf_kbest``), best first.

        The first is ``predict``'s Viterbi path; an empty word list gives ``[([], 0.0)]``.
        """
        k = check_k(k)
        sentences = self._checked(sentences, "predict_kbest")
        out: list[KBest] = [[([], 0.0)] for _ in sentences]
        with torch.inference_mode():
            for index, emissions, mask in self._batches(sentences, batch_size):
                for i, found in zip(index, crf_kbest(self.network.crf, emissions, mask, k)):
                    out[i] = [([self.labels[t] for t in path], log_p) for path, log_p in found]
        return out

    def predict_confidence(self, sentences: Sentences, k: int = 5, batch_size: int = 64) -> list[TagConfidence]:
        """Viterbi tags (the first of the k best), forward-backward marginals and the k best sequences,
        from one pass of the network and one forward-backward (``crf_confidence``)."""
        k = check_k(k)
        sentences = self._checked(sentences, "predict_confidence")
        return crf_confidences(self.network.crf, self._batches(sentences, batch_size), sentences, self.labels, k)

    # -- saving and loading ----------------------------------------------------------------------
    def _save_weights(self, directory: Path) -> dict[str, Any]:
        from safetensors.torch import save_file

        state = {k: v.detach().cpu().contiguous() for k, v in self.network.state_dict().items()}
        save_file(state, str(directory / WEIGHTS_FILE), metadata={"kind": self.kind})
        (directory / VOCABULARY_FILE).write_text(json.dumps(self.vocabulary, ensure_ascii=False) + "\n", encoding="utf-8")
        files = {"weights": WEIGHTS_FILE, "vocabulary": VOCABULARY_FILE}
        if self.uses_characters:
            (directory / CHAR_VOCABULARY_FILE).write_text(
                json.dumps(self.characters, ensure_ascii=False) + "\n", encoding="utf-8"
            )
            files["characters"] = CHAR_VOCABULARY_FILE
        return {"files": files}

    @staticmethod
    def _read_characters(directory: Path) -> list[str]:
        """The character vocabulary of a saved tagger with character features; TaggerLoadError if unusable."""
        path = directory / CHAR_VOCABULARY_FILE
        if not path.is_file():
            raise TaggerLoadError(
                f"{directory} is not a complete saved tagger: its settings use character features "
                f"but {CHAR_VOCABULARY_FILE} is missing"
            )
        try:
            characters = json.loads(path.read_text(encoding="utf-8"))
        except (json.JSONDecodeError, UnicodeDecodeError) as e:
            raise TaggerLoadError(f"{directory}: {CHAR_VOCABULARY_FILE} is not valid JSON ({e})") from None
        n = len(CHAR_SPECIAL_TOKENS)
        if (
            not isinstance(characters, list)
            or characters[:n] != list(CHAR_SPECIAL_TOKENS)
            or not all(isinstance(c, str) and len(c) == 1 for c in characters[n:])
            or len(set(characters)) != len(characters)
        ):
            raise TaggerLoadError(
                f"{directory}: {CHAR_VOCABULARY_FILE} is not a character vocabulary "
                f"(a list starting with {list(CHAR_SPECIAL_TOKENS)}, then distinct single characters)"
            )
        return characters

    @classmethod
    def _load_weights(cls, directory: Path, meta: Mapping[str, Any]) -> "BiLstmCrfTagger":
        from safetensors import SafetensorError
        from safetensors.torch import load_file

        tagger = cls(labels=meta["labels"], tag_field=meta["tag_field"], **meta["settings"])
        for name in (VOCABULARY_FILE, WEIGHTS_FILE):
            if not (directory / name).is_file():
                raise TaggerLoadError(f"{directory} is not a complete saved tagger: {name} is missing")
        try:
            vocabulary = json.loads((directory / VOCABULARY_FILE).read_text(encoding="utf-8"))
        except (json.JSONDecodeError, UnicodeDecodeError) as e:
            raise TaggerLoadError(f"{directory}: {VOCABULARY_FILE} is not valid JSON ({e})") from None
        if not isinstance(vocabulary, list) or any(t not in vocabulary for t in SPECIAL_TOKENS):
            raise TaggerLoadError(f"{directory}: {VOCABULARY_FILE} is not a vocabulary list with the special tokens")
        characters = cls._read_characters(directory) if tagger.uses_characters else []
        try:
            state = load_file(str(directory / WEIGHTS_FILE), device="cpu")
        except (SafetensorError, OSError, ValueError) as e:
            raise TaggerLoadError(f"{directory}: {WEIGHTS_FILE} is corrupt ({e})") from None
        tagger._build(vocabulary, characters)
        try:
            tagger.network.load_state_dict({k: v.float() for k, v in state.items()})
        except RuntimeError as e:
            if "char_cnn.embedding.weight" in str(e) and "char_cnn.embedding.weight" in state:
                raise TaggerLoadError(
                    f"{directory}: {CHAR_VOCABULARY_FILE} lists {len(characters)} characters but {WEIGHTS_FILE} was "
                    f"trained with {state['char_cnn.embedding.weight'].shape[0]}; the files do not belong together"
                ) from None
            raise TaggerLoadError(
                f"{directory}: {WEIGHTS_FILE} does not fit the settings in tagger.json ({str(e).splitlines()[0]})"
            ) from None
        tagger.network.eval()
        return tagger
