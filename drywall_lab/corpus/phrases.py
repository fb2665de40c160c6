"""Phrase banks: how a worker says which panel, which stud and how to place it.

Each bank is a list of templates in the markup of ``markup.py``. A template that
starts with ``~`` is *withheld*: it is used only for the ``novel`` split, so that
split measures generalisation to phrasings a tagger never saw in training.

The tagging conventions these banks follow are the project's annotation
guidelines (``annotation_guidelines/``), in short:

- ids, numbers and size words carry the tag; ``by``, ``feet`` and generic nouns do not;
- a position phrase is tagged from its count word to its direction word
  (``second to the left``, ``third from the right``); a generic noun inside it
  stays ``O`` (``the third stud from the left``);
- the anchor of a relative position (an id, ``leftmost``, ``previous``) carries
  ``Dw_loc2``/``St_loc2``;
- placement phrases tag their line/row words (``middle line``, ``upper part``);
  ``vertically`` and ``horizontally`` stay ``O`` (the default is vertical too).
"""
from __future__ import annotations

import random
from dataclasses import dataclass

from drywall_lab.corpus.markup import Phrase, Token, parse, plain, tagged

NUMBER_WORDS = {0: "zero", 1: "one", 2: "two", 3: "three", 4: "four", 5: "five", 6: "six",
                7: "seven", 8: "eight", 9: "nine", 10: "ten", 12: "twelve"}
ORDINAL_WORDS = {1: "first", 2: "second", 3: "third", 4: "fourth", 5: "fifth", 6: "sixth", 7: "seventh"}
ORDINAL_DIGITS = {1: "1st", 2: "2nd", 3: "3rd", 4: "4th", 5: "5th", 6: "6th", 7: "7th"}


@dataclass
class Chooser:
    """Picks templates at random: only the withheld ones (``novel``) or only the others."""

    rng: random.Random
    novel: bool = False
    #: whether the instruction will be written with its punctuation (an overlay whose form needs it asks)
    punctuated: bool = True

    def template(self, bank: list[str]) -> str:
        withheld = [t[1:] for t in bank if t.startswith("~")]
        shared = [t for t in bank if not t.startswith("~")]
        pool = withheld if (self.novel and withheld) else shared
        return self.rng.choice(pool)

    def say(self, bank: list[str], **slots: Phrase) -> Phrase:
        return parse(self.template(bank), **slots)

    def chance(self, p: float) -> bool:
        return self.rng.random() < p

    def number(self, n: int, tag: str) -> Phrase:
        """A number as digits or as a word ("4" or "four")."""
        return tagged(str(n) if self.chance(0.55) else NUMBER_WORDS[n], tag)

    def ordinal(self, n: int) -> str:
        return ORDINAL_DIGITS[n] if self.chance(0.25) else ORDINAL_WORDS[n]


# --- generic words ---------------------------------------------------------------
PANEL_NOUNS = [
    "panel/@T", "panel/@T", "drywall/@T", "drywall/@T", "sheet/@T", "board/@T", "piece/@T",
    "drywall/@T panel/@T", "drywall/@T sheet/@T", "wall/@T panel/@T", "drywall/@T board/@T",
    "~gypsum/@T board/@T", "~sheet/@T of/@T drywall/@T", "~plasterboard/@T", "~sheetrock/@T",
]
PANEL_NOUNS_PLAIN = [t.replace("/@T", "") for t in PANEL_NOUNS]  # the same words, not the target
STUD_NOUNS = ["stud/@D", "stud/@D", "stud/@D", "~wall/@D stud/@D", "~framing/@D stud/@D"]
IT = ["it/@T", "it/@T", "it/@T", "the/O {noun}", "~this/O {noun}"]

PICK_VERBS = ["pick up", "grab", "take", "get", "lift", "pick up", "~fetch", "~bring over", "~go get", "~collect", "~hoist"]
PLACE_VERBS = ["put", "place", "install", "hang", "mount", "set", "attach", "put", "place", "carefully put",
               "carefully place", "go and install", "then hang", "then place", "now put",
               "~fasten", "~secure", "~fix", "~screw", "~stick", "~position"]
PREPOSITIONS = ["on", "onto", "to", "on", "at", "~against", "~up on"]
POLITE_OPENERS = ["I would like you to", "can you go ahead and", "okay so now I want you to", "alright robot , please", "please", "please", "can you please", "could you please", "I want you to", "now I need you to", "okay robot", "please", "can you", "could you", "would you", "I need you to",
                  "go ahead and", "now", "okay", "alright", "um", "okay now", "next",
                  "~hey robot", "~when you are ready", "~robot , please", "~hey there robot , could you", "~listen robot , I want you to", "~right , so"]
POLITE_CLOSERS = ["", "", "please", "for me", "thanks", "right now", "when you are ready", "thank you", "carefully", "for me please", "~if you can", "~when you get a chance", "~if that works", "~nice and slow", "~as soon as you can"]
GREETINGS = [
    "okay , next one .", "alright , let's keep going .", "good job .", "thank you .",
    "let's do the next panel .", "be careful with this one .", "this one is important .",
    "we are almost done with this wall .", "listen carefully .", "next step .",
    "great , that looks good .", "we need another one on the wall .",
    "~nice work so far .", "~here comes the next step .", "~let's get moving .",
]

# --- the target panel -------------------------------------------------------------
TARGET_BY_ID = [
    "the {noun} {id}", "{noun} {id}", "the {noun} number {id}", "the {noun} with the id {id}",
    "{noun} number {id}", "~the {noun} labeled {id}", "~the {noun} marked {id}",
]
TARGET_ID_SENTENCE = [
    "it is {noun} {id} .", "the {noun} is {id} .", "its id is {id} .", "the id of the {noun} is {id} .",
    "use {noun} {id} .", "~the number on it is {id} .",
]
# {a} is the first number (tagged width), {b} the second (tagged length)
TARGET_BY_SIZE = [
    "the {a} by {b} {noun}", "a {a} by {b} {noun}", "the {a} foot by {b} foot {noun}",
    "the {noun} that is {a} by {b}", "a {a} by {b} foot {noun}",
    "the {noun} that is {a} feet wide and {b} feet long",
    "a {noun} with a width of {a} and a length of {b}",
    "the {noun} with a width of {a} feet and a length of {b} feet",
    "~a {noun} measuring {a} by {b}", "~the {noun} sized {a} by {b}",
]
TARGET_BY_SIZE_TURNED = [t for t in TARGET_BY_SIZE if " by " in t]  # "the 8 by 4 panel"
TARGET_SIZE_SENTENCE_TURNED = ["the {noun} is {a} by {b} .", "the size is {a} by {b} .", "~it measures {a} by {b} ."]
TARGET_BY_SIZE_LENGTH_FIRST = [
    "the {noun} that is {b} feet long and {a} feet wide",
    "a {noun} with a length of {b} and a width of {a}",
    "~a {noun} {b} feet long and {a} feet across",
]
TARGET_SIZE_SENTENCE = [
    "the width is {a} and the length is {b} .", "the {noun} is {a} by {b} .",
    "it is {a} feet wide and {b} feet long .", "the width of the {noun} is {a} and the length of the {noun} is {b} .",
    "the size is {a} by {b} .", "~it measures {a} by {b} .",
]
TARGET_SIZE_SENTENCE_LENGTH_FIRST = [
    "the length is {b} and the width is {a} .", "the length of the {noun} is {b} feet and the width is {a} feet .",
    "~it runs {b} feet long and {a} feet wide .",
]
TARGET_BY_WIDTH = ["the {noun} that is {a} feet wide", "a {a} foot wide {noun}", "a {noun} with a width of {a}",
                   "~a {noun} {a} feet across"]
TARGET_BY_LENGTH = ["the {noun} that is {b} feet long", "a {b} foot long {noun}", "the {noun} with a length of {b}",
                    "~a {noun} running {b} feet"]
TARGET_STANDARD = [
    "the full-size/dim {noun}", "a standard/dim {noun}", "a regular/dim {noun}", "a full/dim {noun}",
    "a standard/dim size/dim {noun}", "a full/dim size/dim {noun}", "the regular/dim size/dim {noun}",
    "~a full-sized/dim {noun}", "~one of the standard/dim {noun}",
]
TARGET_STANDARD_SENTENCE = ["it is a full-size/dim one/@T .", "it should be a standard/dim {noun} .",
                            "use a regular/dim size/dim one/@T .", "~we want a full-sized/dim one/@T ."]
TARGET_SAME_AS_PREVIOUS = [
    "the same/dim {noun} as the previously/dim installed/dim one",
    "a {noun} of the same/dim size as the previous/dim one",
    "the same/dim kind of {noun} as last/dim time/dim",
    "another {noun} like the previous/dim one",
    "a {noun} the same/dim size as the one you just/dim hung/dim",
    "~a {noun} matching/dim the last/dim one", "~one more {noun} like the last/dim one",
]
TARGET_SAME_SENTENCE = ["it is the same/dim size as the previous/dim one .",
                        "use the same/dim kind as last/dim time/dim .",
                        "~make it match/dim the last/dim one ."]
TARGET_ABSOLUTE = {  # stack -> templates, {noun} is the target
    "left": [
        "the leftmost/Dw_loc1 {noun}", "the {noun} on the left/Dw_loc1", "the {noun} from the left/Dw_loc1 stack",
        "the {noun} on the far/Dw_loc1 left/Dw_loc1", "the {noun} in the first/Dw_loc1 stack",
        "the {noun} from the most/Dw_loc1 left/Dw_loc1 stack", "the first/Dw_loc1 {noun} from/Dw_loc1 the/Dw_loc1 left/Dw_loc1",
        "~the {noun} at the left/Dw_loc1 end", "~the {noun} from the left/Dw_loc1 pile",
    ],
    "middle": [
        "the {noun} in the middle/Dw_loc1", "the {noun} from the middle/Dw_loc1 stack", "the middle/Dw_loc1 {noun}",
        "the {noun} in the center/Dw_loc1", "the {noun} from the second/Dw_loc1 stack",
        "the {noun} in the centre/Dw_loc1", "the second/Dw_loc1 {noun} from/Dw_loc1 the/Dw_loc1 left/Dw_loc1",
        "the second/Dw_loc1 {noun} from/Dw_loc1 the/Dw_loc1 right/Dw_loc1",
        "~the {noun} from the center/Dw_loc1 pile", "~the {noun} sitting in the middle/Dw_loc1",
    ],
    "right": [
        "the rightmost/Dw_loc1 {noun}", "the {noun} on the right/Dw_loc1", "the {noun} from the right/Dw_loc1 stack",
        "the {noun} from the last/Dw_loc1 stack", "the {noun} in the third/Dw_loc1 stack",
        "the first/Dw_loc1 {noun} from/Dw_loc1 the/Dw_loc1 right/Dw_loc1", "the {noun} on the far/Dw_loc1 right/Dw_loc1",
        "~the {noun} at the right/Dw_loc1 end", "~the {noun} from the right/Dw_loc1 pile",
    ],
}
TARGET_ABSOLUTE_SENTENCE = ["it is the one/@T {where} .", "take it/@T from the stack {where} .",
                            "~you will find it/@T {where} ."]
STACK_WHERE = {  # "{where}" for the sentences above
    "left": ["on the left/Dw_loc1", "on the far/Dw_loc1 left/Dw_loc1", "~at the left/Dw_loc1 end"],
    "middle": ["in the middle/Dw_loc1", "in the center/Dw_loc1", "~in the centre/Dw_loc1"],
    "right": ["on the right/Dw_loc1", "on the far/Dw_loc1 right/Dw_loc1", "~at the right/Dw_loc1 end"],
}
# relative panel positions: {dir} is the tagged direction phrase, {anchor} the tagged anchor
TARGET_RELATIVE = [
    "the {noun} {dir} of {anchor}", "the {noun} to the {dir} of {anchor}", "the {noun} from the stack {dir} of {anchor}",
    "the {noun} that is {dir} of {anchor}", "~the {noun} sitting {dir} of {anchor}",
]
TARGET_RELATIVE_SENTENCE = ["it is the one/@T {dir} of {anchor} .", "take it/@T from the stack {dir} of {anchor} .",
                            "~it sits {dir} of {anchor} ."]
