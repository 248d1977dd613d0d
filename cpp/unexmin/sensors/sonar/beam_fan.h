// The rays of one sonar beam (docs/sonars.md "Beams, rays and footprints"): a column of rays across the beam's
// wide aperture, each carrying its share of the beam and the range extent of its footprint. Shared by the
// imaging sonar (one fan per beam) and the side-scan sonar (one fan per side). Knows no ROS.
//
// Beam coordinates: the beam's axis is +x, the aperture opens about +y (elevation e, positive towards +z), the
// narrow width about +z. Ray j (j = 0 .. rays-1) is at e_j = -aperture/2 + (j + 1/2) aperture / rays, direction
// d_j = (cos e_j, 0, sin e_j). `axis` turns beam coordinates into the sensor frame.
//
// Footprint: a ray of angular size de = aperture / rays by dw = width that meets a plane of normal n at range r
// covers the ranges r +- extent/2 with
//   extent = r (de |t_e . n| + dw |t_w . n|) / |d . n|        (|d . n| bounded >= 1e-3)
// t_e = (-sin e, 0, cos e) and t_w = (0, 1, 0) the unit tangents of d along the aperture and across the width:
// a plate facing the ray returns from one range, a floor at grazing incidence from a long stretch. Where the surface
// curves away or ends (a sphere's rim, an edge) the plane would reach too far: the extent is bounded by twice the
// range step to a neighbouring ray of the fan that hit, or by r (de + dw) when neither neighbour hit.
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sensors/sonar/beam_receiver.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

class BeamFan {
public:
  /// `axis`: beam coordinates -> sensor frame (a rotation); `aperture` [rad] in (0, pi], `width` [rad] > 0;
  /// `rays` >= 1. The caller checks the numbers (the sensors name the parameters).
  BeamFan(const Eigen::Matrix3d& axis, double aperture, double width, int rays);

  std::size_t size() const { return dirs_.size(); }
  double aperture() const { return aperture_; }  ///< [rad]
  double width() const { return width_; }        ///< [rad]
  /// Elevation of ray j in beam coordinates [rad].
  double elevation(std::size_t j) const;
  /// Unit direction of ray j in the sensor frame.
  const Eigen::Vector3d& direction(std::size_t j) const { return dirs_[j]; }
  /// Range extent [m] of ray j's footprint at range r [m] on a surface of unit normal n (sensor frame).
  double extent(std::size_t j, double r, const Eigen::Vector3d& n) const;
  /// Solid angle of the beam, width x 2 sin(aperture / 2) [sr] (the azimuth x elevation rectangle).
  double solidAngle() const;

  /// Writes the size() rays of the fan of a sensor at `sensor` (world frame) to out[0 .. size()): from its origin,
  /// up to `range_max` [m] (the longest path cast) or to the free surface at height surface_z [m] (sound does not leave
  /// the water: a ray stops there with no echo; a sensor above the surface hears nothing).
  void aim(const Eigen::Isometry3d& sensor, double range_max, double surface_z, raycast::Ray* out) const;
  /// Adds the echo of every hit of hits[0 .. size()) (the answers to aim()'s rays; `rotation`: sensor frame ->
  /// world) to `energy` through `receiver`: range, incidence from the hit's normal, spread over its footprint, binned
  /// at the ranges the sonar times (x scale, BeamReceiver::add).
  void listen(const Eigen::Matrix3d& rotation, const raycast::Hit* hits, const BeamReceiver& receiver, double scale,
              std::vector<double>& energy) const;

private:
  double aperture_ = 0.0, width_ = 0.0, ray_angle_ = 0.0;
  std::vector<Eigen::Vector3d> dirs_, along_;  ///< d_j and t_e (sensor frame)
  Eigen::Vector3d across_{0, 1, 0};            ///< t_w (sensor frame)
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin
