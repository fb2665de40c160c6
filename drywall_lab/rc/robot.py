"""The robot: a 6-axis industrial arm on a linear rail, with a vacuum lifter (the paper's Fig. 5(a)).

The paper's robot is a 6-DoF KUKA arm whose base moves in a straight line between the
stud wall and the panel stacks (section "Research Methodology", Fig. 5(a)), simulated in
Gazebo and driven by MoveIt. Here it is this project's own MJCF, built from boxes and
cylinders with the proportions of a KUKA KR 120 R2700 (about 2.8 m from the shoulder to
the lifter's pad), on a rail parallel to the wall at ``RAIL_Y``. Seven joints: the rail
``rail`` and the arm's ``a1``-``a6``.

Frame of the arm: forward is its local +x. At ``a1 = 0`` the arm reaches toward the wall
(world -y); ``a1 = 180 deg`` faces the stacks. ``a2 = 0`` holds the upper arm upright,
``a3 = 0`` the forearm at a right angle to it; positive ``a2``/``a3``/``a5`` pitch
forward and down.

Each joint is driven by one servo (a MuJoCo ``position`` actuator with ``kp`` and ``kv``)
whose set point carries velocity and gravity feed-forward, as an industrial drive's does
(``RobotCell._control_step`` in ``drywall_lab.rc.cell``). Inverse kinematics uses mink on a
model of the robot alone (``ArmIK``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import mink
import mujoco
import numpy as np

if TYPE_CHECKING:
    import pandas as pd

#: The rail's centre line (y, m): between the wall (y = 0) and the stacks (y = STACK_Y), clear of
#: the 8 ft sheets, which reach to y = STACK_Y - 1.22 = 1.38.
RAIL_Y = 1.0
#: How far the rail runs (x of the carriage, m); it passes both ends of the 4.88 m wall.
RAIL_RANGE = (-1.2, 5.8)
#: Collision bits: the environment (floor, studs), panels, and the robot.
ENV_BIT, PANEL_BIT, ROBOT_BIT = 1, 2, 4
#: The joints, in the order of ``qpos`` after the panels' free joints: the rail first.
JOINTS = ("rail", "a1", "a2", "a3", "a4", "a5", "a6")
ARM_JOINTS = JOINTS[1:]
#: Planning speed limits (m/s for the rail, rad/s for the arm): well under a KR 120's.
SPEED_LIMITS = np.array([1.0, 1.0, 0.9, 0.9, 2.0, 2.0, 2.5])
#: The vacuum lifter's pad: half sizes (m) and the site at the centre of its face.
PAD_HALF = (0.012, 0.32, 0.22)
TCP_SITE = "tcp"
TOOL_BODY = "link6"


@dataclass(frozen=True)
class ServoGains:
    """Position and velocity gains of one joint servo, and its force limit."""

    kp: float
    kv: float
    force: float


#: The joint servos: stiff enough to hold a 25 kg sheet at arm's length within a fraction of a
#: millimetre once the gravity feed-forward has done most of the work.
SERVOS = {
    "rail": ServoGains(kp=4.0e5, kv=6.0e4, force=3.0e4),
    "a1": ServoGains(kp=1.5e6, kv=1.2e5, force=3.0e4),
    "a2": ServoGains(kp=1.5e6, kv=1.2e5, force=3.0e4),
    "a3": ServoGains(kp=1.0e6, kv=6.0e4, force=2.0e4),
    "a4": ServoGains(kp=1.5e5, kv=6.0e3, force=4.0e3),
    "a5": ServoGains(kp=1.5e5, kv=6.0e3, force=4.0e3),
    "a6": ServoGains(kp=1.0e5, kv=4.0e3, force=3.0e3),
}


def robot_mjcf(rail_y: float = RAIL_Y) -> str:
    """The rail, carriage, arm and vacuum lifter as a complete MJCF document (loadable on its own).

    Lengths follow a KR 120 R2700: shoulder 0.33 m ahead of and 0.645 m above the turntable,
    upper arm 1.15 m, forearm 1.22 m with a 0.115 m offset, wrist to flange 0.215 m; the lifter
    adds 0.23 m to the pad's face. Masses are a heavy-payload arm's, about a tonne in all.
    """
    lo, hi = RAIL_RANGE
    rail_len = hi - lo
    s = SERVOS
    servos = "\n".join(
        f'    <position name="servo_{j}" joint="{j}" kp="{s[j].kp:g}" kv="{s[j].kv:g}" '
        f'forcerange="{-s[j].force:g} {s[j].force:g}"/>'
        for j in JOINTS
    )
    return f"""<mujoco model="rail_arm">
  <compiler angle="degree" autolimits="true"/>
  <default>
    <default class="robot">
      <joint damping="5" armature="5"/>
      <geom contype="{ROBOT_BIT}" conaffinity="{ENV_BIT | PANEL_BIT}" rgba="0.95 0.45 0.05 1"/>
      <position ctrllimited="false" forcelimited="true"/>
      <default class="robot_dark">
        <geom rgba="0.2 0.2 0.22 1"/>
      </default>
      <default class="robot_visual">
        <geom contype="0" conaffinity="0" rgba="0.45 0.45 0.48 1"/>
      </default>
    </default>
  </default>
  <worldbody>
    <!-- the rail: two steel beams on the floor along x (drawn only; the carriage rides on them) -->
    <geom name="rail_beam_front" class="robot_visual" type="box" pos="{lo + rail_len / 2:.3f} {rail_y - 0.2:.3f} 0.01"
          size="{rail_len / 2:.3f} 0.04 0.01"/>
    <geom name="rail_beam_back" class="robot_visual" type="box" pos="{lo + rail_len / 2:.3f} {rail_y + 0.2:.3f} 0.01"
          size="{rail_len / 2:.3f} 0.04 0.01"/>
    <!-- the carriage slides along x; the arm's local +x points to the wall (world -y) -->
    <body name="carriage" pos="0 {rail_y} 0" childclass="robot">
      <joint name="rail" type="slide" axis="1 0 0" range="{lo} {hi}" armature="200" damping="50"/>
      <geom name="carriage_box" class="robot_dark" type="box" pos="0 0 0.17" size="0.42 0.30 0.15" mass="600"/>
      <body name="link1" pos="0 0 0.32" quat="0.70710678 0 0 -0.70710678">
        <joint name="a1" axis="0 0 1" range="-185 185" armature="40"/>
        <geom name="turntable" type="cylinder" pos="0 0 0.1" size="0.36 0.1" mass="150"/>
        <geom name="shoulder_housing" type="box" pos="0.18 0 0.42" size="0.24 0.2 0.22" mass="100"/>
        <body name="link2" pos="0.33 0 0.645">
          <joint name="a2" axis="0 1 0" range="-80 110" armature="40"/>
          <geom name="shoulder_hub" class="robot_dark" type="cylinder" quat="0.70710678 0.70710678 0 0"
                size="0.17 0.2" mass="40"/>
          <geom name="upper_arm" type="box" pos="0 0 0.575" size="0.11 0.14 0.5" mass="100"/>
          <body name="link3" pos="0 0 1.15">
            <joint name="a3" axis="0 1 0" range="-120 155" armature="30"/>
            <geom name="elbow_hub" class="robot_dark" type="cylinder" quat="0.70710678 0.70710678 0 0"
                  size="0.14 0.17" mass="30"/>
            <geom name="elbow_housing" type="box" pos="0.12 0 0.115" size="0.2 0.13 0.12" mass="40"/>
            <body name="link4" pos="0.5 0 0.115">
              <joint name="a4" axis="1 0 0" range="-300 300" armature="8"/>
              <geom name="forearm" type="cylinder" pos="0.33 0 0" quat="0.70710678 0 0.70710678 0"
                    size="0.085 0.33" mass="40"/>
              <body name="link5" pos="0.72 0 0">
                <joint name="a5" axis="0 1 0" range="-125 125" armature="6"/>
                <geom name="wrist" class="robot_dark" type="cylinder" quat="0.70710678 0.70710678 0 0"
                      size="0.075 0.1" mass="15"/>
                <body name="link6" pos="0.15 0 0">
                  <joint name="a6" axis="1 0 0" range="-350 350" armature="4"/>
                  <geom name="flange" class="robot_dark" type="cylinder" pos="0.03 0 0" quat="0.70710678 0 0.70710678 0"
                        size="0.1 0.03" mass="5"/>
                  <!-- the vacuum lifter: a stem and a pad whose face meets the panel -->
                  <geom name="lifter_stem" class="robot_dark" type="cylinder" pos="0.145 0 0"
                        quat="0.70710678 0 0.70710678 0" size="0.04 0.085" mass="6"/>
                  <geom name="lifter_pad" type="box" pos="{0.23 + 0.011 - PAD_HALF[0]:.4f} 0 0"
                        size="{PAD_HALF[0]} {PAD_HALF[1]} {PAD_HALF[2]}" rgba="0.15 0.35 0.75 1" mass="12"/>
                  <!-- tool centre point on the pad's face; its z axis points into the gripped panel -->
                  <site name="{TCP_SITE}" pos="{0.23 + 0.011:.4f} 0 0" quat="0.70710678 0 0.70710678 0" size="0.02"/>
                </body>
              </body>
            </body>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
{servos}
  </actuator>
</mujoco>
"""


def joint_table(model: mujoco.MjModel | None = None) -> pd.DataFrame:
    """The seven joints as the servos and the planner see them: range (from the MJCF), servo gains and force
    limit (``SERVOS``), planning speed limit (``SPEED_LIMITS``); metres for the rail, degrees for the arm.

    ``model`` is any compiled model holding the robot (a scene's, say); the robot's own MJCF when None.
    The ``kp``/``kv``/force columns are read from the model's actuators, so a scene given other gains
    (``Scene.set_servo_gains``) shows its own.
    """
    import pandas as pd

    model = model if model is not None else mujoco.MjModel.from_xml_string(robot_mjcf())
    rows = []
    for j, name in enumerate(JOINTS):
        joint = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        actuator = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, f"servo_{name}")
        scale, unit = (1.0, "m") if j == 0 else (math.degrees(1.0), "deg")
        low, high = model.jnt_range[joint] * scale
        rows.append({"joint": name, "unit": unit, "low": round(float(low), 1), "high": round(float(high), 1),
                     "kp": float(model.actuator_gainprm[actuator, 0]), "kv": float(-model.actuator_biasprm[actuator, 2]),
                     "force limit": float(model.actuator_forcerange[actuator, 1]),
                     "speed limit (unit/s)": round(float(SPEED_LIMITS[j] * scale), 1)})
    return pd.DataFrame(rows)


def tcp_reach() -> float:
    """Shoulder (a2) to the pad's face with the arm stretched out (m)."""
    return 1.15 + float(np.hypot(0.5 + 0.72, 0.115)) + 0.15 + 0.241


# --- poses --------------------------------------------------------------------------------
def pose_matrix(position, quaternion) -> np.ndarray:
    """A 4x4 homogeneous transform from a position and a (w, x, y, z) quaternion."""
    T = np.eye(4)
    mat = np.zeros(9)
    mujoco.mju_quat2Mat(mat, np.asarray(quaternion, dtype=float))
    T[:3, :3] = mat.reshape(3, 3)
    T[:3, 3] = position
    return T


def grip_transform(thickness: float) -> np.ndarray:
    """The panel's pose in the TCP frame when the pad is centred on the panel's +y face.

    The panel's own axes (``Pose``): x along its width, y through its thickness, z along its
    length. The TCP's z axis points into the panel (along the panel's -y), its x axis along the
    panel's x, so the panel's z is the TCP's y; the panel's centre lies half a thickness deep.
    """
    T = np.eye(4)
    T[:3, :3] = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
    T[:3, 3] = (0.0, 0.0, thickness / 2)
    return T


# --- inverse kinematics ---------------------------------------------------------------------
class IKFailure(RuntimeError):
    """A pose the arm cannot reach (from this rail position, when the rail is held)."""


@dataclass
class IKSolution:
    q: np.ndarray  #: the seven joint values, rail first
    position_error: float  #: m
    angle_error: float  #: rad
    iterations: int


class ArmIK:
    """Inverse kinematics of the rail and arm with mink (quadratic program, ``daqp`` solver).

    One ``FrameTask`` puts the TCP at the target; a light ``PostureTask`` keeps the arm near the
    seed (so that consecutive points of a path give a continuous joint path); ``ConfigurationLimit``
    keeps every joint inside its range. The rail can be held where it is (``hold_rail=True``):
    the paper gives the arm's motion priority over the base's, so the planner first asks the
    arm alone to reach a pose, and moves the base only when it cannot (``drywall_lab.rc.motion``).
    """

    def __init__(self, rail_y: float = RAIL_Y) -> None:
        self.model = mujoco.MjModel.from_xml_string(robot_mjcf(rail_y))
        self.configuration = mink.Configuration(self.model)
        self.frame_task = mink.FrameTask(TCP_SITE, "site", position_cost=1.0, orientation_cost=1.0, lm_damping=1e-6)
        self.posture_task = mink.PostureTask(self.model, cost=np.array([0.0, 1e-3, 1e-3, 1e-3, 2e-4, 2e-4, 2e-4]))
        self.limits = [mink.ConfigurationLimit(self.model, gain=0.5, min_distance_from_limits=0.02)]
        self.hold = mink.DofFreezingTask(self.model, dof_indices=[0])
        self.lower = self.model.jnt_range[:, 0].copy()
        self.upper = self.model.jnt_range[:, 1].copy()

    def fk(self, q: np.ndarray) -> np.ndarray:
        """The TCP's world transform at joint values ``q``."""
        self.configuration.update(np.asarray(q, dtype=float))
        return self.configuration.get_transform_frame_to_world(TCP_SITE, "site").as_matrix()

    def solve(self, target: np.ndarray, seed: np.ndarray, hold_rail: bool = True, max_iterations: int = 200,
              position_tolerance: float = 1e-5, angle_tolerance: float = 1e-5) -> IKSolution:
        """Joint values putting the TCP at ``target`` (4x4), starting from ``seed``; ``IKFailure`` if none."""
        q = np.clip(np.asarray(seed, dtype=float), self.lower + 1e-9, self.upper - 1e-9)
        cfg = self.configuration
        cfg.update(q)
        self.frame_task.set_target(mink.SE3.from_matrix(target))
        self.posture_task.set_target(q)
        constraints = [self.hold] if hold_rail else []
        pos_err = ang_err = np.inf
        for it in range(1, max_iterations + 1):
            velocity = mink.solve_ik(configuration=cfg, tasks=[self.frame_task, self.posture_task], dt=1.0,
                                     solver="daqp", damping=1e-5, limits=self.limits,
                                     constraints=constraints)
            cfg.integrate_inplace(velocity, 1.0)
            err = self.frame_task.compute_error(cfg)
            pos_err, ang_err = float(np.linalg.norm(err[:3])), float(np.linalg.norm(err[3:]))
            if pos_err < position_tolerance and ang_err < angle_tolerance:
                solution = cfg.q.copy()
                if hold_rail:
                    solution[0] = q[0]  # exactly where it was (the frozen joint drifts by rounding only)
                return IKSolution(solution, pos_err, ang_err, it)
            if it > 20 and np.linalg.norm(velocity) < 1e-7:
                break
        raise IKFailure(f"the TCP cannot reach the pose (left {pos_err * 1000:.1f} mm, "
                        f"{np.degrees(ang_err):.2f} deg off after {it} iterations)")

    @cached_property
    def home(self) -> np.ndarray:
        """The arm's resting posture (rail at 0): facing the stacks, pad down, 1.1 m above the floor."""
        seed = np.radians([0.0, 150.0, -10.0, 30.0, 0.0, 70.0, 0.0])
        seed[0] = 0.0
        target = pose_matrix((1.0, 2.0, 1.1), (0.0, 1.0, 0.0, 0.0))  # TCP z pointing down
        return self.solve(target, seed, hold_rail=True, max_iterations=400).q
