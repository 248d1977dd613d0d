// Reads the values of one robot description's XML elements, failing with ConfigError("<source>: <problem>") that
// names the element and the attribute (sim/robot_description.h). Used by the entity parsers of
// sim/description_entities.h only.
#pragma once

#include <unexmin/hydro/thruster.h>

#include <tinyxml2.h>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {
namespace description {

class DescriptionReader {
public:
  explicit DescriptionReader(std::string source) : source_(std::move(source)) {}

  const std::string& source() const { return source_; }

  /// Throws ConfigError("<source>: <what>").
  [[noreturn]] void fail(const std::string& what) const;

  /// The whitespace-separated finite numbers of `text` (none when null); `where` names them in the error.
  std::vector<double> numbers(const char* text, const std::string& where) const;
  /// The numbers of attribute `attr` of `e`, which must exist and hold `count` of them (any number when 0).
  std::vector<double> attrNumbers(const tinyxml2::XMLElement* e, const char* attr, std::size_t count,
                                  const std::string& where) const;
  /// The one number of attribute `name` of `e`, which must exist.
  double attr(const tinyxml2::XMLElement* e, const char* name, const std::string& where) const;
  /// The one number of attribute `name` of `e`, `fallback` when `e` or the attribute is missing.
  double attrOr(const tinyxml2::XMLElement* e, const char* name, const std::string& where, double fallback) const;
  /// Three numbers of attribute `attr` of `e`, as a vector.
  Eigen::Vector3d vector3(const tinyxml2::XMLElement* e, const char* attr, const std::string& where) const;
  /// The first child <name> of `e`, which must exist.
  const tinyxml2::XMLElement* child(const tinyxml2::XMLElement* e, const char* name, const std::string& where) const;
  /// Value of <name value="..."/> under e, with `count` numbers.
  std::vector<double> valueOf(const tinyxml2::XMLElement* e, const char* name, std::size_t count,
                              const std::string& where) const;
  /// The <param name="..." value="numbers"/> children of `e`.
  hydro::ParamMap params(const tinyxml2::XMLElement* e, const std::string& where) const;

private:
  std::string source_;
};

/// Attribute `name` of `e`, "" when missing.
std::string textOf(const tinyxml2::XMLElement* e, const char* name);

}  // namespace description
}  // namespace sim
}  // namespace unexmin
