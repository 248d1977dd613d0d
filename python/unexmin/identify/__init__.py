"""Identification of the robot's dynamics from a mission bag (docs/identification.md).

    python -m unexmin.identify BAG --out DIR [--robot UX_1] [--motors-topic ...] [--nav-topic ...]

vehicle: what the fit derives from the robot description (unexmin.description); model: the
simulator's Fossen model as an equation error, linear in the parameters, on Savitzky-Golay
derivatives of the navigation and the commands integrated at the physics rate; fit:
scipy.optimize.least_squares, 1-sigma from the Jacobian, flat directions fixed at the description's
value and reported; report: identified.yaml, the overrides xacro, report.md with plots (cli).
Importing this package needs neither ROS nor rosbags.
"""

from unexmin.identify.cli import identify_bag, main, overrides_xacro, summary

__all__ = ["identify_bag", "main", "overrides_xacro", "summary"]
