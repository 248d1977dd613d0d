"""The shipped vehicle types and the names their robots take in a team (launch/simulation.launch `vehicles:=`,
docs/adding_a_vehicle.md). Pure Python, no ROS.

The k-th vehicle of a type in a team list is the world's robot <prefix>_k: ux1 -> UX_k, bluerov2_heavy -> ROV_k,
remus100 -> AUV_k; the world file lists that robot with the type's description.
"""

#: vehicle type -> (robot name prefix, description file in urdf/)
VEHICLE_TYPES = {
    "ux1": ("UX", "ux1.urdf.xacro"),
    "bluerov2_heavy": ("ROV", "bluerov2_heavy.urdf.xacro"),
    "remus100": ("AUV", "remus100.urdf.xacro"),
}


def parse_vehicles(value, where="vehicles"):
    """The vehicle types of `value` (a comma-separated text or a list), in order; ValueError naming `where` and the
    known types for an unknown or empty one."""
    items = value.split(",") if isinstance(value, str) else list(value) if isinstance(value, (list, tuple)) else None
    if items is None:
        raise ValueError(f"{where}: expected a list of vehicle types ({', '.join(VEHICLE_TYPES)}), got {value!r}")
    types = [str(v).strip() for v in items]
    bad = [v for v in types if v not in VEHICLE_TYPES]
    if not types or bad:
        raise ValueError(f"{where}: unknown vehicle type(s) {bad or ['']} (expected: {', '.join(VEHICLE_TYPES)})")
    return types


def team_names(vehicles):
    """Robot names of the team `vehicles` (types, in order): ['ux1', 'remus100', 'ux1'] -> UX_1, AUV_1, UX_2."""
    types = parse_vehicles(vehicles)
    return [f"{VEHICLE_TYPES[v][0]}_{types[: i + 1].count(v)}" for i, v in enumerate(types)]
