"""Command line: ``python -m drywall_lab COMMAND`` (``--help`` lists the commands)."""
from __future__ import annotations

import argparse
import contextlib
import os
import shutil
import sys
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from drywall_lab.im import ActionHistory


def _cmd_corpus(args: argparse.Namespace) -> int:
    from drywall_lab import corpus

    if args.action == "generate":
        from drywall_lab.corpus.io import read_jsonl

        if args.field:
            from drywall_lab.corpus.field_generator import FIELD_DIR, FIELD_SEED, write_field_corpus

            paths = write_field_corpus(args.out or FIELD_DIR, seed=FIELD_SEED if args.seed is None else args.seed)
        else:
            paths = corpus.write_corpus(args.out or args.default_out, seed=corpus.SEED if args.seed is None else args.seed)
        for split, path in paths.items():
            print(f"{split:<11} {len(read_jsonl(path)):>5} instructions -> {path}")
        return 0
    rows = corpus.read_corpus(args.corpus_dir)
    if args.action == "stats":
        corpus.print_comparison(rows)
        return 0 if not corpus.check_against_paper(rows) else 1
    if args.action == "conll":
        text = corpus.to_conll(rows[args.split])
        if args.out:
            Path(args.out).write_text(text, encoding="utf-8")
            print(f"{len(rows[args.split])} instructions -> {args.out}")
        else:
            sys.stdout.write(text)
        return 0
    raise AssertionError(args.action)


def _cmd_score(args: argparse.Namespace) -> int:
    from drywall_lab.annotation import score_annotator
    from drywall_lab.corpus import from_conll

    gold = from_conll(Path(args.gold))
    answer = from_conll(Path(args.answer))
    report = score_annotator([r["tags"] for r in gold], [r["tags"] for r in answer])
    print(report.summary())
    return 0


def _cmd_demo(args: argparse.Namespace) -> int:
    """A headless walk through the course: site, corpus, agreement, tagger, information mapping."""
    import pandas as pd

    from drywall_lab import corpus
    from drywall_lab.annotation import score_annotator
    from drywall_lab.im import task_accuracy
    from drywall_lab.nlu import default_tagger, score_tagging
    from drywall_lab.pipeline import paper_layouts, run_episode
    from drywall_lab.site import default_site

    site = default_site()
    print("== The site (spec section 1) ==")
    print(pd.DataFrame([vars(s) for s in site.studs]).to_string(index=False))
    print(pd.DataFrame([vars(p) for p in site.panels]).to_string(index=False))
    rows = corpus.read_corpus()
    print("\n== Three training instructions with their tags ==")
    for row in rows["train"][:3]:
        print(row["text"])
        print("   " + " ".join(f"{w}/{t}" for w, t in zip(row["words"], row["tags"]) if t != "O"))
        print("   expected:", row["expected"])
    print("\n== The corpus against the paper's Table 2 ==")
    corpus.print_comparison(rows)
    practice = Path(__file__).resolve().parent.parent / "annotation_guidelines" / "practice"
    if (practice / "student_answer.conll").exists():
        key = corpus.from_conll(practice / "practice_key.conll")
        answer = corpus.from_conll(practice / "student_answer.conll")
        print("\n== A student's practice annotation scored against the key ==")
        print(score_annotator([r["tags"] for r in key], [r["tags"] for r in answer]).summary())

    tagger = default_tagger()
    print(f"\n== The default tagger ({tagger.kind}, {tagger.n_parameters():,} parameters) on the test split ==")
    test = rows["test"]
    predicted = tagger.predict([r["words"] for r in test])
    scores = score_tagging([r["tags"] for r in test], predicted)
    print(f"acc_word={scores.acc_word:.4f} acc_inst={scores.acc_inst:.4f} "
          f"acc_task={task_accuracy(test, predicted):.4f} n_instructions={scores.n_instructions}")

    print("\n== The paper's layouts (Figs. 15-18): instruction -> tags -> command ==")
    for layout in paper_layouts():
        print(f"-- {layout['id']}: {layout['paper']}")
        results = run_episode(layout, tagger)
        for text, r in zip(layout["instructions"], results):
            print(f"  {text}")
            print("     " + " ".join(f"{w}/{t}" for w, t in zip(r.words, r.tags) if t != "O"))
            print("     -> " + (str(r.command) if r.command else f"refused ({r.refusal.reason}): {r.refusal.message}"))
    return 0


def _interpretation(args: argparse.Namespace, history: "ActionHistory"):
    """The instruction's interpretation: its markup's tags through the IM (``--tagged``), or a tagger's
    readings through the decision layer, as ``run`` decides (``drywall_lab.decision``)."""
    from drywall_lab.corpus.markup import parse
    from drywall_lab.im import interpret
    from drywall_lab.nlu.normalise import normalise

    if args.tagged:
        tokens = [t for t in parse(args.text.replace(",", " , ").replace(".", " . ")) if t.is_word]
        return interpret([t.word for t in tokens], [t.tag for t in tokens], history)
    from drywall_lab.decision import interpret_instruction
    from drywall_lab.pipeline import load_tagger_option

    return interpret_instruction(list(normalise(args.text).words), load_tagger_option(args.tagger), history)


def _cmd_interpret(args: argparse.Namespace) -> int:
    """One instruction through NLU and IM: words and tags, the rule trace, the command or refusal.

    With ``--history FILE`` the IM starts from that action history (spec section 4); the file must
    exist unless ``--record`` is given, when a missing file starts a new wall. ``--record`` writes
    an accepted command into the file, whole or not at all.
    """
    _check_text(args.text)
    history_path = Path(args.history) if args.history else None
    if args.record and history_path is None:
        raise ValueError("--record needs --history FILE: the action history CSV to record the command in")
    history = _read_history(history_path, start_new=args.record)
    new_file = history_path is not None and not history_path.exists()
    result = _interpretation(args, history)
    words, tags = result.words, result.tags
    print("words and tags:")
    print("  " + " ".join(w if t == "O" else f"{w}/{t}" for w, t in zip(words, tags)))
    print(f"rule trace (history: {len(history)} accepted command(s) before this one):")
    for line in str(result.trace).splitlines():
        print("  " + line)
    if result.command is None:
        print(f"refused ({result.refusal.reason}): {result.refusal.message}")
        print("the action history is unchanged")
        if args.record and new_file:
            _save_history(history, history_path)
            print(f"started a new action history with no rows: {history_path}")
        return 1
    print(f"command: {result.command}")
    print("new action history row:")
    import pandas as pd

    print(pd.DataFrame([result.history_row]).to_string(index=False))
    if args.record:
        history.record(result.command)
        _save_history(history, history_path)
        print(f"recorded: {history_path} now has {len(history)} row(s)")
    return 0


def _check_text(text: str) -> None:
    """A ``ValueError`` for an instruction holding bytes that are not UTF-8 (they reach ``argv`` as surrogates)."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError as e:
        raise ValueError(f"the instruction is not valid UTF-8 text (at character {e.start + 1})") from None


def _read_history(path: Path | None, start_new: bool) -> ActionHistory:
    """The action history ``--history`` names: empty without one; a missing file is an error unless
    ``start_new`` (``--record``), so that a mistyped path never silently starts from an empty wall."""
    from drywall_lab.im import ActionHistory

    if path is None:
        return ActionHistory()
    if path.is_dir():
        raise ValueError(f"--history {path} is a folder, not an action history CSV file")
    if not path.exists():
        if start_new:
            folder = next(p for p in path.absolute().parents if p.exists())
            if not folder.is_dir():
                raise ValueError(f"--history {path} cannot be created: {folder} is a file, not a folder")
            return ActionHistory()
        raise FileNotFoundError(f"no action history at {path} (to start a new wall in that file, add --record)")
    return ActionHistory.from_csv(path)


def _save_history(history: ActionHistory, path: Path) -> None:
    """Write the history CSV whole or not at all: a temporary file beside it, then ``os.replace``."""
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        history.to_csv(temporary)
        if path.exists():
            shutil.copymode(path, temporary)
        os.replace(temporary, path)
    finally:
        with contextlib.suppress(OSError):
            temporary.unlink(missing_ok=True)


def _cmd_run(args: argparse.Namespace) -> int:
    """The batch contract of spec section 6: JSON lines in, one JSON line per instruction out."""
    import json

    from drywall_lab.pipeline import load_tagger_option, read_episodes, run_episodes

    episodes = read_episodes(args.episodes)
    tagger = load_tagger_option(args.tagger)
    # JSON's \u escapes where the output cannot take the characters themselves
    ascii_only = (getattr(sys.stdout, "encoding", None) or "").lower().replace("-", "").replace("_", "") != "utf8"
    for record in run_episodes(episodes, tagger):
        sys.stdout.write(json.dumps(record, ensure_ascii=ascii_only) + "\n")
    return 0


def _cmd_simulate(args: argparse.Namespace) -> int:
    """The batch contract carried through the simulated robot: the ``run`` fields plus ``placement`` per
    instruction (``drywall_lab.rc.batch``), and with ``--html`` one self-contained animation of all episodes."""
    import json

    from drywall_lab.pipeline import load_tagger_option, read_episodes
    from drywall_lab.rc.batch import simulate_episodes, simulation_records
    from drywall_lab.rc.settings import record_fps

    html = _html_output(args.html)
    episodes = read_episodes(args.episodes)
    tagger = load_tagger_option(args.tagger)
    ascii_only = (getattr(sys.stdout, "encoding", None) or "").lower().replace("-", "").replace("_", "") != "utf8"
    recordings, model = [], None
    for episode, run in zip(episodes, simulate_episodes(episodes, tagger, record_fps() if html else None)):
        for record in simulation_records(run, episode["id"]):
            sys.stdout.write(json.dumps(record, ensure_ascii=ascii_only) + "\n")
        sys.stdout.flush()
        if html is not None:
            recordings.append(run.cell.recording)
            model = run.cell.scene.model
    if html is not None:
        from drywall_lab import viz

        if model is None:  # no episodes: the site as every episode starts
            from drywall_lab.rc import RobotCell

            cell = RobotCell(record_fps=record_fps())
            recordings, model = [cell.recording], cell.scene.model
        summary = viz.save_animation(recordings, model, html)
        print(f"animation of {len(episodes)} episode(s): {html} ({summary})", file=sys.stderr)
    return 0


def _html_output(option: str | None) -> Path | None:
    """The ``--html`` file, checked before anything is simulated: not a folder, its folder creatable."""
    if option is None:
        return None
    path = Path(option)
    if path.is_dir():
        raise ValueError(f"--html {path} is a folder, not an HTML file to write")
    folder = next(p for p in path.absolute().parents if p.exists())
    if not folder.is_dir():
        raise ValueError(f"--html {path} cannot be created: {folder} is a file, not a folder")
    return path


def _cmd_chat(args: argparse.Namespace) -> int:
    """A dialogue in the terminal: instructions, the robot's commands and questions, the wall after each step."""
    from drywall_lab.dialogue import Dialogue, run_chat
    from drywall_lab.pipeline import load_tagger_option

    return run_chat(Dialogue(load_tagger_option(args.tagger)), input, sys.stdout)


def _cmd_dialogue(args: argparse.Namespace) -> int:
    """The dialogue contract: JSON requests on stdin, one JSON reply each on stdout (the spec's dialogue.md)."""
    from drywall_lab.dialogue import Dialogue, serve
    from drywall_lab.pipeline import load_tagger_option

    return serve(Dialogue(load_tagger_option(args.tagger)), sys.stdin, sys.stdout)


def _cmd_experiment(args: argparse.Namespace) -> int:
    """The paper's NLU study (Tables 3-5, Fig. 13) on this corpus, or the field ablation (issue 11)."""
    if args.study == "field":
        from drywall_lab.nlu.field_study import FieldStudySettings, run_field_study

        run_field_study(args.out or "results/field", FieldStudySettings.fast() if args.fast else FieldStudySettings.full(),
                        args.models, keep_models=None if args.keep_models == "none" else args.keep_models)
        return 0
    from drywall_lab.nlu.experiments import ExperimentSettings, run_paper_experiment, run_seed_study

    settings = ExperimentSettings.fast() if args.fast else ExperimentSettings.paper()
    if args.study == "seeds":
        from drywall_lab.nlu.experiments import SEED_MODELS

        run_seed_study(args.out or "results/paper", settings, models=tuple(args.models or SEED_MODELS))
        return 0
    run_paper_experiment(args.out or "results/paper", settings)
    return 0


def build_parser() -> argparse.ArgumentParser:
    from drywall_lab.corpus import CORPUS_DIR, SEED

    parser = argparse.ArgumentParser(prog="python -m drywall_lab", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("corpus", help="generate the instruction corpus, print its statistics, export CoNLL")
    p.add_argument("action", choices=["generate", "stats", "conll"])
    p.add_argument("--out", default=None,
                   help="generate: output folder (default data/corpus, or data/field_corpus with --field); conll: file")
    p.add_argument("--field", action="store_true",
                   help="generate: the field corpus (registers of site language; train, validation, test, novel)")
    p.add_argument("--seed", type=int, default=None, help="generate: the seed (default: the corpus's own)")
    p.add_argument("--split", default="test", choices=["train", "validation", "test", "novel"])
    p.add_argument("--corpus-dir", default=None, help="read the corpus from here (default data/corpus)")
    p.set_defaults(func=_cmd_corpus)

    p = sub.add_parser("score", help="score an annotation (CoNLL) against a gold CoNLL file")
    p.add_argument("gold")
    p.add_argument("answer")
    p.set_defaults(func=_cmd_score)

    from drywall_lab.nlu.cli import add_commands as add_tagger_commands

    add_tagger_commands(sub)  # train, ensemble, evaluate (drywall_lab/nlu/cli.py)

    p = sub.add_parser("experiment", help="paper: the paper's NLU study (LSTM/BERT-M1..M4, BERT-C1..C4, Tables 3-5, "
                                          "Fig. 13); seeds: LSTM-M1..M4 and BERT-M1..M4 over three seeds; field: the "
                                          "ablation from the corpus to the field")
    p.add_argument("study", choices=["paper", "seeds", "field"])
    p.add_argument("--out", default=None, help="output folder (default results/paper, or results/field)")
    p.add_argument("--fast", action="store_true", help="an eighth of the data and 3 / 1 epochs: a quick check, not the study")
    p.add_argument("--models", nargs="+", default=None, metavar="MODEL",
                   help='field: train only these models of the ablation, e.g. "MiniLM field" (the others\' rows are '
                        "kept when they are current); two runs with different models may run at once. seeds: "
                        'train only these, e.g. "BERT-M1 BERT-M2" (the other models\' rows are kept)')
    p.add_argument("--keep-models", default="build/field_study", metavar="DIR",
                   help="field: keep the trained models here, and score a model kept here under the same corpus and "
                        "settings instead of training it again (default build/field_study; 'none': keep nothing)")
    p.set_defaults(func=_cmd_experiment)

    p = sub.add_parser("interpret", help="one instruction: tags, the information-mapping rule trace, the command")
    p.add_argument("text", help='the instruction, e.g. "Pick up the full-size drywall and put it on stud 500100"')
    p.add_argument("--tagger", default=None, help="a saved tagger's directory (default: the shipped tagger, an ensemble of two BiLSTM-CRFs)")
    p.add_argument("--tagged", action="store_true",
                   help='TEXT is already tagged, word/TAG for tagged words: "the full-size/dim drywall on stud 500100/ID_stud"')
    p.add_argument("--history", default=None,
                   help="an action history CSV to start from; it must exist unless --record is given")
    p.add_argument("--record", action="store_true",
                   help="append an accepted command to the --history CSV (a missing file starts a new wall)")
    p.set_defaults(func=_cmd_interpret)

    p = sub.add_parser("run", help="episodes (JSON lines) through NLU and IM; one JSON line per instruction (spec section 6)")
    p.add_argument("episodes", help='a JSON-lines file, one {"id": ..., "instructions": [...]} per line')
    p.add_argument("--tagger", default=None, help="a saved tagger's directory (default: the shipped tagger, an ensemble of two BiLSTM-CRFs)")
    p.set_defaults(func=_cmd_run)

    p = sub.add_parser("simulate", help="episodes through NLU, IM and the simulated robot: the run fields plus "
                                        "each placement's outcome; --html writes an animation")
    p.add_argument("episodes", help='a JSON-lines file, one {"id": ..., "instructions": [...]} per line')
    p.add_argument("--tagger", default=None, help="a saved tagger's directory (default: the shipped tagger, an ensemble of two BiLSTM-CRFs)")
    p.add_argument("--html", default=None,
                   help="write one self-contained HTML animation of all the episodes here (plays offline)")
    p.set_defaults(func=_cmd_simulate)

    p = sub.add_parser("dialogue", help="the dialogue contract: JSON requests (new, say, choose) on stdin, one JSON "
                                        "reply each on stdout; a question carries the commands it weighs as options")
    p.add_argument("--tagger", default=None, help="a saved tagger's directory (default: the shipped tagger, an ensemble of two BiLSTM-CRFs)")
    p.set_defaults(func=_cmd_dialogue)

    p = sub.add_parser("chat", help="talk to the robot: an instruction, its command or question, your answer")
    p.add_argument("--tagger", default=None, help="a saved tagger's directory (default: the shipped tagger, an ensemble of two BiLSTM-CRFs)")
    p.set_defaults(func=_cmd_chat)

    p = sub.add_parser("demo", help="headless walk-through of the course material")
    p.set_defaults(func=_cmd_demo)
    parser.set_defaults(default_out=CORPUS_DIR)
    return parser


def _error_message(error: Exception) -> str:
    """What ``main`` prints after ``error:``: the message, or for a failed file operation the path and why."""
    if isinstance(error, OSError) and error.filename is not None:
        paths = str(error.filename) + (f" -> {error.filename2}" if error.filename2 is not None else "")
        return f"{paths}: {error.strerror or type(error).__name__}"
    return str(error)


def main(argv: list[str] | None = None) -> int:
    """Run one command; bad input (a missing, unreadable or garbled file, a wrong option) exits 2 with a message."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except BrokenPipeError:  # the reader of the output went away (``run ... | head``)
        with contextlib.suppress(OSError, ValueError):  # so that the final flush does not fail again
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        print("error: the output was closed before everything was written", file=sys.stderr)
        return 2
    except (ValueError, OSError) as e:
        print(f"error: {_error_message(e)}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
