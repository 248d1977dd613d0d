// The keys of a world file (docs/worlds.md), written once in the package's config/world_schema.yaml and read both
// here and by the Python tools (python/unexmin/worlds/schema.py). Knows no ROS.
#pragma once

#include <unexmin/core/error.h>

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace unexmin {
namespace sim {

/// The schema file: $UNEXMIN_WORLD_SCHEMA if set, else config/world_schema.yaml of the package's source folder
/// or of its installed share folder (catkin's share path), the first that exists; ConfigError naming the places
/// looked at when there is none.
std::string worldSchemaFile();

/// The package's configuration file `name` (e.g. "minerals.yaml"): $<variable> if set, else config/<name> of the
/// package's source folder or of its installed share folder, the first that exists; ConfigError naming the places
/// looked at when there is none ("<what> not found at ...").
std::string packageConfigFile(const std::string& name, const char* variable, const std::string& what);

/// The parsed schema of `schema_file` (cached after the first read); ConfigError naming it when it cannot be read.
const YAML::Node& worldSchema(const std::string& schema_file);

/// The choices of the schema's visibility.level (none, low, medium, high), in the schema's order; ConfigError when the
/// schema has none.
const std::vector<std::string>& visibilityLevels();

/// How alike two keys are, in [0, 1]: 2 M / (|a| + |b|), M the characters of the longest common blocks found as
/// Python's difflib.SequenceMatcher(None, a, b).ratio() finds them.
double keySimilarity(const std::string& a, const std::string& b);

/// The accepted key most like `key` (similarity >= 0.6; of equal ones the last in byte order, as Python's
/// difflib.get_close_matches), or "" when none is.
std::string nearestKey(const std::string& key, const std::vector<std::string>& accepted);

/// Throws ConfigError "<file>: unknown key '<path>' (accepted: a, b, ...); did you mean '<k>'?" at the first key of
/// the parsed world file `root` (read from `file`) that the schema does not know, at any level (`meshes[1].albdo`).
void checkWorldKeys(const YAML::Node& root, const std::string& file, const std::string& schema_file);

}  // namespace sim
}  // namespace unexmin
