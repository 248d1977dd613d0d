"""ROS's rectification judges the cameras: with the published CameraInfo, the checkerboard's lines come out straight.

Camera 0 (640 x 480, its k1 = -0.1, k2 = 0.02 barrel distortion) sees the tank's checkerboard target
(worlds/tank_target.world's: 8 x 6 inner corners of 0.08 m squares) 0.55-0.6 m away, filling the image, tilted or
turned so that the distortion bends its rows most (frames of the simulator's own camera model in-process:
unexmin.core, visual mode, clear water, seeded noise, the SLS laser off; the LEDs' beams broad and the exposure
lower as in a lit calibration tank: camera_views.camera_0). Each raw frame is rectified as image_proc's `rectify`
does: a sensor_msgs/CameraInfo with the camera's K and D (the numbers camera_publisher sends), R = I, P = [K | 0],
given to image_geometry's PinholeCameraModel (Debian's python3-image-geometry), whose rectifyImage is the
undistortion map and remap the rectify nodelet applies. (Debian 12's /usr/lib/image_proc/image_proc stops at
start-up: pluginlib finds no package 'nodelet', and image_proc's package.xml names a nodelet_plugins.xml Debian does
not ship, so the node cannot load its rectify nodelet here; the nodelet's rectification is the same image_geometry
call, in C++.) Then OpenCV finds the inner corners (findChessboardCorners, cornerSubPix) and each row of 8 and each
column of 6 corners, the images of straight lines of the board, must lie on a straight line within 1 px (the largest
distance of a corner from the row's least-squares line; measured 0.56-0.63 px). In the raw frames the same rows are
bent by more than 1.5 px (measured 2.2-3.1 px; 2.1-2.6 px from the projection): the test sees the lens, and a wrong
D would fail it.

Needs the built workspace (unexmin.core), xacro on PATH and Debian's python3-image-geometry (scripts/setup.sh).
Run: source scripts/env.sh; python -m pytest test/pytest/test_camera_rectify.py -q
"""

import camera_views as views
import cv2
import numpy as np
from image_geometry import PinholeCameraModel
from sensor_msgs.msg import CameraInfo

# The board's views (found by searching poses for the largest bend of a row in the raw image with every square
# 15 px inside it): distance [m], pixel (u, v) where its centre is seen, tilt about the image's x axis and turn about
# the optical axis [rad]. Nearer than 0.55 m or farther out in the image, a square leaves it.
VIEWS = [
    (0.55, 320, 240, -0.4, 0.0),
    (0.55, 320, 240, 0.4, 0.0),
    (0.6, 200, 240, 0.0, 1.5708),
    (0.6, 440, 240, 0.0, 1.5708),
]


def camera_info(K, D):
    msg = CameraInfo()
    msg.width, msg.height = views.SIZE
    msg.distortion_model = "plumb_bob"
    msg.D = [float(v) for v in D]
    msg.K = [float(v) for v in K.ravel()]
    msg.R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    msg.P = [float(v) for v in np.hstack([K, np.zeros((3, 1))]).ravel()]
    return msg


def corners(image):
    """The board's 8 x 6 inner corners [px] (rows of 8), sub-pixel, or None."""
    ok, c = cv2.findChessboardCorners(image, (views.COLUMNS - 1, views.ROWS - 1), flags=cv2.CALIB_CB_ADAPTIVE_THRESH)
    if not ok:
        return None
    c = cv2.cornerSubPix(image, c, (5, 5), (-1, -1), (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 50, 0.01))
    return c.reshape(views.ROWS - 1, views.COLUMNS - 1, 2)


def straightness(points):
    """Largest distance [px] of `points` (n x 2) from their total-least-squares line."""
    centred = points - points.mean(axis=0)
    normal = np.linalg.svd(centred)[2][-1]
    return float(np.abs(centred @ normal).max())


def worst_line(grid):
    """The worst straightness [px] over the grid's rows and columns."""
    return max([straightness(r) for r in grid] + [straightness(c) for c in grid.transpose(1, 0, 2)])


def test_rectified_rows_of_corners_are_straight(tmp_path):
    urdf = views.camera_0(tmp_path, broad_lights=True)
    _, K, D = views.render(views.world_file(tmp_path, "tank", views.TANK_POSE, name="empty"), urdf, seed=1)
    model = PinholeCameraModel()
    model.fromCameraInfo(camera_info(K, D))
    raw_worst, rectified_worst = [], []
    for i, (distance, u, v, tilt, turn) in enumerate(VIEWS):
        centre = np.array([(u - K[0, 2]) / K[0, 0], (v - K[1, 2]) / K[1, 1], 1.0]) * distance
        R_cb = views.axis_rotation(0, tilt) @ views.axis_rotation(2, turn)
        assert views.in_view(centre, R_cb, K, D, margin=10), f"view {i}: the board leaves the image"
        t, R = views.board_in_world(urdf, views.TANK_POSE, centre, R_cb)
        image = cv2.cvtColor(
            views.render(
                views.world_file(tmp_path, "tank", views.TANK_POSE, [views.board_mesh(t, R)], name=f"q{i}"),
                urdf,
                seed=10 + i,
            )[0],
            cv2.COLOR_RGB2GRAY,
        )
        rectified = np.zeros_like(image)
        model.rectifyImage(image, rectified)
        raw, rect = corners(image), corners(rectified)
        assert raw is not None and rect is not None, f"view {i}: no checkerboard found (raw {raw is not None})"
        raw_worst.append(worst_line(raw))
        rectified_worst.append(worst_line(rect))
    print(
        "worst row or column off its line [px], raw:",
        np.round(raw_worst, 2),
        "rectified:",
        np.round(rectified_worst, 2),
    )
    assert max(rectified_worst) <= 1.0, f"rectified: a row of corners {max(rectified_worst):.2f} px off straight"
    assert min(raw_worst) > 1.5, f"raw: rows within {min(raw_worst):.2f} px of straight: the lens should bend them"
