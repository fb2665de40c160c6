"""In a real browser: headless Chromium opens the animation ``simulate --html`` writes and notebook 06 exported
to HTML, and the test checks what was drawn, in screenshots, and that no JavaScript error was reported.

Chromium is driven through its DevTools protocol (``websocket-client``, which Jupyter's server already needs):
open a page, wait for it to draw, take a screenshot, and collect uncaught exceptions and console errors.
WebGL runs on SwiftShader, Chromium's software renderer, so no GPU is needed. Chromium is the Debian package
``chromium`` (``.ci/run`` installs it); without it the tests are skipped, except under ``CI=true``, where a
missing browser is a failure.
"""
from __future__ import annotations

import base64
import contextlib
import io
import json
import os
import shutil
import subprocess
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from matplotlib.colors import rgb_to_hsv
from PIL import Image

# meshcat 0.3.2 (the animations simulate --html writes) imports a pyzmq module that pyzmq has deprecated
pytestmark = pytest.mark.filterwarnings("ignore:zmq.eventloop.ioloop is deprecated:DeprecationWarning")

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM_FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
    "--disable-quic", "--no-first-run", "--disable-background-networking", "--disable-component-update",
    "--disable-sync", "--disable-extensions", "--mute-audio", "--remote-debugging-port=0",
]
PAGE_TIMEOUT = 60.0  # s


def find_chromium() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.fixture(scope="module")
def chromium() -> str:
    path = find_chromium()
    if path is None:
        if os.environ.get("CI", "").strip().lower() == "true":
            pytest.fail("CI=true but chromium is not installed: .ci/run installs the Debian package `chromium`")
        pytest.skip("headless Chromium is not installed (Debian: apt-get install chromium); CI installs it")
    return path


class Browser:
    """One headless Chromium with one page, driven over the DevTools protocol."""

    def __init__(self, executable: str, profile: Path, width: int = 1280, height: int = 800) -> None:
        import websocket

        profile.mkdir(parents=True, exist_ok=True)
        self.log = profile / "chromium.log"
        with open(self.log, "wb") as log:
            self.process = subprocess.Popen([executable, *CHROMIUM_FLAGS, f"--user-data-dir={profile}",
                                             f"--window-size={width},{height}", "about:blank"],
                                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=log)
        port_file = profile / "DevToolsActivePort"
        deadline = time.monotonic() + PAGE_TIMEOUT
        while not (port_file.exists() and port_file.read_text().strip()):
            if self.process.poll() is not None or time.monotonic() > deadline:
                self.close()
                raise RuntimeError(f"chromium did not start: {self.log.read_text(errors='replace')[-2000:]}")
            time.sleep(0.1)
        port = int(port_file.read_text().split()[0])
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=10) as answer:
            page = next(t for t in json.load(answer) if t["type"] == "page")
        self.socket = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=PAGE_TIMEOUT,
                                                  suppress_origin=True)
        self.events: list[dict] = []
        self._next_id = 0
        for domain in ("Runtime", "Log", "Page"):
            self.call(f"{domain}.enable")

    def call(self, method: str, **params) -> dict:
        self._next_id += 1
        self.socket.send(json.dumps({"id": self._next_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.socket.recv())
            if message.get("id") == self._next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.events.append(message)

    def open(self, url: str) -> None:
        """Load ``url`` and wait for its load event; the events seen so far are dropped."""
        self.events.clear()
        self.call("Page.navigate", url=url)
        deadline = time.monotonic() + PAGE_TIMEOUT
        while not any(e.get("method") == "Page.loadEventFired" for e in self.events):
            if time.monotonic() > deadline:
                raise TimeoutError(f"{url} did not finish loading")
            self.events.append(json.loads(self.socket.recv()))

    def evaluate(self, expression: str):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def screenshot(self, clip: dict | None = None) -> np.ndarray:
        """The page (or the ``clip`` rectangle of it, in page coordinates) as an RGB array in [0, 1]."""
        params = {"format": "png"}
        if clip is not None:
            params.update(clip=dict(clip, scale=1), captureBeyondViewport=True)
        png = base64.b64decode(self.call("Page.captureScreenshot", **params)["data"])
        return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=float) / 255.0

    def javascript_errors(self) -> list[str]:
        """Uncaught exceptions, console errors and the browser's JavaScript errors since the page was opened."""
        errors = []
        for e in self.events:
            method, params = e.get("method"), e.get("params", {})
            if method == "Runtime.exceptionThrown":
                details = params["exceptionDetails"]
                errors.append(details.get("exception", {}).get("description") or details.get("text", ""))
            elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
                errors.append(" ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", [])))
            elif method == "Log.entryAdded" and params["entry"]["level"] == "error" \
                    and params["entry"]["source"] not in ("network",):
                errors.append(params["entry"]["text"])
        return errors

    def network_errors(self) -> list[str]:
        return [e["params"]["entry"]["text"] for e in self.events if e.get("method") == "Log.entryAdded"
                and e["params"]["entry"]["source"] == "network" and e["params"]["entry"]["level"] == "error"]

    def close(self) -> None:
        with contextlib.suppress(Exception):
            self.socket.close()
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()


@pytest.fixture(scope="module")
def browser(chromium, tmp_path_factory):
    b = Browser(chromium, tmp_path_factory.mktemp("chromium"))
    yield b
    b.close()


# --- colours ----------------------------------------------------------------------------------------------------
def scene_colours() -> dict[str, tuple[float, float, float]]:
    """The robot's orange and the left and right stacks' panel colours, from the MuJoCo model itself. (The middle
    stack's light blue is left out: it is the hue of meshcat's sky.)"""
    import mujoco

    from drywall_lab.rc import robot_mjcf
    from drywall_lab.rc.scene import PANEL_COLOURS

    robot = mujoco.MjModel.from_xml_string(robot_mjcf())
    arm = robot.geom_rgba[mujoco.mj_name2id(robot, mujoco.mjtObj.mjOBJ_GEOM, "upper_arm")][:3]
    colours = {"robot": tuple(float(v) for v in arm)}
    for stack in ("left", "right"):
        colours[f"{stack} panels"] = tuple(float(v) for v in PANEL_COLOURS[stack].split()[:3])
    return colours


def colour_share(image: np.ndarray, rgb: tuple[float, float, float]) -> float:
    """The share of pixels of the colour ``rgb`` however lit: hue within 6 degrees, saturation within 0.12."""
    hsv = rgb_to_hsv(image)
    h, s, _ = rgb_to_hsv(np.array(rgb))
    hue_off = np.abs((hsv[..., 0] - h + 0.5) % 1.0 - 0.5) * 360
    return float(np.mean((hue_off < 6) & (np.abs(hsv[..., 1] - s) < 0.12) & (hsv[..., 2] > 0.25)))


def missing_colours(image: np.ndarray, least: float = 0.002) -> list[str]:
    return [name for name, rgb in scene_colours().items() if colour_share(image, rgb) < least]


def test_the_colour_check_finds_nothing_on_a_blank_page(browser):
    browser.open("about:blank")
    assert sorted(missing_colours(browser.screenshot())) == sorted(scene_colours())


# --- the animation simulate writes ------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def simulated_page(tmp_path_factory) -> Path:
    """``simulate --html`` on one instruction (one placement: the simulation stays short)."""
    from drywall_lab.__main__ import main

    folder = tmp_path_factory.mktemp("simulate")
    episodes = folder / "episodes.jsonl"
    episodes.write_text(json.dumps({"id": "one", "instructions": [
        "Pick up the full-size drywall and put it on stud 500100."]}) + "\n", encoding="utf-8")
    page = folder / "one.html"
    with contextlib.redirect_stdout(io.StringIO()) as out, contextlib.redirect_stderr(io.StringIO()):
        assert main(["simulate", str(episodes), "--html", str(page)]) == 0
    assert json.loads(out.getvalue())["placement"]["status"] == "placed"
    return page


def test_the_simulated_animation_draws_the_robot_and_the_panels_in_chromium(browser, simulated_page):
    browser.open(simulated_page.as_uri())
    deadline = time.monotonic() + PAGE_TIMEOUT
    while True:  # the scene arrives as data: URLs fetched after the load event, then WebGL draws it
        image = browser.screenshot()
        missing = missing_colours(image)
        if not missing or time.monotonic() > deadline:
            break
        time.sleep(0.5)
    assert not missing, f"not drawn: {missing}"
    assert browser.evaluate("document.querySelectorAll('#meshcat-pane canvas').length") >= 1
    assert browser.javascript_errors() == []
    assert browser.network_errors() == []  # self-contained: nothing fetched from anywhere


# --- a notebook exported to HTML ----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def exported_notebook(tmp_path_factory) -> tuple[Path, int]:
    """The committed notebook 06, as executed, exported with nbconvert; and how many PNG figures it holds."""
    import nbformat
    from nbconvert import HTMLExporter

    notebook = nbformat.read(ROOT / "notebooks" / "06_end_to_end.ipynb", as_version=4)
    figures = sum("image/png" in o.get("data", {}) for c in notebook.cells if c.cell_type == "code"
                  for o in c.outputs)
    figures += sum(c.source.count("](animations/") for c in notebook.cells if c.cell_type == "markdown")  # the GIF
    body, _ = HTMLExporter().from_notebook_node(notebook)
    folder = tmp_path_factory.mktemp("notebook")
    (folder / "animations").symlink_to(ROOT / "notebooks" / "animations", target_is_directory=True)
    page = folder / "06_end_to_end.html"
    page.write_text(body, encoding="utf-8")
    return page, figures


def test_the_exported_notebook_shows_its_figures_and_film_strip_in_chromium(browser, exported_notebook):
    page, figures = exported_notebook
    assert figures >= 5
    browser.open(page.as_uri())
    images = browser.evaluate("""Promise.all(Array.from(document.images).map(i => i.decode().then(() => true,
        () => false).then(decoded => ({decoded, complete: i.complete, width: i.naturalWidth,
        height: i.naturalHeight, film: i.closest('.celltag_film-strip') !== null}))))""")
    assert len(images) == figures
    assert all(i["decoded"] and i["complete"] and i["width"] > 100 and i["height"] > 100 for i in images), images
    assert sum(i["film"] for i in images) == 1
    box = browser.evaluate("""(() => { const i = document.querySelector('.celltag_film-strip img');
        i.scrollIntoView(); const r = i.getBoundingClientRect();
        return {x: r.left + window.scrollX, y: r.top + window.scrollY, width: r.width, height: r.height}; })()""")
    film = browser.screenshot(box)
    assert film.shape[0] > 100 and film.shape[1] > 100
    assert not missing_colours(film, least=0.005), f"not in the film strip: {missing_colours(film, least=0.005)}"
    assert browser.javascript_errors() == []
