"""The project's own hand-written field set (issue 11): read it, check its gold, score a run on it.

``data/field/`` holds instructions written by hand, in voices the corpus generator was not
written from (texting, radio, non-native English, checklists, formal engineering English,
explanations, impatience, long stories), in episodes that each start from the fresh site of
spec section 1. Every step has the command or refusal that spec sections 3-5 demand and
hand-written word tags (13 labels, spec section 2). It is for evaluation only: never for
training, never to tune the generator's wording.

- ``field_set.txt`` is the hand-typed source; ``assemble`` turns it into the two JSON-lines
  files (``instructions.jsonl``, the ``run`` input of spec section 6, and ``gold.jsonl``).
- ``read_field_set`` reads and checks the two files.
- ``check_gold`` maps every step's hand-written tags with the IM and lists the steps whose
  outcome is not the expected one.
- ``score_run`` scores the ``run`` contract's records against the gold, by voice.

``python -m drywall_lab.field build | check | score RUN.jsonl`` does the same from a shell.
"""
from __future__ import annotations

import argparse
import json
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Mapping, Sequence

import pandas as pd

from drywall_lab.corpus.io import read_jsonl, tokenize, write_jsonl
from drywall_lab.corpus.tags import TAGS
from drywall_lab.errors import REFUSAL_REASONS, Refusal
from drywall_lab.im import ActionHistory, InformationMapper, RobotCommand
from drywall_lab.site import DATA_DIR, Placement, Site

FIELD_DIR = DATA_DIR / "field"
SOURCE_NAME = "field_set.txt"
INSTRUCTIONS_NAME = "instructions.jsonl"
GOLD_NAME = "gold.jsonl"
COMMAND_KEYS = ("drywall_id", "stud_id", "placement")
#: The row of ``score_run``'s table that covers every voice.
ALL = "ALL"

_TAG_ALTERNATIVES = "|".join(re.escape(t) for t in sorted(TAGS, key=len, reverse=True))
#: ``word/TAG`` with optional punctuation after the tag: ``500109/ID_stud.`` is ``500109.`` tagged ID_stud.
_TAGGED_PIECE = re.compile(rf"^(?P<word>.+?)/(?P<tag>{_TAG_ALTERNATIVES})(?P<after>[.,?!;:\"')\]]*)$")
_LINE_BREAK = "\\n"


# --- the hand-typed source -----------------------------------------------------------------------
def parse_instruction(line: str, where: str = "instruction") -> tuple[str, list[str], list[str]]:
    """One hand-tagged line: the plain text, its words (``tokenize``) and their tags.

    ``"Panel 500320/ID_wall, stud 500100/ID_stud."`` -> ``("Panel 500320, stud 500100.",
    ["Panel", "500320", "stud", "500100"], ["O", "ID_wall", "O", "ID_stud"])``; a lone ``\\n`` is a line break.
    """
    text = ""
    tagged: list[tuple[str, str]] = []  # (surface piece, tag)
    for piece in line.split():
        if piece == _LINE_BREAK:
            text = text.rstrip(" ") + "\n"
            continue
        m = _TAGGED_PIECE.match(piece)
        surface, tag = (m.group("word") + m.group("after"), m.group("tag")) if m else (piece, "O")
        text += ("" if not text or text.endswith("\n") else " ") + surface
        tagged.append((surface, tag))
    words: list[str] = []
    tags: list[str] = []
    for surface, tag in tagged:
        piece_words = tokenize(surface)
        if not piece_words and tag != "O":
            raise ValueError(f"{where}: {surface!r} is tagged {tag} but is only punctuation, not a word")
        words.extend(piece_words)
        tags.extend([tag] * len(piece_words))
    if words != tokenize(text):
        raise ValueError(f"{where}: the tagged words {words} are not tokenize(text) {tokenize(text)}")
    return text, words, tags


def _parse_expect(line: str, where: str) -> dict:
    """``= PANEL STUD PLACEMENT`` or ``= refuse REASON``."""
    parts = line.split()
    if len(parts) == 2 and parts[0] == "refuse":
        if parts[1] not in REFUSAL_REASONS:
            raise ValueError(f"{where}: unknown refusal reason {parts[1]!r}; expected one of {sorted(REFUSAL_REASONS)}")
        return {"refusal": parts[1]}
    if len(parts) == 3:
        Placement(parts[2])  # a ValueError naming the placement if it is not one of the four
        return dict(zip(COMMAND_KEYS, parts))
    raise ValueError(f"{where}: expected '= PANEL STUD PLACEMENT' or '= refuse REASON', not {line!r}")


def assemble(source: Path | str = FIELD_DIR / SOURCE_NAME) -> tuple[list[dict], list[dict]]:
    """The hand-typed source as (episodes for ``run``, gold lines); a ``ValueError`` naming the line on a slip.

    Nothing is generated: every text, tag and expected outcome is the source's, as typed.
    """
    source = Path(source)
    episodes: list[dict] = []
    gold: list[dict] = []
    voice = ""
    pending: dict | None = None
    for number, raw in enumerate(source.read_text(encoding="utf-8").splitlines(), start=1):
        where = f"{source}, line {number}"
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if line.startswith("=="):
            if pending is not None:
                raise ValueError(f"{where}: the instruction before has no '=' line")
            parts = line[2:].split()
            if len(parts) != 2:
                raise ValueError(f"{where}: expected '== EPISODE_ID VOICE', not {line!r}")
            episode_id, voice = parts
            if any(e["id"] == episode_id for e in episodes):
                raise ValueError(f"{where}: episode {episode_id} appears twice")
            episodes.append({"id": episode_id, "instructions": []})
        elif line.startswith(">"):
            if not episodes or pending is not None:
                raise ValueError(f"{where}: an instruction outside an episode or without its '=' line")
            text, words, tags = parse_instruction(line[1:], where)
            episode = episodes[-1]
            pending = {"episode": episode["id"], "step": len(episode["instructions"]), "text": text,
                       "style": voice, "words": words, "tags": tags}
            episode["instructions"].append(text)
        elif line.startswith("="):
            if pending is None:
                raise ValueError(f"{where}: an expected outcome with no instruction before it")
            pending["expect"] = _parse_expect(line[1:], where)
            gold.append({k: pending[k] for k in ("episode", "step", "text", "style", "expect", "words", "tags")})
            pending = None
        else:
            raise ValueError(f"{where}: a line must start with '#', '==', '>' or '=': {line[:40]!r}")
    if pending is not None:
        raise ValueError(f"{source}: the last instruction has no '=' line")
    return episodes, gold


def write_field_set(source: Path | str = FIELD_DIR / SOURCE_NAME, out_dir: Path | str = FIELD_DIR) -> dict[str, Path]:
    """Write ``instructions.jsonl`` and ``gold.jsonl`` from the source; the paths written."""
    episodes, gold = assemble(source)
    out_dir = Path(out_dir)
    return {
        "instructions": write_jsonl(episodes, out_dir / INSTRUCTIONS_NAME),
        "gold": write_jsonl(gold, out_dir / GOLD_NAME),
    }


# --- reading and checking -----------------------------------------------------------------------
@dataclass(frozen=True)
class FieldSet:
    """The field set: ``episodes`` in the ``run`` input format and one ``gold`` line per step."""

    episodes: list[dict]
    gold: list[dict]

    @property
    def voices(self) -> list[str]:
        return sorted({g["style"] for g in self.gold})

    def frame(self) -> pd.DataFrame:
        """One row per step: episode, step, style, text, expected command or refusal."""
        rows = [{"episode": g["episode"], "step": g["step"], "style": g["style"], "text": g["text"],
                 **{k: g["expect"].get(k) for k in COMMAND_KEYS}, "refusal": g["expect"].get("refusal")}
                for g in self.gold]
        return pd.DataFrame(rows)


def _check_gold_line(g: Mapping, where: str, tagged: bool = True) -> None:
    required = ("episode", "step", "text", "style", "expect") + (("words", "tags") if tagged else ())
    missing = [k for k in required if k not in g]
    if missing:
        raise ValueError(f"{where}: the gold line has no {', '.join(missing)}")
    expect = g["expect"]
    if set(expect) == {"refusal"}:
        if tagged and expect["refusal"] not in REFUSAL_REASONS:
            raise ValueError(f"{where}: unknown refusal reason {expect['refusal']!r}")
    elif set(expect) == set(COMMAND_KEYS):
        if expect["placement"] not in {p.value for p in Placement}:
            raise ValueError(f"{where}: unknown placement {expect['placement']!r}; expected one of "
                             f"{', '.join(p.value for p in Placement)}")
    elif tagged or set(expect) != {"refusal"}:
        raise ValueError(f"{where}: 'expect' must be {{drywall_id, stud_id, placement}} or {{refusal}}, not {expect}")
    if not tagged:
        return
    if list(g["words"]) != tokenize(g["text"]):
        raise ValueError(f"{where}: 'words' are not tokenize(text)")
    if len(g["tags"]) != len(g["words"]):
        raise ValueError(f"{where}: {len(g['words'])} words but {len(g['tags'])} tags")
    unknown = sorted(set(g["tags"]) - set(TAGS))
    if unknown:
        raise ValueError(f"{where}: unknown tag(s) {', '.join(unknown)}; the tags are {', '.join(TAGS)}")


def read_field_set(dir: Path | str = FIELD_DIR, tagged: bool = True) -> FieldSet:  # noqa: A002 (the issue's name)
    """Read ``instructions.jsonl`` and ``gold.jsonl`` from ``dir`` and check that they agree, step for step.

    ``tagged=False`` reads a set whose gold has no hand-written ``words``/``tags`` and may name refusals
    in its own words (``../shared/field``): it can be scored, not checked.
    """
    directory = Path(dir)
    for name in (INSTRUCTIONS_NAME, GOLD_NAME):
        if not (directory / name).is_file():
            raise FileNotFoundError(f"no {name} in {directory}: is this a field set's directory?")
    episodes = read_jsonl(directory / INSTRUCTIONS_NAME)
    gold = read_jsonl(directory / GOLD_NAME)
    by_step = {}
    for number, g in enumerate(gold, start=1):
        where = f"{directory / GOLD_NAME}, line {number}"
        _check_gold_line(g, where, tagged)
        key = (g["episode"], g["step"])
        if key in by_step:
            raise ValueError(f"{where}: episode {g['episode']} step {g['step']} appears twice")
        by_step[key] = g
    texts = {(e["id"], k): text for e in episodes for k, text in enumerate(e["instructions"])}
    if set(texts) != set(by_step):
        only_run = sorted(set(texts) - set(by_step))[:3]
        only_gold = sorted(set(by_step) - set(texts))[:3]
        raise ValueError(f"{directory}: instructions and gold do not cover the same steps "
                         f"(only in instructions: {only_run}; only in gold: {only_gold})")
    for key, text in texts.items():
        if by_step[key]["text"] != text:
            raise ValueError(f"{directory}: episode {key[0]} step {key[1]}: the gold text is not the instruction")
    ordered = [by_step[(e["id"], k)] for e in episodes for k in range(len(e["instructions"]))]
    return FieldSet(episodes, ordered)


def _outcome(interpretation) -> dict:
    if interpretation.command is not None:
        return interpretation.command.as_contract()
    return {"refusal": interpretation.refusal.reason}


def check_gold(field_set: FieldSet | None = None, site: Site | None = None) -> list[dict]:
    """The steps whose hand-written tags, through the IM, do not give the expected outcome.

    Each step is mapped by an ``InformationMapper`` whose history holds the episode's
    expected commands before it (refused steps add nothing: spec section 3, "previous"
    is the last accepted command), so that a step the IM gets wrong does not change
    what the steps after it are checked against. Each mismatch: ``episode``, ``step``,
    ``text``, ``expect``, ``got`` and the IM's ``message`` (its refusal message or the command).
    """
    field_set = field_set if field_set is not None else read_field_set()
    mismatches = []
    histories: dict[str, ActionHistory] = {}
    for g in field_set.gold:
        history = histories.setdefault(g["episode"], ActionHistory(site))
        result = InformationMapper(history=history.copy()).apply(g["words"], g["tags"])
        got = _outcome(result)
        if got != g["expect"]:
            message = str(result.command) if result.command is not None else result.refusal.message
            mismatches.append({"episode": g["episode"], "step": g["step"], "text": g["text"],
                               "expect": g["expect"], "got": got, "message": message})
        if "refusal" not in g["expect"]:
            expect = g["expect"]
            try:
                history.record(RobotCommand.build(history.site, expect["drywall_id"], expect["stud_id"],
                                                  expect["placement"]))
            except Refusal:
                pass  # the site cannot carry it out, so the IM did not give it: already a mismatch above
    return mismatches


def field_set_rows(field_set: FieldSet | None = None, site: Site | None = None) -> list[dict]:
    """The set's steps as corpus rows (``words``, ``tags``, ``context.history``, ``expected``), so that the
    taggers' ``evaluate`` scores it like a corpus split: each step's history is the episode's expected
    commands before it, as in ``check_gold``."""
    field_set = field_set if field_set is not None else read_field_set()
    rows, histories = [], {}
    for g in field_set.gold:
        history = histories.setdefault(g["episode"], [])
        expect = g["expect"]
        expected = ({"drywall_id": None, "stud_id": None, "placement": None, "refusal": expect["refusal"]}
                    if "refusal" in expect else {**{k: expect[k] for k in COMMAND_KEYS}, "refusal": None})
        rows.append({"id": f"field-set-{g['episode']}-{g['step']}", "text": g["text"], "words": list(g["words"]),
                     "tags": list(g["tags"]), "register": g["style"],
                     "context": {"episode": g["episode"], "step": g["step"], "history": [dict(h) for h in history]},
                     "expected": expected})
        if "refusal" not in expect:
            history.append({k: expect[k] for k in COMMAND_KEYS})
    return rows


# --- scoring a run ------------------------------------------------------------------------------
def _step_outcome(record: Mapping, expect: Mapping, where: str) -> str:
    """``right``, ``wrong_action`` (acted, not as intended) or ``over_refusal`` (refused a feasible command)."""
    command, refusal = record.get("command"), record.get("refusal")
    if (command is None) == (refusal is None):
        raise ValueError(f"{where}: a run record needs exactly one of 'command' and 'refusal'")
    if "refusal" in expect:
        return "right" if command is None else "wrong_action"
    if command is None:
        return "over_refusal"
    said = {k: str(command.get(k)) for k in COMMAND_KEYS}
    return "right" if said == {k: str(expect[k]) for k in COMMAND_KEYS} else "wrong_action"


def _ratio(part: int, whole: int) -> float:
    return part / whole if whole else math.nan


def score_run(records: Iterable[Mapping], gold: Sequence[Mapping] | FieldSet) -> pd.DataFrame:
    """Score ``run`` records (spec section 6) against the gold, one row per voice and ``ALL``.

    A step is right when the command equals the expected one, or a refusal was expected and
    the output is a refusal (any reason). Columns: ``n``; ``accuracy``; ``wrong_action_rate``
    (the robot acted and not as intended: a command where a refusal or another command was
    expected); ``over_refusal_rate`` (a refusal where a command was expected), all three as
    shares of the voice's steps, so they add up to 1; ``refusal_precision`` (expected among
    the refusals given) and ``refusal_recall`` (given among the refusals expected), NaN when
    there is nothing to divide by; and the counts they come from.
    """
    gold_lines = gold.gold if isinstance(gold, FieldSet) else list(gold)
    expected = {(str(g["episode"]), int(g["step"])): g for g in gold_lines}
    seen: dict[tuple[str, int], str] = {}
    for number, record in enumerate(records, start=1):
        key = (str(record.get("episode")), int(record.get("step", -1)))
        where = f"run record {number} (episode {key[0]}, step {key[1]})"
        if key not in expected:
            raise ValueError(f"{where}: no such step in the gold")
        if key in seen:
            raise ValueError(f"{where}: the step appears twice in the run")
        seen[key] = _step_outcome(record, expected[key]["expect"], where)
    missing = sorted(set(expected) - set(seen))
    if missing:
        raise ValueError(f"the run has no record for {len(missing)} gold step(s), e.g. "
                         f"episode {missing[0][0]} step {missing[0][1]}")
    rows = []
    for key, g in expected.items():
        refusal_expected = "refusal" in g["expect"]
        outcome = seen[key]
        refusal_given = (outcome == "right" and refusal_expected) or outcome == "over_refusal"
        rows.append({"voice": g["style"], "outcome": outcome, "refusal_expected": refusal_expected,
                     "refusal_given": refusal_given})
    steps = pd.DataFrame(rows, columns=["voice", "outcome", "refusal_expected", "refusal_given"])
    groups = [(voice, steps[steps.voice == voice]) for voice in sorted(steps.voice.unique())] + [(ALL, steps)]
    return pd.DataFrame([_scores(part) for _, part in groups], index=pd.Index([v for v, _ in groups], name="voice"))


