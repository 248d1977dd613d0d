// mapping::FrameHistory: one frame's samples kept in stamp order for the cache length, repeated and too old
// samples refused, a time between two samples interpolated (with their gap), the ends of the history typed as
// too old or too new, a static frame answering every time, clear() sparing it.
#include <unexmin/mapping/frame_history.h>

#include <gtest/gtest.h>

namespace unexmin {
namespace mapping {
namespace {

constexpr Stamp kSec = 1000000000;

FrameSample at(double seconds, double x, const std::string& parent = "world") {
  FrameSample s;
  s.stamp = static_cast<Stamp>(seconds * kSec);
  s.parent = parent;
  s.transform.translation = Eigen::Vector3d(x, 0.0, 0.0);
  return s;
}

TEST(FrameHistory, SecondsOfStampsRoundAsRosDurations) {
  EXPECT_EQ(toSeconds(1500000000), 1.5);
  EXPECT_EQ(toSeconds(-1500000000), -2.0 + 0.5);  // -2 s + 0.5e9 ns
  EXPECT_EQ(toSeconds(3 * kSec + 7), 3.0 + 1e-9 * 7.0);
}

TEST(FrameHistory, InterpolatesBetweenTwoSamplesAndReportsTheirGap) {
  FrameHistory h(false, 120 * kSec);
  EXPECT_EQ(h.insert(at(1.0, 0.0)), FrameHistory::Insert::kStored);
  EXPECT_EQ(h.insert(at(3.0, 4.0)), FrameHistory::Insert::kStored);
  const FrameAnswer mid = h.at(static_cast<Stamp>(1.5 * kSec));
  ASSERT_EQ(mid.status, FrameAnswer::Status::kOk);
  EXPECT_DOUBLE_EQ(mid.transform.translation.x(), 1.0);
  EXPECT_DOUBLE_EQ(mid.gap, 2.0);
  EXPECT_EQ(mid.parent, "world");
  const FrameAnswer exact = h.at(3 * kSec);
  ASSERT_EQ(exact.status, FrameAnswer::Status::kOk);
  EXPECT_EQ(exact.transform.translation.x(), 4.0);
  EXPECT_EQ(exact.gap, 0.0);
}

TEST(FrameHistory, TypesTimesOutsideItsSamples) {
  FrameHistory h(false, 120 * kSec);
  EXPECT_EQ(h.at(kSec).status, FrameAnswer::Status::kEmpty);
  h.insert(at(2.0, 0.0));
  EXPECT_EQ(h.at(kSec).status, FrameAnswer::Status::kTooOld);
  EXPECT_EQ(h.at(3 * kSec).status, FrameAnswer::Status::kTooNew);
  EXPECT_EQ(h.at(2 * kSec).status, FrameAnswer::Status::kOk);
  h.insert(at(4.0, 1.0));
  EXPECT_EQ(h.at(2 * kSec - 1).status, FrameAnswer::Status::kTooOld);
  EXPECT_EQ(h.at(4 * kSec + 1).status, FrameAnswer::Status::kTooNew);
  EXPECT_EQ(h.at(0).transform.translation.x(), 1.0);  // time 0: the newest
}

TEST(FrameHistory, KeepsSamplesInStampOrderAndRefusesRepeatedOnes) {
  FrameHistory h(false, 120 * kSec);
  h.insert(at(1.0, 1.0));
  h.insert(at(3.0, 3.0));
  EXPECT_EQ(h.insert(at(2.0, 2.0)), FrameHistory::Insert::kStored);
  EXPECT_EQ(h.insert(at(2.0, 9.0)), FrameHistory::Insert::kRepeated);
  EXPECT_EQ(h.size(), 3u);
  EXPECT_EQ(h.at(2 * kSec).transform.translation.x(), 2.0);
  EXPECT_EQ(h.oldest(), kSec);
  EXPECT_EQ(h.newest(), 3 * kSec);
}

TEST(FrameHistory, ForgetsSamplesOlderThanTheCacheLength) {
  FrameHistory h(false, 10 * kSec);
  for (int s = 0; s <= 30; ++s)
    h.insert(at(s, s));
  EXPECT_EQ(h.oldest(), 20 * kSec);  // 30 - 10: kept while no more than the cache length behind the newest
  EXPECT_EQ(h.size(), 11u);
  EXPECT_EQ(h.insert(at(20.5, 0.0)), FrameHistory::Insert::kStored);  // within 10 s of the newest
  EXPECT_EQ(h.insert(at(19.5, 0.0)), FrameHistory::Insert::kTooOld);  // more than 10 s behind
  EXPECT_EQ(h.at(15 * kSec).status, FrameAnswer::Status::kTooOld);
}

TEST(FrameHistory, KeepsTheOlderSampleWhenTheParentChangesBetweenTwo) {
  FrameHistory h(false, 120 * kSec);
  h.insert(at(1.0, 1.0, "a"));
  h.insert(at(2.0, 5.0, "b"));
  const FrameAnswer mid = h.at(static_cast<Stamp>(1.5 * kSec));
  EXPECT_EQ(mid.parent, "a");
  EXPECT_EQ(mid.transform.translation.x(), 1.0);
}

TEST(FrameHistory, AStaticFrameAnswersEveryTimeAndSurvivesClear) {
  FrameHistory h(true, 120 * kSec);
  h.insert(at(5.0, 1.0));
  h.insert(at(1.0, 2.0));  // replaces, whatever the stamp
  EXPECT_EQ(h.size(), 1u);
  for (Stamp t : {Stamp(0), kSec, 1000 * kSec}) {
    const FrameAnswer a = h.at(t);
    ASSERT_EQ(a.status, FrameAnswer::Status::kOk);
    EXPECT_EQ(a.transform.translation.x(), 2.0);
    EXPECT_EQ(a.gap, 0.0);
  }
  h.clear();
  EXPECT_EQ(h.at(kSec).status, FrameAnswer::Status::kOk);
  FrameHistory d(false, 120 * kSec);
  d.insert(at(1.0, 1.0));
  d.clear();
  EXPECT_TRUE(d.empty());
  EXPECT_EQ(d.at(kSec).status, FrameAnswer::Status::kEmpty);
}

}  // namespace
}  // namespace mapping
}  // namespace unexmin
