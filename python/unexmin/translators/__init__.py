"""Message translators between the simulator and the real robot's drivers (docs/translators.md):
m3.py (LaserScan <-> PointCloud2), dvl.py (Nortek DVL), kvh.py (KVH 1775 IMU); node.py runs one as a node."""
