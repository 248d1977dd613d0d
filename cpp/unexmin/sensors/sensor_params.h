// Typed, checked access to one sensor's <param> elements (sim::SensorSpec::params / text). Every
// failure is a ConfigError naming the robot, the sensor, the parameter, its value and the
// accepted range. Knows no ROS.
#pragma once

#include <unexmin/sim/robot_description.h>

#include <Eigen/Core>

#include <set>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {

class SensorParams {
public:
  /// `robot`: robot name (or description source), used in messages only.
  SensorParams(const sim::SensorSpec& spec, std::string robot);

  /// Scalar in [lo, hi] (hi excluded when `hi_open`), `fallback` when absent. `unit` for messages.
  double number(const std::string& key, double fallback, double lo, double hi, const std::string& unit,
                bool hi_open = false);
  /// Three numbers, `fallback` when absent.
  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback);
  /// Exactly `fallback.size()` finite numbers, `fallback` when absent.
  std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback);
  /// Text, `fallback` when absent; when `allowed` is not empty the value must be one of them.
  std::string text(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed = {});
  /// A switch: true/false (xacro's True/False, 1/0 too), `fallback` when absent.
  bool flag(const std::string& key, bool fallback);
  /// Whitespace-separated words (e.g. link names); empty when absent.
  std::vector<std::string> words(const std::string& key);

  /// The continuous or revolute joint that moves the sensor link (an MSIS head, an SLS motor): the joint named
  /// by the `joint` parameter, or by default the one whose child is the sensor link; fails naming `joint`
  /// otherwise.
  const sim::JointInfo& movingJoint(const sim::RobotDescription& description);

  /// Throws for any parameter no reader asked for (a typo), except "topic" and names ending in
  /// "_topic", which belong to the publishing layer.
  void finish() const;

  /// Prefix of every message: "<robot>: sensor '<name>' (type <type>)".
  std::string where() const;
  [[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& expected) const;

private:
  const sim::SensorSpec& spec_;
  std::string robot_;
  std::set<std::string> used_;
};

}  // namespace sensors
}  // namespace unexmin
