"""Natural language understanding: word-level taggers (the paper's NLU module).

Two taggers with one interface (``Tagger``): ``BiLstmCrfTagger`` (the paper's
BiLSTM-CRF) and ``BertTagger`` (a fine-tuned BERT-family encoder; offline MiniLM by
default, ``bert-base-uncased`` as in the paper where the hub is reachable). Both
``fit(train_rows, validation_rows)`` with a per-epoch ``history``, ``predict`` word tag
lists, ``save(directory)``, and come back with ``load_tagger(directory)``.
``default_tagger()`` is the shipped BiLSTM-CRF. ``metrics`` has the paper's Acc_word,
Acc_inst (Table 3) and per-tag error table (Table 4).

>>> from drywall_lab.nlu import default_tagger
>>> default_tagger().tag_text("Put panel 500310 on stud 500113")
[('Put', 'O'), ('panel', 'O'), ('500310', 'ID_wall'), ('on', 'O'), ('stud', 'O'), ('500113', 'ID_stud')]
"""
from drywall_lab.nlu.base import (
    DEFAULT_SEED,
    HISTORY_COLUMNS,
    Tagger,
    TaggerLoadError,
    TaggerNotTrainedError,
    labels_for,
    load_tagger,
    seed_everything,
)
from drywall_lab.nlu.bert import (
    DEFAULT_ENCODER,
    PAPER_ENCODER,
    BertTagger,
    EncoderNotFoundError,
    default_encoder_path,
    split_into_pieces,
    vote_word_tags,
)
from drywall_lab.nlu.bilstm_crf import BiLstmCrfTagger, fallback_token, word_key
from drywall_lab.nlu.default import DEFAULT_TAGGER_DIR, default_tagger
from drywall_lab.nlu.metrics import (
    TaggingScores,
    acc_inst,
    acc_word,
    confusion_pairs,
    count_instruction_errors,
    count_word_errors,
    instruction_errors,
    score_tagging,
    tag_error_table,
)

__all__ = [
    "DEFAULT_SEED", "HISTORY_COLUMNS", "Tagger", "TaggerLoadError", "TaggerNotTrainedError", "labels_for",
    "load_tagger", "seed_everything", "DEFAULT_ENCODER", "PAPER_ENCODER", "BertTagger", "EncoderNotFoundError",
    "default_encoder_path", "split_into_pieces", "vote_word_tags", "BiLstmCrfTagger", "fallback_token", "word_key",
    "DEFAULT_TAGGER_DIR", "default_tagger", "TaggingScores", "acc_inst", "acc_word", "confusion_pairs",
    "count_instruction_errors", "count_word_errors", "instruction_errors", "score_tagging", "tag_error_table",
]
