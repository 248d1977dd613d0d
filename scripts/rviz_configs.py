#!/usr/bin/env python3
"""Write the shipped rviz configurations for one and two robots, and for a mixed team, from the three-robot one.

launch/unexmin.rviz (three robots, UX_1..UX_3) is the template and the configuration for three robots;
launch/unexmin_<n>.rviz (n = 1, 2) is the same file without the displays of UX_<n+1>..UX_3 and their
entries in the Camera display's visibility list, so that rviz shows no display of a robot that does not
exist (it would be a red error row). simulation.launch opens the file that matches its `robots` argument.
launch/unexmin_team.rviz (simulation.launch with `vehicles:=`) is the one-robot file with the BlueROV2 Heavy's (ROV_1)
and the REMUS 100's (AUV_1) models, odometry and sonar images (the imaging sonar's fan, the side-scan's waterfall).

    python scripts/rviz_configs.py            # rewrite launch/unexmin_1.rviz, unexmin_2.rviz, unexmin_team.rviz
    python scripts/rviz_configs.py --check    # exit 1 if a shipped file differs from what it would write

Edit launch/unexmin.rviz (by hand or by saving from rviz with three robots), then run this script.
"""

import argparse
import re
import sys
from pathlib import Path

LAUNCH = Path(__file__).resolve().parents[1] / "launch"
TEMPLATE = LAUNCH / "unexmin.rviz"
ROBOTS = 3  # the robots the template names: UX_1..UX_3
ROBOT_NAME = re.compile(r"^UX_(\d+)\b")


def indent_of(line):
    return len(line) - len(line.lstrip(" "))


def blocks(lines, start, indent):
    """Split lines[start:] into the blocks of one YAML list or mapping at `indent`: each block is (first, end),
    a line at `indent` and the deeper lines after it; stops at the first line less indented than `indent`."""
    out, i = [], start
    while i < len(lines) and (not lines[i].strip() or indent_of(lines[i]) >= indent):
        j = i + 1
        while j < len(lines) and (not lines[j].strip() or indent_of(lines[j]) > indent):
            j += 1
        out.append((i, j))
        i = j
    return out


def display_name(lines, first, end, indent):
    """The `Name:` of the display item lines[first:end] whose keys stand at `indent`."""
    for line in lines[first:end]:
        if indent_of(line) == indent and line.strip().startswith("Name: "):
            return line.strip()[len("Name: ") :]
    return ""


def robot_index(name):
    m = ROBOT_NAME.match(name)
    return int(m.group(1)) if m else 0


def config_for(text, robots):
    """The template's text without the displays (and visibility entries) of robots after UX_<robots>."""
    if not 1 <= robots <= ROBOTS:
        raise ValueError(f"robots = {robots}: expected 1 to {ROBOTS}")
    lines = text.splitlines(keepends=True)
    drop = []
    for i, line in enumerate(lines):
        stripped = line.strip()
        if stripped == "Displays:" and i + 1 < len(lines) and lines[i + 1].lstrip().startswith("- "):
            item_indent = indent_of(lines[i + 1])
            for first, end in blocks(lines, i + 1, item_indent):
                if robot_index(display_name(lines, first, end, item_indent + 2)) > robots:
                    drop.append((first, end))
        elif stripped == "Visibility:":
            for first, end in blocks(lines, i + 1, indent_of(line) + 2):
                if robot_index(lines[first].strip()) > robots:
                    drop.append((first, end))
    dropped = set()
    for first, end in drop:
        dropped.update(range(first, end))
    return "".join(line for k, line in enumerate(lines) if k not in dropped)


#: The mixed team of launch/unexmin_team.rviz (simulation.launch with vehicles:=): each other vehicle's model and
#: odometry as the UX_1's, and its sonar image.
TEAM = {"ROV_1": "/ROV_1/imaging_sonar/fan", "AUV_1": "/AUV_1/side_scan/waterfall"}
TEAM_PATH = LAUNCH / "unexmin_team.rviz"
IMAGE_DISPLAY = """    - Class: rviz/Image
      Enabled: true
      Image Topic: {topic}
      Max Value: 1
      Median window: 5
      Min Value: 0
      Name: {robot} {sonar}
      Normalize Range: false
      Queue Size: 2
      Transport Hint: raw
      Unreliable: false
      Value: true
"""


def team_config(text):
    """The one-robot configuration (of the template's text) with, before UX_1's sensors, each TEAM vehicle's model
    and odometry (copies of UX_1's displays) and its sonar image."""
    lines = config_for(text, 1).splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if line.strip() == "Displays:") + 1
    indent = indent_of(lines[start])
    items = {display_name(lines, f, e, indent + 2): (f, e) for f, e in blocks(lines, start, indent)}
    added = []
    for robot, topic in TEAM.items():
        for name in ("UX_1 model", "UX_1 odom"):
            first, end = items[name]
            added += [line.replace("UX_1", robot) for line in lines[first:end]]
        sonar = topic.split("/")[2].replace("_", " ")
        added.append(IMAGE_DISPLAY.format(topic=topic, robot=robot, sonar=sonar))
    at = items["UX_1 sensors"][0]
    return "".join(lines[:at] + added + lines[at:])


def path_for(robots):
    return TEMPLATE if robots == ROBOTS else LAUNCH / f"unexmin_{robots}.rviz"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="only compare; exit 1 if a shipped file differs")
    args = parser.parse_args(argv)
    text = TEMPLATE.read_text()
    stale = []
    for robots in range(1, ROBOTS):
        path, wanted = path_for(robots), config_for(text, robots)
        if args.check:
            if not path.exists() or path.read_text() != wanted:
                stale.append(path)
        else:
            path.write_text(wanted)
            print(f"wrote {path}")
    wanted = team_config(text)
    if not args.check:
        TEAM_PATH.write_text(wanted)
        print(f"wrote {TEAM_PATH}")
    elif not TEAM_PATH.exists() or TEAM_PATH.read_text() != wanted:
        stale.append(TEAM_PATH)
    for path in stale:
        print(f"{path} differs from what {Path(__file__).name} writes from {TEMPLATE.name}: run it", file=sys.stderr)
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
