// Camera model (cpp/unexmin/sensors/vision/camera_sensor.h) against closed forms computed here: a wall of known
// albedo lit by one LED in the 4 m test box (direct + backscatter + forward scattering's gain, every visibility level),
// a small bright target found where CameraInfo's K and D put it (distortion on), the contrast of a bright and a dark
// patch falling with turbidity, shadows, the SLS laser line on the wall (position and strength), sensor noise
// statistics, seeds, modes, demand, vignetting, auto-exposure and parameter errors.
#include <unexmin/raycast/ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/sensor_suite.h>
#include <unexmin/sensors/vision/camera_sensor.h>
#include <unexmin/sensors/vision/sls_sensor.h>
#include "expect_error.h"
#include "mesh_fixture.h"
#include "sensor_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace unexmin {
namespace test {
namespace {

using sensors::vision::CameraSensor;
using sensors::vision::WaterOptics;

constexpr double kDeg = M_PI / 180.0;
const Eigen::Vector3d kCamera(0.3, 0.0, 0.0);             // [m] lens on the hull front, base frame
const Eigen::Vector3d kOptical(-M_PI / 2, 0, -M_PI / 2);  // optical frame: z forward (+x), x right (-y), y down (-z)
// [m] the LED on a boom above the hull, 0.3 m behind the lens (so the light's path to the wall differs from the
// lens's by 0.35 m: a model that attenuated both legs by the camera's range would be caught), beam along +x
const Eigen::Vector3d kLight(0.0, 0.0, 0.45);
constexpr double kWall = 2.0;           // [m] the test box's +x wall
constexpr double kI0 = 2.0;             // [W/sr] LED on-axis intensity, every channel
constexpr double kExponent = 2.0;       // cos^m beam
constexpr double kCone = 120.0 * kDeg;  // [rad] full cone

/// Rotation of the optical frame in the base (= world: the robot sits at the origin, level) frame.
Eigen::Matrix3d opticalRotation() {
  return sim::poseFromXyzRpy(Eigen::Vector3d::Zero(), kOptical).linear();
}

std::map<std::string, std::string> cameraParams(std::map<std::string, std::string> extra) {
  std::map<std::string, std::string> p{{"width", "101"},
                                       {"height", "81"},
                                       {"hfov", num(60 * kDeg)},
                                       {"noise", "none"},
                                       {"exposure", "10"},
                                       {"clip_far", "10"},
                                       {"lights", "T/light"},
                                       {"light_intensity", num(kI0) + " " + num(kI0) + " " + num(kI0)},
                                       {"light_exponent", num(kExponent)},
                                       {"light_cone", num(kCone)},
                                       {"marine_snow", "false"}};  // specks at random pixels: test_marine_snow
  for (auto& kv : extra)
    p[kv.first] = kv.second;
  return p;
}

/// The test sphere with the camera and the LED; `extra` links and sensors.
std::string cameraUrdf(const std::map<std::string, std::string>& params, const std::string& extra_links = "",
                       const std::string& extra_sensors = "") {
  const std::string links =
      mountLink("T/cam", kCamera, kOptical) + mountLink("T/light", kLight, Eigen::Vector3d::Zero());
  return sensorUrdf(SphereSpec(), links + extra_links,
                    sensorXml("cam", "camera", "T/cam", 10.0, params) + extra_sensors);
}

/// The test box (walls at +-2 m) with `albedo` on its walls, visibility `level`, and extra boxes (name, lo, hi,
/// albedo).
struct Plate {
  std::string name;
  Eigen::Vector3d lo, hi;
  double albedo;
};
sim::WorldConfig box(const std::string& level, double albedo, const std::vector<Plate>& plates = {}) {
  sim::WorldConfig config = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
  config.visibility = level;
  config.meshes.at(0).albedo = Eigen::Vector3d::Constant(albedo);
  for (const auto& p : plates) {
    sim::MeshEntry e;
    e.name = p.name;
    e.file = writeStl(p.name, test::box(p.lo, p.hi));
    e.albedo = Eigen::Vector3d::Constant(p.albedo);
    config.meshes.push_back(e);
  }
  return config;
}

/// A world with the camera robot (visual mode unless told), its suite built with the core's models plus the
/// camera and SLS families, stepped as the simulator does.
struct CameraWorld {
  CameraWorld(const sim::WorldConfig& config, const std::string& urdf, bool visual = true, std::uint64_t seed = 1) {
    std::map<std::string, sim::RobotDescription> d;
    d.emplace(config.robots.at(0).name, sim::parseRobotDescription(urdf, "(test robot)"));
    world = std::make_unique<sim::World>(config, d, 1, 0.002, seed);
    caster = raycast::makeRayCaster("embree", *world);
    caster->update();
    static const sensors::SensorFactory factory = [] {
      sensors::SensorFactory f = coreModels();
      f.add<CameraSensor>("camera");
      f.add<sensors::vision::SlsSensor>("sls");
      return f;
    }();
    suite = std::make_unique<sensors::SensorSuite>(*world, world->robot(0), caster.get(), factory,
                                                   sensors::SensorSelection(), visual);
  }
  CameraSensor& camera(const std::string& name = "cam") { return dynamic_cast<CameraSensor&>(*suite->find(name)); }
  /// Steps until `camera` has taken one more sample, the robot held at the origin, level.
  const sensors::vision::CameraFrame& frame(const std::string& name = "cam") {
    const CameraSensor& c = camera(name);
    const std::uint64_t target = c.sampleCount() + 1;
    while (c.sampleCount() < target) {
      world->robot(0).setPose(Eigen::Isometry3d::Identity());
      world->step();
      world->robot(0).setPose(Eigen::Isometry3d::Identity());
      caster->update();
      suite->update();
    }
    return c.last();
  }

  std::unique_ptr<sim::World> world;
  std::unique_ptr<raycast::RayCaster> caster;
  std::unique_ptr<sensors::SensorSuite> suite;
};

// ---------------------------------------------------------------- the closed form, written out here
double henyeyGreenstein(double g, double cos_psi) {
  return (1 - g * g) / (4 * M_PI * std::pow(1 + g * g - 2 * g * cos_psi, 1.5));
}

/// LED intensity towards unit direction `dir` (from the light) [W/sr]: I0 cos^m(theta), faded to 0 by a smoothstep
/// over the outer 20 % of the cone's half angle.
double led(const Eigen::Vector3d& dir) {
  const double theta = std::acos(std::min(1.0, dir.x())), half = kCone / 2;  // beam along +x
  if (theta >= half)
    return 0.0;
  const double x = std::min(1.0, (half - theta) / (0.2 * half));
  return kI0 * std::pow(std::cos(theta), kExponent) * x * x * (3 - 2 * x);
}

/// Unit ray of pixel (u, v) of an undistorted camera with focal f and centre (cx, cy), world frame.
Eigen::Vector3d pixelRay(double u, double v, double f, double cx, double cy) {
  return (opticalRotation() * Eigen::Vector3d((u - cx) / f, (v - cy) / f, 1.0)).normalized();
}

struct Expected {
  Eigen::Vector3d direct, backscatter;
  double range;
};

/// Forward scattering's gain on the direct light of a surface at range r inside a smooth image: exp(eta b r), eta
/// the share of Henyey-Greenstein scattering within 10 degrees (the lobe's closed form); 1 where b < 0.1 1/m (the
/// pass does not run in clear water).
double forwardGain(const WaterOptics& water, double r, int channel) {
  if (water.b.maxCoeff() < 0.1)
    return 1.0;
  const double g = water.g, lobe = 10 * kDeg;
  const double eta = (1 - g * g) / (2 * g) * (1 / (1 - g) - 1 / std::sqrt(1 + g * g - 2 * g * std::cos(lobe)));
  return std::exp(eta * water.b[channel] * r);
}

/// Radiance at the lens [W m^-2 sr^-1] per channel along unit ray `d` (world frame, from the lens) that meets the
/// +x wall (albedo rho): Lambertian reflection of the LED, both legs attenuated, and the LED's light scattered
/// back by the water along the ray (midpoint rule, 20 000 steps).
Expected closedForm(const Eigen::Vector3d& d, double rho, const WaterOptics& water, bool forward = true) {
  Expected e;
  e.range = (kWall - kCamera.x()) / d.x();
  const Eigen::Vector3d p = kCamera + e.range * d;
  const Eigen::Vector3d to = p - kLight;
  const double rl = to.norm();
  const double cos_phi = to.x() / rl;  // the wall's normal is -x
  const Eigen::Vector3d c = water.c();
  for (int k = 0; k < 3; ++k)
    e.direct[k] = rho / M_PI * led(to / rl) * cos_phi * std::exp(-c[k] * (rl + e.range)) / (rl * rl) *
                  (forward ? forwardGain(water, e.range, k) : 1.0);
  e.backscatter.setZero();
  const int n = 20000;
  const double ds = e.range / n;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) * ds;
    const Eigen::Vector3d w = kCamera + s * d - kLight;
    const double r = w.norm();
    const double p_psi = henyeyGreenstein(water.g, (w / r).dot(-d));
    for (int k = 0; k < 3; ++k)
      e.backscatter[k] += water.b[k] * p_psi * led(w / r) * std::exp(-c[k] * (s + r)) / (r * r) * ds;
  }
  return e;
}

// ---------------------------------------------------------------- tests
TEST(Camera, AWallLitByOneLedHasTheDirectPlusBackscatterRadianceOfTheModel) {
  const double rho = 0.5;
  for (const std::string level : {"none", "low", "medium", "high"}) {
    SCOPED_TRACE(level);
    const WaterOptics water = WaterOptics::fromVisibility(level, sim::WorldConfig().visibility_colour);
    const double f = 50.5 / std::tan(30 * kDeg), cx = 50.0, cy = 40.0;
    const std::vector<Eigen::Vector2i> pixels{{50, 40}, {10, 10}, {90, 70}, {73, 22}, {31, 57}};
    // Exposure from the closed form: the brightest channel of these pixels at 80 % of full scale.
    double brightest = 0.0;
    for (const auto& uv : pixels) {
      const Expected e = closedForm(pixelRay(uv.x(), uv.y(), f, cx, cy), rho, water);
      brightest = std::max(brightest, (e.direct + e.backscatter).maxCoeff());
    }
    const double exposure = 0.8 / brightest;
    CameraWorld w(box(level, rho), cameraUrdf(cameraParams({{"exposure", num(exposure)}})));
    const auto& frame = w.frame();
    ASSERT_TRUE(frame.rendered);
    ASSERT_EQ(frame.width, 101);
    ASSERT_EQ(frame.height, 81);
    ASSERT_NE(w.camera().formation(), nullptr);
    for (const auto& uv : pixels) {
      SCOPED_TRACE("pixel " + std::to_string(uv.x()) + ", " + std::to_string(uv.y()));
      const Expected e = closedForm(pixelRay(uv.x(), uv.y(), f, cx, cy), rho, water);
      const std::size_t i = static_cast<std::size_t>(uv.y()) * 101 + uv.x();
      EXPECT_NEAR(frame.range[i], e.range, 1e-4);
      // The model's backscatter term alone (it dominates at high turbidity), then the rendered pixel.
      const Eigen::Array3f b = w.camera().formation()->backscatter(uv.x(), uv.y(), frame.range[i]);
      for (int k = 0; k < 3; ++k) {
        const double total = e.direct[k] + e.backscatter[k];
        EXPECT_NEAR(b[k], e.backscatter[k], 0.05 * e.backscatter[k]) << "channel " << k;
        EXPECT_NEAR(frame.radiance[3 * i + k], total, 0.05 * total) << "channel " << k;
        const double value = 255.0 * exposure * total;  // gain 1, gamma 1, noise none
        ASSERT_LT(value, 255.0);
        EXPECT_NEAR(frame.rgb[3 * i + k], value, 0.05 * value + 0.5) << "channel " << k;
      }
      // Where the test lives: direct light dominates in clear water, backscatter in turbid water.
      if (level == "none") {
        EXPECT_GT(e.direct.y(), 10 * e.backscatter.y());
      }
      if (level == "high") {
        EXPECT_GT(e.backscatter.y(), 10 * e.direct.y());
      }
    }
  }
}

