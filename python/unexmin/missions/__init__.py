"""The missions, in one place: tank.py (`python -m unexmin.missions.tank`, the tank survey), mine/
(`python -m unexmin.missions.mine`, the mine mapping survey that scripts/mission.sh runs: a plan plus a runner),
explore/ (`python -m unexmin.missions.explore`, frontier exploration by one to three robots: a plan plus a runner)
and batch.py (the mission functions shipped for `python -m unexmin.batch`: mission(sim, params) -> metrics).
survey.py: the mine survey's plan and tracking controller; waypoints.py: a straight route through the shipped mine
and a waypoint controller (the batch missions', the gym's gallery task's); common.py: what the missions share."""
