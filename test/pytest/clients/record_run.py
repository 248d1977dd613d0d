#!/usr/bin/env python3
"""Client process of test_recording.py (one rospy node per process, one master per world).

Launches the tank world (lockstep, paused) with the launch arguments given after `--`, optionally starts a
stock `rosbag record` of TOPICS, steps SECONDS of sim time (+1 s so that every recorded topic has a
message after SECONDS), stops the simulator's recorder through /sim/record, stops rosbag record with SIGINT
and the world, and prints one JSON line: {"wall": stepping wall time [s], "sim": sim time reached [s]}.

usage: record_run.py <log dir> <seconds> <commands> [--world tank|mine] [--rosbag <bag> <topic>...] -- <launch args>
"""

import json
import subprocess
import sys
import time


def main():
    argv = sys.argv[1:]
    sep = argv.index("--")
    own, launch_args = argv[:sep], argv[sep + 1 :]
    log_dir, seconds, commands = own[0], float(own[1]), int(own[2])
    rosbag_bag, rosbag_topics, world_name = None, [], "tank"
    rest = own[3:]
    if rest[:1] == ["--world"]:
        world_name, rest = rest[1], rest[2:]
    if rest[:1] == ["--rosbag"]:
        rosbag_bag, rosbag_topics = rest[1], rest[2:]

    import rosgraph
    import rospy

    from unexmin.scripting.launcher import WorldProcess, stop_process_group, wait_for
    from unexmin.scripting.ros_backend import RosSimulation
    from unexmin.srv import Record

    world = WorldProcess(world=world_name, paused=True, log_dir=log_dir, extra_args=launch_args)
    recorder = None
    try:
        sim = RosSimulation(world=world, timeout=60.0)
        if rosbag_bag:
            recorder = subprocess.Popen(
                ["rosbag", "record", "--lz4", "-O", rosbag_bag, *rosbag_topics],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
            master = rosgraph.Master("/record_run")

            def subscribed():
                _, subs, _ = master.getSystemState()
                by_topic = {t: nodes for t, nodes in subs}
                return all(any(n.startswith("/record") for n in by_topic.get(t, ())) for t in rosbag_topics)

            wait_for(subscribed, 30.0, "rosbag record to subscribe every topic")
            # Registered is not connected: messages published before the TCP connection exists are not
            # queued for it. Wait until the simulator lists an outgoing connection to rosbag on each topic.
            import xmlrpc.client

            simulator = xmlrpc.client.ServerProxy(master.lookupNode("/simulator"))

            def connected():
                _, _, bus = simulator.getBusInfo("/record_run")
                out = {c[4] for c in bus if c[2] == "o" and c[1].startswith("/record") and c[5]}
                return out >= set(rosbag_topics)

            wait_for(connected, 30.0, "the simulator to connect to rosbag record on every topic")
        ux = sim.robot("UX_1")
        t0 = time.monotonic()
        # `commands` thruster commands, each applied before a step of 20 ms (recorded on thrusters/<i>/input).
        # A /sim/step call publishes odom and thrusts once more at its end unless they are due then
        # (docs/simulator_node.md): 20 ms is a whole number of their 50 Hz periods, so they are due.
        steps_left = round(seconds * sim.physics_rate)
        chunk = round(0.02 * sim.physics_rate)
        for k in range(commands):
            ux.thrusts([0.5 * (k % 3)] * 8)
            sim.step(chunk)
            steps_left -= chunk
        sim.step(steps_left)
        wall = time.monotonic() - t0
        sim.run_for(1.0)
        stop = rospy.ServiceProxy("/sim/record", Record)(path="")
        if not stop.ok:
            raise RuntimeError(stop.message)
        print(json.dumps({"wall": wall, "sim": sim.time, "record": stop.message}), flush=True)
    finally:
        if recorder is not None:
            stop_process_group(recorder, 30.0)
        world.close()


if __name__ == "__main__":
    main()