TEST(Camera, ASmallTargetIsWhereCameraInfoProjectsIt) {
  // A 3 cm plate 1.2 m away, seen off-axis through a strongly distorting lens; dark walls.
  const std::array<double, 5> d{{-0.25, 0.06, 0.002, -0.0015, 0.0}};
  const Eigen::Vector3d xy_depth(0.42, -0.28, 1.2);  // normalised (x, y) and depth in the optical frame
  const Eigen::Vector3d centre =
      kCamera +
      opticalRotation() * Eigen::Vector3d(xy_depth.x() * xy_depth.z(), xy_depth.y() * xy_depth.z(), xy_depth.z());
  const Plate target{"target", centre - Eigen::Vector3d(0, 0.015, 0.015), centre + Eigen::Vector3d(0.004, 0.015, 0.015),
                     0.9};
  CameraWorld w(box("none", 0.02, {target}),
                cameraUrdf(cameraParams({{"width", "320"},
                                         {"height", "240"},
                                         {"hfov", num(70 * kDeg)},
                                         {"distortion", num(d[0]) + " " + num(d[1]) + " " + num(d[2]) + " " +
                                                            num(d[3]) + " " + num(d[4])}})));
  const auto& frame = w.frame();
  ASSERT_TRUE(frame.rendered);
  // The pixel CameraInfo predicts for the plate's centre (its front face), from K and D alone (plumb_bob).
  const auto k = w.camera().model().K();
  const auto& dd = w.camera().model().distortion();
  const Eigen::Vector3d p = opticalRotation().transpose() * (centre - kCamera);  // optical frame
  const double x = p.x() / p.z(), y = p.y() / p.z(), r2 = x * x + y * y;
  const double radial = 1 + dd[0] * r2 + dd[1] * r2 * r2 + dd[4] * r2 * r2 * r2;
  const double xd = x * radial + 2 * dd[2] * x * y + dd[3] * (r2 + 2 * x * x);
  const double yd = y * radial + dd[2] * (r2 + 2 * y * y) + 2 * dd[3] * x * y;
  const Eigen::Vector2d expected(k[0] * xd + k[2], k[4] * yd + k[5]);
  const Eigen::Vector2d pinhole(k[0] * x + k[2], k[4] * y + k[5]);
  ASSERT_GT((expected - pinhole).norm(), 3.0) << "the lens must move the target for the test to mean something";

  // Find it: the centroid of the pixels brighter than half the brightest.
  int best = 0;
  for (std::size_t i = 1; i < frame.rgb.size(); i += 3)
    best = std::max<int>(best, frame.rgb[i]);
  ASSERT_GT(best, 100);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int count = 0;
  for (int v = 0; v < 240; ++v)
    for (int u = 0; u < 320; ++u)
      if (frame.rgb[3 * (v * 320 + u) + 1] > best / 2) {
        sum += Eigen::Vector2d(u, v);
        ++count;
      }
  ASSERT_GT(count, 9);
  ASSERT_LT(count, 100);
  const Eigen::Vector2d found = sum / count;
  EXPECT_NEAR(found.x(), expected.x(), 1.0);
  EXPECT_NEAR(found.y(), expected.y(), 1.0);
}

