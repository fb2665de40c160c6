"""The field corpus: every meaning of the paper corpus, said in the registers people use on a site.

The paper corpus (``generator.py``) is kept as it is for the paper's study. It measures the
generator more than language: a tagger trained on it is right on 100% of its test split and on
about half of hand-written field instructions. The field corpus keeps the same episodes and
meanings (``command_meaning`` and ``refusal_meaning``: every target and stud kind, the four
placements, every refusal) and says them through a much richer grammar:

- **registers**: formal, polite and hedging, foreman and trade talk, verbless fragments, lists,
  checklists and key-value notes, speech-recogniser text (lowercase, fillers, restarts), radio (with
  prowords: ``break``, ``I say again``), non-native word order and prepositions, self-corrections (the
  final intention counts; the abandoned words are ``O``: a phrase, a whole sentence, a negated
  alternative, "did I say ...? I meant ..."), context or a reason first, questions (also asked and
  answered), phone messages (also an apprentice checking), explanations (a reason after, a lesson, a
  purpose first, a story of what happened before, clauses around the instruction), an impatient boss
  (barked pieces, a repeated id) and a site engineer's notes with technical detail whose numbers are ``O``;
- **clause orders**: the stud, the placement or the panel first or last, asides between the parts, the
  placement wrapped round the stud ("with its edge on the centre line of stud 500105");
- **vocabulary** (``field_phrases.py``): trade nouns, sizes in one word and with feet marks, number
  words, many wordings of each stack, stud and placement;
- **noise**: dropped articles, inserted fillers, lost casing and punctuation (or Title Case, or a
  boss's capitals), stutters and typos in words that carry no tag.

Then **noise channels** (``channels.py``: spoken ids, shorthand, disfluency, asides, plural sizes), in any register,
rewrite how it is said; the novel split alone has the channels held back from training. Each row's words are its
text read through the front end (``drywall_lab.nlu.normalise``), as a worker's instruction is before tagging.

Every row has the paper corpus's fields (words, 13-label tags, co-reference tags, context, meaning,
expected) plus its ``register`` and ``channels``. With the gold tags every row gives its expected command or refusal
through the information-mapping rules (tested). Splits: ``train`` (generated on demand, not committed),
``validation`` and ``test`` (the same families as train), and ``novel``: only held-back families
(``field_phrases.HELD_BACK``) wherever a bank has them.
"""
from __future__ import annotations

import functools
import hashlib
import random
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable, Sequence

from drywall_lab.corpus import channels as C
from drywall_lab.corpus import field_phrases as F
from drywall_lab.corpus import generator as G
from drywall_lab.corpus.io import UNSPACED, read_jsonl, tokenize, unspaced, write_jsonl
from drywall_lab.corpus.markup import Phrase, Token, parse, plain, tagged
from drywall_lab.corpus.phrases import NUMBER_WORDS, ORDINAL_DIGITS, ORDINAL_WORDS, Chooser
from drywall_lab.im import words as W
from drywall_lab.im.mapper import task_correct
from drywall_lab.im.trace import TaggedInstruction
from drywall_lab.site import DATA_DIR, Site, default_site, size_words

FIELD_SEED = 2026
FIELD_DIR = DATA_DIR / "field_corpus"
FIELD_SPLITS = ("train", "validation", "test", "novel")
FIELD_SPLIT_SIZES = {"train": 20000, "validation": 1000, "test": 1000, "novel": 1000}
#: The committed splits; ``train`` is regenerated from the seed when it is first needed (``field_split``).
COMMITTED_SPLITS = ("validation", "test", "novel")
FIELD_REFUSAL_RATE = 0.12  #: about one step in eight must be refused, as in hand-written field sets

#: Meanings: references named about as often as people name them; every placement common.
FIELD_WEIGHTS = G.MeaningWeights(
    target={"id": 0.22, "size": 0.24, "standard": 0.14, "same": 0.16, "absolute": 0.12, "relative": 0.12},
    stud={"id": 0.40, "absolute": 0.24, "relative": 0.36},
    placement={"vertical_left": 0.34, "vertical_middle": 0.34, "horizontal_top": 0.16, "horizontal_bottom": 0.16},
)
#: How often each register is used.
REGISTERS: dict[str, float] = {
    "formal": 0.08, "polite": 0.07, "foreman": 0.11, "fragment": 0.10, "list": 0.06, "speech": 0.10,
    "radio": 0.06, "non_native": 0.08, "correction": 0.08, "context": 0.05, "question": 0.06, "texting": 0.05,
    "explain": 0.04, "boss": 0.03, "engineer": 0.03,
}


# --- small pieces -----------------------------------------------------------------------------------------
def punct(mark: str) -> Token:
    """A punctuation mark: written after the word before it, not a word itself."""
    return Token(mark, None, None)


def words_of(ch: Chooser, bank: list[str]) -> Phrase:
    """A template of plain words from a bank (may be empty)."""
    return parse(ch.template(bank))


def _number(ch: Chooser, n: int, tag: str, suffixes: tuple[str, ...] = ("",)) -> Phrase:
    """A number as digits or a word, optionally with a feet mark glued on ("4'", "4ft", "four-foot")."""
    digits = ch.chance(0.6) or n not in NUMBER_WORDS
    suffix = ch.rng.choice(suffixes)
    if not digits and suffix in ("ft", "'"):
        suffix = "-foot"  # "eightft" is not a word anyone writes
    word = (str(n) if digits else NUMBER_WORDS[n]) + suffix
    return tagged(word, tag) if " " not in word else tagged(word.split()[0], tag) + plain(word.split()[1])


def _ordinal(ch: Chooser, n: int) -> str:
    return ORDINAL_DIGITS[n] if ch.chance(0.35) else ORDINAL_WORDS[n]


DIGIT_NAMES = {"0": ("zero", "oh", "0"), "1": ("one", "1"), "2": ("two", "2"), "3": ("three", "3"), "4": ("four", "4"),
               "5": ("five", "5"), "6": ("six", "6"), "7": ("seven", "7"), "8": ("eight", "8"), "9": ("nine", "9")}


def id_phrase(ch: Chooser, ident: str, tag: str, read_out: float = 0.0) -> Phrase:
    """An id, now and then written with a number sign ("#500107"); with chance ``read_out``, read out digit
    by digit as on a radio ("five oh oh one oh seven"), every digit carrying the tag."""
    if ch.chance(read_out):
        as_words = ch.chance(0.7)
        return [Token(DIGIT_NAMES[d][ch.rng.randrange(len(DIGIT_NAMES[d]) - 1)] if as_words else d, tag, tag)
                for d in ident]
    return tagged(("#" if ch.chance(0.06) else "") + ident, tag)


def size_phrase(ch: Chooser, ref: G.TargetRef) -> Phrase:
    """The size of the target as said: numbers tagged ``width`` / ``length`` (guidelines 3, 4.3 and 4.7)."""
    a, b = ref.size
    rng = ch.rng
    if ref.kind == "width":  # "two-foot wide", "a 2' wide sheet"
        form = rng.randrange(4)
        if form == 0:
            return _number(ch, a, "width", ("-foot", "-ft", "'")) + plain("wide")
        if form == 1:
            return tagged(f"{NUMBER_WORDS[a] if ch.chance(0.5) else a}-foot-wide", "width")
        if form == 2:
            return _number(ch, a, "width") + plain(rng.choice(["foot wide", "feet wide", "ft wide", "wide"]))
        if form == 3 and ch.chance(0.5):  # the role's noun after the number: "of 2 ft width", "2 feet in width"
            return _number(ch, a, "width") + plain(rng.choice(F.SIZE_NOUN_AFTER)) + plain("width")
        return plain(rng.choice(["width", "width of"])) + _number(ch, a, "width")
    if ref.kind == "length":  # "a six-footer", "the 6 foot one", "six feet long"
        form = rng.randrange(4)
        if form == 0:
            return _number(ch, b, "length") + plain(rng.choice(["foot long", "feet long", "ft long", "long"]))
        if form == 1:
            word = NUMBER_WORDS[b] if ch.chance(0.6) else str(b)
            return tagged(f"{word}-footer", "length") if ch.chance(0.5) else tagged(f"{word}-foot", "length") + plain("long")
        if form == 2:
            return _number(ch, b, "length", ("-foot", "'", " foot"))
        if form == 3 and ch.chance(0.5):  # "of 6 ft length", "six feet in length"
            return _number(ch, b, "length") + plain(rng.choice(F.SIZE_NOUN_AFTER)) + plain("length")
        return plain(rng.choice(["length", "length of"])) + _number(ch, b, "length")
    if ref.length_first:  # "8 long by 4 wide": the words name the roles
        first = _number(ch, b, "length") + plain(rng.choice(["long", "foot long", "feet long", "ft long"]))
        second = _number(ch, a, "width") + plain(rng.choice(["wide", "foot wide", "feet wide", "ft wide"]))
        return first + plain(rng.choice(["by", "and", "x", ""])) + second
    form = rng.randrange(11)
    if form >= 9:  # the roles named, in either order: "length 8 and width 4", "the width is 4 feet, the length 8"
        unit = rng.choice(["", "", "feet", "foot", "ft"])
        width = plain(rng.choice(["width", "the width is", "width is", "the width of it is", "wide"])) \
            + _number(ch, a, "width") + plain(unit)
        length = plain(rng.choice(["length", "the length is", "length is", "the length of it is", "long"])) \
            + _number(ch, b, "length") + plain(unit)
        first, second = (length, width) if form == 10 else (width, length)
        link = rng.choice(["and", "and", "", ","])
        return first + ([punct(",")] if link == "," else plain(link)) + second
    if form <= 2:  # one word: "4x8", "4'x8'", "four-by-eight" (tagged width, guidelines 4.7)
        if form == 0:
            word = f"{a}{rng.choice(['x', 'X', 'x', '-by-', 'by'])}{b}"
        elif form == 1:
            word = f"{a}'{rng.choice(['x', 'X'])}{b}'"
        else:
            word = f"{NUMBER_WORDS[a]}-by-{NUMBER_WORDS[b]}"
        return tagged(word, "width")
    if form == 3:
        return _number(ch, a, "width") + plain("x") + _number(ch, b, "length")
    if form == 4:
        return _number(ch, a, "width", ("'", "ft", "-foot")) + plain(rng.choice(["by", "x"])) + \
            _number(ch, b, "length", ("'", "ft", "-foot"))
    if form == 5:
        return _number(ch, a, "width") + plain(rng.choice(["foot by", "feet by", "ft by"])) + \
            _number(ch, b, "length") + plain(rng.choice(["foot", "feet", "ft", ""]))
    if form == 6:
        return _number(ch, a, "width") + plain(rng.choice(["wide", "feet wide", "across"])) + \
            plain(rng.choice(["and", "by", ""])) + _number(ch, b, "length") + plain(rng.choice(["long", "feet long", "tall"]))
    return _number(ch, a, "width") + plain("by") + _number(ch, b, "length")


