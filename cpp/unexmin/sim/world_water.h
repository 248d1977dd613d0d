// The `water:` block of a world file beyond density and surface_z: the water column's profiles
// (water/water_column.h, docs/worlds.md "Water column").
#pragma once

#include <unexmin/sim/world_reader.h>
#include <unexmin/water/water_column.h>

#include <yaml-cpp/yaml.h>

#include <memory>

namespace unexmin {
namespace sim {

/// The water column of the map `water` (keys profile, interpolation, boundary, regions), or nullptr when it gives
/// no profile (regions without one are refused). Throws ConfigError "<file>: '<key>' ..." through `r`.
std::shared_ptr<const water::WaterColumn> readWaterColumn(const WorldReader& r, const YAML::Node& water,
                                                          double surface_z, double gravity);

}  // namespace sim
}  // namespace unexmin
