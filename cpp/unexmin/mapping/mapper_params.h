// Parameters of the occupancy mapper (docs/mapping.md): voxel size, free-space range and the sensor model.
// Knows no ROS.
#pragma once

#include <limits>
#include <string>

namespace unexmin {
namespace mapping {

/// The mapper's parameters; validate() checks every one of them.
struct MapperParams {
  /// Edge of a leaf voxel [m], in [0.001, 10].
  double resolution = 0.1;
  /// Free-space range [m]: an endpoint farther than this from its sensor origin is not marked occupied and
  /// its ray carves free space up to this distance only. <= 0: no limit.
  double max_range = 10.0;
  /// Probability that a voxel holding an endpoint is occupied, in (0.5, 1).
  double prob_hit = 0.7;
  /// Probability that a voxel a ray crosses is occupied, in (0, 0.5).
  double prob_miss = 0.4;
  /// Lower clamp of a voxel's occupancy probability, in (0, prob_miss].
  double clamp_min = 0.12;
  /// Upper clamp of a voxel's occupancy probability, in [prob_hit, 1).
  double clamp_max = 0.97;

  /// Throws ParameterError naming the first parameter out of its range, its value and the range.
  void validate() const;
};

/// Which sensors' clouds a mapper takes from each robot, and how far it trusts each source's points.
struct MapperSources {
  bool m3 = true;                                    ///< the M3's scans (m3/scan)
  int sls_units = 4;                                 ///< the SLS units' clouds sls_<i>/points, i < sls_units, 0..16
  bool sonar = true;                                 ///< the imaging sonar's cloud (sonar_topic)
  std::string sonar_topic = "imaging_sonar/points";  ///< the sonar cloud's topic, relative to /<robot>/
  bool dvl = false;                                  ///< the DVL's beam ranges (dvl_sonar0..3)
  /// Each source's own range [m]: its points farther than this are not marked occupied and their rays carve free
  /// space up to it only; in (0, max_range] (any finite value when max_range <= 0; <= 0: no limit). NaN: max_range.
  double m3_max_range = std::numeric_limits<double>::quiet_NaN();
  double sls_max_range = std::numeric_limits<double>::quiet_NaN();
  double sonar_max_range = std::numeric_limits<double>::quiet_NaN();
  double dvl_max_range = std::numeric_limits<double>::quiet_NaN();

  /// Sets each range left NaN to max_range [m] (the map's MapperParams::max_range), then throws ParameterError
  /// naming the first parameter out of its range, its value and the range.
  void resolve(double max_range);
};

}  // namespace mapping
}  // namespace unexmin
