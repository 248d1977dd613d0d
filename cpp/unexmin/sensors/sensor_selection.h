// Which sensor families run: "all", "none" or a comma-separated list of family names ("imu,dvl"), as the
// `sensors:=` launch argument gives it. Sensors of families left out are not built (no cost, no topic).
#pragma once

#include <set>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {

class SensorSelection {
public:
  /// Every family.
  SensorSelection() = default;
  /// Parses `text` ("all", "none" or "a,b,..."; spaces around names ignored). Throws ConfigError naming
  /// `source` (e.g. "parameter ~sensors") and the known families when a name is not in `known` or the list
  /// is empty.
  static SensorSelection parse(const std::string& text, const std::vector<std::string>& known,
                               const std::string& source);

  bool all() const { return all_; }
  bool none() const { return !all_ && families_.empty(); }
  bool selected(const std::string& type) const { return all_ || families_.count(type) > 0; }
  /// "all", "none" or the sorted list, comma-separated.
  std::string text() const;

private:
  bool all_ = true;
  std::set<std::string> families_;
};

}  // namespace sensors
}  // namespace unexmin
