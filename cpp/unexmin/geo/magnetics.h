// Magnetic anomalies of a world's geology (docs/magnetometer.md, "The field"): every body magnetised by the ambient
// (Earth) field through its susceptibility contrast with the host rock, plus its remanence, and the total field
// B(p) = ambient + sum of the bodies' anomalies at a world point. SI throughout, fields in nT, world frame ENU (x
// east, y north, z up). Knows no ROS.
//
//   induced + remanent magnetisation  (I + dchi N) M = dchi F / mu0 + dM_r   (body axes; N the demagnetising
//                                     factors: an ellipsoid's from Osborn 1945 / Stoner 1945, zero for the prisms)
//   ellipsoid   outside: a dipole m = V M at its centre (exact for a sphere, an approximation for other
//               ellipsoids whose error falls as (size / distance)^2); inside: the uniform mu0 (I - N) M
//   box         the closed-form field of a uniformly magnetised rectangular prism from its eight corners
//               (Bhattacharyya 1964; Blakely 1995, "Potential Theory in Gravity and Magnetic Applications")
//   vein        a prism of the vein's thickness and a square face of the disc's area (side e sqrt(pi)); an
//               unbounded vein a square of side 2 kTruncation
//   stratum     a prism of its thickness and a square face of side 2 kTruncation about its reference point
// dchi = chi_body - chi_host and dM_r = M_r,body d_body - M_r,host F/|F| (the host rock fills everything, its own
// uniform magnetisation has no field). The demagnetisation of a prism is neglected (valid while chi << 1). Overlapping
// bodies add (the later one does not cut the earlier); mine workings inside a body are not removed from it.
#pragma once

#include <unexmin/geo/geology.h>

#include <Eigen/Geometry>

#include <memory>
#include <vector>

namespace unexmin {
namespace geo {

constexpr double kMu0 = 4.0e-7 * 3.14159265358979323846;  ///< vacuum permeability [T m/A]
constexpr double kNanoteslaPerMilligauss = 100.0;         ///< 1 mG = 1e-7 T = 100 nT
/// Half the side of the square an unbounded vein or a stratum is truncated to [m].
constexpr double kTruncation = 1000.0;

/// The ENU field vector [nT] of total intensity `intensity` [nT], inclination `inclination` [deg] (positive
/// down) and declination `declination` [deg] (positive east of north): (H sin D, H cos D, -F sin I), H = F cos I.
Eigen::Vector3d fieldFromAngles(double intensity, double inclination, double declination);

/// Carlson's symmetric elliptic integral R_D(x, y, z) = 3/2 int_0^inf dt / ((t + z) sqrt((t + x)(t + y)(t + z))),
/// x, y >= 0 (not both 0), z > 0; by duplication to a relative error below 1e-12.
double carlsonRD(double x, double y, double z);

/// Demagnetising factors (N_a, N_b, N_c) of an ellipsoid of semi-axes `semi_axes` [m] along its own axes, summing
/// to 1 (Osborn 1945: N_a = abc/3 R_D(b^2, c^2, a^2)); a sphere's are 1/3 each.
Eigen::Vector3d demagnetisingFactors(const Eigen::Vector3d& semi_axes);

/// Field [nT] at offset `r` [m] from a dipole of moment `m` [A m^2]: mu0 / (4 pi |r|^3) (3 (m.r^) r^ - m).
Eigen::Vector3d dipoleField(const Eigen::Vector3d& m, const Eigen::Vector3d& r);

/// Field [nT] at `q` [m] (the prism's frame, origin at its centre) of a rectangular prism of full edge lengths
/// `size` [m] uniformly magnetised with `M` [A/m] (same frame), inside and outside: B = mu0 (H + M inside),
/// H_i = 1/(4 pi) sum_j U_ij M_j, U the second derivatives of the prism's Newtonian potential in closed form.
Eigen::Vector3d prismField(const Eigen::Vector3d& size, const Eigen::Vector3d& M, const Eigen::Vector3d& q);

/// One body's magnetisation as the anomaly model uses it.
struct BodyMagnet {
  BodyKind kind = BodyKind::ellipsoid;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< centre and axes of the magnetised solid, world
  Eigen::Vector3d size{1, 1, 1};                           ///< ellipsoid: semi-axes; prisms: full edge lengths [m]
  Eigen::Vector3d magnetisation{0, 0, 0};                  ///< contrast M, world frame [A/m]
  Eigen::Vector3d moment{0, 0, 0};                         ///< V M [A m^2], world frame (the ellipsoid's dipole)
};

class MagneticAnomalies {
public:
  /// `ambient`: the Earth field, world frame [nT]; `geology` may be null (no anomaly).
  MagneticAnomalies(const Eigen::Vector3d& ambient, std::shared_ptr<const Geology> geology);

  const Eigen::Vector3d& ambient() const { return ambient_; }
  /// Sum of the bodies' anomalies at world point `p` [m], world frame [nT].
  Eigen::Vector3d anomaly(const Eigen::Vector3d& p) const;
  /// The total field ambient + anomaly(p), world frame [nT].
  Eigen::Vector3d field(const Eigen::Vector3d& p) const { return ambient_ + anomaly(p); }
  /// Per body of the geology, in its order.
  const std::vector<BodyMagnet>& magnets() const { return magnets_; }

private:
  Eigen::Vector3d ambient_;
  std::shared_ptr<const Geology> geology_;
  std::vector<BodyMagnet> magnets_;
};

}  // namespace geo
}  // namespace unexmin
