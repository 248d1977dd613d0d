#include <unexmin/ros_layer/mapper_ros.h>

#include <unexmin/core/error.h>
#include <unexmin/mapping/map_display.h>
#include <unexmin/mapping/scan_points.h>

#include <octomap_msgs/Octomap.h>
#include <sensor_msgs/point_cloud2_iterator.h>
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
class FunctionCallback : public ros::CallbackInterface {
public:
  explicit FunctionCallback(std::function<void()> f) : f_(std::move(f)) {}
  CallResult call() override {
    f_();
    return Success;
  }

private:
  std::function<void()> f_;
};

void require(bool ok, const std::string& name, double value, const std::string& expected) {
  if (!ok || !std::isfinite(value)) {
    throw ParameterError("mapper: parameter '~" + name + "' = " + formatNumber(value) + ": expected " + expected);
  }
}

mapping::TfSample sampleOf(const geometry_msgs::TransformStamped& t) {
  mapping::TfSample s;
  s.parent = t.header.frame_id;
  s.child = t.child_frame_id;
  s.stamp = static_cast<mapping::Stamp>(t.header.stamp.toNSec());
  const geometry_msgs::Vector3& v = t.transform.translation;
  const geometry_msgs::Quaternion& q = t.transform.rotation;
  s.transform.translation = Eigen::Vector3d(v.x, v.y, v.z);
  s.transform.rotation = Eigen::Quaterniond(q.w, q.x, q.y, q.z);
  return s;
}

}  // namespace

MapperRos::MapperRos(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
  loadParams();
  queue_ = std::make_unique<mapping::CloudQueue>(world_frame_, tf_timeout_, tf_max_gap_);
  // Our own /tf subscribers with the clouds' queue depth: in lockstep the simulator publishes tf far faster
  // than real time, and tf2_ros's TransformListener (queue 100) would drop samples under load. They run on
  // their own queue and thread, so that a busy insertion never lets their queue overflow.
  ros::NodeHandle tf_nh(nh_);
  tf_nh.setCallbackQueue(&tf_queue_);
  using TfEvent = ros::MessageEvent<tf2_msgs::TFMessage const>;
  tf_sub_ = tf_nh.subscribe<tf2_msgs::TFMessage, const TfEvent&>(
      "/tf", queue_size_, [this](const TfEvent& e) { onTf(e, false); }, ros::VoidConstPtr(),
      ros::TransportHints().tcpNoDelay());
  tf_static_sub_ = tf_nh.subscribe<tf2_msgs::TFMessage, const TfEvent&>("/tf_static", queue_size_,
                                                                        [this](const TfEvent& e) { onTf(e, true); });
  all_ = makeOutput(nh_);
  for (const std::string& robot : robots_) {
    if (per_robot_)
      robot_maps_.emplace(robot, makeOutput(ros::NodeHandle(nh_, robot)));
    subscribe(robot);
  }
  stats_pub_ = pnh_.advertise<unexmin::MapperStats>("stats", 10);
  save_srv_ = pnh_.advertiseService("save_map", &MapperRos::onSaveMap, this);
  reset_srv_ = pnh_.advertiseService("reset", &MapperRos::onReset, this);
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / publish_rate_), &MapperRos::onTimer, this);
  tf_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &tf_queue_);
  tf_spinner_->start();
  ROS_INFO_STREAM("mapper: " << robots_.size() << " robot(s), resolution " << params_.resolution << " m, max range "
                             << params_.max_range << " m (M3 " << sources_.m3_max_range << " m, SLS "
                             << sources_.sls_max_range << " m, sonar " << sources_.sonar_max_range << " m, DVL "
                             << sources_.dvl_max_range << " m), M3 " << (sources_.m3 ? "on" : "off") << ", "
                             << sources_.sls_units << " SLS unit(s), sonar "
                             << (sources_.sonar ? "/<robot>/" + sources_.sonar_topic : "off") << ", DVL "
                             << (sources_.dvl ? "on" : "off") << (map_file_.empty() ? "" : ", saves to " + map_file_));
}

