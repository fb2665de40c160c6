"""Generate the instruction corpus in episode context, as the paper's authors did.

The paper's 1,584 instructions are not public, so the project writes its own:
each instruction is produced while simulating an *episode*, a fresh site on
which a worker has the robot install panels one after another. The worker first
decides what they want (a feasible command, or about one time in twenty a
command the spec says must be refused), then how to say it: which reference to
use for the panel and the stud (id, size, position, relative position, a
back-reference to the last action), how many sentences, which synonyms, and
whether it reads like typed text or like a speech recogniser's output.

Every instruction records its words, its 13-label tags, its 15-label
co-reference tags, its sentence count, the ``context`` the information mapping
needs (the accepted commands before it in its episode) and the ``expected``
result: the command, or the refusal reason.
"""
from __future__ import annotations

import random
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable, Iterable

from drywall_lab.corpus import phrases as P
from drywall_lab.corpus.markup import Phrase, Token, parse, plain, tagged
from drywall_lab.corpus.tags import COREF_TAGS
from drywall_lab.errors import Refusal
from drywall_lab.site import STACK_NAMES, Placement, Site, SiteState, default_site

SEED = 2024
SPLIT_SIZES = {"train": 1268, "validation": 158, "test": 158, "novel": 200}
#: Instructions with 1, 2, 3 and 4 sentences in each split. The test split is the
#: paper's (46/74/27/11); the others keep the paper's overall mean of 1.94.
SENTENCE_QUOTAS = {
    "train": {1: 393, 2: 609, 3: 216, 4: 50},
    "validation": {1: 49, 2: 76, 3: 27, 4: 6},
    "test": {1: 46, 2: 74, 3: 27, 4: 11},
    "novel": {1: 60, 2: 95, 3: 34, 4: 11},
}
REFUSAL_RATE = 0.05  # about one instruction in twenty must be refused

#: How often each kind of reference is chosen when it can describe the command.
TARGET_WEIGHTS = {"id": 0.24, "size": 0.21, "standard": 0.18, "same": 0.18, "absolute": 0.06, "relative": 0.13}
STUD_WEIGHTS = {"id": 0.32, "absolute": 0.20, "relative": 0.48}
PLACEMENT_WEIGHTS = {"vertical_left": 0.36, "vertical_middle": 0.53, "horizontal_top": 0.055, "horizontal_bottom": 0.055}

STUD_ABS_NAMES = {0: "leftmost", 12: "rightmost", 6: "middle"}
#: Relative positions: near neighbours are named more often than far ones.
COUNT_WEIGHT = {1: 4, 2: 2, 3: 1, 4: 1}


# --- what the worker means -----------------------------------------------------------
@dataclass(frozen=True)
class TargetRef:
    """How the worker points at the panel (the paper's Figs. 10 and 11)."""

    kind: str  # id | size | width | length | standard | same | absolute | relative | none
    panel_id: str | None = None
    size: tuple[int, int] | None = None  # (first number, second number) as said
    length_first: bool = False
    stack: str | None = None
    direction: str | None = None
    count: int = 1
    anchor: str | None = None  # a panel id, or "previous"


@dataclass(frozen=True)
class StudRef:
    """How the worker points at the stud (the paper's Fig. 12)."""

    kind: str  # id | absolute | from_end | ordinal | relative | same | none
    stud_id: str | None = None
    name: str | None = None  # leftmost | rightmost | middle
    side: str | None = None
    nth: int = 0
    direction: str | None = None
    count: int = 1
    anchor: str | None = None  # a stud id, leftmost, rightmost or previous


@dataclass
class Meaning:
    """What the worker wants to say, and what the robot should make of it."""

    target: TargetRef
    stud: StudRef
    placement: str
    expected: dict

    def describe(self) -> dict:
        """The references as plain dicts (unset fields left out), for the corpus files."""
        def clean(ref) -> dict:
            return {k: (list(v) if isinstance(v, tuple) else v) for k, v in asdict(ref).items()
                    if v is not None and not (k == "count" and ref.kind not in ("relative",))
                    and not (k == "nth" and v == 0) and not (k == "length_first" and not v)}
        return {"target": clean(self.target), "stud": clean(self.stud), "placement": self.placement}


@dataclass
class Episode:
    """The state an episode has reached: the site and the accepted commands."""

    state: SiteState
    history: list[dict] = field(default_factory=list)

    @property
    def last(self) -> dict | None:
        return self.history[-1] if self.history else None

    def accept(self, e: dict) -> None:
        """Carry out a row's expected command, if it is one: the panel goes on the wall and into the history."""
        if e["refusal"] is None:
            self.state = self.state.install(e["drywall_id"], e["stud_id"], e["placement"])
            self.history.append({k: e[k] for k in ("drywall_id", "stud_id", "placement")})


