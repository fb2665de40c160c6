"""Does every word-level rule earn its keep on generated language? Each rule switched off in turn (issue 29, item 3).

"Every rule earns its keep on generated language. A rule, word list or decision check that moves no generated outcome
goes, or gets a generated channel that exercises it." This script measures it. ``REGISTRY`` lists the small predicates
(and a few word lists) that the information-mapping rules (``drywall_lab/im/``) and the decision layer's checks
(``drywall_lab/decision.py``) consult; each entry names the attribute, what "switched off" means (a neutral replacement
chosen so that the code path the rule adds is skipped) and what the rule is for. Switching off is a
``unittest.mock.patch`` of the attribute in its own module and in every project module that imported the same object
under the same name (``from X import name``), so the patch reaches every caller. A check written inline in a function
(a closure inside ``decide``) cannot be patched: ``UNSWITCHABLE`` lists those, reported as "not switchable without a
code change", never faked.

Every set is tagged once by the shipped tagger (``drywall_lab.nlu.default_tagger()``, ``predict_confidence`` with the
decision layer's ``k``); a caching tagger then hands the stored readings to the decision layer, which is run again
with each rule switched off (``DEFAULT_SETTINGS``). The sets:

- **generated** (the field corpus, ``drywall_lab.splits``): ``field-validation``, ``field-test`` and ``field-novel``
  (the splits the tagger did not train on), each decided two
  ways: row by row in the row's own context (``decide_rows``: the figure ``acc_decided`` of ``evaluate``) and played
  as episodes (``play_episode``, as ``benchmarks/decision.py`` plays them: each step against the commands the layer
  itself acted on), which is where step 5 of the layer (a question left open) can act at all;
- **hand-written**, regression sets only: ``data/field`` (``read_field_set``), ``../shared/field`` where it exists and
  each folder of ``data/first_sight/``, played as ``run`` plays them (``pipeline.run_episode``: the front end, then
  the decision layer episode by episode) and scored by ``field.score_run``.

An outcome *moves* when the decided outcome of a step changes (another command, a command instead of a refusal or
question, or the other way round, or another refusal reason: ``decision.outcome_of``); the right answers and wrong
actions are counted with the project's own definitions (``decision.step_outcome`` for the generated rows,
``field.score_run`` for the hand-written sets). The verdict of a rule, from the numbers: **earns its keep** (it moves
an outcome of a generated set, either way of deciding it), **moves only hand-written outcomes** (none generated, some
hand-written), **moves nothing**.

    python benchmarks/rule_ablation.py [--jobs N] [--rule NAME ...] [--out FILE] [--quick]

It writes its results file (default ``benchmarks/results/rule_ablation.md``) with the machine, the date and the
command; ``--quick`` (~50 steps a set, a few rules) only checks that the script works.
"""
from __future__ import annotations

import argparse
import importlib
import multiprocessing
import sys
import time
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator, Sequence
from unittest import mock

ROOT = Path(__file__).resolve().parent.parent
RESULTS = Path(__file__).resolve().parent / "results" / "rule_ablation.md"
SHARED_FIELD = ROOT.parent / "shared" / "field"
FIRST_SIGHT = ROOT / "data" / "first_sight"
GENERATED_SPLITS = ("field-validation", "field-test", "field-novel")
QUICK_ROWS = 50
#: How many moved steps the report quotes, per rule and set.
EXAMPLES = 2
#: The modules whose names the registry may patch: imported before anything is patched, so that every ``from X
#: import name`` copy exists and is found.
PROJECT_MODULES = ("drywall_lab.im", "drywall_lab.im.words", "drywall_lab.im.correction", "drywall_lab.im.trace",
                   "drywall_lab.im.target", "drywall_lab.im.stud", "drywall_lab.im.placement",
                   "drywall_lab.im.context", "drywall_lab.im.alternatives", "drywall_lab.im.mapper",
                   "drywall_lab.decision", "drywall_lab.pipeline", "drywall_lab.field")

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

EARNS = "earns its keep"
HAND_ONLY = "moves only hand-written outcomes"
NOTHING = "moves nothing"


# --- the neutral replacements ------------------------------------------------------------------------------
def _false(*args: Any, **kwargs: Any) -> bool:
    return False


def _true(*args: Any, **kwargs: Any) -> bool:
    return True


