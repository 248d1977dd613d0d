// M3 multibeam model (cpp/unexmin/sensors/sonar/m3_sensor.h) in the 4 m test box (worlds/test_box.world, walls
// at +-2 m): every beam's range against the analytic distance to the walls (+-1 cm) along the beam's closed-form
// direction (beam k at -fov_h/2 + k fov_h / (beams - 1), beam 0 to the right, REP-103), beam order and angle_min <
// angle_max with the robot off-centre, the REP-117 markers beyond range_max and inside range_min, Gaussian range noise,
// seeds, the 40 Hz schedule, ranges timed at the water column's sound speed and start-up errors.
#include <unexmin/sensors/sonar/m3_sensor.h>
#include <unexmin/water/seawater.h>
#include <unexmin/water/water_column.h>
#include "sonar_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace unexmin {
namespace test {
namespace {

using sensors::sonar::M3Scan;
using sensors::sonar::M3Sensor;

constexpr double kDeg = M_PI / 180.0;
const Eigen::Vector3d kMount(0.3, 0.0, -0.05);           // [m] M3 link in the base frame
const Eigen::Vector3d kMountRpy(0.0, 0.0, 20.0 * kDeg);  // [rad] fan turned 20 deg to the left

std::string m3Urdf(std::map<std::string, std::string> params, double rate = 40.0) {
  params.emplace("noise", "none");
  return sensorUrdf(SphereSpec(), mountLink("T/m3_link", kMount, kMountRpy),
                    sensorXml("m3", "m3", "T/m3_link", rate, params));
}

sim::WorldConfig testBox() {
  return sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/test_box.world");
}

// The model's documented defaults (m3_sensor.h), which m3Urdf() leaves alone.
constexpr int kBeams = 256, kRaysPerBeam = 4;
constexpr double kFovH = 120.0 * kDeg, kFovV = 3.0 * kDeg;

/// Ray j of beam k in the sensor frame, from the documented closed form (not from the model):
/// azimuth a_k = -fov_h/2 + k fov_h / (beams - 1) about z, elevation e_j = -fov_v/2 + (j + 1/2) fov_v / n.
Eigen::Vector3d ray(int k, int j, int beams = kBeams, double fov_h = kFovH, int rays = kRaysPerBeam,
                    double fov_v = kFovV) {
  const double a = -fov_h / 2.0 + k * fov_h / (beams - 1);
  const double e = -fov_v / 2.0 + (j + 0.5) * fov_v / rays;
  return Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
}

// The M3's documented sonar equation (m3_sensor.h, echo_model.h) with its defaults, evaluated here: SL 210 dB,
// BS0 -20 dB, alpha 0.1 dB/m, Lambert n = 2, the beam's solid angle omega = fov_h / beams x 2 sin(fov_v / 2);
// gain 0.5 x 40 dB, TVG 20 log r + 2 alpha r, 8 bits over 80 dB from 125 dB; detection at noise_level 72 dB +
// detection_threshold 10 dB.
const double kOmega = kFovH / kBeams * 2.0 * std::sin(kFovV / 2.0);  // [sr]
constexpr double kDetection = 72.0 + 10.0;                           // [dB re 1 uPa]
/// Echo level of a beam's echo from range r at cos(incidence) c, X = extra [dB re 1 uPa].
double m3Level(double r, double c, double extra = 0.0, double omega = kOmega) {
  return 210.0 - 40 * std::log10(r) - 0.2 * r - 20.0 + 20 * std::log10(c) + 10 * std::log10(r * r * omega / c) + extra;
}
/// The intensity (code / 255) of an echo of level L from range r.
double m3Intensity(double level, double r) {
  const double out = level + 20.0 + 20 * std::log10(r) + 0.2 * r;
  return std::clamp(std::round((out - 125.0) / 80.0 * 255.0), 0.0, 255.0) / 255.0;
}

/// Distance from p along the unit d to the first wall of the box (+-2 m); `cos_incidence`: |d . normal| there.
double toBoxWall(const Eigen::Vector3d& p, const Eigen::Vector3d& d, double* cos_incidence = nullptr) {
  double nearest = INFINITY;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) <= 1e-12)
      continue;
    const double t = ((d[a] > 0 ? 2.0 : -2.0) - p[a]) / d[a];
    if (t < nearest) {
      nearest = t;
      if (cos_incidence)
        *cos_incidence = std::abs(d[a]);
    }
  }
  return nearest;
}

