"""Deciding safely: one scored decision over the tagger's readings, and a question instead of a guess (issue 30;
spec section 5, ``unclear``).

The paper's pipeline acts on the single best tag sequence. This module reads the tagger's **k best** tag sequences
instead (``Tagger.predict_kbest``: ``readings``), puts each through the information-mapping rules against the site and the
action history, and decides in one step:

1. **Candidates.** Each reading *r* is a candidate, with the command (or refusal) the rules make of it. After an
   unanswered question, each reading is a candidate once more for each history the instruction may rest on: the
   history had the robot carried out a command it asked about (``had_it_been_done``), each history counting as much
   as the one as things stand. A reading whose words name two panels or two studs (``two_meanings``) adds a
   candidate for the other meaning, as likely as the one the rules took; a reading that offers two things with
   "or" (``Interpretation.alternatives``) is a candidate for each command offered, each as likely; a reading that
   takes the default placement while a word saying the centre line before a word for the stud stands untagged
   ("centred over the first framing member"; ``unread_centre``) is a candidate on the centre line too, as likely.
   The probability the k best leave over (1 minus their sum) is one more candidate, "none of these". (Features for
   the first three kinds, and one for the centre line, fitted, came out at weight 0: they were dropped.)
2. **One score each**, the tagger's log-probability plus weighted features of how the words support the reading::

       score(r) = w_logp * log p(r) + sum_f w_f * feature_f(r)
       P(outcome) = sum of softmax(score) over the candidates that give that outcome

   ``FEATURES`` lists the features; their weights are fitted on generated episodes only (``fit_weights`` for the
   likelihood of the intended outcome, then ``tune_weights`` for the least cost of the decisions, by
   ``benchmarks/decision.py``), never on the hand-written sets. Switching a feature off is one line:
   ``replace(settings, off=("site_refusal",))``.
3. **Least expected cost** (``DecisionCosts``, written down: a wrong move costs 10, a refusal of a meant command
   1, a question ``ask``)::

       act on the likeliest command c:  wrong  * (1 - P(c))
       ask about the options O:         ask + refuse * P(a command outside O)
       refuse:                          refuse * P(a command)

   The options of a question are the commands whose probability reaches ``option_floor``, at most three (the
   likeliest first; the likeliest command alone when none does). The floor is calibrated by split conformal
   prediction (``conformal_floor``) on generated episodes held out from the fit, so that the options hold the
   intended command at a chosen rate, as KnowNo does for robot planners (Ren et al., CoRL 2023).

The trace (``Interpretation.trace``) ends with a ``decision`` stage naming the probabilities and the three expected
costs. ``decide_tags`` (gold tags: one reading, probability 1) always acts on the reading's command or refuses
with its refusal, so gold tags give every intended outcome. In an episode (``play_episode``), a question stays open
(``pending``) until the end of the episode (``through``) or the next action, and an instruction refused as
``undetermined`` that said something of the part it could not resolve stays open with the commands it may have
meant (``completions``; ``half``).
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace
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
from drywall_lab.nlu.base import TagConfidence
from drywall_lab.site import Placement


#: Which ``undetermined`` refusals leave an instruction open in an episode: none; those whose reading says something
#: about the part it could not resolve ("three studs to the left of that one"); every one.
HALF_UNDERSTOOD = ("off", "said", "all")

#: The features of a candidate (step 2 of the module docstring), each with what it says.
FEATURES = {
    "log_probability": "the tagger's natural-log probability of the reading",
    "undetermined": "the rules cannot make a command of the reading (a part missing)",
    "site_refusal": "the site refuses the reading's command (overlap, buried panel, unknown id, ...)",
    "refusal_log_probability": "a refusal's log-probability again (a refusal's probability weighs otherwise)",
    "beyond_k_best": "'none of these': the log of the probability the k best readings leave over",
}


@dataclass(frozen=True)
class DecisionCosts:
    """What each outcome costs, in units of one instruction said again (step 3 of the module docstring): ``wrong``
    a wrong move (a 25 kg sheet in the wrong place), ``refuse`` a refusal where a command was meant (the worker says
    it again), ``ask`` a question (one more turn, when its options hold the intended command)."""

    wrong: float = 10.0
    refuse: float = 1.0
    ask: float = 0.3


#: The weights before any fit: the tagger's probabilities as they are (the k best and what they leave over), every
#: other feature 0.
START_WEIGHTS = {"log_probability": 1.0, "beyond_k_best": 1.0}


def _weights(**given: float) -> tuple[tuple[str, float], ...]:
    unknown = set(given) - set(FEATURES)
    if unknown:
        raise ValueError(f"unknown features {sorted(unknown)}; the features are {list(FEATURES)}")
    return tuple((name, float(given.get(name, START_WEIGHTS.get(name, 0.0)))) for name in FEATURES)


@dataclass(frozen=True)
class DecisionSettings:
    """The decision's weights, costs and options floor (fitted and calibrated by ``benchmarks/decision.py``; see
    ``DEFAULT_SETTINGS``), and how an episode keeps questions open.

    ``k``: tag sequences read; ``weights``: (feature, weight) pairs in ``FEATURES`` order; ``off``: features
    switched off (weight 0); ``costs``: ``DecisionCosts``; ``option_floor``: the probability a command needs to be
    an option of a question; ``margin``: natural-log probability below the best within which a reading counts for
    what an instruction said (``completions``); ``pending``: read an instruction against the histories an
    unanswered question leaves open; ``half``: which ``undetermined`` refusals stay open (``HALF_UNDERSTOOD``);
    ``through``: whether a question stays open after the robot acts on something else; ``open_questions``: how many
    of the latest questions still open an instruction is read against (an older one lapses: each open question adds
    up to three histories times ``k`` readings to read, so a long run of questions would make every step slower
    than the last; 4 is the most ever open at once on any set the project scores, so the bound moves no outcome);
    ``doubt_default``: a reading's default placement beside an untagged centre word is a candidate on the centre
    line too (``unread_centre``; off for tags known for certain, ``decide_tags``).
    """

    k: int = 8
    weights: tuple[tuple[str, float], ...] = _weights()
    off: tuple = ()
    costs: DecisionCosts = DecisionCosts()
    option_floor: float = 0.0
    margin: float = 1.5
    pending: bool = True
    half: str = "said"
    through: bool = True
    open_questions: int = 4
    doubt_default: bool = True

    def __post_init__(self) -> None:
        if self.k < 1:
            raise ValueError(f"k must be at least 1, got {self.k}")
        if [name for name, _ in self.weights] != list(FEATURES):
            raise ValueError(f"weights must name the features {list(FEATURES)} in that order")
        unknown = set(self.off) - set(FEATURES)
        if unknown:
            raise ValueError(f"cannot switch off unknown features {sorted(unknown)}")
        if not 0 <= self.option_floor <= 1:
            raise ValueError(f"option_floor must be between 0 and 1, got {self.option_floor}")
        if min(self.costs.wrong, self.costs.refuse, self.costs.ask) < 0:
            raise ValueError(f"costs must not be negative, got {self.costs}")
        if self.half not in HALF_UNDERSTOOD:
            raise ValueError(f"half must be one of {sorted(HALF_UNDERSTOOD)}, got {self.half!r}")
        if self.margin < 0:
            raise ValueError(f"margin must be at least 0, got {self.margin}")
        if self.open_questions < 0:
            raise ValueError(f"open_questions must be at least 0, got {self.open_questions}")

    @property
    def weight_vector(self) -> np.ndarray:
        """The weights in ``FEATURES`` order, those switched off as 0."""
        return np.array([0.0 if name in self.off else w for name, w in self.weights])


#: Acting on the single best reading, as the paper does: a wrong move costs nothing, so the robot acts on any command.
BEST_PATH = DecisionSettings(k=1, costs=DecisionCosts(wrong=0.0, refuse=1.0, ask=1.0), pending=False, half="off",
                             through=False)

#: The weights, costs and options floor ``benchmarks/decision.py`` fitted and calibrated on the generated field
#: corpus's validation split for the shipped tagger (``benchmarks/results/decision.md``; a test checks that they are
#: the recorded ones).
DEFAULT_SETTINGS = DecisionSettings(weights=_weights(
    log_probability=1.6744, undetermined=-2.9124, site_refusal=-5.6283, refusal_log_probability=0.538,
    beyond_k_best=2.018),
    costs=DecisionCosts(wrong=10, refuse=1.0, ask=0.3), option_floor=0.0)

#: The settings for tags known for certain (``decide_tags``): no doubt about a placement the tags leave out.
CERTAIN = replace(DEFAULT_SETTINGS, doubt_default=False)


# --- readings --------------------------------------------------------------------------------------------
Outcome = tuple  # ("command", drywall_id, stud_id, placement), ("refusal", reason) or NONE_OF_THESE
#: The outcome of the "none of these" candidate: a reading outside the k best.
NONE_OF_THESE = ("refusal", "none of the k best")


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
class Candidate:
    """One scored candidate (module docstring, step 1): an outcome, its features (``FEATURES`` order), the reading
    it comes from (None for "none of these") and the unanswered question whose command its history assumes done
    (None: the history as it stands)."""

    outcome: Outcome
    features: np.ndarray
    reading: Reading | None
    assumes: "Decision | None" = None


@dataclass
class Decision:
    """What the robot does with one instruction: act on ``interpretation.command``, or refuse/ask.

    ``interpretation`` is the chosen reading's (its trace ends with the decision); ``confidence`` the
    probability of the chosen outcome; ``readings`` the tagger's readings; ``action``: ``act``, ``recover`` (acted
    on a command that is not the best reading's), ``ask`` or ``refuse``; ``options``: the commands a question asks
    about (``Outcome`` tuples, the likelier first), so that an answer ("yes", "the second") can pick one
    (``drywall_lab.dialogue``); ``probabilities``: each outcome's probability; ``costs``: the expected cost of
    acting, asking and refusing; ``candidates``: the scored candidates (``Candidate``), in the order of
    ``candidates``, so that the weights can be fitted on what the decision saw.
    """

    words: list[str]
    tags: list[str]
    interpretation: Interpretation
    confidence: float
    action: str
    readings: list[Reading] = field(default_factory=list)
    options: list[Outcome] = field(default_factory=list)
    probabilities: dict = field(default_factory=dict)
    costs: dict = field(default_factory=dict)
    candidates: list = field(default_factory=list)

    @property
    def command(self):
        return self.interpretation.command

    @property
    def refusal(self) -> Refusal | None:
        return self.interpretation.refusal

    @property
    def acted(self) -> bool:
        return self.interpretation.command is not None


# --- telling commands apart, in words ------------------------------------------------------------------------
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


def question_about(options: Sequence[Outcome]) -> str:
    """The question for one, two or three options (the likeliest first)."""
    if len(options) == 1:
        return _confirm(options[0])
    if len(options) == 2:
        return question_between(*options)
    return "Did you mean " + ", or ".join(f"({n}) {_describe(o)}" for n, o in enumerate(options, start=1)) + "?"


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


#: Words that say a panel's edge goes on the stud's centre line ("centred", "half on the stud", "in the middle of
#: the stud"; annotation guidelines, Vr_md).
CENTRE_WORDS = frozenset({"centre", "center", "centred", "centered", "centreline", "centerline", "middle", "mid",
                          "half", "halfway", "split"})


#: Words for the stud a centre word must come before (within ``CENTRE_REACH`` words) to say the centre line.
STUD_NOUNS = frozenset({"stud", "studs", "stud's", "upright", "uprights", "post", "posts", "framing", "member"})
#: Words that take a centre word back when they come just before it ("not on centre", "without the centre line").
NEGATIONS = frozenset({"not", "no", "without", "never", "don't", "dont"})
CENTRE_REACH = 4


def unread_centre(outcome: Outcome, words: Sequence[str], tags: Sequence[str]) -> Outcome | None:
    """The command on the stud's centre line, where a reading's command takes the default placement (no placement
    word tagged) while a word that says the centre line is left untagged before a word for the stud ("centred over
    the first framing member", "half on the upright", with the centre word read as ``O``) and not after a negation:
    the words may mean the centre line, and the default is what the rules take when nothing is said. None
    otherwise."""
    if outcome[0] != "command" or outcome[3] != Placement.VERTICAL_LEFT.value or set(tags) & set(PLACEMENT_TAGS):
        return None
    said = [W.normalise(w) for w in words]
    for k, (w, t) in enumerate(zip(said, tags)):
        if t == "O" and w in CENTRE_WORDS and STUD_NOUNS & set(said[k + 1:k + 1 + CENTRE_REACH]) \
                and not NEGATIONS & set(said[max(0, k - CENTRE_REACH):k]):
            return (*outcome[:3], Placement.VERTICAL_MIDDLE.value)
    return None


# --- step 1: the candidates and their features ---------------------------------------------------------------
_INDEX = {name: i for i, name in enumerate(FEATURES)}


def _features(**values: float) -> np.ndarray:
    out = np.zeros(len(FEATURES))
    for name, value in values.items():
        out[_INDEX[name]] = value
    return out


def reading_candidates(words: Sequence[str], reading: Reading, history: ActionHistory,
                       assumes: "Decision | None" = None, actual: ActionHistory | None = None,
                       doubt_default: bool = True) -> list[Candidate]:
    """The candidates of one reading read against ``history``: its own outcome, and the other meaning when its words
    name two panels or studs. ``actual``: the history as it stands, when ``history`` assumes an unanswered question's
    command done (``assumes``); a command the site would not allow as things stand then is a question (the worker
    builds on a step not carried out), scored without the ``site_refusal`` feature of a misreading."""
    outcome = reading.outcome
    tags = reading.read_tags
    base = dict(log_probability=reading.logprob)
    offered = [alt for alt in reading.interpretation.alternatives if alt.command is not None
               and (actual is None or _feasible(actual, outcome_of(alt)))]
    if offered:  # two things offered with "or": each command as likely, and the question when one alone stands
        out = [Candidate(outcome_of(alt), _features(**base), Reading(reading.tags, reading.logprob, alt), assumes)
               for alt in offered]
        return out if len(offered) > 1 else out + [Candidate(outcome, _features(**base), reading, assumes)]
    if outcome[0] == "refusal":
        kind = "undetermined" if outcome[1] == "undetermined" else "site_refusal"
        return [Candidate(outcome, _features(**base, **{kind: 1.0}, refusal_log_probability=reading.logprob),
                          reading, assumes)]
    if actual is not None and not _feasible(actual, outcome):
        # the worker builds on a step not carried out: a question, not a misreading the site refuses
        return [Candidate(("refusal", "unclear"), _features(**base), reading, assumes)]
    centre = unread_centre(outcome, words, tags) if doubt_default else None
    if centre is not None and _feasible(history, centre) and (actual is None or _feasible(actual, centre)):
        # the centre line too, as likely as the default
        return [Candidate(outcome, _features(**base), reading, assumes),
                Candidate(centre, _features(**base), reading, assumes)]
    two = two_meanings(outcome, words, tags, history)
    if two is None:
        return [Candidate(outcome, _features(**base), reading, assumes)]
    out = [Candidate(outcome, _features(**base), reading, assumes)]
    for other in two[2][1:]:  # the other meaning, as likely as the one the rules took
        if actual is None or _feasible(actual, other):
            out.append(Candidate(other, _features(**base), reading, assumes))
    return out


def candidates(words: Sequence[str], readings: Sequence[Reading], history: ActionHistory,
               unanswered: Sequence = (), interpreter: Callable = im_interpret,
               doubt_default: bool = True) -> list[Candidate]:
    """Step 1 of the module docstring: every reading's candidates against ``history``, and again against each
    history an unanswered question leaves open (``unanswered``: (decision, the commands it asked about or may have
    meant, how many commands ``history`` held when it asked) triples), and "none of these"."""
    out = [c for r in readings for c in reading_candidates(words, r, history, doubt_default=doubt_default)]
    for entry in unanswered:
        asked, options = entry[0], entry[1]
        asked_at = entry[2] if len(entry) > 2 else len(history)
        for option in options:
            if option[0] != "command":
                continue
            other = had_it_been_done(history, asked_at, option)
            if other is None:
                continue  # no longer possible on the site: nothing the worker now builds on
            for r in readings:
                assumed = Reading(r.tags, r.logprob, interpreter(list(words), r.tags, other))
                out += reading_candidates(words, assumed, other, asked, history, doubt_default)
    left = 1.0 - sum(r.probability for r in readings)
    if left > 1e-9:
        out.append(Candidate(NONE_OF_THESE, _features(beyond_k_best=math.log(left)), None))
    return out


def probabilities(cands: Sequence[Candidate], weights: np.ndarray) -> np.ndarray:
    """Step 2: each candidate's probability, the softmax of its score ``features @ weights``."""
    scores = np.array([c.features for c in cands]) @ weights
    scores = np.exp(scores - scores.max())
    return scores / scores.sum()


#: A reading this far (natural log) below the best is not read: its probability, a ten-thousandth of the best one's or
#: less, goes to "none of these" (it could not move a decision; reading it would cost time).
NEGLIGIBLE = 9.2


# --- steps 2 and 3: the scores and the decision ------------------------------------------------------------
def expected_costs(mass: Mapping[Outcome, float], costs: DecisionCosts,
                   option_floor: float) -> tuple[dict[str, float], Outcome | None, list[Outcome]]:
    """Step 3 of the module docstring: the expected cost of acting on the likeliest command, of asking about the
    options, and of refusing, from each outcome's probability; with that command (None when there is none) and the
    options (at most three, the likeliest first)."""
    commands = sorted((o for o in mass if o[0] == "command"), key=lambda o: -mass[o])
    p_commands = sum(mass[o] for o in commands)
    out = {"refuse": costs.refuse * p_commands}
    if not commands:
        return out, None, []
    best = commands[0]
    options = [o for o in commands if mass[o] >= option_floor][:3] or [best]
    out["act"] = costs.wrong * (1.0 - mass[best])
    out["ask"] = costs.ask + costs.refuse * (p_commands - sum(mass[o] for o in options))
    return out, best, options


def decide(words: Sequence[str], kbest: Sequence[tuple[Sequence[str], float]], marginals: np.ndarray,
           labels: Sequence[str], history: ActionHistory | None = None,
           settings: DecisionSettings = DEFAULT_SETTINGS, interpreter: Callable = im_interpret,
           unanswered: Sequence = ()) -> Decision:
    """Choose what to do with one instruction from the tagger's readings (module docstring).

    ``kbest``: tag sequences with natural-log probabilities, best first (``Tagger.predict_kbest``); ``marginals``:
    (n_words, n_labels) tag probabilities in ``labels`` order (not read; kept so that a ``predict_confidence``
    result is passed as it comes); ``unanswered``: the questions still open in an episode (``candidates``).
    Nothing is recorded. ``interpreter(words, tags, history)`` is the IM's ``interpret`` (a cached one when many
    settings are compared on the same readings).
    """
    words = list(words)
    history = history if history is not None else ActionHistory()
    kbest = list(kbest)[: settings.k]
    if not kbest:
        raise ValueError("decide needs at least one tag sequence")
    top = float(kbest[0][1])
    readings = [Reading(list(tags), float(lp), interpreter(words, tags, history))
                for tags, lp in kbest if float(lp) >= top - NEGLIGIBLE]
    cands = candidates(words, readings, history, unanswered if settings.pending else (), interpreter,
                       settings.doubt_default)
    p = probabilities(cands, settings.weight_vector)
    mass: dict[Outcome, float] = {}
    for c, q in zip(cands, p):
        mass[c.outcome] = mass.get(c.outcome, 0.0) + float(q)
    costs, best, options = expected_costs(mass, settings.costs, settings.option_floor)
    choice = min(costs, key=lambda k: (costs[k], ("refuse", "ask", "act").index(k)))  # ties: the more careful

    def likeliest(outcome: Outcome) -> Candidate:
        return max((c for c in cands if c.outcome == outcome and c.reading is not None), key=lambda c: c.reading.logprob)

    shown = "; ".join(f"{_describe(o) if o[0] == 'command' else 'refused (' + o[1] + ')'} p={q:.3f}"
                      for o, q in sorted(mass.items(), key=lambda item: -item[1])[:4])
    note = (f"expected costs: " + ", ".join(f"{k} {v:.3f}" for k, v in costs.items()) + f" [outcomes: {shown}]")
    if choice == "act":
        chosen = likeliest(best)
        action = "act" if chosen.assumes is None and best == readings[0].outcome else "recover"
        source, refusal = chosen.reading.interpretation, None
    elif choice == "ask":
        chosen = likeliest(best)
        action, source = "ask", chosen.reading.interpretation
        question = question_about(options)
        refused = [o for o in mass if o[0] == "refusal" and o[1] not in ("undetermined", "unclear", NONE_OF_THESE[1])]
        if refused and len(options) == 1:
            top = max(refused, key=lambda o: mass[o])
            message = likeliest(top).reading.interpretation.refusal.message
            if mass[top] >= mass[options[0]]:
                question = f"{message} Or did you mean {_describe(options[0])}?"
        assumed = [(c.assumes, q) for c, q in zip(cands, p) if c.assumes is not None]
        if sum(q for _, q in assumed) >= 0.5:  # most of the probability rests on a question not answered
            question = f"I have not carried out \"{' '.join(assumed[0][0].words)}\". " + question
        refusal = Refusal("unclear", question)
    else:
        action, options = "refuse", []
        resting = [c.assumes for c, q in zip(cands, p) if c.assumes is not None and c.outcome == ("refusal", "unclear")]
        refusals = [o for o in mass if o[0] == "refusal" and o != NONE_OF_THESE and o[1] != "unclear"]
        source = likeliest(max(refusals, key=lambda o: mass[o])).reading.interpretation if refusals \
            else readings[0].interpretation
        refusal = source.refusal or (
            Refusal("unclear", f"I have not carried out \"{' '.join(resting[0].words)}\", and this rests on it as "
                               "far as I can tell. Which panel should I pick, and which stud does it go on?")
            if resting else Refusal("undetermined", "I could not work out one command from that: which panel should I "
                                                    "pick, and which stud does it go on?"))
    result = Interpretation(list(words), list(source.tags), Trace(list(source.trace.steps)),
                            source.command if refusal is None else None, refusal)
    result.trace.add("decision", f"D {action}", True, conclusion=note)
    outcome = outcome_of(result)
    return Decision(words, list(source.tags), result, mass.get(outcome, 0.0) if choice != "ask" else mass[best],
                    action, readings, list(options), mass, costs, cands)


def decide_tags(words: Sequence[str], tags: Sequence[str], labels: Sequence[str],
                history: ActionHistory | None = None) -> Decision:
    """The decision for tags known for certain (gold tags): one reading with probability 1, so the robot acts on
    its command or refuses with its refusal, whatever the weights."""
    marginals = np.zeros((len(tags), len(labels)))
    index = {label: i for i, label in enumerate(labels)}
    for i, tag in enumerate(tags):
        marginals[i, index.get(tag, index["O"])] = 1.0
    return decide(words, [(list(tags), 0.0)], marginals, labels, history, CERTAIN)


# --- one instruction, whole episodes ----------------------------------------------------------------------
def decide_instruction(words: Sequence[str], tagger, history: ActionHistory,
                       settings: DecisionSettings = DEFAULT_SETTINGS) -> Decision:
    """The decision for one instruction's words: the tagger's readings (``readings``), then ``decide``."""
    reading = readings(tagger, [list(words)], settings.k)[0]
    return decide(list(words), reading.kbest, reading.marginals, tagger.labels, history, settings)


def readings(tagger, sentences: Sequence[Sequence[str]], k: int) -> list[TagConfidence]:
    """The tagger's k best readings of each word list (``predict_kbest``), as ``play_episode`` and ``decide_rows``
    take them: ``TagConfidence`` without marginals (None), which ``decide`` does not read (the k best alone need only
    the CRF's forward pass)."""
    return [TagConfidence(kbest[0][0], None, kbest) for kbest in tagger.predict_kbest(sentences, k=k)]


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


def _counted_from_elsewhere(ti: TaggedInstruction, tag: str) -> bool:
    """A position counted from words no rule read that do not point back ("right of the door", not "left of that
    one"): something the site does not have, so nothing a later instruction can build on."""
    unread = W.unread_anchor(ti.words, ti.tags, tag)
    return bool(unread) and not W.points_back(unread)


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
        if half == "said" and (not said & set(TARGET_TAGS) or _counted_from_elsewhere(ti, "Dw_loc1")):
            return []  # nothing said about the panel ("any sheet"), or counted from what the site lacks ("right of
            # the door"): nothing to build on
        panels = [p for p in history.state.tops.values() if p is not None]
    try:
        studs = [resolve_stud(ti, ctx)]
    except Refusal:
        if half == "said" and (not said & set(DESTINATION_TAGS) or _counted_from_elsewhere(ti, "St_loc1")):
            return []  # nothing said about the stud ("over there"), or counted from what the site lacks
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


def play_episode(instructions: Sequence[Sequence[str]], confidences: Sequence, labels: Sequence[str],
                 history: ActionHistory, settings: DecisionSettings = DEFAULT_SETTINGS,
                 interpreter: Callable = im_interpret) -> list[Decision]:
    """Decide an episode's instructions in order from the tagger's readings (``confidences``, one
    ``predict_confidence`` result each), recording in ``history`` the commands acted on: ``decide``, each
    instruction read also against the histories the questions still open leave (``settings.pending``)."""
    decisions: list[Decision] = []
    unanswered: list[tuple] = []
    for words, conf in zip(instructions, confidences):
        words = list(words)
        unanswered = unanswered[-settings.open_questions:] if settings.open_questions else []  # older ones lapse
        decision = decide(words, conf.kbest, conf.marginals, labels, history, settings, interpreter, unanswered)
        if decision.acted:
            history.record(decision.command)
            if not settings.through:
                unanswered = []
        elif decision.refusal.reason in NOT_UNDERSTOOD:
            if not (decision.readings and decision.readings[0].interpretation.alternatives):
                # a question about two things offered with "or" stays open no longer: the worker said they had
                # not decided, so no later instruction rests on either
                unanswered.append((decision, decision.options, len(history)))
        else:
            meant = completions(decision, history, settings.half, settings.margin)
            if meant:
                unanswered.append((decision, meant, len(history)))
        decisions.append(decision)
    return decisions


def decide_episode(instructions: Sequence[Sequence[str]], tagger, settings: DecisionSettings = DEFAULT_SETTINGS,
                   history: ActionHistory | None = None) -> list[Decision]:
    """Decide each instruction of an episode in order, recording the commands acted on in ``history``
    (``play_episode`` on the tagger's readings)."""
    history = history if history is not None else ActionHistory()
    instructions = [list(w) for w in instructions]
    confidences = readings(tagger, instructions, settings.k) if instructions else []
    return play_episode(instructions, confidences, tagger.labels, history, settings, im_interpret)


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

    ``confidences`` (``readings`` or ``tagger.predict_confidence`` of the rows' words) may be given to decide the same
    rows under several settings without tagging them again; ``tagger`` then only gives its ``labels``.
    """
    if confidences is None:
        confidences = readings(tagger, [list(r["words"]) for r in rows], settings.k)
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


def candidate_table(decision: Decision, settings: DecisionSettings = DEFAULT_SETTINGS) -> "pd.DataFrame":
    """The worked example of the module docstring for one decision: each candidate with its outcome, its features
    (those not 0), its score and its probability, the likeliest first."""
    import pandas as pd

    weights = settings.weight_vector
    p = probabilities(decision.candidates, weights)
    rows = []
    for c, q in zip(decision.candidates, p):
        said = {n: round(float(v), 3) for n, v in zip(FEATURES, c.features) if v}
        rows.append({"outcome": _describe(c.outcome) if c.outcome[0] == "command" else f"refused ({c.outcome[1]})",
                     "features": said, "score": round(float(c.features @ weights), 3), "probability": float(q)})
    return pd.DataFrame(rows).sort_values("probability", ascending=False, kind="stable").reset_index(drop=True)


# --- fitting the weights, calibrating the options ----------------------------------------------------------
def truth_mask(cands: Sequence[Candidate], expected: Mapping) -> np.ndarray:
    """Which candidates give the intended outcome (``expected``: a command's ``drywall_id``, ``stud_id`` and
    ``placement``, or a ``refusal``): any refusal where a refusal was intended (the batch contract counts any
    refusal right), the command itself where one was; "none of these" when no reading gives it."""
    if expected.get("refusal") is not None:
        mask = np.array([c.outcome[0] == "refusal" for c in cands])
    else:
        meant = ("command", expected["drywall_id"], expected["stud_id"], expected["placement"])
        mask = np.array([c.outcome == meant for c in cands])
    if not mask.any():
        mask = np.array([c.outcome == NONE_OF_THESE for c in cands])
    return mask


def fit_weights(examples: Sequence[tuple[np.ndarray, np.ndarray]], l2: float = 0.01,
                off: Iterable[str] = ()) -> tuple[tuple[str, float], ...]:
    """The weights of least regularised negative log-likelihood of the intended outcome: ``examples`` are (features,
    truth mask) pairs, one per instruction (``candidates`` and ``truth_mask``); an instruction no candidate gets
    right says nothing and is left out. ``l2`` pulls each weight towards its start (1 for ``log_probability``,
    0 for the others); the features in ``off`` stay 0. The log-likelihood is concave in the weights, so L-BFGS
    finds its one maximum."""
    from scipy.optimize import minimize

    data = [(np.asarray(x, dtype=float), np.asarray(y, dtype=bool)) for x, y in examples if np.any(y)]
    if not data:
        raise ValueError("no instruction to fit on: no candidate gives any intended outcome")
    start = np.array([START_WEIGHTS.get(name, 0.0) for name in FEATURES])
    free = np.array([name not in set(off) for name in FEATURES])

    def loss(w: np.ndarray) -> tuple[float, np.ndarray]:
        w = np.where(free, w, 0.0)
        total, grad = 0.0, np.zeros_like(w)
        for x, y in data:
            s = x @ w
            top = s.max()
            p = np.exp(s - top)
            z, zy = p.sum(), p[y].sum()
            total -= math.log(zy) - math.log(z)
            grad -= (p[y] @ x[y]) / zy - (p @ x) / z
        total += l2 * float(((w - start) ** 2).sum()) * len(data)
        grad += 2 * l2 * (w - start) * len(data)
        return total / len(data), np.where(free, grad, 0.0) / len(data)

    found = minimize(loss, np.where(free, start, 0.0), jac=True, method="L-BFGS-B")
    return tuple((name, round(float(w) if f else 0.0, 4)) for name, w, f in zip(FEATURES, found.x, free))


def conformal_floor(truth_probabilities: Sequence[float], coverage: float = 0.98) -> float:
    """Split conformal prediction: the probability floor at which the options (the commands whose probability
    reaches it) hold the intended command at least ``coverage`` of the time on exchangeable instructions, from the
    intended command's probability on held-out calibration instructions (Angelopoulos and Bates, 2021, section 1)."""
    scores = np.sort(1.0 - np.asarray(truth_probabilities, dtype=float))
    n = len(scores)
    if n == 0:
        raise ValueError("conformal calibration needs at least one instruction")
    rank = math.ceil((n + 1) * coverage)
    if rank > n:
        return 0.0  # too few instructions for that coverage: every command is an option
    return round(max(0.0, 1.0 - float(scores[rank - 1])), 4)


#: The steps ``tune_weights`` tries on each weight, in units of ``TUNING_UNIT`` (a log-probability weight moves
#: in quarters, the others in whole units).
TUNING_STEPS = (-2.0, -1.0, -0.5, 0.5, 1.0, 2.0)
TUNING_UNIT = {"log_probability": 0.25, "refusal_log_probability": 0.25}


def tune_weights(settings: DecisionSettings, cost: Callable[[DecisionSettings], float], sweeps: int = 2,
                 min_gain: float = 0.0) -> tuple[DecisionSettings, list[dict]]:
    """Coordinate search from ``settings``'s weights for the least ``cost`` (the decisions' expected cost on
    generated episodes, which the likelihood does not see: it weighs every instruction, the cost only those near a
    decision's edge): each weight in turn moved by ``TUNING_STEPS``, a move kept when it lowers the cost by more than
    ``min_gain`` (say, what one instruction more or less right is worth: a smaller gain is noise). Returns the tuned
    settings and the moves kept."""
    weights = dict(settings.weights)
    best = cost(settings)
    moves = [{"sweep": 0, "feature": "(start)", "weight": float("nan"), "cost": best}]
    for sweep in range(1, sweeps + 1):
        for name in FEATURES:
            if name in settings.off:
                continue
            for step in TUNING_STEPS:
                trial = dict(weights)
                trial[name] = round(weights[name] + step * TUNING_UNIT.get(name, 1.0), 4)
                found = cost(DecisionSettings(**{**settings.__dict__, "weights": tuple(trial.items())}))
                if found < best - max(min_gain, 1e-12):
                    best, weights = found, trial
                    moves.append({"sweep": sweep, "feature": name, "weight": trial[name], "cost": found})
    return DecisionSettings(**{**settings.__dict__, "weights": tuple(weights.items())}), moves
