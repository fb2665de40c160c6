"""Visualisation (drywall_lab/viz.py): the meshcat scene from the MuJoCo geoms, kept in this process (no
server) and exported as the same self-contained HTML meshcat's own server writes, its recorded animation,
keyframe thinning, the page shown in a notebook, and the matplotlib fallbacks (film strips, joint plots)."""
from __future__ import annotations

import base64
import re

import matplotlib
import numpy as np
import pytest
import umsgpack

matplotlib.use("Agg")
# meshcat 0.3.2 imports a pyzmq module that pyzmq has deprecated; nothing here uses it
pytestmark = pytest.mark.filterwarnings("ignore:zmq.eventloop.ioloop is deprecated:DeprecationWarning")

from drywall_lab import viz  # noqa: E402
from drywall_lab.rc import JointTrace, RobotCell  # noqa: E402
from drywall_lab.rc.robot import JOINTS  # noqa: E402


def decode_commands(page: str) -> list[dict]:
    """The meshcat commands a static page replays: base64 msgpack blobs in data: URLs."""
    blobs = re.findall(r"data:application/octet-binary;base64,([A-Za-z0-9+/=]+)", page)
    return [umsgpack.unpackb(base64.b64decode(b)) for b in blobs]


def without_uuids(commands):
    """The commands with meshcat's random object ids replaced by their order of first appearance."""
    seen: dict[str, str] = {}

    def walk(x):
        if isinstance(x, dict):
            return {k: (seen.setdefault(v, f"id{len(seen)}") if k in ("uuid", "geometry", "material") and
                        isinstance(v, str) else walk(v)) for k, v in x.items()}
        if isinstance(x, list):
            return [walk(v) for v in x]
        return x

    return walk(commands)


@pytest.fixture(scope="module")
def recorded_cell():
    """A fresh cell whose base drives 0.6 m along the rail, recorded at 10 frames a second."""
    cell = RobotCell(record_fps=10)
    q = cell.scene.q
    with cell.planner.checking(cell.state):
        drive = cell.planner.base_stage("base_demo", "free", q, q[0] + 0.6)
    cell.run_stage(drive)
    cell.hold(0.3)
    return cell


@pytest.fixture(scope="module")
def exported(recorded_cell, tmp_path_factory):
    """The recorded animation as a page (``html``) and as a file (``save_html``), and the keyframes kept."""
    scene = viz.MeshcatScene(recorded_cell.scene.model)
    try:
        kept = scene.animate(recorded_cell.recording)
        page = scene.html()
        saved = scene.save_html(tmp_path_factory.mktemp("viz") / "animation" / "robot.html")
    finally:
        scene.close()
    return page, kept, saved


def test_static_html_is_self_contained_with_the_scene_and_the_animation(exported, recorded_cell):
    page, kept, _ = exported
    assert page.lstrip().startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in page
    assert not re.search(r'<script[^>]+src=', page)  # the viewer's code is inline: no server, no network
    commands = decode_commands(page)
    objects = {c["path"].split("/")[-1] for c in commands if c["type"] == "set_object"}
    for name in ("floor", "stud_500100", "stud_500112", "panel_500320", "carriage_box", "upper_arm", "lifter_pad"):
        assert name in objects
    animations = [c for c in commands if c["type"] == "set_animation"]
    assert len(animations) == 1 and animations[0]["options"]["play"]
    clips = {a["path"].split("/")[-1]: a["clip"] for a in animations[0]["animations"]}
    assert {"carriage", "link1", "link6", "panel_500320"} <= set(clips)
    track = {t["name"]: t for t in clips["carriage"]["tracks"]}[".position"]
    xs = [k["value"][0] for k in track["keys"]]
    assert xs[-1] - xs[0] == pytest.approx(0.6, abs=0.01)  # the carriage's drive along the rail is in it
    assert kept.frames == len(recorded_cell.recording) and kept.bodies == len(clips)
    assert 0 < kept.keyframes < kept.poses == kept.frames * kept.bodies  # thinned
    assert str(kept).startswith(f"{kept.frames} recorded frames x {kept.bodies} moving bodies")


def test_saved_html_plays_on_its_own(exported):
    """The file ``save_html`` writes (its folder created) holds the viewer's code inline and every command
    of the scene and the animation as data: URLs; the only URL in it is the XHTML namespace."""
    page, _, saved = exported
    text = saved.read_text(encoding="utf-8")
    assert saved.is_file() and text == page
    assert text.lstrip().startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in text
    # no script, style sheet, image or frame loaded from elsewhere
    assert not re.search(r"<(?:script|link|img|iframe|embed|object)\b[^>]*\b(?:src|href|data)\s*=", text)
    fetched = re.findall(r'fetch\("([^"]*)"\)', text)
    assert fetched and all(url.startswith("data:application/octet-binary;base64,") for url in fetched)
    assert set(re.findall(r"https?://[^\s\"'<>)]+", text)) <= {"http://www.w3.org/1999/xhtml"}
    animations = [c for c in decode_commands(text) if c["type"] == "set_animation"]
    assert len(animations) == 1
    clips = {a["path"].split("/")[-1]: a["clip"] for a in animations[0]["animations"]}
    track = {t["name"]: t for t in clips["carriage"]["tracks"]}[".position"]
    assert track["keys"][-1]["value"][0] - track["keys"][0]["value"][0] == pytest.approx(0.6, abs=0.01)


def test_keyframes_thin_straight_motion_and_keep_turns():
    t = np.linspace(0, 4, 81)
    still = np.tile([1.0, 0, 0, 0], (81, 1))
    line = np.c_[t, 0 * t, 0 * t]
    assert viz.keyframes(t, line, still) == [0, 80]
    corner = np.c_[np.minimum(t, 2), np.maximum(t - 2, 0), 0 * t]
    keep = viz.keyframes(t, corner, still)
    assert keep[0] == 0 and keep[-1] == 80 and 2 <= len(keep) <= 5
    assert any(abs(t[k] - 2) <= 0.05 for k in keep)  # the corner survives


def test_elevation_draws_every_geom_but_the_floor(recorded_cell):
    m = recorded_cell.scene.model
    ax = viz.draw_elevation(m, recorded_cell.scene.data)
    shapes = sum(len(viz.geom_shapes(m, g)) for g in viz.visible_geoms(m) if m.geom_type[g] != 0)
    assert len(ax.patches) == shapes
    top = viz.draw_elevation(m, viz.recording_frame(recorded_cell.recording, 0.0), view="top")
    assert top.get_ylabel().startswith("y")
    fig = viz.draw_film(m, recorded_cell.recording, [0.0, 1.0, 2.0], ncols=3)
    assert len(fig.axes) == 3


def test_joint_trajectory_plot_shows_the_set_point_over_the_measured_value_and_the_error_beside():
    """The set point was drawn first and wider, so the measured curve hid it; now it is dashed, on top, and the
    error (measured - set point) has its own panel, in mm for the rail and degrees for the arm."""
    trace = JointTrace()
    for k in range(50):
        q = np.full(len(JOINTS), 0.01 * k)
        trace.add(0.02 * k, q, q + 0.001)
    trace.stages = [("approach_pick", 0.0, 0.5), ("descend", 0.5, 1.0)]
    fig = viz.plot_joint_trajectories(trace, "test")
    assert len(fig.axes) == 2 * len(JOINTS)
    curves, errors = fig.axes[0::2], fig.axes[1::2]
    for ax in curves:
        measured, set_point = ax.get_lines()
        assert measured.get_label() == "measured" and set_point.get_label() == "set point"
        assert set_point.get_linestyle() == "--" and measured.get_linewidth() > set_point.get_linewidth()
    rail_error, a1_error = errors[0].get_lines()[0].get_ydata(), errors[1].get_lines()[0].get_ydata()
    assert rail_error == pytest.approx(np.full(50, -1.0))  # mm
    assert a1_error == pytest.approx(np.full(50, -np.degrees(0.001)))
    assert trace.largest_tracking_error == pytest.approx(np.full(len(JOINTS), 0.001))


def test_join_recordings_plays_them_one_after_another(recorded_cell):
    rec = recorded_cell.recording
    joined = viz.join_recordings([rec, rec])
    assert len(joined) == 2 * len(rec)
    assert np.all(np.diff(joined.times) > 0)
    assert joined.duration == pytest.approx(2 * rec.duration + 1 / rec.fps)


# --- the scene kept in this process -------------------------------------------------------------------------
def test_a_static_scene_starts_no_server_and_prints_nothing(recorded_cell, capsys):
    """Notebook 05 printed meshcat's server URL, dead two lines later when the server was stopped: the static
    export needs no server at all."""
    scene = viz.MeshcatScene(recorded_cell.scene.model)
    assert isinstance(scene.vis.window, viz.StaticWindow) and scene.vis.window.server_proc is None
    scene.animate(recorded_cell.recording)
    assert "MeshCat.Viewer" in scene.html()
    scene.close()
    assert capsys.readouterr().out == ""
    with pytest.raises(ValueError, match="live=True"):
        scene.live()


def test_the_static_page_replays_what_meshcats_own_server_would(recorded_cell):
    """The same drawing sent to meshcat's server and to ``StaticWindow`` gives the same commands in the page."""
    import meshcat

    served = viz.MeshcatScene(recorded_cell.scene.model, live=True)
    try:
        served.animate(recorded_cell.recording)
        served_page = served.html()
    finally:
        served.close()
    assert served.vis.window.server_proc.poll() is not None  # stopped
    static = viz.MeshcatScene(recorded_cell.scene.model)
    static.animate(recorded_cell.recording)
    static_page = static.html()
    assert without_uuids(decode_commands(static_page)) == without_uuids(decode_commands(served_page))
    assert isinstance(served.vis, meshcat.Visualizer)


def test_deleting_a_path_removes_it_from_the_static_page(recorded_cell):
    scene = viz.MeshcatScene(recorded_cell.scene.model)
    scene.root["world"].delete()
    paths = {c["path"] for c in decode_commands(scene.html())}
    assert not any("/world/" in p for p in paths) and any("/carriage/" in p for p in paths)
    scene.vis.delete()  # everything under /meshcat; the camera (/Cameras) stays
    assert {c["path"].split("/")[1] for c in decode_commands(scene.html())} == {"Cameras"}


def test_save_animation_writes_the_page_and_show_html_points_at_it(recorded_cell, tmp_path, monkeypatch):
    page = tmp_path / "notebooks" / "animations" / "film.html"
    summary = viz.save_animation([recorded_cell.recording, recorded_cell.recording], recorded_cell.scene.model, page)
    assert page.is_file() and summary.frames == 2 * len(recorded_cell.recording)
    animations = [c for c in decode_commands(page.read_text(encoding="utf-8")) if c["type"] == "set_animation"]
    assert len(animations) == 1
    monkeypatch.chdir(tmp_path / "notebooks")
    frame = viz.show_html(page, height=300)
    assert frame.src == "animations/film.html" and frame.height == 300
    assert 'src="animations/film.html"' in frame._repr_html_()
    with pytest.raises(FileNotFoundError, match="save_animation"):
        viz.show_html(tmp_path / "notebooks" / "animations" / "missing.html")


def test_a_placement_film_shows_the_ends_of_its_stages(recorded_cell):
    """The frames are taken at the placement's start plus each chosen stage's end (trace times count from it)."""
    from drywall_lab.im import RobotCommand
    from drywall_lab.rc import PlacementResult
    from drywall_lab.site import default_site

    recording = recorded_cell.recording
    trace = JointTrace(stages=[("approach_pick", 0.0, 0.4), ("descend", 0.4, 0.9), ("lift", 0.9, 1.4)])
    command = RobotCommand.build(default_site(), "500320", "500100", "vertical_left")
    result = PlacementResult(command, True, None, None, 0.0, 0.0, 0.0, 1.4, 1.0, 0, trace=trace,
                             sim_start=recording.times[0])
    fig = viz.draw_placement_film(recorded_cell.scene.model, recording, result, stages=("lift", "descend"), ncols=2)
    assert [ax.get_title() for ax in fig.axes] == ["end of lift, t = 1 s", "end of descend, t = 1 s"]
    with pytest.raises(ValueError, match="none of the stages"):
        viz.draw_placement_film(recorded_cell.scene.model, recording, result, stages=("swing",))
