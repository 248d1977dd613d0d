// What a front end asks of the engine, as its user spells it: the simulator node's ~parameters and unexmin.core's
// World arguments are the same settings, checked here once (ranges and choices: settingRules(); the visibility
// levels are the world schema's). The front ends translate their own spelling and never check again.
#pragma once

#include <unexmin/core/error.h>
#include <unexmin/engine/engine.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace unexmin {
namespace engine {

/// A setting out of its domain: what() is "<spelling> = <value>: expected <expected>", `spelling` the setting's name as
/// the front end's user writes it (e.g. "parameter ~robots"); name() is the setting's own.
class SettingError : public ConfigError {
public:
  SettingError(std::string name, const std::string& spelling, std::string value, std::string expected);
  const std::string& name() const { return name_; }
  const std::string& value() const { return value_; }
  const std::string& expected() const { return expected_; }

private:
  std::string name_, value_, expected_;
};

struct EngineSettings {
  std::string world_file;            ///< path of a world file (YAML, docs/worlds.md)
  int robots = 1;                    ///< how many of the world's robots run, the first ones (when `spawns` is empty)
  std::vector<std::string> spawns;   ///< the world's robots to run by name, in this order (sim::selectRobots)
  std::int64_t seed = 0;             ///< seed of every random generator, >= 0
  std::string sensors = "all";       ///< "all", "none" or families "imu,dvl,..." (sensors::SensorSelection)
  std::string visibility;            ///< a visibility level of the world schema, "" = the world file's
  double physics_rate = 500.0;       ///< [Hz] in [kMinPhysicsRate, kMaxPhysicsRate]
  std::string mode = "operational";  ///< operational|visual (cameras render, lights and lasers on)
  int ray_caster_threads = 0;        ///< >= 0 (0 = every hardware thread)
};

constexpr int kMaxRobots = 3;                ///< robots `robots` may ask for (a `spawns` list may name more)
constexpr double kMinPhysicsRate = 100.0;    ///< [Hz]
constexpr double kMaxPhysicsRate = 20000.0;  ///< [Hz]

/// The modes a world runs in: operational (fastest), visual.
const std::vector<std::string>& modes();

/// Each setting's rule as the error messages state it, by name (robots, seed, sensors, visibility, physics_rate,
/// mode, ray_caster_threads): e.g. "physics_rate" -> "[100, 20000] Hz".
std::vector<std::pair<std::string, std::string>> settingRules(const sensors::SensorFactory& models);

/// A world ready to be built: the world file with the settings applied (visibility, the robots to run first), the
/// engine's options and the names of the robots to run, in order.
struct EnginePlan {
  sim::WorldConfig config;
  EngineOptions options;
  std::vector<std::string> robots;
};

/// How a front end's user writes setting `name` in an error ("robots" -> "parameter ~robots"); null: as it is.
using SettingSpelling = std::function<std::string(const std::string& name)>;

/// Checks every setting but the world file's (SettingError naming the first one out of its domain as `spelling` writes
/// it; the robot count against the world's spawns is planEngine's). Returns the sensor families `sensors` selects.
sensors::SensorSelection checkSettings(const EngineSettings& settings, const sensors::SensorFactory& models,
                                       const SettingSpelling& spelling = nullptr);

/// Checks every setting (SettingError naming the first one out of its domain as `spelling` writes it), loads the world
/// file (ConfigError naming it) and applies them. `models`: the sensor families `sensors` may name.
EnginePlan planEngine(const EngineSettings& settings, const sensors::SensorFactory& models,
                      const SettingSpelling& spelling = nullptr);

}  // namespace engine
}  // namespace unexmin
