"""What the missions share: the command line, waiting for a rosbag recorder, the summary file."""

import argparse
import json
import os
import time

from unexmin.scripting.launcher import wait_for


def recorder_connected(master, publishers, topics):
    """True once the publishing nodes have a live connection to a rosbag recorder on every topic of `topics`
    (a publisher drops messages for subscribers that are registered but not yet connected)."""
    from xmlrpc.client import ServerProxy

    connected = set()
    for node in publishers:
        bus = ServerProxy(master.lookupNode(node)).getBusInfo(master.caller_id)[2]
        connected |= {c[4] for c in bus if c[1].startswith("/record") and c[2] == "o" and c[5]}
    return all(t in connected for t in topics)


def wait_until_written(path, timeout=30.0, quiet=0.5):
    """Wait until the recorder's file has stopped growing for `quiet` s (it has written what it got)."""
    last = (-1, time.monotonic())

    def settled():
        nonlocal last
        size = os.path.getsize(path) if os.path.exists(path) else -1
        now = time.monotonic()
        if size != last[0]:
            last = (size, now)
        return size > 0 and now - last[1] >= quiet

    wait_for(settled, timeout, f"{path} to be written", poll=0.1)


def write_summary(out, summary):
    """`summary` as out/summary.json (every mission's machine-readable result); returns it."""
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
    return summary


def mission_parser(prog, description):
    """The command line every mission shares: --out (the output folder) and --seed."""
    parser = argparse.ArgumentParser(prog=prog, description=description)
    parser.add_argument("--out", default="mission_output", help="output folder (created)")
    parser.add_argument("--seed", type=int, default=0, help="seed of every random generator")
    return parser
