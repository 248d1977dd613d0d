"""The scripting API (docs/python_api.md): simulation.py (Simulation, Robot), streams.py (sensor streams),
launcher.py (the launched world, ports, process groups), rospy_node.py (this process's ROS node).
`from unexmin import Simulation` is the way in."""
