"""Notebook 04 (information mapping): rule S3 and its exercise, the paper's layouts step by step, and every
refusal reason with an example."""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy as np
import pandas as pd

from drywall_lab.course.common import solution_file
from drywall_lab.exercise import ExerciseCheck, call_student, is_unattempted

if TYPE_CHECKING:
    import matplotlib.pyplot as plt

    from drywall_lab.im import ActionHistory, Interpretation
    from drywall_lab.site import Site, SiteState


#: How the S3 exercise's cases say a count.
COUNT_WORDS = {0: "zero", 1: "one", 2: "two", 3: "3", 4: "four", 5: "5th", 12: "12", 13: "thirteen"}


def words_and_tags(markup: str) -> tuple[list[str], list[str]]:
    """Words and tags from the project's markup: ``"the full-size/dim drywall on stud 500107/ID_stud"``."""
    from drywall_lab.corpus.markup import parse

    tokens = [t for t in parse(markup) if t.is_word]
    return [t.word for t in tokens], [t.tag for t in tokens]


def relative_stud_cases(site: "Site | None" = None) -> list[tuple[str, str, int, str]]:
    """(anchor id, direction, count, the instruction's words) for every stud of the site as anchor, both
    directions and counts from 0 to past the wall's end."""
    from drywall_lab.site import default_site

    site = site or default_site()
    cases = []
    for anchor in site.stud_ids:
        for direction in ("left", "right"):
            for count, said in COUNT_WORDS.items():
                cases.append((anchor, direction, count,
                              f"put the full-size/dim panel on the stud {said}/St_loc1 to/St_loc1 the/St_loc1 "
                              f"{direction}/St_loc1 of 500000/St_loc2".replace("500000", anchor)))
    return cases


def rule_s3(markup: str, site: "Site | None" = None) -> tuple[str | None, str]:
    """What the library's rules (``resolve_stud``, Fig. 12) make of one instruction: (stud id or None, why)."""
    from drywall_lab.errors import Refusal
    from drywall_lab.im import MappingContext, TaggedInstruction, resolve_stud
    from drywall_lab.site import default_site

    site = site or default_site()
    words, tags = words_and_tags(markup)
    try:
        return resolve_stud(TaggedInstruction(words, tags), MappingContext(site, site.fresh())), ""
    except Refusal as refusal:
        return None, f"{refusal.reason}: {refusal}"


def check_relative_stud(relative_stud: Callable[["Site", str, str, int], str | None],
                        site: "Site | None" = None) -> ExerciseCheck:
    """Notebook 04's exercise: ``relative_stud(site, anchor_id, direction, count)`` (rule S3 of Fig. 12: the stud
    ``count`` places to the ``direction`` of the anchor, ``None`` past the wall's end) against the library's
    rules on every anchor, both directions and counts from 0 to past the end; the first disagreement and
    how many there are. The notebook's stub (a function that raises ``NotImplementedError``) is "not attempted
    yet"; ``None`` is a real answer here (past the wall's end), so a function returning it is attempted."""
    from drywall_lab.site import default_site

    site = site or default_site()
    cases = relative_stud_cases(site)
    if is_unattempted(relative_stud, site, *cases[0][:3]):
        return ExerciseCheck.not_attempted("relative_stud(site, anchor_id, direction, count): the id of the stud "
                                           "count places to the direction of the anchor, None past either end",
                                           solution_file(4))
    disagreements = []
    for anchor, direction, count, markup in cases:
        want, why = rule_s3(markup, site)
        got, error = call_student(relative_stud, site, anchor, direction, count)
        if error or got != want:
            disagreements.append((anchor, direction, count, markup, want, why, got, error))
    if not disagreements:
        return ExerciseCheck(True, [f"all {len(cases)} cases agree with rule S3 ({len(site.stud_ids)} anchors, left "
                                    f"and right, counts {', '.join(map(str, sorted(COUNT_WORDS)))})"])
    messages = [f"{len(disagreements)} of {len(cases)} cases disagree with rule S3; the first of each kind:"]
    seen = set()
    for anchor, direction, count, markup, want, why, got, error in disagreements:
        kind, hint = _s3_mistake(site, anchor, direction, count, want, got, error)
        if kind in seen:
            continue
        seen.add(kind)
        said = " ".join(words_and_tags(markup)[0])
        result = f"raised {error}" if error else repr(got)
        rules = repr(want) if want else f"no stud ({why})"
        messages.append(f"'{said}': the rules give {rules}, your function {result}"
                        + (f"; {hint}" if hint else ""))
    return ExerciseCheck(False, messages)


def _s3_mistake(site: "Site", anchor: str, direction: str, count: int, want: str | None, got: Any,
                error: str | None) -> tuple[str, str]:
    """(the kind of a wrong S3 answer, a hint saying what to change)."""
    ids = site.stud_ids
    if error:
        return "error", "it should return a stud id or None, never raise"
    if got is not None and not isinstance(got, str):
        return "type", f"return the stud's id as a string, like {ids[0]!r}, or None"
    if got is not None and got not in ids:
        return "unknown", f"{got!r} is not a stud of this site; the studs are {ids[0]} to {ids[-1]}"
    if want is None:
        step = ids.index(anchor) + (count if direction == "right" else -count)
        wrapped = 0 <= step % len(ids) < len(ids) and got == ids[step % len(ids)] and step < 0
        return "past the end", ("past the end of the wall there is no stud: return None"
                                + (" (a negative list index counts from the other end in Python)" if wrapped else ""))
    if got is None:
        return "none", "that stud is on the wall: only a step past either end gives None"
    step = site.stud(got).index - site.stud(want).index
    if count == 0:
        return "zero", "zero places away is the anchor itself"
    if site.stud(got).index - site.stud(anchor).index == -(site.stud(want).index - site.stud(anchor).index):
        return "direction", "that is the other direction: right is towards higher ids, left towards lower"
    return "distance", (f"your stud is {abs(step)} stud{'s' if abs(step) != 1 else ''} to the "
                        f"{'right' if step > 0 else 'left'} of the one the rules give")


