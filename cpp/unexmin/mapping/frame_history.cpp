#include <unexmin/mapping/frame_history.h>

#include <algorithm>

namespace unexmin {
namespace mapping {

double toSeconds(Stamp ns) {
  constexpr Stamp kSecond = 1000000000;
  Stamp sec = ns / kSecond, rest = ns % kSecond;
  if (rest < 0) {
    --sec;
    rest += kSecond;
  }
  return static_cast<double>(sec) + 1e-9 * static_cast<double>(rest);
}

FrameHistory::FrameHistory(bool is_static, Stamp cache_length) : is_static_(is_static), cache_length_(cache_length) {}

FrameHistory::Insert FrameHistory::insert(const FrameSample& sample) {
  if (is_static_) {
    samples_.assign(1, sample);
    return Insert::kStored;
  }
  if (!samples_.empty() && samples_.back().stamp > sample.stamp + cache_length_)
    return Insert::kTooOld;
  auto it = std::lower_bound(samples_.begin(), samples_.end(), sample.stamp,
                             [](const FrameSample& s, Stamp t) { return s.stamp < t; });
  if (it != samples_.end() && it->stamp == sample.stamp)
    return Insert::kRepeated;
  samples_.insert(it, sample);
  const Stamp newest = samples_.back().stamp;
  while (samples_.front().stamp + cache_length_ < newest)
    samples_.pop_front();
  return Insert::kStored;
}

void FrameHistory::clear() {
  if (!is_static_)
    samples_.clear();
}

FrameAnswer FrameHistory::at(Stamp time) const {
  FrameAnswer answer;
  if (samples_.empty())
    return answer;
  const FrameSample* one = nullptr;
  const FrameSample* two = nullptr;
  bool on_sample = false;
  if (is_static_ || time == 0 || time == samples_.back().stamp) {
    one = &samples_.back();
  } else if (time == samples_.front().stamp) {
    one = &samples_.front();
  } else if (time > samples_.back().stamp) {
    answer.status = FrameAnswer::Status::kTooNew;
    return answer;
  } else if (time < samples_.front().stamp) {
    answer.status = FrameAnswer::Status::kTooOld;
    return answer;
  } else {
    auto after = std::lower_bound(samples_.begin(), samples_.end(), time,
                                  [](const FrameSample& s, Stamp t) { return s.stamp < t; });
    // A time on an inner sample is interpolated from it towards the next at ratio 0, as tf2 does: the slerp's
    // sin(theta) / sin(theta) can move the rotation by an ulp, and the numbers must be tf2's.
    on_sample = after->stamp == time;
    one = on_sample ? &*after : &*(after - 1);
    two = on_sample ? &*(after + 1) : &*after;
  }
  answer.status = FrameAnswer::Status::kOk;
  answer.parent = one->parent;
  if (!two) {
    answer.transform = one->transform;
  } else {
    if (one->parent != two->parent) {
      answer.transform = one->transform;  // re-parented between the two: the older sample, as tf2 does
    } else {
      const double ratio = toSeconds(time - one->stamp) / toSeconds(two->stamp - one->stamp);
      answer.transform = RigidTransform::interpolate(one->transform, two->transform, ratio);
    }
    answer.gap = on_sample ? 0.0 : toSeconds(two->stamp - one->stamp);
  }
  return answer;
}

}  // namespace mapping
}  // namespace unexmin
