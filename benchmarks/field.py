"""The pipeline end to end on hand-written field instructions: the `run` contract, scored by voice.

Runs ``python -m drywall_lab run``'s pipeline (``drywall_lab.pipeline.run_episodes``: tagger, then the
information-mapping rules and the decision layer, episode by episode) on

- ``data/field/``: the project's own hand-written set (evaluation only; ``data/field/README.md``), and
- ``../shared/field/``, when it exists beside the checkout: a measuring stick kept outside the project,
  scored by this script and by its own ``score.py``;
- ``data/first_sight/*/``: the first-sight sets (issue 29), each scored once blind when it was written
  (its README records that figure) and a regression set since;

and prints, by voice and overall, accuracy (the intended command, or a refusal where one was expected),
the wrong-action rate (the robot acted, and not as intended), the over-refusal rate (a refusal or a
question where a command was expected) and refusal precision and recall. It writes its results file
(default ``benchmarks/results/field.md``) with the machine, the date, the command and the tagger.

    python benchmarks/field.py [--tagger DIR] [--out FILE]

The last lines it prints are ``<set>_accuracy=...`` and ``<set>_wrong_action_rate=...`` for each set.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pandas as pd

from drywall_lab import course
from drywall_lab.field import FIELD_DIR, read_field_set, score_run
from drywall_lab.machine import describe_machine
from drywall_lab.pipeline import load_tagger_option, run_episodes

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_file import add_results_options, command_line, results_path, write_results_file  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
SHARED_FIELD = ROOT.parent / "shared" / "field"
RESULTS = Path(__file__).resolve().parent / "results" / "field.md"
COLUMNS = ["n", "accuracy", "wrong_action_rate", "over_refusal_rate", "refusal_precision", "refusal_recall"]


FIRST_SIGHT = ROOT / "data" / "first_sight"


def field_sets() -> dict[str, Path]:
    """The sets to score: the project's own, the shared one where it exists, and each first-sight set
    (``data/first_sight/DATE/``: scored once blind when it was written, a regression set since)."""
    sets = {"data_field": FIELD_DIR}
    if (SHARED_FIELD / "instructions.jsonl").is_file():
        sets["shared_field"] = SHARED_FIELD
    for directory in sorted(FIRST_SIGHT.glob("*/instructions.jsonl")):
        sets["first_sight_" + directory.parent.name.replace("-", "_")] = directory.parent
    return sets


def run_set(directory: Path, tagger) -> tuple[list[dict], pd.DataFrame, float]:
    """The `run` records of one set, their scores by voice, and the seconds it took (a set without
    hand-written tags, ``../shared/field``, is scored only)."""
    field_set = read_field_set(directory, tagged=directory == FIELD_DIR)
    started = time.perf_counter()
    records = list(run_episodes(field_set.episodes, tagger))
    seconds = time.perf_counter() - started
    return records, score_run(records, field_set), seconds


def shared_score(records: list[dict]) -> str:
    """The shared set's own scorer's report on the records."""
    with tempfile.NamedTemporaryFile("w", suffix=".jsonl", delete=False, encoding="utf-8") as f:
        for record in records:
            f.write(json.dumps(record, ensure_ascii=False) + "\n")
    try:
        done = subprocess.run([sys.executable, str(SHARED_FIELD / "score.py"), f.name], capture_output=True, text=True,
                              cwd=ROOT, check=True)
    finally:
        Path(f.name).unlink()
    return done.stdout


def describe_tagger(option: str | None, tagger) -> str:
    """Which tagger played the sets, and what it is (``course.describe_tagger``: from its own record)."""
    where = option or "the shipped default tagger (drywall_lab/models/default_tagger)"
    return f"{where}: {course.describe_tagger(tagger)}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tagger", default=None, help="a saved tagger's directory (default: the shipped one)")
    add_results_options(parser, RESULTS)
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    machine = describe_machine()
    tagger = load_tagger_option(args.tagger)
    command = command_line("field.py", (argv if argv is not None else sys.argv[1:]))
    lines = ["# Field benchmark (`benchmarks/field.py`)", "", f"**Command:** `{command}`", "",
             f"**Tagger:** {describe_tagger(args.tagger, tagger)}", "", *machine.markdown_lines(), ""]
    summary = []
    for name, directory in field_sets().items():
        records, scores, seconds = run_set(directory, tagger)
        table = scores[COLUMNS].copy()
        print(f"== {name} ({directory}) ==")
        print(table.to_string(float_format=lambda x: f"{x:.3f}"))
        lines += [f"## {name}", "", f"`{directory}`: {int(table.loc['ALL', 'n'])} steps, {seconds:.1f} s.", "",
                  "```", table.to_string(float_format=lambda x: f"{x:.3f}"), "```", ""]
        if name == "shared_field":
            report = shared_score(records)
            print(report)
            lines += ["Its own scorer (`score.py`):", "", "```", report.rstrip(), "```", ""]
        summary += [f"{name}_accuracy={table.loc['ALL', 'accuracy']:.4f}",
                    f"{name}_wrong_action_rate={table.loc['ALL', 'wrong_action_rate']:.4f}",
                    f"{name}_over_refusal_rate={table.loc['ALL', 'over_refusal_rate']:.4f}"]
    lines += ["## Summary", "", "```", *summary, "```", ""]
    write_results_file(out, lines)
    print("\n".join(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
