"""The shipped default tagger: a BiLSTM-CRF trained on the full training split.

It lives in ``drywall_lab/models/default_tagger/`` (package data) and is rebuilt,
deterministically, by ``make default-tagger``, which runs::

    python -m drywall_lab train bilstm-crf --out drywall_lab/models/default_tagger --seed 0

(the paper's settings: 20 epochs, batch 16, Adam 1e-3; about two minutes on two CPU cores)
and then ``make tagger-scores``: ``python -m drywall_lab evaluate`` on the validation, test
and novel splits, whose last lines (``acc_word=… acc_inst=… n_instructions=… acc_task=…``)
it writes to ``scores.txt`` in that directory, one line a split. ``history.csv`` holds the
per-epoch training figures (the paper's Fig. 13 for this model).
"""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from drywall_lab.nlu.base import Tagger, TaggerLoadError, load_tagger

DEFAULT_TAGGER_DIR = Path(__file__).resolve().parent.parent / "models" / "default_tagger"


@lru_cache(maxsize=1)
def default_tagger() -> Tagger:
    """The shipped BiLSTM-CRF, loaded once and shared; ``load_tagger(DEFAULT_TAGGER_DIR)`` gives a private copy."""
    if not (DEFAULT_TAGGER_DIR / "tagger.json").is_file():
        raise TaggerLoadError(
            f"the default tagger is not built ({DEFAULT_TAGGER_DIR} has no tagger.json); run `make default-tagger`"
        )
    return load_tagger(DEFAULT_TAGGER_DIR)
