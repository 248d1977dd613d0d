// Inertial measurement unit with magnetometer, thermometer and pressure sensor (the UX-1's KVH 1775
// and its depth cell). Type name "imu". From the IMU link's true motion:
//   specific force  f = R_s^T (a_P - g),  a_P = a_O + alpha x r + w x (w x r)
//   angular rate    R_s^T w
//   magnetic field  R_s^T B_world, B_world the world's total field at the IMU origin (the world file's
//                   magnetic_field and the geology's anomalies) through the robot's own field, [mG]
//                   (sensors/magnetic_field.h, docs/magnetometer.md)
// with a_O the base link origin's acceleration over the last physics step, alpha the angular
// acceleration from the difference of the last two angular velocities, r the IMU origin's offset
// from the base link origin (world axes), R_s the IMU link's orientation in the world and g = (0, 0, -g).
// Pressure is the hydrostatic pressure at the IMU origin (see pressure_sensor.h).
//
// Parameters (optional; defaults give an ideal sensor; units per axis):
//   noise                    gaussian | none (gaussian)
//   gyro_noise_density       [rad/s/sqrt(Hz)] (0)    gyro_bias_random_walk  [rad/s/sqrt(s)] (0)
//   gyro_turn_on_bias        [rad/s] 1 sigma (0)     gyro_range             [rad/s] (1e3)
//   accel_noise_density      [m/s^2/sqrt(Hz)] (0)    accel_bias_random_walk [m/s^2/sqrt(s)] (0)
//   accel_turn_on_bias       [m/s^2] 1 sigma (0)     accel_range            [m/s^2] (1e4)
//   mag_noise_density        [mG/sqrt(Hz)] (0)       mag_bias_random_walk   [mG/sqrt(s)] (0)
//   mag_turn_on_bias         [mG] 1 sigma (0)        mag_range              [mG] (1e5)
//   temperature              [degC] (20)             temperature_noise      [degC] 1 sigma (0)
//   water_temperature        [degC] (20): what the pressure cell's thermometer reads
//   pressure_noise           [Pa] 1 sigma (0)        pressure_range         [Pa] (1e8)
// A density N becomes a per-sample standard deviation N sqrt(rate).
#pragma once

#include <unexmin/sensors/noise_model.h>
#include <unexmin/sensors/sensor.h>

#include <array>
#include <memory>

namespace unexmin {
namespace sensors {

class SensorParams;

struct ImuSample {
  double time = 0.0;                          ///< [s]
  Eigen::Vector3d specific_force{0, 0, 0};    ///< IMU frame [m/s^2]
  Eigen::Vector3d angular_velocity{0, 0, 0};  ///< IMU frame [rad/s]
  Eigen::Vector3d magnetic_field{0, 0, 0};    ///< IMU frame [mG]
  double temperature = 0.0;                   ///< IMU internal [degC]
  double pressure = 0.0;                      ///< absolute, at the IMU origin [Pa]
  double pressure_temperature = 0.0;          ///< [degC]
  /// Per-sample white-noise variances (message covariances) [(m/s^2)^2, (rad/s)^2, mG^2, Pa^2].
  double accel_variance = 0.0, gyro_variance = 0.0, mag_variance = 0.0, pressure_variance = 0.0;
};

class ImuSensor : public Sensor {
public:
  /// Throws ConfigError naming the sensor and the parameter.
  ImuSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const ImuSample& last() const { return last_; }

protected:
  void onReset() override;
  void track(const SensorContext& ctx) override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  using Channel = std::array<std::unique_ptr<NoiseModel>, 3>;
  /// Reads <prefix>_noise_density, _bias_random_walk, _turn_on_bias and builds three channels.
  static Channel makeChannel(SensorParams& p, const std::string& family, const std::string& prefix,
                             const std::string& unit, double rate);
  Eigen::Vector3d corrupt(Channel& channel, const Eigen::Vector3d& truth, double range);

  Channel gyro_, accel_, mag_;
  std::unique_ptr<NoiseModel> temperature_noise_, pressure_noise_, pressure_temperature_noise_;
  double gyro_range_ = 1e3, accel_range_ = 1e4, mag_range_ = 1e5, pressure_range_ = 1e8;
  double temperature_ = 20.0, water_temperature_ = 20.0;

  Eigen::Vector3d previous_w_{0, 0, 0};  ///< world angular velocity at the previous step [rad/s]
  Eigen::Vector3d alpha_{0, 0, 0};       ///< world angular acceleration over the last step [rad/s^2]
  bool have_previous_ = false;
  ImuSample last_;
};

}  // namespace sensors
}  // namespace unexmin