PANEL_ANCHOR_ID = ["{id}", "panel {id}", "the {plainnoun} {id}", "~the stack of {id}"]
PANEL_ANCHOR_PREVIOUS = [
    "the previous/Dw_loc2 one", "the one you just/Dw_loc2 installed/Dw_loc2", "the previously/Dw_loc2 installed/Dw_loc2 {plainnoun}",
    "the last/Dw_loc2 one", "the previous/Dw_loc2 {plainnoun}", "~the one you hung last/Dw_loc2",
]
TARGET_UNDETERMINED = ["the {noun}", "a {noun}", "that {noun}", "one of the {noun}", "~the next {noun}"]

# --- the destination stud -------------------------------------------------------------
STUD_BY_ID = ["stud/@D {id}", "the stud/@D {id}", "stud/@D number {id}", "the stud/@D number {id}", "{id}",
              "the stud/@D with id {id}", "~stud/@D id {id}", "~the stud/@D tagged {id}"]
STUD_ID_SENTENCE = ["the stud/@D is {id} .", "the stud/@D number is {id} .", "use stud/@D {id} .",
                    "~the id of the stud/@D is {id} ."]
STUD_ABSOLUTE = {
    "leftmost": ["the leftmost/St_loc1 {stud}", "the most/St_loc1 left/St_loc1 {stud}", "the first/St_loc1 {stud}",
                 "the {stud} on the far/St_loc1 left/St_loc1", "the very/St_loc1 first/St_loc1 {stud}",
                 "~the {stud} furthest/St_loc1 to/St_loc1 the/St_loc1 left/St_loc1", "~the {stud} at the left/St_loc1 end/St_loc1"],
    "rightmost": ["the rightmost/St_loc1 {stud}", "the last/St_loc1 {stud}", "the most/St_loc1 right/St_loc1 {stud}",
                  "the {stud} on the far/St_loc1 right/St_loc1", "the very/St_loc1 last/St_loc1 {stud}",
                  "~the {stud} furthest/St_loc1 to/St_loc1 the/St_loc1 right/St_loc1", "~the {stud} at the right/St_loc1 end/St_loc1"],
    "middle": ["the middle/St_loc1 {stud}", "the center/St_loc1 {stud}", "the centre/St_loc1 {stud}",
               "the {stud} in the middle/St_loc1", "the {stud} in the center/St_loc1 of the wall",
               "~the {stud} at the center/St_loc1", "~the {stud} halfway/St_loc1 along"],
}
# {ord} is a tagged ordinal, {side} "left"/"right" tagged
STUD_FROM_END = ["the {ord} {stud} from/St_loc1 the/St_loc1 {side}", "the {stud} {ord} from/St_loc1 the/St_loc1 {side}",
                 "the {ord} {stud} from/St_loc1 the/St_loc1 {side} end/St_loc1",
                 "~the {ord} {stud} counting/St_loc1 from/St_loc1 the/St_loc1 {side}"]
STUD_BARE_ORDINAL = ["the {ord} {stud}", "~{stud} number {ord}"]
STUD_RELATIVE = [
    "the {stud} {dir} of {anchor}", "the {stud} {dir} from {anchor}", "the {stud} that is {dir} of {anchor}",
    "the {stud} to the {dir} of {anchor}", "~the {stud} sitting {dir} of {anchor}",
]
STUD_RELATIVE_SENTENCE = ["the stud/@D is {dir} of {anchor} .", "the stud/@D is laying {dir} from {anchor} .",
                          "it/@T goes {dir} of {anchor} .", "~the stud/@D you want is {dir} of {anchor} ."]
STUD_SAME = ["the same/St_loc1 {stud} as the previous/St_loc2 one", "the same/St_loc1 {stud} as last/St_loc2 time/St_loc2",
             "the same/St_loc1 {stud} you just/St_loc2 used/St_loc2", "~that same/St_loc1 {stud} from before/St_loc2"]
STUD_ANCHOR_ID = ["stud {id}", "the stud {id}", "{id}", "~stud number {id}"]
STUD_ANCHOR_END = {
    "leftmost": ["the leftmost/St_loc2 stud", "the most/St_loc2 left/St_loc2 stud", "the very/St_loc2 first/St_loc2 stud",
                 "the stud at the far/St_loc2 left/St_loc2 end/St_loc2", "~the far/St_loc2 left/St_loc2 stud"],
    "rightmost": ["the rightmost/St_loc2 stud", "the most/St_loc2 right/St_loc2 stud", "the very/St_loc2 last/St_loc2 stud",
                  "the stud at the far/St_loc2 right/St_loc2 end/St_loc2", "~the far/St_loc2 right/St_loc2 stud"],
}
STUD_ANCHOR_PREVIOUS = ["the previous/St_loc2 stud", "the previous/St_loc2 one", "the stud you used last/St_loc2",
                        "the stud you just/St_loc2 used/St_loc2", "the last/St_loc2 stud you used",
                        "the stud you used last/St_loc2 time/St_loc2", "the one you just/St_loc2 used/St_loc2",
                        "the previously/St_loc2 used/St_loc2 stud",
                        "~the stud from the previous/St_loc2 step"]
STUD_SENTENCE = ["the stud/@D is {d} .", "use {d} .", "it/@T goes on {d} .", "~the target stud/@D is {d} ."]
STUD_UNDETERMINED = ["the stud", "a stud", "that stud", "the wall", "~the frame"]

# --- placement ------------------------------------------------------------------------
PLACEMENT = {
    "vertical_left": [  # the default: mostly nothing is said
        "", "", "", "", "", "", "", "vertically", "upright", "standing up",
        "with its edge on the left side of the stud/@D", "~standing upright",
    ],
    "vertical_middle": [
        "on the middle/Vr_md line/Vr_md", "on the center/Vr_md line/Vr_md", "on the centre/Vr_md line/Vr_md",
        "in the middle/Vr_md", "vertically on the center/Vr_md line/Vr_md", "vertically on the middle/Vr_md line/Vr_md",
        "on the middle/Vr_md line/Vr_md of the stud/@D", "with its edge on the center/Vr_md line/Vr_md",
        "in the middle/Vr_md of the stud/@D", "into the middle/Vr_md line/Vr_md",
        "~along the centre/Vr_md line/Vr_md", "~on/Vr_md center/Vr_md", "~lined up with the middle/Vr_md line/Vr_md",
    ],
    "horizontal_top": [
        "in the top/Hr_top row/Hr_top", "on the upper/Hr_top part/Hr_top", "in the upper/Hr_top horizontal/Hr_top row/Hr_top",
        "on the top/Hr_top part/Hr_top", "horizontally at the top/Hr_top", "horizontally in the upper/Hr_top row/Hr_top",
        "~across the top/Hr_top half/Hr_top", "~up high in the top/Hr_top row/Hr_top",
    ],
    "horizontal_bottom": [
        "in the bottom/Hr_btm row/Hr_btm", "on the lower/Hr_btm part/Hr_btm", "in the lower/Hr_btm horizontal/Hr_btm row/Hr_btm",
        "on the bottom/Hr_btm part/Hr_btm", "horizontally at the bottom/Hr_btm", "horizontally in the lower/Hr_btm row/Hr_btm",
        "~across the bottom/Hr_btm half/Hr_btm", "~down low in the bottom/Hr_btm row/Hr_btm",
    ],
}
PLACEMENT_SENTENCE = ["put it/@T {p} .", "place it/@T {p} .", "hang the {noun} {p} .", "it/@T goes {p} .",
                      "make sure it/@T sits {p} .", "~set it/@T {p} ."]
DEFAULT_PLACEMENT_SENTENCE = ["keep it/@T vertical .", "it/@T goes in upright .", "install it/@T vertically .",
                              "line its edge up with the left side of the stud/@D .", "~stand it/@T up straight ."]


def direction_phrase(ch: Chooser, direction: str, count: int, tag: str) -> Phrase:
    """A tagged direction with a count: "left", "second to the left", "two to the right"."""
    if count == 1:
        form = ch.template(["{d}", "{d}", "{d}", "one to the {d}", "~just to the {d}", "~one over to the {d}"])
    else:
        form = ch.template(["{o} to the {d}", "{n} to the {d}", "{o} {d}", "{o} {d}", "{n} places to the {d}",
                            "~{n} over to the {d}", "~{o} one to the {d}"])
    words = form.replace("{d}", direction).replace("{o}", ch.ordinal(count)).replace("{n}", NUMBER_WORDS[count])
    return tagged(words, tag)


__all__ = [name for name in dir() if name.isupper()] + ["Chooser", "direction_phrase", "Token", "plain"]
