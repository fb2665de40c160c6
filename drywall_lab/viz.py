"""Seeing the robot cell: a meshcat 3D scene (live, or recorded as a self-contained HTML animation)
and matplotlib drawings as the quick fallback.

The paper shows its robot in Gazebo (Figs. 16-18). Here the scene is drawn from the MuJoCo
model's own geoms (boxes, cylinders, the floor plane), so there is nothing to keep in step:

- ``MeshcatScene``: the geoms in meshcat, grouped by body. ``update(data)`` moves the bodies
  to the simulation's state (live in JupyterLab with ``live()``); ``animate(recording)``
  turns a ``Recording`` into a meshcat animation; ``html()`` / ``embed()`` / ``save_html()``
  give the scene and its animation as one self-contained HTML page that plays without a server.
  No OpenGL is needed: the browser draws it.
- ``draw_elevation``: a matplotlib elevation (or plan) of the same geoms at one moment;
  ``draw_film``: a row of such drawings through a recording; ``plot_joint_trajectories``:
  set points against measured joint values for one placement.

All meshcat code lives in this module, so it can be replaced without touching the simulation.
"""
from __future__ import annotations

import html as html_lib
from pathlib import Path
from typing import Sequence

import matplotlib.pyplot as plt
import mujoco
import numpy as np
from matplotlib.patches import Polygon

from drywall_lab.rc.recording import JointTrace, Recording

ROOT = "drywall"
#: Keyframes are dropped while linear interpolation between the kept ones stays this close.
KEY_POSITION_TOLERANCE = 0.002  # m
KEY_ANGLE_TOLERANCE_DEG = 0.5
MAX_KEY_GAP = 120  # frames


# --- geometry ------------------------------------------------------------------------------------
def _rgb(rgba: np.ndarray) -> int:
    r, g, b = (np.clip(rgba[:3], 0, 1) * 255).astype(int)
    return int(r) << 16 | int(g) << 8 | int(b)


def _body_name(model: mujoco.MjModel, body: int) -> str:
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or f"body{body}"


def _geom_name(model: mujoco.MjModel, geom: int) -> str:
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, geom) or f"geom{geom}"


def _quat_matrix(quat: np.ndarray) -> np.ndarray:
    mat = np.zeros(9)
    mujoco.mju_quat2Mat(mat, np.asarray(quat, dtype=float))
    return mat.reshape(3, 3)


def _transform(pos: np.ndarray, quat: np.ndarray) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = _quat_matrix(quat)
    T[:3, 3] = pos
    return T


def geom_shapes(model: mujoco.MjModel, geom: int) -> list[tuple[str, tuple, np.ndarray]]:
    """The geom as simple shapes in its body's frame: ``(kind, dimensions, 4x4 local transform)``.

    ``kind`` is ``box`` (full lengths), ``cylinder`` (height, radius; along z) or ``sphere`` (radius).
    A capsule is a cylinder with two spheres; the floor plane is a thin box just under z = 0.
    """
    gtype, size = model.geom_type[geom], model.geom_size[geom]
    local = _transform(model.geom_pos[geom], model.geom_quat[geom])
    t = mujoco.mjtGeom
    if gtype == t.mjGEOM_BOX:
        return [("box", tuple(2 * size), local)]
    if gtype == t.mjGEOM_PLANE:
        below = local.copy()
        below[:3, 3] = local[:3, 3] - local[:3, 2] * 0.005
        return [("box", (2 * size[0], 2 * size[1], 0.01), below)]
    if gtype == t.mjGEOM_CYLINDER:
        return [("cylinder", (2 * size[1], size[0]), local)]
    if gtype == t.mjGEOM_SPHERE:
        return [("sphere", (size[0],), local)]
    if gtype == t.mjGEOM_CAPSULE:
        shapes = [("cylinder", (2 * size[1], size[0]), local)]
        for sign in (-1, 1):
            end = local.copy()
            end[:3, 3] = local[:3, 3] + sign * size[1] * local[:3, 2]
            shapes.append(("sphere", (size[0],), end))
        return shapes
    raise ValueError(f"geom {_geom_name(model, geom)}: type {gtype} is not drawn (boxes, cylinders, spheres, "
                     "capsules and planes are)")


def visible_geoms(model: mujoco.MjModel) -> list[int]:
    """Geoms to draw: all but those made invisible (alpha 0)."""
    return [g for g in range(model.ngeom) if model.geom_rgba[g, 3] > 0]


