"""What the replay reads from a robot bag: its commands and its navigation, as a Mission.

The bag is read completely before any simulator starts (unexmin.bag: rosbags, no roscore), so a
truncated or corrupt bag stops the replay with one error line. Topic roles and their defaults:
docs/replay.md, "Bag contents".
"""

from dataclasses import dataclass, field

import numpy as np

from unexmin.bag import BagError, read_messages, topic_types
from unexmin.replay.errors import ReplayError
from unexmin.replay.metrics import pose_row
from unexmin.topics import ESC_COMMAND_TOPIC

MOTORS_TOPIC = ESC_COMMAND_TOPIC  # default motor command topic of a robot bag
MOTOR_TYPE = "ux1_msgs/msg/MotorCommand"
FLOAT64_TYPE = "std_msgs/msg/Float64"
NAV_TYPES = ("nav_msgs/msg/Odometry", "geometry_msgs/msg/PoseWithCovarianceStamped", "geometry_msgs/msg/PoseStamped")


@dataclass
class Mission:
    """What the replay needs from a bag. Times are mission times [s]: bag time minus t0."""

    path: str
    t0: float  # bag time [s] of the first command
    motors: list  # (t, mode, values[8])
    pendulum: list = field(default_factory=list)  # (t, angle [rad])
    vbs: list = field(default_factory=list)  # (t, mass [kg])
    nav: np.ndarray = None  # rows of metrics.TRAJ_COLUMNS, or None
    topics: dict = field(default_factory=dict)  # role -> topic used

    def events(self):
        """Every command in time order: (t, kind, payload), kind 'motors' | 'pendulum' | 'vbs'."""
        ev = [(t, "motors", (mode, values)) for t, mode, values in self.motors]
        ev += [(t, "pendulum", v) for t, v in self.pendulum]
        ev += [(t, "vbs", v) for t, v in self.vbs]
        order = {"motors": 0, "pendulum": 1, "vbs": 2}
        return sorted(ev, key=lambda e: (e[0], order[e[1]]))

    @property
    def duration(self):
        """[s] up to the last command or navigation sample."""
        ends = [self.events()[-1][0]]
        if self.nav is not None and len(self.nav):
            ends.append(float(self.nav[-1, 0]))
        return max(ends)


def pick_topic(types, wanted, accepted, role, required):
    """Topic of the bag for `role`: `wanted` if given (it must exist with one of the `accepted` types),
    else the bag's only topic of those types; None when absent and not `required`.
    types: {topic: message type} of the bag. Raises ReplayError naming the role and the bag's topics."""
    listing = ", ".join(f"{t} [{m}]" for t, m in sorted(types.items())) or "none"
    if wanted:
        if wanted not in types:
            if required:
                raise ReplayError(f"no topic {wanted} in the bag (topics: {listing})")
            return None
        if types[wanted] not in accepted:
            raise ReplayError(f"topic {wanted} is {types[wanted]}, expected {' or '.join(accepted)} for the {role}")
        return wanted
    candidates = sorted(t for t, m in types.items() if m in accepted)
    if len(candidates) == 1:
        return candidates[0]
    if len(candidates) > 1:
        raise ReplayError(
            f"several {role} topics in the bag ({', '.join(candidates)}): choose one with --{role.split()[0]}-topic"
        )
    if required:
        raise ReplayError(f"no {role} ({' or '.join(accepted)}) in the bag (topics: {listing})")
    return None


def read_bag(path, robot="UX_1", motors_topic=MOTORS_TOPIC, pendulum_topic=None, vbs_topic=None, nav_topic=None):
    """Read a robot bag into a Mission. Raises ReplayError (one message) for a missing, truncated or
    corrupt bag or one without motor commands.

    Topic defaults: motors_topic (else the bag's only MotorCommand topic); /<robot>/pendulum and
    /<robot>/vbs; navigation /<robot>/odom, else the bag's only Odometry/Pose topic.
    """
    try:
        types = topic_types(path)
        chosen = {
            # The default topic falls back to the bag's only MotorCommand topic; an explicit one must exist.
            "motors": pick_topic(
                types,
                None if motors_topic == MOTORS_TOPIC and motors_topic not in types else motors_topic,
                (MOTOR_TYPE,),
                "motors command",
                True,
            ),
            "pendulum": pick_topic(
                types, pendulum_topic or f"/{robot}/pendulum", (FLOAT64_TYPE,), "pendulum command", bool(pendulum_topic)
            ),
            "vbs": pick_topic(types, vbs_topic or f"/{robot}/vbs", (FLOAT64_TYPE,), "vbs command", bool(vbs_topic)),
            "nav": pick_topic(
                types,
                nav_topic or (f"/{robot}/odom" if f"/{robot}/odom" in types else None),
                NAV_TYPES,
                "nav topic",
                bool(nav_topic),
            ),
        }
        role_of = {t: r for r, t in chosen.items() if t}
        messages = read_messages(path, set(role_of))
    except BagError as e:
        raise ReplayError(str(e)) from None
    rows = {"motors": [], "pendulum": [], "vbs": [], "nav": []}
    for topic, msgtype, t, msg in messages:
        role = role_of[topic]
        if role == "motors":
            rows["motors"].append((t, int(msg.mode), tuple(float(v) for v in msg.values)))
        elif role in ("pendulum", "vbs"):
            rows[role].append((t, float(msg.data)))
        else:
            pose = msg.pose if msgtype == "geometry_msgs/msg/PoseStamped" else msg.pose.pose
            rows["nav"].append(pose_row(t, pose))
    if not rows["motors"]:
        raise ReplayError(f"{path}: no messages on {chosen['motors']}")
    commands = rows["motors"] + [(t, 0, ()) for t, _ in rows["pendulum"] + rows["vbs"]]
    t0 = min(t for t, _, _ in commands)
    nav = None
    if rows["nav"]:
        nav = np.array(rows["nav"], dtype=float)
        nav = nav[np.argsort(nav[:, 0], kind="stable")]
        nav[:, 0] -= t0
        nav = nav[nav[:, 0] >= -1e-9]
        if len(nav) < 2:
            nav = None
    return Mission(
        path=str(path),
        t0=t0,
        motors=[(t - t0, m, v) for t, m, v in rows["motors"]],
        pendulum=[(t - t0, v) for t, v in rows["pendulum"]],
        vbs=[(t - t0, v) for t, v in rows["vbs"]],
        nav=nav,
        topics={k: v for k, v in chosen.items() if v},
    )
