#!/usr/bin/env python3
"""Write the shipped rviz configurations for one and two robots, and for a mixed team, from the three-robot one.

launch/unexmin.rviz (three robots, UX_1..UX_3) is the template and the configuration for three robots;
launch/unexmin_<n>.rviz (n = 1, 2) is the same file without the displays of UX_<n+1>..UX_3 and their
entries in the Camera display's visibility list, so that rviz shows no display of a robot that does not
exist (it would be a red error row). simulation.launch opens the file that matches its `robots` argument.
launch/unexmin_team.rviz is the one-robot file with the BlueROV2 Heavy's (ROV_1) and the REMUS 100's (AUV_1) models,
odometry and sonar displays (the imaging sonar's fan and point cloud, the side-scan's waterfall): the team
ux1,bluerov2_heavy,remus100, for opening by hand. simulation.launch with `vehicles:=` writes its own team's file
at start-up (nodes/team_rviz, the same rules: python/unexmin/rviz_config.py).

    python scripts/rviz_configs.py            # rewrite launch/unexmin_1.rviz, unexmin_2.rviz, unexmin_team.rviz
    python scripts/rviz_configs.py --check    # exit 1 if a shipped file differs from what it would write

Edit launch/unexmin.rviz (by hand or by saving from rviz with three robots), then run this script.
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from unexmin.rviz_config import ROBOTS, config_for, team_config  # noqa: E402

LAUNCH = Path(__file__).resolve().parents[1] / "launch"
TEMPLATE = LAUNCH / "unexmin.rviz"


#: The mixed team of launch/unexmin_team.rviz (simulation.launch's default with vehicles:=ux1,bluerov2_heavy,remus100
#: when rviz is opened by hand; a running team's configuration is written by nodes/team_rviz).
TEAM = ["UX_1", "ROV_1", "AUV_1"]
TEAM_PATH = LAUNCH / "unexmin_team.rviz"


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
    wanted = team_config(text, TEAM)
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
