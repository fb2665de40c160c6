"""The shipped default tagger: an ensemble of two BiLSTM-CRFs trained on the field corpus.

It lives in ``drywall_lab/models/default_tagger/`` (package data; each member in its own ``member<N>/``) and is
rebuilt, bit for bit on the same machine and torch build, by ``make default-tagger``, which trains the recipe
(``drywall_lab.nlu.field_study.DEFAULT_FIELD_TAGGER``: character features, 8 epochs, batch 32, the weights
averaged over the last 3 epochs) with each seed of ``DEFAULT_ENSEMBLE_SEEDS``, one thread on the CPU, combines
the two with ``python -m drywall_lab ensemble`` (``CrfEnsembleTagger``: their CRF scores averaged) and then runs
``make tagger-scores``: ``python -m drywall_lab evaluate`` on every evaluation set, whose last lines
(``acc_word=… acc_inst=… n_instructions=… acc_task=…`` and the decision layer's figures) it writes to
``scores.txt`` in that directory, one line a set. Each member's ``history.csv`` holds its per-epoch training
figures (the paper's Fig. 13 for that model).
"""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from drywall_lab.nlu.base import Tagger, TaggerLoadError, load_tagger

DEFAULT_TAGGER_DIR = Path(__file__).resolve().parent.parent / "models" / "default_tagger"


@lru_cache(maxsize=1)
def default_tagger() -> Tagger:
    """The shipped tagger, loaded once and shared; ``load_tagger(DEFAULT_TAGGER_DIR)`` gives a private copy."""
    if not (DEFAULT_TAGGER_DIR / "tagger.json").is_file():
        raise TaggerLoadError(
            f"the default tagger is not built ({DEFAULT_TAGGER_DIR} has no tagger.json); run `make default-tagger`"
        )
    return load_tagger(DEFAULT_TAGGER_DIR)
