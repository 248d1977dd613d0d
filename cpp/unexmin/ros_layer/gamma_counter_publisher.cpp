#include <unexmin/ros_layer/gamma_counter_publisher.h>

#include <unexmin/GammaCounts.h>

#include <algorithm>
#include <cstdint>
#include <limits>

namespace unexmin {
namespace ros_layer {
namespace {

/// A count as the message's uint32 (saturating: 4.3e9 counts in one integration is far beyond any detector).
std::uint32_t count32(std::uint64_t n) {
  return static_cast<std::uint32_t>(std::min<std::uint64_t>(n, std::numeric_limits<std::uint32_t>::max()));
}

}  // namespace

GammaCounterPublisher::GammaCounterPublisher(const sensors::science::GammaCounterSensor& sensor,
                                             const PublisherContext& ctx)
    : sensor_(sensor) {
  pub_ = ctx.nh.advertise<unexmin::GammaCounts>(resolve(ctx.ns, topicParam(sensor, "topic", sensor.name())),
                                                queueSize(sensor.rate()));
}

void GammaCounterPublisher::publish() {
  if (!wanted(pub_))
    return;
  using sensors::science::kPotassium;
  using sensors::science::kThorium;
  using sensors::science::kUranium;
  const sensors::science::GammaSample& s = sensor_.last();
  unexmin::GammaCounts m;
  m.header.stamp.fromSec(s.time);
  m.header.frame_id = sensor_.frame();
  m.integration_time = s.integration_time;
  m.counts_total = count32(s.counts_total);
  m.counts_potassium = count32(s.counts[kPotassium]);
  m.counts_uranium = count32(s.counts[kUranium]);
  m.counts_thorium = count32(s.counts[kThorium]);
  m.rate_total = s.rate_total;
  m.rate_potassium = s.rate[kPotassium];
  m.rate_uranium = s.rate[kUranium];
  m.rate_thorium = s.rate[kThorium];
  m.dead_time_fraction = s.dead_time_fraction;
  emit(pub_, m);
}

}  // namespace ros_layer
}  // namespace unexmin
