#include <unexmin/mapping/tf_history.h>

#include <unexmin/core/error.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace mapping {

namespace {

constexpr std::size_t kMaxDepth = 1000;  // a longer chain is a loop

std::string stripSlash(const std::string& frame) {
  return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}

/// Why tf2 would refuse a sample (empty: it is fine).
std::string refusal(const TfSample& s) {
  if (s.child.empty())
    return "no child frame";
  if (s.parent.empty())
    return "'" + s.child + "': no parent frame";
  if (s.child == s.parent)
    return "'" + s.child + "': its own parent";
  const Eigen::Vector3d& t = s.transform.translation;
  const Eigen::Quaterniond& q = s.transform.rotation;
  const double norm2 = q.w() * q.w() + q.x() * q.x() + q.y() * q.y() + q.z() * q.z();
  if (!t.allFinite() || !q.coeffs().allFinite())
    return "'" + s.child + "': not a finite transform";
  if (!(std::abs(norm2 - 1.0) < 1e-2))
    return "'" + s.child + "': a quaternion of squared norm " + std::to_string(norm2);
  return "";
}

TfLookup::Status statusOf(FrameAnswer::Status s) {
  switch (s) {
    case FrameAnswer::Status::kOk:
      return TfLookup::Status::kOk;
    case FrameAnswer::Status::kTooOld:
      return TfLookup::Status::kTooOld;
    case FrameAnswer::Status::kTooNew:
      return TfLookup::Status::kTooNew;
    case FrameAnswer::Status::kEmpty:
      break;
  }
  return TfLookup::Status::kNoChain;
}

}  // namespace

TfHistory::TfHistory(double cache_length, double handover_silence)
    : cache_length_(0), handover_silence_(handover_silence) {
  if (!(cache_length > 0.0 && cache_length < 1e9)) {
    throw ParameterError("TfHistory: cache_length = " + formatNumber(cache_length) + ": expected (0, 1e9) s");
  }
  if (!(handover_silence >= 0.0) || !std::isfinite(handover_silence)) {
    throw ParameterError("TfHistory: handover_silence = " + formatNumber(handover_silence) + ": expected >= 0 s");
  }
  cache_length_ = static_cast<Stamp>(std::llround(cache_length * 1e9));
}

FrameHistory& TfHistory::frame(const std::string& child, bool is_static) {
  auto it = frames_.find(child);
  if (it == frames_.end())
    it = frames_.emplace(child, FrameHistory(is_static, cache_length_)).first;
  return it->second;
}

void TfHistory::clearDynamic() {
  for (auto& entry : frames_)
    entry.second.clear();
}

TfUpdate TfHistory::add(const std::vector<TfSample>& raw, const std::string& publisher, double now, bool is_static) {
  TfUpdate update;
  std::vector<TfSample> samples;
  samples.reserve(raw.size());
  for (const TfSample& r : raw) {
    TfSample s = r;
    s.parent = stripSlash(s.parent);
    s.child = stripSlash(s.child);
    const std::string why = refusal(s);
    if (why.empty()) {
      samples.push_back(std::move(s));
    } else {
      update.refused.push_back(why);
    }
  }
  if (!is_static) {
    // A hand-over or a frame's stamps going back start a new history.
    for (const TfSample& s : samples) {
      auto owner = owners_.find(s.child);
      if (owner == owners_.end())
        continue;
      if (owner->second.node != publisher) {
        if (now - owner->second.last <= handover_silence_)
          continue;  // a second live publisher: ignored below
        update.jump = "'" + s.child + "' now comes from " + publisher + " (" + owner->second.node + " fell silent)";
        owner->second.node = publisher;
        break;
      }
      auto history = frames_.find(s.child);
      if (history != frames_.end() && !history->second.empty() && s.stamp < history->second.newest()) {
        update.jump = "'" + s.child + "' went back in time from " +
                      std::to_string(toSeconds(history->second.newest())) + " to " +
                      std::to_string(toSeconds(s.stamp)) + " s";
        break;
      }
    }
    if (!update.jump.empty()) {
      clearDynamic();
      ++jumps_;
      last_jump_ = now;
    }
  }
  for (const TfSample& s : samples) {
    if (!is_static) {
      Owner& owner = owners_.emplace(s.child, Owner{publisher, now}).first->second;
      if (owner.node != publisher) {
        ++ignored_;
        if (warned_.insert(s.child + " " + publisher).second) {
          update.newly_ignored.push_back("'" + s.child + "' from " + publisher + " (it comes from " + owner.node + ")");
        }
        continue;
      }
      owner.last = now;
    }
    if (frame(s.child, is_static).insert(FrameSample{s.stamp, s.parent, s.transform}) ==
        FrameHistory::Insert::kTooOld) {
      update.refused.push_back("'" + s.child + "': older than the tf kept (" + std::to_string(toSeconds(s.stamp)) +
                               " s)");
    }
  }
  return update;
}

FrameAnswer TfHistory::at(const std::string& name, Stamp time) const {
  auto it = frames_.find(name);
  return it == frames_.end() ? FrameAnswer{} : it->second.at(time);
}

Stamp TfHistory::commonTime(const std::string& target, const std::string& source) const {
  Stamp common = 0;
  for (const std::string& start : {source, target}) {
    std::string f = start;
    for (std::size_t depth = 0; depth < kMaxDepth; ++depth) {
      auto it = frames_.find(f);
      if (it == frames_.end() || it->second.empty())
        break;
      const Stamp newest = it->second.newest();
      if (newest != 0 && (common == 0 || newest < common))
        common = newest;
      f = it->second.at(0).parent;
    }
  }
  return common;
}

TfLookup TfHistory::lookup(const std::string& target, const std::string& source, Stamp time) const {
  TfLookup result;
  if (source == target) {
    result.status = TfLookup::Status::kOk;
    return result;
  }
  if (time == 0)
    time = commonTime(target, source);
  const auto loop = [](const std::string& f) {
    TfLookup l;
    l.frame = f;  // kNoChain: the parents form a loop
    return l;
  };
  const auto noteGap = [&result](const FrameAnswer& a, const std::string& f) {
    if (a.gap > result.gap) {
      result.gap = a.gap;
      result.frame = f;
    }
  };
  // Up from the source to the root (or to the first frame that cannot answer), as tf2 walks.
  RigidTransform source_in_top;
  std::string top = source, frame = source;
  FrameAnswer::Status source_failure = FrameAnswer::Status::kOk;
  std::string failed;
  for (std::size_t depth = 0;; ++depth) {
    if (frames_.find(frame) == frames_.end()) {
      top = frame;
      break;
    }
    const FrameAnswer a = at(frame, time);
    if (a.status != FrameAnswer::Status::kOk) {
      top = frame;
      source_failure = a.status;
      failed = frame;
      break;
    }
    if (frame == target) {  // the target is an ancestor of the source
      result.status = TfLookup::Status::kOk;
      result.transform = source_in_top;
      return result;
    }
    noteGap(a, frame);
    source_in_top = a.transform * source_in_top;
    top = frame;
    frame = a.parent;
    if (depth > kMaxDepth)
      return loop(frame);
  }
  // Up from the target to the same top.
  RigidTransform target_in_top;
  frame = target;
  for (std::size_t depth = 0; frame != top; ++depth) {
    if (frames_.find(frame) == frames_.end())
      break;
    const FrameAnswer a = at(frame, time);
    if (a.status != FrameAnswer::Status::kOk) {
      result.status = statusOf(a.status);
      result.frame = frame;
      result.gap = 0.0;
      return result;
    }
    if (frame == source) {  // the source is an ancestor of the target
      result.status = TfLookup::Status::kOk;
      result.transform = target_in_top.inverse();
      return result;
    }
    noteGap(a, frame);
    target_in_top = a.transform * target_in_top;
    frame = a.parent;
    if (depth > kMaxDepth)
      return loop(frame);
  }
  if (frame != top) {
    // The source's walk stopped short (a frame could not answer) or the two walks never meet.
    result.status = failed.empty() ? TfLookup::Status::kNoChain : statusOf(source_failure);
    result.frame = failed.empty() ? source : failed;
    result.gap = 0.0;
    return result;
  }
  result.status = TfLookup::Status::kOk;
  result.transform = target_in_top.inverse() * source_in_top;
  return result;
}

}  // namespace mapping
}  // namespace unexmin
