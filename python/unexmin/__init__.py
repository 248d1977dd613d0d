"""UNEXMIN UX-1 simulator: Python tools and the scripting API.

``from unexmin import Simulation`` gives the "pybind-style" API over the ROS 1 simulator or the engine in-process
(see docs/python_api.md); it imports no ROS module until the ROS back end is chosen. Submodules that need no ROS
(unexmin.core, unexmin.gym, allocation maths, bag analysis) import where ROS is not installed.
"""

from pkgutil import extend_path

# Also the devel space's unexmin/ (the compiled _core, generated messages) when this source folder comes first on
# sys.path, as in a process spawned by multiprocessing from one where catkin's package shim put it there.
__path__ = extend_path(__path__, __name__)
__all__ = ["Simulation"]


def __getattr__(name):
    # Lazy so that ``import unexmin.<module>`` does not load the scripting API it does not use.
    if name == "Simulation":
        from unexmin.scripting.simulation import Simulation

        return Simulation
    raise AttributeError(name)
