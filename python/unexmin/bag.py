"""ROS 1 bags, read and written without a ROS installation (the PyPI package rosbags).

Every tool that reads a bag goes through open_bag() or read_messages(): the mission replay, the
main job's report, the benchmarks and the tests. Message types are registered from the definitions
stored in the bag, so types of this project (ux1_msgs/MotorCommand, kvh_1775/ImuRawKvh) need no build.
Messages come back as rosbags objects: the fields of the ROS message, stamps with sec/nanosec.
"""

from contextlib import contextmanager
from pathlib import Path


class BagError(Exception):
    """A bag that cannot be read: missing, truncated, corrupt or not a bag; the message names the file."""


def stamp_to_sec(stamp):
    """Seconds [s] of a time stamp, rosbags (sec, nanosec) or rospy (secs, nsecs)."""
    if hasattr(stamp, "nanosec"):
        return stamp.sec + 1e-9 * stamp.nanosec
    return stamp.secs + 1e-9 * stamp.nsecs


@contextmanager
def open_bag(path):
    """A rosbags AnyReader on the bag at `path` (ROS 1 Noetic types plus those stored in the bag).

    Raises BagError with one line naming the file for a missing, truncated, corrupt or non-bag file,
    also for damage found while reading messages inside the `with` block.
    """
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    path = Path(path)
    if not path.is_file():
        raise BagError(f"{path}: no such bag file")
    try:
        with AnyReader([path], default_typestore=get_typestore(Stores.ROS1_NOETIC)) as reader:
            yield reader
    except BagError:
        raise
    except Exception as e:  # rosbags raises several error types (and struct/unicode errors) on damaged files
        raise BagError(
            f"{path}: cannot read the bag ({type(e).__name__}: {e}); is it truncated or corrupt? "
            "(`rosbag reindex` repairs a bag whose recording was cut off)"
        ) from None


def topic_types(path):
    """{topic: message type} of the bag, types as rosbags names them ('nav_msgs/msg/Odometry')."""
    with open_bag(path) as reader:
        return {c.topic: c.msgtype for c in reader.connections}


def read_messages(path, topics=None):
    """Every message of the bag at `path` (of `topics` only, if given) in receive-time order, as
    (topic, message type, receive time [s], message) tuples. Raises BagError (see open_bag)."""
    with open_bag(path) as reader:
        conns = [c for c in reader.connections if topics is None or c.topic in topics]
        return [
            (conn.topic, conn.msgtype, t * 1e-9, reader.deserialize(raw, conn.msgtype))
            for conn, t, raw in reader.messages(connections=conns)
        ]


class BagWriter:
    """Writes rospy messages (their ROS 1 serialisation and definition) into a new bag at `path`.

    with BagWriter(path) as bag: bag.write("/UX_1/odom", odom, t)     # t: receive time [s]
    """

    def __init__(self, path, callerid="/unexmin"):
        from rosbags.rosbag1 import Writer

        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        if self.path.exists():
            self.path.unlink()
        self.callerid = callerid
        self.writer = Writer(self.path)
        self.writer.open()
        self.conns = {}

    def write(self, topic, msg, t):
        """Append the rospy message `msg` on `topic` at receive time t [s]."""
        import io

        if topic not in self.conns:
            pkg, name = msg._type.split("/")
            self.conns[topic] = self.writer.add_connection(
                topic, f"{pkg}/msg/{name}", msgdef=msg._full_text, md5sum=msg._md5sum, callerid=self.callerid
            )
        buf = io.BytesIO()
        msg.serialize(buf)
        self.writer.write(self.conns[topic], int(round(t * 1e9)), buf.getvalue())

    def close(self):
        self.writer.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
