// The simulator's fin lift families: one line each (docs/hydrodynamics.md, "Fins").
#include <unexmin/hydro/fin_factory.h>

namespace unexmin {
namespace hydro {

FinFactory FinFactory::builtin() {
  FinFactory f;
  f.model.add<LinearLift>("linear_lift");
  return f;
}

}  // namespace hydro
}  // namespace unexmin
