"""World files and meshes (docs/worlds.md): files.py (shipped worlds by name, reading a world file, linking its
meshes, its collision triangles), meshes.py (STL/PLY reading and writing, surface sampling), spawn.py (a
shipped world with a robot spawned elsewhere, as a launch file), mesh_marker.py (the rviz mesh node)."""
