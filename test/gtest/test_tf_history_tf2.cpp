// mapping::TfHistory and RigidTransform::apply against tf2's own buffer (tf2::BufferCore, no roscore), bit for bit:
// a seeded tree of dynamic and static frames sampled at irregular stamps, looked up at sample times, between them
// and outside them, in every direction. The mapper's clouds must land where tf2_ros would have put them.
#include <unexmin/mapping/tf_history.h>

#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/buffer_core.h>

#include <cstring>
#include <random>

namespace unexmin {
namespace mapping {
namespace {

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (a == 0.0 && b == 0.0);
}

struct Twin {
  tf2::BufferCore tf2{ros::Duration(120.0)};
  TfHistory ours{120.0, 1.0};

  void add(const std::string& parent, const std::string& child, Stamp stamp, const RigidTransform& t, bool is_static) {
    geometry_msgs::TransformStamped m;
    m.header.frame_id = parent;
    m.child_frame_id = child;
    m.header.stamp.fromNSec(static_cast<uint64_t>(stamp));
    m.transform.translation.x = t.translation.x();
    m.transform.translation.y = t.translation.y();
    m.transform.translation.z = t.translation.z();
    m.transform.rotation.x = t.rotation.x();
    m.transform.rotation.y = t.rotation.y();
    m.transform.rotation.z = t.rotation.z();
    m.transform.rotation.w = t.rotation.w();
    tf2.setTransform(m, "sim", is_static);
    ours.add({TfSample{parent, child, stamp, t}}, "sim", 0.0, is_static);
  }
};

RigidTransform randomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RigidTransform t;
  t.translation = Eigen::Vector3d(u(rng) * 20, u(rng) * 20, u(rng) * 5);
  t.rotation = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
  return t;
}

TEST(TfHistoryAgainstTf2, SameTransformsBitForBit) {
  std::mt19937 rng(2024);
  Twin twin;
  // world -> base_i (dynamic) -> arm_i (dynamic, its own stamps) -> m3_i (static); world -> map (static).
  std::vector<Stamp> times;
  for (int r = 0; r < 2; ++r) {
    const std::string id = std::to_string(r);
    twin.add("arm" + id, "m3_" + id, 0, randomPose(rng), true);
    Stamp t = 1000000000 + r * 7000000;
    for (int k = 0; k < 40; ++k) {
      t += std::uniform_int_distribution<Stamp>(1000000, 300000000)(rng);
      twin.add("world", "base" + id, t, randomPose(rng), false);
      times.push_back(t);
      if (k % 3 != 1)
        twin.add("base" + id, "arm" + id, t + 500000, randomPose(rng), false);
    }
  }
  twin.add("world", "map", 0, randomPose(rng), true);
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"world", "m3_0"}, {"world", "arm1"}, {"base0", "m3_0"}, {"m3_0", "world"},
      {"map", "m3_1"},   {"m3_1", "m3_0"},  {"arm0", "base0"}, {"world", "unknown"}};
  std::uniform_int_distribution<std::size_t> pick(0, times.size() - 1);
  std::uniform_int_distribution<Stamp> jitter(-200000000, 200000000);
  std::size_t compared = 0;
  for (int i = 0; i < 3000; ++i) {
    const auto& [target, source] = pairs[i % pairs.size()];
    const Stamp t = times[pick(rng)] + (i % 3 == 0 ? 0 : jitter(rng));
    ros::Time stamp;
    stamp.fromNSec(static_cast<uint64_t>(t));
    const bool tf2_can = twin.tf2.canTransform(target, source, stamp);
    const TfLookup ours = twin.ours.lookup(target, source, t);
    ASSERT_EQ(tf2_can, ours.status == TfLookup::Status::kOk) << target << " <- " << source << " at " << t;
    if (!tf2_can)
      continue;
    const geometry_msgs::TransformStamped ref = twin.tf2.lookupTransform(target, source, stamp);
    const auto& rt = ref.transform.translation;
    const auto& rq = ref.transform.rotation;
    const RigidTransform& o = ours.transform;
    ASSERT_TRUE(sameBits(rt.x, o.translation.x()) && sameBits(rt.y, o.translation.y()) &&
                sameBits(rt.z, o.translation.z()))
        << target << " <- " << source << " at " << t << ": tf2 " << rt.x << " " << rt.y << " " << rt.z << ", ours "
        << o.translation.transpose();
    ASSERT_TRUE(sameBits(rq.x, o.rotation.x()) && sameBits(rq.y, o.rotation.y()) && sameBits(rq.z, o.rotation.z()) &&
                sameBits(rq.w, o.rotation.w()))
        << target << " <- " << source << " at " << t;
    // A cloud through the matrix, as the mapper moved clouds with tf2's types.
    const tf2::Matrix3x3 R(tf2::Quaternion(rq.x, rq.y, rq.z, rq.w));
    std::vector<octomap::point3d> cloud;
    for (int k = 0; k < 8; ++k) {
      cloud.emplace_back(std::uniform_real_distribution<float>(-30.f, 30.f)(rng),
                         std::uniform_real_distribution<float>(-30.f, 30.f)(rng), 0.0f);
    }
    const std::vector<octomap::point3d> moved = o.apply(cloud);
    for (std::size_t k = 0; k < cloud.size(); ++k) {
      const tf2::Vector3 w = R * tf2::Vector3(cloud[k].x(), cloud[k].y(), cloud[k].z());
      ASSERT_EQ(moved[k].x(), static_cast<float>(w.x() + rt.x));
      ASSERT_EQ(moved[k].y(), static_cast<float>(w.y() + rt.y));
      ASSERT_EQ(moved[k].z(), static_cast<float>(w.z() + rt.z));
    }
    ++compared;
  }
  EXPECT_GT(compared, 1000u);
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin
