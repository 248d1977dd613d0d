"""ESC table (python/unexmin/control/esc.py) and the simulated ESC driver node (nodes/esc_driver).

The table tests need no roscore. Expected thrusts are computed here from the T200 16 V rows typed in
again from Blue Robotics' published sheet (PWM [us], RPM, force [kgf]) and the definition of linear
interpolation. The driver test runs the real node on a private master and checks the round trip
MotorCommand -> thrust on /UX_1/thrusters/<i>/input.

Run: /work/main_ws/venv/bin/python -m pytest test/pytest/test_esc.py
"""

import json
import shutil
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from unexmin.control.esc import (
    DEFAULT_DUTY_TABLE,
    DEFAULT_RPM_TABLE,
    KGF,
    MODE_DUTY_CYCLE,
    MODE_RPM,
    EscConverter,
    EscTableError,
    ThrustTable,
    converter_from_params,
    parse_mode,
)

G = 9.80665
# Rows of the sheet used by the defaults (PWM us, RPM, kgf), typed in again.
ROWS = [
    (1100, 3465, -4.07),
    (1400, 1246, -0.48),
    (1468, 317, -0.04),
    (1472, 0, 0.0),
    (1528, 0, 0.0),
    (1532, 308, 0.04),
    (1600, 1237, 0.60),
    (1652, 1740, 1.18),
    (1900, 3533, 5.25),
]


def lerp(x, x0, y0, x1, y1):
    return y0 + (x - x0) * (y1 - y0) / (x1 - x0)


def test_kgf():
    assert KGF == G


@pytest.mark.parametrize("pwm, rpm, kgf", [r for r in ROWS if r[1] > 0])
def test_default_rpm_table_hits_the_datasheet_rows(pwm, rpm, kgf):
    t = ThrustTable(*DEFAULT_RPM_TABLE)
    signed = -rpm if pwm < 1500 else rpm
    assert t.thrust(signed) == pytest.approx(kgf * G, abs=1e-9)


@pytest.mark.parametrize("pwm, rpm, kgf", ROWS)
def test_default_duty_table_hits_the_datasheet_rows(pwm, rpm, kgf):
    t = ThrustTable(*DEFAULT_DUTY_TABLE)
    assert t.thrust((pwm - 1500) / 400.0) == pytest.approx(kgf * G, abs=1e-9)


def test_interpolation_between_rows_is_linear():
    t = ThrustTable(*DEFAULT_RPM_TABLE)
    for x in (1300.0, 1488.5, 1700.0):
        assert t.thrust(x) == pytest.approx(lerp(x, 1237, 0.60 * G, 1740, 1.18 * G), abs=1e-9)
    # between 0 rpm (0 N) and the first forward row (308 rpm, 0.04 kgf)
    assert t.thrust(154.0) == pytest.approx(0.02 * G, abs=1e-12)


def test_dead_band_gives_no_thrust_and_the_ends_clamp():
    duty = ThrustTable(*DEFAULT_DUTY_TABLE)
    for d in (-0.07, -0.03, 0.0, 0.05, 0.07):
        assert duty.thrust(d) == 0.0
    assert duty.thrust(1.5) == pytest.approx(5.25 * G)  # beyond the table: its last thrust
    assert duty.thrust(-3.0) == pytest.approx(-4.07 * G)
    assert duty.thrust_range == pytest.approx((-4.07 * G, 5.25 * G))
    assert duty.command_range == (-1.0, 1.0)


def test_inverse_round_trip_is_exact_inside_the_table():
    rng = np.random.default_rng(7)
    for table in (ThrustTable(*DEFAULT_RPM_TABLE), ThrustTable(*DEFAULT_DUTY_TABLE)):
        lo, hi = table.thrust_range
        thrusts = np.concatenate([rng.uniform(lo, hi, 200), [lo, hi, 0.0, 1e-6, -1e-6]])
        np.testing.assert_allclose(table.thrust(table.command(thrusts)), thrusts, atol=1e-9)
    # command -> thrust -> command outside the dead band
    rpm = ThrustTable(*DEFAULT_RPM_TABLE)
    cmds = rng.uniform(-3465, 3533, 200)
    np.testing.assert_allclose(rpm.command(rpm.thrust(cmds)), cmds, rtol=1e-9, atol=1e-6)


def test_inverse_of_zero_is_the_middle_of_the_dead_band_and_edges_are_exact():
    duty = ThrustTable(*DEFAULT_DUTY_TABLE)
    assert duty.command(0.0) == 0.0
    # just above 0 N the command is on the segment leaving the dead band at duty 0.07
    assert duty.command(0.02 * G) == pytest.approx(lerp(0.02, 0.0, 0.07, 0.04, 0.08), abs=1e-12)
    assert duty.command(100.0) == 1.0 and duty.command(-100.0) == -1.0


@pytest.mark.parametrize(
    "inputs, outputs, words",
    [
        ([0, 1, 2], [0, 1], ["3 entries", "2"]),
        ([0], [0], ["at least 2"]),
        ([0, 2, 1], [0, 1, 2], ["strictly increasing", "input[1]"]),
        ([0, 1, 2], [0, 2, 1], ["must not decrease", "output[1]"]),
        ([0, 1], [5, 5], ["constant"]),
        ([0, float("nan")], [0, 1], ["finite"]),
        ("ab", [0, 1], ["lists of numbers"]),
    ],
)
def test_bad_table_is_rejected_naming_the_parameter(inputs, outputs, words):
    with pytest.raises(EscTableError) as e:
        ThrustTable(inputs, outputs, name="rpm_table_input/output")
    assert "rpm_table_input/output" in str(e.value)
    for w in words:
        assert w in str(e.value)


def test_converter_clamps_to_the_thruster_limit_and_rejects_bad_input():
    esc = EscConverter(max_thrust=40.0)
    thrusts, clamped = esc.to_thrust(MODE_DUTY_CYCLE, [1.0, -1.0, 0.0, 0.25, 0, 0, 0, 0])
    assert clamped
    np.testing.assert_allclose(thrusts[:4], [40.0, -4.07 * G, 0.0, 0.60 * G], atol=1e-9)
    thrusts, clamped = esc.to_thrust(MODE_RPM, [1237, -1246, 0, 0, 0, 0, 0, 0])
    assert not clamped
    np.testing.assert_allclose(thrusts[:3], [0.60 * G, -0.48 * G, 0.0], atol=1e-9)
    with pytest.raises(EscTableError, match="mode 7"):
        esc.to_thrust(7, [0] * 8)
    with pytest.raises(EscTableError, match="not finite"):
        esc.to_thrust(MODE_RPM, [float("nan")] + [0] * 7)
    with pytest.raises(EscTableError, match="max_thrust"):
        EscConverter(max_thrust=0.0)


def test_mode_names_and_params():
    assert parse_mode("rpm") == MODE_RPM and parse_mode("DUTY_CYCLE") == MODE_DUTY_CYCLE and parse_mode(1) == 1
    with pytest.raises(EscTableError, match="motor_command_mode"):
        parse_mode("pwm")
    params = {"rpm_table_input": [-100, 0, 100], "rpm_table_output": [-2, 0, 4], "max_thrust": 3.0}
    esc = converter_from_params(lambda name, default: params.get(name, default))
    thrusts, clamped = esc.to_thrust(MODE_RPM, [50, 100, -100])
    np.testing.assert_allclose(thrusts, [2.0, 3.0, -2.0])
    assert clamped


# ---------------------------------------------------------------------------------------------
# The node, on a private master
# ---------------------------------------------------------------------------------------------
CLIENT = textwrap.dedent("""
    import json, sys, threading, time
    import rospy
    from std_msgs.msg import Float64
    from ux1_msgs.msg import MotorCommand
    from unexmin.topics import ESC_COMMAND_TOPIC
    cases = json.loads(sys.argv[1])
    rospy.init_node("esc_test_client", disable_signals=True)
    got, cond = {}, threading.Condition()
    def cb(msg, i):
        with cond:
            got.setdefault(i, []).append(msg.data)
            cond.notify_all()
    subs = [rospy.Subscriber(f"/UX_1/thrusters/{i}/input", Float64, cb, i) for i in range(8)]
    pub = rospy.Publisher(ESC_COMMAND_TOPIC, MotorCommand, queue_size=10)
    deadline = time.monotonic() + 60  # a loaded machine starts rospy nodes slowly
    while time.monotonic() < deadline and not (
        pub.get_num_connections() and all(s.get_num_connections() for s in subs)):
        time.sleep(0.05)
    out = []
    for n, (mode, values) in enumerate(cases, 1):
        pub.publish(MotorCommand(mode=mode, values=values))
        with cond:
            ok = cond.wait_for(lambda: all(len(got.get(i, [])) >= n for i in range(8)), 30)
        out.append([got[i][n - 1] for i in range(8)] if ok else None)
    print(json.dumps(out))
""")


@pytest.fixture
def master(tmp_path):
    if not shutil.which("rosmaster"):
        pytest.skip("rosmaster not installed")
    from unexmin.scripting.launcher import free_port, start_private_master, stop_process_group

    proc, env = start_private_master(free_port(), tmp_path)
    try:
        yield env
    finally:
        stop_process_group(proc)


def test_driver_round_trip_follows_the_table(master):
    rpm = [1237, -1246, 0, 1488.5, 3533, -3465, 308, 154]
    duty = [0.25, -0.25, 0.0, 0.05, 1.0, -1.0, 0.45, -0.08]
    driver = subprocess.Popen(
        ["rosrun", "unexmin", "esc_driver"],
        env=master,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        res = subprocess.run(
            [sys.executable, "-c", CLIENT, json.dumps([[MODE_RPM, rpm], [MODE_DUTY_CYCLE, duty]])],
            env=master,
            capture_output=True,
            text=True,
            timeout=180,  # the client's own waits: 60 s for its connections, then 30 s per case
        )
        assert res.returncode == 0, res.stderr
        by_rpm, by_duty = json.loads(res.stdout.strip().splitlines()[-1])
    finally:
        driver.terminate()
        driver.wait(10)
    expected_rpm = [
        0.60 * G,
        -0.48 * G,
        0.0,
        lerp(1488.5, 1237, 0.60, 1740, 1.18) * G,
        40.0,  # 51.5 N clamped
        -4.07 * G,
        0.04 * G,
        0.02 * G,
    ]
    expected_duty = [0.60 * G, -0.48 * G, 0.0, 0.0, 40.0, -4.07 * G, lerp(0.45, 0.38, 1.18, 0.5, 1.82) * G, -0.04 * G]
    np.testing.assert_allclose(by_rpm, expected_rpm, atol=1e-9)
    np.testing.assert_allclose(by_duty, expected_duty, atol=1e-9)
