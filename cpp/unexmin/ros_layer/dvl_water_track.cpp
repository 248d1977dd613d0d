#include <unexmin/ros_layer/dvl_water_track.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace unexmin {
namespace ros_layer {
namespace {

constexpr double kPascalPerDbar = 1e4;
/// Beams behind x, y, z1, z2.
constexpr std::array<std::array<int, 2>, 4> kPairs{{{0, 2}, {1, 3}, {0, 2}, {1, 3}}};

double mean(const std::vector<double>& v) {
  if (v.empty())
    return 0.0;
  double s = 0.0;
  for (double x : v)
    s += x;  // in order, as Python's sum
  return s / static_cast<double>(v.size());
}

}  // namespace

dvl_nortek::DvlBottomWaterTrack waterTrack(const unexmin::Dvl& dvl) {
  using Track = dvl_nortek::DvlBottomWaterTrack;
  Track out;
  out.header = dvl.header;
  out.sound_speed = dvl.sound_speed;
  out.temperature = dvl.temperature;
  out.pressure = dvl.pressure / kPascalPerDbar;
  const double cos_a = std::cos(dvl.beam_angle);
  std::array<bool, 4> valid{};
  std::array<double, 4> dt1{};
  bool any = false;
  double last_echo = 0.0;
  for (int i = 0; i < 4; ++i) {
    valid[i] = dvl.beam_valid[i] && std::isfinite(dvl.range[i]) && std::isfinite(dvl.beam_velocity[i]);
    dt1[i] = valid[i] ? 2.0 * dvl.range[i] / dvl.sound_speed : 0.0;
    if (valid[i])
      last_echo = any ? std::max(last_echo, dt1[i]) : dt1[i];
    any = any || valid[i];
  }
  for (int i = 0; i < 4; ++i) {
    if (valid[i]) {
      out.range[i] = dvl.range[i] * cos_a;
      out.velocity_beam[i] = dvl.beam_velocity[i];
      out.fom_beam[i] = dvl.beam_velocity_std[i];
      out.dt1_beam[i] = dt1[i];
      out.dt2_beam[i] = last_echo - dt1[i];
      out.time_beam[i] = dt1[i] / 2.0;
    } else {
      out.range[i] = Track::INVALID_RANGE;
      out.velocity_beam[i] = Track::INVALID_VELOCITY;
      out.fom_beam[i] = Track::INVALID_FOM;
      out.dt1_beam[i] = out.dt2_beam[i] = out.time_beam[i] = 0.0;
    }
  }
  const auto& cov = dvl.velocity_covariance;
  const std::array<double, 4> values{dvl.velocity.x, dvl.velocity.y, dvl.velocity_z1, dvl.velocity_z2};
  // z1, z2 = (u_i + u_j) / (2 cos a): the std of a pair's mean over 2 cos a.
  std::array<double, 4> foms{std::sqrt(std::max(cov[0], 0.0)), std::sqrt(std::max(cov[4], 0.0)), 0.0, 0.0};
  for (int k = 2; k < 4; ++k)
    foms[k] = std::hypot(dvl.beam_velocity_std[kPairs[k][0]], dvl.beam_velocity_std[kPairs[k][1]]) / (2.0 * cos_a);
  for (int k = 0; k < 4; ++k) {
    if (dvl.bottom_lock && std::isfinite(values[k])) {
      std::vector<int> used;
      for (int b : kPairs[k])
        if (valid[b])
          used.push_back(b);
      if (used.size() != 2) {
        used.clear();
        for (int b = 0; b < 4; ++b)
          if (valid[b])
            used.push_back(b);
      }
      std::vector<double> d1, d2, t;
      for (int b : used) {
        d1.push_back(out.dt1_beam[b]);
        d2.push_back(out.dt2_beam[b]);
        t.push_back(out.time_beam[b]);
      }
      out.velocity_xyzz[k] = values[k];
      out.fom_xyzz[k] = foms[k];
      out.dt1_xyzz[k] = mean(d1);
      out.dt2_xyzz[k] = mean(d2);
      out.time_xyzz[k] = mean(t);
    } else {
      out.velocity_xyzz[k] = Track::INVALID_VELOCITY;
      out.fom_xyzz[k] = Track::INVALID_FOM;
      out.dt1_xyzz[k] = out.dt2_xyzz[k] = out.time_xyzz[k] = 0.0;
    }
  }
  return out;
}

}  // namespace ros_layer
}  // namespace unexmin