void MapperRos::loadParams() {
  pnh_.param("resolution", params_.resolution, params_.resolution);
  pnh_.param("max_range", params_.max_range, params_.max_range);
  pnh_.param("prob_hit", params_.prob_hit, params_.prob_hit);
  pnh_.param("prob_miss", params_.prob_miss, params_.prob_miss);
  pnh_.param("clamp_min", params_.clamp_min, params_.clamp_min);
  pnh_.param("clamp_max", params_.clamp_max, params_.clamp_max);
  params_.validate();
  pnh_.param("m3", sources_.m3, sources_.m3);
  pnh_.param("sls_units", sources_.sls_units, sources_.sls_units);
  pnh_.param("sonar", sources_.sonar, sources_.sonar);
  pnh_.param("sonar_topic", sources_.sonar_topic, sources_.sonar_topic);
  pnh_.param("dvl", sources_.dvl, sources_.dvl);
  pnh_.param("m3_max_range", sources_.m3_max_range, sources_.m3_max_range);
  pnh_.param("sls_max_range", sources_.sls_max_range, sources_.sls_max_range);
  pnh_.param("sonar_max_range", sources_.sonar_max_range, sources_.sonar_max_range);
  pnh_.param("dvl_max_range", sources_.dvl_max_range, sources_.dvl_max_range);
  sources_.resolve(params_.max_range);
  pnh_.param("frame_id", world_frame_, world_frame_);
  pnh_.param("per_robot", per_robot_, per_robot_);
  pnh_.param("publish_rate", publish_rate_, publish_rate_);
  pnh_.param("tf_timeout", tf_timeout_, tf_timeout_);
  pnh_.param("tf_max_gap", tf_max_gap_, tf_max_gap_);
  pnh_.param("queue_size", queue_size_, queue_size_);
  pnh_.param("map_file", map_file_, map_file_);
  double robots_timeout = 30.0;
  pnh_.param("robots_timeout", robots_timeout, robots_timeout);
  require(publish_rate_ > 0.0 && publish_rate_ <= 100.0, "publish_rate", publish_rate_, "(0, 100] Hz");
  require(tf_timeout_ > 0.0, "tf_timeout", tf_timeout_, "> 0 s");
  require(tf_max_gap_ > 0.0, "tf_max_gap", tf_max_gap_, "> 0 s");
  require(queue_size_ >= 1, "queue_size", queue_size_, ">= 1");
  require(robots_timeout >= 0.0, "robots_timeout", robots_timeout, ">= 0 s");
  if (world_frame_.empty())
    throw ParameterError("mapper: parameter '~frame_id' is empty: expected a frame");

  // The robots: ~robots, else the simulator's /sim/robots (set at its start-up: wait for it).
  if (!pnh_.getParam("robots", robots_)) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(robots_timeout);
    while (!nh_.getParam("/sim/robots", robots_) && ros::ok() && ros::WallTime::now() < deadline) {
      ros::WallDuration(0.1).sleep();
    }
  }
  if (robots_.empty()) {
    throw ConfigError("mapper: no robots: neither '~robots' nor '/sim/robots' (waited " + formatNumber(robots_timeout) +
                      " s) names any");
  }
}

MapperRos::Output MapperRos::makeOutput(ros::NodeHandle nh) {
  Output out;
  out.map = std::make_unique<mapping::OccupancyMap>(params_);
  out.binary = nh.advertise<octomap_msgs::Octomap>("octomap_binary", 1, true);
  out.markers = nh.advertise<visualization_msgs::MarkerArray>("occupied_cells_vis_array", 1, true);
  out.centers = nh.advertise<sensor_msgs::PointCloud2>("octomap_point_cloud_centers", 1, true);
  return out;
}

void MapperRos::subscribe(const std::string& robot) {
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  if (sources_.m3) {
    subscribers_.push_back(nh_.subscribe<sensor_msgs::LaserScan>(
        "/" + robot + "/m3/scan", queue_size_,
        [this, robot](const sensor_msgs::LaserScanConstPtr& m) { onScan(robot, m); }, ros::VoidConstPtr(), hints));
  }
  for (int i = 0; i < sources_.sls_units; ++i) {
    subscribers_.push_back(nh_.subscribe<sensor_msgs::PointCloud2>(
        "/" + robot + "/sls_" + std::to_string(i) + "/points", queue_size_,
        [this, robot](const sensor_msgs::PointCloud2ConstPtr& m) { onCloud(robot, m, sources_.sls_max_range); },
        ros::VoidConstPtr(), hints));
  }
  if (sources_.sonar) {
    subscribers_.push_back(nh_.subscribe<sensor_msgs::PointCloud2>(
        "/" + robot + "/" + sources_.sonar_topic, queue_size_,
        [this, robot](const sensor_msgs::PointCloud2ConstPtr& m) { onCloud(robot, m, sources_.sonar_max_range); },
        ros::VoidConstPtr(), hints));
  }
  for (int i = 0; sources_.dvl && i < 4; ++i) {
    subscribers_.push_back(nh_.subscribe<sensor_msgs::Range>(
        "/" + robot + "/dvl_sonar" + std::to_string(i), queue_size_,
        [this, robot](const sensor_msgs::RangeConstPtr& m) { onRange(robot, m); }, ros::VoidConstPtr(), hints));
  }
}

