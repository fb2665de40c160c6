"""From tagged words to a robot command or a refusal: the IM module (the paper's Fig. 1).

``interpret`` reads the tags as the guidelines mean them (a place in a stack, or a word a change of mind took
back, is ``O``: ``TaggedInstruction``; the trace's ``R0`` steps name what was read so), runs the target rules
(Figs. 10-11), the destination rules (Fig. 12) and the placement rule, then checks that the robot can carry the
command out (the panel can be picked; it fits on the wall). It changes nothing: ``InformationMapper`` keeps the
action history and records a command only when it is accepted.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Mapping, Sequence, TypeVar

from drywall_lab.errors import Refusal
from drywall_lab.im import words as W
from drywall_lab.im.alternatives import Offer, offered_alternatives
from drywall_lab.im.command import RobotCommand
from drywall_lab.im.context import MappingContext
from drywall_lab.im.history import ActionHistory
from drywall_lab.im.placement import resolve_placement
from drywall_lab.im.stud import resolve_stud
from drywall_lab.im.target import resolve_target
from drywall_lab.im.trace import TaggedInstruction, Trace
from drywall_lab.site import Site

T = TypeVar("T")


@dataclass
class Interpretation:
    """The outcome for one instruction: a command or a refusal, and the rule trace that led there."""

    words: list[str]
    tags: list[str]
    trace: Trace = field(default_factory=Trace)
    command: RobotCommand | None = None
    refusal: Refusal | None = None
    #: Where the worker offered two things with "or" and they give different outcomes: each alternative read on its
    #: own (``alternatives.offered_alternatives``); the refusal is then ``unclear``.
    alternatives: list["Interpretation"] = field(default_factory=list)

    @property
    def accepted(self) -> bool:
        return self.command is not None

    @property
    def history_row(self) -> dict | None:
        """The row an accepted command adds to the action history."""
        return self.command.history_row() if self.command else None

    def outcome(self) -> dict:
        """``{"drywall_id", "stud_id", "placement", "refusal"}``, the shape of a corpus row's ``expected``."""
        if self.command is not None:
            return {**self.command.as_contract(), "refusal": None}
        return {"drywall_id": None, "stud_id": None, "placement": None, "refusal": self.refusal.reason}

    def summary(self) -> str:
        tagged = " ".join(w if t == "O" else f"{w}/{t}" for w, t in zip(self.words, self.tags))
        result = f"command: {self.command}" if self.command else f"refused ({self.refusal.reason}): {self.refusal.message}"
        return f"{tagged}\n{self.trace}\n{result}"


def interpret(words: Sequence[str], tags: Sequence[str], history: ActionHistory | None = None,
              site: Site | None = None, offers: bool = True) -> Interpretation:
    """Map one tagged instruction to a command or a refusal, given the history so far (not changed).

    The order of the checks: target rules, destination rules, placement, then whether
    the panel can be picked (``already_installed``, ``not_on_top``) and whether it fits
    (``past_wall_end``, ``overlap``). The first refusal stops the rest. Before them, a part offered twice with
    "or" (``offered_alternatives``; ``offers``) is read once for each alternative: where the two give different
    outcomes the robot asks which (``unclear``).
    """
    history = history if history is not None else ActionHistory(site)
    site = history.site
    ti = TaggedInstruction(words, tags)
    result = Interpretation(list(ti.words), list(ti.tags))
    trace = result.trace
    if not ti.words:
        message = "The instruction is empty: say which panel to pick and which stud to put it on."
        trace.add("target", "empty instruction", True, conclusion=f"refused (undetermined): {message}")
        result.refusal = Refusal("undetermined", message)
        return result
    if ti.in_stack:
        trace.add("reading", "R0 place in a stack", True,
                  conclusion=f"{W.quote([ti.words[i] for i in ti.in_stack])} names a place in a stack, not a row "
                             "on the wall: read as O")
    if ti.taken_back:
        trace.add("reading", "R0 final intention", True, conclusion=_taken_back_text(ti))
    offer = offered_alternatives(ti.words, ti.tags) if offers else None
    if offer is not None:
        undecided = _undecided(ti, offer, history, trace)
        if undecided is not None:
            result.refusal, result.alternatives = undecided
            return result
    ctx = MappingContext(site, history.state, history.last)
    try:
        drywall_id = resolve_target(ti, ctx, trace)
        stud_id = resolve_stud(ti, ctx, trace)
        placement = resolve_placement(ti, trace)
        _check("C1 panel can be picked", trace, lambda: ctx.state.check_pickable(drywall_id),
               lambda panel: f"panel {drywall_id} is on top of the {panel.stack} stack")
        _check("C2 panel fits on the wall", trace, lambda: ctx.state.check_fits(drywall_id, stud_id, placement),
               lambda r: f"x {r.x_left:.4f}..{r.x_right:.4f} m, z {r.z_bottom:.4f}..{r.z_top:.4f} m: "
                         "inside the wall, no overlap")
        result.command = RobotCommand.build(site, drywall_id, stud_id, placement)
    except Refusal as refusal:
        result.refusal = refusal
    return result


