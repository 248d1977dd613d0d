#include <unexmin/sensors/sensor_params.h>

#include <unexmin/sim/world_config.h>

#include <cmath>
#include <sstream>

namespace unexmin {
namespace sensors {
namespace {

std::string show(double v) {
  return formatNumber(v);
}

std::string showAll(const std::vector<double>& v) {
  std::string out;
  for (double x : v)
    out += (out.empty() ? "" : " ") + show(x);
  return out;
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

SensorParams::SensorParams(const sim::SensorSpec& spec, std::string robot) : spec_(spec), robot_(std::move(robot)) {}

std::string SensorParams::where() const {
  return robot_ + ": sensor '" + spec_.name + "' (type " + spec_.type + ")";
}

void SensorParams::fail(const std::string& key, const std::string& value, const std::string& expected) const {
  throw ConfigError(where() + ": parameter '" + key + "' = " + value + ": expected " + expected);
}

double SensorParams::number(const std::string& key, double fallback, double lo, double hi, const std::string& unit,
                            bool hi_open) {
  used_.insert(key);
  const std::string range = "a number in [" + show(lo) + ", " + show(hi) + (hi_open ? ")" : "]") + " " + unit;
  if (spec_.text.count(key))
    fail(key, "'" + spec_.text.at(key) + "'", range);
  const auto it = spec_.params.find(key);
  if (it == spec_.params.end())
    return fallback;
  if (it->second.size() != 1)
    fail(key, showAll(it->second), "one number: " + range);
  const double v = it->second[0];
  if (!std::isfinite(v) || v < lo || v > hi || (hi_open && v >= hi))
    fail(key, show(v), range);
  return v;
}

Eigen::Vector3d SensorParams::vec3(const std::string& key, const Eigen::Vector3d& fallback) {
  used_.insert(key);
  if (spec_.text.count(key))
    fail(key, "'" + spec_.text.at(key) + "'", "three numbers");
  const auto it = spec_.params.find(key);
  if (it == spec_.params.end())
    return fallback;
  if (it->second.size() != 3)
    fail(key, showAll(it->second), "three numbers");
  return Eigen::Vector3d(it->second[0], it->second[1], it->second[2]);
}

std::vector<double> SensorParams::numbers(const std::string& key, const std::vector<double>& fallback) {
  used_.insert(key);
  const std::string expected = formatNumber(static_cast<double>(fallback.size())) + " finite numbers";
  if (spec_.text.count(key))
    fail(key, "'" + spec_.text.at(key) + "'", expected);
  const auto it = spec_.params.find(key);
  if (it == spec_.params.end())
    return fallback;
  if (it->second.size() != fallback.size())
    fail(key, showAll(it->second), expected);
  for (double v : it->second)
    if (!std::isfinite(v))
      fail(key, showAll(it->second), expected);
  return it->second;
}

std::string SensorParams::text(const std::string& key, const std::string& fallback,
                               const std::vector<std::string>& allowed) {
  used_.insert(key);
  std::string value = fallback;
  if (spec_.text.count(key))
    value = spec_.text.at(key);
  else if (spec_.params.count(key))
    value = showAll(spec_.params.at(key));
  if (allowed.empty())
    return value;
  for (const auto& a : allowed)
    if (a == value)
      return value;
  std::string list;
  for (const auto& a : allowed)
    list += (list.empty() ? "" : "|") + a;
  fail(key, "'" + value + "'", "one of " + list);
}

bool SensorParams::flag(const std::string& key, bool fallback) {
  // xacro writes a Python bool as True/False.
  const std::string v = text(key, fallback ? "true" : "false", {"true", "false", "True", "False", "1", "0"});
  return v == "true" || v == "True" || v == "1";
}

std::vector<std::string> SensorParams::words(const std::string& key) {
  std::istringstream in(text(key, ""));
  std::vector<std::string> out;
  std::string w;
  while (in >> w)
    out.push_back(w);
  return out;
}

const sim::JointInfo& SensorParams::movingJoint(const sim::RobotDescription& description) {
  const std::vector<std::string> named = words("joint");
  const sim::JointInfo* joint = nullptr;
  for (const auto& j : description.joints)
    if (named.empty() ? j.child == spec_.link : j.name == named[0])
      joint = &j;
  if (!joint || joint->child != spec_.link || (joint->type != "continuous" && joint->type != "revolute"))
    fail("joint", named.empty() ? "(none: the joint whose child is " + spec_.link + ")" : "'" + named[0] + "'",
         "a continuous or revolute joint whose child is the sensor link '" + spec_.link + "'");
  return *joint;
}

void SensorParams::finish() const {
  std::vector<std::string> keys;
  for (const auto& kv : spec_.params)
    keys.push_back(kv.first);
  for (const auto& kv : spec_.text)
    keys.push_back(kv.first);
  for (const auto& k : keys) {
    if (used_.count(k) || k == "topic" || endsWith(k, "_topic"))
      continue;
    std::string known;
    for (const auto& u : used_)
      known += (known.empty() ? "" : ", ") + u;
    throw ConfigError(where() + ": unknown parameter '" + k + "' (this type reads: " + known +
                      "; 'topic' and names ending in _topic are for the publisher)");
  }
}

}  // namespace sensors
}  // namespace unexmin
