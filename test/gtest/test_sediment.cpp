// The thrusters' silt (cpp/unexmin/sim/sediment.h) against closed forms computed here: a puff's optical depth along
// a ray (against a numerical integral of its scattering), merging by moments, drift with the current, sinking and
// spreading, removal once settled, bad parameters; and the camera's per-frame view of it (sensors/vision/silt_view.h)
// against the exact optical depth along pixel rays.
#include <unexmin/sensors/vision/silt_view.h>
#include <unexmin/sim/sediment.h>
#include "expect_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sim::SedimentField;
using sim::SedimentParams;

SedimentParams params() {
  SedimentParams p;
  p.enabled = true;
  p.settling_speed = 0.01;
  p.puff_size = 0.3;
  p.diffusivity = 1e-3;
  return p;
}

/// Optical depth by the midpoint rule over the field's scattering coefficient.
double integrate(const SedimentField& f, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double length) {
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    sum += f.scattering(o + (i + 0.5) * length / n * d);
  return sum * length / n;
}

TEST(Sediment, OpticalDepthAlongARayIsTheIntegralOfTheScattering) {
  SedimentField f(params());
  f.add(Eigen::Vector3d(1.0, 0.2, -0.1), 0.5, -10.0);
  f.add(Eigen::Vector3d(2.0, -0.4, 0.3), 0.2, -10.0);
  ASSERT_EQ(f.puffs().size(), 2u);
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d d : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 0.2, -0.1).normalized(),
                                  Eigen::Vector3d(0.8, -0.3, 0.2).normalized(), Eigen::Vector3d(0, 0, 1)})
    for (const double length : {0.5, 1.0, 2.5, 6.0}) {
      const double exact = integrate(f, o, d, length);
      EXPECT_NEAR(f.opticalDepth(o, d, length), exact, 1e-6 + 1e-6 * exact) << d.transpose() << " " << length;
    }
  // Many lengths at once: the same numbers.
  const float lengths[5] = {0.1f, 0.9f, 1.5f, 2.2f, 7.0f};
  double many[5];
  const Eigen::Vector3d d = Eigen::Vector3d(1, 0.1, 0.0).normalized();
  f.opticalDepths(o, d, lengths, 5, many);
  for (int j = 0; j < 5; ++j)
    EXPECT_NEAR(many[j], f.opticalDepth(o, d, lengths[j]), 1e-9);
  // Through a puff's centre and far beyond: Q / (2 pi sigma^2).
  SedimentField one(params());
  one.add(Eigen::Vector3d(3, 0, 0), 0.4, -10.0);
  EXPECT_NEAR(one.opticalDepth(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0), 100.0), 0.4 / (2 * M_PI * 0.09),
              1e-9);
  EXPECT_NEAR(one.scattering(Eigen::Vector3d(3, 0, 0)), 0.4 / (std::pow(2 * M_PI, 1.5) * 0.027), 1e-9);
}

TEST(Sediment, NearbyPuffsMergeByTheirMoments) {
  SedimentField f(params());
  f.add(Eigen::Vector3d(0, 0, 0), 0.3, -5.0);
  f.add(Eigen::Vector3d(0.2, 0, 0), 0.3, -5.0);  // nearer than puff_size: one puff
  ASSERT_EQ(f.puffs().size(), 1u);
  const auto& p = f.puffs()[0];
  EXPECT_NEAR(p.strength, 0.6, 1e-12);
  EXPECT_NEAR((p.centre - Eigen::Vector3d(0.1, 0, 0)).norm(), 0.0, 1e-12);
  // Each puff 0.1 m from the merged centre: sigma^2 = s0^2 + 0.1^2 / 3.
  EXPECT_NEAR(p.sigma * p.sigma, 0.09 + 0.01 / 3, 1e-12);
  f.add(Eigen::Vector3d(1.0, 0, 0), 0.1, -5.0);  // farther: a second puff
  EXPECT_EQ(f.puffs().size(), 2u);
  f.add(Eigen::Vector3d(0, 0, 0), 0.0, -5.0);  // nothing raised: nothing added
  EXPECT_EQ(f.puffs().size(), 2u);
}

