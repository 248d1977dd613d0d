// A diffuse reflectance spectrum over 400..1000 nm, held on a 10 nm grid (linear between the knots it was made
// from, flat beyond the first and last knot), and the RGB albedo it gives. Knows no ROS.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

namespace unexmin {
namespace geo {

class Spectrum {
public:
  static constexpr double kFirst = 400.0;  ///< [nm]
  static constexpr double kLast = 1000.0;  ///< [nm]
  static constexpr double kStep = 10.0;    ///< [nm]
  static constexpr int kSize = 61;

  Spectrum() { values_.fill(0.0); }
  /// Linear through the knots (wavelengths [nm] strictly increasing, reflectances in [0, 1]; checked by the caller).
  static Spectrum fromKnots(const std::vector<double>& nm, const std::vector<double>& reflectance);

  /// Reflectance in [0, 1] at `nm` [nm] (clamped to 400..1000).
  double at(double nm) const;
  /// Mean reflectance over the bands blue 400-500, green 500-600, red 600-700 nm (box filters, assumed), as
  /// (r, g, b): the albedo the cameras' RGB channels see.
  Eigen::Vector3d rgb() const;
  /// this + w * other on the grid (linear mixing of areal fractions).
  void addScaled(const Spectrum& other, double w);

private:
  std::array<double, kSize> values_;
};

}  // namespace geo
}  // namespace unexmin
