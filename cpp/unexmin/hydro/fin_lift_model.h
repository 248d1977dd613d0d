// Lift and drag coefficients of a control surface against its angle of attack: a family chosen by the name in the
// robot description (<fin><model type="linear_lift">), built by a FinFactory (fin_factory.h).
#pragma once

#include <unexmin/hydro/actuator_family_params.h>

namespace unexmin {
namespace hydro {

/// Lift and drag coefficients of a fin [-] at angle of attack `alpha` [rad] (positive: the flow meets the fin's
/// +normal side, lift towards its +normal).
class FinLiftModel {
public:
  virtual ~FinLiftModel() = default;
  virtual double lift(double alpha) const = 0;
  virtual double drag(double alpha) const = 0;
};

/// "linear_lift": C_L = lift_slope * alpha, C_D = drag0 + induced * C_L^2 (thin-aerofoil lift with a drag polar; no
/// stall). Parameters: lift_slope [1/rad] >= 0, drag0 [-] >= 0, induced [-] >= 0.
class LinearLift : public FinLiftModel {
public:
  LinearLift(double lift_slope, double drag0, double induced);
  explicit LinearLift(ActuatorFamilyParams& params);
  double lift(double alpha) const override { return lift_slope_ * alpha; }
  double drag(double alpha) const override;

private:
  double lift_slope_;
  double drag0_;
  double induced_;
};

}  // namespace hydro
}  // namespace unexmin
