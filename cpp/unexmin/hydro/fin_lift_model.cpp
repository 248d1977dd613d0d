#include <unexmin/hydro/fin_lift_model.h>

#include <cmath>
#include <limits>

namespace unexmin {
namespace hydro {
namespace {

const char* const kLinearLift = "fin model 'linear_lift'";

void requireNonNegative(const char* key, double value, const char* unit) {
  if (!std::isfinite(value) || value < 0.0)
    throw ParameterError(std::string(kLinearLift) + ": parameter '" + key + "' = " + formatNumber(value) +
                         " must be finite and >= 0 " + unit);
}

}  // namespace

LinearLift::LinearLift(double lift_slope, double drag0, double induced)
    : lift_slope_(lift_slope), drag0_(drag0), induced_(induced) {
  requireNonNegative("lift_slope", lift_slope, "[1/rad]");
  requireNonNegative("drag0", drag0, "[-]");
  requireNonNegative("induced", induced, "[-]");
}

LinearLift::LinearLift(ActuatorFamilyParams& params)
    : LinearLift(params.scalar("lift_slope"), params.scalar("drag0"), params.scalar("induced")) {}

double LinearLift::drag(double alpha) const {
  const double cl = lift(alpha);
  return drag0_ + induced_ * cl * cl;
}

}  // namespace hydro
}  // namespace unexmin
