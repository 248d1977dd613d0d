"""Headless lockstep missions: tank.py (`python -m unexmin.missions.tank`, the tank survey) and mine/
(`python -m unexmin.missions.mine`, the mine mapping survey that scripts/mission.sh runs: a plan plus a runner).
survey.py: the mine survey's plan and tracking controller; waypoints.py: a straight route through the shipped mine
and a waypoint controller (the batch missions', the gym's gallery task's); common.py: what the missions share."""
