"""A dialogue with the robot (issue 12): an instruction, the robot's command or question, the worker's answer.

``Dialogue.say(text)`` takes what the worker types. A new instruction goes through the tagger and the
decision layer (``drywall_lab.decision``): the robot says the command it carries out, or asks one
question (refusal reason ``unclear``), or refuses with the IM's message. While a question is open the
next words answer it: "yes" (or "the first") carries out the command asked about, "the second" the
other one, "no" drops it; anything else is taken as a corrected instruction. Nothing is recorded
unless the robot acts. ``wall_text`` draws the wall and the stacks in text after each step;
``python -m drywall_lab chat`` runs the dialogue in a terminal and ``chat_widget`` in a notebook.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, TextIO

from drywall_lab.nlu.normalise import normalise
from drywall_lab.decision import DEFAULT_SETTINGS, Decision, DecisionSettings, decide_instruction
from drywall_lab.im import ActionHistory, RobotCommand
from drywall_lab.site import STACK_NAMES, FOOT, Site, SiteState, default_site

YES = frozenset({"yes", "y", "yeah", "yep", "yup", "correct", "right", "ok", "okay", "sure", "do it", "go", "go ahead",
                 "affirmative", "confirm", "that's right", "first", "the first", "the first one", "1", "a"})
SECOND = frozenset({"second", "the second", "the second one", "the other", "the other one", "other", "2", "b"})
NO = frozenset({"no", "n", "nope", "cancel", "neither", "stop", "none", "negative", "don't"})


def _answer(text: str) -> str:
    return " ".join(w.lower().strip(".,!?") for w in text.split())


@dataclass
class Reply:
    """What the robot says to one line, and what it did: ``command`` when it acted."""

    text: str
    command: RobotCommand | None = None
    question: bool = False


class Dialogue:
    """The worker and the robot, one line at a time, on one wall (``history``)."""

    def __init__(self, tagger=None, settings: DecisionSettings = DEFAULT_SETTINGS, site: Site | None = None) -> None:
        if tagger is None:
            from drywall_lab.nlu import default_tagger

            tagger = default_tagger()
        self.tagger = tagger
        self.settings = settings
        self.history = ActionHistory(site)
        self.pending: Decision | None = None

    @property
    def state(self) -> SiteState:
        return self.history.state

    def _act(self, command: RobotCommand, how: str = "") -> Reply:
        self.history.record(command)
        self.pending = None
        return Reply(f"{how}Placing {command.drywall_id} on stud {command.stud_id}, {command.placement.described}.",
                     command)

    def _choose(self, index: int) -> Reply:
        decision = self.pending
        option = decision.options[index]
        reading = next(r for r in decision.readings if r.outcome == option)
        return self._act(reading.interpretation.command, "Understood. ")

    def say(self, text: str) -> Reply:
        """The robot's reply to one line from the worker (an instruction, or the answer to its question)."""
        answer = _answer(text)
        if self.pending is not None:
            if answer in YES:
                return self._choose(0)
            if answer in SECOND and len(self.pending.options) > 1:
                return self._choose(1)
            if answer in NO:
                self.pending = None
                return Reply("Okay, I will not do that. What should I do instead?")
            self.pending = None  # anything else is a corrected instruction
        words = list(normalise(text).words)
        if not words:
            return Reply("I did not hear an instruction: which panel should I pick, and which stud does it go on?")
        decision = decide_instruction(words, self.tagger, self.history, self.settings)
        if decision.acted:
            return self._act(decision.command)
        if decision.action == "ask":
            self.pending = decision
            return Reply(decision.refusal.message, question=True)
        return Reply(decision.refusal.message)


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
