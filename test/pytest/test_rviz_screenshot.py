"""rviz under Xvfb with the shipped config (launch/unexmin.rviz) renders the mine and the robots.

Starts a virtual X server, then `roslaunch unexmin mine_world.launch robots:=3 rviz:=true` on a private
master (the simulator, the mesh marker, rviz), waits until rviz is subscribed to the mesh marker and
the robots' tf, then takes screenshots of the root window (ImageMagick `import`) until the 3-D view
shows both the mine's walls (the mesh marker's slate colour, mesh_marker.ROCK, under rviz's shading)
and the three yellow hulls (urdf/properties.xacro hull_rgba) as three separate blobs, or a timeout.

    UNEXMIN_DOCS_SCREENSHOT=1 python -m pytest test/pytest/test_rviz_screenshot.py   # also refreshes
                                                                                       # docs/images/mine_rviz.png
"""
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from unexmin.launcher import stop_process_group

REPO = Path(__file__).resolve().parents[2]
DOCS_IMAGE = REPO / "docs" / "images" / "mine_rviz.png"
WIDTH, HEIGHT = 1024, 768
pytestmark = pytest.mark.skipif(not all(shutil.which(t) for t in ("Xvfb", "import", "rviz", "roslaunch")),
                                reason="needs Xvfb, ImageMagick's import, rviz and roslaunch")


def view_region(img):
    """The 3-D view of rviz's window (right of the Displays dock, below the toolbar) in the
    shipped config's 1024 x 768 layout."""
    h, w = img.shape[:2]
    return img[int(0.12 * h):int(0.94 * h), int(0.38 * w):int(0.97 * w)].astype(int)


def classify(img):
    """Fractions of rock-coloured pixels and the count of yellow hull blobs in the 3-D view."""
    from scipy import ndimage

    v = view_region(img)
    r, g, b = v[..., 0], v[..., 1], v[..., 2]
    # slate (0.42, 0.47, 0.55) scaled by the light: blue above red by >= 8 % of brightness, not saturated
    rock = (b > 40) & (b - r >= 0.08 * b) & (b - r <= 0.45 * b) & (g >= r) & (g <= b)
    # hull yellow (0.95, 0.75, 0.10): strong red and green, little blue
    hull = (r > 120) & (g > 90) & (b < 0.45 * r) & (r - b > 80)
    labels, n = ndimage.label(hull)
    sizes = np.bincount(labels.ravel())[1:]
    return {"rock": float(rock.mean()), "hull_blobs": int((sizes >= 20).sum()), "std": float(v.std()),
            "hull_pixels": int(hull.sum())}


def screenshot(display, path):
    subprocess.run(["import", "-display", display, "-window", "root", str(path)], check=True,
                   capture_output=True, timeout=30)
    from PIL import Image
    return np.asarray(Image.open(path).convert("RGB"))


@pytest.fixture
def xvfb():
    proc = subprocess.Popen(["Xvfb", "-displayfd", "1", "-screen", "0", f"{WIDTH}x{HEIGHT}x24", "-nolisten", "tcp"],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, start_new_session=True)
    try:
        number = proc.stdout.readline().strip()
        if not number.isdigit():
            pytest.fail("Xvfb did not report a display number")
        yield f":{number}"
    finally:
        proc.terminate()
        proc.wait(10)


def subscribed(master, topic, node):
    _, subs, _ = master.getSystemState()
    return any(t == topic and node in nodes for t, nodes in subs)


def test_shipped_config_shows_the_mine_and_three_robots(xvfb, tmp_path):
    import rosgraph

    from unexmin.launcher import free_port, wait_for

    port = free_port()
    env = dict(os.environ, DISPLAY=xvfb, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_IP="127.0.0.1",
               ROS_LOG_DIR=str(tmp_path / "log"), ROS_HOME=str(tmp_path))
    log = open(tmp_path / "roslaunch.log", "w")
    launch = subprocess.Popen(["roslaunch", "--port", str(port), "unexmin", "mine_world.launch", "robots:=3",
                               "rviz:=true", "seed:=1"], env=env, stdout=log, stderr=subprocess.STDOUT,
                              start_new_session=True)
    stats = {}
    try:
        master = rosgraph.Master("/rviz_screenshot_test", master_uri=env["ROS_MASTER_URI"])

        missing = ["the master"]

        def ready():
            checks = {"the simulator (/sim/step)": lambda: master.lookupService("/sim/step"),
                      "the mesh marker node (/mesh_marker)": lambda: master.lookupNode("/mesh_marker"),
                      "rviz subscribed to /world_meshes": lambda: subscribed(master, "/world_meshes", "/rviz"),
                      "rviz subscribed to /tf": lambda: subscribed(master, "/tf", "/rviz")}
            missing[:] = []
            for what, check in checks.items():
                try:
                    if not check():
                        missing.append(what)
                except (OSError, rosgraph.MasterError):
                    missing.append(what)
            return not missing

        try:
            wait_for(lambda: launch.poll() is not None or ready(), 90, "the simulator, the mesh marker and rviz")
        except TimeoutError:
            pytest.fail(f"after 90 s still missing: {', '.join(missing)} (log: {tmp_path / 'roslaunch.log'})")
        assert launch.poll() is None, f"roslaunch exited: see {tmp_path / 'roslaunch.log'}"
        shot = tmp_path / "shot.png"

        def rendered():
            stats.update(classify(screenshot(xvfb, shot)))
            return stats["rock"] > 0.05 and stats["hull_blobs"] >= 3

        try:
            wait_for(rendered, 90, "rviz to draw the mine and the robots", poll=1.0)
        except TimeoutError:
            pass  # the assertions below report what was seen
        assert stats["std"] > 10.0, f"blank 3-D view: {stats}"
        assert stats["rock"] > 0.05, f"too little of the mine's wall colour in the view: {stats}"
        assert stats["hull_blobs"] >= 3, f"expected the three yellow hulls: {stats}"
        if os.environ.get("UNEXMIN_DOCS_SCREENSHOT") == "1":
            DOCS_IMAGE.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(shot, DOCS_IMAGE)
    finally:
        stop_process_group(launch, 30.0)
        log.close()


def test_classifier_tells_rock_hull_and_background_apart():
    """The colour tests above against synthetic pixels: the slate and the yellow under a range of
    shading, rviz's background and the docks' greys."""
    img = np.zeros((HEIGHT, WIDTH, 3), np.uint8)
    img[:] = (30, 30, 36)                                          # the config's background
    rows = np.linspace(int(0.12 * HEIGHT), int(0.94 * HEIGHT), 4).astype(int)
    x0, x1 = int(0.38 * WIDTH), int(0.97 * WIDTH)
    for shade, (top, bottom) in zip((0.4, 0.7, 1.0), zip(rows[:-1], rows[1:])):
        img[top:bottom, x0:x1] = np.round(255 * shade * np.array([0.42, 0.47, 0.55]))
    for k, shade in enumerate((0.6, 0.8, 1.0)):                    # three hulls
        y, x = 300, x0 + 60 + 120 * k
        img[y:y + 12, x:x + 12] = np.round(255 * shade * np.array([0.95, 0.75, 0.10]))
    stats = classify(img)
    assert stats["hull_blobs"] == 3
    assert stats["rock"] > 0.9
    grey = np.full((HEIGHT, WIDTH, 3), 200, np.uint8)              # Qt's panels: neither
    assert classify(grey)["rock"] == 0.0 and classify(grey)["hull_blobs"] == 0
