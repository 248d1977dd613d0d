// The mapper node: every robot's M3 scans, SLS clouds, imaging sonar clouds and (optionally) DVL beam ranges, each
// placed in the world frame through tf at its own stamp and ray-cast from its own sensor origin into one OctoMap (and
// per-robot maps on request); the map published on a timer to whoever subscribes, saved on request and at shutdown.
// Parameters, topics and services: docs/mapping.md. ROS plumbing only: the tf history and its rules
// (mapping::TfHistory), the clouds waiting for tf (mapping::CloudQueue), scan -> points (mapping::scanPoints), the map
// and what is shown of it (mapping::OccupancyMap, mapping::occupiedCubes) are in cpp/unexmin/mapping (no ROS).
#pragma once

#include <unexmin/mapping/cloud_queue.h>
#include <unexmin/mapping/occupancy_map.h>
#include <unexmin/mapping/tf_history.h>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/Range.h>
#include <std_srvs/Empty.h>
#include <tf2_msgs/TFMessage.h>
#include <unexmin/SaveMap.h>

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace unexmin {
namespace ros_layer {

class MapperRos {
public:
  /// Loads and checks the parameters (throws ConfigError naming the bad one), waits (up to ~robots_timeout
  /// wall seconds) for the robot list, subscribes and advertises.
  MapperRos(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Spins until shutdown (SIGINT included), then saves the map to ~map_file if set.
  void spin();

private:
  /// One map with its output publishers.
  struct Output {
    std::unique_ptr<mapping::OccupancyMap> map;
    ros::Publisher binary, markers, centers;
    bool changed_binary = false, changed_markers = false, changed_centers = false;
    uint32_t subs_binary = 0, subs_markers = 0, subs_centers = 0;
    void changed() { changed_binary = changed_markers = changed_centers = true; }
  };

  void loadParams();
  void subscribe(const std::string& robot);
  Output makeOutput(ros::NodeHandle nh);
  void onScan(const std::string& robot, const sensor_msgs::LaserScanConstPtr& scan);
  /// A point cloud of a source whose points beyond max_range [m] are not marked occupied.
  void onCloud(const std::string& robot, const sensor_msgs::PointCloud2ConstPtr& cloud, double max_range);
  /// One DVL beam's range: a point on the beam's +x at that range (none for an invalid or out-of-window range).
  void onRange(const std::string& robot, const sensor_msgs::RangeConstPtr& range);
  /// Queues a cloud [m, sensor frame] of a source whose points beyond max_range [m] are not marked occupied.
  void enqueue(const std::string& robot, const std_msgs::Header& header, double max_range,
               std::vector<octomap::point3d>&& points);
  /// On the tf thread: hands the samples to the tf history, logs what it reports and asks the main thread to drain.
  void onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& event, bool is_static);
  /// Inserts the pending clouds whose tf has come, drops those the queue gives up on (mapping::CloudQueue).
  void drain();
  void publish(Output& out, const ros::Time& stamp);
  void onTimer(const ros::WallTimerEvent&);
  bool onSaveMap(unexmin::SaveMap::Request& req, unexmin::SaveMap::Response& res);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  void saveOnShutdown();

  ros::NodeHandle nh_, pnh_;
  mapping::MapperParams params_;
  std::string world_frame_ = "world";
  std::vector<std::string> robots_;
  mapping::MapperSources sources_;  ///< the sources and their ranges (m3, sls_units, sonar, dvl, *_max_range)
  bool per_robot_ = false;
  double publish_rate_ = 1.0;  ///< [Hz, wall]
  double tf_timeout_ = 10.0;   ///< [s, wall]
  double tf_max_gap_ = 0.5;    ///< [s, sim]
  int queue_size_ = 5000;
  std::string map_file_;

  // /tf and /tf_static on their own queue and thread: tf is never held up behind cloud insertion (a busy
  // insertion thread let the /tf subscriber queue overflow, its oldest samples dropped, and clouds were then
  // transformed with poses interpolated over the gap).
  ros::CallbackQueue tf_queue_;
  std::unique_ptr<ros::AsyncSpinner> tf_spinner_;
  ros::Subscriber tf_sub_, tf_static_sub_;  ///< deep queues: tf2_ros's listener drops beyond 100 messages
  std::atomic<bool> drain_posted_{false};
  std::atomic<std::size_t> pending_count_{0};
  std::mutex tf_mutex_;                         ///< guards tf_: written on the tf thread, read on the main thread
  mapping::TfHistory tf_;                       ///< 120 s of samples; a frame handed over after 1 s of silence
  std::unique_ptr<mapping::CloudQueue> queue_;  ///< main thread only
  std::vector<ros::Subscriber> subscribers_;
  ros::Publisher stats_pub_;
  ros::ServiceServer save_srv_, reset_srv_;
  ros::WallTimer timer_;

  Output all_;
  std::map<std::string, Output> robot_maps_;
  ros::Time newest_stamp_;
  uint64_t inserted_ = 0, points_ = 0;
  double insert_seconds_ = 0.0;
};

}  // namespace ros_layer
}  // namespace unexmin
