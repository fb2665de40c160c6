"""Robot control (the paper's RC module, Figs. 5-6 and 15-18): the drywall site simulated in MuJoCo.

- ``scene``: the MJCF of the site (floor, studs, panel stacks) and the robot, from the site tables;
- ``robot``: the rail-mounted 6-axis arm with its vacuum lifter, and inverse kinematics (mink);
- ``motion``: the stages of a pick-and-place, planned and timed (the arm before the base);
- ``collision``: the planner's collision check, the carried panel counted as part of the robot;
- ``contacts``: the contacts watched while the simulation runs;
- ``cell``: ``RobotCell``, the simulated site that carries out ``RobotCommand`` s;
- ``placement``: ``PlacementResult`` and how the placed panel is measured;
- ``recording``: body poses for animations, joint traces for plots;
- ``episode``: instructions -> tags -> commands -> motion, one instruction at a time;
- ``batch``: the ``simulate`` command's records (spec section 6's ``run`` fields plus each placement);
- ``layouts``: the paper's three layouts replayed through the whole pipeline and checked;
- ``exercises``: the checks of notebooks 05 and 06's exercises;
- ``settings``: time step, and the frames recorded in and out of the course's fast mode (``DRYWALL_FAST``).
"""
from drywall_lab.rc.cell import RobotCell
from drywall_lab.rc.contacts import ContactEvent
from drywall_lab.rc.episode import EpisodeRun, EpisodeStep, goes_on_after, simulate_episode
from drywall_lab.rc.layouts import LayoutReplay, replay_layout
from drywall_lab.rc.motion import MotionPlanner, PlacementPlan, PlanningError, Stage
from drywall_lab.rc.placement import ANGLE_TOLERANCE_DEG, POSITION_TOLERANCE, PlacementResult, pose_error
from drywall_lab.rc.recording import JointTrace, Recording
from drywall_lab.rc.robot import JOINTS, RAIL_Y, SERVOS, ArmIK, ServoGains, joint_table, robot_mjcf
from drywall_lab.rc.scene import AREAL_DENSITY, Scene, build_scene, panel_mass, site_mjcf
from drywall_lab.rc.settings import record_fps

__all__ = [
    "ANGLE_TOLERANCE_DEG", "AREAL_DENSITY", "ArmIK", "ContactEvent", "EpisodeRun", "EpisodeStep", "JOINTS",
    "JointTrace", "LayoutReplay", "MotionPlanner", "POSITION_TOLERANCE", "PlacementPlan", "PlacementResult",
    "PlanningError", "RAIL_Y", "Recording", "RobotCell", "SERVOS", "Scene", "ServoGains", "Stage", "build_scene",
    "goes_on_after", "joint_table", "panel_mass", "pose_error", "record_fps", "replay_layout",
    "robot_mjcf", "simulate_episode", "site_mjcf",
]
