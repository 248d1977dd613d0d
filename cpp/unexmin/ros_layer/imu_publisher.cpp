#include <unexmin/ros_layer/imu_publisher.h>

#include <kvh_1775/ImuRawKvh.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/MagneticField.h>
#include <unexmin/ImuRaw.h>

namespace unexmin {
namespace ros_layer {
namespace {

constexpr double kTeslaPerMilliGauss = 1e-7;
constexpr double kBarPerPascal = 1e-5;

template <class V>
void set(V& out, const Eigen::Vector3d& v, double scale = 1.0) {
  out.x = scale * v.x();
  out.y = scale * v.y();
  out.z = scale * v.z();
}

/// The fields of a raw IMU message (unexmin/ImuRaw, kvh_1775/ImuRawKvh: the same quantities under other names).
struct RawFields {
  geometry_msgs::Vector3& specific_force;
  geometry_msgs::Vector3& angular_velocity;
  geometry_msgs::Vector3& magnetic_field;
  double& temperature;
  double& pressure;
  double& pressure_temperature;
};

/// Fills `out` from `s`: the magnetic field [mG] times `field_scale`, the pressure [Pa] times `pressure_scale`.
void setRaw(const RawFields& out, const sensors::ImuSample& s, double field_scale, double pressure_scale) {
  set(out.specific_force, s.specific_force);
  set(out.angular_velocity, s.angular_velocity);
  set(out.magnetic_field, s.magnetic_field, field_scale);
  out.temperature = s.temperature;
  out.pressure = s.pressure * pressure_scale;
  out.pressure_temperature = s.pressure_temperature;
}

}  // namespace

ImuPublisher::ImuPublisher(const sensors::ImuSensor& sensor, const PublisherContext& ctx) : sensor_(sensor) {
  ros::NodeHandle& nh = ctx.nh;
  const std::string& ns = ctx.ns;
  bool kvh_direct = true, raw = false;
  nh.param(ns + "kvh_from_simulator", kvh_direct, true);
  nh.param(ns + "kvh_raw", raw, !kvh_direct);
  const std::string& name = sensor.name();
  const int kQueue = queueSize(sensor.rate());
  imu_ = nh.advertise<sensor_msgs::Imu>(resolve(ns, topicParam(sensor, "topic", name)), kQueue);
  mag_ = nh.advertise<sensor_msgs::MagneticField>(resolve(ns, topicParam(sensor, "mag_topic", name + "/mag")), kQueue);
  if (raw)
    raw_ = nh.advertise<unexmin::ImuRaw>(resolve(ns, topicParam(sensor, "raw_topic", name + "/raw")), kQueue);
  const std::string kvh = topicParam(sensor, "kvh_topic", "");
  if (kvh_direct && !kvh.empty())
    kvh_ = nh.advertise<kvh_1775::ImuRawKvh>(resolve(ns, kvh), kQueue);
}

void ImuPublisher::publish() {
  const sensors::ImuSample& s = sensor_.last();
  std_msgs::Header header;
  header.stamp.fromSec(s.time);
  header.frame_id = sensor_.frame();
  if (wanted(imu_)) {
    sensor_msgs::Imu m;
    m.header = header;
    m.orientation.w = 1.0;
    m.orientation_covariance[0] = -1.0;  // no orientation estimate
    set(m.angular_velocity, s.angular_velocity);
    set(m.linear_acceleration, s.specific_force);
    for (int i = 0; i < 3; ++i) {
      m.angular_velocity_covariance[4 * i] = s.gyro_variance;
      m.linear_acceleration_covariance[4 * i] = s.accel_variance;
    }
    emit(imu_, m);
  }
  if (wanted(mag_)) {
    sensor_msgs::MagneticField m;
    m.header = header;
    set(m.magnetic_field, s.magnetic_field, kTeslaPerMilliGauss);
    for (int i = 0; i < 3; ++i)
      m.magnetic_field_covariance[4 * i] = s.mag_variance * kTeslaPerMilliGauss * kTeslaPerMilliGauss;
    emit(mag_, m);
  }
  if (raw_ && wanted(raw_)) {
    unexmin::ImuRaw m;
    m.header = header;
    setRaw({m.linear_acceleration, m.angular_velocity, m.magnetic_field, m.temperature, m.pressure,
            m.pressure_temperature},
           s, kTeslaPerMilliGauss, 1.0);
    emit(raw_, m);
  }
  if (kvh_ && wanted(kvh_)) {
    // Same conversion as python/unexmin/translators/kvh.py (checked by test/rostest/sensors.py).
    kvh_1775::ImuRawKvh m;
    m.header = header;
    setRaw({m.accelerometer, m.gyroscope, m.magnetometer, m.temperature_imu, m.pressure, m.temperature_pressure}, s,
           1.0, kBarPerPascal);
    emit(kvh_, m);
  }
}

}  // namespace ros_layer
}  // namespace unexmin
