"""The explorer (docs/explore.md): `python -m unexmin.explore`.

octree.py reads the mapper's .bt; grid.py turns it into a coarse unknown/free/occupied grid; plan.py finds
frontiers, goals and paths; navigation.py dead-reckons from the IMU, DVL and pressure; budget.py says when to turn
for home; runner.py flies the robots; truth.py scores against the world (never steers); report.py writes the
outputs; course.py builds small test mines; cli.py is the command line.
"""
