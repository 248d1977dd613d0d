// CurrentModel: bounded Gauss-Markov (Ornstein-Uhlenbeck) channels, seeded, against their
// closed-form statistics. No ROS: links the hydro core, Eigen and gtest only.
#include <unexmin/hydro/current.h>

#include "expect_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace unexmin {
namespace hydro {
namespace {

using unexmin::test::contains;
using unexmin::test::thrownMessage;

GaussMarkovParams channel(double mean, double min, double max, double noise, double mu) {
  GaussMarkovParams p;
  p.mean = mean;
  p.min = min;
  p.max = max;
  p.noise = noise;
  p.mu = mu;
  return p;
}

/// A mine current: 0.1 m/s mean, direction wandering around +x, nearly horizontal.
CurrentParams mineCurrent() {
  CurrentParams p;
  p.speed = channel(0.1, 0.0, 0.3, 0.02, 0.1);
  p.horizontal_angle = channel(0.0, -0.5, 0.5, 0.05, 0.2);
  p.vertical_angle = channel(0.0, -0.1, 0.1, 0.01, 0.5);
  return p;
}

struct Moments {
  double mean = 0.0;
  double variance = 0.0;
  double lag1 = 0.0;  ///< lag-one autocorrelation
};

Moments moments(const std::vector<double>& x) {
  Moments m;
  const double n = static_cast<double>(x.size());
  for (double v : x) {
    m.mean += v;
  }
  m.mean /= n;
  double cov = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    m.variance += (x[i] - m.mean) * (x[i] - m.mean);
    if (i > 0) {
      cov += (x[i] - m.mean) * (x[i - 1] - m.mean);
    }
  }
  m.variance /= n - 1.0;
  m.lag1 = cov / (n - 1.0) / m.variance;
  return m;
}

// ---------------------------------------------------------------------------------- determinism

TEST(CurrentModel, SameSeedGivesTheIdenticalSequence) {
  CurrentModel a(mineCurrent(), 42);
  CurrentModel b(mineCurrent(), 42);
  for (int i = 0; i < 2000; ++i) {
    a.update(0.05);
    b.update(0.05);
    // Bitwise equality is the point here: the same seed must replay the same run.
    ASSERT_EQ(a.speed(), b.speed()) << "step " << i;
    ASSERT_EQ(a.horizontalAngle(), b.horizontalAngle()) << "step " << i;
    ASSERT_EQ(a.verticalAngle(), b.verticalAngle()) << "step " << i;
    ASSERT_EQ(a.acceleration(), b.acceleration()) << "step " << i;
  }
}

TEST(CurrentModel, DifferentSeedsDiffer) {
  CurrentModel a(mineCurrent(), 1);
  CurrentModel b(mineCurrent(), 2);
  int differing = 0;
  for (int i = 0; i < 100; ++i) {
    a.update(0.05);
    b.update(0.05);
    differing += (a.speed() != b.speed()) ? 1 : 0;
  }
  EXPECT_GT(differing, 95);
  EXPECT_GT(std::abs(a.speed() - b.speed()) + std::abs(a.horizontalAngle() - b.horizontalAngle()), 1e-6);
}

TEST(CurrentModel, ResetWithTheSeedReplaysFromTheMeans) {
  CurrentModel model(mineCurrent(), 5);
  std::vector<double> first;
  for (int i = 0; i < 101; ++i)  // odd count: leaves a cached Box-Muller value behind
  {
    model.update(0.1);
    first.push_back(model.horizontalAngle());
  }
  model.reset(5);
  EXPECT_EQ(model.speed(), 0.1);
  EXPECT_EQ(model.acceleration(), Eigen::Vector3d::Zero());
  for (int i = 0; i < 101; ++i) {
    model.update(0.1);
    ASSERT_EQ(model.horizontalAngle(), first[i]) << "step " << i;
  }
}

TEST(CurrentModel, ZeroNoiseChannelsDoNotShiftTheOthers) {
  // Every update draws three normals in a fixed order, so silencing one channel leaves the
  // random sequence of the others unchanged.
  CurrentParams quiet = mineCurrent();
  quiet.speed.noise = 0.0;
  CurrentModel a(mineCurrent(), 9);
  CurrentModel b(quiet, 9);
  for (int i = 0; i < 500; ++i) {
    a.update(0.1);
    b.update(0.1);
    ASSERT_EQ(a.horizontalAngle(), b.horizontalAngle()) << "step " << i;
    ASSERT_EQ(a.verticalAngle(), b.verticalAngle()) << "step " << i;
  }
  EXPECT_EQ(b.speed(), 0.1);
}

// ------------------------------------------------------------------------------------ behaviour

TEST(CurrentModel, ValuesStayWithinTheBoundsAndReachThem) {
  CurrentParams p = mineCurrent();
  p.speed = channel(0.2, 0.1, 0.3, 0.5, 0.05);  // noise far larger than the band
  p.horizontal_angle = channel(1.0, 0.8, 1.2, 1.0, 0.0);
  p.vertical_angle = channel(-0.05, -0.1, 0.0, 0.3, 2.0);
  CurrentModel model(p, 123);
  bool at_min = false, at_max = false;
  for (int i = 0; i < 20000; ++i) {
    model.update(0.1);
    ASSERT_GE(model.speed(), 0.1);
    ASSERT_LE(model.speed(), 0.3);
    ASSERT_GE(model.horizontalAngle(), 0.8);
    ASSERT_LE(model.horizontalAngle(), 1.2);
    ASSERT_GE(model.verticalAngle(), -0.1);
    ASSERT_LE(model.verticalAngle(), 0.0);
    ASSERT_LE(model.velocity().norm(), 0.3 + 1e-12);
    at_min = at_min || model.speed() == 0.1;
    at_max = at_max || model.speed() == 0.3;
  }
  EXPECT_TRUE(at_min);  // the clamp is active, not just never reached
  EXPECT_TRUE(at_max);
}

TEST(CurrentModel, NoNoiseMeansAConstantCurrentAtTheMean) {
  CurrentParams p;
  p.speed = channel(0.2, 0.0, 1.0, 0.0, 0.3);
  p.horizontal_angle = channel(M_PI / 2.0, 0.0, M_PI, 0.0, 0.0);
  p.vertical_angle = channel(0.0, -0.2, 0.2, 0.0, 1.0);
  CurrentModel model(p, 77);
  for (int i = 0; i < 1000; ++i) {
    model.update(0.01);
    ASSERT_EQ(model.speed(), 0.2);
    ASSERT_EQ(model.acceleration(), Eigen::Vector3d::Zero());
  }
  // speed (cos v cos h, cos v sin h, sin v) with h = 90 deg, v = 0: along world +y.
  EXPECT_NEAR(model.velocity().x(), 0.0, 1e-15);
  EXPECT_NEAR(model.velocity().y(), 0.2, 1e-15);
  EXPECT_NEAR(model.velocity().z(), 0.0, 1e-15);

  // Elevated 30 deg towards -x: (-0.2 cos 30, 0, 0.2 sin 30).
  p.horizontal_angle = channel(M_PI, 0.0, M_PI, 0.0, 0.0);
  p.vertical_angle = channel(M_PI / 6.0, 0.0, 1.0, 0.0, 0.0);
  CurrentModel up(p, 1);
  EXPECT_NEAR(up.velocity().x(), -0.2 * std::cos(M_PI / 6.0), 1e-12);
  EXPECT_NEAR(up.velocity().y(), 0.0, 1e-12);
  EXPECT_NEAR(up.velocity().z(), 0.1, 1e-12);
}

TEST(CurrentModel, AccelerationIsTheVelocityChangeOverTheStep) {
  CurrentModel model(mineCurrent(), 31);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d before = model.velocity();
    model.update(0.2);
    const Eigen::Vector3d expected = (model.velocity() - before) / 0.2;
    ASSERT_LT((model.acceleration() - expected).norm(), 1e-12);
  }
  EXPECT_GT(model.acceleration().norm(), 0.0);
  const double speed = model.speed();
  model.update(0.0);  // no time: no change, no acceleration
  EXPECT_EQ(model.speed(), speed);
  EXPECT_EQ(model.acceleration(), Eigen::Vector3d::Zero());
  EXPECT_THROW(model.update(std::numeric_limits<double>::quiet_NaN()), ParameterError);
}

// ---------------------------------------------------------------------------------- statistics

TEST(CurrentModel, StationaryVarianceIsNoiseSquaredOverTwoMu) {
  // OU stationary law: variance noise^2 / (2 mu), lag-k correlation exp(-mu k dt). The bounds are
  // far away (over 30 sigma). dt = 1 s with mu = 0.5 is where an Euler-Maruyama step would be off
  // by a third (variance noise^2 dt / (1 - (1 - mu dt)^2) = 0.0133, lag-one correlation 0.5).
  const double noise = 0.1, mu = 0.5, mean = 0.3;
  const double stationary = noise * noise / (2.0 * mu);  // 0.01
  for (double dt : {0.1, 1.0}) {
    CurrentParams p;
    p.speed = channel(mean, -10.0, 10.0, noise, mu);
    CurrentModel model(p, 2024);
    const int burn_in = static_cast<int>(20.0 / dt);
    for (int i = 0; i < burn_in; ++i) {
      model.update(dt);
    }
    std::vector<double> samples;
    const int n = static_cast<int>(50000.0 / dt) > 200000 ? 200000 : static_cast<int>(50000.0 / dt);
    samples.reserve(n);
    for (int i = 0; i < n; ++i) {
      model.update(dt);
      samples.push_back(model.speed());
    }
    const Moments m = moments(samples);
    EXPECT_NEAR(m.variance, stationary, 0.1 * stationary) << "dt = " << dt;
    EXPECT_NEAR(m.mean, mean, 3.0 * std::sqrt(stationary) / 10.0) << "dt = " << dt;
    EXPECT_NEAR(m.lag1, std::exp(-mu * dt), 0.02) << "dt = " << dt;
  }
}

TEST(CurrentModel, WithoutReversionTheVarianceGrowsLinearly) {
  // mu = 0: a Wiener process, Var[x(T)] = noise^2 T. Ensemble over independently seeded models.
  const double noise = 0.05, T = 10.0, dt = 0.1;
  CurrentParams p;
  p.speed = channel(1.0, -100.0, 100.0, noise, 0.0);
  std::vector<double> finals;
  for (std::uint64_t seed = 1; seed <= 4000; ++seed) {
    CurrentModel model(p, seed);
    for (int i = 0; i < static_cast<int>(T / dt + 0.5); ++i) {
      model.update(dt);
    }
    finals.push_back(model.speed());
  }
  const Moments m = moments(finals);
  EXPECT_NEAR(m.variance, noise * noise * T, 0.1 * noise * noise * T);
  EXPECT_NEAR(m.mean, 1.0, 4.0 * noise * std::sqrt(T / 4000.0));
}

// ----------------------------------------------------------------------------------- validation

TEST(CurrentModel, ValidationNamesTheChannelAndField) {
  EXPECT_NO_THROW(validate(mineCurrent()));

  CurrentParams p = mineCurrent();
  p.speed.min = 0.5;  // above max 0.3
  const std::string m = thrownMessage([&] { validate(p); });
  EXPECT_TRUE(contains(m, "current.speed.min")) << m;
  EXPECT_TRUE(contains(m, "0.5")) << m;
  EXPECT_THROW(CurrentModel(p, 1), ParameterError);

  p = mineCurrent();
  p.horizontal_angle.mean = 0.7;  // outside [-0.5, 0.5]
  EXPECT_TRUE(contains(thrownMessage([&] { validate(p); }), "current.horizontal_angle.mean"));

  p = mineCurrent();
  p.vertical_angle.noise = -0.01;
  EXPECT_TRUE(contains(thrownMessage([&] { validate(p); }), "current.vertical_angle.noise"));

  p = mineCurrent();
  p.speed.mu = -1.0;
  EXPECT_TRUE(contains(thrownMessage([&] { validate(p); }), "current.speed.mu"));

  p = mineCurrent();
  p.vertical_angle.max = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(contains(thrownMessage([&] { validate(p); }), "current.vertical_angle.max"));
}

}  // namespace
}  // namespace hydro
}  // namespace unexmin