# --- meshcat -----------------------------------------------------------------------------------------
class MeshcatScene:
    """The MuJoCo model's geoms in a meshcat viewer, one node per body (see the module's docstring).

    Creating one starts meshcat's server process on this machine's loopback (``meshcat.Visualizer``);
    ``close()`` stops it.
    """

    def __init__(self, model: mujoco.MjModel, visualizer=None) -> None:
        import meshcat

        self.model = model
        self.vis = visualizer if visualizer is not None else meshcat.Visualizer()
        self._own_server = visualizer is None
        self.root = self.vis[ROOT]
        self.root.delete()
        self.moving_bodies = sorted({int(model.geom_bodyid[g]) for g in visible_geoms(model)} - {0})
        self._draw_geoms()
        self._place_camera()

    # drawing
    def _node(self, body: int):
        return self.root["world"] if body == 0 else self.root[_body_name(self.model, body)]

    def _draw_geoms(self) -> None:
        import meshcat.geometry as mg

        m = self.model
        for geom in visible_geoms(m):
            rgba = m.geom_rgba[geom]
            material = mg.MeshLambertMaterial(color=_rgb(rgba), opacity=float(rgba[3]), transparent=bool(rgba[3] < 1))
            for k, (kind, dims, local) in enumerate(geom_shapes(m, geom)):
                if kind == "box":
                    shape, fix = mg.Box(list(dims)), np.eye(4)
                elif kind == "cylinder":  # meshcat's cylinders run along y, MuJoCo's along z
                    shape = mg.Cylinder(height=dims[0], radius=dims[1])
                    fix = _transform(np.zeros(3), (0.70710678, 0.70710678, 0, 0))
                else:
                    shape, fix = mg.Sphere(dims[0]), np.eye(4)
                node = self._node(int(m.geom_bodyid[geom]))[f"{_geom_name(m, geom)}_{k}" if k else _geom_name(m, geom)]
                node.set_object(shape, material)
                node.set_transform(local @ fix)

    def _place_camera(self) -> None:
        """Look at the wall from behind the robot, slightly from above."""
        self.vis["/Cameras/default"].set_transform(_transform(np.array([2.4, 1.2, 0.9]), (1, 0, 0, 0)))
        # the camera's own frame is y-up: (x, z, -y) in the world's terms
        self.vis["/Cameras/default/rotated/<object>"].set_property("position", [0.6, 2.6, -5.2])

    def update(self, data: mujoco.MjData) -> None:
        """Move every body to where the simulation has it now."""
        for b in self.moving_bodies:
            self._node(b).set_transform(_transform(data.xpos[b], data.xquat[b]))

    def live(self, height: int = 480):
        """The viewer in a notebook cell, connected to the server (for JupyterLab on this machine)."""
        return self.vis.jupyter_cell(height=height)

    # animation
    def animate(self, recording: Recording | Sequence[Recording], repetitions: int = 1, speed: float = 1.0,
                position_tolerance: float = KEY_POSITION_TOLERANCE,
                angle_tolerance_deg: float = KEY_ANGLE_TOLERANCE_DEG) -> int:
        """Send the recording (or several, played one after another) as a meshcat animation; returns
        the number of keyframes kept.

        Frames are thinned: a body's frame is kept only where linear interpolation between the kept
        frames would be off by more than ``position_tolerance`` (m) or ``angle_tolerance_deg``.
        ``speed`` > 1 plays faster than real time.
        """
        from meshcat.animation import Animation

        recording = recording if isinstance(recording, Recording) else join_recordings(recording)
        if len(recording) == 0:
            raise ValueError("the recording is empty: build the cell with record_fps to record")
        fps = recording.fps * speed
        anim = Animation(default_framerate=fps)
        times = np.asarray(recording.times) - recording.times[0]
        frames = np.rint(times * recording.fps).astype(int)
        positions = np.array(recording.positions)
        quaternions = _continuous(np.array(recording.quaternions))
        index = {b: i for i, b in enumerate(recording.body_ids)}
        kept_total = 0
        for b in self.moving_bodies:
            if b not in index:
                continue
            i = index[b]
            keep = keyframes(times, positions[:, i], quaternions[:, i], position_tolerance, angle_tolerance_deg)
            kept_total += len(keep)
            name = _body_name(self.model, b)
            for k in keep:
                with anim.at_frame(self.root, int(frames[k])) as frame:
                    frame[name].set_transform(_transform(positions[k, i], quaternions[k, i]))
        self.vis.set_animation(anim, play=True, repetitions=repetitions)
        return kept_total

    # static export
    def html(self) -> str:
        """The scene (and its animation, if any) as one self-contained HTML page."""
        return self.vis.static_html()

    def save_html(self, path: Path | str) -> Path:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(self.html(), encoding="utf-8")
        return path

    def embed(self, height: int = 460):
        """The static page in a notebook output (an iframe with the page inline): plays without a server."""
        from IPython.display import HTML

        return HTML(iframe_html(self.html(), height))

    def close(self) -> None:
        """Stop the meshcat server this scene started."""
        proc = getattr(self.vis.window, "server_proc", None)
        if self._own_server and proc is not None and proc.poll() is None:
            proc.kill()
            proc.wait()


def iframe_html(page: str, height: int = 460) -> str:
    """An iframe that holds ``page`` inline (``srcdoc``), resizable."""
    return (f'<div style="height: {height}px; width: 100%; overflow: hidden; resize: both">'
            f'<iframe srcdoc="{html_lib.escape(page, quote=True)}" style="width: 100%; height: 100%; border: none">'
            f"</iframe></div>")


def join_recordings(recordings: Sequence[Recording]) -> Recording:
    """Recordings of the same scene one after another (each later one shifted to start after the last)."""
    first = recordings[0]
    joined = Recording(first.body_names, first.body_ids, first.fps)
    offset = 0.0
    for rec in recordings:
        if list(rec.body_ids) != list(first.body_ids) or rec.fps != first.fps:
            raise ValueError("only recordings of the same model at the same frame rate can be joined")
        if not rec.times:
            continue
        shift = offset - rec.times[0]
        joined.times += [t + shift for t in rec.times]
        joined.positions += rec.positions
        joined.quaternions += rec.quaternions
        joined.captions += [(t + shift, text) for t, text in rec.captions]
        offset = joined.times[-1] + 1.0 / first.fps
    return joined


def _continuous(quaternions: np.ndarray) -> np.ndarray:
    """Flip signs so that consecutive quaternions (frames along axis 0) lie on the same side."""
    q = quaternions.copy()
    for k in range(1, len(q)):
        flip = np.sum(q[k] * q[k - 1], axis=-1) < 0
        q[k][flip] *= -1
    return q


def keyframes(times: np.ndarray, positions: np.ndarray, quaternions: np.ndarray,
              position_tolerance: float = KEY_POSITION_TOLERANCE,
              angle_tolerance_deg: float = KEY_ANGLE_TOLERANCE_DEG) -> list[int]:
    """Indices of the frames to keep for one body (see ``MeshcatScene.animate``); first and last always."""
    n = len(times)
    if n <= 2:
        return list(range(n))
    keep = [0]
    start = 0
    for end in range(2, n):
        span = slice(start, end + 1)
        t = (times[span] - times[start]) / (times[end] - times[start])
        p = positions[start] + t[:, None] * (positions[end] - positions[start])
        q = quaternions[start] + t[:, None] * (quaternions[end] - quaternions[start])
        q /= np.linalg.norm(q, axis=1, keepdims=True)
        pos_dev = np.max(np.linalg.norm(p - positions[span], axis=1))
        cos = np.clip(np.abs(np.sum(q * quaternions[span], axis=1)), 0, 1)
        ang_dev = np.max(2 * np.arccos(cos))
        if pos_dev > position_tolerance or ang_dev > np.radians(angle_tolerance_deg) or end - start > MAX_KEY_GAP:
            start = end - 1
            keep.append(start)
    keep.append(n - 1)
    return keep


# --- matplotlib ------------------------------------------------------------------------------------------
def _shape_corners(kind: str, dims: tuple, T: np.ndarray) -> np.ndarray:
    if kind == "box":
        half = np.array(dims) / 2
    elif kind == "cylinder":
        half = np.array([dims[1], dims[1], dims[0] / 2])
    else:
        half = np.array([dims[0]] * 3)
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    return (T[:3, :3] @ (signs * half).T).T + T[:3, 3]


