// The sensors of one robot: built from its description by a SensorFactory, reset with the world's
// seed, updated after every physics step. Descriptions may also carry sensors of families this
// factory does not know (simulated elsewhere): they are listed by skipped(), not built.
#pragma once

#include "sensors/sensor_factory.h"

#include <memory>
#include <vector>

namespace unexmin {
namespace sensors {

class SensorSuite
{
public:
  /// `world` and `robot` must outlive the suite; `rays` (may be null: ray-cast sensors then never
  /// see a hit) answers the ray-cast sensors. Throws sim::ConfigError on a bad sensor parameter.
  /// Resets every sensor with world.seed().
  SensorSuite(const sim::World& world, const sim::Robot& robot, std::shared_ptr<const RayCaster> rays,
              const SensorFactory& factory = SensorFactory());

  /// Back to t = 0 with the world's seed `seed` (after World::reset).
  void reset(std::uint64_t seed);
  /// After every physics step; fresh(i) then tells whether sensor i took a sample at this step.
  void update();

  std::size_t size() const { return sensors_.size(); }
  Sensor& sensor(std::size_t i) { return *sensors_.at(i); }
  const Sensor& sensor(std::size_t i) const { return *sensors_.at(i); }
  bool fresh(std::size_t i) const { return fresh_.at(i) != 0; }
  /// nullptr when the robot has no sensor of that name.
  Sensor* find(const std::string& name);
  /// Names of the description's sensors whose type the factory does not know.
  const std::vector<std::string>& skipped() const { return skipped_; }

private:
  const sim::World& world_;
  const sim::Robot& robot_;
  std::shared_ptr<const RayCaster> rays_;
  std::vector<std::unique_ptr<Sensor>> sensors_;
  std::vector<char> fresh_;
  std::vector<std::string> skipped_;
};

}  // namespace sensors
}  // namespace unexmin