def corpus_row(row_id: str, said: tuple[str, list[str], list[str], list[str]], n_sentences: int, episode_id: str,
               step: int, ep: Episode, meaning: "Meaning", **extra) -> dict:
    """One corpus row: ``said`` is ``render``'s (text, words, tags, co-reference tags); ``extra`` fields
    (the field corpus's ``register``) follow ``n_sentences``."""
    text, words, tags, coref = said
    return {"id": row_id, "text": text, "words": words, "tags": tags, "coref_tags": coref, "n_sentences": n_sentences,
            **extra, "context": {"episode": episode_id, "step": step, "history": [dict(h) for h in ep.history]},
            "meaning": meaning.describe(), "expected": meaning.expected}


# --- choosing a command and its references ------------------------------------------
def feasible_commands(state: SiteState) -> list[tuple[str, str, str]]:
    """Every (panel, stud, placement) the robot could carry out now."""
    out = []
    for stack in STACK_NAMES:
        top = state.top(stack)
        if top is None:
            continue
        for stud in state.site.studs:
            for placement in Placement:
                try:
                    state.check_fits(top, stud.stud_id, placement)
                except Refusal:
                    continue
                out.append((top, stud.stud_id, placement.value))
    return out


def _weighted(rng: random.Random, options: dict[str, float]) -> str:
    keys = [k for k, w in options.items() if w > 0]
    return rng.choices(keys, weights=[options[k] for k in keys])[0]


def target_refs(ep: Episode, panel_id: str) -> dict[str, list[TargetRef]]:
    """All the ways the worker could name ``panel_id`` now, grouped by kind."""
    site = ep.state.site
    panel = site.panel(panel_id)
    stack = panel.stack
    w, l = int(panel.w_ft), int(panel.l_ft)
    refs: dict[str, list[TargetRef]] = {k: [] for k in TARGET_WEIGHTS}
    refs["id"].append(TargetRef("id", panel_id=panel_id))
    refs["size"] += [TargetRef("size", size=(w, l)), TargetRef("size", size=(w, l), length_first=True),
                     TargetRef("size", size=(l, w))]  # "8 by 4": turned, the IM tries it swapped
    if (w, l) == (2, 8):
        refs["size"].append(TargetRef("width", size=(w, l)))
    if (w, l) == (4, 6):
        refs["size"].append(TargetRef("length", size=(w, l)))
    if stack == "left":
        refs["standard"].append(TargetRef("standard"))
    if ep.last and site.panel(ep.last["drywall_id"]).stack == stack:
        refs["same"].append(TargetRef("same"))
    refs["absolute"].append(TargetRef("absolute", stack=stack))
    target_index = STACK_NAMES.index(stack)
    for anchor_stack in STACK_NAMES:
        delta = target_index - STACK_NAMES.index(anchor_stack)
        if delta == 0:
            continue
        direction = "right" if delta > 0 else "left"
        anchor_ids = [p.drywall_id for p in site.stack(anchor_stack)]
        for aid in anchor_ids:
            refs["relative"] += [TargetRef("relative", direction=direction, count=abs(delta), anchor=aid)] * (3 if abs(delta) == 1 else 1)
        if ep.last and site.panel(ep.last["drywall_id"]).stack == anchor_stack:
            refs["relative"] += [TargetRef("relative", direction=direction, count=abs(delta), anchor="previous")] * 3
    return refs


def stud_refs(ep: Episode, stud_id: str) -> dict[str, list[StudRef]]:
    """All the ways the worker could name ``stud_id`` now, grouped by kind."""
    site = ep.state.site
    i = site.stud(stud_id).index
    n = len(site.studs)
    refs: dict[str, list[StudRef]] = {k: [] for k in STUD_WEIGHTS}
    refs["id"].append(StudRef("id", stud_id=stud_id))
    if i in STUD_ABS_NAMES:
        refs["absolute"] += [StudRef("absolute", name=STUD_ABS_NAMES[i])] * 2
    if i < 6:
        refs["absolute"] += [StudRef("from_end", side="left", nth=i + 1), StudRef("ordinal", nth=i + 1)]
    if i > n - 7:
        refs["absolute"].append(StudRef("from_end", side="right", nth=n - i))
    for a in range(n):
        delta = i - a
        if 1 <= abs(delta) <= 4:
            refs["relative"] += [StudRef("relative", direction="right" if delta > 0 else "left",
                                         count=abs(delta), anchor=site.studs[a].stud_id)] * COUNT_WEIGHT[abs(delta)]
    if 1 <= i <= 4:
        refs["relative"] += [StudRef("relative", direction="right", count=i, anchor="leftmost")] * 2 * COUNT_WEIGHT[i]
    if n - 5 <= i <= n - 2:
        refs["relative"] += [StudRef("relative", direction="left", count=n - 1 - i, anchor="rightmost")] * 2 * COUNT_WEIGHT[n - 1 - i]
    if ep.last:
        p = site.stud(ep.last["stud_id"]).index
        if p == i:
            refs["relative"] += [StudRef("same", anchor="previous")] * 6
        elif abs(i - p) <= 4:
            refs["relative"] += [StudRef("relative", direction="right" if i > p else "left",
                                         count=abs(i - p), anchor="previous")] * (3 * COUNT_WEIGHT[abs(i - p)])
    return refs


def choose_ref(rng: random.Random, refs: dict[str, list], weights: dict[str, float]):
    kinds = {k: weights[k] for k, v in refs.items() if v}
    return rng.choice(refs[_weighted(rng, kinds)])


def choose_command(rng: random.Random, ep: Episode,
                   placement_weights: dict[str, float] = PLACEMENT_WEIGHTS) -> tuple[str, str, str] | None:
    """A feasible command, placements weighted as in the paper's corpus (or by ``placement_weights``);
    None when the wall is full."""
    options = feasible_commands(ep.state)
    if not options:
        return None
    if ep.last and rng.random() < 0.25:  # a second panel on the stud just used: top row over bottom row
        same_stud = [c for c in options if c[1] == ep.last["stud_id"]]
        if same_stud:
            return rng.choice(same_stud)
    if not ep.history and rng.random() < 0.3:  # walls are usually started at their left end
        options = [c for c in options if c[1] == ep.state.site.studs[0].stud_id] or options
    by_placement: dict[str, list] = {}
    for c in options:
        by_placement.setdefault(c[2], []).append(c)
    placement = _weighted(rng, {k: placement_weights[k] for k in by_placement})
    candidates = by_placement[placement]
    if ep.history and rng.random() < 0.5:  # panels go up from left to right: often right next to the last one
        last_right = max(i.rect.x_right for i in ep.state.installed)
        candidates = sorted(candidates, key=lambda c: abs(ep.state.site.rect(c[0], c[1], c[2]).x_left - last_right))[:3]
    return rng.choice(candidates)


@dataclass(frozen=True)
class MeaningWeights:
    """How often each kind of reference and each placement is chosen (the paper corpus's by default)."""

    target: dict[str, float] = field(default_factory=lambda: dict(TARGET_WEIGHTS))
    stud: dict[str, float] = field(default_factory=lambda: dict(STUD_WEIGHTS))
    placement: dict[str, float] = field(default_factory=lambda: dict(PLACEMENT_WEIGHTS))


PAPER_WEIGHTS = MeaningWeights()


def command_meaning(rng: random.Random, ep: Episode, weights: MeaningWeights = PAPER_WEIGHTS) -> Meaning | None:
    """A feasible command and the references the worker uses for it."""
    command = choose_command(rng, ep, weights.placement)
    if command is None:
        return None
    panel_id, stud_id, placement = command
    target = choose_ref(rng, target_refs(ep, panel_id), weights.target)
    if ep.last and ep.last["stud_id"] == stud_id and rng.random() < 0.6:
        stud = StudRef("same", anchor="previous")  # "the same stud as the previous one"
    else:
        stud = choose_ref(rng, stud_refs(ep, stud_id), weights.stud)
    expected = {"drywall_id": panel_id, "stud_id": stud_id, "placement": placement, "refusal": None}
    return Meaning(target, stud, placement, expected)


