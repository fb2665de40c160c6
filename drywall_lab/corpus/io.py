"""Reading and writing the corpus: JSON lines, CoNLL, and a ``datasets.DatasetDict``."""
from __future__ import annotations

import codecs
import json
import re
from pathlib import Path
from typing import Callable, Iterable, Mapping

from drywall_lab.corpus.tags import COREF_TAGS, TAGS
from drywall_lab.site import DATA_DIR

CORPUS_DIR = DATA_DIR / "corpus"
SPLITS = ("train", "validation", "test", "novel")

#: The marks of Chinese, Japanese, Arabic-script and Indic text that close a word ("，", "。", "،", "।") and that open one.
MARKS_AFTER = "，、。；：！？）」』】،؛؟।"
MARKS_BEFORE = "（「『【"
_EDGE_PUNCTUATION = re.compile(rf"^[\"'(\[{MARKS_BEFORE}]+|[.,?!;:\"')\]{MARKS_AFTER}]+$")

#: Characters of scripts written without spaces between words: Chinese characters and Japanese kana. A run of them is
#: one chunk of text that holds several words (``drywall_lab.nlu.normalise.split_unspaced`` finds them).
UNSPACED = re.compile(r"[\u3040-\u30ff\u31f0-\u31ff\u3400-\u4dbf\u4e00-\u9fff\uf900-\ufaff\uff66-\uff9f]")


def unspaced(char: str) -> bool:
    """Whether ``char`` belongs to a script written without spaces between words ("板": yes; "b", "5", "ы": no)."""
    return bool(UNSPACED.fullmatch(char))


def tokenize(text: str) -> list[str]:
    """Split an instruction into words the way the corpus does.

    Words are separated by white space; punctuation at a word's edges is dropped,
    while hyphens and inner apostrophes stay ("full-size", "stud's").

    >>> tokenize("Pick up the full-size drywall, and put it on stud 500107.")
    ['Pick', 'up', 'the', 'full-size', 'drywall', 'and', 'put', 'it', 'on', 'stud', '500107']
    """
    words = []
    for piece in text.split():
        word = _EDGE_PUNCTUATION.sub("", piece)
        word = _EDGE_PUNCTUATION.sub("", word)
        if word:
            words.append(word)
    return words


def read_jsonl(path: Path | str, check: Callable[[object, str], dict] | None = None) -> list[dict]:
    """One JSON object a line (blank lines skipped); a ``ValueError`` naming the file and line of any problem.

    The file is UTF-8, with or without a byte-order mark at its start. Each line is decoded
    on its own, so a byte that is not UTF-8 is reported with its line. ``check(value, where)``
    turns each line's value into a row or raises a ``ValueError`` starting with ``where``
    (``"FILE, line N"``); without it, every line must be a JSON object.
    """
    path = Path(path)
    data = path.read_bytes()
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8):]
    rows = []
    for number, raw in enumerate(data.split(b"\n"), start=1):
        where = f"{path}, line {number}"
        try:
            line = raw.decode("utf-8")
        except UnicodeDecodeError as e:
            raise ValueError(f"{where}: not valid UTF-8 text (byte 0x{raw[e.start]:02x} at position {e.start + 1} "
                             f"of the line: {e.reason})") from None
        if not line.strip(" \t\r"):  # JSON's white space
            continue
        try:
            value = json.loads(line)
        except json.JSONDecodeError as e:
            reason = ("a byte-order mark is allowed only at the start of the file" if line.startswith("\ufeff")
                      else f"{e.msg} at position {e.colno}")
            raise ValueError(f"{where}: not a JSON object ({reason})") from None
        except RecursionError:
            raise ValueError(f"{where}: not a JSON object (nested too deeply)") from None
        except ValueError as e:  # e.g. an integer with more digits than Python converts
            raise ValueError(f"{where}: not a JSON object ({e})") from None
        if check is not None:
            rows.append(check(value, where))
        elif isinstance(value, dict):
            rows.append(value)
        else:
            raise ValueError(f"{where}: not a JSON object (a JSON {type(value).__name__} value)")
    return rows


def write_jsonl(rows: Iterable[Mapping], path: Path | str) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", encoding="utf-8") as f:
        for row in rows:
            f.write(json.dumps(row, ensure_ascii=False) + "\n")
    return path


def read_split(split: str, corpus_dir: Path | str | None = None) -> list[dict]:
    """The rows of one split as plain dicts."""
    if split not in SPLITS:
        raise ValueError(f"unknown split {split!r}; the corpus has {', '.join(SPLITS)}")
    return read_jsonl(Path(corpus_dir or CORPUS_DIR) / f"{split}.jsonl")


def read_corpus(corpus_dir: Path | str | None = None, splits: Iterable[str] = SPLITS) -> dict[str, list[dict]]:
    return {s: read_split(s, corpus_dir) for s in splits}


# --- CoNLL ------------------------------------------------------------------------------
_CONLL_META = ("text", "n_sentences", "context", "meaning", "expected")


