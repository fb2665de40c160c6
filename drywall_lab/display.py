"""HTML helpers for notebooks: tagged words in colour."""
from __future__ import annotations

from html import escape
from typing import Sequence

from drywall_lab.corpus.tags import TAG_COLOURS


def tagged_html(words: Sequence[str], tags: Sequence[str], other: Sequence[str] | None = None) -> str:
    """Words as coloured boxes labelled with their tag; with ``other``, differing tags are shown struck through."""
    spans = []
    for i, (word, tag) in enumerate(zip(words, tags)):
        alt = other[i] if other is not None else tag
        if tag == "O" and alt == "O":
            spans.append(f"<span style='padding:1px 2px'>{escape(word)}</span>")
            continue
        label = escape(tag) if alt == tag else f"{escape(tag)} <s style='color:#c0392b'>{escape(alt)}</s>"
        border = "2px solid #c0392b" if alt != tag else "1px solid #999"
        spans.append(
            f"<span style='background:{TAG_COLOURS.get(tag, '#eee')};border:{border};border-radius:4px;"
            f"padding:1px 3px;margin:1px;display:inline-block;line-height:1.1'>{escape(word)}"
            f"<sub style='font-size:65%;margin-left:2px'>{label}</sub></span>"
        )
    return "<div style='line-height:2.1'>" + " ".join(spans) + "</div>"


def legend_html() -> str:
    """One coloured box per tag."""
    return tagged_html(list(TAG_COLOURS), list(TAG_COLOURS))