def _said(ti: TaggedInstruction, offer: Offer, which: int) -> str:
    positions = (offer.first, offer.second)[which] or offer.default_words
    return W.quote(ti.words[min(positions):max(positions) + 1])


def _undecided(ti: TaggedInstruction, offer: Offer, history: ActionHistory,
               trace: Trace) -> tuple[Refusal, list[Interpretation]] | None:
    """Each alternative of an offer read on its own; the refusal and the alternatives where their outcomes differ,
    None (read as one instruction) where both say the same."""
    readings = [interpret(ti.words, tags, history, offers=False) for tags in offer.readings(ti.tags)]
    first, second = _said(ti, offer, 0), _said(ti, offer, 1)
    if readings[0].outcome() == readings[1].outcome():
        trace.add("reading", "R0 alternatives", True,
                  conclusion=f"{first} or {second}: both give the same {offer.part}, read as one")
        return None
    said = [f"panel {r.command.drywall_id} on stud {r.command.stud_id}, {r.command.placement.described}"
            if r.command else f"nothing I can do ({r.refusal.message})" for r in readings]
    message = f"You said {first} or {second}: which {offer.part} do you mean, {said[0]}, or {said[1]}?"
    trace.add("reading", "R0 alternatives", True, conclusion=f"refused (unclear): {message}")
    return Refusal("unclear", message), readings


def _taken_back_text(ti: TaggedInstruction) -> str:
    """ "'second from the right' taken back by 'no'": what a change of mind took back (guidelines 4.7)."""
    by_cue: dict[str, list[str]] = {}
    for i, cue in ti.taken_back.items():
        by_cue.setdefault(cue, []).append(ti.words[i])
    return "; ".join(f"{W.quote(said)} taken back by '{cue}'" for cue, said in by_cue.items()) + ": only the final intention counts, read as O"


def _check(rule: str, trace: Trace, check: Callable[[], T], conclusion: Callable[[T], str]) -> T:
    """Run one of the site's checks and record what it found."""
    try:
        value = check()
    except Refusal as refusal:
        trace.add("check", rule, True, conclusion=f"refused ({refusal.reason}): {refusal.message}")
        raise
    trace.add("check", rule, True, conclusion=conclusion(value))
    return value


class InformationMapper:
    """The IM module with its action history: ``apply`` interprets and records accepted commands.

    >>> im = InformationMapper()
    >>> r = im.apply("Pick up the full-size drywall and put it on stud 500100".split(),
    ...              ["O", "O", "O", "dim", "O", "O", "O", "O", "O", "O", "ID_stud"])
    >>> r.command.drywall_id, r.command.stud_id, len(im.history)
    ('500320', '500100', 1)
    """

    def __init__(self, site: Site | None = None, history: ActionHistory | None = None) -> None:
        self.history = history if history is not None else ActionHistory(site)

    @property
    def site(self) -> Site:
        return self.history.site

    def interpret(self, words: Sequence[str], tags: Sequence[str]) -> Interpretation:
        """What the instruction would do now; nothing is recorded."""
        return interpret(words, tags, self.history)

    def apply(self, words: Sequence[str], tags: Sequence[str]) -> Interpretation:
        """Interpret, and record the command in the history if it is accepted."""
        result = self.interpret(words, tags)
        if result.command is not None:
            self.history.record(result.command)
        return result


# --- the corpus: task accuracy ------------------------------------------------------------
def interpret_row(row: Mapping, tags: Sequence[str] | None = None, site: Site | None = None) -> Interpretation:
    """Interpret a corpus row in its own context (the accepted commands before it in its episode).

    ``tags`` are a tagger's predictions; the row's gold tags when None.
    """
    history = ActionHistory.from_commands(row["context"]["history"], site)
    return interpret(row["words"], row["tags"] if tags is None else tags, history)


def task_correct(row: Mapping, tags: Sequence[str] | None = None, site: Site | None = None) -> bool:
    """Whether the instruction's final command (or refusal reason) is the one it was written to give."""
    return interpret_row(row, tags, site).outcome() == dict(row["expected"])


def task_accuracy(rows: Sequence[Mapping], predicted: Sequence[Sequence[str]] | None = None,
                  site: Site | None = None) -> float:
    """``acc_task``: the share of instructions whose command or refusal is the intended one."""
    if not rows:
        raise ValueError("no instructions to score")
    predicted = predicted if predicted is not None else [None] * len(rows)
    if len(predicted) != len(rows):
        raise ValueError(f"{len(rows)} instructions but {len(predicted)} predicted tag lists")
    return sum(task_correct(r, t, site) for r, t in zip(rows, predicted)) / len(rows)
