"""A small animated GIF of a recording, for the committed notebooks (05, 06): the meshcat page is the
interactive view, but it is megabytes and not committed; a GIF of a few hundred kilobytes plays in any
notebook viewer.

Each frame puts the robot links and panels at their recorded poses (``Recording``: body positions and
quaternions) and draws the model's own geoms: with MuJoCo's offscreen renderer (``mujoco.Renderer``) where an
OpenGL context can be made (headless: ``MUJOCO_GL=egl`` or ``osmesa``, set before ``mujoco`` is first
imported), otherwise with matplotlib's 3-D axes (every geom as the box around it). Pillow writes the GIF with
one shared, optimised palette. The same recording gives the same frames: nothing here is random.
"""
from __future__ import annotations

import io
import os
import sys
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import mujoco
import numpy as np

from drywall_lab.rc.recording import Recording

#: The GIF's size in pixels (width, height) and frames per second of the played GIF.
FILM_SIZE = (320, 240)
FILM_FPS = 8.0
#: At most this many frames: keeps a GIF of the whole recording near 200 KB.
MAX_FRAMES = 96
#: A GIF larger than this is written again with every other frame (the repository keeps its GIFs under 300 KB).
MAX_BYTES = 280_000
#: The free camera: looking at the wall's middle from behind the robot, slightly from above (as the meshcat page).
CAMERA = {"lookat": (2.3, 0.9, 0.9), "distance": 6.2, "azimuth": -105.0, "elevation": -22.0}


@dataclass
class FilmSummary:
    """What ``save_film`` wrote: the file, its frames, its size and which renderer drew it."""

    path: Path
    frames: int
    bytes: int
    renderer: str  #: ``"mujoco"`` (OpenGL, offscreen) or ``"matplotlib"`` (3-D axes, no OpenGL)
    seconds_per_frame: float  #: simulated seconds between two frames

    def __str__(self) -> str:
        return (f"{self.path.name}: {self.frames} frames, {self.bytes / 1024:.0f} KB, one every "
                f"{self.seconds_per_frame:.2f} simulated s, drawn with {self.renderer}")


def film_indices(times: Sequence[float], speed: float, fps: float = FILM_FPS, max_frames: int = MAX_FRAMES) -> list[int]:
    """Which recorded frames the film shows: one every ``speed / fps`` simulated seconds (played ``speed``
    times faster than real time at ``fps``), spaced out further if that would be more than ``max_frames``;
    the first and the last frame always."""
    times = np.asarray(times, dtype=float)
    if len(times) == 0:
        return []
    duration = times[-1] - times[0]
    count = int(min(max_frames, max(2, round(duration * fps / speed) + 1)))
    wanted = np.linspace(times[0], times[-1], count)
    picked = np.searchsorted(times, wanted).clip(0, len(times) - 1)
    return sorted(set(int(k) for k in picked) | {0, len(times) - 1})


def _quat_matrix(quat: np.ndarray) -> np.ndarray:
    mat = np.zeros(9)
    mujoco.mju_quat2Mat(mat, np.asarray(quat, dtype=float))
    return mat.reshape(3, 3)


def pose_data(model: mujoco.MjModel, data: mujoco.MjData, recording: Recording, k: int) -> None:
    """Put the recorded bodies of frame ``k`` and their geoms where the recording has them (``data``'s other
    bodies, the static ones, stay as they are)."""
    for i, b in enumerate(recording.body_ids):
        pos, rot = recording.positions[k][i], _quat_matrix(recording.quaternions[k][i])
        data.xpos[b], data.xquat[b], data.xmat[b] = pos, recording.quaternions[k][i], rot.ravel()
    moving = np.isin(model.geom_bodyid, recording.body_ids)
    for g in np.flatnonzero(moving):
        b = model.geom_bodyid[g]
        rot = data.xmat[b].reshape(3, 3)
        data.geom_xpos[g] = data.xpos[b] + rot @ model.geom_pos[g]
        data.geom_xmat[g] = (rot @ _quat_matrix(model.geom_quat[g])).ravel()


def _mujoco_frames(model: mujoco.MjModel, recording: Recording, indices: Sequence[int],
                   size: tuple[int, int]) -> list[np.ndarray]:
    """The frames drawn by MuJoCo's offscreen renderer; raises if no OpenGL context can be made."""
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    camera = mujoco.MjvCamera()
    camera.type = mujoco.mjtCamera.mjCAMERA_FREE
    camera.lookat[:] = CAMERA["lookat"]
    camera.distance, camera.azimuth, camera.elevation = CAMERA["distance"], CAMERA["azimuth"], CAMERA["elevation"]
    option = mujoco.MjvOption()
    option.sitegroup[:] = 0  # sites are markers of the controller, not part of the film
    frames = []
    with mujoco.Renderer(model, height=size[1], width=size[0]) as renderer:
        for k in indices:
            pose_data(model, data, recording, k)
            renderer.update_scene(data, camera=camera, scene_option=option)
            frames.append(renderer.render().copy())
    return frames


_FACES = ((0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5))


