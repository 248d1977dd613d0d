// A rock: an assemblage of minerals by volume fraction and the properties it mixes from the mineral table
// (docs/minerals.md, "Mixing"). Knows no ROS.
#pragma once

#include <unexmin/geo/mineral_table.h>

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace unexmin {
namespace geo {

/// One mineral of an assemblage and its volume fraction in (0, 1].
struct Component {
  std::string mineral;
  double fraction = 0.0;
};

struct Rock {
  std::vector<Component> components;
  double density = 0.0;             ///< [kg/m^3]: sum of f_i rho_i
  double susceptibility = 0.0;      ///< [SI]: sum of f_i chi_i (valid while chi << 1; assumed beyond)
  double remanence = 0.0;           ///< [A/m]: sum of f_i M_i
  double potassium = 0.0;           ///< [% by weight]: mass-weighted, sum f_i rho_i K_i / density
  double uranium = 0.0;             ///< [ppm by weight]: mass-weighted
  double thorium = 0.0;             ///< [ppm by weight]: mass-weighted
  Spectrum reflectance;             ///< sum of f_i R_i(lambda) (areal mixing)
  Eigen::Vector3d albedo{0, 0, 0};  ///< reflectance.rgb(): (r, g, b) in [0, 1]
  /// The fluorescent minerals, each with its yield scaled by its fraction.
  std::vector<Fluorescence> fluorescence;

  /// Reflectance in [0, 1] at `nm` [nm].
  double reflectanceAt(double nm) const { return reflectance.at(nm); }
  /// The RGB light re-emitted per unit of absorbed excitation light at `excitation_nm` [nm] (zero when none of its
  /// minerals fluoresces there): the sum over its fluorescent minerals excited there of yield * fraction * colour.
  Eigen::Vector3d fluorescenceAt(double excitation_nm) const;
};

/// The rock of `components` from `table`; throws ConfigError "'<where>...' ..." on an unknown mineral (listing the
/// table's), a fraction outside (0, 1], a mineral given twice, or fractions not summing to 1 within 1e-6.
/// `where`: the key of the list, e.g. "geology.bodies[2].minerals".
Rock mixRock(const MineralTable& table, const std::vector<Component>& components, const std::string& where);

}  // namespace geo
}  // namespace unexmin
