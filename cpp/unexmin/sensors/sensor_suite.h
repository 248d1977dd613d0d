// The sensors of one robot: built from its description by a SensorFactory (every <sensor> of a selected
// family; an unknown type stops construction), reset with the world's seed, updated after every physics step.
// Ray-cast sensors cast through the world's caster, which its owner (the simulator, a test) updates after each
// physics step, before update().
#pragma once

#include <unexmin/sensors/sensor_factory.h>
#include <unexmin/sensors/sensor_selection.h>

#include <memory>
#include <vector>

namespace unexmin {
namespace sensors {

class SensorSuite {
public:
  /// `world`, `robot` and `rays` (null: rays hit nothing) must outlive the suite. Throws ConfigError when the
  /// robot is not in the world, on a sensor of unknown type (naming the robot, the sensor and the known types;
  /// whether selected or not) and on a bad sensor parameter. Sensors of families `selection` leaves out are
  /// not built (listed by skipped()). Resets every sensor with world.seed().
  /// `visual`: the simulator's visual mode (SensorSetup::visual).
  SensorSuite(const sim::World& world, sim::Robot& robot, const raycast::RayCaster* rays, const SensorFactory& factory,
              const SensorSelection& selection = SensorSelection(), bool visual = false);

  /// Back to t = 0 with the world's seed `seed` (after World::reset).
  void reset(std::uint64_t seed);
  /// After every physics step; fresh(i) then tells whether sensor i took a sample at this step. Then the robot
  /// carries what its sensors carry (Sensor::carriedMass, each at its mount): sim::Robot::setPayloadMass.
  void update();

  std::size_t size() const { return sensors_.size(); }
  Sensor& sensor(std::size_t i) { return *sensors_.at(i); }
  const Sensor& sensor(std::size_t i) const { return *sensors_.at(i); }
  bool fresh(std::size_t i) const { return fresh_.at(i) != 0; }
  /// nullptr when the robot has no (built) sensor of that name.
  Sensor* find(const std::string& name);
  /// Names of the description's sensors left out by the selection.
  const std::vector<std::string>& skipped() const { return skipped_; }
  /// Every joint the sensors move, with its state now.
  std::vector<MovedJoint> movedJoints() const;
  /// Hands the robot the mass its sensors carry now (after update(), reset()).
  void applyCarriedMass();

private:
  const sim::World& world_;
  sim::Robot& robot_;
  const raycast::RayCaster* rays_;
  int robot_index_ = -1;
  std::vector<std::unique_ptr<Sensor>> sensors_;
  std::vector<char> fresh_;
  std::vector<std::string> skipped_;
};

}  // namespace sensors
}  // namespace unexmin
