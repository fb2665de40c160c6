"""Deciding safely: IM-aware decoding, and a question instead of a guess (issue 12; spec section 5, ``unclear``).

The paper's pipeline acts on the single best tag sequence. The paper's future work asks to
"integrate the NLU and IM modules and use the building component information as an input"; this
module does that. The tagger gives its k most probable tag sequences with their probabilities and
each word's tag probabilities (``Tagger.predict_confidence``); every reading goes through the
information-mapping rules against the site and the action history, and then:

1. **One command, and sure of it**: the best reading gives a command, no other reading within the
   margin gives another command, and the readings that give it carry at least ``act`` of the probability.
   The robot acts. A check of the best reading against its own words comes first; gold tags never meet it (tested
   on every generated split and on ``data/field``'s hand-written tags):

   - **Two panels or two studs** (``two_meanings``): the IM takes the first target rule that applies ("the 2x8"
     before "a full one"), but when another rule that applies on its own names another panel (or stud), the
     words allow two commands: the robot asks, naming both.

   A rival within the margin whose own words name two panels or studs, one of them the best reading's command
   ("Unit two, a full sheet on 500103" with "two" read as a width), is torn between that command and another, which
   is no reading against the command (``two_meanings``); nor, when the best reading's placement agrees with the
   words, is one whose placement goes against a word that says how the panel goes (a row although "stands" is said;
   ``placement_contradicted``).
2. **A second reading would be safer**: the best reading is ``undetermined`` (a missed tag), and
   readings within the margin give exactly one command, with at least ``recover`` of the probability:
   the robot takes that reading (the most probable one that is determined and feasible on the site), provided it
   passes the check of step 1 (otherwise it asks, as step 1 would).
3. **Otherwise, ask** (refusal reason ``unclear``): two commands within the margin, or a command that
   is not sure enough. The message says what was understood and asks one question ("Did you mean
   panel 500321 on stud 500104 on its centre line, or on its left line?"). History and site untouched.
4. A reading that the site refuses (overlap, buried panel, ...) is refused with the IM's own message
   unless a feasible reading within the margin is likely enough to be worth a question. When the refused reading's
   placement goes against a word that says how the panel goes (a row although "stands" is said;
   ``placement_contradicted``) and the one command within the margin comes from a reading that differs from it only
   in the placement tags and agrees with that word, the robot takes that reading as in step 2 (same ``recover``
   probability, same word check). So too when the best reading is a command whose placement goes against such a word
   ("keep the top clear , the 4x6 stands on 500102" with "top" read as the top row): rather than ask, the robot takes
   the reading that stands the panel up, if it is the only command the readings that agree with the words give.

5. **Nothing rests on an unanswered question** (``pending``, in an episode): after the robot asked about an
   instruction (``unclear``) and before it next acts, a command that would be another one had the robot carried
   out a command it asked about (the same reading through the rules with that command in the history: "the
   same size as last time", "the top panel of the middle stack", a stud taken) is asked about too, naming both:
   the worker may well have meant the instruction the robot did not carry out. The command asked about is carried
   out in thought where the robot asked, before the commands acted on since (``had_it_been_done``: "the previous
   stud" is still the last one the robot used). One that would make this instruction impossible is no reason to
   ask when another command asked about leaves it as it is: the worker's words fit that one.

   - ``half="said"``: an instruction refused as ``undetermined`` although it said something of the part the rules
     could not resolve ("a four by eight three studs to the left of that one", with "that one" missed) is half
     understood: the worker meant a command, and the robot's "which stud?" was never answered. It stays open like
     a question, with the commands it may have meant (``completions``: the panel it names on every stud where it
     fits, or every panel on top of a stack for the stud it names), and a command that any of them would change
     is asked about. A part counts as said when the best reading or a rival within the margin tags a word for it
     ("two right of the one you just used", read as a stack's position by the best reading and as the stud's by a
     rival, said something of the stud). Only a changed *command* counts here (a completion on a stud the command would overlap says
     nothing). An instruction that said nothing of the missing part ("put any sheet on 500104"), and a site
     refusal (overlap, buried panel), are definite answers: "previous" is then the last accepted command, as spec
     section 3 says. With gold tags the layer still gives every intended outcome on every generated split
     (``half="all"``, counting every ``undetermined`` refusal, does not: it is measured, never the default).
   - ``through``: acting on an instruction the question does not touch does not answer it: the question stays
     open until the end of the episode (otherwise the next action closes it).

6. Optionally, **a second opinion** (``second_opinion``; ``decide_episode(..., check=...)``): a second,
   differently built tagger whose best reading gives another command turns an action into a question.
   Off by default (``benchmarks/second_opinion.py`` measures it).

``DecisionSettings`` holds the thresholds; ``benchmarks/decision.py`` chooses them on the generated
field-corpus validation and novel splits (never on the hand-written field sets) and records the
risk-coverage curve. The rule trace (``Interpretation.trace``) ends with a ``decision`` stage naming the
readings considered and why one was taken.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Callable, Iterable, Mapping, Sequence

import numpy as np

from drywall_lab.corpus.tags import DESTINATION_TAGS, PLACEMENT_TAGS, TARGET_TAGS
from drywall_lab.errors import Refusal
from drywall_lab.im import ActionHistory, Interpretation, RobotCommand, Trace
from drywall_lab.im import interpret as im_interpret
from drywall_lab.im import words as W
from drywall_lab.im.context import MappingContext
from drywall_lab.im.placement import resolve_placement
from drywall_lab.im.stud import STUD_RULES, resolve_stud
from drywall_lab.im.target import TARGET_RULES, resolve_target
from drywall_lab.im.trace import TaggedInstruction
from drywall_lab.site import Placement


#: Which ``undetermined`` refusals leave an instruction open (step 5): none; those whose reading says something
#: about the part it could not resolve ("three studs to the left of that one"); every one.
HALF_UNDERSTOOD = ("off", "said", "all")


@dataclass(frozen=True)
class DecisionSettings:
    """The decision layer's thresholds (chosen by ``benchmarks/decision.py``; see ``DEFAULT_SETTINGS``).

    ``k``: tag sequences read; ``margin``: natural-log probability below the best within which a reading
    counts as a rival; ``act``: the probability the readings of a command must carry to act on it;
    ``recover``: the same when the best reading was undetermined; ``question``: the probability of a feasible reading that
    turns a site refusal into a question; ``pending``: in an episode, after a step not understood, ask before
    acting on a command that step would change (module docstring, step 5); ``half``: which ``undetermined``
    refusals count as not understood (``HALF_UNDERSTOOD``); ``through``: whether a question stays open after the
    robot acts on something else; ``word_checks``: the readings checked against their own words (steps 1 and 4).
    """

    k: int = 8
    margin: float = 3.0
    act: float = 0.5
    recover: float = 0.3
    question: float = 0.2
    pending: bool = True
    half: str = "off"
    through: bool = False
    word_checks: bool = True

    def __post_init__(self) -> None:
        if self.k < 1:
            raise ValueError(f"k must be at least 1, got {self.k}")
        for name in ("act", "recover", "question"):
            value = getattr(self, name)
            if not 0 <= value <= 1:
                raise ValueError(f"{name} must be between 0 and 1, got {value}")
        if self.half not in HALF_UNDERSTOOD:
            raise ValueError(f"half must be one of {sorted(HALF_UNDERSTOOD)}, got {self.half!r}")
        if self.margin < 0:
            raise ValueError(f"margin must be at least 0, got {self.margin}")


#: Acting on the single best reading, as the paper does: the layer switched off.
BEST_PATH = DecisionSettings(k=1, margin=0.0, act=0.0, recover=1.0, question=1.0, pending=False, word_checks=False)
#: The thresholds ``benchmarks/decision.py`` chose on the field corpus's validation and novel splits for the shipped
#: recipe (an ensemble of two seed models), by the mean cost over the three ensembles of two of the seed models 0-2
#: (``benchmarks/results/decision.md``; a test checks that they are the recorded choice).
DEFAULT_SETTINGS = DecisionSettings(k=8, margin=1.5, act=0.0, recover=0.05, question=0.2, pending=True, half="said",
                                    through=True)


# --- readings --------------------------------------------------------------------------------------------
Outcome = tuple  # ("command", drywall_id, stud_id, placement) or ("refusal", reason)


def outcome_of(interpretation: Interpretation) -> Outcome:
    if interpretation.command is not None:
        c = interpretation.command
        return ("command", c.drywall_id, c.stud_id, c.placement.value)
    return ("refusal", interpretation.refusal.reason)


@dataclass
class Reading:
    """One tag sequence, its probability, and what the rules make of it."""

    tags: list[str]
    logprob: float
    interpretation: Interpretation

    @property
    def outcome(self) -> Outcome:
        return outcome_of(self.interpretation)

    @property
    def read_tags(self) -> list[str]:
        """The tags as the rules read them: a place in a stack, or a word a change of mind took back, is ``O``
        (``TaggedInstruction``); the checks of a reading against its own words look at these."""
        return self.interpretation.tags

    @property
    def probability(self) -> float:
        return math.exp(self.logprob)


@dataclass
class Decision:
    """What the robot does with one instruction: act on ``interpretation.command``, or refuse/ask.

    ``interpretation`` is the chosen reading's (its trace ends with the decision); ``confidence`` the
    probability of the readings that give the chosen outcome; ``readings`` every reading considered;
    ``action``: ``act``, ``recover`` (acted on a second reading), ``ask`` or ``refuse``; ``options``: for a
    question, the commands it asks about (``Outcome`` tuples, the likelier first), so that an answer
    ("yes", "the second") can pick one (``drywall_lab.dialogue``).
    """

    words: list[str]
    tags: list[str]
    interpretation: Interpretation
    confidence: float
    action: str
    readings: list[Reading] = field(default_factory=list)
    options: list[Outcome] = field(default_factory=list)

    @property
    def command(self):
        return self.interpretation.command

    @property
    def refusal(self) -> Refusal | None:
        return self.interpretation.refusal

    @property
    def acted(self) -> bool:
        return self.interpretation.command is not None


# --- telling readings apart, in words ------------------------------------------------------------------------
_PLACEMENT_TEXT = {
    "vertical_left": "upright with its edge on the stud's left line",
    "vertical_middle": "upright with its edge on the stud's centre line",
    "horizontal_top": "lying in the top row",
    "horizontal_bottom": "lying in the bottom row",
}


def _describe(outcome: Outcome) -> str:
    _, panel, stud, placement = outcome
    return f"panel {panel} on stud {stud}, {_PLACEMENT_TEXT[placement]}"


def question_between(first: Outcome, second: Outcome) -> str:
    """One question that tells two commands apart, naming what they share once.

    >>> question_between(("command", "500321", "500104", "vertical_middle"), ("command", "500321", "500104", "vertical_left"))
    "Did you mean panel 500321 on stud 500104 upright with its edge on the stud's centre line, or upright with its edge on the stud's left line?"
    """
    _, p1, s1, l1 = first
    _, p2, s2, l2 = second
    if p1 == p2 and s1 == s2:
        return f"Did you mean panel {p1} on stud {s1} {_PLACEMENT_TEXT[l1]}, or {_PLACEMENT_TEXT[l2]}?"
    if p1 == p2 and l1 == l2:
        return f"Did you mean panel {p1} {_PLACEMENT_TEXT[l1]} on stud {s1}, or on stud {s2}?"
    if s1 == s2 and l1 == l2:
        return f"Did you mean panel {p1} or panel {p2}, on stud {s1} {_PLACEMENT_TEXT[l1]}?"
    return f"Did you mean {_describe(first)}, or {_describe(second)}?"


def _confirm(outcome: Outcome) -> str:
    return f"I understood {_describe(outcome)}. I am not sure I understood. Is that right?"


def _mass(readings: Iterable[Reading]) -> dict[Outcome, float]:
    mass: dict[Outcome, float] = {}
    for r in readings:
        mass[r.outcome] = mass.get(r.outcome, 0.0) + r.probability
    return mass


def _feasible(history: ActionHistory, command: Outcome) -> bool:
    """Whether the site, as ``history`` leaves it, lets the robot carry out ``command`` (pick, then fit)."""
    _, panel, stud, placement = command
    try:
        history.state.check_pickable(panel)
        history.state.check_fits(panel, stud, placement)
    except Refusal:
        return False
    return True


def _rule_values(rules, ti: TaggedInstruction, ctx: MappingContext) -> dict[str, str]:
    """Every rule of ``rules`` that applies to the reading, on its own, and the panel or stud it gives."""
    out = {}
    for name, tags, rule in rules:
        if not ti.has(*tags):
            continue  # a rule reads only its own tags
        try:
            found = rule(ti, ctx)
        except Refusal:
            continue
        if found is not None:
            out[name] = found.value
    return out


def two_meanings(outcome: Outcome, words: Sequence[str], tags: Sequence[str],
                 history: ActionHistory) -> tuple[str, str, list[Outcome]] | None:
    """A reading that names two panels or two studs ("the 2 x 8 ... a full one" with both size words tagged; "the
    middle pile, same size" with "same" tagged): the IM takes the first rule that applies, but the words say
    another thing too. Returns why, the question and the commands meant (the reading's own first, then the other
    where the site allows it); None when every rule that applies agrees. Gold tags never name two (tested on every
    split)."""
    present = set(tags)
    ti = ctx = None
    for what, rules, index in (("panels", TARGET_RULES, 1), ("studs", STUD_RULES, 2)):
        if sum(1 for _, read, _ in rules if present.intersection(read)) < 2:
            continue  # one rule at most can apply: nothing to disagree with
        if ti is None:
            ti = TaggedInstruction(list(words), list(tags))
            ctx = MappingContext(history.site, history.state, history.last)
        found = _rule_values(rules, ti, ctx)
        others = [v for v in dict.fromkeys(found.values()) if v != outcome[index]]
        if not others:
            continue
        other = list(outcome)
        other[index] = others[0]
        options = [outcome] + ([tuple(other)] if _feasible(history, tuple(other)) else [])
        question = question_between(*options) if len(options) > 1 else _confirm(outcome)
        rules_text = " and ".join(f"{name} ({value})" for name, value in found.items())
        return f"the words name two {what}: {rules_text}", question, options
    return None


def placement_contradicted(words: Sequence[str], tags: Sequence[str]) -> bool:
    """Whether a reading's placement goes against a word that says how the panel goes: a row although a word says it
    stands ("keep the top clear , the 4x6 stands on 500102" with "top" read as the top row)."""
    return bool({"Hr_top", "Hr_btm"}.intersection(tags)) and bool(W.upright_words(words, tags))


def _differs_in_placement_only(tags: Sequence[str], other: Sequence[str]) -> bool:
    return all(a == b or {a, b} <= set(PLACEMENT_TAGS) | {"O"} for a, b in zip(tags, other))


# --- the decision ------------------------------------------------------------------------------------------
def decide(words: Sequence[str], kbest: Sequence[tuple[Sequence[str], float]], marginals: np.ndarray,
           labels: Sequence[str], history: ActionHistory | None = None,
           settings: DecisionSettings = DEFAULT_SETTINGS, interpreter: Callable = im_interpret) -> Decision:
    """Choose what to do with one instruction from the tagger's readings (module docstring, steps 1-4).

    ``kbest``: tag sequences with natural-log probabilities, best first (``Tagger.predict_kbest``);
    ``marginals``: (n_words, n_labels) tag probabilities in ``labels`` order (not read by the steps as they stand;
    kept so that a ``predict_confidence`` result is passed as it comes). Nothing is recorded.
    ``interpreter(words, tags, history)`` is the IM's ``interpret`` (a cached one when many settings
    are compared on the same readings).
    """
    interpret = interpreter
    words = list(words)
    history = history if history is not None else ActionHistory()
    readings = [Reading(list(tags), float(lp), interpret(words, tags, history))
                for tags, lp in list(kbest)[: settings.k]]
    if not readings:
        raise ValueError("decide needs at least one tag sequence")
    best = readings[0]
    within = [best] + [r for r in readings[1:] if r.logprob >= best.logprob - settings.margin]
    mass = _mass(readings)
    rival_commands = list(dict.fromkeys(r.outcome for r in within if r.outcome[0] == "command"))

    def finish(reading: Reading, action: str, note: str, refusal: Refusal | None = None,
               options: Sequence[Outcome] = ()) -> Decision:
        result = Interpretation(list(words), list(reading.tags), Trace(list(reading.interpretation.trace.steps)),
                                reading.interpretation.command if refusal is None else None,
                                reading.interpretation.refusal if refusal is None else refusal)
        alternatives = "; ".join(
            f"{'command ' + _describe(r.outcome) if r.outcome[0] == 'command' else 'refused (' + r.outcome[1] + ')'}"
            f" p={r.probability:.3f}" for r in readings[:4])
        result.trace.add("decision", f"D {action}", True, conclusion=f"{note} [readings: {alternatives}]")
        return Decision(words, list(reading.tags), result, mass.get(reading.outcome, 0.0), action, readings,
                        list(options))

    contradicted_of: dict[int, bool] = {}

    def contradicted(reading: Reading) -> bool:
        """``placement_contradicted`` for a reading, worked out once per decision."""
        if id(reading) not in contradicted_of:
            contradicted_of[id(reading)] = placement_contradicted(words, reading.read_tags)
        return contradicted_of[id(reading)]

    def torn_towards(rival: Reading, outcome: Outcome) -> bool:
        """Whether a rival's own words name two panels or studs, one of them giving ``outcome`` ("Unit two, a full
        sheet on 500103" read with "two" as a width and "full" as the size word): it would ask between them, so it is no
        reading against ``outcome``."""
        if not settings.word_checks:
            return False
        torn = two_meanings(rival.outcome, words, rival.read_tags, history)
        return torn is not None and outcome in torn[2]

    def word_checks(reading: Reading) -> tuple[str, str, list[Outcome]] | None:
        """The check of a reading against its own words (step 1), or None when it passes it or it is off."""
        if not settings.word_checks:
            return None
        return two_meanings(reading.outcome, words, reading.read_tags, history)

    def placed_instead() -> Reading | None:
        """Step 4's reading for a best one whose placement goes against its words: the one command within the margin
        of the readings that differ from the best only in the placement tags and agree with the words, when no other
        reading that agrees with them gives another command; None otherwise."""
        if not settings.word_checks or not contradicted(best):
            return None
        agree = [r for r in within[1:] if r.outcome[0] == "command" and not contradicted(r)]
        placed = [r for r in agree if _differs_in_placement_only(best.read_tags, r.read_tags)]
        if not placed or len({r.outcome for r in agree}) != 1 or mass[placed[0].outcome] < settings.recover:
            return None
        return placed[0] if word_checks(placed[0]) is None else None

    if best.outcome[0] == "command":
        placed = placed_instead()
        if placed is not None:
            return finish(placed, "recover",
                          f"the best reading's placement goes against the words; the reading that differs only in the "
                          f"placement and says it as the words do gives one command, p={mass[placed.outcome]:.3f}")
        sound = settings.word_checks and not contradicted(best)
        others = list(dict.fromkeys(r.outcome for r in within[1:] if r.outcome[0] == "command"
                                    and r.outcome != best.outcome and not torn_towards(r, best.outcome)
                                    and not (sound and contradicted(r))))
        if others:
            return finish(best, "ask", "two readings give different commands",
                          Refusal("unclear", question_between(best.outcome, others[0])), [best.outcome, others[0]])
        checked = word_checks(best)
        if checked is not None:
            why, question, options = checked
            return finish(best, "ask", why, Refusal("unclear", question), options)
        if mass[best.outcome] < settings.act:
            why = f"the command's readings carry p={mass[best.outcome]:.3f} < {settings.act}"
            return finish(best, "ask", why, Refusal("unclear", _confirm(best.outcome)), [best.outcome])
        return finish(best, "act", f"one command, p={mass[best.outcome]:.3f}")

    reason = best.outcome[1]
    if rival_commands:
        first = max(rival_commands, key=lambda o: mass[o])
        chosen = next(r for r in within if r.outcome == first)
        if len(rival_commands) > 1:
            second = next(o for o in rival_commands if o != first)
            return finish(chosen, "ask", "readings within the margin give different commands",
                          Refusal("unclear", question_between(first, second)), [first, second])
        if reason == "undetermined" and mass[first] >= settings.recover:
            checked = word_checks(chosen)  # the reading taken must pass the checks the best one would have had to
            if checked is not None:
                why, question, options = checked
                return finish(chosen, "ask", f"the best reading is undetermined, and the next one fails a check: {why}",
                              Refusal("unclear", question), options)
            return finish(chosen, "recover",
                          f"the best reading is undetermined; the next reading within the margin gives one command, "
                          f"p={mass[first]:.3f}")
        placed = placed_instead() if reason != "undetermined" else None
        if placed is not None:
            return finish(placed, "recover",
                          f"refused ({reason}), but its placement goes against the words; the reading that differs only "
                          f"in the placement and says it as the words do gives one command, p={mass[placed.outcome]:.3f}")
        if mass[first] >= settings.question:
            message = best.interpretation.refusal.message if reason != "undetermined" else None
            question = _confirm(first)
            text = f"{message} Or did you mean {_describe(first)}?" if message else question
            return finish(chosen, "ask", f"refused ({reason}), but a feasible reading has p={mass[first]:.3f}",
                          Refusal("unclear", text), [first])
    return finish(best, "refuse", f"refused ({reason})")


def decide_tags(words: Sequence[str], tags: Sequence[str], labels: Sequence[str],
                history: ActionHistory | None = None) -> Decision:
    """The decision for tags known for certain (gold tags): one reading with probability 1."""
    marginals = np.zeros((len(tags), len(labels)))
    index = {label: i for i, label in enumerate(labels)}
    for i, tag in enumerate(tags):
        marginals[i, index.get(tag, index["O"])] = 1.0
    return decide(words, [(list(tags), 0.0)], marginals, labels, history)


def second_opinion(decision: Decision, check: Interpretation, any_difference: bool = False) -> Decision:
    """A check on confident mistakes: ``decision`` stands unless the robot would act and a second, differently
    built tagger's best reading (``check``: its tags through the IM rules against the same history) gives
    another command (with ``any_difference``, any other outcome, a refusal included). Then the robot asks,
    naming both readings, and the trace says why. ``benchmarks/second_opinion.py`` measures the rule."""
    own, other = outcome_of(decision.interpretation), outcome_of(check)
    if not decision.acted or other == own or (other[0] != "command" and not any_difference):
        return decision
    if other[0] == "command":
        question, options, seen = question_between(own, other), [own, other], f"command {_describe(other)}"
    else:
        question, options, seen = _confirm(own), [own], f"refused ({other[1]})"
    return ask_instead(decision, question, options, "D second opinion",
                       f"a second tagger's reading gives {seen} (tags: {' '.join(check.tags)}): ask")


def ask_instead(decision: Decision, question: str, options: Sequence[Outcome], rule: str, why: str) -> Decision:
    """``decision`` turned into a question (refusal ``unclear``) about ``options``; the trace ends with ``rule``
    and why. Nothing is recorded."""
    chosen = decision.interpretation
    result = Interpretation(list(chosen.words), list(chosen.tags), Trace(list(chosen.trace.steps)), None,
                            Refusal("unclear", question))
    result.trace.add("decision", rule, True, conclusion=why)
    return Decision(decision.words, decision.tags, result, decision.confidence, "ask", decision.readings,
                    list(options))


# --- one instruction, whole episodes ----------------------------------------------------------------------
def decide_instruction(words: Sequence[str], tagger, history: ActionHistory,
                       settings: DecisionSettings = DEFAULT_SETTINGS) -> Decision:
    """The decision for one instruction's words: the tagger's readings (``predict_confidence``), then ``decide``."""
    confidence = tagger.predict_confidence([list(words)], k=settings.k)[0]
    return decide(list(words), confidence.kbest, confidence.marginals, tagger.labels, history, settings)


def interpret_instruction(words: Sequence[str], tagger, history: ActionHistory,
                          settings: DecisionSettings | None = None) -> Interpretation:
    """One instruction as ``run`` interprets it against ``history``: a tagger with confidence through the
    decision layer (``settings``, the defaults when None), any other tagger's best tags through the IM rules.
    Nothing is recorded."""
    if hasattr(tagger, "predict_confidence"):
        return decide_instruction(words, tagger, history, settings or DEFAULT_SETTINGS).interpretation
    return im_interpret(list(words), tagger.predict([list(words)])[0], history)


# --- whole episodes --------------------------------------------------------------------------------------
#: The refusal that leaves a question open: the robot asked, and the instruction may still stand.
NOT_UNDERSTOOD = frozenset({"unclear"})


def said_tags(decision: Decision, margin: float = 0.0) -> set[str]:
    """The tags that the decision's reading, or any reading within ``margin`` of the best, gives some word: what
    the instruction may have said, as far as the layer read it ("two right of the one you just used" read as a
    stack's position by the best reading and as the stud's by a rival)."""
    readings = list(decision.readings)
    best = readings[0].logprob if readings else 0.0
    said = set(decision.tags)
    for reading in readings:
        if reading.logprob >= best - margin:
            said.update(reading.tags)
    return said


def completions(decision: Decision, history: ActionHistory, half: str = "said", margin: float = 0.0) -> list[Outcome]:
    """The commands an instruction refused as ``undetermined`` may have meant, feasible on the site as ``history``
    leaves it: the panel and the stud its reading determines, and any panel on top of a stack or any stud for the
    part it does not; and the command of every reading within ``margin`` that gives one (a rival may have read the
    part the best reading got wrong). Empty when ``half`` (``HALF_UNDERSTOOD``) does not count this refusal; with ``"said"``, a part
    counts as said when a reading within ``margin`` of the best tags a word for it (``said_tags``)."""
    if half == "off" or decision.acted or decision.refusal.reason != "undetermined":
        return []
    said = said_tags(decision, margin)
    ti = TaggedInstruction(decision.words, decision.tags)
    ctx = MappingContext(history.site, history.state, history.last)
    try:
        panels = [resolve_target(ti, ctx)]
    except Refusal:
        if half == "said" and not said & set(TARGET_TAGS):
            return []  # nothing said about the panel ("any sheet"): nothing to build on
        panels = [p for p in history.state.tops.values() if p is not None]
    try:
        studs = [resolve_stud(ti, ctx)]
    except Refusal:
        if half == "said" and not said & set(DESTINATION_TAGS):
            return []  # nothing said about the stud ("over there")
        studs = list(history.site.stud_ids)
    try:
        placements = [resolve_placement(ti)]
    except Refusal:
        placements = list(Placement)  # two placements said: either
    meant = [("command", panel, stud, placement.value)
             for panel, stud, placement in itertools.product(panels, studs, placements)]
    best = decision.readings[0].logprob if decision.readings else 0.0
    meant += [r.outcome for r in decision.readings  # what a rival read it as ("left/Dw_loc1 500103/ID_stud")
              if r.outcome[0] == "command" and r.logprob >= best - margin and r.outcome not in meant]
    return [command for command in meant if _feasible(history, command)]


def had_it_been_done(history: ActionHistory, asked_at: int, option: Outcome) -> ActionHistory | None:
    """The history as it would stand had the robot carried out ``option`` when it asked (after the first ``asked_at``
    commands of ``history``), the commands acted on since then following it: the worker who meant it builds on
    that order ("the previous stud" is still the last one the robot used). None when it no longer fits: the
    site does not allow it before the commands since (a panel taken since, an overlap)."""
    commands = history.commands
    other = ActionHistory(history.site)
    try:
        for command in commands[:asked_at]:
            other.record(command)
        other.record(RobotCommand.build(history.site, option[1], option[2], option[3]))
        for command in commands[asked_at:]:
            other.record(command)
    except Refusal:
        return None
    return other


def not_carried_out(decision: Decision, unanswered: Sequence[tuple[Decision, Sequence[Outcome]] | tuple[Decision, Sequence[Outcome], int]],
                    history: ActionHistory, interpreter: Callable = im_interpret) -> Decision:
    """Step 5 of the module docstring: ``decision`` would act, but the robot has asked about earlier steps
    (``unanswered``: (decision, the commands it asked about or may have meant, and how many commands ``history``
    held when it asked, all of them when left out) triples) and has not carried them out. If one of those
    commands, carried out when the robot asked (``had_it_been_done``), would make the same reading give another
    command, ask, naming both. A command that would make this instruction impossible or unclear is no reason to ask
    when another command asked about leaves it as it is: the worker's words fit that one (not for a question
    whose every command would)."""
    if not decision.acted:
        return decision
    own = outcome_of(decision.interpretation)
    for entry in unanswered:
        asked, options = entry[0], entry[1]
        asked_at = entry[2] if len(entry) > 2 else len(history)
        guessed = asked.refusal.reason not in NOT_UNDERSTOOD  # a half-understood refusal: what it may have meant
        outcomes = []
        for option in options:
            if option[0] != "command":
                continue
            other_history = had_it_been_done(history, asked_at, option)
            if other_history is None:
                continue  # no longer possible on the site: it cannot be what the worker now builds on
            outcomes.append((option, outcome_of(interpreter(decision.words, decision.tags, other_history))))
        fits_one = any(other == own for _, other in outcomes)
        for option, other in outcomes:
            if other == own or (other[0] != "command" and (guessed or fits_one)):
                continue
            said = " ".join(asked.words)
            if other[0] == "command":
                question = (f"I have not carried out \"{said}\". As things stand this is {_describe(own)}; had I "
                            f"carried it out, {_describe(other)}. Which do you mean?")
                options = [own, other]
            else:
                question = (f"I have not carried out \"{said}\". As things stand this is {_describe(own)}. "
                            "Is that what you mean?")
                options = [own]
            gives = _describe(other) if other[0] == "command" else f"a refusal ({other[1]})"
            return ask_instead(decision, question, options, "D unanswered question",
                               f"with {_describe(option)} carried out the reading gives {gives}: ask")
    return decision


def play_episode(instructions: Sequence[Sequence[str]], confidences: Sequence, labels: Sequence[str],
                 history: ActionHistory, settings: DecisionSettings = DEFAULT_SETTINGS,
                 interpreter: Callable = im_interpret, checks: Sequence[Interpretation | None] | None = None,
                 any_difference: bool = False) -> list[Decision]:
    """Decide an episode's instructions in order from the tagger's readings (``confidences``, one
    ``predict_confidence`` result each), recording in ``history`` the commands acted on: ``decide``, then the
    second opinion of ``checks`` (the check tagger's tags, one per instruction, or None), then step 5
    (``settings.pending``)."""
    decisions: list[Decision] = []
    unanswered: list[Decision] = []
    for n, (words, conf) in enumerate(zip(instructions, confidences)):
        words = list(words)
        decision = decide(words, conf.kbest, conf.marginals, labels, history, settings, interpreter)
        if checks is not None and checks[n] is not None:
            decision = second_opinion(decision, interpreter(words, checks[n], history), any_difference)
        if settings.pending and unanswered:
            decision = not_carried_out(decision, unanswered, history, interpreter)
        if decision.acted:
            history.record(decision.command)
            if not settings.through:
                unanswered = []
        elif decision.refusal.reason in NOT_UNDERSTOOD:
            unanswered.append((decision, decision.options, len(history)))
        else:
            meant = completions(decision, history, settings.half, settings.margin)
            if meant:
                unanswered.append((decision, meant, len(history)))
        decisions.append(decision)
    return decisions


def decide_episode(instructions: Sequence[Sequence[str]], tagger, settings: DecisionSettings = DEFAULT_SETTINGS,
                   history: ActionHistory | None = None, check=None, any_difference: bool = False) -> list[Decision]:
    """Decide each instruction of an episode in order, recording the commands acted on in ``history``
    (``play_episode`` on the tagger's readings).

    ``check``: a second tagger whose best tags give each decision a ``second_opinion`` (off by default)."""
    history = history if history is not None else ActionHistory()
    instructions = [list(w) for w in instructions]
    confidences = tagger.predict_confidence(instructions, k=settings.k) if instructions else []
    checks = check.predict(instructions) if check is not None and instructions else None
    return play_episode(instructions, confidences, tagger.labels, history, settings, im_interpret, checks,
                        any_difference)


# --- measuring: accuracy, wrong actions, over-refusals, risk against coverage ------------------------------
def step_outcome(decision_outcome: Outcome, expected: Mapping) -> str:
    """``right`` (the intended command, or a refusal or question where a refusal was expected),
    ``wrong_action`` (the robot acted, and not as intended) or ``over_refusal`` (a refusal or question
    where a command was expected)."""
    refusal_expected = expected.get("refusal") is not None
    if decision_outcome[0] == "refusal":
        return "right" if refusal_expected else "over_refusal"
    if refusal_expected:
        return "wrong_action"
    command = {"drywall_id": decision_outcome[1], "stud_id": decision_outcome[2], "placement": decision_outcome[3]}
    return "right" if all(expected[k] == v for k, v in command.items()) else "wrong_action"


def decide_rows(rows: Sequence[Mapping], tagger, settings: DecisionSettings = DEFAULT_SETTINGS,
                confidences=None) -> list[Decision]:
    """One decision per corpus row, each in its own context (the accepted commands before it in its episode).

    ``confidences`` (``tagger.predict_confidence`` of the rows' words) may be given to decide the same
    rows under several settings without tagging them again; ``tagger`` then only gives its ``labels``.
    """
    if confidences is None:
        confidences = tagger.predict_confidence([list(r["words"]) for r in rows], k=settings.k)
    return [decide(r["words"], c.kbest, c.marginals, tagger.labels,
                   ActionHistory.from_commands(r["context"]["history"]), settings)
            for r, c in zip(rows, confidences)]


def decision_scores(rows: Sequence[Mapping], decisions: Sequence[Decision]) -> dict[str, float]:
    """``accuracy``, ``wrong_action_rate``, ``over_refusal_rate`` (shares of the rows, adding up to 1) and
    ``coverage`` (the share acted on)."""
    if len(rows) != len(decisions) or not rows:
        raise ValueError(f"{len(rows)} rows but {len(decisions)} decisions")
    outcomes = [step_outcome(outcome_of(d.interpretation), r["expected"]) for r, d in zip(rows, decisions)]
    n = len(outcomes)
    return {"accuracy": outcomes.count("right") / n, "wrong_action_rate": outcomes.count("wrong_action") / n,
            "over_refusal_rate": outcomes.count("over_refusal") / n,
            "coverage": sum(d.acted for d in decisions) / n}


def risk_coverage(rows: Sequence[Mapping], decisions: Sequence[Decision]) -> "pd.DataFrame":
    """Selective prediction: as the threshold on the acted command's probability rises, the share of
    instructions acted on (coverage) and the wrong actions among all instructions (risk).

    ``decisions`` should be made with ``act=0`` (every determined, unrivalled command acted on), so
    that each threshold keeps the actions whose ``confidence`` reaches it. One row per threshold.
    """
    import pandas as pd

    acted = sorted(((d.confidence, step_outcome(outcome_of(d.interpretation), r["expected"]) == "wrong_action")
                    for r, d in zip(rows, decisions) if d.acted), reverse=True)
    n = len(rows)
    out, wrong = [], 0
    for i, (confidence, is_wrong) in enumerate(acted, start=1):
        wrong += is_wrong
        out.append({"threshold": confidence, "coverage": i / n, "wrong_action_rate": wrong / n,
                    "risk_among_acted": wrong / i})
    frame = pd.DataFrame(out, columns=["threshold", "coverage", "wrong_action_rate", "risk_among_acted"])
    return frame.groupby("threshold", sort=False).last().reset_index()
