#include <unexmin/ros_layer/imaging_sonar_publisher.h>

#include <unexmin/core/error.h>

#include <sensor_msgs/image_encodings.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace unexmin {
namespace ros_layer {
namespace {

/// /<robot>/<sensor>/cloud_threshold [dB], 15 when unset; ParameterError naming it unless > 0.
double cloudThreshold(const ros::NodeHandle& nh, const std::string& param) {
  double threshold = 15.0;
  nh.param(param, threshold, threshold);
  if (!(threshold > 0.0) || !std::isfinite(threshold))
    throw ParameterError("parameter " + param + " = " + formatNumber(threshold) + ": expected > 0 dB");
  return threshold;
}

}  // namespace

ImagingSonarPublisher::ImagingSonarPublisher(sensors::sonar::ImagingSonarSensor& sensor, const PublisherContext& ctx)
    : sensor_(sensor),
      fan_(sensor.beams(), sensor.fovH(), sensor.bins(), sensor.rangeMin(), sensor.rangeMax(), sensor.fanHeight()),
      cloud_(sensor, cloudThreshold(ctx.nh, ctx.ns + sensor.name() + "/cloud_threshold")) {
  // Images are large: a short queue (a slow subscriber drops images rather than filling the memory).
  const int queue = std::max(2, static_cast<int>(2.0 * sensor.rate()));
  polar_pub_ = ctx.nh.advertise<sensor_msgs::Image>(
      resolve(ctx.ns, topicParam(sensor, "topic", sensor.name() + "/polar")), queue);
  fan_pub_ = ctx.nh.advertise<sensor_msgs::Image>(
      resolve(ctx.ns, topicParam(sensor, "fan_topic", sensor.name() + "/fan")), queue);
  points_pub_ = ctx.nh.advertise<sensor_msgs::PointCloud2>(
      resolve(ctx.ns, topicParam(sensor, "points_topic", sensor.name() + "/points")), queue);
  std::vector<double> azimuths(sensor.beams());
  for (std::size_t k = 0; k < azimuths.size(); ++k)
    azimuths[k] = sensor.azimuth(k);
  const std::string params = ctx.ns + sensor.name() + "/";
  ctx.nh.setParam(params + "beam_azimuths", azimuths);
  ctx.nh.setParam(params + "range_min", sensor.rangeMin());
  ctx.nh.setParam(params + "range_max", sensor.rangeMax());
  ctx.nh.setParam(params + "range_resolution", sensor.rangeResolution());
  ctx.nh.setParam(params + "fan_pixel_size", fan_.pixelSize());
  // Ping only while someone subscribes to an image or the cloud, or the simulator records one.
  sensor_.setDemand([this] { return wanted(polar_pub_) || wanted(fan_pub_) || wanted(points_pub_); });
}

ImagingSonarPublisher::~ImagingSonarPublisher() {
  sensor_.setDemand(nullptr);
}

sensor_msgs::Image ImagingSonarPublisher::mono8(double time, const std::string& frame, std::size_t rows,
                                                std::size_t cols) {
  sensor_msgs::Image m;
  m.header.stamp.fromSec(time);
  m.header.frame_id = frame;
  m.height = static_cast<std::uint32_t>(rows);
  m.width = static_cast<std::uint32_t>(cols);
  m.encoding = sensor_msgs::image_encodings::MONO8;
  m.is_bigendian = 0;
  m.step = static_cast<std::uint32_t>(cols);
  m.data.resize(rows * cols);
  return m;
}

sensor_msgs::Image ImagingSonarPublisher::polar() const {
  const sensors::sonar::PolarImage& p = sensor_.last();
  sensor_msgs::Image m = mono8(p.time, sensor_.frame(), p.bins, p.beams);
  m.data = p.codes;
  return m;
}

sensor_msgs::Image ImagingSonarPublisher::fan() const {
  const sensors::sonar::PolarImage& p = sensor_.last();
  sensor_msgs::Image m = mono8(p.time, sensor_.frame(), fan_.height(), fan_.width());
  fan_.render(p.codes, m.data);
  return m;
}

sensor_msgs::PointCloud2 ImagingSonarPublisher::points() {
  const sensors::sonar::PolarImage& p = sensor_.last();
  const std::vector<sensors::sonar::SonarPoint>& found = cloud_.build(p);
  sensor_msgs::PointCloud2 m;
  m.header.stamp.fromSec(p.time);
  m.header.frame_id = sensor_.frame();
  sensor_msgs::PointCloud2Modifier modifier(m);
  modifier.setPointCloud2Fields(4, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32,
                                "z", 1, sensor_msgs::PointField::FLOAT32, "intensity", 1,
                                sensor_msgs::PointField::FLOAT32);
  modifier.resize(found.size());
  m.height = 1;
  m.width = static_cast<std::uint32_t>(found.size());
  m.is_dense = true;
  sensor_msgs::PointCloud2Iterator<float> x(m, "x"), y(m, "y"), z(m, "z"), intensity(m, "intensity");
  for (const auto& f : found) {
    *x = f.xyz.x();
    *y = f.xyz.y();
    *z = f.xyz.z();
    *intensity = static_cast<float>(f.code) / 255.0f;
    ++x, ++y, ++z, ++intensity;
  }
  return m;
}

void ImagingSonarPublisher::publish() {
  if (!sensor_.last().built)
    return;
  if (wanted(polar_pub_))
    emit(polar_pub_, polar());
  if (wanted(fan_pub_))
    emit(fan_pub_, fan());
  if (wanted(points_pub_))
    emit(points_pub_, points());
}

}  // namespace ros_layer
}  // namespace unexmin
