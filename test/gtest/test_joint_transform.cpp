// mapping::jointOriginTransform against what robot_state_publisher computes for a fixed joint, bit for bit: urdfdom's
// Rotation::setFromRPY, kdl_parser's KDL::Rotation::Quaternion and KDL's GetQuaternion (as tf2_kdl's kdlToTransform
// reads it), over the mounts of the shipped robots' angles and 200 000 seeded random rpy. A mount a bit off would
// put the in-process mapper's clouds on other floats than the mapper node's.
#include <unexmin/mapping/joint_transform.h>

#include <gtest/gtest.h>
#include <urdf_model/pose.h>
#include <kdl/frames.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace unexmin {
namespace mapping {
namespace {

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (a == 0.0 && b == 0.0);
}

/// The quaternion robot_state_publisher publishes for a joint origin of these angles [rad].
Eigen::Quaterniond published(double roll, double pitch, double yaw) {
  urdf::Rotation r;
  r.setFromRPY(roll, pitch, yaw);
  const KDL::Rotation m = KDL::Rotation::Quaternion(r.x, r.y, r.z, r.w);
  double x, y, z, w;
  m.GetQuaternion(x, y, z, w);
  return Eigen::Quaterniond(w, x, y, z);
}

int differences(const std::vector<Eigen::Vector3d>& angles) {
  int bad = 0;
  for (const Eigen::Vector3d& rpy : angles) {
    const Eigen::Quaterniond want = published(rpy.x(), rpy.y(), rpy.z());
    const RigidTransform got = jointOriginTransform(Eigen::Vector3d(0.1, -0.2, 0.3), rpy);
    const bool same = sameBits(got.rotation.x(), want.x()) && sameBits(got.rotation.y(), want.y()) &&
                      sameBits(got.rotation.z(), want.z()) && sameBits(got.rotation.w(), want.w());
    if (!same && ++bad <= 3)
      ADD_FAILURE() << "rpy " << rpy.transpose() << ": got " << got.rotation.coeffs().transpose() << ", KDL "
                    << want.coeffs().transpose();
  }
  return bad;
}

TEST(JointTransform, TranslationIsTheOriginAsWritten) {
  const RigidTransform t =
      jointOriginTransform(Eigen::Vector3d(0.27189233611099495, 0.0, -0.12678547852220984), Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(t.translation, Eigen::Vector3d(0.27189233611099495, 0.0, -0.12678547852220984));
  EXPECT_EQ(t.rotation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
}

TEST(JointTransform, RotationIsRobotStatePublishersForTheShippedMounts) {
  // The angles of urdf/*.xacro's fixed joints: the DVL upside down and its beams, the optical frames, the sonar's tilt.
  const double a[] = {0.0,
                      M_PI,
                      -M_PI,
                      M_PI / 2,
                      -M_PI / 2,
                      1.1344640137963142,
                      -1.1344640137963142,
                      4.71238898038469,
                      0.17453292519943295,
                      0.3490658503988659,
                      0.9599310885968813,
                      2.356194490192345};
  std::vector<Eigen::Vector3d> angles;
  for (double r : a)
    for (double p : a)
      for (double y : a)
        angles.emplace_back(r, p, y);
  EXPECT_EQ(differences(angles), 0);
}

TEST(JointTransform, RotationIsRobotStatePublishersForRandomAngles) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-7.0, 7.0);
  std::vector<Eigen::Vector3d> angles(200000);
  for (auto& rpy : angles)
    rpy = Eigen::Vector3d(angle(rng), angle(rng), angle(rng));
  EXPECT_EQ(differences(angles), 0);
}

TEST(JointTransform, RotationTurnsAxesAsTheAnglesSay) {
  // rpy (0, 0, pi/2): the child's x axis is the parent's y axis.
  const RigidTransform t = jointOriginTransform(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, M_PI / 2));
  EXPECT_NEAR((t.rotate(Eigen::Vector3d::UnitX()) - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-15);
  // rpy (pi, 0, 0): the child's z axis points down.
  const RigidTransform d = jointOriginTransform(Eigen::Vector3d::Zero(), Eigen::Vector3d(M_PI, 0, 0));
  EXPECT_NEAR((d.rotate(Eigen::Vector3d::UnitZ()) + Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin
