"""Seeing the robot cell: a meshcat 3D scene (live, or recorded as a self-contained HTML animation)
and matplotlib drawings as the quick fallback.

The paper shows its robot in Gazebo (Figs. 16-18). Here the scene is drawn from the MuJoCo
model's own geoms (boxes, cylinders, the floor plane), so there is nothing to keep in step:

- ``MeshcatScene``: the geoms in meshcat, grouped by body. ``animate(recording)`` turns a
  ``Recording`` into a meshcat animation; ``html()`` / ``save_html()`` give the scene and its
  animation as one self-contained HTML page that plays without a server (``save_animation`` does it
  for whole episodes, ``show_html`` shows the saved page in a notebook). The scene is kept in this
  process (``StaticWindow``): no server is started unless ``live=True`` asks for meshcat's own, to
  watch the simulation live in JupyterLab (``live()``, ``update(data)``). No OpenGL is needed: the
  browser draws it.
- ``draw_elevation``: a matplotlib elevation (or plan) of the same geoms at one moment;
  ``draw_film``: a grid of such drawings through a recording, ``draw_placement_film`` and
  ``draw_episode_film`` choose the moments (stage ends, one per placement);
  ``plot_joint_trajectories``: set points against measured joint values for one placement.

All meshcat code lives in this module, so it can be replaced without touching the simulation.
"""
from __future__ import annotations

import base64
import html as html_lib
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Sequence

import matplotlib.pyplot as plt
import mujoco
import numpy as np
from matplotlib.patches import Polygon

from drywall_lab.rc.recording import JointTrace, Recording

if TYPE_CHECKING:
    from drywall_lab.rc.episode import EpisodeRun
    from drywall_lab.rc.placement import PlacementResult

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
_STATIC_PAGE = """<!DOCTYPE html>
<html>
    <head> <meta charset=utf-8> <title>{title}</title> </head>
    <body>
        <div id="meshcat-pane">
        </div>
        <script>
{viewer}
        </script>
        <script>
            var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));
{commands}
        </script>
        <style>
            body {{margin: 0; }}
            #meshcat-pane {{
                width: 100vw;
                height: 100vh;
                overflow: hidden;
            }}
        </style>
    </body>
</html>
"""


class StaticWindow:
    """Meshcat's viewer window kept in this process: no server, no port, nothing printed.

    ``meshcat.Visualizer(window=StaticWindow())`` takes every drawing command as usual; the window keeps
    the scene tree the way meshcat's own server does (``meshcat.servers.tree``: the latest object,
    properties, transform and animation of each path), and ``get_scene()`` writes the same
    self-contained page the server's static export writes: meshcat's viewer code inline, then every
    command as a ``data:`` URL.
    """

    server_proc = None

    def __init__(self, title: str = "drywall-lab") -> None:
        from meshcat.servers.tree import SceneTree

        self.tree = SceneTree()
        self.title = title

    def send(self, command) -> None:
        import umsgpack
        from meshcat.servers.tree import SceneTree, find_node

        data = command.lower()
        kind = data["type"]
        path = [part for part in data.get("path", "").split("/") if part]
        packed = umsgpack.packb(data)
        if kind == "delete":
            if not path:
                self.tree = SceneTree()
            else:
                parent = find_node(self.tree, path[:-1])
                parent.pop(path[-1], None)
            return
        node = find_node(self.tree, path)
        if kind == "set_object":
            node.object, node.properties = packed, []
        elif kind == "set_transform":
            node.transform = packed
        elif kind == "set_property":
            node.properties.append(packed)
        elif kind == "set_animation":
            node.animation = packed
        else:
            raise ValueError(f"a static meshcat scene cannot take a {kind!r} command")

    def commands(self) -> list[bytes]:
        """The packed commands that rebuild the scene, in the order meshcat's server replays them."""
        from meshcat.servers.tree import walk

        packed: list[bytes] = []
        for node in walk(self.tree):
            packed += ([node.object] if node.object is not None else []) + list(node.properties)
            packed += [x for x in (node.transform, node.animation) if x is not None]
        return packed

    def get_scene(self) -> str:
        """The scene as one self-contained HTML page (meshcat's static export)."""
        import meshcat

        viewer = (Path(meshcat.__file__).parent / "viewer" / "dist" / "main.min.js").read_text(encoding="utf-8")
        commands = "".join(
            f'fetch("data:application/octet-binary;base64,{base64.b64encode(c).decode("ascii")}")\n'
            "    .then(res => res.arrayBuffer())\n"
            "    .then(buffer => viewer.handle_command_bytearray(new Uint8Array(buffer)));\n"
            for c in self.commands())
        return _STATIC_PAGE.format(title=html_lib.escape(self.title), viewer=viewer, commands=commands)


@dataclass(frozen=True)
class AnimationSummary:
    """What ``MeshcatScene.animate`` sent: ``frames`` recorded frames of ``bodies`` moving bodies, of whose
    ``frames * bodies`` poses ``keyframes`` were kept (the rest lie on straight lines between them)."""

    frames: int
    bodies: int
    keyframes: int

    @property
    def poses(self) -> int:
        return self.frames * self.bodies

    def __str__(self) -> str:
        share = self.keyframes / self.poses if self.poses else 0.0
        return (f"{self.frames} recorded frames x {self.bodies} moving bodies = {self.poses} body poses, "
                f"{self.keyframes} of them kept as keyframes ({share:.0%})")


class MeshcatScene:
    """The MuJoCo model's geoms in a meshcat viewer, one node per body (see the module's docstring).

    By default the scene is kept in this process (``StaticWindow``) for the self-contained HTML export.
    ``live=True`` starts meshcat's server process on this machine's loopback instead, for ``live()``
    and ``update()`` in JupyterLab; ``close()`` stops it.
    """

    def __init__(self, model: mujoco.MjModel, visualizer=None, live: bool = False) -> None:
        import meshcat

        self.model = model
        if visualizer is None:
            visualizer = meshcat.Visualizer() if live else meshcat.Visualizer(window=StaticWindow())
            self._own_server = live
        else:
            self._own_server = False
        self.vis = visualizer
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
        if isinstance(self.vis.window, StaticWindow):
            raise ValueError("this scene has no server to watch live: build it with MeshcatScene(model, live=True)")
        return self.vis.jupyter_cell(height=height)

    # animation
    def animate(self, recording: Recording | Sequence[Recording], repetitions: int = 1, speed: float = 1.0,
                position_tolerance: float = KEY_POSITION_TOLERANCE,
                angle_tolerance_deg: float = KEY_ANGLE_TOLERANCE_DEG) -> AnimationSummary:
        """Send the recording (or several, played one after another) as a meshcat animation; returns how
        many frames were recorded and how many body poses were kept as keyframes (``AnimationSummary``).

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
        kept_total, bodies = 0, 0
        for b in self.moving_bodies:
            if b not in index:
                continue
            bodies += 1
            i = index[b]
            keep = keyframes(times, positions[:, i], quaternions[:, i], position_tolerance, angle_tolerance_deg)
            kept_total += len(keep)
            name = _body_name(self.model, b)
            for k in keep:
                with anim.at_frame(self.root, int(frames[k])) as frame:
                    frame[name].set_transform(_transform(positions[k, i], quaternions[k, i]))
        self.vis.set_animation(anim, play=True, repetitions=repetitions)
        return AnimationSummary(len(recording), bodies, kept_total)

    # static export
    def html(self) -> str:
        """The scene (and its animation, if any) as one self-contained HTML page."""
        return self.vis.static_html()

    def save_html(self, path: Path | str) -> Path:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(self.html(), encoding="utf-8")
        return path

    def close(self) -> None:
        """Stop the meshcat server this scene started (``live=True``); nothing to do otherwise."""
        proc = getattr(self.vis.window, "server_proc", None)
        if self._own_server and proc is not None and proc.poll() is None:
            proc.kill()
            proc.wait()


def save_animation(recordings: Recording | Sequence[Recording], model: mujoco.MjModel, path: Path | str,
                   speed: float = 4.0, position_tolerance: float = 0.005,
                   angle_tolerance_deg: float = 1.0) -> AnimationSummary:
    """The recordings (several are played one after another) as one self-contained HTML animation in
    ``path`` (its folder created), played ``speed`` times faster than real time: no server, no network.

    The default keyframe tolerances (5 mm, 1 deg) are ample for a film played at 4x; the simulation's
    own errors are measured on the panels, not on the film.
    """
    scene = MeshcatScene(model)
    try:
        summary = scene.animate(recordings, speed=speed, position_tolerance=position_tolerance,
                                angle_tolerance_deg=angle_tolerance_deg)
        scene.save_html(path)
    finally:
        scene.close()
    return summary


def show_html(path: Path | str, height: int = 480):
    """A saved page (``save_animation``) shown in a notebook: an IFrame pointing at the file, relative to the
    notebook's folder, so the notebook itself stays small. JupyterLab serves the file beside the notebook."""
    from IPython.display import IFrame

    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no page at {path}: write it with save_animation first")
    return IFrame(Path(os.path.relpath(path.resolve(), Path.cwd().resolve())).as_posix(), width="100%",
                  height=height)


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


def draw_history_and_wall(run: EpisodeRun, width: float = 15.0) -> plt.Figure:
    """Side by side: the wall as the episode's action history records it, and the simulated wall as the robot
    left it (they agree while every placement succeeds)."""
    from drywall_lab.plots import draw_wall

    fig, (recorded, simulated) = plt.subplots(1, 2, figsize=(width, 3.6))
    draw_wall(run.history.state, recorded, "What IM recorded (the action history)")
    draw_elevation(run.cell.scene.model, run.cell.scene.data, simulated, "front", "What the simulated robot built")
    fig.tight_layout()
    return fig


def plot_placement_errors(results: Sequence[PlacementResult], width: float = 11.0) -> plt.Figure:
    """Each placement's position and angle error as bars, with the project's tolerances as dashed lines."""
    from drywall_lab.rc.placement import ANGLE_TOLERANCE_DEG, POSITION_TOLERANCE

    labels = [f"{r.command.drywall_id} {r.command.placement.value}" for r in results]
    fig, (pos, ang) = plt.subplots(1, 2, figsize=(width, 0.5 + 0.45 * len(results)), sharey=True)
    pos.barh(labels, [r.position_error_mm for r in results], color="C0")
    pos.axvline(POSITION_TOLERANCE * 1000, color="C3", ls="--", label="tolerance")
    ang.barh(labels, [r.angle_error_deg for r in results], color="C1")
    ang.axvline(ANGLE_TOLERANCE_DEG, color="C3", ls="--", label="tolerance")
    pos.set_xlabel("position error (mm)")
    ang.set_xlabel("angle error (deg)")
    pos.invert_yaxis()
    pos.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    return fig


#: The stages whose ends ``draw_placement_film`` shows: on the pad, tilted up, swung round, turned, seated,
#: stepped back.
FILM_STAGES = ("descend", "tilt", "swing", "turn", "seat", "retreat")


def draw_placement_film(model: mujoco.MjModel, recording: Recording, result: PlacementResult,
                        stages: Sequence[str] = FILM_STAGES, view: str = "front", ncols: int = 3,
                        width: float = 15.0) -> plt.Figure:
    """One placement as a film strip: the recorded scene at the end of each of ``stages`` it went through."""
    ends: dict[str, float] = {}
    for name, _, end in result.trace.stages:
        if name in stages and name not in ends:
            ends[name] = end
    chosen = [name for name in stages if name in ends]
    if not chosen:
        raise ValueError(f"the placement went through none of the stages {', '.join(stages)}")
    times = [result.sim_start + ends[name] for name in chosen]
    titles = [f"end of {name}, t = {ends[name]:.0f} s" for name in chosen]
    return draw_film(model, recording, times, titles, view, ncols, width)


def draw_episode_film(run: EpisodeRun, stage: str = "approach", view: str = "front", ncols: int = 3,
                      width: float = 15.0) -> plt.Figure:
    """An episode as a film strip: each placement at the end of ``stage`` (the panel at the wall, about to be
    set; the middle of the placement if it never got there), then the wall as the robot left it."""
    recording = run.cell.recording
    if recording is None or len(recording) == 0:
        raise ValueError("the episode was not recorded: simulate it with record_fps")
    times, titles = [], []
    for step in run.steps:
        r = step.result
        if r is None:
            continue
        ends = [end for name, _, end in r.trace.stages if name == stage]
        times.append(r.sim_start + (ends[0] if ends else r.sim_time / 2))
        titles.append(f"step {step.step}: {r.command.drywall_id} to {r.command.stud_id}"
                      + ("" if r.success else f" ({step.status})"))
    times.append(recording.times[-1])
    titles.append(f"{run.episode_id}: the wall at the end")
    return draw_film(run.cell.scene.model, recording, times, titles, view, ncols, width)


def plot_joint_trajectories(trace: JointTrace, title: str = "", unit_degrees: bool = True) -> plt.Figure:
    """Each joint over one placement, stages shaded: on the left the measured value (solid) with the set point
    drawn over it (dashed), on the right the tracking error, measured minus set point (mm for the rail, deg or
    rad for the arm), which is far too small to see as a gap between the two curves on the left."""
    from drywall_lab.rc.robot import JOINTS

    q, q_set = np.array(trace.q), np.array(trace.q_set)
    t = np.asarray(trace.times)
    fig, axes = plt.subplots(len(JOINTS), 2, figsize=(13, 1.45 * len(JOINTS)), sharex=True,
                             gridspec_kw={"width_ratios": (3, 2)})
    for j, name in enumerate(JOINTS):
        ax, err_ax = axes[j]
        scale, unit = (1.0, "m") if j == 0 else ((np.degrees(1.0), "deg") if unit_degrees else (1.0, "rad"))
        err_scale, err_unit = (1000.0, "mm") if j == 0 else (scale, unit)
        ax.plot(t, q[:, j] * scale, color="C1", lw=2.6, alpha=0.75, label="measured")
        ax.plot(t, q_set[:, j] * scale, color="k", lw=1.0, ls=(0, (4, 3)), label="set point")
        err_ax.plot(t, (q[:, j] - q_set[:, j]) * err_scale, color="C3", lw=0.9)
        err_ax.axhline(0.0, color="0.5", lw=0.6)
        ax.set_ylabel(f"{name} ({unit})", fontsize=8)
        err_ax.set_ylabel(f"error ({err_unit})", fontsize=8)
        for a in (ax, err_ax):
            for k, (stage, start, end) in enumerate(trace.stages):
                if k % 2 == 0:
                    a.axvspan(start, end, color="0.93", lw=0)
    for stage, start, end in trace.stages:
        if end - start > 1.2:
            axes[0, 0].text((start + end) / 2, 1.02, stage, transform=axes[0, 0].get_xaxis_transform(), ha="center",
                            va="bottom", fontsize=7, rotation=30)
    axes[0, 0].legend(loc="upper right", fontsize=7)
    axes[0, 1].set_title("measured - set point", fontsize=9)
    for a in axes[-1]:
        a.set_xlabel("time (s, simulated)")
    if title:
        fig.suptitle(title, y=1.0)
    fig.tight_layout()
    return fig