/// First-return distance of beam k (default fan): the nearest wall over the beam's rays.
double analytic(const Eigen::Isometry3d& sonar, int k) {
  double nearest = INFINITY;
  for (int j = 0; j < kRaysPerBeam; ++j)
    nearest = std::min(nearest, toBoxWall(sonar.translation(), sonar.linear() * ray(k, j)));
  return nearest;
}

Eigen::Isometry3d sonarPose(SonarWorld& w) {
  return w.robot().state().pose * sim::poseFromXyzRpy(kMount, kMountRpy);
}

TEST(M3, EveryBeamMeasuresTheAnalyticDistanceToTheBoxWalls) {
  SonarWorld w(testBox(), m3Urdf({}));
  auto& m3 = w.sensor<M3Sensor>("m3");
  const Eigen::Isometry3d pose = sim::poseFromXyzRpy(Eigen::Vector3d(-0.4, 0.3, 0.2), Eigen::Vector3d(0.1, -0.15, 0.3));
  w.place(pose);
  w.samples(m3, 1);
  ASSERT_EQ(m3.beams(), static_cast<std::size_t>(kBeams));
  ASSERT_EQ(m3.raysPerBeam(), kRaysPerBeam);
  ASSERT_EQ(m3.last().ranges.size(), 256u);
  EXPECT_NEAR(m3.angleIncrement(), 120.0 * kDeg / 255, 1e-12);
  const Eigen::Isometry3d sonar = sonarPose(w);
  for (int k = 0; k < 256; ++k) {
    const double expected = analytic(sonar, k);
    ASSERT_LT(expected, 150.0);
    EXPECT_NEAR(m3.last().ranges[k], expected, 0.01) << "beam " << k;
    // Quantised to the 1 cm resolution.
    EXPECT_NEAR(m3.last().ranges[k] / 0.01, std::round(m3.last().ranges[k] / 0.01), 1e-3) << "beam " << k;
    EXPECT_GT(m3.last().intensities[k], 0.0f);
  }
}

TEST(M3, BeamZeroLooksRightAndTheLastLeftWithTheRobotOffCentre) {
  // Five beams over 120 deg (-60, -30, 0, 30, 60 deg), one ray each, the fan level and straight ahead; the robot
  // 0.8 m left of the box centre (+y, REP-103: x forward, y left, z up), so the right wall (y = -2) is 2.8 m
  // away and the left one 1.2 m: beam 0 (-60 deg, to the right) measures 2.8 / sin 60 = 3.23 m, beam 4
  // 1.2 / sin 60 = 1.39 m. A reversed beam order swaps them (and makes angle_min > angle_max).
  const int beams = 5;
  const double fov = 120.0 * kDeg;
  const Eigen::Vector3d mount(0.3, 0.0, -0.05);
  const std::string urdf =
      sensorUrdf(SphereSpec(), mountLink("T/m3_link", mount, Eigen::Vector3d::Zero()),
                 sensorXml("m3", "m3", "T/m3_link", 40.0,
                           {{"noise", "none"}, {"beams", num(beams)}, {"fov_h", num(fov)}, {"rays_per_beam", "1"}}));
  SonarWorld w(testBox(), urdf);
  auto& m3 = w.sensor<M3Sensor>("m3");
  w.place(sim::poseFromXyzRpy(Eigen::Vector3d(0.0, 0.8, 0.0), Eigen::Vector3d::Zero()));
  w.samples(m3, 1);

  // What M3Publisher copies into the LaserScan: angle_min = beamAngle(0), angle_max = beamAngle(beams - 1),
  // angle_increment; a consumer puts beam k at angle_min + k angle_increment.
  EXPECT_LT(m3.beamAngle(0), m3.beamAngle(beams - 1));
  EXPECT_LT(m3.angleMin(), m3.angleMax());
  EXPECT_NEAR(m3.angleMin(), -fov / 2.0, 1e-12);
  EXPECT_NEAR(m3.angleMax(), fov / 2.0, 1e-12);
  EXPECT_NEAR(m3.angleIncrement(), fov / (beams - 1), 1e-12);
  for (int k = 0; k < beams; ++k) {
    EXPECT_NEAR(m3.beamAngle(k), -fov / 2.0 + k * fov / (beams - 1), 1e-12) << "beam " << k;
    EXPECT_NEAR(m3.beamAngle(0) + k * m3.angleIncrement(), m3.beamAngle(k), 1e-12) << "beam " << k;
  }

  const Eigen::Vector3d p = w.robot().state().pose * mount;
  ASSERT_LT((p - Eigen::Vector3d(0.3, 0.8, -0.05)).norm(), 1e-3);  // the robot stayed put for the ping
  // By hand: beam 0 (-60 deg) meets y = -2 at 2.8 / sin 60 (x = 2 only at 1.7 / cos 60 = 3.4); beams 1 and 3
  // (-+30 deg) meet x = 2 at 1.7 / cos 30; beam 2 at 1.7; beam 4 (60 deg) meets y = 2 at 1.2 / sin 60.
  const std::vector<double> by_hand = {2.8 / std::sin(60 * kDeg), 1.7 / std::cos(30 * kDeg), 1.7,
                                       1.7 / std::cos(30 * kDeg), 1.2 / std::sin(60 * kDeg)};
  ASSERT_EQ(m3.last().ranges.size(), static_cast<std::size_t>(beams));
  for (int k = 0; k < beams; ++k) {
    const Eigen::Vector3d d = w.robot().state().pose.linear() * ray(k, 0, beams, fov, 1);
    double cos_incidence = 0.0;
    const double range = toBoxWall(p, d, &cos_incidence);
    ASSERT_NEAR(range, by_hand[k], 0.005) << "beam " << k;
    EXPECT_NEAR(m3.last().ranges[k], range, 0.01) << "beam " << k;
    // Intensity: the documented sonar equation (m3_sensor.h, echo_model.h) of the beam's solid angle
    // (fov / beams x 2 sin(fov_v / 2)) at the return's incidence, gain 0.5 x 40 dB, TVG 20 log r + 2 alpha r,
    // 8 bits over 80 dB from 125 dB; within one code. Beam 2 is head-on, the side walls at 60 deg
    // incidence are 6 dB (19 codes) weaker per the cos^2 x footprint / cos law.
    const double level = m3Level(range, cos_incidence, 0.0, fov / beams * 2.0 * std::sin(kFovV / 2.0));
    EXPECT_NEAR(m3.last().intensities[k], m3Intensity(level, range), 1.01 / 255) << "beam " << k << " level " << level;
  }
}

