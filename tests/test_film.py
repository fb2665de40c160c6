"""The small animated GIFs of notebooks 05 and 06 (``drywall_lab.rc.film``): written from a recording, more than one
frame, under the size the repository allows; the committed ones exist, are tracked by git and play in the
notebook exported to HTML, in headless Chromium (``tests/test_browser.py``'s helpers).
"""
from __future__ import annotations

import subprocess
from pathlib import Path

import mujoco
import numpy as np
import pytest
from PIL import Image

from drywall_lab.rc.film import MAX_FRAMES, film_indices, render_frames, save_film
from drywall_lab.rc.recording import Recording
from drywall_lab.rc.robot import JOINTS
from drywall_lab.rc.scene import build_scene
from drywall_lab.site import default_site
from test_browser import PAGE_TIMEOUT, browser, chromium  # noqa: F401 - fixtures, and the page timeout

ROOT = Path(__file__).resolve().parent.parent
ANIMATIONS = ROOT / "notebooks" / "animations"
COMMITTED = {"05_robot_control.ipynb": "05_four_placements.gif", "06_end_to_end.ipynb": "06_three_layouts.gif"}
MAX_BYTES = 300_000  # bytes: the most a committed GIF may take


@pytest.fixture(scope="module")
def short_recording() -> tuple[mujoco.MjModel, Recording]:
    """The site's scene with the robot's rail and first two arm joints swept, a few seconds at 10 frames a second."""
    scene = build_scene(default_site().fresh())
    model, data = scene.model, mujoco.MjData(scene.model)
    recording = Recording.for_model(model, fps=10.0)
    adr = {name: model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)] for name in JOINTS}
    for k in range(30):
        data.qpos[:] = model.qpos0
        data.qpos[adr["rail"]] = 1.5 * k / 29
        data.qpos[adr["a1"]] = model.qpos0[adr["a1"]] + 0.8 * k / 29
        data.qpos[adr["a2"]] = model.qpos0[adr["a2"]] - 0.3 * k / 29
        mujoco.mj_kinematics(model, data)
        recording.capture(data, k * 0.1)
    return model, recording


def test_film_indices_take_first_and_last_and_keep_within_the_cap():
    times = np.arange(0, 100, 0.05)
    picked = film_indices(times, speed=1.0, fps=10.0, max_frames=40)
    assert picked[0] == 0 and picked[-1] == len(times) - 1 and len(picked) <= 40
    assert picked == sorted(set(picked))
    short = film_indices(times[:41], speed=1.0, fps=10.0)  # 2 s at 10 fps played in real time: 21 frames
    assert len(short) == 21


@pytest.mark.parametrize("renderer", ["auto", "matplotlib"])
def test_a_short_recording_becomes_a_small_gif_of_several_frames(short_recording, tmp_path, renderer):
    model, recording = short_recording
    film = save_film(recording, model, tmp_path / "short.gif", speed=1.0, renderer=renderer)
    assert film.path.is_file() and film.bytes == film.path.stat().st_size < MAX_BYTES
    with Image.open(film.path) as gif:
        assert gif.format == "GIF" and gif.n_frames == film.frames > 1 and gif.size == (320, 240)
        gif.seek(0)
        first = np.asarray(gif.convert("RGB"), dtype=int)
        gif.seek(gif.n_frames - 1)
        last = np.asarray(gif.convert("RGB"), dtype=int)
    assert np.abs(first - last).sum(axis=2).astype(bool).mean() > 0.005  # the robot moved between them
    if renderer == "matplotlib":
        assert film.renderer == "matplotlib"
    assert film.renderer in str(film)


def test_the_film_is_the_same_every_time(short_recording, tmp_path):
    model, recording = short_recording
    a = save_film(recording, model, tmp_path / "a.gif", speed=2.0, renderer="matplotlib")
    b = save_film(recording, model, tmp_path / "b.gif", speed=2.0, renderer="matplotlib")
    assert a.path.read_bytes() == b.path.read_bytes()


def test_the_frames_show_the_robot_where_the_recording_has_it(short_recording):
    """The robot's orange moves with the rail: it is further to one side in the last frame than in the first."""
    model, recording = short_recording
    frames, _ = render_frames(model, recording, [0, len(recording) - 1], renderer="matplotlib")
    orange = [np.argwhere((f[..., 0] > 200) & (f[..., 1] > 80) & (f[..., 1] < 160) & (f[..., 2] < 80)) for f in frames]
    assert all(len(o) > 50 for o in orange)
    assert abs(orange[0][:, 1].mean() - orange[1][:, 1].mean()) > 10  # pixels, along the image's width


@pytest.mark.parametrize("notebook, name", sorted(COMMITTED.items()))
def test_the_committed_gifs_are_small_tracked_and_animated(notebook, name):
    path = ANIMATIONS / name
    assert path.is_file(), f"{name} is missing: run notebooks/{notebook}"
    assert path.stat().st_size < MAX_BYTES
    with Image.open(path) as gif:
        assert gif.format == "GIF" and gif.n_frames >= 10 and gif.n_frames <= MAX_FRAMES + 2
    ignored = subprocess.run(["git", "check-ignore", "-q", str(path)], cwd=ROOT).returncode == 0
    assert not ignored, f"{path} is ignored by git: the GIFs are committed"
    page = ANIMATIONS / name.replace(".gif", ".html")
    assert subprocess.run(["git", "check-ignore", "-q", str(page)], cwd=ROOT).returncode == 0  # the pages are not


@pytest.mark.parametrize("notebook, name", sorted(COMMITTED.items()))
def test_the_notebook_shows_the_gif_from_a_markdown_cell(notebook, name):
    import nbformat

    cells = nbformat.read(ROOT / "notebooks" / notebook, as_version=4).cells
    shown = [c for c in cells if c.cell_type == "markdown" and f"](animations/{name})" in c.source]
    written = [c for c in cells if c.cell_type == "code" and f'"{name}"' in c.source and "save_film" in c.source]
    assert len(shown) == 1 and len(written) == 1
    assert cells.index(written[0]) < cells.index(shown[0])


@pytest.mark.parametrize("notebook, name", sorted(COMMITTED.items()))
def test_the_exported_notebook_loads_the_gif_in_chromium(browser, tmp_path, notebook, name):  # noqa: F811
    """``jupyter nbconvert --to html`` beside the animations folder: the GIF is loaded (naturalWidth > 0)."""
    folder = tmp_path / "notebooks"
    folder.mkdir()
    (folder / "animations").symlink_to(ANIMATIONS, target_is_directory=True)
    subprocess.run([str(Path(ROOT / ".venv" / "bin" / "jupyter")) if (ROOT / ".venv" / "bin" / "jupyter").exists()
                    else "jupyter", "nbconvert", "--to", "html", "--output-dir", str(folder),
                    str(ROOT / "notebooks" / notebook)], check=True, capture_output=True, timeout=PAGE_TIMEOUT * 2)
    page = folder / notebook.replace(".ipynb", ".html")
    browser.open(page.as_uri())
    image = browser.evaluate(f"""(() => {{ const i = Array.from(document.images).find(
        i => i.getAttribute('src') === 'animations/{name}');
        if (!i) return null;
        return i.decode().then(() => ({{width: i.naturalWidth, height: i.naturalHeight, complete: i.complete}}),
                               () => ({{width: 0, height: 0, complete: i.complete}})); }})()""")
    assert image is not None, f"no <img src='animations/{name}'> in the exported notebook"
    assert image["complete"] and image["width"] == 320 and image["height"] == 240, image


def test_with_egl_mujoco_draws_the_frames(tmp_path):
    """In a fresh interpreter with ``MUJOCO_GL=egl`` (as the notebooks set it) the frames come from MuJoCo's own
    renderer; skipped where this machine has no EGL."""
    import os
    import sys

    script = (
        "import mujoco\n"
        "from drywall_lab.rc.film import save_film\n"
        "from drywall_lab.rc.recording import Recording\n"
        "from drywall_lab.rc.scene import build_scene\n"
        "from drywall_lab.site import default_site\n"
        "scene = build_scene(default_site().fresh())\n"
        "model, data = scene.model, mujoco.MjData(scene.model)\n"
        "rec = Recording.for_model(model, 10.0)\n"
        "for k in range(12):\n"
        "    data.qpos[:] = model.qpos0\n"
        "    data.qpos[scene.qpos_index[0]] = 0.1 * k\n"
        "    mujoco.mj_kinematics(model, data)\n"
        "    rec.capture(data, 0.1 * k)\n"
        f"film = save_film(rec, model, {str(tmp_path / 'egl.gif')!r}, speed=1.0)\n"
        "print(film.renderer, film.frames, film.bytes)\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, MUJOCO_GL="egl"))
    assert done.returncode == 0, done.stderr[-2000:]
    renderer, frames, size = done.stdout.split()
    if renderer != "mujoco":
        pytest.skip("no EGL on this machine: the film falls back to matplotlib")
    assert int(frames) > 1 and int(size) < MAX_BYTES


def test_a_film_over_its_byte_budget_keeps_every_other_frame(short_recording, tmp_path):
    model, recording = short_recording
    full = save_film(recording, model, tmp_path / "full.gif", speed=1.0, renderer="matplotlib")
    thinned = save_film(recording, model, tmp_path / "thin.gif", speed=1.0, renderer="matplotlib",
                        max_bytes=full.bytes - 1)
    assert thinned.bytes <= full.bytes - 1 and 2 <= thinned.frames <= (full.frames + 1) // 2 + 1
