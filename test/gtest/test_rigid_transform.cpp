// mapping::RigidTransform against closed forms: rotations about an axis by known angles, composition and inversion
// giving the identity, slerp halfway between two rotations, the long-way case (q and -q are one rotation), and
// clouds moved through the rotation matrix.
#include <unexmin/mapping/rigid_transform.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace unexmin {
namespace mapping {
namespace {

constexpr double kPi = 3.14159265358979323846;

RigidTransform make(double x, double y, double z, double angle, const Eigen::Vector3d& axis) {
  RigidTransform t;
  t.translation = Eigen::Vector3d(x, y, z);
  t.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
  return t;
}

void expectNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol) {
  EXPECT_NEAR(a.x(), b.x(), tol);
  EXPECT_NEAR(a.y(), b.y(), tol);
  EXPECT_NEAR(a.z(), b.z(), tol);
}

/// The angle [rad] between two rotations.
double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return 2.0 * std::acos(std::min(1.0, std::abs(a.dot(b))));
}

TEST(RigidTransform, RotatesAboutZByAQuarterTurn) {
  const RigidTransform t = make(1.0, 2.0, 3.0, kPi / 2, Eigen::Vector3d::UnitZ());
  expectNear(t.rotate(Eigen::Vector3d(1, 0, 0)), Eigen::Vector3d(0, 1, 0), 1e-15);
  expectNear(t.rotate(Eigen::Vector3d(0, 1, 0)), Eigen::Vector3d(-1, 0, 0), 1e-15);
  expectNear(t.rotate(Eigen::Vector3d(0, 0, 1)), Eigen::Vector3d(0, 0, 1), 1e-15);
}

TEST(RigidTransform, ComposesParentAfterChild) {
  // base 2 m ahead of the world origin turned a quarter turn left; the sensor 1 m ahead of base.
  const RigidTransform world_base = make(2.0, 0.0, 0.0, kPi / 2, Eigen::Vector3d::UnitZ());
  const RigidTransform base_sensor = make(1.0, 0.0, 0.5, 0.0, Eigen::Vector3d::UnitZ());
  const RigidTransform world_sensor = world_base * base_sensor;
  expectNear(world_sensor.translation, Eigen::Vector3d(2.0, 1.0, 0.5), 1e-15);
  EXPECT_NEAR(angleBetween(world_sensor.rotation, world_base.rotation), 0.0, 1e-7);
}

TEST(RigidTransform, InverseUndoesIt) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const RigidTransform t =
        make(u(rng) * 5, u(rng) * 5, u(rng) * 5, u(rng) * kPi, Eigen::Vector3d(u(rng), u(rng), 1.0));
    const RigidTransform id = t.inverse() * t;
    expectNear(id.translation, Eigen::Vector3d::Zero(), 1e-14);
    EXPECT_NEAR(angleBetween(id.rotation, Eigen::Quaterniond::Identity()), 0.0, 1e-7);
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    expectNear(t.inverse().rotate(t.rotate(p)), p, 1e-14);
  }
}

TEST(RigidTransform, InterpolatesLinearlyAndAlongTheShortestArc) {
  const RigidTransform a = make(0.0, 0.0, 0.0, 0.0, Eigen::Vector3d::UnitZ());
  const RigidTransform b = make(4.0, -2.0, 1.0, kPi / 2, Eigen::Vector3d::UnitZ());
  const RigidTransform q = RigidTransform::interpolate(a, b, 0.25);
  expectNear(q.translation, Eigen::Vector3d(1.0, -0.5, 0.25), 1e-15);
  EXPECT_NEAR(angleBetween(q.rotation, make(0, 0, 0, kPi / 8, Eigen::Vector3d::UnitZ()).rotation), 0.0, 1e-7);
  // -b.rotation is the same rotation: the slerp takes the short way all the same.
  RigidTransform b_neg = b;
  b_neg.rotation.coeffs() = -b.rotation.coeffs();
  const RigidTransform q_neg = RigidTransform::interpolate(a, b_neg, 0.25);
  EXPECT_NEAR(angleBetween(q_neg.rotation, q.rotation), 0.0, 1e-7);
  // The ends are the samples.
  EXPECT_NEAR(angleBetween(RigidTransform::interpolate(a, b, 1.0).rotation, b.rotation), 0.0, 1e-7);
  EXPECT_EQ(RigidTransform::interpolate(a, a, 0.3).rotation.coeffs(), a.rotation.coeffs());
}

TEST(RigidTransform, MovesCloudsLikeRotateAndTranslate) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const RigidTransform t = make(3.0, -1.0, 0.5, 2.0, Eigen::Vector3d(0.3, -0.2, 1.0));
  std::vector<octomap::point3d> cloud;
  for (int i = 0; i < 50; ++i)
    cloud.emplace_back(u(rng) * 10, u(rng) * 10, u(rng) * 10);
  const std::vector<octomap::point3d> moved = t.apply(cloud);
  ASSERT_EQ(moved.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d e = t.rotate(Eigen::Vector3d(cloud[i].x(), cloud[i].y(), cloud[i].z())) + t.translation;
    expectNear(Eigen::Vector3d(moved[i].x(), moved[i].y(), moved[i].z()), e, 1e-5);  // float rounding of 10 m
  }
  EXPECT_TRUE(t.apply({}).empty());
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin
