"""What every benchmark does with its results file: the ``--out`` and ``--quick`` options, the command line it
records, and writing the file.

The recorded results (``benchmarks/results/*.md``) are full runs: ``--quick`` checks that a script works on a few
instructions, and its figures mean nothing, so it must be given a file of its own (``--out``).
"""
from __future__ import annotations

import argparse
import shlex
from pathlib import Path
from typing import Sequence

ROOT = Path(__file__).resolve().parent.parent


def add_results_options(parser: argparse.ArgumentParser, default: Path, quick: str | None = None) -> None:
    """``--out FILE`` (default: the recorded results file ``default``) and, when ``quick`` says what it shrinks the
    benchmark to, ``--quick``."""
    parser.add_argument("--out", type=Path, default=None,
                        help=f"the results file to write (default {default.relative_to(ROOT)})")
    if quick is not None:
        parser.add_argument("--quick", action="store_true",
                            help=f"a check that the script works: {quick}; the figures mean nothing (needs --out)")


def results_path(parser: argparse.ArgumentParser, args: argparse.Namespace, default: Path) -> Path:
    """``--out``, or the recorded results file; ``--quick`` without ``--out`` stops with a message."""
    if args.out is not None:
        return args.out
    if getattr(args, "quick", False):
        parser.error("--quick figures mean nothing: give --out FILE so that they do not replace the recorded results")
    return default


def command_line(script: str, argv: Sequence[str]) -> str:
    """The command as a reader would type it again: ``python benchmarks/<script> ARGS``."""
    return shlex.join(["python", f"benchmarks/{script}", *argv])


def write_results_file(path: Path, lines: Sequence[str]) -> None:
    """Write the results file (its folder created if missing)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines), encoding="utf-8")
