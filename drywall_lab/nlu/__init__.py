"""Natural language understanding: word-level taggers (the paper's NLU module).

Two taggers with one interface (``Tagger``): ``BiLstmCrfTagger`` (the paper's
BiLSTM-CRF) and ``BertTagger`` (a fine-tuned BERT-family encoder; offline MiniLM by
default, ``bert-base-uncased`` as in the paper where the hub is reachable). Both
``fit(train_rows, validation_rows)`` with a per-epoch ``history``, ``predict`` word tag
lists, ``save(directory)``, and come back with ``load_tagger(directory)``. Both give their
confidence too: ``predict_marginals`` (per word, each label's probability) and
``predict_kbest`` (the k most probable tag sequences with log-probabilities), all three at
once with ``predict_confidence`` (one ``TagConfidence`` per instruction); ``to(device)``,
``fit(..., device=)`` and ``load_tagger(directory, device=)`` run them on ``"cpu"``,
``"cuda"`` or ``"auto"``. The BiLSTM-CRF can read characters too (``CHAR_FEATURES``).
``default_tagger()`` is the shipped tagger (an ensemble of two BiLSTM-CRFs, ``ensemble``). ``metrics`` has the paper's Acc_word,
Acc_inst (Table 3) and per-tag error table (Table 4).

>>> from drywall_lab.nlu import default_tagger
>>> default_tagger().tag_text("Put panel 500310 on stud 500113")
[('Put', 'O'), ('panel', 'O'), ('500310', 'ID_wall'), ('on', 'O'), ('stud', 'O'), ('500113', 'ID_stud')]
"""
import importlib
from typing import Any

#: name -> module: imported on first use, so that commands that need no model do not load torch.
_EXPORTS = {
    "DEFAULT_SEED": "drywall_lab.nlu.base",
    "DEVICE_CHOICES": "drywall_lab.nlu.base",
    "KBest": "drywall_lab.nlu.base",
    "TagConfidence": "drywall_lab.nlu.base",
    "resolve_device": "drywall_lab.nlu.base",
    "HISTORY_COLUMNS": "drywall_lab.nlu.base",
    "Tagger": "drywall_lab.nlu.base",
    "TaggerLoadError": "drywall_lab.nlu.base",
    "TaggerNotTrainedError": "drywall_lab.nlu.base",
    "labels_for": "drywall_lab.nlu.base",
    "load_tagger": "drywall_lab.nlu.base",
    "seed_everything": "drywall_lab.nlu.base",
    "DEFAULT_ENCODER": "drywall_lab.nlu.bert",
    "PAPER_ENCODER": "drywall_lab.nlu.bert",
    "BertTagger": "drywall_lab.nlu.bert",
    "EncoderNotFoundError": "drywall_lab.nlu.bert",
    "default_encoder_path": "drywall_lab.nlu.bert",
    "split_into_pieces": "drywall_lab.nlu.bert",
    "subword_marginals": "drywall_lab.nlu.bert",
    "beam_kbest": "drywall_lab.nlu.bert",
    "vote_word_tags": "drywall_lab.nlu.bert",
    "BiLstmCrfTagger": "drywall_lab.nlu.bilstm_crf",
    "CHAR_FEATURES": "drywall_lab.nlu.bilstm_crf",
    "character_vocabulary": "drywall_lab.nlu.bilstm_crf",
    "word_characters": "drywall_lab.nlu.bilstm_crf",
    "crf_confidence": "drywall_lab.nlu.bilstm_crf",
    "crf_kbest": "drywall_lab.nlu.bilstm_crf",
    "crf_log_partition": "drywall_lab.nlu.bilstm_crf",
    "crf_marginals": "drywall_lab.nlu.bilstm_crf",
    "crf_sequence_scores": "drywall_lab.nlu.bilstm_crf",
    "fallback_token": "drywall_lab.nlu.bilstm_crf",
    "word_key": "drywall_lab.nlu.bilstm_crf",
    "CrfEnsembleTagger": "drywall_lab.nlu.ensemble",
    "DEFAULT_TAGGER_DIR": "drywall_lab.nlu.default",
    "default_tagger": "drywall_lab.nlu.default",
    "TaggingScores": "drywall_lab.nlu.metrics",
    "acc_inst": "drywall_lab.nlu.metrics",
    "acc_word": "drywall_lab.nlu.metrics",
    "confusion_pairs": "drywall_lab.nlu.metrics",
    "count_instruction_errors": "drywall_lab.nlu.metrics",
    "count_word_errors": "drywall_lab.nlu.metrics",
    "error_examples": "drywall_lab.nlu.metrics",
    "instruction_errors": "drywall_lab.nlu.metrics",
    "score_tagging": "drywall_lab.nlu.metrics",
    "tag_error_table": "drywall_lab.nlu.metrics",
}


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "DEFAULT_SEED", "DEVICE_CHOICES", "KBest", "TagConfidence", "resolve_device", "HISTORY_COLUMNS", "Tagger", "TaggerLoadError",
    "TaggerNotTrainedError", "labels_for", "load_tagger", "seed_everything", "DEFAULT_ENCODER", "PAPER_ENCODER",
    "BertTagger", "EncoderNotFoundError", "default_encoder_path", "split_into_pieces", "subword_marginals",
    "beam_kbest", "vote_word_tags", "BiLstmCrfTagger", "CHAR_FEATURES", "character_vocabulary", "word_characters",
    "crf_confidence", "crf_kbest", "crf_log_partition", "crf_marginals", "crf_sequence_scores", "fallback_token", "word_key",
    "CrfEnsembleTagger", "DEFAULT_TAGGER_DIR", "default_tagger", "TaggingScores", "acc_inst", "acc_word", "confusion_pairs",
    "count_instruction_errors", "count_word_errors", "error_examples", "instruction_errors", "score_tagging", "tag_error_table",
]