def direction_phrase(ch: Chooser, direction: str, count: int, tag: str, unit: str) -> Phrase:
    """A tagged direction with its count: "two to the left", "2 studs right", "next one over to the right"."""
    rng = ch.rng
    side = rng.choice([direction, direction, f"{direction}-hand"]) if ch.chance(0.1) else direction
    if count == 1:
        form = rng.choice(["{d}", "{d}", "one to the {d}", "one {u} to the {d}", "one {d}", "1 {d}",
                           "next {u} to the {d}", "one over to the {d}", "just to the {d}", "first {u} to the {d}"])
    else:
        form = rng.choice(["{n} to the {d}", "{n} {u}s to the {d}", "{n} {d}", "{o} to the {d}", "{o} {d}",
                           "{n} over to the {d}", "{n} {u}s {d}", "{n} places to the {d}", "{o} {u} to the {d}",
                           "{n} {u}s over to the {d}", "{n} {u}s further {d}"])
    number = str(count) if ch.chance(0.4) else NUMBER_WORDS[count]
    words = form.replace("{d}", side).replace("{n}", number).replace("{o}", _ordinal(ch, count))
    out: Phrase = []
    for w in words.split():
        if w in ("{u}", "{u}s"):  # "studs", "piles": a generic noun inside the span stays O
            out.append(Token(unit + w[3:], "O", "O"))
        else:
            out.append(Token(w, tag, tag))
    return out


# --- the three pieces of information ---------------------------------------------------------------------
@dataclass
class Pieces:
    """Phrase makers for one meaning; ``terse`` drops articles and verbs (fragments, lists)."""

    ch: Chooser
    meaning: G.Meaning
    read_out_ids: float = 0.0  #: chance that an id is read out digit by digit (radio, speech)
    bare_stacks: bool = False  #: a stack may be named by its side alone (where a key or a line says it is the panel)
    count_last: float = 0.0  #: chance that a relative stud position gives its count after the anchor (non-native)
    stud_ids: tuple[str, ...] = ()  #: the wall's studs, left to right: a stud id may come with its position too
    #: The size said by a property instead ("the narrow one"; ``size_property_words``): its own draws and its words.
    size_property: tuple[Chooser, tuple[str, ...]] | None = None
    said_property: bool = False  #: whether the target was said by a property

    def noun(self) -> Phrase:
        return words_of(self.ch, F.PANEL_NOUNS)

    def target(self, terse: bool = False, ref: G.TargetRef | None = None) -> Phrase:
        """The target as said; the meant target said by a property when ``size_property`` is set (drawn after
        the words it replaces, so the split's own draws are those it would make without it)."""
        phrase = self._target(terse, ref)
        if self.size_property is None or ref not in (None, self.meaning.target):
            return phrase
        ch, words = self.size_property
        self.said_property = True
        word = ch.rng.choice(words)
        slots = {"noun": words_of(ch, F.PANEL_NOUNS), "plural": words_of(ch, F.PANEL_NOUNS_PLURAL),
                 "prop": tagged(word, "dim")}
        bank = F.TARGET_PROPERTY_TERSE if terse else F.TARGET_PROPERTY
        if word.endswith("est"):  # "the narrowest one", never "a narrowest one"
            bank = [t for t in bank if not t.lstrip("~").startswith("a ")]
        return ch.say(bank, **slots)

    def _target(self, terse: bool = False, ref: G.TargetRef | None = None) -> Phrase:
        ch, ref = self.ch, ref or self.meaning.target
        slots = {"noun": self.noun(), "idnoun": words_of(ch, F.ID_NOUNS), "plural": words_of(ch, F.PANEL_NOUNS_PLURAL),
                 "stack": plain(ch.rng.choice(F.STACK_NOUNS))}
        if ref.kind == "id":
            return ch.say(F.TARGET_ID_TERSE if terse else F.TARGET_ID, id=id_phrase(ch, ref.panel_id, "ID_wall", self.read_out_ids), **slots)
        if ref.kind == "size" and not terse and not ref.length_first and ch.chance(0.05):  # "one of the 4x8s"
            a, b = ref.size
            return plain(ch.rng.choice(["one of the", "one of them", "one of the"])) + \
                tagged(f"{a}{ch.rng.choice(['x', 'X'])}{b}s", "width")
        if ref.kind in ("size", "width", "length"):
            return ch.say(F.TARGET_SIZE_TERSE if terse else F.TARGET_SIZE, size=size_phrase(ch, ref), **slots)
        if ref.kind == "standard":
            return ch.say(F.TARGET_STANDARD_TERSE if terse else F.TARGET_STANDARD, std=words_of(ch, F.STANDARD_WORDS), **slots)
        if ref.kind == "same":
            return ch.say(F.TARGET_SAME_TERSE if terse else F.TARGET_SAME, **slots)
        if ref.kind == "absolute":
            if terse and self.bare_stacks and ch.chance(0.3):  # the side alone: "panel: left", "Middle. Stud 500105."
                return ch.say(F.STACK_BARE[ref.stack])
            if not terse and ch.chance(0.15):  # "the one on the right"
                return ch.say(F.TARGET_SIDE[ref.stack], **slots)
            where = ch.say(F.STACK_WHERE[ref.stack], stack=slots["stack"])
            return ch.say(F.TARGET_STACK_TERSE if terse else F.TARGET_STACK, where=where, **slots)
        if ref.kind == "relative":
            unit = ch.rng.choice(["stack", "pile"])
            direction = direction_phrase(ch, ref.direction, ref.count, "Dw_loc1", unit)
            if ref.anchor == "previous":
                anchor = ch.say(F.PANEL_ANCHOR_PREVIOUS, plainnoun=words_of(ch, F.ID_NOUNS), stack=slots["stack"])
            else:
                anchor = ch.say(F.PANEL_ANCHOR_ID, id=id_phrase(ch, ref.anchor, "Dw_loc2"),
                                plainnoun=words_of(ch, F.ID_NOUNS), stack=slots["stack"])
            return ch.say(F.TARGET_RELATIVE_TERSE if terse else F.TARGET_RELATIVE, dir=direction, anchor=anchor, **slots)
        if ref.kind == "none":
            return ch.say(F.TARGET_NONE, **slots)
        raise ValueError(ref)

    def stud(self, terse: bool = False, ref: G.StudRef | None = None) -> Phrase:
        ch, ref = self.ch, ref or self.meaning.stud
        stud = words_of(ch, F.STUD_NOUNS)
        if ref.kind == "id":
            said = ch.say(F.STUD_ID_TERSE if terse else F.STUD_ID, id=id_phrase(ch, ref.stud_id, "ID_stud", self.read_out_ids),
                          stud=stud)
            position = self.position_of(ref.stud_id) if ch.chance(0.05) else None
            return position + [punct(",")] + said if position else said
        if ref.kind == "absolute":
            return ch.say((F.STUD_END_TERSE if terse else F.STUD_END)[ref.name], stud=stud)
        if ref.kind == "from_end":
            return ch.say(F.STUD_FROM_END_TERSE if terse else F.STUD_FROM_END, stud=stud,
                          ord=tagged(_ordinal(ch, ref.nth), "St_loc1"), side=tagged(ref.side, "St_loc1"))
        if ref.kind == "ordinal":
            return ch.say(F.STUD_ORDINAL_TERSE if terse else F.STUD_ORDINAL, stud=stud,
                          ord=tagged(_ordinal(ch, ref.nth), "St_loc1"))
        if ref.kind == "same":
            return ch.say(F.STUD_SAME_TERSE if terse else F.STUD_SAME, stud=stud)
        if ref.kind == "relative":
            if ch.chance(self.count_last):
                return self.count_after_anchor(ref)
            direction = direction_phrase(ch, ref.direction, ref.count, "St_loc1", "stud")
            return ch.say(F.STUD_RELATIVE_TERSE if terse else F.STUD_RELATIVE, dir=direction, anchor=self.stud_anchor(ref),
                          stud=stud)
        if ref.kind == "none":
            return ch.say(F.STUD_NONE)
        raise ValueError(ref)

    def stud_anchor(self, ref: G.StudRef) -> Phrase:
        """The anchor of a relative stud position, tagged St_loc2."""
        ch = self.ch
        if ref.anchor == "previous":
            return ch.say(F.STUD_ANCHOR_PREVIOUS)
        if ref.anchor in ("leftmost", "rightmost"):
            return ch.say(F.STUD_ANCHOR_END[ref.anchor])
        if ref.anchor in self.stud_ids and ch.chance(0.2):  # "three left of the centre stud", "past the third stud"
            index, middle = self.stud_ids.index(ref.anchor), len(self.stud_ids) // 2
            if index == middle:
                return ch.say(F.STUD_ANCHOR_POSITION["middle"])
            side, nth = ("left", index + 1) if index < middle else ("right", len(self.stud_ids) - index)
            return ch.say(F.STUD_ANCHOR_POSITION[side], ord=tagged(_ordinal(ch, nth), "St_loc2"))
        return ch.say(F.STUD_ANCHOR_ID, id=id_phrase(ch, ref.anchor, "St_loc2"))

    def count_after_anchor(self, ref: G.StudRef) -> Phrase:
        """Non-native order, the count after the anchor: "at left of 500104 , three studs", "to the right side of
        the previous stud , 2 studs". The side word and the count carry St_loc1, the rest is O (guidelines 4.7)."""
        ch, rng = self.ch, self.ch.rng
        number = str(ref.count) if ch.chance(0.4) else NUMBER_WORDS[ref.count]
        unit = rng.choice(["stud", "stud", "", "stud away", "stud distance", "place"])
        if unit and ref.count != 1:
            unit = unit.replace("stud", "studs").replace("place", "places")
        count = ch.say(F.COUNT_AFTER_ANCHOR, n=tagged(number, "St_loc1"), unit=plain(unit))
        side = plain(rng.choice(F.SIDE_LEADS)) + tagged(ref.direction, "St_loc1") + plain(rng.choice(["", "", "side"]))
        return side + plain(rng.choice(["of", "of", "from"])) + self.stud_anchor(ref) + [punct(",")] + count

    def position_of(self, stud_id: str) -> Phrase | None:
        """The stud's position said before its id, both tagged ("the far left stud , 500100", "the third stud ,
        500102"): redundant, the id decides (guidelines 4.7). None where no short position names it."""
        if stud_id not in self.stud_ids:
            return None
        ch, i, n = self.ch, self.stud_ids.index(stud_id), len(self.stud_ids)
        stud = words_of(ch, F.STUD_NOUNS)
        if i == 0:
            return ch.say(F.STUD_END["leftmost"], stud=stud)
        if i == n - 1:
            return ch.say(F.STUD_END["rightmost"], stud=stud)
        ends = [(nth, side) for nth, side in ((i + 1, "left"), (n - i, "right")) if nth in ORDINAL_WORDS]
        if not ends:
            return None
        nth, side = ch.rng.choice(ends)
        if side == "left" and ch.chance(0.4):
            return ch.say(F.STUD_ORDINAL, stud=stud, ord=tagged(_ordinal(ch, nth), "St_loc1"))
        return ch.say(F.STUD_FROM_END, stud=stud, ord=tagged(_ordinal(ch, nth), "St_loc1"), side=tagged(side, "St_loc1"))

    def placement(self, placement: str | None = None) -> Phrase:
        """The placement as said; now and then after a placement ruled out ("not up top , centre line")."""
        said = self.ch.say(F.PLACEMENT[placement or self.meaning.placement], stud=words_of(self.ch, F.STUD_NOUNS))
        if placement is None and self.ch.chance(0.05):
            return self.ruled_out() + (parse(self.ch.rng.choice(F.PLACEMENT_NEGATED_LINKS)) + said if said else [])
        return said

    def ruled_out(self) -> Phrase:
        """Another placement, ruled out: all O (guidelines 4.7, a negated alternative)."""
        others = [p for p in F.PLACEMENT_NEGATED if p != self.meaning.placement]
        return plain(self.ch.rng.choice(F.PLACEMENT_NEGATED[self.ch.rng.choice(others)]))

    def placement_sentence(self) -> Phrase | None:
        """A sentence of its own for the placement ("Put it up top."); None for the unsaid default."""
        p = self.placement()
        if not p:
            return None
        return self.ch.say(F.PLACEMENT_SENTENCE, p=p)


# --- alternatives for a change of mind ------------------------------------------------------------------
def abandoned_target(rng: random.Random, ep: G.Episode, meaning: G.Meaning) -> G.TargetRef:
    """A different panel the worker names first and then takes back."""
    panel = meaning.expected["drywall_id"]
    site = ep.state.site
    others = [p.drywall_id for p in site.panels if p.drywall_id != panel]
    choice = rng.random()
    if choice < 0.5:
        return G.TargetRef("id", panel_id=rng.choice(others))
    if choice < 0.8:
        stacks = [s for s in ("left", "middle", "right") if panel is None or site.panel(panel).stack != s]
        return G.TargetRef("absolute", stack=rng.choice(stacks))
    sizes = [(4, 8), (2, 8), (4, 6)]
    if panel is not None:
        own = site.panel(panel).size_ft
        sizes = [s for s in sizes if (float(s[0]), float(s[1])) != tuple(own)]
    return G.TargetRef("size", size=rng.choice(sizes))


def abandoned_stud(rng: random.Random, meaning: G.Meaning) -> G.StudRef:
    """A different stud the worker names first and then takes back: mostly an id; a position said whole with another
    count or side ("the second from the right , no , the fourth from the right"; "two right of 500109 , no , three left
    of 500109"); or an end of the wall."""
    stud, ref = meaning.expected["stud_id"], meaning.stud
    choice = rng.random()
    if ref.kind == "relative" and choice < 0.35:
        if rng.random() < 0.5:
            return replace(ref, direction="left" if ref.direction == "right" else "right")
        return replace(ref, count=rng.choice([n for n in range(1, 5) if n != ref.count]))
    if ref.kind == "from_end" and choice < 0.35:
        if rng.random() < 0.3:
            return replace(ref, side="left" if ref.side == "right" else "right")
        return replace(ref, nth=rng.choice([n for n in range(1, 6) if n != ref.nth]))
    if choice < 0.5:
        return G.StudRef("from_end", side=rng.choice(["left", "right"]), nth=rng.randint(2, 5))
    ids = [f"5001{i:02d}" for i in range(13) if f"5001{i:02d}" != stud]
    return G.StudRef("id", stud_id=rng.choice(ids))


def as_plain(phrase: Phrase) -> Phrase:
    """The same words, every one ``O``: what a worker said and then took back (guidelines 4.7)."""
    return [Token(t.word, "O", "O") if t.is_word else t for t in phrase]


def without_end(sentence: Phrase) -> Phrase:
    """The sentence without its closing punctuation, to go on with it."""
    out = list(sentence)
    while out and not out[-1].is_word:
        out.pop()
    return out


def in_brackets(phrase: Phrase) -> Phrase:
    """Untagged words in round brackets glued to their first and last word: "(12.5 mm board)"."""
    out = list(phrase)
    idx = [i for i, t in enumerate(out) if t.is_word]
    if idx:
        first, last = idx[0], idx[-1]
        out[first] = Token("(" + out[first].word, out[first].tag, out[first].coref)
        out[last] = Token(out[last].word + ")", out[last].tag, out[last].coref)
    return out


# --- registers: sentence plans ---------------------------------------------------------------------------
Sentences = list[Phrase]


