"""The scripting API's way in: `Simulation` (docs/python_api.md), one front for its two back ends.

    from unexmin import Simulation
    with Simulation.launch("tank", robots=1, seed=3) as sim:                   # the ROS simulator
        ...
    with Simulation.launch("tank", robots=1, seed=3, backend="core") as sim:   # the engine in-process, no ROS
        ...

This module imports no ROS module: the back end chosen is imported when it is chosen (the ROS one,
python/unexmin/scripting/ros_backend.py, brings rospy; the core one, python/unexmin/scripting/core_backend.py,
runs on unexmin._core alone), so a script of the core back end runs where ROS is not installed.
"""

from unexmin.scripting.api import BACKENDS
from unexmin.vehicles import parse_vehicles


class Simulation:
    """A simulated world and its robots, stepped by the script.

    `Simulation(node_name="unexmin_script", timeout=30.0)` joins the running ROS simulator of ROS_MASTER_URI and
    `Simulation.launch(...)` starts a world; both give a back end's object (RosSimulation or CoreSimulation), each a
    unexmin.scripting.api.SimulationApi with the same calls, units and errors.
    """

    def __new__(cls, node_name="unexmin_script", timeout=30.0):
        """The RosSimulation client of the simulator of ROS_MASTER_URI (waits up to `timeout` s of wall time for its
        /sim services)."""
        from unexmin.scripting.ros_backend import RosSimulation

        return RosSimulation(node_name=node_name, timeout=timeout)

    @staticmethod
    def launch(
        world="tank",
        robots=1,
        seed=0,
        log_dir=None,
        timeout=60.0,
        launch_file=None,
        vehicles=None,
        backend="ros",
        **kwargs,
    ):
        """Start a world paused and connect to it; returns the back end's Simulation (a context manager).

        backend: "ros" (a headless lockstep world of the ROS simulator on a private master:
        ros_backend.RosSimulation.launch, which documents the arguments) or "core" (the engine in this process, no
        ROS: core_backend.CoreSimulation.launch; the arguments it cannot honour raise ValueError naming them).
        world: a world name (tank, mine, test_box); robots: how many of the world's robots to spawn; seed: the
        simulator's seed; log_dir: folder for the ROS world's logs; timeout [s] of wall time for the world to start;
        launch_file: a launch file of the caller's instead of the world's (ROS only); vehicles: a mixed team instead
        of `robots` UX-1s, vehicle types in order (e.g. "ux1,bluerov2_heavy,remus100" or a list; robots UX_1, ROV_1,
        AUV_1: unexmin.vehicles); kwargs: the back end's other arguments (mode, visibility, sensors, mapping,
        map_file, overrides, record, node_name; for "core" also descriptions, physics_rate, ray_caster_threads).
        ValueError for another backend, before anything starts.
        """
        if backend not in BACKENDS:
            raise ValueError(f"backend = {backend!r}: expected one of {', '.join(BACKENDS)}")
        if vehicles:
            kwargs["vehicles"] = parse_vehicles(vehicles)
        kwargs.update(log_dir=log_dir, timeout=timeout, launch_file=launch_file)
        if backend == "core":
            from unexmin.scripting.core_backend import CoreSimulation

            return CoreSimulation.launch(world, robots, seed, **kwargs)
        from unexmin.scripting.ros_backend import RosSimulation

        return RosSimulation.launch(world, robots, seed, **kwargs)
