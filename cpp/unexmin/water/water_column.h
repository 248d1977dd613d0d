// The water column of a world (key `water:` of a world file, docs/worlds.md): profiles of temperature,
// conductivity or salinity, pH, redox potential, dissolved oxygen and turbidity against depth below the free
// surface, one for the whole world and optionally one per region (a box, the last listed winning), each with an
// optional boundary that heaves slowly; density and sound speed derived at every query (seawater.h). Knows no ROS.
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace unexmin {
namespace water {

/// One row of a profile: the water at `depth` [m below the free surface].
struct WaterRow {
  double depth = 0.0;         ///< [m] >= 0
  double temperature = 10.0;  ///< [degC] in [0, 40]
  double salinity = 0.0;      ///< practical salinity [PSU] in [0, 42] (when the profile gives salinity)
  double conductivity = 0.0;  ///< in-situ electrical conductivity [uS/cm] >= 0 (when it gives conductivity)
  double ph = 7.0;            ///< in [0, 14]
  double redox = 200.0;       ///< redox potential (ORP) [mV]
  double oxygen = 10.0;       ///< dissolved oxygen [mg/L] >= 0
  double turbidity = 0.0;     ///< [NTU] >= 0
};

/// A boundary inside a profile that heaves as d(t) = amplitude sin(2 pi t / period + phase) [m, down positive]:
/// the water at rest depth `depth` is found at depth + d(t); the displacement falls linearly to zero at the surface
/// and at the profile's last row, so the layers above and below stretch and nothing folds.
struct Boundary {
  bool enabled = false;
  double depth = 0.0;      ///< rest depth [m], strictly between 0 and the last row's depth
  double amplitude = 0.0;  ///< [m], |amplitude| below both the depth and the last row's depth minus it
  double period = 3600.0;  ///< [s] > 0
  double phase = 0.0;      ///< [rad]
};

struct Profile {
  std::vector<WaterRow> rows;  ///< sorted by depth; two rows at one depth make a sharp step there
  bool layers = false;         ///< false: linear between rows; true: each row holds down to the next row's depth
  bool conductivity = false;   ///< the rows give conductivity (salinity derived), else salinity
  Boundary boundary;
};

/// A profile that holds inside an axis-aligned box of the world frame.
struct Region {
  Eigen::AlignedBox3d box;  ///< [m]
  Profile profile;
};

/// The water at a point at a time; above the first row the first row's water, below the last the last's.
struct WaterSample {
  double depth = 0.0;         ///< [m] below the free surface (0 above it)
  double pressure = 0.0;      ///< sea pressure [dbar]: 1e-4 * 1000 kg/m^3 * g * depth (see docs/worlds.md)
  double temperature = 0.0;   ///< [degC]
  double salinity = 0.0;      ///< practical salinity [PSU]
  double conductivity = 0.0;  ///< in situ [uS/cm]
  double ph = 0.0;
  double redox = 0.0;        ///< [mV]
  double oxygen = 0.0;       ///< [mg/L]
  double turbidity = 0.0;    ///< [NTU]
  double density = 0.0;      ///< [kg/m^3] (EOS-80)
  double sound_speed = 0.0;  ///< [m/s] (Chen & Millero 1977)
};

/// Throws ConfigError "'<where>...' ...: expected ..." naming the first bad row and field: rows missing or not
/// sorted by depth (a depth given by more than two rows), a value out of its range (above), a bad boundary.
/// `where` is the profile's key path, e.g. "water.profile" or "water.regions[1].profile".
void checkProfile(const Profile& profile, const std::string& where);

class WaterColumn {
public:
  /// `surface_z` [m]: world z of the free surface; `gravity` [m/s^2]. Profiles must pass checkProfile().
  WaterColumn(Profile profile, std::vector<Region> regions, double surface_z, double gravity);

  /// The water at `point` (world frame [m]) at sim time `time` [s].
  WaterSample at(const Eigen::Vector3d& point, double time) const;
  /// The density [kg/m^3] and sound speed [m/s] of at(), without its other fields (no conductivity inverted).
  double densityAt(const Eigen::Vector3d& point, double time) const;
  double soundSpeedAt(const Eigen::Vector3d& point, double time) const;
  /// The weight of the water above `point` at `time`: g * integral of densityAt() along the vertical through the
  /// point's x, y from the free surface down to it [Pa, gauge] (0 at or above the surface). The vertical is cut at
  /// the faces of the regions it crosses and, inside each, at the depths where the rows of the profile holding
  /// there lie now (heaved by its boundary) and at the moved boundary; each piece is integrated by 3-point
  /// Gauss-Legendre (exact to degree 5). Exact for layers (EOS-80's own rise with pressure, quadratic in depth, is
  /// integrated exactly); within 1e-8 relative for linear profiles, measured 1.5e-9 over 150 m
  /// (test/gtest/test_water_pressure.cpp; docs/water_probe.md, "Pressure through the column").
  double hydrostaticPressure(const Eigen::Vector3d& point, double time) const;
  /// The profile that holds at `point`: the last region containing it, else the world's.
  const Profile& profileAt(const Eigen::Vector3d& point) const;
  /// The rest depth [m] whose water is found at `depth` at `time` under `profile`'s boundary (depth itself
  /// without one).
  static double restDepth(const Profile& profile, double depth, double time);

private:
  /// Salinity [PSU], temperature [degC] and sea pressure [dbar] at `point` at `time`.
  Eigen::Vector3d stp(const Eigen::Vector3d& point, double time) const;
  /// The density [kg/m^3] of `profile`'s water at `depth` [m] below the free surface at `time`.
  double densityIn(const Profile& profile, double depth, double time) const;

  Profile profile_;
  std::vector<Region> regions_;
  double surface_z_;
  double gravity_;
};

}  // namespace water
}  // namespace unexmin