def _matplotlib_frames(model: mujoco.MjModel, recording: Recording, indices: Sequence[int],
                       size: tuple[int, int]) -> list[np.ndarray]:
    """The frames drawn with matplotlib's 3-D axes, every geom as its bounding box (no OpenGL needed)."""
    import matplotlib

    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    from drywall_lab.viz import _shape_corners, _transform, geom_shapes, visible_geoms

    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    geoms = [g for g in visible_geoms(model) if model.geom_type[g] != mujoco.mjtGeom.mjGEOM_PLANE]
    frames = []
    dpi = 80
    with matplotlib.rc_context({"figure.dpi": dpi}):
        for k in indices:
            pose_data(model, data, recording, k)
            fig = Figure(figsize=(size[0] / dpi, size[1] / dpi), dpi=dpi)
            ax = fig.add_axes((0, 0, 1, 1), projection="3d")
            faces, colours = [], []
            for g in geoms:
                b = model.geom_bodyid[g]
                T_body = _transform(data.xpos[b], data.xquat[b])
                for kind, dims, local in geom_shapes(model, g):
                    corners = _shape_corners(kind, dims, T_body @ local)
                    faces += [corners[list(f)] for f in _FACES]
                    colours += [model.geom_rgba[g, :3]] * len(_FACES)
            ax.add_collection3d(Poly3DCollection(faces, facecolors=colours, edgecolors=(0, 0, 0, 0.2), linewidths=0.2))
            ax.set_xlim(-0.8, 5.4), ax.set_ylim(-0.2, 3.6), ax.set_zlim(0, 2.8)
            ax.set_box_aspect((6.2, 3.8, 2.8), zoom=1.5)
            ax.view_init(elev=-CAMERA["elevation"], azim=CAMERA["azimuth"] - 180)
            ax.set_axis_off()
            buffer = io.BytesIO()
            fig.savefig(buffer, format="rgba", dpi=dpi)
            frames.append(np.frombuffer(buffer.getvalue(), np.uint8).reshape(size[1], size[0], 4)[..., :3].copy())
    return frames


def opengl_possible() -> bool:
    """Whether MuJoCo may get an OpenGL context here: a headless backend chosen (``MUJOCO_GL`` = ``egl`` or
    ``osmesa``), or a display to open a window on (GLFW, MuJoCo's default)."""
    backend = os.environ.get("MUJOCO_GL", "").strip().lower()
    if backend in ("egl", "osmesa"):
        return True
    if backend in ("disable", "disabled", "off", "false", "0"):
        return False
    return not sys.platform.startswith("linux") or bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def render_frames(model: mujoco.MjModel, recording: Recording, indices: Sequence[int],
                  size: tuple[int, int] = FILM_SIZE, renderer: str = "auto") -> tuple[list[np.ndarray], str]:
    """The recording's frames ``indices`` as RGB images (height x width x 3) and the renderer that drew them:
    ``"mujoco"`` when ``renderer`` is ``"auto"`` and an OpenGL context can be made, else ``"matplotlib"``."""
    if renderer == "mujoco" or (renderer == "auto" and opengl_possible()):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # GLFW's complaints when it finds no display
                return _mujoco_frames(model, recording, indices, size), "mujoco"
        except Exception:  # noqa: BLE001 - no OpenGL after all (no EGL/OSMesa library): draw with matplotlib
            if renderer == "mujoco":
                raise
    return _matplotlib_frames(model, recording, indices, size), "matplotlib"


def write_gif(frames: Sequence[np.ndarray], path: Path | str, fps: float = FILM_FPS, colours: int = 64) -> Path:
    """The frames as a looping GIF at ``fps``, one palette of ``colours`` colours for all (taken from the
    frames themselves, so that every frame is dithered the same way and the file stays small)."""
    from PIL import Image

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    images = [Image.fromarray(np.asarray(f, dtype=np.uint8)) for f in frames]
    sample = Image.fromarray(np.concatenate([np.asarray(f, dtype=np.uint8) for f in frames[:: max(1, len(frames) // 8)]]))
    palette = sample.quantize(colors=colours, method=Image.Quantize.MEDIANCUT)
    quantised = [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in images]
    quantised[0].save(path, save_all=True, append_images=quantised[1:], duration=int(round(1000 / fps)), loop=0,
                      optimize=True, disposal=1)
    return path


def save_film(recordings: Recording | Sequence[Recording], model: mujoco.MjModel, path: Path | str,
              speed: float = 8.0, fps: float = FILM_FPS, size: tuple[int, int] = FILM_SIZE,
              max_frames: int = MAX_FRAMES, max_bytes: int = MAX_BYTES, renderer: str = "auto") -> FilmSummary:
    """The recordings (several are played one after another) as a small looping GIF in ``path``, played
    ``speed`` times faster than real time at ``fps`` frames a second (fewer frames if that would be more than
    ``max_frames``, and every other frame, as often as needed, while the file is over ``max_bytes``)."""
    from drywall_lab.viz import join_recordings

    recording = recordings if isinstance(recordings, Recording) else join_recordings(list(recordings))
    if len(recording) < 2:
        raise ValueError("the recording has fewer than two frames: build the cell with record_fps to record")
    indices = film_indices(recording.times, speed, fps, max_frames)
    frames, used = render_frames(model, recording, indices, size, renderer)
    path = write_gif(frames, path, fps)
    while path.stat().st_size > max_bytes and len(frames) > 2:
        keep = sorted(set(range(0, len(frames), 2)) | {len(frames) - 1})
        frames, indices = [frames[k] for k in keep], [indices[k] for k in keep]
        path = write_gif(frames, path, fps)
    step = recording.duration / max(1, len(indices) - 1)
    return FilmSummary(path, len(frames), path.stat().st_size, used, step)
