"""Inverse text normalisers on the site's forms: accuracy and time (the normaliser issue's comparison).

Every candidate rewrites each form of ``data/normalisation/forms.tsv`` (columns ``class``, ``spoken``,
``expected``; its header says what this project needs written), and its output is right when it equals one of
the acceptable outputs in ``expected`` (several are separated by `` || ``: a count may stay as said or be written in
digits) after lower-casing, collapsing white space and dropping sentence punctuation at the end of a word (exact
match, whole form). The forms that must not change (class ``keep``) have one acceptable output. The candidates:

- ``nemo``: NeMo's English inverse text normaliser (``nemo-text-processing``, pynini grammars),
  ``InverseNormalizer(lang="en").inverse_normalize(text, verbose=False)``;
- ``number_parser``: ``number_parser.parse(text)``;
- ``numerizer``: ``numerizer.numerize(text)``;
- ``project``: the project's own grammar, ``drywall_lab.nlu.normalise.normalise_text(text)``;
- ``identity``: the text unchanged, a baseline (what doing nothing scores), never chosen.

A candidate that cannot be imported is reported as not installed (or not importable) instead of
stopping the script: the libraries are not in ``environment.txt``, so in the project's ``.venv`` only
the project's grammar and the baseline run. The recorded results come from a scratch environment that
has all of them (see "How to re-run" in the results file).

Time: *load* is the wall time of importing the candidate and building it (NeMo compiles its grammars
then); *per form* is the wall time of one call on one form after loading and one warm-up call,
over ``--repeats`` passes of the whole table (median and p95 over every call).

Run from the repository root: ``python benchmarks/normalisers.py [--repeats N] [--out FILE]``; it writes
``benchmarks/results/normalisers.md`` and prints one line per candidate. ``--quick`` (two forms a class,
one pass) checks that the script works; its figures mean nothing, so it needs ``--out``.
"""
from __future__ import annotations

import argparse
import importlib.metadata
import importlib.util
import os
import platform
import re
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results_file import ROOT, add_results_options, command_line, results_path, write_results_file  # noqa: E402

TABLE = ROOT / "data" / "normalisation" / "forms.tsv"
RESULTS = Path(__file__).resolve().parent / "results" / "normalisers.md"
COLUMNS = ("class", "spoken", "expected")
#: What separates the acceptable outputs in ``expected`` ("two studs over || 2 studs over").
ALTERNATIVES = " || "
#: Classes with one acceptable output only: the forms that must not change.
STRICT_CLASSES = frozenset({"keep"})
#: What ``--quick`` shrinks the benchmark to: a check that the script runs, not a measurement.
QUICK = {"forms_per_class": 2, "repeats": 1}
BASELINE = "identity"


@dataclass(frozen=True)
class Form:
    cls: str
    spoken: str
    expected: str  #: as in the table: the acceptable outputs separated by ``ALTERNATIVES``
    line: int  #: its line in the table (1-based)

    @property
    def alternatives(self) -> tuple[str, ...]:
        """The acceptable outputs, the first being what the project's grammar writes."""
        return tuple(a.strip() for a in self.expected.split(ALTERNATIVES))

    def accepts(self, output: str) -> bool:
        """Whether ``output`` is one of the acceptable outputs (compared as ``comparable`` says)."""
        return comparable(output) in {comparable(a) for a in self.alternatives}


