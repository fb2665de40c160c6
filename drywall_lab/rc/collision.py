"""Collision checking while planning: the robot, with the carried panel as part of it, against the site.

The paper's planner (MoveIt) checks collisions "while the target is considered as part of the
robot, so that the robot and the target object will not collide with their surroundings"
(Robot Control section). ``CollisionChecker`` does the same on a copy of the scene built from
the site tables (not from the running simulation): for each joint sample of a planned stage it
puts the robot there, puts the carried panel where the robot believes it holds it, and asks
MuJoCo's collision detection for contacts, with a safety clearance around the robot's links.
Contacts that are part of the job (``ContactWatch.expect``) are allowed.
"""
from __future__ import annotations

import mujoco
import numpy as np

from drywall_lab.im.command import RobotCommand
from drywall_lab.rc.contacts import ContactWatch
from drywall_lab.rc.scene import Scene, build_scene
from drywall_lab.site import SiteState

LINK_CLEARANCE = 0.03  #: m kept between the robot's links and anything else
PAD_CLEARANCE = 0.005  #: m for the lifter's pad, which works close to panels
PANEL_CLEARANCE = 0.003  #: m around the carried panel, except while it is set on the studs


class CollisionChecker:
    """The planning scene for one site state: ``first_collision(q)`` names a contact at joint values ``q``, if any."""

    def __init__(self, state: SiteState) -> None:
        self.state = state
        self.scene: Scene = build_scene(state)
        self.watch = ContactWatch(self.scene)
        m = self.scene.model
        robot = self.scene.robot_geom_mask
        self.base_margin = np.where(robot, LINK_CLEARANCE, 0.0)
        self.base_margin[self.scene.pad_geom] = PAD_CLEARANCE
        carriage = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "carriage_box")
        self.base_margin[carriage] = PAD_CLEARANCE  # it rides 2 cm above the floor, on the rail
        self.command: RobotCommand | None = None
        self.grip: np.ndarray | None = None
        self._free_adr = None
        m.geom_margin[:] = self.base_margin

    def reset(self) -> None:
        """Every panel back where the site tables put it (a plan may have moved the carried one)."""
        self.scene.data.qpos[:] = self.scene.model.qpos0

    def set_context(self, context: str, command: RobotCommand | None, grip: np.ndarray | None = None,
                    panel_pose: np.ndarray | None = None) -> None:
        """What the next samples are: the stage's contact context and, while carrying, the grip (the panel
        in the TCP frame); otherwise ``panel_pose`` (4x4) says where the command's panel lies (its stack, or
        its place once released)."""
        m = self.scene.model
        m.geom_margin[:] = self.base_margin
        self.command, self.grip = command, grip
        self.watch.expect(context, command, self.state, carrying=grip is not None)
        if command is None:
            return
        joint = m.body_jntadr[self.scene.panel_body[command.drywall_id]]
        self._free_adr = m.jnt_qposadr[joint]
        if grip is not None:
            m.geom_margin[self.scene.panel_geom[command.drywall_id]] = 0.0 if context == "set" else PANEL_CLEARANCE
        elif panel_pose is not None:
            self._put_panel(panel_pose)

    def _put_panel(self, P: np.ndarray) -> None:
        quat = np.zeros(4)
        mujoco.mju_mat2Quat(quat, np.ascontiguousarray(P[:3, :3]).reshape(9))
        d = self.scene.data
        d.qpos[self._free_adr:self._free_adr + 3] = P[:3, 3]
        d.qpos[self._free_adr + 3:self._free_adr + 7] = quat

    def first_collision(self, q: np.ndarray) -> str | None:
        """A description of the first unexpected contact (within the clearances) at ``q``, or None."""
        sc = self.scene
        m, d = sc.model, sc.data
        d.qpos[sc.qpos_index] = q
        mujoco.mj_kinematics(m, d)
        if self.grip is not None and self.command is not None:
            self._put_panel(sc.tcp_matrix() @ self.grip)
            mujoco.mj_kinematics(m, d)
        mujoco.mj_collision(m, d)
        for g1, g2, dist in self.watch.unexpected_now():
            return f"{sc.geom_name(g1)} would come within {dist * 1000:.0f} mm of {sc.geom_name(g2)}"
        return None


__all__ = ["CollisionChecker"]
