"""The typed record of a robot description, field for field the simulator's (cpp/unexmin/sim/robot_description.h).

Body frame: the base link's (x forward, y left, z up, origin at the hull centre); every pose is composed along the
joint chain with the movable joints at zero. Parameters of a family (<param name value>) are lists of numbers.
"""

from dataclasses import dataclass, field

import numpy as np

from unexmin.description.errors import DescriptionError


@dataclass
class Joint:
    """A URDF <joint>: the child link's frame in the parent's (`position` [m], `rotation` 3 x 3) and its unit axis."""

    name: str
    type: str  # fixed, continuous, revolute, ...
    parent: str
    child: str
    position: np.ndarray  # [m] in the parent link's frame
    rotation: np.ndarray  # 3 x 3, child frame -> parent frame
    axis: np.ndarray  # unit, in the joint frame (URDF default 1 0 0)


@dataclass
class Hydrodynamics:
    """<hydrodynamics>: the rigid body on the base link."""

    mass: float  # [kg] dry mass, pendulum included, VBS empty
    volume: float  # [m^3] displaced when fully submerged
    radius: float  # [m] hull radius (partial submersion at the surface)
    center_of_gravity: np.ndarray  # [m] of the vehicle less the pendulum
    center_of_buoyancy: np.ndarray  # [m]
    inertia: np.ndarray  # [kg m^2] principal moments ixx iyy izz
    added_mass: np.ndarray  # 6 x 6 M_A [kg | kg m | kg m^2]
    linear_damping: np.ndarray  # 6, diagonal of D_l [N s/m | N m s/rad]
    quadratic_damping: np.ndarray  # 6, diagonal of D_q [N s^2/m^2 | N m s^2/rad^2]
    hull_box: np.ndarray  # [m] length, width, height of <bounding_box>; zeros when none


@dataclass
class Thruster:
    """<thruster>: thrust along `axis` at `position` (body frame); command -> thrust by its conversion family."""

    id: int
    joint: str
    position: np.ndarray  # [m] body frame
    axis: np.ndarray  # unit direction of positive thrust, body frame
    dynamics: str  # dynamics family (zero_order, first_order, ...)
    dynamics_params: dict
    conversion: str  # conversion family (identity, basic, table, ...)
    conversion_params: dict
    min_thrust: float  # [N]
    max_thrust: float  # [N]
    min_command: float  # command unit; the thrust range when the description gives no <command>
    max_command: float
    timeout: float = 1.0  # [s] command watchdog; <= 0 off


@dataclass
class Fin:
    """<fin>: turns about `axis` (span) at `position` (centre of pressure); at angle 0 its chord is `chord`."""

    id: int
    joint: str
    position: np.ndarray  # [m] body frame
    axis: np.ndarray  # unit span, body frame
    chord: np.ndarray  # unit, body frame
    model: str  # lift family (linear_lift, ...)
    model_params: dict
    area: float  # [m^2]
    min_angle: float  # [rad]
    max_angle: float  # [rad]
    rate: float  # [rad/s] largest angular speed
    timeout: float = 1.0  # [s] command watchdog; <= 0 off

    @property
    def movable(self):
        """False for a fixed surface (limits 0, 0: a body-lift term)."""
        return self.max_angle > self.min_angle


@dataclass
class Pendulum:
    """<pendulum>: the internal pitch pendulum; `joint` empty (and the simulator's defaults) when there is none."""

    joint: str = ""
    mass: float = 0.0  # [kg] part of the vehicle mass
    arm: float = 0.0  # [m] pivot to mass
    speed: float = 0.1  # [rad/s]
    min_angle: float = -0.5  # [rad]
    max_angle: float = 0.5  # [rad]

    @property
    def present(self):
        return bool(self.joint)


@dataclass
class Vbs:
    """<vbs>: the variable ballast system; a range of 0 kg when there is none."""

    min_mass: float = 0.0  # [kg] negative: lighter than the trim point
    max_mass: float = 0.0  # [kg]
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))  # [m] body frame


@dataclass
class Magnetics:
    """<magnetic>: the robot's own field at its magnetometers (zero when there is none), body frame:
    B_read = soft_iron B_ext + hard_iron + sum_i thruster_field[i] current_coefficient |T_i|^current_exponent."""

    hard_iron: np.ndarray = field(default_factory=lambda: np.zeros(3))  # [nT]
    soft_iron: np.ndarray = field(default_factory=lambda: np.eye(3))  # 3 x 3, on the external field
    thruster_field: list = field(default_factory=list)  # [np.ndarray(3)] [nT/A] by thruster id (empty: none)
    current_coefficient: float = 0.0  # [A / N^n]
    current_exponent: float = 1.5


@dataclass
class Sensor:
    """<sensor>: its link's pose in the body frame; numeric <param>s in `params`, the others in `text`."""

    name: str
    type: str
    link: str
    position: np.ndarray  # [m] of the link in the body frame
    rotation: np.ndarray  # 3 x 3, link frame -> body frame
    rate: float  # [Hz of sim time]
    params: dict = field(default_factory=dict)
    text: dict = field(default_factory=dict)


@dataclass
class RobotDescription:
    """A parsed robot description (unexmin.description.parse)."""

    source: str  # the file or parameter it came from (for messages)
    name: str  # <robot name>
    base_link: str  # the link carrying the hydrodynamics
    hydro: Hydrodynamics
    joints: list  # [Joint], document order
    thrusters: list  # [Thruster], sorted by id 0..n-1
    fins: list  # [Fin], sorted by id 0..n-1
    pendulum: Pendulum
    vbs: Vbs
    sensors: list  # [Sensor], document order
    magnetics: Magnetics = field(default_factory=Magnetics)

    def link_pose(self, link):
        """(position [m], rotation 3 x 3) of `link` in the base link's frame through the joint origins, every joint
        at zero."""
        p, rot = np.zeros(3), np.eye(3)
        current = link
        for _ in range(len(self.joints) + 1):
            if current == self.base_link:
                return p, rot
            joint = next((j for j in self.joints if j.child == current), None)
            if joint is None:
                raise DescriptionError(f"{self.source}: link '{link}' is not connected to '{self.base_link}'")
            p, rot = joint.rotation @ p + joint.position, joint.rotation @ rot
            current = joint.parent
        if current == self.base_link:
            return p, rot
        raise DescriptionError(f"{self.source}: joint loop above link '{link}'")

    def movable_joints(self):
        """Names of the non-fixed joints, in document order."""
        return [j.name for j in self.joints if j.type != "fixed"]
