"""Driving the robots: allocation.py (body wrench -> thruster forces, no ROS) and allocator_node.py (its
node), esc.py (ESC tables, no ROS) and esc_driver_node.py (the simulated ESC driver), operator_commands.py
(operator intents -> commands) used by teleop.py (keyboard) and joystick.py (gamepad)."""
