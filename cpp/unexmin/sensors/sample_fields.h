// What a sensor family's sample holds, told once by the family's model (Sensor::describe): named fields with their
// element type, shape and unit. Every reader that is not the family's own publisher reads a sample through this
// description and knows no family: the in-process Python module (unexmin.core's sample dicts), tests, exporters.
// Knows no ROS.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {

/// Element type of a sample field.
enum class FieldType { float64, float32, uint8, uint64, boolean };

/// The name of `t` ("float64", "float32", "uint8", "uint64", "bool").
const char* fieldTypeName(FieldType t);

/// One field of a sample: a scalar (empty shape) or an array of shape[0] x shape[1] x ... elements, row-major.
struct SampleField {
  std::string name;  ///< the field's key, e.g. "ranges"
  std::string unit;  ///< e.g. "m", "rad/s", "-" (dimensionless); "" for flags and counts
  FieldType type = FieldType::float64;
  std::vector<std::size_t> shape;  ///< empty: one element
  const void* data = nullptr;      ///< the elements; valid during SampleWriter::field() only, unless `kept`
  /// The data lives in the model until its next sample or reset: a reader may keep a view instead of a copy.
  bool kept = false;

  std::size_t size() const;  ///< elements: the product of `shape` (1 for a scalar)
};

/// Receives the fields of one sample, in the family's order (a visitor; a reader implements field()).
class SampleWriter {
public:
  virtual ~SampleWriter() = default;
  virtual void field(const SampleField& f) = 0;

  // Shorthands that build the SampleField; the data must live until the call returns.
  void scalar(const std::string& name, const std::string& unit, const double& v);
  void flag(const std::string& name, const bool& v);
  void count(const std::string& name, const std::uint64_t& v);
  /// Three doubles (x, y, z) in the frame the family documents.
  void vector3(const std::string& name, const std::string& unit, const Eigen::Vector3d& v);
  void array(const std::string& name, const std::string& unit, const std::vector<double>& v,
             std::vector<std::size_t> shape = {});
  void array(const std::string& name, const std::string& unit, const std::vector<float>& v,
             std::vector<std::size_t> shape = {});
  void array(const std::string& name, const std::string& unit, const std::vector<std::uint8_t>& v,
             std::vector<std::size_t> shape = {}, bool kept = false);
  /// `n` flags (std::vector<bool> holds no array of bool: the family copies them into a buffer of its own).
  void flags(const std::string& name, const bool* v, std::size_t n);

private:
  void put(const std::string& name, const std::string& unit, FieldType type, std::vector<std::size_t> shape,
           const void* data, std::size_t elements, bool kept);
};

}  // namespace sensors
}  // namespace unexmin
