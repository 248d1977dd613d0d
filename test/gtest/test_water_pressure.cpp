// Pressure through the water column (water::WaterColumn::hydrostaticPressure, sensors::hydrostaticPressure): the
// density integrated from the free surface down to the point, against closed forms computed here from EOS-80
// (water/seawater.h, held to UNESCO's check values in test_seawater.cpp): two layers, a linear profile against the
// trapezoid rule and its error bound, a region and a heaving boundary against a fine Simpson sum; the pressure sensor
// reading it; and the cost of one call (printed, not asserted).
#include <unexmin/sensors/pressure_sensor.h>
#include <unexmin/water/seawater.h>
#include <unexmin/water/water_column.h>
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

namespace unexmin {
namespace test {
namespace {

constexpr double kG = 9.80665;
constexpr double kSurface = 2.0;  // [m] world z of the free surface

water::WaterRow row(double depth, double temperature, double salinity) {
  water::WaterRow r;
  r.depth = depth;
  r.temperature = temperature;
  r.salinity = salinity;
  return r;
}

water::Profile profile(std::vector<water::WaterRow> rows, bool layers) {
  water::Profile p;
  p.rows = std::move(rows);
  p.layers = layers;
  water::checkProfile(p, "water.profile");
  return p;
}

/// EOS-80 at `depth` as the column takes its pressure (1e-4 * 1000 kg/m^3 * g * depth [dbar]).
double rho(double salinity, double temperature, double depth) {
  return water::density(salinity, temperature, 1e-4 * 1000.0 * kG * depth);
}

/// Composite Simpson of f over [a, b] in n (even) intervals, its ends taken 1 nm inside: at a step or a region's face
/// the density holds the side the interval lies on.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  a += 1e-9;
  b -= 1e-9;
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i)
    s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

TEST(WaterPressure, TwoLayersAddTheirWeights) {
  // fresh water of 8 degC over 20 m, salinity 5 at 16 degC below: layers, a step at h1
  const double h1 = 20.0, s1 = 0.0, t1 = 8.0, s2 = 5.0, t2 = 16.0;
  const water::WaterColumn c(profile({row(0.0, t1, s1), row(h1, t2, s2), row(100.0, t2, s2)}, /*layers=*/true), {},
                             kSurface, kG);
  for (const double depth : {5.0, 20.0, 35.0, 80.0, 140.0}) {
    const Eigen::Vector3d point(3.0, -4.0, kSurface - depth);
    // each layer's mean density over the stretch the point lies below: inside a layer only EOS-80's rise with
    // pressure varies it, a quadratic in depth (to 1e-12 over these depths), whose mean over [a, b] is Simpson's
    // (rho(a) + 4 rho(middle) + rho(b)) / 6
    const double above = std::min(depth, h1), below = std::max(0.0, depth - h1);
    auto mean = [](double s, double t, double a, double b) {
      return (rho(s, t, a) + 4.0 * rho(s, t, 0.5 * (a + b)) + rho(s, t, b)) / 6.0;
    };
    const double rho1 = mean(s1, t1, 0.0, above), rho2 = mean(s2, t2, h1, h1 + below);
    const double expected = kG * (rho1 * above + rho2 * below);
    EXPECT_NEAR(c.hydrostaticPressure(point, 0.0), expected, 1e-6 * (101325.0 + expected)) << depth << " m";
    EXPECT_NEAR(c.hydrostaticPressure(point, 0.0), expected, 1e-9 * expected) << depth << " m";
    // not the surface's density times the depth: the lower layer is 3.6 kg/m^3 heavier
    if (below > 0.0)
      EXPECT_GT(std::abs(c.hydrostaticPressure(point, 0.0) - kG * rho(s1, t1, 0.0) * depth), 1e-4 * expected);
  }
  EXPECT_EQ(c.hydrostaticPressure(Eigen::Vector3d(0, 0, kSurface + 1.0), 0.0), 0.0);  // above the surface
  EXPECT_EQ(c.hydrostaticPressure(Eigen::Vector3d(0, 0, kSurface), 0.0), 0.0);
}

TEST(WaterPressure, ALinearProfileMatchesTheTrapezoidRuleWithinItsErrorBound) {
  // temperature 4 -> 12 degC and salinity 0 -> 2 linear over 60 m, then 12 -> 20 degC and 2 -> 8 over 90 m
  const std::vector<water::WaterRow> rows{row(0.0, 4.0, 0.0), row(60.0, 12.0, 2.0), row(150.0, 20.0, 8.0)};
  const water::WaterColumn c(profile(rows, false), {}, kSurface, kG);
  const double depth = 150.0;
  const Eigen::Vector3d point(0.0, 0.0, kSurface - depth);
  // trapezoid closed form over the rows: exact for a density linear in depth between rows
  double trapezoid = 0.0, bound = 0.0;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const water::WaterRow &a = rows[i], &b = rows[i + 1];
    const double h = b.depth - a.depth;
    trapezoid += 0.5 * h * (rho(a.salinity, a.temperature, a.depth) + rho(b.salinity, b.temperature, b.depth));
    // |error| <= h^3 / 12 max |rho''|: EOS-80 is not linear in T and S; rho'' by central differences along the
    // segment
    double curvature = 0.0;
    for (int k = 1; k < 20; ++k) {
      const double d = a.depth + h * k / 20.0, e = 0.5;
      auto at = [&](double x) {
        const double w = (x - a.depth) / h;
        return rho(a.salinity + w * (b.salinity - a.salinity), a.temperature + w * (b.temperature - a.temperature), x);
      };
      curvature = std::max(curvature, std::abs(at(d + e) - 2.0 * at(d) + at(d - e)) / (e * e));
    }
    bound += h * h * h / 12.0 * curvature;
  }
  const double p = c.hydrostaticPressure(point, 0.0);
  EXPECT_NEAR(p, kG * trapezoid, kG * 1.2 * bound);
  // and the trapezoid's error is real: the integral is nearer a fine Simpson sum of the column's own density
  auto density = [&](double d) { return c.densityAt(Eigen::Vector3d(0.0, 0.0, kSurface - d), 0.0); };
  const double fine = kG * (simpson(density, 0.0, 60.0, 20000) + simpson(density, 60.0, 150.0, 20000));
  EXPECT_NEAR(p, fine, 1e-8 * fine);
  std::printf(
      "[ linear  ] 150 m: Gauss-Legendre %.6f Pa, fine Simpson %.6f Pa (rel. %.2e), trapezoid %.6f Pa "
      "(rel. %.2e, bound %.2e)\n",
      p, fine, std::abs(p - fine) / fine, kG * trapezoid, std::abs(p - kG * trapezoid) / p, kG * bound / p);
}

TEST(WaterPressure, FollowsRegionsAndAHeavingBoundaryAlongTheVertical) {
  water::Profile world_water =
      profile({row(0.0, 10.0, 0.0), row(30.0, 14.0, 1.0), row(30.0, 16.0, 6.0), row(120.0, 18.0, 7.0)}, false);
  world_water.boundary.enabled = true;
  world_water.boundary.depth = 30.0;
  world_water.boundary.amplitude = 4.0;
  world_water.boundary.period = 600.0;
  world_water.boundary.phase = 0.3;
  water::checkProfile(world_water, "water.profile");
  water::Region box;  // salt water in a box from 50 to 80 m below the surface around x, y = 0
  box.box = Eigen::AlignedBox3d(Eigen::Vector3d(-5, -5, kSurface - 80.0), Eigen::Vector3d(5, 5, kSurface - 50.0));
  box.profile = profile({row(0.0, 20.0, 30.0)}, false);
  const water::WaterColumn c(world_water, {box}, kSurface, kG);
  const double time = 170.0, depth = 100.0;
  for (const double x : {0.0, 20.0}) {  // through the box, beside it
    const Eigen::Vector3d point(x, 1.0, kSurface - depth);
    auto density = [&](double d) { return c.densityAt(Eigen::Vector3d(x, 1.0, kSurface - d), time); };
    // the heaved step, then the box's faces: a fine Simpson sum on each piece
    const double moved = 30.0 + 4.0 * std::sin(2.0 * M_PI * time / 600.0 + 0.3);
    std::vector<double> cuts{0.0, moved, depth};
    if (x == 0.0)
      cuts = {0.0, moved, 50.0, 80.0, depth};
    double fine = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
      fine += kG * simpson(density, cuts[i], cuts[i + 1], 20000);
    EXPECT_NEAR(c.hydrostaticPressure(point, time), fine, 1e-8 * fine) << "x = " << x;
    std::printf("[ regions ] x = %2.0f m: %.6f Pa, fine Simpson %.6f Pa (rel. %.2e)\n", x,
                c.hydrostaticPressure(point, time), fine, std::abs(c.hydrostaticPressure(point, time) - fine) / fine);
  }
  // the box adds the weight of its brine: about 30 m x 25 kg/m^3 more than beside it
  const double through = c.hydrostaticPressure(Eigen::Vector3d(0, 1, kSurface - depth), time);
  const double beside = c.hydrostaticPressure(Eigen::Vector3d(20, 1, kSurface - depth), time);
  EXPECT_GT(through - beside, kG * 30.0 * 15.0);
}

TEST(WaterPressure, TheSensorsReadTheColumnAndWorldsWithoutOneAreUnchanged) {
  SphereSpec s;
  sim::WorldConfig config = openWater(s, Eigen::Vector3d(0, 0, -40.0));
  config.gravity = kG;
  config.surface_z = kSurface;
  const std::string urdf = sensorUrdf(s, mountLink("T/pressure_link", Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                                      sensorXml("pressure", "pressure", "T/pressure_link", 500.0, {{"noise", "none"}}));
  {  // no column: p_atm + rho g depth, the same double as ever
    SensorWorld w(config, urdf);
    w.step();
    const double z = w.robot().state().pose.translation().z();
    EXPECT_EQ(sensors::hydrostaticPressure(*w.world, Eigen::Vector3d(7.0, 8.0, z)),
              config.atmospheric_pressure + s.rho * kG * std::max(0.0, kSurface - z));
    EXPECT_EQ(w.sensor<sensors::PressureSensor>("pressure").last().pressure,
              config.atmospheric_pressure + s.rho * kG * std::max(0.0, kSurface - z));
  }
  config.water_column = std::make_shared<const water::WaterColumn>(
      profile({row(0.0, 8.0, 0.0), row(20.0, 16.0, 5.0), row(100.0, 16.0, 5.0)}, true), std::vector<water::Region>{},
      kSurface, kG);
  SensorWorld w(config, urdf);
  w.step();
  const Eigen::Vector3d at = w.robot().state().pose.translation();
  const double expected = config.atmospheric_pressure + config.water_column->hydrostaticPressure(at, w.world->time());
  EXPECT_EQ(sensors::hydrostaticPressure(*w.world, at), expected);
  EXPECT_EQ(w.sensor<sensors::PressureSensor>("pressure").last().pressure, expected);
  const double depth = kSurface - at.z();
  EXPECT_NEAR(expected,
              config.atmospheric_pressure +
                  kG * (rho(0, 8, 10.0) * 20.0 + rho(5, 16, 20.0 + 0.5 * (depth - 20.0)) * (depth - 20.0)),
              1e-6 * expected);
}

TEST(WaterPressure, CostOfOneCall) {
  // a mine-like column: conductivity (PSS-78 at each node), a chemocline that heaves, one region
  water::Profile p;
  p.conductivity = true;
  for (const auto& r :
       std::vector<std::array<double, 3>>{{0, 12, 450}, {35, 11, 520}, {35, 16, 9000}, {150, 17, 9400}}) {
    water::WaterRow w;
    w.depth = r[0];
    w.temperature = r[1];
    w.conductivity = r[2];
    p.rows.push_back(w);
  }
  p.boundary = {true, 35.0, 0.5, 7200.0, 0.0};
  water::checkProfile(p, "water.profile");
  water::Region box;
  box.box = Eigen::AlignedBox3d(Eigen::Vector3d(-60, 80, -40), Eigen::Vector3d(-40, 120, 0));
  box.profile = profile({row(0.0, 9.0, 0.2)}, false);
  const water::WaterColumn c(p, {box}, 0.0, kG);
  for (const double depth : {10.0, 60.0, 200.0}) {
    const int n = 20000;
    double sum = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i)
      sum += c.hydrostaticPressure(Eigen::Vector3d(0.0, 0.0, -depth - 1e-6 * i), 1e-3 * i);
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / n;
    std::printf("[ cost    ] depth %5.0f m: %.0f ns per call (mean %.1f Pa)\n", depth, ns, sum / n);
    EXPECT_GT(sum, 0.0);
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin
