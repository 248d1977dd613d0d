#!/usr/bin/env python3
"""Client process of test_fuzz.py: the tank world in real time with UX_1 moving (a steady wrench through its
allocator) and the ESC driver of UX_1 started beside it; then for FUZZ s every input gets bad messages at
about 1 kHz in turn (NaN, +-inf, 1e300, -1e300, negative, empty and short raw payloads, a MotorCommand of an
unknown mode), and every /sim/* service bad requests. Prints one JSON line with what it saw.

usage: fuzz_run.py <log dir> <fuzz seconds>
"""

import json
import math
import os
import struct
import subprocess
import sys
import time


def raw_class(msg_class, payload):
    """A message class with `msg_class`'s type and md5sum whose serialisation is the bytes `payload`
    (an empty or short body: what a broken driver might send)."""
    import genpy

    class Raw(genpy.Message):
        _type, _md5sum, _full_text, _has_header = msg_class._type, msg_class._md5sum, msg_class._full_text, False
        __slots__ = []
        _slot_types = []

        def serialize(self, buff):
            buff.write(payload)

        def deserialize(self, s):
            return self

    return Raw


def main():
    log_dir, fuzz_seconds = sys.argv[1], float(sys.argv[2])
    import rospy
    from geometry_msgs.msg import Wrench
    from nav_msgs.msg import Odometry
    from rosgraph_msgs.msg import Log
    from std_msgs.msg import Float64
    from std_srvs.srv import Empty
    from ux1_msgs.msg import MotorCommand

    from unexmin.scripting.launcher import WorldProcess, stop_process_group, wait_for
    from unexmin.srv import Record, Reset, Step

    world = WorldProcess(world="tank", realtime=True, paused=False, log_dir=log_dir)
    esc = None
    result = {}
    try:
        wait_for(lambda: _up(world), 60.0, "the simulator")
        rospy.init_node("fuzzer", disable_signals=True)
        esc = subprocess.Popen(
            ["roslaunch", "--wait", "unexmin", "control.launch", "robot:=UX_1", "allocator:=false", "esc_driver:=true"],
            stdout=open(os.path.join(log_dir, "esc.log"), "w"),
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        odom, warnings = [], []
        rospy.Subscriber("/UX_1/odom", Odometry, lambda m: odom.append(m), queue_size=1000)
        rospy.Subscriber(
            "/rosout_agg",
            Log,
            lambda m: warnings.append((time.monotonic(), m.name, m.level, m.msg[:90])),
            queue_size=10000,
        )
        ns = "/UX_1/"
        floats = [rospy.Publisher(ns + f"thrusters/{i}/input", Float64, queue_size=100) for i in range(8)]
        floats += [
            rospy.Publisher(ns + "pendulum", Float64, queue_size=100),
            rospy.Publisher(ns + "vbs", Float64, queue_size=100),
        ]
        wrench = rospy.Publisher(ns + "force_moments", Wrench, queue_size=100)
        motors = rospy.Publisher("/ux1/command/motors", MotorCommand, queue_size=100)
        raw_float = [rospy.Publisher(p.resolved_name, raw_class(Float64, b""), queue_size=100) for p in floats[:1]]
        raw_float += [rospy.Publisher(floats[8].resolved_name, raw_class(Float64, b"\x00\x00\x00"), queue_size=100)]
        raw_motors = rospy.Publisher("/ux1/command/motors", raw_class(MotorCommand, b"\x01\x02"), queue_size=100)
        raw_wrench = rospy.Publisher(
            ns + "force_moments", raw_class(Wrench, struct.pack("<3d", 1, 2, 3)), queue_size=100
        )
        wait_for(
            lambda: all(p.get_num_connections() > 0 for p in floats + [wrench, motors]), 60.0, "the inputs to connect"
        )
        wait_for(lambda: len(odom) > 0, 60.0, "odometry")
        start_pose = odom[-1].pose.pose.position
        bad = [float("nan"), float("inf"), float("-inf"), 1e300, -1e300, -5.0]

        def good_wrench():
            w = Wrench()
            w.force.x, w.torque.z = 10.0, 1.0
            wrench.publish(w)

        t0 = time.monotonic()
        sent = 0
        k = 0
        while time.monotonic() - t0 < fuzz_seconds:
            # each input in turn, and at each of its turns the next bad value: every input gets every value
            v = bad[(k // len(floats)) % len(bad)]
            floats[k % len(floats)].publish(Float64(v))
            if k % 10 == 0:
                w = Wrench()
                w.force.x, w.force.y, w.torque.z = v, 1e300, -v
                wrench.publish(w)
                m = MotorCommand()
                m.mode = k % 3  # 2: no such mode
                m.values = [v] * 8
                motors.publish(m)
            if k % 50 == 0:
                for p in raw_float + [raw_motors, raw_wrench]:
                    p.publish(p.data_class())
                good_wrench()  # the robot keeps moving between the bad ones
            sent += 1
            k += 1
            time.sleep(0.001)
        result["fuzz_messages"] = sent
        result["fuzz_rate_hz"] = sent / (time.monotonic() - t0)

        # Absurd service requests: each must fail fast (an error, not a hang).
        step = rospy.ServiceProxy("/sim/step", Step)
        pause, unpause = rospy.ServiceProxy("/sim/pause", Empty), rospy.ServiceProxy("/sim/unpause", Empty)
        reset_seed = rospy.ServiceProxy("/sim/reset_seed", Reset)
        record = rospy.ServiceProxy("/sim/record", Record)
        pause()
        errors = {}
        for name, call in (
            ("step duration -1", lambda: step(duration=-1.0)),
            ("step duration nan", lambda: step(duration=float("nan"))),
            ("step duration inf", lambda: step(duration=float("inf"))),
            ("step duration 1e9", lambda: step(duration=1e9)),
            ("step steps 2^32-1", lambda: step(steps=2**32 - 1)),
            ("reset_seed -1", lambda: reset_seed(seed=-1)),
        ):
            t = time.monotonic()
            try:
                call()
                errors[name] = "accepted"
            except rospy.ServiceException:
                errors[name] = "error"
            errors[name] += f" in {time.monotonic() - t:.3f} s"
        rec = record(path="/nonexistent_dir_unexmin/x.bag")
        errors["record into a missing folder"] = f"ok={rec.ok}: {rec.message}"
        res = step(duration=0.5)  # still steps normally afterwards
        result["step_after"] = res.time
        unpause()
        result["services"] = errors
        result["odom_messages"] = len(odom)
        result["odom_finite"] = all(
            math.isfinite(v)
            for m in odom
            for v in (
                m.pose.pose.position.x,
                m.pose.pose.position.y,
                m.pose.pose.position.z,
                m.pose.pose.orientation.w,
                m.twist.twist.linear.x,
                m.twist.twist.angular.z,
            )
        )
        end = odom[-1].pose.pose.position
        result["moved_m"] = math.dist((start_pose.x, start_pose.y, start_pose.z), (end.x, end.y, end.z))
        per_second = {}
        texts = {}
        for t, name, level, text in warnings:
            if level >= Log.WARN and "Exception thrown when deserializing" not in text:  # roscpp's own, per message
                key = (name, int(t - t0))
                per_second[key] = per_second.get(key, 0) + 1
                texts[(name, text[:50])] = texts.get((name, text[:50]), 0) + 1
            elif level >= Log.WARN:
                texts[(name, text[:50])] = texts.get((name, text[:50]), 0) + 1
        result["max_warnings_per_node_second"] = max(per_second.values(), default=0)
        result["warning_kinds"] = sorted(f"{n}: {t} x{c}" for (n, t), c in texts.items())
        result["warning_nodes"] = sorted({n for n, _ in per_second})
        result["world_alive"] = world.alive()
        result["esc_alive"] = esc.poll() is None
        print(json.dumps(result), flush=True)
    finally:
        if esc is not None:
            stop_process_group(esc)
        world.close()


def _up(world):
    import rosgraph

    if not world.alive():
        raise RuntimeError("the world exited")
    try:
        return "/sim/step" in str(rosgraph.Master("/fuzz_probe").getSystemState()[2])
    except Exception:
        return False


if __name__ == "__main__":
    main()
