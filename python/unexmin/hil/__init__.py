"""Hardware in the loop across machines (docs/real_robot.md): the simulator on one host, the robot's software on
another, joined by ROS over a network link.

| module | what |
| --- | --- |
| `clock_sync` | the clock offset between two hosts from a four-timestamp (NTP-style) exchange over UDP; no ROS |
| `robot_standin` | a stand-in for the robot's software: ESC commands and navigation on its own wall clock |
| `probe` | records the robot's commands and the simulator's thrust as they arrive; latency and watchdog figures |
| `rig` | two hosts on one machine (network namespaces) for the test and the bench; needs root |
| `listen` | the tools' own nodes listen on ROS_IP only: they start themselves again with the bind shim preloaded |
| `check` | `python -m unexmin.hil.check`: a one-line diagnosis of the link to the robot |
"""
