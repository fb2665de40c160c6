"""The dialogue measured with a worker who answers (issue 30): success, wrong actions, missed steps, first-reply
accuracy and extra turns per step.

A scripted worker plays every episode against ``drywall_lab.dialogue.Dialogue`` through the dialogue contract
(``Dialogue.respond``: ``new``, ``say``, ``choose``), in-process, by the rules of ``../shared/field/score_dialogue.py``
(the spec's dialogue.md): it says the step's text; a command ends the step (right if it is the intended one,
otherwise a wrong action); a refusal is right where a refusal was intended, otherwise the worker restates the
instruction plainly once; a question is answered with the intended command's option when it is among at most three
options, otherwise with none (and, where a command was intended, the instruction is restated plainly once). Each
``choose`` and each restatement is one extra turn; a restated step still not done is missed.

Sets: the generated field splits (``field-validation``, ``field-novel``: every episode from the fresh site, the
novel split with its held-back channels) and every hand-written set (``data/field``, ``../shared/field`` where it
exists, ``data/first_sight/*``). For ``../shared/field`` its own scorer (``score_dialogue.py``, which starts
``python -m drywall_lab dialogue``) is run too and its report kept.

    python benchmarks/dialogue.py [--tagger DIR] [--out FILE]

The last lines it prints are ``<set>_success=...``, ``<set>_wrong_action_rate=...`` and
``<set>_extra_turns_per_step=...`` for each set.
"""
from __future__ import annotations

import argparse
import collections
import json
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import pandas as pd

from drywall_lab.corpus.field_generator import field_split
from drywall_lab.decision import DEFAULT_SETTINGS
from drywall_lab.dialogue import MAX_OPTIONS, Dialogue
from drywall_lab.machine import describe_machine
from drywall_lab.pipeline import load_tagger_option

sys.path.insert(0, str(Path(__file__).resolve().parent))
from field import SHARED_FIELD, describe_tagger, field_sets  # noqa: E402
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
RESULTS = Path(__file__).resolve().parent / "results" / "dialogue.md"
FIELDS = ("drywall_id", "stud_id", "placement")
PLAIN = {
    "vertical_left": "vertically, with its edge on the stud's left line",
    "vertical_middle": "vertically, with its edge on the centre line of the stud",
    "horizontal_top": "horizontally, in the top row",
    "horizontal_bottom": "horizontally, in the bottom row",
}
GENERATED = ("field-validation", "field-novel")
ASK_COSTS = (0.1, 0.3, 0.5, 1.0)


def _same(command: dict | None, expect: dict) -> bool:
    return isinstance(command, dict) and all(str(command.get(k)) == str(expect[k]) for k in FIELDS)


def plainly(expect: dict) -> str:
    """The worker's plain restatement of an intended command."""
    return f"Put panel {expect['drywall_id']} on stud {expect['stud_id']}, {PLAIN[expect['placement']]}."


def play_step(dialogue: Dialogue, text: str, expect: dict) -> dict:
    """One step as the scripted worker plays it: ``outcome`` (right, wrong, missed), ``extra`` turns, ``first``
    (right at the first reply)."""
    wants_refusal = expect.get("refusal") is not None
    extra, restated, first, asked, held = 0, False, None, 0, 0
    reply = dialogue.respond({"say": text})
    while True:
        kind = reply["kind"]
        if first is None:
            first = (kind == "refusal" and wants_refusal) or (
                kind == "command" and not wants_refusal and _same(reply.get("command"), expect))
        if kind == "command":
            ok = not wants_refusal and _same(reply["command"], expect)
            return {"outcome": "right" if ok else "wrong", "extra": extra, "first": first, "asked": asked, "held": held}
        if kind == "question":
            options = reply.get("options") or []
            pick = None
            if not wants_refusal and len(options) <= MAX_OPTIONS:
                pick = next((k for k, c in enumerate(options) if _same(c, expect)), None)
            if not wants_refusal:
                asked, held = asked + 1, held + (pick is not None)
            extra += 1
            answer = dialogue.respond({"choose": pick})
            if pick is not None:
                reply = answer
                continue
            if answer["kind"] == "command":
                return {"outcome": "wrong", "extra": extra, "first": first, "asked": asked, "held": held}
            if wants_refusal:
                return {"outcome": "right", "extra": extra, "first": first, "asked": asked, "held": held}
        elif kind == "refusal":
            if wants_refusal:
                return {"outcome": "right", "extra": extra, "first": first, "asked": asked, "held": held}
        else:
            raise RuntimeError(f"unexpected reply to a step: {reply}")
        if restated:
            return {"outcome": "missed", "extra": extra, "first": first, "asked": asked, "held": held}
        restated = True
        extra += 1
        reply = dialogue.respond({"say": plainly(expect)})


def episodes_of_gold(path: Path) -> dict[str, list[dict]]:
    """A hand-written set's gold steps by episode: ``{"text", "style", "expect"}``."""
    episodes: dict[str, list[dict]] = collections.OrderedDict()
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.strip():
            step = json.loads(line)
            episodes.setdefault(step["episode"], []).append(step)
    return {ep: sorted(steps, key=lambda s: s["step"]) for ep, steps in episodes.items()}


def episodes_of_split(split: str) -> dict[str, list[dict]]:
    """A generated split's rows by episode, as steps: the row's text, its register as the voice, its outcome."""
    episodes: dict[str, list[dict]] = collections.OrderedDict()
    for row in field_split(split.removeprefix("field-")):
        expect = {k: v for k, v in row["expected"].items() if v is not None}
        episodes.setdefault(row["context"]["episode"], []).append(
            {"text": row["text"], "style": row["register"], "expect": expect, "step": row["context"]["step"]})
    return {ep: sorted(steps, key=lambda s: s["step"]) for ep, steps in episodes.items()}


