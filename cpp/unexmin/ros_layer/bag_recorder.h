// The simulator's own recorder (docs/recording.md): every message the simulator publishes on a recorded
// topic is handed to this hook by its publisher and written to a rosbag (lz4 chunks) in the simulator's
// thread, stamped with the sim time of the step that made it. Nothing goes through TCP, so nothing is lost
// however fast lockstep runs. Commands the simulator receives (thruster inputs, pendulum, vbs) are written
// with the sim time at which they were applied.
#pragma once

#include <unexmin/ros_layer/stream.h>

#include <ros/ros.h>
#include <rosbag/bag.h>

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace unexmin {
namespace ros_layer {

class BagRecorder {
public:
  /// Topics recorded when no list is given: everything the simulator publishes or receives except these
  /// (in lockstep they are limited to a wall-clock rate, docs/simulator_node.md; /tf duplicates odom).
  static const std::set<std::string>& excludedByDefault();

  /// `topics`: absolute topic names to record; empty = the default set (every sensor, command, odometry,
  /// thrust and /current topic of every robot).
  explicit BagRecorder(std::vector<std::string> topics = {});
  ~BagRecorder();

  /// Opens `path` for writing (lz4 chunks) and records from now on; a recording in progress is closed
  /// first. Throws std::runtime_error naming the path when it cannot be opened.
  void start(const std::string& path);
  /// Closes (and indexes) the bag; nothing when not recording.
  void stop();
  bool active() const { return active_; }
  const std::string& path() const { return path_; }
  /// Messages written since start(), per topic.
  const std::map<std::string, std::uint64_t>& counts() const { return counts_; }
  /// The recorded topic list given at construction (empty: the default set).
  const std::vector<std::string>& topics() const { return topics_; }

  /// Sim time [s] written as the bag time of the messages that follow (t = 0, which a bag cannot hold,
  /// is written as ros::TIME_MIN, 1 ns).
  void setTime(double t) {
    time_.fromSec(t);
    if (time_ < ros::TIME_MIN)
      time_ = ros::TIME_MIN;
  }

  /// Whether a message on `topic` is recorded now (recording and the topic selected).
  bool records(const std::string& topic) {
    if (!active_)
      return false;
    auto it = selected_.find(topic);
    if (it == selected_.end())
      it = selected_.emplace(topic, select(topic)).first;
    return it->second;
  }

  /// Writes `m` on `topic` when it is recorded.
  template <class M>
  void write(const std::string& topic, const M& m) {
    if (!records(topic))
      return;
    try {
      bag_.write(topic, time_, m);
    } catch (const std::exception& e) {
      fail(e.what());
      return;
    }
    ++counts_[topic];
  }

private:
  bool select(const std::string& topic) const;
  /// A write failed (disk full, ...): say so once, close what can be closed, record nothing more.
  void fail(const std::string& what);

  std::vector<std::string> topics_;
  std::set<std::string> topic_set_;
  std::unordered_map<std::string, bool> selected_;
  rosbag::Bag bag_;
  bool active_ = false;
  std::string path_;
  ros::Time time_ = ros::TIME_MIN;
  std::map<std::string, std::uint64_t> counts_;
};

/// Publishes `m` on `stream` and hands it to `recorder` (may be null): the one way out of every simulator stream.
template <class M>
void publishRecorded(const Stream& stream, BagRecorder* recorder, const M& m) {
  if (recorder && recorder->active())
    recorder->write(stream.topic(), m);
  if (stream.subscribers() > 0)
    stream.publish(m);
}

/// Whether a message for `stream` is needed: someone subscribes or the recorder records its topic.
inline bool wanted(const Stream& stream, BagRecorder* recorder) {
  return stream.subscribers() > 0 || (recorder && recorder->active() && recorder->records(stream.topic()));
}

}  // namespace ros_layer
}  // namespace unexmin