def _none(*args: Any, **kwargs: Any) -> None:
    return None


def _empty_list(*args: Any, **kwargs: Any) -> list:
    return []  # a new list each call: a caller may extend it (``play_episode`` does ``meant += ...``)


def _empty_dict(*args: Any, **kwargs: Any) -> dict:
    return {}


def _all_of_before(part: str, before: list[int], after: list[int], words: Sequence[str],
                   tags: Sequence[str]) -> list[int]:
    return before


@dataclass(frozen=True)
class Rule:
    """One switchable rule: ``module.attribute`` replaced by ``off`` (described by ``off_text``)."""

    name: str
    module: str
    attribute: str
    off: Any
    off_text: str
    what: str
    group: str

    @property
    def path(self) -> str:
        return f"{self.module.removeprefix('drywall_lab.')}.{self.attribute}"


@dataclass(frozen=True)
class Unswitchable:
    """A check written inline (a closure, a condition in a function body): no attribute to patch."""

    name: str
    where: str
    what: str


W, C, T, S, D = ("drywall_lab.im.words", "drywall_lab.im.correction", "drywall_lab.im.target", "drywall_lab.im.stud",
                 "drywall_lab.decision")
A = "drywall_lab.im.alternatives"
REGISTRY: tuple[Rule, ...] = (
    # reading the tags as the guidelines mean them (TaggedInstruction, im/trace.py)
    Rule("stack_place", W, "stack_place", _empty_list, "returns []",
         "a row word naming a place in a stack ('off the top of the pile') is read as O", "reading"),
    Rule("_names_the_uppermost", W, "_names_the_uppermost", _false, "returns False",
         "the stack's uppermost sheet named as such ('the top sheet', 'the top 2x8') is no row: read as O",
         "reading"),
    Rule("taken_back", C, "taken_back", _empty_dict, "returns {}",
         "the final intention: tagged words a correction takes back are read as O (all of it)",
         "reading"),
    Rule("CORRECTION_CUES", C, "CORRECTION_CUES", (), "()",
         "word list: the corrections ('no', 'wait', 'scratch that', ...) that take earlier words back", "reading"),
    Rule("offered_alternatives", A, "offered_alternatives", _none, "returns None",
         "two things offered with 'or' ('500105 or 500106, not sure which'): the robot asks which (guidelines 4.8)",
         "reading"),
    Rule("_replaced", C, "_replaced", _all_of_before, "returns all the earlier words",
         "a correction that says only a count or an anchor again takes back only the earlier count or anchor",
         "reading"),
    # target rules (im/target.py)
    Rule("says_same_size", W, "says_same_size", _true, "returns True",
         "T3: a back-reference that does not say the size ('another', 'one of those') gives way when other words "
         "name the panel (off: every back-reference says the same size)", "target"),
    Rule("_named_otherwise", T, "_named_otherwise", _false, "returns False",
         "T3: whether words other than dim name the panel (the other half of the rule above)", "target"),
    Rule("back_reference_words", W, "back_reference_words", _empty_list, "returns []",
         "T3 (spec): 'same as the previous one' is the last panel's size (a control: a spec rule)", "target"),
    Rule("standard_size_words", W, "standard_size_words", _empty_list, "returns []",
         "T3 (spec): 'full-size', 'standard' is the 4 x 8 (a control: a spec rule)", "target"),
    Rule("property_size_words", W, "property_size_words", _empty_list, "returns []",
         "T3: a size said by a property ('the narrow one', 'the short one') is the size with the least or the most "
         "of that measure on the site", "target"),
    Rule("unread_anchor", W, "unread_anchor", _empty_list, "returns []",
         "T4 and S2: a side followed by 'of' and words none of which was read as an anchor ('the pile to the right of "
         "the door') is a question, never the side's stack or stud", "target"),
    Rule("points_back", W, "points_back", _false, "returns False",
         "T5 and S3: an anchor that points back ('previous', 'that one') is the last command's stack or stud",
         "target"),
    Rule("ANCHOR_POINTING_WORDS", W, "ANCHOR_POINTING_WORDS", frozenset(), "frozenset()",
         "word list: 'that', 'it', 'where', 'came', 'went' point back in an anchor", "target"),
    Rule("says_same", W, "says_same", _false, "returns False",
         "T5/S2/S3 (spec): 'same', 'where' are 0 places; 'the same stud' alone is the last stud", "target"),
    # stud rules (im/stud.py)
    Rule("_position_said_too", S, "_position_said_too", _none, "returns None",
         "S1: position words beside a stud id must name the same stud ('the far left stud, 500100')", "stud"),
    Rule("ORDER_WORDS", W, "ORDER_WORDS", {}, "{}",
         "word list: a step said as an order along the wall ('two past 500104', 'the stud before it')", "stud"),
    Rule("says_end", W, "says_end", _false, "returns False",
         "S3: 'the very last stud' as an anchor is the right end, not the previous stud", "stud"),
    Rule("stud_going_on", S, "stud_going_on", _none, "returns None",
         "S2: a step said as going on from where the work is ('two studs further right', 'one more to the left') "
         "counts from the previous stud", "stud"),
    # the decision layer's checks (decision.py)
    Rule("two_meanings", D, "two_meanings", _none, "returns None",
         "words naming two panels or studs give the other meaning as a candidate, as likely as the first",
         "decision"),
    Rule("unread_centre", D, "unread_centre", _none, "returns None",
         "the default placement while a centre word before a word for the stud stands untagged ('centred over the "
         "first framing member') gives the centre line as a candidate, as likely", "decision"),
    # step 5, in episodes only
    Rule("had_it_been_done", D, "had_it_been_done", _none, "returns None",
         "an instruction is read against the histories an unanswered question leaves, each as likely",
         "episode"),
    Rule("completions", D, "completions", _empty_list, "returns []",
         "half='said' (as in DEFAULT_SETTINGS): a refusal that said something of the part it could not "
         "resolve stays open with the commands it may have meant",
         "episode"),
)
QUICK_RULES = ("stack_place", "two_meanings", "points_back", "had_it_been_done")

