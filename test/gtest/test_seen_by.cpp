// Which ray sensors see which world meshes (docs/worlds.md, "Who sees a mesh"): a visual-only plate is in the camera
// image where CameraInfo projects it and is not felt; a collision-only plate stops the robot, echoes and is not in
// the image; entries of one file share one mesh; a bad `seen_by` stops start-up naming its key.
#include <unexmin/raycast/bullet_ray_caster.h>
#include <unexmin/raycast/embree_ray_caster.h>
#include <unexmin/raycast/ray_caster_factory.h>
#include <unexmin/sensors/vision/camera_sensor.h>
#include <unexmin/sensors/vision/sls_sensor.h>
#include "expect_error.h"
#include "mesh_fixture.h"
#include "sensor_fixture.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

namespace unexmin {
namespace test {
namespace {

using raycast::SeenBy;

const Eigen::Vector3d kSpawn(0.0, 0.0, -10.0);  // [m] the sphere robot, open water
const Eigen::Vector3d kLens(0.3, 0.0, 0.0);     // [m] camera on the hull's front, base frame
constexpr int kWidth = 160, kHeight = 120;      // [px]

/// A thin plate across +x at `x` [m] (world), y in [y0, y1], z within `half` of the robot's depth.
sim::MeshEntry plate(const std::string& name, double x, double y0, double y1, double half, bool collision,
                     bool visual) {
  sim::MeshEntry e;
  e.name = name;
  e.file =
      writeStl(name, box(Eigen::Vector3d(x, y0, kSpawn.z() - half), Eigen::Vector3d(x + 0.01, y1, kSpawn.z() + half)));
  e.albedo = Eigen::Vector3d::Constant(0.8);
  e.collision = e.seen_by_sonars = collision;
  e.visual = e.seen_by_cameras = visual;
  return e;
}

sim::WorldConfig withPlates(const std::vector<sim::MeshEntry>& plates) {
  sim::WorldConfig config = openWater(SphereSpec(), kSpawn);
  config.meshes = plates;
  return config;
}

/// The sphere robot with a forward camera (optical z along +x) and an LED beside the lens.
std::string cameraRobot() {
  const std::map<std::string, std::string> params{
      {"width", num(kWidth)}, {"height", num(kHeight)},    {"hfov", num(60.0 * M_PI / 180.0)},
      {"noise", "none"},      {"exposure", "10"},          {"clip_far", "10"},
      {"lights", "T/led"},    {"light_intensity", "2 2 2"}};
  return sensorUrdf(SphereSpec(),
                    mountLink("T/cam", kLens, Eigen::Vector3d(-M_PI / 2, 0, -M_PI / 2)) +
                        mountLink("T/led", kLens + Eigen::Vector3d(0, 0, 0.1), Eigen::Vector3d::Zero()),
                    sensorXml("cam", "camera", "T/cam", 10.0, params));
}

/// One camera frame of the robot held at its spawn pose in `config`, cast by back end `backend`.
sensors::vision::CameraFrame render(const sim::WorldConfig& config, const std::string& backend = "embree") {
  std::map<std::string, sim::RobotDescription> d;
  d.emplace("T", sim::parseRobotDescription(cameraRobot(), "(camera robot)"));
  sim::World world(config, d, 1, 0.002, 1);
  auto caster = raycast::makeRayCaster(backend, world);
  sensors::SensorFactory factory = coreModels();
  factory.add<sensors::vision::CameraSensor>("camera");
  sensors::SensorSuite suite(world, world.robot(0), caster.get(), factory, sensors::SensorSelection(), true);
  const sensors::Sensor& cam = *suite.find("cam");
  const Eigen::Isometry3d pose = Eigen::Isometry3d(Eigen::Translation3d(kSpawn));
  while (cam.sampleCount() == 0) {
    world.robot(0).setPose(pose);
    world.step();
    world.robot(0).setPose(pose);
    caster->update();
    suite.update();
  }
  return dynamic_cast<const sensors::vision::CameraSensor&>(cam).last();
}

/// Centroid [px] and count of the pixels of `frame` whose green exceeds `level` in columns [u0, u1).
Eigen::Vector3d brightPixels(const sensors::vision::CameraFrame& f, int u0, int u1, int level) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int v = 0; v < f.height; ++v)
    for (int u = u0; u < u1; ++u)
      if (f.rgb[3 * (v * f.width + u) + 1] > level)
        sum += Eigen::Vector3d(u, v, 1);
  return sum.z() > 0 ? Eigen::Vector3d(sum.x() / sum.z(), sum.y() / sum.z(), sum.z()) : sum;
}

TEST(SeenBy, AVisualOnlyPlateIsInTheImageWhereCameraInfoPutsItAndACollisionOnlyOneIsNot) {
  // Two plates 1.5 m ahead: the visual-only one on the left (+y), the collision-only one on the right (-y).
  const double x = 1.5, y0 = 0.1, y1 = 0.4, half = 0.15;
  const sim::MeshEntry decoration = plate("decoration", x, y0, y1, half, false, true);
  const sim::MeshEntry twin = plate("coarse_twin", x, -y1, -y0, half, true, false);
  for (const std::string backend : {"embree", "bullet"}) {
    SCOPED_TRACE(backend);
    const auto frame = render(withPlates({decoration, twin}), backend);
    ASSERT_TRUE(frame.rendered);
    // CameraInfo of this camera: pinhole, no distortion, fx = (w / 2) / tan(hfov / 2), principal point at the
    // centre ((w - 1) / 2 with pixel centres at integers, as CameraModel writes K).
    const double f = kWidth / 2.0 / std::tan(30.0 * M_PI / 180.0), cx = (kWidth - 1) / 2.0, cy = (kHeight - 1) / 2.0;
    const double depth = x - kLens.x();  // optical z of the plate's face
    const Eigen::Vector2d expected(cx + f * (-(y0 + y1) / 2.0) / depth, cy);
    const Eigen::Vector3d left = brightPixels(frame, 0, kWidth / 2, 20);
    const double side = f * (y1 - y0) / depth;  // [px] the plate's width in the image
    EXPECT_NEAR(left.z(), side * side, 0.25 * side * side);
    EXPECT_NEAR(left.x(), expected.x(), 0.6);
    EXPECT_NEAR(left.y(), expected.y(), 0.6);
    EXPECT_EQ(brightPixels(frame, kWidth / 2, kWidth, 20).z(), 0) << "the collision-only plate was seen";
    EXPECT_EQ(frame.rgb, render(withPlates({decoration}), backend).rgb) << "the collision-only plate changed the image";
    sim::MeshEntry seen = twin;  // the same plate shown to the cameras is in the image (the comparison can fail)
    seen.seen_by_cameras = true;
    EXPECT_GT(brightPixels(render(withPlates({decoration, seen}), backend), kWidth / 2, kWidth, 20).z(),
              0.5 * left.z());
  }
}

/// x [m] of the robot after pushing +x for `seconds` towards a plate at x = 1 m.
double pushedTowards(const sim::MeshEntry& wall, double seconds) {
  auto world = makeWorld(withPlates({wall}), SphereSpec());
  for (int i = 0; i < static_cast<int>(seconds / world->dt()); ++i) {
    world->robot(0).thruster(0).setCommand(30.0, world->time());
    world->step();
  }
  return world->robot(0).state().pose.translation().x();
}

TEST(SeenBy, ACollisionOnlyPlateStopsTheRobotAndAVisualOnlyOneIsNotFelt) {
  // 30 N against quadratic damping 66.44 N s^2/m^2: ~0.67 m/s, 3 m in 6 s unless something stops the sphere.
  const double wall = 1.0, radius = SphereSpec().radius;
  const double stopped = pushedTowards(plate("wall", wall, -1.0, 1.0, 1.0, true, false), 6.0);
  EXPECT_LT(stopped, wall - radius + 0.02);
  EXPECT_GT(stopped, wall - radius - 0.1);
  EXPECT_GT(pushedTowards(plate("wall", wall, -1.0, 1.0, 1.0, false, true), 6.0), wall + 1.0);
}

TEST(SeenBy, SonarRaysMeetTheCollisionMeshesAndCameraRaysTheVisualOnes) {
  auto world = makeWorld(withPlates({plate("decoration", 1.5, 0.1, 0.4, 0.15, false, true),
                                     plate("coarse_twin", 1.5, -0.4, -0.1, 0.15, true, false)}),
                         SphereSpec());
  for (const std::string backend : {"embree", "bullet"}) {
    SCOPED_TRACE(backend);
    auto caster = raycast::makeRayCaster(backend, *world);
    caster->update();
    std::vector<raycast::Ray> rays(2);
    for (int k = 0; k < 2; ++k) {
      rays[k].origin = Eigen::Vector3f(0.5f, k == 0 ? 0.25f : -0.25f, static_cast<float>(kSpawn.z()));
      rays[k].max_range = 5.0f;
    }
    std::vector<raycast::Hit> sonar, camera;
    caster->cast(rays, sonar, 0);
    caster->cast(rays, camera, 0, raycast::Incidence::compute, SeenBy::cameras);
    EXPECT_FALSE(sonar[0].hit());
    ASSERT_TRUE(sonar[1].hit());
    EXPECT_EQ(sonar[1].index, 1);
    EXPECT_NEAR(sonar[1].range, 1.0, 1e-4);
    ASSERT_TRUE(camera[0].hit());
    EXPECT_EQ(camera[0].index, 0);
    EXPECT_NEAR(camera[0].range, 1.0, 1e-4);
    EXPECT_FALSE(camera[1].hit());
    // The triangle and the barycentric coordinates give back the hit point.
    const sim::TriangleMesh& m = world->mesh(0);
    const raycast::Hit& h = camera[0];
    ASSERT_GE(h.primitive, 0);
    const Eigen::Vector3f p = (1 - h.u - h.v) * m.vertices[m.indices[3 * h.primitive]] +
                              h.u * m.vertices[m.indices[3 * h.primitive + 1]] +
                              h.v * m.vertices[m.indices[3 * h.primitive + 2]];
    EXPECT_LT((p - h.point(rays[0])).norm(), 1e-4f);
  }
}

/// The SLS scan of a unit 10 cm left of the lens (vertical fan of 1 rad, 50 rays, along +x) facing `plate`.
sensors::vision::SlsScan slsScan(const sim::MeshEntry& wall) {
  const std::string links =
      mountLink("T/cam", kLens, Eigen::Vector3d(-M_PI / 2, 0, -M_PI / 2)) +
      "<link name='T/sls'/><joint name='T/sls_motor' type='revolute'><parent link='T/base_link'/><child "
      "link='T/sls'/><origin xyz='0.3 0.1 0' rpy='0 0 0'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' "
      "effort='1' velocity='1'/></joint>\n";
  const std::map<std::string, std::string> params{{"camera_frame", "T/cam"},
                                                  {"camera_width", "160"},
                                                  {"camera_height", "120"},
                                                  {"camera_hfov", "1.0471975511965976"},
                                                  {"fan", "1"},
                                                  {"rays", "50"},
                                                  {"motor_speed", "0"},
                                                  {"noise", "none"}};
  SensorWorld w(withPlates({wall}), sensorUrdf(SphereSpec(), links, sensorXml("sls", "sls", "T/sls", 10.0, params)));
  const auto& sls = dynamic_cast<const sensors::vision::SlsSensor&>(*w.suite->find("sls"));
  w.samples(sls, 1);
  return sls.last();
}

TEST(SeenBy, TheSlsLaserAndItsCameraSeeTheVisualMeshesOnly) {
  // A 0.6 m plate 1.2 m ahead of the unit: 0.6 / 1.2 rad of the 1 rad fan meet it (about 24 of the 50 rays).
  const auto count = [](const std::vector<float>& r) {
    return std::count_if(r.begin(), r.end(), [](float x) { return std::isfinite(x); });
  };
  const auto seen = slsScan(plate("decoration", 1.5, -0.3, 0.3, 0.3, false, true));
  EXPECT_NEAR(count(seen.ranges), 50 * 2 * std::atan(0.3 / 1.2), 2.0);
  EXPECT_EQ(seen.points.size(), static_cast<std::size_t>(count(seen.ranges)));
  const auto unseen = slsScan(plate("coarse_twin", 1.5, -0.3, 0.3, 0.3, true, false));
  EXPECT_EQ(count(unseen.ranges), 0);
  EXPECT_TRUE(unseen.points.empty());
}

TEST(SeenBy, EntriesOfOneFileShareOneMeshAndRenderAsOneEntry) {
  // The plate as one entry (collision and visual), then as a collision-only and a visual-only entry of that file.
  const sim::MeshEntry both = plate("plate", 1.5, -0.3, 0.3, 0.3, true, true);
  sim::MeshEntry sonar_twin = both, camera_twin = both;
  sonar_twin.visual = sonar_twin.seen_by_cameras = false;
  camera_twin.collision = camera_twin.seen_by_sonars = false;
  camera_twin.albedo = Eigen::Vector3d::Constant(0.4);
  const sim::WorldConfig split = withPlates({sonar_twin, camera_twin});
  auto world = makeWorld(split, SphereSpec());
  EXPECT_EQ(&world->mesh(0), &world->mesh(1)) << "the same file, scale and pose is loaded once";
  raycast::EmbreeRayCaster caster(*world);
  EXPECT_EQ(raycast::seenMeshes(*world).size(), 1u);
  std::vector<raycast::Ray> ray(1);
  ray[0].origin = kSpawn.cast<float>() + Eigen::Vector3f(0.5f, 0, 0);
  std::vector<raycast::Hit> hit;
  caster.cast(ray, hit, 0);
  EXPECT_EQ(hit[0].index, 0);
  caster.cast(ray, hit, 0, raycast::Incidence::compute, SeenBy::cameras);
  EXPECT_EQ(hit[0].index, 1);

  sim::WorldConfig one = withPlates({both});
  one.meshes[0].albedo = camera_twin.albedo;  // the cameras see the visual entry's material
  EXPECT_EQ(render(split).rgb, render(one).rgb);
}

TEST(SeenBy, ABadSeenByStopsStartUpNamingTheFileAndTheKey) {
  const std::string dir = testTempDir() + "seen_by/";
  std::filesystem::create_directories(dir);
  writeStl("seen_by/plate", box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()));
  const auto load = [&](const std::string& seen_by) {
    std::ofstream(dir + "w.world")
        << "robots: [{name: UX_1}]\nmeshes:\n  - {file: plate.stl, collision: false, seen_by: " << seen_by << "}\n";
    return sim::loadWorldConfig(dir + "w.world");
  };
  const sim::WorldConfig ok = load("[sonars]");
  EXPECT_TRUE(ok.meshes[0].seen_by_sonars);
  EXPECT_FALSE(ok.meshes[0].seen_by_cameras);
  const sim::WorldConfig none = load("[]");
  EXPECT_FALSE(none.meshes[0].seen_by_sonars || none.meshes[0].seen_by_cameras);
  for (const auto& bad : {std::make_pair("[camera]", "seen_by[0]' is 'camera'"),
                          std::make_pair("[cameras, cameras]", "seen_by[1]' is 'cameras'"),
                          std::make_pair("cameras", "seen_by' must be a list")}) {
    const std::string what = thrownMessage<ConfigError>([&] { load(bad.first); });
    EXPECT_TRUE(contains(what, dir + "w.world: ")) << what;
    EXPECT_TRUE(contains(what, "'meshes[0]." + std::string(bad.second))) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace test
}  // namespace unexmin
