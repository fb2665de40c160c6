"""Notebook 05 (robot control), exercise "softer servos": reference solution.

Reference solution: try the exercise first (``check_servo_gains(softer, KP_SCALE)`` in the notebook checks your
gain rule on every joint, then runs a placement with your servos and says why it fails, if it does).
"""
from __future__ import annotations

from drywall_lab.rc.robot import ServoGains


def softer(gains: ServoGains, kp_scale: float) -> ServoGains:
    """The servo's gains with its stiffness kp scaled by kp_scale, its damping ratio and force limit kept.

    For a joint of inertia J the damping ratio is kv / (2 sqrt(kp J)): it stays the same when kv scales with the
    square root of kp's scale. The force limit is the motor's, not the controller's.
    """
    return ServoGains(kp=gains.kp * kp_scale, kv=gains.kv * kp_scale ** 0.5, force=gains.force)


#: A tenth of the robot's stiffness: within ``SOFTEST_ASKED`` (0.2), and the placement stays within tolerance;
#: at 0.02 the servos lag and sag so far that the panel hits something.
KP_SCALE = 0.1

#: Notebook 05 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
