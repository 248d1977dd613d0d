"""Headless lockstep missions: tank.py (`python -m unexmin.missions.tank`, the tank survey) and mine.py
(`python -m unexmin.missions.mine`, the mine mapping survey that scripts/mission.sh runs)."""
