"""A textbook monocular visual odometry judges the cameras: camera 0's frame-to-frame rotation against ground truth.

UX_1 turns on the spot in the mine's first-level gallery (worlds/mine.world, its rock; the robot at x = 11.5 m,
y = -0.07 m, z = -21.4 m as in docs/vision.md's pictures) from rest under a constant yaw moment of 1 N m, in clear
water, for 10 s of sim time: the turn grows from 0 to 2.9 deg per frame (29 deg/s), median 1.9 deg. Camera 0's 100
frames (640 x 480 at 10 fps, the simulator's own camera model in-process, unexmin.core, visual mode, seeded noise;
the robot's own LEDs, the SLS laser off, as a VO run on the lights alone). The VO is OpenCV's textbook chain:
Shi-Tomasi corners in frame k (cv2.goodFeaturesToTrack), tracked into frame k + 1 by pyramidal Lucas-Kanade
(cv2.calcOpticalFlowPyrLK), undistorted with the published CameraInfo's K and D, an essential matrix by RANSAC
(cv2.findEssentialMat) and its rotation (cv2.recoverPose). Ground truth: the robot's orientation at each frame (the
core's state, the odometry's) turned into camera 0's optical frame by the description's joints. The error of a pair
is the angle of R_vo^T R_true (a failed pair counts as infinite). Expected: median over the 99 pairs <= 0.5 deg.

Measured (seed 3): median 0.29 deg, 3 of 99 pairs flipped by 180 deg (recoverPose's twisted pair: the camera moves
only 0.3 m x the turn, so the essential matrix's translation is nearly nil). The error grows with the turn: VO
overestimates the rotation by about 15 % (2.6 for 2.2 deg), which is what the camera's sideways slide gives if
taken for rotation: 0.3 m off the yaw axis, it slides by 0.3 m x the turn in front of a wall 1.5-2 m away (flow of
0.15-0.2 x the turn), and over one frame pair of a narrow view the essential matrix barely tells the two apart; at
6 N m (7.8 deg per frame) the median error is 0.70 deg. At `medium` visibility the same run gives a median of
2.0 deg, the size of the turn itself: the wall is lost in the murk and KLT tracks the backscatter glow and the noise,
which turn with the camera (not asserted: measured once, 26 s of rendering).

Needs the built workspace (unexmin.core), xacro on PATH and the generated mine (scripts/setup.sh).
Run: source scripts/env.sh; python -m pytest test/pytest/test_camera_vo.py -q -s
"""

import math

import cv2
import numpy as np
import pytest
from camera_views import REPO, SIZE, angle_of, camera_0, camera_pose, world_file

from unexmin.control.allocation import ThrusterAllocator
from unexmin.geometry import quaternion_to_rpy, rpy_matrix

GALLERY = (11.5, -0.07, -21.4, 0.0, 0.0, 0.0)  # [m, rad] UX_1's spawn pose: the first level's gallery
YAW_MOMENT = 1.0  # [N m] about the body's z: the turn grows from 0 to 29 deg/s over the 10 s
SECONDS = 10.0


def turning_sequence(folder, visibility):
    """Camera 0's grey frames, their camera orientations in the world and (K, D) over SECONDS of turning."""
    from unexmin.core import World

    assert (REPO / "worlds" / "meshes" / "mine" / "mine_collision.ply").exists(), "run scripts/setup.sh (the mine)"
    urdf = camera_0(folder)
    _, R_bc = camera_pose(urdf, "camera_0")
    w = World(
        str(world_file(folder, "mine", GALLERY, name=f"gallery_{visibility}")),
        seed=3,
        sensors="camera",
        visibility=visibility,
        mode="visual",
        descriptions={"UX_1": urdf},
    )
    ux = w.robot("UX_1")
    ux.thrusts(ThrusterAllocator().allocate((0, 0, 0, 0, 0, YAW_MOMENT))[0])
    frames, rotations, count = [], [], 0
    K = D = None
    while w.time < SECONDS - 1e-9:
        w.step(1)
        s = ux.sample("camera_0")
        if s["count"] == count:
            continue
        count = s["count"]
        assert s["rendered"]
        frames.append(cv2.cvtColor(s["image"], cv2.COLOR_RGB2GRAY))
        rotations.append(rpy_matrix(quaternion_to_rpy(*ux.state()["orientation"])) @ R_bc)
        K, D = s["K"].copy(), s["D"].copy()
    return frames, rotations, K, D


def vo_rotation(a, b, K, D):
    """Rotation R of camera frame a to frame b (x_b = R x_a + t) by Shi-Tomasi + KLT + essential matrix, or None."""
    p = cv2.goodFeaturesToTrack(a, maxCorners=1000, qualityLevel=0.01, minDistance=8, blockSize=7)
    if p is None or len(p) < 8:
        return None
    q, status, _ = cv2.calcOpticalFlowPyrLK(a, b, p, None, winSize=(21, 21), maxLevel=3)
    ok = status.ravel() == 1
    if ok.sum() < 8:
        return None
    na = cv2.undistortPoints(p[ok], K, D).reshape(-1, 2)
    nb = cv2.undistortPoints(q[ok], K, D).reshape(-1, 2)
    E, mask = cv2.findEssentialMat(
        na, nb, np.eye(3), method=cv2.RANSAC, prob=0.999, threshold=1.0 / K[0, 0], maxIters=2000
    )
    if E is None or E.shape != (3, 3):
        return None
    _, R, _, _ = cv2.recoverPose(E, na, nb, np.eye(3), mask=mask)
    return R


def rotation_errors(frames, rotations, K, D):
    """Per consecutive pair: (VO error [deg] or inf when the VO fails, true rotation [deg])."""
    cv2.setRNGSeed(7)
    out = []
    for k in range(len(frames) - 1):
        true = rotations[k + 1].T @ rotations[k]
        R = vo_rotation(frames[k], frames[k + 1], K, D)
        out.append((math.inf if R is None else math.degrees(angle_of(R.T @ true)), math.degrees(angle_of(true))))
    return np.array(out)


@pytest.mark.long
def test_vo_follows_the_turn_in_clear_water(tmp_path):
    frames, rotations, K, D = turning_sequence(tmp_path, "none")
    assert len(frames) == round(SECONDS * 10) and frames[0].shape == (SIZE[1], SIZE[0])
    errors = rotation_errors(frames, rotations, K, D)
    median, turned = float(np.median(errors[:, 0])), float(np.median(errors[:, 1]))
    print(
        f"clear water: median VO rotation error {median:.3f} deg over {len(errors)} pairs "
        f"(median turn {turned:.2f} deg per frame, failures {int(np.isinf(errors[:, 0]).sum())})"
    )
    assert turned > 0.5, f"the robot turns {turned:.2f} deg per frame: expected a turn"
    assert median <= 0.5, f"median VO rotation error {median:.3f} deg, expected <= 0.5 deg"