UNSWITCHABLE: tuple[Unswitchable, ...] = (
    Unswitchable("the decision's features", "decision.DecisionSettings.off",
                 "each feature of the scored decision is switched off by its settings (weight 0), not by faking a "
                 "function: benchmarks/decision.py measures each one"),
    Unswitchable("turned size", "im.target.target_by_size (inline loop)",
                 "T2: a size that matches no stack as said is tried turned (width and length swapped)"),
)


def rule_named(name: str) -> Rule:
    for rule in REGISTRY:
        if rule.name == name:
            return rule
    raise KeyError(f"no rule {name!r} in the registry")


# --- switching a rule off --------------------------------------------------------------------------------
def import_project() -> None:
    for name in PROJECT_MODULES:
        importlib.import_module(name)


def holders(rule: Rule) -> list[Any]:
    """The modules that hold the rule's object under its name: its own module, and every project module that imported
    it with ``from X import name`` (a module that reads it as ``W.name`` reaches it through its own module)."""
    import_project()
    home = importlib.import_module(rule.module)
    original = getattr(home, rule.attribute)
    out = [home]
    for module_name, module in sorted(sys.modules.items()):
        if (module is not home and module is not None and module_name.startswith("drywall_lab")
                and getattr(module, rule.attribute, None) is original
                and rule.attribute in getattr(module, "__dict__", {})):
            out.append(module)
    return out


@contextmanager
def switched_off(rule: Rule | None) -> Iterator[list[Any]]:
    """Within the block, ``rule`` is switched off everywhere it is read (nothing when None); yields the patched
    modules."""
    if rule is None:
        yield []
        return
    modules = holders(rule)
    with ExitStack() as stack:
        for module in modules:
            stack.enter_context(mock.patch.object(module, rule.attribute, rule.off))
        yield modules


# --- the readings, tagged once --------------------------------------------------------------------------
class StoredReadings:
    """A tagger that gives back stored ``predict_confidence`` results: every set is tagged once by the real tagger
    (``add``), and the decision layer, run again for each rule switched off, reads the stored results."""

    def __init__(self, tagger, k: int) -> None:
        self.tagger = tagger
        self.labels = tagger.labels
        self.k = k
        self._stored: dict[tuple[str, ...], Any] = {}

    def add(self, sentences: Sequence[Sequence[str]]) -> None:
        new = list(dict.fromkeys(tuple(s) for s in sentences if tuple(s) not in self._stored))
        if new:
            for words, confidence in zip(new, self.tagger.predict_confidence([list(w) for w in new], k=self.k)):
                self._stored[words] = confidence

    def predict_confidence(self, sentences: Sequence[Sequence[str]], k: int = 5, batch_size: int = 64) -> list:
        if k != self.k:
            raise ValueError(f"the readings were stored with k={self.k}, not k={k}")
        return [self._stored[tuple(s)] for s in sentences]

    def predict_kbest(self, sentences: Sequence[Sequence[str]], k: int, batch_size: int = 64) -> list:
        return [c.kbest for c in self.predict_confidence(sentences, k, batch_size)]

    def __len__(self) -> int:
        return len(self._stored)


