// The numeric parameters an actuator family reads from the robot description (<param name="..." value="..."/>
// inside a thruster's <dynamics> or <conversion>, or a fin's <model>), with the wording of every error: it names the
// family, the parameter, its value and what is accepted. The factory (actuator_family_factory.h) rejects a parameter
// the family did not read.
#pragma once

#include <unexmin/hydro/types.h>

#include <set>
#include <string>
#include <vector>

namespace unexmin {
namespace hydro {

class ActuatorFamilyParams {
public:
  /// `family` names the model in messages, e.g. "thruster dynamics 'first_order'".
  ActuatorFamilyParams(std::string family, ParamMap params);

  const std::string& family() const { return family_; }

  /// Whether the description gives `key` (marks it read).
  bool has(const std::string& key);
  /// A required parameter of exactly one finite number; throws ParameterError naming the family and `key`.
  double scalar(const std::string& key);
  /// A required number in [min, max] `unit` (e.g. "[s]"); throws ParameterError naming the family, `key`, the
  /// value and the range.
  double scalar(const std::string& key, double min, double max, const std::string& unit);
  /// A required list of numbers (any length; the family checks it); throws ParameterError naming `key`.
  const std::vector<double>& list(const std::string& key);

  /// Throws ParameterError naming the first parameter no call above read (a misspelt or foreign name) and the
  /// ones that were read.
  void finish() const;

private:
  std::string family_;
  ParamMap params_;
  std::set<std::string> read_;
};

}  // namespace hydro
}  // namespace unexmin
