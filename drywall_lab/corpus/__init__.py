"""The instruction corpus (the paper's "Data Generation" section and Table 2).

- ``tags``: the 13 labels and the 15-label co-reference variant;
- ``generator``: instructions written in episode context, with tags and meanings;
- ``stats``: the corpus against the paper's Table 2;
- ``io``: JSON lines, CoNLL and ``load_corpus()`` (a ``datasets.DatasetDict``).
"""
from drywall_lab.corpus.generator import SEED, SPLIT_SIZES, generate_corpus, write_corpus
from drywall_lab.corpus.io import (
    CORPUS_DIR,
    SPLITS,
    from_conll,
    load_corpus,
    read_corpus,
    read_split,
    to_conll,
    tokenize,
)
from drywall_lab.corpus.stats import (
    check_against_paper,
    find_examples,
    print_comparison,
    sentence_groups,
    summary_table,
    tag_table,
    tags_of_word,
)
from drywall_lab.corpus.tags import COREF_TAGS, TAG_COLOURS, TAG_MEANINGS, TAGS

__all__ = [
    "SEED", "SPLIT_SIZES", "generate_corpus", "write_corpus", "CORPUS_DIR", "SPLITS", "from_conll", "load_corpus",
    "read_corpus", "read_split", "to_conll", "tokenize", "check_against_paper", "print_comparison",
    "sentence_groups", "summary_table", "tag_table", "find_examples", "tags_of_word", "COREF_TAGS", "TAG_COLOURS", "TAG_MEANINGS", "TAGS",
]
