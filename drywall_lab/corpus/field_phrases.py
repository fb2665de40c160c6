"""Phrase banks for the field corpus: the same meanings, said the way people on a site say them.

The paper corpus (``phrases.py``) follows the paper's examples: whole, polite sentences. Workers
talk differently: trade words ("sheet", "rock", "pile", "course"), sizes in one word ("4x8",
"four-by-eight", "an eight-footer"), verbless fragments and key-value lists, radio habits,
speech-recogniser text, non-native word order, and changes of mind. These banks cover those,
in the markup of ``markup.py`` (``word/TAG``; ``word/@T`` and ``word/@D`` are ``O`` words that
the co-reference variant marks), tagged by the project's annotation guidelines
(``annotation_guidelines/README.md``, section 4.7 for the constructions that only this corpus has).

A template that starts with ``~`` belongs to a **held-back family**: it is used only in the field
corpus's ``novel`` split, so that split measures language a tagger never saw. Whole families are
held back (every template of a kind of phrasing, or a whole sentence frame), not single picks; the
families are listed in ``HELD_BACK`` and in the README. No held-back family needs a word that the
information-mapping rules look up (``drywall_lab.im.words``): the rules' word lists are all learnt
from the training split.
"""
from __future__ import annotations

#: The held-back families, in words (the README repeats this list).
HELD_BACK: dict[str, str] = {
    "wallboard nouns": "'wallboard', 'GWB', 'gyp board' for the panel",
    "tier rows": "'tier' for a horizontal row ('top tier', 'the bottom tier')",
    "make-that corrections": "corrections introduced by 'make that', 'let me rephrase', 'rather'",
    "job tickets": "instructions written as a job ticket ('ticket 12: item ...; location ...; mount ...')",
    "sign-off radio frames": "radio calls with a call sign and 'over and out' / 'how copy'",
    "member nouns": "'framing member', 'upright' for the stud",
    "hedge-after frames": "an instruction followed by a hedge ('..., if that works for you?')",
}

# --- generic words -----------------------------------------------------------------------------------
#: The panel in full noun phrases ("the 4x8 sheet"); O words, Trg in the co-reference variant.
PANEL_NOUNS = [
    "sheet/@T", "sheet/@T", "sheet/@T", "panel/@T", "panel/@T", "board/@T", "board/@T", "drywall/@T",
    "piece/@T", "drywall/@T sheet/@T", "one/@T", "one/@T", "drywall/@T board/@T", "plasterboard/@T",
    "rock/@T", "sheetrock/@T", "~gyp/@T board/@T", "~wallboard/@T", "~GWB/@T",
]
#: The panel before its id ("sheet 500320"): the nouns without "one".
ID_NOUNS = [n for n in PANEL_NOUNS if not n.startswith("one/")]
PANEL_NOUNS_PLURAL = ["sheets", "panels", "boards", "ones", "pieces", "rocks"]
STUD_NOUNS = ["stud/@D", "stud/@D", "stud/@D", "stud/@D", "post/@D", "~framing/@D member/@D", "~upright/@D"]
STACK_NOUNS = ["stack", "stack", "pile", "pile", "pallet", "bunch", "lot"]

PICK_VERBS = ["grab", "grab", "take", "get", "pick up", "lift", "fetch", "bring", "pull", "snag", "haul over",
              "go get", "get me", "pick", "collect"]
PLACE_VERBS = ["put", "put", "hang", "hang", "install", "mount", "set", "stick", "throw", "screw", "fasten", "fix",
               "tack", "slap", "get", "run", "board", "place", "secure", "land"]
PREPOSITIONS = ["on", "on", "onto", "to", "at", "against", "up on", "over", "on to"]
FILLERS = ["uh", "um", "uhh", "er", "like", "you know", "so", "okay", "alright", "yeah", "well", "hmm",
           "let's see", "basically", "ok"]
#: Openers for a spoken or typed instruction.
OPENERS = ["", "", "", "", "okay", "ok", "alright", "right", "so", "next", "now", "then", "and", "okay next",
           "next up", "alright next one", "right then", "yo", "hey", "hey robot", "robot", "listen", "good",
           "nice", "cool", "perfect"]
CLOSERS = ["", "", "", "", "", "thanks", "thank you", "cheers", "please", "pls", "thx", "ta", "when you can",
           "nice and easy", "carefully", "good", "go", "for me", "mate", "buddy", "boss", "pal", "chief"]
#: Ways of saying "do this" that carry no information ("let's", "you're gonna", "what I want is").
INTENTS = ["let's", "you're gonna", "you gonna", "we need to", "I want you to", "gonna have to", "next we", "we'll",
           "what I want is", "ok so for this one", "the plan is to", "time to", "go ahead and", "you can"]
#: Reasons and context said before the instruction ("We're closing up this bay, so ...").
CONTEXT = [
    "we are closing up this bay", "the inspector is coming after lunch", "we need to finish this wall today",
    "the electrician is done here", "we're working left to right", "the bottom is done on this side",
    "that last one looks good", "the tape crew is waiting", "we're short on time", "the plumber signed off",
    "the insulation is in", "this is the last wall before break", "we're doing the top rows now",
    "I checked the layout", "the foreman wants this section done", "we changed the plan a bit",
    "good job on the last one", "we're behind schedule", "the framing got checked", "this wall is next",
    "we have {n} sheets left", "{n} more to go after this", "it's almost {n} o'clock", "we did {n} already",
    "{sid} is done", "we just finished {sid}", "{sid} looks good", "the window is on the left side",
    "we start at the left end", "the right side is done", "the top row on the left is finished",
    "we did the bottom course yesterday", "there's a window in the middle of the wall",
    "the last stud is a bit crooked", "the 4x8s are heavy so go slow", "the left pile is getting low",
    "the first stud has a pipe next to it", "the centre line is marked in blue", "we're two sheets behind",
    "the switch box is on the right side", "the top of the wall is not straight", "the full sheets are heavy",
    "mind the outlet box", "the door opening is further down", "careful , the floor is wet",
    "there's a pipe behind the wall", "the ceiling is eight feet here",
]
CONTEXT_LINKS = ["so", "so", "and", "which means", "therefore", "hence", "that's why", ""]
#: Words that abandon what was just said: the final intention counts.
CORRECTIONS = ["no", "no wait", "wait", "sorry", "actually", "actually no", "no no", "hold on", "oops",
               "my bad", "correction", "not that", "or no", "hang on", "scratch that", "I mean", "wait no",
               "~make that", "~let me rephrase", "~rather"]
CORRECTION_ENDS = ["", "", "instead", "not the other one", "sorry", "my mistake", "I meant", "I mean that"]
RADIO_CALLS = ["copy", "roger", "roger that", "copy that", "ten four", "10-4", "affirmative", "go ahead",
               "robot, copy", "come in robot", "over", "read you"]
RADIO_ENDS = ["over", "over", "over", "copy", "copy?", "confirm", "how copy", "roger", "out"]
CALL_SIGNS = ["base to robot", "crew two to robot", "robot , this is crew one", "crew one here",
              "~robot one , this is the foreman", "~drywall crew to robot one", "~this is station two"]
QUESTION_OPENERS = ["can you", "could you", "would you", "can you please", "will you", "could you maybe",
                    "you wanna", "mind if you", "any chance you could", "how about you", "why don't you"]
HEDGES = ["I think", "I guess", "maybe", "probably", "if possible", "I believe", "if that's okay",
          "if you don't mind", "I'd say", "let's say", "perhaps"]

# --- the target panel --------------------------------------------------------------------------------
#: {id} is the tagged id (ID_wall), {noun} a panel noun.
TARGET_ID = [
    "the {idnoun} {id}", "{idnoun} {id}", "{id}", "{id}", "number {id}", "{idnoun} number {id}",
    "the {idnoun} marked {id}", "the {idnoun} tagged {id}", "the {idnoun} labelled {id}", "{id} {idnoun}",
    "the one with {id} on it", "id {id}", "the {idnoun} with id {id}", "panel {id}",
]
TARGET_ID_TERSE = ["{id}", "{idnoun} {id}", "{id}", "{id}"]
#: {size} is a tagged size phrase.
TARGET_SIZE = [
    "a {size} {noun}", "the {size} {noun}", "a {size}", "the {size}", "one {size}", "one of the {size} {plural}",
    "a {noun} that is {size}", "the {noun} that's {size}", "a {size} one", "the {noun} {size}",
    "a {noun} {size}", "the {size} size {noun}",
]
TARGET_SIZE_TERSE = ["{size}", "{size}", "{size} {noun}", "{noun} {size}", "{size} one"]
#: {std} is a tagged standard-size phrase.
TARGET_STANDARD = [
    "a {std} {noun}", "the {std} {noun}", "one of the {std} {plural}", "a {std} one", "a {std}",
]
TARGET_STANDARD_TERSE = ["{std} {noun}", "{std}", "{std} one"]
STANDARD_WORDS = [
    "full/dim", "full/dim", "full-size/dim", "full/dim size/dim", "standard/dim", "standard/dim",
    "standard/dim size/dim", "regular/dim", "regular/dim size/dim", "normal/dim", "normal/dim size/dim",
    "full-sized/dim", "whole/dim", "fullsize/dim", "standard-size/dim",
]
#: The size of the last installed panel: tagged dim (guidelines 3, dim; 4.7 for "another", "the pile the last one came from").
TARGET_SAME = [
    "the same/dim as last/dim time/dim", "same/dim as before/dim", "the same/dim kind as before/dim",
    "another/dim one like the last/dim one", "another/dim of those/dim", "one more of those/dim",
    "the same/dim size as the last/dim one", "same/dim size again/dim", "the same/dim again/dim",
    "a {noun} like the last/dim one", "a {noun} just like the previous/dim one", "one like the last/dim",
    "the same/dim type you just/dim hung/dim", "same/dim {noun} as the one you just/dim put/dim up",
    "a {noun} matching/dim the last/dim one", "one that matches/dim the previous/dim", "same/dim as the previous/dim",
    "a {noun} to match/dim the last/dim one",
    "another/dim {noun} the same/dim", "the same/dim as the one before/dim", "a matching/dim {noun}",
    "from the {stack} the last/dim one came/dim from", "from the same/dim {stack} as last/dim time/dim",
    "same/dim again/dim", "ditto/dim",
]
TARGET_SAME_TERSE = ["same/dim again/dim", "same/dim as last/dim", "same/dim size", "another/dim", "same/dim {noun}",
                     "ditto/dim", "same/dim as before/dim", "like last/dim time/dim"]
#: A stack named by where it is: {where} is one of STACK_WHERE[stack].
TARGET_STACK = [
    "the {noun} from the {where}", "a {noun} off the {where}", "the {noun} {where}", "one from the {where}",
    "whatever's on top of the {where}", "the top {noun} from the {where}", "the one {where}",
    "the top one off the {where}", "the uppermost {noun} on the {where}", "the next {noun} off the {where}",
]
TARGET_STACK_TERSE = ["{where}", "{where}", "top of the {where}", "{noun} from {where}"]
#: Where each stack is, as a phrase with the position words tagged Dw_loc1 ({stack} is a stack noun).
STACK_WHERE = {
    "left": [
        "left/Dw_loc1 {stack}", "left/Dw_loc1 {stack}", "left-hand/Dw_loc1 {stack}", "far/Dw_loc1 left/Dw_loc1 {stack}",
        "{stack} on the left/Dw_loc1", "first/Dw_loc1 {stack}", "leftmost/Dw_loc1 {stack}",
        "{stack} furthest/Dw_loc1 left/Dw_loc1", "{stack} on the far/Dw_loc1 left/Dw_loc1",
        "first/Dw_loc1 {stack} from/Dw_loc1 the/Dw_loc1 left/Dw_loc1", "1st/Dw_loc1 {stack}",
        "{stack} at the left/Dw_loc1 end", "left/Dw_loc1 side {stack}",
    ],
    "middle": [
        "middle/Dw_loc1 {stack}", "middle/Dw_loc1 {stack}", "centre/Dw_loc1 {stack}", "center/Dw_loc1 {stack}",
        "{stack} in the middle/Dw_loc1", "second/Dw_loc1 {stack}", "2nd/Dw_loc1 {stack}",
        "{stack} in the centre/Dw_loc1", "second/Dw_loc1 {stack} from/Dw_loc1 the/Dw_loc1 left/Dw_loc1",
        "second/Dw_loc1 {stack} from/Dw_loc1 the/Dw_loc1 right/Dw_loc1", "mid/Dw_loc1 {stack}",
    ],
    "right": [
        "right/Dw_loc1 {stack}", "right/Dw_loc1 {stack}", "right-hand/Dw_loc1 {stack}", "far/Dw_loc1 right/Dw_loc1 {stack}",
        "{stack} on the right/Dw_loc1", "last/Dw_loc1 {stack}", "third/Dw_loc1 {stack}", "rightmost/Dw_loc1 {stack}",
        "{stack} furthest/Dw_loc1 right/Dw_loc1", "{stack} on the far/Dw_loc1 right/Dw_loc1",
        "first/Dw_loc1 {stack} from/Dw_loc1 the/Dw_loc1 right/Dw_loc1", "3rd/Dw_loc1 {stack}",
        "{stack} at the right/Dw_loc1 end",
    ],
}
#: A stack counted from an anchor: {dir} the tagged direction with its count, {anchor} the tagged anchor.
TARGET_RELATIVE = [
    "the {noun} from the {stack} {dir} of {anchor}", "a {noun} off the {stack} {dir} of {anchor}",
    "the {noun} {dir} of {anchor}", "one from the {stack} {dir} of {anchor}", "the {stack} {dir} of {anchor}",
    "whatever's on the {stack} {dir} of {anchor}", "the {noun} from {dir} of {anchor}",
]
TARGET_RELATIVE_TERSE = ["{stack} {dir} of {anchor}", "{dir} of {anchor}", "{noun} {dir} of {anchor}"]
PANEL_ANCHOR_ID = ["{id}", "{id}", "{plainnoun} {id}", "the {plainnoun} {id}", "the {stack} with {id}",
                   "where {id} is", "the {stack} {id} sits on"]
