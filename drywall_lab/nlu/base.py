"""What both taggers share: training history, prediction, saving and loading.

The paper's NLU module (section "Natural Language Understanding") frames slot filling as
word-level sequence labelling: every word of an instruction gets one of the 13 tags (or
one of 15 in the co-reference variant of Table 5). Two architectures do it, the
BiLSTM-CRF (``BiLstmCrfTagger``) and a fine-tuned BERT (``BertTagger``); both follow
the interface of ``Tagger`` so that experiments, the latency benchmark and notebooks can
swap one for the other:

>>> from drywall_lab.nlu import BiLstmCrfTagger, load_tagger           # doctest: +SKIP
>>> tagger = BiLstmCrfTagger()                                         # doctest: +SKIP
>>> history = tagger.fit(read_split("train"), read_split("validation"))  # doctest: +SKIP
>>> tagger.predict([["Pick", "up", "panel", "500310"]])                # doctest: +SKIP
[['O', 'O', 'O', 'ID_wall']]
>>> tagger.save("my_tagger"); load_tagger("my_tagger")                 # doctest: +SKIP

Beyond the single best tags, both give their confidence (issue 12): ``predict_marginals``
(per word, the probability of each label) and ``predict_kbest`` (the k most probable tag
sequences with their log-probabilities). ``to(device)`` / ``fit(..., device=...)`` /
``load_tagger(directory, device=...)`` run a tagger on ``"cpu"``, ``"cuda"`` or ``"auto"``
(``resolve_device``).

A saved tagger is a directory with ``tagger.json`` (kind, labels, settings, versions),
``history.csv`` (one row per training epoch) and the kind's own weight files.
"""
from __future__ import annotations

import importlib
import json
import platform
import random
import re
import time
from abc import ABC, abstractmethod
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path
from typing import Any, ClassVar, Mapping, Sequence

import numpy as np
import pandas as pd

from drywall_lab.corpus.tags import COREF_TAGS, TAGS
from drywall_lab.nlu.metrics import TaggingScores, acc_inst, acc_word, score_tagging

#: Bumped when the layout of a saved tagger changes in a way old code cannot read.
FORMAT_VERSION = 1
TAGGER_JSON = "tagger.json"
HISTORY_CSV = "history.csv"
DEFAULT_SEED = 0
#: Columns of ``Tagger.history`` (validation columns are NaN when no validation rows were given).
HISTORY_COLUMNS = ("epoch", "train_loss", "train_acc_word", "val_acc_word", "val_acc_inst", "seconds")
#: Row fields a tagger can learn from: the 13 tags or the 15 co-reference tags.
TAG_FIELDS = ("tags", "coref_tags")
#: kind -> (module, class); modules are imported only when a tagger of that kind is loaded.
KINDS: dict[str, tuple[str, str]] = {
    "bilstm-crf": ("drywall_lab.nlu.bilstm_crf", "BiLstmCrfTagger"),
    "bert": ("drywall_lab.nlu.bert", "BertTagger"),
    "bilstm-crf-ensemble": ("drywall_lab.nlu.ensemble", "CrfEnsembleTagger"),
}

Sentences = Sequence[Sequence[str]]
#: One instruction's k best tag sequences: (tags, log-probability), most probable first.
KBest = list[tuple[list[str], float]]
#: What ``device`` arguments accept: ``"auto"`` (cuda when available, else cpu), ``"cpu"``, ``"cuda"``, ``"cuda:N"``.
DEVICE_CHOICES = ("auto", "cpu", "cuda")


@dataclass(frozen=True)
class TagConfidence:
    """One instruction's tags with the tagger's confidence in them (``Tagger.predict_confidence``).

    ``tags``: what ``predict`` gives; ``marginals``: (n_words, n_labels), each word's
    probability of each label (columns in the tagger's ``labels`` order), None where only the
    k best were asked for (``decision.readings``); ``kbest``: the k most probable tag sequences
    with their log-probabilities, best first.
    """

    tags: list[str]
    marginals: np.ndarray | None
    kbest: KBest


class TaggerLoadError(ValueError):
    """A directory that cannot be read as a saved tagger (missing, incomplete or corrupt)."""


class TaggerNotTrainedError(RuntimeError):
    """``predict``, ``save`` or ``n_parameters`` called before ``fit`` or ``load_tagger``."""


