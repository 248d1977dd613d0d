// mapping::CloudQueue: a cloud waits for its tf and goes in once it has come, placed by the tf at its stamp; it is
// dropped when older than the tf kept, when its tf has not come within tf_timeout (wall), when its pose would be
// interpolated over more than tf_max_gap, or when tf jumped back after it was received; the clouds behind a
// waiting one wait too.
#include <unexmin/mapping/cloud_queue.h>

#include "expect_error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace unexmin {
namespace mapping {
namespace {

constexpr Stamp kSec = 1000000000;
using Kind = CloudStep::Kind;

Stamp sec(double t) {
  return static_cast<Stamp>(std::llround(t * kSec));
}

TfSample base(double t, double x) {
  TfSample s;
  s.parent = "world";
  s.child = "base";
  s.stamp = sec(t);
  s.transform.translation = Eigen::Vector3d(x, 0.0, 0.0);
  return s;
}

PendingCloud cloud(double t, double received, const std::string& frame = "base") {
  return PendingCloud{"UX_1", frame, sec(t), {octomap::point3d(1.0f, 0.0f, 0.0f)}, received};
}

TEST(CloudQueue, ChecksItsParameters) {
  EXPECT_TRUE(test::contains(test::thrownMessage([] { CloudQueue("", 1.0, 1.0); }), "map frame"));
  EXPECT_TRUE(test::contains(test::thrownMessage([] { CloudQueue("world", 0.0, 1.0); }), "tf_timeout = 0"));
  EXPECT_TRUE(test::contains(test::thrownMessage([] { CloudQueue("world", 1.0, -1.0); }), "tf_max_gap = -1"));
}

TEST(CloudQueue, ACloudWaitsForItsTfThenGoesInPlacedByIt) {
  TfHistory tf;
  CloudQueue q("world", 10.0, 0.5);
  tf.add({base(1.0, 0.0)}, "sim", 0.0, false);
  q.push(cloud(1.2, 0.0));
  q.push(cloud(1.1, 0.0));
  EXPECT_EQ(q.next(tf, 1.0).kind, Kind::kWait);  // tf only up to 1.0 s: both wait, the second behind the first
  EXPECT_EQ(q.size(), 2u);
  tf.add({base(1.4, 4.0)}, "sim", 1.0, false);
  const CloudStep first = q.next(tf, 1.0);
  ASSERT_EQ(first.kind, Kind::kInsert);
  EXPECT_EQ(first.cloud.stamp, sec(1.2));
  EXPECT_NEAR(first.sensor_in_map.translation.x(), 2.0, 1e-12);  // halfway from 0 to 4 m
  const CloudStep second = q.next(tf, 1.0);
  ASSERT_EQ(second.kind, Kind::kInsert);
  EXPECT_NEAR(second.sensor_in_map.translation.x(), 1.0, 1e-12);
  EXPECT_EQ(q.next(tf, 1.0).kind, Kind::kWait);
  EXPECT_EQ(q.received(), 2u);
  EXPECT_EQ(q.dropped(), 0u);
}

TEST(CloudQueue, DropsACloudOlderThanTheTfKept) {
  TfHistory tf;
  CloudQueue q("world", 10.0, 0.5);
  tf.add({base(1.0, 0.0)}, "sim", 0.0, false);
  tf.add({base(1.1, 0.0)}, "sim", 0.0, false);
  q.push(cloud(0.5, 0.0));
  const CloudStep s = q.next(tf, 0.0);
  ASSERT_EQ(s.kind, Kind::kDrop);
  EXPECT_TRUE(test::contains(s.why, "older than the tf kept of 'base'"));
  EXPECT_EQ(q.dropped(), 1u);
  EXPECT_EQ(q.size(), 0u);
}

TEST(CloudQueue, GivesUpOnATfThatDoesNotComeWithinTheTimeout) {
  TfHistory tf;
  CloudQueue q("world", 2.0, 0.5);
  q.push(cloud(1.0, 100.0, "sensor"));
  EXPECT_EQ(q.next(tf, 102.0).kind, Kind::kWait);  // 2 s: not more than the timeout yet
  const CloudStep s = q.next(tf, 102.5);
  ASSERT_EQ(s.kind, Kind::kDrop);
  EXPECT_TRUE(test::contains(s.why, "~tf_timeout"));
  EXPECT_TRUE(test::contains(s.why, "no chain at 'sensor'"));
}

TEST(CloudQueue, DropsACloudWhosePoseWouldBeInterpolatedOverAGap) {
  TfHistory tf;
  CloudQueue q("world", 10.0, 0.5);
  for (double t : {0.0, 0.1, 0.8, 0.9})
    tf.add({base(t, t)}, "sim", 0.0, false);
  q.push(cloud(0.5, 0.0));   // between 0.1 and 0.8: a gap of 0.7 s
  q.push(cloud(0.85, 0.0));  // between 0.8 and 0.9
  const CloudStep gap = q.next(tf, 0.0);
  ASSERT_EQ(gap.kind, Kind::kDrop);
  EXPECT_TRUE(test::contains(gap.why, "gap of 0.7"));
  EXPECT_EQ(q.next(tf, 0.0).kind, Kind::kInsert);
}

TEST(CloudQueue, ForgetsTheCloudsReceivedBeforeAJumpBack) {
  TfHistory tf;
  CloudQueue q("world", 10.0, 0.5);
  tf.add({base(5.0, 0.0)}, "sim", 0.0, false);
  q.push(cloud(6.0, 1.0));  // waits for tf of 6 s
  q.push(cloud(7.0, 2.0));
  EXPECT_EQ(q.next(tf, 2.0).kind, Kind::kWait);
  tf.add({base(0.5, 0.0)}, "sim", 3.0, false);  // a reset: back to 0.5 s
  q.push(cloud(0.5, 4.0));                      // of the new run
  const CloudStep s = q.next(tf, 4.0);
  ASSERT_EQ(s.kind, Kind::kInsert);
  EXPECT_EQ(s.cloud.stamp, sec(0.5));
  EXPECT_EQ(q.dropped(), 2u);
  EXPECT_EQ(q.size(), 0u);
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin
