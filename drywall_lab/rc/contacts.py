"""Watching contacts: the robot and the carried panel against studs, panels and the floor.

The paper's planner treats the carried panel as part of the robot when it checks for
collisions (Robot Control section). Here the simulation watches every contact that involves
a robot geom or the panel being carried, and reports those that are not part of the job:

- ``pick``: the lifter on the target panel, the target on the panel below it (or the floor);
- ``carry``: the lifter (pad, stem, flange) on the carried panel;
- ``set``: the carried panel on the studs behind it, on the floor when its bottom edge is at
  z = 0, and against installed panels whose edges its placement meets; the lifter on it;
- ``free``: nothing.

Everything else is an unexpected contact, reported once per pair of geoms with when it was
first seen, in which stage, for how many control steps, and how deep it went.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from drywall_lab.im.command import RobotCommand
from drywall_lab.rc.scene import Scene
from drywall_lab.site import TOLERANCE, Rect, SiteState

EDGE_TOLERANCE = 1e-3  #: m: rectangles this close count as touching


@dataclass
class ContactEvent:
    """One pair of geoms that touched when they should not have."""

    geom1: str
    geom2: str
    stage: str
    first_time: float  # simulated seconds
    steps: int  # control steps during which they touched
    max_depth: float  # m, deepest penetration

    def __str__(self) -> str:
        return (f"{self.geom1} against {self.geom2} in '{self.stage}' at t = {self.first_time:.2f} s "
                f"({self.steps} steps, {self.max_depth * 1000:.1f} mm deep)")


def _touching(a: Rect, b: Rect) -> bool:
    """The two rectangles meet along an edge (or overlap)."""
    return (min(a.x_right, b.x_right) - max(a.x_left, b.x_left) > -EDGE_TOLERANCE
            and min(a.z_top, b.z_top) - max(a.z_bottom, b.z_bottom) > -EDGE_TOLERANCE)


class ContactWatch:
    """Classifies the simulation's contacts each control step (vectorised over the contact list)."""

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        n = scene.model.ngeom
        self.robot = scene.robot_geom_mask
        self.watched_base = self.robot[:, None] | self.robot[None, :]
        self.watched = self.watched_base.copy()
        self.expected = np.zeros((n, n), dtype=bool)
        self.events: dict[tuple[int, int], ContactEvent] = {}
        m = scene.model
        self.tool_geoms = [g for g in range(n) if m.geom_bodyid[g] == scene.tool_body and self.robot[g]]

    def _allow(self, a: int, b: int) -> None:
        self.expected[a, b] = self.expected[b, a] = True

    def expect(self, context: str, command: RobotCommand | None, state: SiteState, carrying: bool) -> None:
        """Set which contacts are part of the job for the next stage (see the module docstring)."""
        sc = self.scene
        n = sc.model.ngeom
        self.expected = np.zeros((n, n), dtype=bool)
        self.watched = self.watched_base.copy()
        if command is None:
            return
        target = sc.panel_geom[command.drywall_id]
        if carrying:
            self.watched[target, :] = self.watched[:, target] = True
        if context in ("pick", "carry", "set"):  # the lifter (pad, stem, flange) on the panel it holds
            for g in self.tool_geoms:
                self._allow(g, target)
        if context == "pick":
            panel = state.site.panel(command.drywall_id)
            below = [p.drywall_id for p in state.site.stack(panel.stack) if p.level == panel.level - 1]
            if below:
                self._allow(target, sc.panel_geom[below[0]])
            else:
                self._allow(target, sc.floor_geom)
        if context == "set":
            rect = Rect(command.x_left, command.x_right, command.z_bottom, command.z_top)
            for stud in state.site.studs:
                if stud.x_right_line > rect.x_left - TOLERANCE and stud.x_left_line < rect.x_right + TOLERANCE:
                    self._allow(target, sc.stud_geom[stud.stud_id])
            if rect.z_bottom <= TOLERANCE:
                self._allow(target, sc.floor_geom)
            for item in state.installed:
                if item.drywall_id != command.drywall_id and _touching(rect, item.rect):
                    self._allow(target, sc.panel_geom[item.drywall_id])

    def check(self, stage: str, time: float) -> None:
        """Record the unexpected contacts present now."""
        d = self.scene.data
        ncon = d.ncon
        if ncon == 0:
            return
        pairs = d.contact.geom[:ncon]
        g1, g2 = pairs[:, 0], pairs[:, 1]
        bad = self.watched[g1, g2] & ~self.expected[g1, g2]
        if not bad.any():
            return
        seen: set[tuple[int, int]] = set()
        for i in np.nonzero(bad)[0]:
            key = (int(min(g1[i], g2[i])), int(max(g1[i], g2[i])))
            depth = max(0.0, -float(d.contact.dist[i]))
            event = self.events.get(key)
            if event is None:
                self.events[key] = ContactEvent(self.scene.geom_name(key[0]), self.scene.geom_name(key[1]),
                                                stage, time, 1, depth)
                seen.add(key)
                continue
            event.max_depth = max(event.max_depth, depth)
            if key not in seen:
                event.steps += 1
                seen.add(key)

    def unexpected_now(self) -> list[tuple[int, int, float]]:
        """The unexpected contacts in the contact list now: ``(geom1, geom2, distance)``."""
        d = self.scene.data
        ncon = d.ncon
        if ncon == 0:
            return []
        pairs = d.contact.geom[:ncon]
        g1, g2 = pairs[:, 0], pairs[:, 1]
        bad = np.nonzero(self.watched[g1, g2] & ~self.expected[g1, g2])[0]
        return [(int(g1[i]), int(g2[i]), float(d.contact.dist[i])) for i in bad]

    def take_events(self) -> list[ContactEvent]:
        """The events recorded since the last call, oldest first."""
        events = sorted(self.events.values(), key=lambda e: e.first_time)
        self.events = {}
        return events
