#include <unexmin/ros_layer/mapper_ros.h>

#include <unexmin/core/error.h>

#include <octomap_msgs/Octomap.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <unexmin/MapperStats.h>
#include <visualization_msgs/MarkerArray.h>

#include <boost/make_shared.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

namespace unexmin {
namespace ros_layer {

namespace {

/// A function run by a ros::CallbackQueue.
class FunctionCallback : public ros::CallbackInterface
{
public:
  explicit FunctionCallback(std::function<void()> f) : f_(std::move(f)) {}
  CallResult call() override
  {
    f_();
    return Success;
  }

private:
  std::function<void()> f_;
};

void require(bool ok, const std::string& name, double value, const std::string& expected)
{
  if (!ok || !std::isfinite(value)) {
    throw ParameterError("mapper: parameter '~" + name + "' = " + formatNumber(value) + ": expected " + expected);
  }
}

/// Colour of a height in [lo, hi]: hue from blue (low) to red (high).
std_msgs::ColorRGBA heightColour(double z, double lo, double hi)
{
  const double t = hi > lo ? std::min(1.0, std::max(0.0, (z - lo) / (hi - lo))) : 0.5;
  const double h = (1.0 - t) * 4.0;  // 4 (blue) .. 0 (red) on the six-sector hue wheel
  const int i = static_cast<int>(std::floor(h));
  const double f = h - i;
  std_msgs::ColorRGBA c;
  c.a = 1.0;
  switch (i) {
    case 0: c.r = 1; c.g = f; c.b = 0; break;
    case 1: c.r = 1 - f; c.g = 1; c.b = 0; break;
    case 2: c.r = 0; c.g = 1; c.b = f; break;
    case 3: c.r = 0; c.g = 1 - f; c.b = 1; break;
    default: c.r = 0; c.g = 0; c.b = 1; break;
  }
  return c;
}

}  // namespace

MapperRos::MapperRos(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh)
{
  loadParams();
  // Our own /tf subscribers with the clouds' queue depth: in lockstep the simulator publishes tf far faster
  // than real time, and tf2_ros's TransformListener (queue 100) would drop samples under load. They run on
  // their own queue and thread, so that a busy insertion never lets their queue overflow.
  ros::NodeHandle tf_nh(nh_);
  tf_nh.setCallbackQueue(&tf_queue_);
  using TfEvent = ros::MessageEvent<tf2_msgs::TFMessage const>;
  tf_sub_ = tf_nh.subscribe<tf2_msgs::TFMessage, const TfEvent&>(
      "/tf", queue_size_, [this](const TfEvent& e) { onTf(e, false); }, ros::VoidConstPtr(),
      ros::TransportHints().tcpNoDelay());
  tf_static_sub_ = tf_nh.subscribe<tf2_msgs::TFMessage, const TfEvent&>(
      "/tf_static", queue_size_, [this](const TfEvent& e) { onTf(e, true); });
  all_ = makeOutput(nh_);
  for (const std::string& robot : robots_) {
    if (per_robot_) robot_maps_.emplace(robot, makeOutput(ros::NodeHandle(nh_, robot)));
    subscribe(robot);
  }
  stats_pub_ = pnh_.advertise<unexmin::MapperStats>("stats", 10);
  save_srv_ = pnh_.advertiseService("save_map", &MapperRos::onSaveMap, this);
  reset_srv_ = pnh_.advertiseService("reset", &MapperRos::onReset, this);
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / publish_rate_), &MapperRos::onTimer, this);
  tf_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &tf_queue_);
  tf_spinner_->start();
  ROS_INFO_STREAM("mapper: " << robots_.size() << " robot(s), resolution " << params_.resolution << " m, max range "
                             << params_.max_range << " m, M3 " << (use_m3_ ? "on" : "off") << ", " << sls_units_
                             << " SLS unit(s)" << (map_file_.empty() ? "" : ", saves to " + map_file_));
}

