// CameraModel (cpp/unexmin/sensors/vision/camera_model.h), the plumb_bob camera of CameraInfo: distortion against
// the formula written out here, distort/undistort round trips, project vs ray, K and P from the field of view and
// render_scale, what project() refuses, and parameter errors.
#include <unexmin/sensors/vision/camera_model.h>
#include "expect_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

namespace unexmin {
namespace test {
namespace {

using sensors::vision::CameraModel;

constexpr double kDeg = M_PI / 180.0;
const std::array<double, 5> kD{{-0.21, 0.04, 0.0012, -0.0008, -0.003}};  // k1 k2 p1 p2 k3 (a real wide lens)

CameraModel lens() {
  return CameraModel(640, 480, 400.0, 402.0, 321.5, 238.25, kD);
}

/// plumb_bob as OpenCV and ROS's image_geometry write it.
Eigen::Vector2d plumbBob(const Eigen::Vector2d& xy, const std::array<double, 5>& d) {
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  const double radial = 1 + d[0] * r2 + d[1] * r2 * r2 + d[4] * r2 * r2 * r2;
  return {x * radial + 2 * d[2] * x * y + d[3] * (r2 + 2 * x * x),
          y * radial + d[2] * (r2 + 2 * y * y) + 2 * d[3] * x * y};
}

void expectConfigError(const std::function<void()>& f, const std::string& part) {
  const std::string message = thrownMessage<ConfigError>(f);
  EXPECT_TRUE(contains(message, part)) << message;
  EXPECT_TRUE(contains(message, "T: sensor 'cam' (type camera)")) << message;
}

sim::SensorSpec cameraSpec(const std::map<std::string, std::vector<double>>& params) {
  sim::SensorSpec s;
  s.name = "cam";
  s.type = "camera";
  s.link = "T/cam";
  s.rate = 10.0;
  s.params = params;
  return s;
}

TEST(CameraModel, DistortIsPlumbBob) {
  const CameraModel m = lens();
  for (double x : {-0.7, -0.2, 0.0, 0.35, 0.6})
    for (double y : {-0.5, 0.0, 0.1, 0.45}) {
      const Eigen::Vector2d xy(x, y);
      EXPECT_NEAR((m.distort(xy) - plumbBob(xy, kD)).norm(), 0.0, 1e-15) << x << " " << y;
    }
}

TEST(CameraModel, UndistortInvertsDistortOverTheImage) {
  const CameraModel m = lens();
  double worst = 0.0;
  for (int v = 0; v < 480; v += 7)
    for (int u = 0; u < 640; u += 7) {
      const Eigen::Vector2d distorted((u - m.cx()) / m.fx(), (v - m.cy()) / m.fy());
      worst = std::max(worst, (m.distort(m.undistort(distorted)) - distorted).norm());
    }
  EXPECT_LT(worst, 1e-9);
}

TEST(CameraModel, RayAndProjectAreInverse) {
  const CameraModel m = lens();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> pu(-0.5, 639.5), pv(-0.5, 479.5), depth(0.2, 30.0);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d uv(pu(rng), pv(rng));
    const Eigen::Vector3d d = m.ray(uv.x(), uv.y());
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    EXPECT_GT(d.z(), 0.0);
    Eigen::Vector2d back;
    ASSERT_TRUE(m.project(depth(rng) * d, back)) << uv.transpose();
    EXPECT_NEAR((back - uv).norm(), 0.0, 1e-6) << uv.transpose();
  }
  // And a point projects where the formula puts it, its pixel's ray pointing back at it.
  const Eigen::Vector3d p(0.8, -0.45, 2.0);
  Eigen::Vector2d uv;
  ASSERT_TRUE(m.project(p, uv));
  const Eigen::Vector2d d = plumbBob(Eigen::Vector2d(p.x() / p.z(), p.y() / p.z()), kD);
  EXPECT_NEAR(uv.x(), m.fx() * d.x() + m.cx(), 1e-9);
  EXPECT_NEAR(uv.y(), m.fy() * d.y() + m.cy(), 1e-9);
  EXPECT_NEAR(m.ray(uv.x(), uv.y()).dot(p.normalized()), 1.0, 1e-12);
}

TEST(CameraModel, ProjectRefusesPointsBehindTheLensOrOutsideTheImage) {
  const CameraModel m = lens();
  Eigen::Vector2d uv;
  EXPECT_FALSE(m.project(Eigen::Vector3d(0, 0, -1), uv));
  EXPECT_FALSE(m.project(Eigen::Vector3d(0, 0, 0), uv));
  EXPECT_FALSE(m.project(Eigen::Vector3d(5, 0, 1), uv));  // far off to the right
  EXPECT_TRUE(m.project(Eigen::Vector3d(0, 0, 1), uv));
  // Far outside the field of view the barrel distortion folds back into the image: refused.
  const CameraModel strong(640, 480, 400, 400, 319.5, 239.5, {-0.4, 0, 0, 0, 0});
  EXPECT_FALSE(strong.project(Eigen::Vector3d(3.0, 0, 1), uv));
}

TEST(CameraModel, KAndPFromTheFieldOfViewAndRenderScale) {
  const double hfov = 80.0 * kDeg;
  sim::SensorSpec spec =
      cameraSpec({{"width", {2054}}, {"height", {1544}}, {"hfov", {hfov}}, {"distortion", {-0.1, 0.02, 0, 0, 0}}});
  sensors::SensorParams p(spec, "T");
  const CameraModel full = CameraModel::fromParams(p);
  const double f = 1027.0 / std::tan(hfov / 2);
  EXPECT_EQ(full.width(), 2054);
  EXPECT_EQ(full.height(), 1544);
  EXPECT_NEAR(full.fx(), f, 1e-9);
  EXPECT_NEAR(full.fy(), f, 1e-9);
  const auto k = full.K();
  const std::array<double, 9> k_expected{{f, 0, 1026.5, 0, f, 771.5, 0, 0, 1}};
  for (int i = 0; i < 9; ++i)
    EXPECT_NEAR(k[i], k_expected[i], 1e-9) << i;
  const auto pm = full.P();
  const std::array<double, 12> p_expected{{f, 0, 1026.5, 0, 0, f, 771.5, 0, 0, 0, 1, 0}};
  for (int i = 0; i < 12; ++i)
    EXPECT_NEAR(pm[i], p_expected[i], 1e-9) << i;
  EXPECT_EQ(full.distortion()[0], -0.1);
  EXPECT_EQ(full.distortion()[1], 0.02);

  // render_scale: the image shrinks, K with it (the same scene), D unchanged.
  spec.params["render_scale"] = {0.25};
  sensors::SensorParams q(spec, "T");
  const CameraModel small = CameraModel::fromParams(q);
  EXPECT_EQ(small.width(), 514);   // round(0.25 * 2054)
  EXPECT_EQ(small.height(), 386);  // round(0.25 * 1544)
  EXPECT_NEAR(small.fx(), f * 514.0 / 2054.0, 1e-9);
  EXPECT_NEAR(small.fy(), f * 386.0 / 1544.0, 1e-9);
  EXPECT_NEAR(small.cx(), 256.5, 1e-12);
  EXPECT_NEAR(small.cy(), 192.5, 1e-12);
  EXPECT_EQ(small.distortion(), full.distortion());
  // The image corner's ray is the same direction at both scales (to the half-pixel the rounding moves it).
  const Eigen::Vector3d a = full.ray(-0.5, -0.5), b = small.ray(-0.5, -0.5);
  EXPECT_LT(std::acos(std::min(1.0, a.dot(b))), 1.0 / small.fx());
}

TEST(CameraModel, BadParametersNameTheParameter) {
  {
    sim::SensorSpec spec = cameraSpec({{"width", {640.5}}});
    sensors::SensorParams p(spec, "T");
    expectConfigError([&] { CameraModel::fromParams(p); }, "parameter 'width' = 640.5: expected a whole number");
  }
  {
    sim::SensorSpec spec = cameraSpec({{"hfov", {M_PI}}});
    sensors::SensorParams p(spec, "T");
    expectConfigError([&] { CameraModel::fromParams(p); }, "parameter 'hfov'");
  }
  {
    sim::SensorSpec spec = cameraSpec({{"render_scale", {1.5}}});
    sensors::SensorParams p(spec, "T");
    expectConfigError([&] { CameraModel::fromParams(p); }, "parameter 'render_scale' = 1.5");
  }
  {
    sim::SensorSpec spec = cameraSpec({{"distortion", {0.1, 0.2}}});
    sensors::SensorParams p(spec, "T");
    expectConfigError([&] { CameraModel::fromParams(p); },
                      "parameter 'distortion' = 0.1 0.2: expected 5 finite numbers");
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin
