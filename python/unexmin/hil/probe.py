"""What the link to the robot does, seen from the simulator's host (docs/real_robot.md).

    python -m unexmin.hil.probe --out events.jsonl [--robot UX_1] [--thruster 0]

A rospy node that writes one JSON line per message, with the wall-clock time it arrived here (`t` [s]):
the robot's ESC commands (`cmd`: their stamp and values[thruster]), the ESC driver's thruster input (`in` [N]), the
simulator's achieved thrust (`thrust` [N]), `/clock` (`clock`: sim time [s]) and the robot's navigation (`nav`:
its stamp), and with `--sensor-topic` the arrival of each message of that topic (`sensor`). The functions below
turn such a record into the figures of docs/real_robot.md; they need no ROS.
Clock offsets are the robot's clock minus this host's (unexmin.hil.clock_sync, with the robot's time server).
"""

import argparse
import json
import statistics
import threading

from unexmin.hil.listen import with_bind_shim
from unexmin.topics import ESC_COMMAND_TOPIC

#: The kinds of event of a record.
KINDS = ("cmd", "in", "thrust", "clock", "nav", "sensor")
#: A thrust "responds" to a step when it has moved this fraction of the step towards the new level.
RESPONSE_FRACTION = 0.02


def load(path):
    """{kind: [event, ...]} of a probe's record, each kind in order of arrival (a last line still being written is
    left out)."""
    events = {k: [] for k in KINDS}
    with open(path) as f:
        for line in f:
            try:
                e = json.loads(line)
            except json.JSONDecodeError:
                continue
            events[e["k"]].append(e)
    return events


def summary(values):
    """{count, median, max} of `values` [s] (None figures when empty)."""
    values = sorted(values)
    return {
        "count": len(values),
        "median": statistics.median(values) if values else None,
        "max": values[-1] if values else None,
    }


def step_latencies(events, offset):
    """Latency of every step of the robot's command, from its stamp (on this host's clock: stamp - offset) to
    (a) its arrival here (`link`), (b) the ESC driver's thruster input changing (`input`), (c) the simulator's thrust
    moving RESPONSE_FRACTION of the step towards the new level (`thrust`). Returns {name: summary} [s]."""
    link = [c["t"] - (c["stamp"] - offset) for c in events["cmd"]]
    to_input, to_thrust = [], []
    previous = None
    for c in events["cmd"]:
        if previous is not None and c["v"] != previous["v"]:
            sent = c["stamp"] - offset
            old = next((e["v"] for e in reversed(events["in"]) if e["t"] < sent), None)
            new = next((e for e in events["in"] if e["t"] >= sent and e["v"] != old), None)
            if old is not None and new is not None:
                to_input.append(new["t"] - sent)
                step = new["v"] - old
                moved = next(
                    (e for e in events["thrust"] if e["t"] >= sent and (e["v"] - old) / step >= RESPONSE_FRACTION), None
                )
                if moved is not None:
                    to_thrust.append(moved["t"] - sent)
        previous = c
    return {"link": summary(link), "input": summary(to_input), "thrust": summary(to_thrust)}