void MapperRos::onScan(const std::string& robot, const sensor_msgs::LaserScanConstPtr& scan) {
  enqueue(robot, scan->header, sources_.m3_max_range,
          mapping::scanPoints(
              mapping::ScanGeometry{scan->angle_min, scan->angle_increment, scan->range_min, scan->range_max},
              scan->ranges));
}

void MapperRos::onCloud(const std::string& robot, const sensor_msgs::PointCloud2ConstPtr& msg, double max_range) {
  std::vector<octomap::point3d> points;
  points.reserve(static_cast<std::size_t>(msg->width) * msg->height);
  if (msg->width * msg->height > 0) {
    sensor_msgs::PointCloud2ConstIterator<float> x(*msg, "x"), y(*msg, "y"), z(*msg, "z");
    for (; x != x.end(); ++x, ++y, ++z)
      points.emplace_back(*x, *y, *z);
  }
  enqueue(robot, msg->header, max_range, std::move(points));
}

void MapperRos::onRange(const std::string& robot, const sensor_msgs::RangeConstPtr& msg) {
  std::vector<octomap::point3d> points;
  if (std::isfinite(msg->range) && msg->range >= msg->min_range && msg->range <= msg->max_range)
    points.emplace_back(msg->range, 0.0f, 0.0f);
  enqueue(robot, msg->header, sources_.dvl_max_range, std::move(points));
}

void MapperRos::onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& event, bool is_static) {
  const tf2_msgs::TFMessage& msg = *event.getConstMessage();
  std::vector<mapping::TfSample> samples;
  samples.reserve(msg.transforms.size());
  for (const geometry_msgs::TransformStamped& t : msg.transforms)
    samples.push_back(sampleOf(t));
  mapping::TfUpdate update;
  {
    std::lock_guard<std::mutex> lock(tf_mutex_);
    update = tf_.add(samples, event.getPublisherName(), ros::WallTime::now().toSec(), is_static);
  }
  if (!update.jump.empty()) {
    ROS_WARN_STREAM("mapper: tf of " << update.jump << ": clearing the tf buffer and the clouds waiting for it");
  }
  // Once per frame and publisher (a throttle runs on ROS time, which a reset sets back).
  for (const std::string& what : update.newly_ignored)
    ROS_WARN_STREAM("mapper: ignoring tf of " << what);
  for (const std::string& why : update.refused)
    ROS_WARN_STREAM_THROTTLE(5.0, "mapper: ignoring a tf sample: " << why);
  // The clouds waiting for tf are drained on the main thread (one request at a time).
  if (pending_count_ > 0 && !drain_posted_.exchange(true)) {
    ros::getGlobalCallbackQueue()->addCallback(boost::make_shared<FunctionCallback>([this] {
      drain_posted_ = false;
      drain();
    }));
  }
}

void MapperRos::enqueue(const std::string& robot, const std_msgs::Header& header, double max_range,
                        std::vector<octomap::point3d>&& points) {
  queue_->push(mapping::PendingCloud{robot, header.frame_id, static_cast<mapping::Stamp>(header.stamp.toNSec()),
                                     std::move(points), ros::WallTime::now().toSec(), max_range});
  pending_count_ = queue_->size();
  drain();
}

void MapperRos::drain() {
  const double now = ros::WallTime::now().toSec();
  for (;;) {
    mapping::CloudStep step;
    {
      std::lock_guard<std::mutex> lock(tf_mutex_);
      step = queue_->next(tf_, now);
    }
    if (step.kind == mapping::CloudStep::Kind::kWait)
      break;
    const mapping::PendingCloud& cloud = step.cloud;
    const ros::Time stamp = ros::Time().fromNSec(static_cast<uint64_t>(cloud.stamp));
    if (step.kind == mapping::CloudStep::Kind::kDrop) {
      ROS_WARN_STREAM_THROTTLE(5.0, "mapper: dropping a cloud of " << cloud.robot << " in '" << cloud.frame << "' at "
                                                                   << stamp << ": " << step.why);
      continue;
    }
    const std::vector<octomap::point3d> world = step.sensor_in_map.apply(cloud.points);
    const Eigen::Vector3d& t = step.sensor_in_map.translation;
    const octomap::point3d origin(static_cast<float>(t.x()), static_cast<float>(t.y()), static_cast<float>(t.z()));
    const ros::WallTime start = ros::WallTime::now();
    all_.map->insertCloud(world, origin, cloud.max_range);
    all_.changed();
    auto robot_map = robot_maps_.find(cloud.robot);
    if (robot_map != robot_maps_.end()) {
      robot_map->second.map->insertCloud(world, origin, cloud.max_range);
      robot_map->second.changed();
    }
    insert_seconds_ += (ros::WallTime::now() - start).toSec();
    ++inserted_;
    points_ += cloud.points.size();
    newest_stamp_ = std::max(newest_stamp_, stamp);
  }
  pending_count_ = queue_->size();
}

