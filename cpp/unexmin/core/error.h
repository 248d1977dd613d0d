// The one root of every error the simulator's core throws (hydro, sim, raycast, sensors) and its ROS layer,
// and the one number formatter of their messages. Knows no ROS.
//
// Every message names the input that is wrong (file, robot, sensor, parameter), its value and what was
// expected, e.g. "UX_1: sensor 'dvl': parameter 'beam_angle' = 2: expected [0, 1.5707963268] rad".
#pragma once

#include <stdexcept>
#include <string>

namespace unexmin {

/// Root of the simulator's errors; catch this to catch them all.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// A robot description, world file, launch parameter or sensor selection is wrong: start-up stops with
/// this one message.
class ConfigError : public Error {
public:
  using Error::Error;
};

/// A numeric model parameter (thruster, damping, noise, echo model, ...) is missing, has the wrong size,
/// or is out of its range.
class ParameterError : public ConfigError {
public:
  using ConfigError::ConfigError;
};

/// A ray caster cannot be built (unknown back end, Embree error) or was handed a bad ray.
class RayCasterError : public Error {
public:
  using Error::Error;
};

/// A number as error messages show it: shortest form up to 12 significant digits ("0.1", "2", "1e-06",
/// "nan", "inf"). Use it for integers too (no std::to_string in messages).
std::string formatNumber(double x);

}  // namespace unexmin