def to_conll(rows: Iterable[Mapping], path: Path | str | None = None) -> str:
    """CoNLL text: ``word<TAB>tag<TAB>coref_tag`` a line, a blank line between instructions.

    Each instruction starts with ``# id = ...`` and ``# key = json`` comment lines so that
    ``from_conll`` gives back exactly what was written.
    """
    blocks = []
    for row in rows:
        lines = [f"# id = {row['id']}"]
        lines += [f"# {k} = {json.dumps(row[k], ensure_ascii=False)}" for k in _CONLL_META if k in row]
        coref = row.get("coref_tags") or row["tags"]
        lines += [f"{w}\t{t}\t{c}" for w, t, c in zip(row["words"], row["tags"], coref)]
        blocks.append("\n".join(lines))
    text = "\n\n".join(blocks) + "\n"
    if path is not None:
        Path(path).write_text(text, encoding="utf-8")
    return text


def from_conll(source: str | Path) -> list[dict]:
    """Read CoNLL written by ``to_conll`` or by hand (``word<TAB>tag`` lines are enough).

    ``source`` is a path or the CoNLL text itself. Unknown tags raise a ValueError
    that names the line.
    """
    text = Path(source).read_text(encoding="utf-8") if isinstance(source, Path) or (
        "\n" not in str(source) and Path(str(source)).exists()) else str(source)
    rows: list[dict] = []
    current: dict | None = None

    def finish():
        if current is not None and current["words"]:
            if all(c is None for c in current["coref_tags"]):
                del current["coref_tags"]
            rows.append(current)

    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.rstrip("\n")
        if not line.strip():
            finish()
            current = None
            continue
        if current is None:
            current = {"id": f"conll-{len(rows):04d}", "words": [], "tags": [], "coref_tags": []}
        if line.startswith("# "):
            key, _, value = line[2:].partition(" = ")
            current[key.strip()] = value if key.strip() == "id" else json.loads(value)
            continue
        parts = line.split("\t") if "\t" in line else line.split()
        if len(parts) < 2:
            raise ValueError(f"line {number}: expected 'word<TAB>tag', got {line!r}")
        word, tag = parts[0], parts[1]
        if tag not in TAGS:
            raise ValueError(f"line {number}: unknown tag {tag!r} for {word!r}; tags are {', '.join(TAGS)}")
        coref = parts[2] if len(parts) > 2 else None
        if coref is not None and coref not in COREF_TAGS:
            raise ValueError(f"line {number}: unknown co-reference tag {coref!r} for {word!r}")
        current["words"].append(word)
        current["tags"].append(tag)
        current["coref_tags"].append(coref)
    finish()
    return rows


# --- datasets ---------------------------------------------------------------------------
def corpus_features():
    """The ``datasets.Features`` of a corpus split: tags as ``ClassLabel``s."""
    from datasets import ClassLabel, Features, List, Value

    ref_target = {k: Value("string") for k in ("kind", "panel_id", "stack", "direction", "anchor")}
    ref_target.update(size=List(Value("int32")), length_first=Value("bool"), count=Value("int32"))
    ref_stud = {k: Value("string") for k in ("kind", "stud_id", "name", "side", "direction", "anchor")}
    ref_stud.update(nth=Value("int32"), count=Value("int32"))
    command = {k: Value("string") for k in ("drywall_id", "stud_id", "placement")}
    return Features(
        {
            "id": Value("string"),
            "text": Value("string"),
            "words": List(Value("string")),
            "tags": List(ClassLabel(names=list(TAGS))),
            "coref_tags": List(ClassLabel(names=list(COREF_TAGS))),
            "n_sentences": Value("int32"),
            "context": {"episode": Value("string"), "step": Value("int32"), "history": List(command)},
            "meaning": {"target": ref_target, "stud": ref_stud, "placement": Value("string")},
            "expected": {**command, "refusal": Value("string")},
        }
    )


def load_corpus(corpus_dir: Path | str | None = None, splits: Iterable[str] = SPLITS):
    """The corpus as a ``datasets.DatasetDict`` (train, validation, test, novel).

    Tags are ``ClassLabel`` features: ``ds["train"].features["tags"].feature.names``
    gives the 13 names, and ``int2str`` turns ids back into tags.
    """
    from datasets import Dataset, DatasetDict

    features = corpus_features()
    out = {}
    for split, rows in read_corpus(corpus_dir, splits).items():
        out[split] = Dataset.from_list([_fill(r) for r in rows], features=features)
    return DatasetDict(out)


def _fill(row: Mapping) -> dict:
    """Every struct field present (missing ones None), as ``datasets`` wants."""
    row = dict(row)
    meaning = row.get("meaning") or {}
    target = dict.fromkeys(("kind", "panel_id", "stack", "direction", "anchor", "size", "length_first", "count"))
    target.update(meaning.get("target", {}))
    stud = dict.fromkeys(("kind", "stud_id", "name", "side", "direction", "anchor", "nth", "count"))
    stud.update(meaning.get("stud", {}))
    row["meaning"] = {"target": target, "stud": stud, "placement": meaning.get("placement")}
    return row
