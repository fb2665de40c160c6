"""Noise channels: the ways a generated instruction is said or typed, combinable with every register (issue 29).

A register (``field_generator.Speaker``) decides what is said; a channel rewrites how it reaches the robot,
keeping the meaning and carrying every word's tag along:

- ``spoken_ids``: ids read out ("five oh oh one oh four", "five double-oh one one two", "five hundred one-oh-four")
  or split when typed ("500 104", "500-104"), now and then broken off and repaired;
- ``shorthand``: a form's or a tablet's written shorthand ("CL", "btm", "pnl", "L", "w/", "stud#", "no."), fields
  separated by ``|`` or ``->``;
- ``disfluency``: fillers, false starts broken off with a dash ("the- the"), a part begun wrongly and repaired
  ("the four by- no, the 2x8"), a trailing confirmation ("yeah, that one");
- ``asides``: a reason or remark around the instruction that names sizes, rows, counts and positions of other
  things ("the top of that pile is chipped", "the 4x8s are heavy") and so must all be ``O``;
- ``plural_sizes``: a panel named as one of its size ("one of the 2x8s").

The front end (``drywall_lab.nlu.normalise``) reads the first three back into the corpus's written forms; the
tagger must learn the others. Whole channels and pairs of channels are held back from the training splits
(``HELD_BACK``, ``HELD_BACK_PAIRS``): the novel split uses them, so that it measures an instruction said in a
way the tagger never met (first sight).
"""
from __future__ import annotations

import random
from typing import Callable

from drywall_lab.corpus.markup import Phrase, Token
from drywall_lab.corpus.phrases import Chooser

Sentences = list[Phrase]
Channel = Callable[[Chooser, Sentences], Sentences]

_DIGIT_WORDS = {"0": ("oh", "zero"), "1": ("one",), "2": ("two",), "3": ("three",), "4": ("four",), "5": ("five",),
                "6": ("six",), "7": ("seven",), "8": ("eight",), "9": ("nine",)}
_ID_TAGS = ("ID_stud", "ID_wall")


def _word(word: str, tag: str | None, coref: str | None) -> Token:
    return Token(word, tag or "O", coref or tag or "O")


def _plain(*words: str) -> Phrase:
    return [Token(w, "O", "O") for w in words]


def _is_id(tok: Token) -> bool:
    return tok.is_word and tok.tag in _ID_TAGS and len(tok.word) == 6 and tok.word.isdigit()


def _map_words(sentences: Sentences, rewrite: Callable[[Token], Phrase | None]) -> Sentences:
    """Each word through ``rewrite`` (None: kept as it is)."""
    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        for tok in sentence:
            replaced = rewrite(tok) if tok.is_word else None
            new += [tok] if replaced is None else replaced
        out.append(new)
    return out


# --- spoken ids -----------------------------------------------------------------------------------------------
def say_id(rng: random.Random, ident: str) -> list[str]:
    """An id as people say or type it: digit by digit, with "double", with "hundred", or split in two."""
    form = rng.randrange(6)
    digits = [rng.choice(_DIGIT_WORDS[d]) for d in ident]
    if form == 0 or form == 1:
        return digits
    if form == 2 and ident[1:3] == "00":  # "five double-oh one oh four", "five double oh ..."
        double = ["double-oh"] if rng.random() < 0.5 else ["double", rng.choice(_DIGIT_WORDS["0"])]
        return digits[:1] + double + digits[3:]
    if form == 3 and ident[1:3] == "00":  # "five hundred one oh four", "five hundred one-oh-four"
        tail = digits[3:]
        return digits[:1] + ["hundred"] + (["-".join(tail)] if rng.random() < 0.5 else tail)
    if form == 4:
        return [ident[:3], ident[3:]]
    return [f"{ident[:3]}-{ident[3:]}"]


def spoken_ids(ch: Chooser, sentences: Sentences) -> Sentences:
    """Every id said or typed in one of ``say_id``'s forms; now and then its last digits are said wrongly, broken
    off and repaired ("five oh oh one one- no, one one one"), the repair's words carrying the tag."""
    def rewrite(tok: Token) -> Phrase | None:
        if not _is_id(tok):
            return None
        said = [_word(w, tok.tag, tok.coref) for w in say_id(ch.rng, tok.word)]
        if len(said) == 6 and ch.chance(0.2):  # "five oh oh one seven- no, one one one"
            wrong = str((int(tok.word[4]) + ch.rng.randint(1, 9)) % 10)
            return said[:3] + [Token(said[3].word, "O", "O"), Token(_DIGIT_WORDS[wrong][0] + "-", "O", "O")] + \
                _plain(*ch.rng.choice(["no", "sorry", "I mean"]).split()) + said[3:]
        return said
    return _map_words(sentences, rewrite)