void MapperRos::loadParams()
{
  pnh_.param("resolution", params_.resolution, params_.resolution);
  pnh_.param("max_range", params_.max_range, params_.max_range);
  pnh_.param("prob_hit", params_.prob_hit, params_.prob_hit);
  pnh_.param("prob_miss", params_.prob_miss, params_.prob_miss);
  pnh_.param("clamp_min", params_.clamp_min, params_.clamp_min);
  pnh_.param("clamp_max", params_.clamp_max, params_.clamp_max);
  params_.validate();
  pnh_.param("frame_id", world_frame_, world_frame_);
  pnh_.param("m3", use_m3_, use_m3_);
  pnh_.param("sls_units", sls_units_, sls_units_);
  pnh_.param("per_robot", per_robot_, per_robot_);
  pnh_.param("publish_rate", publish_rate_, publish_rate_);
  pnh_.param("tf_timeout", tf_timeout_, tf_timeout_);
  pnh_.param("tf_max_gap", tf_max_gap_, tf_max_gap_);
  pnh_.param("queue_size", queue_size_, queue_size_);
  pnh_.param("map_file", map_file_, map_file_);
  double robots_timeout = 30.0;
  pnh_.param("robots_timeout", robots_timeout, robots_timeout);
  require(sls_units_ >= 0 && sls_units_ <= 16, "sls_units", sls_units_, "0..16");
  require(publish_rate_ > 0.0 && publish_rate_ <= 100.0, "publish_rate", publish_rate_, "(0, 100] Hz");
  require(tf_timeout_ > 0.0, "tf_timeout", tf_timeout_, "> 0 s");
  require(tf_max_gap_ > 0.0, "tf_max_gap", tf_max_gap_, "> 0 s");
  require(queue_size_ >= 1, "queue_size", queue_size_, ">= 1");
  require(robots_timeout >= 0.0, "robots_timeout", robots_timeout, ">= 0 s");
  if (world_frame_.empty()) throw ParameterError("mapper: parameter '~frame_id' is empty: expected a frame");

  // The robots: ~robots, else the simulator's /sim/robots (set at its start-up: wait for it).
  if (!pnh_.getParam("robots", robots_)) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(robots_timeout);
    while (!nh_.getParam("/sim/robots", robots_) && ros::ok() && ros::WallTime::now() < deadline) {
      ros::WallDuration(0.1).sleep();
    }
  }
  if (robots_.empty()) {
    throw ConfigError("mapper: no robots: neither '~robots' nor '/sim/robots' (waited " +
                      formatNumber(robots_timeout) + " s) names any");
  }
}

MapperRos::Output MapperRos::makeOutput(ros::NodeHandle nh)
{
  Output out;
  out.map = std::make_unique<mapping::OccupancyMap>(params_);
  out.binary = nh.advertise<octomap_msgs::Octomap>("octomap_binary", 1, true);
  out.markers = nh.advertise<visualization_msgs::MarkerArray>("occupied_cells_vis_array", 1, true);
  out.centers = nh.advertise<sensor_msgs::PointCloud2>("octomap_point_cloud_centers", 1, true);
  return out;
}

void MapperRos::subscribe(const std::string& robot)
{
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  if (use_m3_) {
    subscribers_.push_back(nh_.subscribe<sensor_msgs::LaserScan>(
        "/" + robot + "/m3/scan", queue_size_,
        [this, robot](const sensor_msgs::LaserScanConstPtr& m) { onScan(robot, m); }, ros::VoidConstPtr(), hints));
  }
  for (int i = 0; i < sls_units_; ++i) {
    subscribers_.push_back(nh_.subscribe<sensor_msgs::PointCloud2>(
        "/" + robot + "/sls_" + std::to_string(i) + "/points", queue_size_,
        [this, robot](const sensor_msgs::PointCloud2ConstPtr& m) { onCloud(robot, m); }, ros::VoidConstPtr(),
        hints));
  }
}

void MapperRos::onScan(const std::string& robot, const sensor_msgs::LaserScanConstPtr& scan)
{
  Cloud cloud{robot, scan->header.frame_id, scan->header.stamp, {}, ros::WallTime::now()};
  cloud.points.reserve(scan->ranges.size());
  for (std::size_t k = 0; k < scan->ranges.size(); ++k) {
    const float r = scan->ranges[k];
    if (!std::isfinite(r) || r < scan->range_min || r > scan->range_max) continue;  // no echo (REP-117)
    const double a = scan->angle_min + k * scan->angle_increment;
    cloud.points.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0.0f);
  }
  enqueue(std::move(cloud));
}

