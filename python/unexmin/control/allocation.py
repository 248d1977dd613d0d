"""Thruster allocation of the UX-1: body wrench -> eight thruster commands. Pure maths, no ROS.

The thesis's Thruster_allocator_sim (section 5.10.2) maps the commanded body wrench
tau = [X Y Z K M N] (forces [N] along body x, y, z; moments [N m] about them; body frame x forward,
y left, z up) to the thruster commands with the allocation matrix A of eq. 5.12 (rows X Y Z K M N,
columns thrusters M0..M7):

    m_i = sum_j A[j][i] * tau_j        (m = A^T tau)

m_i is the thrust [N] commanded to thruster i along its positive thrust axis. A is a mixing
matrix, not an exact inverse of the thruster geometry: with the shipped UX-1 geometry the body
wrench actually produced is B A^T tau = diag(sqrt2, sqrt2, sqrt2, 0, 0, 0.3 m) tau (B the 6x8
thruster-geometry matrix; see docs/thruster_allocator.md). K and M rows are zero: eight thrusters
in this layout cannot roll or pitch the sphere (the pendulum pitches it).

Saturation: when the largest |m_i| exceeds max_thrust, the whole vector m is multiplied by
max_thrust / max|m_i|. Every thruster is scaled by the same factor, so the produced wrench keeps
the commanded direction and only its magnitude shrinks (clamping each thruster on its own would
turn the robot off its commanded course).
"""

import math

import numpy as np

#: Names of the wrench components, in the row order of the allocation matrix.
DOF = ("X", "Y", "Z", "K", "M", "N")

#: Thesis eq. 5.12: rows X Y Z K M N, columns M0..M7 (thrust per unit wrench component).
THESIS_MATRIX = (
    (0.5, 0.0, -0.5, 0.0, 0.5, 0.0, -0.5, 0.0),
    (-0.25, -0.25, -0.25, 0.25, 0.25, -0.25, 0.25, -0.25),
    (0.0, -0.5, 0.0, -0.5, 0.0, 0.5, 0.0, -0.5),
    (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    (-0.25, 0.0, 0.25, 0.0, 0.25, 0.0, -0.25, 0.0),
)

#: [N] default saturation of one thruster: the simulated thrusters' accepted command range
#: (urdf/properties.xacro thruster_command_min/max = -/+40 N).
DEFAULT_MAX_THRUST = 40.0


class AllocationError(ValueError):
    """A parameter or an input of the allocation is invalid; the message names it."""


def validate_matrix(matrix, name="allocation_matrix"):
    """Return `matrix` as a 6 x n float array (n >= 1 thrusters).

    Accepts a nested list (6 rows of n) or a flat row-major list of 6 n numbers. Raises
    AllocationError naming `name` when the shape is wrong or an entry is not a finite number,
    or when a thruster (column) has only zeros (it would never be used: almost always a typo).
    """
    try:
        a = np.array(matrix, dtype=float)
    except (TypeError, ValueError) as e:
        raise AllocationError(
            f"parameter {name}: expected 6 rows of numbers (X Y Z K M N), got {matrix!r} ({e})"
        ) from None
    if a.ndim == 1:
        if a.size == 0 or a.size % 6:
            raise AllocationError(
                f"parameter {name}: a flat list needs 6 x n numbers (row-major, rows X Y Z K M N), got {a.size}"
            )
        a = a.reshape(6, -1)
    if a.ndim != 2 or a.shape[0] != 6 or a.shape[1] < 1:
        raise AllocationError(
            f"parameter {name}: expected shape 6 x n (rows X Y Z K M N, one column per thruster), "
            f"got shape {' x '.join(str(s) for s in a.shape)}"
        )
    bad = np.argwhere(~np.isfinite(a))
    if bad.size:
        r, c = bad[0]
        raise AllocationError(f"parameter {name}: entry [{DOF[r]}][M{c}] = {a[r, c]} is not a finite number")
    unused = [int(c) for c in np.flatnonzero(~a.any(axis=0))]
    if unused:
        raise AllocationError(f"parameter {name}: thruster column(s) {', '.join(f'M{c}' for c in unused)} are all zero")
    return a


def validate_max_thrust(value, name="max_thrust"):
    """Return `value` [N] as a float; it must be finite and > 0."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise AllocationError(f"parameter {name}: expected a number of newtons > 0, got {value!r}") from None
    if not math.isfinite(v) or v <= 0.0:
        raise AllocationError(f"parameter {name} = {v}: expected a finite thrust > 0 N")
    return v


def validate_wrench(wrench, name="wrench"):
    """Return `wrench` [X Y Z K M N] as a float array of 6; raises AllocationError if not 6 finite numbers."""
    try:
        w = np.array(wrench, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise AllocationError(f"{name}: expected 6 numbers [X Y Z K M N], got {wrench!r}") from None
    if w.size != 6:
        raise AllocationError(f"{name}: expected 6 numbers [X Y Z K M N], got {w.size}")
    bad = [DOF[i] for i in np.flatnonzero(~np.isfinite(w))]
    if bad:
        raise AllocationError(f"{name}: component(s) {', '.join(bad)} not finite: {w.tolist()}")
    return w


class ThrusterAllocator:
    """m = A^T tau with direction-preserving saturation.

    matrix: 6 x n allocation matrix (rows X Y Z K M N), default the thesis's eq. 5.12.
    max_thrust: [N] largest thrust magnitude one thruster may be commanded.
    """

    def __init__(self, matrix=THESIS_MATRIX, max_thrust=DEFAULT_MAX_THRUST):
        self.matrix = validate_matrix(matrix)
        self.max_thrust = validate_max_thrust(max_thrust)

    @property
    def thrusters(self):
        """Number of thrusters (columns of the matrix)."""
        return self.matrix.shape[1]

    def unsaturated(self, wrench):
        """Thrusts [N] m = A^T tau before saturation."""
        return self.matrix.T @ validate_wrench(wrench)

    def allocate(self, wrench):
        """Thrusts [N] for the body wrench [X Y Z K M N] ([N], [N m]), saturated.

        Returns (thrusts, scale): thrusts = scale * A^T tau with scale = min(1, max_thrust / max|m_i|),
        so every |thrust| <= max_thrust and the thrust vector keeps its direction.
        """
        m = self.unsaturated(wrench)
        peak = float(np.max(np.abs(m))) if m.size else 0.0
        scale = 1.0 if peak <= self.max_thrust else self.max_thrust / peak
        return m * scale, scale
