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
    "plate rows": "'top plate' / 'bottom plate' for a horizontal row ('tight to the top plate')",
    "handover notes": "an instruction left as a note for the next shift ('note for the next shift: ...')",
}

# --- generic words -----------------------------------------------------------------------------------
#: The panel in full noun phrases ("the 4x8 sheet"); O words, Trg in the co-reference variant.
PANEL_NOUNS = [
    "sheet/@T", "sheet/@T", "sheet/@T", "panel/@T", "panel/@T", "board/@T", "board/@T", "drywall/@T",
    "piece/@T", "drywall/@T sheet/@T", "one/@T", "one/@T", "drywall/@T board/@T", "plasterboard/@T",
    "rock/@T", "sheetrock/@T", "sheet/@T of/@T rock/@T", "piece/@T of/@T rock/@T",
    "~gyp/@T board/@T", "~wallboard/@T", "~GWB/@T",
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
           "nice and easy", "carefully", "good", "go", "for me", "mate", "buddy", "boss", "pal", "chief",
           # time words after a position: "right" here is not a side ("... third to the right, right now")
           "right now", "right away", "right now please", "right after this", "straight away"]
#: Ways of saying "do this" that carry no information ("let's", "you're gonna", "what I want is").
INTENTS = ["let's", "you're gonna", "you gonna", "we need to", "I want you to", "gonna have to", "next we", "we'll",
           "what I want is", "ok so for this one", "the plan is to", "time to", "go ahead and", "you can"]
#: Reasons and context said before the instruction ("We're closing up this bay, so ...").
CONTEXT = [
    "we are closing up this bay", "the inspector is coming after lunch", "we need to finish this wall today",
    "the electrician is done here", "we're working left to right", "the bottom is done on this side",
    "that last one looks good", "the tape crew is waiting", "we're short on time", "the plumber signed off",
    "the insulation is in", "this is the last wall before break",
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
    # stud spacing: how the wall is framed, never the centre-line placement (guidelines 4.7)
    "the studs are 16 in on centre", "studs here are sixteen inches on center", "this wall is framed 16 o.c.",
    "it's sixteen-inch centres on this wall", "stud spacing is 16 on center", "the framing is 24 inch on centre",
    "there's a pipe behind the wall", "the ceiling is eight feet here",
]
CONTEXT_LINKS = ["so", "so", "and", "which means", "therefore", "hence", "that's why", ""]
#: Words that abandon what was just said: the final intention counts.
CORRECTIONS = ["no", "no wait", "wait", "sorry", "actually", "actually no", "no no", "hold on", "oops",
               "my bad", "correction", "not that", "or no", "hang on", "scratch that", "I mean", "wait no",
               "on second thought", "hmm , no", "~make that", "~let me rephrase", "~rather"]
CORRECTION_ENDS = ["", "", "instead", "not the other one", "sorry", "my mistake", "I meant", "I mean that"]
#: A sentence that takes back the whole sentence before it ("... Correction: ...").
CORRECTION_SENTENCES = ["correction", "sorry , I mean", "scratch that", "no wait", "let me say that again", "my bad",
                        "wrong one", "no no no", "hold on , I got that wrong", "disregard that", "strike that",
                        "ignore that"]
#: "Did I say X? I meant Y."
CORRECTION_ASKS = ["did I say", "wait , did I say", "I said", "oops , I said"]
CORRECTION_MEANT = ["I meant", "sorry , I meant", "I mean", "should be", "it's", "meant to say"]
RADIO_CALLS = ["copy", "roger", "roger that", "copy that", "ten four", "10-4", "affirmative", "go ahead",
               "robot, copy", "come in robot", "over", "read you", "message follows", "next task", "stand by for task",
               "radio check , loud and clear"]
RADIO_ENDS = ["over", "over", "over", "copy", "copy?", "confirm", "how copy", "roger", "out", "acknowledge",
              "read back , over", "how do you read", "over to you"]
CALL_SIGNS = ["base to robot", "crew two to robot", "robot , this is crew one", "crew one here",
              "~robot one , this is the foreman", "~drywall crew to robot one", "~this is station two"]
QUESTION_OPENERS = ["can you", "could you", "would you", "can you please", "will you", "could you maybe",
                    "you wanna", "mind if you", "any chance you could", "how about you", "why don't you"]
HEDGES = ["I think", "I guess", "maybe", "probably", "if possible", "I believe", "if that's okay",
          "if you don't mind", "I'd say", "let's say", "perhaps"]
#: Asides between the parts of one instruction: they carry nothing.
ASIDES = ["you see it", "got it", "yeah", "careful it's heavy", "mind your fingers", "nice and square", "you with me",
          "okay", "right", "watch the corner", "take your time", "good", "no rush", "easy does it", "that's the one",
          "two hands on it", "don't drop it", "keep it flat", "yeah that one"]
#: Reasons said after the instruction ("..., because the bottom course is done"); position words here are O.
REASONS_AFTER = [
    "the bottom course is done", "the joints don't line up that way", "that keeps the seams staggered",
    "the tapers are coming after lunch", "we need this wall closed up today", "the inspector wants it done by three",
    "it has to be up before the electrician comes back", "the left side is finished", "we start taping tomorrow",
    "the framing there got checked", "that's how the drawing has it", "the butt joints have to land on a stud",
    "the top row on the other wall is done", "the mud guys want the long seams flat", "we're running out of daylight",
    "the boss changed the plan", "that stud is the straight one", "there's backing behind it",
]
REASON_LINKS = ["because", "because", "since", "cause", "so that", "as", "that's because", "reason is"]
#: Purposes said before the instruction ("To keep the joints staggered, ...").
PURPOSES = ["to keep the joints staggered", "so the tapers have an easy time", "to close this bay up",
            "so we finish before lunch", "to get the long seams flat", "so the butt joints land on a stud",
            "to keep the crew busy", "for the inspection", "to stay ahead of the tapers", "so the wall is ready for mud"]
#: A teacher's opening and tips for an apprentice: no information.
TEACH_OPENERS = ["watch how we do this", "okay , listen up", "here's how it goes", "let me show you", "pay attention",
                 "this is how we do it", "first time doing this ? easy", "rookie , listen", "look", "remember this",
                 "you'll do this a hundred times , so watch"]
TEACH_TIPS = [
    "always screw it off from the middle out", "keep the factory edge out", "check it's plumb before you screw it",
    "stagger the butt joints", "don't let the seams line up with the door", "screws about a foot apart",
    "don't break the paper with the screws", "keep it tight to the one next to it", "the tapered edges meet , see",
    "push it up tight before you screw it", "that's the whole trick", "the mud guys will thank you",
    "measure twice , cut once", "that's how you learn", "next time you do it yourself",
]
#: What happened before, told before the instruction; position and back-reference words here are O.
STORIES = [
    "yesterday we finished the other wall", "last week we had to pull two sheets off because the joints lined up",
    "this morning the framer fixed the crooked stud", "when I started we had four guys on one wall",
    "the last crew left this wall half done", "we had a sheet crack on us earlier",
    "the inspector came by and said the wall looks good", "on the last job every wall went sideways and the joints were a pain",
    "the delivery came late so we lost an hour", "before lunch we did the bottom on the other side",
    "the taper complained about the seams on the east wall", "we got the layout from the engineer today",
    "the foreman checked the first few and they were fine", "somebody put a screw through a pipe last month",
]
#: A story about the last accepted step, with its ids ({panel}, {stud}: all O).
STORIES_LAST = ["you put {panel} on {stud} before and it looks good", "{panel} went on {stud} , nice job",
                "the last one , {panel} , went on {stud}", "good , {panel} is on {stud} now",
                "we just did {panel} on {stud}"]
STORY_LINKS = ["so now", "anyway", "so this time", "today", "now", "right , so", "okay so", "so", "next"]
#: An impatient boss.
BOSS_OPENERS = ["come on", "hurry up", "let's go", "move it", "what are you waiting for", "are you deaf",
                "how many times do I have to say it", "not tomorrow , today", "wake up", "stop standing around",
                "I haven't got all day", "for the last time", "quick", "listen to me"]
BOSS_ENDS = ["now", "right now", "today", "move", "quick", "come on", "hurry", "let's go", "and make it quick",
             "before lunch", "chop chop", "I'm waiting", "go go go", "no more mistakes"]
#: A site engineer's openers and technical details: numbers and references that carry no tag.
ENG_OPENERS = ["please proceed as follows", "next activity", "work instruction", "installation sequence , next item",
               "as per the layout drawing", "per drawing A-201", "in accordance with the method statement",
               "as discussed at the coordination meeting", "for the record", "task {k}", "item {k} of {m}",
               "ref. RFI {k}", "level 2 , gridline C", "zone B , wall W{k}"]
ENG_DETAILS = [
    "12.5 mm board", "half inch board", "fix with 25 mm drywall screws at 300 mm centres", "screws at 12 inch spacing",
    "tolerance 3 mm", "check plumb and line before fixing", "leave a 10 mm expansion gap", "fire rating 60 minutes",
    "fixings to manufacturer's specification", "joints to be staggered", "paper face out", "no cut edges at openings",
    "moisture resistant board not required", "screw heads to be set just below the paper", "2 fixings per metre minimum",
    "record completion in the site diary", "studs at 406 mm centres", "framing at 16 in on centre",
]
ENG_DEFAULT_PLACEMENT = ["vertical", "vertical , edge on the left line of the stud", "portrait", "vertical , default",
                         "vertical , left edge on stud line", "vertical as usual"]
#: The words of an engineer's placement line when a placement is said.
ENG_PLACEMENT_KEYS = ["orientation", "position", "placement", "fixing position", "mounting"]
#: An instruction left for the next shift (held back: the novel split only).
HANDOVER = ["~note for the next shift", "~handover note", "~for the morning shift , first job",
            "~for whoever is on tomorrow", "~handover to the night shift"]
#: Clauses before and after an instruction in a long explanatory sentence: no information.
LEAD_CLAUSES = ["once you're done with the screws on that one", "when the lift is free", "after you've checked the stud is straight",
                "as soon as the tapers are out of the way", "before you break for lunch", "when you've got a second",
                "if the glue is on already", "while I get the screws"]
TRAIL_CLAUSES = ["and make sure it sits tight against its neighbour", "and check it's plumb before you screw it off",
                 "then give me a shout", "and don't forget the screws along the edge", "and let me know when it's up",
                 "and mind the outlet box", "then we break"]
#: Question tags after an instruction ("..., yeah?").
QUESTION_TAGS = ["yeah", "okay", "right", "got it", "alright", "you good", "can do", "understood", "sound good"]
#: Phone-message openers and ends (an apprentice texting).
TEXT_OPENERS = ["", "", "hey", "yo", "k so", "ok", "boss says", "next one", "fyi", "so", "hi"]
TEXT_ENDS = ["", "", "thx", "ty", "asap", "k?", "pls", "cheers", "when u can", "ta"]
#: Prepositions a non-native speaker uses before the stud.
NN_PREPOSITIONS = ["in", "at", "to", "into", "by", "for", "on", "in", "at"]

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
    "a {noun} {size}", "the {size} size {noun}", "a {noun} of {size}", "one of {size}",
    # an ordinal that counts the panels put up, not a stack: O ("a second 4x8 sheet")
    "a second {size} {noun}",
]
TARGET_SIZE_TERSE = ["{size}", "{size}", "{size} {noun}", "{noun} {size}", "{size} one"]
#: {std} is a tagged standard-size phrase.
TARGET_STANDARD = [
    "a {std} {noun}", "the {std} {noun}", "one of the {std} {plural}", "a {std} one", "a {std}",
    "a second {std} {noun}", "one more {std} {noun}",
]
TARGET_STANDARD_TERSE = ["{std} {noun}", "{std}", "{std} one"]
STANDARD_WORDS = [
    "full/dim", "full/dim", "full-size/dim", "full/dim size/dim", "standard/dim", "standard/dim",
    "standard/dim size/dim", "regular/dim", "regular/dim size/dim", "normal/dim", "normal/dim size/dim",
    "full-sized/dim", "whole/dim", "fullsize/dim", "standard-size/dim",
]
#: A size said by a property: {prop} is a word of ``data/site/size_words.csv`` that names one stack on the site,
#: tagged dim ("the narrow/dim one", "a short/dim sheet"; guidelines 3, dim).
TARGET_PROPERTY = [
    "the {prop} {noun}", "a {prop} {noun}", "the {prop} one", "a {prop} one", "one of the {prop} {plural}",
    "one of the {prop} ones", "the {prop} {noun}", "~the {prop} {noun} there", "~one of those {prop} ones",
    "~a nice {prop} one",
]
TARGET_PROPERTY_TERSE = ["{prop}", "{prop} {noun}", "{prop} one", "the {prop} one"]
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
    "another/dim of the same/dim", "the same/dim as you just/dim did/dim", "same/dim thing again/dim",
    "same/dim deal as last/dim time/dim", "the same/dim sort as before/dim", "another/dim one just like it",
    "the same/dim size you just/dim used/dim", "same/dim as that last/dim one", "the same/dim as earlier/dim",
    "off the same/dim {stack} again/dim", "from the {stack} you took the last/dim one from",
]
TARGET_SAME_TERSE = ["same/dim again/dim", "same/dim as last/dim", "same/dim size", "another/dim", "same/dim {noun}",
                     "ditto/dim", "same/dim as before/dim", "like last/dim time/dim", "another/dim of those/dim",
                     "same/dim thing"]
#: A stack named by where it is: {where} is one of STACK_WHERE[stack].
TARGET_STACK = [
    "the {noun} from the {where}", "a {noun} off the {where}", "the {noun} {where}", "one from the {where}",
    "whatever's on top of the {where}", "the top {noun} from the {where}", "the one {where}",
    "the top one off the {where}", "the uppermost {noun} on the {where}", "the next {noun} off the {where}",
]
TARGET_STACK_TERSE = ["{where}", "{where}", "top of the {where}", "{noun} from {where}"]
#: A stack named by its side with no stack noun ("the one on the right", "the panel on the left", as the robot's
#: refusals suggest): the side words are Dw_loc1.
TARGET_SIDE = {
    "left": ["the one on the left/Dw_loc1", "the {noun} on the left/Dw_loc1", "one from the left/Dw_loc1",
             "the one at the far/Dw_loc1 left/Dw_loc1", "the {noun} furthest/Dw_loc1 left/Dw_loc1", "the left/Dw_loc1 one"],
    "middle": ["the one in the middle/Dw_loc1", "the {noun} in the middle/Dw_loc1", "one from the middle/Dw_loc1",
               "the one in the centre/Dw_loc1", "the middle/Dw_loc1 one", "the centre/Dw_loc1 one"],
    "right": ["the one on the right/Dw_loc1", "the {noun} on the right/Dw_loc1", "one from the right/Dw_loc1",
              "the one at the far/Dw_loc1 right/Dw_loc1", "the {noun} furthest/Dw_loc1 right/Dw_loc1", "the right/Dw_loc1 one"],
}
#: A stack named by its side alone, where the slot says it is the panel ("panel: left", "Middle. Stud 500105."):
#: the side word is Dw_loc1 (guidelines 4.7, key-value and list styles).
STACK_BARE = {"left": ["left/Dw_loc1", "left/Dw_loc1", "far/Dw_loc1 left/Dw_loc1", "leftmost/Dw_loc1", "left/Dw_loc1 one"],
              "middle": ["middle/Dw_loc1", "middle/Dw_loc1", "centre/Dw_loc1", "center/Dw_loc1", "middle/Dw_loc1 one"],
              "right": ["right/Dw_loc1", "right/Dw_loc1", "far/Dw_loc1 right/Dw_loc1", "rightmost/Dw_loc1",
                        "right/Dw_loc1 one"]}
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
    "the {stack} the last/Dw_loc2 one came/Dw_loc2 from", "the {stack} you just/Dw_loc2 took/Dw_loc2 from",
    "the one you took last/Dw_loc2",
    # only a pointing word says it is the last one (guidelines 4.7): it carries the anchor tag
    "that/Dw_loc2 one", "the {stack} that/Dw_loc2 one came/Dw_loc2 from", "the {stack} it/Dw_loc2 came/Dw_loc2 off",
    "wherever that/Dw_loc2 {plainnoun} came/Dw_loc2 from",
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
#: Non-native order, the count after the anchor ("at left of 500104 , three studs"): {n} the tagged count.
COUNT_AFTER_ANCHOR = ["{n} {unit}", "{n} {unit}", "distance {n} {unit}", "{n} {unit} far", "count {n}", "{n} {unit} from it",
                      "is {n} {unit}", "about {n} {unit}"]
#: The words before the side in that order: O ("to the right side of ...", "at left of ...").
SIDE_LEADS = ["to the", "to the", "at", "at the", "on the", "in the", "", "on", "the stud at", "the stud on the", "for"]
STUD_ANCHOR_ID = ["{id}", "{id}", "stud {id}", "the stud {id}", "the {id} stud", "{id} stud"]
STUD_ANCHOR_END = {
    "leftmost": ["the first/St_loc2 stud", "the leftmost/St_loc2 stud", "the far/St_loc2 left/St_loc2 stud",
                 "the left/St_loc2 end/St_loc2", "the very/St_loc2 first/St_loc2 one", "the left/St_loc2 end/St_loc2 stud"],
    "rightmost": ["the very/St_loc2 last/St_loc2 stud", "the rightmost/St_loc2 stud", "the far/St_loc2 right/St_loc2 stud",
                  "the right/St_loc2 end/St_loc2", "the right/St_loc2 end/St_loc2 stud"],
}
#: An anchor stud named by where it is on the wall ({ord} a tagged ordinal): "three left of the centre stud".
STUD_ANCHOR_POSITION = {
    "middle": ["the middle/St_loc2 stud", "the centre/St_loc2 stud", "the stud in the middle/St_loc2",
               "the center/St_loc2 one", "the middle/St_loc2 one"],
    "left": ["the {ord} stud", "the {ord} one", "the {ord} stud from/St_loc2 the/St_loc2 left/St_loc2",
             "the {ord} from/St_loc2 the/St_loc2 left/St_loc2"],
    "right": ["the {ord} stud from/St_loc2 the/St_loc2 right/St_loc2", "the {ord} one from/St_loc2 the/St_loc2 right/St_loc2",
              "the {ord} from/St_loc2 the/St_loc2 right/St_loc2 end/St_loc2"],
}
STUD_ANCHOR_PREVIOUS = [
    "the last/St_loc2 one", "the previous/St_loc2 stud", "where the last/St_loc2 one went",
    "the stud you just/St_loc2 used/St_loc2", "last/St_loc2 time/St_loc2", "the one before/St_loc2",
    "where you put the last/St_loc2 one", "the last/St_loc2 stud you used", "the previous/St_loc2 one",
    "that last/St_loc2 one", "where the previous/St_loc2 one went", "the stud from last/St_loc2 time/St_loc2",
    "where that last/St_loc2 one went", "the stud you just/St_loc2 did/St_loc2", "the last/St_loc2 one you did",
    # only a pointing word says it is the last one (guidelines 4.7): it carries the anchor tag
    "that/St_loc2 one", "that/St_loc2 one", "where/St_loc2 that one went", "where/St_loc2 you put it",
    "it/St_loc2", "where/St_loc2 it went", "that/St_loc2 stud", "where/St_loc2 you hung that one",
]
#: The stud of the last accepted command (St_loc1 "same" or "where" + St_loc2, guidelines 4.7).
STUD_SAME = [
    "the same/St_loc1 {stud}", "the same/St_loc1 {stud}", "same/St_loc1 {stud} as last/St_loc2 time/St_loc2",
    "the same/St_loc1 {stud} again/St_loc2", "that same/St_loc1 {stud}", "the same/St_loc1 one",
    "same/St_loc1 {stud} as before/St_loc2", "the same/St_loc1 {stud} you just/St_loc2 used/St_loc2",
    "where/St_loc1 the last/St_loc2 one went", "where/St_loc1 you put the last/St_loc2 one",
    "the same/St_loc1 {stud} as the previous/St_loc2 one", "right where/St_loc1 the last/St_loc2 one went",
    "the same/St_loc1 spot", "the same/St_loc1 spot as before/St_loc2", "where/St_loc1 that one went",
    "exactly where/St_loc1 the previous/St_loc2 one went", "where/St_loc1 you did the last/St_loc2 one",
    "the same/St_loc1 place again/St_loc2", "the same/St_loc1 {stud} as that one", "same/St_loc1 place as last/St_loc2 time/St_loc2",
]
STUD_SAME_TERSE = ["same/St_loc1 {stud}", "same/St_loc1 {stud}", "same/St_loc1 one", "same/St_loc1 again/St_loc2",
                   "same/St_loc1 spot", "same/St_loc1 place", "where/St_loc1 that one went", "same/St_loc1 as before/St_loc2",
                   "same/St_loc1 {stud} as before/St_loc2"]