def link_drop(events, down, up, offset, settle=0.02, zero=0.01):
    """What a link drop between the wall times `down` and `up` [s] (this host's clock) did: the last thruster input
    before the drop (`last_input`: t, level [N]); until when the thrust stayed within `settle` x level of it
    (`held_until`) and when it first fell to within `zero` x level of 0 (`zero_at`), both [s] after that input;
    the sim time the simulator advanced during the drop (`sim_advance` [s]) and its longest silence on /clock
    (`clock_gap` [s]); the first command stamped after `up` (`recovered_after`, its arrival [s] after up), the
    commands stamped during the drop that arrived after it (`late_commands`), and the time from that first fresh
    command to the first thrust within `settle` x level of the input then in effect (`thrust_follows_after` [s])."""
    before = [e for e in events["in"] if e["t"] < up]
    if not before:
        raise ValueError("no thruster input before the link came back: the commands never reached the simulator")
    last = before[-1]
    level = last["v"]
    thrust_after = [e for e in events["thrust"] if e["t"] > last["t"]]
    zero_at = next((e["t"] for e in thrust_after if abs(e["v"]) <= zero * abs(level)), None)
    held_until = last["t"]
    for e in thrust_after:
        if abs(e["v"] - level) > settle * abs(level):
            break
        held_until = e["t"]
    ticks = [e for e in events["clock"] if down <= e["t"] <= up]
    gaps = [b["t"] - a["t"] for a, b in zip(ticks, ticks[1:])]
    fresh = next((c for c in events["cmd"] if c["stamp"] - offset >= up), None)
    result = {
        "last_input": {"t": last["t"], "level": level},
        "held_until": held_until - last["t"],
        "zero_at": None if zero_at is None else zero_at - last["t"],
        "sim_advance": ticks[-1]["sim"] - ticks[0]["sim"] if ticks else 0.0,
        "clock_gap": max(gaps) if gaps else None,
        "recovered_after": None if fresh is None else fresh["t"] - up,
        "late_commands": sum(1 for c in events["cmd"] if c["t"] >= up and down <= c["stamp"] - offset < up),
        "thrust_follows_after": None,
    }
    if fresh is not None:
        inputs = [e for e in events["in"] if e["t"] >= fresh["t"]]  # the ESC driver's inputs from the fresh command on
        k = 0
        for e in (e for e in events["thrust"] if inputs and e["t"] >= inputs[0]["t"]):
            while k + 1 < len(inputs) and inputs[k + 1]["t"] <= e["t"]:
                k += 1
            if abs(e["v"] - inputs[k]["v"]) <= settle * max(abs(inputs[k]["v"]), 1.0):  # on the input in effect
                result["thrust_follows_after"] = e["t"] - fresh["t"]
                break
    return result


class Probe:
    """The recording node: subscribers that write one JSON line per message to `out` (a text file)."""

    def __init__(self, out, robot="UX_1", thruster=0, motor_topic=ESC_COMMAND_TOPIC, nav_topic=None, sensor_topic=None):
        import time

        import rospy
        from nav_msgs.msg import Odometry
        from rosgraph_msgs.msg import Clock
        from std_msgs.msg import Float64
        from ux1_msgs.msg import MotorCommand

        from unexmin.hil.robot_standin import NAV_TOPIC

        self.out, self.lock, self.clock = out, threading.Lock(), time.time
        ns = f"/{robot}/thrusters/{thruster}/"
        self.subs = [
            rospy.Subscriber(
                motor_topic,
                MotorCommand,
                lambda m: self.write("cmd", stamp=m.header.stamp.to_sec(), v=m.values[thruster]),
                tcp_nodelay=True,
            ),
            rospy.Subscriber(ns + "input", Float64, lambda m: self.write("in", v=m.data), tcp_nodelay=True),
            rospy.Subscriber(ns + "thrust", Float64, lambda m: self.write("thrust", v=m.data), tcp_nodelay=True),
            rospy.Subscriber("/clock", Clock, lambda m: self.write("clock", sim=m.clock.to_sec()), tcp_nodelay=True),
            rospy.Subscriber(
                nav_topic or NAV_TOPIC, Odometry, lambda m: self.write("nav", stamp=m.header.stamp.to_sec())
            ),
        ]
        if sensor_topic:
            self.subs.append(rospy.Subscriber(sensor_topic, rospy.AnyMsg, lambda m: self.write("sensor")))

    def write(self, kind, **fields):
        t = self.clock()
        with self.lock:
            self.out.write(json.dumps({"k": kind, "t": t, **fields}) + "\n")
            self.out.flush()


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m unexmin.hil.probe", description=__doc__.split("\n\n")[0])
    p.add_argument("--out", required=True, help="the record (JSON lines), written as messages come")
    p.add_argument("--robot", default="UX_1", help="the simulated robot (default %(default)s)")
    p.add_argument("--thruster", type=int, default=0, choices=range(8), help="thruster watched (default 0)")
    p.add_argument("--motor-topic", default=ESC_COMMAND_TOPIC)
    p.add_argument(
        "--nav-topic", default=None, help="the robot's navigation topic, nav_msgs/Odometry (default: the stand-in's)"
    )
    p.add_argument("--sensor-topic", default=None, help="a topic whose arrivals are recorded (default: none)")
    args = p.parse_args(argv)
    with_bind_shim("unexmin.hil.probe", argv)
    import rospy

    rospy.init_node("hil_probe", anonymous=True)
    with open(args.out, "w") as out:
        Probe(out, args.robot, args.thruster, args.motor_topic, args.nav_topic, args.sensor_topic)
        rospy.spin()


if __name__ == "__main__":
    main()
