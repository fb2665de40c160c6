"""The paper's three demonstration layouts (Figs. 15-18) replayed through the whole pipeline and checked.

``replay_layout`` sends one layout (``drywall_lab.pipeline.paper_layouts``) through the tagger, the IM
rules and the simulated robot (``simulate_episode``) and compares what happened with what the layout
expects: every instruction gives its hand-checked command or refusal, every command is placed within
the project's tolerances (``POSITION_TOLERANCE``, ``ANGLE_TOLERANCE_DEG``), nothing is hit.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import pandas as pd

from drywall_lab.pipeline import WordTagger
from drywall_lab.rc.episode import EpisodeRun, simulate_episode
from drywall_lab.rc.placement import ANGLE_TOLERANCE_DEG, POSITION_TOLERANCE

#: Where the paper shows each layout's action history table.
HISTORY_FIGURES = {"layout1": "Fig. 16(e)", "layout2": "Fig. 17(c)", "layout3": "Fig. 18(c)"}


@dataclass
class LayoutReplay:
    """One layout carried out by the simulated robot, and how it compares with the layout's ``expected``."""

    layout: Mapping
    run: EpisodeRun

    @property
    def history_figure(self) -> str:
        """The paper's figure with this layout's action history table ("" for a layout not in the paper)."""
        return HISTORY_FIGURES.get(self.layout["id"], "")

    def problems(self) -> list[str]:
        """Everything that is not as the layout expects, one sentence each (none: the replay is right)."""
        found = []
        for k, (got, want) in enumerate(zip(self.run.outcomes(), self.layout["expected"])):
            if got != want:
                found.append(f"step {k}: expected {want}, got {got}")
        if len(self.run.steps) != len(self.layout["expected"]):
            found.append(f"{len(self.run.steps)} steps, the layout expects {len(self.layout['expected'])}")
        for step in self.run.steps:
            r = step.result
            if r is None:
                continue
            if not r.success:
                found.append(f"step {step.step}: {r.command.drywall_id} not placed ({r.failure})")
            if r.position_error_mm > POSITION_TOLERANCE * 1000 or r.angle_error_deg > ANGLE_TOLERANCE_DEG:
                found.append(f"step {step.step}: off by {r.position_error_mm:.2f} mm and {r.angle_error_deg:.3f} deg "
                             f"(tolerance {POSITION_TOLERANCE * 1000:g} mm, {ANGLE_TOLERANCE_DEG:g} deg)")
            found += [f"step {step.step}: unexpected contact, {e}" for e in r.unexpected_contacts]
        return found

    @property
    def ok(self) -> bool:
        return not self.problems()

    def report(self) -> str:
        """A few lines: the outcome of each instruction against the layout, then the largest errors against
        the tolerances, then anything that went wrong."""
        lines = [f"{self.layout['id']} ({self.layout.get('paper', '')})"]
        for step, want in zip(self.run.steps, self.layout["expected"]):
            lines.append(f"  step {step.step}: {step.status:<15} {'as expected' if self.run.outcomes()[step.step] == want else 'NOT as expected'}")
        placed = [r for r in self.run.placements if r.success]
        if placed:
            lines.append(f"  {len(placed)} placed; largest errors {max(r.position_error_mm for r in placed):.2f} mm "
                         f"(tolerance {POSITION_TOLERANCE * 1000:g} mm) and {max(r.angle_error_deg for r in placed):.3f} "
                         f"deg (tolerance {ANGLE_TOLERANCE_DEG:g} deg); "
                         f"{sum(len(r.unexpected_contacts) for r in self.run.placements)} unexpected contacts")
        lines += [f"  problem: {p}" for p in self.problems()]
        return "\n".join(lines)


def replay_layout(layout: Mapping, tagger: WordTagger | None = None, record_fps: float | None = None) -> LayoutReplay:
    """The layout through NLU (``tagger``; its hand-checked tags when None), IM and the simulated robot, from
    the fresh site, recorded at ``record_fps`` frames a second if given."""
    return LayoutReplay(layout, simulate_episode(layout, tagger, record_fps=record_fps))


def placements_table(replays: Sequence[LayoutReplay]) -> pd.DataFrame:
    """Every instruction the robot carried out, layout by layout: the command, the outcome, the errors (mm,
    deg) and the simulated seconds (refusals, which moved nothing, left out)."""
    table = pd.concat([r.run.table().assign(layout=r.layout["id"]) for r in replays], ignore_index=True)
    table = table[table.outcome != "no motion"].reset_index(drop=True)
    return table[["layout", "step", "command", "outcome", "pos_err_mm", "ang_err_deg", "sim_s"]]