def read_forms(path: Path = TABLE) -> list[Form]:
    """The table's forms: lines starting with ``#`` are comments, the first other line is the header. ``expected``
    holds one acceptable output or several separated by ``ALTERNATIVES``, none empty, none the same as another once
    compared, and one only in the classes of ``STRICT_CLASSES``."""
    forms: list[Form] = []
    header_seen = False
    for number, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if not raw.strip() or raw.startswith("#"):
            continue
        cells = raw.split("\t")
        if len(cells) != len(COLUMNS) or not all(c.strip() for c in cells):
            raise ValueError(f"{path}:{number}: expected {len(COLUMNS)} non-empty tab-separated cells, got {cells!r}")
        if not header_seen:
            if tuple(cells) != COLUMNS:
                raise ValueError(f"{path}:{number}: the header must be {' / '.join(COLUMNS)}, got {cells!r}")
            header_seen = True
            continue
        form = Form(cells[0].strip(), cells[1], cells[2], number)
        alternatives = form.alternatives
        if not all(alternatives) or any("||" in a for a in alternatives):
            raise ValueError(f"{path}:{number}: acceptable outputs are separated by {ALTERNATIVES!r} and none is "
                             f"empty, got {form.expected!r}")
        if len({comparable(a) for a in alternatives}) != len(alternatives):
            raise ValueError(f"{path}:{number}: an acceptable output is listed twice in {form.expected!r}")
        if form.cls in STRICT_CLASSES and len(alternatives) > 1:
            raise ValueError(f"{path}:{number}: a {form.cls!r} form has one acceptable output, got {form.expected!r}")
        forms.append(form)
    if not forms:
        raise ValueError(f"{path}: no forms")
    return forms


def percentile(values: list[float], q: float) -> float:
    """The q-th percentile, linearly interpolated (numpy's default)."""
    ordered = sorted(values)
    position = (len(ordered) - 1) * q / 100
    low = int(position)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (position - low)


#: Sentence punctuation that ends a word ("no, the other one"): not compared, since the project's grammar returns the
#: words the tagger reads, without it. Punctuation inside a word or before a digit ("500,106", "No.500321", "#500104",
#: "4'x8'") is compared.
_END_PUNCTUATION = re.compile(r"[,.;:!?]+(?=\s|$)")


def comparable(text: str) -> str:
    """What is compared: lower case, white space collapsed, sentence punctuation at the end of a word dropped."""
    return " ".join(_END_PUNCTUATION.sub("", text).split()).lower()


def classes_of(forms: list[Form]) -> list[str]:
    """The classes in the order they first appear in the table."""
    return list(dict.fromkeys(f.cls for f in forms))


# --- the candidates ---------------------------------------------------------------------------------------------
def _version(distribution: str) -> str:
    try:
        return importlib.metadata.version(distribution)
    except importlib.metadata.PackageNotFoundError:
        return "?"


def _load_nemo() -> tuple[Callable[[str], str], str]:
    import logging

    from nemo_text_processing.inverse_text_normalization.inverse_normalize import InverseNormalizer

    logging.getLogger("NeMo-text-processing").setLevel(logging.WARNING)
    normaliser = InverseNormalizer(lang="en")
    return (lambda text: normaliser.inverse_normalize(text, verbose=False),
            f"nemo-text-processing {_version('nemo-text-processing')} (pynini {_version('pynini')}), "
            '`InverseNormalizer(lang="en").inverse_normalize(text, verbose=False)`')


def _load_number_parser() -> tuple[Callable[[str], str], str]:
    from number_parser import parse

    return parse, f"number-parser {_version('number-parser')}, `number_parser.parse(text)`"


def _load_numerizer() -> tuple[Callable[[str], str], str]:
    from numerizer import numerize

    return numerize, f"numerizer {_version('numerizer')}, `numerizer.numerize(text)`"


def _load_project() -> tuple[Callable[[str], str], str]:
    from drywall_lab.nlu.normalise import normalise_text

    return normalise_text, "the project's grammar, `drywall_lab.nlu.normalise.normalise_text(text)`"


def _load_identity() -> tuple[Callable[[str], str], str]:
    return (lambda text: text), "baseline: the text unchanged (not a candidate)"


#: name -> (what to install, loader); the order of the results file.
CANDIDATES: dict[str, tuple[str, Callable[[], tuple[Callable[[str], str], str]]]] = {
    "project": ("drywall_lab.nlu.normalise (this repository)", _load_project),
    "nemo": ("nemo-text-processing", _load_nemo),
    "number_parser": ("number-parser", _load_number_parser),
    "numerizer": ("numerizer", _load_numerizer),
    BASELINE: ("nothing", _load_identity),
}
#: The libraries (name -> the module they are imported as): the recorded results need every one of them.
LIBRARIES = {"nemo": "nemo_text_processing", "number_parser": "number_parser", "numerizer": "numerizer"}
#: The libraries' distributions, as ``environment.txt`` would list them.
DISTRIBUTIONS = {"nemo": "nemo-text-processing", "number_parser": "number-parser", "numerizer": "numerizer"}