TEST(M3, BeamsBeyondRangeMaxReportNoReturnAndInsideRangeMinTooClose) {
  const double range_min = 1.9, range_max = 2.4;
  SonarWorld w(testBox(), m3Urdf({{"range_min", num(range_min)}, {"range_max", num(range_max)}}));
  auto& m3 = w.sensor<M3Sensor>("m3");
  w.samples(m3, 1);
  const Eigen::Isometry3d sonar = sonarPose(w);
  int inf = 0, too_close = 0, ranged = 0;
  for (int k = 0; k < 256; ++k) {
    const double expected = analytic(sonar, k);
    const float r = m3.last().ranges[k];
    if (expected > range_max + 0.01) {
      EXPECT_TRUE(std::isinf(r) && r > 0) << "beam " << k << ": " << r;  // REP-117: +inf, no return
      EXPECT_EQ(m3.last().intensities[k], 0.0f);
      ++inf;
    } else if (expected < range_min - 0.01) {
      EXPECT_TRUE(std::isinf(r) && r < 0) << "beam " << k << ": " << r;  // REP-117: -inf, too close
      ++too_close;
    } else if (expected > range_min + 0.01 && expected < range_max - 0.01) {
      EXPECT_NEAR(r, expected, 0.01) << "beam " << k;
      ++ranged;
    }
  }
  EXPECT_GT(inf, 10);
  EXPECT_GT(too_close, 10);
  EXPECT_GT(ranged, 10);
}

TEST(M3, GaussianRangeNoiseHasItsStandardDeviationAndRepeatsWithTheSeed) {
  const double sigma = 0.05;
  const auto residuals = [&](std::uint64_t seed, const std::string& noise) {
    SonarWorld w(testBox(), m3Urdf({{"noise", noise}, {"range_noise", num(sigma)}}), seed);
    auto& m3 = w.sensor<M3Sensor>("m3");
    std::vector<double> out;
    for (int ping = 0; ping < 20; ++ping) {
      w.samples(m3, 1);
      const Eigen::Isometry3d sonar = sonarPose(w);
      for (int k = 0; k < 256; ++k)
        out.push_back(m3.last().ranges[k] - analytic(sonar, k));
    }
    return out;
  };
  const auto a = residuals(3, "gaussian");
  double s1 = 0, s2 = 0;
  for (double r : a)
    s1 += r, s2 += r * r;
  const double n = static_cast<double>(a.size()), mean = s1 / n, sd = std::sqrt(s2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(n));
  // sqrt(sigma^2 + res^2 / 12) with the 1 cm rounding; 5120 samples: +-1 % (1 sigma).
  EXPECT_NEAR(sd, std::sqrt(sigma * sigma + 0.01 * 0.01 / 12), 0.05 * sigma);
  EXPECT_EQ(a, residuals(3, "gaussian"));
  EXPECT_NE(a, residuals(4, "gaussian"));
  for (double r : residuals(3, "none"))
    ASSERT_LE(std::abs(r), 0.01);  // noise = none: clean
}

TEST(M3, PingsAtFortyHertzOfSimulationTime) {
  SonarWorld w(testBox(), m3Urdf({}));
  auto& m3 = w.sensor<M3Sensor>("m3");
  for (int k = 1; k <= 80; ++k) {
    w.samples(m3, 1);
    EXPECT_GE(m3.last().time, k / 40.0 - 1e-9);
    EXPECT_LT(m3.last().time, k / 40.0 + 0.002 - 1e-9);
  }
  EXPECT_NEAR(w.world->time(), 2.0, 1e-9);
}

TEST(M3, FirstReturnsStayOnTheTankSurfacesBelowTheWaterNearTheSurface) {
  // worlds/tank.world (walls x = +-3, y = +-2, rim 0.3 m above the free surface z = 0). (a) The M3 0.2 m deep in the
  // corner (0.7 m from x = 3, 0.4 m from y = 2), the fan pitched 20 deg up: beams that meet a wall below the
  // surface (the left ones, on y = 2) measure it (+-1 cm, the ray-plane distance computed here for each ray);
  // beams whose rays meet the surface first report, with multipath off, no return (+inf, not the wall above the
  // water) and with multipath on (the default) the surface's own echo at the nearest ray's surface range (each
  // such echo is a detection: its level by the documented equation, X = -30 - (-20) dB, is computed here and
  // asserted above 82 dB). (b) The UX-1's level fan 1 m deep in the middle of the tank: every beam on a wall, the
  // surface (1 / sin 1.125 deg = 51 m away for the top ray) out of reach, multipath or not.
  struct Case {
    Eigen::Vector3d robot, mount_rpy;
  };
  for (const Case& c : {Case{Eigen::Vector3d(2.0, 1.6, -0.2), Eigen::Vector3d(0.0, -20.0 * kDeg, 0.0)},
                        Case{Eigen::Vector3d(-0.5, 0.3, -1.0), Eigen::Vector3d(0.0, 0.0, 0.3)}}) {
    for (const bool multipath : {false, true}) {
      sim::WorldConfig tank = sim::loadWorldConfig(std::string(UNEXMIN_SOURCE_DIR) + "/worlds/tank.world");
      tank.robots.resize(1);
      const Eigen::Vector3d mount(0.3, 0.0, 0.0);
      tank.robots[0].pose = sim::poseFromXyzRpy(c.robot, Eigen::Vector3d::Zero());
      SonarWorld w(tank, sensorUrdf(SphereSpec(), mountLink("T/m3_link", mount, c.mount_rpy),
                                    sensorXml("m3", "m3", "T/m3_link", 40.0,
                                              {{"noise", "none"}, {"multipath", multipath ? "true" : "false"}})));
      auto& m3 = w.sensor<M3Sensor>("m3");
      w.samples(m3, 1);
      const Eigen::Isometry3d link = w.robot().state().pose * sim::poseFromXyzRpy(mount, c.mount_rpy);
      const Eigen::Vector3d p = link.translation();
      ASSERT_LT(p.z(), 0.0);
      int on_walls = 0, surface = 0;
      for (int k = 0; k < kBeams; ++k) {
        double first = INFINITY;          // the nearest wall hit below the surface over the beam's rays
        double first_surface = INFINITY;  // the nearest surface range over the rays that meet it first
        double surface_level = 0.0;
        bool all_surface = true, all_wall = true;
        for (int j = 0; j < kRaysPerBeam; ++j) {
          const Eigen::Vector3d d = link.linear() * ray(k, j);
          const double lim[2][2] = {{-3, 3}, {-2, 2}};
          double wall = INFINITY;
          for (int a = 0; a < 2; ++a)
            if (std::abs(d[a]) > 1e-12)
              wall = std::min(wall, ((d[a] > 0 ? lim[a][1] : lim[a][0]) - p[a]) / d[a]);
          const double to_surface = d.z() > 0 ? -p.z() / d.z() : INFINITY;
          if (wall < to_surface) {
            first = std::min(first, wall), all_surface = false;
            continue;
          }
          all_wall = false;
          if (to_surface < first_surface)
            first_surface = to_surface, surface_level = m3Level(to_surface, d.z(), -10.0);
        }
        const float r = m3.last().ranges[k];
        if (multipath && std::isfinite(first_surface)) {
          ASSERT_GE(surface_level, kDetection) << "beam " << k;  // the surface echo is a detection
          EXPECT_NEAR(r, std::min(first, first_surface), 0.01) << "beam " << k;
          if (first_surface < first) {
            EXPECT_NEAR(m3.last().intensities[k], m3Intensity(surface_level, first_surface), 1.01 / 255)
                << "beam " << k;
            ++surface;
          }
        } else if (all_surface) {
          EXPECT_EQ(r, std::numeric_limits<float>::infinity()) << "beam " << k;
          ++surface;
        } else if (all_wall) {
          EXPECT_NEAR(r, first, 0.01) << "beam " << k;
          ++on_walls;
        } else {  // multipath off, the beam straddles the waterline: its lowest rays' wall or nothing
          EXPECT_TRUE(std::isinf(r) || std::abs(r - first) < 0.01) << "beam " << k << " range " << r;
        }
      }
      if (c.robot.z() == -0.2) {
        EXPECT_GT(on_walls, 20);
        EXPECT_GT(surface, 20);
      } else {
        EXPECT_EQ(on_walls, kBeams) << "1 m deep";
      }
    }
  }
}

/// The face x = x0 of the plate target (plateTarget: y0..y1, z0..z1), world frame.
struct Face {
  double x0, y0, y1, z0, z1;
  bool inside(const Eigen::Vector3d& q) const { return q.y() >= y0 && q.y() <= y1 && q.z() >= z0 && q.z() <= z1; }
  /// Within 2 cm of an edge: the ray may meet the plate's top or side (1 cm thick) or miss it.
  bool nearEdge(const Eigen::Vector3d& q) const {
    return std::min({std::abs(q.y() - y0), std::abs(q.y() - y1), std::abs(q.z() - z0), std::abs(q.z() - z1)}) < 0.02;
  }
};

enum class Kind { none, direct, surface, ghost };

/// What one beam should report in open water with the face ahead and the free surface z = 0, by the documented
/// model: per ray its direct echo from the face (if it meets it below the surface), else its surface echo at
/// s = -o_z / d_z and its ghost, the reflected ray (d_z -> -d_z) from the surface point to the face at the
/// unfolded range s + leg; levels by m3Level (surface: X = surface_backscatter - BS0, ghost: 40 log10 0.9);
/// the nearest echo whose level reaches `detection` [dB re 1 uPa]. `ambiguous`: a ray that meets the face within
/// 2 cm of an edge would change the answer.
struct Expected {
  double range = INFINITY, level = 0.0;
  Kind kind = Kind::none;
  bool ambiguous = false;
};
Expected firstDetection(const Eigen::Isometry3d& link, int k, const Face& f, double surface_backscatter,
                        double detection, double range_max) {
  Expected sure, any;  // without and with the echoes near an edge
  const Eigen::Vector3d o = link.translation();
  const auto consider = [&](double range, double level, Kind kind, bool edge) {
    if (!(level >= detection && range <= range_max))
      return;
    for (Expected* e : {&any, edge ? nullptr : &sure})
      if (e && range < e->range)
        e->range = range, e->level = level, e->kind = kind;
  };
  for (int j = 0; j < kRaysPerBeam; ++j) {
    const Eigen::Vector3d d = link.linear() * ray(k, j);
    const double t = (f.x0 - o.x()) / d.x();  // d.x > 0: every beam looks ahead
    const double s = d.z() > 0 ? -o.z() / d.z() : INFINITY;
    const Eigen::Vector3d q = o + t * d;
    if (t < s) {
      if (f.nearEdge(q))
        consider(t, m3Level(t, d.x()), Kind::direct, true);  // it may pass over the plate too
      if (f.inside(q)) {
        consider(t, m3Level(t, d.x()), Kind::direct, false);
        continue;
      }
    }
    if (!(s < range_max))
      continue;
    consider(s, m3Level(s, d.z(), surface_backscatter + 20.0), Kind::surface, false);
    if (t <= s)
      continue;  // passed beside the face before the surface: the reflected ray goes away from it
    const Eigen::Vector3d q_s = o + s * d, d_r(d.x(), d.y(), -d.z());
    const double leg = (f.x0 - q_s.x()) / d_r.x();
    const Eigen::Vector3d g = q_s + leg * d_r;
    if (f.inside(g) || f.nearEdge(g))
      consider(s + leg, m3Level(s + leg, d_r.x(), 40 * std::log10(0.9)), Kind::ghost, f.nearEdge(g));
  }
  sure.ambiguous = std::abs(any.range - sure.range) > 0.01 || any.kind != sure.kind;
  return sure;
}

