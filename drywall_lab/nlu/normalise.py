"""The front end before tagging: the worker's words, as typed or spoken, to the words the tagger reads (issue 29).

People say and type the same instruction in many surface forms: an id read out digit by digit ("five oh oh one oh
eight", "five double-oh one one two", "five hundred one-oh-eight") or split ("500 104", "500-104"), a size in the
plural ("one of the 2x8s"), a board's sides in metric ("1200 x 2400", "600 mm wide", "twelve hundred by twenty-four
hundred": the feet they stand for), the site's written shorthand ("CL", "btm", "pnl", "w/", "stud#", fields
separated by ``|`` or ``->``), spoken disfluency (fillers, stutters, a false start broken off with a dash and
repaired: "the four by- no, the two by eight"; a value taken back by another of its kind: "stud 500101, er, 500100,
sorry", also late, after a reason or the rest of its clause: "on 500111... nah that'd hang past the end, 500110"),
what comes with a message copied in (a chat message's header, an e-mail's subject line, quoted lines and sign-off,
the speakers' labels of a conversation, where the next speaker may overrule a value: "MIKE: ... on 500104. DAVE:
nah, 500103"), an id with a case ending ("500104'e"), a stud written as a sum as a program has it ("stud=prev+2",
"500104-1"), a compound typed with hyphens ("left-line", "bottom-row"), text in a script written without spaces,
cut into words against the lexicon ("竖着装在500106上"), and words of another language or
dialect a crew mixes into English (Spanish, German, French, Portuguese, Polish, West African Pidgin, Jamaican
Creole, spoken English dialects: "la pila de la izquierda", "cuatro por ocho", "der mittlere Stapel", "stand am for
stud", "that'n": ``data/lexicon/code_switch.tsv``). The paper's tagger (Sec. 3.1) learns surface forms from its
corpus; a form it never met is a guess. This module reads every such form into one written form first, for training
and prediction alike (``drywall_lab.corpus.field_generator`` writes its rows through it), so that a new voice
reaches the tagger in words it knows.

It is a small grammar of the project's own, not a general inverse text normaliser: the comparison on a table of
site forms (``benchmarks/normalisers.py``, ``benchmarks/results/normalisers.md``) found that the general
libraries do not read ids said digit by digit, which is most of what this site needs. Cardinals and ordinals
said as single words ("two studs over", "the third pile") are left as said: the tagger and the IM read both
forms, and rewriting them would turn the pronoun "one" into a count.

Every step is a small pure function on a list of ``Piece`` (a word and the worker's words it comes from), so
that ``Normalised`` keeps an alignment to the worker's own words: ``run`` reports the worker's words with their
tags (``tags_of_said``), and the trace lists what was normalised (``changes``).
"""
from __future__ import annotations

import csv
import itertools
import re
import unicodedata
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path
from typing import Callable, Iterable, Sequence

from drywall_lab.corpus.io import MARKS_AFTER, MARKS_BEFORE, UNSPACED, tokenize, unspaced
from drywall_lab.im.trace import TraceStep
from drywall_lab.site import DATA_DIR

LEXICON_PATH = DATA_DIR / "lexicon" / "abbreviations.tsv"
CODE_SWITCH_PATH = DATA_DIR / "lexicon" / "code_switch.tsv"

#: Sounds and phrases that carry nothing in an instruction (spoken disfluency).
FILLERS: frozenset[tuple[str, ...]] = frozenset({
    ("um",), ("umm",), ("uh",), ("uhh",), ("uhm",), ("er",), ("erm",), ("hmm",), ("ah",), ("eh",),
    ("you", "know"), ("like,",), ("i", "think"), ("i", "guess"), ("kinda",), ("sorta",),
})
#: Words that start a repair after a broken-off word ("the four by- no, the two by eight").
REPAIR_CUES: tuple[tuple[str, ...], ...] = (("no",), ("nah",), ("nope",), ("sorry",), ("i", "mean"), ("wait",),
                                             ("make", "that"), ("rather",), ("scratch", "that"))
#: How far back a repair may start again: the words said just before the break.
REPAIR_REACH = 4
DIGIT_WORDS: dict[str, str] = {"zero": "0", "oh": "0", "o": "0", "nought": "0", "one": "1", "two": "2", "three": "3",
                               "four": "4", "five": "5", "six": "6", "seven": "7", "eight": "8", "nine": "9"}
TEEN_WORDS: dict[str, str] = {"ten": "10", "eleven": "11", "twelve": "12", "thirteen": "13", "fourteen": "14",
                              "fifteen": "15", "sixteen": "16", "seventeen": "17", "eighteen": "18", "nineteen": "19"}
TENS_WORDS: dict[str, str] = {"twenty": "2", "thirty": "3", "forty": "4", "fifty": "5", "sixty": "6", "seventy": "7",
                              "eighty": "8", "ninety": "9"}
REPEATS: dict[str, int] = {"double": 2, "triple": 3}
#: Every word of a number (a compound with one is a size or a count: "four-by-six", "eight-foot", "twenty-two").
_NUMBER_WORDS = frozenset({*DIGIT_WORDS, *TEEN_WORDS, *TENS_WORDS, *REPEATS, "hundred", "thousand", "by"})
#: The site's ids are six digits starting 500 (spec section 1: studs 5001xx, panels 5003xx); an unknown one is still
#: read, to be refused by the IM as unknown.
ID_PATTERN = re.compile(r"^500\d{3}$")
_DIGITS = re.compile(r"^\d+$")
_SPLIT_ID = re.compile(r"^(\d{3})[-–.,](\d{3})$")
_MARKED_ID = re.compile(r"^(?:#|no\.?|nr\.?|num\.?)(5\d{5})$", re.I)
#: An id with a case ending, as languages with cases write one ("500104'e", "500104-го", "500104:een"), or with a
#: Korean particle written on it ("500104에", "500104번": Hangul, its syllables taken apart by ``fold``); not the
#: English possessive ("500100's covered": the stud spoken of, not named for this step).
_CASE_ENDING_ID = re.compile(r"^(5\d{5})(?:['’:-](?!s$)[^\W\d_]{1,4}|[\u1100-\u11ff]{2,12})$")
_BROKEN_OFF = re.compile(r"[\w'][-–—]+$")
_PAUSE = re.compile(r"\w[,;，、；،؛]+$")
_STOP = re.compile(r"\w[.!?…。！？।؟]+$")
#: What glues a form's or a program's fields into one word: "|", arrows, a colon before text, "=", brackets, "_", a
#: leading "--" ("Stud:500104", "2x8->500106", "place(stud=500104", "centre_line", "--stack").
_FIELD_SEPARATORS = re.compile(r"\s*(?:\||->|=>|→|⇒|—>|:(?=\S)|=|[()\[\]{}]|_|^--)\s*")
_PLURAL_SIZE = re.compile(r"^(.*?(?:\d|one|two|three|four|five|six|seven|eight|nine|ten|twelve)'?)(?:'?s|es)$", re.I)
_SIZE_WORD = re.compile(r"(?:\d|four|two|six|eight)'?\s*(?:x|by|-by-)", re.I)


@dataclass(frozen=True)
class Piece:
    """One word as the tagger will read it, with the indices of the worker's words it comes from."""

    word: str
    said: tuple[int, ...]
    broken_off: bool = False  #: the worker broke off after it ("by-"): a false start or a repair follows
    paused: bool = False  #: a comma or a semicolon after it ("500101, er, 500100, sorry")
    #: how a corpus row tags it, where one worker's word became several with different parts ("prev+2" -> "2 to the
    #: right of the previous stud"): "" its source's tag, "O" none, "anchor" the anchor tag of its source's
    #: relative tag (``St_loc1`` -> ``St_loc2``)
    role: str = ""
    #: (line, cell) of the worker's text it stands in: a new line, a tab, or a comma or semicolon after a word start
    #: another cell (a table pasted from a spreadsheet: ``read_tables``)
    cell: tuple[int, int] = (0, 0)
    #: a colon after it, as typed ("Kev:" in a chat message's header)
    labelled: bool = False
    #: a full stop, an ellipsis, "!" or "?" after it ("500111... nah", "no. Bottom course")
    stopped: bool = False
    #: on a line quoted from an earlier e-mail ("> is the 2x8 in the top row?")
    quoted: bool = False
    #: the first word of another speaker's turn, after a speaker's label was dropped ("MIKE: ... DAVE: nah, ...")
    turn: bool = False


@dataclass(frozen=True)
class Change:
    """One normalisation, for the trace: what kind, the worker's words, what is read instead ("" if dropped)."""

    kind: str
    said: str
    read: str

    def __str__(self) -> str:
        return f"{self.kind}: {self.said!r} -> {self.read!r}" if self.read else f"{self.kind}: {self.said!r} dropped"


@dataclass(frozen=True)
class Normalised:
    """An instruction read by the front end: the worker's words (``said``, as ``corpus.io.tokenize`` splits them),
    the words the tagger and the IM read (``words``) and, for each of those, the worker's words it comes from."""

    said: tuple[str, ...]
    words: tuple[str, ...]
    sources: tuple[tuple[int, ...], ...]
    changes: tuple[Change, ...]
    roles: tuple[str, ...] = ()  #: each word's ``Piece.role`` (none: every word takes its source's tag)

    def tags_of_said(self, tags: Sequence[str]) -> list[str]:
        """The tags of the worker's own words: each takes the first tag other than ``O`` of the words it became
        ("prev+2" -> "2 to the right of the previous stud": ``St_loc1``); a dropped word is ``O``."""
        if len(tags) != len(self.words):
            raise ValueError(f"{len(tags)} tags for {len(self.words)} normalised words")
        out = ["O"] * len(self.said)
        for tag, sources in zip(tags, self.sources):
            for i in sources:
                if out[i] == "O":
                    out[i] = tag
        return out

    def trace_steps(self) -> list[TraceStep]:
        """What the front end changed, as the first steps of an instruction's rule trace (stage ``front end``)."""
        return [TraceStep("front end", f"N {c.kind}", True, conclusion=str(c)) for c in self.changes]

    def tags_of_words(self, said_tags: Sequence[str]) -> list[str]:
        """The tags of the normalised words from the worker's words' tags (a corpus row's gold): each word takes the
        first tag other than ``O`` among its sources, or what its role makes of it (``Piece.role``)."""
        if len(said_tags) != len(self.said):
            raise ValueError(f"{len(said_tags)} tags for {len(self.said)} words")
        tags = [next((said_tags[i] for i in sources if said_tags[i] != "O"), "O") for sources in self.sources]
        for k, role in enumerate(self.roles):
            if role == "O":
                tags[k] = "O"
            elif role == "anchor":
                tags[k] = tags[k].replace("_loc1", "_loc2")
        return tags


# --- the lexicon ----------------------------------------------------------------------------------------
@lru_cache(maxsize=4)
def read_lexicon(path: Path | str = LEXICON_PATH) -> tuple[dict[str, str], dict[str, str]]:
    """The shorthand lexicon (``data/lexicon/abbreviations.tsv``): forms read only as written, and forms read in any
    case (keys lower-cased)."""
    exact: dict[str, str] = {}
    any_case: dict[str, str] = {}
    for number, row in _tsv_entries(path):
        if len(row) != 3 or row[2] not in ("exact", "any"):
            raise ValueError(f"{path}: entry {number} must be FORM<TAB>READING<TAB>exact|any, not {row}")
        form, reading, case = row
        (exact if case == "exact" else any_case)[form if case == "exact" else form.lower()] = reading
    return exact, any_case


def _tsv_entries(path: Path | str) -> list[tuple[int, list[str]]]:
    """A lexicon file's entries, numbered from 1: its tab-separated lines, blank lines and ``#`` comments skipped."""
    with open(path, encoding="utf-8") as f:
        return list(enumerate(csv.reader((line for line in f if line.strip() and not line.startswith("#")),
                                         delimiter="\t"), start=1))


@lru_cache(maxsize=65536)
def fold(word: str) -> str:
    """A word as the code-switch lexicon matches it: lower case, accents dropped ("Perdón" -> "perdon")."""
    return "".join(c for c in unicodedata.normalize("NFD", word.lower()) if unicodedata.category(c) != "Mn")


