"""Notebook 04 (information mapping): rule S3 and its exercise, rule T2 from scratch (``check_stacks_of_size``), one
instruction's path through the rules drawn as a flowchart (Figs. 10-12: ``draw_rule_path``), the paper's layouts step
by step, and every refusal reason with an example."""
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


# --- from scratch: rule T2, the stacks a size names (Fig. 10) ---------------------------------------------------
#: The sites the T2 exercise is checked on: the project's, and two with other panel sizes (left, middle, right stack;
#: width x length in feet) where the usual slips show.
SIZE_SITES: tuple[tuple[tuple[float, float], ...], ...] = (
    (), ((2.0, 4.0), (4.0, 8.0), (4.0, 12.0)), ((4.0, 4.0), (4.0, 8.0), (2.0, 4.0)))
#: The numbers the T2 exercise's cases say (feet), each as width, as length, or both.
SIZE_NUMBERS = tuple(range(1, 13))


def site_with_sizes(sizes: Sequence[tuple[float, float]] = ()) -> "Site":
    """The project's site with the panels of each stack (left, middle, right) of another size, in feet; the
    project's own for ``()``. Only the sizes the rules read (``size_ft``) change."""
    from dataclasses import replace

    from drywall_lab.site import STACK_NAMES, default_site

    site = default_site()
    if not sizes:
        return site
    by_stack = dict(zip(STACK_NAMES, sizes))
    return replace(site, panels=tuple(replace(p, w_ft=by_stack[p.stack][0], l_ft=by_stack[p.stack][1])
                                      for p in site.panels))


def size_markup(width: float | None, length: float | None) -> str:
    """An instruction that says a size, in the project's markup: "take the 8/width by 4/length panel", "take the
    panel that is 2/width feet wide", "take the panel that is 8/length feet long"."""
    if width is not None and length is not None:
        return f"take the {width:g}/width by {length:g}/length panel"
    if width is not None:
        return f"take the panel that is {width:g}/width {'foot' if width == 1 else 'feet'} wide"
    return f"take the panel that is {length:g}/length {'foot' if length == 1 else 'feet'} long"


def rule_t2(width: float | None, length: float | None, site: "Site | None" = None) -> tuple[str, str]:
    """What the library's target rules (``resolve_target``, rule T2 of Fig. 10) make of a said size on a fresh
    site: ("stack", its name) for the panel on top of one stack, or ("refusal", the reason and message)."""
    from drywall_lab.errors import Refusal
    from drywall_lab.im import MappingContext, TaggedInstruction, resolve_target
    from drywall_lab.site import default_site

    site = site or default_site()
    words, tags = words_and_tags(size_markup(width, length))
    try:
        panel = resolve_target(TaggedInstruction(words, tags), MappingContext(site, site.fresh()))
    except Refusal as refusal:
        return "refusal", f"{refusal.reason}: {refusal}"
    return "stack", site.panel(panel).stack


def library_stacks_of_size(sizes: Mapping[str, tuple[float, float]], width: float | None,
                           length: float | None) -> list[str]:
    """The stacks rule T2 weighs (``drywall_lab.im.target``'s ``_stacks_of_size``): those of the size as said,
    else those of the size turned."""
    from types import SimpleNamespace

    from drywall_lab.im.target import _stacks_of_size

    ctx = SimpleNamespace(site=SimpleNamespace(sizes=dict(sizes)))
    return _stacks_of_size(ctx, width, length) or _stacks_of_size(ctx, length, width)


def stacks_of_size_cases() -> list[tuple["Site", float | None, float | None]]:
    """(site, width, length) for every site of ``SIZE_SITES`` and every width and length of ``SIZE_NUMBERS`` said
    alone or together."""
    said = [None, *map(float, SIZE_NUMBERS)]
    sites = [site_with_sizes(s) for s in SIZE_SITES]
    return [(site, w, l) for site in sites for w in said for l in said if (w, l) != (None, None)]


def check_stacks_of_size(stacks_of_size: Callable[[dict[str, tuple[float, float]], float | None, float | None],
                                                  Sequence[str]]) -> ExerciseCheck:
    """Notebook 04's from-scratch exercise: ``stacks_of_size(sizes, width, length)`` (rule T2 of Fig. 10: the
    stacks whose panels have the size said, a ``None`` side open; turned when none has it as said) against the
    library's rules on the project's site and two sites with other sizes, every width and length from 1 to 12 feet
    said alone or together. One stack must be the stack the rules pick, two or more the rules' question
    (``ambiguous_size``), none their refusal (``no_matching_size``); the stacks must be the library's. The first
    disagreement of each kind is explained. The notebook's stub (a function that raises ``NotImplementedError``)
    is "not attempted yet"."""
    cases = stacks_of_size_cases()
    first_site, w0, l0 = cases[0]
    if is_unattempted(stacks_of_size, dict(first_site.sizes), w0, l0):
        return ExerciseCheck.not_attempted("stacks_of_size(sizes, width, length): the list of the stacks whose "
                                           "panels have that size (None: either), turned when none has it as said",
                                           solution_file(4))
    disagreements = []
    for site, width, length in cases:
        sizes = dict(site.sizes)
        want = library_stacks_of_size(sizes, width, length)
        got, error = call_student(stacks_of_size, dict(sizes), width, length)
        if error or not _is_stack_list(got, sizes) or sorted(got) != sorted(want):
            disagreements.append((sizes, width, length, want, got, error))
    if not disagreements:
        return ExerciseCheck(True, [f"all {len(cases)} cases agree with rule T2 ({len(SIZE_SITES)} sites, every "
                                    f"width and length from {SIZE_NUMBERS[0]} to {SIZE_NUMBERS[-1]} feet, alone "
                                    "and together)"])
    messages = [f"{len(disagreements)} of {len(cases)} cases disagree with rule T2; the first of each kind:"]
    seen = set()
    for sizes, width, length, want, got, error in disagreements:
        kind, hint = _t2_mistake(sizes, width, length, want, got, error)
        if kind in seen:
            continue
        seen.add(kind)
        said = " ".join(words_and_tags(size_markup(width, length))[0])
        stacks = ", ".join(f"{s} {w:g} x {l:g}" for s, (w, l) in sizes.items())
        result = f"raised {error}" if error else repr(got)
        rules = ("no stack (the rules refuse: no_matching_size)" if not want
                 else f"{want} (the rules ask which: ambiguous_size)" if len(want) > 1
                 else f"the {want[0]} stack (the rule picks its top panel)")
        messages.append(f"'{said}' with the stacks {stacks}: the rules give {rules}, your function {result}"
                        + (f"; {hint}" if hint else ""))
    return ExerciseCheck(False, messages)


def _is_stack_list(got: Any, sizes: Mapping[str, Any]) -> bool:
    return (isinstance(got, (list, tuple)) and all(isinstance(s, str) and s in sizes for s in got)
            and len(set(got)) == len(got))


def _t2_mistake(sizes: Mapping[str, tuple[float, float]], width: float | None, length: float | None,
                want: list[str], got: Any, error: str | None) -> tuple[str, str]:
    """(the kind of a wrong T2 answer, a hint saying what to change)."""
    def matching(w: float | None, l: float | None) -> list[str]:
        return [s for s, (sw, sl) in sizes.items() if (w is None or sw == w) and (l is None or sl == l)]

    if error:
        return "error", "it should return a list of stacks (perhaps empty), never raise"
    if not _is_stack_list(got, sizes):
        return "type", f"return a list of stack names, each once, from {list(sizes)}"
    got = list(got)
    as_said, turned = matching(width, length), matching(length, width)
    if not got and not as_said and turned:
        return "not turned", ("nothing has that size as said: try it turned (width and length swapped), as the rule "
                              "does" + ("; a side not said (None) matches any" if None in (width, length) else ""))
    if not got and None in (width, length) and want:
        return "open side", ("a size said with one number leaves the other side open: None matches every "
                             f"{'width' if width is None else 'length'}")
    if sorted(got) == sorted(set(as_said) | set(turned)) and as_said and turned:
        return "always turned", "try the size turned only when nothing has it as said"
    if len(got) == 1 and len(want) > 1 and got[0] in want:
        return "first only", ("return every stack of that size: with two or more the rule does not guess, it asks "
                              "which one (ambiguous_size)")
    if sorted(got) == sorted(matching(length, width) or matching(width, length)):
        return "swapped", "the width is the first number said (the short side), the length the second"
    return "other", f"the stacks of that size are {want or 'none'}"


# --- one instruction's path through a map's rules, as a flowchart (Figs. 10-12) ------------------------------------
#: The three maps of the IM, in the order they run: each rule's name (as the trace writes it), the tags it reads and
#: what it gives when it applies; then what happens when none does.
RULE_MAPS: dict[str, tuple[tuple[tuple[str, str, str], ...], str]] = {
    "target": ((("T1 panel id", "ID_wall", "that panel"),
                ("T2 width and length", "width, length", "the top panel of the stack of that size"),
                ("T3 size word or same as before", "dim", "the top panel of the standard or the last size"),
                ("T4 stack position", "Dw_loc1 alone", "the top panel of the stack there"),
                ("T5 relative stack position", "Dw_loc1 + Dw_loc2", "the top panel of the stack counted")),
               "refuse (undetermined): which panel?"),
    "destination": ((("S1 stud id", "ID_stud", "that stud"),
                     ("S2 stud position", "St_loc1 alone", "the stud there on the wall"),
                     ("S3 relative stud position", "St_loc1 + St_loc2", "the stud counted from the anchor")),
                    "refuse (undetermined): which stud?"),
    "placement": ((("P1 placement tags", "Vr_md, Hr_top, Hr_btm", "that placement"),
                   ("P2 default", "", "vertical, left edge on the stud's left line")),
                  "(never reached: P2 always applies)"),
}


@dataclass(frozen=True)
class RuleStep:
    """One rule of a map on an instruction's path: ``tried`` (the trace has it), ``applies``, what it concluded."""

    rule: str
    reads: str
    gives: str
    tried: bool
    applies: bool
    conclusion: str


def rule_path(result: "Interpretation", stage: str) -> tuple[list[RuleStep], str | None]:
    """The rules of one map (``RULE_MAPS``: ``target``, ``destination`` or ``placement``) in order, each with what
    the instruction's trace says of it, and the refusal when no rule applied (None otherwise)."""
    rules, nothing = RULE_MAPS[stage]
    traced = {step.rule: step for step in result.trace if step.stage == stage}
    steps = [RuleStep(name, reads, gives, name in traced, name in traced and traced[name].applies,
                      traced[name].conclusion if name in traced else "") for name, reads, gives in rules]
    none = next((s.conclusion for s in result.trace if s.stage == stage and s.rule.startswith("no ")), None)
    return steps, none


def draw_rule_path(result: "Interpretation", stage: str = "target", ax: "plt.Axes | None" = None,
                   width: int = 38, rows: int = 0) -> "plt.Axes":
    """One map of the IM (the paper's Figs. 10-12: the target, the destination or the placement) as a flowchart: its
    rules top to bottom in the order they are tried, "no" down to the next rule, "yes" right to what the rule gives;
    the path the instruction's trace took drawn in colour, with the deciding rule's conclusion (or refusal), the
    rules never reached in grey. ``rows``: room for that many rules (to draw several maps to one scale)."""
    import textwrap

    import matplotlib.pyplot as plt

    steps, none = rule_path(result, stage)
    if ax is None:
        _, ax = plt.subplots(figsize=(8, 1.5 * len(steps) + 2))
    path, grey, faint = "tab:orange", "0.6", "0.93"
    gap = 1.5
    ys = [-(i + 1) * gap for i in range(len(steps))]
    ax.set_xlim(0, 10)
    ax.set_ylim(-(max(rows, len(steps)) + 1) * gap - 0.6, 0.7)
    ax.axis("off")

    def box(x: float, y: float, text: str, on: bool, fill: str = "white", bold: bool = False, size: float = 9) -> None:
        ax.text(x, y, text, ha="center", va="center", fontsize=size, fontweight="bold" if bold else "normal",
                color="black" if on else grey, wrap=False,
                bbox=dict(boxstyle="round,pad=0.4", fc=fill if on else faint, ec=path if on else grey,
                          lw=2.2 if on else 1.0))

    def arrow(x0: float, y0: float, x1: float, y1: float, on: bool, label: str) -> None:
        ax.annotate("", (x1, y1), (x0, y0), arrowprops=dict(arrowstyle="-|>", color=path if on else grey,
                                                           lw=2.2 if on else 1.0))
        ax.text((x0 + x1) / 2 + 0.12, (y0 + y1) / 2 + 0.08, label, fontsize=8, color=path if on else grey)

    words = " ".join(w if t == "O" else f"{w}/{t}" for w, t in zip(result.words, result.tags))
    reached = any(step.tried for step in steps) or none is not None
    box(2.2, 0.2, textwrap.fill(words, width), reached, fill="#fff4e0", size=8)
    arrow(2.2, -0.15, 2.2, ys[0] + 0.35, reached, "")
    decided = False
    for step, y in zip(steps, ys):
        on = step.tried and not decided
        box(2.2, y, f"{step.rule}\n" + (f"reads {step.reads}?" if step.reads else "always applies"), on,
            bold=on and step.applies)
        yes_on = on and step.applies
        arrow(3.9, y, 5.6, y, yes_on, "yes")
        text = step.conclusion if yes_on else step.gives
        box(7.9, y, textwrap.fill(text, width), yes_on, fill="#fde0e0" if text.startswith("refused") else "#fff4e0",
            size=8 if yes_on else 7.5)
        decided = decided or yes_on
        last = y == ys[-1]
        next_y = ys[-1] - gap if last else y - gap
        arrow(2.2, y - 0.4, 2.2, next_y + 0.35, on and not step.applies, "no")
    box(2.2, ys[-1] - gap, textwrap.fill(none or RULE_MAPS[stage][1], width), none is not None,
        fill="#fde0e0", size=8)
    ax.set_title(f"The {stage} rules, in order: the path of this instruction", fontsize=10)
    return ax


def draw_rule_paths(result: "Interpretation", stages: Sequence[str] = tuple(RULE_MAPS)) -> "plt.Figure":
    """``draw_rule_path`` for each of ``stages`` side by side: the instruction's whole path through the IM."""
    import matplotlib.pyplot as plt

    n = max(len(RULE_MAPS[s][0]) for s in stages)
    fig, axes = plt.subplots(1, len(stages), figsize=(8 * len(stages), 1.5 * n + 2.2), squeeze=False)
    for ax, stage in zip(axes[0], stages):
        draw_rule_path(result, stage, ax, rows=n)
    fig.tight_layout()
    return fig
