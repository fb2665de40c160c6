"""The annotation guidelines agree with the corpus, and the practice set with its answer key."""
from __future__ import annotations

import importlib.util
from pathlib import Path

from drywall_lab.corpus import from_conll, read_split

GUIDELINES = Path(__file__).resolve().parent.parent / "annotation_guidelines"


def _load(path: Path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_tagged_example_in_the_guidelines_occurs_in_the_corpus(capsys):
    assert _load(GUIDELINES / "check_examples.py").main([]) == 0, capsys.readouterr().out


def test_practice_key_has_the_corpus_tags():
    by_text = {r["text"]: r for r in read_split("validation")}
    key = from_conll(GUIDELINES / "practice" / "practice_key.conll")
    assert len(key) == 20
    for item in key:
        gold = by_text[item["text"]]
        assert (item["words"], item["tags"], item["coref_tags"]) == (gold["words"], gold["tags"], gold["coref_tags"])
