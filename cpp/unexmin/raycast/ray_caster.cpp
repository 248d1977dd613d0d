#include <unexmin/raycast/ray_caster.h>

#include <unexmin/sim/world.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <sstream>
#include <thread>

namespace unexmin {
namespace raycast {

/// A fixed set of worker threads that, with the caller, run the blocks [0, n) of one job at a time.
class WorkerPool {
public:
  using Job = std::function<void(std::size_t)>;

  explicit WorkerPool(int threads) {
    for (int i = 1; i < threads; ++i)
      workers_.emplace_back([this] { loop(); });
  }

  ~WorkerPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (auto& w : workers_)
      w.join();
  }

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  /// Runs job(b) for every b in [0, blocks) on the workers and the caller; returns when all are done.
  /// Returns false without running anything when another call is using the workers, or when called from inside a
  /// job (a block that casts). Workers that wake only after the caller has taken the last block stay out, so a
  /// descheduled worker never delays it.
  bool tryRun(std::size_t blocks, const Job& job) {
    if (in_job_)
      return false;  // the caller's own thread may hold run_mutex_: never lock it twice
    std::unique_lock<std::mutex> busy(run_mutex_, std::try_to_lock);
    if (!busy.owns_lock())
      return false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = &job;
      blocks_ = blocks;
      next_.store(0);
      open_ = true;
      ++generation_;
    }
    wake_.notify_all();
    drain(job, blocks);
    std::unique_lock<std::mutex> lock(mutex_);
    open_ = false;
    done_.wait(lock, [this] { return active_ == 0; });
    job_ = nullptr;
    return true;
  }

private:
  void drain(const Job& job, std::size_t blocks) {
    in_job_ = true;
    for (std::size_t b = next_.fetch_add(1); b < blocks; b = next_.fetch_add(1))
      job(b);
    in_job_ = false;
  }

  static thread_local bool in_job_;  ///< this thread is running a block of some pool's job

  void loop() {
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_)
        return;
      seen = generation_;
      if (!open_)
        continue;  // the caller already finished this job
      ++active_;
      const Job* job = job_;
      const std::size_t blocks = blocks_;
      lock.unlock();
      drain(*job, blocks);
      lock.lock();
      if (--active_ == 0)
        done_.notify_one();
    }
  }

  std::vector<std::thread> workers_;
  std::mutex run_mutex_;  // one job at a time
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const Job* job_ = nullptr;
  std::size_t blocks_ = 0;
  std::atomic<std::size_t> next_{0};
  bool open_ = false;  // the current job still takes workers
  int active_ = 0;     // workers inside the current job
  std::uint64_t generation_ = 0;
  bool stop_ = false;
};

thread_local bool WorkerPool::in_job_ = false;

namespace {

int resolveThreads(int threads) {
  if (threads < 0)
    throw RayCasterError("ray caster: threads = " + formatNumber(threads) + " must be >= 0 (0 = all)");
  if (threads == 0)
    threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return threads;
}

std::string describe(const Eigen::Vector3f& v) {
  return "(" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + ")";
}

/// Throws RayCasterError naming ray i and its defect.
void checkRay(const Ray& ray, std::size_t i) {
  const auto bad = [&](const std::string& what) {
    return RayCasterError("ray caster: ray " + formatNumber(i) + ": " + what);
  };
  if (!ray.origin.allFinite())
    throw bad("origin " + describe(ray.origin) + " is not finite");
  // |d|^2 within 1 +- 2e-3 <=> |d| within 1 +- 1e-3; written so that NaN fails.
  if (!(std::abs(ray.direction.squaredNorm() - 1.0f) <= 2e-3f))
    throw bad("direction " + describe(ray.direction) + " is not a unit vector");
  if (!(ray.max_range > 0.0f) || !std::isfinite(ray.max_range))
    throw bad("max_range " + formatNumber(ray.max_range) + " m must be finite and > 0");
}

}  // namespace

RayCaster::RayCaster(const RayCasterOptions& options)
    : pool_(std::make_unique<WorkerPool>(resolveThreads(options.threads))) {}

RayCaster::~RayCaster() = default;

