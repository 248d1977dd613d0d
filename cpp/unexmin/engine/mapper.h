// The mapper in-process (docs/mapping.md, "In-process"): after every engine step, the new samples of each robot's
// mapped sensors become clouds exactly as the simulator's publishers and the mapper node make them (the M3's scan
// through its published float fields and mapping::scanPoints, the SLS units' and the imaging sonar's float points,
// a DVL beam's float range on the beam's +x), and go into one mapping::OccupancyMap with the node's parameters and
// rules. Each cloud is placed as the node places it: through a mapping::TfHistory fed with what the simulator and
// robot_state_publisher put on tf (each robot's base link in the world at tf_rate, stamped as ros::Time stamps,
// every fixed joint's mount as robot_state_publisher computes it: mapping::jointOriginTransform; a moving joint of
// the chain at its position at the tf sample), queued in a mapping::CloudQueue until tf can place it at its stamp.
// So the same world, seed and commands give the map of the mapper node, voxel for voxel, when the simulator publishes
// tf at tf_rate (its ~odom_rate) and each /sim/step call ends on a tf sample. Knows no ROS.
#pragma once

#include <unexmin/engine/engine.h>
#include <unexmin/mapping/cloud_queue.h>
#include <unexmin/mapping/mapper_params.h>
#include <unexmin/mapping/occupancy_map.h>
#include <unexmin/mapping/scan_points.h>
#include <unexmin/mapping/tf_history.h>
#include <unexmin/sensors/sonar/m3_sensor.h>
#include <unexmin/sensors/sonar/sonar_cloud.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace unexmin {
namespace engine {

/// How the in-process mapper maps: the mapper node's parameters of the same names (docs/mapping.md) and its own.
struct MapperSettings {
  mapping::MapperParams params;    ///< resolution, max_range, prob_hit, prob_miss, clamp_min, clamp_max
  mapping::MapperSources sources;  ///< m3, sls_units, sonar, sonar_topic, dvl, *_max_range (resolved)
  std::string frame_id = "world";  ///< the map's frame (the world's)
  double tf_max_gap = 0.5;         ///< [s] a cloud whose pose would be interpolated over a longer gap is dropped
  /// [Hz of sim time] how often each robot's pose goes into the tf history, as the simulator's ~odom_rate publishes
  /// /tf; a cloud between two samples is placed at the pose interpolated between them. 0: every physics step.
  double tf_rate = 50.0;
  /// [dB] the imaging sonar's detection threshold above the noise floor (the simulator's
  /// /<robot>/<sonar>/cloud_threshold), > 0.
  double sonar_threshold = 15.0;
};

/// A setting's value as a front end hands it over (a Python dict's).
using MapperValue = std::variant<double, bool, std::string>;

/// The settings from named values (the names of MapperSettings' fields and of their members; absent: the default).
/// Throws ParameterError naming an unknown name (and the known ones), a value of the wrong kind or out of range.
MapperSettings mapperSettings(const std::map<std::string, MapperValue>& values);
/// The names mapperSettings() knows, sorted.
std::vector<std::string> mapperSettingNames();

/// The placing fields of the M3's sensor_msgs/LaserScan, rounded to float as its publisher rounds them.
mapping::ScanGeometry m3ScanGeometry(const sensors::sonar::M3Sensor& m3);

/// A stamp [ns] as ros::Time(t).toNSec() makes it from a sim time t [s] >= 0: whole seconds, then the nanoseconds
/// rounded half away from zero.
mapping::Stamp stampOf(double t);

/// What the in-process mapper has done since it was built (the mapper node's ~stats).
struct MapperStats {
  std::uint64_t clouds_received = 0, clouds_inserted = 0, clouds_dropped = 0, pending = 0, points_inserted = 0;
};

class Mapper {
public:
  /// Picks every robot's mapped sensors among those `engine` runs (as the mapper node subscribes their topics) and
  /// puts every robot's fixed mounts on the tf history. `engine` must outlive this. Throws ConfigError for a mapped
  /// sensor whose frame is not connected to its robot's base link.
  Mapper(const Engine& engine, const MapperSettings& settings);

  /// After each Engine::step(): the robots' poses when a tf sample is due, then the clouds of the sensors that
  /// sampled at this step, then every queued cloud tf can place now goes into the map.
  void afterStep();
  /// After Engine::reset(): the robots' poses at t = 0 (the tf history starts again, as the node's on a jump back:
  /// the clouds still waiting are dropped); the map is kept, as the node keeps its map across /sim/reset.
  void afterReset();
  /// Empties the map (the node's ~reset).
  void clear();

  mapping::OccupancyMap& map() { return *map_; }
  const MapperSettings& settings() const { return settings_; }
  MapperStats stats() const;
  /// The mapped sources: one "<robot>/<sensor>" per sensor whose clouds go in.
  std::vector<std::string> sources() const;

private:
  /// One mapped sensor of a robot and how its sample becomes clouds.
  struct Source {
    std::size_t sensor;  ///< index in the robot's SensorSuite
    enum class Kind { kM3, kSls, kSonar, kDvl } kind;
    double max_range;                                      ///< [m]
    std::vector<std::string> frames;                       ///< the clouds' frames (DVL: one per beam)
    std::unique_ptr<sensors::sonar::SonarCloud> detector;  ///< kSonar: the sonar's point cloud step
  };
  struct RobotMount {
    std::string base_link;
    std::vector<Source> sources;
    std::vector<std::size_t> moving_joints;  ///< indices in the description's joints on a mapped frame's chain
  };

  void sampleTf(std::size_t robot);
  void queueClouds(std::size_t robot);
  void drain();

  const Engine& engine_;
  MapperSettings settings_;
  std::uint64_t tf_every_ = 1;  ///< physics steps between tf samples
  std::unique_ptr<mapping::OccupancyMap> map_;
  mapping::TfHistory tf_;
  std::unique_ptr<mapping::CloudQueue> queue_;
  std::vector<RobotMount> robots_;
  /// The queue's clock: it orders tf samples and clouds as they would arrive (a cloud received before a jump back
  /// is dropped); it runs on calls, not on wall time, so no cloud ever times out waiting.
  double clock_ = 0.0;
  std::uint64_t inserted_ = 0, points_ = 0;
};

}  // namespace engine
}  // namespace unexmin