def refusal_meaning(rng: random.Random, ep: Episode, weights: MeaningWeights = PAPER_WEIGHTS) -> Meaning | None:
    """An instruction the spec says must be refused, with exactly one thing wrong."""
    base = command_meaning(rng, ep, weights)
    if base is None:
        return None
    site, state = ep.state.site, ep.state
    makers: dict[str, callable] = {}

    def unknown_panel():
        return TargetRef("id", panel_id=rng.choice(["500330", "500303", "500340", "500313", "500299", "500400"])), base.stud
    def unknown_stud():
        return base.target, StudRef("id", stud_id=rng.choice(["500113", "500115", "500099", "500120", "500200"]))
    makers["unknown_id"] = lambda: rng.choice([unknown_panel, unknown_stud])()

    def off_end_target():
        edge = rng.choice(["left", "right"])
        anchor = site.stack(edge)[rng.randrange(3)].drywall_id
        return TargetRef("relative", direction=edge, count=rng.choice([1, 1, 2]), anchor=anchor), base.stud
    def off_end_stud():
        if rng.random() < 0.4:
            end = rng.choice(["leftmost", "rightmost"])
            return base.target, StudRef("relative", direction="left" if end == "leftmost" else "right", count=1, anchor=end)
        d = rng.choice(["left", "right"])
        count = rng.randint(2, 4)
        idx = rng.randrange(0, count) if d == "left" else rng.randrange(len(site.studs) - count, len(site.studs))
        return base.target, StudRef("relative", direction=d, count=count, anchor=site.studs[idx].stud_id)
    makers["off_the_end"] = lambda: rng.choice([off_end_target, off_end_stud])()

    makers["ambiguous_size"] = lambda: (rng.choice([TargetRef("width", size=(4, 8)), TargetRef("length", size=(4, 8)),
                                                   TargetRef("length", size=(2, 8))]), base.stud)
    makers["no_matching_size"] = lambda: (TargetRef("size", size=rng.choice([(3, 5), (4, 10), (2, 6), (5, 8), (3, 8)])), base.stud)
    if not ep.history:
        makers["no_history"] = lambda: rng.choice([
            (TargetRef("same"), base.stud),
            (TargetRef("relative", direction="right", count=1, anchor="previous"), base.stud),
            (base.target, StudRef("relative", direction=rng.choice(["left", "right"]), count=rng.randint(1, 3), anchor="previous")),
        ])
    buried = [p for s in STACK_NAMES for p in state.stacks[s][:-1]]
    if buried:
        makers["not_on_top"] = lambda: (TargetRef("id", panel_id=rng.choice(buried)), base.stud)
    if ep.history:
        makers["already_installed"] = lambda: (TargetRef("id", panel_id=rng.choice(ep.history)["drywall_id"]), base.stud)
    empty = [s for s in STACK_NAMES if not state.stacks[s]]
    if empty:
        makers["stack_empty"] = lambda: (TargetRef("absolute", stack=rng.choice(empty)), base.stud)

    # placements that do not fit: past the wall's end, or over an installed panel
    top = base.expected["drywall_id"]
    misfits: dict[str, list] = {"past_wall_end": [], "overlap": []}
    for stud in site.studs:
        for placement in Placement:
            try:
                state.check_fits(top, stud.stud_id, placement)
            except Refusal as r:
                misfits[r.reason].append((stud.stud_id, placement.value))
    for reason, cases in misfits.items():
        if cases:
            makers[reason] = lambda cases=cases: cases

    makers["undetermined"] = lambda: rng.choice([(TargetRef("none"), base.stud), (base.target, StudRef("none"))])

    reason = rng.choice(sorted(makers))
    expected = {"drywall_id": None, "stud_id": None, "placement": None, "refusal": reason}
    if reason in ("past_wall_end", "overlap"):
        stud_id, placement = rng.choice(makers[reason]())
        return Meaning(choose_ref(rng, target_refs(ep, top), weights.target), StudRef("id", stud_id=stud_id)
                       if rng.random() < 0.6 else choose_ref(rng, stud_refs(ep, stud_id), weights.stud), placement, expected)
    target, stud = makers[reason]()
    return Meaning(target, stud, base.placement, expected)


# --- saying it -------------------------------------------------------------------------
def _ids(word: str, tag: str) -> Phrase:
    return tagged(word, tag)


def _size_numbers(ch: P.Chooser, ref: TargetRef) -> dict[str, Phrase]:
    a, b = ref.size
    if ref.kind == "width":
        return {"a": ch.number(a, "width")}
    if ref.kind == "length":
        return {"b": ch.number(b, "length")}
    return {"a": ch.number(a, "width"), "b": ch.number(b, "length")}


def _panel_anchor(ch: P.Chooser, anchor: str) -> Phrase:
    if anchor == "previous":
        return ch.say(P.PANEL_ANCHOR_PREVIOUS, plainnoun=ch.say(P.PANEL_NOUNS_PLAIN))
    return ch.say(P.PANEL_ANCHOR_ID, id=_ids(anchor, "Dw_loc2"), plainnoun=ch.say(P.PANEL_NOUNS_PLAIN))


def _relative_phrase(ch: P.Chooser, bank: list[str], noun_slot: str, noun: Phrase, ref, tag: str, anchor) -> Phrase:
    """ "the panel second to the right of 500310": a noun, a tagged direction with its count, an anchor.

    Templates that already say "to the" take a bare direction word when the count is one.
    ``anchor`` is a callable, drawn last, so the random draws keep the order the corpus was made with.
    """
    template = ch.template(bank)
    direction = P.direction_phrase(ch, ref.direction, ref.count, tag)
    if "to the {dir}" in template:
        if ref.count != 1:
            template = "the {%s} {dir} of {anchor}" % noun_slot
        else:
            direction = tagged(ref.direction, tag)
    return parse(template, **{noun_slot: noun}, dir=direction, anchor=anchor())


def _by_id_or_size(ch: P.Chooser, ref: TargetRef, noun: Phrase, by_id: list[str], by_size: list[str],
                   by_size_length_first: list[str], by_size_turned: list[str]) -> Phrase | None:
    """The target panel said by its id or its size (``ref.kind`` "id" or "size") from these banks, the size's
    bank by the order its numbers are said in and by whether the panel is turned; None for the other kinds."""
    if ref.kind == "id":
        return ch.say(by_id, noun=noun, id=_ids(ref.panel_id, "ID_wall"))
    if ref.kind == "size":
        bank = by_size_length_first if ref.length_first else by_size
        if ref.size[0] > ref.size[1]:
            bank = by_size_turned
        return ch.say(bank, noun=noun, **_size_numbers(ch, ref))
    return None


def target_phrase(ch: P.Chooser, ref: TargetRef) -> Phrase:
    """A noun phrase for the target panel: "the full-size drywall"."""
    noun = ch.say(P.PANEL_NOUNS)
    said = _by_id_or_size(ch, ref, noun, P.TARGET_BY_ID, P.TARGET_BY_SIZE, P.TARGET_BY_SIZE_LENGTH_FIRST,
                          P.TARGET_BY_SIZE_TURNED)
    if said is not None:
        return said
    if ref.kind == "width":
        return ch.say(P.TARGET_BY_WIDTH, noun=noun, **_size_numbers(ch, ref))
    if ref.kind == "length":
        return ch.say(P.TARGET_BY_LENGTH, noun=noun, **_size_numbers(ch, ref))
    if ref.kind == "standard":
        return ch.say(P.TARGET_STANDARD, noun=noun)
    if ref.kind == "same":
        return ch.say(P.TARGET_SAME_AS_PREVIOUS, noun=noun)
    if ref.kind == "absolute":
        return ch.say(P.TARGET_ABSOLUTE[ref.stack], noun=noun)
    if ref.kind == "relative":
        return _relative_phrase(ch, P.TARGET_RELATIVE, "noun", noun, ref, "Dw_loc1", lambda: _panel_anchor(ch, ref.anchor))
    if ref.kind == "none":
        return ch.say(P.TARGET_UNDETERMINED, noun=noun)
    raise ValueError(ref)


def target_sentence(ch: P.Chooser, ref: TargetRef) -> Phrase | None:
    """A sentence that says which panel on its own: "The width is 4 and the length is 8."; None if none fits."""
    noun = ch.say(P.PANEL_NOUNS)
    said = _by_id_or_size(ch, ref, noun, P.TARGET_ID_SENTENCE, P.TARGET_SIZE_SENTENCE,
                          P.TARGET_SIZE_SENTENCE_LENGTH_FIRST, P.TARGET_SIZE_SENTENCE_TURNED)
    if said is not None:
        return said
    if ref.kind == "standard":
        return ch.say(P.TARGET_STANDARD_SENTENCE, noun=noun)
    if ref.kind == "same":
        return ch.say(P.TARGET_SAME_SENTENCE, noun=noun)
    if ref.kind == "absolute":
        return ch.say(P.TARGET_ABSOLUTE_SENTENCE, where=ch.say(P.STACK_WHERE[ref.stack]))
    if ref.kind == "relative":
        return ch.say(P.TARGET_RELATIVE_SENTENCE, dir=P.direction_phrase(ch, ref.direction, ref.count, "Dw_loc1"),
                      anchor=_panel_anchor(ch, ref.anchor))
    return None


def _stud_anchor(ch: P.Chooser, anchor: str) -> Phrase:
    if anchor == "previous":
        return ch.say(P.STUD_ANCHOR_PREVIOUS)
    if anchor in ("leftmost", "rightmost"):
        return ch.say(P.STUD_ANCHOR_END[anchor])
    return ch.say(P.STUD_ANCHOR_ID, id=_ids(anchor, "St_loc2"))


