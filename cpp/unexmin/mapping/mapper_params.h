// Parameters of the occupancy mapper (docs/mapping.md): voxel size, free-space range and the sensor model.
// Knows no ROS.
#pragma once

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

}  // namespace mapping
}  // namespace unexmin
