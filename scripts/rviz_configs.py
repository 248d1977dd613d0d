#!/usr/bin/env python3
"""Write the shipped rviz configurations for one and two robots from the three-robot one.

launch/unexmin.rviz (three robots, UX_1..UX_3) is the template and the configuration for three robots;
launch/unexmin_<n>.rviz (n = 1, 2) is the same file without the displays of UX_<n+1>..UX_3 and their
entries in the Camera display's visibility list, so that rviz shows no display of a robot that does not
exist (it would be a red error row). simulation.launch opens the file that matches its `robots` argument.

    python scripts/rviz_configs.py            # rewrite launch/unexmin_1.rviz and launch/unexmin_2.rviz
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
    for path in stale:
        print(f"{path} differs from what {Path(__file__).name} writes from {TEMPLATE.name}: run it", file=sys.stderr)
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