TEST(Camera, ContrastOfABrightAndADarkPatchFallsWithTurbidity) {
  // Two plates 1.2 m in front of the lens, left (albedo 0.8) and right (0.1), lit alike by the LED above the lens.
  const std::vector<Plate> plates{
      {"bright", Eigen::Vector3d(1.5, 0.05, -0.15), Eigen::Vector3d(1.51, 0.35, 0.15), 0.8},
      {"dark", Eigen::Vector3d(1.5, -0.35, -0.15), Eigen::Vector3d(1.51, -0.05, 0.15), 0.1}};
  const double f = 50.5 / std::tan(30 * kDeg);
  const int u_bright = static_cast<int>(std::lround(50 - f * 0.2 / 1.2)),
            u_dark = static_cast<int>(std::lround(50 + f * 0.2 / 1.2));
  double last = 2.0, last_rgb = 2.0, first = 0.0;
  for (const std::string level : {"none", "low", "medium", "high"}) {
    CameraWorld w(box(level, 0.3, plates), cameraUrdf(cameraParams({{"noise", "gaussian"}, {"exposure", "2"}})));
    const auto& frame = w.frame();
    double bright = 0, dark = 0, bright_rgb = 0, dark_rgb = 0;
    for (int v = 38; v <= 42; ++v)
      for (int du = -2; du <= 2; ++du) {
        const std::size_t b = static_cast<std::size_t>(v) * 101 + u_bright + du,
                          d = static_cast<std::size_t>(v) * 101 + u_dark + du;
        ASSERT_NEAR(frame.range[b], std::hypot(1.2, 0.2), 0.03);  // on the plates
        ASSERT_NEAR(frame.range[d], std::hypot(1.2, 0.2), 0.03);
        bright += frame.radiance[3 * b + 1];
        dark += frame.radiance[3 * d + 1];
        bright_rgb += frame.rgb[3 * b + 1];
        dark_rgb += frame.rgb[3 * d + 1];
        ASSERT_LT(frame.rgb[3 * b + 1], 250) << level << ": saturated";
      }
    const double contrast = (bright - dark) / (bright + dark);
    const double contrast_rgb = (bright_rgb - dark_rgb) / std::max(1.0, bright_rgb + dark_rgb);
    SCOPED_TRACE(level);
    EXPECT_LT(contrast, last);
    EXPECT_LE(contrast_rgb, last_rgb + 0.02);  // 8 bits and noise
    if (level == "none") {
      first = contrast;
      EXPECT_NEAR(contrast, (0.8 - 0.1) / (0.8 + 0.1), 0.05);  // nearly the albedos' contrast in clear water
    }
    last = contrast;
    last_rgb = contrast_rgb;
  }
  EXPECT_LT(last, 0.2 * first);  // high turbidity: the patches drown in backscatter
}

TEST(Camera, ShadowRaysDarkenTheWallBehindAnOccluder) {
  // A plate between the LED and the wall; the lens sees the plate's shadow on the wall, below the plate.
  const Eigen::Vector3d plate_centre(1.0, 0.0, 0.35);
  const Plate plate{"occluder", plate_centre - Eigen::Vector3d(0.005, 0.05, 0.05),
                    plate_centre + Eigen::Vector3d(0.005, 0.05, 0.05), 0.5};
  const Eigen::Vector3d shadow =
      kLight + (plate_centre - kLight) * ((kWall - kLight.x()) / (plate_centre.x() - kLight.x()));
  const Eigen::Vector3d p = opticalRotation().transpose() * (shadow - kCamera);
  const double f = 50.5 / std::tan(30 * kDeg);
  const int u = static_cast<int>(std::lround(50 + f * p.x() / p.z())),
            v = static_cast<int>(std::lround(40 + f * p.y() / p.z()));
  const std::size_t i = static_cast<std::size_t>(v) * 101 + u;
  const WaterOptics water = WaterOptics::fromVisibility("low", sim::WorldConfig().visibility_colour);
  const Expected e = closedForm(pixelRay(u, v, f, 50, 40), 0.5, water, false);

  // Without forward scattering: its halo would carry the lit wall's light into the shadow.
  CameraWorld lit(box("low", 0.5, {plate}), cameraUrdf(cameraParams({{"forward_scatter", "false"}})));
  CameraWorld shaded(box("low", 0.5, {plate}),
                     cameraUrdf(cameraParams({{"shadows", "true"}, {"forward_scatter", "false"}})));
  EXPECT_TRUE(shaded.camera().shadows());
  const auto& a = lit.frame();
  const auto& b = shaded.frame();
  ASSERT_NEAR(a.range[i], e.range, 0.01) << "the lens must see the wall at the shadow";
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a.radiance[3 * i + k], e.direct[k] + e.backscatter[k], 0.05 * (e.direct[k] + e.backscatter[k]));
    EXPECT_NEAR(b.radiance[3 * i + k], e.backscatter[k], 0.05 * e.backscatter[k]);  // only the water's glow
  }
  // Away from the shadow (the centre of the image) the two agree.
  const std::size_t c = 40 * 101 + 50;
  EXPECT_NEAR(a.radiance[3 * c + 1], b.radiance[3 * c + 1], 1e-6 * a.radiance[3 * c + 1]);
}

/// The SLS unit 10 cm left of the lens, its vertical fan (head x-z plane) at motor angle 0, seen by the camera.
std::string slsLinks() {
  return "<link name='T/sls'/><joint name='T/sls_motor' type='revolute'><parent link='T/base_link'/>"
         "<child link='T/sls'/><origin xyz='0.3 0.1 0' rpy='0 0 0'/><axis xyz='0 0 1'/>"
         "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>\n";
}
std::string slsSensor(double fan) {
  return sensorXml("sls", "sls", "T/sls", 10.0,
                   {{"camera_frame", "T/cam"},
                    {"camera_width", "101"},
                    {"camera_height", "81"},
                    {"camera_hfov", num(60 * kDeg)},
                    {"fan", num(fan)},
                    {"rays", "50"},
                    {"motor_min", "-0.5"},
                    {"motor_max", "0.5"},
                    {"motor_speed", "0"},
                    {"motor_start", "0"},
                    {"noise", "none"}});
}

