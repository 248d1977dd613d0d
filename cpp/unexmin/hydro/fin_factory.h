// Fin lift models by family name: the type of <model type="..."> inside a robot description's <fin>.
// FinFactory::builtin() registers the simulator's families (fin_factory.cpp, one line each); a program or a test adds
// its own to a copy and hands it to sim::parseRobotDescription. Same mechanism as the thrusters' families
// (ActuatorFamilyFactory, actuator_family_factory.h).
#pragma once

#include <unexmin/hydro/actuator_family_factory.h>
#include <unexmin/hydro/fin_lift_model.h>

namespace unexmin {
namespace hydro {

struct FinFactory {
  ActuatorFamilyFactory<FinLiftModel> model{"fin model"};

  /// The simulator's families: linear_lift (docs/hydrodynamics.md, "Fins").
  static FinFactory builtin();
};

}  // namespace hydro
}  // namespace unexmin