void MapperRos::onCloud(const std::string& robot, const sensor_msgs::PointCloud2ConstPtr& msg)
{
  Cloud cloud{robot, msg->header.frame_id, msg->header.stamp, {}, ros::WallTime::now()};
  cloud.points.reserve(static_cast<std::size_t>(msg->width) * msg->height);
  if (msg->width * msg->height > 0) {
    sensor_msgs::PointCloud2ConstIterator<float> x(*msg, "x"), y(*msg, "y"), z(*msg, "z");
    for (; x != x.end(); ++x, ++y, ++z) cloud.points.emplace_back(*x, *y, *z);
  }
  enqueue(std::move(cloud));
}

void MapperRos::onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& event, bool is_static)
{
  const std::string& from = event.getPublisherName();
  const tf2_msgs::TFMessage& msg = *event.getConstMessage();
  const ros::WallTime now = ros::WallTime::now();
  // A dynamic frame has one publisher at a time: the first heard, until it has been silent for
  // kHandoverSilence (then a new one, e.g. a second `rosbag play`, takes over). A second live publisher (a
  // leftover process on the same master, a second simulator) is ignored: the buffer would interpolate between
  // two different poses.
  constexpr double kHandoverSilence = 1.0;  // [s, wall]
  std::lock_guard<std::mutex> lock(tf_mutex_);
  if (!is_static) {
    // A frame's stamps going back (a simulation reset, a bag looping) or a new publisher of it start a new
    // history: the buffer is cleared (static transforms stay), as tf2_ros's TransformListener does on a jump
    // back of ros::Time; otherwise it would interpolate between the old and the new run.
    std::string why;
    for (const geometry_msgs::TransformStamped& t : msg.transforms) {
      auto owner = tf_state_.publisher.find(t.child_frame_id);
      if (owner == tf_state_.publisher.end()) continue;
      if (owner->second.node != from) {
        if ((now - owner->second.last).toSec() <= kHandoverSilence) continue;  // ignored below
        why = "'" + t.child_frame_id + "' now comes from " + from + " (" + owner->second.node + " fell silent)";
        owner->second.node = from;
        break;
      }
      const std::deque<ros::Time>& stamps = tf_state_.stamps[t.child_frame_id];
      if (!stamps.empty() && t.header.stamp < stamps.back()) {
        why = "'" + t.child_frame_id + "' went back in time from " + std::to_string(stamps.back().toSec()) + " to " +
              std::to_string(t.header.stamp.toSec()) + " s";
        break;
      }
    }
    if (!why.empty()) {
      ROS_WARN_STREAM("mapper: tf of " << why << ": clearing the tf buffer and the clouds waiting for it");
      tf_buffer_.clear();
      for (auto& entry : tf_state_.stamps) entry.second.clear();
      ++tf_state_.jumps;
      tf_state_.jump_wall = now;
    }
  }
  for (const geometry_msgs::TransformStamped& t : msg.transforms) {
    if (!is_static) {
      TfState::Owner& owner = tf_state_.publisher.emplace(t.child_frame_id, TfState::Owner{from, now}).first->second;
      if (owner.node != from) {
        // Once per frame and publisher (a throttle runs on ROS time, which a reset sets back).
        ++tf_state_.ignored;
        if (tf_state_.warned.insert(t.child_frame_id + " " + from).second) {
          ROS_WARN_STREAM("mapper: ignoring tf of '" << t.child_frame_id << "' from " << from << ": it comes from "
                                                     << owner.node);
        }
        continue;
      }
      owner.last = now;
    }
    try {
      tf_buffer_.setTransform(t, "tf", is_static);
    } catch (const tf2::TransformException& e) {
      ROS_WARN_STREAM_THROTTLE(5.0, "mapper: bad transform " << t.header.frame_id << " -> " << t.child_frame_id
                                                              << ": " << e.what());
      continue;
    }
    if (is_static) continue;
    std::deque<ros::Time>& stamps = tf_state_.stamps[t.child_frame_id];
    if (stamps.empty() || t.header.stamp > stamps.back()) stamps.push_back(t.header.stamp);
    while (stamps.front() + tf_buffer_.getCacheLength() < stamps.back()) stamps.pop_front();
  }
  // The clouds waiting for tf are drained on the main thread (one request at a time).
  if (pending_count_ > 0 && !drain_posted_.exchange(true)) {
    ros::getGlobalCallbackQueue()->addCallback(boost::make_shared<FunctionCallback>([this] {
      drain_posted_ = false;
      drain();
    }));
  }
}