@lru_cache(maxsize=4)
def read_code_switch(path: Path | str = CODE_SWITCH_PATH) -> tuple[tuple[str, str, str], ...]:
    """The code-switch lexicon (``data/lexicon/code_switch.tsv``): (form, reading, language) as written, a reading
    of "" dropping its form."""
    entries = []
    for number, row in _tsv_entries(path):
        if len(row) != 3 or not all(cell.strip() for cell in row):
            raise ValueError(f"{path}: entry {number} must be FORM<TAB>READING<TAB>LANGUAGE, not {row}")
        form, reading, language = (cell.strip() for cell in row)
        entries.append((form, "" if reading == "-" else reading, language))
    return tuple(entries)


#: Languages whose accents tell words apart (Vietnamese tones: "năm" five, "nằm" lying, "bảy" seven, "bay" to fly):
#: their forms are matched only as written with their accents, never folded.
ACCENTS_TELL_APART = frozenset({"vi", "ja"})


@lru_cache(maxsize=65536)
def as_written(word: str) -> str:
    """A word as a form of a language whose accents tell words apart is matched: lower case, accents kept (composed)."""
    return unicodedata.normalize("NFC", word.lower())


@lru_cache(maxsize=4)
def _code_switch_table(path: Path | str = CODE_SWITCH_PATH) -> dict[tuple[str, ...], tuple[str, ...]]:
    """Each form's key (its words folded, or as written in a language whose accents tell words apart) -> its reading.
    A folded key and a key as written never meet: a folded key holds no accents, and a form as written that has none
    is folded like every other."""
    table: dict[tuple[str, ...], tuple[str, ...]] = {}
    for form, reading, language in read_code_switch(path):
        key = _form_key(form, language)
        if table.get(key, tuple(reading.split())) != tuple(reading.split()):
            raise ValueError(f"{path}: {form!r} is read as {' '.join(table[key])!r} and as {reading!r}")
        table[key] = tuple(reading.split())
    return table


@lru_cache(maxsize=4)
def _lengths_by_start(path: Path | str = CODE_SWITCH_PATH) -> dict[tuple[str, ...], tuple[int, ...]]:
    """Each start of a key of ``_code_switch_table`` (a key of one word starts with that word, a longer one with its
    first two) -> the lengths of the keys that start so: a common word that starts only long forms ("stud", "left")
    is passed over unless the word after it goes on one."""
    out: dict[tuple[str, ...], set[int]] = {}
    for key in _code_switch_table(path):
        out.setdefault(key[:2], set()).add(len(key))
    return {start: tuple(lengths) for start, lengths in out.items()}


def _form_starts(folded: Sequence[str], written: Sequence[str],
                 starts: dict[tuple[str, ...], tuple[int, ...]]) -> dict[int, list[int]]:
    """Where a key of ``_code_switch_table`` may start in the words, folded or as written, and the lengths of the keys
    that may start there, the longest first: a word alone (``zip(words)``: each word as a tuple of one) or two words
    in a row are a start of ``starts`` (``_lengths_by_start``). Empty where no key may start."""
    out: dict[int, set[int]] = {}
    for words in (folded,) if written == folded else (folded, written):  # the same words (no accents) looked up once
        for run in (zip(words), zip(words, words[1:])):
            for i, start in enumerate(run):
                if start in starts:
                    out.setdefault(i, set()).update(starts[start])
    return {i: sorted(lengths, reverse=True) for i, lengths in out.items()}


def _form_key(form: str, language: str) -> tuple[str, ...]:
    if language in ACCENTS_TELL_APART and any(fold(w) != w.lower() for w in form.split()):
        return tuple(as_written(w) for w in form.split())
    return tuple(fold(w) for w in form.split())


# --- steps: each takes and returns a list of pieces, and says what it changed ------------------------------
Step = Callable[[list[Piece], list[Change]], list[Piece]]


def _read_as(words: Sequence[str], said: tuple[int, ...], last: Piece, roles: Sequence[str] = (),
             first: Piece | None = None) -> list[Piece]:
    """The pieces for ``words``, read in place of a span of the worker's words (``said``) whose last piece is
    ``last`` (and first ``first``, if not ``last``): the last word keeps its break and its pause, the first whether
    it starts a speaker's turn; ``roles`` as in ``Piece.role``."""
    end = len(words) - 1
    turn = (first or last).turn
    return [Piece(w, said, last.broken_off and k == end, last.paused and k == end, roles[k] if roles else "",
                  stopped=last.stopped and k == end, turn=turn and k == 0) for k, w in enumerate(words)]


def _text(pieces: Sequence[Piece], said: Sequence[str]) -> str:
    return " ".join(said[i] for p in pieces for i in p.said)


#: Words that make a hyphen-joined word a position said as one ("3rd-from-right", "second-to-last", "one-to-the-left").
POSITION_LINKS = frozenset({"from", "to", "of", "the", "in"})
_ORDINAL = re.compile(r"^\d+(?:st|nd|rd|th)$|^(?:first|second|third|fourth|fifth|sixth|seventh|eighth|ninth|tenth|"
                      r"eleventh|twelfth|last)$", re.I)


def joined_position(word: str) -> list[str] | None:
    """The words of a position typed as one hyphen-joined word ("3rd-from-right" -> 3rd, from, right), or None."""
    parts = word.split("-")
    if len(parts) < 2 or not all(parts):
        return None
    low = [p.lower() for p in parts]
    return parts if POSITION_LINKS.intersection(low) and (any(_ORDINAL.match(p) for p in low)
                                                          or {"left", "right", "end", "last"}.intersection(low)) else None


#: Words that name the field a value fills in a form or a program ("stud=500104", "size=same", "row: top").
FIELD_LABELS = frozenset({"stud", "panel", "sheet", "board", "pile", "stack", "row", "size", "edge", "line", "id",
                          "side", "orient", "orientation", "placement"})