def stud_phrase(ch: P.Chooser, ref: StudRef) -> Phrase:
    """A noun phrase for the destination stud: "the stud second to the left of 500109"."""
    stud = ch.say(P.STUD_NOUNS)
    if ref.kind == "id":
        return ch.say(P.STUD_BY_ID, id=_ids(ref.stud_id, "ID_stud"))
    if ref.kind == "absolute":
        return ch.say(P.STUD_ABSOLUTE[ref.name], stud=stud)
    if ref.kind == "from_end":
        return ch.say(P.STUD_FROM_END, stud=stud, ord=tagged(ch.ordinal(ref.nth), "St_loc1"), side=tagged(ref.side, "St_loc1"))
    if ref.kind == "ordinal":
        return ch.say(P.STUD_BARE_ORDINAL, stud=stud, ord=tagged(ch.ordinal(ref.nth), "St_loc1"))
    if ref.kind == "same":
        return ch.say(P.STUD_SAME, stud=stud)
    if ref.kind == "relative":
        return _relative_phrase(ch, P.STUD_RELATIVE, "stud", stud, ref, "St_loc1", lambda: _stud_anchor(ch, ref.anchor))
    if ref.kind == "none":
        return ch.say(P.STUD_UNDETERMINED)
    raise ValueError(ref)


def stud_sentence(ch: P.Chooser, ref: StudRef) -> Phrase:
    """A sentence that says which stud on its own: "The stud is laying third to the left from 500105."."""
    if ref.kind == "id":
        return ch.say(P.STUD_ID_SENTENCE, id=_ids(ref.stud_id, "ID_stud"))
    if ref.kind == "relative" and ch.chance(0.6):
        return ch.say(P.STUD_RELATIVE_SENTENCE, dir=P.direction_phrase(ch, ref.direction, ref.count, "St_loc1"),
                      anchor=_stud_anchor(ch, ref.anchor))
    return ch.say(P.STUD_SENTENCE, d=stud_phrase(ch, ref))


def placement_phrase(ch: P.Chooser, placement: str) -> Phrase:
    return ch.say(P.PLACEMENT[placement])


def placement_sentence(ch: P.Chooser, placement: str) -> Phrase:
    noun = ch.say(P.PANEL_NOUNS)
    if placement == "vertical_left":
        return ch.say(P.DEFAULT_PLACEMENT_SENTENCE, noun=noun)
    return ch.say(P.PLACEMENT_SENTENCE, noun=noun, p=placement_phrase(ch, placement))


def _words(text: str) -> Phrase:
    return parse(text)