TEST(Sediment, PuffsDriftSinkSpreadAndGoOnceSettled) {
  const SedimentParams p = params();
  SedimentField f(p);
  const Eigen::Vector3d c0(0, 0, -1.7), current(0.05, -0.02, 0.0);
  f.add(c0, 0.5, -2.0);  // raised 0.3 m above a floor at z = -2
  double t = 0.0;
  const double dt = 0.01;
  for (int i = 0; i < 1000; ++i, t += dt)
    f.evolve(dt, current);
  ASSERT_EQ(f.puffs().size(), 1u);
  const auto& q = f.puffs()[0];
  EXPECT_NEAR((q.centre - (c0 + t * current - Eigen::Vector3d(0, 0, p.settling_speed * t))).norm(), 0.0, 1e-9);
  EXPECT_NEAR(q.sigma * q.sigma, 0.09 + 2 * p.diffusivity * t, 1e-9);
  EXPECT_NEAR(q.strength, 0.5, 1e-12);
  // Gone once its centre is kGone sigma below the floor: (0.3 + 3 sigma(t)) / w_s, sigma growing meanwhile.
  double gone = -1.0;
  for (int i = 0; i < 100000 && !f.empty(); ++i, t += dt) {
    f.evolve(dt, current);
    if (f.empty())
      gone = t + dt;
  }
  ASSERT_GT(gone, 0.0);
  const double sigma = std::sqrt(0.09 + 2 * p.diffusivity * gone);
  EXPECT_NEAR(gone, (0.3 + SedimentField::kGone * sigma) / p.settling_speed, 2 * dt);
}

TEST(Sediment, BadParametersNameTheKey) {
  const std::vector<std::pair<std::string, std::function<void(SedimentParams&)>>> bad{
      {"sediment.settling_speed", [](SedimentParams& p) { p.settling_speed = -0.1; }},
      {"sediment.reach", [](SedimentParams& p) { p.reach = 0.0; }},
      {"sediment.max_puffs", [](SedimentParams& p) { p.max_puffs = 0; }}};
  for (const auto& b : bad) {
    SedimentParams p = params();
    b.second(p);
    const std::string m = thrownMessage<ConfigError>([&] { sim::validate(p, "w.world"); });
    EXPECT_TRUE(contains(m, b.first) && contains(m, "w.world")) << m;
  }
  EXPECT_NO_THROW(sim::validate(params(), "w.world"));
}

TEST(Sediment, TheCamerasViewInterpolatesTheOpticalDepthAlongPixelRays) {
  using namespace sensors::vision;
  const CameraModel camera(160, 120, 100.0, 100.0, 79.5, 59.5, {-0.1, 0.02, 0, 0, 0});
  LedLight l;
  l.axis = Eigen::Vector3d(0, 0, 1);
  const ImageFormation formation(camera, {l}, WaterOptics::fromVisibility("low", Eigen::Vector3d(0.25, 0.3, 0.2)), 10.0,
                                 1);
  SiltView view(camera, formation);
  SedimentField f(params());
  EXPECT_FALSE(view.update(f, Eigen::Isometry3d::Identity()));  // no silt: nothing to see
  f.add(Eigen::Vector3d(0.2, 0.1, 1.2), 0.4, -10.0);
  f.add(Eigen::Vector3d(-0.5, -0.2, 2.5), 0.3, -10.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the optical frame = the world's axes
  ASSERT_TRUE(view.update(f, pose));
  double worst = 0.0;
  for (int v = 3; v < 120; v += 13)
    for (int u = 5; u < 160; u += 17)
      for (const double r : {0.7, 1.2, 2.0, 3.3}) {
        const double exact = f.opticalDepth(Eigen::Vector3d::Zero(), camera.ray(u, v), r);
        const double got = view.opticalDepth(static_cast<float>(u), static_cast<float>(v), static_cast<float>(r));
        worst = std::max(worst, std::abs(got - exact) / (0.02 + exact));
      }
  EXPECT_LT(worst, 0.1);  // bilinear over 16 px and linear over range bins, against a smooth field
  // Far from the silt (beyond max_range + 4 sigma) the camera sees none.
  pose.translation() = Eigen::Vector3d(0, 0, -20);
  EXPECT_FALSE(view.update(f, pose));
}

}  // namespace
}  // namespace test
}  // namespace unexmin