TEST(M3, SurfaceMultipathGhostsAtTheMirrorRangeNearTheSurfaceAndNoneDeeper) {
  // Open water; the M3 pitched 5 deg up (its rays 3.9..6.1 deg up in the middle of the fan, 1.4..3.6 deg at its
  // edges) looking along +x at a plate whose face is 6 m ahead, 24 m wide, from 0.05 to 1.2 m below the surface;
  // range_max 15 m (a tank setting, the thesis used 5 m). Every beam's first return and intensity against the
  // documented model evaluated here (firstDetection: ray-plane geometry, levels, threshold 82 dB), +-1 cm and
  // one code:
  //  - 0.4 m deep, the surface's own echo off (surface_backscatter -100 dB, to see the ghosts alone, as the MSIS
  //    test does): the beams whose rays pass above the plate's top reach the surface (3.7 m on for the steepest
  //    ray) and report the ghost, the plate's mirror image, at surface leg + mirrored leg; the others the plate;
  //  - 0.4 m deep, the default surface_backscatter (-30 dB): those beams report the surface's own echo first;
  //  - 2 m deep (robot and plate 1.6 m deeper, the same geometry relative to each other): the steepest ray meets
  //    the surface 2 / sin 6.1 deg = 18.7 m away, beyond range_max: the geometry no longer reaches it, the ghost
  //    beams report nothing (+inf), the direct ones the same range and code as at 0.4 m;
  //  - 0.4 m deep with the detection threshold raised to 64 dB (detection at 136 dB): the ghosts with the longer
  //    paths (beyond ~6.7 m, levels 134..136 dB: the ghost level falls with the path) fall below it, the nearer
  //    ones (6.0..6.7 m, up to 137.7 dB) stay. (The direct echoes of the fan's sides, 9..12 m, 129..134 dB, go too.)
  // With the defaults the ghosts are 134..138 dB and the direct echoes 129..134 dB against the 82 dB threshold.
  const double pitch = 5.0 * kDeg, ahead = 6.0, range_max = 15.0;
  const Eigen::Vector3d mount(0.3, 0.0, 0.0), mount_rpy(0.0, -pitch, 0.0);
  struct Case {
    double depth, surface_backscatter, threshold;
  };
  const std::vector<Case> cases = {{0.4, -100.0, 10.0}, {0.4, -30.0, 10.0}, {2.0, -100.0, 10.0}, {0.4, -100.0, 64.0}};
  std::vector<M3Scan> scans;
  std::vector<std::vector<Expected>> expected;
  for (const Case& c : cases) {
    const Eigen::Vector3d robot(0.0, 0.0, -c.depth - mount.z());
    const Eigen::Vector3d sonar = robot + mount;
    const double below = c.depth - 0.4 + 0.625;  // plate centre: 0.05..1.2 m below the surface at 0.4 m
    SonarWorld w(meshWorld({{"plate", plateTarget(sonar, ahead, below, 24.0, 1.15)}}, robot),
                 sensorUrdf(SphereSpec(), mountLink("T/m3_link", mount, mount_rpy),
                            sensorXml("m3", "m3", "T/m3_link", 40.0,
                                      {{"noise", "none"},
                                       {"range_max", num(range_max)},
                                       {"surface_backscatter", num(c.surface_backscatter)},
                                       {"detection_threshold", num(c.threshold)}})));
    auto& m3 = w.sensor<M3Sensor>("m3");
    ASSERT_NEAR(m3.detectionLevel(), 72.0 + c.threshold, 1e-12);
    w.samples(m3, 1);
    const Eigen::Isometry3d link = w.robot().state().pose * sim::poseFromXyzRpy(mount, mount_rpy);
    ASSERT_LT((link.translation() - sonar).norm(), 1e-3);  // the robot stayed put
    const Face face{sonar.x() + ahead, -12.0, 12.0, -below - 0.575, -below + 0.575};
    scans.push_back(m3.last());
    expected.emplace_back();
    std::map<Kind, int> kinds;
    for (int k = 0; k < kBeams; ++k) {
      const Expected e = firstDetection(link, k, face, c.surface_backscatter, 72.0 + c.threshold, range_max);
      expected.back().push_back(e);
      if (e.ambiguous)
        continue;
      ++kinds[e.kind];
      const float r = m3.last().ranges[k];
      if (e.kind == Kind::none) {
        EXPECT_EQ(r, std::numeric_limits<float>::infinity()) << "beam " << k << " depth " << c.depth;
        continue;
      }
      EXPECT_NEAR(r, e.range, 0.0051) << "beam " << k << " depth " << c.depth << " kind " << static_cast<int>(e.kind);
      EXPECT_NEAR(m3.last().intensities[k], m3Intensity(e.level, e.range), 1.01 / 255) << "beam " << k;
    }
    std::printf("[ M3 ] %.1f m deep, surface %.0f dB, threshold %.0f dB: %d direct, %d surface, %d ghost, %d none\n",
                c.depth, c.surface_backscatter, c.threshold, kinds[Kind::direct], kinds[Kind::surface],
                kinds[Kind::ghost], kinds[Kind::none]);
    if (&c == &cases[0]) {
      EXPECT_GT(kinds[Kind::ghost], 50);
      EXPECT_GT(kinds[Kind::direct], 50);
    } else if (&c == &cases[1]) {
      EXPECT_GT(kinds[Kind::surface], 50);
      EXPECT_EQ(kinds[Kind::ghost], 0);
    } else if (&c == &cases[2]) {
      EXPECT_EQ(kinds[Kind::ghost] + kinds[Kind::surface], 0);
      // The geometry: no ray of the fan meets the surface within range_max at 2 m.
      for (int k = 0; k < kBeams; ++k)
        for (int j = 0; j < kRaysPerBeam; ++j) {
          const Eigen::Vector3d d = link.linear() * ray(k, j);
          ASSERT_GT(-link.translation().z() / d.z(), range_max) << "beam " << k;
        }
    } else {
      EXPECT_GT(kinds[Kind::ghost], 20);  // the strong ghosts stay
    }
  }
  // 2 m against 0.4 m: the ghost beams empty, the direct ones code for code the same.
  int ghosts_gone = 0, weak_ghosts = 0;  // of the ghost beams at 0.4 m: gone at 2 m; below the raised threshold
  for (int k = 0; k < kBeams; ++k) {
    const Expected& near = expected[0][k];
    if (near.ambiguous || expected[2][k].ambiguous)
      continue;
    if (near.kind == Kind::direct) {
      EXPECT_EQ(scans[2].ranges[k], scans[0].ranges[k]) << "beam " << k;
      EXPECT_EQ(scans[2].intensities[k], scans[0].intensities[k]) << "beam " << k;
    } else if (near.kind == Kind::ghost) {
      EXPECT_EQ(scans[2].ranges[k], std::numeric_limits<float>::infinity()) << "beam " << k;
      ++ghosts_gone;
      weak_ghosts += expected[3][k].kind == Kind::none;
    }
  }
  EXPECT_GT(ghosts_gone, 50);
  EXPECT_GT(weak_ghosts, 20);  // the raised threshold removes the weak (long-path) ghosts
}

