#include <unexmin/sim/world_schema.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>

namespace unexmin {
namespace sim {
namespace {

/// Python's difflib matching-block count of a[alo, ahi) and b[blo, bhi): the longest common block (the earliest
/// in a, then in b, among equal lengths), then the same on either side of it.
std::size_t matchingCharacters(const std::string& a, std::size_t alo, std::size_t ahi, const std::string& b,
                               std::size_t blo, std::size_t bhi) {
  std::size_t best_i = alo, best_j = blo, best = 0;
  for (std::size_t i = alo; i < ahi; ++i)
    for (std::size_t j = blo; j < bhi; ++j) {
      std::size_t k = 0;
      while (i + k < ahi && j + k < bhi && a[i + k] == b[j + k])
        ++k;
      if (k > best)
        best_i = i, best_j = j, best = k;
    }
  if (best == 0)
    return 0;
  return best + matchingCharacters(a, alo, best_i, b, blo, best_j) +
         matchingCharacters(a, best_i + best, ahi, b, best_j + best, bhi);
}

std::string joined(const std::vector<std::string>& keys) {
  std::string out;
  for (const auto& k : keys)
    out += (out.empty() ? "" : ", ") + k;
  return out;
}

void checkKeys(const YAML::Node& spec, const YAML::Node& value, const std::string& path, const std::string& file) {
  const std::string type = spec["type"] ? spec["type"].as<std::string>() : "";
  if (type == "list" && value.IsSequence()) {
    for (std::size_t i = 0; i < value.size(); ++i)
      checkKeys(spec["items"], value[i], path + "[" + std::to_string(i) + "]", file);
    return;
  }
  if (type != "map" || !value.IsMap())
    return;  // the value's type is checked where it is read
  const YAML::Node keys = spec["keys"];
  std::vector<std::string> accepted;
  for (const auto& kv : keys)
    accepted.push_back(kv.first.as<std::string>());
  for (const auto& kv : value) {
    const std::string key = kv.first.Scalar();
    const std::string sub_path = path.empty() ? key : path + "." + key;
    if (std::find(accepted.begin(), accepted.end(), key) == accepted.end()) {
      const std::string near = nearestKey(key, accepted);
      throw ConfigError(file + ": unknown key '" + sub_path + "' (accepted: " + joined(accepted) + ")" +
                        (near.empty() ? "" : "; did you mean '" + near + "'?"));
    }
    checkKeys(keys[key], kv.second, sub_path, file);
  }
}

}  // namespace

std::string packageConfigFile(const std::string& name, const char* variable, const std::string& what) {
  std::vector<std::string> places;
  if (const char* env = std::getenv(variable); env && *env) {
    places.push_back(env);
  } else {
    // the package's source folder, then its installed share folder (CMakeLists.txt)
    for (const char* dir : {UNEXMIN_SCHEMA_SOURCE_DIR, UNEXMIN_SCHEMA_SHARE_DIR})
      places.push_back(std::string(dir) + "/" + name);
  }
  for (const auto& p : places)
    if (std::ifstream(p))
      return p;
  throw ConfigError(what + " not found at " + joined(places) + ": expected the unexmin package's config/" + name +
                    " (or a file named by $" + variable + ")");
}

std::string worldSchemaFile() {
  return packageConfigFile("world_schema.yaml", "UNEXMIN_WORLD_SCHEMA", "world-file schema");
}

const YAML::Node& worldSchema(const std::string& schema_file) {
  static std::mutex mutex;
  static std::map<std::string, YAML::Node> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(schema_file);
  if (it != cache.end())
    return it->second;
  YAML::Node node;
  try {
    node = YAML::LoadFile(schema_file);
  } catch (const YAML::Exception& e) {
    throw ConfigError(schema_file + ": cannot read the world-file schema: " + e.what());
  }
  if (!node.IsMap() || !node["keys"])
    throw ConfigError(schema_file + ": not a world-file schema (no 'keys')");
  return cache.emplace(schema_file, node).first->second;
}

const std::vector<std::string>& visibilityLevels() {
  static const std::vector<std::string> levels = [] {
    const std::string file = worldSchemaFile();
    std::vector<std::string> out;
    const YAML::Node choices = worldSchema(file)["keys"]["visibility"]["keys"]["level"]["choices"];
    if (choices && choices.IsSequence())
      for (const auto& c : choices)
        out.push_back(c.as<std::string>());
    if (out.empty())
      throw ConfigError(file + ": 'visibility.level' lists no choices");
    return out;
  }();
  return levels;
}

double keySimilarity(const std::string& a, const std::string& b) {
  if (a.empty() && b.empty())
    return 1.0;
  return 2.0 * matchingCharacters(a, 0, a.size(), b, 0, b.size()) / static_cast<double>(a.size() + b.size());
}

std::string nearestKey(const std::string& key, const std::vector<std::string>& accepted) {
  std::string best;
  double best_score = 0.0;
  for (const auto& k : accepted) {
    // difflib.get_close_matches(key, accepted): SequenceMatcher(a = candidate, b = key), cutoff 0.6
    const double s = keySimilarity(k, key);
    if (s >= 0.6 && (s > best_score || (s == best_score && k > best)))
      best = k, best_score = s;
  }
  return best;
}

void checkWorldKeys(const YAML::Node& root, const std::string& file, const std::string& schema_file) {
  checkKeys(worldSchema(schema_file), root, "", file);
}

}  // namespace sim
}  // namespace unexmin
