"""Motion for one ``RobotCommand``: the waypoints of a pick-and-place and the joint trajectories.

The paper's Robot Control section (after Wang et al.): the robot picks the target panel,
carries it, turns it to the placement the command asks for (vertical, or a quarter turn for
horizontal), and sets it on the stud; "the robotic arm movement ... has higher priority than
the base movement to reduce localization error". Here that rule reads: every stage moves
either the arm or the base, never both; the base moves only when the arm cannot do the next
part of the job from where the base stands (the target lies outside the arm's work window in
front of the base, or no continuous, collision-free arm motion reaches it from there), and then
only after the arm has finished its own stage (folded to its ready posture, or holding the panel
in its carrying posture). As in the paper, collisions are checked while planning with the
carried panel counted as part of the robot (``drywall_lab.rc.collision``).

The stages of one placement (``PlacementPlan``):

1. empty: ``ready`` (arm to its resting posture), ``base_to_stack`` (only if needed),
   ``approach_pick`` (pad 0.25 m above the top panel), ``descend`` (pad on the panel);
2. vacuum on (``drywall_lab.rc.cell``), then carrying: ``lift`` (0.12 m straight up), ``tilt``
   (the panel turns up on its near edge until it stands facing the robot; the edge toward the
   robot keeps its height, so it slides over the stack and never swings into the robot),
   ``swing`` (around the robot to stand 0.4 m off the wall, facing it, at a height where it
   can turn), ``turn`` (about its face normal: half a turn for a vertical placement, a quarter
   turn for a horizontal one, which puts the sheet's length along the wall), ``base_to_wall``
   (only if needed), ``to_row`` (down or up to the placement's height), ``approach`` (to 2 cm
   off the studs, a few millimetres clear of its place: ``seating_offset``), ``set`` (onto the
   studs' face), ``seat`` (the last millimetres into place, onto the floor for a panel that
   reaches it);
3. vacuum off and screws on, then ``retreat`` (pad 0.2 m back off the panel) and ``ready``.

Every stage is checked for collisions against the site tables before the robot may run it
(``MotionPlanner.checking``; ``RobotCell`` runs no stage that was not): the stages of the plan,
the carry and the retreat re-planned from where the robot really is, a planned stage taken up
again (``verified``), and the way back after a failed grip (``plan_withdraw``).

Positions are sampled along each stage every ``2 cm`` / ``2 deg``, each sample solved by
``ArmIK`` from the previous one; the joint path is timed with a minimum-jerk profile under the
joint speed limits and a Cartesian speed limit for the stage.
"""
from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Iterator

import numpy as np

from drywall_lab.im.command import RobotCommand
from drywall_lab.rc.collision import CollisionChecker
from drywall_lab.rc.robot import JOINTS, RAIL_RANGE, RAIL_Y, SPEED_LIMITS, ArmIK, IKFailure, grip_transform, pose_matrix
from drywall_lab.site import Rect, Site, SiteState

if TYPE_CHECKING:
    import pandas as pd

#: The base stands this far (x, m) to the left of the point it works on, by preference ...
STATION_DX = 1.0
#: ... or, when that collides, at one of these distances (tried in this order).
STATION_OFFSETS = (1.0, 1.3, 0.7, 1.6)
#: The arm works alone while the target's x lies within this distance of the base's best station.
WORK_WINDOW = 0.55
#: The panel's centre stands this far (m) off its place pose while it turns and travels.
STANDOFF = 0.4
#: Clearance (m) of the panel's lowest point above the floor while it turns.
TURN_CLEARANCE = 0.12
LIFT = 0.12  #: m, straight up off the stack
PRE_PICK = 0.25  #: m, pad above the panel before it descends
APPROACH_GAP = 0.02  #: m, off the studs before the panel is set
DROP = 0.004  #: m, the panel is set this far clear of its place and then slid into it
RETREAT = 0.2  #: m, pad back off the installed panel
LINEAR_STEP, ANGULAR_STEP = 0.02, math.radians(2.0)  #: path sampling
MAX_JOINT_JUMP = 0.25  #: rad (or m) between two samples: more means the IK switched branches
#: rad (or m): a stage planned earlier may be taken up this far from where the robot's set points are.
#: The carry re-planned from the measured grip ends about 2e-5 rad from the first plan's; 2e-4 rad
#: moves the pad at most about 0.6 mm at full reach.
RESUME_TOLERANCE = 2e-4