PANEL_ANCHOR_PREVIOUS = [
    "the last/Dw_loc2 one", "the previous/Dw_loc2 one", "the one you just/Dw_loc2 hung/Dw_loc2",
    "where the last/Dw_loc2 one came from", "the {stack} you used last/Dw_loc2", "the last/Dw_loc2 {plainnoun}",
    "the one before/Dw_loc2", "the previous/Dw_loc2 {plainnoun}", "the one you just/Dw_loc2 used/Dw_loc2",
    "the {stack} from last/Dw_loc2 time/Dw_loc2",
]
#: No target said (refused as undetermined).
TARGET_NONE = ["a {noun}", "the {noun}", "one", "a {noun}", "the next {noun}", "any {noun}", "whatever {noun}",
               "a {noun} from the {stack}", "that {noun}", "some {noun}"]

# --- the destination stud ----------------------------------------------------------------------------
STUD_ID = [
    "stud {id}", "stud {id}", "{id}", "{id}", "the stud {id}", "stud number {id}", "{id} stud",
    "the {id} stud", "stud id {id}", "the one marked {id}", "{stud} {id}", "number {id}",
]
STUD_ID_TERSE = ["{id}", "{id}", "stud {id}", "{id} stud"]
STUD_END = {
    "leftmost": [
        "the first/St_loc1 {stud}", "the far/St_loc1 left/St_loc1 {stud}", "the left/St_loc1 end/St_loc1 {stud}",
        "the leftmost/St_loc1 {stud}", "the {stud} all/St_loc1 the/St_loc1 way/St_loc1 left/St_loc1",
        "the very/St_loc1 first/St_loc1 {stud}", "the {stud} furthest/St_loc1 left/St_loc1",
        "the end/St_loc1 {stud} on the left/St_loc1", "the {stud} at the far/St_loc1 left/St_loc1",
        "the left-most/St_loc1 {stud}",
    ],
    "rightmost": [
        "the last/St_loc1 {stud}", "the far/St_loc1 right/St_loc1 {stud}", "the right/St_loc1 end/St_loc1 {stud}",
        "the rightmost/St_loc1 {stud}", "the {stud} all/St_loc1 the/St_loc1 way/St_loc1 right/St_loc1",
        "the very/St_loc1 last/St_loc1 {stud}", "the {stud} furthest/St_loc1 right/St_loc1",
        "the end/St_loc1 {stud} on the right/St_loc1", "the {stud} at the far/St_loc1 right/St_loc1",
    ],
    "middle": [
        "the middle/St_loc1 {stud}", "the centre/St_loc1 {stud}", "the center/St_loc1 {stud}",
        "the {stud} in the middle/St_loc1", "the {stud} in the middle/St_loc1 of the wall",
        "the {stud} halfway/St_loc1 along", "the {stud} at the centre/St_loc1 of the wall", "the mid/St_loc1 {stud}",
        "the {stud} dead/St_loc1 centre/St_loc1",
    ],
}
STUD_END_TERSE = {
    "leftmost": ["first/St_loc1 {stud}", "far/St_loc1 left/St_loc1", "left/St_loc1 end/St_loc1", "leftmost/St_loc1"],
    "rightmost": ["last/St_loc1 {stud}", "far/St_loc1 right/St_loc1", "right/St_loc1 end/St_loc1", "rightmost/St_loc1"],
    "middle": ["middle/St_loc1 {stud}", "centre/St_loc1 {stud}", "center/St_loc1 {stud}", "mid/St_loc1 {stud}"],
}
#: {ord} a tagged ordinal, {side} a tagged side: counted from one end.
STUD_FROM_END = [
    "the {ord} {stud} from/St_loc1 the/St_loc1 {side}", "the {ord} {stud} in/St_loc1 from/St_loc1 the/St_loc1 {side}",
    "the {ord} one from/St_loc1 the/St_loc1 {side}", "{ord} from/St_loc1 the/St_loc1 {side}",
    "the {ord} {stud} counting/St_loc1 from/St_loc1 the/St_loc1 {side}",
    "the {ord} {stud} from/St_loc1 the/St_loc1 {side} end/St_loc1",
    "counting/St_loc1 from/St_loc1 the/St_loc1 {side} , the {ord} {stud}",
    "{stud} {ord} from/St_loc1 the/St_loc1 {side}",
]
STUD_FROM_END_TERSE = ["{ord} from/St_loc1 {side}", "{ord} {stud} from/St_loc1 {side}", "{ord} from/St_loc1 the/St_loc1 {side}"]
STUD_ORDINAL = ["the {ord} {stud}", "the {ord} {stud}", "the {ord} one"]
STUD_ORDINAL_TERSE = ["{ord} {stud}"]
#: {dir} the tagged direction with its count; {anchor} the tagged anchor.
STUD_RELATIVE = [
    "the {stud} {dir} of {anchor}", "{dir} of {anchor}", "{dir} from {anchor}", "the {stud} {dir} from {anchor}",
    "{dir} of {anchor}", "the one {dir} of {anchor}",
]
STUD_RELATIVE_TERSE = ["{dir} of {anchor}", "{dir} from {anchor}", "{dir} {anchor}"]
STUD_ANCHOR_ID = ["{id}", "{id}", "stud {id}", "the stud {id}", "the {id} stud", "{id} stud"]
STUD_ANCHOR_END = {
    "leftmost": ["the first/St_loc2 stud", "the leftmost/St_loc2 stud", "the far/St_loc2 left/St_loc2 stud",
                 "the left/St_loc2 end/St_loc2", "the very/St_loc2 first/St_loc2 one", "the left/St_loc2 end/St_loc2 stud"],
    "rightmost": ["the very/St_loc2 last/St_loc2 stud", "the rightmost/St_loc2 stud", "the far/St_loc2 right/St_loc2 stud",
                  "the right/St_loc2 end/St_loc2", "the right/St_loc2 end/St_loc2 stud"],
}
STUD_ANCHOR_PREVIOUS = [
    "the last/St_loc2 one", "the previous/St_loc2 stud", "where the last/St_loc2 one went",
    "the stud you just/St_loc2 used/St_loc2", "last/St_loc2 time/St_loc2", "the one before/St_loc2",
    "where you put the last/St_loc2 one", "the last/St_loc2 stud you used", "the previous/St_loc2 one",
    "that last/St_loc2 one", "where the previous/St_loc2 one went", "the stud from last/St_loc2 time/St_loc2",
]
#: The stud of the last accepted command (St_loc1 "same" or "where" + St_loc2, guidelines 4.7).
STUD_SAME = [
    "the same/St_loc1 {stud}", "the same/St_loc1 {stud}", "same/St_loc1 {stud} as last/St_loc2 time/St_loc2",
    "the same/St_loc1 {stud} again/St_loc2", "that same/St_loc1 {stud}", "the same/St_loc1 one",
    "same/St_loc1 {stud} as before/St_loc2", "the same/St_loc1 {stud} you just/St_loc2 used/St_loc2",
    "where/St_loc1 the last/St_loc2 one went", "where/St_loc1 you put the last/St_loc2 one",
    "the same/St_loc1 {stud} as the previous/St_loc2 one", "right where/St_loc1 the last/St_loc2 one went",
]
STUD_SAME_TERSE = ["same/St_loc1 {stud}", "same/St_loc1 {stud}", "same/St_loc1 one", "same/St_loc1 again/St_loc2"]
#: No stud said (refused as undetermined).
STUD_NONE = ["the wall", "a stud", "the stud", "up there", "the frame", "somewhere", "that stud", "the next stud",
             "wherever", "over there"]

