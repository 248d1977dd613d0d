"""One message in, one message out: the ROS wrapper shared by the real-robot translators
(KVH, DVL, M3). Each translator module gives its pure conversion function and its defaults."""

import rospy

from unexmin.topics import run_node


class TranslatorNode:
    """Subscribes ~input_topic (in_type), publishes convert(msg) on ~output_topic (out_type).

    Parameters (private): input_topic, output_topic (topic names, relative to the node's namespace),
    queue_size (integer >= 1, both sides). Bad values raise ValueError naming the parameter.
    """

    def __init__(self, name, in_type, out_type, convert, input_topic, output_topic, queue_size=100):
        self.name = name
        self.convert = convert
        self.load_params(input_topic, output_topic, queue_size)
        self.translated = 0
        self.pub = rospy.Publisher(self.output_topic, out_type, queue_size=self.queue_size)
        self.sub = rospy.Subscriber(
            self.input_topic, in_type, self.on_message, queue_size=self.queue_size, tcp_nodelay=True
        )
        rospy.loginfo("%s: %s -> %s", name, self.sub.resolved_name, self.pub.resolved_name)

    def load_params(self, input_topic, output_topic, queue_size):
        """Every parameter, checked in one place (ValueError names the parameter)."""
        self.input_topic = str(rospy.get_param("~input_topic", input_topic))
        self.output_topic = str(rospy.get_param("~output_topic", output_topic))
        self.queue_size = rospy.get_param("~queue_size", queue_size)
        if not isinstance(self.queue_size, int) or self.queue_size < 1:
            raise ValueError(f"parameter ~queue_size = {self.queue_size!r}: expected an integer >= 1")
        for name in ("input_topic", "output_topic"):
            if not getattr(self, name):
                raise ValueError(f"parameter ~{name}: expected a topic name, got ''")

    def on_message(self, msg):
        self.pub.publish(self.convert(msg))
        self.translated += 1


def run(name, *args, **kwargs):
    """main() of a translator node: init, construct, spin (a bad parameter: one fatal line, exit status 1)."""
    run_node(name, lambda: TranslatorNode(name, *args, **kwargs))