def _hull(points: np.ndarray) -> np.ndarray:
    """Convex hull of 2D points (monotone chain)."""
    pts = sorted(set(map(tuple, np.round(points, 6))))
    if len(pts) <= 2:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def draw_elevation(model: mujoco.MjModel, body_poses: dict[int, tuple[np.ndarray, np.ndarray]] | mujoco.MjData,
                   ax: plt.Axes | None = None, view: str = "front", title: str | None = None) -> plt.Axes:
    """The geoms at one moment, projected: ``front`` (x-z, the wall as the worker faces it) or ``top`` (x-y).

    ``body_poses`` is an ``MjData`` or ``{body id: (position, quaternion)}`` (a recording's frame).
    The floor is left out; nearer geoms are drawn over farther ones.
    """
    ax = ax or plt.subplots(figsize=(10, 4.5))[1]
    if isinstance(body_poses, mujoco.MjData):
        body_poses = {b: (body_poses.xpos[b], body_poses.xquat[b]) for b in range(model.nbody)}
    axes, depth_axis = ((0, 2), 1) if view == "front" else ((0, 1), 2)
    patches = []
    for geom in visible_geoms(model):
        if model.geom_type[geom] == mujoco.mjtGeom.mjGEOM_PLANE:
            continue
        body = int(model.geom_bodyid[geom])
        pos, quat = body_poses.get(body, (np.zeros(3), np.array([1.0, 0, 0, 0])))
        T_body = _transform(pos, quat)
        for kind, dims, local in geom_shapes(model, geom):
            corners = _shape_corners(kind, dims, T_body @ local)
            depth = corners[:, depth_axis].mean()
            patches.append((depth, _hull(corners[:, axes]), model.geom_rgba[geom]))
    # front view: larger y is nearer the viewer (the robot's side); top view: higher is nearer
    for _, hull, rgba in sorted(patches, key=lambda p: p[0]):
        ax.add_patch(Polygon(hull, closed=True, facecolor=rgba[:3], edgecolor=(0, 0, 0, 0.35), linewidth=0.4,
                             alpha=float(rgba[3])))
    if view == "front":
        ax.set_xlim(-1.3, 6.0)
        ax.set_ylim(-0.1, 3.0)
        ax.set_xlabel("x along the wall (m)")
        ax.set_ylabel("z (m)")
    else:
        ax.set_xlim(-1.3, 6.0)
        ax.set_ylim(-0.3, 4.0)
        ax.set_xlabel("x along the wall (m)")
        ax.set_ylabel("y from the wall (m)")
    ax.set_aspect("equal")
    ax.set_title(title or ("Robot cell, elevation" if view == "front" else "Robot cell, plan"))
    return ax


def recording_frame(recording: Recording, time: float) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """The recorded body poses nearest to ``time`` (simulated seconds)."""
    k = int(np.argmin(np.abs(np.asarray(recording.times) - time)))
    return {int(b): (recording.positions[k][i], recording.quaternions[k][i]) for i, b in enumerate(recording.body_ids)}


def draw_film(model: mujoco.MjModel, recording: Recording, times: list[float], titles: list[str] | None = None,
              view: str = "front", ncols: int = 3, width: float = 15.0) -> plt.Figure:
    """Snapshots of a recording at the given simulated times, in a grid."""
    nrows = -(-len(times) // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, width / ncols * 0.6 * nrows), squeeze=False)
    for k, (ax, t) in enumerate(zip(axes.flat, times)):
        draw_elevation(model, recording_frame(recording, t), ax, view, titles[k] if titles else f"t = {t:.1f} s")
    for ax in list(axes.flat)[len(times):]:
        ax.axis("off")
    fig.tight_layout()
    return fig


def plot_joint_trajectories(trace: JointTrace, title: str = "", unit_degrees: bool = True) -> plt.Figure:
    """Each joint's set point and measured value over one placement, with the stages shaded."""
    from drywall_lab.rc.robot import JOINTS

    q, q_set = np.array(trace.q), np.array(trace.q_set)
    t = np.asarray(trace.times)
    fig, axes = plt.subplots(len(JOINTS), 1, figsize=(11, 1.45 * len(JOINTS)), sharex=True)
    for j, (ax, name) in enumerate(zip(axes, JOINTS)):
        scale, unit = (1.0, "m") if j == 0 else ((np.degrees(1.0), "deg") if unit_degrees else (1.0, "rad"))
        ax.plot(t, q_set[:, j] * scale, color="0.6", lw=2.5, label="set point")
        ax.plot(t, q[:, j] * scale, color="C1", lw=1.0, label="measured")
        ax.set_ylabel(f"{name} ({unit})", fontsize=8)
        for k, (stage, a, b) in enumerate(trace.stages):
            if k % 2 == 0:
                ax.axvspan(a, b, color="0.93", lw=0)
    for stage, a, b in trace.stages:
        if b - a > 1.2:
            axes[0].text((a + b) / 2, 1.02, stage, transform=axes[0].get_xaxis_transform(), ha="center",
                         va="bottom", fontsize=7, rotation=30)
    axes[0].legend(loc="upper right", fontsize=7)
    axes[-1].set_xlabel("time (s, simulated)")
    if title:
        fig.suptitle(title, y=1.0)
    fig.tight_layout()
    return fig