# --- the sets ---------------------------------------------------------------------------------------------
@dataclass
class Played:
    """One run of a set: each step's decided outcome and its scored outcome (right / wrong_action / over_refusal)."""

    outcomes: list[tuple]
    scored: list[str]

    @property
    def right(self) -> int:
        return self.scored.count("right")

    @property
    def wrong(self) -> int:
        return self.scored.count("wrong_action")


@dataclass
class EvalSet:
    """A set and how it is decided: ``play()`` runs the decision layer (as the rules now stand) on stored readings."""

    column: str      # the results' column
    kind: str        # generated | hand-written
    mode: str        # rows | episodes
    n: int
    play: Callable[[], Played] = field(repr=False)
    texts: list[str] = field(default_factory=list, repr=False)  # each step's instruction, to quote a moved one


def generated_sets(readings: StoredReadings, split: str, limit: int | None) -> list[EvalSet]:
    """A generated split decided row by row (``decide_rows``) and played as episodes (``play_episode``)."""
    from drywall_lab.decision import DEFAULT_SETTINGS, decide_rows, outcome_of, play_episode, step_outcome
    from drywall_lab.im import ActionHistory
    from drywall_lab.splits import split_rows

    rows = split_rows(split)[:limit] if limit else split_rows(split)
    readings.add([r["words"] for r in rows])
    confidences = readings.predict_confidence([r["words"] for r in rows], k=readings.k)
    column = split.removeprefix("field-")

    def by_rows() -> Played:
        decisions = decide_rows(rows, readings, DEFAULT_SETTINGS, confidences)
        outcomes = [outcome_of(d.interpretation) for d in decisions]
        return Played(outcomes, [step_outcome(o, r["expected"]) for o, r in zip(outcomes, rows)])

    episodes: dict[str, list[int]] = {}
    for i, row in enumerate(rows):
        episodes.setdefault(row["context"]["episode"], []).append(i)
    ordered = [sorted(steps, key=lambda i: rows[i]["context"]["step"]) for steps in episodes.values()]

    def by_episodes() -> Played:
        decided: list = [None] * len(rows)
        for steps in ordered:
            history = ActionHistory.from_commands(rows[steps[0]]["context"]["history"])
            for i, d in zip(steps, play_episode([rows[i]["words"] for i in steps], [confidences[i] for i in steps],
                                                readings.labels, history, DEFAULT_SETTINGS)):
                decided[i] = d
        outcomes = [outcome_of(d.interpretation) for d in decided]
        return Played(outcomes, [step_outcome(o, r["expected"]) for o, r in zip(outcomes, rows)])

    texts = [r["text"] for r in rows]
    return [EvalSet(column, "generated", "rows", len(rows), by_rows, texts),
            EvalSet(column, "generated", "episodes", len(rows), by_episodes, texts)]


