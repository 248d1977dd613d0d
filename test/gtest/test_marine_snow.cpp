// Suspended particles (cpp/unexmin/sensors/vision/marine_snow.h): counts per visibility level, seeds, drift with the
// current and the robot moving through them, and the light of one particle against the closed form computed here
// (Lambert's sphere lit by one LED: its power in the image and its streak during the exposure).
#include <unexmin/sensors/vision/marine_snow.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using namespace sensors::vision;  // CameraModel, ImageFormation, LedLight, MarineSnow, WaterOptics

const Eigen::Vector3d kColour(0.25, 0.3, 0.2);
constexpr double kSide = 2.0 * MarineSnow::kHalfSize;

bool inCube(const Eigen::Vector3d& p, const Eigen::Vector3d& lens) {
  const Eigen::Vector3d d = p - lens;
  return (d.array() >= -MarineSnow::kHalfSize).all() && (d.array() < MarineSnow::kHalfSize).all();
}

TEST(MarineSnow, CountsFollowTheVisibilityLevel) {
  const std::vector<std::pair<std::string, double>> levels{{"none", 0}, {"low", 50}, {"medium", 200}, {"high", 500}};
  std::size_t last = 0;
  for (const auto& l : levels) {
    EXPECT_EQ(MarineSnow::density(l.first), l.second);
    const MarineSnow snow(MarineSnow::density(l.first), 7, Eigen::Vector3d(1, 2, 3));
    EXPECT_EQ(snow.size(), static_cast<std::size_t>(std::llround(l.second * kSide * kSide * kSide))) << l.first;
    if (l.first != "none") {
      EXPECT_GT(snow.size(), last);
    }
    last = snow.size();
    for (const auto& p : snow.particles())
      ASSERT_TRUE(inCube(p, Eigen::Vector3d(1, 2, 3)));
  }
  EXPECT_THROW(MarineSnow::density("murky"), ConfigError);
  EXPECT_THROW(MarineSnow(-1.0, 1, Eigen::Vector3d::Zero()), ParameterError);
}

TEST(MarineSnow, TheSameSeedGivesTheSameParticles) {
  MarineSnow a(200, 11, Eigen::Vector3d::Zero()), b(200, 11, Eigen::Vector3d::Zero()),
      c(200, 12, Eigen::Vector3d::Zero());
  EXPECT_EQ(a.particles(), b.particles());
  EXPECT_NE(a.particles(), c.particles());
  for (int i = 0; i < 50; ++i) {  // the robot moving through them: the same wraps, the same draws
    a.advance(Eigen::Vector3d(0.1 * i, 0, 0), Eigen::Vector3d(0.05, 0.02, 0), 0.1);
    b.advance(Eigen::Vector3d(0.1 * i, 0, 0), Eigen::Vector3d(0.05, 0.02, 0), 0.1);
  }
  EXPECT_EQ(a.particles(), b.particles());
}

TEST(MarineSnow, ParticlesDriftWithTheCurrentAndTheRobotMovesThroughThem) {
  MarineSnow snow(200, 3, Eigen::Vector3d::Zero());
  const std::vector<Eigen::Vector3d> before = snow.particles();
  const Eigen::Vector3d current(0.1, -0.05, 0.02);
  snow.advance(Eigen::Vector3d::Zero(), current, 2.0);  // 0.2 m: those that stay inside moved by exactly that
  std::size_t moved = 0;
  for (std::size_t i = 0; i < before.size(); ++i)
    if (inCube(before[i] + 2.0 * current, Eigen::Vector3d::Zero())) {
      EXPECT_NEAR((snow.particles()[i] - before[i] - 2.0 * current).norm(), 0.0, 1e-12);
      ++moved;
    }
  EXPECT_GT(moved, before.size() / 2);
  // The robot travels 30 m along +x in still water: the particles stay in the cube around it, as many, and as
  // dense in its front half as in its back half (uniform: the two counts within 5 binomial sigmas).
  Eigen::Vector3d lens = Eigen::Vector3d::Zero();
  for (int i = 0; i < 300; ++i) {
    lens.x() += 0.1;
    snow.advance(lens, Eigen::Vector3d::Zero(), 0.1);
  }
  ASSERT_EQ(snow.size(), before.size());
  std::size_t front = 0;
  for (const auto& p : snow.particles()) {
    ASSERT_TRUE(inCube(p, lens));
    front += p.x() > lens.x() ? 1 : 0;
  }
  const double n = static_cast<double>(snow.size());
  EXPECT_NEAR(static_cast<double>(front), n / 2, 5 * std::sqrt(n / 4));
  // None of them is one it started with at the same place in the water (it passed 30 m of water).
  for (const auto& p : snow.particles())
    EXPECT_GT(p.x(), 30.0 - MarineSnow::kHalfSize - 1e-9);
}