TEST(M3, AboveTheWaterTheRaysThatGoUpHearNothing) {
  // The M3 0.2 m above the free surface of open water, its fan pitched 10 deg up (every ray up): a ray that starts
  // above the surface and goes up never enters the water, so it has no echo (a zero-length ray before, which the
  // caster refuses). Every beam: +inf; no surface echo or ghost (the sonar is not submerged).
  const Eigen::Vector3d mount(0.3, 0.0, 0.0), mount_rpy(0.0, -10.0 * kDeg, 0.0);
  const Eigen::Vector3d robot(0.0, 0.0, 0.2);
  SonarWorld w(meshWorld({{"plate", plateTarget(robot + mount, 3.0, -1.0, 10.0, 1.0)}}, robot),
               sensorUrdf(SphereSpec(), mountLink("T/m3_link", mount, mount_rpy),
                          sensorXml("m3", "m3", "T/m3_link", 40.0, {{"noise", "none"}})));
  auto& m3 = w.sensor<M3Sensor>("m3");
  ASSERT_NO_THROW(w.samples(m3, 1));
  ASSERT_GT((w.robot().state().pose * mount).z(), 0.0);
  for (int k = 0; k < kBeams; ++k)
    EXPECT_EQ(m3.last().ranges[k], std::numeric_limits<float>::infinity()) << "beam " << k;
}

