// Buoyancy in a layered water column (docs/worlds.md, "Water column"): the robot's buoyancy uses the density of the
// water where it is, so a robot trimmed neutral above a halocline is buoyant below it and comes to rest at it.
// The density step is computed here from EOS-80's published check values' equation (water/seawater.h, tested
// against them in test_seawater.cpp).
#include "sphere_fixture.h"

#include <unexmin/water/seawater.h>
#include <unexmin/water/water_column.h>

#include <gtest/gtest.h>

using unexmin::test::makeWorld;
using unexmin::test::openWater;
using unexmin::test::runFor;
using unexmin::test::SphereSpec;
namespace sim = unexmin::sim;
namespace water = unexmin::water;

namespace {

constexpr double kG = 9.81;
constexpr double kHalocline = 20.0;  // [m] below the surface
constexpr double kT = 10.0;          // [degC] above and below
constexpr double kSalinityBelow = 5.0;

/// Fresh water over water of salinity 5, both at 10 degC, a step at 20 m.
std::shared_ptr<const water::WaterColumn> halocline() {
  water::Profile p;
  for (const auto& ds : {std::pair<double, double>{0.0, 0.0},
                         {kHalocline, 0.0},
                         {kHalocline, kSalinityBelow},
                         {100.0, kSalinityBelow}}) {
    water::WaterRow r;
    r.depth = ds.first;
    r.temperature = kT;
    r.salinity = ds.second;
    p.rows.push_back(r);
  }
  water::checkProfile(p, "water.profile");
  return std::make_shared<const water::WaterColumn>(p, std::vector<water::Region>{}, 0.0, kG);
}

/// EOS-80 at the depth the column takes its pressure from (1e-4 * 1000 kg/m^3 * g * depth [dbar]).
double densityAt(double salinity, double depth) {
  return water::density(salinity, kT, 1e-4 * 1000.0 * kG * depth);
}

}  // namespace

TEST(WaterBuoyancy, ARobotTrimmedAboveAHaloclineRisesBelowIt) {
  SphereSpec s;
  s.rho = densityAt(0.0, kHalocline);  // neutral in the fresh water just above the step
  s.mass = s.rho * s.volume();
  s.added_mass = 0.5 * s.rho * s.volume();
  const double start = 35.0;
  sim::WorldConfig layered = openWater(s, Eigen::Vector3d(0, 0, -start));
  layered.water_column = halocline();
  auto world = makeWorld(layered, s);

  // below the step it is pushed up by (rho_below - rho_trim) V g: about 0.4 % of its weight
  world->step();
  const double lift = (densityAt(kSalinityBelow, start) - s.rho) * s.volume() * kG;
  const double m = world->robot(0).totalMass();
  EXPECT_GT(lift, 0.003 * m * kG);
  EXPECT_NEAR(world->robot(0).state().linear_acceleration.z(), lift / (m + s.added_mass), 0.02 * lift / m);
  // in water of one density (a world without a column) the same robot does not move
  auto still = makeWorld(openWater(s, Eigen::Vector3d(0, 0, -start)), s);
  still->step();
  EXPECT_NEAR(still->robot(0).state().linear_acceleration.z(), 0.0, 1e-3 * lift / m);

  // it rises at the terminal speed of that lift, d_q v^2 + d_l v = lift, while below the step
  runFor(*world, 30.0);
  const double z = world->robot(0).state().pose.translation().z();
  ASSERT_LT(z, -kHalocline - 1.0) << "still below the step";
  const double f = (densityAt(kSalinityBelow, -z) - s.rho) * s.volume() * kG;
  const double dq = s.quad[2], dl = s.lin[2];
  const double v = (-dl + std::sqrt(dl * dl + 4.0 * dq * f)) / (2.0 * dq);
  EXPECT_NEAR(world->robot(0).state().linear_velocity.z(), v, 0.01 * v);

  // past the step its lift is gone: above it the water is as light as its trim (less 0.005 kg/m^3 per metre)
  runFor(*world, 120.0);
  EXPECT_GT(world->robot(0).state().pose.translation().z(), -kHalocline);
  EXPECT_LT(world->robot(0).restoringWrench().head<3>().norm(), 0.03 * lift);
}
