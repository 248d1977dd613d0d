"""The robot description (urdf/*.urdf.xacro), read once: expand the xacro file, parse the URDF into one typed
record. Pure Python, no ROS.

    from unexmin import description
    robot = description.load(description.ROBOT_FILE, "UX_1")        # or description.parse(urdf_text, source)
    robot.hydro.mass, robot.thrusters[0].axis, robot.sensors[0].position, robot.link_pose("UX_1/dvl_link")

The record (unexmin.description.records) is field for field the simulator's (cpp/unexmin/sim/robot_description.h)
and the parse follows the simulator's rules (test/pytest/test_description_twin.py holds the two together on every
shipped vehicle and on malformed descriptions). Every failure is a DescriptionError naming the file, the element and
what was expected.
"""

from unexmin.description.errors import DescriptionError
from unexmin.description.parse import load, parse
from unexmin.description.records import (
    Fin,
    Hydrodynamics,
    Joint,
    Magnetics,
    Pendulum,
    RobotDescription,
    Sensor,
    Thruster,
    Vbs,
)
from unexmin.description.xacro import ROBOT_FILE, expand, xacro_executable

__all__ = [
    "ROBOT_FILE",
    "DescriptionError",
    "Fin",
    "Hydrodynamics",
    "Joint",
    "Magnetics",
    "Pendulum",
    "RobotDescription",
    "Sensor",
    "Thruster",
    "Vbs",
    "expand",
    "load",
    "parse",
    "xacro_executable",
]