class PlanningError(RuntimeError):
    """No feasible motion for a command: a pose out of reach or a discontinuous joint path."""


# --- rotations ------------------------------------------------------------------------------------
def rot_x(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def transform(R: np.ndarray, p) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


def rotation_angle(R: np.ndarray) -> float:
    """The angle (rad) of a rotation matrix."""
    return math.acos(max(-1.0, min(1.0, (np.trace(R) - 1) / 2)))


def interpolate_transforms(Ta: np.ndarray, Tb: np.ndarray, s: float) -> np.ndarray:
    """Straight line in position, shortest arc in rotation (axis-angle), at fraction ``s``."""
    Rrel = Ta[:3, :3].T @ Tb[:3, :3]
    angle = rotation_angle(Rrel)
    if angle < 1e-9:
        R = Ta[:3, :3]
    else:
        axis = np.array([Rrel[2, 1] - Rrel[1, 2], Rrel[0, 2] - Rrel[2, 0], Rrel[1, 0] - Rrel[0, 1]])
        norm = np.linalg.norm(axis)
        if norm < 1e-9:  # half a turn: any perpendicular axis; take the eigenvector
            w, v = np.linalg.eigh((Rrel + Rrel.T) / 2)
            axis = v[:, np.argmax(w)]
        else:
            axis = axis / norm
        K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
        a = s * angle
        R = Ta[:3, :3] @ (np.eye(3) + math.sin(a) * K + (1 - math.cos(a)) * K @ K)
    return transform(R, (1 - s) * Ta[:3, 3] + s * Tb[:3, 3])


# --- trajectories ------------------------------------------------------------------------------------
def minimum_jerk(tau: float) -> tuple[float, float]:
    """Progress s and ds/dtau of the minimum-jerk profile at normalised time ``tau`` in [0, 1]."""
    tau = min(max(tau, 0.0), 1.0)
    return tau**3 * (10 - 15 * tau + 6 * tau**2), 30 * tau**2 * (1 - tau) ** 2


@dataclass
class Stage:
    """One stage of a placement: a joint path (rail first) timed over ``duration`` seconds.

    ``kind`` is ``"arm"`` or ``"base"`` (which part moves); ``context`` says which contacts are
    expected while it runs: ``free`` (none), ``pick`` (the pad on the target, the target on
    the stack), ``carry`` (the pad on the carried panel only), ``set`` (the carried panel on the
    studs, on the floor and against installed neighbours whose edges it meets).
    """

    name: str
    kind: str
    context: str
    samples: np.ndarray  # (n + 1, 7)
    duration: float
    tcp_path: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))  # planned TCP positions
    collision_checked: bool = False  # set by ``MotionPlanner`` once no sample collides

    def at(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """Joint positions and velocities at ``t`` seconds into the stage (held after the end)."""
        n = len(self.samples) - 1
        if n == 0 or self.duration <= 0:
            return self.samples[-1].copy(), np.zeros(len(JOINTS))
        s, ds = minimum_jerk(t / self.duration)
        u = s * n
        i = min(int(u), n - 1)
        f = u - i
        delta = self.samples[i + 1] - self.samples[i]
        return self.samples[i] + f * delta, delta * n * ds / self.duration

    @property
    def end(self) -> np.ndarray:
        return self.samples[-1]


def timed_stage(name: str, kind: str, context: str, samples: np.ndarray, linear_speed: float,
                tcp_path: np.ndarray | None = None, angular_speed: float = math.radians(40)) -> Stage:
    """A stage whose duration keeps every joint under ``SPEED_LIMITS`` and the TCP under the given speeds.

    The minimum-jerk profile peaks at 1.875 times its mean speed; samples are evenly spaced
    along the path, so the largest step between samples sets the pace.
    """
    samples = np.asarray(samples, dtype=float)
    n = len(samples) - 1
    if n == 0:
        return Stage(name, kind, context, samples, 0.0)
    steps = np.abs(np.diff(samples, axis=0))
    joint_time = float(np.max(steps.max(axis=0) * n / SPEED_LIMITS))
    cart_time = 0.0
    if tcp_path is not None and len(tcp_path) > 1:
        cart_time = float(np.max(np.linalg.norm(np.diff(tcp_path, axis=0), axis=1)) * n / linear_speed)
    duration = max(1.875 * max(joint_time, cart_time), 0.4)
    return Stage(name, kind, context, samples, duration,
                 np.zeros((0, 3)) if tcp_path is None else np.asarray(tcp_path))


# --- planner -------------------------------------------------------------------------------------------
@dataclass
class PlacementPlan:
    """The stages before the vacuum grips, while it holds, and after it lets go."""

    command: RobotCommand
    before_grip: list[Stage]
    carrying: list[Stage]
    after_release: list[Stage]
    pick_station: float  # rail x while picking
    place_station: float  # rail x while placing

    @property
    def stages(self) -> list[Stage]:
        return self.before_grip + self.carrying + self.after_release

    @property
    def base_moves(self) -> int:
        return sum(s.kind == "base" and s.duration > 0 for s in self.stages)

    @property
    def duration(self) -> float:
        return sum(s.duration for s in self.stages)

    def table(self) -> pd.DataFrame:
        """One row per stage that takes time: its name, what moves (arm or base), the contacts expected, the
        number of IK samples and the duration (s)."""
        import pandas as pd

        return pd.DataFrame([{"stage": s.name, "moves": s.kind, "contacts expected": s.context,
                              "samples": len(s.samples), "duration (s)": round(s.duration, 2)}
                             for s in self.stages if s.duration > 0])


def seating_offset(command: RobotCommand, state: SiteState) -> tuple[float, float]:
    """Where (dx, dz) the panel waits before its last few millimetres into place.

    The panel comes to the studs ``DROP`` above its place and is then lowered onto it; when
    something meets its top edge (an installed panel) it comes from below instead, and when both
    edges are taken (the floor and a panel above) it comes straight in. Likewise it keeps ``DROP``
    away from an installed panel that meets one of its side edges.
    """
    rect = Rect(command.x_left, command.x_right, command.z_bottom, command.z_top)
    near = lambda a, b: abs(a - b) < 1e-3  # noqa: E731
    x_shared = lambda r: min(r.x_right, rect.x_right) - max(r.x_left, rect.x_left) > 1e-3  # noqa: E731
    z_shared = lambda r: min(r.z_top, rect.z_top) - max(r.z_bottom, rect.z_bottom) > 1e-3  # noqa: E731
    others = [i.rect for i in state.installed if i.drywall_id != command.drywall_id]
    top = any(near(r.z_bottom, rect.z_top) and x_shared(r) for r in others)
    bottom = rect.z_bottom < 1e-3 or any(near(r.z_top, rect.z_bottom) and x_shared(r) for r in others)
    left = any(near(r.x_right, rect.x_left) and z_shared(r) for r in others)
    right = any(near(r.x_left, rect.x_right) and z_shared(r) for r in others)
    dz = DROP if not top else (-DROP if not bottom else 0.0)
    dx = DROP if left and not right else (-DROP if right and not left else 0.0)
    return dx, dz


class MotionPlanner:
    """Plans the stages of a placement with ``ArmIK`` and checks them with ``CollisionChecker``.

    See the module's docstring for the stages and for how the arm takes priority over the base.
    """

    def __init__(self, site: Site, ik: ArmIK | None = None) -> None:
        self.site = site
        self.ik = ik or ArmIK()
        self._checker: CollisionChecker | None = None
        self._check: tuple[CollisionChecker, RobotCommand | None] | None = None

    def checker(self, state: SiteState) -> CollisionChecker:
        """The planning scene for ``state`` (rebuilt when the state changes)."""
        if self._checker is None or self._checker.state != state:
            self._checker = CollisionChecker(state)
        return self._checker

    @contextmanager
    def checking(self, state: SiteState, command: RobotCommand | None = None) -> Iterator[CollisionChecker]:
        """Check every stage planned inside the block against ``state`` (the site tables, every panel where
        they put it); ``command``'s panel counts as part of the robot while it is carried.

        >>> from drywall_lab.site import default_site
        >>> planner = MotionPlanner(default_site())
        >>> q = planner.ready_posture(0.0)
        >>> with planner.checking(default_site().fresh()):
        ...     planner.base_stage("along_the_rail", "free", q, 0.5).collision_checked
        True
        """
        previous = self._check
        checker = self.checker(state)
        checker.reset()
        self._check = (checker, command)
        try:
            yield checker
        finally:
            self._check = previous

    # --- building blocks ---------------------------------------------------------------------
    def solve_path(self, poses: list[np.ndarray], seed: np.ndarray) -> np.ndarray:
        """Joint samples (seed first) through the TCP ``poses``, the rail held; ``PlanningError`` if none."""
        qs = [np.asarray(seed, dtype=float)]
        for T in poses:
            try:
                q = self.ik.solve(T, qs[-1], hold_rail=True).q
            except IKFailure as e:
                raise PlanningError(str(e)) from None
            if np.max(np.abs(q - qs[-1])) > MAX_JOINT_JUMP:
                raise PlanningError("the joint path is not continuous (the arm would have to flip)")
            qs.append(q)
        return np.array(qs)

    def _checked(self, stage: Stage, grip: np.ndarray | None = None, panel_pose: np.ndarray | None = None) -> Stage:
        """The stage, marked checked, if no sample of it collides (the carried panel counted as part of the
        robot); a ``PlanningError`` naming the first collision otherwise.

        Every stage the planner makes passes here. Outside ``checking`` there is nothing to check it
        against: that is a mistake in the calling code, and it raises rather than let an unchecked motion by.
        """
        if self._check is None:
            raise RuntimeError(f"stage {stage.name!r} was planned outside MotionPlanner.checking(state): "
                               "every motion must be checked for collisions")
        checker, command = self._check
        checker.set_context(stage.context, command, grip, panel_pose)
        for q in stage.samples:
            hit = checker.first_collision(q)
            if hit:
                raise PlanningError(f"{stage.name}: {hit}")
        stage.collision_checked = True
        return stage

    @staticmethod
    def samples_between(Ta: np.ndarray, Tb: np.ndarray, step: float = LINEAR_STEP) -> list[np.ndarray]:
        """Poses from ``Ta`` (excluded) to ``Tb`` (included), evenly spaced."""
        dist = np.linalg.norm(Tb[:3, 3] - Ta[:3, 3])
        angle = rotation_angle(Ta[:3, :3].T @ Tb[:3, :3])
        n = max(1, int(math.ceil(max(dist / step, angle / ANGULAR_STEP))))
        return [interpolate_transforms(Ta, Tb, k / n) for k in range(1, n + 1)]

    def line_stage(self, name: str, context: str, q: np.ndarray, Tb: np.ndarray, speed: float,
                   panel_pose: np.ndarray | None = None) -> Stage:
        """The empty TCP in a straight line (and shortest turn) from where ``q`` puts it to ``Tb``."""
        Ta = self.ik.fk(q)
        poses = self.samples_between(Ta, Tb)
        samples = self.solve_path(poses, q)
        stage = timed_stage(name, "arm", context, samples, speed, np.array([Ta[:3, 3]] + [T[:3, 3] for T in poses]))
        return self._checked(stage, panel_pose=panel_pose)

    def panel_stage(self, name: str, context: str, q: np.ndarray, panel_poses: list[np.ndarray],
                    grip: np.ndarray, speed: float) -> Stage:
        """The TCP carrying the panel through ``panel_poses`` (``grip``: the panel in the TCP frame)."""
        tcp = [P @ np.linalg.inv(grip) for P in panel_poses]
        samples = self.solve_path(tcp, q)
        stage = timed_stage(name, "arm", context, samples, speed,
                            np.array([self.ik.fk(q)[:3, 3]] + [T[:3, 3] for T in tcp]))
        return self._checked(stage, grip=grip)

    def joint_stage(self, name: str, context: str, q: np.ndarray, q_end: np.ndarray,
                    panel_pose: np.ndarray | None = None) -> Stage:
        """A move in joint space (every joint straight from ``q`` to ``q_end``), skipped when already there."""
        n = max(1, int(math.ceil(np.max(np.abs(q_end - q)) / 0.05)))
        samples = np.array([q + (q_end - q) * k / n for k in range(n + 1)])
        if np.max(np.abs(q_end - q)) < 1e-6:
            samples = samples[:1]
        return self._checked(timed_stage(name, "arm", context, samples, 1.0), panel_pose=panel_pose)

    def base_stage(self, name: str, context: str, q: np.ndarray, rail_x: float, grip: np.ndarray | None = None,
                   panel_pose: np.ndarray | None = None) -> Stage:
        """The carriage along the rail to ``rail_x``; the arm holds its posture."""
        q_end = q.copy()
        q_end[0] = rail_x
        n = max(1, int(math.ceil(abs(rail_x - q[0]) / LINEAR_STEP)))
        samples = np.array([q + (q_end - q) * k / n for k in range(n + 1)])
        if abs(rail_x - q[0]) < 1e-6:
            return self._checked(Stage(name, "base", context, samples[:1], 0.0), grip=grip, panel_pose=panel_pose)
        return self._checked(timed_stage(name, "base", context, samples, 1.0), grip=grip, panel_pose=panel_pose)

    def ready_posture(self, rail_x: float) -> np.ndarray:
        q = self.ik.home.copy()
        q[0] = rail_x
        return q

    @staticmethod
    def stations(x: float, rail_x: float) -> list[float]:
        """Rail positions to try for work on a point at ``x``: where the base is (the arm alone), if the
        point lies in the arm's work window, then the stations at ``STATION_OFFSETS`` to its left."""
        lo, hi = RAIL_RANGE[0] + 0.05, RAIL_RANGE[1] - 0.05
        out = [rail_x] if abs(x - STATION_DX - rail_x) <= WORK_WINDOW else []
        for dx in STATION_OFFSETS:
            station = float(np.clip(x - dx, lo, hi))
            if all(abs(station - s) > 0.05 for s in out):
                out.append(station)
        return out

    # --- the three parts of a placement ----------------------------------------------------------
    def plan_pick(self, command: RobotCommand, q_now: np.ndarray) -> tuple[list[Stage], float]:
        """``ready``, ``base_to_stack`` (only if the arm cannot do it from here), ``approach_pick``, ``descend``."""
        pick = pose_matrix(command.pick_pose.position, command.pick_pose.quaternion)
        thickness = self.site.panel(command.drywall_id).thickness
        tcp_pick = pick @ np.linalg.inv(grip_transform(thickness))
        above = tcp_pick.copy()
        above[2, 3] += PRE_PICK
        errors = []
        for rail_x in self.stations(command.pick_pose.position[0], q_now[0]):
            try:
                stages = [self.joint_stage("ready", "free", q_now, self.ready_posture(q_now[0]), panel_pose=pick)]
                stages.append(self.base_stage("base_to_stack", "free", stages[-1].end, rail_x, panel_pose=pick))
                stages.append(self.line_stage("approach_pick", "free", stages[-1].end, above, 0.8, panel_pose=pick))
                stages.append(self.line_stage("descend", "pick", stages[-1].end, tcp_pick, 0.2, panel_pose=pick))
                return stages, rail_x
            except PlanningError as e:
                errors.append(f"rail at {rail_x:.2f} m: {e}")
        raise PlanningError(f"cannot pick panel {command.drywall_id}: " + "; ".join(errors))

    def plan_carry(self, command: RobotCommand, q_grip: np.ndarray, grip: np.ndarray, state: SiteState,
                   station: float | None = None) -> tuple[list[Stage], float]:
        """From the gripped panel on its stack to the panel seated on the studs (see the module docstring).

        ``station`` forces the rail position for placing; by default the arm alone is tried first.
        """
        panel = self.site.panel(command.drywall_id)
        pick = pose_matrix(command.pick_pose.position, command.pick_pose.quaternion)
        place = pose_matrix(command.place_pose.position, command.place_pose.quaternion)
        half_diagonal = math.hypot(panel.w, panel.l) / 2
        z_turn = half_diagonal + TURN_CLEARANCE
        dx, dz = seating_offset(command, state)
        x, y, z = place[:3, 3]
        R = place[:3, :3]

        # lift, then tilt up on the near edge
        lifted = pick.copy()
        lifted[2, 3] += LIFT
        head = [self.panel_stage("lift", "pick", q_grip, [lifted], grip, 0.2)]
        sx, sy, z_lift = lifted[:3, 3]
        n_tilt = int(math.ceil(math.radians(90) / ANGULAR_STEP))
        tilt = [transform(rot_x(math.radians(90) + th), (sx, sy, z_lift + panel.l / 2 * math.sin(th)))
                for th in (math.radians(90) * k / n_tilt for k in range(1, n_tilt + 1))]
        head.append(self.panel_stage("tilt", "carry", head[-1].end, tilt, grip, 0.6))
        q_tilted, start = head[-1].end, tilt[-1]

        def swing_and_turn(q: np.ndarray, x_standoff: float) -> list[Stage]:
            """Around the robot to stand off the wall at ``x_standoff``, then turn to the placement's orientation."""
            rail_x = q[0]
            end_pos = np.array([x_standoff, y + STANDOFF, z_turn])
            pa, pb = start[:3, 3] - (rail_x, RAIL_Y, 0), end_pos - (rail_x, RAIL_Y, 0)
            phi_a, phi_b = math.atan2(pa[1], pa[0]), math.atan2(pb[1], pb[0])
            r_a, r_b = math.hypot(pa[0], pa[1]), math.hypot(pb[0], pb[1])
            n = int(math.ceil(max(abs(phi_a - phi_b) * max(r_a, r_b) / LINEAR_STEP, math.pi / ANGULAR_STEP)))
            swing = []
            for k in range(1, n + 1):
                s = k / n
                phi, r = phi_a + s * (phi_b - phi_a), r_a + s * (r_b - r_a)
                swing.append(transform(rot_z(math.pi * (1 - s)) @ rot_y(math.pi),
                                       (rail_x + r * math.cos(phi), RAIL_Y + r * math.sin(phi),
                                        start[2, 3] + s * (z_turn - start[2, 3]))))
            out = [self.panel_stage("swing", "carry", q, swing, grip, 0.8)]
            rho_end = math.atan2(R[0, 2], R[0, 0])  # place = rot_y(rho_end): 0 upright, 90 deg on its side
            errors = []
            for rho in sorted({rho_end, rho_end + 2 * math.pi, rho_end - 2 * math.pi}, key=lambda r: abs(r - math.pi)):
                n_turn = max(1, int(math.ceil(abs(rho - math.pi) / ANGULAR_STEP)))
                turn = [transform(rot_y(math.pi + (rho - math.pi) * k / n_turn), end_pos) for k in range(1, n_turn + 1)]
                try:
                    return out + [self.panel_stage("turn", "carry", out[-1].end, turn, grip, 0.4)]
                except PlanningError as e:
                    errors.append(str(e))
            raise PlanningError("; ".join(errors))

        # a panel that fits exactly between the floor and a panel above comes in on the floor
        on_floor = "set" if dz == 0 and command.z_bottom < 1e-6 else "carry"

        def to_wall(q: np.ndarray) -> list[Stage]:
            """to the row, approach (2 cm off the studs), set (onto the studs), seat (the last millimetres)."""
            waiting = (x + dx, y, z + dz)
            line = self.samples_between
            out = [self.panel_stage("to_row", on_floor, q, line(transform(R, (x, y + STANDOFF, z_turn)),
                                                                transform(R, (x + dx, y + STANDOFF, z + dz))),
                                    grip, 0.5)]
            out.append(self.panel_stage("approach", on_floor, out[-1].end,
                                        line(transform(R, (x + dx, y + STANDOFF, z + dz)),
                                             transform(R, (x + dx, y + APPROACH_GAP, z + dz))), grip, 0.3))
            out.append(self.panel_stage("set", "set", out[-1].end,
                                        line(transform(R, (x + dx, y + APPROACH_GAP, z + dz)), transform(R, waiting),
                                             step=0.004), grip, 0.03))
            out.append(self.panel_stage("seat", "set", out[-1].end, line(transform(R, waiting), place, step=0.001),
                                        grip, 0.01))
            return out

        rail_x = q_tilted[0]
        candidates = [station] if station is not None else self.stations(x, rail_x)
        errors = []
        for place_x in candidates:
            try:
                stages = swing_and_turn(q_tilted, x - place_x + rail_x)
                stages.append(self.base_stage("base_to_wall", "carry", stages[-1].end, place_x, grip=grip))
                stages += to_wall(stages[-1].end)
                return head + stages, place_x
            except PlanningError as e:
                errors.append(f"rail at {place_x:.2f} m: {e}")
        raise PlanningError(f"cannot place panel {command.drywall_id}: " + "; ".join(errors))

    def plan_release(self, command: RobotCommand, q_set: np.ndarray) -> list[Stage]:
        """``retreat`` (the pad straight back off the panel) and ``ready``."""
        place = pose_matrix(command.place_pose.position, command.place_pose.quaternion)
        T = self.ik.fk(q_set)
        back = T.copy()
        back[:3, 3] -= RETREAT * T[:3, 2]  # against the TCP's z axis, which points into the panel
        stages = [self.line_stage("retreat", "set", q_set, back, 0.3, panel_pose=place)]
        stages.append(self.joint_stage("ready", "free", stages[-1].end, self.ready_posture(q_set[0]), panel_pose=place))
        return stages

    def plan(self, command: RobotCommand, q_now: np.ndarray, state: SiteState) -> PlacementPlan:
        """The whole placement, with the panel assumed where the site tables say; ``PlanningError`` if infeasible.

        ``state`` is the site before the command (what is installed, what is stacked).
        """
        thickness = self.site.panel(command.drywall_id).thickness
        with self.checking(state, command):
            before, pick_station = self.plan_pick(command, q_now)
            carrying, place_station = self.plan_carry(command, before[-1].end, grip_transform(thickness), state)
            after = self.plan_release(command, carrying[-1].end)
        return PlacementPlan(command, before, carrying, after, pick_station, place_station)

    def replan_carry(self, command: RobotCommand, q_grip: np.ndarray, grip: np.ndarray, state: SiteState,
                     station: float) -> list[Stage]:
        """The carrying stages again, from the measured grip, to the station chosen by ``plan``."""
        with self.checking(state, command):
            return self.plan_carry(command, q_grip, grip, state, station)[0]

    def replan_release(self, command: RobotCommand, q_set: np.ndarray, state: SiteState) -> list[Stage]:
        """The release stages from where the robot is after seating the panel."""
        with self.checking(state, command):
            return self.plan_release(command, q_set)

    def plan_withdraw(self, command: RobotCommand, q_now: np.ndarray, state: SiteState) -> list[Stage]:
        """The empty pad back off a panel it is not taking: ``withdraw`` (straight up ``PRE_PICK``) and ``ready``.

        After a failed grip, or after letting go of a gripped panel whose carry cannot be planned; the
        panel is where the site tables put it, on its stack.
        """
        pick = pose_matrix(command.pick_pose.position, command.pick_pose.quaternion)
        above = self.ik.fk(q_now)
        above[2, 3] += PRE_PICK
        with self.checking(state, command):
            stages = [self.line_stage("withdraw", "pick", q_now, above, 0.2, panel_pose=pick)]
            stages.append(self.joint_stage("ready", "free", stages[-1].end, self.ready_posture(q_now[0]),
                                           panel_pose=pick))
        return stages

    def verified(self, stages: list[Stage], q_now: np.ndarray, command: RobotCommand, state: SiteState,
                 grip: np.ndarray | None = None, panel_pose: np.ndarray | None = None) -> list[Stage]:
        """Stages planned earlier, if the robot can still run them: a ``PlanningError`` unless they start
        within ``RESUME_TOLERANCE`` of ``q_now`` and no sample collides when checked again against ``state``.

        ``grip`` is the panel in the TCP frame as the robot now believes it holds it (for carrying
        stages); ``panel_pose`` puts the command's panel for stages that do not carry it. The first
        stage is returned starting exactly at ``q_now``, so that the set points do not jump.
        """
        if not stages:
            return []
        gap = float(np.max(np.abs(stages[0].samples[0] - q_now)))
        if gap > RESUME_TOLERANCE:
            raise PlanningError(f"{stages[0].name}: the planned motion starts {gap:.2e} rad (or m) away from where "
                                f"the robot is (at most {RESUME_TOLERANCE:g})")
        first = stages[0].samples.copy()
        first[0] = q_now
        taken_up = [replace(stages[0], samples=first, collision_checked=False)]
        taken_up += [replace(s, collision_checked=False) for s in stages[1:]]
        with self.checking(state, command):
            return [self._checked(s, grip=grip, panel_pose=panel_pose) for s in taken_up]


def believed_grip(ik: ArmIK, q: np.ndarray, command: RobotCommand) -> np.ndarray:
    """Where the robot believes the gripped panel sits in its TCP frame.

    From its own joint readings (forward kinematics) and the panel's pose in the site tables;
    the simulator's record of the panel is not used, as a real robot could not read it.
    """
    tcp = ik.fk(q)
    pick = pose_matrix(command.pick_pose.position, command.pick_pose.quaternion)
    return np.linalg.inv(tcp) @ pick


__all__ = ["MotionPlanner", "PlacementPlan", "PlanningError", "Stage", "believed_grip", "seating_offset"]