def seed_everything(seed: int) -> None:
    """Fix Python's, NumPy's and torch's random generators, so CPU training repeats exactly."""
    import torch

    random.seed(seed)
    np.random.seed(seed)
    torch.manual_seed(seed)


def resolve_device(device: Any = "auto") -> str:
    """The torch device name to run on: ``"auto"`` is ``"cuda"`` when ``torch.cuda.is_available()``, else ``"cpu"``.

    ``"cpu"``, ``"cuda"``, ``"cuda:N"`` (or a ``torch.device``) are checked: asking for cuda on a
    machine without one is a ValueError that says so, instead of torch's error deep in training.

    >>> resolve_device("cpu")
    'cpu'
    """
    import torch

    name = str(device).strip().lower() if device is not None else "auto"
    if name == "auto":
        return "cuda" if torch.cuda.is_available() else "cpu"
    if name == "cpu":
        return "cpu"
    if re.fullmatch(r"cuda(:\d+)?", name):
        if not torch.cuda.is_available():
            raise ValueError(
                f"device {name!r} was asked for, but torch sees no CUDA GPU on this machine "
                f"(torch {torch.__version__}); use device 'cpu' or 'auto'"
            )
        index = int(name.split(":")[1]) if ":" in name else 0
        if index >= torch.cuda.device_count():
            raise ValueError(f"device {name!r} was asked for, but this machine has {torch.cuda.device_count()} CUDA GPU(s)")
        return name
    raise ValueError(f"unknown device {device!r}; expected one of {', '.join(DEVICE_CHOICES)} (or 'cuda:N')")


def check_k(k: Any) -> int:
    """``k`` for ``predict_kbest``: a whole number of at least 1."""
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 1:
        raise ValueError(f"k must be a whole number of at least 1, got {k!r}")
    return int(k)


def package_versions(*names: str) -> dict[str, str]:
    """The installed versions of drywall-lab, Python and the named packages (for ``tagger.json``)."""
    versions = {"python": platform.python_version()}
    for name in ("drywall-lab", *names):
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = "not installed"
    return versions


def check_sentences(sentences: Sentences) -> list[list[str]]:
    """``sentences`` as a list of word lists; a TypeError for the usual mistakes.

    Passing one word list instead of a list of them (``predict(["stud", "500107"])``)
    would tag single characters, so it is refused with a hint.
    """
    if isinstance(sentences, str):
        raise TypeError("predict takes a list of word lists, not a string; use tag_text() for raw text")
    out = []
    for i, words in enumerate(sentences):
        if isinstance(words, str):
            raise TypeError(
                f"predict takes a list of word lists, but item {i} is the string {words!r}; "
                "for one instruction pass [words]"
            )
        words = list(words)
        for j, word in enumerate(words):
            if not isinstance(word, str):
                raise TypeError(f"item {i}, word {j}: expected a string, got {type(word).__name__}")
        out.append(words)
    return out


def empty_history() -> pd.DataFrame:
    return pd.DataFrame({c: pd.Series(dtype="int64" if c == "epoch" else "float64") for c in HISTORY_COLUMNS})


