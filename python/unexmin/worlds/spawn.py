"""A shipped world with one robot spawned at another attitude and/or with another description, as a
temporary world file and launch file for Simulation.launch(launch_file=...).

Used by the replay (--overrides: the identified robot starts at the bag's first roll and pitch, as
the real one did) and by worlds/tools/make_sample_bag.py (the perturbed robot starts at rest).
"""

from pathlib import Path

import yaml

from unexmin.worlds.files import PACKAGE_DIR as REPO
from unexmin.worlds.files import link_meshes
from unexmin.worlds.schema import read_world


def world_launch_file(
    tmp, world="tank", robot="UX_1", roll_pitch=None, overrides=None, description=None, robots=1, seed=0, spawn_xyz=None
):
    """Write `<tmp>/<world>_spawn.world` and `.launch`; returns the launch file's path.

    world: a shipped world (worlds/<world>.world); roll_pitch: (roll, pitch) [rad] of `robot`'s spawn
    attitude (its yaw and position are the world's; spawn_xyz [m] replaces its position); overrides: xacro
    overrides file of that robot (UX_k_overrides:=); description: a whole robot file to use instead (with its own
    overrides).
    The world starts paused in lockstep with `robots` robots and `seed`.
    """
    source = REPO / "worlds" / f"{world}.world"
    if not source.is_file():
        raise FileNotFoundError(f"world {world!r}: no {source}")
    data = read_world(source)
    link_meshes(data.get("meshes") or [], str(source.parent), str(tmp))
    entry = next((r for r in data["robots"] if r["name"] == robot), None)
    if entry is None:
        raise ValueError(f"world {world!r} has no robot {robot!r}")
    if spawn_xyz is not None:
        entry["xyz"] = [float(v) for v in spawn_xyz]
    if roll_pitch is not None:
        entry["rpy"] = [float(roll_pitch[0]), float(roll_pitch[1]), entry["rpy"][2]]
    world_file = Path(tmp) / f"{world}_spawn.world"
    world_file.write_text(
        f"# generated from worlds/{world}.world (unexmin.worlds.spawn)\n"
        + yaml.safe_dump(data, default_flow_style=None, sort_keys=False)
    )
    read_world(world_file)  # what the simulator will read follows the schema
    override_arg = f'\n    <arg name="{robot}_overrides" value="{Path(overrides).resolve()}"/>' if overrides else ""
    description_param = (
        f"\n  <!-- replaces the description set by robot.launch (the later definition wins) -->"
        f'\n  <param name="/{robot}/robot_description" command="xacro \'{description}\' name:={robot}"/>'
        if description
        else ""
    )
    launch_file = Path(tmp) / f"{world}_spawn.launch"
    launch_file.write_text(f"""<launch>
  <include file="$(find unexmin)/launch/simulation.launch">
    <arg name="world" value="{world_file}"/>
    <arg name="robots" value="{robots}"/>
    <arg name="realtime" value="false"/>
    <arg name="paused" value="true"/>
    <arg name="seed" value="{seed}"/>{override_arg}
  </include>{description_param}
</launch>
""")
    return launch_file
