"""The robot cell: the simulated site with its robot, carrying out ``RobotCommand`` s one after another.

``RobotCell.execute(command)`` is the paper's RC module for one command (Fig. 1: IM -> RC):
it checks the command against the site as it is now (a ``Refusal`` before any motion if it
cannot be carried out), plans the whole placement (``MotionPlanner``; an unreachable command
fails before any motion), then drives the simulated robot through it: the joint servos track
the planned trajectory with velocity and gravity feed-forward (the payload's weight included
once it is gripped), the vacuum grips and lets go, the screws fasten the panel where it
actually is, the contacts are watched, and the placed panel is measured.

Once a placement has begun it ends in a ``PlacementResult``, never an exception: a failed grip
or a carry that cannot be planned safely from the measured grip lets go of the panel on its
stack and withdraws the pad; a re-planning error is recorded in the result's ``notes``, and the
first plan is taken up instead only if it still passes the collision check
(``MotionPlanner.verified``). Every stage the robot runs has been checked for collisions
(``run_stage`` refuses any other). ``state`` changes only when the panel is fastened to the wall.
"""
from __future__ import annotations

import time as wallclock
from typing import Mapping

import mujoco
import numpy as np

from drywall_lab.im.command import RobotCommand
from drywall_lab.rc.contacts import ContactWatch
from drywall_lab.rc.motion import MotionPlanner, PlacementPlan, PlanningError, Stage, believed_grip
from drywall_lab.rc.placement import PlacementResult, judge, pose_error
from drywall_lab.rc.recording import JointTrace, Recording
from drywall_lab.rc.robot import ArmIK, ServoGains, pose_matrix
from drywall_lab.rc.scene import Scene, build_scene, panel_mass
from drywall_lab.rc.settings import CONTROL_PERIOD
from drywall_lab.site import SiteState, default_site

GRIP_GAP = (-0.002, 0.003)  #: m: the pad seals when its face is this close to the panel's face
GRIP_ALIGNMENT = np.cos(np.radians(5.0))  #: the pad's normal within 5 deg of the face's
VACUUM_TIME = 0.3  #: s for the vacuum to build up (and to let go)
SETTLE_TIME = 0.5  #: s of rest before the placed panel is measured
SETTLED = 2e-5  #: m or rad: the servos count as settled when every joint is this close to its set point
TRACE_PERIOD = 0.02  #: s between samples of the joint trace


class RobotCell:
    """A simulated drywall site (``state``) with the rail-mounted arm, ready for commands.

    ``record_fps`` records body poses for an animation (``drywall_lab.viz``); ``None`` records
    nothing. ``servo_gains`` gives some joints' servos other gains than ``robot.SERVOS`` (notebook 05's
    exercise). The cell keeps its own ``state``: after each placement the panel is on the wall.
    """

    def __init__(self, state: SiteState | None = None, rail_x: float = 0.0, record_fps: float | None = None,
                 servo_gains: Mapping[str, ServoGains] | None = None) -> None:
        self.state = state or default_site().fresh()
        self.site = self.state.site
        self.ik = ArmIK()
        self.planner = MotionPlanner(self.site, self.ik)
        self.scene: Scene = build_scene(self.state, rail_x, self.ik.home[1:])
        if servo_gains:
            self.scene.set_servo_gains(servo_gains)
        self.watch = ContactWatch(self.scene)
        self.recording = Recording.for_model(self.scene.model, record_fps) if record_fps else None
        self.results: list[PlacementResult] = []
        self.steps_per_control = max(1, round(CONTROL_PERIOD / self.scene.model.opt.timestep))
        self.control_period = self.steps_per_control * self.scene.model.opt.timestep
        self._payload: tuple[float, np.ndarray] | None = None  # (mass, believed panel pose in the TCP frame)
        self._q_set = self.scene.q
        self._jacp = np.zeros((3, self.scene.model.nv))
        self._stage_name = "start"
        self._trace: JointTrace | None = None
        self._trace_next = 0.0
        self.hold(SETTLE_TIME)  # the stacks come to rest on the floor

    @property
    def time(self) -> float:
        """Simulated seconds since the cell was built."""
        return float(self.scene.data.time)

    # --- the servo loop ---------------------------------------------------------------
    def _feedforward(self) -> np.ndarray:
        """Joint torques that hold the arm (and its payload, as the robot believes it) against gravity."""
        sc = self.scene
        d = sc.data
        tau = d.qfrc_bias[sc.dof_index].copy()
        if self._payload is not None:
            mass, grip = self._payload
            com = (sc.tcp_matrix() @ grip)[:3, 3]
            mujoco.mj_jac(sc.model, d, self._jacp, None, com, sc.tool_body)
            tau += self._jacp[:, sc.dof_index].T @ np.array([0.0, 0.0, mass * 9.81])
        return tau

    def _control_step(self, q_set: np.ndarray, qd_set: np.ndarray) -> None:
        sc = self.scene
        d = sc.data
        d.ctrl[sc.actuator_index] = q_set + (sc.kv * qd_set + self._feedforward()) / sc.kp
        mujoco.mj_step(sc.model, d, nstep=self.steps_per_control)
        self.watch.check(self._stage_name, d.time)
        if self.recording is not None and self.recording.due(d.time):
            self.recording.capture(d, float(d.time))
        if self._trace is not None and d.time >= self._trace_next:
            self._trace.add(float(d.time - self._trace_start), sc.q, q_set.copy())
            self._trace_next = d.time + TRACE_PERIOD

    def run_stage(self, stage: Stage) -> None:
        """Track one stage's trajectory to its end; a ``ValueError`` (and no motion) for a stage that was not
        checked for collisions (plan it inside ``MotionPlanner.checking``)."""
        if not stage.collision_checked:
            raise ValueError(f"stage {stage.name!r} was not checked for collisions: plan it with "
                             "MotionPlanner inside MotionPlanner.checking(state)")
        self._stage_name = stage.name
        start = self.time
        t = 0.0
        while t < stage.duration:
            q, qd = stage.at(t + self.control_period)
            self._control_step(q, qd)
            t += self.control_period
        self._q_set = stage.end.copy()
        if self._trace is not None and stage.duration > 0:
            self._trace.stages.append((stage.name, start - self._trace_start, self.time - self._trace_start))

    def hold(self, seconds: float, until_settled: bool = False) -> None:
        """Hold the last set point for ``seconds`` (or less, once settled, with ``until_settled``)."""
        zero = np.zeros_like(self._q_set)
        end = self.time + seconds
        while self.time < end:
            self._control_step(self._q_set, zero)
            if until_settled and np.max(np.abs(self.scene.q - self._q_set)) < SETTLED \
                    and np.max(np.abs(self.scene.qd)) < 1e-3:
                break

    def run_stages(self, stages: list[Stage], command: RobotCommand | None) -> None:
        for stage in stages:
            self.watch.expect(stage.context, command, self.state, carrying=self._payload is not None)
            self.run_stage(stage)

    # --- the vacuum and the screws --------------------------------------------------------
    def pad_seals(self, drywall_id: str) -> bool:
        """True when the pad's face lies flat on the panel's gripped face, within the panel's outline."""
        sc = self.scene
        panel = self.site.panel(drywall_id)
        pose = sc.panel_pose(drywall_id)
        P = pose_matrix(pose.position, pose.quaternion)
        tcp = sc.tcp_matrix()
        local = P[:3, :3].T @ (tcp[:3, 3] - P[:3, 3])
        gap = local[1] - panel.thickness / 2
        facing = float(tcp[:3, 2] @ -P[:3, 1])
        inside = abs(local[0]) <= panel.w / 2 and abs(local[2]) <= panel.l / 2
        return GRIP_GAP[0] <= gap <= GRIP_GAP[1] and facing >= GRIP_ALIGNMENT and inside

    def grip(self, command: RobotCommand) -> bool:
        """Switch the vacuum on; the panel is held (a weld at its present pose on the pad) if the pad seals."""
        sc = self.scene
        if not self.pad_seals(command.drywall_id):
            return False
        sc.activate_weld(sc.grip_weld[command.drywall_id])
        self._payload = (panel_mass(self.site.panel(command.drywall_id)), believed_grip(self.ik, sc.q, command))
        self._stage_name = "grip"
        self.hold(VACUUM_TIME)
        return True

    def release(self, command: RobotCommand) -> None:
        """Fasten the panel where it is now (screws: a weld to the wall at its present pose), then let go."""
        self.scene.activate_weld(self.scene.screws_weld[command.drywall_id])
        self.let_go(command, "release")

    def let_go(self, command: RobotCommand, stage_name: str = "let_go") -> None:
        """Switch the vacuum off: the panel is left where it is (on its stack, unless it was fastened)."""
        self.scene.deactivate_weld(self.scene.grip_weld[command.drywall_id])
        self._payload = None
        self._stage_name = stage_name
        self.hold(VACUUM_TIME)

    def _panel_in_tcp(self, drywall_id: str) -> np.ndarray:
        pose = self.scene.panel_pose(drywall_id)
        return np.linalg.inv(self.scene.tcp_matrix()) @ pose_matrix(pose.position, pose.quaternion)

    # --- one command -------------------------------------------------------------------------
    def check(self, command: RobotCommand) -> SiteState:
        """The state after the command; a ``Refusal`` (and no motion) if the site does not allow it."""
        expected = RobotCommand.build(self.site, command.drywall_id, command.stud_id, command.placement)
        if expected != command:
            raise ValueError(f"the command's geometry does not match the site tables: {command}")
        return self.state.install(command.drywall_id, command.stud_id, command.placement)

    def execute(self, command: RobotCommand) -> PlacementResult:
        """Carry out ``command``; a ``Refusal`` is raised before anything moves if the site does not allow it.

        Once it has begun, a placement that goes wrong ends in a failed ``PlacementResult`` (see
        ``drywall_lab.rc.placement`` for the reasons) with the robot withdrawn where it can be.
        """
        before = self.state
        after = self.check(command)  # Refusal: nothing has moved
        wall_start, sim_start = wallclock.perf_counter(), self.time
        self._trace, self._trace_start, self._trace_next = JointTrace(), sim_start, sim_start
        if self.recording is not None:
            self.recording.caption(sim_start, str(command))
        notes: list[str] = []

        def finish(failure: str | None, stages: list[Stage], **outcome) -> PlacementResult:
            base_moves = sum(s.kind == "base" and s.duration > 0 for s in stages)
            return self._finish(command, sim_start, wall_start, failure, base_moves=base_moves, notes=notes, **outcome)

        try:
            plan = self.planner.plan(command, self._q_set, before)
        except PlanningError as e:
            return finish(f"unreachable: {e}", [])
        self.run_stages(plan.before_grip, command)
        self._stage_name = "descend"
        self.hold(1.0, until_settled=True)
        if not self.grip(command):
            return finish("grip_failed", plan.before_grip, robot_clear=self._withdraw(command, notes))
        held = self._panel_in_tcp(command.drywall_id)
        carrying = self._carrying(command, plan, notes)
        if carrying is None:
            self.let_go(command)
            return finish("unreachable: no safe carry from the grip the robot measured", plan.before_grip,
                          robot_clear=self._withdraw(command, notes))
        self.run_stages(carrying, command)
        self._stage_name = "seat"
        self.hold(1.5, until_settled=True)
        drift = np.linalg.norm(self._panel_in_tcp(command.drywall_id)[:3, 3] - held[:3, 3])
        self.release(command)
        self.state = after  # the panel is fastened to the wall, where it is
        leaving = self._leaving(command, plan, before, notes)
        if leaving is not None:
            self.run_stages(leaving, command)
        self._stage_name = "settle"
        self.hold(SETTLE_TIME)
        return finish(None if leaving is not None else "retreat_blocked: no safe way back from the panel",
                      plan.before_grip + carrying, slip_mm=1000 * float(drift), gripped=True, panel_lifted=True,
                      robot_clear=leaving is not None)

    def _carrying(self, command: RobotCommand, plan: PlacementPlan, notes: list[str]) -> list[Stage] | None:
        """The carry re-planned from the servos' set points with the grip the robot believes it has (from its
        joint readings and the site tables); if that fails, the first plan's carry if it is still safe with
        that grip; None when neither is."""
        grip = self._payload[1]
        try:
            return self.planner.replan_carry(command, self._q_set, grip, self.state, plan.place_station)
        except PlanningError as e:
            notes.append(f"re-planning the carry from the measured grip failed: {e}")
        try:
            stages = self.planner.verified(plan.carrying, self._q_set, command, self.state, grip=grip)
        except PlanningError as e:
            notes.append(f"the first plan's carry is not safe with the measured grip: {e}")
            return None
        notes.append("carried as first planned (checked again with the measured grip)")
        return stages

    def _leaving(self, command: RobotCommand, plan: PlacementPlan, before: SiteState,
                 notes: list[str]) -> list[Stage] | None:
        """The retreat re-planned from where the robot seated the panel; if that fails, the first plan's
        retreat if it starts there and is still safe; None when neither is."""
        try:
            return self.planner.replan_release(command, self._q_set, before)
        except PlanningError as e:
            notes.append(f"re-planning the retreat failed: {e}")
        place = pose_matrix(command.place_pose.position, command.place_pose.quaternion)
        try:
            stages = self.planner.verified(plan.after_release, self._q_set, command, before, panel_pose=place)
        except PlanningError as e:
            notes.append(f"the first plan's retreat cannot be taken up: {e}; the robot stays where it is")
            return None
        notes.append("retreated as first planned (checked again)")
        return stages

    def _withdraw(self, command: RobotCommand, notes: list[str]) -> bool:
        """The empty pad up off the panel on its stack and the arm to its ready posture; False, and no
        motion, when no safe way back can be planned."""
        try:
            stages = self.planner.plan_withdraw(command, self._q_set, self.state)
        except PlanningError as e:
            notes.append(f"no safe way back off the panel: {e}; the robot stays where it is")
            return False
        self.run_stages(stages, command)
        return True

    def _finish(self, command: RobotCommand, sim_start: float, wall_start: float, failure: str | None,
                base_moves: int = 0, slip_mm: float = 0.0, gripped: bool = False, panel_lifted: bool = False,
                robot_clear: bool = True, notes: list[str] | None = None) -> PlacementResult:
        pose = self.scene.panel_pose(command.drywall_id)
        pos_err, ang_err = pose_error(pose, command.place_pose)
        contacts = self.watch.take_events()
        if failure is None:
            failure = judge(gripped, slip_mm, contacts, 1000 * pos_err, ang_err)
        result = PlacementResult(
            command=command, success=failure is None, failure=failure, final_pose=pose,
            position_error_mm=1000 * pos_err, angle_error_deg=ang_err, slip_mm=slip_mm,
            sim_time=self.time - sim_start, wall_time=wallclock.perf_counter() - wall_start,
            base_moves=base_moves, unexpected_contacts=contacts, trace=self._trace or JointTrace(),
            panel_lifted=panel_lifted, robot_clear=robot_clear, notes=list(notes or []), sim_start=sim_start,
        )
        self._trace = None
        self.results.append(result)
        return result