def missing_libraries() -> list[str]:
    """The libraries this environment cannot import (found without importing them)."""
    return [name for name, module in LIBRARIES.items() if importlib.util.find_spec(module) is None]


@dataclass
class Outcome:
    """One candidate on the table: its outputs and times, or why it did not run."""

    name: str
    description: str = ""
    missing: str | None = None  #: why it could not be loaded; None when it ran
    load_s: float = float("nan")
    outputs: list[str] = field(default_factory=list)
    errors: int = 0  #: forms on which it raised
    times_s: list[float] = field(default_factory=list)  #: every timed call, seconds

    def median_s(self) -> float:
        return statistics.median(self.times_s)

    def p95_s(self) -> float:
        return percentile(self.times_s, 95)

    def correct(self, forms: list[Form]) -> list[bool]:
        return [f.accepts(out) for out, f in zip(self.outputs, forms)]

    def accuracy(self, forms: list[Form], cls: str | None = None) -> tuple[int, int]:
        """(correct, total) over the table or one class."""
        hits = [ok for ok, f in zip(self.correct(forms), forms) if cls is None or f.cls == cls]
        return sum(hits), len(hits)


def _call(function: Callable[[str], str], text: str) -> tuple[str, bool]:
    try:
        return str(function(text)), False
    except Exception as error:  # a library that fails on a form gets it wrong, and the run goes on
        return f"<error: {type(error).__name__}: {error}>", True


def run_candidate(name: str, forms: list[Form], repeats: int) -> Outcome:
    """Load one candidate and run it on every form ``repeats`` times."""
    install, loader = CANDIDATES[name]
    outcome = Outcome(name)
    started = time.perf_counter()
    try:
        function, outcome.description = loader()
    except ImportError as error:
        outcome.missing = (f"not importable ({type(error).__name__}: {error})" if name == "project"
                           else f"not installed in this environment (`pip install {install}`; {type(error).__name__}: {error})")
        return outcome
    outcome.load_s = time.perf_counter() - started
    _call(function, forms[0].spoken)  # warm-up
    for r in range(repeats):
        for form in forms:
            t0 = time.perf_counter()
            output, failed = _call(function, form.spoken)
            outcome.times_s.append(time.perf_counter() - t0)
            if r == 0:
                outcome.outputs.append(output)
                outcome.errors += failed
    return outcome


# --- the results file -------------------------------------------------------------------------------------------
def _percent(hits: int, total: int) -> str:
    return f"{100 * hits / total:.1f}% ({hits}/{total})" if total else "-"


def _ms(seconds: float) -> str:
    return f"{1e3 * seconds:.3f}"


def _cell(text: str) -> str:
    return "`" + text.replace("|", "\\|").replace("`", "'") + "`"


def _expected_cell(form: Form) -> str:
    return " or ".join(_cell(a) for a in form.alternatives)


def _requirement_names(path: Path | None = None) -> set[str]:
    """The distributions ``environment.txt`` lists (names normalised: lower case, ``-`` for ``_`` and ``.``)."""
    path = ROOT / "environment.txt" if path is None else path
    names: set[str] = set()
    if path.exists():
        for line in path.read_text(encoding="utf-8").splitlines():
            name = re.match(r"[A-Za-z0-9][A-Za-z0-9._-]*", line.split("#")[0].strip())
            if name:
                names.add(re.sub(r"[-_.]+", "-", name.group(0)).lower())
    return names


def _imported_by_project(module: str) -> bool:
    """Whether any module of ``drywall_lab/`` imports ``module``."""
    statement = re.compile(rf"^\s*(?:import|from)\s+{re.escape(module)}\b", re.M)
    return any(statement.search(p.read_text(encoding="utf-8", errors="replace"))
               for p in (ROOT / "drywall_lab").rglob("*.py"))


def choice_lines(outcomes: list[Outcome], forms: list[Form]) -> list[str]:
    """The "Choice" paragraph, computed from the figures: the most accurate candidate overall; each class's best
    candidates, and whether leaving the text unchanged does as well there; what the project uses; and, for every
    class a library does better on than the project's grammar, the forms it gets that the grammar misses and what
    speaks against using it (the forms that must not change it changes, its cost)."""
    ran = [o for o in outcomes if o.missing is None and o.name != BASELINE]
    baseline = next((o for o in outcomes if o.name == BASELINE and o.missing is None), None)
    if not ran:
        return ["No candidate ran: nothing to choose."]
    # Ties go to the project's grammar (no dependency), then to the faster one.
    order = {name: i for i, name in enumerate(CANDIDATES)}

    def rank(o: Outcome) -> tuple:
        return (-o.accuracy(forms)[0], o.name != "project", o.median_s(), order[o.name])

    best = min(ran, key=rank)
    hits, total = best.accuracy(forms)
    lines = [f"**{best.name}** is the most accurate candidate on the table: {_percent(hits, total)} right, "
             f"median {_ms(best.median_s())} ms a form after a load of {best.load_s:.2f} s."]
    if baseline is not None:
        base_hits = baseline.accuracy(forms)[0]
        no_better = [o for o in ran if o.accuracy(forms)[0] <= base_hits]
        if no_better:
            lines.append(f"Leaving the text unchanged scores {_percent(*baseline.accuracy(forms))}: "
                         + ", ".join(f"{o.name} ({_percent(*o.accuracy(forms))})" for o in no_better)
                         + f" {'does' if len(no_better) == 1 else 'do'} no better on the table as a whole.")
    project = next((o for o in ran if o.name == "project"), None)
    if project is None:
        missing = next(o.missing for o in outcomes if o.name == "project")
        lines.append(f"The project's grammar did not run here ({missing}); this choice is among the libraries only, "
                     "and the script is to be run again once `normalise_text` exists.")
    lines += ["", "Per class, the best candidates:", ""]
    for cls in classes_of(forms):
        top = max(o.accuracy(forms, cls)[0] for o in ran)
        leaders = [o for o in ran if o.accuracy(forms, cls)[0] == top]
        n = leaders[0].accuracy(forms, cls)[1]
        names = ", ".join(o.name for o in leaders)
        note = ""
        if baseline is not None and baseline.accuracy(forms, cls)[0] >= top:
            note = (f"; leaving the text unchanged does as well ({_percent(*baseline.accuracy(forms, cls))}), so no "
                    "normaliser is needed for this class")
            if any(len(f.alternatives) > 1 for f in forms if f.cls == cls):
                note += (": the table accepts its forms as said, since the tagger and the IM read them, and a "
                         "candidate that writes digits there is not wrong, just not needed")
        if best.name not in {o.name for o in leaders}:
            lines.append(f"- `{cls}`: {names} {'tie' if len(leaders) > 1 else 'wins'} with {_percent(top, n)} "
                         f"against {best.name}'s {_percent(*best.accuracy(forms, cls))}{note}.")
        elif len(leaders) > 1:
            lines.append(f"- `{cls}`: {names} tie with {_percent(top, n)}{note}.")
        else:
            lines.append(f"- `{cls}`: {best.name} alone is best with {_percent(top, n)}{note}.")
    libraries = [o for o in ran if o.name != "project"]
    if project is None:
        return lines
    lines.append("")
    listed = _requirement_names()
    used = [o.name for o in libraries if _imported_by_project(LIBRARIES[o.name])]
    in_requirements = [o.name for o in libraries if DISTRIBUTIONS[o.name] in listed]
    uses = ("The project normalises with its own grammar (`drywall_lab.nlu.normalise`); "
            + (f"`drywall_lab/` imports {', '.join(used)}" if used else "`drywall_lab/` imports none of the libraries")
            + (f", and `environment.txt` lists {', '.join(in_requirements)}." if in_requirements
               else ", and `environment.txt` lists none of them."))
    wrong = [f for f, ok in zip(forms, project.correct(forms)) if not ok]
    if wrong:
        by_class = {cls: sum(f.cls == cls for f in wrong) for cls in classes_of(forms)}
        uses += (f" The grammar is still wrong on {len(wrong)} of {len(forms)} forms ("
                 + ", ".join(f"`{cls}` {k}" for cls, k in by_class.items() if k) + "; listed under project below).")
    else:
        uses += " The grammar gets every form of the table right."
    lines.append(uses)
    if not libraries:
        return lines
    lines.append("")
    beaten = {cls: [o for o in libraries if o.accuracy(forms, cls)[0] > project.accuracy(forms, cls)[0]]
              for cls in classes_of(forms)}
    beaten = {cls: better for cls, better in beaten.items() if better}
    if not beaten:
        lines.append("No library does better than the project's grammar on any class, so the project uses none and "
                     "takes on no dependency.")
        return lines
    lines.append("A library does better than the project's grammar on "
                 + ", ".join(f"`{cls}`" for cls in beaten) + ":")
    lines.append("")
    project_right = project.correct(forms)
    for cls, better in beaten.items():
        for o in better:
            right = o.correct(forms)
            gained = [(f, out) for f, out, ok, mine in zip(forms, o.outputs, right, project_right)
                      if f.cls == cls and ok and not mine]
            lost = sum(1 for f, ok, mine in zip(forms, right, project_right) if f.cls == cls and mine and not ok)
            text = (f"- `{cls}`: {o.name} {_percent(*o.accuracy(forms, cls))} against the grammar's "
                    f"{_percent(*project.accuracy(forms, cls))}; it gets {len(gained)} form(s) the grammar misses ("
                    + "; ".join(f"{_cell(f.spoken)} -> {_cell(out)}" for f, out in gained) + ")"
                    + (f" and misses {lost} the grammar gets" if lost else "") + ". ")
            keep_hits, keep_total = o.accuracy(forms, "keep")  # (0, 0) for a table without the class
            if o.name in used:
                text += "`drywall_lab/` imports it."
            elif keep_total and keep_hits < keep_total:
                text += (f"The project does not use it: a library rewrites the whole text, not one class, and "
                         f"{o.name} changes {keep_total - keep_hits} of the {keep_total} forms that must not change "
                         f"(`keep` {_percent(keep_hits, keep_total)}).")
            else:
                text += (f"The project does not use it; nothing on this table speaks against it but its cost: load "
                         f"{o.load_s:.2f} s and median {_ms(o.median_s())} ms a form against the grammar's "
                         f"{project.load_s:.2f} s and {_ms(project.median_s())} ms, and a dependency.")
            lines.append(text)
    return lines