def hand_written_set(readings: StoredReadings, column: str, directory: Path, limit: int | None) -> EvalSet:
    """A hand-written set played as ``run`` plays it (``pipeline.run_episode``), scored by ``field.score_run``."""
    from drywall_lab import field as F
    from drywall_lab.decision import DEFAULT_SETTINGS, outcome_of
    from drywall_lab.pipeline import contract_record, read_instructions, run_episode

    field_set = F.read_field_set(directory, tagged=directory == F.FIELD_DIR)
    episodes, steps = [], 0
    for episode in field_set.episodes:
        if limit and steps >= limit:
            break
        episodes.append(episode)
        steps += len(episode["instructions"])
    chosen = {str(e["id"]) for e in episodes}
    gold = [g for g in field_set.gold if str(g["episode"]) in chosen]
    expect = {(str(g["episode"]), int(g["step"])): g["expect"] for g in gold}
    read = [read_instructions(e["instructions"]) for e in episodes]  # the front end, once (no rule of the registry)
    readings.add([list(n.words) for said in read for n in said])

    def play() -> Played:
        outcomes, records = [], []
        for episode, said in zip(episodes, read):
            for step, result in enumerate(run_episode(episode, readings, settings=DEFAULT_SETTINGS, read=said)):
                outcomes.append(outcome_of(result))
                records.append(contract_record(episode["id"], step, result, said[step]))
        scored = [F._step_outcome(r, expect[(str(r["episode"]), int(r["step"]))], "ablation") for r in records]
        scores = F.score_run(records, gold).loc[F.ALL]
        counted = (scored.count("right"), scored.count("wrong_action"))
        if (int(scores["right"]), int(scores["wrong_actions"])) != counted:
            raise AssertionError(f"{column}: the step outcomes do not add up to score_run's")
        return Played(outcomes, scored)

    # a hand-written set is a regression set: its steps are named, never quoted (issue 29)
    return EvalSet(column, "hand-written", "episodes", len(gold), play,
                   [f"episode {g['episode']}, step {g['step']}" for g in gold])


def hand_written_dirs() -> dict[str, Path]:
    """``data/field``, ``../shared/field`` where it exists, and each ``data/first_sight/*/``."""
    from drywall_lab.field import FIELD_DIR

    dirs = {"data/field": FIELD_DIR}
    if (SHARED_FIELD / "instructions.jsonl").is_file():
        dirs["shared/field"] = SHARED_FIELD
    for instructions in sorted(FIRST_SIGHT.glob("*/instructions.jsonl")):
        dirs[f"first_sight/{instructions.parent.name}"] = instructions.parent
    return dirs


def build_sets(readings: StoredReadings, limit: int | None) -> list[EvalSet]:
    sets = [s for split in GENERATED_SPLITS for s in generated_sets(readings, split, limit)]
    sets += [hand_written_set(readings, column, directory, limit) for column, directory in hand_written_dirs().items()]
    return sets


# --- measuring ------------------------------------------------------------------------------------------
@dataclass
class Effect:
    """What switching a rule off did to one set (against the rules as shipped)."""

    moved: int          # steps whose decided outcome changed
    rescored: int       # steps whose scored outcome changed
    d_right: int
    d_wrong: int
    examples: list[tuple[int, tuple, tuple]]  # the first few moved steps: (index, outcome as shipped, outcome now)


def compare(base: Played, now: Played) -> Effect:
    moved = [i for i, (a, b) in enumerate(zip(base.outcomes, now.outcomes)) if a != b]
    rescored = sum(a != b for a, b in zip(base.scored, now.scored))
    return Effect(len(moved), rescored, now.right - base.right, now.wrong - base.wrong,
                  [(i, base.outcomes[i], now.outcomes[i]) for i in moved[:EXAMPLES]])


def describe_outcome(outcome: tuple) -> str:
    """ "500320 on 500100, vertical_left" or "refused (unclear)"."""
    return f"{outcome[1]} on {outcome[2]}, {outcome[3]}" if outcome[0] == "command" else f"refused ({outcome[1]})"


def play_all(sets: Sequence[EvalSet], rule: Rule | None) -> list[Played]:
    with switched_off(rule):
        return [s.play() for s in sets]


def verdict(sets: Sequence[EvalSet], effects: Sequence[Effect]) -> str:
    if any(e.moved for s, e in zip(sets, effects) if s.kind == "generated"):
        return EARNS
    if any(e.moved for e in effects):
        return HAND_ONLY
    return NOTHING