def sentences_for(ch: P.Chooser, meaning: Meaning, n_sentences: int) -> list[Phrase]:
    """Arrange target, stud and placement into ``n_sentences`` sentences (the sentence plans)."""
    pick = lambda: _words(ch.template(P.PICK_VERBS))
    place = lambda: _words(ch.template(P.PLACE_VERBS))
    prep = lambda: _words(ch.template(P.PREPOSITIONS))
    opener = lambda: _words(ch.template(P.POLITE_OPENERS))
    closer = lambda: _words(ch.template(P.POLITE_CLOSERS))
    it = lambda: ch.say(P.IT, noun=ch.say(P.PANEL_NOUNS))
    greeting = lambda: _words(ch.template(P.GREETINGS))
    T = lambda: target_phrase(ch, meaning.target)
    D = lambda: stud_phrase(ch, meaning.stud)
    Pp = lambda: placement_phrase(ch, meaning.placement)
    generic_pick = lambda: opener() + pick() + parse("the {noun}", noun=ch.say(P.PANEL_NOUNS))
    t_sentence = target_sentence(ch, meaning.target)

    def end(phrase: Phrase, mark: str = ".") -> Phrase:
        return phrase + [Token(mark, None, None)]

    def one_sentence() -> list[Phrase]:
        form = ch.rng.randrange(6)
        if form == 0:
            return [end(opener() + pick() + T() + plain("and") + place() + it() + prep() + D() + Pp() + closer())]
        if form == 1:
            return [end(opener() + place() + T() + prep() + D() + Pp() + closer())]
        if form == 2:
            return [end(opener() + place() + T() + Pp() + prep() + D() + closer())]
        if form == 3:
            return [end(plain("can you") + place() + T() + prep() + D() + Pp(), "?")]
        if form == 4 and ch.novel:
            return [end(T() + plain("goes") + prep() + D() + Pp())]
        return [end(plain("I need") + T() + prep() + D() + Pp() + closer())]

    def two_sentences() -> list[Phrase]:
        form = ch.rng.randrange(5)
        if form == 0:
            return [end(opener() + pick() + T() + closer()), end(place() + it() + prep() + D() + Pp())]
        if form == 1:
            return [end(opener() + pick() + T() + plain("and") + place() + it() + prep() + D()),
                    end(placement_sentence(ch, meaning.placement)[:-1])]
        if form == 2 and t_sentence is not None:
            return [end(t_sentence[:-1]), end(opener() + place() + it() + prep() + D() + Pp() + closer())]
        if form == 3:
            return [end(opener() + place() + T() + Pp()), stud_sentence(ch, meaning.stud)]
        return [end(opener() + pick() + T() + closer()), end(place() + it() + Pp() + prep() + D())]

    def three_sentences() -> list[Phrase]:
        form = ch.rng.randrange(4)
        if form == 0 and t_sentence is not None:
            return [end(generic_pick()), t_sentence, end(place() + it() + prep() + D() + Pp())]
        if form == 1:
            return [end(opener() + pick() + T()), end(place() + it() + prep() + D()),
                    placement_sentence(ch, meaning.placement)]
        if form == 2:
            return [greeting(), end(opener() + pick() + T()), end(place() + it() + prep() + D() + Pp())]
        return [end(opener() + place() + T() + Pp()), stud_sentence(ch, meaning.stud), greeting()]

    def four_sentences() -> list[Phrase]:
        form = ch.rng.randrange(3)
        if form == 0 and t_sentence is not None:
            return [greeting(), end(generic_pick()), t_sentence, end(place() + it() + prep() + D() + Pp())]
        if form == 1 and t_sentence is not None:
            return [end(generic_pick()), t_sentence,
                    end(place() + it() + prep() + parse("the {stud}", stud=ch.say(P.STUD_NOUNS)) + Pp()),
                    stud_sentence(ch, meaning.stud)]
        return [greeting(), end(opener() + pick() + T()), end(place() + it() + prep() + D()),
                placement_sentence(ch, meaning.placement)]

    return {1: one_sentence, 2: two_sentences, 3: three_sentences, 4: four_sentences}[n_sentences]()


def join_tokens(sentences: Iterable[Phrase], keep_punctuation: bool, cased: Callable[[str, bool], str],
                word_of: Callable[[str], str] = str,
                attach: Callable[[str, str], bool] | None = None) -> tuple[str, list[str], list[str], list[str]]:
    """Text, words, tags and co-reference tags of tokenised sentences: each word written as ``cased(word, whether
    it begins its sentence)`` and read as ``word_of`` that; punctuation glued to the word before it when
    ``keep_punctuation``, dropped otherwise; a word written without a space after the text before it where
    ``attach(text, word)`` says so (a script written without spaces)."""
    words: list[str] = []
    tags: list[str] = []
    coref: list[str] = []
    pieces: list[str] = []
    for sentence in sentences:
        first = True
        for tok in sentence:
            if not tok.is_word:
                if keep_punctuation and pieces:
                    pieces[-1] += tok.word
                continue
            w = cased(tok.word, first)
            first = False
            words.append(word_of(w))
            tags.append(tok.tag)
            coref.append(tok.coref)
            if attach is not None and pieces and attach(pieces[-1], w):
                pieces[-1] += w
            else:
                pieces.append(w)
    return " ".join(pieces), words, tags, coref


def render(ch: P.Chooser, sentences: list[Phrase]) -> tuple[str, list[str], list[str], list[str]]:
    """Text, words, tags and co-reference tags, typed style or speech-recogniser style."""
    asr = ch.chance(0.4)  # lowercase, no punctuation

    def cased(w: str, first: bool) -> str:
        if asr:
            return w.lower()
        w = w[0].upper() + w[1:] if first else w
        return "I" if w == "i" else w

    return join_tokens(sentences, not asr, cased)


