// mapping::TfHistory without a roscore: lookups along a chain of frames against poses composed in the test, the
// typed failures (too old, too new, no chain), the owner of a dynamic frame and its hand-over after silence, the
// history cleared on a jump back in time with the static frames kept, the gap of an interpolation reported, and
// the samples tf2 refuses.
#include <unexmin/mapping/tf_history.h>

#include "expect_error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace mapping {
namespace {

constexpr Stamp kSec = 1000000000;
constexpr double kPi = 3.14159265358979323846;
using Status = TfLookup::Status;

/// child in parent at t [s]: at (x, y, 0), turned by yaw [rad] about z.
TfSample sample(const std::string& parent, const std::string& child, double t, double x, double y = 0.0,
                double yaw = 0.0) {
  TfSample s;
  s.parent = parent;
  s.child = child;
  s.stamp = static_cast<Stamp>(std::llround(t * kSec));
  s.transform.translation = Eigen::Vector3d(x, y, 0.0);
  s.transform.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  return s;
}

Stamp sec(double t) {
  return static_cast<Stamp>(std::llround(t * kSec));
}

/// A robot: base in world (dynamic, from "sim"), sensor 1 m ahead of base (static).
TfHistory robot() {
  TfHistory tf;
  tf.add({sample("base", "sensor", 0.0, 1.0)}, "rsp", 0.0, true);
  tf.add({sample("world", "base", 1.0, 0.0, 0.0, 0.0)}, "sim", 0.0, false);
  tf.add({sample("world", "base", 2.0, 2.0, 0.0, kPi / 2)}, "sim", 0.1, false);
  return tf;
}

TEST(TfHistory, ChecksItsParameters) {
  EXPECT_TRUE(test::contains(test::thrownMessage([] { TfHistory(0.0, 1.0); }), "cache_length = 0"));
  EXPECT_TRUE(test::contains(test::thrownMessage([] { TfHistory(120.0, -1.0); }), "handover_silence = -1"));
  EXPECT_TRUE(test::contains(test::thrownMessage([] { TfHistory(std::nan(""), 1.0); }), "cache_length = nan"));
}

TEST(TfHistory, ComposesTheChainAndInterpolatesItsDynamicFrame) {
  const TfHistory tf = robot();
  const TfLookup at2 = tf.lookup("world", "sensor", sec(2.0));
  ASSERT_EQ(at2.status, Status::kOk);
  // base at (2, 0) facing +y: the sensor 1 m ahead is at (2, 1).
  EXPECT_NEAR(at2.transform.translation.x(), 2.0, 1e-12);
  EXPECT_NEAR(at2.transform.translation.y(), 1.0, 1e-12);
  EXPECT_EQ(at2.gap, 0.0);
  const TfLookup mid = tf.lookup("world", "sensor", sec(1.5));
  ASSERT_EQ(mid.status, Status::kOk);
  // base at (1, 0) turned pi/4: the sensor at (1 + cos 45, sin 45).
  EXPECT_NEAR(mid.transform.translation.x(), 1.0 + std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(mid.transform.translation.y(), std::sqrt(0.5), 1e-12);
  EXPECT_DOUBLE_EQ(mid.gap, 1.0);
  EXPECT_EQ(mid.frame, "base");
  // The other way round, and between two frames below the root.
  const TfLookup back = tf.lookup("sensor", "world", sec(2.0));
  ASSERT_EQ(back.status, Status::kOk);
  EXPECT_NEAR((back.transform * at2.transform).translation.norm(), 0.0, 1e-12);
  const TfLookup side = tf.lookup("base", "sensor", sec(1.25));
  ASSERT_EQ(side.status, Status::kOk);
  EXPECT_NEAR(side.transform.translation.x(), 1.0, 1e-12);
  EXPECT_EQ(tf.lookup("sensor", "sensor", sec(9.0)).status, Status::kOk);
}

TEST(TfHistory, TypesWhatItCannotAnswer) {
  const TfHistory tf = robot();
  const TfLookup old = tf.lookup("world", "sensor", sec(0.5));
  EXPECT_EQ(old.status, Status::kTooOld);
  EXPECT_EQ(old.frame, "base");
  EXPECT_EQ(tf.lookup("world", "sensor", sec(2.5)).status, Status::kTooNew);
  EXPECT_EQ(tf.lookup("world", "camera", sec(1.5)).status, Status::kNoChain);
  EXPECT_EQ(tf.lookup("map", "sensor", sec(1.5)).status, Status::kNoChain);
  EXPECT_EQ(tf.lookup("world", "/sensor", sec(1.5)).status, Status::kNoChain);
}

TEST(TfHistory, TimeZeroIsTheNewestCommonTime) {
  const TfHistory tf = robot();
  const TfLookup latest = tf.lookup("world", "sensor", 0);
  ASSERT_EQ(latest.status, Status::kOk);
  EXPECT_NEAR(latest.transform.translation.x(), 2.0, 1e-12);
  EXPECT_NEAR(latest.transform.translation.y(), 1.0, 1e-12);
}

TEST(TfHistory, ADynamicFrameHasOneOwnerUntilItFallsSilent) {
  TfHistory tf(120.0, 1.0);
  tf.add({sample("world", "base", 1.0, 1.0)}, "sim", 10.0, false);
  // A second publisher while the first is alive: ignored, warned about once.
  TfUpdate second = tf.add({sample("world", "base", 1.5, 9.0)}, "leftover", 10.5, false);
  ASSERT_EQ(second.newly_ignored.size(), 1u);
  EXPECT_NE(second.newly_ignored[0].find("leftover"), std::string::npos);
  EXPECT_TRUE(second.jump.empty());
  EXPECT_TRUE(tf.add({sample("world", "base", 1.6, 9.0)}, "leftover", 10.6, false).newly_ignored.empty());
  EXPECT_EQ(tf.ignored(), 2u);
  tf.add({sample("world", "base", 2.0, 2.0)}, "sim", 10.9, false);
  EXPECT_EQ(tf.lookup("world", "base", sec(1.5)).transform.translation.x(), 1.5);
  // sim silent for more than 1 s: leftover takes over, the history restarts.
  const TfUpdate over = tf.add({sample("world", "base", 5.0, 7.0)}, "leftover", 12.0, false);
  EXPECT_NE(over.jump.find("now comes from leftover"), std::string::npos);
  EXPECT_EQ(tf.jumps(), 1u);
  EXPECT_EQ(tf.lastJump(), 12.0);
  EXPECT_EQ(tf.lookup("world", "base", sec(1.5)).status, Status::kTooOld);
  EXPECT_EQ(tf.lookup("world", "base", sec(5.0)).transform.translation.x(), 7.0);
  // Now sim is the second publisher.
  EXPECT_EQ(tf.add({sample("world", "base", 6.0, 0.0)}, "sim", 12.1, false).newly_ignored.size(), 1u);
}

TEST(TfHistory, AJumpBackInTimeClearsTheDynamicFramesAndKeepsTheStaticOnes) {
  TfHistory tf = robot();
  const TfUpdate jump = tf.add({sample("world", "base", 0.5, 5.0)}, "sim", 3.0, false);
  EXPECT_NE(jump.jump.find("went back in time"), std::string::npos);
  EXPECT_EQ(tf.jumps(), 1u);
  EXPECT_EQ(tf.lastJump(), 3.0);
  EXPECT_EQ(tf.lookup("world", "sensor", sec(1.5)).status, Status::kTooNew);  // the old run is gone
  const TfLookup now = tf.lookup("world", "sensor", sec(0.5));
  ASSERT_EQ(now.status, Status::kOk);
  EXPECT_NEAR(now.transform.translation.x(), 6.0, 1e-12);  // the static sensor offset kept
  // Equal stamps are no jump (tf2 keeps the first sample).
  EXPECT_TRUE(tf.add({sample("world", "base", 0.5, 8.0)}, "sim", 3.1, false).jump.empty());
  EXPECT_EQ(tf.jumps(), 1u);
  EXPECT_NEAR(tf.lookup("world", "base", sec(0.5)).transform.translation.x(), 5.0, 1e-12);
}

TEST(TfHistory, ReportsTheLargestGapAlongTheChain) {
  TfHistory tf;
  for (double t : {0.0, 0.1, 0.2, 1.0, 1.1})
    tf.add({sample("world", "base", t, t)}, "sim", t, false);
  for (double t : {0.0, 0.5, 1.0})
    tf.add({sample("base", "arm", t, 1.0)}, "sim", t, false);
  const TfLookup in_gap = tf.lookup("world", "arm", sec(0.6));
  ASSERT_EQ(in_gap.status, Status::kOk);
  EXPECT_NEAR(in_gap.gap, 0.8, 1e-12);
  EXPECT_EQ(in_gap.frame, "base");
  const TfLookup before = tf.lookup("world", "arm", sec(0.15));
  EXPECT_NEAR(before.gap, 0.5, 1e-12);
  EXPECT_EQ(before.frame, "arm");
}

TEST(TfHistory, RefusesWhatTf2Refuses) {
  TfHistory tf;
  TfSample bad_q = sample("world", "a", 1.0, 0.0);
  bad_q.transform.rotation = Eigen::Quaterniond(0.5, 0.0, 0.0, 0.0);
  TfSample nan = sample("world", "b", 1.0, std::nan(""));
  const TfUpdate u = tf.add({sample("x", "x", 1.0, 0.0), sample("", "c", 1.0, 0.0), sample("world", "", 1.0, 0.0),
                             bad_q, nan, sample("/world", "/d", 1.0, 3.0)},
                            "sim", 0.0, false);
  EXPECT_EQ(u.refused.size(), 5u);
  EXPECT_EQ(tf.lookup("world", "a", sec(1.0)).status, Status::kNoChain);
  EXPECT_EQ(tf.lookup("world", "d", sec(1.0)).transform.translation.x(), 3.0);  // leading '/' stripped
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin
