"""A dialogue with the robot (issue 12): an instruction, the robot's command or question, the worker's answer.

``Dialogue.say(text)`` takes what the worker types. A new instruction goes through the tagger and the
decision layer (``drywall_lab.decision``): the robot says the command it carries out, or asks one
question (refusal reason ``unclear``), or refuses with the IM's message. While a question is open the
next words answer it: "yes" (or "the first") carries out the command asked about, "the second" the
other one, "no" drops it; anything else is taken as a corrected instruction. Nothing is recorded
unless the robot acts. ``wall_text`` draws the wall and the stacks in text after each step;
``python -m drywall_lab chat`` runs the dialogue in a terminal and ``chat_widget`` in a notebook.

``python -m drywall_lab dialogue`` speaks the same dialogue to a program, one JSON request and one JSON reply a
line (``serve``; the contract of the spec's dialogue.md): ``{"new": ID}``, ``{"say": TEXT}``, ``{"choose": K}``.
A question carries ``options``: the commands the robot weighs, each one it would carry out as it stands, at most
``MAX_OPTIONS``, the likelier first; choosing one carries it out. An instruction longer than
``pipeline.MAX_INSTRUCTION_WORDS`` words or ``pipeline.MAX_INSTRUCTION_CHARS`` characters is refused before tagging (``run``, ``chat``
and ``dialogue`` alike), and a request that is not JSON, too long or of no known kind gets an ``error`` reply.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Callable, Iterable, TextIO

from drywall_lab.nlu.normalise import normalise
from drywall_lab.decision import DEFAULT_SETTINGS, Decision, DecisionSettings, decide_instruction
from drywall_lab.errors import Refusal
from drywall_lab.im import ActionHistory, RobotCommand
from drywall_lab.pipeline import too_long
from drywall_lab.site import STACK_NAMES, FOOT, Site, SiteState

YES = frozenset({"yes", "y", "yeah", "yep", "yup", "correct", "right", "ok", "okay", "sure", "do it", "go", "go ahead",
                 "affirmative", "confirm", "that's right", "yes please", "yes do it"})
#: Answers that pick an option by its place in the question.
ORDINAL_ANSWERS: dict[str, int] = {
    **{a: 0 for a in ("first", "the first", "the first one", "1", "a", "option 1", "one")},
    **{a: 1 for a in ("second", "the second", "the second one", "the other", "the other one", "other", "2", "b",
                      "option 2", "two", "the latter")},
    **{a: 2 for a in ("third", "the third", "the third one", "3", "c", "option 3", "three", "the last one")},
}
NO = frozenset({"no", "n", "nope", "cancel", "neither", "stop", "none", "negative", "don't", "neither of them",
                "none of them", "no neither", "nothing"})
#: The longest request line ``serve`` reads; the most options a question offers (a worker reads no longer list).
MAX_REQUEST_CHARS = 20_000
MAX_OPTIONS = 3


def _answer(text: str) -> str:
    return " ".join(w.lower().strip(".,!?") for w in text.split())


@dataclass
class Reply:
    """What the robot says to one line, and what it did: ``command`` when it acted; a question's ``options`` (the
    commands it weighs, each one it would carry out now); a refusal's ``reason``."""

    text: str
    command: RobotCommand | None = None
    question: bool = False
    options: list[RobotCommand] = field(default_factory=list)
    reason: str | None = None

    def as_contract(self) -> dict:
        """The reply as the dialogue contract writes it."""
        if self.command is not None:
            return {"kind": "command", "command": self.command.as_contract(), "text": self.text}
        if self.question:
            return {"kind": "question", "options": [c.as_contract() for c in self.options], "text": self.text}
        if self.reason is not None:
            return {"kind": "refusal", "reason": self.reason, "text": self.text}
        return {"kind": "nothing", "text": self.text}


def _keywords(command: RobotCommand) -> set[str]:
    """The words an answer may pick a command by: its ids, its stack and size, its placement."""
    words = {command.drywall_id, command.stud_id, command.stud_id[-2:], command.stud_id[-1:]}
    size = f"{command.w / 0.3048:g}x{command.l / 0.3048:g}"
    words |= {size, size.replace("x", "by")}
    placement = command.placement.value
    words |= {"vertical", "upright", "standing"} if placement.startswith("vertical") else {"horizontal", "lying",
                                                                                          "flat", "sideways"}
    words |= {"centre", "center", "middle", "centre-line", "centreline", "centerline"} if placement == "vertical_middle" \
        else {"top"} if placement == "horizontal_top" else {"bottom"} if placement == "horizontal_bottom" else {"left"}
    return words


def described(command: RobotCommand) -> str:
    """A command in the worker's terms: "panel 500321 on stud 500104, upright, edge on the stud's centre line"."""
    return f"panel {command.drywall_id} on stud {command.stud_id}, {command.placement.described}"


_ANSWER_FILLER = frozenset({"the", "one", "on", "its", "it", "a", "panel", "stud", "with", "edge", "line", "row", "of",
                            "please", "yes", "i", "mean", "meant", "that", "sheet", "in", "by", "x", "ft", "foot",
                            "feet", "to", "go", "put"})


def pick_by_words(answer: str, options: list[RobotCommand]) -> int | None:
    """The one option an answer names by what it says ("the 2x8", "the centre line", "500104"), or None."""
    said = [w for w in normalise(answer).words if w.lower() not in _ANSWER_FILLER]
    if not said:
        return None
    fits = [k for k, c in enumerate(options) if all(w.lower() in _keywords(c) for w in said)]
    return fits[0] if len(fits) == 1 else None


class Dialogue:
    """The worker and the robot, one line at a time, on one wall (``history``)."""

    def __init__(self, tagger=None, settings: DecisionSettings = DEFAULT_SETTINGS, site: Site | None = None) -> None:
        if tagger is None:
            from drywall_lab.nlu import default_tagger

            tagger = default_tagger()
        self.tagger = tagger
        self.settings = settings
        self.site = site
        self.history = ActionHistory(site)
        self.pending: list[RobotCommand] | None = None

    @property
    def state(self) -> SiteState:
        return self.history.state

    def _act(self, command: RobotCommand, how: str = "") -> Reply:
        self.history.record(command)
        self.pending = None
        return Reply(f"{how}Placing {command.drywall_id} on stud {command.stud_id}, {command.placement.described}.",
                     command)

    def new(self) -> Reply:
        """A fresh site: every panel stacked, nothing installed, no question open."""
        self.history = ActionHistory(self.site)
        self.pending = None
        return Reply("Ready: a fresh wall, every panel in its stack.")

    def choose(self, index: int | None) -> Reply:
        """The answer to the open question: its option ``index`` (carried out), or None for none of them."""
        if self.pending is None:
            raise ValueError("there is no open question to answer")
        if index is None:
            self.pending = None
            return Reply("Okay, I will not do that. What should I do instead?")
        if not 0 <= index < len(self.pending):
            raise ValueError(f"the question has {len(self.pending)} option(s): choose 0 to {len(self.pending) - 1} "
                             "or null")
        return self._act(self.pending[index], "Understood. ")

    def options(self, decision: Decision) -> list[RobotCommand]:
        """The commands a question weighs: those it asks about, then the other commands by probability; each one the
        robot would carry out as it stands, at most ``MAX_OPTIONS``."""
        mass = {o: q for o, q in decision.probabilities.items() if o[0] == "command"}
        ordered = [o for o in decision.options if o in mass]
        ordered += sorted((o for o in mass if o not in ordered), key=lambda o: -mass[o])
        out = []
        for o in ordered:
            try:
                command = RobotCommand.build(self.history.site, o[1], o[2], o[3])
                self.history.state.check_pickable(o[1])
                self.history.state.check_fits(o[1], o[2], o[3])
            except Refusal:
                continue
            out.append(command)
        return out[:MAX_OPTIONS]

    def instruction(self, text: str) -> Reply:
        """A new instruction (a question still open is dropped first): the command, a question, or a refusal."""
        self.pending = None
        refusal = too_long(text)
        if refusal is not None:
            return Reply(refusal.message, reason=refusal.reason)
        words = list(normalise(text).words)
        if not words:
            return Reply("I did not hear an instruction: which panel should I pick, and which stud does it go on?",
                         reason="undetermined")
        decision = decide_instruction(words, self.tagger, self.history, self.settings)
        if decision.acted:
            return self._act(decision.command)
        reason = decision.refusal.reason
        if reason == "unclear" or reason == "undetermined":
            options = self.options(decision)
            if reason == "unclear" or options:
                self.pending = options
                text = decision.refusal.message
                if options and reason == "undetermined":
                    text += " Did you mean " + ", or ".join(map(described, options)) + "?"
                return Reply(text, question=True, options=options)
        return Reply(decision.refusal.message, reason=reason)

    def say(self, text: str) -> Reply:
        """The robot's reply to one line from the worker (an instruction, or the answer to its question): "yes" or
        "no" to one option; "the first", "the centre line", "the 2x8", "neither" to several; a bare "yes" to
        several is no answer, and the robot asks which."""
        answer = _answer(text)
        if self.pending:
            options = self.pending
            if answer in NO:
                return self.choose(None)
            if answer in YES:
                if len(options) == 1:
                    return self.choose(0)
                return Reply("Which one: " + ", or ".join(f"({k + 1}) {described(c)}" for k, c in enumerate(options))
                             + "?", question=True, options=options)
            index = ORDINAL_ANSWERS.get(answer)
            if index is None:
                index = pick_by_words(text, options)
            if index is not None and index < len(options):
                return self.choose(index)
        elif self.pending is not None and answer in NO:
            return self.choose(None)
        return self.instruction(text)

    def respond(self, request: object) -> dict:
        """One request of the dialogue contract, one reply (a dict); a bad request gets an ``error`` reply and
        changes nothing."""
        if not isinstance(request, dict) or len(request) != 1:
            return _error("a request is one JSON object with one key: new, say or choose")
        (key, value), = request.items()
        if key == "new" and isinstance(value, (str, int)):
            return {"kind": "ready", "text": self.new().text}
        if key == "say" and isinstance(value, str):
            return self.instruction(value).as_contract()
        if key == "choose" and (value is None or (isinstance(value, int) and not isinstance(value, bool))):
            try:
                return self.choose(value).as_contract()
            except ValueError as e:
                return _error(str(e))
        return _error(f"unknown request {json.dumps(request)[:100]}: send new, say (text) or choose (an option's "
                      "index or null)")


def _error(text: str) -> dict:
    return {"kind": "error", "text": text}


def _lines(stream: TextIO, limit: int = MAX_REQUEST_CHARS) -> Iterable[str | None]:
    """The stream's lines; None for a line longer than ``limit`` (read to its end, never held whole)."""
    while True:
        line = stream.readline(limit + 1)
        if not line:
            return
        if len(line) > limit and not line.endswith("\n"):
            while True:  # the rest of the over-long line
                rest = stream.readline(limit)
                if not rest or rest.endswith("\n"):
                    break
            yield None
            continue
        yield line


def serve(dialogue: Dialogue, requests: TextIO, replies: TextIO) -> int:
    """The dialogue contract (``python -m drywall_lab dialogue``): one JSON reply a JSON request line, flushed."""
    for line in _lines(requests):
        if line is None:
            reply = _error(f"the request is longer than {MAX_REQUEST_CHARS:,} characters")
        elif not line.strip():
            continue
        else:
            try:
                request = json.loads(line)
            except ValueError:
                reply = _error("the request is not JSON: send one JSON object a line")
            else:
                reply = dialogue.respond(request)
        replies.write(json.dumps(reply, ensure_ascii=False) + "\n")
        replies.flush()
    return 0


