// The geology of a world (key `geology:` of a world file, docs/worlds.md "Geology"): a host rock and bodies of
// other rock (ellipsoids, rotated boxes, veins, strata), the later body winning where two overlap, and the query
// every instrument asks: which body is at a point and what its rock is. Knows no ROS.
#pragma once

#include <unexmin/geo/rock.h>

#include <Eigen/Geometry>

#include <limits>
#include <string>
#include <vector>

namespace unexmin {
namespace geo {

enum class BodyKind { ellipsoid, box, vein, stratum };

/// The kinds' names as world files write them, in BodyKind's order.
const std::vector<std::string>& bodyKindNames();

struct Body {
  std::string name;
  BodyKind kind = BodyKind::ellipsoid;
  /// ellipsoid, box: body frame in the world (centre and axes). vein, stratum: a point of the mid-plane (vein) or
  /// of the base (stratum), and the plane's unit normal as the frame's z axis.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// ellipsoid: semi-axes [m]; box: full edge lengths [m]; vein: (extent, extent, thickness) [m] (extent: the
  /// radius of its disc in the plane, infinity for an unbounded vein); stratum: (inf, inf, thickness) [m].
  Eigen::Vector3d size{1, 1, 1};
  /// Unit direction of the rock's remanence in the world; zero: along the ambient field (assumed).
  Eigen::Vector3d remanence_direction{0, 0, 0};
  Rock rock;

  /// Whether the world point `p` [m] is inside it (on its surface counts as inside).
  bool contains(const Eigen::Vector3d& p) const;
};

class Geology {
public:
  /// The host rock fills everything no body covers; `bodies` in the world file's order (the last wins).
  Geology(Rock host, std::vector<Body> bodies);

  /// The body at world point `p` [m]: 0 for the host rock, k >= 1 for bodies()[k - 1]. Tests the bodies from the
  /// last, each behind a bounding-box test; docs/benchmarks.md gives its cost per query.
  int bodyAt(const Eigen::Vector3d& p) const;
  /// The rock of body id `id` (0: the host).
  const Rock& rock(int id) const { return id == 0 ? host_ : bodies_[static_cast<std::size_t>(id) - 1].rock; }
  /// The rock at world point `p`.
  const Rock& rockAt(const Eigen::Vector3d& p) const { return rock(bodyAt(p)); }
  /// "host" for 0, else the body's name.
  const std::string& name(int id) const;
  const Rock& host() const { return host_; }
  const std::vector<Body>& bodies() const { return bodies_; }

private:
  Rock host_;
  std::vector<Body> bodies_;
  std::vector<Eigen::AlignedBox3d> bounds_;  ///< world-frame bounds per body (infinite for unbounded ones)
  std::vector<Eigen::Isometry3d> inverse_;   ///< world to body frame per body
  std::string host_name_ = "host";
};

}  // namespace geo
}  // namespace unexmin
