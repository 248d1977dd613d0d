"""The simulator's topics as a script sees them: the newest message of each, and whole series.

The simulator builds a sensor message only for a topic that has a subscriber, and in lockstep it
publishes everything a /sim/step produces while it steps, before it answers. So a script that wants
"the IMU at sim.time" after a step must have subscribed *before* the step, and must wait after the
answer until the step's messages, still in flight over TCP, have arrived.

StreamSet does both. It subscribes topics up front (the Simulation subscribes every topic the
simulator publishes under /<robot>/ when a robot handle is made), keeps the newest message of each
and feeds collectors. After every step, sync() waits until every message the simulator has queued
for this node on those topics has been received: the simulator's ROS node reports, per connection,
how many messages it has queued (XML-RPC getBusStats), and this
process counts what its callbacks have received on the same connection. No rates, no sleeps: the
wait ends when the two counts agree, or fails with TimeoutError naming the topics still short.

roscpp counts a message when its network thread moves it from the publisher's queue to the
connections' outgoing queues, which can lag the publish() call (and so the step's answer) by
hundreds of messages. Before reading the counters, sync() therefore asks the simulator twice for a
step of 0 steps, each time on a new connection (`flush`; such a step changes nothing and publishes
only a /clock message). That thread moves every queued message at the start of each of its rounds,
and accepts a new connection in a round of its own: the second connection is accepted in a round
that began after the step's last message was published, so once its answer is back the counters
include every message of the step. (A persistent connection would not do: roscpp may read the next
request on it from the thread that wrote the previous answer.)

Subscriptions are made with unbounded receive queues (queue_size=None) and tcp_nodelay, so rospy
drops nothing; the simulator's outgoing queues hold 20 s of sim time per topic (see
Simulation.step, which steps in shorter bursts while streams are subscribed).
Topics of other nodes (translators, the allocator) are not synchronised with the steps: their
newest message and collectors are filled as they arrive, and latest() waits for them.
"""

import threading
import time
import xmlrpc.client

import rospy


def header_stamp(msg):
    """Header stamp [s] of a message, None for a message without header (std_msgs/Float64)."""
    header = getattr(msg, "header", None)
    return None if header is None else header.stamp.to_sec()


class Collector:
    """Every message of one topic from its creation until stop(), in order of arrival.

        c = ux.collect("imu")        # start: collects from now on
        sim.run_for(2.0)             # step (any number of step calls)
        msgs = c.messages            # every message of those steps; c.stop() when done

    For a topic of the simulator, c.messages is complete after each step call returns (nothing lost,
    nothing in flight). For other nodes' topics, wait_count() / wait_until() wait for what is due.
    Also a context manager: `with ux.collect("imu") as c: sim.run_for(2.0)` stops it at the end.
    """

    def __init__(self, stream_set, stream):
        self._set, self._stream = stream_set, stream
        self._msgs = []
        self.topic = stream.topic
        self.active = True

    def _add(self, msg):  # called with the stream set's lock held
        self._msgs.append(msg)

    @property
    def messages(self):
        """The messages collected so far (a copy of the list), oldest first."""
        with self._set.cond:
            return list(self._msgs)

    def stamps(self):
        """Header stamps [s] of the messages collected so far (None for messages without header)."""
        return [header_stamp(m) for m in self.messages]

    def __len__(self):
        with self._set.cond:
            return len(self._msgs)

    def clear(self):
        """Forget the messages collected so far; keep collecting."""
        with self._set.cond:
            self._msgs.clear()

    def stop(self):
        """Stop collecting (the messages stay readable)."""
        with self._set.cond:
            if self in self._stream.collectors:
                self._stream.collectors.remove(self)
        self.active = False

    def wait_count(self, n, timeout=30.0):
        """Every message collected, once there are at least n; TimeoutError after `timeout` s of wall time."""
        return self._wait(lambda: len(self._msgs) >= n, timeout, f"{n} messages")

    def wait_until(self, stamp, timeout=30.0):
        """Every message collected, once one stamped >= stamp [s] has arrived (for other nodes' topics,
        whose messages are not synchronised with the steps); TimeoutError after `timeout` s."""

        def ready():
            s = header_stamp(self._msgs[-1]) if self._msgs else None
            return s is not None and s >= stamp - 1e-9

        return self._wait(ready, timeout, f"a message stamped {stamp} s")

    def _wait(self, ready, timeout, what):
        with self._set.cond:
            if not self._set.cond.wait_for(ready, timeout):
                raise TimeoutError(
                    f"{self.topic}: no {what} within {timeout} s of wall time "
                    f"({len(self._msgs)} messages collected)"
                )
            return list(self._msgs)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()
        return False


class Stream:
    """One subscribed topic: its newest message, its collectors and, for a topic the simulator
    publishes (`synced`), how many messages have arrived from the simulator."""

    def __init__(self, topic, msg_class, synced):
        self.topic, self.msg_class, self.synced = topic, msg_class, synced
        self.latest = None  # newest message received
        self.received = 0  # messages received from the simulator's node
        self.offset = 0  # messages the simulator sent before this stream counted (see StreamSet)
        self.collectors = []
        self.sub = None
        self.preexisting = False  # another subscriber of this process had the topic's connection first
        self.fresh = True  # subscribed after the last step call (so it holds nothing of it)


class StreamSet:
    """The subscriptions of one Simulation (every robot's), and the barrier that ends a step.

    master: rosgraph.Master of the simulator's ROS master; sim_node: the simulator's node name
    (the node that offers /sim/step); timeout: default wait [s] of wall time.
    """

    def __init__(self, master, sim_node, timeout=30.0):
        from unexmin.srv import Step

        self.master, self.sim_node, self.timeout = master, sim_node, timeout
        self._step0 = rospy.ServiceProxy("/sim/step", Step)  # not persistent: see the module's docstring
        self.me = rospy.get_name()
        self.cond = threading.Condition()
        self.streams = {}  # topic -> Stream
        self._links = {}  # the simulator's connection id -> topic, for connections to this node
        self._other_links = set()  # the simulator's connection ids to other nodes
        self._proxy = xmlrpc.client.ServerProxy(master.lookupNode(sim_node))

    # -- graph --------------------------------------------------------------------------------
    def published(self, prefix=""):
        """{topic: (type name, [publisher nodes])} of the topics published under `prefix` now."""
        types = dict(self.master.getTopicTypes())
        pubs = dict(self.master.getSystemState()[0])
        return {t: (types.get(t, ""), nodes) for t, nodes in pubs.items() if t.startswith(prefix)}

    def simulator_topics(self, prefix):
        """{topic: type name} of the topics under `prefix` that the simulator publishes."""
        return {t: ty for t, (ty, nodes) in self.published(prefix).items() if self.sim_node in nodes}

    # -- subscriptions ---------------------------------------------------------------------------
    def subscribe(self, topics, synced, wait=True, timeout=None):
        """Subscribe each of `topics` ({topic: message class}) not subscribed yet; returns the streams.
        synced: the simulator publishes them (they take part in sync()). wait: until each new
        subscription is connected to a publisher (always for synced topics)."""
        new = []
        for topic, msg_class in topics.items():
            if topic in self.streams:
                continue
            stream = Stream(topic, msg_class, synced)
            sub = rospy.Subscriber(topic, msg_class, self._on_message, stream, queue_size=None, tcp_nodelay=True)
            # rospy shares one connection per topic within a process: if another subscriber of this
            # process had it first, the simulator has counted messages this stream never saw.
            stream.preexisting = bool(sub.impl.connections)
            stream.sub = sub
            with self.cond:
                self.streams[topic] = stream
            new.append(stream)
        if new and (synced or wait):
            from unexmin.scripting.launcher import wait_for

            timeout = self.timeout if timeout is None else timeout
            who = "the simulator" if synced else "a publisher"
            wait_for(
                lambda: all(s.sub.get_num_connections() > 0 for s in new),
                timeout,
                f"{who} to connect to {len(new)} topic(s): {', '.join(s.topic for s in new)}",
            )
        if new and synced:
            sent = self._sent()
            with self.cond:
                for s in new:
                    if s.preexisting:
                        s.offset = sent.get(s.topic, 0) - s.received
        return [self.streams[t] for t in topics]

    def _on_message(self, msg, stream):
        with self.cond:
            if stream.synced and msg._connection_header.get("callerid") == self.sim_node:
                stream.received += 1
            stream.latest = msg
            for c in stream.collectors:
                c._add(msg)
            self.cond.notify_all()

    def collector(self, stream):
        """A new Collector on `stream`, collecting from now on."""
        c = Collector(self, stream)
        with self.cond:
            stream.collectors.append(c)
        return c

    def newest(self, stream):
        with self.cond:
            return stream.latest

    def wait_newest(self, stream, ready, timeout):
        """Wait until ready(stream.latest) (wall-clock timeout [s]); returns the message or None."""
        with self.cond:
            if self.cond.wait_for(lambda: stream.latest is not None and ready(stream.latest), timeout):
                return stream.latest
            return None

    def forget_newest(self):
        """Forget every topic's newest message (after a reset, they belong to the old run)."""
        with self.cond:
            for s in self.streams.values():
                s.latest = None

    def close(self):
        """Unregister every subscription and stop every collector."""
        with self.cond:
            streams = list(self.streams.values())
            self.streams.clear()
        for s in streams:
            for c in list(s.collectors):
                c.stop()
            s.sub.unregister()

    # -- the barrier --------------------------------------------------------------------------------
    def _sent(self):
        """{topic: messages the simulator's node has queued for this node}, from its bus statistics."""
        stats = self._proxy.getBusStats(self.me)
        # roscpp answers [publish stats, subscribe stats] without rospy's [code, status, value] wrapper
        pub_stats = stats[2][0] if isinstance(stats[0], int) else stats[0]
        conns = [(topic, c[0], c[3]) for topic, links in pub_stats for c in links]
        if any(cid not in self._links and cid not in self._other_links for _, cid, _ in conns):
            info = self._proxy.getBusInfo(self.me)[2]  # [id, destination, direction, transport, topic, ...]
            self._links = {c[0]: c[4] for c in info if c[2] == "o" and c[1] == self.me}
            self._other_links = {c[0] for c in info} - set(self._links)
        sent = {}
        for topic, cid, count in conns:
            if cid in self._links:
                sent[topic] = sent.get(topic, 0) + count
        return sent

    def _flush(self):
        """Two round trips to the simulator's node: see the module's docstring."""
        for _ in range(2):
            self._step0(duration=0.0, steps=0, client="", commands=0, hold=False)

    def sync(self, timeout=None):
        """Wait until every message the simulator has published for this node on a subscribed topic
        has been received (call it after a step, reset or pause returns). TimeoutError after `timeout`
        s of wall time names the topics still short and by how many messages."""
        with self.cond:
            synced = [s for s in self.streams.values() if s.synced]
        if not synced:
            return
        timeout = self.timeout if timeout is None else timeout
        self._flush()
        sent = self._sent()

        def short():
            return [
                (s, sent.get(s.topic, 0) - s.offset - s.received)
                for s in synced
                if s.received < sent.get(s.topic, 0) - s.offset
            ]

        t0 = time.monotonic()
        with self.cond:
            if self.cond.wait_for(lambda: not short(), timeout):
                return
            missing = short()
        detail = ", ".join(f"{s.topic} ({n} of {sent.get(s.topic, 0) - s.offset})" for s, n in missing[:5])
        raise TimeoutError(
            f"after {time.monotonic() - t0:.0f} s of wall time, messages the simulator sent are "
            f"still missing: {detail} (lost to a queue too short: the simulator's outgoing queue of the "
            "topic, or a subscriber of this process with a finite queue_size on it)"
        )
