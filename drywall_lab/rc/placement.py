"""The result of one simulated placement, and how its error is measured.

A placement succeeds when the vacuum gripped the panel, the panel did not slip on the pad,
no unexpected contact happened (``drywall_lab.rc.contacts``), and, measured after the
release and a short settle, the panel's centre lies within ``POSITION_TOLERANCE`` of the
command's place pose and its orientation within ``ANGLE_TOLERANCE_DEG``. A panel that ends
off its pose is a failure, whatever the robot believed it did.

The reasons a placement fails (``PlacementResult.failure``; the code before any colon):

- ``unreachable``: no collision-free motion, found while planning; before any motion, or with the
  panel gripped on its stack when neither the carry re-planned from the measured grip nor the
  first plan's carry is safe (the vacuum then lets go and the pad withdraws);
- ``grip_failed``: the pad did not seal on the panel (the pad withdraws);
- ``slipped``, ``off_pose``, ``collision``: measured once the panel was fastened (see above);
- ``retreat_blocked``: the panel is fastened but no safe way back from it could be planned, so the
  robot stays where it stopped.

``panel_lifted`` says whether the panel left its stack and ``robot_clear`` whether the robot
ended in its ready posture; ``notes`` records what did not go as first planned (a re-planning
error, a plan taken up again), for the worker and the episode table.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import mujoco
import numpy as np

from drywall_lab.im.command import RobotCommand
from drywall_lab.rc.contacts import ContactEvent
from drywall_lab.rc.recording import JointTrace
from drywall_lab.site import Pose

POSITION_TOLERANCE = 0.005  #: m
ANGLE_TOLERANCE_DEG = 0.5  #: degrees
SLIP_TOLERANCE = 0.001  #: m: the panel's drift on the pad between grip and release


def pose_error(actual: Pose, target: Pose) -> tuple[float, float]:
    """Distance between the centres (m) and the angle of the rotation between the orientations (deg)."""
    pos = float(np.linalg.norm(np.subtract(actual.position, target.position)))
    q_inv = np.zeros(4)
    mujoco.mju_negQuat(q_inv, np.asarray(target.quaternion, dtype=float))
    rel = np.zeros(4)
    mujoco.mju_mulQuat(rel, q_inv, np.asarray(actual.quaternion, dtype=float))
    angle = 2 * math.atan2(float(np.linalg.norm(rel[1:])), abs(float(rel[0])))
    return pos, math.degrees(angle)


@dataclass
class PlacementResult:
    """What happened when the robot carried out one ``RobotCommand``.

    Errors are measured on the simulated panel after it was released and left to settle:
    ``position_error_mm`` between its centre and the place pose's, ``angle_error_deg`` the
    angle of the rotation between the two orientations. ``sim_time`` is simulated seconds,
    ``wall_time`` the real seconds it took (planning included).
    """

    command: RobotCommand
    success: bool
    failure: str | None
    final_pose: Pose | None
    position_error_mm: float
    angle_error_deg: float
    slip_mm: float
    sim_time: float
    wall_time: float
    base_moves: int
    unexpected_contacts: list[ContactEvent] = field(default_factory=list)
    trace: JointTrace = field(default_factory=JointTrace)
    panel_lifted: bool = False  #: the panel left its stack
    robot_clear: bool = True  #: the robot ended in its ready posture (False: it stopped where it was)
    notes: list[str] = field(default_factory=list)  #: re-planning errors and plans taken up again
    sim_start: float = 0.0  #: the cell's simulated clock (s) when the placement began (trace times count from it)

    @property
    def realtime_factor(self) -> float:
        """Simulated seconds per wall-clock second."""
        return self.sim_time / self.wall_time if self.wall_time > 0 else math.inf

    def summary(self) -> dict:
        """One row for a table of placements."""
        c = self.command
        return {
            "drywall_id": c.drywall_id,
            "stud_id": c.stud_id,
            "placement": c.placement.value,
            "success": self.success,
            "failure": self.failure or "",
            "pos_err_mm": round(self.position_error_mm, 3),
            "ang_err_deg": round(self.angle_error_deg, 4),
            "slip_mm": round(self.slip_mm, 3),
            "base_moves": self.base_moves,
            "unexpected_contacts": len(self.unexpected_contacts),
            "sim_s": round(self.sim_time, 2),
            "wall_s": round(self.wall_time, 2),
            "notes": "; ".join(self.notes),
        }

    def __str__(self) -> str:
        status = "placed" if self.success else f"FAILED ({self.failure})"
        notes = f" ({'; '.join(self.notes)})" if self.notes else ""
        return (f"{self.command}: {status}; error {self.position_error_mm:.2f} mm, {self.angle_error_deg:.3f} deg; "
                f"{self.sim_time:.1f} s simulated in {self.wall_time:.1f} s{notes}")


def judge(grip_ok: bool, slip_mm: float, contacts: list[ContactEvent], pos_mm: float, ang_deg: float) -> str | None:
    """The reason a placement failed, or None if it succeeded (see the module docstring)."""
    if not grip_ok:
        return "grip_failed"
    if slip_mm > SLIP_TOLERANCE * 1000:
        return "slipped"
    if pos_mm > POSITION_TOLERANCE * 1000 or ang_deg > ANGLE_TOLERANCE_DEG:
        return "off_pose"
    if contacts:
        return "collision"
    return None