TEST(M3, BadParametersNameTheSensorAndTheParameter) {
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{{"beams", "0"},
                                                                                   {"beams", "2.5"},
                                                                                   {"range_max", "0.1"},
                                                                                   {"fov_h", "7"},
                                                                                   {"range_resolution", "0"},
                                                                                   {"rays_per_beam", "0"},
                                                                                   {"noise", "white"},
                                                                                   {"ranges_max", "3"},
                                                                                   {"multipath", "maybe"},
                                                                                   {"surface_reflection", "1.5"},
                                                                                   {"detection_threshold", "-1"},
                                                                                   {"noise_level", "-5"}}) {
    try {
      SonarWorld w(testBox(), m3Urdf({{key, value}}));
      ADD_FAILURE() << "no error for " << key << " = " << value;
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("sensor 'm3'"), std::string::npos) << m;
      EXPECT_NE(m.find("'" + key + "'"), std::string::npos) << m;
    }
  }
}

TEST(M3, InColdFreshWaterASonarSetToFifteenHundredReadsEveryRangeLong) {
  // the box filled with fresh water at 8 degC: sound at ~1440 m/s, so a sonar that assumes 1500 m/s reads each
  // range 1500 / c times the true one (about 4 % long); set to the water's own speed, it reads the truth
  sim::WorldConfig box = testBox();
  water::Profile cold;
  cold.rows.resize(1);
  cold.rows[0].temperature = 8.0;
  water::checkProfile(cold, "water.profile");
  box.water_column =
      std::make_shared<const water::WaterColumn>(cold, std::vector<water::Region>{}, box.surface_z, box.gravity);
  const Eigen::Isometry3d pose = sim::poseFromXyzRpy(Eigen::Vector3d(-0.4, 0.3, 0.2), Eigen::Vector3d(0.1, -0.15, 0.3));
  SonarWorld w(box, m3Urdf({}));
  auto& m3 = w.sensor<M3Sensor>("m3");
  w.place(pose);
  w.samples(m3, 1);
  const Eigen::Isometry3d sonar = sonarPose(w);
  const double depth = box.surface_z - sonar.translation().z();
  const double c = water::soundSpeed(0.0, 8.0, 1e-4 * 1000.0 * box.gravity * depth);  // at the sonar
  ASSERT_NEAR(c, 1439.1 + 0.0163 * depth, 0.3);  // Chen & Millero's pure water plus ~0.016 m/s per dbar
  int long_by_4cm = 0;
  for (int k = 0; k < 256; ++k) {
    const double truth = analytic(sonar, k);
    EXPECT_NEAR(m3.last().ranges[k], truth * 1500.0 / c, 0.01) << "beam " << k;
    long_by_4cm += m3.last().ranges[k] - truth > 0.04;
  }
  EXPECT_GT(long_by_4cm, 200);  // the stretch is far beyond the resolution: a model that ignores it fails
  SonarWorld tuned(box, m3Urdf({{"sound_speed", num(c)}}));
  auto& right = tuned.sensor<M3Sensor>("m3");
  tuned.place(pose);
  tuned.samples(right, 1);
  for (int k = 0; k < 256; ++k)
    EXPECT_NEAR(right.last().ranges[k], analytic(sonar, k), 0.01) << "beam " << k;
  // sound_speed = probe: the head's sound velocity probe gives the water's speed, so the ranges are true there too
  SonarWorld probed(box, m3Urdf({{"sound_speed", "probe"}}));
  auto& probe = probed.sensor<M3Sensor>("m3");
  probed.place(pose);
  probed.samples(probe, 1);
  for (int k = 0; k < 256; ++k)
    EXPECT_NEAR(probe.last().ranges[k], analytic(sonar, k), 0.01) << "beam " << k;
  // a text other than probe names the parameter
  EXPECT_THROW(SonarWorld(box, m3Urdf({{"sound_speed", "auto"}})), ConfigError);
}

}  // namespace
}  // namespace test
}  // namespace unexmin
