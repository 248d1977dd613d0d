"""rviz configurations for any set of robots, written from the three-UX-1 template launch/unexmin.rviz (pure text, no
ROS). scripts/rviz_configs.py writes the shipped files with it; nodes/team_rviz writes the one of a running team.

- config_for(text, robots): the template without the displays (and Camera visibility entries) of UX_<robots+1>..UX_3.
- team_config(text, names): the displays of the robots `names` (UX_k, ROV_k, AUV_k, in any number): each UX-1 of the
  template keeps its displays; every other robot gets a copy of UX_1's model and odometry displays, and the ROV its
  imaging sonar's fan image and point cloud, the AUV its side-scan waterfall.
"""

import re

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


def keep_robots(text, keep):
    """The template's text without the displays (and visibility entries) of the UX_k with k not in `keep`."""
    lines = text.splitlines(keepends=True)
    drop = []
    for i, line in enumerate(lines):
        stripped = line.strip()
        if stripped == "Displays:" and i + 1 < len(lines) and lines[i + 1].lstrip().startswith("- "):
            item_indent = indent_of(lines[i + 1])
            for first, end in blocks(lines, i + 1, item_indent):
                k = robot_index(display_name(lines, first, end, item_indent + 2))
                if k and k not in keep:
                    drop.append((first, end))
        elif stripped == "Visibility:":
            for first, end in blocks(lines, i + 1, indent_of(line) + 2):
                k = robot_index(lines[first].strip())
                if k and k not in keep:
                    drop.append((first, end))
    dropped = set()
    for first, end in drop:
        dropped.update(range(first, end))
    return "".join(line for k, line in enumerate(lines) if k not in dropped)


def config_for(text, robots):
    """The template's text without the displays (and visibility entries) of robots after UX_<robots>."""
    if not 1 <= robots <= ROBOTS:
        raise ValueError(f"robots = {robots}: expected 1 to {ROBOTS}")
    return keep_robots(text, set(range(1, robots + 1)))


IMAGE_DISPLAY = """    - Class: rviz/Image
      Enabled: true
      Image Topic: {topic}
      Max Value: 1
      Median window: 5
      Min Value: 0
      Name: {name}
      Normalize Range: false
      Queue Size: 2
      Transport Hint: raw
      Unreliable: false
      Value: true
"""
CLOUD_DISPLAY = """    - Alpha: 1
      Autocompute Intensity Bounds: true
      Class: rviz/PointCloud2
      Color: 255; 170; 0
      Color Transformer: FlatColor
      Decay Time: 2
      Enabled: true
      Name: {name}
      Position Transformer: XYZ
      Queue Size: 10
      Selectable: true
      Size (Pixels): 3
      Size (m): 0.05
      Style: Points
      Topic: {topic}
      Unreliable: false
      Use Fixed Frame: true
      Value: true
"""
#: robot name prefix -> the sonar displays of that vehicle type: (display kind, topic under /<robot>/, name suffix)
SONAR_DISPLAYS = {
    "ROV": [
        (IMAGE_DISPLAY, "imaging_sonar/fan", "imaging sonar"),
        (CLOUD_DISPLAY, "imaging_sonar/points", "sonar cloud"),
    ],
    "AUV": [(IMAGE_DISPLAY, "side_scan/waterfall", "side scan")],
}


def team_config(text, names):
    """The template's text for the robots `names` (see the module's doc), the added displays before the first UX-1's
    sensors (at the end of the display list when the team has no UX_1). ValueError for a name of no known prefix."""
    names = list(names)
    ux = {robot_index(n) for n in names if robot_index(n) and robot_index(n) <= ROBOTS}
    full = text.splitlines(keepends=True)
    start = next(i for i, line in enumerate(full) if line.strip() == "Displays:") + 1
    indent = indent_of(full[start])
    items = {display_name(full, f, e, indent + 2): (f, e) for f, e in blocks(full, start, indent)}
    added = []
    for robot in names:
        prefix = robot.rsplit("_", 1)[0]
        if robot_index(robot) in ux:
            continue
        if prefix not in SONAR_DISPLAYS and prefix != "UX":
            raise ValueError(
                f"rviz team: robot {robot!r}: expected UX_k, {', '.join(p + '_k' for p in SONAR_DISPLAYS)}"
            )
        for name in ("UX_1 model", "UX_1 odom"):
            first, end = items[name]
            added += [line.replace("UX_1", robot) for line in full[first:end]]
        for display, topic, suffix in SONAR_DISPLAYS.get(prefix, []):
            added.append(display.format(topic=f"/{robot}/{topic}", name=f"{robot} {suffix}"))
    lines = keep_robots(text, ux).splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if line.strip() == "Displays:") + 1
    kept = {display_name(lines, f, e, indent + 2): (f, e) for f, e in blocks(lines, start, indent)}
    at = kept["UX_1 sensors"][0] if "UX_1 sensors" in kept else blocks(lines, start, indent)[-1][1]
    return "".join(lines[:at] + added + lines[at:])
