// The `geology:` block of a world file (geo/geology.h, docs/worlds.md "Geology"), its minerals from the shipped
// mineral table (docs/minerals.md).
#pragma once

#include <unexmin/geo/geology.h>
#include <unexmin/sim/world_reader.h>

#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>

namespace unexmin {
namespace sim {

/// The mineral table: $UNEXMIN_MINERALS if set, else the package's config/minerals.yaml (world_schema.h's
/// packageConfigFile); ConfigError naming the places looked at when there is none.
std::string mineralTableFile();

/// The geology of the map `geology` (keys host, bodies) with minerals from the table in `minerals_file`. Throws
/// ConfigError "<world file>: '<key>' ..." through `r` on an unknown mineral, fractions not summing to 1, a bad
/// body; the table's own defects name the table's file.
std::shared_ptr<const geo::Geology> readGeology(const WorldReader& r, const YAML::Node& geology,
                                                const std::string& minerals_file);

}  // namespace sim
}  // namespace unexmin