class Tagger(ABC):
    """A word-level tagger: ``fit`` on corpus rows, ``predict`` tag lists, ``save`` and load.

    ``labels`` are the tags it can give (``TAGS``, or ``COREF_TAGS`` for the paper's
    co-reference experiment, Table 5) and ``tag_field`` names the row field it learns
    from (``"tags"`` or ``"coref_tags"``). ``history`` is a DataFrame with one row per
    training epoch (``HISTORY_COLUMNS``), the data of the paper's Fig. 13.
    """

    kind: ClassVar[str]

    def __init__(self, *, labels: Sequence[str] = TAGS, tag_field: str = "tags") -> None:
        labels = list(labels)
        if not labels or len(set(labels)) != len(labels) or not all(isinstance(t, str) for t in labels):
            raise ValueError(f"labels must be a non-empty list of distinct tag names, got {labels!r}")
        if tag_field not in TAG_FIELDS:
            raise ValueError(f"tag_field must be one of {TAG_FIELDS}, got {tag_field!r}")
        self.labels: list[str] = labels
        self.tag_field = tag_field
        self.history: pd.DataFrame = empty_history()
        self.training_info: dict[str, Any] = {}
        self._device = "cpu"

    # -- what each kind implements ------------------------------------------------------
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
        """Train from scratch on ``train_rows``; return (and keep as ``history``) one row per epoch.

        ``device`` (``"auto"``, ``"cpu"``, ``"cuda"``): where to train, and where the trained
        tagger then predicts; ``None`` keeps the tagger's device (``"cpu"`` unless ``to`` said otherwise).
        How each kind trains, and what its history records: its ``_fit``.
        """
        return self._fit(train_rows, validation_rows, epochs=epochs, progress=progress, seed=seed, device=device)

    @abstractmethod
    def _fit(self, train_rows: Sequence[Mapping], validation_rows: Sequence[Mapping] | None, *, epochs: int | None,
             progress: bool, seed: int, device: str | None) -> pd.DataFrame:
        """``fit`` for this kind of tagger (the arguments as ``fit`` takes them, ``epochs`` None for the kind's)."""

    @abstractmethod
    def predict(self, sentences: Sentences, batch_size: int = 64) -> list[list[str]]:
        """One tag per word for each word list; an empty word list gives an empty tag list."""

    @abstractmethod
    def predict_marginals(self, sentences: Sentences, batch_size: int = 64) -> list[np.ndarray]:
        """Per word list, an array of shape (n_words, n_labels): row i is word i's probability of each label
        (columns in the order of ``labels``), rows summing to 1. An empty word list gives shape (0, n_labels)."""

    @abstractmethod
    def predict_kbest(self, sentences: Sentences, k: int, batch_size: int = 64) -> list[KBest]:
        """Per word list, up to ``k`` tag sequences with their natural-log probabilities, most probable first
        (fewer when fewer sequences are possible). An empty word list has one sequence, ``([], 0.0)``."""

    def predict_confidence(self, sentences: Sentences, k: int = 5, batch_size: int = 64) -> list[TagConfidence]:
        """``predict``, ``predict_marginals`` and ``predict_kbest`` together, one ``TagConfidence`` per word list.

        The kinds compute all three from one pass of the network (this default calls the three).
        """
        k = check_k(k)
        return [
            TagConfidence(tags, marginals, kbest)
            for tags, marginals, kbest in zip(
                self.predict(sentences, batch_size), self.predict_marginals(sentences, batch_size),
                self.predict_kbest(sentences, k, batch_size),
            )
        ]

    @abstractmethod
    def _move(self, device: str) -> None:
        """Move the trained network (if any) to ``device`` (already resolved)."""

    @abstractmethod
    def n_parameters(self) -> int:
        """The number of trainable numbers in the network."""

    @abstractmethod
    def settings(self) -> dict[str, Any]:
        """The constructor settings (JSON-serialisable) that ``load_tagger`` passes back."""

    @property
    @abstractmethod
    def is_trained(self) -> bool:
        """True after ``fit`` or when loaded from a directory."""

    @abstractmethod
    def _save_weights(self, directory: Path) -> dict[str, Any]:
        """Write the weight files into ``directory``; return extra entries for ``tagger.json``."""

    @classmethod
    @abstractmethod
    def _load_weights(cls, directory: Path, meta: Mapping[str, Any]) -> "Tagger":
        """Build a trained tagger from ``directory`` whose ``tagger.json`` says ``meta``."""

    # -- device ------------------------------------------------------------------------------
    @property
    def device(self) -> str:
        """The torch device this tagger trains and predicts on (``"cpu"`` unless ``to`` or ``fit`` said otherwise)."""
        return self._device

    def to(self, device: str = "auto") -> "Tagger":
        """Run on ``device`` (``"auto"``, ``"cpu"``, ``"cuda"``, ``"cuda:N"``; see ``resolve_device``); return self."""
        resolved = resolve_device(device)
        self._move(resolved)
        self._device = resolved
        return self

    # -- shared by the kinds' ``fit`` ---------------------------------------------------
    def _fit_input(
        self, train_rows: Sequence[Mapping], validation_rows: Sequence[Mapping] | None, epochs: int | None,
        default_epochs: int, *, device: str | None, seed: int,
    ) -> tuple[list[Mapping], list[list[str]], list[Mapping], list[list[str]] | None, int]:
        """Checked training input: rows with words and their gold tags, validation rows and tags, epochs. Once
        the input is checked, the tagger moves to ``device`` (unless None) and every random generator is seeded."""
        pairs = [(r, tags) for r, tags in zip(train_rows, self.gold_tags(train_rows)) if tags]
        if not pairs:
            raise ValueError("fit needs at least one training instruction with words")
        validation_rows = list(validation_rows or [])
        validation_gold = self.gold_tags(validation_rows) if validation_rows else None
        epochs = default_epochs if epochs is None else int(epochs)
        if epochs < 1:
            raise ValueError(f"epochs must be at least 1, got {epochs}")
        if device is not None:
            self._device = resolve_device(device)
        seed_everything(seed)
        return [r for r, _ in pairs], [tags for _, tags in pairs], validation_rows, validation_gold, epochs

    def _epoch_record(
        self, epoch: int, *, loss_sum: float, n_items: int, correct: int, seen: int,
        validation_rows: Sequence[Mapping], validation_gold: list[list[str]] | None, bar: Any, started: float,
    ) -> dict[str, float]:
        """One ``history`` row: mean training loss and word accuracy, validation scores, seconds since ``started``."""
        record = {
            "epoch": epoch,
            "train_loss": loss_sum / n_items,
            "train_acc_word": correct / seen,
            "val_acc_word": float("nan"),
            "val_acc_inst": float("nan"),
        }
        if validation_gold is not None:
            predicted = self.predict([r["words"] for r in validation_rows])
            record["val_acc_word"] = acc_word(validation_gold, predicted)
            record["val_acc_inst"] = acc_inst(validation_gold, predicted)
            bar.set_postfix(epoch=epoch, val_acc_inst=f"{record['val_acc_inst']:.4f}")
        record["seconds"] = time.perf_counter() - started
        return record

    def _finish_fit(
        self, records: list[dict[str, float]], *, n_train: int, n_validation: int, epochs: int, seed: int,
        started: float,
    ) -> pd.DataFrame:
        """Keep the epochs as ``history`` and the run's facts as ``training_info``; return ``history``."""
        self.history = pd.DataFrame(records, columns=list(HISTORY_COLUMNS))
        self.training_info = {
            "n_train_instructions": n_train,
            "n_validation_instructions": n_validation,
            "epochs": epochs,
            "seed": seed,
            "wall_seconds": round(time.perf_counter() - started, 2),
        }
        return self.history

    # -- shared ---------------------------------------------------------------------------
    def gold_tags(self, rows: Sequence[Mapping]) -> list[list[str]]:
        """The tag lists this tagger learns from (``row[tag_field]``), checked against ``labels``."""
        known = set(self.labels)
        out = []
        for i, row in enumerate(rows):
            if "words" not in row or self.tag_field not in row:
                raise ValueError(f"row {i} has no 'words' or no {self.tag_field!r} field")
            tags = list(row[self.tag_field])
            if len(tags) != len(row["words"]):
                raise ValueError(f"row {i} ({row.get('id', '?')}): {len(row['words'])} words but {len(tags)} tags")
            unknown = [t for t in tags if t not in known]
            if unknown:
                raise ValueError(
                    f"row {i} ({row.get('id', '?')}): tag {unknown[0]!r} is not one of this tagger's labels "
                    f"({', '.join(self.labels)}); is tag_field={self.tag_field!r} the right field?"
                )
            out.append(tags)
        return out

    def evaluate(self, rows: Sequence[Mapping], batch_size: int = 64) -> TaggingScores:
        """Acc_word, Acc_inst, N_w and N_l on corpus rows (the paper's Table 3)."""
        gold = self.gold_tags(rows)
        predicted = self.predict([row["words"] for row in rows], batch_size=batch_size)
        return score_tagging(gold, predicted)

    def tag_text(self, text: str) -> list[tuple[str, str]]:
        """Read ``text`` through the front end (``normalise``) and pair each word it reads with its tag."""
        from drywall_lab.nlu.normalise import normalise

        words = list(normalise(text).words)
        return list(zip(words, self.predict([words])[0]))

    def save(self, directory: str | Path) -> Path:
        """Write the trained tagger into ``directory`` (created if needed); return its path."""
        if not self.is_trained:
            raise TaggerNotTrainedError("this tagger is not trained yet: call fit() before save()")
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        extra = self._save_weights(directory)
        self.history.to_csv(directory / HISTORY_CSV, index=False)
        meta = {
            "format_version": FORMAT_VERSION,
            "kind": self.kind,
            "labels": self.labels,
            "tag_field": self.tag_field,
            "settings": self.settings(),
            "n_parameters": self.n_parameters(),
            "training": self.training_info,
            "versions": package_versions(*self._version_packages()),
            **extra,
        }
        (directory / TAGGER_JSON).write_text(json.dumps(meta, indent=2) + "\n", encoding="utf-8")
        return directory

    def _version_packages(self) -> tuple[str, ...]:
        return ("torch",)

    def _check_trained(self, what: str) -> None:
        if not self.is_trained:
            raise TaggerNotTrainedError(f"this tagger is not trained yet: call fit() or load_tagger() before {what}()")

    def _checked(self, sentences: Sentences, what: str) -> list[list[str]]:
        """``sentences`` checked (``check_sentences``) for ``what``, a prediction only a trained tagger makes."""
        sentences = check_sentences(sentences)
        self._check_trained(what)
        return sentences

    def __repr__(self) -> str:
        state = f"{self.n_parameters():,} parameters" if self.is_trained else "not trained"
        return f"{type(self).__name__}({len(self.labels)} labels from {self.tag_field!r}, {state})"


