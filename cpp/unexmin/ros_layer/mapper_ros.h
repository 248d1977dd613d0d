// The mapper node: every robot's M3 scans and SLS clouds, each transformed to the world frame through tf at its
// own stamp and ray-cast from its own sensor origin into one OctoMap (and per-robot maps on request); the map
// published on a timer to whoever subscribes, saved on request and at shutdown. Parameters, topics and
// services: docs/mapping.md. The maths is in cpp/unexmin/mapping (no ROS).
#pragma once

#include <unexmin/mapping/occupancy_map.h>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/buffer.h>
#include <tf2_msgs/TFMessage.h>
#include <unexmin/SaveMap.h>

#include <atomic>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace unexmin {
namespace ros_layer {

class MapperRos
{
public:
  /// Loads and checks the parameters (throws ConfigError naming the bad one), waits (up to ~robots_timeout
  /// wall seconds) for the robot list, subscribes and advertises.
  MapperRos(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Spins until shutdown (SIGINT included), then saves the map to ~map_file if set.
  void spin();

private:
  /// One received cloud, in its sensor frame [m].
  struct Cloud
  {
    std::string robot;
    std::string frame;
    ros::Time stamp;
    std::vector<octomap::point3d> points;
    ros::WallTime received;
  };
  /// One map with its output publishers.
  struct Output
  {
    std::unique_ptr<mapping::OccupancyMap> map;
    ros::Publisher binary, markers, centers;
    bool changed_binary = false, changed_markers = false, changed_centers = false;
    uint32_t subs_binary = 0, subs_markers = 0, subs_centers = 0;
  };

  void loadParams();
  void subscribe(const std::string& robot);
  Output makeOutput(ros::NodeHandle nh);
  void onScan(const std::string& robot, const sensor_msgs::LaserScanConstPtr& scan);
  void onCloud(const std::string& robot, const sensor_msgs::PointCloud2ConstPtr& cloud);
  void enqueue(Cloud&& cloud);
  /// On the tf thread: stores the transforms (a dynamic frame's samples from one publisher at a time), clears
  /// the buffer when a frame's stamps go back (simulation reset) or its publisher changes, and asks the main
  /// thread to drain.
  void onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& event, bool is_static);
  /// The largest gap [s] between the stored samples of a dynamic frame of the chain from frame to the map
  /// frame around stamp (0 when the chain is static); the frame's name in *frame_out.
  double tfGap(const std::string& frame, const ros::Time& stamp, std::string* frame_out);
  /// Inserts the pending clouds in arrival order up to the first whose tf has not arrived yet; drops those
  /// past the timeout, those whose tf would be interpolated over a gap longer than ~tf_max_gap and those
  /// received before a jump back in time that are stamped after it.
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
  bool use_m3_ = true;
  int sls_units_ = 4;
  bool per_robot_ = false;
  double publish_rate_ = 1.0;   ///< [Hz, wall]
  double tf_timeout_ = 10.0;    ///< [s, wall]
  double tf_max_gap_ = 0.5;     ///< [s, sim]
  int queue_size_ = 5000;
  std::string map_file_;

  tf2_ros::Buffer tf_buffer_{ros::Duration(120.0)};
  // /tf and /tf_static on their own queue and thread: tf is never held up behind cloud insertion (a busy
  // insertion thread let the /tf subscriber queue overflow, its oldest samples dropped, and clouds were then
  // transformed with poses interpolated over the gap).
  ros::CallbackQueue tf_queue_;
  std::unique_ptr<ros::AsyncSpinner> tf_spinner_;
  ros::Subscriber tf_sub_, tf_static_sub_;  ///< deep queues: tf2_ros's listener drops beyond 100 messages
  std::atomic<bool> drain_posted_{false};
  std::atomic<std::size_t> pending_count_{0};
  /// Shared by the tf thread (writes) and the main thread (reads).
  struct TfState
  {
    /// The node whose /tf samples of a frame are used, and when it last sent one.
    struct Owner
    {
      std::string node;
      ros::WallTime last;
    };
    std::map<std::string, Owner> publisher;                ///< dynamic child frame -> its owner
    std::map<std::string, std::deque<ros::Time>> stamps;   ///< dynamic child frame -> its sample stamps
    uint64_t jumps = 0;                                    ///< jumps back in time seen
    ros::WallTime jump_wall;                               ///< when the last one was seen
    ros::Time jump_to;                                     ///< the stamp it went back to
    uint64_t ignored = 0;                                  ///< samples from a second publisher of a frame
    std::set<std::string> warned;                          ///< "frame publisher" pairs warned about
  };
  std::mutex tf_mutex_;
  TfState tf_state_;
  uint64_t jumps_seen_ = 0;  ///< main thread: jumps already handled
  std::vector<ros::Subscriber> subscribers_;
  ros::Publisher stats_pub_;
  ros::ServiceServer save_srv_, reset_srv_;
  ros::WallTimer timer_;

  Output all_;
  std::map<std::string, Output> robot_maps_;
  std::deque<Cloud> pending_;
  ros::Time newest_stamp_;
  uint64_t received_ = 0, inserted_ = 0, dropped_ = 0, points_ = 0;
  double insert_seconds_ = 0.0;
};

}  // namespace ros_layer
}  // namespace unexmin
