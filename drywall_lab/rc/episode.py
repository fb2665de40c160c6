"""From instructions to motion: an episode carried out step by step by the simulated robot.

The paper's whole pipeline (Fig. 1): NLU tags each instruction, IM turns the tags into a
command (or refuses), RC carries the command out, and "a human operator can give the next
instructions after target placement is completed" (Robot Control section). So each step here
is: tag the instruction, interpret it against the action history, let the robot carry the
command out, and record the command in the history only if the placement succeeded. The
history and the robot cell's site state therefore always agree while the episode goes on.

- A refused instruction never reaches the robot: nothing moves, the simulated clock does not
  advance, the history is unchanged, and the episode goes on (spec section 6).
- A placement that fails before the panel left its stack, without touching anything it should
  not have, and with the robot back in its ready posture (no collision-free motion found while
  planning, the grip failed, no safe carry from the grip the robot measured) leaves the site and
  the history as they were: the episode goes on, and a later instruction may ask again.
- Any other failure (the panel slipped, hit something, ended off its pose, or the robot could not
  get back clear of it; or anything was hit at all) means the site may no longer be what the tables
  say, so the robot stops: the remaining instructions are reported as ``not carried out``; they
  are neither interpreted nor executed. The cell then shows the panel where it really is (fastened
  off its pose, say) while the history holds only the placements that succeeded; that difference
  is why the robot stops (``goes_on_after``).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from drywall_lab.nlu.normalise import normalise
from drywall_lab.decision import interpret_instruction
from drywall_lab.im import ActionHistory, InformationMapper, Interpretation
from drywall_lab.pipeline import WordTagger
from drywall_lab.rc.cell import RobotCell
from drywall_lab.rc.placement import PlacementResult


PLACED, FAILED, REFUSED, NOT_CARRIED_OUT = "placed", "failed", "refused", "not carried out"


def goes_on_after(result: PlacementResult) -> bool:
    """Whether the episode goes on after this placement (see the module's docstring): it succeeded, or it
    failed with the panel still on its stack, nothing hit and the robot back in its ready posture."""
    return result.success or (not result.panel_lifted and not result.unexpected_contacts and result.robot_clear)


@dataclass
class EpisodeStep:
    """One instruction: what IM made of it and, if it was accepted, what the robot did.

    ``interpretation`` is None for a step not carried out (the robot had stopped before it).
    """

    step: int
    interpretation: Interpretation | None
    result: PlacementResult | None  # None: refused or not carried out, nothing moved
    sim_time_before: float
    sim_time_after: float
    robot_moved: bool
    instruction: str = ""  # as the worker said it (the words joined, if not given)

    @property
    def text(self) -> str:
        if self.instruction or self.interpretation is None:
            return self.instruction
        return " ".join(self.interpretation.words)

    @property
    def status(self) -> str:
        """``placed``, ``failed``, ``refused`` or ``not carried out``."""
        if self.interpretation is None:
            return NOT_CARRIED_OUT
        if self.interpretation.command is None:
            return REFUSED
        return PLACED if self.result.success else FAILED


@dataclass
class EpisodeRun:
    """A whole episode in one robot cell (its recording, if any, holds the film of all of it).

    The steps were carried out one by one: tagged, interpreted against ``history``, executed, and
    recorded in ``history`` only when the placement succeeded. A refusal, or a failure before the
    panel left its stack, lets the episode go on; after any other failure the robot stopped
    (``stopped_after`` is that step) and the later steps are ``not carried out``.
    """

    episode_id: str
    cell: RobotCell
    steps: list[EpisodeStep] = field(default_factory=list)
    mapper: InformationMapper | None = None  # the IM with the episode's action history
    stopped_after: int | None = None  # the step whose failure stopped the robot

    def __post_init__(self) -> None:
        if self.mapper is None:
            self.mapper = InformationMapper(history=history_of(self.cell))

    @property
    def placements(self) -> list[PlacementResult]:
        return [s.result for s in self.steps if s.result is not None]

    @property
    def history(self) -> ActionHistory:
        """The action history of the placements that succeeded (the paper's nine fields, Fig. 16(e)); a copy."""
        return self.mapper.history.copy()

    def outcomes(self) -> list[dict | None]:
        """What IM made of each instruction: ``{"drywall_id", "stud_id", "placement"}`` or ``{"refusal": reason}``
        (the shape of a layout's ``expected``), whatever the robot then did; None for a step not carried out."""
        return [None if s.interpretation is None
                else s.interpretation.command.as_contract() if s.interpretation.command is not None
                else {"refusal": s.interpretation.refusal.reason} for s in self.steps]

    @property
    def all_placed(self) -> bool:
        """Every accepted command was placed (and no step was left undone)."""
        return all(s.status in (PLACED, REFUSED) for s in self.steps)

    def table(self) -> pd.DataFrame:
        """One row per instruction: the command or refusal, the placement's outcome, and its notes
        (re-planning errors, plans taken up again)."""
        rows = []
        for s in self.steps:
            i, r = s.interpretation, s.result
            row = {"step": s.step, "instruction": s.text}
            if i is None:
                row.update(command="not interpreted", outcome=f"not carried out: the robot stopped after step "
                           f"{self.stopped_after}", pos_err_mm=np.nan, ang_err_deg=np.nan, sim_s=0.0, notes="")
            elif i.command is None:
                row.update(command=f"refused ({i.refusal.reason})", outcome="no motion", pos_err_mm=np.nan,
                           ang_err_deg=np.nan, sim_s=s.sim_time_after - s.sim_time_before, notes="")
            else:
                c = i.command
                outcome = "placed" if r.success else f"failed: {r.failure}"
                if s.step == self.stopped_after:
                    outcome += "; the robot stopped"
                row.update(command=f"{c.drywall_id} -> {c.stud_id}, {c.placement.value}", outcome=outcome,
                           pos_err_mm=round(r.position_error_mm, 3), ang_err_deg=round(r.angle_error_deg, 4),
                           sim_s=round(r.sim_time, 1), notes="; ".join(r.notes))
            rows.append(row)
        return pd.DataFrame(rows)

    # --- carrying the episode out ------------------------------------------------------------------
    def carry_out(self, words: Sequence[str], tags: Sequence[str], instruction: str = "",
                  interpretation: Interpretation | None = None) -> EpisodeStep:
        """The next step: interpret the tagged words against the history (or take ``interpretation``, made
        against it, as it is), let the robot carry the command out, and record it in the history if the
        placement succeeded (see the module's docstring)."""
        cell = self.cell
        step = len(self.steps)
        before_t, before_q = cell.time, cell.scene.data.qpos.copy()
        if self.stopped_after is not None:
            done = EpisodeStep(step, None, None, before_t, before_t, False, instruction)
            self.steps.append(done)
            return done
        if interpretation is None:
            interpretation = self.mapper.interpret(words, tags)
        result = None
        if interpretation.command is not None:
            result = cell.execute(interpretation.command)  # the history and the cell agree: no Refusal here
            if result.success:
                self.mapper.history.record(interpretation.command)
            if not goes_on_after(result):
                self.stopped_after = step
        moved = bool(cell.time != before_t or not np.array_equal(before_q, cell.scene.data.qpos))
        done = EpisodeStep(step, interpretation, result, before_t, cell.time, moved, instruction)
        self.steps.append(done)
        return done


def history_of(cell: RobotCell) -> ActionHistory:
    """The action history that leads to the cell's site state (its installed panels, in order)."""
    history = ActionHistory.from_commands([{"drywall_id": i.drywall_id, "stud_id": i.stud_id,
                                            "placement": i.placement} for i in cell.state.installed], cell.site)
    if history.state != cell.state:
        raise ValueError("the robot cell's site state is not one an action history leads to")
    return history


def simulate_episode(episode: Mapping, tagger: WordTagger | None = None, record_fps: float | None = None,
                     cell: RobotCell | None = None) -> EpisodeRun:
    """An episode ``{"id", "instructions"}`` through NLU (``tagger``), IM and RC, one instruction at a time.

    Each instruction is tagged and interpreted as ``run`` does it (``interpret_instruction``) against the
    history of the placements that succeeded so far. Without a tagger the episode's own gold
    ``words``/``tags`` are used (the paper's layouts carry them). ``cell`` is the robot cell to use (a fresh
    site, recorded at ``record_fps``, when None).
    """
    instructions = list(episode.get("instructions") or [])
    if tagger is None and ("words" not in episode or "tags" not in episode):
        raise ValueError(f"episode {episode.get('id', '')!r} has no gold \"words\" and \"tags\": give a tagger")
    run = EpisodeRun(str(episode.get("id", "")), cell if cell is not None else RobotCell(record_fps=record_fps))
    gold = list(zip(episode["words"], episode["tags"])) if tagger is None else []
    n = len(gold) if tagger is None else len(instructions)

    def step_input(k: int) -> tuple[Sequence[str], Sequence[str], Interpretation | None]:
        """The words, the tags and (through a tagger) the interpretation of instruction ``k``, made now
        against the history of the placements that succeeded so far."""
        if tagger is None:
            return gold[k][0], gold[k][1], None
        interpretation = interpret_instruction(list(normalise(instructions[k]).words), tagger, run.mapper.history)
        return list(interpretation.words), list(interpretation.tags), interpretation

    for k in range(n):
        stopped = run.stopped_after is not None  # then the step is not carried out, not even tagged
        words, tags, interpretation = ([], [], None) if stopped else step_input(k)
        run.carry_out(words, tags, instructions[k] if k < len(instructions) else "", interpretation)
    return run