double MapperRos::tfGap(const std::string& frame, const ros::Time& stamp, std::string* frame_out)
{
  std::vector<std::string> chain;
  try {
    tf_buffer_._chainAsVector(world_frame_, stamp, frame, stamp, world_frame_, chain);
  } catch (const tf2::TransformException&) {
    return 0.0;  // no chain: lookupTransform reports it
  }
  std::lock_guard<std::mutex> lock(tf_mutex_);
  double gap = 0.0;
  for (const std::string& f : chain) {
    auto it = tf_state_.stamps.find(f);
    if (it == tf_state_.stamps.end() || it->second.empty()) continue;
    const std::deque<ros::Time>& stamps = it->second;
    auto after = std::lower_bound(stamps.begin(), stamps.end(), stamp);
    if (after == stamps.end() || *after == stamp) continue;  // beyond the newest: canTransform said no
    if (after == stamps.begin()) continue;                   // before the oldest kept: the buffer's answer
    const double g = (*after - *(after - 1)).toSec();
    if (g > gap) {
      gap = g;
      *frame_out = f;
    }
  }
  return gap;
}

void MapperRos::enqueue(Cloud&& cloud)
{
  ++received_;
  pending_.push_back(std::move(cloud));
  pending_count_ = pending_.size();
  drain();
}

void MapperRos::drain()
{
  const ros::WallTime now = ros::WallTime::now();
  uint64_t jumps;
  ros::WallTime jump_wall;
  {
    std::lock_guard<std::mutex> lock(tf_mutex_);
    jumps = tf_state_.jumps;
    jump_wall = tf_state_.jump_wall;
  }
  if (jumps != jumps_seen_) {
    // Time went back: the clouds received before are of the old run, their tf is gone.
    jumps_seen_ = jumps;
    const std::size_t before = pending_.size();
    pending_.erase(std::remove_if(pending_.begin(), pending_.end(),
                                  [&](const Cloud& c) { return c.received <= jump_wall; }),
                   pending_.end());
    dropped_ += before - pending_.size();
  }
  for (auto it = pending_.begin(); it != pending_.end();) {
    std::string error;
    if (!tf_buffer_.canTransform(world_frame_, it->frame, it->stamp, &error)) {
      // Older than the tf cache or waited too long: give up; otherwise wait for the tf to arrive.
      const bool too_old = error.find("past") != std::string::npos;
      if (too_old || now - it->received > ros::WallDuration(tf_timeout_)) {
        ROS_WARN_STREAM_THROTTLE(5.0, "mapper: dropping a cloud of " << it->robot << " in '" << it->frame << "' at "
                                                                      << it->stamp << ": " << error);
        ++dropped_;
        it = pending_.erase(it);
        continue;
      }
      // Clouds and tf arrive in stamp order: the clouds behind this one wait too (one check per call, not one
      // per pending cloud, however long the queue).
      break;
    }
    // tf2 interpolates between the samples either side of the stamp however far apart they are: a gap
    // (samples lost, a publisher stalled) would place the cloud at a pose the robot never had.
    std::string gap_frame;
    const double gap = tfGap(it->frame, it->stamp, &gap_frame);
    if (gap > tf_max_gap_) {
      ROS_WARN_STREAM_THROTTLE(5.0, "mapper: dropping a cloud of " << it->robot << " at " << it->stamp << ": the tf of '"
                                                                    << gap_frame << "' has a gap of " << gap
                                                                    << " s there (~tf_max_gap " << tf_max_gap_ << " s)");
      ++dropped_;
      it = pending_.erase(it);
      continue;
    }
    geometry_msgs::TransformStamped tf;
    try {
      tf = tf_buffer_.lookupTransform(world_frame_, it->frame, it->stamp);
    } catch (const tf2::TransformException&) {
      break;  // the tf thread cleared the buffer since canTransform (a jump back): the next drain sees it
    }
    const auto& q = tf.transform.rotation;
    const auto& t = tf.transform.translation;
    const tf2::Matrix3x3 R(tf2::Quaternion(q.x, q.y, q.z, q.w));
    std::vector<octomap::point3d> world;
    world.reserve(it->points.size());
    for (const octomap::point3d& p : it->points) {
      const tf2::Vector3 w = R * tf2::Vector3(p.x(), p.y(), p.z());
      world.emplace_back(static_cast<float>(w.x() + t.x), static_cast<float>(w.y() + t.y),
                         static_cast<float>(w.z() + t.z));
    }
    const octomap::point3d origin(static_cast<float>(t.x), static_cast<float>(t.y), static_cast<float>(t.z));
    const ros::WallTime start = ros::WallTime::now();
    all_.map->insertCloud(world, origin);
    all_.changed_binary = all_.changed_markers = all_.changed_centers = true;
    auto robot_map = robot_maps_.find(it->robot);
    if (robot_map != robot_maps_.end()) {
      robot_map->second.map->insertCloud(world, origin);
      robot_map->second.changed_binary = robot_map->second.changed_markers = robot_map->second.changed_centers = true;
    }
    insert_seconds_ += (ros::WallTime::now() - start).toSec();
    ++inserted_;
    points_ += it->points.size();
    newest_stamp_ = std::max(newest_stamp_, it->stamp);
    it = pending_.erase(it);
  }
  pending_count_ = pending_.size();
}

