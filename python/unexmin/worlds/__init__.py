"""Worlds, in one place (docs/worlds.md): files.py (shipped worlds by name, reading a world file, linking its
meshes, its collision triangles), schema.py (the world file's schema), meshes.py (STL/PLY reading and writing, surface
sampling), spawn.py (a shipped world with a robot spawned elsewhere, as a launch file), mesh_marker.py (the rviz mesh
node); generator/ (`python -m unexmin.worlds.generator`, the procedural mine, docs/mine_world.md) and from_scan/
(`python -m unexmin.worlds.from_scan`, a world from a surveyed point cloud, docs/world_from_scan.md)."""
