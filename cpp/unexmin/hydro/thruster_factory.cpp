// The simulator's thruster families: one line each (docs/hydrodynamics.md). Adding a family:
// docs/adding_a_thruster.md.
#include <unexmin/hydro/thruster_factory.h>

namespace unexmin {
namespace hydro {

ThrusterFactory ThrusterFactory::builtin() {
  ThrusterFactory f;
  f.dynamics.add<ZeroOrderDynamics>("zero_order");
  f.dynamics.add<FirstOrderDynamics>("first_order");
  f.conversion.add<IdentityConversion>("identity");
  f.conversion.add<BasicConversion>("basic");
  f.conversion.add<TableConversion>("table");
  return f;
}

}  // namespace hydro
}  // namespace unexmin