void MapperRos::publish(Output& out, const ros::Time& stamp)
{
  // Each output only when someone listens and the map changed since, or a listener joined.
  const uint32_t nb = out.binary.getNumSubscribers(), nm = out.markers.getNumSubscribers(),
                 nc = out.centers.getNumSubscribers();
  const bool want_binary = nb > 0 && (out.changed_binary || nb > out.subs_binary);
  const bool want_markers = nm > 0 && (out.changed_markers || nm > out.subs_markers);
  const bool want_centers = nc > 0 && (out.changed_centers || nc > out.subs_centers);
  out.subs_binary = nb;
  out.subs_markers = nm;
  out.subs_centers = nc;
  if (want_binary) {
    octomap_msgs::Octomap msg;
    msg.header.frame_id = world_frame_;
    msg.header.stamp = stamp;
    msg.binary = true;
    msg.id = out.map->tree().getTreeType();
    msg.resolution = out.map->tree().getResolution();
    const std::string data = out.map->binaryData();
    msg.data.assign(data.begin(), data.end());
    out.binary.publish(msg);
    out.changed_binary = false;
  }
  if (!want_markers && !want_centers) return;
  const std::vector<mapping::Voxel> voxels = out.map->occupiedVoxels();
  if (want_markers) {
    double lo = 0, hi = 0;
    if (!voxels.empty()) {
      const auto mm = std::minmax_element(voxels.begin(), voxels.end(),
                                          [](const mapping::Voxel& a, const mapping::Voxel& b) { return a.z < b.z; });
      lo = mm.first->z;
      hi = mm.second->z;
    }
    // One CUBE_LIST per voxel size (pruned leaves are larger), as octomap_server does.
    const unsigned depths = out.map->tree().getTreeDepth() + 1;
    visualization_msgs::MarkerArray array;
    array.markers.resize(depths);
    for (unsigned d = 0; d < depths; ++d) {
      visualization_msgs::Marker& m = array.markers[d];
      m.header.frame_id = world_frame_;
      m.header.stamp = stamp;
      m.ns = "occupied_cells";
      m.id = static_cast<int>(d);
      m.type = visualization_msgs::Marker::CUBE_LIST;
      m.pose.orientation.w = 1.0;
      const double size = out.map->tree().getNodeSize(d);
      m.scale.x = m.scale.y = m.scale.z = size;
    }
    for (const mapping::Voxel& v : voxels) {
      const unsigned d = std::min<unsigned>(depths - 1, static_cast<unsigned>(std::lround(
          out.map->tree().getTreeDepth() - std::log2(v.size / out.map->tree().getResolution()))));
      geometry_msgs::Point p;
      p.x = v.x;
      p.y = v.y;
      p.z = v.z;
      array.markers[d].points.push_back(p);
      array.markers[d].colors.push_back(heightColour(v.z, lo, hi));
    }
    for (visualization_msgs::Marker& m : array.markers) {
      m.action = m.points.empty() ? visualization_msgs::Marker::DELETE : visualization_msgs::Marker::ADD;
    }
    out.markers.publish(array);
    out.changed_markers = false;
  }
  if (want_centers) {
    sensor_msgs::PointCloud2 cloud;
    cloud.header.frame_id = world_frame_;
    cloud.header.stamp = stamp;
    sensor_msgs::PointCloud2Modifier modifier(cloud);
    modifier.setPointCloud2FieldsByString(1, "xyz");
    modifier.resize(voxels.size());
    sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
    for (const mapping::Voxel& v : voxels) {
      *x = static_cast<float>(v.x);
      *y = static_cast<float>(v.y);
      *z = static_cast<float>(v.z);
      ++x, ++y, ++z;
    }
    out.centers.publish(cloud);
    out.changed_centers = false;
  }
}