@dataclass
class Speaker:
    """Builds the sentences of one instruction in one register."""

    ch: Chooser
    meaning: G.Meaning
    ep: G.Episode
    register: str = "formal"

    size_property: tuple[Chooser, tuple[str, ...]] | None = None  #: see ``Pieces.size_property``

    def __post_init__(self) -> None:
        self.p = Pieces(self.ch, self.meaning, read_out_ids=0.3 if self.register in ("radio", "speech") else 0.0,
                        count_last=0.35 if self.register == "non_native" else 0.03,
                        stud_ids=tuple(self.ep.state.site.stud_ids), size_property=self.size_property)

    # words
    def w(self, bank: list[str]) -> Phrase:
        return words_of(self.ch, bank)

    def pick(self) -> Phrase:
        return self.w(F.PICK_VERBS)

    def place(self) -> Phrase:
        return self.w(F.PLACE_VERBS)

    def prep(self) -> Phrase:
        return self.w(F.PREPOSITIONS)

    def it(self) -> Phrase:
        return parse(self.ch.rng.choice(["it/@T", "it/@T", "it/@T", "that/@T", "this/@T one/@T", "her/@T", "the {n}"]),
                     n=self.p.noun())

    def T(self, terse: bool = False) -> Phrase:
        return self.p.target(terse)

    def D(self, terse: bool = False) -> Phrase:
        return self.p.stud(terse)

    def P(self) -> Phrase:
        return self.p.placement()

    def form(self, names: list[str]) -> str:
        """Which sentence frame: a name from ``names``; a ``~`` name is a held-back frame (novel split only)."""
        return self.ch.template(names)

    def end(self, phrase: Phrase, mark: str = ".") -> Phrase:
        return phrase + [punct(mark)]

    def comma(self) -> Phrase:
        return [punct(",")]

    def colon(self) -> Phrase:
        return [punct(":")]

    def P_first(self) -> Phrase:
        """The placement said before the rest ("up top this time"); the default in O words when unsaid."""
        p = self.P()
        return self.ch.say(F.PLACEMENT_FIRST, p=p) if p else self.w(F.DEFAULT_FIRST)

    def PD(self) -> Phrase:
        """The placement wrapped round the stud: "with its edge on the centre line of stud 500105"."""
        return self.ch.say(F.PLACEMENT_OF_STUD[self.meaning.placement], d=self.D())

    def id_again(self) -> Phrase | None:
        """The stud's (or else the panel's) id said once more, as typed, for a repetition; None without an id."""
        stud, target = self.meaning.stud, self.meaning.target
        if stud.kind == "id":
            return plain(self.ch.rng.choice(["", "stud", "", "I said"])) + id_phrase(self.ch, stud.stud_id, "ID_stud")
        if target.kind == "id":
            return plain(self.ch.rng.choice(["panel", "sheet", "I said", "I said panel"])) + \
                id_phrase(self.ch, target.panel_id, "ID_wall")
        return None

    def body(self) -> Sentences:
        """A plain instruction in a foreman's or a formal frame, for registers that wrap one."""
        return self.foreman() if self.ch.chance(0.55) else self.formal()

    # registers
    def formal(self) -> Sentences:
        ch, T, D, P = self.ch, self.T, self.D, self.P
        form = ch.rng.randrange(9)
        opener = self.w(["", "please", "please", "I would like you to", "I need you to", "next, please"])
        if form == 0:
            return [self.end(opener + self.pick() + T() + plain("and") + self.place() + self.it() + self.prep() + D() + P())]
        if form == 1:
            return [self.end(opener + self.place() + T() + self.prep() + D() + P())]
        if form == 2:
            return [self.end(opener + self.pick() + T()), self.end(self.place() + self.it() + self.prep() + D() + P())]
        if form == 3:
            out = [self.end(plain("the next panel is") + T()), self.end(plain("it goes") + self.prep() + D() + P())]
            return out
        if form == 4:
            return [self.end(opener + self.place() + T() + P() + self.prep() + D())]
        if form == 6:  # the placement wrapped round the stud
            return [self.end(opener + self.place() + T() + self.PD())]
        if form == 7:  # the stud first
            return [self.end(plain(ch.rng.choice(["on", "for", "at", "onto"])) + D() + self.comma()
                             + self.w(["please", "I would like you to", "kindly", "we need you to"]) + self.place() + T() + P())]
        if form == 8:
            return [self.end(T() + plain(ch.rng.choice(["should go", "is to go", "needs to go", "will go"])) + self.prep()
                             + D() + P())]
        sentences = [self.end(opener + self.pick() + T() + plain("and") + self.place() + self.it() + self.prep() + D())]
        p = self.p.placement_sentence()
        return sentences + ([self.end(p)] if p else [])

    def polite(self) -> Sentences:
        ch, T, D, P = self.ch, self.T, self.D, self.P
        q = self.w(F.QUESTION_OPENERS)
        hedge = self.w(F.HEDGES)
        form = int(self.form(["0", "1", "2", "3", "5", "~4"]))
        if form == 0:
            return [self.end(q + self.pick() + T() + plain("and") + self.place() + self.it() + self.prep() + D() + P(), "?")]
        if form == 1:
            return [self.end(hedge + plain("we need") + T() + plain("next")),
                    self.end(q + self.place() + self.it() + self.prep() + D() + P(), "?")]
        if form == 2:
            return [self.end(plain("sorry to bother you") + self.comma() + q + self.place() + T() + self.prep() + D() + P()
                             + plain("please"), "?")]
        if form == 3:
            return [self.end(plain("if you could") + self.comma() + self.pick() + T() + plain("and") + self.place()
                             + self.it() + self.prep() + D() + P()), self.end(plain("thank you so much"))]
        if form == 4:
            return [self.end(self.place() + T() + self.prep() + D() + P() + self.comma()
                             + plain(ch.rng.choice(["if that works for you", "if that's alright", "if you can"])), "?")]
        return [self.end(hedge + plain("it should be") + T()),
                self.end(plain("and") + hedge + plain("it goes") + self.prep() + D() + P())]

    def foreman(self) -> Sentences:
        ch, T, D, P = self.ch, self.T, self.D, self.P
        rng = ch.rng
        form = rng.randrange(16)
        if form == 0:
            return [self.end(T() + self.prep() + D() + self.comma() + P())]
        if form == 1:
            return [self.end(self.pick() + T() + self.comma() + self.place() + self.it() + self.prep() + D() + P())]
        if form == 2:
            return [self.end(T() + plain("goes") + self.prep() + D() + P())]
        if form == 3:
            out = [self.end(plain(ch.rng.choice(["next one's", "next is", "now", "next"])) + T()), self.end(D(True))]
            p = P()
            return out + ([self.end(p)] if p else [])
        if form == 4:
            return [self.end(plain("get") + T() + plain("up") + self.prep() + D() + P() + self.comma()
                             + plain(ch.rng.choice(["let's go", "come on", "move it", "chop chop", "today"])))]
        if form == 5:
            return [self.end(self.place() + T() + P() + self.prep() + D())]
        if form == 6:
            return [self.end(self.w(F.INTENTS) + self.place() + T() + self.prep() + D() + P() + self.w(F.CLOSERS))]
        if form == 8:  # the stud first
            return [self.end(plain(rng.choice(["on", "onto", "for", "at", "over on"])) + D() + self.comma() + self.place()
                             + T() + P())]
        if form == 9:  # the stud as the subject
            return [self.end(D() + plain(rng.choice(["gets", "needs", "takes", "is getting", "wants"])) + T() + P())]
        if form == 10:  # the target last
            kind = rng.randrange(3)
            if kind == 0:
                return [self.end(plain("what goes on") + D() + plain("is") + T() + self.comma() + P())]
            if kind == 1:
                return [self.end(plain("on") + D() + P() + plain(rng.choice(["goes", "we want", "I want"])) + T())]
            return [self.end(D() + self.comma() + P() + self.comma() + plain("with") + T())]
        if form == 11:  # a cleft
            if rng.random() < 0.5:
                return [self.end(plain("it's") + T() + plain("that goes") + self.prep() + D() + P())]
            return [self.end(plain("what I want") + self.prep() + D() + plain("is") + T() + P())]
        if form == 12:  # the placement first
            return [self.end(self.P_first() + self.colon() + T() + self.prep() + D())]
        if form == 13:  # an aside between the parts
            return [self.end(self.pick() + T() + self.comma() + self.w(F.ASIDES) + self.comma() + self.place() + self.it()
                             + self.prep() + D() + P())]
        if form == 14:  # the placement wrapped round the stud
            return [self.end(self.place() + T() + self.PD())]
        if form == 15:  # asked and answered
            out = [self.end(T()), self.end(plain(rng.choice(["where", "where to", "on what"])), "?"), self.end(D())]
            p = P()
            return out + ([self.end(plain("how"), "?"), self.end(p)] if p else [])
        return [self.end(T() + self.comma() + D() + self.comma() + P() + self.comma() + plain("go"))]

    def fragment(self) -> Sentences:
        ch = self.ch
        form = ch.rng.randrange(10)
        self.p.bare_stacks = form in (0, 2)  # "Left. 500107." / "left, 500107": a stack by its side alone
        T, D, P = self.T(True), self.D(True), self.P()
        if form == 6 and P:  # the placement first
            return [self.end(P + self.colon() + T + self.comma() + D)]
        if form == 7:  # the stud as the key
            return [self.end(D + self.colon() + T + P)]
        if form == 8:
            return [T + plain("/") + D + (plain("/") + P if P else [])]
        if form == 9:
            return [self.end(T + plain(ch.rng.choice(["@", "=>", "at"])) + D + P)]
        if form == 0:
            return [self.end(T), self.end(D)] + ([self.end(P)] if P else [])
        if form == 1:
            return [T + D + P]
        if form == 2:
            return [self.end(T + self.comma() + D + (self.comma() + P if P else []))]
        if form == 3:
            return [self.end(T + plain(ch.rng.choice(["to", "on", "onto", "at", "->"])) + D + P)]
        if form in (4, 6):
            return [self.end(D + self.comma() + T + (self.comma() + P if P else []))]
        return [self.end(T + plain("on") + D), self.end(P)] if P else [self.end(T + plain("on") + D)]

    def listing(self) -> Sentences:
        ch = self.ch
        form = int(self.form(["0", "1", "2", "3", "4", "5", "7", "8", "9", "10", "~6"]))
        self.p.bare_stacks = form in (0, 2, 4, 8, 9, 10)  # keyed or one per line: "panel: left"
        T, D, P = self.T(True), self.D(True), self.P()
        colon = [punct(":")]
        if form != 6 and ch.chance(0.25):  # a numbered label first: "task #3 :" (the number is a label, O)
            label = plain(f"{ch.rng.choice(F.LABEL_NOUNS)} #{ch.rng.randint(1, 12)}") + \
                (colon if ch.chance(0.5) else plain(ch.rng.choice(["-", "--", "|"])))
            return [label + sentence if i == 0 else sentence for i, sentence in enumerate(self._listing(form, T, D, P))]
        return self._listing(form, T, D, P)

    def _listing(self, form: int, T: Phrase, D: Phrase, P: Phrase) -> Sentences:
        ch = self.ch
        colon = [punct(":")]
        if form == 7:  # numbered steps
            out = [self.end(plain("step 1") + colon + self.pick() + T), self.end(plain("step 2") + colon + self.place()
                                                                              + plain(ch.rng.choice(["on", "to", "at"])) + D)]
            return out + ([self.end(plain("step 3") + colon + P)] if P else [])
        if form == 8:  # bullets
            return [plain("-") + T, plain("-") + D] + ([plain("-") + P] if P else [])
        if form == 9:
            out = plain(ch.rng.choice(["panel =", "sheet =", "board ="])) + T + self.comma() + plain("stud =") + D
            return [out + (self.comma() + plain(ch.rng.choice(["position =", "pos =", "orient ="])) + P if P else [])]
        if form == 10:
            out = plain("task") + colon + plain(ch.rng.choice(["hang", "install", "fix"])) + T + plain("|") + \
                plain("stud") + colon + D
            return [out + (plain("|") + plain("orientation") + colon + P if P else [])]
        if form == 0:
            out = plain(ch.rng.choice(["panel", "sheet", "board", "what"])) + colon + T + [punct(";")] + \
                plain(ch.rng.choice(["stud", "where", "location", "dest"])) + colon + D
            if P:
                out += [punct(";")] + plain(ch.rng.choice(["placement", "how", "orientation", "position"])) + colon + P
            return [out]
        if form == 1:
            out = plain("sheet -") + T + plain("| stud -") + D + (plain("|") + P if P else [])
            return [out]
        if form == 2:
            return [plain("target") + T + self.comma() + plain("destination") + D + (self.comma() + P if P else [])]
        if form == 3:  # a numbered checklist
            return [plain("1)") + self.pick() + T + plain("2)") + self.place() + plain("on") + D
                    + (plain("3)") + P if P else [])]
        if form == 4:
            out = [self.end(plain("what") + colon + T), self.end(plain("where") + colon + D)]
            return out + ([self.end(plain("how") + colon + P)] if P else [])
        if form == 5:
            return [plain("*") + T + plain("*") + D + (plain("*") + P if P else [])]
        ticket = plain(f"ticket {ch.rng.randint(1, 40)}") + colon  # a job ticket (held back: the novel split only)
        out = ticket + plain("item") + T + [punct(";")] + plain("location") + D
        return [out + ([punct(";")] + plain("mount") + P if P else [])]

    def speech(self) -> Sentences:
        """Spoken: a foreman's or polite frame; ``render`` lowercases it and adds fillers and restarts."""
        return self.foreman() if self.ch.chance(0.5) else self.formal()

    def radio(self) -> Sentences:
        ch, T, D, P = self.ch, self.T, self.D, self.P
        call = self.w(F.RADIO_CALLS)
        end = self.w(F.RADIO_ENDS)
        form = int(self.form(["0", "1", "2", "4", "5", "6", "7", "~3"]))
        if form == 5:  # "message follows", the parts split by "break"
            return [self.end(self.call_sign() + self.comma() + plain("message follows")),
                    self.end(T() + self.comma() + plain("break") + self.comma() + D() + P()), self.end(end)]
        if form == 6:  # "I say again": the id repeated
            again = self.id_again()
            if again is not None:
                if self.meaning.stud.kind == "id":
                    return [self.end(T() + self.prep() + D() + self.comma() + plain("I say again") + self.comma()
                                     + again + P() + self.comma() + end)]
                return [self.end(T() + self.comma() + plain("I say again") + self.comma() + again + self.prep() + D()
                                 + P() + self.comma() + end)]
            form = 0
        if form == 7:
            return [self.end(call), self.end(plain(ch.rng.choice(["next task", "task"])) + self.colon() + T() + self.prep()
                                             + D() + P()), self.end(end)]
        if form == 0:
            sign = self.call_sign() + self.comma() if ch.chance(0.3) else []
            return [self.end(sign + call + self.comma() + T() + self.prep() + D() + P() + self.comma() + end)]
        if form == 4:
            return [self.end(self.call_sign()), self.end(T() + self.prep() + D() + P() + self.comma() + end)]
        if form == 1:
            return [self.end(T() + plain("to") + D() + self.comma() + P()), self.end(end)]
        if form == 2:
            return [self.end(call), self.end(plain("next") + T() + self.comma() + self.place() + plain("on") + D() + P()),
                    self.end(end)]
        return [self.end(self.w(F.CALL_SIGNS) + self.comma() + T() + self.prep() + D() + P()),
                self.end(plain(ch.rng.choice(["over and out", "how copy", "over and out"])))]

    def call_sign(self) -> Phrase:
        """Who calls whom: a fixed call sign, or a unit with a number ("team two , this is bravo"), all O."""
        rng = self.ch.rng
        if self.ch.chance(0.4):
            return self.w(F.CALL_SIGNS)
        n = rng.randint(1, 9)
        return parse(rng.choice(F.CALL_FRAMES).format(unit=rng.choice(F.CALL_UNITS), name=rng.choice(F.CALL_NAMES),
                                                      n=str(n) if self.ch.chance(0.35) else NUMBER_WORDS[n]))

    def non_native(self) -> Sentences:
        ch, T, D, P = self.ch, self.T, self.D, self.P
        rng = ch.rng
        form = rng.randrange(14)
        nn = lambda: self.w(F.NN_PREPOSITIONS)  # noqa: E731
        if form == 6:
            return [self.end(T() + plain(rng.choice(["you must to put", "you must put", "you need put"])) + nn() + D() + P())]
        if form == 7:
            return [self.end(plain("for") + D() + plain(rng.choice(["you take", "you are take", "take"])) + T() + P())]
        if form == 8:
            return [self.end(plain(rng.choice(["is need", "need", "is necessary"])) + T() + nn() + D() + P())]
        if form == 9:
            return [self.end(plain("take") + T() + self.comma() + plain(rng.choice(["after put", "after you put", "then is put"]))
                             + nn() + D() + self.comma() + plain("position") + (P() or self.w(F.ENG_DEFAULT_PLACEMENT)))]
        if form == 10:
            return [self.end(plain("you are taking") + T() + plain("and putting") + nn() + D() + P())]
        if form == 11:  # the verb last
            return [self.end(plain(rng.choice(["now", "so", "next"])) + T() + nn() + D() + P()
                             + plain(rng.choice(["you put", "you install", "you are put"])))]
        if form == 12:
            return [self.end(plain(rng.choice(["please make install", "please do install", "please to make"])) + T() + nn()
                             + D() + P())]
        if form == 13:
            return [self.end(D() + plain(rng.choice(["is the place for", "is place for", "is for"])) + T() + P())]
        if form == 0:
            return [self.end(plain("you") + self.pick() + T() + plain("and") + self.place() + plain("on") + D() + P())]
        if form == 1:
            return [self.end(plain("please to") + self.place() + T() + plain(ch.rng.choice(["on", "in", "at"])) + D() + P())]
        if form == 2:
            return [self.end(self.place() + plain(ch.rng.choice(["on", "in", "at"])) + self.D(True) + plain("the") + T(True) + P())]
        if form == 3:
            return [self.end(plain(ch.rng.choice(["begin from", "start from", "start in", "begin in"])) + D()
                             + self.comma() + self.place() + T() + P())]
        if form == 4:
            return [self.end(T() + plain("you") + self.place() + plain("it in") + D() + P())]
        return [self.end(plain(ch.rng.choice(["now is", "now it is", "is"])) + T() + self.comma()
                         + plain(ch.rng.choice(["for", "in", "to"])) + D() + self.comma() + P())]

    def correction(self) -> Sentences:
        """A change of mind: something is said and taken back; only the final words carry tags."""
        ch, rng = self.ch, self.ch.rng
        fix = self.w(F.CORRECTIONS)
        tail = self.w(F.CORRECTION_ENDS)
        which = rng.choice(["target", "stud", "placement"]) if self.meaning.target.kind != "none" else "stud"
        if which == "stud" and self.meaning.stud.kind == "none":
            which = "placement"
        style = rng.randrange(6)
        if style == 5:  # the next sentence takes back one part: "Take the 4x8. Actually no, the 2x8. Hang it on ..."
            return self.part_taken_back(which, fix)
        if style == 1:  # a whole sentence taken back, then said again right
            T, D, P = self.T(), self.D(), self.P()
            if which == "target":
                T = self.p.target(ch.chance(0.4), abandoned_target(rng, self.ep, self.meaning))
            elif which == "stud":
                D = self.p.stud(ch.chance(0.4), abandoned_stud(rng, self.meaning))
            else:
                others = [p for p in F.PLACEMENT if p != self.meaning.placement and p != "vertical_left"]
                P = self.p.placement(rng.choice(others))
            wrong = as_plain(self.place() + T + self.prep() + D + P)
            return [self.end(wrong), self.end(self.w(F.CORRECTION_SENTENCES) + self.colon() + self.place() + self.T()
                                              + self.prep() + self.D() + self.P())]
        if style == 2:  # a negated alternative: "on 500105, not 500104"
            if which == "target":
                wrong = as_plain(self.p.target(ch.chance(0.4), abandoned_target(rng, self.ep, self.meaning)))
                if ch.chance(0.5):
                    return [self.end(self.place() + self.T() + self.comma() + plain("not") + wrong + self.comma()
                                     + self.prep() + self.D() + self.P())]
                return [self.end(plain("not") + wrong + self.comma() + self.T() + self.comma() + self.prep() + self.D()
                                 + self.P())]
            if which == "stud":
                wrong = as_plain(self.p.stud(ch.chance(0.4), abandoned_stud(rng, self.meaning)))
                return [self.end(self.place() + self.T() + self.prep() + self.D() + self.comma() + plain("not") + wrong
                                 + self.P())]
            others = [p for p in F.PLACEMENT if p != self.meaning.placement and p != "vertical_left"]
            wrong = as_plain(self.p.placement(rng.choice(others)))
            right = self.P() or plain(rng.choice(["standing up", "upright", "vertical"]))
            return [self.end(self.place() + self.T() + self.prep() + self.D() + right + self.comma() + plain("not") + wrong)]
        if style == 3 and which in ("target", "stud"):  # "did I say X? I meant Y."
            if which == "stud":
                wrong = as_plain(self.p.stud(True, abandoned_stud(rng, self.meaning)))
                first = self.place() + self.T() + self.prep() + wrong + self.P()
                right = self.D()
            else:
                wrong = as_plain(self.p.target(True, abandoned_target(rng, self.ep, self.meaning)))
                first = self.place() + wrong + self.prep() + self.D() + self.P()
                right = self.T()
            return [self.end(first), self.end(self.w(F.CORRECTION_ASKS) + wrong, "?"),
                    self.end(self.w(F.CORRECTION_MEANT) + right)]
        if which == "target":
            wrong = as_plain(self.p.target(ch.chance(0.4), abandoned_target(rng, self.ep, self.meaning)))
            return [self.end(self.place() + wrong + self.comma() + fix + self.comma() + self.T() + tail + self.prep()
                             + self.D() + self.P())]
        if which == "stud":
            recount = self.count_corrected(fix) if self.meaning.stud.kind == "relative" and ch.chance(0.5) else None
            if recount is not None:
                return [self.end(self.place() + self.T() + self.prep() + recount + self.P())]
            wrong = as_plain(self.p.stud(ch.chance(0.4), abandoned_stud(rng, self.meaning)))
            return [self.end(self.place() + self.T() + self.prep() + wrong + self.comma() + fix + self.comma()
                             + self.D() + tail + self.P())]
        others = [p for p in F.PLACEMENT if p != self.meaning.placement and p != "vertical_left"]
        wrong = as_plain(self.p.placement(rng.choice(others)))
        right = self.P() or plain(rng.choice(["the normal way", "just upright", "regular, upright", "standing up"]))
        return [self.end(self.place() + self.T() + self.prep() + self.D() + wrong + self.comma() + fix + self.comma()
                         + right + tail)]

    def part_taken_back(self, which: str, fix: Phrase) -> Sentences:
        """One part said, then taken back in a sentence of its own that says only the new part; the rest follows
        or came before. The abandoned words are O, the new part carries the tags (guidelines 4.7)."""
        ch, rng = self.ch, self.ch.rng
        fix = fix + self.comma() if fix else plain(rng.choice(["no", "sorry", "wait"])) + self.comma()
        if which == "target":
            wrong = as_plain(self.p.target(ch.chance(0.4), abandoned_target(rng, self.ep, self.meaning)))
            return [self.end(self.pick() + wrong), self.end(fix + self.T() + self.w(F.CORRECTION_ENDS)),
                    self.end(self.place() + self.it() + self.prep() + self.D() + self.P())]
        if which == "stud":
            wrong = as_plain(self.p.stud(ch.chance(0.4), abandoned_stud(rng, self.meaning)))
            return [self.end(self.place() + self.T() + self.prep() + wrong),
                    self.end(fix + self.prep() + self.D() + self.P() + self.w(F.CORRECTION_ENDS))]
        others = [p for p in F.PLACEMENT if p != self.meaning.placement and p != "vertical_left"]
        wrong = as_plain(self.p.placement(rng.choice(others)))
        right = self.P() or plain(rng.choice(["stand it up", "upright", "standing up", "just vertical", "the normal way"]))
        if ch.chance(0.5):  # the stud last: "... across the top. No, forget the top row; stand it up on 500108."
            return [self.end(self.T() + wrong), self.end(fix + right + self.prep() + self.D())]
        return [self.end(self.place() + self.T() + self.prep() + self.D() + wrong), self.end(fix + right)]

    def count_corrected(self, fix: Phrase) -> Phrase | None:
        """A relative stud said with the wrong count, and only the count said again: "two studs right of 500104 ,
        wait no , three". The first count is O, the rest of the position keeps its tags; None where the wording
        has no count word to take back."""
        ch, ref = self.ch, self.meaning.stud
        wrong_count = ch.rng.choice([n for n in range(2, 6) if n != ref.count])
        said = self.p.stud(ch.chance(0.4), replace(ref, count=wrong_count))
        spellings = {str(wrong_count), NUMBER_WORDS[wrong_count], ORDINAL_WORDS[wrong_count], ORDINAL_DIGITS[wrong_count]}
        counts = [i for i, t in enumerate(said) if t.tag == "St_loc1" and t.word.lower() in spellings]
        if len(counts) != 1:
            return None
        said[counts[0]] = Token(said[counts[0]].word, "O", "O")
        again = _number(ch, ref.count, "St_loc1") + plain(ch.rng.choice(["", "", "studs", "places", "over"]))
        return said + [punct(".") if ch.chance(0.3) else punct(",")] + fix + self.comma() + again

    def context(self) -> Sentences:
        ch = self.ch
        if self.meaning.placement in F.CONTEXT_PLACEMENT and ch.chance(0.4):
            return self.context_placement()
        context = ch.rng.choice(F.CONTEXT)
        number = str(ch.rng.randint(2, 9)) if ch.chance(0.5) else NUMBER_WORDS[ch.rng.randint(2, 9)]
        reason = parse(context.replace("{n}", number).replace("{sid}", f"5001{ch.rng.randrange(13):02d}"))
        body = self.formal() if ch.chance(0.4) else self.foreman()
        if ch.chance(0.5):
            return [self.end(reason)] + body
        first = body[0]
        return [reason + self.comma() + self.w(F.CONTEXT_LINKS) + first] + body[1:]

    def context_placement(self) -> Sentences:
        """Context that sets this panel's placement ("we're doing the top row now, so ..."): its placement words are
        tagged, and the instruction after it mostly leaves the placement out (guidelines 4.7)."""
        ch, rng = self.ch, self.ch.rng
        reason = ch.say(F.CONTEXT_PLACEMENT[self.meaning.placement])
        form = rng.randrange(3)
        if form == 0:
            body = self.place() + self.T() + self.prep() + self.D()
        elif form == 1:
            body = self.pick() + self.T() + plain("and") + self.place() + self.it() + self.prep() + self.D()
        else:
            body = self.T(True) + self.prep() + self.D(True)
        if ch.chance(0.25):
            body += self.comma() + self.P()
        if ch.chance(0.5):
            return [self.end(reason), self.end(body)]
        return [self.end(reason + self.comma() + self.w(F.CONTEXT_LINKS) + body)]

    def question(self) -> Sentences:
        ch, T, D, P = self.ch, self.T, self.D, self.P
        form = ch.rng.randrange(8)
        if form == 4:  # asked and answered
            return [self.end(plain(ch.rng.choice(["where does", "where should", "where's"])) + T()
                             + plain(ch.rng.choice(["go", "go", "going"])), "?"), self.end(D() + P())]
        if form == 5:
            return [self.end(plain(ch.rng.choice(["you see", "see", "got", "found"])) + T(), "?"),
                    self.end(self.place() + self.it() + self.prep() + D() + P())]
        if form == 6:  # a question tag
            return [self.end(T() + self.prep() + D() + P() + self.comma() + self.w(F.QUESTION_TAGS), "?")]
        if form == 7:
            return [self.end(plain(ch.rng.choice(["can we get", "could we have", "can I get"])) + T() + self.prep() + D()
                             + P(), "?")]
        if form == 0:
            return [self.end(self.w(F.QUESTION_OPENERS) + self.place() + T() + self.prep() + D() + P(), "?")]
        if form == 1:
            return [self.end(plain("how about") + T() + plain("on") + D() + P(), "?")]
        if form == 2:
            return [self.end(plain("is") + D() + plain("free"), "?"), self.end(self.place() + T() + plain("there") + P())]
        return [self.end(plain("what if we") + self.place() + T() + self.prep() + D() + P(), "?")]

    def texting(self) -> Sentences:
        """A phone message: a fragment, a foreman's line or an apprentice checking; ``render`` abbreviates it
        (``texting_forms``)."""
        ch = self.ch
        r = ch.rng.random()
        if r < 0.4:
            out = self.fragment()
        elif r < 0.75:
            out = self.foreman()
        else:  # an apprentice checking what to do
            T, D, P = self.T(True), self.D(True), self.P()
            frame = ch.rng.randrange(4)
            if frame == 0:
                out = [self.end(plain("so") + T + plain("on") + D + P, "?")]
            elif frame == 1:
                out = [self.end(plain("u want") + T + plain(ch.rng.choice(["on", "to", "at"])) + D + P, "?")]
            elif frame == 2:
                out = [self.end(plain("ok") + T + plain("to") + D + P + plain("then"))]
            else:
                out = [self.end(plain("u do") + T + plain("on") + D + P + plain("next k"))]
        out = [self.w(F.TEXT_OPENERS) + out[0]] + out[1:]
        core = without_end(out[-1])  # the message's last words go before its closing mark: "... asap?"
        return out[:-1] + [core + self.w(F.TEXT_ENDS) + out[-1][len(core):]]

    def explain(self) -> Sentences:
        """Someone explaining: a reason after the instruction, a lesson for an apprentice, a purpose first, a story
        of what happened before, a reason in the middle, a long sentence with clauses around it. Only the
        instruction's own words carry tags."""
        ch, T, D, P = self.ch, self.T, self.D, self.P
        rng = ch.rng
        form = int(self.form(["0", "1", "2", "3", "4", "5", "~6"]))
        if form == 0:  # a reason after
            body = self.body()
            reason = self.w(F.REASON_LINKS) + self.w(F.REASONS_AFTER)
            if ch.chance(0.5):
                return body[:-1] + [self.end(without_end(body[-1]) + self.comma() + reason)]
            return body + [self.end(reason)]
        if form == 1:  # teaching an apprentice
            out = [self.end(self.w(F.TEACH_OPENERS))]
            if ch.chance(0.5):
                out.append(self.end(plain("first you") + self.pick() + T() + self.comma()
                                    + plain(rng.choice(["then you", "and then you", "then"])) + self.place() + self.it()
                                    + self.prep() + D() + P()))
            else:
                out += [self.end(plain("you take") + T()), self.end(plain("you line it up") + self.prep() + D() + P()),
                        self.end(plain(rng.choice(["and you screw it off", "then you screw it", "done"])))]
            return out + ([self.end(self.w(F.TEACH_TIPS))] if ch.chance(0.7) else [])
        if form == 2:  # a purpose first
            return [self.end(self.w(F.PURPOSES) + self.comma() + self.place() + T() + self.prep() + D() + P())]
        if form == 3:  # a story of what happened before
            last = self.ep.last
            if last is not None and ch.chance(0.4):
                story = ch.say(F.STORIES_LAST, panel=plain(last["drywall_id"]), stud=plain(last["stud_id"]))
            else:
                story = self.w(F.STORIES)
            body = self.body()
            return [self.end(story), self.w(F.STORY_LINKS) + body[0]] + body[1:]
        if form == 4:  # a reason in the middle
            return [self.end(self.pick() + T() + self.comma() + self.w(F.REASONS_AFTER) + self.comma()
                             + plain(rng.choice(["so", "so", "and"])) + self.place() + self.it() + self.prep() + D() + P())]
        if form == 5:  # a long sentence: clauses before and after
            return [self.end(self.w(F.LEAD_CLAUSES) + self.comma() + self.place() + T() + self.prep() + D() + P()
                             + self.comma() + self.w(F.TRAIL_CLAUSES))]
        body = self.body()  # a note left for the next shift (held back: the novel split only)
        tip = [self.end(self.w(F.TEACH_TIPS))] if ch.chance(0.4) else []
        return [self.w(F.HANDOVER) + self.colon() + body[0]] + body[1:] + tip

    def boss(self) -> Sentences:
        """An impatient boss: barked pieces, exclamations, "why isn't it up yet?", a repeated id."""
        ch, rng = self.ch, self.ch.rng
        opener, end = self.w(F.BOSS_OPENERS), self.w(F.BOSS_ENDS)
        form = rng.randrange(6)
        if form == 3:  # a repetition: "... 500105. Stud 500105!"
            again = self.id_again()
            if again is not None:
                return [self.end(opener, "!"), self.end(self.place() + self.T() + self.prep() + self.D() + self.P()),
                        self.end(again, "!")]
            form = 4
        if form == 0:  # barked pieces
            T, D, P = self.T(True), self.D(True), self.P()
            return [self.end(opener, "!"), self.end(T, "!"), self.end(D, "!")] + ([self.end(P, "!")] if P else []) \
                + [self.end(end, "!")]
        if form == 1:
            return [self.end(opener + self.comma() + self.pick() + self.T() + plain("and get it") + self.prep() + self.D()
                             + self.P() + self.comma() + end, "!")]
        if form == 2:  # why isn't it done yet
            frame = rng.choice(["why is {t} not on {d} yet", "why isn't {t} on {d} yet", "{t} should be on {d} by now",
                                "I wanted {t} on {d} ten minutes ago"])
            out = [self.end(parse(frame, t=self.T(), d=self.D()), "?" if frame.startswith("why") else "!")]
            p = self.P()
            return out + [self.end((p + self.comma() if p else []) + end, "!")]
        if form == 4:
            return [self.end(opener, "!"), self.end(self.T() + self.prep() + self.D() + self.P() + self.comma() + end, "!")]
        return [self.end(plain(rng.choice(["I told you already", "I said it once", "listen"])) + self.comma() + self.T()
                         + plain("goes") + self.prep() + self.D() + self.P(), "!")]

    def engineer(self) -> Sentences:
        """A site engineer writing formally, with technical detail (thicknesses, screw spacing, drawing
        references) whose numbers carry no tag."""
        ch, rng = self.ch, self.ch.rng
        opener = parse(ch.template(F.ENG_OPENERS).replace("{k}", str(rng.randint(1, 40)))
                       .replace("{m}", str(rng.randint(41, 60))))
        detail = self.w(F.ENG_DETAILS)
        P = self.P()
        orient = P or self.w(F.ENG_DEFAULT_PLACEMENT)
        key = self.w(F.ENG_PLACEMENT_KEYS)
        colon = self.colon()
        form = rng.randrange(6)
        if form == 0:
            return [self.end(opener + colon + self.T() + plain(rng.choice(["to be installed at", "to be fixed to",
                                                                            "to be mounted on", "shall be installed on"]))
                             + self.D() + (self.comma() + P if P else [])), self.end(detail)]
        if form == 1:
            return [self.end(plain(rng.choice(["the next panel to be fixed is", "next panel", "panel to install"])) + self.T()),
                    self.end(plain(rng.choice(["location", "stud", "fixing location"])) + colon + self.D()),
                    self.end(key + colon + orient), self.end(detail)]
        if form == 2:
            return [self.end(plain(rng.choice(["install", "fix", "mount", "erect"])) + self.T()
                             + plain(rng.choice(["at", "to", "on"])) + self.D() + self.comma() + orient + [punct(";")] + detail)]
        if form == 3:
            return [self.end(plain(rng.choice(["it is requested that", "kindly ensure that", "please arrange that"]))
                             + self.T() + plain("be fixed to") + self.D() + P), self.end(detail)]
        if form == 4:
            return [self.end(opener + colon + self.T() + in_brackets(detail) + self.comma() + plain("to") + self.D()
                             + self.comma() + orient)]
        ref = plain(rng.choice(["the layout drawing", "drawing A-201", "the method statement", "the wall schedule",
                                "the coordination meeting"]))
        return [self.end(plain("with reference to") + ref + self.comma() + self.T() + plain("is to be installed on")
                         + self.D() + self.comma() + key + orient + [punct(";")] + detail)]

    def sentences(self) -> Sentences:
        register = self.register
        maker: Callable[[], Sentences] = {
            "formal": self.formal, "polite": self.polite, "foreman": self.foreman, "fragment": self.fragment,
            "list": self.listing, "speech": self.speech, "radio": self.radio, "non_native": self.non_native,
            "correction": self.correction, "context": self.context, "question": self.question,
            "texting": self.texting, "explain": self.explain, "boss": self.boss, "engineer": self.engineer,
        }[register]
        return [s for s in maker() if any(t.is_word for t in s)]


# --- rendering and noise ------------------------------------------------------------------------------
#: Words that a hurried worker or a speech recogniser drops; never tagged, never a correction marker.
DROPPABLE = frozenset({"the", "a", "an", "it", "please", "and", "that", "is", "for", "then", "now", "up"})
CASING = {"typed": 0.53, "lower": 0.34, "upper": 0.04, "no_first_capital": 0.06, "title": 0.03}


def _typo(rng: random.Random, word: str) -> str:
    i = rng.randrange(len(word) - 1)
    kind = rng.randrange(3)
    if kind == 0:
        return word[:i] + word[i + 1] + word[i] + word[i + 2:]  # swapped letters
    if kind == 1:
        return word[:i] + word[i + 1:]  # a letter missing
    return word[:i] + word[i] + word[i:]  # a letter twice


#: Untagged words the IM reads (the default placement offered with "or": "the left line"; a row word after "along",
#: "across", "onto": ``im.words.stack_place``): never misspelt.
READ_UNTAGGED = frozenset({"left", "line", "edge", "side", "along", "across", "onto", "into", "near"})


@functools.lru_cache(maxsize=1)
def _read_by_front_end() -> frozenset[str]:
    """The one-word forms the front end reads as other words (the code-switch and shorthand lexicons): a typo that
    lands on one ("come" -> "comme", French for "as") would say another word."""
    from drywall_lab.nlu.normalise import _form_key, read_code_switch, read_lexicon

    exact, any_case = read_lexicon()
    return frozenset({_form_key(form, language)[0] for form, _, language in read_code_switch() if " " not in form}
                     | set(any_case) | {form.lower() for form in exact})


