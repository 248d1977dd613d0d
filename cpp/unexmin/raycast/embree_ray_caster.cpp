#include <unexmin/raycast/embree_ray_caster.h>

#include <unexmin/sim/world.h>

#include <cmath>
#include <cstring>
#include <string>

namespace unexmin {
namespace raycast {
namespace {

const char* errorName(RTCError e) {
  switch (e) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "unrecognised error";
}

/// Nearest robot sphere along the ray (origin o, unit direction d) closer than t_max [m], robot `exclude`
/// left out; returns its index (t_max lowered to its range) or -1.
int nearestRobot(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const std::vector<RobotSphere>& robots,
                 int exclude, float& t_max) {
  int best = -1;
  double t_best = t_max;
  for (int i = 0; i < static_cast<int>(robots.size()); ++i) {
    double t;
    if (i == exclude || !raySphere(o, d, robots[i].center, robots[i].radius, t) || t > t_best)
      continue;
    t_best = t;
    best = i;
  }
  if (best >= 0)
    t_max = static_cast<float>(t_best);
  return best;
}

}  // namespace

EmbreeRayCaster::EmbreeRayCaster(const std::vector<const sim::TriangleMesh*>& meshes, RobotSphereSource robots,
                                 const RayCasterOptions& options)
    : RayCaster(options), source_(std::move(robots)) {
  std::vector<SeenMesh> seen;
  for (std::size_t i = 0; i < meshes.size(); ++i)  // geometry ID = position in `meshes`, null ones skipped
    seen.push_back(SeenMesh{meshes[i], meshes[i] ? 3u : 0u, static_cast<int>(i), static_cast<int>(i)});
  build(seen, options.watertight, false);
  update();
}

EmbreeRayCaster::EmbreeRayCaster(const std::vector<SeenMesh>& meshes, RobotSphereSource robots,
                                 const RayCasterOptions& options)
    : RayCaster(options), source_(std::move(robots)) {
  build(meshes, options.watertight, false);
  update();
}

EmbreeRayCaster::EmbreeRayCaster(sim::World& world, const RayCasterOptions& options)
    : RayCaster(options), source_([&world](std::vector<RobotSphere>& s) { s = robotSpheres(world); }) {
  build(seenMeshes(world), options.watertight, true);  // the world outlives the caster: its arrays are used in place
  update();
}

EmbreeRayCaster::~EmbreeRayCaster() {
  if (scene_)
    rtcReleaseScene(scene_);
  if (device_)
    rtcReleaseDevice(device_);
}

void EmbreeRayCaster::check(const char* what) const {
  const RTCError e = rtcGetDeviceError(device_);
  if (e != RTC_ERROR_NONE)
    throw RayCasterError(std::string("embree ray caster: ") + what + ": " + errorName(e));
}

void EmbreeRayCaster::build(const std::vector<SeenMesh>& meshes, bool watertight, bool in_place) {
  device_ = rtcNewDevice(nullptr);
  if (!device_)
    throw RayCasterError(std::string("embree ray caster: cannot create a device: ") +
                         errorName(rtcGetDeviceError(nullptr)));
  scene_ = rtcNewScene(device_);
  // Robust mode makes shared triangle edges watertight: without it 1-5 % of rays aimed exactly at a shared
  // edge of a closed mesh slip through (measured: tunnel, icosphere); with it none do, for 5-25 % of speed.
  // (Rays aimed exactly at a vertex still leak at ~0.2 %; real rays meet a vertex with probability ~1e-12.)
  rtcSetSceneFlags(scene_, watertight ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
  // Which sensors see a mesh is its geometry mask, tested against the ray's mask (SeenBy) inside the traversal:
  // one scene for every sensor.
  const bool masks = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED) != 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const sim::TriangleMesh* mesh = meshes[m].mesh;
    index_.push_back({meshes[m].sonar_index, meshes[m].camera_index});
    if (!mesh || mesh->triangleCount() == 0 || meshes[m].seen_by == 0)
      continue;
    if (!masks && meshes[m].seen_by != 3u)
      throw RayCasterError("embree ray caster: mesh '" + mesh->name +
                           "' is not seen by every ray sensor (seen_by), and this Embree library was built "
                           "without ray masks (EMBREE_RAY_MASK): use ray_caster: bullet");
    const std::size_t nv = mesh->vertices.size();
    for (int i : mesh->indices)
      if (i < 0 || static_cast<std::size_t>(i) >= nv)
        throw RayCasterError("embree ray caster: mesh '" + mesh->name + "' has vertex index " + formatNumber(i) +
                             " outside [0, " + formatNumber(nv) + ")");
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float) && sizeof(int) == sizeof(unsigned),
                  "the mesh arrays are Embree's FLOAT3 and UINT3 layouts");
    if (in_place && mesh->vertices.capacity() > nv) {
      // The mesh's own arrays (indices checked >= 0 above): Embree's 16-byte load of the last vertex reads the spare
      // slot loadMesh() leaves after it (TriangleMesh::vertices).
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh->vertices.data(), 0,
                                 sizeof(Eigen::Vector3f), nv);
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh->indices.data(), 0,
                                 3 * sizeof(int), mesh->triangleCount());
      check(("sharing the arrays of mesh '" + mesh->name + "'").c_str());
    } else {
      // Embree's own buffers are padded for its 16-byte vertex loads, which a tight Vector3f array is not.
      auto* v = static_cast<float*>(
          rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
      auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), mesh->triangleCount()));
      check(("allocating mesh '" + mesh->name + "'").c_str());
      for (std::size_t i = 0; i < nv; ++i)
        std::memcpy(v + 3 * i, mesh->vertices[i].data(), 3 * sizeof(float));
      for (std::size_t i = 0; i < mesh->indices.size(); ++i)
        t[i] = static_cast<unsigned>(mesh->indices[i]);
    }
    rtcSetGeometryMask(geometry, meshes[m].seen_by);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene_, geometry, static_cast<unsigned>(m));  // geometry ID = position in `meshes`
    rtcReleaseGeometry(geometry);
    check(("adding mesh '" + mesh->name + "'").c_str());
  }
  rtcCommitScene(scene_);
  check("building the scene");
}