/// One LED at the lens looking along the optical axis, medium water; a 200 x 200 pinhole camera (f 200 px).
struct Scene {
  Scene() : camera(200, 200, 200.0, 200.0, 99.5, 99.5, {0, 0, 0, 0, 0}) {
    LedLight l;
    l.position.setZero();
    l.axis = Eigen::Vector3d(0, 0, 1);
    l.intensity = Eigen::Vector3d(2, 2, 2);
    l.cone = M_PI / 2;
    l.exponent = 1;
    water = WaterOptics::fromVisibility("medium", kColour);
    formation = std::make_unique<ImageFormation>(camera, std::vector<LedLight>{l}, water, 10.0, 1);
  }
  CameraModel camera;
  WaterOptics water;
  std::unique_ptr<ImageFormation> formation;
};

TEST(MarineSnow, AParticleSendsBackLambertsSphereOfItsLight) {
  const Scene s;
  const MarineSnow snow(0, 1, Eigen::Vector3d::Zero());
  // On the axis at 0.5 m: light and lens on the same side, phase angle 0: J = (2/3) rho a^2 E.
  const double r = 0.5;
  const Eigen::Array3d j = snow.intensity(*s.formation, Eigen::Vector3d(0, 0, r));
  const double e = 2.0 * std::exp(-s.water.c().y() * r) / (r * r);
  EXPECT_NEAR(j[1], 2.0 / 3.0 * MarineSnow::kAlbedo * MarineSnow::kRadius * MarineSnow::kRadius * e, 1e-6 * j[1]);
}

TEST(MarineSnow, OneParticlesPowerAndStreakInTheImage) {
  const Scene s;
  MarineSnow one(1.0 / (kSide * kSide * kSide), 5, Eigen::Vector3d::Zero());  // one particle
  ASSERT_EQ(one.size(), 1u);
  const Eigen::Vector3d p(0.05, -0.02, 0.6);  // where we want it: move it there with the current
  one.advance(Eigen::Vector3d::Zero(), p - one.particles()[0], 1.0);
  ASSERT_NEAR((one.particles()[0] - p).norm(), 0.0, 1e-12);

  const std::vector<float> range(200 * 200, std::numeric_limits<float>::infinity());
  MarineSnow::Motion still;  // camera at the origin, optical frame = world
  std::vector<float> radiance(3 * 200 * 200, 0.0f);
  std::vector<std::size_t> touched;
  EXPECT_EQ(one.draw(s.camera, *s.formation, still, range, radiance, touched), 1u);
  double sum = 0, mu = 0;
  for (std::size_t i = 0; i < 200 * 200; ++i) {
    sum += radiance[3 * i + 1];
    mu += radiance[3 * i + 1] * static_cast<double>(i % 200);
  }
  const double rp = p.norm();
  const double expected = one.intensity(*s.formation, p)[1] * std::exp(-s.water.c().y() * rp) * 200 * 200 / (rp * rp);
  EXPECT_NEAR(sum, expected, 1e-4 * expected);
  EXPECT_NEAR(mu / sum, 99.5 + 200 * p.x() / p.z(), 0.1);
  EXPECT_FALSE(touched.empty());

  // The robot moving at 1 m/s along -x during a 20 ms exposure: the particle streaks 2 cm along +x in the camera,
  // 200 * 0.02 / 0.6 = 6.7 px, centred half way.
  MarineSnow::Motion moving;
  moving.velocity = Eigen::Vector3d(-1, 0, 0);
  moving.exposure_time = 0.02;
  std::vector<float> streak(3 * 200 * 200, 0.0f);
  touched.clear();
  one.draw(s.camera, *s.formation, moving, range, streak, touched);
  double su = 0, m1 = 0, m2 = 0;
  for (std::size_t i = 0; i < 200 * 200; ++i) {
    const double x = streak[3 * i + 1], u = static_cast<double>(i % 200);
    su += x;
    m1 += x * u;
    m2 += x * u * u;
  }
  const double len = 200 * 0.02 / 0.6, start = 99.5 + 200 * p.x() / p.z();
  EXPECT_NEAR(su, expected, 1e-4 * expected);
  EXPECT_NEAR(m1 / su, start + len / 2, 0.1);
  // A uniform segment of length len spread by the spot: variance len^2 / 12 + sigma^2 (sigma 0.6 px, sampled).
  const double var = m2 / su - (m1 / su) * (m1 / su);
  EXPECT_NEAR(var, len * len / 12 + MarineSnow::kSpot * MarineSnow::kSpot, 0.15 * len * len / 12);

  // A wall at 0.4 m hides it.
  const std::vector<float> wall(200 * 200, 0.4f);
  std::vector<float> hidden(3 * 200 * 200, 0.0f);
  touched.clear();
  EXPECT_EQ(one.draw(s.camera, *s.formation, still, wall, hidden, touched), 0u);
  EXPECT_TRUE(touched.empty());
}

}  // namespace
}  // namespace test
}  // namespace unexmin
