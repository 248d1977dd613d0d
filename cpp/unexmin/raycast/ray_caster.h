// One ray-casting service for every ray sensor (MSIS, multibeam, DVL beams, SLS lasers): batched rays
// against the same world as physics, the static triangle meshes and the robots' hull spheres.
// Knows no ROS. Back ends by name: "embree" (default, fast) and "bullet" (fallback). See docs/ray_casting.md.
#pragma once

#include <unexmin/core/error.h>
#include <unexmin/raycast/block.h>

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {
class World;
struct TriangleMesh;
}  // namespace sim

namespace raycast {

/// One ray, world frame. Single precision, like the meshes and both back ends.
struct Ray {
  Eigen::Vector3f origin{0, 0, 0};     ///< Start point, world frame [m].
  Eigen::Vector3f direction{1, 0, 0};  ///< World frame, unit length (checked to 1e-3).
  float max_range = 1.0f;              ///< Farthest distance that counts as a hit [m], finite and > 0.
};

/// What a ray hit.
enum class HitKind : std::uint8_t {
  none,   ///< Nothing within max_range.
  mesh,   ///< A static mesh: Hit::index is its index in World::mesh() (the world file's mesh entry).
  robot,  ///< A robot hull: Hit::index is its index in World::robot(i).
};

/// Which world meshes a cast meets (the world file's `seen_by:` of each mesh, docs/worlds.md): the acoustic sensors
/// (M3, MSIS, DVL, imaging and side-scan sonars) see the meshes seen by `sonars` (by default the collision meshes, as
/// physics), the optical ones (cameras, their shadow rays, the SLS lasers and their sight lines) those seen by
/// `cameras` (by default the visual meshes). Robots are seen by both.
enum class SeenBy : std::uint8_t {
  sonars = 1,   ///< the acoustic sensors (and any caller that does not say)
  cameras = 2,  ///< the optical sensors
};

struct Hit {
  /// Distance from the ray origin to the first surface [m]; +inf when nothing within max_range.
  float range = std::numeric_limits<float>::infinity();
  /// Surface normal at the hit, world frame, unit, facing the ray (normal . direction <= 0); zero on no hit.
  Eigen::Vector3f normal{0, 0, 0};
  /// Angle between -direction and the normal [rad], 0 (head-on) .. pi/2 (grazing); NaN on no hit, and NaN when
  /// the cast asked for no incidence (Incidence::skip: RayCaster::incidence() gives it for the hits that need it).
  float incidence = std::numeric_limits<float>::quiet_NaN();
  HitKind kind = HitKind::none;
  int index = -1;  ///< Mesh or robot index (see HitKind); -1 on no hit.
  /// Triangle of the mesh hit (its position in TriangleMesh::indices / 3); -1 on no hit and on a robot.
  int primitive = -1;
  /// Barycentric coordinates of the hit in that triangle: point = (1 - u - v) p0 + u p1 + v p2, with p0, p1, p2 its
  /// three vertices in index order [-]; 0 on no hit and on a robot.
  float u = 0.0f, v = 0.0f;

  bool hit() const { return kind != HitKind::none; }
  /// World point of the hit [m] (meaningless on no hit).
  Eigen::Vector3f point(const Ray& ray) const { return ray.origin + range * ray.direction; }
};

/// A robot hull as rays see it: a sphere, world frame.
struct RobotSphere {
  Eigen::Vector3d center{0, 0, 0};  ///< World frame [m].
  double radius = 0.0;              ///< [m]
};

/// Whether RayCaster::cast() fills Hit::incidence. `skip` saves an atan2 per hit (about a tenth of a sonar's cost)
/// for callers that need the incidence of a few hits only (RayCaster::incidence() gives the same value) or none.
enum class Incidence : std::uint8_t {
  compute,  ///< every hit's incidence (the default)
  skip,     ///< left NaN
};

/// Distance [m] along the ray (origin o, unit direction d) to the sphere (c, r): the entry point, or the exit
/// point when o is inside (as a ray meets the inside of a closed mesh); false when it misses or is behind.
/// Exact in double precision; both back ends use it for robot hulls (inline: it runs for every ray and robot).
inline bool raySphere(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& c, double r,
                      double& t) {
  const Eigen::Vector3d oc = c - o;
  const double b = oc.dot(d);                            // along the ray to the closest approach
  const double h2 = r * r - (oc - b * d).squaredNorm();  // half chord squared, free of cancellation
  if (h2 < 0.0)
    return false;
  const double h = std::sqrt(h2);
  t = oc.squaredNorm() < r * r ? b + h : b - h;
  return t >= 0.0;
}

/// A mesh as a caster holds it: the triangles (world frame), which sensors see them (SeenBy bits) and the mesh
/// index a hit reports to each: entries of the world file with the same triangles (file, scale and pose) share one.
struct SeenMesh {
  const sim::TriangleMesh* mesh = nullptr;
  unsigned seen_by = 3;   ///< SeenBy bits: 1 sonars, 2 cameras
  int sonar_index = -1;   ///< Hit::index of a hit cast for the sonars (-1 when they do not see it)
  int camera_index = -1;  ///< Hit::index of a hit cast for the cameras (-1 when they do not see it)
  /// The index a hit cast for `seen_by` reports.
  int index(SeenBy who) const { return who == SeenBy::cameras ? camera_index : sonar_index; }
};

/// The world's meshes that some sensor sees (MeshEntry::seen_by_cameras / seen_by_sonars), one per distinct mesh
/// of World::mesh(), in the order of their first entry; a mesh seen by the same sensors through two entries reports
/// the first of them.
std::vector<SeenMesh> seenMeshes(const sim::World& world);

/// Fills the robots' current spheres, indexed by robot index (called by update()).
using RobotSphereSource = std::function<void(std::vector<RobotSphere>&)>;

/// The hull spheres of the world's robots now: centre from the body pose, radius from the collision shape.
/// Throws RayCasterError when a robot's collision shape is not a sphere.
std::vector<RobotSphere> robotSpheres(sim::World& world);

struct RayCasterOptions {
  /// Threads that cast, the calling thread included; 0 = every hardware thread. Results do not depend on it.
  int threads = 0;
  /// Embree: robust triangle test, so no ray slips between two triangles sharing an edge. false is 5-25 %
  /// faster but lets rays passing within rounding of an edge through (5 % of rays aimed exactly at edges;
  /// none of 409 600 random rays in the benchmark). See docs/ray_casting.md. Bullet: always watertight.
  bool watertight = true;
};

class WorkerPool;

/// Casts batches of rays against a world whose meshes are fixed when the caster is built and whose robots
/// move (seen as of the last update()). update() and cast() must not run while the world steps; cast() is
/// const and may be called from several threads at once (only one call at a time uses the worker threads,
/// the others cast on their caller's thread; the results are the same).
class RayCaster {
public:
  /// Batches shorter than this are cast on the calling thread alone (waking workers costs more).
  static constexpr std::size_t kParallelMin = 256;