# --- the placement -----------------------------------------------------------------------------------
PLACEMENT = {
    "vertical_left": [  # the default: mostly nothing said; all O
        "", "", "", "", "", "", "", "", "", "standing up", "upright", "vertical", "vertically", "straight up",
        "on its edge", "plumb", "the usual way", "edge on the left side of the {stud}", "long way up",
        "standing", "up and down", "portrait", "portrait style", "stood up", "on the stud's left edge",
    ],
    "vertical_middle": [
        "on the centre/Vr_md line/Vr_md", "on the center/Vr_md line/Vr_md", "on/Vr_md centre/Vr_md", "on/Vr_md center/Vr_md",
        "centered/Vr_md", "centred/Vr_md", "centred/Vr_md on the {stud}", "on the centerline/Vr_md",
        "on the centreline/Vr_md", "edge on the centre/Vr_md line/Vr_md", "with its edge on the middle/Vr_md line/Vr_md",
        "on the middle/Vr_md of the {stud}", "middle/Vr_md line/Vr_md", "centre/Vr_md line/Vr_md",
        "center/Vr_md line/Vr_md", "half/Vr_md on the {stud}", "split/Vr_md the {stud}", "break/Vr_md on the centre/Vr_md",
        "down the middle/Vr_md of the {stud}", "on the {stud} centre/Vr_md", "at the middle/Vr_md line/Vr_md",
        "in the middle/Vr_md of the {stud}", "lined up on the centre/Vr_md line/Vr_md", "vertical on/Vr_md centre/Vr_md",
        "upright on the center/Vr_md line/Vr_md", "edge on c-l/Vr_md", "on the mid/Vr_md line/Vr_md",
        "portrait on the centre/Vr_md line/Vr_md", "with the edge in the middle/Vr_md of the {stud}",
    ],
    "horizontal_top": [
        "up top/Hr_top", "in the top/Hr_top row/Hr_top", "across the top/Hr_top", "top/Hr_top row/Hr_top",
        "along the top/Hr_top", "flat along the top/Hr_top", "sideways up top/Hr_top", "on the upper/Hr_top row/Hr_top",
        "in the upper/Hr_top half/Hr_top", "horizontal at the top/Hr_top", "high/Hr_top", "up high/Hr_top",
        "top/Hr_top half/Hr_top", "lying across the top/Hr_top", "laid flat at the top/Hr_top",
        "on the top/Hr_top part/Hr_top", "horizontally in the top/Hr_top row/Hr_top", "top/Hr_top",
        "tight to the ceiling/Hr_top", "up against the ceiling/Hr_top", "landscape at the top/Hr_top",
        "landscape up top/Hr_top", "lying down at the top/Hr_top",
        "in the top/Hr_top course/Hr_top", "top/Hr_top course/Hr_top", "the upper/Hr_top course/Hr_top",
        "~in the top/Hr_top tier/Hr_top", "~top/Hr_top tier/Hr_top", "~the upper/Hr_top tier/Hr_top",
    ],
    "horizontal_bottom": [
        "down low/Hr_btm", "in the bottom/Hr_btm row/Hr_btm", "across the bottom/Hr_btm", "bottom/Hr_btm row/Hr_btm",
        "along the bottom/Hr_btm", "flat along the bottom/Hr_btm", "sideways at the bottom/Hr_btm",
        "on the lower/Hr_btm row/Hr_btm", "in the lower/Hr_btm half/Hr_btm", "horizontal at the bottom/Hr_btm",
        "low/Hr_btm", "bottom/Hr_btm half/Hr_btm", "lying across the bottom/Hr_btm", "at floor/Hr_btm level/Hr_btm",
        "on the bottom/Hr_btm part/Hr_btm", "horizontally in the bottom/Hr_btm row/Hr_btm", "bottom/Hr_btm",
        "down at the bottom/Hr_btm", "tight to the floor/Hr_btm", "on the floor/Hr_btm",
        "landscape at the bottom/Hr_btm", "landscape down low/Hr_btm", "lying down at the bottom/Hr_btm",
        "in the bottom/Hr_btm course/Hr_btm", "bottom/Hr_btm course/Hr_btm", "the lower/Hr_btm course/Hr_btm",
        "~in the bottom/Hr_btm tier/Hr_btm", "~bottom/Hr_btm tier/Hr_btm", "~the lower/Hr_btm tier/Hr_btm",
    ],
}
#: Placements that cannot be said without a verb-free phrase ("up top" reads fine everywhere).
PLACEMENT_SENTENCE = ["put it {p}", "it goes {p}", "{p}", "{p} please", "make it {p}", "do it {p}",
                      "this one {p}", "hang it {p}", "set it {p}", "want it {p}"]
