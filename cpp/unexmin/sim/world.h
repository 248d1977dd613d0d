// The simulated world: Bullet dynamics world with the static meshes, the robots and the current.
// Steps at a fixed physics step; deterministic for a given seed and command sequence.
#pragma once

#include <unexmin/geo/magnetics.h>
#include <unexmin/hydro/current.h>
#include <unexmin/sim/mesh.h>
#include <unexmin/sim/robot.h>
#include <unexmin/sim/sediment.h>
#include <unexmin/sim/spawn_placement.h>
#include <unexmin/sim/texture_image.h>
#include <unexmin/sim/world_config.h>

#include <cstdint>
#include <map>
#include <memory>

class btDiscreteDynamicsWorld;
class btCollisionConfiguration;
class btCollisionDispatcher;
class btBroadphaseInterface;
class btSequentialImpulseConstraintSolver;
class btRigidBody;
struct btDefaultMotionState;

namespace unexmin {
namespace sim {

class World {
public:
  /// `descriptions` maps robot name -> description for every robot to spawn; robots are spawned in
  /// the world file's order, the first `robot_count` of them (all when robot_count < 0); those not `placed` get a
  /// pose by placeSpawns (sim/spawn_placement.h) among the collision meshes.
  /// dt: physics step [s] > 0. Throws ConfigError on a bad mesh, a missing description or a bad step.
  World(const WorldConfig& config, const std::map<std::string, RobotDescription>& descriptions, int robot_count,
        double dt, std::uint64_t seed);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advance by one physics step.
  void step();

  double time() const { return time_; }  ///< Simulation time [s].
  std::uint64_t stepCount() const { return steps_; }
  double dt() const { return dt_; }
  std::uint64_t seed() const { return seed_; }
  const WorldConfig& config() const { return config_; }
  const WaterState& water() const { return water_; }
  hydro::CurrentModel& current() { return current_; }
  /// The silt the thrusters raised (empty when the world's sediment is off).
  const SedimentField& sediment() const { return sediment_; }
  SedimentField& sediment() { return sediment_; }
  /// The Earth field (config().magnetic_field) and the geology's anomalies (docs/magnetometer.md).
  const geo::MagneticAnomalies& magnetics() const { return magnetics_; }
  /// The total magnetic field at world point `p` [m]: ambient + the geology's anomalies, world frame (ENU) [nT].
  Eigen::Vector3d magneticField(const Eigen::Vector3d& p) const { return magnetics_.field(p); }

  std::size_t robotCount() const { return robots_.size(); }
  Robot& robot(std::size_t i) { return *robots_.at(i); }
  const Robot& robot(std::size_t i) const { return *robots_.at(i); }
  /// nullptr when there is no robot of that name.
  Robot* robot(const std::string& name);

  /// Meshes of the world file, one per entry of config().meshes in its order (the index of a ray hit). Entries of
  /// the same file, scale and pose share one mesh (loaded once); an entry that neither physics nor a ray sensor
  /// uses (collision false, seen by none) is not loaded: its mesh is empty.
  std::size_t meshCount() const { return meshes_.size(); }
  const TriangleMesh& mesh(std::size_t i) const { return *meshes_.at(i); }
  /// The decoded image of mesh entry i's material of kind `image` (entries naming one file share it), else nullptr.
  const TextureImage* image(std::size_t i) const { return images_.at(i).get(); }
  /// The static contact body of mesh entry i, or nullptr when it is not a collision mesh.
  const btRigidBody* meshBody(std::size_t i) const { return mesh_bodies_.at(i); }
  btDiscreteDynamicsWorld& physics() { return *dynamics_; }

  /// Everything back to t = 0 with a new seed: robots at their spawn poses at rest, actuators
  /// zeroed, current at its mean.
  void reset(std::uint64_t seed);

private:
  /// The spawn placement's questions answered by the static collision bodies (before any robot is added).
  SpawnProbe spawnProbe();
  /// The image texture or vertex colours of mesh entry i's material, checked against its mesh (after it is loaded).
  void loadSurface(std::size_t i);

  WorldConfig config_;
  double dt_;
  std::uint64_t seed_;
  double time_ = 0.0;
  std::uint64_t steps_ = 0;
  hydro::CurrentModel current_;
  WaterState water_;
  SedimentField sediment_;
  geo::MagneticAnomalies magnetics_;

  std::unique_ptr<btCollisionConfiguration> collision_config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> dynamics_;

  std::vector<std::shared_ptr<const TriangleMesh>> meshes_;
  std::vector<const btRigidBody*> mesh_bodies_;
  std::vector<std::shared_ptr<const TextureImage>> images_;
  struct StaticBody;
  std::vector<std::unique_ptr<StaticBody>> static_bodies_;
  std::vector<std::unique_ptr<Robot>> robots_;
};

}  // namespace sim
}  // namespace unexmin
