"""The Fossen model of the simulator as an equation error: what a bag's commands and navigation
give at each navigation sample, and the residual for a parameter vector. Pure numpy/scipy.

The simulator (cpp/unexmin/sim/robot.cpp) integrates one rigid body at the hull centre with the mass
m + m_VBS + m_A (translational added mass folded in) and inertia I + I_A, forces applied at the
centre, torques from thrusters, damping and the restoring forces of weight at the centre of gravity
and buoyancy at the centre of buoyancy. For a sphere, with ZYX attitude R (body -> world):

  (m + m_VBS + m_A) R^T a      = g_h F_h + g_v F_v - D_l v - D_q |v| v + (rho V f(z) - m - m_VBS) g R^T e_z
  (I + I_A) w_dot              = g_h M_h + g_v M_v - D_l w - D_q |w| w
                                 + (m c + m_p (r_p(alpha) - r_p(0)) + m_VBS r_VBS) x R^T (0, 0, -g)
                                 + c_B x R^T (0, 0, rho V f(z) g)

a: world acceleration of the centre; v, w: body linear and angular velocity; F, M: thrust force and
moment of each thruster group at unit gain (thruster first-order dynamics and watchdog as simulated);
m = rho V - b with b the net buoyancy [kg]; c: whole-vehicle centre of gravity (pendulum at 0, VBS
empty) = c_B + cog; f(z): submerged fraction. Each row is linear in the unknowns except through m.
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy.signal import savgol_filter

from unexmin.identify.vehicle import thrust_gain, thruster_groups, time_constant, whole_cog

GRAVITY = 9.81  # [m/s^2] of the shipped worlds (worlds/*.world)
DOF = ("surge", "sway", "heave", "roll", "pitch", "yaw")


# Parameter vector: (name, group, index in the group)
PARAMS = (
    ["buoyancy_kg", "added_mass"]
    + [f"added_inertia_{d}" for d in DOF[3:]]
    + ["thrust_gain_horizontal", "thrust_gain_vertical"]
    + [f"damping_linear_{d}" for d in DOF]
    + [f"damping_quadratic_{d}" for d in DOF]
    + ["cog_x", "cog_y", "cog_z"]
)
INDEX = {name: i for i, name in enumerate(PARAMS)}


def nominal_vector(physics):
    """Parameter vector of a robot description (unexmin.description.RobotDescription): its values are the prior."""
    x = np.zeros(len(PARAMS))
    x[INDEX["buoyancy_kg"]] = 1000.0 * physics.hydro.volume - physics.hydro.mass  # water density set by Signals
    x[INDEX["added_mass"]] = float(np.mean(np.diag(physics.hydro.added_mass)[:3]))
    for k, d in enumerate(DOF[3:]):
        x[INDEX[f"added_inertia_{d}"]] = physics.hydro.added_mass[3 + k, 3 + k]
    for name, ids in thruster_groups(physics).items():
        gains = [thrust_gain(physics.thrusters[i]) for i in ids]
        x[INDEX[f"thrust_gain_{name}"]] = float(np.mean(gains)) if ids else 1.0
    for k, d in enumerate(DOF):
        x[INDEX[f"damping_linear_{d}"]] = physics.hydro.linear_damping[k]
        x[INDEX[f"damping_quadratic_{d}"]] = physics.hydro.quadratic_damping[k]
    x[INDEX["cog_x"] : INDEX["cog_z"] + 1] = whole_cog(physics) - physics.hydro.center_of_buoyancy
    return x


def rotations(rpy):
    """(n, 3, 3) matrices R = Rz(yaw) Ry(pitch) Rx(roll) (body -> world) of rows of rpy [rad]."""
    r, p, y = rpy[:, 0], rpy[:, 1], rpy[:, 2]
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.stack(
        [
            np.stack([cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr], -1),
            np.stack([sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr], -1),
            np.stack([-sp, cp * sr, cp * cr], -1),
        ],
        1,
    )


def body_rates(e, de, dde):
    """Body angular velocity and acceleration [rad/s, rad/s^2] from ZYX angles e = (roll, pitch, yaw)
    and their first and second time derivatives (rows)."""
    ph, th = e[:, 0], e[:, 1]
    dph, dth, dps = de.T
    ddph, ddth, ddps = dde.T
    sph, cph, sth, cth = np.sin(ph), np.cos(ph), np.sin(th), np.cos(th)
    w = np.stack([dph - dps * sth, dth * cph + dps * sph * cth, -dth * sph + dps * cph * cth], -1)
    dw = np.stack(
        [
            ddph - ddps * sth - dps * dth * cth,
            ddth * cph - dth * dph * sph + ddps * sph * cth + dps * dph * cph * cth - dps * dth * sph * sth,
            -ddth * sph - dth * dph * cph + ddps * cph * cth - dps * dph * sph * cth - dps * dth * cph * sth,
        ],
        -1,
    )
    return w, dw


def submerged_fraction(z, surface_z, radius):
    """Submerged volume fraction of a sphere of `radius` [m] centred at world z [m] (simulator's formula)."""
    h = np.clip(surface_z - (np.asarray(z) - radius), 0.0, 2.0 * radius)
    return np.clip(h * h * (3.0 * radius - h) / (4.0 * radius**3), 0.0, 1.0)


def thrust_history(physics, motors, times, rate=500.0, converter=None):
    """Achieved thrust [N] of each thruster at unit gain at `times` [s] (mission time), from the
    mission's motor commands [(t, mode, values[8])]: the ESC conversion (unexmin.control.esc), then each
    thruster's command limits, watchdog and first-order dynamics at the physics `rate` [Hz], as the
    simulator applies them (a command acts from the physics step after its time)."""
    from unexmin.control.esc import EscConverter

    converter = converter or EscConverter()
    dt = 1.0 / rate
    n_steps = int(math.ceil(max(times[-1], motors[-1][0]) * rate)) + 2
    cmd_steps = [(round(t * rate), converter.to_thrust(mode, values)[0]) for t, mode, values in motors]
    th = physics.thrusters
    lo = np.array([t.min_command for t in th])
    hi = np.array([t.max_command for t in th])
    taus = [time_constant(t) for t in th]
    alpha = np.array([1.0 - math.exp(-dt / tau) if tau > 0 else 1.0 for tau in taus])
    timeout_steps = np.array([t.timeout * rate if t.timeout > 0 else np.inf for t in th])
    state = np.zeros(len(th))
    command = np.zeros(len(th))
    last = np.full(len(th), -np.inf)
    out = np.zeros((n_steps + 1, len(th)))
    k_cmd = 0
    for step in range(n_steps + 1):
        while k_cmd < len(cmd_steps) and cmd_steps[k_cmd][0] < step:
            values = cmd_steps[k_cmd][1][: len(th)]
            ok = (values >= lo) & (values <= hi)
            command = np.where(ok, values, command)
            last = np.where(ok, cmd_steps[k_cmd][0], last)
            k_cmd += 1
        active = np.where(step - last > timeout_steps, 0.0, command)
        state = state + alpha * (active - state)
        out[step] = state
    idx = np.clip(np.round(np.asarray(times) * rate).astype(int), 0, n_steps)
    return out[idx]


def step_signal(events, times, initial, lo, hi):
    """Piecewise-constant command (VBS mass [kg]) at `times`: last value of events [(t, v)] before t."""
    out = np.full(len(times), float(initial))
    for t, v in sorted(events):
        out[np.asarray(times) > t] = min(max(float(v), lo), hi)
    return out


def pendulum_history(physics, events, times, rate=500.0):
    """Pendulum angle [rad] at `times`: starts at 0 and turns at its constant speed to each target."""
    n_steps = int(math.ceil(max(times[-1], max([t for t, _ in events], default=0.0)) * rate)) + 2
    lo, hi = physics.pendulum.min_angle, physics.pendulum.max_angle
    ev = sorted((round(t * rate), min(max(v, lo), hi)) for t, v in events)
    angle, target, k, step_max = 0.0, 0.0, 0, physics.pendulum.speed / rate
    out = np.zeros(n_steps + 1)
    for step in range(n_steps + 1):
        while k < len(ev) and ev[k][0] < step:
            target = ev[k][1]
            k += 1
        rem = target - angle
        angle = target if abs(rem) <= step_max else angle + math.copysign(step_max, rem)
        out[step] = angle
    return out[np.clip(np.round(np.asarray(times) * rate).astype(int), 0, n_steps)]


@dataclass
class Signals:
    """The bag on two grids: navigation samples (t, filtered states) and the physics rate (commands)."""

    t: np.ndarray  # [s] navigation grid (uniform)
    R: np.ndarray  # (n, 3, 3) body -> world, smoothed
    v: np.ndarray  # [m/s] body linear velocity
    w: np.ndarray  # [rad/s] body angular velocity
    acc: np.ndarray  # [m/s^2] world acceleration D2[x] (Savitzky-Golay second derivative)
    dw: np.ndarray  # [rad/s^2] body angular acceleration R^T D1[w_world]
    th: np.ndarray  # [s] physics-rate grid
    Rh: np.ndarray  # (N, 3, 3) attitude on th
    vh: np.ndarray  # body velocity on th
    wh: np.ndarray  # body angular velocity on th
    zh: np.ndarray  # [m] world z on th
    thrust: np.ndarray  # (N, 8) [N] at unit gain on th
    pendulum: np.ndarray  # [rad] on th
    vbs: np.ndarray  # [kg] on th
    vbs_nav: np.ndarray  # [kg] on t
    water_density: float
    surface_z: float
    window: int  # samples of the Savitzky-Golay window
    keep: np.ndarray  # navigation samples used in the fit (edges trimmed)
    d1: object = None  # D1 of the navigation grid (callable)
    d2: object = None


def _interp_rows(t_new, t, x):
    return np.stack([np.interp(t_new, t, x[:, i]) for i in range(x.shape[1])], -1)


def prepare(mission, physics, window_s=0.7, water_density=1000.0, surface_z=0.0, rate=500.0):
    """Signals of a replay Mission (commands + navigation): the navigation resampled on a uniform
    grid; its Savitzky-Golay derivatives (window_s [s], cubic): world acceleration D2[x] and the
    derivative D1 of the world angular velocity (central differences of the attitude); the commands
    reconstructed at the physics rate."""
    from scipy.spatial.transform import Rotation

    nav = mission.nav
    if nav is None or len(nav) < 10:
        raise ValueError(
            f"{mission.path}: the identification needs navigation (pose) samples; found "
            f"{0 if nav is None else len(nav)}"
        )
    dt = float(np.median(np.diff(nav[:, 0])))
    if not dt > 0:
        raise ValueError(f"{mission.path}: navigation times are not increasing")
    t = np.arange(max(nav[0, 0], 0.0), nav[-1, 0] + 1e-9, dt)
    pos = _interp_rows(t, nav[:, 0], nav[:, 1:4])
    ang = _interp_rows(t, nav[:, 0], np.unwrap(nav[:, 4:7], axis=0))
    win = max(5, int(round(window_s / dt)) | 1)
    if 2 * win >= len(t):
        raise ValueError(f"window {window_s} s is too long for the navigation ({len(t)} samples of {dt} s)")

    def sg(x, d):
        return savgol_filter(x, win, 3, deriv=d, delta=dt, axis=0, mode="interp")

    R_raw = rotations(ang)
    rel = Rotation.from_matrix(np.einsum("nij,nkj->nik", R_raw[2:], R_raw[:-2]))
    w_world = np.zeros_like(pos)
    w_world[1:-1] = rel.as_rotvec() / (2.0 * dt)
    w_world[0], w_world[-1] = w_world[1], w_world[-2]
    e = sg(ang, 0)
    R = rotations(e)
    Rt = np.transpose(R, (0, 2, 1))
    v = np.einsum("nij,nj->ni", Rt, sg(pos, 1))
    w_s = sg(w_world, 0)
    w = np.einsum("nij,nj->ni", Rt, w_s)
    th = np.arange(t[0], t[-1] + 0.5 / rate, 1.0 / rate)
    Rh = rotations(_interp_rows(th, t, e))
    Rht = np.transpose(Rh, (0, 2, 1))
    keep = np.zeros(len(t), bool)
    keep[win : len(t) - win] = True
    # at the free surface the buoyancy changes by rho g pi R^2 per metre of z: a few mm of navigation
    # error would be newtons of force; such samples are left out (the hull must be 1 cm under)
    keep &= sg(pos, 0)[:, 2] + physics.hydro.radius < surface_z - 0.01
    if keep.sum() < 2 * win:
        raise ValueError(
            f"{mission.path}: only {int(keep.sum())} navigation samples with the robot submerged "
            f"(centre more than {physics.hydro.radius + 0.01:.2f} m below the surface z = {surface_z} m)"
        )
    return Signals(
        t=t,
        R=R,
        v=v,
        w=w,
        acc=sg(pos, 2),
        dw=np.einsum("nij,nj->ni", Rt, sg(w_world, 1)),
        th=th,
        Rh=Rh,
        vh=np.einsum("nij,nj->ni", Rht, _interp_rows(th, t, sg(pos, 1))),
        wh=np.einsum("nij,nj->ni", Rht, _interp_rows(th, t, w_s)),
        zh=np.interp(th, t, sg(pos, 0)[:, 2]),
        thrust=thrust_history(physics, mission.motors, th, rate),
        pendulum=pendulum_history(physics, mission.pendulum, th, rate),
        vbs=step_signal(mission.vbs, th, 0.0, physics.vbs.min_mass, physics.vbs.max_mass),
        vbs_nav=step_signal(mission.vbs, t, 0.0, physics.vbs.min_mass, physics.vbs.max_mass),
        water_density=water_density,
        surface_z=surface_z,
        window=win,
        keep=keep,
        d1=lambda x: sg(x, 1),
        d2=lambda x: sg(x, 2),
    )


class EquationError:
    """The equation error as a linear regression, residual(x) = A x + c, shape (n, 6): world-frame
    force rows [N] and body-frame moment rows [N m] at the navigation samples.

    Both sides see the same filter: the translational equation M a = F is compared as
    M D2[x] = D2[double integral of F], the rotational one as I R^T D1[w] = R^T D1[integral of R tau],
    the integrals taken at the physics rate from the commands. D2 and D1 are the Savitzky-Golay
    derivatives of the navigation; they are exact for the polynomial part, so the thrust steps do
    not leak into neighbouring samples as they would with a filtered derivative against raw forces.
    """

    def __init__(self, signals, physics):
        from scipy.integrate import cumulative_trapezoid

        s, p = signals, physics
        self.s, self.p = s, p
        dt_h = s.th[1] - s.th[0]
        g = GRAVITY
        rhoV = s.water_density * p.hydro.volume
        n, k = len(s.t), len(PARAMS)
        idx = np.clip(np.round((s.t - s.th[0]) / dt_h).astype(int), 0, len(s.th) - 1)

        def T(gw):  # world force history on th -> D2[double integral] on t
            ii = cumulative_trapezoid(cumulative_trapezoid(gw, dx=dt_h, axis=0, initial=0), dx=dt_h, axis=0, initial=0)
            return s.d2(ii[idx])

        def U(hb):  # body moment history on th -> R^T D1[integral of R h] on t
            hw = np.einsum("nij,nj->ni", s.Rh, hb)
            ii = cumulative_trapezoid(hw, dx=dt_h, axis=0, initial=0)
            return np.einsum("nji,nj->ni", s.R, s.d1(ii[idx]))

        groups = thruster_groups(p)
        dirs = np.array([t.axis for t in p.thrusters])
        moms = np.array([np.cross(t.position, t.axis) for t in p.thrusters])
        A = np.zeros((n, 6, k))
        c = np.zeros((n, 6))
        ez = np.array([0.0, 0.0, 1.0])
        # translation (world frame)
        A[:, :3, INDEX["buoyancy_kg"]] = -s.acc - g * ez
        A[:, :3, INDEX["added_mass"]] = s.acc
        for name, ids in groups.items():
            A[:, :3, INDEX[f"thrust_gain_{name}"]] = -T(np.einsum("nij,nj->ni", s.Rh, s.thrust[:, ids] @ dirs[ids]))
            A[:, 3:, INDEX[f"thrust_gain_{name}"]] = -U(s.thrust[:, ids] @ moms[ids])
        f_sub = submerged_fraction(s.zh, s.surface_z, p.hydro.radius)
        for j in range(3):
            col = s.Rh[:, :, j]
            A[:, :3, INDEX[f"damping_linear_{DOF[j]}"]] = T(col * s.vh[:, j : j + 1])
            A[:, :3, INDEX[f"damping_quadratic_{DOF[j]}"]] = T(col * (np.abs(s.vh[:, j]) * s.vh[:, j])[:, None])
        c[:, :3] = (rhoV + s.vbs_nav)[:, None] * s.acc - T(((rhoV * f_sub - rhoV - s.vbs) * g)[:, None] * ez)
        # rotation (body frame)
        for j in range(3):
            e_j = np.eye(3)[j]
            A[:, 3:, INDEX[f"added_inertia_{DOF[3 + j]}"]] = s.dw * e_j
            A[:, 3:, INDEX[f"damping_linear_{DOF[3 + j]}"]] = U(e_j * s.wh[:, j : j + 1])
            A[:, 3:, INDEX[f"damping_quadratic_{DOF[3 + j]}"]] = U(e_j * (np.abs(s.wh[:, j]) * s.wh[:, j])[:, None])
        down = np.einsum("nji,j->ni", s.Rh, np.array([0.0, 0.0, -g]))  # R^T (0, 0, -g)
        m_nom = p.hydro.mass
        for j, name in enumerate(("cog_x", "cog_y", "cog_z")):
            A[:, 3:, INDEX[name]] = -U(m_nom * np.cross(np.eye(3)[j], down))
        arm = p.pendulum.arm
        r_p = np.stack([arm * np.sin(s.pendulum), np.zeros_like(s.pendulum), -arm * np.cos(s.pendulum)], -1)
        shift = p.pendulum.mass * (r_p - np.array([0.0, 0.0, -arm])) + s.vbs[:, None] * p.vbs.position
        buoy = -(rhoV * f_sub)[:, None] * down
        known = np.cross(m_nom * p.hydro.center_of_buoyancy + shift, down) + np.cross(p.hydro.center_of_buoyancy, buoy)
        c[:, 3:] = p.hydro.inertia * s.dw - U(known)
        self.A, self.c = A[s.keep], c[s.keep]

    def residual(self, x):
        return self.A @ x + self.c
