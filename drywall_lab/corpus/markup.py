"""A small markup for tagged phrases, so the phrase banks read like sentences.

A template is words separated by spaces:

- ``word`` is an ``O`` word;
- ``word/TAG`` carries one of the 13 tags (``second/St_loc1``);
- ``word/@T`` and ``word/@D`` are ``O`` words that the co-reference variant
  tags ``Trg`` or ``Dst`` (generic words for the target or destination);
- ``{name}`` is replaced by a phrase given as a keyword argument;
- ``,`` ``?`` ``.`` are punctuation: attached to the word before, not words.

>>> [t.word for t in parse("put {it} on stud 500107/ID_stud", it=parse("it/@T"))]
['put', 'it', 'on', 'stud', '500107']
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from drywall_lab.corpus.tags import TAGS

PUNCTUATION = {",", ".", "?", "!"}


@dataclass(frozen=True)
class Token:
    """One word with its tag and its co-reference tag, or a punctuation mark (tag None)."""

    word: str
    tag: str | None = "O"
    coref: str | None = "O"

    @property
    def is_word(self) -> bool:
        return self.tag is not None


Phrase = list[Token]

_SLOT = re.compile(r"^\{(\w+)\}$")


def parse(template: str, **slots: Phrase) -> Phrase:
    """Turn a template into tokens, filling ``{slots}`` with phrases."""
    out: Phrase = []
    for piece in template.split():
        m = _SLOT.match(piece)
        if m:
            out.extend(slots[m.group(1)])
            continue
        if piece in PUNCTUATION:
            out.append(Token(piece, None, None))
            continue
        word, _, tag = piece.partition("/")
        if not tag:
            out.append(Token(word))
        elif tag == "@T":
            out.append(Token(word, "O", "Trg"))
        elif tag == "@D":
            out.append(Token(word, "O", "Dst"))
        else:
            if tag not in TAGS:
                raise ValueError(f"unknown tag {tag!r} in template {template!r}")
            out.append(Token(word, tag, tag))
    return out


def tagged(words: str, tag: str) -> Phrase:
    """Every word of ``words`` with the same tag: ``tagged("second to the left", "St_loc1")``."""
    return [Token(w, tag, tag) for w in words.split()]


def plain(words: str) -> Phrase:
    """Words that are all ``O``."""
    return [Token(w) for w in words.split()]