def split_fields(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A form's or a program's fields glued by a separator ("Stud:500104", "2x8->500106", "stud=500104",
    "place(panel", "centre_line") are words apart, and so are the words of a position typed as one with hyphens
    ("3rd-from-right"). A label whose value is one word that says which ("size=same", "row=top", "pile:left") is
    read in the order people say it ("same size", "top row", "left pile"). A separator said alone ("|", "->", "=")
    stays: the IM reads it as punctuation, a boundary between fields."""
    fields = [_field_words(p.word) for p in pieces]
    if all(words is None for words in fields):
        return pieces  # no word glues fields or a position's words
    out: list[Piece] = []
    for p, words in zip(pieces, fields):
        if words is None:
            out.append(p)
            continue
        if words != (p.word,):
            changes.append(Change("separator", p.word, " ".join(words)))
        out += _read_as(words, p.said, p)
    return out


@lru_cache(maxsize=65536)
def _field_words(word: str) -> tuple[str, ...] | None:
    """The words of a word that glues a form's fields or a position's words (``split_fields``), or None where it glues
    none. A pure function of the word, so each word is read once."""
    glued = _FIELD_SEPARATORS.search(word) and any(c.isalnum() for c in word)
    if not glued and joined_position(word) is None:
        return None
    parts = [w for w in _FIELD_SEPARATORS.split(word) if w] if glued else [word]
    k = len(parts) - 2  # the label and its value, the last two parts ("place(size=same")
    if k >= 0 and parts[k].lower() in FIELD_LABELS and parts[k + 1].isalpha() and parts[k + 1].lower() != "id" \
            and parts[k + 1].lower() not in DIGIT_WORDS:
        parts[k:k + 2] = parts[k + 1], parts[k]  # "size=same" -> "same size"
    return tuple(w for part in parts for word in tokenize(part) if any(c.isalnum() for c in word)
                 for w in joined_position(word) or [word])


#: A count added to or taken from a stud written as a sum ("prev+2", "500104-1", "last + 3", "prev stud +5"): the
#: anchor, the sign, the count (at most two digits).
_OFFSET = re.compile(r"^(prev|previous|last|500\d{3})?(?:stud)?([+-])(\d{1,2})$", re.I)
_SIGNED_COUNT = re.compile(r"[+-]\d")
_OFFSET_ANCHORS = {"prev": ("the", "previous", "stud"), "previous": ("the", "previous", "stud"),
                   "last": ("the", "last", "stud")}


def read_offsets(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A stud written as a sum, as a program or a tablet form has it ("stud=prev+2", "500104-1", "prev + 3"), read in
    words: "2 to the right of the previous stud", "1 to the left of 500104". "prev" or "last" may stand apart from the
    sign, with or without "stud" ("prev +2", "prev + 2", "last -1", "prev stud +5"), an id only from "+N" ("500104 +2": "500321 - 1" is more likely a dash
    between fields); a sign with no anchor ("+2") is left as written (counted from what?)."""
    if not _SIGNED_COUNT.search("".join([p.word for p in pieces])):
        return pieces  # a sum's sign is followed by its count, in the words run together as ``_OFFSET`` reads them
    out: list[Piece] = []
    signed = [("+" in p.word or "-" in p.word) for p in pieces]
    i = 0
    while i < len(pieces):
        if not any(signed[i:i + 4]):  # no sign in reach: no sum starts here
            out.append(pieces[i])
            i += 1
            continue
        match, n = None, 0
        for n in (1, 2, 3, 4):  # "prev+2"; "prev" "+2"; "prev" "+" "2"; "prev" "stud" "+" "2"
            match = _OFFSET.match("".join(p.word for p in pieces[i:i + n])) if i + n <= len(pieces) else None
            if match:
                break
        if match and n > 1 and (match.group(2) == "-" or n >= 3) and (match.group(1) or "").isdigit():
            match = None  # "500321 - 1", "500104 + 2" apart: a dash between fields, or an id and a count
        if not match or not match.group(1):
            out.append(pieces[i])
            i += 1
            continue
        anchor, sign, count = match.groups()
        named = _OFFSET_ANCHORS.get(anchor.lower(), (anchor,))
        words = [count, "to", "the", "right" if sign == "+" else "left", "of", *named]
        roles = ["", "", "", "", "O", *("O" if w in ("the", "stud") else "anchor" for w in named)]
        span = pieces[i:i + n]
        changes.append(Change("offset", " ".join(p.word for p in span), " ".join(words)))
        out += _read_as(words, tuple(k for p in span for k in p.said), span[-1], roles, span[0])
        i += n
    return out


#: A lower-case "l" or "r" is a side where a side is due: after these words (a texted "from" too: "2nd frm r") or before
#: these ("2nd from r", "to the l of", "l line"); elsewhere a lower-case "r" is a texted "are".
_BEFORE_SIDE = frozenset({"the", "from", "frm", "fr", "to", "far", "furthest", "of", "on", "studs", "places", "stacks",
                          "piles", "over", "further", "just"})
_AFTER_SIDE = frozenset({"of", "from", "line", "edge", "side", "end", "pile", "stack"})
_SIDES = {"l": "left", "r": "right"}
_ANCHOR_NOUNS = frozenset({"stud", "post", "upright", "pile", "stack", "panel", "sheet"})


def _side_letter(pieces: Sequence[Piece], k: int) -> str | None:
    word = pieces[k].word
    if word not in _SIDES:
        return None
    j = k - 1
    while j >= 0 and (pieces[j].word.lower(),) in FILLERS:
        j -= 1  # "from the erm l": fillers go later (``drop_fillers``)
    before = pieces[j].word.lower() if j >= 0 else ""
    after = pieces[k + 1].word.lower() if k + 1 < len(pieces) else ""
    count = before.isdigit() or before in DIGIT_WORDS or before in TEEN_WORDS  # "2 r of 500103"
    then = pieces[k + 2].word.lower() if k + 2 < len(pieces) else ""
    anchor = after == "the" and (then in _ANCHOR_NOUNS or then.isdigit())  # "r the stud 500109": right of it
    return _SIDES[word] if before in _BEFORE_SIDE or after in _AFTER_SIDE or count or anchor else None


def _count_follows(pieces: Sequence[Piece], k: int) -> bool:
    after = pieces[k + 1].word.lower() if k + 1 < len(pieces) else ""
    return (after.isdigit() and len(after) <= 2) or after in DIGIT_WORDS or after in TEEN_WORDS


def expand_shorthand(pieces: list[Piece], changes: list[Change], lexicon: Path | str = LEXICON_PATH) -> list[Piece]:
    """The site's shorthand read out in full from the lexicon ("CL" -> "centre line", "btm" -> "bottom"); a
    lower-case side letter where a side is due ("to the r of")."""
    exact, any_case = read_lexicon(lexicon)
    words = [p.word for p in pieces]
    if exact.keys().isdisjoint(words) and any_case.keys().isdisjoint(map(str.lower, words)) \
            and _SIDES.keys().isdisjoint(words):
        return pieces  # no word is in the lexicon or a side letter: nothing is read
    out: list[Piece] = []
    for k, p in enumerate(pieces):
        reading = exact.get(p.word, any_case.get(p.word.lower())) or _side_letter(pieces, k)
        if p.word.lower() == "bot" and _count_follows(pieces, k):
            reading = None  # "bot four" is a unit's call sign, not the bottom row
        if reading == "-" and p.word == "no." and not _number_follows(pieces, k):
            out.append(replace(p, word=p.word.rstrip(".:"), stopped=p.word.endswith(".")))  # "no. Bottom course"
            continue
        if reading is None:
            out.append(p)
            continue
        changes.append(Change("shorthand", p.word, "" if reading == "-" else reading))
        if reading != "-":
            out += _read_as(reading.split(), p.said, p)
    return out


def _number_follows(pieces: Sequence[Piece], k: int) -> bool:
    """Whether a number (digits, "#", a digit word) follows piece ``k``: what a label such as "no." introduces."""
    after = pieces[k + 1].word if k + 1 < len(pieces) else ""
    return _count_follows(pieces, k) or after[:1].isdigit() or after.startswith("#")


def translate_code_switch(pieces: list[Piece], changes: list[Change],
                          lexicon: Path | str = CODE_SWITCH_PATH) -> list[Piece]:
    """Words and phrases of another language mixed into an instruction read in English from the code-switch lexicon,
    the longest form first ("la pila de la izquierda" -> "the pile on the left", "cuatro por ocho" -> "four by eight"),
    never across a comma; a filler ("pues") is dropped."""
    table = _code_switch_table(lexicon)
    folded = [fold(p.word) for p in pieces]
    written = [as_written(p.word) for p in pieces]
    lengths = _form_starts(folded, written, _lengths_by_start(lexicon))
    if not lengths:
        return pieces  # no form may start anywhere: nothing to read
    out: list[Piece] = []
    i = 0
    while i < len(pieces):
        key: tuple[str, ...] = ()
        for n in lengths.get(i, ()):
            if n > len(pieces) - i or any(p.paused for p in pieces[i:i + n - 1]):  # never across a comma
                continue
            found = next((k for k in (tuple(written[i:i + n]), tuple(folded[i:i + n])) if k in table), ())
            if found and (n > 1 or folded[i] not in DIGITS_ONLY_IN_A_RUN or _in_foreign_number(folded, i, lexicon)):
                key = found
                break
        if not key:
            out.append(pieces[i])
            i += 1
            continue
        n = len(key)
        span, reading = pieces[i:i + n], table[key]
        changes.append(Change("code switch", " ".join(p.word for p in span), " ".join(reading)))
        out += _read_as(reading, tuple(k for p in span for k in p.said), span[-1], first=span[0])
        i += n
    return out


#: Digit words of the code-switch lexicon that mean something else outside a number ("um": one in Portuguese, a filler
#: in English; "meia": six in a Portuguese number, "half" elsewhere): read as the digit only inside a number said in
#: their language (``_in_foreign_number``).
DIGITS_ONLY_IN_A_RUN = frozenset({"um", "meia"})


@lru_cache(maxsize=4)
def _foreign_digits(lexicon: Path | str = CODE_SWITCH_PATH) -> dict[str, frozenset[str]]:
    """Each folded one-word form of the code-switch lexicon read as a digit, with the languages that say it so."""
    out: dict[str, set[str]] = {}
    for form, reading, language in read_code_switch(lexicon):
        if " " not in form and reading in DIGIT_WORDS:
            out.setdefault(fold(form), set()).add(language)
    return {form: frozenset(languages) for form, languages in out.items()}


def _in_foreign_number(folded: Sequence[str], i: int, lexicon: Path | str = CODE_SWITCH_PATH) -> bool:
    """Whether the word at ``i`` (one of ``DIGITS_ONLY_IN_A_RUN``) is in a run of three or more number words that has
    another digit word of its language ("cinco zero zero um zero meia"; not "five oh oh one um oh three")."""
    digits = _foreign_digits(lexicon)
    languages = digits[folded[i]]

    def number(word: str) -> bool:
        return word in DIGIT_WORDS or word in digits

    start, end = i, i
    while start > 0 and number(folded[start - 1]):
        start -= 1
    while end < len(folded) - 1 and number(folded[end + 1]):
        end += 1
    return end - start >= 2 and any(k != i and folded[k] not in DIGITS_ONLY_IN_A_RUN
                                    and languages & digits.get(folded[k], frozenset()) for k in range(start, end + 1))


@lru_cache(maxsize=16)
def _by_first_word(phrases: tuple[tuple[str, ...], ...] | frozenset) -> dict[str, tuple[tuple[str, ...], ...]]:
    """``phrases`` by their first word, the longest first."""
    out: dict[str, list[tuple[str, ...]]] = {}
    for phrase in sorted(phrases, key=len, reverse=True):
        out.setdefault(phrase[0], []).append(phrase)
    return {word: tuple(group) for word, group in out.items()}


@lru_cache(maxsize=16)
def _phrase_starts(phrases: tuple[tuple[str, ...], ...] | frozenset) -> frozenset[tuple[str, ...]]:
    """How ``phrases`` start: a phrase of one word with that word, a longer one with its first two."""
    return frozenset(phrase[:2] for phrase in phrases)


def _may_start(pieces: Sequence[Piece], phrases: tuple[tuple[str, ...], ...] | frozenset) -> bool:
    """Whether one of ``phrases`` may start anywhere in ``pieces`` (where none may, ``_starts`` finds none): a word
    alone (``zip(low)``: each word as a tuple of one) or two words in a row are how one starts (``_phrase_starts``)."""
    low = [p.word.lower() for p in pieces]
    if _by_first_word(phrases).keys().isdisjoint(low):
        return False  # no word is the first word of one (most texts): no pairs to look up
    starts = _phrase_starts(phrases)
    return not (starts.isdisjoint(zip(low)) and starts.isdisjoint(zip(low, low[1:])))


def _starts(pieces: Sequence[Piece], i: int, phrases: tuple[tuple[str, ...], ...] | frozenset) -> int:
    """The length of the phrase of ``phrases`` that starts at ``i`` (0: none), the longest first."""
    if i >= len(pieces):
        return 0
    for phrase in _by_first_word(phrases).get(pieces[i].word.lower(), ()):
        if tuple(p.word.lower() for p in pieces[i:i + len(phrase)]) == phrase:
            return len(phrase)
    return 0


#: Parts that make a hyphen-joined word one word, not two ("re-hang", "top-most", "square-ish").
_BOUND_PARTS = frozenset({"re", "pre", "un", "non", "most", "ish", "wise", "like"})


@lru_cache(maxsize=1)
def _whole_compounds() -> frozenset[str]:
    """The hyphen-joined words the IM reads whole ("left-hand", "full-size"): those of ``im.words``' word lists."""
    from drywall_lab.im import words as W

    lists = [v for v in vars(W).values() if isinstance(v, (frozenset, set, tuple, list))]
    return frozenset(w.lower() for v in lists for w in v if isinstance(w, str) and "-" in w)


def _lexicon_word(word: str) -> bool:
    """Whether a lexicon reads ``word`` whole: the shorthand ("ctr-line") or the code switch ("mets-la")."""
    exact, any_case = read_lexicon()
    return (word in exact or word.lower() in any_case or (fold(word),) in _code_switch_table()
            or (word.lower(),) in _code_switch_table())


def joined_compound(word: str) -> list[str] | None:
    """The words of a compound typed with hyphens ("left-line", "bottom-row" -> left, line; bottom, row), or None:
    parts of letters only, two or more each, none a number word (a size: "four-by-six", "eight-foot") or a bound
    part ("re-hang", "top-most"), and not a word the IM reads whole ("left-hand", ``_whole_compounds``) or a lexicon
    form ("ctr-line", "mets-la")."""
    parts = word.split("-")
    if len(parts) < 2 or word.lower() in _whole_compounds() or _lexicon_word(word):
        return None
    low = {p.lower() for p in parts}
    if not all(len(p) >= 2 and p.isalpha() for p in parts) or low & _BOUND_PARTS or low & _NUMBER_WORDS:
        return None
    return parts


def split_compounds(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A compound typed with hyphens read as its words, as said apart ("left-line" is the left line, "bottom-row" the
    bottom row: ``joined_compound``), before the lexicons read them ("stud-vert" -> stud, vert -> stud, vertical);
    each word comes from the worker's one word."""
    if "-" not in "".join([p.word for p in pieces]):
        return pieces  # a compound is typed with a hyphen
    out: list[Piece] = []
    for p in pieces:
        parts = joined_compound(p.word)
        if parts is None:
            out.append(p)
            continue
        changes.append(Change("compound", p.word, " ".join(parts)))
        end = len(parts) - 1
        out += [replace(p, word=w, broken_off=p.broken_off and k == end, paused=p.paused and k == end,
                        stopped=p.stopped and k == end, labelled=p.labelled and k == end, turn=p.turn and k == 0)
                for k, w in enumerate(parts)]
    return out


def drop_fillers(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """Fillers ("um", "uh", "you know") are dropped; the word before one is paused after, and a word broken off
    before one stays broken off."""
    if not _may_start(pieces, FILLERS):
        return pieces  # no word starts a filler
    pieces = list(pieces)  # a turn's start moves past a filler dropped: on a copy, the step stays pure
    out: list[Piece] = []
    i = 0
    while i < len(pieces):
        n = _starts(pieces, i, FILLERS)
        if n:
            changes.append(Change("filler", " ".join(p.word for p in pieces[i:i + n]), ""))
            if out:  # a filler is a pause ("500101 er 500100, sorry"); a word broken off before one stays so
                out[-1] = replace(out[-1], broken_off=out[-1].broken_off or pieces[i + n - 1].broken_off, paused=True)
            if pieces[i].turn and i + n < len(pieces):  # "DAVE: uh, 500106": the turn starts after the filler
                pieces[i + n] = replace(pieces[i + n], turn=True)
            i += n
            continue
        out.append(pieces[i])
        i += 1
    return out


# --- numbers --------------------------------------------------------------------------------------------
@lru_cache(maxsize=1)
def radio_digit_readings() -> dict[str, str]:
    """The digits as radio operators say them, each with the digit's word ("fife" -> "five"): the shorthand lexicon's
    forms read as a digit word."""
    return {form: reading for form, reading in read_lexicon()[1].items() if reading in DIGIT_WORDS}


def _radio_digit(word: str) -> str:
    """A digit as radio operators say it read as the digit's word ("fife" -> "five"); any other word as it is."""
    return radio_digit_readings().get(word, word)


@lru_cache(maxsize=65536)
def _number_parts(word: str) -> tuple[str, ...] | None:
    """The parts of a word that belongs to a spoken or split number ("one-oh-eight" -> ("one", "oh", "eight")),
    or None. A pure function of the word, so each word is read once."""
    w = _radio_digit(fold(word))  # "zéro" is "zero", "fife" is "five"
    if _DIGITS.match(w) or w in DIGIT_WORDS or w in TEEN_WORDS or w in TENS_WORDS or w in REPEATS or w == "hundred":
        return (w,)
    marked = _MARKED_ID.match(w) or _CASE_ENDING_ID.match(w)
    if marked:
        return (marked.group(1),)
    split = _SPLIT_ID.match(w)
    if split:
        return split.group(1), split.group(2)
    parts = [_radio_digit(p) for p in w.split("-")]
    if len(parts) > 1 and all(p in DIGIT_WORDS or p in TEEN_WORDS or p in TENS_WORDS or p in REPEATS or _DIGITS.match(p)
                              for p in parts if p):
        return tuple(p for p in parts if p)
    return None


def digits_of(parts: Sequence[str]) -> str | None:
    """The digit string a run of number parts says, read out as ids are ("five double oh one one two" -> "500112",
    "five hundred one oh eight" -> "500108"); None if it says no digit string."""
    out = ""
    repeat = 1
    for k, part in enumerate(parts):
        if part in REPEATS:
            if repeat != 1:
                return None
            repeat = REPEATS[part]
            continue
        if part == "hundred":
            if not out or repeat != 1:
                return None
            out += "00"
            continue
        if part in TENS_WORDS:  # "twenty" is 20; "twenty two" is 22
            nxt = parts[k + 1] if k + 1 < len(parts) else ""
            out += TENS_WORDS[part] + ("" if nxt in DIGIT_WORDS and nxt not in ("oh", "o", "zero") else "0")
            continue
        digits = part if _DIGITS.match(part) else DIGIT_WORDS.get(part, TEEN_WORDS.get(part))
        if digits is None:
            return None
        if repeat != 1:
            if len(digits) != 1:
                return None
            digits *= repeat
            repeat = 1
        if k and parts[k - 1] == "hundred" and out.endswith("00") and len(digits) <= 2 and \
                k + 1 == len(parts) and len(out) + len(digits) < 6:
            out = out[:-len(digits)] + digits  # "five hundred four": 504, a number, not an id
            continue
        out += digits
    return out if repeat == 1 and out else None


def _below_a_hundred(parts: Sequence[str]) -> str | None:
    """The number a one- or two-word run of number parts says below a hundred ("six", "twelve", "twenty two",
    "20"), or None."""
    if len(parts) == 1:
        p = parts[0]
        if p in DIGIT_WORDS and p not in ("oh", "o", "nought"):
            return DIGIT_WORDS[p]
        if p in TEEN_WORDS:
            return TEEN_WORDS[p]
        if p in TENS_WORDS:
            return TENS_WORDS[p] + "0"
        return p if _DIGITS.match(p) and len(p) <= 2 else None
    if len(parts) == 2 and parts[0] in TENS_WORDS and parts[1] in DIGIT_WORDS and DIGIT_WORDS[parts[1]] != "0":
        return TENS_WORDS[parts[0]] + DIGIT_WORDS[parts[1]]
    return None


def hundreds_of(parts: Sequence[str]) -> str | None:
    """The digits of a run said as numbers of hundreds, each of three digits ("five hundred one hundred six" ->
    "500106", "five hundred three hundred twenty" -> "500320"), or None when the run is not such numbers."""
    out = ""
    k = 0
    while k < len(parts):
        lead = DIGIT_WORDS.get(parts[k], parts[k] if _DIGITS.match(parts[k]) and len(parts[k]) == 1 else None)
        if k + 1 >= len(parts) or parts[k + 1] != "hundred" or lead in (None, "0"):
            return None
        end = next((j for j in range(k + 2, len(parts) - 1) if parts[j + 1] == "hundred"), len(parts))
        rest = "0" if end == k + 2 else _below_a_hundred(parts[k + 2:end])
        if rest is None:
            return None
        out += lead + rest.zfill(2)
        k = end
    return out or None


def id_of(parts: Sequence[str]) -> str | None:
    """The id a run of number parts says, read digit by digit (``digits_of``) or as numbers of hundreds
    (``hundreds_of``), or None."""
    for reading in (digits_of(parts), hundreds_of(parts)):
        if reading and ID_PATTERN.match(reading):
            return reading
    return None


def _repaired_id(before: str, repair: Sequence[Piece]) -> tuple[str, int] | None:
    """An id broken off and repaired ("five oh oh one one- no, one one one"): the repair says the id's last digits
    again, starting at a digit said before the break that it repeats (or right after the break). The id and how
    many of ``repair``'s pieces it takes (as many as make an id), or None where no reading gives an id."""
    for k in range(len(repair), 0, -1):
        again = digits_of(_parts(repair[:k])) or ""
        start = 6 - len(again)
        if again and 0 < start <= len(before) and (start == len(before) or before[start] == again[0]) \
                and ID_PATTERN.match(before[:start] + again):
            return before[:start] + again, k
    return None


def _first_id(run: Sequence[str], k: int) -> tuple[int, int] | None:
    """The first stretch of a run of number words from ``k`` on that says an id, as long as it can be: "station two,
    five double-oh three one two" has one in its last five words, "500 320 five hundred one-oh-oh" two."""
    for a in range(k, len(run)):
        for b in range(len(run), a, -1):
            if id_of(_parts_of(run[a:b])):
                return a, b
    return None


@lru_cache(maxsize=65536)
def _ids_in_run(run: tuple[str, ...]) -> tuple[tuple[int, int, str], ...]:
    """The ids a run of number words says, in order: where each starts and ends in the run, and its digits
    (``_first_id``). A pure function of the words, so each run met again ("500104") is read once."""
    ids = []
    k = 0
    while (found := _first_id(run, k)) is not None:
        a, b = found
        ids.append((a, b, id_of(_parts_of(run[a:b])) or ""))
        k = b
    return tuple(ids)


def _parts_of(words: Iterable[str]) -> list[str]:
    """The number parts of words of a number, in order (``_number_parts``)."""
    return [part for word in words for part in _number_parts(word) or ()]


def _parts(run: Sequence[Piece]) -> list[str]:
    return _parts_of(p.word for p in run)


def _number_run(pieces: Sequence[Piece], i: int) -> int:
    """The end of the run of number words starting at ``i`` (a word broken off ends it)."""
    j = i
    while j < len(pieces) and _number_parts(pieces[j].word) is not None:
        j += 1
        if pieces[j - 1].broken_off:
            break
    return j


def _id_piece(run: Sequence[Piece], digits: str, changes: list[Change], also: Sequence[Piece] = ()) -> Piece:
    """One word for an id said in several (``also``: the words of a repair that it covers too)."""
    words = [*run, *also]
    if len(words) > 1 or words[0].word != digits:
        changes.append(Change("id", " ".join(p.word for p in words), digits))
    said = tuple(sorted({s for p in words for s in p.said}))  # a pair read as two digits ("de de": two two) once
    return Piece(digits, said, words[-1].broken_off, words[-1].paused,
                 words[0].role, stopped=words[-1].stopped, turn=words[0].turn)


def read_ids(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """Ids as people say and type them, read as six digits: digit by digit ("five oh oh one oh eight"), with
    "double", "hundred" or a teen ("five oh oh one twelve"), as two numbers of hundreds ("five hundred one hundred
    six"), split ("500 104", "500-104", "#500104"), several in
    one run of number words, and broken off and repaired ("five oh oh one one- no, one one one"). Number words
    that say no id are left as said."""
    out: list[Piece] = []
    i = 0
    while i < len(pieces):
        if _number_parts(pieces[i].word) is None:  # most words start no run of number words
            out.append(pieces[i])
            i += 1
            continue
        j = _number_run(pieces, i)
        run = pieces[i:j]
        k = 0
        for a, b, digits in _ids_in_run(tuple(p.word for p in run)):
            out += run[k:a]
            out.append(_id_piece(run[a:b], digits, changes))
            k = b
        rest = run[k:]
        cue = _starts(pieces, j, REPAIR_CUES) if rest and rest[-1].broken_off and j < len(pieces) else 0
        if cue:  # a repair of the run's broken-off end follows
            end = _number_run(pieces, j + cue)
            for a in range(len(rest)):
                fixed = _repaired_id(digits_of(_parts(rest[a:])) or "", pieces[j + cue:end])
                if fixed:
                    digits, used = fixed
                    out += rest[:a]
                    out.append(_id_piece(rest[a:], digits, changes, pieces[j:j + cue + used]))
                    rest, j = [], j + cue + used
                    break
        out += rest
        i = j
    return out


@dataclass(frozen=True)
class PluralSize:
    """A word that may be a size in the plural: its singular, and whether it says a size by itself."""

    singular: str  #: "2x8s" -> "2x8", "eights" -> "eight"
    says_a_size: bool  #: a side before "x" or "by" ("2x8s", "two-by-eights"), not a side alone ("eights": after "by")


@lru_cache(maxsize=65536)
def _plural_size(word: str) -> PluralSize | None:
    """A word that may be a size in the plural (``singular_sizes``), or None: an id in the plural ("500104s") is
    none. A pure function of the word, so each word is read once."""
    plural = _PLURAL_SIZE.match(word)
    if not plural or ID_PATTERN.match(plural.group(1)):
        return None
    return PluralSize(plural.group(1), bool(_SIZE_WORD.search(word)))


def singular_sizes(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A size in the plural names one panel of that size: "the 2x8s" -> "2x8", "two-by-eights" -> "two-by-eight",
    "four by eights" -> "four by eight"."""
    plurals = [_plural_size(p.word) for p in pieces]
    if all(plural is None for plural in plurals):
        return pieces  # no word may be a size in the plural
    out: list[Piece] = []
    for k, (p, plural) in enumerate(zip(pieces, plurals)):
        if plural and (plural.says_a_size or k > 0 and pieces[k - 1].word.lower() in ("by", "x")):
            changes.append(Change("size", p.word, plural.singular))
            out.append(Piece(plural.singular, p.said, p.broken_off))
        else:
            out.append(p)
    return out


# --- metric sizes -------------------------------------------------------------------------------------------
#: A board's nominal metric sides and the feet they stand for, by unit (1200 x 2400 mm is the metric 4 x 8 sheet;
#: spec section 1 gives the panels in feet, "what people say").
METRIC_SIDES: dict[str, dict[str, str]] = {
    "mm": {"600": "2", "610": "2", "1200": "4", "1220": "4", "1800": "6", "1830": "6", "2400": "8", "2440": "8"},
    "cm": {"60": "2", "61": "2", "120": "4", "122": "4", "180": "6", "183": "6", "240": "8", "244": "8"},
    "m": {"0.6": "2", "0.61": "2", "1.2": "4", "1.22": "4", "1.8": "6", "1.83": "6", "2.4": "8", "2.44": "8"},
}
METRIC_UNITS: dict[str, str] = {
    **dict.fromkeys(("mm", "mil", "mils", "millimetre", "millimetres", "millimeter", "millimeters"), "mm"),
    **dict.fromkeys(("cm", "cms", "centimetre", "centimetres", "centimeter", "centimeters"), "cm"),
    **dict.fromkeys(("m", "metre", "metres", "meter", "meters"), "m"),
}
_WITH_UNIT = re.compile(r"^(\d+(?:[.,]\d+)?)(mm|cm|m)$", re.I)
_METRIC_PAIR = re.compile(r"^(\d+(?:\.\d+)?)[x×*](\d+(?:\.\d+)?)(mm|cm|m)?$", re.I)
_SIDE_WORDS = frozenset({"wide", "long", "high", "tall", "across"})
_THOUSANDS = re.compile(r"\d{1,2},\d{3}")


def _feet(number: str, unit: str | None) -> str | None:
    """The feet a nominal metric side stands for ("1200", "mm" -> "4"); without a unit, millimetres or metres."""
    number = number.replace(",", "") if unit != "m" and _THOUSANDS.fullmatch(number) else number.replace(",", ".")
    units = [unit] if unit else ["mm", "m"]
    return next((METRIC_SIDES[u][number] for u in units if number in METRIC_SIDES[u]), None)


@lru_cache(maxsize=65536)
def _may_be_metric(word: str) -> bool:
    """Whether ``metric_sizes`` may read the (lower-case) word written in digits as a side: a side with its unit
    ("1.2m"), a pair of sides ("1200x2400"), or a side in some unit ("1200", "0.6", "60"). Not "2x8" or "500104"."""
    attached, pair = _WITH_UNIT.match(word), _METRIC_PAIR.match(word)
    return bool(attached and _feet(attached.group(1), attached.group(2).lower())
                or pair and _feet(pair.group(1), pair.group(3)) and _feet(pair.group(2), pair.group(3))
                or any(_feet(word, unit) for unit in METRIC_SIDES))


#: Spoken hundreds of millimetres ("twelve hundred") and spoken metres ("one point two"): the words of a side.
_HUNDREDS = {**{w: d for w, d in DIGIT_WORDS.items() if w not in ("oh", "o", "nought", "zero")}, **TEEN_WORDS}
_POINT_LEAD = {"zero": "0", "nought": "0", "oh": "0", "one": "1", "two": "2"}


def _spoken_side(low: Sequence[str], k: int) -> tuple[str, int] | None:
    """The metric side said in words from ``low[k]`` on, in digits, and how many words it takes: "twelve hundred"
    -> ("1200", 2), "twenty four hundred" / "twenty-four hundred" -> "2400", "one point two" -> "1.2", "point six" ->
    "0.6". None when the words there say no side of a board (``METRIC_SIDES``)."""
    word = low[k]
    if word in _POINT_LEAD or word == "point":  # "one point two (two)", "point six": metres
        lead, at = ("0", k) if word == "point" else (_POINT_LEAD[word], k + 1)
        if at + 1 < len(low) and low[at] == "point" and low[at + 1] in DIGIT_WORDS:
            decimals = DIGIT_WORDS[low[at + 1]]
            if at + 2 < len(low) and low[at + 2] in DIGIT_WORDS:
                decimals += DIGIT_WORDS[low[at + 2]]
            for digits in (decimals, decimals[:1]):  # "one point two two" (1.22), else "one point two"
                if f"{lead}.{digits}" in METRIC_SIDES["m"]:
                    return f"{lead}.{digits}", at + 1 + len(digits) - k
    tens = word.split("-")
    if len(tens) == 2 and tens[0] in TENS_WORDS and tens[1] in DIGIT_WORDS:  # "twenty-four"
        number, used = TENS_WORDS[tens[0]] + DIGIT_WORDS[tens[1]], 1
    elif word in TENS_WORDS and k + 1 < len(low) and low[k + 1] in _HUNDREDS and low[k + 1] not in TEEN_WORDS:
        number, used = TENS_WORDS[word] + DIGIT_WORDS[low[k + 1]], 2  # "twenty four"
    elif word in _HUNDREDS:
        number, used = _HUNDREDS[word], 1
    else:
        return None
    if k + used < len(low) and low[k + used] == "hundred" and number + "00" in METRIC_SIDES["mm"]:
        return number + "00", used + 1
    return None


def _spoken_sides(pieces: list[Piece]) -> tuple[list[Piece], dict[int, list[Piece]]]:
    """``pieces`` with each metric side said in words as one piece in digits, and the pieces each one stands for."""
    low = [p.word.lower() for p in pieces]
    out: list[Piece] = []
    spoken: dict[int, list[Piece]] = {}
    k = 0
    while k < len(pieces):
        side = _spoken_side(low, k)
        if side is None:
            out.append(pieces[k])
            k += 1
            continue
        digits, used = side
        spoken[len(out)] = pieces[k:k + used]
        out.append(Piece(digits, tuple(i for p in pieces[k:k + used] for i in p.said), pieces[k + used - 1].broken_off))
        k += used
    return out, spoken


def metric_sizes(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A board's sides said in metric, read as the feet they stand for: with a unit ("600 mil" -> "2 ft", "1.2m" ->
    "4ft"), or both sides of a size without one ("1200 x 2400" -> "4 x 8", "1.2 by 1.8" -> "4 by 6", "600 wide by
    2400 long"), in digits or in words ("twelve hundred by twenty-four hundred", "one point two metres"). A lone
    number without a unit is left as said, and so is any other measure ("25 mm screws")."""
    low = [p.word.lower() for p in pieces]
    if "hundred" not in low and "point" not in low and not any(map(_may_be_metric, low)):
        return pieces  # no side in words (they need "hundred" or "point": ``_spoken_side``) or in digits
    pieces, spoken = _spoken_sides(pieces)
    out = list(pieces)
    low = [p.word.lower() for p in pieces]
    read: dict[int, str] = {}
    for k, word in enumerate(low):
        attached, pair = _WITH_UNIT.match(word), _METRIC_PAIR.match(word)
        unit = METRIC_UNITS.get(low[k + 1]) if k + 1 < len(low) else None
        if attached and (feet := _feet(attached.group(1), attached.group(2).lower())):
            read[k] = feet + "ft"
        elif pair and (a := _feet(pair.group(1), pair.group(3))) and (b := _feet(pair.group(2), pair.group(3))):
            read[k] = f"{a}x{b}"
        elif unit and (feet := _feet(word, unit)):
            read[k], read[k + 1] = feet, "ft"
        elif (feet := _feet(word, None)) and k not in read:  # a side of a pair: "1200 x 2400", "600 wide by 2400"
            j = k + 1 + (k + 1 < len(low) and low[k + 1] in _SIDE_WORDS)
            if j + 1 < len(low) and low[j] in ("x", "by", "*") and (other := _feet(low[j + 1], None)) and \
                    ("." in word) == ("." in low[j + 1]):
                read[k], read[j + 1] = feet, other
            elif k > 1 and low[k - 1] in ("x", "by", "*") and any(read.get(i, "ft") != "ft" for i in range(k - 4, k - 1)):
                read[k] = feet  # the second side, after a first read with its unit: "2400 mm long by 1200 wide"
    for k, word in sorted(read.items()):
        said = " ".join(p.word for p in spoken[k]) if k in spoken else pieces[k].word
        changes.append(Change("metric", said, word))
        out[k] = Piece(word, pieces[k].said, pieces[k].broken_off)
    return [q for k, piece in enumerate(out) for q in (spoken[k] if k in spoken and k not in read else [piece])]


# --- disfluency ---------------------------------------------------------------------------------------------
def resolve_false_starts(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A word broken off with a dash is a false start: said again ("the- the", "fo- four") it is dropped; followed by
    a repair cue ("the four by- no, the two by eight") the words from where the repair starts again are dropped
    with the cue (the final intention counts). The repair starts again at the last earlier word equal to its own
    first word, or at the broken-off word."""
    if not any(p.broken_off for p in pieces):
        return pieces  # no word broken off: no false start
    out: list[Piece] = []
    i = 0
    while i < len(pieces):
        p = pieces[i]
        if not p.broken_off or i + 1 >= len(pieces):
            out.append(Piece(p.word, p.said) if p.broken_off else p)
            i += 1
            continue
        nxt = pieces[i + 1].word.lower()
        stem = p.word.lower()
        if nxt == stem or (len(stem) >= 2 and nxt.startswith(stem)):
            changes.append(Change("false start", p.word, ""))
            i += 1
            continue
        cue = _starts(pieces, i + 1, REPAIR_CUES)
        if cue and i + 1 + cue < len(pieces):
            first = pieces[i + 1 + cue].word.lower()
            start = next((k for k in range(len(out) - 1, max(-1, len(out) - 1 - REPAIR_REACH), -1)
                          if out[k].word.lower() == first), len(out))
            dropped = out[start:] + pieces[i:i + 1 + cue]
            changes.append(Change("repair", " ".join(d.word for d in dropped), ""))
            out = out[:start]
            i += 1 + cue
            continue
        out.append(Piece(p.word, p.said))
        i += 1
    return out


# --- chat messages ---------------------------------------------------------------------------------------------
_CLOCK = re.compile(r"^\d{1,2}[:.]\d{2}(?:[:.]\d{2})?(?:am|pm)?$", re.I)
_DATE = re.compile(r"^\d{1,4}[/.-]\d{1,2}(?:[/.-]\d{2,4})?$")
_NAME = re.compile(r"^[^\W\d_][\w.'’-]*$")


def _stamp_at(pieces: Sequence[Piece], k: int) -> int:
    """The length of a chat message's header at ``k`` ("[07:09] Kev:", "12/07/2026, 07:09:11 - Kev Smith:", "Kev
    (07:09):"): a clock time, a date or not, a name of one to three words, the header's colon last; 0 where none."""
    low = [p.word.lower() for p in pieces[k:k + 8]]
    n, clock = 0, False
    while n < len(low) and n < 4 and (_CLOCK.match(low[n]) or _DATE.match(low[n]) or low[n] in ("am", "pm", "-")):
        clock, n = clock or bool(_CLOCK.match(low[n])), n + 1
        if pieces[k + n - 1].labelled:  # "07:09:" with no name
            return n if clock else 0
    names = 0
    while n < len(low) and names < 3 and _NAME.match(pieces[k + n].word):
        n, names = n + 1, names + 1
        if pieces[k + n - 1].labelled:
            return n if clock and names else 0
    if not clock and names and n < len(low) and _CLOCK.match(low[n]) and pieces[k + n].labelled:  # "Kev (07:09):"
        return n + 1
    return 0


def drop_chat_stamps(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """The header of each message of a chat copied in ("[07:09] Kev:", "Kev (07:09):"), at the start of a line, is
    dropped: a time, a date and a sender's name say nothing of the command (a time said inside an instruction, "at
    12:30", stays)."""
    if not any(p.labelled for p in pieces):
        return pieces  # a header ends with its colon (``_stamp_at``)
    out: list[Piece] = []
    i = 0
    while i < len(pieces):
        n = _stamp_at(pieces, i) if _starts_line(pieces, i) else 0
        if n:
            changes.append(Change("chat header", " ".join(p.word for p in pieces[i:i + n]), ""))
            i += n
            continue
        out.append(pieces[i])
        i += 1
    return out


# --- an e-mail and a conversation copied in ------------------------------------------------------------------
#: Labels that start an e-mail's header line ("Subject: RE: East wall", "Fwd: ...").
EMAIL_HEADERS = frozenset({"subject", "re", "fwd", "fw", "cc", "bcc"})
#: Words that close an e-mail, on a line of their own before the sender's name.
EMAIL_CLOSINGS = frozenset({"thanks", "thank", "cheers", "regards", "best", "rgds", "thx", "ta", "sincerely"})
_PHONE = re.compile(r"^\+?\d{2,4}[-.]\d{3,4}(?:[-.]\d{3,4})?$|\w@\w")


def _lines(pieces: Sequence[Piece]) -> list[list[int]]:
    """The indices of ``pieces`` by the line of the worker's text they stand on."""
    out: list[list[int]] = []
    for k in range(len(pieces)):
        if _starts_line(pieces, k):
            out.append([])
        out[-1].append(k)
    return out


def _signed(line: Sequence[Piece]) -> bool:
    """Whether a line at the end of an e-mail is its sign-off: a closing ("Thanks,"), a sender's name or initial
    ("Dana", "D."), a signature's fields ("Dana Whitfield | Project Manager", "Office 555-0142"), "Sent from my
    phone"."""
    words = [p.word for p in line]
    low = [w.lower() for w in words]
    if len(words) > 10:
        return False
    if low[:2] == ["sent", "from"] or "|" in words or any(_PHONE.search(w) for w in words):
        return True
    if len(words) <= 3 and all(_NAME.match(w) and (w[0].isupper() or w == "--") or w == "--" for w in words):
        return low[0] in EMAIL_CLOSINGS or not any(w in FIELD_LABELS or w in _SIDE_VALUES or w in _ROW_VALUES
                                                   for w in low)
    return len(words) <= 2 and low[0] in EMAIL_CLOSINGS


def drop_email_frame(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """An instruction sent as an e-mail reply: its header lines ("Subject: RE: East wall, L2"), the lines it quotes
    from the message it answers ("> is the 2x8 in the top row here?": what was asked, not what is meant now) and its
    sign-off after a blank line ("Dana | PM | Sent from my phone") are dropped."""
    if len({p.cell[0] for p in pieces}) < 2:
        return pieces  # all on one line (fewer than two ``_lines``): no frame to drop
    lines = _lines(pieces)
    drop: set[int] = set()
    for line in lines:
        first = pieces[line[0]]
        if first.quoted or (first.labelled and first.word.lower() in EMAIL_HEADERS):
            drop.update(line)
    kept = [line for line in lines if line[0] not in drop]
    block = 0  # the sign-off: the last lines, each one of a sign-off's, the first after a blank line
    while block < len(kept) - 1 and _signed([pieces[k] for k in kept[-1 - block]]):
        block += 1
    while block and pieces[kept[-block][0]].cell[0] <= pieces[kept[-block - 1][-1]].cell[0] + 1:
        block -= 1
    for line in kept[len(kept) - block:]:
        drop.update(line)
    if not drop or len(drop) == len(pieces):
        return pieces
    for line in lines:
        if line[0] in drop:
            changes.append(Change("e-mail", " ".join(pieces[k].word for k in line), ""))
    return [p for k, p in enumerate(pieces) if k not in drop]


#: Words that label a form's field or a note, not a speaker ("Note: ...", "Target: 500322").
NOT_SPEAKERS = frozenset({"note", "notes", "nb", "ps", "also", "target", "destination", "location", "ticket", "task",
                          "job", "todo", "reason", "update", "edit", "next", "then", "first", "last", "step", "why",
                          "where", "what", "which", "how", "question", "answer", "q", "a", "ok", "okay", "important",
                          "warning", "careful", "caution", "tip", "remember", "reminder", "fyi"})


def _speaker_at(pieces: Sequence[Piece], k: int) -> int:
    """The length of a speaker's label at ``k`` ("MIKE:", "Sam Ortiz:", "kim:"): one name, or two capitalised, the
    colon last; 0 where none."""
    for n in (1, 2):
        names = pieces[k:k + n]
        if len(names) == n and names[-1].labelled and not any(p.labelled for p in names[:-1]) and all(
                _NAME.match(p.word) and (n == 1 or p.word[0].isupper()) and p.word.lower() not in NOT_SPEAKERS
                | FIELD_LABELS | _NUMBERING_LABELS | EMAIL_HEADERS for p in names):  # "Sam Ortiz:", not "left kim:"
            return n
    return 0


def _starts_line(pieces: Sequence[Piece], k: int) -> bool:
    """Whether piece ``k`` is the first of a line of the worker's text."""
    return k == 0 or pieces[k].cell[0] != pieces[k - 1].cell[0]


def _turn_starts(pieces: Sequence[Piece], k: int) -> bool:
    """Whether a turn may start at ``k``: the text's start, a new line, after a full stop."""
    return _starts_line(pieces, k) or pieces[k - 1].stopped


def drop_speaker_labels(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A conversation copied in as a transcript ("MIKE: next full sheet on 500104. DAVE: nah, 500103 ..."): a text
    that opens with a speaker's label and has another where a turn may start (``_turn_starts``; anywhere when the
    text lost its full stops, as a phone types it: "kim: ... raj: ...") has each label dropped, and the word after it
    starts a turn (``Piece.turn``: a value a speaker overrules, ``resolve_late_repairs``). A single label ("Kev:
    ...") is left to the chat header step."""
    if not _speaker_at(pieces, 0):
        return pieces
    starts = [(k, n) for k in range(len(pieces)) if (n := _speaker_at(pieces, k))]
    stopped = any(p.stopped for p in pieces)
    starts = [(k, n) for k, n in starts if not stopped or _turn_starts(pieces, k)]
    if len(starts) < 2:
        return pieces
    pieces = list(pieces)  # the turns are marked on a copy: the step stays pure
    out: list[Piece] = []
    k = 0
    for start, n in starts:
        out += pieces[k:start]
        changes.append(Change("speaker", " ".join(p.word for p in pieces[start:start + n]), ""))
        if start + n < len(pieces):
            pieces[start + n] = replace(pieces[start + n], turn=True)
        k = start + n
    return out + pieces[k:]


_TYPED_SIZE = re.compile(r"^\d+(?:'|ft)?x\d+(?:'|ft)?$", re.I)


def _starred_kind(word: str) -> str | None:
    """The kind of value a starred correction may take the place of: ``_value_kind``'s, or a size typed "4x8"."""
    return _value_kind(word) or ("size" if _TYPED_SIZE.match(word) else None)


def read_star_corrections(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A value typed with a star after a message ("*500105", "*left"), as chat users correct a word they sent, takes
    the place of the last value of its kind before it (an id, an ordinal, a side, a row): the final intention counts.
    With none before it, the value stays where it is, its star dropped."""
    if "*" not in "".join([p.word for p in pieces]):
        return pieces  # no star typed
    out: list[Piece] = []
    for p in pieces:
        value = p.word.strip("*")
        if value == p.word or not value:
            out.append(p)
            continue
        kind = _starred_kind(value)
        old = next((k for k in range(len(out) - 1, -1, -1) if _starred_kind(out[k].word) == kind), None) if kind else None
        read = replace(p, word=value)
        if old is None:
            changes.append(Change("star correction", p.word, value))
            out.append(read)
        else:
            changes.append(Change("star correction", f"{out[old].word} ... {p.word}", value))
            out[old] = replace(read, paused=out[old].paused, broken_off=out[old].broken_off)
    return out


# --- word order -----------------------------------------------------------------------------------------------
#: What leads an anchor said before the step counted from it ("from the previous stud, two to the right").
_ANCHOR_LEADS: tuple[tuple[str, ...], ...] = (("starting", "from"), ("starting", "at"), ("counting", "from"),
                                              ("start", "from"), ("start", "at"), ("from",))
#: Words that point an anchor back at the last stud used ("the previous stud", "that one", "the last one").
_BACK_ANCHOR_WORDS = frozenset({"previous", "prev", "last", "that", "same"})
_STUD_NOUNS = frozenset({"stud", "studs", "post", "one"})
_STEP_COUNTS = frozenset({*(w for w, d in DIGIT_WORDS.items() if d != "0"), "ten", "eleven", "twelve",
                          *(str(n) for n in range(1, 13))})
#: Words between a step's count and its side ("two studs over to the right", "three more left").
_STEP_MIDDLE = frozenset({"stud", "studs", "more", "over", "to", "the", "further", "farther", "places", "along"})
#: Words after a side that make it something else than a step's side ("right of", "left stack", "right line").
_NOT_A_STEP_SIDE = frozenset({"of", "from", "stack", "pile", "side", "end", "line", "edge", "hand"})


#: Words after which an anchor with no lead is inside another phrase ("on the last stud, two more right").
_INSIDE_A_PHRASE = frozenset({"of", "from", "at", "on", "to", "onto", "the", "a", "that", "this", "by", "beside", "past",
                              "as", "like", "than"})


#: Words that may stand between an anchor's determiner and its noun ("the fourth stud", "the far right one").
#: (ordinals, "fourth" or "4th", are matched by ``_ORDINAL``).
_ANCHOR_MODIFIERS = frozenset({*_BACK_ANCHOR_WORDS, "far", "very", "left", "right", "leftmost", "rightmost", "middle",
                               "end"})


#: The words an anchor said first may start with: a lead's first word, a determiner, a word that points back.
_ANCHOR_STARTS = frozenset({w[0] for w in _ANCHOR_LEADS} | {"the", "that", "this"} | _BACK_ANCHOR_WORDS)
#: A lead's first word or a word that points back: an anchor said first has one of them (``anchor_last``).
_LEAD_OR_BACK = frozenset({w[0] for w in _ANCHOR_LEADS} | _BACK_ANCHOR_WORDS)


def _stud_anchor(pieces: Sequence[Piece], j: int) -> tuple[int, bool]:
    """The end of a stud anchor that starts at ``j`` ("the previous stud", "that one", "the fourth stud", "stud
    500104", "500104 stud") and whether it points back at the last stud used; (``j``, False) where none starts there."""
    low = [p.word.lower() for p in pieces[j:j + 6]]
    k = 1 if low[:1] in (["the"], ["that"], ["this"]) else 0
    if low[k:k + 1] == ["stud"] and k + 1 < len(low) and ID_PATTERN.match(low[k + 1]):
        return j + k + 2, False
    if k < len(low) and ID_PATTERN.match(low[k]):
        return j + k + 1 + (low[k + 1:k + 2] in (["stud"], ["post"])), False
    back, mods, ordinal = low[:1] == ["that"], 0, False
    while k < len(low) and mods < 3 and (low[k] in _ANCHOR_MODIFIERS or _ORDINAL.match(low[k])):
        back, ordinal = back or low[k] in _BACK_ANCHOR_WORDS, ordinal or bool(_ORDINAL.match(low[k]))
        k, mods = k + 1, mods + 1
    noun = k < len(low) and low[k] in _STUD_NOUNS and (mods or low[0] == "that")
    end = k + noun
    counted = _counted_from(pieces, j + end)  # "the fourth (stud) from the right end", "the stud in the middle"
    if noun or (ordinal and counted):
        return j + end + counted, back
    if low[k:k + 1] == ["stud"] and tuple(low[k + 1:k + 4]) == ("in", "the", "middle"):
        return j + k + 4, False
    return j, False


def _counted_from(pieces: Sequence[Piece], k: int) -> int:
    """The length of "from the right (end)" or "from left" at ``k`` (an ordinal's side), 0 where none."""
    low = [p.word.lower() for p in pieces[k:k + 4]]
    n = 1 + (low[1:2] == ["the"]) if low[:1] == ["from"] else 0
    if not n or low[n:n + 1] not in (["left"], ["right"]):
        return 0
    return n + 1 + (low[n + 1:n + 2] == ["end"])


def _step_after(pieces: Sequence[Piece], k: int) -> int:
    """The end of a step counted from an anchor that starts at ``k`` ("two studs to the right", "go three more left",
    "one over"): a count, a few linking words and a side not followed by what makes it another side; ``k`` where none."""
    c = k
    while c < len(pieces) and pieces[c].word.lower() in ("go", "then", "move", "and"):
        c += 1
    if c >= len(pieces) or pieces[c].word.lower() not in _STEP_COUNTS:
        return k
    e = c + 1
    while e < len(pieces) and e <= c + 4 and pieces[e].word.lower() in _STEP_MIDDLE:
        e += 1
    if e >= len(pieces) or pieces[e].word.lower() not in ("left", "right"):
        return k
    if e + 1 < len(pieces) and pieces[e + 1].word.lower() in _NOT_A_STEP_SIDE:
        return k
    return e + 1


def _may_step_from_an_anchor(low: Sequence[str]) -> bool:
    """Whether ``anchor_last`` may read a step counted from an anchor in the (lower-case) words: a lead or a word that
    points back (``_LEAD_OR_BACK``), after it a count, and a side at most five words after the count
    (``_step_after``: four linking words at most between them)."""
    if _LEAD_OR_BACK.isdisjoint(low) or _STEP_COUNTS.isdisjoint(low):
        return False  # most texts: no lead and no word that points back, or no count
    first = next((k for k, w in enumerate(low) if w in _LEAD_OR_BACK), len(low))
    return any(w in _STEP_COUNTS and ("left" in low[c + 1:c + 6] or "right" in low[c + 1:c + 6])
               for c, w in enumerate(low[first + 1:], first + 1))


def anchor_last(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A stud counted from an anchor said first, as verb-final languages put it and people thinking aloud do ("from
    the previous stud, two studs to the right", "starting at 500104 go three right", Hindi "pichhle stud se do stud
    right" once the code-switch lexicon has read it), read in the order the corpus says it: "two studs to the right
    of the previous stud". Without a lead ("from"), only an anchor that points back is one ("the last stud six stud
    right"): a bare id before a count is more often the end of another field."""
    low = [p.word.lower() for p in pieces]
    if not _may_step_from_an_anchor(low):
        return pieces  # no lead or word that points back before a step: nothing to read
    out: list[Piece] = []
    i = 0
    while i < len(pieces):
        if low[i] not in _ANCHOR_STARTS:  # most words start nothing here
            out.append(pieces[i])
            i += 1
            continue
        lead = next((len(w) for w in _ANCHOR_LEADS if tuple(low[i:i + len(w)]) == w), 0)
        a_end, back = _stud_anchor(pieces, i + lead)
        begins = a_end > i + lead and (lead or back) and not (lead == 0 and out and out[-1].word.lower() in
                                                                _INSIDE_A_PHRASE)
        s_end = _step_after(pieces, a_end) if begins else a_end
        if not begins or s_end == a_end:
            out.append(pieces[i])
            i += 1
            continue
        count = next(k for k in range(a_end, s_end) if pieces[k].word.lower() in _STEP_COUNTS)
        step, anchor = pieces[count:s_end], pieces[i + lead:a_end]
        read = [*step, Piece("of", step[-1].said, role="O"), *anchor]
        changes.append(Change("anchor first", " ".join(p.word for p in pieces[i:s_end]),
                              " ".join(p.word for p in read)))
        out += read
        i = s_end
    return out


#: Values a worker takes back by saying another of the same kind: an id, an ordinal, a side, a row.
_SIDE_VALUES = frozenset({"left", "right"})
_ROW_VALUES = frozenset({"top", "bottom"})
#: Nouns a value may carry before the break ("the bottom row— top row").
_VALUE_NOUNS = frozenset({"row", "course", "stud", "pile", "stack", "one", "panel", "sheet", "line", "side"})


@lru_cache(maxsize=65536)
def _value_kind(word: str) -> str | None:
    """The kind of value a word is ("id", "ordinal", "side", "row"), or None. A pure function of the word, so each
    word is read once."""
    low = word.lower()
    if ID_PATTERN.match(low):
        return "id"
    if _ORDINAL.match(low) and low != "last":
        return "ordinal"
    return "side" if low in _SIDE_VALUES else "row" if low in _ROW_VALUES else None


#: Words that say how a repaired id lies from the one taken back ("one more over to the right", "the next one").
_RELATION_WORDS = frozenset({"one", "two", "three", "1", "2", "3", "more", "over", "to", "the", "right", "left", "next",
                             "further", "along"})


def _told_from_the_old(pieces: Sequence[Piece], k: int) -> int:
    """How many words from ``k`` say how a new id lies from the one taken back before it ("one more over to the
    right" before "500106"): 0 where no id follows within a few such words."""
    n = 0
    while k + n < len(pieces) and n <= 6 and pieces[k + n].word.lower() in _RELATION_WORDS:
        n += 1
    return n if 0 < n <= 6 and k + n < len(pieces) and ID_PATTERN.match(pieces[k + n].word) else 0


def resolve_value_repairs(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A value taken back by another of the same kind said right after it (the final intention counts): an id, an
    ordinal, a side or a row, broken off ("four studs to the left— right", "the bottom row— top row"), followed by a
    repair cue ("the third, no, the fourth", "500104 I mean 500105"), or by a pause (a comma, a filler) and the new
    value with a cue after it ("stud 500101, er, 500100, sorry"). The old value, its noun and the cues are dropped,
    and so are the words that say how a new id lies from the old ("500105- no, one more over to the right, 500106").
    Two values of a kind said without a break or a cue ("500104, 500105") are left for the IM (two values: a
    question)."""
    kinds = [kind for p in pieces if (kind := _value_kind(p.word))]
    if len(kinds) == len(set(kinds)) or not (any(p.broken_off for p in pieces) or _may_start(pieces, REPAIR_CUES)):
        return pieces  # a value is taken back by another of its kind, after a break or with a repair cue
    out: list[Piece] = []
    i = 0
    while i < len(pieces):
        kind = _value_kind(pieces[i].word)
        j = i + 1 if kind and i + 1 < len(pieces) and pieces[i + 1].word.lower() in _VALUE_NOUNS else i
        a = pieces[j] if kind else None
        if a is None or j + 1 >= len(pieces):
            out.append(pieces[i])
            i += 1
            continue
        cue = _starts(pieces, j + 1, REPAIR_CUES)
        told = _told_from_the_old(pieces, j + 1 + cue) if kind == "id" and cue else 0
        if told:  # "500105- no, one more over to the right, 500106": the new id, and how it lies from the old
            changes.append(Change("repair", " ".join(p.word for p in pieces[i:j + 1 + cue + told]), ""))
            i = j + 1 + cue + told
            continue
        b = j + 1 + cue + (j + 1 + cue < len(pieces) and pieces[j + 1 + cue].word.lower() in ("the", "a"))
        end = b + 1 + (b + 1 < len(pieces) and pieces[b + 1].word.lower() in _VALUE_NOUNS)  # after "bottom row"
        after = _starts(pieces, end, REPAIR_CUES) if b < len(pieces) else 0
        if after and end + after < len(pieces) and _value_kind(pieces[end + after].word) == kind:
            after = 0  # "left— right, I mean right": the cue leads the next repair
        if after and _late_repair(pieces[j + 1:]) is not None:
            after = 0  # "500302, 500111, nope, wrong one, 500110": the cue takes back the value before it
        if b >= len(pieces) or _value_kind(pieces[b].word) != kind or not (a.broken_off or cue or (a.paused and after)):
            out.append(pieces[i])
            i += 1
            continue
        article = b > j + 1 + cue and bool(out) and out[-1].word.lower() in ("the", "a")
        changes.append(Change("repair", " ".join(p.word for p in pieces[i:(b if article else j + 1 + cue)]), ""))
        i = b if article else j + 1 + cue  # "the third, no, the fourth": one article
        if after:  # the cue after the new value: "500100, sorry"
            out += pieces[i:end]
            changes.append(Change("repair", " ".join(p.word for p in pieces[end:end + after]), ""))
            i = end + after
    return out


#: How many words may stand between a value and the cue that takes it back later ("top course from the first
#: stud, no. bottom course"), and how many words of a reason between the cue and the value meant ("500111... nah
#: that'd hang past the end, 500110").
LATE_REACH = 6
REASON_REACH = 8
#: Values that name the same thing in two ways: a stud said by its id or by its place in the row.
_KIND_GROUPS = {"id": {"id", "ordinal"}, "ordinal": {"id", "ordinal"}}


def _late_repair(pieces: Sequence[Piece]) -> tuple[int, int, int, int] | None:
    """The first value taken back late in ``pieces``: (the old value, the cue, the value meant, the end of what goes),
    or None (``resolve_late_repairs``). Without the pauses (a text said, or typed with no punctuation) none is read:
    "... on 500109 no wait the one marked 500102" may take back the panel or the stud, and the decision asks."""
    if not any(p.paused or p.stopped for p in pieces) or not _may_start(pieces, REPAIR_CUES):
        return None  # nothing is taken back late without a pause or a full stop before a repair cue
    for c in range(1, len(pieces)):
        cue = _starts(pieces, c, REPAIR_CUES)
        if not cue or not (pieces[c - 1].paused or pieces[c - 1].stopped):
            continue
        d = c + cue
        while (more := _starts(pieces, d, REPAIR_CUES)):
            d += more  # "no wait", "nah sorry"
        plain_no = d == c + 1 and pieces[c].word.lower() == "no" and not (pieces[c].paused or pieces[c].stopped)
        if pieces[c].turn:  # another speaker overrules a value anywhere in the turn before
            reach = next((k for k in range(c - 1, -1, -1) if pieces[k].turn), 0) - 1
        else:
            reach = max(-1, c - 2 - LATE_REACH)
        for e in range(d, min(len(pieces), d + REASON_REACH + 1)):
            if e > d and (plain_no or not (pieces[e - 1].paused or pieces[e - 1].stopped)):
                continue  # a reason ends with a pause before the value meant; "no gaps, ..." is no cue
            if e == d and not (pieces[d - 1].stopped or pieces[c].turn):
                continue  # a cue between commas is read where it is said (``resolve_value_repairs``), or left to the tagger
            b = e + (e < len(pieces) - 1 and pieces[e].word.lower() in ("the", "a"))
            kind = _value_kind(pieces[b].word) if b < len(pieces) else None
            if kind is None:
                continue
            if any(_value_kind(p.word) for p in pieces[d:e]):
                break  # the reason holds a value of its own: not a repair read here
            group = _KIND_GROUPS.get(kind, {kind})
            old = next((k for k in range(c - 1, reach, -1) if _value_kind(pieces[k].word) in group), None)
            if old is None or _value_kind(pieces[old].word) != kind or pieces[old].word.lower() == pieces[b].word.lower():
                break  # the nearest value of its group is of another kind ("500321 at stud 3rd ..., no, 500108")
            end = b + 1
            if (old + 1 < c and end < len(pieces) and pieces[old + 1].word.lower() in _VALUE_NOUNS
                    and pieces[end].word.lower() == pieces[old + 1].word.lower()):
                end += 1  # the noun said again with the value meant ("... no. Bottom course")
            between = [p.word.lower() for p in pieces[old + 1:c]]
            end += next((n for n in range(len(between), 0, -1)
                         if [p.word.lower() for p in pieces[end:end + n]] == between[-n:]), 0)  # "from the right" again
            return old, c, b, end
    return None


def resolve_late_repairs(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A value taken back a few words after it was said (the final intention counts): after a pause, a repair cue,
    perhaps a short reason ending with a pause, and a value of the same kind ("top course from the first stud, no.
    bottom course"; "on 500111... nah that'd hang past the end, 500110"), or in the next speaker's turn anywhere in
    the turn before ("MIKE: ... on 500104, centre line. DAVE: nah, 500103"). The value meant takes the old one's place,
    the words between them stay, and the cue, the reason and the noun said again are dropped. Runs after
    ``resolve_value_repairs``, which reads a value taken back right where it was said."""
    while (found := _late_repair(pieces)) is not None:
        old, c, b, end = found
        changes.append(Change("repair", " ".join(p.word for p in [pieces[old], *pieces[c:b]]), pieces[b].word))
        pieces = [*pieces[:old], replace(pieces[b], paused=pieces[old].paused, stopped=pieces[old].stopped),
                  *pieces[old + 1:c], *pieces[end:]]
    return pieces


#: Words a speaker agrees with, in a turn of a conversation that only takes up what was said ("yeah fair, 500103").
AGREEMENT_WORDS = frozenset({"yep", "yeah", "yes", "yup", "ok", "okay", "k", "fair", "enough", "right", "sweet", "copy",
                             "go", "then", "cool", "sure", "good", "done", "alright", "aye", "roger", "that's", "it",
                             "on", "mate", "too", "sounds", "works", "got"})


def drop_echo_turns(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """In a conversation copied in (``drop_speaker_labels``), a later turn that only agrees ("yep.", "copy, on it")
    or says again a value already said ("MIKE: yeah fair, 500103.", "ok, left then", "top row, yep") is dropped: it
    adds nothing to the command, and a value said twice reads as two. Runs after ``resolve_late_repairs``, so the
    value a turn takes up is the one meant."""
    starts = [k for k, p in enumerate(pieces) if p.turn]
    if len(starts) < 2:
        return pieces
    drop: set[int] = set()
    for a, b in zip(starts[1:], [*starts[2:], len(pieces)]):
        said_before = {p.word.lower() for p in pieces[:a]}
        turn = pieces[a:b]
        if all(p.word.lower() in AGREEMENT_WORDS or ((_value_kind(p.word) or p.word.lower() in _VALUE_NOUNS)
                                                      and p.word.lower() in said_before) for p in turn):
            changes.append(Change("echo", " ".join(p.word for p in turn), ""))
            drop.update(range(a, b))
    return [p for k, p in enumerate(pieces) if k not in drop]


# --- a table pasted from a spreadsheet ----------------------------------------------------------------------
#: What separates a table's cells inside one typed word ("1;500320;500100", "qty,size,stack", "line|panel").
_INNER_CELLS = re.compile(r"[;,|]")
_NUMBER_WITH_COMMAS = re.compile(r"^\d{1,3}(?:,\d{3})+$")
#: A cell that only numbers or dates a row of a table ("12", "3.", "07/12", "2026-12-07") under a label that is no
#: field of the site (``_NUMBERING_LABELS``, or none of ``FIELD_LABELS``).
_ROW_NUMBER = re.compile(r"^[#\d][\d/.:\-]*$")
_NUMBERING_LABELS = frozenset({"line", "item", "no", "nr", "num", "number", "qty", "quantity", "date", "pos", "step",
                               "seq", "ref"})
#: The fewest cells of a table's header line.
TABLE_CELLS = 2


def _table_cells(pieces: Sequence[Piece]) -> dict[int, list[list[Piece]]]:
    """Each line's cells, in order: the pieces split where the cell changes (``Piece.cell``: a tab or a comma or
    semicolon after a word) and at a comma, a semicolon or a "|" inside a word ("1;500320;500100": pieces of their
    own, from the same worker's word); a lone "|" only separates."""
    lines: dict[int, list[list[Piece]]] = {}
    last: tuple[int, int] | None = None
    for p in pieces:
        cells = lines.setdefault(p.cell[0], [])
        if p.word == "|":
            cells.append([])
            last = None
            continue
        parts = [p.word]
        if _INNER_CELLS.search(p.word) and not _SPLIT_ID.match(p.word) and not _NUMBER_WITH_COMMAS.match(p.word):
            parts = _INNER_CELLS.split(p.word)
        for k, part in enumerate(parts):
            if k > 0 or p.cell != last or not cells:
                cells.append([])
            if part:
                cells[-1].append(replace(p, word=part) if part != p.word else p)
        last = p.cell
    return {line: [c for c in cells if c] for line, cells in lines.items()}


#: Words after a field's name in a header that say its value is an id or a number ("stud_id", "panel no").
_ID_SUFFIXES = frozenset({"id", "no", "nr", "num", "number"})


def _label(cell: Sequence[Piece]) -> str | None:
    """The field a header cell names ("stud", "from_stack" -> "stack", "Panel ID" and "stud_no" -> "panel" and
    "stud"), or None when the cell is no label (a number, an id, more than two words)."""
    words = [w for p in cell for w in re.split(r"[_\-/.#]+", p.word.lower()) if w]
    if not words or len(cell) > 2 or not all(w.isalpha() for w in words):
        return None
    if len(words) > 1 and words[-1] in _ID_SUFFIXES:  # "stud_id", "panel no": the field is the stud, the panel
        return words[-2]
    return words[-1]


def _table_row(header: Sequence[Sequence[Piece]], row: Sequence[Sequence[Piece]],
               changes: list[Change]) -> list[Piece]:
    """One row of a table read as the words of a form: each value after its field's label ("stud 500100", "panel
    500320"), a one-word value that says which before it ("left stack", "bottom row"), a value under a label that
    is no field of the site as it stands ("vertical" under "orientation"), and a cell that only numbers or dates the
    row ("12" under "line", "07/12" under "date") left out."""
    out: list[Piece] = []
    for label_cell, value in zip(header, row):
        label = _label(label_cell)
        said = tuple(k for p in label_cell for k in p.said)
        words = [p.word for p in value]
        numbering = label not in FIELD_LABELS or label in _NUMBERING_LABELS
        if numbering and len(value) == 1 and _ROW_NUMBER.match(value[0].word) \
                and not ID_PATTERN.match(value[0].word.lstrip("#")):
            changes.append(Change("table", f"{' '.join(p.word for p in label_cell)} {value[0].word}", ""))
            continue
        if label not in FIELD_LABELS:
            read = list(value)
        elif len(value) == 1 and value[0].word.isalpha():
            read = [*value, *_read_as([label], said, label_cell[-1])]
        else:
            read = [*_read_as([label], said, label_cell[-1]), *value]
        changes.append(Change("table", f"{' '.join(p.word for p in label_cell)}: {' '.join(words)}",
                              " ".join(p.word for p in read)))
        out += [replace(p, paused=False, cell=(0, 0)) for p in read]
    return out


def read_tables(pieces: list[Piece], changes: list[Change]) -> list[Piece]:
    """A table pasted from a spreadsheet or a CSV file: a header line of at least ``TABLE_CELLS`` labels, at least
    two of them fields of a form ("line;panel;stud;orientation", "qty, size, from_stack, stud"), and the lines
    below it with as many cells, each read as a form's words (``_table_row``: "panel 500320 stud 500100 vertical").
    The header's words are read where its labels are; the lines around the table stay as written."""
    if len({p.cell[0] for p in pieces}) < 2:
        return pieces
    lines = _table_cells(pieces)
    order = sorted(lines)
    out: list[Piece] = []
    k = 0
    while k < len(order):
        header = lines[order[k]]
        labels = [_label(c) for c in header]
        rows = []
        if len(header) >= TABLE_CELLS and None not in labels and sum(l in FIELD_LABELS for l in labels) >= 2:
            rows = list(itertools.takewhile(lambda line: len(lines[line]) == len(header), order[k + 1:]))
        if not rows:
            out += [p for p in pieces if p.cell[0] == order[k]]
            k += 1
            continue
        changes.append(Change("table", " | ".join(" ".join(p.word for p in c) for c in header), ""))
        for line in rows:
            out += _table_row(header, lines[line], changes)
        k += 1 + len(rows)
    return out


#: The front end's steps, in order.
STEPS: tuple[Step, ...] = (drop_email_frame, drop_chat_stamps, drop_speaker_labels, read_tables, split_fields, read_offsets, split_compounds, translate_code_switch,
                           expand_shorthand, drop_fillers, read_ids, read_star_corrections, resolve_value_repairs, resolve_late_repairs,
                           drop_echo_turns, resolve_false_starts, anchor_last, metric_sizes, singular_sizes)


#: Written labels that only introduce the number after them ("stud no. 500104"); their full stop is what tells them
#: from the word "no", so they are read before ``tokenize`` drops it.
_LABELS = frozenset({"no.", "nr.", "num.", "no:"})
#: Words whose comma marks them as fillers ("grab, like, the ..."): read with it, for ``FILLERS``.
_COMMA_FILLERS = frozenset({"like,"})
_READ_AS_TYPED = _LABELS | _COMMA_FILLERS


# --- scripts written without spaces (Chinese, Japanese) -----------------------------------------------------
#: The marks of Chinese, Japanese, Arabic-script and Indic text ("，", "。", "،", "।"): the worker's words end (or, for an
#: opening bracket, start) at them, as at a space, and ``corpus.io.tokenize`` drops them from a word's edges.
_SPACED_MARKS = str.maketrans({**{mark: mark + " " for mark in MARKS_AFTER}, **{mark: " " + mark for mark in MARKS_BEFORE}})
#: Full-width letters and the decimal digits of every script ("５００", "٥٠٠", "۵۰۰", "५००"), read as the ASCII
#: characters they stand for; the worker's words keep them as typed.
_WIDE_CHARACTERS = {**{code: chr(code - 0xFEE0) for code in range(0xFF21, 0xFF5B) if chr(code - 0xFEE0).isalpha()},
                    **{code: str(unicodedata.digit(chr(code))) for code in range(0x0660, 0x10000)
                       if unicodedata.category(chr(code)) == "Nd"}}


@lru_cache(maxsize=4)
def _unspaced_forms(lexicon: Path | str = CODE_SWITCH_PATH) -> tuple[frozenset[str], int]:
    """The code-switch lexicon's forms written in a script without spaces, and the longest one's length."""
    forms = frozenset(form for form, _, _ in read_code_switch(lexicon) if all(unspaced(c) for c in form))
    return forms, max(map(len, forms), default=1)


def segment_unspaced(run: str, lexicon: Path | str = CODE_SWITCH_PATH) -> list[str]:
    """A run of a script written without spaces cut into words by forward maximum matching against the code-switch
    lexicon's forms (the longest form starting at each place; Wong and Chan, COLING 1996): "从左边那摞拿" -> "从",
    "左边那摞", "拿" where those are forms. Characters that start no form stay together as one word."""
    forms, longest = _unspaced_forms(lexicon)
    out: list[str] = []
    unknown = ""
    i = 0
    while i < len(run):
        n = next((n for n in range(min(longest, len(run) - i), 0, -1) if run[i:i + n] in forms), 0)
        if not n:
            unknown += run[i]
            i += 1
            continue
        out += [unknown] if unknown else []
        unknown = ""
        out.append(run[i:i + n])
        i += n
    return out + ([unknown] if unknown else [])


def split_unspaced(chunk: str, lexicon: Path | str = CODE_SWITCH_PATH) -> list[str]:
    """A chunk of text without white space cut where a script written without spaces meets another ("在500106上" ->
    "在", "500106", "上") and within each run of that script (``segment_unspaced``); a mark stays with the word
    before it ("上," -> "上,"). A chunk with no such script is one word."""
    if not UNSPACED.search(chunk):
        return [chunk]
    out: list[str] = []
    for part in re.findall(f"{UNSPACED.pattern}+|(?:(?!{UNSPACED.pattern}).)+", chunk):
        if unspaced(part[0]):
            out += segment_unspaced(part, lexicon)
        elif out and not any(c.isalnum() for c in part):
            out[-1] += part
        else:
            out.append(part)
    return out


@dataclass(frozen=True)
class Chunk:
    """A chunk of the worker's text without white space, as ``_pieces`` reads it: its words (each as said and as
    read) and what follows it."""

    words: tuple[tuple[str, str], ...]
    broken_off: bool
    paused: bool
    stopped: bool
    labelled: bool


@lru_cache(maxsize=65536)
def _read_chunk(raw: str) -> Chunk:
    """A chunk of text without white space read into words (``corpus.io.tokenize``): a word broken off with a dash
    loses the dash, a label's full stop is kept for the lexicon, full-width letters and other scripts' digits are
    read as ASCII. A pure function of the chunk, so each chunk met again is read once."""
    low = raw.lower()
    broken_off = bool(_BROKEN_OFF.search(raw))
    words = []
    for word in tokenize(raw):
        read = low if low in _READ_AS_TYPED else (word.rstrip("-–—") or word) if broken_off else word
        words.append((word, read.translate(_WIDE_CHARACTERS)))
    return Chunk(tuple(words), broken_off, paused=bool(_PAUSE.search(raw)), stopped=bool(_STOP.search(raw)),
                 labelled=raw.endswith(":"))


def _pieces(text: str) -> tuple[list[str], list[Piece]]:
    """The worker's words (as ``corpus.io.tokenize`` splits them, a script written without spaces cut into words by
    ``split_unspaced``) and a piece for each: a word broken off with a dash loses the dash; a label's full stop is
    kept for the lexicon (``_read_chunk``)."""
    said: list[str] = []
    pieces: list[Piece] = []
    if not text.isascii():  # the marks of ``_SPACED_MARKS`` are none of them ASCII
        text = text.translate(_SPACED_MARKS)
    for line, text_line in enumerate(text.split("\n")):
        cell = 0
        quoted = text_line.lstrip().startswith(">")
        for k, between_tabs in enumerate(text_line.split("\t")):
            cell += k > 0
            chunks = between_tabs.split()
            if UNSPACED.search(between_tabs):
                chunks = [word for chunk in chunks for word in split_unspaced(chunk)]
            for raw in chunks:
                chunk = _read_chunk(raw)
                for word, read in chunk.words:
                    pieces.append(Piece(read, (len(said),), chunk.broken_off, paused=chunk.paused, cell=(line, cell),
                                        labelled=chunk.labelled, stopped=chunk.stopped, quoted=quoted))
                    said.append(word)
                cell += chunk.paused
    return said, pieces


def normalise(text: str) -> Normalised:
    """The instruction ``text`` read by the front end (module docstring): the worker's words, the words to tag,
    their alignment and what changed.

    >>> n = normalise("uh put the two-by-eights on stud five oh oh one oh four, CL")
    >>> n.words
    ('put', 'the', 'two-by-eight', 'on', 'stud', '500104', 'centre', 'line')
    >>> n.said[5:10]
    ('five', 'oh', 'oh', 'one', 'oh')
    """
    said, pieces = _pieces(text)
    changes: list[Change] = []
    for step in STEPS:
        pieces = step(pieces, changes)
    return Normalised(tuple(said), tuple([p.word for p in pieces]), tuple([p.said for p in pieces]), tuple(changes),
                      tuple([p.role for p in pieces]))


def normalise_text(text: str) -> str:
    """The normalised words of ``text`` as one string (the form ``benchmarks/normalisers.py`` compares)."""
    return " ".join(normalise(text).words)
