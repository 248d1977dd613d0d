"""The mine mission's plan (no ROS): the survey of unexmin.missions.survey for the world's mine (its layout from
the mine generator's report beside the world's collision mesh), at the run's visibility, from the first spawn."""

import os
from dataclasses import dataclass

from unexmin.missions.survey import Reference, SurveyOptions, mine_layout, options_for, plan


@dataclass
class MinePlan:
    """What the mission flies and under which conditions."""

    world_file: str  # absolute path of the world file
    visibility: str | None  # the visibility asked for (None: the world file's)
    level: str  # the visibility the plan is made for (the one asked for, else the world file's)
    options: SurveyOptions  # the survey's stand-offs and speeds at that visibility
    reference: Reference  # the reference path against progress [s]
    time_limit: float  # [s, sim] the flight stops here if the plan is not done


def make_plan(world_file=None, gallery=40.0, visibility=None, time_limit=None):
    """The plan for world_file (default: the shipped mine), flying `gallery` m along the first level's gallery;
    time_limit [s, sim] defaults to the plan's duration and half again, plus 60 s, for the robot to catch up."""
    from unexmin.worlds.files import world_path
    from unexmin.worlds.schema import read_world

    world_file = os.path.abspath(world_file) if world_file else world_path("mine")
    layout, preset = mine_layout(world_file)
    spawn = layout.spawns[0]
    level = visibility or (read_world(world_file).get("visibility") or {}).get("level", "none")
    options = options_for(level, sum(amplitude for _, amplitude in preset.octaves), gallery)
    reference = Reference(*plan(layout, preset, (spawn[0], spawn[1], spawn[2], 0.0), options))
    if time_limit is None:
        time_limit = 1.5 * reference.duration + 60.0
    return MinePlan(world_file, visibility, level, options, reference, time_limit)
