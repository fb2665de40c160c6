"""What the rules look at and what they decide: the tagged instruction and the rule trace."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import pandas as pd

from drywall_lab.corpus.tags import COREF_TAGS, PLACEMENT_TAGS
from drywall_lab.errors import Refusal
from drywall_lab.im import words as W
from drywall_lab.im.correction import taken_back


_LEAD_IN = frozenset({"the", "a", "an", "is", "of", "that", "with", "width", "length", "size", "stud", "panel",
                      "on", "to", "from", "at", "in"})
_UNITS = frozenset({"foot", "feet", "ft", "long", "wide", "across", "by", "tall", "stud", "stack"})


@dataclass(frozen=True)
class TaggedInstruction:
    """An instruction's words with one tag each, as the NLU module gives them.

    The co-reference tags ``Trg`` and ``Dst`` (the paper's Table 5 variant) are
    accepted and read as ``O``: the rules use only the 13 tags of spec section 2. The tags of
    words a change of mind takes back (``correction.taken_back``: "the second from the right, no,
    the fourth from the right") are read as ``O``: only the final intention counts (guidelines 4.7).
    ``taken_back`` keeps which words those were, and what took each back. The placement tags of a
    place in a stack ("the 2x8 off the top of the middle pile", ``words.stack_place``; kept in
    ``in_stack``) are read as ``O`` too: it says which panel, or why, never the row.
    """

    words: tuple[str, ...]
    tags: tuple[str, ...]
    #: The positions whose tags a correction took back, each with the words that did.
    taken_back: dict[int, str] = field(init=False, repr=False, compare=False)
    #: The positions of a place in a stack ("off the top of the middle pile") whose placement tags were read as ``O``.
    in_stack: tuple[int, ...] = field(init=False, repr=False, compare=False)
    #: Where each tag stands (tag -> word positions): the rules ask for it thousands of times per decision.
    _positions: dict[str, list[int]] = field(init=False, repr=False, compare=False)

    def __init__(self, words: Sequence[str], tags: Sequence[str]) -> None:
        words, tags = tuple(str(w) for w in words), tuple(str(t) for t in tags)
        if len(words) != len(tags):
            raise ValueError(f"{len(words)} words but {len(tags)} tags: every word needs exactly one tag")
        unknown = sorted(set(tags) - set(COREF_TAGS))
        if unknown:
            raise ValueError(f"unknown tag(s) {', '.join(unknown)}; the tags are {', '.join(COREF_TAGS)}")
        in_stack = tuple(i for i in W.stack_place(words) if tags[i] in PLACEMENT_TAGS)
        if in_stack:
            tags = tuple("O" if i in in_stack else t for i, t in enumerate(tags))
        back = taken_back(words, tags)
        if back:
            tags = tuple("O" if i in back else t for i, t in enumerate(tags))
        object.__setattr__(self, "taken_back", back)
        object.__setattr__(self, "in_stack", in_stack)
        object.__setattr__(self, "words", words)
        object.__setattr__(self, "tags", tags)
        positions: dict[str, list[int]] = {}
        for i, t in enumerate(tags):
            positions.setdefault(t, []).append(i)
        object.__setattr__(self, "_positions", positions)

    def indices(self, *tags: str) -> list[int]:
        """The positions of the words carrying any of ``tags``, in order."""
        if len(tags) == 1:
            return list(self._positions.get(tags[0], ()))
        return sorted(i for t in set(tags) for i in self._positions.get(t, ()))

    def words_with(self, *tags: str) -> list[str]:
        """The words carrying any of ``tags``, in order."""
        return [self.words[i] for i in self.indices(*tags)]

    def has(self, *tags: str) -> bool:
        return any(t in self._positions for t in tags)

    def span(self, *tags: str) -> list[str]:
        """The words from the first to the last word carrying any of ``tags``: ``"third stud left"``."""
        idx = self.indices(*tags)
        return list(self.words[idx[0]:idx[-1] + 1]) if idx else []

    def phrase(self, *tags: str) -> list[str]:
        """The tagged words with the few words around them that make them readable, to quote back.

        ``phrase("length")`` on "take the panel with a length of 8 feet" gives
        ["a", "length", "of", "8", "feet"]: lead-in words ("the", "is", "of", "that",
        "width", ...) before the first tagged word and units ("feet", "long") after the last.
        """
        idx = self.indices(*tags)
        if not idx:
            return []
        start, end = idx[0], idx[-1] + 1
        while start > 0 and idx[0] - start < 4 and self.words[start - 1].lower() in _LEAD_IN:
            start -= 1
        while end < len(self.words) and end - idx[-1] <= 2 and self.words[end].lower() in _UNITS:
            end += 1
        return list(self.words[start:end])

    def __str__(self) -> str:
        return " ".join(w if t == "O" else f"{w}/{t}" for w, t in zip(self.words, self.tags))


@dataclass(frozen=True)
class Decision:
    """What a rule concluded: a panel id (target rules) or a stud id (destination rules), and why."""

    value: str
    conclusion: str


@dataclass(frozen=True)
class TraceStep:
    """One rule's decision: which words and tags it used and what it concluded."""

    stage: str  # target | destination | placement | check
    rule: str
    applies: bool
    words: tuple[str, ...] = ()
    tags: tuple[str, ...] = ()
    conclusion: str = ""


@dataclass
class Trace:
    """Every rule consulted for one instruction, in order, including the ones that did not apply."""

    steps: list[TraceStep] = field(default_factory=list)

    def add(self, stage: str, rule: str, applies: bool, ti: TaggedInstruction | None = None,
            tags: Sequence[str] = (), conclusion: str = "") -> TraceStep:
        words: tuple[str, ...] = ()
        used: tuple[str, ...] = ()
        if ti is not None and tags:
            idx = ti.indices(*tags)
            words = tuple(ti.words[i] for i in idx)
            used = tuple(ti.tags[i] for i in idx)
        step = TraceStep(stage, rule, applies, words, used, conclusion)
        self.steps.append(step)
        return step

    def to_frame(self) -> pd.DataFrame:
        """The trace as a table: stage, rule, applies, words, tags, conclusion."""
        return pd.DataFrame(
            [
                {"stage": s.stage, "rule": s.rule, "applies": s.applies, "words": " ".join(s.words),
                 "tags": " ".join(s.tags), "conclusion": s.conclusion}
                for s in self.steps
            ],
            columns=["stage", "rule", "applies", "words", "tags", "conclusion"],
        )

    def __iter__(self):
        return iter(self.steps)

    def __len__(self) -> int:
        return len(self.steps)

    def __str__(self) -> str:
        lines = []
        for s in self.steps:
            mark = "->" if s.applies else "  "
            used = " ".join(f"{w}/{t}" for w, t in zip(s.words, s.tags))
            lines.append(f"{mark} [{s.stage}] {s.rule}: {s.conclusion}" + (f"  ({used})" if used else ""))
        return "\n".join(lines)


Rule = tuple[str, tuple[str, ...], Callable[[TaggedInstruction, Any], "Decision | None"]]


def first_decision(stage: str, rules: Sequence[Rule], ti: TaggedInstruction, ctx: Any, trace: Trace | None,
                   nothing_applies: str) -> Decision:
    """Try ``rules`` (name, tags it reads, function) in order, record each in ``trace`` (None: a trace of its own,
    not kept), return the first decision.

    A rule's ``Refusal`` is recorded and raised again; when no rule applies, the
    ``undetermined`` refusal with the message ``nothing_applies`` is.
    """
    trace = trace if trace is not None else Trace()
    for name, tags, rule in rules:
        try:
            decision = rule(ti, ctx)
        except Refusal as refusal:
            trace.add(stage, name, True, ti, tags, f"refused ({refusal.reason}): {refusal.message}")
            raise
        if decision is None:
            trace.add(stage, name, False, ti, tags, "does not apply")
            continue
        trace.add(stage, name, True, ti, tags, decision.conclusion)
        return decision
    trace.add(stage, f"no {stage} rule applies", True, conclusion=f"refused (undetermined): {nothing_applies}")
    raise Refusal("undetermined", nothing_applies)
