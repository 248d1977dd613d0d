#include <unexmin/sim/world.h>

#include <unexmin/sim/collision_shape.h>
#include <unexmin/sim/spawn_placement.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>

namespace unexmin {
namespace sim {

namespace {

/// Whether two mesh entries give the same triangles: the same file, scale and pose.
bool sameGeometry(const MeshEntry& a, const MeshEntry& b) {
  return a.file == b.file && a.scale == b.scale && a.pose.matrix() == b.pose.matrix();
}

}  // namespace

struct World::StaticBody {
  std::unique_ptr<MeshCollisionShape> shape;
  std::unique_ptr<btRigidBody> body;
};

World::World(const WorldConfig& config, const std::map<std::string, RobotDescription>& descriptions, int robot_count,
             double dt, std::uint64_t seed)
    : config_(config),
      dt_(dt),
      seed_(seed),
      current_(config.current, seed),
      sediment_(config.sediment),
      magnetics_(config.magnetic_field * geo::kNanoteslaPerMilligauss, config.geology) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw ConfigError(config.file + ": physics step " + formatNumber(dt) + " s must be > 0");
  const int available = static_cast<int>(config.robots.size());
  if (robot_count > available)
    throw ConfigError(config.file + ": " + formatNumber(robot_count) + " robots asked for, the world spawns at most " +
                      formatNumber(available));
  if (robot_count < 0)
    robot_count = available;

  collision_config_ = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(collision_config_.get());
  broadphase_ = std::make_unique<btDbvtBroadphase>();
  solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  dynamics_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                        collision_config_.get());
  dynamics_->setGravity(btVector3(0, 0, 0));  // weight and buoyancy are applied by each robot

  for (std::size_t i = 0; i < config.meshes.size(); ++i) {
    const MeshEntry& entry = config.meshes[i];
    meshes_.push_back(nullptr);
    mesh_bodies_.push_back(nullptr);
    for (std::size_t k = 0; k < i && !meshes_[i]; ++k)
      if (sameGeometry(config.meshes[k], entry) && !meshes_[k]->indices.empty())
        meshes_[i] = meshes_[k];  // the same file, scale and pose: loaded once
    if (!meshes_[i])
      meshes_[i] = std::make_shared<const TriangleMesh>(entry.collision || entry.seen_by_cameras || entry.seen_by_sonars
                                                            ? loadMesh(entry)
                                                            : TriangleMesh{entry.name});
    loadSurface(i);
    if (!entry.collision)
      continue;
    const TriangleMesh& mesh = *meshes_[i];
    auto sb = std::make_unique<StaticBody>();
    sb->shape = std::make_unique<MeshCollisionShape>(mesh, bvhCacheFile(entry, mesh));
    btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, &sb->shape->shape());
    info.m_friction = 0.5;
    sb->body = std::make_unique<btRigidBody>(info);
    dynamics_->addRigidBody(sb->body.get());
    mesh_bodies_[i] = sb->body.get();
    static_bodies_.push_back(std::move(sb));
  }

  std::vector<double> radii;
  for (int i = 0; i < robot_count; ++i) {
    const auto it = descriptions.find(config.robots[i].name);
    if (it == descriptions.end())
      throw ConfigError(config.file + ": no robot description for '" + config.robots[i].name + "'");
    radii.push_back(hullRadius(it->second));
  }
  placeSpawns(config_.robots, radii, static_cast<std::size_t>(robot_count), config.surface_z, spawnProbe(),
              config.file);

  for (int i = 0; i < robot_count; ++i) {
    const RobotSpawn& spawn = config_.robots[i];
    robots_.push_back(std::make_unique<Robot>(descriptions.at(spawn.name), spawn));
    dynamics_->addRigidBody(robots_.back()->body());
    robots_.back()->body()->setGravity(btVector3(0, 0, 0));
  }

  water_.density = config.water_density;
  water_.gravity = config.gravity;
  water_.surface_z = config.surface_z;
  water_.current = current_.velocity();
}