#: No stud said (refused as undetermined).
STUD_NONE = ["the wall", "a stud", "the stud", "up there", "the frame", "somewhere", "that stud", "the next stud",
             "wherever", "over there"]

# --- the placement -----------------------------------------------------------------------------------
PLACEMENT = {
    "vertical_left": [  # the default: mostly nothing said; all O
        "", "", "", "", "", "", "", "", "", "standing up", "upright", "vertical", "vertically", "straight up",
        "on its edge", "plumb", "the usual way", "edge on the left side of the {stud}", "long way up",
        "standing", "up and down", "portrait", "portrait style", "stood up", "on the stud's left edge",
        "stood up on its end", "standing up like always", "left edge on the {stud}", "edge on the left of the {stud}",
        # the default named as the robot names it (spec section 4, and the robot's own questions): still all O
        "on the left line", "on its left line", "left line", "on the left line of the {stud}", "edge on the left line",
        "left edge on the left line", "default , left line", "the default", "default", "on the stud's left line",
        "lined up on the left line", "the normal left line", "on the left side of the {stud}",
        "left side of the {stud}",
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
        "centre/Vr_md of the {stud}", "to the centre/Vr_md line/Vr_md", "edge to centre/Vr_md", "edge on centre/Vr_md",
        "leave half/Vr_md the {stud} for the next one", "centered/Vr_md up on the {stud}", "middle/Vr_md of the {stud}",
        "on the centre/Vr_md", "centre/Vr_md line/Vr_md please", "stood up on the centre/Vr_md line/Vr_md",
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
        "up at the top/Hr_top", "laid flat up top/Hr_top", "top/Hr_top position", "upper/Hr_top position",
        "high/Hr_top row/Hr_top", "at the ceiling/Hr_top", "the high/Hr_top course/Hr_top", "top/Hr_top , horizontal",
        "lying flat along the top/Hr_top", "lay it down up top/Hr_top", "sideways along the top/Hr_top",
        "~in the top/Hr_top tier/Hr_top", "~top/Hr_top tier/Hr_top", "~the upper/Hr_top tier/Hr_top",
        "~tight to the top/Hr_top plate/Hr_top", "~up against the top/Hr_top plate/Hr_top", "~along the top/Hr_top plate/Hr_top",
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
        "down at the floor/Hr_btm", "lower/Hr_btm position", "bottom/Hr_btm position", "low/Hr_btm row/Hr_btm",
        "along the floor/Hr_btm", "down on the floor/Hr_btm", "laid flat down low/Hr_btm", "bottom/Hr_btm , horizontal",
        "lying flat along the bottom/Hr_btm", "lay it down low/Hr_btm", "sideways along the bottom/Hr_btm",
        "~in the bottom/Hr_btm tier/Hr_btm", "~bottom/Hr_btm tier/Hr_btm", "~the lower/Hr_btm tier/Hr_btm",
        "~tight to the bottom/Hr_btm plate/Hr_btm", "~along the bottom/Hr_btm plate/Hr_btm", "~down on the bottom/Hr_btm plate/Hr_btm",
    ],
}
#: A placement ruled out ("not on the centre line", "forget the top row"): all O (guidelines 4.7, a negated
#: alternative), said before the placement meant, which may be the unsaid default.
PLACEMENT_NEGATED = {
    "vertical_left": ["not on the left line", "not standing up", "not upright", "not the usual way", "not the default"],
    "vertical_middle": ["not on the centre line", "not centred", "without the centre line",
                        "forget the centre line", "not on centre", "never mind the middle line", "not on the middle line"],
    "horizontal_top": ["not up top", "forget the top", "forget the top row", "never mind the top row",
                       "not in the top row", "not the upper course", "skip the top row"],
    "horizontal_bottom": ["not down low", "forget the bottom", "forget the bottom row",
                          "never mind the bottom row", "not in the bottom row", "not the lower course",
                          "skip the bottom row"],
}
#: What follows a ruled-out placement ("not up top , just standing up"); empty or O words.
PLACEMENT_NEGATED_LINKS = [",", ",", ", just", ", but", ", instead", ", simply", ". this one", ", only"]
#: Context said first that does set this panel's placement ("we're doing the top row now, so ..."): the
#: placement words in it are tagged (guidelines 4.7); the instruction after it may leave the placement out.
CONTEXT_PLACEMENT = {
    "vertical_middle": ["everything goes on the centre/Vr_md line/Vr_md on this wall", "this wall we do centred/Vr_md",
                        "we're splitting/Vr_md the studs on this one", "these go on/Vr_md centre/Vr_md today"],
    "horizontal_top": ["we're doing the top/Hr_top row/Hr_top now", "we're on the top/Hr_top course/Hr_top now",
                       "time for the top/Hr_top row/Hr_top", "this one is for the upper/Hr_top row/Hr_top",
                       "we're starting the top/Hr_top course/Hr_top", "now we work up top/Hr_top",
                       "the scaffold is up so we go high/Hr_top"],
    "horizontal_bottom": ["we're doing the bottom/Hr_btm row/Hr_btm now", "we're on the bottom/Hr_btm course/Hr_btm now",
                          "time for the bottom/Hr_btm row/Hr_btm", "this one is for the lower/Hr_btm row/Hr_btm",
                          "we're starting the bottom/Hr_btm course/Hr_btm", "now we work down low/Hr_btm",
                          "no scaffold yet so we stay low/Hr_btm"],
}
#: The role's noun after a single size number ("of 2 ft width", "six feet in length"): O, the number carries the tag.
SIZE_NOUN_AFTER = ["ft", "ft in", "foot", "feet in", "feet", "foot in"]
#: Radio call signs built from a unit and a number ("team two , this is bravo"): every word O, the number too.
CALL_UNITS = ["crew", "team", "unit", "robot", "bot", "lift", "truck", "gang", "squad", "car", "mobile", "arm",
              "crane", "loader", "cart", "tower", "station", "machine", "forklift", "hoist", "tractor", "group", "cell"]
