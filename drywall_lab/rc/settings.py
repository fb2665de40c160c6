"""Run settings for robot control: the simulation's time step and what the fast mode changes.

``DRYWALL_FAST=1`` (the project's fast mode, read by ``drywall_lab.fast.fast_mode``, see the
README) makes the notebooks record fewer animation frames; the physics, the motion and every
measured figure stay the same, so a fast run's placement errors are the real ones.
"""
from __future__ import annotations

from drywall_lab.fast import fast_mode

#: Simulation time step (s). 2 ms is small enough for the stiff joint servos and contacts.
TIMESTEP = 0.002
#: Servo (control) period (s): the joint set points are updated every control step.
CONTROL_PERIOD = 0.004
#: Animation frames per second recorded for meshcat, in full and in fast mode.
RECORD_FPS = 20.0
RECORD_FPS_FAST = 8.0


def record_fps() -> float:
    """Frames per second for recordings: fewer in the course's fast mode (``drywall_lab.fast.fast_mode``)."""
    return RECORD_FPS_FAST if fast_mode() else RECORD_FPS
