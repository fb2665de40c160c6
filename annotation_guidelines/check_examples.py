"""Check that the tagged examples in README.md agree with the corpus.

    python annotation_guidelines/check_examples.py [--corpus-dir DIR]

Every code span of README.md that holds a ``word/TAG`` is an example. It must occur in
data/corpus (any split) or in the field corpus (data/field_corpus: its committed splits and its seeded training split) as consecutive words with exactly those tags, a word without ``/TAG``
being ``O``; ``...`` in a span skips words. Examples in section 5 are checked against the
co-reference tags. A six-digit id matches any id of the same kind (5001xx or 5003xx) unless it
is one that does not exist on the site (an unknown id must match itself). Examples marked wrong
(after ✗) are not checked; examples on a line marked *phrase bank* may be missing from the
corpus. Exits 1 when an example is missing.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from drywall_lab.corpus import COREF_TAGS, read_corpus
from drywall_lab.corpus.field_generator import COMMITTED_SPLITS, field_split
from drywall_lab.site import default_site

README = Path(__file__).resolve().parent / "README.md"
SITE_IDS = set(default_site().stud_ids) | set(default_site().panel_ids)


def examples(text: str):
    """(line number, span, in section 5, marked phrase bank) for every tagged code span."""
    text = re.sub(r"```.*?```", lambda m: re.sub(r"[^\n]", " ", m.group(0)), text, flags=re.S)
    coref_from = text.index("## 5. Co-reference")
    coref_to = text.index("## 6. ")
    tag = re.compile(r"/(%s)\b" % "|".join(COREF_TAGS))
    for m in re.finditer(r"`([^`\n]+)`", text):
        span = m.group(1)
        if not tag.search(span) or text[max(0, m.start() - 2):m.start()].strip() == "✗":
            continue
        line_no = text.count("\n", 0, m.start()) + 1
        line = text.splitlines()[line_no - 1]
        yield line_no, span, coref_from <= m.start() < coref_to, "phrase bank" in line


def _same(word: str, want: str) -> bool:
    if re.fullmatch(r"\d{6}", want) and want in SITE_IDS:
        return bool(re.fullmatch(r"\d{6}", word)) and word in SITE_IDS and word[:4] == want[:4]
    return word == want


def occurs(span: str, rows: list[dict], coref: bool) -> str | None:
    """The id of a corpus instruction where ``span`` occurs, or None."""
    segments = []
    for part in span.split("..."):
        tokens = []
        for piece in part.split():
            word, _, tag = piece.partition("/")
            tokens.append((word.lower(), tag or "O"))
        if tokens:
            segments.append(tokens)
    key = "coref_tags" if coref else "tags"
    for row in rows:
        words = [w.lower() for w in row["words"]]
        tags = row[key]
        start, ok = 0, True
        for seg in segments:
            hit = next((i for i in range(start, len(words) - len(seg) + 1)
                        if all(_same(words[i + j], w) and tags[i + j] == t for j, (w, t) in enumerate(seg))), None)
            if hit is None:
                ok = False
                break
            start = hit + len(seg)
        if ok:
            return row["id"]
    return None


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--corpus-dir", default=None)
    args = parser.parse_args(argv)
    rows = [r for split in read_corpus(args.corpus_dir).values() for r in split]
    rows += [r for split in (*COMMITTED_SPLITS, "train") for r in field_split(split)]
    missing = checked = 0
    for line_no, span, coref, phrase_bank in examples(README.read_text(encoding="utf-8")):
        checked += 1
        if occurs(span, rows, coref) is None:
            note = "phrase bank, not in the corpus (allowed)" if phrase_bank else "NOT IN THE CORPUS"
            print(f"README.md:{line_no}: {note}: {span}{'  [co-reference tags]' if coref else ''}")
            missing += not phrase_bank
    print(f"{checked} examples checked, {missing} missing from the corpus")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
