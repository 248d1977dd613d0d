"""ROS's camera calibrator judges the cameras: it recovers camera 0's published CameraInfo from checkerboard views.

Twelve views of the tank's checkerboard target (worlds/tank_target.world's: 9 x 7 squares of 0.08 m, 8 x 6 inner
corners, kind `checkerboard`, docs/worlds.md) are rendered by the simulator's own camera model in-process
(unexmin.core, visual mode, clear water, seeded sensor noise; camera 0 at 640 x 480, the SLS laser off as during a
calibration, the LEDs' beams broad and the exposure lower as in a lit calibration tank: camera_views.camera_0).
UX_1 holds still in the tank; the target is placed at seeded random poses in front of the lens (0.6-1.2 m away,
tilted up to 30 deg, turned up to 17 deg, anywhere in the image: poses whose squares would leave the image are
redrawn). The frames go, as grey images, to the calibrator of Debian's ros-camera-calibration 1.17
(`camera_calibration.calibrator.MonoCalibrator`, the class `cameracalibrator.py` runs, with its default model: k1,
k2, p1, p2 free, k3 fixed at 0 (`--k-coefficients 2`)). Expected, from the camera's CameraInfo (`K` and `D` of the
unexmin.core sample: the numbers camera_publisher sends): fx, fy, cx and cy within 1 % and k1 within 0.02 (the
UX-1's camera: k1 = -0.1, k2 = 0.02). Measured: the board found in 12 of 12 views; fx and fy +0.2 %, cx -0.3 %,
cy -0.2 %, k1 -0.1005.

Needs the built workspace (unexmin.core), xacro on PATH and Debian's ros-camera-calibration (scripts/setup.sh).
Run: source scripts/env.sh; python -m pytest test/pytest/test_camera_calibration.py -q
"""

import cv2
import numpy as np
from camera_calibration.calibrator import ChessboardInfo, MonoCalibrator, Patterns
from camera_views import (
    COLUMNS,
    ROWS,
    SIZE,
    SQUARE,
    TANK_POSE,
    axis_rotation,
    board_in_world,
    board_mesh,
    camera_0,
    in_view,
    render,
    world_file,
)

VIEWS = 12


def board_poses(urdf, K, D, rng):
    """VIEWS poses (t, R) of the board in the world, seeded: 0.6-1.2 m from the lens, tilted up to 0.5 rad about
    the image's x and y axes, turned up to 0.3 rad about the optical axis, centred anywhere in the image; every
    square inside the image (12 px from its edges)."""
    poses = []
    while len(poses) < VIEWS:
        z = rng.uniform(0.6, 1.2)
        u, v = rng.uniform(0, SIZE[0]), rng.uniform(0, SIZE[1])
        centre = np.array([(u - K[0, 2]) / K[0, 0] * z, (v - K[1, 2]) / K[1, 1] * z, z])
        R_cb = axis_rotation(0, rng.uniform(-0.5, 0.5)) @ axis_rotation(1, rng.uniform(-0.5, 0.5))
        R_cb = R_cb @ axis_rotation(2, rng.uniform(-0.3, 0.3))
        if in_view(centre, R_cb, K, D, margin=12):
            poses.append(board_in_world(urdf, TANK_POSE, centre, R_cb))
    return poses


def views(folder):
    """(grey images of the board, K, D) of camera 0."""
    urdf = camera_0(folder, broad_lights=True)
    _, K, D = render(world_file(folder, "tank", TANK_POSE, name="empty"), urdf, seed=1)
    images = []
    for i, (t, R) in enumerate(board_poses(urdf, K, D, np.random.default_rng(5))):
        image, K_i, D_i = render(
            world_file(folder, "tank", TANK_POSE, [board_mesh(t, R)], name=f"view{i}"), urdf, seed=i
        )
        assert np.array_equal(K_i, K) and np.array_equal(D_i, D)
        images.append(cv2.cvtColor(image, cv2.COLOR_RGB2GRAY))
    return images, K, D


def test_the_ros_calibrator_recovers_the_published_camera_info(tmp_path):
    images, K, D = views(tmp_path)
    assert images[0].shape == (SIZE[1], SIZE[0])
    assert np.isclose(D[0], -0.1) and np.isclose(K[0, 0], 320 / np.tan(np.radians(40))), "not the UX-1's camera 0"
    calibrator = MonoCalibrator(
        [ChessboardInfo("chessboard", COLUMNS - 1, ROWS - 1, SQUARE)],
        flags=cv2.CALIB_FIX_K3,
        pattern=Patterns.Chessboard,
    )
    good = calibrator.collect_corners(images)
    print(f"checkerboard found in {len(good)} of {len(images)} views")
    assert len(good) >= 10, f"the calibrator found the board in {len(good)} of {len(images)} views, expected >= 10"
    calibrator.cal_fromcorners(good)
    k, d = calibrator.intrinsics, calibrator.distortion.ravel()
    print("published K", K.ravel().tolist(), "D", D.tolist())
    print("calibrated K", k.ravel().tolist(), "D", d.tolist())
    for name, (i, j) in {"fx": (0, 0), "fy": (1, 1), "cx": (0, 2), "cy": (1, 2)}.items():
        assert abs(k[i, j] - K[i, j]) <= 0.01 * K[i, j], f"{name} = {k[i, j]:.2f}, published {K[i, j]:.2f} (1 %)"
    assert abs(d[0] - D[0]) <= 0.02, f"k1 = {d[0]:.4f}, published {D[0]:.4f} (0.02)"