def _misspelt(rng: random.Random, word: str) -> str:
    """A typo in ``word``, or the word as it is where the typo would be a word the front end reads as another, or
    where the word is typed in a script written without spaces (an input method picks whole words)."""
    typo = _typo(rng, word)
    return word if typo.lower() in _read_by_front_end() or word.lower() in READ_UNTAGGED or UNSPACED.search(word) \
        else typo


def add_noise(ch: Chooser, sentences: Sentences, spoken: bool) -> Sentences:
    """Dropped articles, fillers, stutters and restarts, typos: only in words that carry no tag."""
    rng = ch.rng
    drop_p = 0.12 if spoken or ch.chance(0.3) else 0.0
    filler_p = 0.08 if spoken else (0.02 if ch.chance(0.3) else 0.0)
    typo_p = 0.03 if ch.chance(0.25) else 0.0
    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        for tok in sentence:
            if tok.is_word and tok.tag == "O":
                lower = tok.word.lower()
                if lower in DROPPABLE and rng.random() < drop_p:
                    continue
                if rng.random() < filler_p:
                    new += plain(rng.choice(F.FILLERS))
                if spoken and rng.random() < 0.03:
                    new.append(Token(tok.word, "O", "O"))  # a stutter: "put put the ..."
                if typo_p and len(tok.word) >= 4 and tok.word.isalpha() and rng.random() < typo_p:
                    tok = Token(_misspelt(rng, tok.word), "O", tok.coref)
            new.append(tok)
        if spoken and rng.random() < 0.12:  # a restart: "put the uh put the 4x8 ..."
            k = rng.randint(1, 3)
            head = new[:k]
            if len(head) == k and all(t.is_word and t.tag == "O" for t in head):
                new = head + plain(rng.choice(["uh", "um", "I mean", "sorry"])) + new
        out.append(new)
    return out


#: Short forms in phone messages. Words the rules read (``from``, ``left``, ...) are shortened only to forms
#: that ``drywall_lab.im.words.SPELLINGS`` spells out again.
TEXTING_FORMS = {
    "please": ("pls", "plz"), "thanks": ("thx", "thnx"), "you": ("u",), "your": ("ur",), "are": ("r",),
    "and": ("n", "&"), "okay": ("k", "ok"), "with": ("w",), "from": ("frm", "fr"), "before": ("b4",),
    "right": ("rt",), "left": ("lft",), "centre": ("ctr",), "center": ("cntr", "ctr"), "previous": ("prev",),
    "next": ("nxt",), "through": ("thru",), "because": ("bc", "cuz"),
}


def texting_forms(ch: Chooser, sentences: Sentences) -> Sentences:
    """Half the words that have a short form are written short ("pls put it frm the lft pile")."""
    out: Sentences = []
    for sentence in sentences:
        new: Phrase = []
        for tok in sentence:
            forms = TEXTING_FORMS.get(tok.word.lower()) if tok.is_word else None
            if forms and ch.rng.random() < 0.5:
                tok = Token(ch.rng.choice(forms), tok.tag, tok.coref)
            new.append(tok)
        out.append(new)
    return out


def render_style(ch: Chooser, spoken: bool, shout: bool = False) -> tuple[str, bool]:
    """The casing and whether the punctuation is kept, as ``render`` draws them."""
    casing = "lower" if spoken else ("upper" if shout and ch.chance(0.3) else G._weighted(ch.rng, CASING))
    return casing, not spoken and ch.rng.random() < 0.85


def keeps_punctuation(ch: Chooser, spoken: bool, shout: bool = False) -> bool:
    """Whether ``render`` will keep the punctuation, its draws left untaken (an overlay asks before it is laid)."""
    state = ch.rng.getstate()
    try:
        return render_style(ch, spoken, shout)[1]
    finally:
        ch.rng.setstate(state)


def render(ch: Chooser, sentences: Sentences, spoken: bool,
           shout: bool = False) -> tuple[str, list[str], list[str], list[str]]:
    """Text, words, tags and co-reference tags; casing and punctuation as typed, lost, shouted (more often when
    ``shout``: an impatient boss) or in Title Case (a checklist, a formal note)."""
    casing, keep_punctuation = render_style(ch, spoken, shout)

    def cased(w: str, first: bool) -> str:
        if casing == "lower":
            return w.lower()
        if casing == "upper":
            return w.upper()
        if (first and casing == "typed") or casing == "title":
            return w[0].upper() + w[1:]
        return w

    def one_word(w: str) -> str:
        clean = tokenize(w)
        if len(clean) != 1:
            raise ValueError(f"{w!r} is not one word when tokenized: {clean}")
        return clean[0]

    sentences = [unspaced_words(sentence) for sentence in sentences]
    return G.join_tokens(sentences, keep_punctuation, cased, one_word, attach=written_together)


def unspaced_words(sentence: Phrase) -> Phrase:
    """A phrase whose tokens of a script written without spaces are the words the front end cuts them into
    (``normalise.split_unspaced``), each with its token's tags."""
    from drywall_lab.nlu.normalise import split_unspaced

    return [Token(part, t.tag, t.coref) if t.is_word else t
            for t in sentence for part in (split_unspaced(t.word) if t.is_word else [t.word])]


def written_together(text: str, word: str) -> bool:
    """Whether ``word`` is written straight after ``text``, as Chinese and Japanese are typed ("竖着装在500106上"):
    where a character of such a script meets another or a digit, and the front end would cut the run they make into
    the same words (``normalise.split_unspaced``), so that it reads the words the row was written from."""
    from drywall_lab.nlu.normalise import split_unspaced

    before, after = text[-1:], word[:1]
    if not (unspaced(before) and (unspaced(after) or after.isdigit()) or before.isdigit() and unspaced(after)):
        return False
    return split_unspaced(text + word) == split_unspaced(text) + split_unspaced(word)


def read_through_front_end(said: tuple[str, list[str], list[str], list[str]]) -> tuple[str, list[str], list[str], list[str]]:
    """A rendered instruction as the tagger reads it: its words through the front end (``nlu.normalise``), each
    normalised word tagged as the words it comes from. Training and prediction read the same words."""
    from drywall_lab.nlu.normalise import normalise

    text, words, tags, coref = said
    read = normalise(text)
    if list(read.said) != words:
        raise ValueError(f"the front end split {text!r} into {list(read.said)}, not {words}")
    return text, list(read.words), read.tags_of_words(tags), read.tags_of_words(coref)


# --- sizes said by a property --------------------------------------------------------------------------
#: How often a target meant by its size ("the 2x8", "a full sheet", "the six-footer") is said by a property instead
#: ("the narrow one", "a skinny sheet", "the short panel"), in every split, drawn apart from the split's own draws.
SIZE_PROPERTY_RATE = 0.12
_SIZE_KINDS = ("size", "width", "length", "standard")


@functools.lru_cache(maxsize=16)
def size_property_words(site: Site, stack: str) -> tuple[str, ...]:
    """The words of ``data/site/size_words.csv`` that name ``stack`` alone on this site ("narrow": the least width
    is the 2 x 8's and no other's); none for a stack whose every property another stack shares. Worked out once a
    site and stack, not once a row."""
    return tuple(word for word, (measure, extreme) in size_words().items()
                 if site.stacks_with_extreme(measure, extreme) == [stack])


def size_property_draw(row_id: str, split: str, meaning: G.Meaning,
                       site: Site) -> tuple[Chooser, tuple[str, ...]] | None:
    """The draws and words for saying this row's target by a property, or None: only a command whose target is
    meant by its size, one row in ``1 / SIZE_PROPERTY_RATE``, drawn from the row's id alone."""
    if meaning.target.kind not in _SIZE_KINDS or meaning.expected.get("refusal") is not None:
        return None
    ch = Chooser(random.Random(f"{row_id}-size_properties"), novel=split == "novel")
    words = size_property_words(site, site.panel(meaning.expected["drywall_id"]).stack)
    return (ch, words) if words and ch.chance(SIZE_PROPERTY_RATE) else None


# --- two things offered with "or" ----------------------------------------------------------------------
#: How often a command is said with one of its parts offered twice, joined by "or" ("on 500105 or 500106, I forget
#: which"): the worker has not decided, so the robot must ask (``refusal: unclear``; guidelines 4.8). In every split,
#: drawn apart from the split's own draws.
UNDECIDED_RATE = 0.04
#: What a worker who has not decided adds after the offer.
UNSURE_BANK = ["not sure which", "I forget which", "I can't remember which", "one of those two", "can't recall which",
               "I'm not sure which one", "one or the other, not sure", "check which"]
_PLACEMENT_PHRASES = {"vertical_middle": ("centre line", "Vr_md"), "horizontal_top": ("top row", "Hr_top"),
                      "horizontal_bottom": ("bottom row", "Hr_btm"), "vertical_left": ("left line", None)}
#: The refusal an undecided instruction expects.
UNCLEAR = {"drywall_id": None, "stud_id": None, "placement": None, "refusal": "unclear"}


def _placement_phrase(ch: Chooser, placement: str) -> Phrase:
    words, tag = _PLACEMENT_PHRASES[placement]
    if tag is None:
        return plain("the left " + ch.rng.choice(["line", "edge", "line", "side"]))
    return plain("the") + tagged(words, tag)


def _size_said(ch: Chooser, size: tuple[float, float]) -> Phrase:
    w, l = (int(x) for x in size)
    if ch.chance(0.5):
        return plain(ch.rng.choice(["the", "a"])) + tagged(f"{w}x{l}", "width")
    return plain(ch.rng.choice(["the", "a"])) + tagged(NUMBER_WORDS[w], "width") + plain("by") + \
        tagged(NUMBER_WORDS[l], "length")


def _groups(sentences: Sentences, tags: frozenset[str]) -> list[tuple[int, int]]:
    """(sentence, last word) of each run of words carrying ``tags`` (across one untagged word: "four by six")."""
    out = []
    for si, sentence in enumerate(sentences):
        idx = [i for i, t in enumerate(sentence) if t.is_word and t.tag in tags]
        for n, i in enumerate(idx):
            if n + 1 == len(idx) or idx[n + 1] - i > 2:
                out.append((si, i))
    return out


def _once(sentences: Sentences, tags: set[str]) -> list[tuple[int, int]]:
    """Where a part is said once, the end of its words ([] where it is said twice or not at all: an offer after
    one saying would leave the other standing)."""
    groups = _groups(sentences, frozenset(tags))
    return groups if len(groups) == 1 else []


def offer_alternative(ch: Chooser, sentences: Sentences, meaning: G.Meaning, site: Site) -> Sentences | None:
    """The instruction with one part offered twice: after the words of its panel id, its size, its stud id or its
    placement (or, for the default placement, after the stud), ", or" and another of the same kind, tagged as
    said (the default placement's words ``O``), and now and then what the worker adds ("not sure which"). None
    where no part is said in a form that can be offered."""
    e = meaning.expected
    options: list[tuple[tuple[int, int], Phrase]] = []
    for at in _once(sentences, {"ID_wall"}):
        other = ch.rng.choice([p for p in site.panel_ids if p != e["drywall_id"]])
        options.append((at, tagged(other, "ID_wall")))
    for at in _once(sentences, {"width", "length"}):
        size = site.panel(e["drywall_id"]).size_ft
        others = sorted({s for s in site.sizes.values() if s != size})
        options.append((at, _size_said(ch, ch.rng.choice(others))))
    for at in _once(sentences, {"ID_stud"}):
        k = site.stud_ids.index(e["stud_id"])
        near = [site.stud_ids[j] for j in range(max(0, k - 3), min(len(site.stud_ids), k + 4)) if j != k]
        options.append((at, (plain("stud") if ch.chance(0.3) else []) + tagged(ch.rng.choice(near), "ID_stud")))
    placed = _once(sentences, {"Vr_md", "Hr_top", "Hr_btm"})
    others = [p for p in _PLACEMENT_PHRASES if p != e["placement"]]
    if placed:
        options.append((placed[0], _placement_phrase(ch, ch.rng.choice(others))))
    elif e["placement"] == "vertical_left":
        for at in _groups(sentences, frozenset({"ID_stud", "St_loc1", "St_loc2"}))[-1:]:
            pair = [_placement_phrase(ch, "vertical_left"), _placement_phrase(ch, ch.rng.choice(others))]
            if ch.chance(0.5):
                pair.reverse()
            options.append((at, [punct(",")] + plain("on") + pair[0] + plain("or") + pair[1]))
    if not options:
        return None
    (si, i), said = ch.rng.choice(options)
    if said[0].word != ",":
        said = ([punct(",")] if ch.chance(0.4) else []) + plain("or") + \
            (plain(ch.rng.choice(["maybe", "perhaps"])) if ch.chance(0.3) else []) + said
    out = [list(sentence) for sentence in sentences]
    out[si][i + 1:i + 1] = said
    if ch.chance(0.6):
        out.append(words_of(ch, UNSURE_BANK) + [punct(".")])
    return out


def undecided_draw(row_id: str, split: str, meaning: G.Meaning) -> Chooser | None:
    """The draws for saying this row undecided, or None: only a command, one row in ``1 / UNDECIDED_RATE``, drawn
    from the row's id alone."""
    if meaning.expected.get("refusal") is not None:
        return None
    ch = Chooser(random.Random(f"{row_id}-{C.UNDECIDED}"), novel=split == "novel")
    return ch if ch.chance(UNDECIDED_RATE) else None


# --- anchors the site does not have -----------------------------------------------------------------
#: How often a novel command counted from an anchor ("the pile right of 500310", "two studs left of 500107") is said
#: counted from a thing the site tables do not have ("the pile right of the door"): the robot cannot count from it
#: and must ask (``UNANCHORED``). The novel split only: a held-back way of saying, drawn apart from the split's own
#: draws.
LANDMARK_RATE = 0.15
#: Things on a wall or a site that are no stack, panel or stud of the site tables.
LANDMARKS = ["the door", "the window", "the window opening", "the vent", "the ladder", "the corner", "the doorway",
             "the outlet box", "the light switch", "the fire extinguisher", "the radiator", "the scaffold"]
#: The refusal an instruction counted from a landmark expects.
UNANCHORED = {"drywall_id": None, "stud_id": None, "placement": None, "refusal": "undetermined"}


def landmark_anchor(ch: Chooser, sentences: Sentences) -> Sentences | None:
    """The instruction with its anchor (the words after "of" through the ``Dw_loc2`` or ``St_loc2`` words) said as a
    landmark of ``LANDMARKS``, all ``O`` ("to the right of the door"); None where no anchor follows "of" or the
    anchor is said twice."""
    anchors = [(si, i) for si, sentence in enumerate(sentences) for i, t in enumerate(sentence)
               if t.is_word and t.tag in ("Dw_loc2", "St_loc2")]
    if not anchors or len({si for si, _ in anchors}) != 1:
        return None
    si = anchors[0][0]
    first, last = anchors[0][1], anchors[-1][1]
    sentence = sentences[si]
    if last - first + 1 != len(anchors):
        return None  # the anchor's words apart: said twice
    of = next((i for i in range(first - 1, max(-1, first - 5), -1) if sentence[i].is_word
               and sentence[i].word.lower() == "of"), None)
    if of is None or any(t.tag != "O" for t in sentence[of + 1:first] if t.is_word) or of == 0 \
            or not sentence[of - 1].is_word or sentence[of - 1].tag not in ("Dw_loc1", "St_loc1"):
        return None
    out = [list(s) for s in sentences]
    out[si][of + 1:last + 1] = plain(ch.rng.choice(LANDMARKS))
    return out


def landmark_draw(row_id: str, split: str, meaning: G.Meaning) -> Chooser | None:
    """The draws for saying this row counted from a landmark, or None: only a novel command counted from an
    anchor, one row in ``1 / LANDMARK_RATE``, drawn from the row's id alone."""
    relative = meaning.target.kind == "relative" or meaning.stud.kind == "relative"
    if split != "novel" or not relative or meaning.expected.get("refusal") is not None:
        return None
    ch = Chooser(random.Random(f"{row_id}-{C.LANDMARK_ANCHORS}"), novel=True)
    return ch if ch.chance(LANDMARK_RATE) else None


# --- episodes and splits ------------------------------------------------------------------------------
def _split_once(split: str, n: int, rng: random.Random, site: Site) -> list[dict]:
    ch = Chooser(rng, novel=(split == "novel"))

    def said(ep: G.Episode, meaning: G.Meaning, row_id: str, prop: tuple[Chooser, tuple[str, ...]] | None,
             undecided: Chooser | None = None, landmark: Chooser | None = None):
        """One step in a register, with noise and channels, read through the front end (None: ``undecided`` found
        no part to offer, or ``landmark`` no anchor to replace)."""
        register = G._weighted(rng, REGISTERS)
        spoken = register in ("speech", "texting") or (register in ("radio", "correction") and rng.random() < 0.5) \
            or (register in ("explain", "boss") and rng.random() < 0.3)
        speaker = Speaker(ch, meaning, ep, register, size_property=prop)
        sentences = speaker.sentences()
        if undecided is not None:
            sentences = offer_alternative(undecided, sentences, meaning, site)
            if sentences is None:
                return None
        if landmark is not None:
            sentences = landmark_anchor(landmark, sentences)
            if sentences is None:
                return None
        sentences = add_noise(ch, sentences, spoken)
        if register == "texting":
            sentences = texting_forms(ch, sentences)
        channels = C.choose_channels(rng, novel=split == "novel")
        sentences = C.apply_channels(ch, sentences, channels)
        if speaker.p.said_property:
            channels += (C.SIZE_PROPERTIES,)
        if undecided is not None:
            channels += (C.UNDECIDED,)
        if landmark is not None:
            channels += (C.LANDMARK_ANCHORS,)
        if split == "novel":
            sentences, overlays = C.apply_overlays(row_id, sentences,
                                                   keeps_punctuation(ch, spoken, shout=register == "boss"), channels)
            channels += overlays
        return register, channels, len(sentences), read_through_front_end(render(ch, sentences, spoken,
                                                                                 shout=register == "boss"))

    def say(ep: G.Episode, meaning: G.Meaning, row_no: int, episode_no: int, step: int) -> dict | None:
        """One step (None: no words left). A step said by a property, undecided or counted from a landmark is said
        again from the same draws, and the split goes on from the first saying: every other row is what it is without
        them. An undecided step expects a question (``UNCLEAR``), one counted from a landmark another
        (``UNANCHORED``); neither changes the episode."""
        row_id = f"field-{split}-{row_no:05d}"
        start = rng.getstate()

        def said_again(*ways: Chooser | tuple | None):
            """The step said once more from the first saying's draws; the split's draws go on as they were."""
            end = rng.getstate()
            rng.setstate(start)
            try:
                return said(ep, meaning, row_id, *ways)
            finally:
                rng.setstate(end)

        register, channels, n_sentences, words = said(ep, meaning, row_id, None)
        prop = size_property_draw(row_id, split, meaning, site)
        undecided = undecided_draw(row_id, split, meaning)
        if (prop is not None or undecided is not None) and words[1]:
            again = said_again(prop, undecided)
            if again is None and prop is not None:  # no part to offer: said by the property alone
                again = said_again(prop)
            if again is not None:
                register, channels, n_sentences, words = again
                if C.UNDECIDED in channels:
                    meaning = replace(meaning, expected=dict(UNCLEAR))
        landmark = landmark_draw(row_id, split, meaning) if words[1] else None
        if landmark is not None:
            again = said_again(None, None, landmark)
            if again is not None:
                register, channels, n_sentences, words = again
                meaning = replace(meaning, expected=dict(UNANCHORED))
        if not words[1]:
            return None
        row = G.corpus_row(row_id, words, n_sentences, f"field-{split}-ep{episode_no:05d}",
                           step, ep, meaning, register=register, channels=list(channels))
        return row if reads_as_meant(row, site) else None  # a saying whose gold tags miss what it means is left out

    return G.episode_rows(rng, site, n, lambda: rng.randint(1, 8), FIELD_REFUSAL_RATE, FIELD_WEIGHTS, say)


def takes_back_only_repeats(words: Sequence[str], tags: Sequence[str]) -> bool:
    """Whether every word the correction rule takes back from ``tags`` is said again later with the same tag (the
    guidelines tag only the final intention, so gold tags take back nothing else)."""
    taken = TaggedInstruction(list(words), list(tags))
    return all(any(W.normalise(taken.words[j]) == W.normalise(words[i]) for j in range(i + 1, len(taken.words))
                   if taken.tags[j] == tags[i]) for i in taken.taken_back)


def reads_as_meant(row: dict, site: Site | None = None) -> bool:
    """Whether a row's gold tags read as it means: they give its expected command or refusal, and take back only
    words said again (``takes_back_only_repeats``). Every row of every split holds (tested); a saying that does not
    is left out."""
    return task_correct(row, site=site) and takes_back_only_repeats(row["words"], row["tags"])


def generate_field_split(split: str, n: int | None = None, seed: int = FIELD_SEED, site: Site | None = None) -> list[dict]:
    """``n`` field instructions of one split (``FIELD_SPLIT_SIZES`` by default), deterministic for a seed.

    Like the paper corpus, a draw that misses one of the meanings every split must contain is
    drawn again from the next sub-seed.
    """
    if split not in FIELD_SPLITS:
        raise ValueError(f"unknown field split {split!r}; the field corpus has {', '.join(FIELD_SPLITS)}")
    n = FIELD_SPLIT_SIZES[split] if n is None else n
    site = site or default_site()
    for attempt in range(100):
        rows = _split_once(split, n, random.Random(f"field-{seed}-{split}-{attempt}"), site)
        if n < 500 or not G.missing_meanings(rows):
            return rows
    raise RuntimeError(f"{split}: no draw contained every meaning; missing {sorted(G.missing_meanings(rows))}")


def write_field_corpus(out_dir: Path | str = FIELD_DIR, seed: int = FIELD_SEED,
                       splits: tuple[str, ...] = FIELD_SPLITS) -> dict[str, Path]:
    """Write ``{split}.jsonl`` for each split (``train`` with its fingerprint); the same seed always gives the
    same bytes."""
    written = {s: write_jsonl(generate_field_split(s, seed=seed), Path(out_dir) / f"{s}.jsonl") for s in splits}
    if "train" in written:
        written["train"].with_suffix(".fingerprint").write_text(generator_fingerprint(seed) + "\n", encoding="utf-8")
    return written


def generator_fingerprint(seed: int = FIELD_SEED) -> str:
    """A hash of everything a generated split depends on: the corpus package's source, the front end and its
    lexicons, the site tables, the seed and the split sizes. The cached ``train`` split carries it, so a changed generator never reads a stale one."""
    digest = hashlib.sha256(f"{seed} {sorted(FIELD_SPLIT_SIZES.items())}".encode())
    from drywall_lab.nlu import normalise as front_end  # the rows are read through it

    sources = sorted(Path(__file__).resolve().parent.glob("*.py")) + sorted((DATA_DIR / "site").glob("*.csv")) + \
        [Path(front_end.__file__), Path(front_end.LEXICON_PATH), Path(front_end.CODE_SWITCH_PATH)]
    for source in sources:
        digest.update(source.name.encode() + b"\0" + source.read_bytes())
    return digest.hexdigest()


def field_split(split: str, corpus_dir: Path | str | None = None) -> list[dict]:
    """The rows of one field split. ``train`` is generated and cached in the corpus directory, beside a
    ``train.fingerprint`` file (``generator_fingerprint``); it is generated again when either is missing or the
    generator has changed since."""
    if split not in FIELD_SPLITS:
        raise ValueError(f"unknown field split {split!r}; the field corpus has {', '.join(FIELD_SPLITS)}")
    path = Path(corpus_dir or FIELD_DIR) / f"{split}.jsonl"
    if split in COMMITTED_SPLITS:
        if not path.is_file():
            if corpus_dir is None:
                raise FileNotFoundError(f"{path} is missing: run `python -m drywall_lab corpus generate --field`")
            write_jsonl(generate_field_split(split), path)
        return read_jsonl(path)
    stamp = path.with_suffix(".fingerprint")
    if not (path.is_file() and stamp.is_file()
            and stamp.read_text(encoding="utf-8").strip() == generator_fingerprint()):
        write_field_corpus(path.parent, splits=(split,))  # the split and its fingerprint
    return read_jsonl(path)