def _read_meta(directory: Path) -> dict[str, Any]:
    if not directory.exists():
        raise TaggerLoadError(f"{directory} is not a saved tagger: the directory does not exist")
    if not directory.is_dir():
        raise TaggerLoadError(f"{directory} is not a saved tagger: it is a file, not a directory")
    path = directory / TAGGER_JSON
    if not path.is_file():
        raise TaggerLoadError(f"{directory} is not a saved tagger: {TAGGER_JSON} is missing")
    try:
        meta = json.loads(path.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise TaggerLoadError(f"{directory} is not a saved tagger: {TAGGER_JSON} is not valid JSON ({e})") from None
    if not isinstance(meta, dict):
        raise TaggerLoadError(f"{directory} is not a saved tagger: {TAGGER_JSON} does not hold a JSON object")
    for key in ("kind", "labels", "tag_field", "settings"):
        if key not in meta:
            raise TaggerLoadError(f"{directory} is not a saved tagger: {TAGGER_JSON} has no {key!r} entry")
    if meta.get("format_version", FORMAT_VERSION) > FORMAT_VERSION:
        raise TaggerLoadError(
            f"{directory} was saved by a newer drywall-lab (format {meta['format_version']}); "
            f"this one reads format {FORMAT_VERSION}"
        )
    return meta


def load_tagger(directory: str | Path, device: str = "cpu") -> Tagger:
    """Load a tagger written by ``Tagger.save``; its ``tagger.json`` says which class.

    The weights are always read onto the CPU first (a tagger trained on a GPU loads on a
    machine without one); then the tagger is moved to ``device`` (``"cpu"`` by default,
    ``"auto"`` or ``"cuda"``: see ``resolve_device``, whose ValueError says when cuda is missing).

    Raises ``TaggerLoadError`` (a ValueError) with a message that says what is wrong: the
    directory is missing, ``tagger.json`` is missing or corrupt, the kind is unknown, or a
    weight file is missing or does not fit the settings.
    """
    directory = Path(directory)
    device = resolve_device(device)
    meta = _read_meta(directory)
    kind = meta["kind"]
    if kind not in KINDS:
        raise TaggerLoadError(
            f"{directory} is not a saved tagger this version knows: unknown kind {kind!r} "
            f"(known kinds: {', '.join(sorted(KINDS))})"
        )
    module_name, class_name = KINDS[kind]
    cls: type[Tagger] = getattr(importlib.import_module(module_name), class_name)
    try:
        tagger = cls._load_weights(directory, meta)
    except TaggerLoadError:
        raise
    except (OSError, ValueError, KeyError, TypeError, RuntimeError) as e:
        raise TaggerLoadError(f"{directory} could not be loaded as a {kind} tagger: {e}") from e
    history_path = directory / HISTORY_CSV
    if history_path.is_file():
        try:
            tagger.history = pd.read_csv(history_path)
        except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
            raise TaggerLoadError(f"{directory}: {HISTORY_CSV} is corrupt ({e})") from None
    tagger.training_info = dict(meta.get("training", {}))
    return tagger.to(device) if device != "cpu" else tagger


def labels_for(coref: bool) -> tuple[tuple[str, ...], str]:
    """(labels, tag_field) for the 13-tag task or the co-reference variant (Table 5)."""
    return (COREF_TAGS, "coref_tags") if coref else (TAGS, "tags")
