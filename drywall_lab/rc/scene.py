"""The MuJoCo scene, built from the site tables: floor, studs, panel stacks, installed panels, robot.

Everything comes from ``Site`` / ``SiteState`` (the paper's Fig. 5 and the tables of Fig. 9,
fixed by the spec's section 1): 13 studs as boxes in the plane y = 0, every panel as a free
body (a box with the panel's own axes, ``Pose``) lying in its stack at ``Site.pick_pose`` or,
if the state says it is installed, on the wall at ``Site.place_pose`` held by its screws.
The robot is ``robot.robot_mjcf``, merged in.

Two equality welds per panel, both off until switched on while the simulation runs:
``grip_<id>`` (the vacuum lifter's pad holding the panel) and ``screws_<id>`` (the panel
fastened to the wall once installed). A weld is always switched on at the two bodies'
*actual* relative pose (``Scene.activate_weld``), never at a planned one, so that what the
simulation measures afterwards is what the robot really did.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
import math
from dataclasses import dataclass, field
from typing import Mapping

import mujoco
import numpy as np

from drywall_lab.rc.robot import (ENV_BIT, JOINTS, PANEL_BIT, RAIL_Y, ROBOT_BIT, TCP_SITE, TOOL_BODY, ServoGains,
                                  robot_mjcf)
from drywall_lab.rc.settings import TIMESTEP
from drywall_lab.site import FOOT, Panel, Pose, SiteState

#: Mass per square metre of 1/2 in drywall: a 4 x 8 ft sheet weighs about 25 kg (55 lb).
AREAL_DENSITY = 25.0 / (4 * 8 * FOOT**2)
#: The welds' constraint stiffness (time constant, damping ratio): stiff but stable at 2 ms.
WELD_SOLREF = (0.004, 1.0)

PANEL_COLOURS = {"left": "0.96 0.82 0.25 1", "middle": "0.52 0.76 0.91 1", "right": "0.95 0.58 0.54 1"}


def panel_mass(panel: Panel) -> float:
    """The panel's mass (kg) from its size: 25 kg for a standard 4 x 8 sheet."""
    return AREAL_DENSITY * panel.w * panel.l


def _fmt(values) -> str:
    return " ".join(f"{float(v):.6g}" for v in values)


def site_mjcf(state: SiteState) -> str:
    """The scene as one MJCF document: the site's floor, studs and panels plus the robot."""
    site = state.site
    installed = {i.drywall_id: i for i in state.installed}
    world = [
        f'<geom name="floor" type="plane" size="8 6 0.1" pos="2.4 1.2 0" rgba="0.8 0.8 0.78 1" '
        f'contype="{ENV_BIT}" conaffinity="{PANEL_BIT | ROBOT_BIT}"/>'
    ]
    for stud in site.studs:
        world.append(
            f'<geom name="stud_{stud.stud_id}" type="box" pos="{stud.x_center:.5f} 0 {stud.height / 2:.5f}" '
            f'size="{stud.width / 2:.5f} {stud.depth / 2:.5f} {stud.height / 2:.5f}" rgba="0.55 0.43 0.39 1" '
            f'contype="{ENV_BIT}" conaffinity="{PANEL_BIT | ROBOT_BIT}"/>'
        )
    equality = []
    for panel in site.panels:
        pid = panel.drywall_id
        done = pid in installed
        if done:
            item = installed[pid]
            pose = site.place_pose(panel, item.stud_id, item.placement)
        else:
            pose = site.pick_pose(panel)
        world.append(
            f'<body name="panel_{pid}" pos="{_fmt(pose.position)}" quat="{_fmt(pose.quaternion)}">'
            f'<freejoint name="panel_{pid}"/>'
            f'<geom name="panel_{pid}" type="box" size="{panel.w / 2:.5f} {panel.thickness / 2:.5f} {panel.l / 2:.5f}" '
            f'mass="{panel_mass(panel):.4f}" rgba="{PANEL_COLOURS[panel.stack]}" '
            f'contype="{PANEL_BIT}" conaffinity="{ENV_BIT | PANEL_BIT | ROBOT_BIT}"/></body>'
        )
        solref = _fmt(WELD_SOLREF)
        equality.append(f'<weld name="grip_{pid}" body1="{TOOL_BODY}" body2="panel_{pid}" active="false" '
                        f'solref="{solref}"/>')
        # an installed panel starts fastened where the state says it is (the initial condition of a partly built wall)
        relpose = f' relpose="{_fmt(pose.position)} {_fmt(pose.quaternion)}"' if done else ""
        equality.append(f'<weld name="screws_{pid}" body1="world" body2="panel_{pid}" active="{str(done).lower()}"'
                        f'{relpose} solref="{solref}"/>')

    robot = ET.fromstring(robot_mjcf(RAIL_Y))
    doc = ET.fromstring(
        f"""<mujoco model="drywall_site">
  <compiler angle="degree" autolimits="true"/>
  <option timestep="{TIMESTEP}" integrator="implicitfast" cone="pyramidal" iterations="30" ls_iterations="12"/>
  <visual><global offwidth="640" offheight="480"/></visual>
  <default/>
  <worldbody>
    <light pos="2.4 1.5 4" dir="0 0 -1" directional="true"/>
    {''.join(world)}
  </worldbody>
  <equality>{''.join(equality)}</equality>
</mujoco>"""
    )
    # merge the robot's defaults, bodies and actuators into the scene
    doc.find("default").extend(list(robot.find("default")))
    doc.find("worldbody").extend(list(robot.find("worldbody")))
    doc.append(robot.find("actuator"))
    ET.indent(doc)
    return ET.tostring(doc, encoding="unicode")


@dataclass
class Scene:
    """A compiled scene and the ids the controller needs; build it with ``build_scene``."""

    state: SiteState
    model: mujoco.MjModel
    data: mujoco.MjData
    panel_body: dict[str, int] = field(default_factory=dict)
    panel_geom: dict[str, int] = field(default_factory=dict)
    stud_geom: dict[str, int] = field(default_factory=dict)
    grip_weld: dict[str, int] = field(default_factory=dict)
    screws_weld: dict[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        m = self.model
        name = lambda kind, n: mujoco.mj_name2id(m, kind, n)  # noqa: E731
        for panel in self.state.site.panels:
            pid = panel.drywall_id
            self.panel_body[pid] = name(mujoco.mjtObj.mjOBJ_BODY, f"panel_{pid}")
            self.panel_geom[pid] = name(mujoco.mjtObj.mjOBJ_GEOM, f"panel_{pid}")
            self.grip_weld[pid] = name(mujoco.mjtObj.mjOBJ_EQUALITY, f"grip_{pid}")
            self.screws_weld[pid] = name(mujoco.mjtObj.mjOBJ_EQUALITY, f"screws_{pid}")
        for stud in self.state.site.studs:
            self.stud_geom[stud.stud_id] = name(mujoco.mjtObj.mjOBJ_GEOM, f"stud_{stud.stud_id}")
        self.floor_geom = name(mujoco.mjtObj.mjOBJ_GEOM, "floor")
        self.tcp_site = name(mujoco.mjtObj.mjOBJ_SITE, TCP_SITE)
        self.tool_body = name(mujoco.mjtObj.mjOBJ_BODY, TOOL_BODY)
        self.pad_geom = name(mujoco.mjtObj.mjOBJ_GEOM, "lifter_pad")
        joint_ids = [name(mujoco.mjtObj.mjOBJ_JOINT, j) for j in JOINTS]
        self.qpos_index = np.array([m.jnt_qposadr[j] for j in joint_ids])
        self.dof_index = np.array([m.jnt_dofadr[j] for j in joint_ids])
        self.actuator_index = np.array([name(mujoco.mjtObj.mjOBJ_ACTUATOR, f"servo_{j}") for j in JOINTS])
        self.kp = m.actuator_gainprm[self.actuator_index, 0].copy()
        self.kv = -m.actuator_biasprm[self.actuator_index, 2].copy()
        carriage = name(mujoco.mjtObj.mjOBJ_BODY, "carriage")
        robot_bodies = {b for b in range(m.nbody) if self._descends_from(b, carriage)}
        self.robot_bodies = np.array(sorted(robot_bodies))
        self.robot_geom_mask = np.array([m.geom_bodyid[g] in robot_bodies and m.geom_contype[g] != 0
                                         for g in range(m.ngeom)])

    def _descends_from(self, body: int, ancestor: int) -> bool:
        while body > 0:
            if body == ancestor:
                return True
            body = self.model.body_parentid[body]
        return False

    # --- reading the simulation -------------------------------------------------------
    @property
    def q(self) -> np.ndarray:
        """The robot's seven joint values (rail first)."""
        return self.data.qpos[self.qpos_index].copy()

    @property
    def qd(self) -> np.ndarray:
        return self.data.qvel[self.dof_index].copy()

    def panel_pose(self, drywall_id: str) -> Pose:
        """Where the panel's body is now (centre and quaternion)."""
        b = self.panel_body[drywall_id]
        return Pose(tuple(float(v) for v in self.data.xpos[b]), tuple(float(v) for v in self.data.xquat[b]))

    def tcp_matrix(self) -> np.ndarray:
        """The TCP's world transform now."""
        T = np.eye(4)
        T[:3, :3] = self.data.site_xmat[self.tcp_site].reshape(3, 3)
        T[:3, 3] = self.data.site_xpos[self.tcp_site]
        return T

    def geom_name(self, geom: int) -> str:
        return mujoco.mj_id2name(self.model, mujoco.mjtObj.mjOBJ_GEOM, geom) or f"geom{geom}"

    # --- welds --------------------------------------------------------------------------
    def activate_weld(self, eq_id: int) -> None:
        """Switch a weld on at the two bodies' present relative pose (body2 in body1's frame)."""
        m, d = self.model, self.data
        b1, b2 = m.eq_obj1id[eq_id], m.eq_obj2id[eq_id]
        q1_inv = np.zeros(4)
        mujoco.mju_negQuat(q1_inv, d.xquat[b1])
        relpos = np.zeros(3)
        mujoco.mju_rotVecQuat(relpos, d.xpos[b2] - d.xpos[b1], q1_inv)
        relquat = np.zeros(4)
        mujoco.mju_mulQuat(relquat, q1_inv, d.xquat[b2])
        m.eq_data[eq_id, 0:3] = 0.0  # anchor at body2's origin
        m.eq_data[eq_id, 3:6] = relpos
        m.eq_data[eq_id, 6:10] = relquat
        d.eq_active[eq_id] = 1

    def deactivate_weld(self, eq_id: int) -> None:
        self.data.eq_active[eq_id] = 0

    # --- servos ---------------------------------------------------------------------------
    def set_servo_gains(self, gains: Mapping[str, ServoGains]) -> None:
        """Give the named joints' servos other gains and force limits (``robot.SERVOS`` otherwise); a
        ``ValueError`` for an unknown joint or a gain that is not a positive finite number (``kv`` may be 0)."""
        unknown = sorted(set(gains) - set(JOINTS))
        if unknown:
            raise ValueError(f"no joint {', '.join(map(repr, unknown))}: the joints are {', '.join(JOINTS)}")
        m = self.model
        for j, name in enumerate(JOINTS):
            if name not in gains:
                continue
            g = gains[name]
            values = {"kp": g.kp, "kv": g.kv, "force": g.force}
            for key, value in values.items():
                if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value) \
                        or value < 0 or (value == 0 and key != "kv"):
                    raise ValueError(f"servo {name}: {key} must be a positive number, not {value!r}")
            a = self.actuator_index[j]
            m.actuator_gainprm[a, 0] = g.kp
            m.actuator_biasprm[a, 1] = -g.kp
            m.actuator_biasprm[a, 2] = -g.kv
            m.actuator_forcerange[a] = (-g.force, g.force)
            self.kp[j], self.kv[j] = g.kp, g.kv


def build_scene(state: SiteState, rail_x: float = 0.0, arm: np.ndarray | None = None) -> Scene:
    """Compile the scene for ``state`` with the robot's carriage at ``rail_x`` and the arm at ``arm`` (6 values)."""
    model = mujoco.MjModel.from_xml_string(site_mjcf(state))
    data = mujoco.MjData(model)
    scene = Scene(state, model, data)
    q = np.zeros(len(JOINTS))
    q[0] = rail_x
    if arm is not None:
        q[1:] = arm
    data.qpos[scene.qpos_index] = q
    data.ctrl[scene.actuator_index] = q
    mujoco.mj_forward(model, data)
    return scene