TEST(Camera, EightLanesAndOneLaneRenderTheSameImage) {
  if (!sensors::vision::ImageFormation::simdAvailable())
    GTEST_SKIP() << "this CPU (or build) has no AVX2 and FMA";
  // 101 x 81 px: the tiles of the right column and bottom row hold 5 x 8, 8 x 1 and 5 x 1 pixels (the lanes' padding);
  // noise, shadows and two plates of other albedos in medium water.
  const std::vector<Plate> plates{{"dark", Eigen::Vector3d(1.5, -0.6, -0.3), Eigen::Vector3d(1.55, -0.1, 0.2), 0.1},
                                  {"bright", Eigen::Vector3d(1.2, 0.1, -0.4), Eigen::Vector3d(1.25, 0.5, 0.0), 0.9}};
  const std::map<std::string, std::string> common{{"noise", "gaussian"}, {"shadows", "true"}};
  auto params = [&](const char* simd) {
    auto p = cameraParams(common);
    p["simd"] = simd;
    return p;
  };
  CameraWorld eight(box("medium", 0.5, plates), cameraUrdf(params("true")), true, 7);
  CameraWorld one(box("medium", 0.5, plates), cameraUrdf(params("false")), true, 7);
  const auto& a = eight.frame();
  const auto& b = one.frame();
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.range.size(); ++i) {
    ASSERT_EQ(a.range[i], b.range[i]) << "pixel " << i;
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(a.radiance[3 * i + k], b.radiance[3 * i + k], 1e-4 * b.radiance[3 * i + k]) << "pixel " << i;
      // A code may round the other way where the signal sits on a step's edge.
      ASSERT_LE(std::abs(int(a.rgb[3 * i + k]) - int(b.rgb[3 * i + k])), 1) << "pixel " << i;
      differ += a.rgb[3 * i + k] != b.rgb[3 * i + k];
    }
  }
  EXPECT_LE(differ, a.rgb.size() / 1000);
  double sum = 0.0;
  for (std::uint8_t x : a.rgb)
    sum += x;
  EXPECT_GT(sum / a.rgb.size(), 5.0);  // an image, not a black frame
}

TEST(Camera, TheSlsLaserLineLandsWhereTheFanMeetsTheWallWithTheModelsStrength) {
  const double fan = 60 * kDeg, power = 0.05, rho = 0.5;
  const std::string distortion = "-0.1 0.01 0 0 0";
  auto params = [&](double p) {
    return cameraParams({{"laser_power", num(p)}, {"laser_width", "1"}, {"distortion", distortion}});
  };
  // Two cameras on the same lens, one with the laser switched off: their difference is the line alone.
  const std::string urdf =
      cameraUrdf(params(power), slsLinks(), sensorXml("dark", "camera", "T/cam", 10.0, params(0.0)) + slsSensor(fan));
  CameraWorld w(box("low", rho), urdf);
  ASSERT_NE(w.camera().laser(), nullptr);
  ASSERT_NE(w.camera("dark").laser(), nullptr);
  const auto& with = w.frame("cam");
  const auto& without = w.camera("dark").last();
  ASSERT_EQ(with.time, without.time);
  std::vector<double> line(101 * 81);
  for (std::size_t i = 0; i < line.size(); ++i)
    line[i] = with.radiance[3 * i + 1] - without.radiance[3 * i + 1];

  // Expected: the fan's plane y = 0.1 meets the wall x = 2 in a vertical line; its image through the lens.
  const sensors::vision::CameraModel& m = w.camera().model();
  const Eigen::Vector3d head(0.3, 0.1, 0.0);
  std::vector<Eigen::Vector2d> expected;
  for (double e = -fan / 2; e <= fan / 2; e += 0.001) {
    const Eigen::Vector3d hit = head + (kWall - head.x()) * Eigen::Vector3d(1, 0, std::tan(e));
    Eigen::Vector2d uv;
    if (m.project(opticalRotation().transpose() * (hit - kCamera), uv))
      expected.push_back(uv);
  }
  ASSERT_GT(expected.size(), 100u);
  int rows = 0;
  for (int v = 5; v < 76; ++v) {
    // The expected column at this row, from the nearest expected samples.
    double u_expected = NAN, best = 1e9;
    for (const auto& uv : expected)
      if (std::abs(uv.y() - v) < best)
        best = std::abs(uv.y() - v), u_expected = uv.x();
    if (best > 0.05)
      continue;
    double sum = 0, moment = 0;
    for (int u = 0; u < 101; ++u) {
      sum += line[v * 101 + u];
      moment += u * line[v * 101 + u];
    }
    ASSERT_GT(sum, 0.0) << "row " << v;
    EXPECT_NEAR(moment / sum, u_expected, 0.25) << "row " << v;
    ++rows;
  }
  EXPECT_GT(rows, 50);

  // Strength at the centre row (a frontal wall): the line carries, per pixel of its length,
  //   (rho / pi) (P / fan) exp(-c (R_L + R_C)) J / (dv/dθ),  J = f_x f_y / Z^2,  dv/dθ = f_y D_L / Z
  // with Z = D_L = 1.7 m the wall's distance from the lens and from the laser.
  const double z = kWall - kCamera.x(), dl = kWall - head.x();
  const double rc = (Eigen::Vector3d(kWall, 0.1, 0.0) - kCamera).norm();
  const double c = WaterOptics::fromVisibility("low", sim::WorldConfig().visibility_colour).c().y();
  const double per_pixel = rho / M_PI * power / fan * std::exp(-c * (dl + rc)) * m.fx() / (z * dl);
  const int v0 = static_cast<int>(std::lround(m.cy()));
  double sum = 0;
  for (int u = 0; u < 101; ++u)
    sum += line[v0 * 101 + u];
  EXPECT_NEAR(sum, per_pixel, 0.05 * per_pixel);
  // Green light: the red and blue channels see 0.05 and 0.15 of it (laser_colour default).
  double red = 0;
  for (int u = 0; u < 101; ++u)
    red += with.radiance[3 * (v0 * 101 + u)] - without.radiance[3 * (v0 * 101 + u)];
  EXPECT_NEAR(red, 0.05 * sum, 0.01 * sum);
}

