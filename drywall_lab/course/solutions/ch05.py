"""Notebook 05 (robot control), exercises "softer servos" and, from scratch, "one step of differential IK":
reference solutions.

Reference solutions: try the exercise first (``check_servo_gains(softer, KP_SCALE)`` in the notebook checks your
gain rule on every joint, then runs a placement with your servos and says why it fails, if it does;
``check_ik_step(ik_step)`` compares your step with the closed form and tries it on the robot).
"""
from __future__ import annotations

import numpy as np

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

def ik_step(jacobian: np.ndarray, error: np.ndarray, damping: float) -> np.ndarray:
    """From scratch: one damped least-squares step of differential IK, dq = J^T (J J^T + damping^2 I)^-1 e.

    It minimises |J dq - e|^2 + damping^2 |dq|^2; the m x m system (m rows of J) is solved, not inverted, and
    damping^2 I keeps it solvable where J J^T is singular (``check_ik_step(ik_step)`` in the notebook).
    """
    J = np.asarray(jacobian, dtype=float)
    e = np.asarray(error, dtype=float)
    return J.T @ np.linalg.solve(J @ J.T + damping**2 * np.eye(J.shape[0]), e)


#: Notebook 05 ends with no "Questions" cell.
ANSWERS: dict[int, str] = {}