# --- shorthand ------------------------------------------------------------------------------------------------
SHORT_FORMS: dict[str, tuple[str, ...]] = {
    "left": ("L", "LH", "lh"), "right": ("R", "RH", "rh"), "bottom": ("btm", "bot"), "vertical": ("vert",),
    "horizontal": ("horiz", "horz"), "panel": ("pnl",), "sheet": ("sht",), "with": ("w/",), "and": ("&", "+"),
    "at": ("@",),
}
_LINE_WORDS = {("centre", "line"), ("center", "line")}


def shorthand(ch: Chooser, sentences: Sentences) -> Sentences:
    """Half the words with a written short form are written short; a centre line is "CL" or "C/L"; a stud's id
    may follow "stud#" or "stud no."; sentences are now and then fields of a form, separated by ``|`` or
    ``->``."""
    rng = ch.rng
    out: Sentences = []
    for k, sentence in enumerate(sentences):
        new: Phrase = []
        i = 0
        while i < len(sentence):
            tok = sentence[i]
            nxt = sentence[i + 1] if i + 1 < len(sentence) else None
            if tok.is_word and nxt is not None and nxt.is_word and (tok.word.lower(), nxt.word.lower()) in _LINE_WORDS \
                    and rng.random() < 0.7:
                tag = tok.tag if tok.tag != "O" else nxt.tag
                new.append(_word(rng.choice(["CL", "C/L", "c/l"]), tag, tok.coref))
                i += 2
                continue
            forms = SHORT_FORMS.get(tok.word.lower()) if tok.is_word else None
            if forms and rng.random() < 0.5:
                tok = Token(rng.choice(forms), tok.tag, tok.coref)
            elif tok.is_word and tok.word.lower() == "stud" and nxt is not None and _is_id(nxt) and rng.random() < 0.5:
                new.append(Token("stud#", tok.tag, tok.coref) if rng.random() < 0.5 else tok)
                if new[-1] is tok:
                    new.append(Token("no.", "O", "O"))
                i += 1
                continue
            new.append(tok)
            i += 1
        if k and rng.random() < 0.5:
            new = _plain(rng.choice(["|", "->", "/"])) + new
        out.append(new)
    return out


# --- disfluency -----------------------------------------------------------------------------------------------
SPOKEN_FILLERS = ("um", "uh", "uhh", "erm", "you know", "like,", "I think")
CONFIRMATIONS = ("yeah", "yep, got it?", "yes, thanks", "okay?", "right, go", "cheers")
_FALSE_START_WORDS = frozenset({"the", "put", "grab", "take", "on", "to", "it", "a", "and", "then", "from"})
_OTHER_SIZES = ("four by", "two by", "4x", "2x", "four-by", "full", "4 by", "2 by", "six")
_BROKEN_SIZES = ("4x", "2x", "four-by", "two-by", "six", "fo", "tw")


def disfluency(ch: Chooser, sentences: Sentences) -> Sentences:
    """Fillers between words, a plain word broken off and said again ("the- the"), a size begun wrongly and
    repaired ("four by- no, the 2x8"), a confirmation at the end."""
    rng = ch.rng
    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        repaired = False
        for tok in sentence:
            if tok.is_word and rng.random() < 0.07:
                new += _plain(*rng.choice(SPOKEN_FILLERS).split())
            if tok.is_word and tok.tag == "O" and tok.word.lower() in _FALSE_START_WORDS and rng.random() < 0.08:
                new.append(Token(tok.word + "-", "O", "O"))
            if tok.is_word and tok.tag in ("width", "length") and not repaired and rng.random() < 0.35:
                # the repair starts again where the false start did: at its article, or at the size itself
                cue = _plain(*rng.choice(["no", "sorry", "I mean"]).split())
                if new and new[-1].is_word and new[-1].word.lower() in ("the", "a"):
                    begun = rng.choice(_OTHER_SIZES).split()
                    new += _plain(new[-1].word, *begun[:-1]) + [Token(begun[-1] + "-", "O", "O")] + cue
                else:
                    new += [Token(rng.choice(_BROKEN_SIZES) + "-", "O", "O")] + cue
                repaired = True
            new.append(tok)
        out.append(new)
    if out and rng.random() < 0.3:
        out.append(_plain(*rng.choice(CONFIRMATIONS).split()))
    return out