def _forked_map(function: Callable, items: list, jobs: int) -> list:
    """``[function(x) for x in items]`` in ``jobs`` forked processes (they share the stored readings), in order."""
    if jobs <= 1 or len(items) <= 1:
        return [function(x) for x in items]
    context = multiprocessing.get_context("fork")
    jobs = min(jobs, len(items))
    bounds = [len(items) * j // jobs for j in range(jobs + 1)]
    workers = []
    for start, stop in zip(bounds, bounds[1:]):
        receive, send = context.Pipe(duplex=False)
        process = context.Process(target=lambda part=items[start:stop], pipe=send:
                                  pipe.send([function(x) for x in part]))
        process.start()
        send.close()
        workers.append((process, receive))
    out = []
    for process, receive in workers:
        try:
            out += receive.recv()
        except EOFError:
            process.join()
            raise RuntimeError(f"a worker process failed (exit code {process.exitcode})") from None
        process.join()
    return out


# --- the report -------------------------------------------------------------------------------------------
def _columns(sets: Sequence[EvalSet]) -> list[str]:
    return list(dict.fromkeys(s.column for s in sets))


def _moved_cell(sets: Sequence[EvalSet], effects: Sequence[Effect], column: str) -> str:
    parts = {s.mode: e.moved for s, e in zip(sets, effects) if s.column == column}
    if set(parts) == {"rows", "episodes"}:
        return f"{parts['rows']} / {parts['episodes']}"
    return str(sum(parts.values()))


def _effect_cell(sets: Sequence[EvalSet], effects: Sequence[Effect], column: str) -> str:
    cells = []
    for s, e in zip(sets, effects):
        if s.column == column and (e.d_right or e.d_wrong or e.rescored):
            mode = f"{s.mode[0]}: " if s.kind == "generated" else ""
            cells.append(f"{mode}{e.d_right:+d} right, {e.d_wrong:+d} wrong")
    return "; ".join(cells) or "·"


def report_lines(sets: Sequence[EvalSet], base: Sequence[Played], results: Sequence[tuple[Rule, list[Effect], float]],
                 command: str, machine_lines: Sequence[str], tagger_text: str, seconds: float, tag_seconds: float,
                 quick: bool) -> list[str]:
    columns = _columns(sets)
    generated = [c for c in columns if any(s.column == c and s.kind == "generated" for s in sets)]
    lines = ["# Rule ablation: does every word-level rule earn its keep on generated language? "
             "(`benchmarks/rule_ablation.py`)", "",
             f"Written by `{command}`", "", f"**Tagger:** {tagger_text}", "", *machine_lines, ""]
    if quick:
        lines += ["**--quick: a check that the script works; the figures mean nothing.**", ""]
    lines += ["Each rule of the registry is switched off in turn (its neutral replacement patched into every module "
              "that reads it) and the decision layer (`DEFAULT_SETTINGS`) is run again on the readings the shipped "
              "tagger gave once. *Moved*: steps whose decided outcome (command, or refusal reason) changed. "
              f"Generated sets ({', '.join(generated)}): `rows / episodes` = decided row by row in the row's own "
              "context (`decide_rows`, the figure acc_decided) / played as episodes (`play_episode`). Hand-written "
              "sets: played as `run` plays them, scored by `field.score_run` (regression sets only: they never "
              "decide a verdict for a rule that moves a generated outcome).", "",
              "## The sets as shipped", "", "| set | decided | steps | right | wrong actions | accuracy |",
              "|---|---|---:|---:|---:|---:|"]
    for s, b in zip(sets, base):
        lines.append(f"| {s.column} | {s.mode} | {s.n} | {b.right} | {b.wrong} | {b.right / s.n:.4f} |")
    header = " | ".join(columns)
    lines += ["", "## Verdicts", "",
              f"| # | rule | switched off | {header} | verdict |",
              "|---:|---|---|" + "---:|" * len(columns) + "---|"]
    for number, (rule, effects, _) in enumerate(results, start=1):
        cells = " | ".join(_moved_cell(sets, effects, c) for c in columns)
        lines.append(f"| {number} | `{rule.path}` | {rule.off_text} | {cells} | {verdict(sets, effects)} |")
    lines += ["", "## What each rule is for, and what switching it off did to the scores", "",
              "Change in right answers and wrong actions against the rules as shipped (generated sets: `r` row by "
              "row, `e` as episodes; `·` nothing changed).", "",
              f"| rule | group | what it does | {header} | s |", "|---|---|---|" + "---|" * len(columns) + "---:|"]
    for rule, effects, rule_seconds in results:
        cells = " | ".join(_effect_cell(sets, effects, c) for c in columns)
        lines.append(f"| `{rule.name}` | {rule.group} | {rule.what} | {cells} | {rule_seconds:.0f} |")
    lines += ["", "## Steps moved", "",
              f"The first {EXAMPLES} steps each rule moved in each set (generated sets: decided row by row, or as "
              "episodes where only that moved them; in an episode a change carries to the steps after it): the "
              "instruction (a hand-written set's step by its episode and number: its sentences stay out of the project), the "
              "outcome as shipped -> with the rule off.", ""]
    for rule, effects, _ in results:
        quoted = []
        seen: set[tuple[str, int]] = set()
        for s, e in zip(sets, effects):
            for i, before, after in e.examples:
                if (s.column, i) in seen:
                    continue
                seen.add((s.column, i))
                text = " ".join(s.texts[i].split()) if i < len(s.texts) else "?"
                said = text if s.kind == "hand-written" else f'"{text}"'
                quoted.append(f"  - {s.column} ({s.mode}): {said}: {describe_outcome(before)} -> "
                              f"{describe_outcome(after)}")
        if quoted:
            lines += [f"- `{rule.name}`", *quoted]
    lines += ["", "## Not switchable without a code change", "",
              "Checks written inline (a closure inside `decide`, a condition in a function body): there is no "
              "attribute to patch, so they are not measured here.", "", "| check | where | what it does |",
              "|---|---|---|"]
    lines += [f"| {u.name} | `{u.where}` | {u.what} |" for u in UNSWITCHABLE]
    tally = {v: [r.name for r, effects, _ in results if verdict(sets, effects) == v]
             for v in (EARNS, HAND_ONLY, NOTHING)}
    lines += ["", "## Summary", ""]
    lines += [f"- {v}: {len(names)}" + (f" ({', '.join(names)})" if names and v != EARNS else "")
              for v, names in tally.items()]
    lines += [f"- not switchable without a code change: {len(UNSWITCHABLE)} "
              f"({', '.join(u.name for u in UNSWITCHABLE)})", "",
              f"{len(results)} rules; tagging {tag_seconds:.0f} s; {seconds:.0f} s in all.", ""]
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--jobs", type=int, default=1, help="rules measured in this many processes at once (default 1)")
    parser.add_argument("--rule", action="append", default=None, metavar="NAME",
                        help="measure only this rule of the registry (repeatable)")
    add_results_options(parser, RESULTS, f"{QUICK_ROWS} steps a set and {len(QUICK_RULES)} rules")
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    if args.jobs < 1:
        parser.error("--jobs must be at least 1")
    try:
        rules = [rule_named(n) for n in (args.rule or (QUICK_RULES if args.quick else [r.name for r in REGISTRY]))]
    except KeyError as error:
        parser.error(str(error.args[0]))

    from drywall_lab import course
    from drywall_lab.decision import DEFAULT_SETTINGS
    from drywall_lab.machine import describe_machine
    from drywall_lab.nlu import default_tagger

    machine = describe_machine()
    command = command_line("rule_ablation.py", argv if argv is not None else sys.argv[1:])
    started = time.perf_counter()
    import_project()
    tagger = default_tagger()
    readings = StoredReadings(tagger, DEFAULT_SETTINGS.k)
    sets = build_sets(readings, QUICK_ROWS if args.quick else None)
    tag_seconds = time.perf_counter() - started
    print(f"tagged {len(readings)} instructions once ({tag_seconds:.0f} s); "
          + ", ".join(f"{s.column} {s.mode} {s.n}" for s in sets), flush=True)
    base = play_all(sets, None)
    again = play_all(sets, None)
    if any(a.outcomes != b.outcomes for a, b in zip(base, again)):
        raise AssertionError("the decision layer gave other outcomes on a second run with nothing switched off")

    def measure(rule: Rule) -> tuple[Rule, list[Effect], float]:
        begun = time.perf_counter()
        effects = [compare(b, p) for b, p in zip(base, play_all(sets, rule))]
        return rule, effects, time.perf_counter() - begun

    results = []
    for rule, effects, seconds in _forked_map(measure, rules, args.jobs):
        results.append((rule, effects, seconds))
        print(f"{rule.name:28} {verdict(sets, effects):34} "
              + " ".join(f"{s.column}:{s.mode[0]}={e.moved}" for s, e in zip(sets, effects)), flush=True)
    seconds = time.perf_counter() - started
    lines = report_lines(sets, base, results, command, machine.markdown_lines(), course.describe_tagger(tagger),
                         seconds, tag_seconds, args.quick)
    write_results_file(out, lines)
    print(f"{len(results)} rules, {seconds:.0f} s; written to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
