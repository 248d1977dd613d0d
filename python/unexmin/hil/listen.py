"""The hil tools' own rospy nodes listen on ROS_IP only, as the simulator's do (docs/reliability.md "Safe by default").

rospy listens on every interface when ROS_IP is not a loopback address; `python -m unexmin.hil.<tool>` therefore
starts itself again with the bind shim (libunexmin_bind_shim.so) in LD_PRELOAD when it is not there yet.
"""

import os
import sys
from pathlib import Path

from unexmin.bind_shim import LIBRARY, ros_environment


def with_bind_shim(module, argv=None):
    """Return if the bind shim is loaded in this process; else replace the process by `python -m module argv` with
    it preloaded (argv: this process's arguments by default). SystemExit(2) naming the library when it is not built."""
    if any(Path(p).name == LIBRARY for p in os.environ.get("LD_PRELOAD", "").replace(":", " ").split()):
        return
    try:
        env = ros_environment(dict(os.environ))
    except FileNotFoundError as e:
        print(f"{module}: {e}", file=sys.stderr)
        raise SystemExit(2) from None
    args = sys.argv[1:] if argv is None else list(argv)
    os.execve(sys.executable, [sys.executable, "-m", module, *args], env)
