"""From instructions to motion: an episode's interpretations carried out by the simulated robot.

The paper's whole pipeline (Fig. 1): NLU tags each instruction, IM turns the tags into a
command (or refuses), RC carries the command out, and "a human operator can give the next
instructions after target placement is completed" (Robot Control section). A refused
instruction never reaches the robot: nothing moves, and the simulated clock does not advance.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from drywall_lab.im import ActionHistory, Interpretation
from drywall_lab.pipeline import WordTagger, map_gold_episode, run_episode
from drywall_lab.rc.cell import RobotCell
from drywall_lab.rc.placement import PlacementResult


@dataclass
class EpisodeStep:
    """One instruction: what IM made of it and, if it was accepted, what the robot did."""

    step: int
    interpretation: Interpretation
    result: PlacementResult | None  # None: refused, nothing moved
    sim_time_before: float
    sim_time_after: float
    robot_moved: bool
    instruction: str = ""  # as the worker said it (the words joined, if not given)

    @property
    def text(self) -> str:
        return self.instruction or " ".join(self.interpretation.words)


@dataclass
class EpisodeRun:
    """A whole episode in one robot cell (its recording, if any, holds the film of all of it)."""

    episode_id: str
    cell: RobotCell
    steps: list[EpisodeStep] = field(default_factory=list)

    @property
    def placements(self) -> list[PlacementResult]:
        return [s.result for s in self.steps if s.result is not None]

    @property
    def history(self) -> ActionHistory:
        """The action history of the accepted commands (the paper's nine fields, Fig. 16(e))."""
        history = ActionHistory(self.cell.site)
        for s in self.steps:
            if s.interpretation.command is not None:
                history.record(s.interpretation.command)
        return history

    def outcomes(self) -> list[dict]:
        """Per instruction, the command ``{"drywall_id", "stud_id", "placement"}`` or ``{"refusal": reason}``
        (the shape of a layout's ``expected``)."""
        return [s.interpretation.command.as_contract() if s.interpretation.command is not None
                else {"refusal": s.interpretation.refusal.reason} for s in self.steps]

    @property
    def all_placed(self) -> bool:
        return all(r.success for r in self.placements)

    def table(self) -> pd.DataFrame:
        """One row per instruction: the command or refusal, and the placement's outcome."""
        rows = []
        for s in self.steps:
            i, r = s.interpretation, s.result
            row = {"step": s.step, "instruction": s.text}
            if i.command is None:
                row.update(command=f"refused ({i.refusal.reason})", outcome="no motion", pos_err_mm=np.nan,
                           ang_err_deg=np.nan, sim_s=s.sim_time_after - s.sim_time_before)
            else:
                c = i.command
                row.update(command=f"{c.drywall_id} -> {c.stud_id}, {c.placement.value}",
                           outcome="placed" if r.success else f"failed: {r.failure}",
                           pos_err_mm=round(r.position_error_mm, 3), ang_err_deg=round(r.angle_error_deg, 4),
                           sim_s=round(r.sim_time, 1))
            rows.append(row)
        return pd.DataFrame(rows)


def carry_out(interpretations: Sequence[Interpretation], cell: RobotCell, episode_id: str = "",
              instructions: Sequence[str] | None = None) -> EpisodeRun:
    """Execute the accepted commands in order; a refused instruction is skipped without any motion."""
    run = EpisodeRun(episode_id, cell)
    texts = list(instructions) if instructions is not None else [""] * len(interpretations)
    for step, (interpretation, text) in enumerate(zip(interpretations, texts)):
        before_t, before_q = cell.time, cell.scene.data.qpos.copy()
        result = cell.execute(interpretation.command) if interpretation.command is not None else None
        moved = bool(cell.time != before_t or not np.array_equal(before_q, cell.scene.data.qpos))
        run.steps.append(EpisodeStep(step, interpretation, result, before_t, cell.time, moved, text))
    return run


def simulate_episode(episode: Mapping, tagger: WordTagger | None = None, record_fps: float | None = None) -> EpisodeRun:
    """An episode ``{"id", "instructions"}`` through NLU (``tagger``), IM and RC, from the fresh site.

    Without a tagger the episode's own gold ``words``/``tags`` are used (the paper's layouts carry them).
    """
    interpretations = map_gold_episode(episode)[0] if tagger is None else run_episode(episode, tagger)
    return carry_out(interpretations, RobotCell(record_fps=record_fps), str(episode.get("id", "")),
                     episode.get("instructions"))
