"""Keep every message of a set of topics in memory, and wait on them: for scripts and tests that
step the simulator and then read what its sensors published during the step."""

import threading

import rospy


class TopicRecorder:
    """Subscribes `ns + topic` for each (topic, message class) of `topics`, with deep queues (a
    /sim/step burst can be thousands of messages), and keeps them all until clear()."""

    def __init__(self, ns, topics, queue_size=10000):
        self.ns = ns
        self.lock = threading.Condition()
        self.msgs = {t: [] for t in topics}
        self.subs = [rospy.Subscriber(ns + t, c, self._on, t, queue_size=queue_size, tcp_nodelay=True)
                     for t, c in topics.items()]

    def _on(self, msg, topic):
        with self.lock:
            self.msgs[topic].append(msg)
            self.lock.notify_all()

    def connected(self):
        """True when every subscription has a publisher connected."""
        return all(s.get_num_connections() > 0 for s in self.subs)

    def clear(self):
        with self.lock:
            for v in self.msgs.values():
                v.clear()

    def _wait(self, topic, ready, timeout, what):
        with self.lock:
            if not self.lock.wait_for(ready, timeout):
                raise AssertionError(f"{self.ns}{topic}: {what} within {timeout} s "
                                     f"({len(self.msgs[topic])} received)")
            return list(self.msgs[topic])

    def wait_until(self, topic, stamp, timeout=30.0):
        """Every message of `topic` once one stamped >= stamp [s] has arrived."""
        def ready():
            m = self.msgs[topic]
            return bool(m) and m[-1].header.stamp.to_sec() >= stamp - 1e-9
        return self._wait(topic, ready, timeout, f"no message stamped {stamp} s")

    def wait_count(self, topic, n, timeout=30.0):
        """Every message of `topic` once there are at least n."""
        return self._wait(topic, lambda: len(self.msgs[topic]) >= n, timeout, f"fewer than {n} messages")