#: The NATO spelling alphabet and a few site names.
CALL_NAMES = ["alpha", "bravo", "charlie", "delta", "echo", "foxtrot", "golf", "hotel", "india", "juliet", "kilo", "lima",
              "mike", "november", "oscar", "papa", "quebec", "romeo", "sierra", "tango", "uniform", "victor", "whiskey",
              "x-ray", "yankee", "zulu", "base", "control", "site office", "the gate", "ops", "the foreman", "supervisor"]
CALL_FRAMES = ["{unit} {n} , this is {name}", "{name} to {unit} {n}", "{unit} {n} , {name}", "{name} calling {unit} {n}",
               "{unit} {n} from {name}", "this is {name} for {unit} {n}", "{name} {n}", "{unit} , this is {name} {n}",
               "this is {name} {n}", "{name} {n} here"]
#: A numbered label before a list or key-value instruction ("task #3 :"): the number is a label, O.
LABEL_NOUNS = ["task", "job", "work order", "card", "entry", "line", "order", "step"]

#: Placements that cannot be said without a verb-free phrase ("up top" reads fine everywhere).
PLACEMENT_SENTENCE = ["put it {p}", "it goes {p}", "{p}", "{p} please", "make it {p}", "do it {p}",
                      "this one {p}", "hang it {p}", "set it {p}", "want it {p}", "and {p}", "{p} , yeah",
                      "oh and {p}", "{p} this time", "I want it {p}"]
