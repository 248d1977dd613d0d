"""ESC command <-> thrust conversion of the UX-1 thrusters. Pure maths, no ROS.

The real robot's ESC driver takes ux1_msgs/MotorCommand on /ux1/command/motors: eight signed values,
either propeller speeds [rev/min] (mode RPM) or ESC duty cycles [-1, 1] (mode DUTY_CYCLE). The
simulated thrusters take thrust [N]. A ThrustTable maps one to the other by linear interpolation in
a measured table, and back (its generalised inverse).

Default tables -- an ASSUMPTION for the UX-1
--------------------------------------------
Neither the thesis nor the SPEC gives the UX-1 thrusters' curve. The defaults are a thruster of the
same class (about 4 kgf, the simulated thrusters' +-40 N): the Blue Robotics T200 at 16 V, from the
manufacturer's published bollard-pull measurements ("T200-Public-Performance-Data-10-20V-
September-2019", sheet "16 V": columns PWM [us], RPM, Force [kgf]). Eighteen rows of that sheet,
about every 50 us, are kept; force is converted with 1 kgf = 9.80665 N. The sheet's RPM column is
unsigned: reverse rows (PWM < 1500 us) are given negative speeds here. Duty cycle is
(PWM - 1500 us) / 400 us, the ESC's +-400 us throttle range mapped to [-1, 1]; the ESC dead band
(1472..1528 us, no rotation) is kept, so small duty cycles give no thrust. Note the asymmetry of a
real propeller: 51.5 N forward, 39.9 N in reverse at full command. Replace both tables with the
UX-1's own bench measurements (parameters of the ESC driver and the allocator) when they exist.
"""

import math

import numpy as np

#: MotorCommand.mode values (message_packages/ux1_msgs/msg/MotorCommand.msg).
MODE_RPM = 0
MODE_DUTY_CYCLE = 1
MODE_NAMES = {MODE_RPM: "rpm", MODE_DUTY_CYCLE: "duty_cycle"}

KGF = 9.80665  # [N] per kilogram-force

# T200 at 16 V (see module docstring): (PWM [us], RPM unsigned, force [kgf]), every ~50 us.
_T200_16V = (
    (1100, 3465, -4.07),
    (1152, 3207, -3.45),
    (1200, 2865, -2.71),
    (1252, 2517, -2.02),
    (1300, 2140, -1.44),
    (1352, 1705, -0.90),
    (1400, 1246, -0.48),
    (1452, 578, -0.10),
    (1468, 317, -0.04),
    (1472, 0, 0.0),
    (1528, 0, 0.0),
    (1532, 308, 0.04),
    (1548, 573, 0.13),
    (1600, 1237, 0.60),
    (1652, 1740, 1.18),
    (1700, 2129, 1.82),
    (1752, 2538, 2.65),
    (1800, 2888, 3.42),
    (1852, 3260, 4.51),
    (1900, 3533, 5.25),
)


def _rpm_table():
    rows = [(-rpm if pwm < 1500 else rpm, kgf * KGF) for pwm, rpm, kgf in _T200_16V if rpm > 0]
    rows.insert(next(i for i, r in enumerate(rows) if r[0] > 0), (0.0, 0.0))
    return tuple(float(r[0]) for r in rows), tuple(r[1] for r in rows)


def _duty_table():
    return (tuple((pwm - 1500) / 400.0 for pwm, _, _ in _T200_16V), tuple(kgf * KGF for _, _, kgf in _T200_16V))


#: Signed propeller speed [rev/min] -> thrust [N] (T200, 16 V; an assumption for the UX-1).
DEFAULT_RPM_TABLE = _rpm_table()
#: ESC duty cycle [-1, 1] -> thrust [N] (T200, 16 V; an assumption for the UX-1).
DEFAULT_DUTY_TABLE = _duty_table()


class EscTableError(ValueError):
    """An ESC table or parameter is invalid; the message names it."""


class ThrustTable:
    """Piecewise-linear map command -> thrust [N], clamped at the table's ends.

    inputs: command values (rpm or duty cycle), strictly increasing, at least 2.
    outputs: thrust [N] at each input, non-decreasing (flat runs allowed: an ESC dead band).
    """

    def __init__(self, inputs, outputs, name="table"):
        self.name = name
        try:
            x = np.array(inputs, dtype=float).reshape(-1)
            y = np.array(outputs, dtype=float).reshape(-1)
        except (TypeError, ValueError) as e:
            raise EscTableError(f"parameter {name}: input and output must be lists of numbers ({e})") from None
        if x.size != y.size:
            raise EscTableError(f"parameter {name}: input has {x.size} entries but output has {y.size}")
        if x.size < 2:
            raise EscTableError(f"parameter {name}: needs at least 2 (input, output) pairs, got {x.size}")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            raise EscTableError(f"parameter {name}: entries must be finite numbers")
        if np.any(np.diff(x) <= 0):
            i = int(np.flatnonzero(np.diff(x) <= 0)[0])
            raise EscTableError(
                f"parameter {name}: input must be strictly increasing, "
                f"but input[{i}] = {x[i]} >= input[{i + 1}] = {x[i + 1]}"
            )
        if np.any(np.diff(y) < 0):
            i = int(np.flatnonzero(np.diff(y) < 0)[0])
            raise EscTableError(
                f"parameter {name}: output (thrust) must not decrease with the input, "
                f"but output[{i}] = {y[i]} > output[{i + 1}] = {y[i + 1]}"
            )
        if y[-1] <= y[0]:
            raise EscTableError(f"parameter {name}: output is constant ({y[0]} N): no thrust can be commanded")
        self.inputs = x
        self.outputs = y
        # Runs of equal outputs (first, last index): a flat run is a plateau such as the dead band.
        self._runs = []
        i = 0
        while i < x.size:
            j = i
            while j + 1 < x.size and y[j + 1] == y[i]:
                j += 1
            self._runs.append((i, j))
            i = j + 1

    @property
    def command_range(self):
        """(min, max) command of the table (rpm or duty cycle)."""
        return float(self.inputs[0]), float(self.inputs[-1])

    @property
    def thrust_range(self):
        """(min, max) thrust [N] the table can produce."""
        return float(self.outputs[0]), float(self.outputs[-1])

    def thrust(self, command):
        """Thrust [N] for a command (scalar or array), clamped to the table's ends."""
        return np.interp(command, self.inputs, self.outputs)

    def command(self, thrust):
        """Command giving `thrust` [N] (scalar or array): thrust(command(t)) == t within the table's range.

        Thrusts beyond the table's range give its end commands. A thrust equal to a plateau value
        (the dead band's 0 N) gives the plateau's middle; a thrust between a plateau and the next
        table point interpolates from the plateau's edge, so the round trip stays exact.
        """
        t = np.asarray(thrust, dtype=float)
        scalar = t.ndim == 0
        t = np.atleast_1d(t)
        out = np.empty_like(t)
        x, y = self.inputs, self.outputs
        for k, v in enumerate(t):
            if not math.isfinite(v):
                raise EscTableError(f"{self.name}: thrust {v} is not a finite number")
            if v <= y[0]:
                a, b = self._runs[0]
                out[k] = 0.5 * (x[a] + x[b])
                continue
            if v >= y[-1]:
                a, b = self._runs[-1]
                out[k] = 0.5 * (x[a] + x[b])
                continue
            for a, b in self._runs:
                if y[a] == v:
                    out[k] = 0.5 * (x[a] + x[b])
                    break
                if b + 1 < x.size and y[b] < v < y[b + 1]:
                    out[k] = x[b] + (v - y[b]) * (x[b + 1] - x[b]) / (y[b + 1] - y[b])
                    break
        return float(out[0]) if scalar else out


class EscConverter:
    """MotorCommand values <-> thrust [N] for both modes, with a thrust limit.

    rpm_table, duty_table: ThrustTable for MODE_RPM and MODE_DUTY_CYCLE.
    max_thrust: [N] thrusts are clamped to +-max_thrust (the simulated thrusters' accepted command
    range, +-40 N for the shipped UX-1; a command outside it would be rejected by the simulator).
    """

    def __init__(self, rpm_table=None, duty_table=None, max_thrust=40.0):
        self.tables = {
            MODE_RPM: rpm_table or ThrustTable(*DEFAULT_RPM_TABLE, name="rpm_table"),
            MODE_DUTY_CYCLE: duty_table or ThrustTable(*DEFAULT_DUTY_TABLE, name="duty_table"),
        }
        try:
            self.max_thrust = float(max_thrust)
        except (TypeError, ValueError):
            raise EscTableError(f"parameter max_thrust: expected a number of newtons > 0, got {max_thrust!r}") from None
        if not math.isfinite(self.max_thrust) or self.max_thrust <= 0.0:
            raise EscTableError(f"parameter max_thrust = {max_thrust}: expected a finite thrust > 0 N")

    def table(self, mode):
        if mode not in self.tables:
            raise EscTableError(
                f"unknown MotorCommand mode {mode}: expected {MODE_RPM} (RPM) or {MODE_DUTY_CYCLE} (DUTY_CYCLE)"
            )
        return self.tables[mode]

    def to_thrust(self, mode, values):
        """Thrusts [N] for MotorCommand values in `mode`; returns (thrusts, clamped).

        clamped is True when a thrust was limited to +-max_thrust. Raises EscTableError for an
        unknown mode or a non-finite value.
        """
        v = np.array(values, dtype=float).reshape(-1)
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise EscTableError(f"motor value(s) {bad.tolist()} not finite: {v.tolist()}")
        thrust = self.table(mode).thrust(v)
        limited = np.clip(thrust, -self.max_thrust, self.max_thrust)
        return limited, bool(np.any(limited != thrust))

    def to_command(self, mode, thrusts):
        """MotorCommand values in `mode` for thrusts [N] (the table's inverse)."""
        return self.table(mode).command(np.array(thrusts, dtype=float).reshape(-1))


def parse_mode(value, name="motor_command_mode"):
    """MODE_RPM or MODE_DUTY_CYCLE from 'rpm' / 'duty_cycle' (or 0 / 1)."""
    if isinstance(value, str):
        key = value.strip().lower()
        for mode, mode_name in MODE_NAMES.items():
            if key == mode_name:
                return mode
    elif value in MODE_NAMES:
        return int(value)
    raise EscTableError(f"parameter {name} = {value!r}: expected 'rpm' or 'duty_cycle'")


def converter_from_params(get_param):
    """EscConverter from parameters read with get_param(name, default) (e.g. rospy's, with '~').

    Parameters: rpm_table_input [rev/min], rpm_table_output [N], duty_table_input [-1..1],
    duty_table_output [N], max_thrust [N] (defaults: module constants).
    """
    rpm = ThrustTable(
        get_param("rpm_table_input", list(DEFAULT_RPM_TABLE[0])),
        get_param("rpm_table_output", list(DEFAULT_RPM_TABLE[1])),
        name="rpm_table_input/output",
    )
    duty = ThrustTable(
        get_param("duty_table_input", list(DEFAULT_DUTY_TABLE[0])),
        get_param("duty_table_output", list(DEFAULT_DUTY_TABLE[1])),
        name="duty_table_input/output",
    )
    return EscConverter(rpm, duty, get_param("max_thrust", 40.0))
