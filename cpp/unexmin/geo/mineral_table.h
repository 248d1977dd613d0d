// The shipped table of minerals (config/minerals.yaml, docs/minerals.md): per mineral its density, magnetic
// susceptibility and remanence, potassium, uranium and thorium contents, reflectance spectrum and UV fluorescence,
// each value with its source or "assumed". Knows no ROS.
#pragma once

#include <unexmin/geo/spectrum.h>

#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

namespace unexmin {
namespace geo {

/// Fluorescence under UV light: excitation inside [excitation_min, excitation_max] [nm] re-emits `yield` of the
/// absorbed light in the colour `emission` (RGB, max channel 1).
struct Fluorescence {
  double excitation_min = 0.0;  ///< [nm]
  double excitation_max = 0.0;  ///< [nm]
  Eigen::Vector3d emission{0, 0, 0};
  double yield = 0.0;  ///< in [0, 1]; 0: does not fluoresce
  bool excitedBy(double nm) const { return yield > 0.0 && nm >= excitation_min && nm <= excitation_max; }
};

struct Mineral {
  std::string name;
  double density = 0.0;         ///< [kg/m^3]
  double susceptibility = 0.0;  ///< volume magnetic susceptibility [SI, dimensionless]
  double remanence = 0.0;       ///< natural remanent magnetisation [A/m]
  double potassium = 0.0;       ///< K [% by weight]
  double uranium = 0.0;         ///< U [ppm by weight]
  double thorium = 0.0;         ///< Th [ppm by weight]
  Spectrum reflectance;         ///< diffuse reflectance 400..1000 nm
  Fluorescence fluorescence;
};

class MineralTable {
public:
  /// Reads and checks `file`; ConfigError "<file>: '<key>' ..." on a bad value, a value without its source, a source
  /// that is neither a key of `references` nor "assumed", or an unknown key.
  static MineralTable load(const std::string& file);

  const std::string& file() const { return file_; }
  /// nullptr when the table has no mineral `name`.
  const Mineral* find(const std::string& name) const;
  /// The minerals' names in byte order.
  std::vector<std::string> names() const;

private:
  std::string file_;
  std::map<std::string, Mineral> minerals_;
};

}  // namespace geo
}  // namespace unexmin
