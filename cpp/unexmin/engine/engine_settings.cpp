#include <unexmin/engine/engine_settings.h>

#include <unexmin/sim/world_schema.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace engine {
namespace {

std::string joined(const std::vector<std::string>& words, const std::string& sep) {
  std::string out;
  for (const auto& w : words)
    out += (out.empty() ? "" : sep) + w;
  return out;
}

std::string visibilityRule() {
  return joined(sim::visibilityLevels(), "|") + " (or empty: the world file's level)";
}

SettingError settingError(const SettingSpelling& spelling, const std::string& name, const std::string& value,
                          const std::string& expected) {
  return SettingError(name, spelling ? spelling(name) : name, value, expected);
}

}  // namespace

SettingError::SettingError(std::string name, const std::string& spelling, std::string value, std::string expected)
    : ConfigError(spelling + " = " + value + ": expected " + expected),
      name_(std::move(name)),
      value_(std::move(value)),
      expected_(std::move(expected)) {}

const std::vector<std::string>& modes() {
  static const std::vector<std::string> m = {"operational", "visual"};
  return m;
}

std::vector<std::pair<std::string, std::string>> settingRules(const sensors::SensorFactory& models) {
  std::string counts;  // "1, 2 or 3"
  for (int n = 1; n <= kMaxRobots; ++n)
    counts += (n == 1 ? "" : n == kMaxRobots ? " or " : ", ") + std::to_string(n);
  return {{"robots", counts},
          {"seed", "a non-negative integer"},
          {"sensors", "all, none or families of " + joined(models.types(), ", ") + " (comma-separated)"},
          {"visibility", visibilityRule()},
          {"physics_rate", "[" + formatNumber(kMinPhysicsRate) + ", " + formatNumber(kMaxPhysicsRate) + "] Hz"},
          {"mode", joined(modes(), "|")},
          {"ray_caster_threads", ">= 0 (0 = every hardware thread)"}};
}

sensors::SensorSelection checkSettings(const EngineSettings& s, const sensors::SensorFactory& models,
                                       const SettingSpelling& spelling) {
  const auto rules = settingRules(models);
  const auto rule = [&](const std::string& name) {
    return std::find_if(rules.begin(), rules.end(), [&](const auto& r) { return r.first == name; })->second;
  };
  const auto bad = [&](const std::string& name, const std::string& value, const std::string& expected) {
    return settingError(spelling, name, value, expected);
  };
  if (s.spawns.empty() && (s.robots < 1 || s.robots > kMaxRobots))
    throw bad("robots", std::to_string(s.robots), rule("robots"));
  if (s.seed < 0)
    throw bad("seed", std::to_string(s.seed), rule("seed"));
  if (!(s.physics_rate >= kMinPhysicsRate && s.physics_rate <= kMaxPhysicsRate))
    throw bad("physics_rate", formatNumber(s.physics_rate), rule("physics_rate"));
  if (std::find(modes().begin(), modes().end(), s.mode) == modes().end())
    throw bad("mode", "'" + s.mode + "'", rule("mode"));
  const auto& levels = sim::visibilityLevels();
  if (!s.visibility.empty() && std::find(levels.begin(), levels.end(), s.visibility) == levels.end())
    throw bad("visibility", "'" + s.visibility + "'", rule("visibility"));
  if (s.ray_caster_threads < 0)
    throw bad("ray_caster_threads", std::to_string(s.ray_caster_threads), rule("ray_caster_threads"));
  return sensors::SensorSelection::parse(s.sensors, models.types(),
                                         spelling ? spelling("sensors") : std::string("sensors"));
}

EnginePlan planEngine(const EngineSettings& s, const sensors::SensorFactory& models, const SettingSpelling& spelling) {
  const sensors::SensorSelection selection = checkSettings(s, models, spelling);
  const auto bad = [&](const std::string& name, const std::string& value, const std::string& expected) {
    return settingError(spelling, name, value, expected);
  };
  EnginePlan plan;
  plan.options.dt = 1.0 / s.physics_rate;
  plan.options.seed = static_cast<std::uint64_t>(s.seed);
  plan.options.selection = selection;
  plan.options.visual = s.mode == "visual";
  plan.options.ray_caster_threads = s.ray_caster_threads;

  plan.config = sim::loadWorldConfig(s.world_file);
  if (!s.visibility.empty())
    plan.config.visibility = s.visibility;  // before the world (and every sensor) sees it
  if (plan.config.visibility == "water" && !plan.config.water_column)
    throw bad("visibility", "'water'",
              "a world whose water has a profile (its turbidity by depth): " + s.world_file + " has none");
  int count = s.robots;
  if (!s.spawns.empty()) {
    sim::selectRobots(plan.config, s.spawns);
    count = static_cast<int>(s.spawns.size());
  }
  if (count > static_cast<int>(plan.config.robots.size()))
    throw bad("robots", std::to_string(count),
              "at most " + std::to_string(plan.config.robots.size()) + " (spawn poses in " + s.world_file + ")");
  for (int i = 0; i < count; ++i)
    plan.robots.push_back(plan.config.robots[i].name);
  return plan;
}

}  // namespace engine
}  // namespace unexmin
