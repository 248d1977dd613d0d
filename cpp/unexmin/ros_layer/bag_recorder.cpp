#include <unexmin/ros_layer/bag_recorder.h>

#include <rosbag/exceptions.h>

#include <stdexcept>

namespace unexmin {
namespace ros_layer {

const std::set<std::string>& BagRecorder::excludedByDefault() {
  static const std::set<std::string> excluded{"/clock", "/tf", "/tf_static", "/rosout"};
  return excluded;
}

BagRecorder::BagRecorder(std::vector<std::string> topics)
    : topics_(std::move(topics)), topic_set_(topics_.begin(), topics_.end()) {}

BagRecorder::~BagRecorder() {
  try {
    stop();
  } catch (const std::exception& e) {
    ROS_ERROR_STREAM("simulator recorder: closing " << path_ << ": " << e.what());
  }
}

bool BagRecorder::select(const std::string& topic) const {
  if (!topic_set_.empty())
    return topic_set_.count(topic) > 0;
  if (excludedByDefault().count(topic))
    return false;
  const std::string suffix = "/joint_states";  // limited to a wall-clock rate in lockstep
  return !(topic.size() >= suffix.size() && topic.compare(topic.size() - suffix.size(), suffix.size(), suffix) == 0);
}

void BagRecorder::start(const std::string& path) {
  stop();
  if (path.empty())
    throw std::runtime_error("recording: empty bag path");
  try {
    bag_.open(path, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("recording: cannot open " + path + " for writing: " + e.what());
  }
  bag_.setCompression(rosbag::compression::LZ4);
  path_ = path;
  counts_.clear();
  selected_.clear();
  active_ = true;
  ROS_INFO_STREAM("simulator recorder: recording to " << path_);
}

void BagRecorder::fail(const std::string& what) {
  ROS_ERROR_STREAM("simulator recorder: writing " << path_ << " failed (" << what << "); recording stopped");
  try {
    stop();
  } catch (const std::exception& e) {
    ROS_ERROR_STREAM("simulator recorder: closing " << path_ << ": " << e.what());
  }
}

void BagRecorder::stop() {
  if (!active_)
    return;
  active_ = false;
  bag_.close();
  std::uint64_t total = 0;
  for (const auto& c : counts_)
    total += c.second;
  ROS_INFO_STREAM("simulator recorder: closed " << path_ << " (" << total << " messages on " << counts_.size()
                                                << " topics)");
}

}  // namespace ros_layer
}  // namespace unexmin
