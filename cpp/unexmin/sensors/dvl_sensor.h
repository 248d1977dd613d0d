// Doppler velocity log with four Janus beams (the UX-1's Nortek DVL1000). Type name "dvl".
// Frame: the DVL link (on the UX-1 Nortek's instrument axes: x forward, y starboard, z out of the
// transducer face). Beam i points along b_i = (sin a cos c_i, sin a sin c_i, cos a), a = beam_angle,
// c_i = beam_azimuth_0 + i * 90 deg. Each ping:
//   - every beam is ray-cast from the DVL origin against the world (RayCaster), up to the free surface (a beam
//     that reaches it first is invalid, flagged `surface`, its figure of merit velocity_std +inf); valid when
//     it hits with a distance along z (range cos a) in [altitude_min, altitude_max];
//   - beam velocity u_i = (1 + e) b_i . v + noise, v the DVL origin's velocity over the (static)
//     bottom in the DVL frame, e a scale error drawn at turn-on;
//   - with >= 3 valid beams (bottom lock) the velocity is the least-squares solution of
//     B v = u over the valid beams, covariance s_b^2 (B^T B)^-1 + diag((s_e v)^2); z1 from beams 0
//     and 2, z2 from beams 1 and 3 ((u_i + u_j) / (2 cos a)); altitude = mean of range cos a.
// Sound speed: Medwin (1975) from the water temperature (the world's water column's at the DVL, else the
// water_temperature parameter), the configured salinity and depth: the speed the DVL assumes. Where the world has a
// water column, its ranges and beam velocities are scaled by assumed / the column's sound speed (sensor.h).
//
// Parameters (optional, defaults in brackets):
//   noise                 gaussian | none                                           (gaussian)
//   beam_angle            from the DVL z axis [rad], in (0, pi/2)                   (25 deg)
//   beam_azimuth_0        azimuth of beam 0 about z, from x [rad]                   (0)
//   beam_width            one-way beam width, for the Range messages [rad]          (3 deg)
//   beam_frames           4 link names whose +x must be the beams (checked to 0.1 deg)   (unchecked)
//   altitude_min / _max   bottom-lock window, distance along z [m]                  (0.1 / 75)
//   beam_velocity_noise   white noise per beam, 1 sigma [m/s]                       (0)
//   velocity_scale_error  scale error drawn at turn-on, 1 sigma [-]                 (0)
//   range_noise           white noise per beam range, 1 sigma [m]                   (0)
//   water_temperature     [degC] (20)   salinity [PSU] (0)   temperature_noise [degC] 1 sigma (0)
//   pressure_noise        [Pa] 1 sigma (0)
#pragma once

#include <unexmin/sensors/noise_model.h>
#include <unexmin/sensors/sensor.h>

#include <array>
#include <memory>
#include <vector>

namespace unexmin {
namespace sensors {

/// Speed of sound in water [m/s] (Medwin 1975): temperature [degC], salinity [PSU], depth [m].
double soundSpeedMedwin(double temperature, double salinity, double depth);

struct DvlBeam {
  Eigen::Vector3d direction{0, 0, 1};  ///< DVL frame, unit
  bool valid = false;                  ///< bottom detected within the altitude window
  double range = 0.0;                  ///< along the beam [m]; +inf when invalid
  double velocity = 0.0;               ///< along the beam, positive away from the face [m/s]; NaN when invalid
  double velocity_std = 0.0;           ///< its white noise, 1 sigma [m/s] (the figure of merit); +inf when
                                       ///< the beam met the free surface
  bool surface = false;                ///< the beam reached the free surface before any bottom: invalid
};

struct DvlSample {
  double time = 0.0;                                     ///< ping time [s]
  bool bottom_lock = false;                              ///< >= 3 valid beams
  Eigen::Vector3d velocity{0, 0, 0};                     ///< DVL over the bottom, DVL frame [m/s]; NaN without lock
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< [m^2/s^2]; -1 without lock
  double velocity_z1 = 0.0;                              ///< [m/s] from beams 0, 2; NaN when one is invalid
  double velocity_z2 = 0.0;                              ///< [m/s] from beams 1, 3; NaN when one is invalid
  double altitude = 0.0;     ///< mean distance along z of the valid beams [m]; NaN without lock
  double sound_speed = 0.0;  ///< [m/s]
  double temperature = 0.0;  ///< water [degC]
  double pressure = 0.0;     ///< absolute [Pa]
  std::array<DvlBeam, 4> beams;
};

class DvlSensor : public Sensor {
public:
  /// Throws ConfigError naming the sensor and the parameter.
  DvlSensor(const sim::SensorSpec& spec, const SensorSetup& setup);

  const DvlSample& last() const { return last_; }
  double beamAngle() const { return beam_angle_; }      ///< [rad]
  double beamAzimuth(std::size_t i) const;              ///< [rad]
  double beamWidth() const { return beam_width_; }      ///< [rad]
  double altitudeMin() const { return altitude_min_; }  ///< [m]
  double altitudeMax() const { return altitude_max_; }  ///< [m]
  /// Along-beam range window of the Range messages [m].
  double rangeMin() const { return altitude_min_ / std::cos(beam_angle_); }
  double rangeMax() const { return altitude_max_ / std::cos(beam_angle_); }

protected:
  void onReset() override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  double beam_angle_, beam_azimuth_0_, beam_width_, altitude_min_, altitude_max_;
  double water_temperature_, salinity_;
  double scale_sigma_ = 0.0;  ///< 1 sigma of the turn-on scale error [-]
  std::array<Eigen::Vector3d, 4> directions_;
  std::array<std::unique_ptr<NoiseModel>, 4> velocity_noise_, range_noise_;
  std::unique_ptr<NoiseModel> scale_noise_, temperature_noise_, pressure_noise_;
  std::vector<raycast::Ray> rays_;
  std::vector<raycast::Hit> hits_;
  DvlSample last_;
};

}  // namespace sensors
}  // namespace unexmin