TEST(Camera, NoiseHasTheShotAndReadNoiseOfItsParameters) {
  const double full_well = 1000, read = 5, gain = 2, exposure = 4;
  CameraWorld w(box("none", 0.5), cameraUrdf(cameraParams({{"noise", "gaussian"},
                                                           {"full_well", num(full_well)},
                                                           {"read_noise", num(read)},
                                                           {"gain", num(gain)},
                                                           {"exposure", num(exposure)}})));
  const int frames = 120;
  const std::vector<std::size_t> pixels{40 * 101 + 50, 40 * 101 + 51, 41 * 101 + 50, 20 * 101 + 30, 60 * 101 + 70};
  std::vector<double> sum(pixels.size()), sum2(pixels.size());
  std::vector<double> signal(pixels.size());
  for (int n = 0; n < frames; ++n) {
    const auto& frame = w.frame();
    for (std::size_t j = 0; j < pixels.size(); ++j) {
      const double value = frame.rgb[3 * pixels[j] + 1];
      sum[j] += value;
      sum2[j] += value * value;
      signal[j] = exposure * frame.radiance[3 * pixels[j] + 1];  // fraction of full well, noise-free
    }
  }
  for (std::size_t j = 0; j < pixels.size(); ++j) {
    ASSERT_GT(signal[j], 0.05);
    ASSERT_LT(gain * signal[j], 0.8);
    const double mean = sum[j] / frames, var = sum2[j] / frames - mean * mean;
    const double sigma = 255 * gain * std::sqrt(signal[j] / full_well + (read / full_well) * (read / full_well));
    EXPECT_NEAR(mean, 255 * gain * signal[j], 3 * sigma / std::sqrt(frames) + 0.5) << j;
    // Sample variance of 120 frames: 13 % standard error; plus the 1/12 DN^2 of rounding to 8 bits.
    EXPECT_NEAR(std::sqrt(var), std::sqrt(sigma * sigma + 1.0 / 12.0), 0.3 * sigma) << j;
  }
}

TEST(Camera, SeededNoiseRepeatsAndDoesNotDependOnWhoWatches) {
  const std::string urdf = cameraUrdf(cameraParams({{"noise", "gaussian"}, {"full_well", "500"}}));
  CameraWorld a(box("low", 0.5), urdf, true, 7), b(box("low", 0.5), urdf, true, 7), c(box("low", 0.5), urdf, true, 8);
  // b renders only its third frame: the noise of that frame is the same as a's, which rendered all three.
  int asked = 0;
  b.camera().setDemand([&asked] { return ++asked == 3; });
  std::vector<std::uint8_t> third_a, third_c;
  for (int n = 0; n < 3; ++n) {
    third_a = a.frame().rgb;
    third_c = c.frame().rgb;
    const auto& fb = b.frame();
    EXPECT_EQ(fb.rendered, n == 2);
  }
  EXPECT_EQ(b.camera().last().rgb, third_a);
  EXPECT_NE(third_c, third_a);
}

TEST(Camera, OperationalModeRendersNothing) {
  CameraWorld w(box("none", 0.5), cameraUrdf(cameraParams({})), /*visual=*/false);
  const auto& frame = w.frame();
  EXPECT_FALSE(w.camera().visual());
  EXPECT_FALSE(frame.rendered);
  EXPECT_TRUE(frame.rgb.empty());
  EXPECT_EQ(w.camera().formation(), nullptr);
  EXPECT_NEAR(frame.time, 0.1, 1e-9);  // the schedule runs: one sample per 1 / fps
  // CameraInfo's geometry is there in both modes.
  EXPECT_EQ(w.camera().model().width(), 101);
}