# --- episodes and splits ---------------------------------------------------------------
def missing_meanings(rows: list[dict]) -> set[str]:
    """Which of the meanings every split must contain are absent from ``rows`` (empty: all present)."""
    def values(get) -> set:
        return {v for r in rows if (v := get(r)) is not None}

    def anchor(ref: dict) -> str | None:
        a = ref.get("anchor") if ref["kind"] in ("relative", "same") else None
        return "id" if a and a[0].isdigit() else a

    wanted = {
        "target": (values(lambda r: r["meaning"]["target"]["kind"]), set(TARGET_WEIGHTS)),
        "stud": (values(lambda r: r["meaning"]["stud"]["kind"]), {"id", "absolute", "from_end", "ordinal", "relative", "same"}),
        "target anchor": (values(lambda r: anchor(r["meaning"]["target"])), {"id", "previous"}),
        "stud anchor": (values(lambda r: anchor(r["meaning"]["stud"])), {"id", "leftmost", "rightmost", "previous"}),
        "stud name": (values(lambda r: r["meaning"]["stud"].get("name")), {"leftmost", "middle"}),
        "stack": (values(lambda r: r["meaning"]["target"].get("stack")), set(STACK_NAMES)),
        "placement": (values(lambda r: r["meaning"]["placement"]), {p.value for p in Placement}),
        "tag": ({t for r in rows for t in r["coref_tags"] + r["tags"]}, set(COREF_TAGS)),
        "outcome": (values(lambda r: "refusal" if r["expected"]["refusal"] else "command"), {"refusal", "command"}),
    }
    return {f"{facet} {v}" for facet, (have, want) in wanted.items() for v in want - have}


def generate_split(split: str, n: int, seed: int = SEED, site: Site | None = None) -> list[dict]:
    """``n`` instructions for one split, from episodes on fresh sites.

    A small split can miss a rare meaning by chance; the split is then drawn again
    from the next sub-seed, so that every split contains every meaning (deterministic).
    """
    site = site or default_site()
    for attempt in range(100):
        rng = random.Random(f"{seed}-{split}-{attempt}")
        rows = _generate_split_once(split, n, rng, site)
        if not missing_meanings(rows):
            return rows
    raise RuntimeError(f"{split}: no draw contained every meaning; missing {sorted(missing_meanings(rows))}")


#: What ``episode_rows`` asks for each step: ``say(episode, meaning, row number, episode number, step)``, the
#: step's corpus row, or None when the step is not said (the episode then goes on as if it had not been asked).
SayStep = Callable[["Episode", Meaning, int, int, int], "dict | None"]


def episode_rows(rng: random.Random, site: Site, n: int, draw_length: Callable[[], int], refusal_rate: float,
                 weights: MeaningWeights, say: SayStep) -> list[dict]:
    """``n`` corpus rows from episodes on fresh sites, as both corpora draw them.

    Each episode is at most ``draw_length()`` steps long; each step means a command, or (with probability
    ``refusal_rate``) an instruction to refuse (``command_meaning``, ``refusal_meaning`` with ``weights``), and an
    episode ends early when no meaning is feasible. ``say`` turns a step into its row; the row's expected command,
    if any, is accepted into the episode.
    """
    rows: list[dict] = []
    episode_no = 0
    while len(rows) < n:
        ep = Episode(site.fresh())
        length = draw_length()
        for step in range(length):
            if len(rows) >= n:
                break
            refuse = rng.random() < refusal_rate
            meaning = (refusal_meaning if refuse else command_meaning)(rng, ep, weights)
            if meaning is None:
                break
            row = say(ep, meaning, len(rows), episode_no, step)
            if row is None:
                continue
            rows.append(row)
            ep.accept(row["expected"])
        episode_no += 1
    return rows


def _generate_split_once(split: str, n: int, rng: random.Random, site: Site) -> list[dict]:
    ch = P.Chooser(rng, novel=(split == "novel"))
    quota = SENTENCE_QUOTAS[split]
    counts = [k for k, v in quota.items() for _ in range(v)]
    counts += [2] * (n - len(counts))
    rng.shuffle(counts)

    def say(ep: Episode, meaning: Meaning, row_no: int, episode_no: int, step: int) -> dict:
        said = render(ch, sentences_for(ch, meaning, counts[row_no]))
        return corpus_row(f"{split}-{row_no:04d}", said, counts[row_no], f"{split}-ep{episode_no:04d}", step, ep,
                          meaning)

    return episode_rows(rng, site, n, lambda: rng.choice([1, 2, 2, 3, 3, 4, 5, 6]), REFUSAL_RATE, PAPER_WEIGHTS, say)


def generate_corpus(seed: int = SEED, sizes: dict[str, int] | None = None) -> dict[str, list[dict]]:
    """All four splits: train, validation, test (the paper's 1,268/158/158) and novel."""
    sizes = sizes or SPLIT_SIZES
    return {split: generate_split(split, n, seed) for split, n in sizes.items()}


def write_corpus(out_dir: Path | str, seed: int = SEED) -> dict[str, Path]:
    """Write ``{split}.jsonl`` files; the same seed always gives the same bytes."""
    from drywall_lab.corpus.io import write_jsonl

    return {split: write_jsonl(rows, Path(out_dir) / f"{split}.jsonl") for split, rows in generate_corpus(seed).items()}
