"""The explorer (docs/explore.md): `python -m unexmin.missions.explore`.

octree.py reads the mapper's .bt; grid.py turns it into a coarse unknown/free/occupied grid; plan.py finds
frontiers, goals and paths; navigation.py dead-reckons from the IMU, DVL and pressure; budget.py says when to turn
for home; runner.py runs the loop (options.py: its options; agent.py: one robot's state and path; live_map.py:
the mapper's map into the grid; replan.py: the team's goals; control.py: each robot's control step); truth.py and
scoring.py score against the world (never steer); report.py writes the outputs; course.py builds small test
mines; cli.py is the command line.
"""
