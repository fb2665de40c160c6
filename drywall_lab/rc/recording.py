"""What a simulation leaves behind: body poses for the animation, joint traces for the plots."""
from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from drywall_lab.rc.robot import JOINTS


@dataclass
class Recording:
    """Poses of the bodies that can move (robot links, panels), sampled ``fps`` times per simulated second.

    ``captions`` are ``(time, text)`` notes (which command, which stage) for the animation's viewer.
    """

    body_names: list[str]
    body_ids: np.ndarray
    fps: float
    times: list[float] = field(default_factory=list)
    positions: list[np.ndarray] = field(default_factory=list)
    quaternions: list[np.ndarray] = field(default_factory=list)
    captions: list[tuple[float, str]] = field(default_factory=list)

    @classmethod
    def for_model(cls, model: mujoco.MjModel, fps: float) -> "Recording":
        ids = np.array([b for b in range(1, model.nbody) if model.body_dofnum[b] > 0 or model.body_parentid[b] > 0])
        names = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, int(b)) for b in ids]
        return cls(names, ids, fps)

    def due(self, time: float) -> bool:
        return not self.times or time >= self.times[-1] + 1.0 / self.fps - 1e-9

    def capture(self, data: mujoco.MjData, time: float) -> None:
        self.times.append(time)
        self.positions.append(data.xpos[self.body_ids].copy())
        self.quaternions.append(data.xquat[self.body_ids].copy())

    def caption(self, time: float, text: str) -> None:
        self.captions.append((time, text))

    @property
    def duration(self) -> float:
        return self.times[-1] - self.times[0] if self.times else 0.0

    def __len__(self) -> int:
        return len(self.times)


@dataclass
class JointTrace:
    """Set points and measured joint values of one placement, about 50 samples per second.

    ``stages`` holds ``(name, start, end)`` in simulated seconds from the placement's start.
    """

    times: list[float] = field(default_factory=list)
    q: list[np.ndarray] = field(default_factory=list)
    q_set: list[np.ndarray] = field(default_factory=list)
    stages: list[tuple[str, float, float]] = field(default_factory=list)

    def add(self, time: float, q: np.ndarray, q_set: np.ndarray) -> None:
        self.times.append(time)
        self.q.append(q)
        self.q_set.append(q_set)

    def frame(self):
        """A pandas DataFrame: ``time`` and, per joint, the measured value and the set point."""
        import pandas as pd

        q, q_set = np.array(self.q), np.array(self.q_set)
        data = {"time": self.times}
        for j, name in enumerate(JOINTS):
            data[name] = q[:, j]
            data[f"{name}_set"] = q_set[:, j]
        return pd.DataFrame(data)

    @property
    def largest_tracking_error(self) -> np.ndarray:
        """Per joint, the largest |set point - measured| over the placement (m for the rail, rad for the arm)."""
        return np.max(np.abs(np.array(self.q) - np.array(self.q_set)), axis=0)

    def stage_table(self):
        """A pandas DataFrame: each stage the robot ran, from and to (simulated s from the placement's start),
        and whether the base or the arm moved (the paper's arm-before-base rule: never both)."""
        import pandas as pd

        table = pd.DataFrame(self.stages, columns=["stage", "from (s)", "to (s)"]).round(2)
        table["moves"] = ["base" if name.startswith("base") else "arm" for name in table.stage]
        return table

    def tracking_table(self):
        """A pandas DataFrame: per joint, the largest |set point - measured| in mm (rail) or degrees (arm)."""
        import pandas as pd

        error = self.largest_tracking_error
        return pd.DataFrame({"joint": JOINTS, "largest |set point - measured|": [
            f"{e * 1000:.2f} mm" if j == 0 else f"{np.degrees(e):.3f} deg" for j, e in enumerate(error)]})
