#include <unexmin/sensors/sample_fields.h>

#include <unexmin/core/error.h>

namespace unexmin {
namespace sensors {

const char* fieldTypeName(FieldType t) {
  switch (t) {
    case FieldType::float64:
      return "float64";
    case FieldType::float32:
      return "float32";
    case FieldType::uint8:
      return "uint8";
    case FieldType::uint64:
      return "uint64";
    case FieldType::boolean:
      return "bool";
  }
  return "?";
}

namespace {

/// `shape`, or one dimension of `n` when it is empty.
std::vector<std::size_t> orFlat(std::vector<std::size_t> shape, std::size_t n) {
  return shape.empty() ? std::vector<std::size_t>{n} : shape;
}

}  // namespace

std::size_t SampleField::size() const {
  std::size_t n = 1;
  for (const std::size_t d : shape)
    n *= d;
  return n;
}

void SampleWriter::put(const std::string& name, const std::string& unit, FieldType type, std::vector<std::size_t> shape,
                       const void* data, std::size_t elements, bool kept) {
  SampleField f;
  f.name = name;
  f.unit = unit;
  f.type = type;
  f.shape = std::move(shape);
  f.data = data;
  f.kept = kept;
  if (f.size() != elements)
    throw ConfigError("sample field '" + name + "': a shape of " + std::to_string(f.size()) + " elements for " +
                      std::to_string(elements) + " values");
  field(f);
}

void SampleWriter::scalar(const std::string& name, const std::string& unit, const double& v) {
  put(name, unit, FieldType::float64, {}, &v, 1, false);
}

void SampleWriter::flag(const std::string& name, const bool& v) {
  put(name, "", FieldType::boolean, {}, &v, 1, false);
}

void SampleWriter::count(const std::string& name, const std::uint64_t& v) {
  put(name, "", FieldType::uint64, {}, &v, 1, false);
}

void SampleWriter::vector3(const std::string& name, const std::string& unit, const Eigen::Vector3d& v) {
  put(name, unit, FieldType::float64, {3}, v.data(), 3, false);
}

void SampleWriter::array(const std::string& name, const std::string& unit, const std::vector<double>& v,
                         std::vector<std::size_t> shape) {
  put(name, unit, FieldType::float64, orFlat(std::move(shape), v.size()), v.data(), v.size(), false);
}

void SampleWriter::array(const std::string& name, const std::string& unit, const std::vector<float>& v,
                         std::vector<std::size_t> shape) {
  put(name, unit, FieldType::float32, orFlat(std::move(shape), v.size()), v.data(), v.size(), false);
}

void SampleWriter::array(const std::string& name, const std::string& unit, const std::vector<std::uint8_t>& v,
                         std::vector<std::size_t> shape, bool kept) {
  put(name, unit, FieldType::uint8, orFlat(std::move(shape), v.size()), v.data(), v.size(), kept);
}

void SampleWriter::flags(const std::string& name, const bool* v, std::size_t n) {
  put(name, "", FieldType::boolean, {n}, v, n, false);
}

}  // namespace sensors
}  // namespace unexmin
