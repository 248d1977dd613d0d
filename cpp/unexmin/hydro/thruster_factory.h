// Thruster models by family name: the type of <dynamics type="..."> and <conversion type="..."> in the robot
// description. ThrusterFactory::builtin() registers the simulator's families (thruster_factory.cpp, one line
// each); a program or a test adds its own to a copy and hands it to sim::parseRobotDescription.
// See docs/adding_a_thruster.md.
#pragma once

#include <unexmin/hydro/actuator_family_factory.h>
#include <unexmin/hydro/thruster_models.h>

namespace unexmin {
namespace hydro {

/// Both kinds of a thruster's models, by family name.
struct ThrusterFactory {
  ActuatorFamilyFactory<ThrusterDynamics> dynamics{"thruster dynamics"};
  ActuatorFamilyFactory<ThrustConversion> conversion{"thrust conversion"};

  /// The simulator's families: dynamics zero_order, first_order; conversion identity, basic, table
  /// (docs/hydrodynamics.md).
  static ThrusterFactory builtin();
};

}  // namespace hydro
}  // namespace unexmin
