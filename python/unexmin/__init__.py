"""UNEXMIN UX-1 simulator: Python tools and the scripting API.

``from unexmin import Simulation`` gives the "pybind-style" API over ROS 1 (see docs/python_api.md).
Submodules that need no ROS (allocation maths, bag analysis) import without a running master.
"""

from pkgutil import extend_path

# Also the devel space's unexmin/ (the compiled _core, generated messages) when this source folder comes first on
# sys.path, as in a process spawned by multiprocessing from one where catkin's package shim put it there.
__path__ = extend_path(__path__, __name__)
__all__ = ["Simulation"]


def __getattr__(name):
    # Lazy so that ``import unexmin.<pure module>`` does not pull in rospy.
    if name == "Simulation":
        from unexmin.scripting.simulation import Simulation

        return Simulation
    raise AttributeError(name)