# --- asides ---------------------------------------------------------------------------------------------------
#: Remarks around an instruction that name sizes, rows, counts and positions of other things: all ``O``.
ASIDES: tuple[str, ...] = (
    "the sheet on top of that pile has a chipped corner",
    "the bottom one in each pile is always a bit damp",
    "the 4x8s are heavy so two of us carry those",
    "there is an outlet box high up on that wall we cut around later",
    "we leave the top row for tomorrow's crew",
    "mind the vent near the bottom of the wall",
    "the window opening is further along on the right",
    "the two 2x8s we got yesterday were warped",
    "the inspector comes at three this afternoon",
    "the last crew left the middle of the wall open",
    "the left end of the room still needs its outlets",
    "keep the offcuts in the corner on the right",
    "a 4 by 6 is easier to lift than a full sheet",
    "we hung the first row too low last time",
    "the drawings say eight foot ceilings",
    "the forklift brought two more pallets this morning",
    "that wall gets tiles above the counter later",
    "the uppermost sheet on the middle pile is scratched",
    "the fourth stud from the corner is a bit bowed",
    "watch the cord on the floor by the stacks",
)


def asides(ch: Chooser, sentences: Sentences) -> Sentences:
    """A remark before or after the instruction (``ASIDES``), its words ``O``; now and then tied on with "by the
    way" or "also"."""
    rng = ch.rng
    words = rng.choice(ASIDES).split()
    lead = rng.choice(["", "", "by the way", "also", "fyi", "heads up"]).split()
    aside = _plain(*lead, *words) + [Token(".", None, None)]
    return [aside] + sentences if rng.random() < 0.5 else sentences + [aside]


# --- plural sizes ---------------------------------------------------------------------------------------------
def plural_sizes(ch: Chooser, sentences: Sentences) -> Sentences:
    """A size said in one word after an article is one of that size: "the 2x8" -> "one of the 2x8s"."""
    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        for tok in sentence:
            compact = tok.is_word and tok.tag == "width" and any(c.isdigit() for c in tok.word) and \
                ("x" in tok.word.lower() or "by" in tok.word.lower())
            if compact and new and new[-1].is_word and new[-1].word.lower() in ("the", "a") and ch.chance(0.6):
                new[-1:] = _plain("one", "of", "the")
                tok = Token(tok.word + "s", tok.tag, tok.coref)
            new.append(tok)
        out.append(new)
    return out


CHANNELS: dict[str, Channel] = {
    "spoken_ids": spoken_ids, "shorthand": shorthand, "disfluency": disfluency, "asides": asides,
    "plural_sizes": plural_sizes,
}
#: How often each channel is applied to a training instruction (independently of each other and of the register).
CHANNEL_RATES: dict[str, float] = {"spoken_ids": 0.15, "shorthand": 0.12, "disfluency": 0.15, "asides": 0.12,
                                   "plural_sizes": 0.10}
#: Held back whole: never in train, validation or test; the novel split uses it.
HELD_BACK: tuple[str, ...] = ("shorthand",)
#: Held back as a pair: each channel is met alone in training, never both at once.
HELD_BACK_PAIRS: tuple[tuple[str, str], ...] = (("spoken_ids", "disfluency"),)


def choose_channels(rng: random.Random, novel: bool) -> tuple[str, ...]:
    """The channels one instruction goes through. In the novel split, each instruction gets one held-back channel
    or held-back pair (and others at their rates); elsewhere none of them."""
    chosen = {name for name, rate in CHANNEL_RATES.items() if rng.random() < rate and name not in HELD_BACK}
    if novel:
        held = [(name,) for name in HELD_BACK] + list(HELD_BACK_PAIRS)
        chosen |= set(rng.choice(held))
    else:
        for a, b in HELD_BACK_PAIRS:
            if a in chosen and b in chosen:
                chosen.discard(rng.choice((a, b)))
    return tuple(name for name in CHANNELS if name in chosen)


def apply_channels(ch: Chooser, sentences: Sentences, names: tuple[str, ...]) -> Sentences:
    """``sentences`` through each named channel, in ``CHANNELS`` order."""
    for name in names:
        sentences = CHANNELS[name](ch, sentences)
    return sentences


def held_back_combinations() -> list[tuple[str, ...]]:
    """Every channel or pair the training splits never contain (for tests and reports)."""
    return [(name,) for name in HELD_BACK] + list(HELD_BACK_PAIRS)