void EmbreeRayCaster::update() {
  if (source_)
    source_(robots_);
}

void EmbreeRayCaster::castBlock(const Ray* rays, Hit* hits, std::size_t n, int exclude_robot, SeenBy seen_by) const {
  RTCRayHit rh[kBlock];
  int robot[kBlock];
  const Eigen::Vector3f d0 = rays[0].direction.normalized();
  bool coherent = true;
  // Robots a ray can meet: none when the only one is the excluded (a robot's own sensors, alone in its world).
  const bool robots = robots_.size() > (exclude_robot >= 0 && static_cast<std::size_t>(exclude_robot) < robots_.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Ray& ray = rays[i];
    const Eigen::Vector3f d = ray.direction.normalized();  // ranges are true distances even if |d| != 1
    float t_far = ray.max_range;
    robot[i] = robots ? nearestRobot(ray.origin.cast<double>(), d.cast<double>(), robots_, exclude_robot, t_far) : -1;
    RTCRay& r = rh[i].ray;
    r.org_x = ray.origin.x();
    r.org_y = ray.origin.y();
    r.org_z = ray.origin.z();
    r.dir_x = d.x();
    r.dir_y = d.y();
    r.dir_z = d.z();
    r.tnear = 0.0f;
    r.tfar = t_far;  // a robot in front hides whatever is behind it: Embree stops looking there
    r.time = 0.0f;
    r.mask = static_cast<unsigned>(seen_by);
    r.id = static_cast<unsigned>(i);
    r.flags = 0;
    rh[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    coherent = coherent && (ray.origin - rays[0].origin).squaredNorm() <= kCoherentOrigin * kCoherentOrigin &&
               d.dot(d0) >= kCoherentCos;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  rtcIntersect1M(scene_, &context, rh, static_cast<unsigned>(n), sizeof(RTCRayHit));

  for (std::size_t i = 0; i < n; ++i) {
    const Ray& ray = rays[i];
    Hit& hit = hits[i];
    const RTCRayHit& h = rh[i];
    if (h.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      const int index = index_[h.hit.geomID][seen_by == SeenBy::cameras ? 1 : 0];
      finishHit(ray, Eigen::Vector3f(h.hit.Ng_x, h.hit.Ng_y, h.hit.Ng_z), h.ray.tfar, HitKind::mesh, index, hit,
                static_cast<int>(h.hit.primID), h.hit.u, h.hit.v);
    } else if (robot[i] >= 0) {
      const RobotSphere& s = robots_[robot[i]];
      const double t = h.ray.tfar;
      const Eigen::Vector3d p = Eigen::Vector3d(h.ray.org_x, h.ray.org_y, h.ray.org_z) +
                                t * Eigen::Vector3d(h.ray.dir_x, h.ray.dir_y, h.ray.dir_z);
      finishHit(ray, (p - s.center).cast<float>(), h.ray.tfar, HitKind::robot, robot[i], hit);
    } else {
      hit = Hit();
    }
  }
}

}  // namespace raycast
}  // namespace unexmin
