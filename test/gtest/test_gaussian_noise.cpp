// The "gaussian" and "none" noise families (cpp/unexmin/sensors/gaussian_noise.h, noise_model.h): white
// noise standard deviation, bias random-walk growth K^2 t, turn-on bias spread, exact "none", errors.
#include <unexmin/sensors/gaussian_noise.h>
#include <unexmin/sensors/noise_factory.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace unexmin {
namespace sensors {
namespace {

TEST(GaussianNoise, WhiteNoiseHasTheConfiguredStandardDeviation) {
  NoiseParams p;
  p.white = 0.7;
  p.interval = 0.002;
  GaussianNoise noise(p);
  Random r;
  r.seed(1);
  noise.reset(r);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double e = noise.apply(5.0, r) - 5.0;
    sum += e;
    sum2 += e * e;
  }
  EXPECT_NEAR(sum / n, 0.0, 4.0 * 0.7 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.7, 0.01 * 0.7);
  EXPECT_DOUBLE_EQ(noise.whiteStd(), 0.7);
}

TEST(GaussianNoise, BiasVarianceGrowsAsTurnOnPlusKSquaredT) {
  NoiseParams p;
  p.bias_random_walk = 0.2;            // [u/sqrt(s)]
  p.turn_on_bias = 0.05;               // [u]
  p.interval = 0.01;                   // [s]
  const int runs = 4000, steps = 500;  // 5 s
  double sum2 = 0.0, sum2_on = 0.0;
  for (int k = 0; k < runs; ++k) {
    GaussianNoise noise(p);
    Random r;
    r.seed(Random::streamSeed(k, "R", "s"));
    noise.reset(r);
    sum2_on += noise.bias() * noise.bias();
    for (int i = 0; i < steps; ++i)
      noise.apply(0.0, r);
    sum2 += noise.bias() * noise.bias();
  }
  const double expected = 0.05 * 0.05 + 0.2 * 0.2 * steps * 0.01;
  EXPECT_NEAR(sum2 / runs, expected, 0.08 * expected);  // 4000 runs: relative std of a variance ~2 %
  EXPECT_NEAR(sum2_on / runs, 0.05 * 0.05, 0.08 * 0.05 * 0.05);
}

TEST(NoiseModel, NoneReturnsTheTruthAndUnknownFamiliesAreRefused) {
  NoiseParams p;
  p.white = 1.0;
  p.interval = 0.1;
  auto none = createNoise("none", p);
  Random r;
  r.seed(3);
  none->reset(r);
  EXPECT_EQ(none->apply(1.25, r), 1.25);
  EXPECT_EQ(none->whiteStd(), 0.0);
  try {
    createNoise("violet", p);
    FAIL() << "an unknown family was accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'violet'"), std::string::npos) << e.what();
  }
  p.white = -1.0;
  EXPECT_THROW(createNoise("gaussian", p), ParameterError);
}

TEST(Random, StreamsDependOnSeedRobotAndSensor) {
  const auto a = Random::streamSeed(1, "UX_1", "imu");
  EXPECT_EQ(a, Random::streamSeed(1, "UX_1", "imu"));
  EXPECT_NE(a, Random::streamSeed(2, "UX_1", "imu"));
  EXPECT_NE(a, Random::streamSeed(1, "UX_2", "imu"));
  EXPECT_NE(a, Random::streamSeed(1, "UX_1", "dvl"));
}

}  // namespace
}  // namespace sensors
}  // namespace unexmin