TEST(Camera, ItsLightsAndItsLaserComeFromTheDescription) {
  CameraWorld w(box("none", 0.5), cameraUrdf(cameraParams({}), slsLinks(), slsSensor(1.0)));
  const auto& lights = w.camera().lights();
  ASSERT_EQ(lights.size(), 1u);
  // The LED 0.45 m above and 0.3 m behind the lens: optical y is down, z forward; beam along the optical axis.
  EXPECT_NEAR((lights[0].position - Eigen::Vector3d(0, -0.45, -0.3)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((lights[0].axis - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(lights[0].intensity.x(), kI0, 1e-12);
  ASSERT_NE(w.camera().laser(), nullptr);
  EXPECT_EQ(w.camera().laser()->sls().cameraFrame(), "T/cam");
  // A camera no SLS unit names has no line.
  CameraWorld plain(box("none", 0.5), cameraUrdf(cameraParams({})));
  EXPECT_EQ(plain.camera().laser(), nullptr);
}

std::string startUpError(const std::string& urdf) {
  try {
    CameraWorld w(box("none", 0.5), urdf);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected ConfigError";
  return "";
}

TEST(Camera, VignettingDarkensEachPixelByItsCos4Falloff) {
  // The 8-bit value of pixel i is round(255 e V_i L_i) (gain 1, gamma 1, no noise) with V = 1 - v + v cos^4 theta,
  // cos theta = 1 / sqrt(1 + x^2 + y^2), (x, y) = ((u - cx) / f, (v - cy) / f): at the corner (0, 0) of the 101 x 81
  // image of hfov 60 deg, cos^4 theta = 0.424. `radiance` stays the light at the lens (before vignetting).
  const double f = 50.5 / std::tan(30 * kDeg), cx = 50.0, cy = 40.0;
  CameraWorld probe(box("none", 0.5), cameraUrdf(cameraParams({{"exposure", "1"}})));
  const auto radiance = probe.frame().radiance;
  const double exposure = 0.9 / *std::max_element(radiance.begin(), radiance.end());
  for (double v : {0.0, 0.5, 1.0}) {
    SCOPED_TRACE("vignetting " + num(v));
    CameraWorld w(box("none", 0.5), cameraUrdf(cameraParams({{"exposure", num(exposure)}, {"vignetting", num(v)}})));
    const auto& frame = w.frame();
    EXPECT_EQ(frame.radiance, radiance);
    for (const Eigen::Vector2i uv :
         {Eigen::Vector2i(0, 0), Eigen::Vector2i(100, 80), Eigen::Vector2i(50, 40), Eigen::Vector2i(80, 10)}) {
      const double x = (uv.x() - cx) / f, y = (uv.y() - cy) / f, c2 = 1.0 / (1.0 + x * x + y * y);
      const double falloff = 1.0 - v + v * c2 * c2;
      if (uv == Eigen::Vector2i(0, 0))
        EXPECT_NEAR(c2 * c2, 0.424, 0.001);
      const std::size_t i = static_cast<std::size_t>(uv.y()) * 101 + uv.x();
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(frame.rgb[3 * i + k], 255.0 * exposure * falloff * radiance[3 * i + k], 0.5 + 1e-3)
            << uv.transpose() << " channel " << k;
    }
  }
}

TEST(Camera, AutoExposureConvergesToItsTargetAsTheClosedFormSays) {
  // A still scene without saturation: the mean signal is m = e M (M the mean radiance over pixels and channels, with
  // no vignetting), and e' = e (T / m)^a gives log(e_N M / T) = (1 - a)^N log(e_0 M / T). Target T at a third of
  // the level where the brightest pixel would saturate; start 50 times too dark.
  CameraWorld probe(box("none", 0.5), cameraUrdf(cameraParams({{"exposure", "1"}})));
  const auto radiance = probe.frame().radiance;
  double mean = 0.0;
  for (float r : radiance)
    mean += r / radiance.size();
  const double brightest = *std::max_element(radiance.begin(), radiance.end());
  const double target = mean / brightest / 3.0, rate = 0.5, e0 = target / mean / 50.0;
  CameraWorld w(box("none", 0.5), cameraUrdf(cameraParams({{"exposure", num(e0)},
                                                           {"auto_exposure", "true"},
                                                           {"auto_exposure_target", num(target)},
                                                           {"auto_exposure_rate", num(rate)},
                                                           {"auto_exposure_range", "1000"}})));
  EXPECT_DOUBLE_EQ(w.camera().currentExposure(), e0);
  const int frames = 12;
  double level = 0.0;
  for (int n = 1; n <= frames; ++n) {
    const auto& frame = w.frame();
    level = 0.0;  // this frame's mean 8-bit level, taken with e_{n-1}
    for (std::uint8_t b : frame.rgb)
      level += b / (255.0 * frame.rgb.size());
    const double expected = target / mean * std::pow(e0 * mean / target, std::pow(1.0 - rate, n));
    EXPECT_NEAR(w.camera().currentExposure(), expected, 1e-4 * expected) << "frame " << n;
  }
  // After 12 frames the error is 50^(1/4096): the image's mean level is the target (8-bit rounding aside).
  EXPECT_NEAR(level, target, 0.01 * target + 0.5 / 255);
  // And it stays within its range: a black scene drives it to exposure * range, no further.
  CameraWorld dark(
      box("none", 0.0),
      cameraUrdf(cameraParams({{"exposure", "2"}, {"auto_exposure", "true"}, {"light_intensity", "0 0 0"}})));
  dark.frame();
  dark.frame();
  EXPECT_DOUBLE_EQ(dark.camera().currentExposure(), 200.0);
}

TEST(Camera, BadParametersStopStartUpNamingThem) {
  EXPECT_EQ(
      startUpError(cameraUrdf(cameraParams({{"lights", "T/light T/lamp"}}))),
      "UX_1: sensor 'cam' (type camera): parameter 'lights' = 'T/lamp': expected links of the robot (the LED lights)");
  EXPECT_EQ(
      startUpError(cameraUrdf(cameraParams({{"shadows", "maybe"}}))),
      "UX_1: sensor 'cam' (type camera): parameter 'shadows' = 'maybe': expected one of true|false|True|False|1|0");
  EXPECT_TRUE(contains(startUpError(cameraUrdf(cameraParams({{"light_intensity", "1 2"}}))),
                       "parameter 'light_intensity' = 1 2: expected three numbers"));
  EXPECT_TRUE(contains(startUpError(cameraUrdf(cameraParams({{"light_intensity", "1 -2 1"}}))),
                       "parameter 'light_intensity' = -2: expected three finite numbers >= 0 W/sr"));
  EXPECT_TRUE(contains(startUpError(cameraUrdf(cameraParams({{"exposure", "-1"}}))), "parameter 'exposure' = -1"));
  EXPECT_TRUE(contains(startUpError(cameraUrdf(cameraParams({{"gama", "2"}}))), "unknown parameter 'gama'"));
  EXPECT_TRUE(
      contains(startUpError(cameraUrdf(cameraParams({{"vignetting", "1.5"}}))), "parameter 'vignetting' = 1.5"));
  EXPECT_TRUE(contains(startUpError(cameraUrdf(cameraParams({{"auto_exposure_target", "0"}}))),
                       "parameter 'auto_exposure_target' = 0"));
  const std::string second =
      "<link name='T/sls2'/><joint name='T/sls2_motor' type='revolute'><parent link='T/base_link'/>"
      "<child link='T/sls2'/><origin xyz='0.3 -0.1 0' rpy='0 0 0'/><axis xyz='0 0 1'/>"
      "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>\n";
  std::string two = slsSensor(1.0) + slsSensor(1.0);
  two.replace(two.rfind("name='sls'"), 10, "name='sls2'");
  two.replace(two.rfind("link='T/sls'"), 12, "link='T/sls2'");
  EXPECT_EQ(startUpError(cameraUrdf(cameraParams({}), slsLinks() + second, two)),
            "UX_1: sensor 'cam' (type camera): SLS units 'sls' and 'sls2' both name it as their camera "
            "(camera_frame T/cam); expected at most one");
}

TEST(Camera, LevelWaterTakesTheWaterColumnsTurbidityWhereTheCameraIs) {
  // Clear water plus particles per NTU (water_optics.h): c = 0.151 + 0.7 T in green, b = 0.037 + 0.6 T.
  const Eigen::Vector3d colour = sim::WorldConfig().visibility_colour;
  for (const double t : {0.0, 1.5, 5.5}) {
    const WaterOptics w = WaterOptics::fromTurbidity(t, colour);
    EXPECT_NEAR(w.c().y(), 0.151 + 0.7 * t, 1e-12);
    EXPECT_NEAR(w.b.y(), 0.037 + 0.6 * t, 1e-12);
    EXPECT_NEAR(w.a.x(), (0.114 + 0.1 * t) * colour.y() / colour.x(), 1e-12);
  }
  EXPECT_THROW(WaterOptics::fromTurbidity(-1.0, colour), ConfigError);
  // A column whose turbidity steps from 1 to 4 NTU at 99 m: the test box (surface 100 m above its centre) holds the
  // camera at 100 m, in the 4 NTU water; a point 2 m higher sees the 1 NTU water.
  sim::WorldConfig config = box("water", 0.5);
  water::Profile profile;
  for (const auto& [depth, ntu] : std::vector<std::pair<double, double>>{{0, 1}, {99, 1}, {99, 4}, {200, 4}}) {
    water::WaterRow row;
    row.depth = depth;
    row.turbidity = ntu;
    profile.rows.push_back(row);
  }
  config.water_column = std::make_shared<water::WaterColumn>(profile, std::vector<water::Region>{}, 100.0, 9.81);
  EXPECT_DOUBLE_EQ(sensors::vision::opticalTurbidity(config, Eigen::Vector3d(0, 0, 0), 0.0), 4.0);
  EXPECT_DOUBLE_EQ(sensors::vision::opticalTurbidity(config, Eigen::Vector3d(0, 0, 2), 0.0), 1.0);
  sim::WorldConfig other = config;
  other.visibility = "medium";
  EXPECT_EQ(sensors::vision::opticalTurbidity(other, Eigen::Vector3d::Zero(), 0.0), -1.0);
  // The rendered wall against the closed form of the 4 NTU water, as the test above does for the levels.
  const WaterOptics water = WaterOptics::fromTurbidity(4.0, colour);
  const double f = 50.5 / std::tan(30 * kDeg), cx = 50.0, cy = 40.0;
  const std::vector<Eigen::Vector2i> pixels{{50, 40}, {10, 10}, {90, 70}};
  double brightest = 0.0;
  for (const auto& uv : pixels) {
    const Expected e = closedForm(pixelRay(uv.x(), uv.y(), f, cx, cy), 0.5, water);
    brightest = std::max(brightest, (e.direct + e.backscatter).maxCoeff());
  }
  CameraWorld w(config, cameraUrdf(cameraParams({{"exposure", num(0.8 / brightest)}})));
  const auto& frame = w.frame();
  ASSERT_TRUE(frame.rendered);
  for (const auto& uv : pixels) {
    const Expected e = closedForm(pixelRay(uv.x(), uv.y(), f, cx, cy), 0.5, water);
    const Expected one = closedForm(pixelRay(uv.x(), uv.y(), f, cx, cy), 0.5, WaterOptics::fromTurbidity(1.0, colour));
    const std::size_t i = static_cast<std::size_t>(uv.y()) * 101 + uv.x();
    for (int k = 0; k < 3; ++k) {
      const double total = e.direct[k] + e.backscatter[k], total1 = one.direct[k] + one.backscatter[k];
      EXPECT_NEAR(frame.radiance[3 * i + k], total, 0.05 * total) << "pixel " << uv.transpose() << " channel " << k;
      EXPECT_GT(std::abs(total1 - total), 0.2 * total);  // the 1 NTU water would be told apart
    }
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin
