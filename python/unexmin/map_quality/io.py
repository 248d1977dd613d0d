"""What map quality reads and writes besides the world (unexmin.worlds.files): an OctoMap .bt's occupied
leaves, and a robot's trajectory from a bag's odometry or a CSV."""

import csv
import os
import re
import shutil
import subprocess
import tempfile

import numpy as np

from unexmin.geometry import yaw_of

TRAJECTORY_COLUMNS = ("t", "x", "y", "z", "yaw")
_TRANSLATION = re.compile(r"translation\s+(\S+)\s+(\S+)\s+(\S+)\s+children \[ Shape \{ geometry Box \{ size (\S+)")


def read_bt(path):
    """(centres N x 3, sizes N) [m] of the occupied leaves of an OctoMap .bt, as OctoMap's bt2vrml writes them."""
    if shutil.which("bt2vrml") is None:
        raise RuntimeError("bt2vrml not found: install octomap-tools (scripts/setup.sh does)")
    if not os.path.exists(path):
        raise FileNotFoundError(path)
    with tempfile.TemporaryDirectory() as tmp:
        copy = os.path.join(tmp, "map.bt")
        shutil.copyfile(path, copy)
        out = subprocess.run(["bt2vrml", copy], capture_output=True, text=True, timeout=600)
        if out.returncode != 0 or not os.path.exists(copy + ".wrl"):
            raise RuntimeError(f"bt2vrml {path} failed: {out.stdout[-500:]} {out.stderr[-500:]}")
        with open(copy + ".wrl") as f:
            text = f.read().replace("\n", " ")
    rows = np.array([[float(v) for v in m] for m in _TRANSLATION.findall(text)]).reshape(-1, 4)
    reported = re.search(r"Finished writing (\d+) voxels", out.stdout)
    if reported and int(reported.group(1)) != len(rows):
        raise RuntimeError(f"bt2vrml reported {reported.group(1)} voxels, {len(rows)} parsed")
    return rows[:, :3], rows[:, 3]


def read_trajectory(path):
    """N x 5 rows (t [s], x, y, z [m], yaw [rad]) in time order: every nav_msgs/Odometry of a bag (its header
    stamps), or the rows of a CSV with x, y, z columns (t and yaw: NaN where the CSV has no such column)."""
    if str(path).endswith(".csv"):
        with open(path) as f:
            rows = list(csv.DictReader(f))
        if rows and not {"x", "y", "z"} <= rows[0].keys():
            raise ValueError(f"{path}: a trajectory CSV needs the columns x, y, z; it has {', '.join(rows[0])}")
        return np.array([[float(r.get(k, "nan")) for k in TRAJECTORY_COLUMNS] for r in rows]).reshape(-1, 5)
    from unexmin.bag import read_messages, stamp_to_sec, topic_types

    odometry = [t for t, kind in topic_types(path).items() if kind == "nav_msgs/msg/Odometry"]
    rows = []
    for _, _, _, msg in read_messages(path, odometry):
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        rows.append((stamp_to_sec(msg.header.stamp), p.x, p.y, p.z, yaw_of(q)))
    if not rows:
        raise ValueError(f"{path}: no nav_msgs/Odometry messages")
    rows.sort()
    return np.array(rows)


def write_trajectory(path, rows):
    """Trajectory rows (read_trajectory's) as a CSV with the columns t, x, y, z, yaw."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(TRAJECTORY_COLUMNS)
        w.writerows(np.asarray(rows).tolist())