@dataclass
class GoldLayoutRun:
    """One of the paper's layouts mapped by the IM rules from its hand-checked tags, step by step."""

    layout: Mapping
    results: list["Interpretation"]
    history: "ActionHistory"
    states: list["SiteState"]  #: the site after each step (a refused step leaves it as it was)

    def outcomes(self) -> list[dict]:
        """Each step as the layout's ``expected`` writes it: the command, or ``{"refusal": reason}``."""
        return [r.command.as_contract() if r.accepted else {"refusal": r.refusal.reason} for r in self.results]

    def problems(self) -> list[str]:
        """Every step whose outcome is not the layout's expected one (none: the rules agree with the layout)."""
        found = [f"step {k}: expected {want}, got {got}"
                 for k, (got, want) in enumerate(zip(self.outcomes(), self.layout["expected"])) if got != want]
        if len(self.results) != len(self.layout["expected"]):
            found.append(f"{len(self.results)} steps, the layout expects {len(self.layout['expected'])}")
        return found

    def step_lines(self) -> list[str]:
        """One line per step: the command, or the refusal and its message."""
        return [str(r.command) if r.accepted else f"refused ({r.refusal.reason}): {r.refusal.message}"
                for r in self.results]

    def titles(self) -> list[str]:
        return [f"after step {k}" + ("" if r.accepted else " (refused: nothing changes)")
                for k, r in enumerate(self.results)]

    def figure(self) -> "plt.Figure":
        """The wall after each step (the paper's Figs. 16-18)."""
        from drywall_lab.plots import draw_wall_steps

        return draw_wall_steps(self.states, self.titles())


def map_layout(layout: Mapping, site: "Site | None" = None) -> GoldLayoutRun:
    """A layout's hand-tagged instructions through the IM rules in order, on a fresh site: no tagger."""
    from drywall_lab.im import InformationMapper

    mapper = InformationMapper(site)
    results, states = [], []
    for words, tags in zip(layout["words"], layout["tags"]):
        results.append(mapper.apply(words, tags))
        states.append(mapper.history.state)
    return GoldLayoutRun(layout, results, mapper.history, states)


def show_layout(layout: Mapping, site: "Site | None" = None) -> GoldLayoutRun:
    """Map a layout (``map_layout``) and show it: each step's tagged words and outcome, then the wall step by step."""
    from IPython.display import HTML, display

    from drywall_lab.display import tagged_html

    run = map_layout(layout, site)
    for step, (words, tags, line) in enumerate(zip(layout["words"], layout["tags"], run.step_lines())):
        display(HTML(f"<b>step {step}</b>" + tagged_html(words, tags)))
        print(f"step {step}: {line}")
    run.figure()
    return run


def unclear_example() -> tuple[str, str]:
    """The decision layer's question (reason ``unclear``, ``drywall_lab.decision``) for one instruction that an
    unsure tagger reads two ways: "middle" as the placement (``Vr_md``) or as nothing (``O``); (text, message)."""
    from drywall_lab.corpus.tags import TAGS as LABELS
    from drywall_lab.decision import decide

    words, centre = words_and_tags("put the full-size/dim panel on stud 500104/ID_stud in the middle/Vr_md")
    default = ["O" if t == "Vr_md" else t for t in centre]
    decision = decide(words, [(centre, np.log(0.55)), (default, np.log(0.45))],
                      np.zeros((len(words), len(LABELS))), LABELS)
    return " ".join(words) + " (read two ways: 'middle' as Vr_md, p = 0.55, or O, p = 0.45)", decision.refusal.message


def refusal_examples(rows_by_split: Mapping[str, Sequence[Mapping]]) -> pd.DataFrame:
    """Spec section 5's refusal reasons, each with the first corpus instruction refused for it and the message
    the worker hears; ``stack_empty`` (which the corpus's episodes never reach) on a history built for it, and
    ``unclear`` (the decision layer's question, never a gold-tag outcome) from ``unclear_example``."""
    from drywall_lab.errors import REFUSAL_REASONS
    from drywall_lab.im import ActionHistory, interpret, interpret_row

    examples: dict[str, tuple[str, str]] = {}
    for rows in rows_by_split.values():
        for r in rows:
            reason = r["expected"]["refusal"]
            if reason and reason not in examples:
                examples[reason] = (r["text"], interpret_row(r).refusal.message)
    if "stack_empty" not in examples:
        emptied = ActionHistory.from_commands([{"drywall_id": d, "stud_id": s, "placement": "vertical_left"}
                                               for d, s in [("500321", "500100"), ("500311", "500102"),
                                                            ("500301", "500104")]])
        words, tags = words_and_tags("Take the 2/width by 8/length panel and put it on stud 500108/ID_stud")
        examples["stack_empty"] = (" ".join(words), interpret(words, tags, emptied).refusal.message)
    if "unclear" not in examples:
        examples["unclear"] = unclear_example()
    return pd.DataFrame([{"reason": k, "meaning": REFUSAL_REASONS[k], "instruction": examples[k][0],
                          "message": examples[k][1]} for k in REFUSAL_REASONS if k in examples])