#: The placement said first, before the rest ("Up top this time: ...").
PLACEMENT_FIRST = ["{p} this time", "{p} now", "{p} for this one", "this one goes {p}",
                   "okay , {p}", "next one {p}"]
#: The default placement said first: all O.
DEFAULT_FIRST = ["standing up this time", "vertical", "upright for this one", "normal way up", "stood up"]
#: A placement wrapped round the stud ({d} is the stud phrase): "with its edge on the centre line of stud 500105".
PLACEMENT_OF_STUD = {
    "vertical_left": ["on {d}", "with its edge on the left side of {d}", "lined up with the left side of {d}",
                      "on {d} , standing up", "on {d} the normal way", "on the left side of {d}", "left side of {d}",
                      "to the left edge of {d}"],
    "vertical_middle": ["with its edge on the centre/Vr_md line/Vr_md of {d}", "on the centreline/Vr_md of {d}",
                        "centred/Vr_md on {d}", "half/Vr_md on {d}", "edge on the centre/Vr_md line/Vr_md of {d}",
                        "on the middle/Vr_md line/Vr_md of {d}", "centered/Vr_md over {d}", "splitting/Vr_md {d}",
                        "centre/Vr_md of {d}", "on the centre/Vr_md of {d}", "in the middle/Vr_md of {d}",
                        "the middle/Vr_md of {d}", "at the center/Vr_md of {d}"],
    "horizontal_top": ["in the top/Hr_top row/Hr_top starting at {d}", "up top/Hr_top from {d}",
                       "across the top/Hr_top starting from {d}", "in the top/Hr_top course/Hr_top at {d}",
                       "flat along the top/Hr_top from {d} on"],
    "horizontal_bottom": ["in the bottom/Hr_btm row/Hr_btm starting at {d}", "down low/Hr_btm from {d}",
                          "across the bottom/Hr_btm starting from {d}", "in the bottom/Hr_btm course/Hr_btm at {d}",
                          "flat along the bottom/Hr_btm from {d} on"],
}