void MapperRos::publish(Output& out, const ros::Time& stamp) {
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
  if (!want_markers && !want_centers)
    return;
  const std::vector<mapping::Voxel> voxels = out.map->occupiedVoxels();
  if (want_markers) {
    const std::vector<mapping::CubeList> cubes = mapping::occupiedCubes(*out.map, voxels);
    visualization_msgs::MarkerArray array;
    array.markers.resize(cubes.size());
    for (std::size_t d = 0; d < cubes.size(); ++d) {
      visualization_msgs::Marker& m = array.markers[d];
      m.header.frame_id = world_frame_;
      m.header.stamp = stamp;
      m.ns = "occupied_cells";
      m.id = static_cast<int>(d);
      m.type = visualization_msgs::Marker::CUBE_LIST;
      m.action = cubes[d].cells.empty() ? visualization_msgs::Marker::DELETE : visualization_msgs::Marker::ADD;
      m.pose.orientation.w = 1.0;
      m.scale.x = m.scale.y = m.scale.z = cubes[d].size;
      m.points.resize(cubes[d].cells.size());
      m.colors.resize(cubes[d].cells.size());
      for (std::size_t k = 0; k < cubes[d].cells.size(); ++k) {
        m.points[k].x = cubes[d].cells[k].x;
        m.points[k].y = cubes[d].cells[k].y;
        m.points[k].z = cubes[d].cells[k].z;
        const mapping::Colour& c = cubes[d].colours[k];
        m.colors[k].r = c.r;
        m.colors[k].g = c.g;
        m.colors[k].b = c.b;
        m.colors[k].a = c.a;
      }
    }
    out.markers.publish(array);
    out.changed_markers = false;
  }
  if (want_centers) {
    const std::vector<octomap::point3d> centres = mapping::voxelCentres(voxels);
    sensor_msgs::PointCloud2 cloud;
    cloud.header.frame_id = world_frame_;
    cloud.header.stamp = stamp;
    sensor_msgs::PointCloud2Modifier modifier(cloud);
    modifier.setPointCloud2FieldsByString(1, "xyz");
    modifier.resize(centres.size());
    sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
    for (const octomap::point3d& c : centres) {
      *x = c.x();
      *y = c.y();
      *z = c.z();
      ++x, ++y, ++z;
    }
    out.centers.publish(cloud);
    out.changed_centers = false;
  }
}

void MapperRos::onTimer(const ros::WallTimerEvent&) {
  drain();
  publish(all_, newest_stamp_);
  for (auto& entry : robot_maps_)
    publish(entry.second, newest_stamp_);
  unexmin::MapperStats stats;
  stats.stamp = newest_stamp_;
  stats.clouds_received = queue_->received();
  stats.clouds_inserted = inserted_;
  stats.clouds_dropped = queue_->dropped();
  stats.points_inserted = points_;
  stats.pending = static_cast<uint32_t>(queue_->size());
  stats.insert_seconds = insert_seconds_;
  stats.occupied_leaves = all_.map->occupiedLeafCount();
  stats.memory_bytes = all_.map->memoryUsage();
  stats_pub_.publish(stats);
}

bool MapperRos::onSaveMap(unexmin::SaveMap::Request& req, unexmin::SaveMap::Response& res) {
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

bool MapperRos::onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  all_.map->reset();
  for (auto& entry : robot_maps_)
    entry.second.map->reset();
  all_.changed();
  for (auto& entry : robot_maps_)
    entry.second.changed();
  return true;
}

void MapperRos::saveOnShutdown() {
  if (map_file_.empty())
    return;
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

void MapperRos::spin() {
  ros::spin();  // returns on SIGINT/SIGTERM (roscpp's handler) or ros::shutdown()
  tf_spinner_->stop();
  saveOnShutdown();
}

}  // namespace ros_layer
}  // namespace unexmin
