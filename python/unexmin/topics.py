"""Topic names and ROS plumbing shared by the nodes, the scripting API, the tools and the tests.

Importing this module needs no ROS: the helpers import rospy when they are called.
"""

import warnings

#: The real UX-1's ESC command (ux1_msgs/MotorCommand: rpm or duty cycle of M0..M7), global, as on the robot.
ESC_COMMAND_TOPIC = "/ux1/command/motors"

#: Robot name used when a node runs in the root namespace.
DEFAULT_ROBOT = "UX_1"


def sync_publisher(topic, msg_class, **kwargs):
    """A rospy publisher whose publish() writes to every subscriber's socket before it returns.

    queue_size=None: in lockstep (/sim/step) a command published before the step request is then
    on the wire first and applies from the next physics step; a node's last message (a zero wrench)
    is sent before it exits. rospy warns for queue_size=None; the choice is deliberate here.
    kwargs go to rospy.Publisher (e.g. latch=True).
    """
    import rospy

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SyntaxWarning)  # rospy's advice to set queue_size
        return rospy.Publisher(topic, msg_class, queue_size=None, **kwargs)


def robot_from_namespace():
    """Robot name from the node's namespace (/UX_2/esc_driver -> UX_2), DEFAULT_ROBOT in the root namespace."""
    import rospy

    return rospy.get_namespace().strip("/").split("/")[0] or DEFAULT_ROBOT


def robot_param(override=None):
    """The robot a node serves, without slashes: `override` if given (an in-process node), else the
    node's ~robot parameter, by default robot_from_namespace(). ValueError names the parameter when empty."""
    import rospy

    robot = str(override or rospy.get_param("~robot", robot_from_namespace())).strip("/")
    if not robot:
        raise ValueError(f"parameter ~robot: expected a robot name such as {DEFAULT_ROBOT}, got ''")
    return robot


def run_node(name, make, errors=(ValueError,)):
    """main() of a node: init `name`, construct the node with make(); one fatal line and exit status 1
    when it raises one of `errors` (a bad parameter); then spin."""
    import rospy

    rospy.init_node(name)
    try:
        make()
    except errors as e:
        rospy.logfatal(f"{name}: {e}")
        raise SystemExit(1) from None
    rospy.spin()


def thruster_publishers(ns, count):
    """Synchronous publishers of the simulated thrusters' commands, <ns>thrusters/<i>/input (std_msgs/Float64,
    thrust [N]) for i in 0..count-1."""
    from std_msgs.msg import Float64

    return [sync_publisher(f"{ns}thrusters/{i}/input", Float64) for i in range(count)]


def publish_thrusts(publishers, thrusts):
    """One thrust [N] on each publisher of thruster_publishers(), in order."""
    from std_msgs.msg import Float64

    for pub, t in zip(publishers, thrusts):
        pub.publish(Float64(float(t)))


def node_command_line(name, doc, argv=None):
    """The command line of the node nodes/<name>: `--help` prints its usage and `doc` and exits 0; ROS
    arguments (topic:=other, _param:=value, __name:=...) and anything else are left to rospy."""
    import argparse
    import sys

    parser = argparse.ArgumentParser(
        prog=f"rosrun unexmin {name}",
        usage=f"rosrun unexmin {name} [_param:=value ...] [topic:=other_topic ...]",
        description=doc,
        epilog="Parameters and topics: see the doc page named above.",
    )
    parser.parse_known_args([a for a in (sys.argv[1:] if argv is None else argv) if ":=" not in a])