void MapperRos::onTimer(const ros::WallTimerEvent&)
{
  drain();
  publish(all_, newest_stamp_);
  for (auto& entry : robot_maps_) publish(entry.second, newest_stamp_);
  unexmin::MapperStats stats;
  stats.stamp = newest_stamp_;
  stats.clouds_received = received_;
  stats.clouds_inserted = inserted_;
  stats.clouds_dropped = dropped_;
  stats.points_inserted = points_;
  stats.pending = static_cast<uint32_t>(pending_.size());
  stats.insert_seconds = insert_seconds_;
  stats.occupied_leaves = all_.map->occupiedLeafCount();
  stats.memory_bytes = all_.map->memoryUsage();
  stats_pub_.publish(stats);
}

bool MapperRos::onSaveMap(unexmin::SaveMap::Request& req, unexmin::SaveMap::Response& res)
{
  drain();
  const std::string path = req.path.empty() ? map_file_ : req.path;
  Output* out = &all_;
  if (!req.robot.empty()) {
    auto it = robot_maps_.find(req.robot);
    if (it == robot_maps_.end()) {
      res.success = false;
      res.message = "no map of robot '" + req.robot + "' (per-robot maps need ~per_robot: true)";
      return true;
    }
    out = &it->second;
  }
  if (path.empty()) {
    res.success = false;
    res.message = "no path given and ~map_file is not set";
    return true;
  }
  try {
    out->map->save(path);
    res.success = true;
    res.message = path;
    res.occupied_leaves = out->map->occupiedLeafCount();
  } catch (const Error& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

bool MapperRos::onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&)
{
  all_.map->reset();
  for (auto& entry : robot_maps_) entry.second.map->reset();
  all_.changed_binary = all_.changed_markers = all_.changed_centers = true;
  for (auto& entry : robot_maps_) entry.second.changed_binary = entry.second.changed_markers = entry.second.changed_centers = true;
  return true;
}

void MapperRos::saveOnShutdown()
{
  if (map_file_.empty()) return;
  try {
    all_.map->save(map_file_);
    ROS_INFO_STREAM("mapper: saved " << all_.map->occupiedLeafCount() << " occupied leaves to " << map_file_);
    for (auto& entry : robot_maps_) {
      const std::string path = map_file_.substr(0, map_file_.rfind(".bt")) + "_" + entry.first + ".bt";
      entry.second.map->save(path);
    }
  } catch (const Error& e) {
    ROS_ERROR_STREAM("mapper: " << e.what());
  }
}

void MapperRos::spin()
{
  ros::spin();  // returns on SIGINT/SIGTERM (roscpp's handler) or ros::shutdown()
  tf_spinner_->stop();
  saveOnShutdown();
}

}  // namespace ros_layer
}  // namespace unexmin
