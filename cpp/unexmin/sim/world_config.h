// World file (YAML): environment, static meshes and robot spawn poses. See docs/worlds.md.
#pragma once

#include <unexmin/core/error.h>

#include <unexmin/geo/geology.h>
#include <unexmin/hydro/current.h>
#include <unexmin/sim/material.h>
#include <unexmin/sim/pose.h>
#include <unexmin/sim/robot_spawn.h>
#include <unexmin/sim/sediment.h>
#include <unexmin/water/water_column.h>

#include <Eigen/Geometry>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {

struct MeshEntry {
  std::string name;
  /// Resolved against the world file's folder, inside it (docs/worlds.md, "Paths").
  std::string file;
  Eigen::Vector3d scale{1, 1, 1};
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< Mesh frame in the world frame.
  bool collision = true;                                   ///< a static contact body of physics
  bool visual = true;                                      ///< shown in rviz
  /// Key `seen_by:` (docs/worlds.md): which ray sensors see the mesh, the optical ones (cameras, SLS) and the
  /// acoustic ones (sonars, DVL); default: the cameras when `visual`, the sonars when `collision`.
  bool seen_by_cameras = true;
  bool seen_by_sonars = true;
  /// Diffuse (Lambertian) reflectance per RGB channel, in [0, 1], for cameras and the SLS lasers
  /// [assumed default 0.3: weathered rock; docs/worlds.md].
  Eigen::Vector3d albedo{0.3, 0.3, 0.3};
  /// Key `material:` (docs/worlds.md): kind, texture and relief; its albedo is `albedo` above. Default: plain.
  Material material;
};

struct WorldConfig {
  std::string file;  ///< Where it was loaded from.
  std::string name;
  double gravity = 9.81;  ///< [m/s^2], along world -z.
  /// [kg/m^3] of uniform water; with a `water_column` its density at the surface (the column's is used).
  double water_density = 1000.0;
  /// Keys `water.profile`, `water.regions`, ...: the water's temperature, chemistry, density and sound speed by depth
  /// (docs/worlds.md, "Water column"); nullptr: uniform water of `water_density`, sound at the sensors' own speed.
  std::shared_ptr<const water::WaterColumn> water_column;
  /// Key `geology:`: the host rock and bodies of ore (docs/worlds.md, "Geology"); nullptr when the world has none.
  std::shared_ptr<const geo::Geology> geology;
  double surface_z = 0.0;                             ///< World z of the free surface [m].
  double atmospheric_pressure = 101325.0;             ///< [Pa]
  std::string visibility = "none";                    ///< none|low|medium|high|water (the column's turbidity)
  Eigen::Vector3d visibility_colour{0.25, 0.3, 0.2};  ///< RGB of the murk, each in (0, 1]
  /// Earth magnetic field, world frame (ENU) [mG]; default: about the UNEXMIN Kaatiala site
  /// (63.5 N, 23 E: 526 mG, inclination 75 deg, declination 10 deg E). Read by magnetometers.
  Eigen::Vector3d magnetic_field{24.0, 134.0, -508.0};
  hydro::CurrentParams current;
  /// Silt raised by the thrusters (key `sediment:`; off by default).
  SedimentParams sediment;
  /// Back end of the world's ray caster for every ray sensor: "embree" (default) or "bullet"
  /// (raycast::rayCasterBackends(); checked when the simulator builds the caster).
  std::string ray_caster = "embree";
  std::vector<MeshEntry> meshes;
  std::vector<RobotSpawn> robots;
};

/// Loads and checks a world file; throws ConfigError("<file>: <problem>") on any defect, first on a key that the
/// world-file schema `schema_file` (default: worldSchemaFile(), world_schema.h) does not know.
WorldConfig loadWorldConfig(const std::string& path, const std::string& schema_file = "");

/// Puts the world's robots named in `names` first, in that order (the simulator then runs the first names.size()
/// robots). A name the world does not list but of the form <prefix>_<k> (k >= 1) where some listed robot is
/// <prefix>_<j> becomes an unplaced spawn anchored at that robot (docs/worlds.md, "Robots the world does not list").
/// Throws ConfigError naming any other unknown name, or one given twice.
void selectRobots(WorldConfig& config, const std::vector<std::string>& names);

}  // namespace sim
}  // namespace unexmin
