"""The scripting API (docs/python_api.md): simulation.py (Simulation, the way in; no ROS import), api.py (the calls
both back ends implement), ros_backend.py (RosSimulation, RosRobot over the ROS simulator) with streams.py (sensor
streams), launcher.py (the launched world, ports, process groups) and rospy_node.py (this process's ROS node), and
core_backend.py (CoreSimulation, CoreRobot over unexmin.core). `from unexmin import Simulation` is the way in."""