int RayCaster::threads() const {
  return pool_->threads();
}

void RayCaster::cast(const std::vector<Ray>& rays, std::vector<Hit>& hits, int exclude_robot, Incidence incidence,
                     SeenBy seen_by) const {
  hits.resize(rays.size());
  cast(rays.data(), hits.data(), rays.size(), exclude_robot, incidence, seen_by);
}

void RayCaster::cast(const Ray* rays, Hit* hits, std::size_t n, int exclude_robot, Incidence incidence,
                     SeenBy seen_by) const {
  if (exclude_robot < -1)
    throw RayCasterError("ray caster: exclude_robot = " + formatNumber(exclude_robot) +
                         " must be a robot index or -1 (none)");
  for (std::size_t i = 0; i < n; ++i)
    checkRay(rays[i], i);
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  const WorkerPool::Job one = [&](std::size_t b) {
    const std::size_t start = b * kBlock;
    const std::size_t m = std::min(kBlock, n - start);
    castBlock(rays + start, hits + start, m, exclude_robot, seen_by);
    if (incidence == Incidence::compute)
      for (std::size_t i = start; i < start + m; ++i)
        hits[i].incidence = RayCaster::incidence(rays[i], hits[i]);
  };
  if (n >= kParallelMin && pool_->threads() > 1 && pool_->tryRun(blocks, one))
    return;
  for (std::size_t b = 0; b < blocks; ++b)
    one(b);
}

void RayCaster::parallelFor(std::size_t blocks, const std::function<void(std::size_t)>& job) const {
  if (blocks > 1 && pool_->threads() > 1 && pool_->tryRun(blocks, job))
    return;
  for (std::size_t b = 0; b < blocks; ++b)
    job(b);
}

float RayCaster::incidence(const Ray& ray, const Hit& hit) {
  if (!hit.hit())
    return std::numeric_limits<float>::quiet_NaN();
  // hit.normal faces the ray (finishHit flipped it if needed, which negates this dot product and the cross
  // product below exactly), so c <= 0. atan2 keeps full precision near head-on incidence, where acos(-c) would not.
  const float c = hit.normal.dot(ray.direction);
  return std::atan2(hit.normal.cross(ray.direction).norm(), -c);
}

std::vector<RobotSphere> robotSpheres(sim::World& world) {
  std::vector<RobotSphere> spheres(world.robotCount());
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const btRigidBody* body = world.robot(i).body();
    const btCollisionShape* shape = body->getCollisionShape();
    if (shape->getShapeType() != SPHERE_SHAPE_PROXYTYPE)
      throw RayCasterError("ray caster: robot '" + world.robot(i).name() + "' has a '" + shape->getName() +
                           "' collision shape; only spheres are supported");
    const btVector3& c = body->getWorldTransform().getOrigin();
    spheres[i].center = Eigen::Vector3d(c.x(), c.y(), c.z());
    spheres[i].radius = static_cast<const btSphereShape*>(shape)->getRadius();
  }
  return spheres;
}

std::vector<SeenMesh> seenMeshes(const sim::World& world) {
  std::vector<SeenMesh> out;
  const auto& entries = world.config().meshes;
  for (std::size_t i = 0; i < world.meshCount(); ++i) {
    const bool sonars = i >= entries.size() || entries[i].seen_by_sonars;
    const bool cameras = i >= entries.size() || entries[i].seen_by_cameras;
    if (!sonars && !cameras)
      continue;
    const sim::TriangleMesh* mesh = &world.mesh(i);
    auto it = std::find_if(out.begin(), out.end(), [&](const SeenMesh& s) { return s.mesh == mesh; });
    if (it == out.end())
      it = out.insert(out.end(), SeenMesh{mesh, 0u, -1, -1});
    if (sonars && it->sonar_index < 0)
      it->sonar_index = static_cast<int>(i);
    if (cameras && it->camera_index < 0)
      it->camera_index = static_cast<int>(i);
    it->seen_by |= (sonars ? 1u : 0u) | (cameras ? 2u : 0u);
  }
  return out;
}

}  // namespace raycast
}  // namespace unexmin
