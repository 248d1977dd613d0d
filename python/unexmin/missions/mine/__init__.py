"""The main job (docs/mapping.md, "The mission"): `python -m unexmin.missions.mine`, what scripts/mission.sh runs.
A plan plus a runner: plan.py (what to fly: the survey of missions/survey.py for the world's mine, at its
visibility; no ROS), runner.py (the plan flown in lockstep with the mapper on, a bag recorded, maps saved),
scoring.py (the map and its snapshots scored against the mine's mesh, the plots, summary.json); cli.py is the
command line and run(), the three in a row."""