# --- the wall in text -------------------------------------------------------------------------------------
COLUMN = FOOT / 3  #: metres a character stands for along the wall (4 in)
ROW = FOOT  #: metres a line stands for up the wall (1 ft)


def wall_text(state: SiteState) -> str:
    """The wall as the worker faces it (one character 4 in wide, one line 1 ft tall), then the stacks.

    Installed panels are drawn with their stack's letter (``L``, ``M``, ``R``), studs as ``|`` where no
    panel covers them; below, each stud's last two digits; then what is left in each stack (top last).
    """
    site = state.site
    width = int(round((site.wall_end_x + 2 * COLUMN) / COLUMN)) + 1
    height = int(round(site.studs[0].height / ROW))
    grid = [[" "] * width for _ in range(height)]

    def column(x: float) -> int:
        return int(round((x + COLUMN) / COLUMN))

    for stud in site.studs:
        for row in grid:
            row[column(stud.x_center)] = "|"
    for installed in state.installed:
        r = installed.rect
        letter = site.panel(installed.drywall_id).stack[0].upper()
        for line in range(height):
            z = (height - line - 0.5) * ROW
            if r.z_bottom <= z <= r.z_top:
                for c in range(column(r.x_left), column(r.x_right)):
                    grid[line][c] = letter
    labels = [" "] * width
    for stud in site.studs:
        c = column(stud.x_center)
        labels[c - 1:c + 1] = list(stud.stud_id[-2:])
    lines = ["".join(row).rstrip() for row in grid] + ["".join(labels).rstrip()]
    for name in STACK_NAMES:
        left = state.stacks[name]
        lines.append(f"{name:>6} stack ({site.stack_size(name)[0]:g} x {site.stack_size(name)[1]:g}): "
                     + (", ".join(left) + " (top last)" if left else "empty"))
    return "\n".join(lines)


# --- in a terminal and in a notebook ---------------------------------------------------------------------
def run_chat(dialogue: Dialogue, read: Callable[[str], str], out: TextIO) -> int:
    """The terminal dialogue: read lines until ``quit``/``exit`` or the end of input; the wall after each step."""
    print("Give an instruction (quit to stop).", file=out)
    print(wall_text(dialogue.state), file=out)
    while True:
        try:
            line = read("worker> ")
        except EOFError:
            break
        if _answer(line) in ("quit", "exit", "bye"):
            break
        reply = dialogue.say(line)
        print(f"robot> {reply.text}", file=out)
        if reply.command is not None:
            print(wall_text(dialogue.state), file=out)
    print(f"{len(dialogue.history)} panel(s) installed.", file=out)
    return 0


def chat_widget(dialogue: Dialogue | None = None):
    """The same dialogue in a notebook: a text box, a Send button, the conversation and the wall (ipywidgets)."""
    import ipywidgets as widgets

    dialogue = dialogue or Dialogue()
    box = widgets.Text(placeholder="Pick up the full-size drywall and put it on stud 500107", layout={"width": "70%"},
                       continuous_update=False)  # the value changes when the worker presses Enter
    send = widgets.Button(description="Send")
    log = widgets.Output()
    wall = widgets.Output()

    def show_wall() -> None:
        wall.clear_output()
        with wall:
            print(wall_text(dialogue.state))

    def on_send(_=None) -> None:
        text = box.value
        if not text.strip():
            return
        box.value = ""
        reply = dialogue.say(text)
        with log:
            print(f"worker> {text}\nrobot> {reply.text}")
        show_wall()

    send.on_click(on_send)
    box.observe(lambda change: on_send() if change["new"].strip() else None, "value")
    show_wall()
    ui = widgets.VBox([widgets.HBox([box, send]), log, wall])
    ui.dialogue, ui.send = dialogue, on_send  # for scripted use and tests
    return ui