SpawnProbe World::spawnProbe() {
  SpawnProbe probe;
  probe.clear = [this](const Eigen::Vector3d& centre, double radius) {
    struct Touch : btCollisionWorld::ContactResultCallback {
      bool touched = false;
      btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper*, int, int,
                               const btCollisionObjectWrapper*, int, int) override {
        touched = touched || point.getDistance() < 0;
        return 0;
      }
    };
    btSphereShape sphere(static_cast<btScalar>(radius));
    btCollisionObject ball;
    ball.setCollisionShape(&sphere);
    ball.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(centre.x(), centre.y(), centre.z())));
    Touch touch;
    dynamics_->contactTest(&ball, touch);
    return !touch.touched;
  };
  probe.open = [this](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const btVector3 from(a.x(), a.y(), a.z()), to(b.x(), b.y(), b.z());
    btCollisionWorld::ClosestRayResultCallback ray(from, to);
    dynamics_->rayTest(from, to, ray);
    return !ray.hasHit();
  };
  return probe;
}

void World::loadSurface(std::size_t i) {
  const MeshEntry& entry = config_.meshes[i];
  const Material& m = entry.material;
  images_.push_back(nullptr);
  if (!m.mapped() || !(entry.seen_by_cameras || entry.seen_by_sonars))
    return;
  const std::string key = config_.file + ": 'meshes[" + formatNumber(i) + "].material.";
  const TriangleMesh& mesh = *meshes_[i];
  if (m.kind == "vertex_colours" && mesh.colours.empty())
    throw ConfigError(key + "kind' = 'vertex_colours': " + entry.file + " has no vertex colours");
  if (m.kind != "image")
    return;
  if (mesh.uvs.empty())
    throw ConfigError(key + "kind' = 'image': " + entry.file + " has no texture coordinates");
  for (std::size_t k = 0; k < i; ++k)
    if (images_[k] && config_.meshes[k].material.image == m.image)
      images_[i] = images_[k];  // one file, decoded once
  try {
    if (!images_[i])
      images_[i] = std::make_shared<const TextureImage>(TextureImage::load(m.image));
  } catch (const ConfigError& e) {
    throw ConfigError(key + "image': " + e.what());
  }
}

World::~World() {
  for (auto& r : robots_)
    dynamics_->removeRigidBody(r->body());
  for (auto& sb : static_bodies_)
    dynamics_->removeRigidBody(sb->body.get());
}

Robot* World::robot(const std::string& name) {
  for (auto& r : robots_)
    if (r->name() == name)
      return r.get();
  return nullptr;
}

void World::step() {
  current_.update(dt_);
  water_.current = current_.velocity();
  water_.current_accel = current_.acceleration();
  for (auto& r : robots_) {
    if (!config_.water_column) {
      r->applyForces(time_, dt_, water_);
      continue;
    }
    WaterState local = water_;  // buoyancy in the water where the robot is
    const btVector3 at = r->body()->getCenterOfMassPosition();
    local.density = config_.water_column->densityAt(Eigen::Vector3d(at.x(), at.y(), at.z()), time_);
    r->applyForces(time_, dt_, local);
  }
  dynamics_->stepSimulation(static_cast<btScalar>(dt_), 0);
  for (auto& r : robots_)
    r->afterStep(dt_);
  ++steps_;
  time_ = static_cast<double>(steps_) * dt_;
  if (config_.sediment.enabled) {
    std::vector<Robot*> robots;
    for (auto& r : robots_)
      robots.push_back(r.get());
    sediment_.step(time_, dt_, robots, *dynamics_, water_.current);
  }
}

void World::reset(std::uint64_t seed) {
  seed_ = seed;
  current_.reset(seed);
  water_.current = current_.velocity();
  water_.current_accel.setZero();
  // Remove and re-add the bodies so cached contacts and solver state start afresh (determinism).
  for (auto& r : robots_)
    dynamics_->removeRigidBody(r->body());
  for (auto& r : robots_)
    r->reset();
  solver_->reset();
  broadphase_->resetPool(dispatcher_.get());
  for (auto& r : robots_) {
    dynamics_->addRigidBody(r->body());
    r->body()->setGravity(btVector3(0, 0, 0));
  }
  time_ = 0.0;
  steps_ = 0;
  sediment_.clear();
}

}  // namespace sim
}  // namespace unexmin