  virtual ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Back-end name, as given to makeRayCaster().
  virtual const char* name() const = 0;

  /// Refresh the moving robots' poses; call once per physics step before the sensors cast.
  virtual void update() = 0;

  /// Casts every ray; `hits` is resized to rays.size(), hits[i] answers rays[i]: the first surface at a
  /// distance in [0, max_range], triangles seen from either side (no back-face culling). The robot with index
  /// `exclude_robot` (the sensor's own; -1 = none; an index with no robot excludes nothing) is invisible.
  /// Throws RayCasterError naming the first bad ray (non-finite origin, direction not unit, max_range not
  /// finite and > 0) before casting any. `incidence`: whether Hit::incidence is filled (Incidence::skip: NaN).
  /// `seen_by`: the meshes the rays meet, those the world shows to the sonars (default) or to the cameras.
  void cast(const std::vector<Ray>& rays, std::vector<Hit>& hits, int exclude_robot = -1,
            Incidence incidence = Incidence::compute, SeenBy seen_by = SeenBy::sonars) const;
  /// Same on raw arrays of n rays and n hits.
  void cast(const Ray* rays, Hit* hits, std::size_t n, int exclude_robot = -1, Incidence incidence = Incidence::compute,
            SeenBy seen_by = SeenBy::sonars) const;

  /// The incidence of `hit`, an answer of cast() to `ray` [rad]: the angle between -ray.direction and hit.normal,
  /// 0 (head-on) .. pi/2 (grazing); NaN on no hit. Bit for bit what cast() writes to Hit::incidence.
  static float incidence(const Ray& ray, const Hit& hit);

  /// Threads in use, the caller included (>= 1).
  int threads() const;

  /// Runs job(b) for every b in [0, blocks) on the caster's threads, the caller included, and returns when all are
  /// done; which thread runs a block is not fixed. For work that casts small batches and uses their hits at once
  /// (a camera's tiles: rays, cast, shading): cast() of fewer than kParallelMin rays inside a job casts on that
  /// job's thread. When another call is using the threads, every block runs on the caller's thread.
  void parallelFor(std::size_t blocks, const std::function<void(std::size_t)>& job) const;

protected:
  explicit RayCaster(const RayCasterOptions& options);

  /// Casts rays[0..n) into hits[0..n), n <= kBlock, rays already checked, against the meshes seen by `seen_by`.
  /// Called concurrently from several threads: must only read shared state. `rays` starts at a multiple of kBlock.
  virtual void castBlock(const Ray* rays, Hit* hits, std::size_t n, int exclude_robot, SeenBy seen_by) const = 0;

  /// Fills the range, kind, index and normal (unit, facing the ray) of a hit from any surface normal (cast() adds
  /// the incidence when asked).
  static void finishHit(const Ray& ray, const Eigen::Vector3f& surface_normal, float range, HitKind kind, int index,
                        Hit& hit, int primitive = -1, float u = 0.0f, float v = 0.0f) {
    const float length = surface_normal.norm();
    Eigen::Vector3f n = length > 0.0f ? Eigen::Vector3f(surface_normal / length) : Eigen::Vector3f(-ray.direction);
    if (n.dot(ray.direction) > 0.0f)
      n = -n;
    hit.range = range;
    hit.normal = n;
    hit.incidence = std::numeric_limits<float>::quiet_NaN();
    hit.kind = kind;
    hit.index = index;
    hit.primitive = primitive;
    hit.u = u;
    hit.v = v;
  }

private:
  std::unique_ptr<WorkerPool> pool_;
};

}  // namespace raycast
}  // namespace unexmin