def play_set(dialogue: Dialogue, episodes: dict[str, list[dict]]) -> tuple[pd.DataFrame, float]:
    """Every episode from the fresh site; the scores by voice and overall, and the seconds it took."""
    rows = []
    started = time.perf_counter()
    for episode, steps in episodes.items():
        dialogue.respond({"new": episode})
        for step in steps:
            rows.append({"voice": step["style"], **play_step(dialogue, step["text"], step["expect"])})
    seconds = time.perf_counter() - started
    frame = pd.DataFrame(rows)
    return pd.concat([scores(frame[frame.voice == v]).rename(v) for v in sorted(frame.voice.unique())]
                     + [scores(frame).rename("ALL")], axis=1).T, seconds


def scores(frame: pd.DataFrame) -> pd.Series:
    outcome = frame["outcome"]
    asked = frame["asked"].sum()
    return pd.Series({"n": len(frame), "success": (outcome == "right").mean(), "wrong": (outcome == "wrong").mean(),
                      "missed": (outcome == "missed").mean(), "first_reply": frame["first"].mean(),
                      "extra_turns": frame["extra"].mean(), "questions": asked,
                      "options_hold": frame["held"].sum() / asked if asked else float("nan")})


def ask_cost_curve(tagger, sets: dict[str, dict[str, list[dict]]]) -> list[str]:
    """Success against extra turns on the generated splits as the cost of a question (``DecisionCosts.ask``) moves,
    the weights as fitted: the curve that replaces risk against coverage once the worker answers."""
    rows = []
    for ask in ASK_COSTS:
        dialogue = Dialogue(tagger, replace(DEFAULT_SETTINGS, costs=replace(DEFAULT_SETTINGS.costs, ask=ask)))
        for split, episodes in sets.items():
            table, _ = play_set(dialogue, episodes)
            rows.append({"ask": ask, "split": split, **table.loc["ALL", ["success", "wrong", "missed", "extra_turns"]]})
    frame = pd.DataFrame(rows)
    print(frame.to_string(index=False))
    return ["## Success against extra turns, by the cost of a question (generated splits)", "",
            f"The shipped cost is {DEFAULT_SETTINGS.costs.ask} (written down in `drywall_lab.decision.DecisionCosts`); "
            "a cheaper question asks more (more turns), a dearer one acts or refuses instead.", "", "```",
            frame.to_string(index=False, float_format=lambda x: f"{x:.4f}"), "```", ""]


def shared_scorer_report(tagger_option: str | None) -> str:
    """``../shared/field/score_dialogue.py`` run against ``python -m drywall_lab dialogue``."""
    command = f"{sys.executable} -m drywall_lab dialogue" + (f" --tagger {tagger_option}" if tagger_option else "")
    done = subprocess.run([sys.executable, str(SHARED_FIELD / "score_dialogue.py"), "--cmd", command],
                          capture_output=True, text=True, cwd=ROOT, check=True)
    return done.stdout


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tagger", default=None, help="a saved tagger's directory (default: the shipped one)")
    parser.add_argument("--skip-generated", action="store_true", help="the hand-written sets only")
    add_results_options(parser, RESULTS)
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    tagger = load_tagger_option(args.tagger)
    dialogue = Dialogue(tagger)
    command = command_line("dialogue.py", (argv if argv is not None else sys.argv[1:]))
    lines = ["# Dialogue benchmark: a worker who answers (`benchmarks/dialogue.py`)", "", f"**Command:** `{command}`",
             "", f"**Tagger:** {describe_tagger(args.tagger, tagger)}", "", *describe_machine().markdown_lines(), "",
             "A scripted worker (the rules of `../shared/field/score_dialogue.py`) plays each set through the dialogue "
             "contract in-process. *success*: the step ended as intended; *wrong*: the robot acted, and not as "
             "intended; *missed*: still not done after one plain restatement; *first_reply*: right at the first "
             "reply (the batch figure); *extra_turns*: answers and restatements a step; *questions*: questions asked where a "
             "command was intended; *options_hold*: the share of them whose options held it (the options are "
             "calibrated on generated episodes for 98%: `benchmarks/results/decision.md`).", ""]
    sets = {} if args.skip_generated else {split: episodes_of_split(split) for split in GENERATED}
    sets.update({name: episodes_of_gold(directory / "gold.jsonl") for name, directory in field_sets().items()})
    summary = []
    for name, episodes in sets.items():
        table, seconds = play_set(dialogue, episodes)
        text = table.to_string(float_format=lambda x: f"{x:.4f}",
                               formatters={"n": "{:.0f}".format, "questions": "{:.0f}".format})
        print(f"== {name} ==\n{text}")
        lines += [f"## {name}", "", f"{len(episodes)} episodes, {int(table.loc['ALL', 'n'])} steps, {seconds:.1f} s.",
                  "", "```", text, "```", ""]
        if name == "shared_field":
            report = shared_scorer_report(args.tagger)
            print(report)
            lines += ["Its own scorer (`score_dialogue.py`, against `python -m drywall_lab dialogue`):", "", "```",
                      report.rstrip(), "```", ""]
        summary += [f"{name}_success={table.loc['ALL', 'success']:.4f}",
                    f"{name}_wrong_action_rate={table.loc['ALL', 'wrong']:.4f}",
                    f"{name}_extra_turns_per_step={table.loc['ALL', 'extra_turns']:.4f}"]
    if not args.skip_generated:
        lines += ask_cost_curve(tagger, {split: sets[split] for split in GENERATED})
    lines += ["## Summary", "", "```", *summary, "```", ""]
    write_results_file(out, lines)
    print("\n".join(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