def render(outcomes: list[Outcome], forms: list[Form], argv: list[str], repeats: int, quick: bool,
           wall_s: float) -> list[str]:
    from drywall_lab.machine import describe_machine

    machine = describe_machine()
    classes = classes_of(forms)
    lines = ["# Inverse text normalisers on the site's forms: results", "",
             f"Written by `{command_line('normalisers.py', argv)}` (repository root, Python `{sys.executable}`), "
             f"{machine.date}; {len(forms)} forms of `{TABLE.relative_to(ROOT)}`, {repeats} pass(es), {wall_s:.1f} s "
             "in all (loading included)."]
    if quick:
        lines += ["", "**`--quick`: a check that the script works; these figures mean nothing.**"]
    lines += ["", "## Machine", "", *machine.markdown_lines(), f"- processor (platform.processor()): "
              f"{platform.processor() or 'not reported'}", f"- cores (os.cpu_count()): {os.cpu_count()}", "",
              "## Summary", "",
              "Exact match of the whole form with one of the acceptable outputs in `expected` (separated by "
              "` || `: a count, an ordinal or a size said in words may stay as said or be written in digits; the "
              "forms that must not change have one), after lower-casing, collapsing white space and dropping "
              "sentence punctuation at the end of a word. "
              "Times: wall time of one call on one form after loading (median and p95 over every call), "
              "and of importing and building the candidate (load).", "",
              "| candidate | overall | " + " | ".join(classes) + " | median ms | p95 ms | load s | raised |",
              "|---|---|" + "---|" * len(classes) + "---|---|---|---|"]
    for o in outcomes:
        if o.missing:
            lines.append(f"| {o.name} | {o.missing} |" + " |" * (len(classes) + 4))
            continue
        per_class = " | ".join(_percent(*o.accuracy(forms, c)) for c in classes)
        lines.append(f"| {o.name} | {_percent(*o.accuracy(forms))} | {per_class} | "
                     f"{_ms(o.median_s())} | {_ms(o.p95_s())} | "
                     f"{o.load_s:.3f} | {o.errors} |")
    lines += ["", "## Choice", "", *choice_lines(outcomes, forms)]
    for o in outcomes:
        lines += ["", f"## {o.name}", ""]
        if o.missing:
            lines += [f"{CANDIDATES[o.name][0]}: {o.missing}."]
            continue
        lines += [f"{o.description}.", "", f"Load {o.load_s:.3f} s; per form median {_ms(o.median_s())} ms, "
                  f"p95 {_ms(o.p95_s())} ms, max {_ms(max(o.times_s))} ms; "
                  f"raised on {o.errors} form(s).", "", "| class | forms | exact | accuracy |", "|---|---|---|---|"]
        for c in classes:
            hits, total = o.accuracy(forms, c)
            lines.append(f"| {c} | {total} | {hits} | {100 * hits / total:.1f}% |")
        hits, total = o.accuracy(forms)
        lines.append(f"| **all** | {total} | {hits} | {100 * hits / total:.1f}% |")
        wrong = [(f, out) for f, out, ok in zip(forms, o.outputs, o.correct(forms)) if not ok]
        if wrong and o.name != BASELINE:
            lines += ["", f"<details><summary>{len(wrong)} form(s) wrong</summary>", "",
                      "| class | spoken | expected | output |", "|---|---|---|---|"]
            lines += [f"| {f.cls} | {_cell(f.spoken)} | {_expected_cell(f)} | {_cell(out)} |" for f, out in wrong]
            lines += ["", "</details>"]
    lines += ["", "## How to re-run", "",
              "The libraries are not in `environment.txt`; the recorded figures come from a scratch environment with "
              "all of them and this repository installed (outside the repository):", "", "```",
              "python3.11 -m venv /tmp/itn-venv",
              "/tmp/itn-venv/bin/pip install number-parser numerizer nemo-text-processing",
              "/tmp/itn-venv/bin/pip install --no-deps -e .",
              "/tmp/itn-venv/bin/python benchmarks/normalisers.py", "```", "",
              "In the project's `.venv` (`.venv/bin/python benchmarks/normalisers.py --out FILE`) only the project's "
              "grammar and the baseline run; the libraries show as not installed.", ""]
    return lines


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--table", type=Path, default=TABLE, help="the forms (default data/normalisation/forms.tsv)")
    parser.add_argument("--repeats", type=int, default=5, help="passes over the table for the times (default 5)")
    parser.add_argument("--candidates", nargs="+", choices=list(CANDIDATES), default=list(CANDIDATES),
                        help="which candidates to run (default all)")
    add_results_options(parser, RESULTS, quick=f"{QUICK['forms_per_class']} forms a class, {QUICK['repeats']} pass")
    args = parser.parse_args(argv)
    out = results_path(parser, args, RESULTS)
    if args.out is None and (missing_libraries() or set(args.candidates) != set(CANDIDATES)):
        parser.error("the recorded results compare every candidate, and "
                     + (f"this environment lacks {', '.join(missing_libraries())}" if missing_libraries()
                        else "--candidates leaves some out")
                     + ": give --out FILE, or run it where all are installed (see 'How to re-run' in "
                       f"{RESULTS.relative_to(ROOT)})")
    forms = read_forms(args.table)
    repeats = args.repeats
    if args.quick:
        forms = [f for f in forms if [g for g in forms if g.cls == f.cls].index(f) < QUICK["forms_per_class"]]
        repeats = QUICK["repeats"]
    started = time.perf_counter()
    outcomes = [run_candidate(name, forms, repeats) for name in args.candidates]
    wall_s = time.perf_counter() - started
    write_results_file(out, render(outcomes, forms, argv, repeats, args.quick, wall_s))
    for o in outcomes:
        if o.missing:
            print(f"{o.name}: {o.missing}")
        else:
            hits, total = o.accuracy(forms)
            print(f"{o.name}: accuracy={hits / total:.3f} ({hits}/{total}) median_ms={1e3 * o.median_s():.3f} "
                  f"p95_ms={1e3 * o.p95_s():.3f} load_s={o.load_s:.3f}")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
