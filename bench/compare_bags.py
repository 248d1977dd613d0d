#!/usr/bin/env python3
"""Compare two ROS 1 bags message for message: per topic, the message type, the count, and each message's bag time
and serialized bytes in order. For checking that a change leaves the simulator's output identical (record both with
`python bench/soak.py --robots 3 --sim-seconds 10 --keep-bag --out DIR`, once per build).

    python bench/compare_bags.py A.bag B.bag        # exit 0 when identical, 1 with the first differences listed
"""

import argparse
import hashlib
import sys
from collections import defaultdict
from pathlib import Path


def digest(path):
    """{topic: (msgtype, count, sha256 over (bag time, serialized bytes) in order)} of one bag."""
    from rosbags.rosbag1 import Reader

    hashes, counts, types = defaultdict(hashlib.sha256), defaultdict(int), {}
    with Reader(path) as reader:
        for conn, stamp, raw in reader.messages():
            types[conn.topic] = conn.msgtype
            counts[conn.topic] += 1
            h = hashes[conn.topic]
            h.update(stamp.to_bytes(8, "little"))
            h.update(len(raw).to_bytes(8, "little"))
            h.update(raw)
    return {t: (types[t], counts[t], hashes[t].hexdigest()) for t in types}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a", type=Path)
    ap.add_argument("b", type=Path)
    args = ap.parse_args(argv)
    a, b = digest(args.a), digest(args.b)
    differences = [f"only in {args.a}: {t}" for t in sorted(a.keys() - b.keys())]
    differences += [f"only in {args.b}: {t}" for t in sorted(b.keys() - a.keys())]
    for topic in sorted(a.keys() & b.keys()):
        (ta, na, ha), (tb, nb, hb) = a[topic], b[topic]
        if (ta, na, ha) != (tb, nb, hb):
            differences.append(f"{topic}: {ta} x {na} vs {tb} x {nb}" + (", contents differ" if na == nb else ""))
    total = sum(n for _, n, _ in a.values())
    if differences:
        print(f"{len(differences)} topic(s) differ:\n" + "\n".join(differences[:40]))
        return 1
    print(f"identical: {len(a)} topics, {total} messages (bag times and serialized bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
