#include <unexmin/ros_layer/dvl_publisher.h>
#include <unexmin/ros_layer/dvl_water_track.h>

#include <geometry_msgs/TwistWithCovarianceStamped.h>
#include <sensor_msgs/Range.h>
#include <unexmin/Dvl.h>

#include <sstream>

namespace unexmin {
namespace ros_layer {
namespace {

/// Variance reported for the unmeasured angular part of the twist [rad^2/s^2].
constexpr double kUnmeasuredVariance = 1e6;

}  // namespace

DvlPublisher::DvlPublisher(const sensors::DvlSensor& sensor, const PublisherContext& ctx) : sensor_(sensor) {
  const std::string& name = sensor.name();
  const int queue = queueSize(sensor.rate());
  dvl_ = ctx.nh.advertise<unexmin::Dvl>(resolve(ctx.ns, topicParam(sensor, "topic", name)), queue);
  twist_ = ctx.nh.advertise<geometry_msgs::TwistWithCovarianceStamped>(
      resolve(ctx.ns, topicParam(sensor, "twist_topic", name + "_twist")), queue);
  bool translate = true;
  ctx.nh.param(ctx.ns + "dvl_from_simulator", translate, true);
  if (translate)
    track_ = ctx.nh.advertise<dvl_nortek::DvlBottomWaterTrack>(
        resolve(ctx.ns, topicParam(sensor, "water_track_topic", name + "_water_track")), queue);
  const std::string sonar = topicParam(sensor, "sonar_topic", name + "_sonar");
  std::istringstream frames(topicParam(sensor, "beam_frames", ""));
  for (std::size_t i = 0; i < 4; ++i) {
    sonar_[i] = ctx.nh.advertise<sensor_msgs::Range>(resolve(ctx.ns, sonar + std::to_string(i)), queue);
    if (!(frames >> beam_frames_[i]))
      beam_frames_[i] = sensor.frame();
  }
}

void DvlPublisher::publish() {
  const sensors::DvlSample& s = sensor_.last();
  std_msgs::Header header;
  header.stamp.fromSec(s.time);
  header.frame_id = sensor_.frame();
  const bool track = track_ && wanted(track_);
  if (wanted(dvl_) || track) {
    unexmin::Dvl m;
    m.header = header;
    m.bottom_lock = s.bottom_lock;
    m.velocity.x = s.velocity.x();
    m.velocity.y = s.velocity.y();
    m.velocity.z = s.velocity.z();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        m.velocity_covariance[3 * r + c] = s.covariance(r, c);
    m.velocity_z1 = s.velocity_z1;
    m.velocity_z2 = s.velocity_z2;
    m.altitude = s.altitude;
    m.sound_speed = s.sound_speed;
    m.temperature = s.temperature;
    m.pressure = s.pressure;
    m.beam_angle = sensor_.beamAngle();
    for (std::size_t i = 0; i < 4; ++i) {
      m.beam_azimuth[i] = sensor_.beamAzimuth(i);
      m.beam_valid[i] = s.beams[i].valid;
      m.range[i] = s.beams[i].range;
      m.beam_velocity[i] = s.beams[i].velocity;
      m.beam_velocity_std[i] = s.beams[i].velocity_std;
    }
    if (wanted(dvl_))
      emit(dvl_, m);
    if (track)
      emit(track_, waterTrack(m));
  }
  for (std::size_t i = 0; i < 4; ++i) {
    if (!wanted(sonar_[i]))
      continue;
    sensor_msgs::Range m;
    m.header.stamp = header.stamp;
    m.header.frame_id = beam_frames_[i];
    m.radiation_type = sensor_msgs::Range::ULTRASOUND;
    m.field_of_view = static_cast<float>(sensor_.beamWidth());
    m.min_range = static_cast<float>(sensor_.rangeMin());
    m.max_range = static_cast<float>(sensor_.rangeMax());
    m.range = static_cast<float>(s.beams[i].range);  // +inf: no bottom within the window (REP 117)
    emit(sonar_[i], m);
  }
  if (s.bottom_lock && wanted(twist_)) {
    geometry_msgs::TwistWithCovarianceStamped m;
    m.header = header;
    m.twist.twist.linear.x = s.velocity.x();
    m.twist.twist.linear.y = s.velocity.y();
    m.twist.twist.linear.z = s.velocity.z();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        m.twist.covariance[6 * r + c] = s.covariance(r, c);
    for (int i = 3; i < 6; ++i)
      m.twist.covariance[7 * i] = kUnmeasuredVariance;
    emit(twist_, m);
  }
}

}  // namespace ros_layer
}  // namespace unexmin
