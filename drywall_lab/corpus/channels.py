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
  things ("the top of that pile is chipped", "the 4x8s are heavy"), or an errand composed of a person, sheets of a size
  or a row, another place and a time ("the tapers would like some 4x6s upstairs"), and so must all be ``O``;
- ``restated_studs``: a stud named by where it is and then said again another way ("on the first stud, the
  leftmost one", "the fourth from the right - the tenth stud");
- ``plural_sizes``: a panel named as one of its size ("one of the 2x8s");
- ``metric_sizes``: a panel's sides in millimetres, centimetres or metres ("1200 x 2400", "a 600 mm wide one");
- ``site_references``: the panel or its stack named first and pointed back at inside the instruction ("the middle
  pile has the ones we want, one from that pile ...", "panel 500310 is next, hang it ..."), or a size said as what is
  left of it ("whatever is left of the full sheets");
- ``openers``: the instruction opened as the next job is ("last thing:", "first off,"), words that name nothing;
- ``code_switch``: words and phrases of another language or dialect mixed in ("la pila de la izquierda", "cuatro
  por ocho", "der mittlere Stapel", "stand am for stud"), from the same lexicon the front end reads them back with
  (``data/lexicon/code_switch.tsv``), an id with the language's case ending now and then ("500104'e"); Chinese and
  Japanese are typed without spaces where the front end cuts them back into the same words
  (``field_generator.written_together``: "装在500106上");
- ``glued_fields``: typed as a program or a terse form ("stud=500104", "centre_line", "3rd-from-right"), a stud as a
  sum ("prev+2", "500104-1") and a value after its label ("size=same", "row=top");
- ``value_repairs``: one value said wrongly and taken back by another of its kind ("stud 500101, er, 500100, sorry",
  "four to the left- right", "the third, no, the fourth").
- ``continued_steps``: a stud counted from the previous one said as going on from where the work is, the anchor
  unsaid ("two studs further right", "one more to the left", "three over to the right").
- ``pasted_tables``: the instruction pasted from a spreadsheet, a header line of labels and a line of values under
  it ("line;panel;stud;edge" / "3;500320;500104;centre line").
- ``chat_messages``: the instruction sent as chat messages under headers with the time and the sender ("[07:09]
  Kev: ..."), now and then a value corrected with a star in a message of its own ("*500105");
- ``anchor_first``: a stud counted from an anchor said before the step, as verb-final languages order it ("from the
  previous stud, two to the right", "starting at 500104 go three to the left").
- ``email_replies``: the instruction sent as an e-mail reply, under a subject line, above or below lines quoted from
  the message it answers (naming other studs, sizes and rows) and over a sign-off ("Dana | PM | Sent from my phone").
- ``crew_crosstalk``: the instruction as two workers said it to each other, copied in under their labels ("MIKE:
  ... DAVE: nah, 500103, ..."), one now and then overruling a value the other said.
- ``hyphenated``: a compound typed with a hyphen, as people write one ("left-line", "bottom-row", "centre-line",
  "far-right").

The front end (``drywall_lab.nlu.normalise``) reads the first three, the metric sides, the code switch, the glued
fields, the values taken back, the pasted tables, an anchor said first, chat messages' headers and starred
corrections, an e-mail's frame, the labels of a conversation and hyphenated compounds into the corpus's written
forms; the tagger must learn the
others, and the IM reads a step that goes on from the last stud (``im.stud.stud_going_on``). Whole channels and pairs of channels are held back from the
training splits (``HELD_BACK``, ``HELD_BACK_PAIRS``): the novel split uses them, so that it measures an instruction
said in a way the tagger never met (first sight).
"""
from __future__ import annotations

import functools
import itertools
import random
import re
from typing import Callable, Iterable

from drywall_lab.corpus.markup import Phrase, Token
from drywall_lab.corpus.phrases import NUMBER_WORDS, ORDINAL_DIGITS, ORDINAL_WORDS, Chooser
from drywall_lab.corpus.tags import PLACEMENT_TAGS
from drywall_lab.site import default_site

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
_ONES = ("", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve",
         "thirteen", "fourteen", "fifteen", "sixteen", "seventeen", "eighteen", "nineteen")
_TENS = ("", "", "twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety")


def _as_hundreds(number: int) -> list[str]:
    """A number from 100 to 999 in words, as an id's last three digits are said ("one hundred six")."""
    rest = number % 100
    words = [_ONES[number // 100], "hundred"]
    if rest >= 20:
        return words + [_TENS[rest // 10]] + ([_ONES[rest % 10]] if rest % 10 else [])
    return words + ([_ONES[rest]] if rest else [])


def say_id(rng: random.Random, ident: str, grouped: bool = True) -> list[str]:
    """An id as people say or type it: digit by digit, with "double", with "hundred" (also as two numbers of
    hundreds: "five hundred one hundred six", unless not ``grouped``), or split in two."""
    form = rng.randrange(6)
    digits = [rng.choice(_DIGIT_WORDS[d]) for d in ident]
    if form == 0 or form == 1:
        return digits
    if form == 2 and ident[1:3] == "00":  # "five double-oh one oh four", "five double oh ..."
        double = ["double-oh"] if rng.random() < 0.5 else ["double", rng.choice(_DIGIT_WORDS["0"])]
        return digits[:1] + double + digits[3:]
    if form == 3 and ident[1:3] == "00":  # "five hundred one oh four", "five hundred one-oh-four", "five hundred
        # one hundred four"
        tail, way = digits[3:], rng.random()
        if grouped and way >= 0.75 and len(_as_hundreds(int(ident[3:]))) == 3:  # as many words as "one oh six"
            return digits[:1] + ["hundred"] + _as_hundreds(int(ident[3:]))
        return digits[:1] + ["hundred"] + (["-".join(tail)] if way < 0.5 else tail)
    if form == 4:
        return [ident[:3], ident[3:]]
    return [f"{ident[:3]}-{ident[3:]}"]


@functools.lru_cache(maxsize=1)
def radio_digits() -> dict[str, str]:
    """Digit words as radio operators say them ("five" -> "fife"), from the shorthand lexicon the front end reads
    them back with (``data/lexicon/abbreviations.tsv``)."""
    from drywall_lab.nlu.normalise import radio_digit_readings

    return {reading: form for form, reading in radio_digit_readings().items()}


def _on_the_radio(ch: Chooser, word: str) -> str:
    """A digit word, or a hyphen-joined run of them, with each digit the radio says its own way so said (half)."""
    forms = radio_digits()
    return "-".join(forms[part] if part in forms and ch.chance(0.5) else part for part in word.split("-"))


def spoken_ids(ch: Chooser, sentences: Sentences) -> Sentences:
    """Every id said or typed in one of ``say_id``'s forms; now and then its last digits are said wrongly, broken
    off and repaired ("five oh oh one one- no, one one one"), the repair's words carrying the tag. One instruction in
    five is said as on a radio: its digits, and the numbers of its counts and sizes, as radio operators say them
    ("five-zero-zero-one-zero-fife", "tree studs over")."""
    radio = ch.chance(0.2)

    def rewrite(tok: Token) -> Phrase | None:
        if radio and not _is_id(tok) and tok.tag != "O" and tok.word.lower() in radio_digits():
            return [_word(_on_the_radio(ch, tok.word.lower()), tok.tag, tok.coref)]
        if not _is_id(tok):
            return None
        said = [_word(_on_the_radio(ch, w) if radio else w, tok.tag, tok.coref) for w in say_id(ch.rng, tok.word, grouped=not radio)]
        if len(said) == 6 and "hundred" not in (t.word for t in said) and ch.chance(0.2):  # digit by digit: "five oh
            # oh one seven- no, one one one"
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
    "the studs on this wall are sixteen on centre",
    "this wall is framed 16 in on center",
    "studs sit at sixteen-inch centres here",
)
#: The things an aside talks about: other panels, piles, rows, studs and openings, by size, count and position.
ASIDE_THINGS: tuple[str, ...] = (
    "the sheet on top of the {side} pile", "the top sheet on the {side} stack", "the bottom one in the {side} pile",
    "the top of the {side} stack", "the {size}s", "two of the {size}s", "the last {size} on the truck",
    "the top row", "the bottom row", "the top course", "the upper half of the wall", "the outlet box near the top",
    "the switch box high on the wall", "the vent down at the bottom", "the window opening on the {side}",
    "the {ordinal} stud from the {side}", "the middle stud", "the stud in the middle", "the centre line marks",
    "the {side} end of the wall", "the door frame on the {side}", "the pile on the {side}", "the {size} offcuts",
    "the {count} sheets left over", "the corner on the {side}",
)
#: What is said of them: no agreement in number needed.
ASIDE_FRAMES: tuple[str, ...] = (
    "mind {thing}", "careful with {thing}", "leave {thing} for later", "don't worry about {thing}",
    "we come back to {thing} tomorrow", "the electrician still has to check {thing}", "watch out for {thing}",
    "ignore {thing} for now", "{thing} can wait", "nobody touches {thing} today", "we measured {thing} twice",
    "the plans changed for {thing}", "I will cut around {thing} myself", "forget about {thing}",
)
#: Remarks about someone else's sheets, another place or a later time: a person or crew, a verb, sheets of a size
#: or a row, a place and a time, composed (``ERRAND_FRAMES``), so that a size or a row said around the instruction
#: is no part of it however the remark is worded. The place is never left out: "we hang a 4x8" alone is a command.
ERRAND_FRAMES: tuple[str, ...] = (
    "{who} will still need {sheets} {where}", "{who} asked for {sheets} {where}", "I promised {sheets} to {who}",
    "we ordered {sheets} {where}", "save {sheets} for {who}", "{sheets} go {where} {when}", "{sheets} are for {who}",
    "the truck brings {sheets} {when}", "we are short on {sheets} {where}", "put {sheets} on the list for {who}",
    "I have to carry {sheets} {where} {when}", "{who} took {sheets} {when}", "we hang {sheets} {where} {when}",
    "leave {sheets} {where} for {who}", "{who} will cut {sheets} {when}", "{who} would like {sheets} {where}",
    "keep {sheets} back for {who}", "{sheets} still have to go {where}", "count {sheets} for {who} {when}",
    "the {row} row {where} waits till {when}", "we do the {row} row {where} {when}",
    "{who} will finish the {row} course {where}", "{who} can start the {row} row {where} {when}",
    "the {row} row {where} is {who}'s job",
)
#: The sheets, rows, people, places and times of an errand.
ERRAND_SLOTS: dict[str, tuple[str, ...]] = {
    "sheets": ("a bundle of {size}s", "a couple of {size}s", "some {size}s", "{count} {size}s", "a stack of {size}s",
               "{count} sheets of {size}", "the rest of the {size}s", "more {size}s", "a few {size} sheets",
               "a {size}", "the {size} pieces", "{count} more {size}s", "the {size}s"),
    "who": ("the tapers", "the other crew", "the crew upstairs", "the framers", "the boss", "Dave", "the client",
            "the next crew", "the electricians", "the plumber", "the site manager", "Ana's team"),
    "where": ("upstairs", "in the hallway", "on the second floor", "on wall B", "on the other wall", "in the garage",
              "for the ceiling", "for the stairwell", "in the back room", "next door", "on the north wall",
              "in unit 4", "at the other job"),
    "when": ("later", "tomorrow", "after lunch", "this afternoon", "first thing monday", "next week", "before five",
             "once we finish here", "", ""),
    "row": ("top", "bottom", "upper", "lower"),
}
#: How an errand is brought up (besides ``ASIDE_LEADS``).
ERRAND_LEADS = ("remind me", "note to self", "don't let me forget", "just so you know", "for the record",
                "side note", "btw", "and")
_ASIDE_SLOTS = {"side": ("left", "right", "middle", "far left", "far right", "first", "last"),
                "size": ("4x8", "2x8", "4x6", "4 by 8", "two by eight", "4 x 6", "full sheet", "2 by 8", "four by six",
                         "4x12", "4 by 10", "half sheet", "four by eight"),
                "ordinal": ("second", "third", "4th", "fifth", "last"), "count": ("two", "three", "4", "five", "six")}


#: How an aside is tied on: before, between or after the instruction; a reason only after it.
ASIDE_LEADS = ("", "", "by the way", "also", "fyi", "heads up", "note", "oh and")
REASON_LEADS = ("because", "since", "as")


def aside_words(rng: random.Random) -> list[str]:
    """One remark: a fixed one (``ASIDES``), a frame (``ASIDE_FRAMES``) said of a thing (``ASIDE_THINGS``), or an
    errand (``ERRAND_FRAMES``), now and then brought up with ``ERRAND_LEADS``."""
    draw = rng.random()
    if draw < 0.2:
        return rng.choice(ASIDES).split()
    if draw < 0.55:
        text = rng.choice(ASIDE_FRAMES).replace("{thing}", rng.choice(ASIDE_THINGS))
    else:
        text = rng.choice(ERRAND_FRAMES)
        for slot, values in ERRAND_SLOTS.items():
            text = text.replace("{" + slot + "}", rng.choice(values))
        if rng.random() < 0.4:
            text = rng.choice(ERRAND_LEADS) + " " + text
        text = text.replace("{count} {size}s", "{count} of the {size}s") if rng.random() < 0.5 else text
    for slot, values in _ASIDE_SLOTS.items():
        text = text.replace("{" + slot + "}", rng.choice(values))
    return re.sub(r"\bsixs\b", "sixes", text).split()


def asides(ch: Chooser, sentences: Sentences) -> Sentences:
    """A remark (``aside_words``) before, between or after the instruction's sentences, its words ``O``; now and
    then tied on with "by the way", "also", "because" (after) or set off with dashes."""
    rng = ch.rng
    at = rng.randrange(len(sentences) + 1)
    lead = rng.choice(list(ASIDE_LEADS) + (list(REASON_LEADS) if at == len(sentences) and at else [])).split()
    aside = _plain(*lead, *aside_words(rng)) + [Token(".", None, None)]
    if 0 < at < len(sentences) and rng.random() < 0.3:  # "-- mind the top row --" inside
        aside = _plain("--") + aside[:-1] + _plain("--")
    return sentences[:at] + [aside] + sentences[at:]


# --- stack talk -----------------------------------------------------------------------------------------------
STACK_WORDS = frozenset({"stack", "pile", "pallet", "bunch", "lot", "stacks", "piles"})
_PANEL_WORDS = frozenset({"sheet", "panel", "board", "drywall", "piece", "one", "rock", "sheetrock", "plasterboard",
                          "wallboard"})
#: Which sheet of a pile: always its top one (the only one the robot may take), so every word here is ``O``.
TOP_OF_A_PILE = (("the", "top", "of"), ("the", "very", "top", "of"), ("on", "top", "of"), ("the", "top", "of"))
TOP_OF_NO_PILE = ("off the top of the pile", "from the top of its stack", "on top", "off the top", "at the top of the pile",
                  "that's on top", "sitting on top", "from the top of the pile")
TOP_BEFORE_A_PANEL = ("top", "topmost", "uppermost", "top")


def stack_talk(ch: Chooser, sentences: Sentences) -> Sentences:
    """The panel taken from the top of its pile, said in words that elsewhere name a row: "from the top of the
    middle pile", "the top 2x8", "the top sheet", "right pile top sheet", "the 4x8 sheet off the top of the pile". Every added word is ``O``: the sheet on
    top is the only one the robot may take, and "top" here is no row."""
    rng = ch.rng
    out: Sentences = []
    done = False
    for sentence in sentences:
        new: Phrase = []
        for i, tok in enumerate(sentence):
            word = tok.word.lower() if tok.is_word else ""
            ahead = [t.word.lower() for t in sentence[i + 1:i + 5] if t.is_word]
            if not done and word in ("from", "off") and ahead[:1] == ["the"] and not STACK_WORDS.isdisjoint(ahead):
                new += [tok] + _plain(*rng.choice(TOP_OF_A_PILE))  # "from" + "the top of" + "the middle pile"
                done = True
                continue
            nxt = sentence[i + 1] if i + 1 < len(sentence) else None
            standard = nxt is not None and nxt.is_word and (nxt.tag == "width" or (
                nxt.tag == "dim" and nxt.word.lower() in ("full", "full-size", "standard", "regular")))
            noun = nxt is not None and nxt.is_word and nxt.tag == "O" and nxt.word.lower() in _PANEL_WORDS - {"one"}
            if not done and (word == "the" or (word in STACK_WORDS and tok.tag == "O")) and (standard or noun) \
                    and rng.random() < 0.5:  # "the top 2x8", "the top sheet", "right pile top sheet"
                new += [tok] + _plain(rng.choice(TOP_BEFORE_A_PANEL))
                done = True
                continue
            new.append(tok)
            last_noun = nxt is None or not nxt.is_word or nxt.word.lower() not in _PANEL_WORDS | {"of"}
            if not done and word in _PANEL_WORDS and tok.tag == "O" and i and sentence[i - 1].is_word and last_noun \
                    and sentence[i - 1].tag in ("width", "length", "dim") and rng.random() < 0.6:
                new += _plain(*rng.choice(TOP_OF_NO_PILE).split())  # "the 4x8 sheet" + "off the top of the pile"
                done = True
        out.append(new)
    return out


# --- relative talk --------------------------------------------------------------------------------------------
#: A step along the wall said as an order, not a side: studs are numbered from the left end, so "past", "after",
#: "beyond", "further along" go right and "before", "back from" go left (``im.words.ORDER_WORDS`` reads them).
ALONG_FORMS: dict[str, tuple[tuple[str, ...], ...]] = {
    "right": (("past",), ("after",), ("beyond",), ("further", "along", "from"), ("along", "from"), ("on", "past"),
              ("up", "past")),
    "left": (("before",), ("back", "from"), ("short", "of")),
}
_SIDE_WORDS = frozenset({"left", "right", "left-hand", "right-hand"})
_SPAN_FILLER = frozenset({"to", "the", "over", "further", "of", "from"})


def _along(rng: random.Random, side: str) -> list[str]:
    return list(rng.choice(ALONG_FORMS[side]))


def relative_talk(ch: Chooser, sentences: Sentences) -> Sentences:
    """A stud counted from another said as an order along the wall: "two to the right of 500104" -> "two past
    500104", "one to the left of the last one" -> "the stud before the last one". The count keeps its tag; the
    order words take the direction's tag (``St_loc1``); the words between go."""
    rng = ch.rng
    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        i = 0
        while i < len(sentence):
            tok = sentence[i]
            if not (tok.is_word and tok.tag == "St_loc1"):
                new.append(tok)
                i += 1
                continue
            j = i
            while j < len(sentence) and sentence[j].is_word and (sentence[j].tag == "St_loc1" or
                                                                  (sentence[j].tag == "O" and sentence[j].word.lower() in ("studs", "stud"))):
                j += 1
            span = sentence[i:j]
            k = j
            while k < len(sentence) and sentence[k].is_word and sentence[k].tag == "O" \
                    and sentence[k].word.lower() in ("of", "from", "the", "stud"):
                k += 1
            sides = {t.word.lower().removesuffix("-hand") for t in span if t.word.lower() in _SIDE_WORDS}
            anchored = k < len(sentence) and sentence[k].is_word and sentence[k].tag == "St_loc2"
            if len(sides) != 1 or not anchored or any(t.word.lower() in ("far", "from") for t in span) \
                    or rng.random() < 0.3:
                new += sentence[i:j]
                i = j
                continue
            side = next(iter(sides))
            kept = [t for t in span if t.word.lower() not in _SIDE_WORDS and t.word.lower() not in _SPAN_FILLER]
            said_stud = bool(new) and new[-1].is_word and new[-1].word.lower() in ("stud", "post", "upright")
            if said_stud and len(kept) == 1 and kept[0].word.lower() in ("one", "1", "just", "next"):
                kept = []  # "on the stud after 500104", "the stud before the last one"
            order = [Token(w, tok.tag, tok.coref) for w in _along(rng, side)]
            between = sentence[j:k]
            determiners = [t for t in between if t.word.lower() == "the"]
            new += kept + order + determiners[-1:] + [t for t in between if t.word.lower() == "stud"][-1:]
            i = k
        out.append(new)
    return out


# --- metric sizes ---------------------------------------------------------------------------------------------
_FEET_WORDS = {"two": 2, "four": 4, "six": 6, "eight": 8, "2": 2, "4": 4, "6": 6, "8": 8}
_METRIC = {"mm": {2: "600", 4: "1200", 6: "1800", 8: "2400"}, "m": {2: "0.6", 4: "1.2", 6: "1.8", 8: "2.4"},
           "cm": {2: "60", 4: "120", 6: "180", 8: "240"}}
METRIC_UNIT_WORDS = {"mm": ("mm", "mil", "millimetres"), "m": ("m", "metres", "meters"), "cm": ("cm", "centimetres")}
_ONE_SIDE = re.compile(r"^(two|four|six|eight|[2468])(?:'|ft|-foot|-ft)?$", re.I)
_BOTH_SIDES = re.compile(r"^(two|four|six|eight|[2468])'?\s*(?:x|-by-|by)\s*(two|four|six|eight|[2468])'?$", re.I)
_FOOT_UNITS = frozenset({"foot", "feet", "ft", "'", "ft."})


def metric_sizes(ch: Chooser, sentences: Sentences) -> Sentences:
    """A panel's sides said in metric, as a worker used to metric boards says them: "1200 x 2400", "a 600 mm wide
    one", "1.2 by 1.8", "120 cm by 240 cm" (one unit an instruction). The numbers keep their tags; a foot unit
    becomes the metric one, and a side said alone gets its unit."""
    rng = ch.rng
    unit = rng.choice(("mm", "mm", "m", "cm"))
    table = _METRIC[unit]

    def side(word: str) -> int | None:
        m = _ONE_SIDE.match(word)
        return _FEET_WORDS[m.group(1).lower()] if m else None

    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        for i, tok in enumerate(sentence):
            if not (tok.is_word and tok.tag in ("width", "length")):
                if tok.is_word and tok.word.lower() in _FOOT_UNITS and new and new[-1].tag in ("width", "length") \
                        and new[-1].word in table.values():
                    new.append(Token(rng.choice(METRIC_UNIT_WORDS[unit]), "O", "O"))  # "4 foot" -> "1200 mm"
                    continue
                new.append(tok)
                continue
            both = _BOTH_SIDES.match(tok.word)
            if both:
                a, b = (table[_FEET_WORDS[g.lower()]] for g in both.groups())
                suffix = unit if unit == "cm" or (unit == "mm" and rng.random() < 0.3) else ""  # "1200x2400mm"
                new.append(Token(f"{a}x{b}{suffix}", tok.tag, tok.coref))
                continue
            feet = side(tok.word)
            if feet is None:
                new.append(tok)
                continue
            new.append(Token(table[feet], tok.tag, tok.coref))
            ahead = [t.word.lower() for t in sentence[i + 1:i + 3] if t.is_word]
            behind = new[-2].word.lower() if len(new) > 1 and new[-2].is_word else ""
            paired = behind in ("x", "by") or any(w in ("x", "by") for w in ahead)  # "1200 by 2400": no unit needed
            said_unit = bool(ahead) and ahead[0] in _FOOT_UNITS  # the foot unit after it becomes the metric one
            if not said_unit and (unit == "cm" or not paired):
                new.append(Token(rng.choice(METRIC_UNIT_WORDS[unit]), "O", "O"))  # "the 600 mm wide one"
        out.append(new)
    return out


# --- references inside the instruction ------------------------------------------------------------------------
_TARGET_TAGS = frozenset({"ID_wall", "dim", "length", "width", "Dw_loc1"})
#: ``O`` words a size or a stack may hold between its tagged words ("2 x 8", "four foot by eight", "full size").
_SPAN_LINKS = frozenset({"x", "by", "-", "foot", "feet", "ft", "wide", "long", "tall", "high", "across", "size", "'",
                         "inch", "inches", "hand", "side"})
_UNIT_WORDS = frozenset({"wide", "long", "tall", "high", "foot", "feet", "ft", "size", "'"})
_ID_LEADS = frozenset({"labelled", "labeled", "marked", "tagged", "with", "id", "number", "no.", "#"})
_DETERMINERS = frozenset({"the", "a", "an", "one"})
_NOUNS = _PANEL_WORDS - {"one"} | {"of", "sheets", "panels", "boards", "pieces", "rocks"}
#: What the first mention says of its referent; the instruction then points back at it (all ``O``).
NAMED_FIRST: dict[str, tuple[tuple[str, ...], ...]] = {
    "size": (("are", "the", "ones", "we", "want"), ("are", "next"), ("are", "what", "we", "need"),
             ("are", "over", "there")),
    "stack": (("has", "the", "ones", "we", "want"), ("is", "where", "they", "are"), ("holds", "what", "we", "need"),
              ("is", "the", "one", "to", "use")),
    "id": (("is", "next"), ("is", "the", "one"), ("is", "what", "we", "need")),
}
POINTING_BACK: dict[str, tuple[tuple[str, ...], ...]] = {
    "size": (("one", "of", "those"), ("one", "of", "them"), ("one",), ("one", "of", "'em")),
    "stack": (("that", "{stack}"), ("that", "one"), ("it",)),
    "id": (("it",), ("that", "one"), ("that", "{noun}")),
}
WHAT_IS_LEFT = (("whatever", "is", "left", "of", "the"), ("one", "of", "whatever"), ("one", "of", "the", "remaining"),
                ("what's", "left", "of", "the"))


def _extend_left(sentence: Phrase, a: int, words: frozenset[str] | set[str]) -> int:
    while a and sentence[a - 1].is_word and sentence[a - 1].tag == "O" and sentence[a - 1].word.lower() in words:
        a -= 1
    return a


def _target_span(sentence: Phrase) -> tuple[int, int, str] | None:
    """Where one sentence names the panel or its stack in one stretch, with its article and noun: ``(start, end,
    kind)``, kind ``size``, ``stack`` or ``id``; None where the words of the target are spread out, or a size is a
    bare number ("width of two")."""
    tagged = [i for i, t in enumerate(sentence) if t.is_word and t.tag in _TARGET_TAGS]
    if not tagged or any(t.is_word and t.tag == "Dw_loc2" for t in sentence):
        return None
    a, b = tagged[0], tagged[-1] + 1
    if any(not t.is_word or (t.tag == "O" and t.word.lower() not in _SPAN_LINKS) or
           (t.tag != "O" and t.tag not in _TARGET_TAGS) for t in sentence[a:b]):
        return None
    tags = {t.tag for t in sentence[a:b]} - {"O"}
    kind = "id" if tags == {"ID_wall"} else "stack" if tags == {"Dw_loc1"} else \
        "size" if tags <= {"dim", "length", "width"} else None
    b_links = b
    while b_links < len(sentence) and sentence[b_links].is_word and sentence[b_links].tag == "O" and \
            sentence[b_links].word.lower() in _UNIT_WORDS:
        b_links += 1
    if kind == "size":
        b = b_links
        said = sentence[a:b]
        has_unit = any(t.tag == "O" for t in said) or "dim" in tags or {"width", "length"} <= tags or \
            any("x" in t.word.lower() and any(c.isdigit() for c in t.word) for t in said)
        if not has_unit:
            return None
    while b < len(sentence) and sentence[b].is_word and sentence[b].tag == "O" and \
            sentence[b].word.lower() in (_NOUNS | STACK_WORDS if kind == "stack" else _NOUNS):
        b += 1
    a = _extend_left(sentence, a, _NOUNS | (_ID_LEADS if kind == "id" else set()))
    a = _extend_left(sentence, a, _DETERMINERS | {"second", "more", "another"})
    if a >= 2 and [t.word.lower() for t in sentence[a - 2:a] if t.is_word] == ["one", "of"]:
        a -= 2
    if kind == "stack" and STACK_WORDS.isdisjoint(t.word.lower() for t in sentence[a:b]):
        return None  # "the one on the right": no stack to name first
    if kind == "id" and [t.word.lower() for t in sentence[b:b + 2] if t.is_word] == ["on", "it"]:
        b += 2  # "the one with 500310 on it"
    return (a, b, kind) if kind else None


def site_references(ch: Chooser, sentences: Sentences) -> Sentences:
    """The panel or its stack named first, the instruction pointing back at it: "the 2x8 sheets are over there. Put
    one of those on 500104", "the middle pile has the ones we want; grab one from that pile", "panel 500310 is next,
    hang it ..."; or a size said as what is left of it ("whatever is left of the full sheets"). The tagged words
    move with their tags; every word added is ``O``."""
    rng = ch.rng
    found = [(k, span) for k, s in enumerate(sentences) if (span := _target_span(s))]
    if len(found) != 1:
        return sentences
    k, (a, b, kind) = found[0]
    sentence = sentences[k]
    named = [t for t in sentence[a:b] if t.tag != "O" or t.word.lower() in _SPAN_LINKS | STACK_WORDS]
    nouns = [t for t in sentence[a:b] if t.tag == "O" and t.word.lower() in _NOUNS]
    if kind == "size" and rng.random() < 0.35:  # "whatever is left of the full sheets"
        plural = _plain(rng.choice(("sheets", "panels", "boards", "ones")))
        left = _plain(*rng.choice(WHAT_IS_LEFT))
        tail = _plain("are", "left") if left[-1].word == "whatever" else []
        return sentences[:k] + [sentence[:a] + left + named + plural + tail + sentence[b:]] + sentences[k + 1:]
    if kind == "size":
        first = _plain("the") + named + _plain(rng.choice(("sheets", "panels", "boards")))
    elif kind == "stack":
        first = _plain("the") + named
    else:
        first = (nouns[:1] or _plain("panel")) + [t for t in named if t.tag == "ID_wall"]
    first += _plain(*rng.choice(NAMED_FIRST[kind]))
    stack = next((t.word for t in named if t.word.lower() in STACK_WORDS), "pile")
    back = [w.replace("{stack}", stack).replace("{noun}", nouns[0].word if nouns else "panel")
            for w in rng.choice(POINTING_BACK[kind])]
    rest = sentence[:a] + _plain(*back) + sentence[b:]
    if rng.random() < 0.5:
        return sentences[:k] + [first + [Token(".", None, None)], rest] + sentences[k + 1:]
    return sentences[:k] + [first + [Token(",", None, None)] + rest] + sentences[k + 1:]


# --- a stud said twice ---------------------------------------------------------------------------------------
#: What joins a stud's position to the same position said again ("the first stud , the leftmost one"): all O.
RESTATE_LEADS = ((",",), (",", "yeah", ","), (",", "so"), (",", "that's"), ("-",), (",", "which", "is"), (".",))


def _stud_positions(ch: Chooser, index: int, studs: int) -> list[Phrase]:
    """The ways to name the stud at ``index`` (0 = the left end) by where it is, each ``St_loc1`` on its position
    words (guidelines: ``the fifth/St_loc1 stud``, ``fourth/St_loc1 from/St_loc1 the/St_loc1 right/St_loc1``)."""
    def pos(*words: str, tagged_from: int = 0, noun: str = "") -> Phrase:
        lead = _plain(*words[:tagged_from])
        said = [Token(w, "St_loc1", "St_loc1") for w in words[tagged_from:]]
        return lead + said + (_plain(noun) if noun else [])
    def from_end(n: int, side: str) -> Phrase:
        said = pos("the", ch.ordinal(n), "from", "the", side, tagged_from=1)
        return said if ch.chance(0.5) else said[:2] + _plain("stud") + said[2:]  # "the fourth stud from the right"
    noun = ch.rng.choice(("stud", "one", "stud"))
    forms: list[Phrase] = []
    if index + 1 in ORDINAL_WORDS:
        forms += [pos("the", ch.ordinal(index + 1), tagged_from=1, noun=noun), from_end(index + 1, "left")]
    if studs - index in ORDINAL_WORDS:
        forms += [from_end(studs - index, "right"), from_end(studs - index, "right")]
    if index == 0:
        forms += [pos("the", "leftmost", tagged_from=1, noun=noun), pos("the", "far", "left", tagged_from=1, noun=noun),
                  pos("the", "very", "first", tagged_from=1, noun=noun)]
    if index == studs - 1:
        forms += [pos("the", "rightmost", tagged_from=1, noun=noun), pos("the", "far", "right", tagged_from=1, noun=noun)]
    if index == studs // 2:
        forms += [pos("the", "middle", tagged_from=1, noun=noun), pos("the", "centre", tagged_from=1, noun=noun)]
    return forms


def restated_studs(ch: Chooser, sentences: Sentences) -> Sentences:
    """A stud named by where it is, then said again another way: "on stud 500100" -> "on the first stud, the
    leftmost one", "on stud 500106" -> "on the seventh from the right - the middle one". Both positions carry ``St_loc1`` (guidelines:
    a stud named twice, tag both); they name the same stud, which the IM checks (``im.stud.stud_by_position``)."""
    studs = len(default_site().studs)
    if any(tok.is_word and tok.tag == "St_loc1" for sentence in sentences for tok in sentence):
        return sentences  # already said by its position as well as by its id: a third saying is no restatement
    out: Sentences = []
    done = False
    for sentence in sentences:
        new: Phrase = []
        for tok in sentence:
            index = int(tok.word) - 500100 if tok.is_word and tok.tag == "ID_stud" and _is_id(tok) else -1
            if done or not 0 <= index < studs:
                new.append(tok)
                continue
            forms = _stud_positions(ch, index, studs)
            first, again = ch.rng.sample(forms, 2) if len(forms) > 1 else (forms[0], forms[0])
            if new and new[-1].is_word and new[-1].tag == "O" and new[-1].word.lower() in ("stud", "post"):
                new.pop()  # "on stud 500104" -> "on the fifth stud , ..."
            lead = [Token(w, None, None) if w in (",", ".") else Token(w) for w in ch.rng.choice(RESTATE_LEADS)]
            new += first + lead + again
            done = True
        out.append(new)
    return out


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


# --- code switch ---------------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=1)
def _foreign_forms() -> dict[str, dict[tuple[str, ...], list[str]]]:
    """Language -> English words (a reading of the code-switch lexicon) -> the forms the front end reads as them."""
    from drywall_lab.nlu.normalise import read_code_switch

    forms: dict[str, dict[tuple[str, ...], list[str]]] = {}
    for form, reading, language in read_code_switch():
        if reading:
            forms.setdefault(language, {}).setdefault(tuple(reading.lower().split()), []).append(form)
    return forms


def _switched(ch: Chooser, sentence: Phrase, forms: dict[tuple[str, ...], list[str]], longest: int) -> Phrase:
    from drywall_lab.nlu.normalise import DIGIT_WORDS, DIGITS_ONLY_IN_A_RUN

    def in_number(k: int) -> bool:  # a digit said between two number words: "um" may be one there
        return all(0 <= j < len(sentence) and sentence[j].word.lower() in DIGIT_WORDS for j in (k - 1, k + 1))

    new: Phrase = []
    i = 0
    while i < len(sentence):
        run = sentence[i:i + longest]
        english = [t.word.lower() for t in run]
        n = next((n for n in range(len(run), 0, -1) if all(t.is_word for t in run[:n])
                  and len({(t.tag, t.coref) for t in run[:n]}) == 1 and tuple(english[:n]) in forms), 0)
        said_as = [f for f in forms[tuple(english[:n])] if f not in DIGITS_ONLY_IN_A_RUN or in_number(i)] if n else []
        if said_as and ch.chance(0.5):
            said = ch.rng.choice(said_as)
            new += [Token(w, run[0].tag, run[0].coref) for w in said.split()]
            i += n
            continue
        new.append(sentence[i])
        i += 1
    return new


def code_switch(ch: Chooser, sentences: Sentences) -> Sentences:
    """A worker who mixes another language into the instruction (one of the code-switch lexicon's,
    ``data/lexicon/code_switch.tsv``, drawn for the instruction): each run of words that the lexicon reads, of one
    tag, is said in that language half the time, the longest run first ("the pile on the left" -> "la pila de la
    izquierda", "the middle pile" -> "der mittlere Stapel"); the words keep their tag. A sentence the front end would
    not read back into its own words and tags (forms run together into a longer one) is drawn again, or left in
    English."""
    from drywall_lab.nlu.normalise import normalise

    by_language = _foreign_forms()
    language = ch.rng.choice(sorted(by_language))
    forms = by_language[language]
    longest = max(map(len, forms))

    def read(phrase: Phrase) -> tuple[list[str], list[str]]:
        said = [t for t in phrase if t.is_word]
        n = normalise(" ".join(t.word for t in said))
        return [w.lower() for w in n.words], n.tags_of_words([t.tag for t in said])

    out: Sentences = []
    for sentence in sentences:
        english = read(sentence)
        new = next((new for new in (_switched(ch, sentence, forms, longest) for _ in range(3))
                    if read(new) == english), sentence)
        if language in CASE_ENDINGS:  # "500104'e": an id takes the language's case ending now and then
            new = [Token(t.word + ch.rng.choice(CASE_ENDINGS[language]), t.tag, t.coref)
                   if _is_id(t) and ch.chance(0.5) else t for t in new]
        out.append(new)
    return out


#: Case endings that languages with cases put on an id, and the particles Korean writes on one, as their speakers type
#: them.
CASE_ENDINGS = {"tr": ("'e", "'a", "'ye", "'ya", "'de", "'da", "'den", "'dan", "’e"),
                "ru": ("-й", "-го", "-му", "-м", "-ом"), "uk": ("-й", "-го", "-му", "-ому"),
                "pl": ("-ego", "-ym", "-u", "-em"), "ko": ("에", "번", "번에", "에다", "부터")}


# --- openers -------------------------------------------------------------------------------------------------
#: How people open the next job: words that name nothing ("last thing", "one more thing", "first off").
OPENERS: tuple[tuple[str, ...], ...] = tuple(sorted(
    {(*lead, noun) for lead in (("last",), ("final",), ("first",), ("next",), ("one", "last"), ("one", "more"))
     for noun in ("thing", "job", "bit")}
    | {("first", "off"), ("next", "up"), ("first", "of", "all"), ("last", "of", "all")}
    | {(last, noun, *when) for last in ("last", "final") for noun in ("one", "panel", "sheet")
       for when in (("for", "today"), ("for", "me"), ("of", "the", "day"))}))
_OPENER_LEADS = ("okay", "right", "so", "and", "alright")


def openers(ch: Chooser, sentences: Sentences) -> Sentences:
    """The instruction opened as people open the next job ("last thing:", "okay, one more thing,", "first off,",
    "final one for today:"): its "last", "first" or "one" names nothing (``O``)."""
    words = list(ch.rng.choice(OPENERS))
    if ch.chance(0.25):
        words = [ch.rng.choice(_OPENER_LEADS), ","] + words
    opener = [Token(w, None, None) if w == "," else Token(w) for w in words]
    opener.append(Token(ch.rng.choice([":", ","]), None, None))
    return [opener + sentences[0], *sentences[1:]] if sentences else sentences


# --- glued fields -------------------------------------------------------------------------------------------



def _glued_runs(sentence: Phrase, position_joiner: str = "_") -> Phrase:
    """Each run of two or more words of one tag as one word joined by "_" ("centre_line", "five_oh_oh_one_oh_four"),
    a position's run by ``position_joiner`` ("3rd-from-right": the front end's ``split_fields`` reads both)."""
    from drywall_lab.nlu.normalise import joined_position

    runs: list[list[Token]] = []
    out: Phrase = []
    for tok in sentence:
        last = runs[-1][-1] if runs else None
        if (tok.is_word and tok.tag != "O" and last is not None and last.is_word and last.tag != "O"
                and (last.tag, last.coref) == (tok.tag, tok.coref)):
            runs[-1].append(tok)
        else:
            runs.append([tok])
    for run in runs:
        if len(run) == 1:
            out.append(run[0])
            continue
        words = [t.word for t in run]
        dashed = "-".join(words)
        joiner = position_joiner if joined_position(dashed) == words else "_"
        out.append(Token(joiner.join(words), run[0].tag, run[0].coref))
    return out


_COUNTS = {**{w: n for n, w in NUMBER_WORDS.items() if n}, **{str(n): n for n in range(1, 13)}}
#: Words inside a relative stud's span or between it and its anchor that a sum leaves out ("two studs over to the
#: right of the previous stud" -> "prev+2").
_SUM_FILLER = frozenset({"to", "the", "over", "studs", "stud", "places", "place", "of", "from", "one"})
#: Anchors a sum can name: the last accepted command's stud, or an id.
_SUM_ANCHORS = {("previous",): "prev", ("last",): "last", ("previous", "one"): "prev", ("last", "one"): "last"}


def _count_and_side(sentence: Phrase, i: int) -> tuple[int, str | None] | None:
    """A count tagged ``St_loc1`` at ``i`` and the words of its step up to its side ("two studs to the right"): the
    position after the side (or after the step's words, when no side is said) and the side, or None when no count
    starts at ``i``."""
    tok = sentence[i]
    if not (tok.is_word and tok.tag == "St_loc1" and tok.word.lower() in _COUNTS):
        return None
    j, side = i + 1, None
    while j < len(sentence) and sentence[j].is_word and (sentence[j].tag == "St_loc1" or (
            sentence[j].tag == "O" and sentence[j].word.lower() in _SUM_FILLER)) and side is None:
        side = sentence[j].word.lower() if sentence[j].word.lower() in ("left", "right") else None
        j += 1
    return j, side


def _sum_at(sentence: Phrase, i: int) -> tuple[int, str, str, int] | None:
    """A stud counted from the previous one or from an id that starts at ``i`` ("two studs to the right of the
    previous stud", "one to the left of 500104"): (the end of its words, the anchor's name in a sum: "prev", "last"
    or the id, the side, the count), or None."""
    counted = _count_and_side(sentence, i)
    if counted is None:
        return None
    j, side = counted
    k = j
    while k < len(sentence) and sentence[k].is_word and sentence[k].tag == "O" and sentence[k].word.lower() in ("of", "the"):
        k += 1
    e = k
    while e < len(sentence) and sentence[e].is_word and sentence[e].tag == "St_loc2":
        e += 1
    anchor = [t.word.lower() for t in sentence[k:e]]
    name = anchor[0] if len(anchor) == 1 and anchor[0].isdigit() and len(anchor[0]) == 6 else _SUM_ANCHORS.get(tuple(anchor))
    if side is None or name is None or sentence[j - 1].word.lower() != side or not 0 < k - j <= 2 or \
            any(t.tag == "St_loc1" and t.word.lower() == "from" for t in sentence[i:j]):
        return None
    if e < len(sentence) and sentence[e].is_word and sentence[e].tag == "O" and sentence[e].word.lower() in ("stud", "one"):
        e += 1
    return e, name, side, _COUNTS[sentence[i].word.lower()]


def _written_sums(sentence: Phrase, spaced: bool = False) -> Phrase:
    """A stud counted from the previous one or from an id, written as a sum ("two studs to the right of the previous
    stud" -> "prev+2", "one to the left of 500104" -> "500104-1"; ``spaced``: "prev stud +2"; tagged ``St_loc1``,
    the front end's ``read_offsets`` reads it back); other relative talk stays as it is."""
    out: Phrase = []
    i = 0
    while i < len(sentence):
        found = _sum_at(sentence, i)
        if found is None:
            out.append(sentence[i])
            i += 1
            continue
        e, name, side, count = found
        tok = sentence[i]
        sign = f"{'+' if side == 'right' else '-'}{count}"
        if spaced and not name.isdigit():
            out += [Token(name, "St_loc1", tok.coref), Token("stud", "St_loc1", tok.coref), Token(sign, "St_loc1", tok.coref)]
        else:
            out.append(Token(f"{name}{sign}", "St_loc1", tok.coref))
        i = e
    return out


#: How a step from the previous stud is said as going on from where the work is ({n}: the count, {s}: the side); the
#: IM counts such a step from the previous stud (``im.stud.stud_going_on``).
GOING_ON_FORMS = ("{n} studs further {s}", "{n} more to the {s}", "{n} studs over to the {s}", "{n} further to the {s}",
                  "{n} stud more {s}", "{n} over to the {s}")


def _step_from_the_last(sentence: Phrase, i: int) -> tuple[int, str] | None:
    """A stud counted from the previous one that starts at ``i`` ("two studs to the right of the previous stud",
    "one to the left of the one you just used", "three over to the right of that one", "two right from the last
    stud"): (the end of its words, the side), or None. The anchor is the ``St_loc2`` words after "of" or "from" (a few
    untagged words may come first: "of the one you just used"), and they point back (``im.words.points_back``)."""
    from drywall_lab.im.words import ids_in, points_back, says_end

    found = _counted_step(sentence, i, ("of", "from"))
    if found is None:
        return None
    e, side, of = found
    anchor = [t.word for t in sentence[of + 1:e] if t.tag == "St_loc2"]
    if not points_back(anchor) or ids_in(anchor) or says_end(anchor):
        return None
    return e, side


def _counted_step(sentence: Phrase, i: int, links: tuple[str, ...] = ("of",)) -> tuple[int, str, int] | None:
    """A stud counted from an anchor that starts at ``i`` ("two studs to the right of the previous stud", "one to the
    left of 500104"; with ``links`` ("of", "from"), "two right from 500104" too): (the end of its words, the side,
    the position of the link), or None. The anchor is the ``St_loc2`` words after the link (a few untagged words may
    come first), and a few untagged nouns after them ("stud", "one")."""
    counted = _count_and_side(sentence, i)
    if counted is None:
        return None
    j, side = counted
    if side is None or sentence[j - 1].word.lower() != side or j >= len(sentence) or sentence[j].word.lower() not in links:
        return None
    k = j + 1
    while k < min(len(sentence), j + 5) and sentence[k].is_word and sentence[k].tag == "O":
        k += 1
    e = k
    while e < len(sentence) and sentence[e].is_word and sentence[e].tag == "St_loc2":
        e += 1
    if e == k:
        return None
    while e < len(sentence) and sentence[e].is_word and sentence[e].tag == "O" and \
            sentence[e].word.lower() in ("stud", "one", "used", "installed", "hung"):
        e += 1
    return e, side, j


def continued_steps(ch: Chooser, sentences: Sentences) -> Sentences:
    """A stud counted from the previous one said as going on from where the work is, the anchor left unsaid ("two
    studs to the right of the previous stud" -> "two studs further right", "one more to the left", "three over to the
    right"; ``GOING_ON_FORMS``). The count, the going-on word and the side are ``St_loc1``, a stud noun ``O``."""
    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        i = 0
        while i < len(sentence):
            found = _step_from_the_last(sentence, i)
            if found is None:
                new.append(sentence[i])
                i += 1
                continue
            e, side = found
            count = sentence[i]
            for k, word in enumerate(ch.rng.choice(GOING_ON_FORMS).format(n=count.word, s=side).split()):
                tag = "O" if word in ("stud", "studs") else "St_loc1"
                word = "stud" if word == "studs" and count.word.lower() in ("one", "1") else word
                new.append(count if k == 0 else Token(word, tag, count.coref if tag != "O" else "O"))
            i = e
        out.append(new)
    return out


#: How an anchor said first is led in ("from the previous stud, two to the right").
ANCHOR_LEADS = (("from",), ("from",), ("starting", "from"), ("counting", "from"), ("starting", "at"))


def anchor_first(ch: Chooser, sentences: Sentences) -> Sentences:
    """A stud counted from an anchor, the anchor said first as verb-final languages and people thinking aloud put it
    ("two studs to the right of the previous stud" -> "from the previous stud two studs to the right", "starting at
    500104 go three to the left"; an anchor that points back sometimes with no lead: "the last one two to the
    left"). The words keep their tags; the link ("of", "from") goes, a lead ("from") and a "go" are ``O``. The front end puts the
    anchor back after the step (``nlu.normalise.anchor_last``)."""
    from drywall_lab.im.words import ids_in, points_back

    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        i = 0
        while i < len(sentence):
            found = _counted_step(sentence, i, ("of", "from"))
            if found is None:
                new.append(sentence[i])
                i += 1
                continue
            e, _, of = found
            anchor = list(sentence[of + 1:e])
            words = [t.word for t in anchor if t.tag == "St_loc2"]
            back = points_back(words) and not ids_in(words)
            lead = () if back and ch.chance(0.25) else ch.rng.choice(ANCHOR_LEADS)
            go = ("go",) if ch.chance(0.2) else ()
            new += [Token(w, "O", "O") for w in lead] + anchor + [Token(w, "O", "O") for w in go] + list(sentence[i:of])
            i = e
        out.append(new)
    return out


# --- chat messages -----------------------------------------------------------------------------------------
#: Who sends a chat message, and the forms of a message's header ({t}: the time, {n}: the sender, {d}: the date).
CHAT_SENDERS = ("Kev", "Dave", "Ana", "Marco", "Li", "Sam Ortiz", "Priya", "Tomek", "J.B.")
CHAT_HEADERS = ("[{t}] {n}:", "{t} - {n}:", "{n} ({t}):", "[{d}, {t}] {n}:", "{d} {t} - {n}:", "[{t}] {n}:")


def _header(form: str, sender: str, minute: int, date: str) -> Phrase:
    clock = f"{minute // 60:02d}:{minute % 60:02d}"
    return [Token(w, "O", "O") for w in form.format(t=clock, n=sender, d=date).split()]


def chat_messages(ch: Chooser, sentences: Sentences) -> Sentences:
    """The instruction sent as chat messages, each on a line of its own under a header with the time and the sender
    ("[07:09] Kev: full sheet off the left" / "[07:10] Kev: stand it on 500104"); now and then a value sent wrongly and
    corrected in a message of its own with a star, as chat users correct a word ("*500105"). The headers and the
    value taken back are ``O``, the starred value keeps its tag. The front end drops the headers
    (``nlu.normalise.drop_chat_stamps``) and puts a starred value in place of the other (``read_star_corrections``)."""
    rng = ch.rng
    words = [t for s in sentences for t in s]
    if sum(t.is_word for t in words) < 4 or any("\n" in t.word for t in words):  # not a table pasted in already
        return sentences
    messages: list[Phrase] = [list(s) for s in sentences if any(t.is_word for t in s)]
    if len(messages) == 1:
        cut = rng.choice([k for k in range(2, len(words) - 1) if words[k - 1].is_word or not words[k].is_word] or [2])
        messages = [words[:cut], words[cut:]]
    from drywall_lab.nlu.normalise import _starred_kind

    starred: Phrase = []
    last_of_kind = {kind: (m, i) for m, message in enumerate(messages) for i, tok in enumerate(message)
                    if tok.is_word and (kind := _starred_kind(tok.word))}  # a star corrects the last of its kind
    spots = [(m, i, other) for m, i in sorted(last_of_kind.values())
             if messages[m][i].tag != "O" and (other := _taken_back(rng, messages[m][i])) is not None]
    if spots and ch.chance(0.4):
        m, i, other = rng.choice(spots)
        meant = messages[m][i]
        messages[m][i] = Token(other, "O", "O")
        starred = [Token("*" + meant.word, meant.tag, meant.coref)]
    sender, form = rng.choice(CHAT_SENDERS), rng.choice(CHAT_HEADERS)
    minute, date = rng.randint(6 * 60, 17 * 60), f"{rng.randint(1, 28):02d}/{rng.randint(1, 12):02d}"
    lines = messages + ([starred] if starred else [])
    out: Phrase = []
    for k, line in enumerate(lines):
        minute += rng.choice((0, 0, 1))
        body = [t for t in line if t.is_word or out]
        last = max(j for j, t in enumerate(body) if t.is_word)
        if k < len(lines) - 1:
            body[last] = Token(body[last].word + "\n", body[last].tag, body[last].coref)
        out += _header(form, sender, minute, date) + body
    return [out]


# --- an e-mail reply --------------------------------------------------------------------------------------------
EMAIL_SUBJECTS = ("{wall} wall, L{n}", "Drywall - {wall} wall", "Hanging sequence", "Job {job} board install",
                  "{wall} wall list", "Level {n} drywall", "Board schedule wk {n}", "Unit {n}{letter} walls")
EMAIL_GREETINGS = ("Hi all,", "Morning team,", "Hi {name},", "Team,", "Hello,", "{name} -")
#: Questions quoted from the message the e-mail answers: they name studs, sizes, rows and stacks that are not the
#: command's ({stud}, {size}, {row}, {side}, {count}, {n}).
QUOTED_QUESTIONS = ("{name} here - are we still starting the {size}s at {stud}?",
                    "Quick one: does the {row} row go in before lunch?",
                    "The plan I have shows {stud} for that one, which is right?",
                    "Should the {size} come off the {side} stack or is that pile for level {n}?",
                    "Inspector asked about {stud} and {stud2}, any update?",
                    "Are we hanging the {row} course first on this wall?",
                    "{count} sheets left on the {side} pile, want me to order more?",
                    "Do you want the {size} upright or flat in the {row} row?")
EMAIL_SIGNOFFS = ("{name}", "Thanks,\n{name}", "{name} | {role} | Sent from my phone", "Cheers,\n{initial}.",
                  "{name} {surname} | {role}\nOffice 555-01{nn} | Job {job}", "{initial}.", "Sent from my iPhone",
                  "Regards,\n{name} {surname}\n{role}")
EMAIL_NAMES = ("Dana", "Marco", "Priya", "Tom", "Lena", "Kofi", "Ines", "Raj")
EMAIL_SURNAMES = ("Whitfield", "Okafor", "Shah", "Brennan", "Novak", "Castillo")
EMAIL_ROLES = ("PM", "Project Manager", "Site Super", "Foreman", "Site Engineer")


def _frame_words(text: str) -> Phrase:
    """Lines of an e-mail's frame, every word ``O``, each line's last word carrying its line break."""
    out: Phrase = []
    for line in text.split("\n"):
        words = [Token(w, "O", "O") for w in line.split()]
        if words:
            out += words[:-1] + [Token(words[-1].word + "\n", "O", "O")]
        elif out:
            out[-1] = Token(out[-1].word + "\n", "O", "O")  # a blank line
    return out


def email_replies(ch: Chooser, sentences: Sentences) -> Sentences:
    """The instruction sent as an e-mail reply: a subject line ("Subject: RE: East wall, L2"), perhaps a greeting,
    the instruction, the lines it quotes from the message it answers ("> are we still starting the 4x8s at
    500107?", naming other studs, sizes and rows), and a sign-off after a blank line ("Dana | PM | Sent from my
    phone"). All but the instruction is ``O``; the front end drops the header, the quoted lines and the sign-off
    (``nlu.normalise.drop_email_frame``)."""
    rng = ch.rng
    words = [t for s in sentences for t in s]
    if sum(t.is_word for t in words) < 3 or any("\n" in t.word for t in words):
        return sentences
    name, surname = rng.choice(EMAIL_NAMES), rng.choice(EMAIL_SURNAMES)
    slots = dict(wall=rng.choice(("North", "East", "South", "West", "Lobby", "Stair")), n=rng.randint(1, 9),
                 job=rng.randint(1000, 4999), letter=rng.choice("ABCD"), name=name, surname=surname,
                 initial=name[0], role=rng.choice(EMAIL_ROLES), nn=f"{rng.randint(0, 99):02d}",
                 stud=f"5001{rng.randint(0, 12):02d}", stud2=f"5001{rng.randint(0, 12):02d}",
                 size=rng.choice(("4x8", "2x8", "4x6", "full sheet", "4 x 8")), row=rng.choice(("top", "bottom")),
                 side=rng.choice(("left", "right", "middle")), count=rng.choice(("two", "three", "5", "12")))
    asker = rng.choice([n for n in EMAIL_NAMES if n != name])
    subject = "Subject: " + "RE: " * rng.choice((0, 1, 1, 2)) + rng.choice(EMAIL_SUBJECTS).format(**slots)
    quoted = [f"> {rng.choice(QUOTED_QUESTIONS).format(**{**slots, 'name': asker})}"]
    if ch.chance(0.5):
        quoted.append(f"> {asker}")
    head = subject + "\n\n" + (rng.choice(EMAIL_GREETINGS).format(**slots) + "\n" if ch.chance(0.4) else "")
    quote_first = ch.chance(0.3)
    if quote_first:
        head += "\n".join(quoted) + "\n\n"
    body = words[next(k for k, t in enumerate(words) if t.is_word):]
    last = max(j for j, t in enumerate(body) if t.is_word)
    body = body[:last] + [Token(body[last].word + "\n\n", body[last].tag, body[last].coref)]  # its closing mark
    # goes: glued to the word before, it would open the next line ("\n\n. > are we ...")
    tail = ("" if quote_first or not ch.chance(0.8) else "\n".join(quoted) + "\n\n") + \
        rng.choice(EMAIL_SIGNOFFS).format(**slots)
    return [_frame_words(head) + body + _frame_words(tail)]


# --- a conversation between two workers ------------------------------------------------------------------------
CREW_SPEAKERS = ("MIKE", "DAVE", "Ana", "RAJ", "Tomek", "LUIS", "Kim", "SHAUNA")
#: How the second speaker overrules a value the first said (B the value meant, R a reason).
OVERRULES = ("nah, {b}", "no, {b}, {r}", "nope, {r}, {b}", "nah, {r}, {b}", "no no, {b}", "nah mate, {b}, {r}")
#: How the first speaker takes the overruling up, if at all.
TAKEN_UP = ("yeah fair, {b}.", "ok, {b} then.", "fair enough.", "right, {b}.", "")
ACKNOWLEDGED = ("yep.", "copy.", "on it.", "sweet.", "yup, go.")


def crew_crosstalk(ch: Chooser, sentences: Sentences) -> Sentences:
    """The instruction as two workers said it to each other, copied in as a transcript under their labels
    ("MIKE: next full sheet on 500104. DAVE: nah, 500103, it'd hit the window. MIKE: yeah fair, 500103."): one
    says the instruction, now and then with a value that the other overrules (the value meant keeps its tag, the
    one overruled and a value said again in agreement are ``O``), or the other acknowledges it. The front end drops
    the labels (``nlu.normalise.drop_speaker_labels``) and reads a value overruled in another speaker's turn as
    taken back (``resolve_late_repairs``)."""
    rng = ch.rng
    words = [t for s in sentences for t in s]
    if sum(t.is_word for t in words) < 3 or any("\n" in t.word or t.word.endswith(":") for t in words):
        return sentences
    a, b = rng.sample(CREW_SPEAKERS, 2)
    body = words[next(k for k, t in enumerate(words) if t.is_word):]
    while body and not body[-1].is_word:
        body.pop()
    spots = [(i, other) for i, tok in enumerate(body) if tok.is_word and tok.tag != "O"
             and (other := _taken_back(rng, tok)) is not None]
    label = lambda who: Token(who + ":", "O", "O")  # noqa: E731
    stop = Token(".", None, None)

    def acknowledged() -> Sentences:  # the other speaker only acknowledges the instruction
        return [[label(a), *body, stop, label(b), *_untagged(rng.choice(ACKNOWLEDGED).rstrip("."))]]
    if not spots or not ch.punctuated or not ch.chance(0.7):  # without its full stops, no turn is told apart
        return acknowledged()
    i, other = rng.choice(spots)
    meant = body[i]
    said = [*body[:i], Token(other, "O", "O"), *body[i + 1:]]
    form = rng.choice(OVERRULES).replace("{r}", rng.choice(REPAIR_REASONS))
    before, after = (_untagged(part) for part in form.split("{b}"))
    out = [label(a), *said, stop, label(b), *before, meant, *after]
    taken_up = rng.choice(TAKEN_UP).rstrip(".")
    if taken_up:
        out += [stop, label(a), *_untagged(taken_up.replace("{b}", meant.word))]
    return [out] if reads_alike([out], [body], other) else acknowledged()  # a form not read back: acknowledged


def _labels_first(sentence: Phrase, glue: str) -> Phrase:
    """A one-word value that says which, typed after its field's label ("same size" -> "size=same", "top row" ->
    "row=top", "the left pile" -> "pile=left"; the front end's ``split_fields`` puts the words back in order)."""
    from drywall_lab.nlu.normalise import DIGIT_WORDS, FIELD_LABELS

    out: Phrase = []
    i = 0
    while i < len(sentence):
        tok, nxt = sentence[i], sentence[i + 1] if i + 1 < len(sentence) else None
        if (nxt is not None and tok.is_word and nxt.is_word and tok.tag not in ("O", *_ID_TAGS) and tok.word.isalpha()
                and tok.word.lower() not in DIGIT_WORDS
                and nxt.word.lower() in FIELD_LABELS and nxt.tag in ("O", tok.tag)
                and (i == 0 or sentence[i - 1].tag != tok.tag)):
            out.append(Token(f"{nxt.word}{glue}{tok.word}", tok.tag, tok.coref))
            i += 2
            continue
        out.append(tok)
        i += 1
    return out


def glued_fields(ch: Chooser, sentences: Sentences) -> Sentences:
    """Typed as a program or a terse form is: each run of words of one tag joined by "_" ("centre_line"; a position's
    now and then by "-": "3rd-from-right"), and a field's label glued to the value after it by "=" or ":"
    ("stud=500104", "size=2x8"; the label takes the value's tag). Half the time, a stud counted from the previous one
    or an id is written as a sum ("prev+2", "500104-1"; with ":" apart: "prev stud +2") and a one-word value that
    says which comes after its label ("size=same", "row=top"). The front end's ``split_fields`` and ``read_offsets``
    take them apart again."""
    from drywall_lab.nlu.normalise import DIGIT_WORDS, FIELD_LABELS

    glue = ch.rng.choice(["=", "=", ":"])
    position_joiner = ch.rng.choice(["_", "-"])
    program = ch.chance(0.5)
    out: Sentences = []
    for sentence in sentences:
        if program:
            sentence = _labels_first(_written_sums(sentence, spaced=glue == ":"), glue)
        runs = _glued_runs(sentence, position_joiner) if ch.chance(0.7) else list(sentence)
        new: Phrase = []
        for tok in runs:
            last = new[-1] if new else None
            if (last is not None and last.is_word and last.tag == "O" and last.word.lower() in FIELD_LABELS
                    and tok.is_word and tok.tag != "O" and tok.word.lower() not in DIGIT_WORDS):  # not inside an id
                new[-1] = Token(f"{last.word}{glue}{tok.word}", tok.tag, tok.coref)
            else:
                new.append(tok)
        out.append(new)
    return out


# --- hyphenated compounds -------------------------------------------------------------------------------------
#: The first word of a compound people write with a hyphen: a side, a row, a line or a part of the wall before the
#: word it qualifies ("left-line", "bottom-row", "far-right", "end-stud").
COMPOUND_HEADS = frozenset({"left", "right", "centre", "center", "middle", "top", "bottom", "far", "upper", "lower",
                            "half", "stud", "edge", "end", "next", "last", "first", "full", "flat", "stand"})


def hyphenated(ch: Chooser, sentences: Sentences) -> Sentences:
    """One to three pairs of words of one tag written as one compound with a hyphen ("left-line", "bottom-row",
    "far-right", "stand-up"): a head word (``COMPOUND_HEADS``) and the word after it, where the front end reads the
    compound as the two words again (``normalise.joined_compound``)."""
    from drywall_lab.nlu.normalise import joined_compound

    slots = [(s, i) for s, sentence in enumerate(sentences) for i in range(len(sentence) - 1)
             if sentence[i].is_word and sentence[i + 1].is_word and sentence[i].word.lower() in COMPOUND_HEADS
             and (sentence[i].tag, sentence[i].coref) == (sentence[i + 1].tag, sentence[i + 1].coref)
             and sentence[i + 1].word.isascii() and joined_compound(f"{sentence[i].word}-{sentence[i + 1].word}")
             and sentence[i + 1].word.lower() not in _FUNCTION_WORDS]
    if not slots:
        return sentences
    chosen = set(ch.rng.sample(slots, min(len(slots), ch.rng.choice([1, 1, 2, 3]))))
    out: Sentences = []
    for s, sentence in enumerate(sentences):
        new: Phrase = []
        skip = False
        for i, tok in enumerate(sentence):
            if skip:
                skip = False
                continue
            if (s, i) in chosen and not (new and new[-1].word.endswith("-")):
                new.append(Token(f"{tok.word}-{sentence[i + 1].word}", tok.tag, tok.coref))
                skip = True
            else:
                new.append(tok)
        out.append(new)
    return out


#: Words a compound never ends on ("left-the").
_FUNCTION_WORDS = frozenset({"the", "a", "an", "of", "to", "on", "in", "it", "and", "from", "at", "by", "with", "one",
                             "or", "is", "for", "then", "so"})


# --- a value taken back -------------------------------------------------------------------------------------
#: How a worker takes a value back and says the one meant (A the value taken back, B the one meant): broken off with
#: or without a cue, or after a pause with a cue before or after the new value.
REPAIR_FORMS = ("{a}- {b}", "{a}— {b}", "{a}- no, {b}", "{a}, er, {b}, sorry", "{a}, no, {b}", "{a}, I mean, {b}",
                "{a} uh {b} sorry", "{a}, sorry, {b}", "{a} no {b}")
_OTHER_SIDE = {"left": "right", "right": "left"}
_OTHER_ROW = {"top": "bottom", "bottom": "top"}
#: A value taken back late (``_late_repair``): after a reason ("500111... nah that'd hang past the end, 500110"), or
#: with a few of the words after it said before the cue, closed by a full stop ("top row from the first stud, no.
#: bottom row"). R the reason; the reasons name ends, rows and neighbours of other things.
LATE_CUES = ("{a}. nah {r}, {b}", "{a}, no wait, {r}, {b}", "{a}. sorry, {r}, {b}", "{a}, nope, {r}, {b}",
             "{a}. no, {r}, {b}")
LATE_CLOSERS = (", no. {b}", ". no. {b}", ", sorry. {b}", ". nah. {b}", ", nope. {b}")
REPAIR_REASONS = ("that one's taken", "that'd hang past the end", "wrong one", "my mistake", "too far over",
                  "that's got a sheet on it already", "can't reach that from here", "I misread the tag",
                  "it would run into the last one", "misread the drawing", "that spot is done", "wrong pile")
#: The share of values taken back that are taken back late.
LATE_SHARE = 0.4


def _taken_back(rng: random.Random, tok: Token) -> str | None:
    """A value of the same kind as ``tok``'s that it is not (an id, an ordinal, a side, a row), or None."""
    low = tok.word.lower()
    if _is_id(tok):
        return low[:4] + rng.choice([f"{n:02d}" for n in range(13) if f"{n:02d}" != low[4:]])
    if low in _OTHER_SIDE and tok.tag in ("St_loc1", "Dw_loc1"):
        return _OTHER_SIDE[low]
    if low in _OTHER_ROW and tok.tag in ("Hr_top", "Hr_btm"):
        return _OTHER_ROW[low]
    for table in (ORDINAL_WORDS, ORDINAL_DIGITS):
        n = next((n for n, w in table.items() if w == low), None)
        if n is not None and tok.tag in ("St_loc1", "Dw_loc1"):
            return table[rng.choice([m for m in table if m != n])]
    return None


def value_repairs(ch: Chooser, sentences: Sentences) -> Sentences:
    """One value said wrongly first and taken back (``REPAIR_FORMS``): "stud 500101, er, 500100, sorry", "four to
    the left- right", "the bottom- no, top row", "the third, no, the fourth stud"; a stud's id now and then with how
    the new one lies from the old ("500105- no, one more over to the right, 500106"). The value taken back, the cues
    and such words are ``O``; the value meant keeps its tag (the final intention counts). The front end's
    ``resolve_value_repairs`` drops what was taken back."""
    spots = [(si, i, other) for si, sentence in enumerate(sentences) for i, tok in enumerate(sentence)
             if tok.is_word and tok.tag != "O" and (other := _taken_back(ch.rng, tok)) is not None]
    if not spots:
        return sentences
    si, i, other = ch.rng.choice(spots)
    form = ch.rng.choice(REPAIR_FORMS)
    meant = sentences[si][i]
    related = False
    if meant.tag == "ID_stud" and _is_id(meant) and ch.chance(0.3):  # "500105- no, one more over to the right, 500106"
        d = ch.rng.choice([-3, -2, -1, 1, 2, 3])
        if 500100 <= int(meant.word) - d <= 500112:
            other = str(int(meant.word) - d)
            side = "right" if d > 0 else "left"
            rel = ch.rng.choice([f"{NUMBER_WORDS[abs(d)]} more over to the {side}", f"{NUMBER_WORDS[abs(d)]} over to the {side}"]
                                + (["the next one", f"the next one to the {side}"] if abs(d) == 1 else []))
            form = ch.rng.choice(["{a}- no, " + rel + ", {b}", "{a}, no, " + rel + ", {b}", "{a}— sorry, " + rel + " {b}"])
            related = True
    out = [list(s) for s in sentences]
    if not related and ch.punctuated and ch.chance(LATE_SHARE):  # without punctuation a late repair is not read
        out[si] = _late_repair(ch, out[si], i, other)
        if reads_alike(out, sentences, other):
            return out
        out[si] = list(sentences[si])  # a form the front end would not read back: said in place instead
    before, after = (_untagged(part) for part in form.replace("{a}", other).split("{b}"))
    out[si][i:i + 1] = before + [out[si][i]] + after
    return out


def reads_alike(new: Sentences, old: Sentences, gone: str) -> bool:
    """Whether the front end reads the tagged words of ``new`` as those of ``old`` and drops the value ``gone`` (one
    taken back), ``new`` typed as written and in lower case: a channel whose form needs more than its tags to be
    read (a late repair's cue after a full stop, a speaker's turn) checks it before saying a row so."""
    from drywall_lab.corpus.generator import join_tokens
    from drywall_lab.corpus.io import tokenize
    from drywall_lab.nlu.normalise import normalise

    def read(sentences: Sentences, punctuated: bool, lower: bool) -> list[tuple[str, str]]:
        marks = [[t if not t.is_word or tokenize(t.word) else Token(t.word, None, None) for t in s] for s in sentences]
        text, _, tags, _ = join_tokens(marks, punctuated, lambda w, first: w.lower() if lower else w)
        n = normalise(text)
        return [(w.lower(), t) for w, t in zip(n.words, n.tags_of_words(tags))]

    def tagged(reading: list[tuple[str, str]]) -> list[tuple[str, str]]:
        return [(w, t) for w, t in reading if t != "O"]

    want = read(old, True, False)
    kept = sum(w == gone.lower() for w, _ in want)
    return all(tagged(got := read(new, punctuated, lower)) == tagged(want)
               and sum(w == gone.lower() for w, _ in got) <= kept
               for punctuated, lower in ((True, False), (True, True)))


def _late_repair(ch: Chooser, sentence: Phrase, i: int, other: str) -> Phrase:
    """``sentence`` with its value at ``i`` taken back late (``LATE_CUES``, ``LATE_CLOSERS``): ``other`` said in its
    place, then a reason or the rest of its clause, the cue and the value meant (with its noun said again, ``O``:
    the noun's tag stays where it was first said). The front end's ``resolve_late_repairs`` puts the value meant back."""
    from drywall_lab.nlu.normalise import _KIND_GROUPS, _value_kind

    meant = sentence[i]
    noun = sentence[i + 1] if i + 1 < len(sentence) and sentence[i + 1].is_word \
        and sentence[i + 1].word.lower() in ("row", "course", "stud", "pile", "stack") else None
    start = i + 1 + (noun is not None)
    end = next((k for k in range(start, len(sentence)) if not sentence[k].is_word), len(sentence))
    kind = _value_kind(meant.word)
    group = _KIND_GROUPS.get(kind, {kind})  # no value that names the same thing may come between (the front end's)
    said_on = end - start if 1 <= end - start <= 5 and not any(_value_kind(t.word) in group
                                                               for t in sentence[start:end]) and ch.chance(0.5) else 0
    closers = [c for c in LATE_CLOSERS if not (_is_id(meant) and "no." in c)]  # "no. 500104": a label
    form = ch.rng.choice(closers) if said_on and ch.chance(0.7) else \
        ch.rng.choice(LATE_CUES).replace("{r}", ch.rng.choice(REPAIR_REASONS))
    cue = _untagged(form.split("{b}")[0].replace("{a}", ""))
    again = [Token(noun.word, "O", "O")] if noun is not None else []
    if said_on:
        return [*sentence[:i], Token(other, "O", "O"), *sentence[i + 1:start + said_on], *cue, meant, *again,
                *sentence[start + said_on:]]
    return [*sentence[:i], Token(other, "O", "O"), *cue, meant, *sentence[i + 1:]]


def _untagged(text: str) -> Phrase:
    """Words said around a value, all ``O``, with their commas and full stops as punctuation ("500101, er," ->
    500101 , er ,)."""
    return [Token(w, None, None) if w in ",." else Token(w, "O", "O") for w in re.findall(r"[,.]|[^\s,.]+", text)]


# --- a table pasted from a spreadsheet ----------------------------------------------------------------------
#: The tags of each field of a pasted table, in the order the columns come, and the labels its header may give it
#: (the first tag of the field's words picks the label).
TABLE_FIELDS: tuple[tuple[tuple[str, ...], dict[str, tuple[str, ...]]], ...] = (
    (("ID_wall", "dim", "width", "length", "Dw_loc1", "Dw_loc2"),
     {"ID_wall": ("panel", "panel_id", "board"), "Dw_loc1": ("stack", "from_stack", "pile"),
      "Dw_loc2": ("stack", "pile")}),
    (("ID_stud", "St_loc1", "St_loc2"), {"": ("stud", "stud_id", "stud")}),
    (("Vr_md",), {"": ("edge", "line")}),
    (("Hr_top", "Hr_btm"), {"": ("row", "row")}),
)
_SIZE_LABELS = ("size", "size", "sheet")
#: Words after a field's last tagged word that still belong to its cell: a size's unit and side ("240 cm long").
_CELL_TAILS = frozenset({"wide", "long", "high", "tall", "across", "mm", "cm", "m", "millimetres", "millimeters",
                         "centimetres", "centimeters", "metres", "meters", "metre", "meter", "feet", "foot", "ft"})
#: Columns that only number or date a row, with their values: read by no rule (``nlu.normalise.read_tables``).
_ROW_COLUMNS = (("line", lambda rng: str(rng.randint(1, 30))), ("item", lambda rng: str(rng.randint(1, 12))),
                ("#", lambda rng: str(rng.randint(1, 40))), ("date", lambda rng: f"{rng.randint(1, 28):02d}/{rng.randint(1, 12):02d}"),
                ("qty", lambda rng: "1"))


def _phrase_after(tokens: Phrase, last: Token, reach: int = 3) -> Phrase:
    """The words (at most ``reach``) after the word ``last`` of ``tokens`` up to a punctuation mark."""
    k = next(i for i, t in enumerate(tokens) if t is last) + 1
    return list(itertools.takewhile(lambda t: t.is_word, tokens[k:k + reach]))


def pasted_tables(ch: Chooser, sentences: Sentences) -> Sentences:
    """The instruction pasted as a table from a spreadsheet: a header line of labels ("line;panel;stud;edge") and a
    line of values under it, the cells separated by ";", "," or a tab, a column that only numbers or dates the row
    now and then first; each field's words are its cell (``TABLE_FIELDS``, with a size's unit and side after it and
    a placement's phrase whole; the words around them are left out). The front end's ``read_tables`` reads it back as a form's words. An instruction whose fields' words interleave, or
    whose field goes on with "of" and words no tag reads ("right of the door"), is left as it is."""
    rng = ch.rng
    tokens = [t for sentence in sentences for t in sentence]
    words = [t for t in tokens if t.is_word]
    for tag, anchor in (("Dw_loc1", "Dw_loc2"), ("St_loc1", "St_loc2")):  # "right of the door", "left, sorry, of
        # the door": an anchor no tag reads
        idx = [i for i, t in enumerate(words) if t.tag == tag] if not any(t.tag == anchor for t in words) else []
        after = words[idx[-1] + 1:idx[-1] + 5] if idx else []
        if any(t.word.lower() == "of" for t in itertools.takewhile(lambda t: t.tag == "O", after)):
            return sentences
    cells: list[tuple[int, str, Phrase]] = []
    for tags, labels in TABLE_FIELDS:
        idx = [i for i, t in enumerate(words) if t.tag in tags]
        if not idx:
            continue
        first = words[idx[0]].tag
        label = rng.choice(labels.get(first) or labels.get("") or _SIZE_LABELS)
        end = idx[-1] + 1
        while end < len(words) and words[end].tag == "O" and words[end].word.lower() in _CELL_TAILS:
            end += 1
        if set(tags) & set(PLACEMENT_TAGS):  # a placement's phrase whole ("half on the stud"), up to a mark
            phrase = _phrase_after(tokens, words[end - 1]) if end < len(words) else []
            end += len(list(itertools.takewhile(lambda t: t.tag == "O", phrase)))
        cells.append((idx[0], label, words[idx[0]:end]))
    spans = sorted((start, start + len(value)) for start, _, value in cells)
    if len(cells) < 2 or any(a[1] > b[0] for a, b in zip(spans, spans[1:])):
        return sentences
    cells.sort(key=lambda c: c[0])
    header = [label for _, label, _ in cells]
    values = [value for _, _, value in cells]
    for name, value_of in rng.sample(_ROW_COLUMNS, rng.choice([0, 1, 1, 2])):
        header.insert(0, name)
        values.insert(0, [Token(value_of(rng), "O", "O")])
    sep = rng.choice([";", ",", "\t"])
    out: Phrase = []
    for k, label in enumerate(header):
        out.append(Token(label + ("\n" if k == len(header) - 1 else sep), "O", "O"))
    for k, value in enumerate(values):
        last = value[-1]
        out += value[:-1] + [Token(last.word + ("" if k == len(values) - 1 else sep), last.tag, last.coref)]
    return [out]


CHANNELS: dict[str, Channel] = {
    "restated_studs": restated_studs, "site_references": site_references, "stack_talk": stack_talk, "relative_talk": relative_talk,
    "spoken_ids": spoken_ids, "shorthand": shorthand,
    "disfluency": disfluency, "asides": asides, "plural_sizes": plural_sizes, "metric_sizes": metric_sizes,
    "code_switch": code_switch, "openers": openers, "glued_fields": glued_fields, "value_repairs": value_repairs,
    "continued_steps": continued_steps, "pasted_tables": pasted_tables, "anchor_first": anchor_first,
    "chat_messages": chat_messages, "email_replies": email_replies, "crew_crosstalk": crew_crosstalk,
    "hyphenated": hyphenated,
}
#: A row whose target is said by a property ("the narrow one") instead of its size, in every split: drawn where the
#: target is said (``field_generator.size_property_draw``), so not a function of sentences; a row records it like one.
SIZE_PROPERTIES = "size_properties"
#: A command with one of its parts offered twice with "or" ("on 500105 or 500106, not sure which"), in every split:
#: it changes what the row means (a question is expected; ``field_generator.offer_alternative``), so not a function of
#: sentences either.
UNDECIDED = "undecided"
#: A novel command counted from a thing the site does not have ("the pile right of the door"): a question is
#: expected (``field_generator.landmark_anchor``), so not a function of sentences either.
LANDMARK_ANCHORS = "landmark_anchors"
#: Every name a row's ``channels`` may hold.
CHANNEL_NAMES: tuple[str, ...] = (*CHANNELS, SIZE_PROPERTIES, UNDECIDED, LANDMARK_ANCHORS)
#: How often each channel is applied to a training instruction (independently of each other and of the register).
CHANNEL_RATES: dict[str, float] = {"site_references": 0.12, "stack_talk": 0.12, "relative_talk": 0.35,
                                   "spoken_ids": 0.15, "shorthand": 0.12, "disfluency": 0.15, "asides": 0.2,
                                   "plural_sizes": 0.10, "restated_studs": 0.06}
#: Held back whole: never in train, validation or test; the novel split uses it.
HELD_BACK: tuple[str, ...] = ("shorthand", "metric_sizes")
#: Held back whole and laid over the novel split's instructions at this rate, on top of their held-back channel or pair,
#: drawn apart from everything else (``overlay_rng``): the rest of the split is what it was without them.
HELD_BACK_OVERLAYS: dict[str, float] = {"code_switch": 0.2, "openers": 0.15, "glued_fields": 0.1, "value_repairs": 0.1,
                                        "continued_steps": 0.5, "pasted_tables": 0.05, "anchor_first": 0.5,
                                        "chat_messages": 0.08, "email_replies": 0.06, "crew_crosstalk": 0.06,
                                        "hyphenated": 0.1}
#: Held back as a pair: each channel is met alone in training, never both at once.
HELD_BACK_PAIRS: tuple[tuple[str, str], ...] = (("spoken_ids", "disfluency"), ("stack_talk", "asides"),
                                                ("site_references", "relative_talk"))


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


def overlay_rng(row_id: str, name: str) -> Chooser:
    """The random draws of one overlay channel on one row, apart from the split's own."""
    return Chooser(random.Random(f"{row_id}-{name}"), novel=True)


def overlay_drawn(row_id: str, name: str) -> tuple[Chooser, bool]:
    """An overlay's draws on one row, and whether its own draw lays it over the row (at its rate)."""
    ch = overlay_rng(row_id, name)
    return ch, ch.chance(HELD_BACK_OVERLAYS[name])


#: Overlays that would lose what a channel of the row already says: a pasted table keeps a form's values, not the
#: words that count a stack or stud from a thing the site lacks ("right of the door"), so that a landmark anchor in
#: a table would no longer say why the row expects a question.
OVERLAYS_LEFT_OUT: dict[str, frozenset[str]] = {"pasted_tables": frozenset({"landmark_anchors"})}


def apply_overlays(row_id: str, sentences: Sentences, punctuated: bool = True,
                   channels: Iterable[str] = ()) -> tuple[Sentences, tuple[str, ...]]:
    """A novel instruction through each overlay channel its own draw picks (``HELD_BACK_OVERLAYS``), and the names of
    those that changed it (an overlay with nothing to rewrite, "two studs further right" in an instruction with no
    step from the last stud, leaves the row as it was and unnamed). ``punctuated``: whether the row will be written
    with its punctuation (``Chooser.punctuated``); ``channels``: the row's channels so far (``OVERLAYS_LEFT_OUT``)."""
    applied = []
    channels = set(channels)
    for name in HELD_BACK_OVERLAYS:
        ch, drawn = overlay_drawn(row_id, name)
        ch.punctuated = punctuated
        if drawn and not OVERLAYS_LEFT_OUT.get(name, frozenset()) & channels:
            said = CHANNELS[name](ch, sentences)
            if said != sentences:
                applied.append(name)
            sentences = said
    return sentences, tuple(applied)


def held_back_combinations() -> list[tuple[str, ...]]:
    """Every channel or pair the training splits never contain (for tests and reports)."""
    return [(name,) for name in HELD_BACK] + list(HELD_BACK_PAIRS)