def _scores(steps: pd.DataFrame) -> dict:
    n = len(steps)
    right = int((steps.outcome == "right").sum())
    wrong = int((steps.outcome == "wrong_action").sum())
    over = int((steps.outcome == "over_refusal").sum())
    expected = int(steps.refusal_expected.sum())
    given = int(steps.refusal_given.sum())
    true_refusals = int((steps.refusal_expected & steps.refusal_given).sum())
    return {
        "n": n,
        "accuracy": _ratio(right, n),
        "wrong_action_rate": _ratio(wrong, n),
        "over_refusal_rate": _ratio(over, n),
        "refusal_precision": _ratio(true_refusals, given),
        "refusal_recall": _ratio(true_refusals, expected),
        "right": right,
        "wrong_actions": wrong,
        "over_refusals": over,
        "refusals_expected": expected,
        "refusals_given": given,
    }


# --- command line -------------------------------------------------------------------------------
def main(argv: Sequence[str] | None = None) -> int:
    """``build`` (source -> JSON lines), ``check`` (gold through the IM), ``score RUN.jsonl`` (a run's table)."""
    parser = argparse.ArgumentParser(prog="python -m drywall_lab.field", description=__doc__.splitlines()[0])
    parser.add_argument("--dir", default=str(FIELD_DIR), help="the field set's directory (default: data/field)")
    sub = parser.add_subparsers(dest="action", required=True)
    sub.add_parser("build", help="write instructions.jsonl and gold.jsonl from field_set.txt")
    sub.add_parser("check", help="map every step's hand-written tags with the IM; list the mismatches")
    score = sub.add_parser("score", help="score a `python -m drywall_lab run` output against the gold")
    score.add_argument("run", help="the run's JSON lines ('-' for standard input)")
    args = parser.parse_args(argv)
    directory = Path(args.dir)
    try:
        if args.action == "build":
            for name, path in write_field_set(directory / SOURCE_NAME, directory).items():
                print(f"{name:<12} -> {path}")
            return 0
        field_set = read_field_set(directory)
        if args.action == "check":
            mismatches = check_gold(field_set)
            for m in mismatches:
                print(f"{m['episode']} step {m['step']}: expected {m['expect']}, got {m['got']}\n  {m['text']}\n  {m['message']}")
            print(f"{len(field_set.gold)} steps, {len(mismatches)} mismatch(es)")
            return 1 if mismatches else 0
        if args.run != "-" and not Path(args.run).is_file():
            raise FileNotFoundError(f"no run output at {args.run}: write one with "
                                    f"`python -m drywall_lab run {directory / INSTRUCTIONS_NAME} > RUN.jsonl`")
        lines = sys.stdin.read().splitlines() if args.run == "-" else Path(args.run).read_text(encoding="utf-8").splitlines()
        records = [json.loads(line) for line in lines if line.strip()]
        with pd.option_context("display.width", 160, "display.max_columns", 20):
            print(score_run(records, field_set).round(3).to_string())
        return 0
    except (ValueError, FileNotFoundError, json.JSONDecodeError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    raise SystemExit(main())


# --- for the course (notebook 07) ----------------------------------------------------------------------------
def failures(records: Iterable[Mapping], field_set: FieldSet) -> pd.DataFrame:
    """The steps a run got wrong, one row each: voice, text, what was expected and what the run did, the
    kind of mistake (``wrong_action`` or ``over_refusal``) and, where the set has hand-written tags, the
    words the tagger tagged differently (``word: gold -> predicted``)."""
    gold = {(str(g["episode"]), int(g["step"])): g for g in field_set.gold}
    rows = []
    for number, record in enumerate(records, start=1):
        g = gold[(str(record["episode"]), int(record["step"]))]
        outcome = _step_outcome(record, g["expect"], f"run record {number}")
        if outcome == "right":
            continue
        did = (" ".join(f"{k}={v}" for k, v in record["command"].items()) if record["command"] is not None
               else f"refused: {record['refusal']}")
        tag_diff = ""
        if "tags" in g and list(g["words"]) == list(record["words"]):
            tag_diff = ", ".join(f"{w}: {a} -> {b}" for w, a, b in zip(g["words"], g["tags"], record["tags"]) if a != b)
        rows.append({"voice": g["style"], "text": g["text"], "expected": " ".join(f"{k}={v}" for k, v in g["expect"].items()),
                     "did": did, "mistake": outcome, "tags_differ": tag_diff})
    return pd.DataFrame(rows, columns=["voice", "text", "expected", "did", "mistake", "tags_differ"])


def check_own_instructions(instructions: Sequence[str], expected: Mapping[str, str], tagger=None,
                           minimum: int = 3):
    """Notebook 07's exercise: instructions of the student's own for one command, through the whole pipeline.

    Passes when there are at least ``minimum`` different instructions, none of them moves the robot wrongly
    (a command other than ``expected``: ``{"drywall_id", "stud_id", "placement"}``), and at least two are
    carried out as intended (a question is safe, but a pipeline that only asks is no help). Each message
    says what the pipeline did with one instruction. Returns a ``drywall_lab.exercise.ExerciseCheck``.

    The notebook's stub, ``[...]`` (or ``...``, ``None``), is "not attempted yet" (``ExerciseCheck.not_attempted``);
    a ``...`` left among instructions is a placeholder, not an instruction, and is left out.
    """
    from drywall_lab.corpus.io import tokenize
    from drywall_lab.nlu.normalise import normalise
    from drywall_lab.exercise import ExerciseCheck, is_unattempted
    from drywall_lab.decision import decide_episode
    from drywall_lab.nlu import default_tagger

    if is_unattempted(instructions, none=True):
        return ExerciseCheck.not_attempted(f"MY_INSTRUCTIONS: at least {minimum} different instructions of your own "
                                           "for the command", "drywall_lab/course/solutions/ch07.py")
    tagger = tagger or default_tagger()
    texts = [str(t) for t in instructions if t is not Ellipsis]
    messages: list[str] = []
    distinct = {" ".join(w.lower() for w in tokenize(t)) for t in texts} - {""}
    if len(distinct) < minimum:
        return ExerciseCheck(False, [f"Write at least {minimum} different instructions; there are {len(distinct)}."])
    right = wrong = 0
    for text in texts:
        decision = decide_episode([list(normalise(text).words)], tagger)[0]
        tagged = " ".join(w if t == "O" else f"{w}/{t}" for w, t in zip(decision.words, decision.tags))
        if decision.acted:
            got = decision.command.as_contract()
            if all(got[k] == expected[k] for k in COMMAND_KEYS):
                right += 1
                messages.append(f"carried out as intended: {text!r} ({tagged})")
            else:
                wrong += 1
                messages.append(f"MOVED THE ROBOT WRONGLY: {text!r} became {got} ({tagged}). Which words were "
                                "tagged wrong, and which tag should they carry?")
        else:
            messages.append(f"no action ({decision.refusal.reason}): {text!r}: {decision.refusal.message} ({tagged})")
    if wrong == 0 and right < 2:
        messages.append("Safe, but only one instruction or none was carried out: try wordings the robot understands.")
    return ExerciseCheck(wrong == 0 and right >= 2, messages)
